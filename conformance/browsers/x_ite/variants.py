"""Scene variants that isolate one thing in X_ITE: a field at its default, the scene made
so X_ITE can show a field at all, a node type taken out.

A probe says a field is ignored only when the field is the one difference between two
recordings, and only where X_ITE could have shown it: X_ITE (Bullet through ammo.js)
takes a body's mass distribution from its collidables alone, so a body without one gets
no inertia and no torque turns it; and it collides only the bodies of one collection, so a
floor that is a collidable on no body stops nothing. `ready` gives such bodies a sphere
and such collidables a fixed RigidBody where they lie, and watches every collision
collection with a CollisionSensor, so that a probe's own run says whether a contact
happened; the probes then remove the field from that one scene. Every node `ready` adds is
named XITE_*, and `without` leaves those alone (a node of the scene it names is X3DRBP_*). All variants are XML (the conformance
scenes are).
"""

from __future__ import annotations

import itertools

import numpy as np
from lxml import etree

COLLIDABLES = ("CollidableShape", "CollidableOffset")
_PARSER = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False)


def _parse(scene: str) -> etree._ElementTree:
    return etree.parse(scene, _PARSER)


def _write(tree: etree._ElementTree, out: str) -> None:
    tree.write(out, xml_declaration=True, encoding="UTF-8")


ADDED = "XITE_"  # the DEF names of the nodes `ready` adds
NAMED = "X3DRBP_"  # the DEF names `ready` gives the scene's own nodes where a USE must reach them


def without(scene: str, node_type: str, fld: str, out: str) -> bool:
    """Writes the XML scene with `fld` removed from every `node_type` element (so at its
    default) to `out`, but for the nodes `ready` added (theirs is the same in both runs);
    False where no element sets it, or the scene is not XML."""
    if not scene.endswith(".x3d"):
        return False
    tree = _parse(scene)
    changed = [e for e in tree.iter(node_type) if fld in e.attrib and not e.get("DEF", "").startswith(ADDED)]
    for e in changed:
        del e.attrib[fld]
    if changed:
        _write(tree, out)
    return bool(changed)


def without_nodes(scene: str, node_type: str, out: str) -> bool:
    """Writes the scene with every `node_type` element taken out to `out`; False where it has none."""
    tree = _parse(scene)
    found = list(tree.iter(node_type))
    for e in found:
        e.getparent().remove(e)
    if found:
        _write(tree, out)
    return bool(found)


def _sphere_radius(body: etree._Element) -> float:
    """The radius of a solid sphere of the body's mass whose moment of inertia is the mean of
    the body's principal moments (2/5 m r^2 = I): the body turns under a torque as much as
    its own inertia says, on average over the axes."""
    mass = float(body.get("mass", "1"))
    inertia = np.array([float(x) for x in body.get("inertia", "1 0 0 0 1 0 0 0 1").replace(",", " ").split()])
    mean = float(np.trace(inertia.reshape(3, 3))) / 3.0
    return float(np.sqrt(2.5 * mean / mass))


# what X_ITE needs to show a field of these: a body's mass distribution from a collidable
# (MASS), a contact with a static collidable held by a body (CONTACT)
MASS, CONTACT = "a collidable on each body without one", "static collidables on fixed bodies"
_CONTACT_TYPES = ("CollisionCollection", "CollisionSpace", "CollisionSensor", "CollidableShape", "CollidableOffset",
                  "Contact")
_CONTACT_FIELDS = ("RigidBodyCollection.contactSurfaceThickness", "RigidBodyCollection.maxCorrectionSpeed")
SENSOR = ADDED + "SENSOR_"  # the CollisionSensors `ready` adds: a contact in a probe's run shows in their isActive


def needs(node_type: str, fld: str) -> tuple[str, ...]:
    """What a probe of this field needs of the scene for X_ITE to show the field at all."""
    if node_type in _CONTACT_TYPES or f"{node_type}.{fld}" in _CONTACT_FIELDS:
        return (CONTACT,)
    if node_type == "RigidBody":
        return (MASS,)
    return ()


def _fresh(tree: etree._ElementTree, prefix: str) -> str:
    """prefix and the least number that no node's DEF has."""
    taken = {x.get("DEF") for x in tree.iter()}
    return next(f"{prefix}{k}" for k in itertools.count(1) if f"{prefix}{k}" not in taken)


def _named(tree: etree._ElementTree, e: etree._Element, prefix: str) -> str:
    """e's DEF, given a fresh one where it has none."""
    if not e.get("DEF"):
        e.set("DEF", _fresh(tree, prefix))
    return e.get("DEF")


def _collection_of(tree: etree._ElementTree, collidable: etree._Element) -> etree._Element | None:
    """The RigidBodyCollection whose collider holds the collidable (X_ITE collides the bodies of
    one collection with each other; the collider only gives their parameters), else the first."""
    holder = next(collidable.iterancestors("CollisionCollection"), None)
    collections = list(tree.iter("RigidBodyCollection"))
    if holder is not None:
        owner = next(holder.iterancestors("RigidBodyCollection"), None)
        if owner is not None:
            return owner
        for c in collections:
            if any(u.get("USE") == holder.get("DEF") for u in c.iter("CollisionCollection") if holder.get("DEF")):
                return c
    return collections[0] if collections else None


def _make_static(tree: etree._ElementTree, e: etree._Element) -> str:
    """Puts the static collidable e on a fixed RigidBody where e lies: the body's position and
    orientation are e's translation and rotation, and e has none of its own, so that both
    readings of a body's collidable placement (docs/spec-loose-ends.md section 22) put it there."""
    name = _named(tree, e, NAMED + "FLOOR_")
    collection = _collection_of(tree, e)
    pose = {"position": e.attrib.pop("translation", "0 0 0"), "orientation": e.attrib.pop("rotation", "0 0 1 0")}
    fixed = etree.SubElement(collection, "RigidBody", DEF=_fresh(tree, ADDED + "STATIC_"),
                             fixed="true", containerField="bodies", **pose)
    use = etree.SubElement(fixed, e.tag, USE=name, containerField="geometry")
    order = {el: k for k, el in enumerate(tree.iter())}
    if order[use] < order[e]:  # a USE follows its DEF: the collidable moves into the body
        e.addnext(etree.Element(e.tag, USE=name, containerField=e.get("containerField", "collidables")))
        e.set("containerField", "geometry")
        use.addprevious(e)
        fixed.remove(use)
    return f"{name} (a collidable on no body) held where it lies by the fixed RigidBody {fixed.get('DEF')}"


def _watch(tree: etree._ElementTree, collider: etree._Element) -> str:
    """A CollisionSensor on the collision collection, at the top of the scene."""
    name = _named(tree, collider, NAMED + "COLLIDER_")
    sensor = etree.SubElement(tree.find(".//Scene"), "CollisionSensor", DEF=_fresh(tree, SENSOR))
    etree.SubElement(sensor, "CollisionCollection", USE=name, containerField="collider")
    return f"{name} watched by the CollisionSensor {sensor.get('DEF')}, so that the run shows its contacts"


def ready(scene: str, out: str, what: tuple[str, ...] = (MASS, CONTACT)) -> list[str]:
    """Writes the scene as X_ITE can show its fields to `out`, and says what was changed
    (nothing written where nothing needs to be). MASS: every moving RigidBody without a
    collidable gets a CollidableShape with a sphere of its mass and mean inertia. CONTACT:
    every collidable a collection or space holds that no body holds goes on a fixed RigidBody
    (XITE_STATIC_k) where it lies, in the collection whose collider holds it, and every
    collision collection gets a CollisionSensor (XITE_SENSOR_k)."""
    tree = _parse(scene)
    changes = []
    for body in tree.iter("RigidBody") if MASS in what else ():
        if body.get("USE") or body.get("fixed") == "true" or any(ch.tag in COLLIDABLES for ch in body):
            continue
        r = _sphere_radius(body)
        collidable = etree.SubElement(body, "CollidableShape", containerField="geometry")
        _named(tree, collidable, ADDED + "SHAPE_")
        shape = etree.SubElement(collidable, "Shape", containerField="shape")
        etree.SubElement(shape, "Sphere", radius=repr(r))
        changes.append(f"{body.get('DEF', 'a RigidBody')} given a collidable sphere of radius {r:.3g} m")
    if CONTACT in what:
        held = {ch.get("USE") or ch.get("DEF") for body in tree.iter("RigidBody") for ch in body
                if ch.tag in COLLIDABLES}
        static = [e for e in tree.iter(*COLLIDABLES) if e.getparent().tag in ("CollisionCollection", "CollisionSpace")
                  and not e.get("USE") and (not e.get("DEF") or e.get("DEF") not in held)]
        changes += [_make_static(tree, e) for e in static if _collection_of(tree, e) is not None]
        changes += [_watch(tree, c) for c in list(tree.iter("CollisionCollection")) if not c.get("USE")]
    if changes:
        _write(tree, out)
    return changes

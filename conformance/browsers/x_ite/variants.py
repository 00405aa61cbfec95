"""Scene variants that isolate one thing in X_ITE: a field at its default, the scene made
so X_ITE can show a field at all, a node type taken out.

A probe says a field is ignored only when the field is the one difference between two
recordings, and only where X_ITE could have shown it: X_ITE (Bullet through ammo.js)
takes a body's mass distribution from its collidables alone, so a body without one gets
no inertia and no torque turns it; and it collides only collidables held by a body, so a
floor that is a collidable on no body stops nothing. `ready` gives such bodies a sphere
and such collidables a fixed RigidBody; the probes then compare variants of that scene.
All variants are XML (the conformance scenes are).
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


def without(scene: str, node_type: str, fld: str, out: str) -> bool:
    """Writes the XML scene with `fld` removed from every `node_type` element (so at its
    default) to `out`; False where no element sets it, or the scene is not XML."""
    if not scene.endswith(".x3d"):
        return False
    tree = _parse(scene)
    changed = [e for e in tree.iter(node_type) if fld in e.attrib]
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


def needs(node_type: str, fld: str) -> tuple[str, ...]:
    """What a probe of this field needs of the scene for X_ITE to show the field at all."""
    if node_type in _CONTACT_TYPES or f"{node_type}.{fld}" in _CONTACT_FIELDS:
        return (CONTACT,)
    if node_type == "RigidBody":
        return (MASS,)
    return ()


def ready(scene: str, out: str, what: tuple[str, ...] = (MASS, CONTACT)) -> list[str]:
    """Writes the scene as X_ITE can show its fields to `out`, and says what was changed
    (nothing written where nothing needs to be). MASS: every moving RigidBody without a
    collidable gets a CollidableShape with a sphere of its mass and mean inertia. CONTACT:
    every collidable a collection or space holds that no body holds goes on a fixed
    RigidBody of the first collection, named XITE_STATIC_k so that its state can be read."""
    tree = _parse(scene)
    changes = []
    for body in tree.iter("RigidBody") if MASS in what else ():
        if body.get("USE") or body.get("fixed") == "true" or any(ch.tag in COLLIDABLES for ch in body):
            continue
        r = _sphere_radius(body)
        shape = etree.SubElement(etree.SubElement(body, "CollidableShape", containerField="geometry"), "Shape",
                                 containerField="shape")
        etree.SubElement(shape, "Sphere", radius=repr(r))
        changes.append(f"{body.get('DEF', 'a RigidBody')} given a collidable sphere of radius {r:.3g} m")
    held = {ch.get("USE") or ch.get("DEF") for body in tree.iter("RigidBody") for ch in body if ch.tag in COLLIDABLES}
    collections = list(tree.iter("RigidBodyCollection"))
    names = (f"XITE_STATIC_{k}" for k in itertools.count(1))
    for e in [e for e in tree.iter(*COLLIDABLES) if CONTACT in what
              and e.getparent().tag in ("CollisionCollection", "CollisionSpace") and not e.get("USE")]:
        if e.get("DEF") in held or not collections:
            continue
        if not e.get("DEF"):
            e.set("DEF", next(names))
        fixed = etree.SubElement(collections[0], "RigidBody", DEF=next(names), fixed="true", containerField="bodies")
        use = etree.SubElement(fixed, e.tag, USE=e.get("DEF"), containerField="geometry")
        order = {el: k for k, el in enumerate(tree.iter())}
        if order[use] < order[e]:  # a USE follows its DEF: the collidable moves into the body
            e.addnext(etree.Element(e.tag, USE=e.get("DEF"), containerField=e.get("containerField", "collidables")))
            e.set("containerField", "geometry")
            use.addprevious(e)
            fixed.remove(use)
        changes.append(f"{e.get('DEF')} (a collidable on no body) held by the fixed RigidBody {fixed.get('DEF')}")
    if changes:
        _write(tree, out)
    return changes

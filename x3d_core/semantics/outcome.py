"""What a run of the scene will really do where the file suggests otherwise (issue 16).

Each warning names the node and what a run does with it: bodies whose collision geometry
nothing lets collide (the collision set is collision.plan's own, so the warning agrees
with it), a body in no collection, a transform around physics nodes, a collidable shared
by two bodies, a scene with nothing to simulate, and a Script with directOutput TRUE that a
run ignores because it holds no physics node (analysis.script_reach). The commands that
judge or run a scene add them to what load() found (load's own diagnostics are about the
file, and a conformance case may leave a body out of its collider on purpose); only a scene
without errors gets them: they say what a run does, and a scene with errors does not run.
"""

from __future__ import annotations

import numpy as np

from x3d_core.model.scene import Diagnostic, Location, Node, Route, Scene

from . import rotation as R
from .analysis import RBP_TYPES, script_reach
from .collision import Geometry, collider, foreign_contacts
from .validate import by_type, diagnostic
from .world import STATIC, World, worlds

EMPTY = "no enabled RigidBody in an enabled RigidBodyCollection"
NOTHING_TO_SIMULATE = f"nothing to simulate: {EMPTY}; `x3drbp run` and `x3drbp compare` exit 1 and write no trace"
ANYWAY = "some browsers, X_ITE and Jolt-based ones, collide them anyway"


def simulates(scene: Scene) -> bool:
    """Whether a run has a body to move: an enabled RigidBody in an enabled collection (what
    world.worlds puts in the trace)."""
    return any(b.get("enabled") for c in scene.of_type("RigidBodyCollection") if c.get("enabled")
               for b in c.get("bodies"))


def outcome_warnings(scene: Scene, ws: list[World] | None = None) -> list[Diagnostic]:
    """Every warning of this module, in the order of its kinds; none for a scene with errors.
    ws: the scene's worlds where the caller has built them already (a run builds them once)."""
    if scene.errors:
        return []
    groups = by_type(scene)
    return [*_nothing_to_simulate(scene, groups), *_in_no_collection(scene, groups), *_transformed(scene, groups),
            *_shared_collidables(scene, groups), *_placed_on_body(scene, groups),
            *_never_colliding(scene, groups, worlds(scene) if ws is None else ws),
            *_scripts_holding_no_physics(scene, groups)]


def _nothing_to_simulate(scene: Scene, groups: dict[str, list[Node]]) -> list[Diagnostic]:
    if simulates(scene):
        return []
    anchor = next(iter(groups.get("RigidBodyCollection", []) + groups.get("RigidBody", [])), None)
    if anchor is None:
        return [Diagnostic("warning", Location(scene.path, 1, 1), "", NOTHING_TO_SIMULATE)]
    return [diagnostic(scene, anchor, "", NOTHING_TO_SIMULATE)]


def _in_no_collection(scene: Scene, groups: dict[str, list[Node]]) -> list[Diagnostic]:
    held = {id(b) for c in groups.get("RigidBodyCollection", []) for b in c.get("bodies")}
    return [diagnostic(scene, b, "", "in no RigidBodyCollection: it is not simulated and not in the trace "
                                  "(it stays where the file puts it)")
            for b in groups.get("RigidBody", []) if id(b) not in held]


def _places(node: Node) -> bool:
    """Whether a node that holds physics nodes moves them: it gives a translation, rotation or
    scale other than the identity (ignoring an identity changes nothing). A node x3drbp does
    not model keeps its values as text: it counts wherever it gives one."""
    given = [f for f in ("translation", "rotation", "scale") if f in node.values]
    if node.spec is None:
        return bool(given)
    return not all(_identity(f, node.values[f]) for f in given)


def _identity(field: str, value: np.ndarray) -> bool:
    if field == "rotation":
        return abs(abs(R.from_axis_angle(value)[0]) - 1) < 1e-12  # a turn of 0 or 2 pi
    return bool(np.all(value == (1 if field == "scale" else 0)))


def _transformed(scene: Scene, groups: dict[str, list[Node]]) -> list[Diagnostic]:
    """A transform around a RigidBodyCollection, or a RigidBody outside one: bodies are in
    world coordinates, so a run ignores it (each transform once, naming what it holds)."""
    parents: dict[int, list[Node]] = {}
    for n in scene.nodes():
        for c in n.children():
            parents.setdefault(id(c), []).append(n)
    held: dict[int, list[Node]] = {}  # transform -> the physics nodes it places
    for p in groups.get("RigidBodyCollection", []) + groups.get("RigidBody", []):
        for a in _ancestors(p, parents):
            if _places(a):
                held.setdefault(id(a), []).append(p)
    return [diagnostic(scene, t, "", f"its transform is ignored for {_names(held[id(t)])}: bodies are in world "
                                  "coordinates, so a run places them by their own fields alone")
            for t in scene.nodes() if id(t) in held]


def _ancestors(node: Node, parents: dict[int, list[Node]]) -> list[Node]:
    """Every node that holds this one, however deep; a RigidBody's search stops at its
    collection, whose own search covers what holds it."""
    out: list[Node] = []
    seen: set[int] = set()
    stack = list(parents.get(id(node), []))
    while stack:
        a = stack.pop()
        if id(a) in seen or (node.type_name == "RigidBody" and a.type_name == "RigidBodyCollection"):
            continue
        seen.add(id(a))
        out.append(a)
        stack.extend(parents.get(id(a), []))
    return out


def _shared_collidables(scene: Scene, groups: dict[str, list[Node]]) -> list[Diagnostic]:
    """A collidable in two bodies' geometry: collision.plan gives it to the first body of the
    collection that holds it, and the other body has no shape from it."""
    out: list[Diagnostic] = []
    for coll in groups.get("RigidBodyCollection", []):
        if not coll.get("enabled"):
            continue
        owner: dict[int, Node] = {}
        for body in dict.fromkeys(coll.get("bodies")):
            for g in body.get("geometry"):
                first = owner.setdefault(id(g), body)
                if first is not body:
                    out.append(diagnostic(scene, body, "geometry", f"{g.label} is also in {first.label}'s geometry, "
                                       f"earlier in {coll.label}'s bodies: it moves and collides with "
                                       f"{first.label} only, and {body.label} gets no collision shape from it"))
    return out


# The clause's two readings of a body's own collidable's translation and rotation
# (docs/spec-loose-ends.md, "A collidable's translation and rotation on a body")
BODY_FRAME_READING = ("the clause reads it two ways: x3drbp takes 37.4.10's (collidables \"have their location set to "
                      "the same location as the body instance in which they are located\", so a run ignores its "
                      "{fields}), another browser may take 37.3.1's "
                      "(\"an offset from, and rotation about, the body's center\") and place the geometry elsewhere")


def _placed_on_body(scene: Scene, groups: dict[str, list[Node]]) -> list[Diagnostic]:
    """A collidable at the top of a RigidBody's geometry that gives a translation or rotation other
    than the identity: the one place where which of the clause's readings a run takes moves the
    geometry, so the scene depends on it."""
    out: list[Diagnostic] = []
    seen: set[int] = set()
    for body in groups.get("RigidBody", []):
        for g in body.get("geometry"):
            given = [f for f in ("translation", "rotation") if f in g.values and not _identity(f, g.values[f])]
            if given and id(g) not in seen:
                seen.add(id(g))
                out.append(diagnostic(scene, g, given[0], BODY_FRAME_READING.format(fields=" and ".join(given))))
    return out


def _never_colliding(scene: Scene, groups: dict[str, list[Node]], ws: list[World]) -> list[Diagnostic]:
    """Per collection, the enabled bodies that carry collision geometry of which collision.plan
    makes nothing that can touch another shape, with why. A body in the collision set whose
    every partner is joined to it is not counted: the joint rule keeps them apart, not the
    collider."""
    out: list[Diagnostic] = []
    for w in ws:
        carriers = [(row, b) for row, b in enumerate(w.bodies.nodes) if w.bodies.enabled[row] and b.get("geometry")]
        if not carriers or foreign_contacts(w.node, scene.routes):  # refused by name: analysis.features
            continue
        why, bodies = _why_apart(w, carriers, scene.routes, groups.get("CollisionSensor", []))
        if bodies:
            one = len(bodies) == 1
            out.append(diagnostic(scene, w.node, "collider", f"{_names(bodies)} carr{'ies' if one else 'y'} collision "
                                  f"geometry that never collides: {why}; "
                                  f"{'it' if one else 'they'} will pass through "
                                  f"{'every other body' if one else 'each other'} and the floor ({ANYWAY})"))
    return out


def _why_apart(w: World, carriers: list[tuple[int, Node]], routes: list[Route],
              sensors: list[Node]) -> tuple[str, list[Node]]:
    """Why the world's collision set leaves bodies out, and which of the carriers it leaves."""
    everyone = [b for _, b in carriers]
    chosen = collider(w.node, routes)
    if chosen is None:
        return _no_collider(w.node, routes, sensors), everyone
    if w.collisions is None:
        return f"its collider {chosen.label} is disabled", everyone
    shapes = w.collisions.geometries
    if len({g.body for g in shapes}) < 2:  # a body's (or the static world's) shapes never touch each other
        return f"its collider {chosen.label} holds {_too_few(shapes)} (a contact takes two collidables of " \
               "different bodies)", everyone
    in_set = {g.body for g in shapes}
    left = [b for row, b in carriers if row not in in_set]
    return f"the collider {chosen.label} gives {'it' if len(left) == 1 else 'them'} no collision shape", left


def _too_few(shapes: list[Geometry]) -> str:
    if len(shapes) < 2:
        return "one collidable" if shapes else "no collidable"
    return "static collidables only" if shapes[0].body == STATIC else "the collidables of one body only"


def _no_collider(coll: Node, routes: list[Route], sensors: list[Node]) -> str:
    """A collection with no collider, naming the sensors whose contacts could have given it one."""
    routed = {id(r.from_node) for r in routes if r.to_node is coll and r.to_field == "set_contacts"}
    unrouted = [s for s in sensors if id(s) not in routed]
    if not unrouted:
        return "the collection has no collider"
    return f"the collection has no collider, and the contacts of {_names(unrouted)} are not routed to its set_contacts"


def _scripts_holding_no_physics(scene: Scene, groups: dict[str, list[Node]]) -> list[Diagnostic]:
    """A Script with directOutput TRUE in a physics scene that holds no physics node, nor a node
    holding one (analysis.script_reach): a run ignores it rather than refusing the scene, and
    says so, with the one way the Script could still reach a body that x3drbp does not follow."""
    if not any(t in groups for t in RBP_TYPES):
        return []
    reaching = {id(r.script) for r in script_reach(scene)}
    return [diagnostic(scene, s, "directOutput", "TRUE, but none of its SFNode/MFNode fields holds a physics node "
                                                "or a node that holds one, so a run goes on without it, as without "
                                                "every Script; a physics node it reaches by name through the Browser "
                                                "would keep the file's values")
            for s in groups.get("Script", []) if s.get("directOutput") and id(s) not in reaching]


def _names(nodes: list[Node]) -> str:
    return ", ".join(n.label for n in nodes)

"""Scene analysis: what a scene holds and which features it needs.

Feature names join scenes, backends, cases and reports. A run models only what its scene
needs, and refuses by name and value each feature its backend declares unsupported at the
scene's value (backends/base.py, Backend.support and judged; `x3drbp run` exits 3): nothing
is ignored silently. 'RigidBody' for a node type in use, 'RigidBody.mass' for an input field
given a value other than its default, and derived names for what a field alone does not say
('RigidBody.inertia.offDiagonal', 'SingleAxisHingeJoint.limits',
'CollidableShape.geometry.Cone', 'CollisionCollection.appliedParameters.SLIP-1'; its
FRICTION_COEFFICIENT-2 only where the two frictionCoefficients differ: with equal ones the
flag asks for nothing beyond isotropic friction).

features() is what a scene uses (`x3drbp check`); run_uses() what a run of it needs: each use
with the value the scene gives it (a backend may hold that value anyway), and only where what
it governs exists (a joint's softness where there are joints, a contact parameter where two
collidables can touch): a field that acts on nothing asks nothing of an engine.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from x3d_core.model import fields as F
from x3d_core.model.scene import Node, Scene

from .applied import applied
from .collision import STATIC, collider, foreign_contacts
from .world import World, forced_outputs, slider_stops, worlds

RBP_TYPES = ("RigidBodyCollection", "RigidBody", "BallJoint", "SingleAxisHingeJoint", "DoubleAxisHingeJoint",
             "SliderJoint", "UniversalJoint", "MotorJoint", "CollisionCollection", "CollisionSpace",
             "CollisionSensor", "CollidableShape", "CollidableOffset", "Contact")
_ANGLE_LIMITS = {"SingleAxisHingeJoint": ("minAngle", "maxAngle"), "DoubleAxisHingeJoint": ("minAngle1", "maxAngle1")}


@dataclass
class Summary:
    bodies: int = 0
    fixed_bodies: int = 0
    joints: Counter = field(default_factory=Counter)
    collidables: Counter = field(default_factory=Counter)  # by geometry type
    collections: int = 0
    collision_collections: int = 0
    spaces: int = 0
    sensors: int = 0
    routes: int = 0

    def lines(self) -> list[str]:
        def counts(c: Counter) -> str:
            return ", ".join(f"{n} {k}" for k, n in sorted(c.items())) or "none"
        fixed = f" ({self.fixed_bodies} fixed)" if self.fixed_bodies else ""
        return [f"bodies: {self.bodies}{fixed}",
                f"joints: {sum(self.joints.values())} ({counts(self.joints)})" if self.joints else "joints: 0",
                f"collidables: {sum(self.collidables.values())} ({counts(self.collidables)})"
                if self.collidables else "collidables: 0",
                f"collections: {self.collections} RigidBodyCollection, {self.collision_collections} "
                f"CollisionCollection, {self.spaces} CollisionSpace",
                f"sensors: {self.sensors} CollisionSensor"]


def summarize(scene: Scene) -> Summary:
    s = Summary(routes=len(scene.routes))
    for n in scene.nodes():
        if n.spec is None:
            continue
        t = n.type_name
        if t == "RigidBody":
            s.bodies += 1
            s.fixed_bodies += bool(n.get("fixed"))
        elif n.spec.is_a("X3DRigidJointNode"):
            s.joints[t] += 1
        elif t == "CollidableShape":
            shape = n.get("shape")
            geom = shape.get("geometry") if shape is not None else None
            s.collidables[geom.type_name if geom is not None else "no geometry"] += 1
        elif t == "RigidBodyCollection":
            s.collections += 1
        elif t == "CollisionCollection":
            s.collision_collections += 1
        elif t == "CollisionSpace":
            s.spaces += 1
        elif t == "CollisionSensor":
            s.sensors += 1
    return s


# A Script whose directOutput is TRUE may set the fields of the nodes its SFNode/MFNode fields
# hold, and of what those hold, with no ROUTE (X3D 4.0 Scripting, the Script node): where one
# of them is a physics node, or holds one, a run that keeps the file's values would not be the
# file's run, so every backend refuses it (backends/base.py, Backend.support), naming the
# Script, the field and the node. A Script that holds none, or has directOutput FALSE, is
# ignored like every Script (x3drbp runs none): the first acts on no physics node it holds
# (outcome.py says so, and that a node it looks up by name is not followed), the second only
# through its ROUTEs, each counted in features() itself.
SCRIPT_DIRECT_OUTPUT = "Script.directOutput"
# A CollisionSensor watching a collection that no enabled RigidBodyCollection collides with: the
# engine must detect that collection's contacts for the sensor without acting on them
# (x3d_core/semantics/collision.py, watch); counted where such a set is planned
WATCHED_ONLY = "CollisionSensor.collider.watchedOnly"


@dataclass(frozen=True)
class Reach:
    """The nodes a directOutput Script holds in one of its fields that are physics nodes or
    hold one (each with the first physics node under it): what the Script may change with no
    ROUTE."""
    script: Node
    field: str
    held: tuple[tuple[Node, Node], ...]  # (node held, the physics node at or under it)

    def __str__(self) -> str:
        """In the file's words: 'Script Mover holds Transform T (holding RigidBodyCollection
        World) in its field root'."""
        nodes = ", ".join(n.label if n is p else f"{n.label} (holding {p.label})" for n, p in self.held)
        return f"{self.script.label} holds {nodes} in its field {self.field}"


def _physics_within(node: Node) -> Node | None:
    """The first physics node at or under the node (through every field), None where it holds none."""
    seen: set[int] = set()
    stack = [node]
    while stack:
        n = stack.pop()
        if id(n) in seen:
            continue
        seen.add(id(n))
        if n.spec is not None and n.type_name in RBP_TYPES:
            return n
        stack.extend(reversed(list(n.children())))
    return None


def script_reach(scene: Scene) -> list[Reach]:
    """Each node a Script with directOutput TRUE holds in a declared SFNode/MFNode field that is
    a physics node or holds one."""
    out = []
    for script in scene.of_type("Script"):
        if not script.get("directOutput"):
            continue
        for decl in script.interface:
            nodes = [n for n in (decl.value if isinstance(decl.value, list) else [decl.value]) if isinstance(n, Node)]
            held = tuple((n, p) for n, p in ((n, _physics_within(n)) for n in nodes) if p is not None)
            if held:
                out.append(Reach(script, decl.name, held))
    return out


@dataclass(frozen=True)
class Use:
    """One feature as a scene uses it: with the value it gives the field where the feature is
    one field's (None for a node type, a derived name or an input). A backend judges both
    (backends/base.py, judged): a value may be what its engine does anyway."""
    feature: str
    value: Any = None
    ftype: F.FieldType | None = None
    where: str = ""  # what in the file makes a use no field value says (a Script's Reach)
    spelled: str = ""  # the field's name in the file, where it is not the feature's (X3D 3.x's stopBounce1)

    def __str__(self) -> str:
        """As a refusal names it: 'RigidBodyCollection.constantForceMix = 0.5',
        'Script.directOutput (Script Mover holds RigidBody Ball in its field ball)',
        'DoubleAxisHingeJoint.stop1Bounce = 0.5 (stopBounce1 in the file)'."""
        if self.where:
            return f"{self.feature} ({self.where})"
        said = self.feature if self.value is None else f"{self.feature} = {F.format_xml(self.ftype, self.value)}"
        return f"{said} ({self.spelled} in the file)" if self.spelled else said


_UNSEEN = ("bboxCenter", "bboxSize", "bboxDisplay", "visible", "metadata", "description")  # no physics


def _derived(n: Node) -> Iterator[str]:
    """The names a field alone does not say: which shape, which limits, which parameters apply."""
    t = n.type_name
    if t == "RigidBody":
        m = np.asarray(n.get("inertia")).reshape(3, 3)
        if np.any(m - np.diag(np.diag(m))):
            yield "RigidBody.inertia.offDiagonal"
        if n.get("massDensityModel") is not None:
            yield f"RigidBody.massDensityModel.{n.get('massDensityModel').type_name}"
        if n.get("forces").size:
            yield "RigidBody.forces"
        if n.get("torques").size:
            yield "RigidBody.torques"
    elif t in _ANGLE_LIMITS:
        lo, hi = (n.get(f) for f in _ANGLE_LIMITS[t])
        if lo > -math.pi + 1e-6 or hi < math.pi - 1e-6:
            yield f"{t}.limits"
    elif t == "SliderJoint" and slider_stops(n) is not None:  # min > max: no stops at all (37.4.13)
        yield "SliderJoint.limits"
    elif t == "CollidableShape":
        shape = n.get("shape")
        geom = shape.get("geometry") if shape is not None else None
        if geom is not None:
            yield f"CollidableShape.geometry.{geom.type_name}"
    if t in ("CollisionCollection", "Contact"):
        on = applied(n.get("appliedParameters"))
        fc = np.asarray(n.get("frictionCoefficients"), dtype=np.float64)
        if fc[0] == fc[1]:  # one coefficient both ways: what every reading of the flag applies
            on = on - {"FRICTION_COEFFICIENT-2"}
        yield from (f"{t}.appliedParameters.{p}" for p in sorted(on))
    if n.spec.is_a("X3DRigidJointNode"):
        outputs = tuple(f for f, fd in n.spec.fields.items() if fd.access == "outputOnly")
        if forced_outputs(outputs, n.get("forceOutput")):  # a selection of none uses nothing
            yield f"{t}.forceOutput"


def _node_uses(n: Node) -> Iterator[Use]:
    """What one physics node uses: its type, each field at a value other than its default."""
    t = n.type_name
    yield Use(t)
    for name, value in n.values.items():
        fd = n.spec.fields[name]
        if fd.type.kind != "node" and name not in _UNSEEN and not F.values_equal(fd.type, value, fd.default):
            spelled = n.spelling(name)
            yield Use(f"{t}.{name}", value, fd.type, spelled=spelled if spelled != name else "")
    yield from map(Use, _derived(n))


def _uses(scene: Scene) -> Iterator[tuple[Node, Use]]:
    """Every use, with the node it acts on (a route's: the node it goes into)."""
    for n in scene.nodes():
        if n.spec is not None and n.type_name in RBP_TYPES:
            yield from ((n, u) for u in _node_uses(n))
    for r in scene.routes:  # inputs that change during a run
        if r.to_node.type_name not in RBP_TYPES:
            continue
        if r.to_field == "set_contacts" and r.from_node.type_name == "CollisionSensor" and r.from_field == "contacts":
            foreign = foreign_contacts(r.to_node, scene.routes)
            yield r.to_node, Use("RigidBodyCollection.set_contacts.fromOtherCollider" if foreign
                                 else "RigidBodyCollection.set_contacts.fromSensor")
        else:
            yield r.to_node, Use(f"{r.to_node.type_name}.{r.to_field}.routed")
    yield from ((r.script, Use(SCRIPT_DIRECT_OUTPUT, where=str(r))) for r in script_reach(scene))
    used = {id(collider(c, scene.routes)) for c in scene.of_type("RigidBodyCollection") if c.get("enabled")}
    yield from ((s, Use(WATCHED_ONLY)) for s in scene.of_type("CollisionSensor")
                if s.get("enabled") and s.get("collider") is not None and id(s.get("collider")) not in used)


def features(scene: Scene) -> list[str]:
    """The sorted feature names the scene uses, whatever they act on (`x3drbp check`)."""
    return sorted({u.feature for _, u in _uses(scene)})


COLLISION_FEATURES = ("CollisionCollection", "CollisionSpace", "CollisionSensor", "CollidableShape",
                      "CollidableOffset")
# RigidBodyCollection fields that act on its joints' constraint rows and on its contacts (ODE's
# world ERP and CFM: a contact takes them unless its collider's appliedParameters say otherwise)
JOINT_SOFTNESS = ("errorCorrection", "constantForceMix")
# fields that act on contacts alone: a RigidBodyCollection's surface layer and correction speed,
# and every CollisionCollection field but enabled and collidables
CONTACT_FIELDS = frozenset({("RigidBodyCollection", f) for f in ("contactSurfaceThickness", "maxCorrectionSpeed")} | {
    ("CollisionCollection", f) for f in ("appliedParameters", "bounce", "minBounceSpeed", "frictionCoefficients",
                                         "surfaceSpeed", "slipFactors", "softnessErrorCorrection",
                                         "softnessConstantForceMix")})


@dataclass(frozen=True)
class _Reach:
    """What a run's enabled collections act on, by node id: whether any has a collider or a
    sensor watches a set no collection collides with, the collections whose joints constrain two
    bodies, the collections and colliders under which two collidables can touch, and the sensors
    of the watched sets."""
    colliding: bool
    jointed: frozenset[int]
    touching: frozenset[int]
    watched: frozenset[int]


def _constrains(w: World) -> bool:
    """Whether a joint of the world holds two bodies together (a MotorJoint only pushes)."""
    return any(j.type != "MotorJoint" and j.body1 != j.body2 for j in w.joints)


def _can_touch(w: World) -> bool:
    """Whether the world's collision set holds a pair it tests with a moving body in it: a
    contact between two static or fixed collidables moves nothing."""
    c = w.collisions
    if c is None:
        return False
    moving = np.array([g.body != STATIC and not w.bodies.fixed[g.body] for g in c.geometries], dtype=bool)
    return bool((moving & c.touchable()).any())


def _reach(scene: Scene, ws: list[World]) -> _Reach:
    """What the worlds a run builds act on (x3d_core/semantics/world.py, the same worlds and collision sets)."""
    touching = [w for w in ws if _can_touch(w)]
    watching = frozenset(id(s) for w in ws for c in w.watched for _, s in c.sensors)
    return _Reach(colliding=bool(watching) or any(collider(w.node, scene.routes) is not None for w in ws),
                  jointed=frozenset(id(w.node) for w in ws if _constrains(w)),
                  touching=frozenset(id(n) for w in touching for n in (w.node, w.collisions.collider)),
                  watched=watching)


def _acts(node: Node, use: Use, r: _Reach) -> bool:
    """Whether a use acts in a run: whether what it governs exists there."""
    kind, _, rest = use.feature.partition(".")
    field_name = rest.partition(".")[0]
    if kind == "Contact":  # only set_contacts gives a Contact an effect, and its route counts
        return False
    if use.feature == WATCHED_ONLY:
        return id(node) in r.watched
    if kind == "SliderJoint" and field_name.startswith("stop") and not use.feature.endswith(".routed"):
        return slider_stops(node) is not None  # a stop's bounce or correction: nothing where there are no stops
    if kind == "RigidBodyCollection" and field_name in JOINT_SOFTNESS:
        return id(node) in r.jointed or id(node) in r.touching
    if (kind, field_name) in CONTACT_FIELDS:
        return id(node) in r.touching
    return r.colliding or not use.feature.startswith(COLLISION_FEATURES)


def run_uses(scene: Scene, ws: list[World] | None = None) -> list[Use]:
    """The uses a run of the scene needs, sorted, each (feature, value) once: a use counts only
    where what it governs exists. Collision geometry and sensors only where some enabled
    RigidBodyCollection has a collider, its own or the one its routed contacts come from, or a
    sensor watches a set that none collides with (WATCHED_ONLY, where one is planned);
    contact parameters (its collider's, and its contactSurfaceThickness and
    maxCorrectionSpeed) only where that collider holds two collidables that can touch, one
    on a moving body; errorCorrection and constantForceMix only where the collection has
    such contacts or a joint between two bodies; a SliderJoint's stopBounce and
    stopErrorCorrection only where it has stops (world.slider_stops); a Contact node never by
    itself. ws: the scene's worlds where the caller has built them already (a run builds them
    once)."""
    r = _reach(scene, worlds(scene) if ws is None else ws)
    out = {str(u): u for n, u in _uses(scene) if _acts(n, u, r)}
    return [out[k] for k in sorted(out)]


def run_features(scene: Scene) -> list[str]:
    """The sorted feature names a run of the scene needs (run_uses)."""
    return sorted({u.feature for u in run_uses(scene)})

"""From a scene to what an engine must build: one World per enabled RigidBodyCollection.

Plain data in bulk arrays (bodies are rows), so that a backend builds its model in a
few loops and reads and writes state as arrays. Every quantity is in SI units and
world coordinates unless its name says 'local'. The data itself (Bodies, State, Joint, World)
is defined in world_data.py, which collision.py imports too; engines import it from here.
"""

from __future__ import annotations

import numpy as np

from x3d_core.model import fields as F
from x3d_core.model.scene import Node, Scene

from . import rotation as R
from .collision import plan, watch
# the data, defined in world_data (module docstring), is imported from here by every engine
from .world_data import JOINT_TYPES, STATIC, Bodies, Joint, State, World  # noqa: F401



def node_names(scene: Scene) -> dict[int, str]:
    """The name each node goes by in traces (unique: see trace_names)."""
    return trace_names(scene)[0]


def trace_names(scene: Scene) -> tuple[dict[int, str], list[tuple[Node, str]]]:
    """The name each node goes by in traces, and the nodes whose name had to be derived.

    A node goes by its DEF, else TYPE_k with k counting that type's nodes without a DEF in
    file order (depth first, from 1). Names must be unique, or two bodies' columns merge in a
    trace: a DEF met again (two PROTO instances' inner DEFs, a redefined DEF) becomes DEF_2,
    DEF_3...; a TYPE_k that a DEF already takes (a DEF RigidBody_1 beside an unnamed body)
    moves on to the next free k. Those nodes are returned with their derived names."""
    nodes = list(scene.nodes())
    taken = {n.def_name for n in nodes if n.def_name}
    names: dict[int, str] = {}
    derived: list[tuple[Node, str]] = []
    used: set[str] = set()
    counts: dict[str, int] = {}
    for n in nodes:
        if n.def_name and n.def_name not in used:
            name = n.def_name
        else:
            base = n.def_name or n.type_name
            k = counts.get(base, 1 if n.def_name else 0) + 1
            natural = k
            while f"{base}_{k}" in taken or f"{base}_{k}" in used:
                k += 1
            counts[base] = k
            name = f"{base}_{k}"
            if n.def_name or k != natural:
                derived.append((n, name))
        names[id(n)] = name
        used.add(name)
    return names, derived


def worlds(scene: Scene) -> list[World]:
    names = node_names(scene)
    out = [_world(c, names) for c in scene.of_type("RigidBodyCollection") if c.get("enabled")]
    sensors = [s for s in scene.of_type("CollisionSensor") if s.get("enabled")]
    for w in out:
        w.collisions = plan(w, names, scene.routes)
        if w.collisions is not None:
            w.collisions.sensors = [(names[id(s)], s) for s in sensors if s.get("collider") is w.collisions.collider]
    watch(out, sensors, names, scene.routes)
    return out


def body_inertia(node: Node) -> np.ndarray:
    """A RigidBody's inertia about its centre of mass, body axes: its inertia field, or its
    massDensityModel's for its mass. Not finite where that overflows (validate says so, one
    line): never a numpy warning, never an OverflowError."""
    m = node.get("mass")
    model = node.get("massDensityModel")
    with np.errstate(over="ignore"):
        if model is None:
            i = np.asarray(node.get("inertia"), dtype=np.float64).reshape(3, 3)
            return 0.5 * i + 0.5 * i.T  # the field is symmetric by definition; read it so (halves: no overflow)
        if model.type_name == "Sphere":
            r = model.get("radius")
            return np.diag([0.4 * m * (r * r)] * 3)  # not eye * it: 0 * inf is nan
        if model.type_name == "Box":
            x, y, z = model.get("size")
            return np.diag([y * y + z * z, x * x + z * z, x * x + y * y]) * m / 12.0
        r, h = model.get("bottomRadius"), model.get("height")  # Cone, about its centroid, axis y
        side = 3.0 / 20.0 * m * r * r + 3.0 / 80.0 * m * h * h
        return np.diag([side, 0.3 * m * r * r, side])


def _bodies(nodes: list[Node], names: dict[int, str]) -> Bodies:
    n = len(nodes)

    def vec(f: str) -> np.ndarray:
        return np.array([b.get(f) for b in nodes], dtype=np.float64).reshape(n, 3)

    def flag(f: str) -> np.ndarray:
        return np.array([bool(b.get(f)) for b in nodes], dtype=bool)

    def num(f: str) -> np.ndarray:
        return np.array([b.get(f) for b in nodes], dtype=np.float64)

    def summed(f: str) -> np.ndarray:
        return np.array([np.sum(b.get(f), axis=0) if len(b.get(f)) else np.zeros(3) for b in nodes]).reshape(n, 3)

    axis = vec("finiteRotationAxis")
    return Bodies(
        names=[names[id(b)] for b in nodes], nodes=nodes, mass=num("mass"),
        inertia=np.array([body_inertia(b) for b in nodes]).reshape(n, 3, 3), com=vec("centerOfMass"),
        position=vec("position"),
        orientation=R.from_axis_angle(np.array([b.get("orientation") for b in nodes]).reshape(n, 4)),
        linear_velocity=vec("linearVelocity"), angular_velocity=vec("angularVelocity"),
        fixed=flag("fixed") | ~flag("enabled"), enabled=flag("enabled"), use_gravity=flag("useGlobalGravity"),
        auto_damp=flag("autoDamp"), linear_damping=num("linearDampingFactor"),
        angular_damping=num("angularDampingFactor"), forces=summed("forces"), torques=summed("torques"),
        finite_rotation=flag("useFiniteRotation"), finite_rotation_axis=axis,
        auto_disable=flag("autoDisable"),
        disable_thresholds=np.stack([num("disableLinearSpeed"), num("disableAngularSpeed"),
                                     num("disableTime")], axis=-1).reshape(n, 3))


# each joint type's axis fields, in the order of Joint.axes's rows
AXES = {"SingleAxisHingeJoint": ("axis",), "SliderJoint": ("axis",),
         "DoubleAxisHingeJoint": ("axis1", "axis2"), "UniversalJoint": ("axis1", "axis2"),
         "MotorJoint": ("motor1Axis", "motor2Axis", "motor3Axis")}


def undirected(w: World) -> list[str]:
    """The axes the world's joints need that are zero, each named as JointType NAME.field =
    the value the scene gives (0 0 0, or -0 0 0): a zero axis defines no direction and the spec
    gives none in its place (it is X3D 3.3's default for most joint axes), so every backend
    refuses it rather than each failing its own way. Any other finite axis, 1e200 0 0 or
    1e-170 0 0, has one (rotation.unit). A joint needs the axes of its type where it joins two
    ends an engine builds it between (not a body to itself, or static to static). A MotorJoint
    needs none: its zero axis is one the clause defines, "disabled" (37.4.9), and pushes nothing
    (evaluator._Motors)."""
    out = []
    for j in w.joints:
        if j.body1 == j.body2 or j.type == "MotorJoint":
            continue
        out += [f"{j.type} {j.name}.{f} = {F.format_xml(F.FIELD_TYPES['SFVec3f'], j.node.get(f))}"
                for k, f in enumerate(AXES.get(j.type, ())) if not np.any(j.axes[k])]
    return out


def slider_stops(node: Node) -> tuple[float, float] | None:
    """A SliderJoint's stops (minSeparation, maxSeparation), or None: "If minSeparation is greater
    than maxSeparation, the stops become ineffective as if the object has no stops at all" (37.4.13
    SliderJoint). Decided here once, so that no backend swaps them into stops of its own."""
    lo, hi = float(node.get("minSeparation")), float(node.get("maxSeparation"))
    return None if lo > hi else (lo, hi)


# below this |axis1 x axis2| (unit axes) the two are one line: ODE's own test for its hinge2
PARALLEL = 1e-9


def parallel(w: World) -> list[str]:
    """The DoubleAxisHingeJoints of the world whose axis1 and axis2 are parallel, each named with
    both axes as the scene gives them: the joint "has two independent axes" (37.4.8
    DoubleAxisHingeJoint), and one line is not two. ODE refused it; MuJoCo's and DART's models were singular (MuJoCo
    non-finite in the first frame of a driven hinge2, DART warning at every step), Bullet ran it:
    every backend refuses it now. Only joints that join two ends and whose axes are not zero
    (undirected names those). A UniversalJoint's axes are the spec's to leave undefined where
    not perpendicular (x3d_core.semantics.validate warns); ODE alone refuses parallel ones, as its engine
    cannot build them. R.cross: np.cross cost 30 us a joint of every run's plan."""
    out = []
    for j in w.joints:
        if j.type == "DoubleAxisHingeJoint" and j.body1 != j.body2 and np.all(np.any(j.axes[:2], axis=1)) \
                and np.linalg.norm(R.cross(j.axes[0], j.axes[1])) < PARALLEL:
            a1, a2 = (F.format_xml(F.FIELD_TYPES["SFVec3f"], j.node.get(f)) for f in ("axis1", "axis2"))
            out.append(f"{j.type} {j.name}: axis1 = {a1} and axis2 = {a2} are parallel")
    return out


def forced_outputs(outputs: tuple[str, ...], wanted: list[str]) -> tuple[str, ...]:
    """The outputs a forceOutput value selects (37.3.3): all where "ALL" is anywhere in it,
    beside "NONE" too (the clause says both there: docs/spec-loose-ends.md, section 22);
    none where "NONE" is (the other values ignored) or it is empty; else those it names."""
    if "ALL" in wanted:
        return outputs
    return () if "NONE" in wanted else tuple(f for f in outputs if f in wanted)


def _joint(node: Node, rows: dict[int, int], fixed: np.ndarray, names: dict[int, str]) -> Joint:
    def row(f: str) -> int:
        b = node.get(f)
        if b is None or id(b) not in rows or fixed[rows[id(b)]]:
            return STATIC
        return rows[id(b)]

    axes = np.zeros((3, 3))
    for k, f in enumerate(AXES.get(node.type_name, ())):
        axes[k] = R.unit(node.get(f))  # 1e200 0 0 is +x; 0 0 0 stays zero (undirected)
    spec = node.spec
    params = {f: float(node.get(f)) for f, fd in spec.fields.items()
              if fd.access != "outputOnly" and fd.type.name in ("SFFloat", "SFInt32", "SFBool")}
    outputs = tuple(f for f, fd in spec.fields.items() if fd.access == "outputOnly")
    selected = forced_outputs(outputs, node.get("forceOutput"))
    anchor = np.asarray(node.get("anchorPoint"), dtype=np.float64) if "anchorPoint" in spec.fields else np.zeros(3)
    stops = slider_stops(node) if node.type_name == "SliderJoint" else None
    return Joint(names[id(node)], node.type_name, node, row("body1"), row("body2"), anchor, axes, params, selected,
                 stops)


def _world(coll: Node, names: dict[int, str]) -> World:
    unique = list({id(b): b for b in coll.get("bodies")}.values())  # a body listed twice is one body
    bodies = _bodies(unique, names)
    rows = {id(b): i for i, b in enumerate(unique)}
    joints = [_joint(j, rows, bodies.fixed, names) for j in coll.get("joints")]
    w = World(name=names[id(coll)], node=coll, gravity=np.asarray(coll.get("gravity"), dtype=np.float64),
              iterations=int(coll.get("iterations")), error_correction=float(coll.get("errorCorrection")),
              constant_force_mix=float(coll.get("constantForceMix")),
              max_correction_speed=float(coll.get("maxCorrectionSpeed")),
              prefer_accuracy=bool(coll.get("preferAccuracy")),
              contact_surface_thickness=float(coll.get("contactSurfaceThickness")),
              bodies=bodies, joints=joints)
    _forest(w)
    return w


def _forest(w: World) -> None:
    """Spanning forest of the joint graph: bodies joined to the static environment hang
    from it, each other connected group from its first body; leftover joints close loops."""
    n = len(w.bodies)
    parent = np.full(n, World.FREE, dtype=int)
    parent_joint = np.full(n, -1, dtype=int)
    placed = np.zeros(n, dtype=bool)
    adjacency: dict[int, list[tuple[int, int]]] = {i: [] for i in range(-1, n)}
    for k, j in enumerate(w.joints):
        if j.body1 == j.body2 or j.type == "MotorJoint":  # a motor constrains nothing: it pushes
            continue
        adjacency[j.body1].append((j.body2, k))
        adjacency[j.body2].append((j.body1, k))
    used: set[int] = set()
    order: list[int] = []

    def grow(start: int) -> None:
        queue = [start]
        while queue:
            a = queue.pop(0)
            for b, k in adjacency[a]:
                if b == STATIC or placed[b] or k in used:
                    continue
                placed[b] = True
                parent[b], parent_joint[b] = a, k
                used.add(k)
                order.append(b)
                queue.append(b)

    for i in np.flatnonzero(w.bodies.fixed):  # a fixed body is part of the static environment
        placed[i] = True
        parent[i] = STATIC
        order.append(int(i))
    grow(STATIC)
    for i in range(n):
        if not placed[i]:
            placed[i] = True
            order.append(i)
            grow(i)
    w.parent, w.parent_joint, w.order = parent, parent_joint, order
    w.loop_joints = [k for k, j in enumerate(w.joints) if k not in used and j.type != "MotorJoint"]

"""Checks that need the whole scene: what clause 37 leaves undefined, and names that must exist."""

from __future__ import annotations

import sys

import numpy as np

from x3d_core.model.scene import Diagnostic, Node, Scene

from . import rotation as R
from .applied import CANONICAL, canonical
from .world import AXES, PARALLEL, body_inertia

# A pair of axes counts as perpendicular when |cos| is below this: well under the
# float32 rounding of an axis written with 6-7 digits, far above any intended angle.
PERPENDICULAR_COS = 1e-5


def by_type(scene: Scene) -> dict[str, list[Node]]:
    """The scene's typed nodes grouped by type name, in one walk."""
    groups: dict[str, list[Node]] = {}
    for n in scene.nodes():
        if n.spec is not None:
            groups.setdefault(n.type_name, []).append(n)
    return groups


def diagnostic(scene: Scene, node: Node, field: str, message: str, severity: str = "warning") -> Diagnostic:
    """A diagnostic about a node's field (by its X3D 4.0 name), at the field's place in the file
    (else the node's), named as the file spells it."""
    subject = f"{node.label}.{node.spelling(field)}" if field else node.label
    return Diagnostic(severity, scene.locate(node.field_locs.get(field, node.loc), subject), subject, message)


def _joints(groups: dict[str, list[Node]]) -> list[Node]:
    return [j for t in AXES.keys() | {"BallJoint"} for j in groups.get(t, [])]


def validate(scene: Scene, groups: dict[str, list[Node]]) -> None:
    out: list[Diagnostic] = []

    def warn(node: Node, field: str, message: str) -> None:
        out.append(diagnostic(scene, node, field, message))

    def err(node: Node, field: str, message: str) -> None:
        out.append(diagnostic(scene, node, field, message, "error"))

    owners: dict[int, list[Node]] = {}
    body_owners: dict[int, tuple[Node, list[Node]]] = {}
    for coll in groups.get("RigidBodyCollection", []):
        bodies = {id(b) for b in coll.get("bodies")}
        for b in coll.get("bodies"):
            body_owners.setdefault(id(b), (b, []))[1].append(coll)
        for j in coll.get("joints"):
            owners.setdefault(id(j), []).append(coll)
            for f in ("body1", "body2"):
                b = j.get(f)
                if b is not None and id(b) not in bodies:
                    warn(j, f, f"{b.label} is not in the joint's collection {coll.label}; the spec leaves such "
                               f"a joint undefined: a run ties this end to the static world, as if {f} were NULL, "
                               f"and the joint does not act on {b.label}")
    for joint in _joints(groups):
        colls = owners.get(id(joint), [])
        if len(colls) > 1:
            warn(joint, "", f"joint is in {len(colls)} collections ({', '.join(c.label for c in colls)}); "
                            "the spec leaves this undefined")
        b1, b2 = joint.get("body1"), joint.get("body2")
        if b1 is None and b2 is None:
            warn(joint, "body1", "joint has neither body1 nor body2 and joins nothing")
        elif b1 is b2:
            warn(joint, "body2", "joint joins a body to itself")
        _force_output(joint, err, warn)
        if joint.type_name in ("UniversalJoint", "DoubleAxisHingeJoint"):
            u1, u2 = R.unit(joint.get("axis1")), R.unit(joint.get("axis2"))  # 1e200 0 0 is +x, no overflow
            cos = float(np.dot(u1, u2))
            if joint.type_name == "UniversalJoint" and abs(cos) > PERPENDICULAR_COS:
                angle = np.degrees(np.arccos(np.clip(cos, -1, 1)))
                warn(joint, "axis2", f"axis1 and axis2 are {angle:.6g} degrees apart, not perpendicular; "
                                     "the spec leaves the joint undefined")
            elif joint.type_name == "DoubleAxisHingeJoint" and np.any(u1) and np.any(u2) \
                    and np.linalg.norm(R.cross(u1, u2)) < PARALLEL:  # world.parallel's test: every backend refuses it
                warn(joint, "axis2", "axis1 and axis2 are parallel: one line, not the two independent axes the "
                                     "joint turns about")
        for f in AXES.get(joint.type_name, ()) if joint.type_name != "MotorJoint" else ():
            if not np.any(joint.get(f)):  # a MotorJoint's zero axis is defined: "disabled" (37.4.9)
                warn(joint, f, "axis is 0 0 0 and defines no direction")
    for body in groups.get("RigidBody", []):
        if "inertia" in body.values and body.get("massDensityModel") is None:
            _physical_inertia(body, err)
        model = body.get("massDensityModel")
        if model is not None and not np.all(np.isfinite(body_inertia(body))):
            err(body, "massDensityModel", f"a {model.type_name} of {body.get('mass'):g} kg makes an inertia past the "
                                          f"largest double ({sys.float_info.max:.3g}): no engine can turn the body")
    for body, colls in body_owners.values():
        distinct = list({id(c): c for c in colls}.values())
        if len(distinct) > 1:
            warn(body, "", f"body is in {len(distinct)} collections; the spec leaves this undefined")
        elif len(colls) > 1:
            warn(body, "", f"body is listed {len(colls)} times in {distinct[0].label}'s bodies; it is one body, "
                           "simulated once")
    for node in groups.get("CollisionCollection", []) + groups.get("Contact", []):
        for v in node.get("appliedParameters"):
            if canonical(v) is None:
                err(node, "appliedParameters", f"{v!r} is not an applied parameter; allowed: "
                                               f"{', '.join(CANONICAL)} (or with '_' for '-')")
    for sensor in groups.get("CollisionSensor", []):
        if sensor.get("collider") is None:
            warn(sensor, "collider", "no collider: the sensor watches nothing and never reports a contact")
    scene.diagnostics.extend(out)


def _physical_inertia(body: Node, err) -> None:
    """A rigid body's principal moments are positive and each is at most the sum of the
    other two; engines refuse (MuJoCo) or quietly clamp (Bullet) anything else."""
    m = np.asarray(body.get("inertia"), dtype=np.float64).reshape(3, 3)
    if not np.allclose(m, m.T, rtol=1e-6, atol=1e-12):
        err(body, "inertia", "the inertia tensor is not symmetric (I12 = I21, I13 = I31, I23 = I32)")
        return
    scale = float(np.max(np.abs(m))) or 1.0  # the moments compared in its units: sums near the largest double overflow
    a, b, c = np.linalg.eigvalsh(m / scale)
    if a <= 0 or a + b < c - 1e-9 * max(abs(c), 1e-300):
        with np.errstate(over="ignore"):
            a, b, c = np.array([a, b, c]) * scale
        err(body, "inertia", f"not the inertia of a rigid body: principal moments {a:.6g}, {b:.6g}, {c:.6g} "
                             "must be positive, each no more than the sum of the other two")


def _force_output(joint: Node, err, warn) -> None:
    """37.3.3: the values name outputs "exactly", so an unknown name is an error; but "Other
    values provided in addition to "NONE" shall be ignored", so beside NONE no value is an
    error, only warned of, and ALL beside NONE is where the clause says both (world.forced_outputs
    takes ALL)."""
    outputs = [f for f, fd in joint.spec.fields.items() if fd.access == "outputOnly"]
    names = joint.get("forceOutput")
    if "NONE" in names:
        others = [v for v in names if v != "NONE"]
        if "ALL" in others:
            warn(joint, "forceOutput", "holds both ALL and NONE, and 37.3.3 gives both: ALL anywhere updates all "
                                       "fields, NONE updates none; a run updates every output (ALL), and an "
                                       "implementation that updates none follows the clause too")
        elif others:
            warn(joint, "forceOutput", f"{', '.join(map(repr, others))} beside NONE: ignored, as 37.3.3 says of "
                                       "values in addition to NONE; the joint reports no outputs")
        return
    for v in names:
        if v != "ALL" and v not in outputs:
            # forceOutput='angle angleRate' in XML is one string: each value needs its own quotes
            words = v.split()
            quote = ("; quote each name: '" + " ".join(f'"{w}"' for w in words) + "'"
                     if len(words) > 1 and all(w in outputs for w in words) else "")
            err(joint, "forceOutput", f"{v!r} is not an output of {joint.type_name}; allowed: "
                                      f"ALL, NONE{', ' if outputs else ''}{', '.join(outputs)}{quote}")

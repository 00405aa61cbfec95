"""Scene analysis: what a scene holds and which features it needs.

Feature names join scenes, backends, cases and reports. A run models only what its scene
needs, and refuses by name each feature its backend declares unsupported (backends/base.py,
Backend.support; `x3drbp run` exits 3): nothing is ignored silently. 'RigidBody' for a
node type in use, 'RigidBody.mass' for an input field given a value other than its
default, and derived names for what a field alone does not say
('RigidBody.inertia.offDiagonal', 'SingleAxisHingeJoint.limits',
'CollidableShape.geometry.Cone', 'CollisionCollection.appliedParameters.SLIP-1'; its
FRICTION_COEFFICIENT-2 only where the two frictionCoefficients differ: with equal ones the
flag asks for nothing beyond isotropic friction).
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, field

import numpy as np

from . import fields as F
from .applied import applied
from .collision import collider, foreign_contacts
from .model import Scene

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


# A Script whose directOutput is TRUE sets fields of other nodes itself, with no ROUTE (X3D
# 4.0 Scripting, the Script node: the nodes its SFNode/MFNode fields hold and what they
# contain; through the Browser object, any named node, and routes it adds): an input that
# no field or ROUTE of the file names. Any such Script in a physics scene counts, whatever
# its fields hold: which nodes it reaches is for its code to say. The name ends in '.routed',
# so every backend refuses it by name (backends/base.py, Backend.support). A Script with
# directOutput FALSE acts only through its ROUTEs, each counted in features() itself.
SCRIPT_DIRECT_OUTPUT = "Script.directOutput.routed"


def features(scene: Scene) -> list[str]:
    """The sorted feature names the scene uses."""
    out: set[str] = set()
    for n in scene.nodes():
        if n.spec is None or n.type_name not in RBP_TYPES:
            continue
        t = n.type_name
        out.add(t)
        for name, value in n.values.items():
            fd = n.spec.fields[name]
            if fd.type.kind == "node" or fd.name in ("bboxCenter", "bboxSize", "bboxDisplay", "visible",
                                                     "metadata", "description"):
                continue
            if not F.values_equal(fd.type, value, fd.default):
                out.add(f"{t}.{name}")
        if t == "RigidBody":
            m = np.asarray(n.get("inertia")).reshape(3, 3)
            if np.any(m - np.diag(np.diag(m))):
                out.add("RigidBody.inertia.offDiagonal")
            if n.get("massDensityModel") is not None:
                out.add(f"RigidBody.massDensityModel.{n.get('massDensityModel').type_name}")
            if n.get("forces").size:
                out.add("RigidBody.forces")
            if n.get("torques").size:
                out.add("RigidBody.torques")
        elif t in _ANGLE_LIMITS:
            lo, hi = (n.get(f) for f in _ANGLE_LIMITS[t])
            if lo > -math.pi + 1e-6 or hi < math.pi - 1e-6:
                out.add(f"{t}.limits")
        elif t == "SliderJoint":
            out.add("SliderJoint.limits")
        elif t == "CollidableShape":
            shape = n.get("shape")
            geom = shape.get("geometry") if shape is not None else None
            if geom is not None:
                out.add(f"CollidableShape.geometry.{geom.type_name}")
        if t in ("CollisionCollection", "Contact"):
            on = applied(n.get("appliedParameters"))
            fc = np.asarray(n.get("frictionCoefficients"), dtype=np.float64)
            if fc[0] == fc[1]:  # one coefficient both ways: what every reading of the flag applies
                on = on - {"FRICTION_COEFFICIENT-2"}
            out.update(f"{t}.appliedParameters.{p}" for p in on)
        if n.spec.is_a("X3DRigidJointNode") and n.get("forceOutput") != ["NONE"]:
            out.add(f"{t}.forceOutput")
    for r in scene.routes:  # inputs that change during a run
        if r.to_node.type_name not in RBP_TYPES:
            continue
        if r.to_field == "set_contacts" and r.from_node.type_name == "CollisionSensor" and r.from_field == "contacts":
            foreign = foreign_contacts(r.to_node, scene.routes)
            out.add("RigidBodyCollection.set_contacts.fromOtherCollider" if foreign
                    else "RigidBodyCollection.set_contacts.fromSensor")
        else:
            out.add(f"{r.to_node.type_name}.{r.to_field}.routed")
    if out and any(n.type_name == "Script" and n.get("directOutput") for n in scene.nodes()):
        out.add(SCRIPT_DIRECT_OUTPUT)
    return sorted(out)


COLLISION_FEATURES = ("CollisionCollection", "CollisionSpace", "CollisionSensor", "CollidableShape",
                      "CollidableOffset", "RigidBodyCollection.contactSurfaceThickness",
                      "RigidBodyCollection.maxCorrectionSpeed")


def run_features(scene: Scene) -> list[str]:
    """The features a run of the scene needs. Collision geometry and contact settings count
    only where some enabled RigidBodyCollection has a collider, its own or the one its
    routed contacts come from (otherwise nothing collides); a Contact node counts never by
    itself: only set_contacts gives it an effect, and its route is counted."""
    colliding = any(collider(c, scene.routes) is not None
                    for c in scene.of_type("RigidBodyCollection") if c.get("enabled"))
    return [f for f in features(scene)
            if not f.startswith("Contact") and (colliding or not f.startswith(COLLISION_FEATURES))]

"""The backend protocol: a declared feature table, and a build step.

A backend is one module in this package exposing `BACKEND`, an instance of a Backend
subclass. It declares, per feature name (the names of x3d_core.analysis), whether the
engine honours it natively, approximately (and how) or not at all (and why); anything
it does not declare is unsupported. `build(world, dt)` returns an
x3d_core.engine.Simulation: step, read state in bulk, set velocities.

To add an engine: write backends/NAME.py against this module and add NAME to
ENGINES below. Nothing else changes.
"""

from __future__ import annotations

import importlib
from abc import ABC, abstractmethod
from dataclasses import dataclass
from enum import Enum

from x3d_core.engine import Simulation
from x3d_core.world import World

ENGINES = ("bullet", "mujoco", "dart", "ode", "pymunk")


class Support(Enum):
    NATIVE = "native"
    APPROXIMATE = "approximate"
    UNSUPPORTED = "unsupported"


@dataclass(frozen=True)
class Declared:
    support: Support
    note: str = ""  # how it is approximated, or why it is unsupported


def native(*features: str) -> dict[str, Declared]:
    return {f: Declared(Support.NATIVE) for f in features}


def approximate(note: str, *features: str) -> dict[str, Declared]:
    return {f: Declared(Support.APPROXIMATE, note) for f in features}


def unsupported(note: str, *features: str) -> dict[str, Declared]:
    return {f: Declared(Support.UNSUPPORTED, note) for f in features}


# What x3d_core does itself for every backend: the frame loop, outputs, damping,
# and fields that only name or group things.
EVALUATOR: dict[str, Declared] = native(
    "RigidBodyCollection", "RigidBody", "RigidBody.enabled", "RigidBody.autoDamp", "RigidBody.linearDampingFactor",
    "RigidBody.angularDampingFactor", "RigidBodyCollection.enabled",
    *(f"{j}.forceOutput" for j in ("BallJoint", "SingleAxisHingeJoint", "DoubleAxisHingeJoint", "SliderJoint",
                                   "UniversalJoint", "MotorJoint")),
    # MotorJoint is ODE's AMotor: torques the evaluator applies through set_loads
    "MotorJoint", "MotorJoint.enabledAxes", "MotorJoint.autoCalc",
    *(f"MotorJoint.axis{k}{f}" for k in (1, 2, 3) for f in ("Angle", "Torque")),
    *(f"MotorJoint.motor{k}Axis" for k in (1, 2, 3)),
    # all three engines turn a body by the exponential map of its angular velocity: ODE's
    # finite rotation mode, whatever the flag says
    "RigidBody.useFiniteRotation") | approximate(
    "bodies on no joint stop after disableTime under both speed thresholds (ODE disables islands of "
    "jointed bodies together; those never stop here)",
    "RigidBody.autoDisable", "RigidBody.disableLinearSpeed", "RigidBody.disableAngularSpeed", "RigidBody.disableTime",
    "RigidBodyCollection.autoDisable", "RigidBodyCollection.disableLinearSpeed",
    "RigidBodyCollection.disableAngularSpeed", "RigidBodyCollection.disableTime") | approximate(
    "contacts routed from a CollisionSensor act in the steps that find them (each step collides with the "
    "sensor's collider), not a frame later as a browser's events deliver them; the two agree at a frame's "
    "first step", "RigidBodyCollection.set_contacts.fromSensor") | unsupported(
    "contacts routed from a sensor whose collider is not the collection's own: x3drbp gives a collection one "
    "collision set", "RigidBodyCollection.set_contacts.fromOtherCollider") | approximate(
    "the exponential map turns the body about its whole angular velocity, not split along this axis as ODE's "
    "finite rotation axis does; the two differ only for fast spin about the axis with a slow tumble",
    "RigidBody.finiteRotationAxis") | approximate(
    "no effect: the joint has no stop angles for these to act on",
    *(f"MotorJoint.stop{k}{f}" for k in (1, 2, 3) for f in ("Bounce", "ErrorCorrection")),
    *(f"UniversalJoint.stop{k}{f}" for k in (1, 2) for f in ("Bounce", "ErrorCorrection")))

# Collision layout x3d_core resolves for every engine (x3d_core/collision.py): which
# collidables take part and where they sit; a backend builds what comes out
EVALUATOR |= native(
    "CollidableShape", "CollidableShape.translation", "CollidableShape.rotation", "CollidableShape.enabled",
    "CollidableOffset", "CollidableOffset.translation", "CollidableOffset.rotation", "CollidableOffset.enabled",
    "CollisionSpace", "CollisionSpace.enabled", "CollisionCollection.enabled", "CollisionSensor.enabled",
    # a speed hint: the geometry itself is always tested (x3d_core/collision.py says why)
    "CollisionSpace.useGeometry")

# What every 3D backend builds from the World's bulk arrays and its joint forest
BODIES = ("RigidBody.mass", "RigidBody.inertia", "RigidBody.inertia.offDiagonal", "RigidBody.centerOfMass",
          "RigidBody.massDensityModel", "RigidBody.massDensityModel.Box", "RigidBody.massDensityModel.Sphere",
          "RigidBody.massDensityModel.Cone", "RigidBody.fixed", "RigidBody.position", "RigidBody.orientation",
          "RigidBody.linearVelocity", "RigidBody.angularVelocity", "RigidBody.forces", "RigidBody.torques",
          "RigidBodyCollection.gravity")
JOINTS = ("BallJoint", "BallJoint.anchorPoint", "SingleAxisHingeJoint", "SingleAxisHingeJoint.anchorPoint",
          "SingleAxisHingeJoint.axis", "SingleAxisHingeJoint.limits", "SingleAxisHingeJoint.minAngle",
          "SingleAxisHingeJoint.maxAngle", "SliderJoint", "SliderJoint.axis", "SliderJoint.limits",
          "SliderJoint.minSeparation", "SliderJoint.maxSeparation", "UniversalJoint", "UniversalJoint.anchorPoint",
          "UniversalJoint.axis1", "UniversalJoint.axis2")

NOT_YET = "not implemented by this backend yet"
ROUTED = Declared(Support.UNSUPPORTED, "x3drbp runs no ROUTEs or Scripts: this input would keep the file's value")


class Backend(ABC):
    name: str
    declared: dict[str, Declared]

    @abstractmethod
    def version(self) -> str:
        """The engine's version."""

    @abstractmethod
    def build(self, world: World, dt: float) -> Simulation:
        """An engine model of the world, stepping at dt."""

    def support(self, feature: str) -> Declared:
        if feature.endswith(".routed"):
            return ROUTED
        # a backend's own word wins: its engine may do natively what the evaluator
        # approximates for all (ODE's finite rotation axis)
        d = self.declared.get(feature) or EVALUATOR.get(feature)
        return d if d is not None else Declared(Support.UNSUPPORTED, NOT_YET)

    def table(self) -> dict[str, Declared]:
        return {**EVALUATOR, **self.declared}


def load(name: str) -> Backend:
    """The backend of that name; ImportError (with the reason) if its engine is missing."""
    if name not in ENGINES:
        raise KeyError(f"no backend {name!r}; known: {', '.join(ENGINES)}")
    return importlib.import_module(f"backends.{name}").BACKEND


def available() -> dict[str, Backend | str]:
    """Each known backend, or the reason it cannot be used here."""
    out: dict[str, Backend | str] = {}
    for name in ENGINES:
        try:
            out[name] = load(name)
        except ImportError as e:
            out[name] = f"unavailable: {e}"
    return out

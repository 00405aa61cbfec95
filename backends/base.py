"""The backend protocol: a declared feature table, and a build step.

A backend is one module exposing `BACKEND`, an instance of a Backend subclass. It
declares, per feature name (the names of x3d_core.semantics.analysis), whether the engine honours
it natively, approximately (and how) or not at all (and why); anything it does not
declare is unsupported. A declaration may name the one value its engine holds anyway
(unsupported(..., native_at=0): a rigid solver's CFM): there the feature is native, since
the scene asks for nothing the engine lacks. judged() weighs a scene's uses, each with its
value, against them. `build(world, dt)` returns an
x3d_core.semantics.engine.Simulation: step, read state in bulk, set velocities.

Backends are found through the entry point group `x3drbp.backends` (registry()): each
entry point names a backend and the module attribute that is its instance. To add an
engine: write a module with BACKEND against this one and declare it as an entry point,
in-tree (pyproject.toml's `[project.entry-points."x3drbp.backends"]`, as the six here) or
in any installed package (docs/example_adapter is one). Nothing else changes: the runner,
the CLI and the pytest plugin (conformance/pytest_plugin.py) take every registered name.
Listing the registry imports no engine; load() imports the one asked for, and an entry
point whose module fails to import is unavailable, with the reason.
"""

from __future__ import annotations

import functools
import importlib
import sys
from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass
from enum import Enum
from typing import Any

import numpy as np

from x3d_core.model import fields as F
from x3d_core.model.scene import Scene
from x3d_core.semantics.analysis import SCRIPT_DIRECT_OUTPUT, Use, run_uses
from x3d_core.semantics.engine import Simulation
from x3d_core.semantics.integration import POSITION_FIRST, RK4, SEMI_IMPLICIT, in_substeps  # noqa: F401  (the backends' names)
from x3d_core.semantics.world import World

GROUP = "x3drbp.backends"  # the entry point group of backends
# the backends x3drbp ships (pyproject.toml declares each): listed first, in this order
IN_TREE = ("bullet", "mujoco", "dart", "ode", "pymunk", "physx", "drake")


class Support(Enum):
    NATIVE = "native"
    APPROXIMATE = "approximate"
    UNSUPPORTED = "unsupported"


@dataclass(frozen=True)
class Declared:
    support: Support
    note: str = ""  # how it is approximated, or why it is unsupported
    # the one value the engine holds anyway (a rigid joint's CFM 0): a scene giving it asks for
    # nothing the engine lacks, so there the feature is native (judged)
    native_at: Any = None


def native(*features: str) -> dict[str, Declared]:
    return {f: Declared(Support.NATIVE) for f in features}


def approximate(note: str, *features: str, native_at: Any = None) -> dict[str, Declared]:
    """Features the engine honours only as the note says, exactly at native_at where one is given."""
    return {f: Declared(Support.APPROXIMATE, note, native_at) for f in features}


def unsupported(note: str, *features: str, native_at: Any = None) -> dict[str, Declared]:
    """Features the engine cannot honour (why: note), except at native_at where one is given."""
    return {f: Declared(Support.UNSUPPORTED, note, native_at) for f in features}


# What x3d_core does itself for every backend: the frame loop, outputs, damping,
# and fields that only name or group things.
EVALUATOR: dict[str, Declared] = native(
    "RigidBodyCollection", "RigidBody", "RigidBody.enabled", "RigidBody.autoDamp", "RigidBody.linearDampingFactor",
    "RigidBody.angularDampingFactor", "RigidBodyCollection.enabled",
    *(f"{j}.forceOutput" for j in ("BallJoint", "SingleAxisHingeJoint", "DoubleAxisHingeJoint", "SliderJoint",
                                   "UniversalJoint", "MotorJoint")),
    # MotorJoint is ODE's AMotor: torques the evaluator applies through set_loads, along the axes
    # where 37.4.9 anchors them (axis 1 in the world, 2 on body1, 3 on body2; 0 0 0: disabled)
    "MotorJoint", "MotorJoint.enabledAxes",
    *(f"MotorJoint.axis{k}{f}" for k in (1, 2, 3) for f in ("Angle", "Torque")),
    *(f"MotorJoint.motor{k}Axis" for k in (1, 2, 3)),
    # ODE's dJointAddSliderForce, applied by the evaluator through set_loads as the motors' torques
    "SliderJoint.sliderForce",
    # all three engines turn a body by the exponential map of its angular velocity, whatever the
    # flag says: ODE's finite rotation mode with a zero axis (X3D 3.x's default finiteRotationAxis)
    "RigidBody.useFiniteRotation") | approximate(
    "motorNAngle is the twist of body1's rotation relative to body2 (from the start) about each motor axis "
    "separately, each where 37.4.9 anchors it (axis 1 in the world, 2 on body1, 3 on body2); ODE's Euler mode "
    "(Xj3D) anchors axis 1 to body1 and splits that rotation into three Euler angles about axis 1, the axis "
    "perpendicular to 1 and 3, and axis 3: the same with one axis, different where several axes turn at once",
    "MotorJoint.autoCalc") | approximate(
    "bodies on no joint stop after disableTime with any one speed under its threshold (the clause's 'any one "
    "of these values'; ODE needs both) and are held (velocities zeroed, weight cancelled; an engine's contact "
    "may still take back the depth they rest at); a new contact, a contact with an awake body, or an applied "
    "force or torque wakes them (ODE: an enabled body touching or joined to them); "
    "ODE disables islands of jointed bodies together, here jointed bodies never stop",
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
    # 0 0 0 (X3D 3.x's default) is ODE's full finite rotation, no axis: the exponential map itself
    "RigidBody.finiteRotationAxis", native_at=(0.0, 0.0, 0.0)) | approximate(
    "no effect: the joint has no stop angles for these to act on",
    *(f"MotorJoint.stop{k}{f}" for k in (1, 2, 3) for f in ("Bounce", "ErrorCorrection")),
    *(f"UniversalJoint.stop{k}{f}" for k in (1, 2) for f in ("Bounce", "ErrorCorrection")))

# Collision layout x3d_core resolves for every engine (x3d_core/semantics/collision.py): which
# collidables take part and where they sit; a backend builds what comes out
EVALUATOR |= native(
    "CollidableShape", "CollidableShape.translation", "CollidableShape.rotation", "CollidableShape.enabled",
    "CollidableOffset", "CollidableOffset.translation", "CollidableOffset.rotation", "CollidableOffset.enabled",
    "CollisionSpace", "CollisionSpace.enabled", "CollisionCollection.enabled", "CollisionSensor.enabled",
    # a speed hint: the geometry itself is always tested (x3d_core/semantics/collision.py says why)
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

# The smallest normal double: a positive value below it (a subnormal, 1e-320) has no finite
# inverse (1/x overflows), and engines that invert masses or inertias then freeze or abort.
SMALLEST_NORMAL = sys.float_info.min


def below(limit: float, why: str) -> Callable[[Any], str | None]:
    """A value check (Backend.limits): refuses a value with a non-zero component of magnitude
    under limit, saying why (the value itself is named by the refusal)."""
    def check(value: Any) -> str | None:
        a = np.abs(np.asarray(value, dtype=np.float64))
        return why if np.any((a > 0) & (a < limit)) else None
    return check


def above(limit: float, why: str) -> Callable[[Any], str | None]:
    """A value check (Backend.limits): refuses a value with a component of magnitude over limit."""
    def check(value: Any) -> str | None:
        return why if np.any(np.abs(np.asarray(value, dtype=np.float64)) > limit) else None
    return check


NOT_YET = "not implemented by this backend yet"
ROUTED = Declared(Support.UNSUPPORTED, "x3drbp runs no ROUTEs or Scripts: this input would keep the file's value")
SCRIPTED = Declared(Support.UNSUPPORTED, "x3drbp runs no Scripts, and with directOutput TRUE a Script may set the "
                                         "fields of the nodes it holds, and of what they hold, with no ROUTE: a run "
                                         "would keep the file's values there")


class Backend(ABC):
    name: str
    declared: dict[str, Declared]
    # Values of a feature the engine cannot take though it honours the feature (a subnormal
    # mass whose inverse overflows): feature -> check(value), the reason or None (below, above).
    # judge() refuses such a use by value; limits that need the whole world or the step (a
    # CFM divided by dt) are refused by build() raising x3d_core.semantics.engine.Unsupported.
    limits: dict[str, Callable[[Any], str | None]] = {}
    # SEMI_IMPLICIT, POSITION_FIRST or RK4, or another scheme in words; None: not declared. Not
    # a feature of the spec (which names no integrator), but it parts free motion between engines.
    integration: str | None = None
    # the scheme where a collection's preferAccuracy is TRUE, where the engine then changes it
    accurate_integration: str | None = None
    # the scenes it takes at all, where not every scene ("planar scenes only"): said beside any
    # recommendation of it, as a scene it suits may not be the reader's
    scope: str | None = None

    @abstractmethod
    def version(self) -> str:
        """The engine's version."""

    @abstractmethod
    def build(self, world: World, dt: float) -> Simulation:
        """An engine model of the world, stepping at dt."""

    def support(self, feature: str) -> Declared:
        if feature.endswith(".routed"):
            return ROUTED
        if feature == SCRIPT_DIRECT_OUTPUT:
            return SCRIPTED
        # a backend's own word wins: its engine may do natively what the evaluator
        # approximates for all (ODE's finite rotation axis)
        d = self.declared.get(feature) or EVALUATOR.get(feature)
        return d if d is not None else Declared(Support.UNSUPPORTED, NOT_YET)

    def table(self) -> dict[str, Declared]:
        return {**EVALUATOR, **self.declared}


def judge(backend: Backend, use: Use) -> Declared:
    """What the backend does with one use: its declaration of the feature, native where the
    scene's value is the one the declaration says the engine holds anyway, unsupported where
    the value is one the engine cannot take (Backend.limits)."""
    d = backend.support(use.feature)
    if d.native_at is not None and use.value is not None and F.values_equal(use.ftype, use.value, d.native_at):
        return Declared(Support.NATIVE)
    check = getattr(backend, "limits", {}).get(use.feature) if use.value is not None else None
    if check is not None and d.support is not Support.UNSUPPORTED:
        why = check(use.value)
        if why:
            return Declared(Support.UNSUPPORTED, why)
    return d


def judged(backend: Backend, scene: Scene, ws: list[World] | None = None) -> list[tuple[Use, Declared]]:
    """Each use a run of the scene needs (x3d_core.semantics.analysis.run_uses, on its worlds ws where
    built already), judged by the backend: what `x3drbp run` refuses (naming the use, field
    and value) or notes as approximated."""
    return [(u, judge(backend, u)) for u in run_uses(scene, ws)]


@dataclass(frozen=True)
class Registered:
    """One backend the registry knows: where its instance is and who declares it."""
    name: str
    value: str  # "module:ATTRIBUTE"
    dist: str  # the distribution declaring it ("" when x3drbp's metadata is not installed)


@functools.cache
def _registry() -> tuple[dict[str, Registered], tuple[str, ...]]:
    import importlib.metadata  # here: reading every package's entry points costs `x3drbp run` 30 ms it rarely needs
    found = [Registered(ep.name, ep.value, ep.dist.name if ep.dist is not None else "")
             for ep in importlib.metadata.entry_points(group=GROUP)]
    # a source checkout without x3drbp's metadata still has its own backends
    found += [Registered(n, f"backends.{n}:BACKEND", "") for n in IN_TREE
              if not any(r.name == n and r.dist == "x3drbp" for r in found)]
    # x3drbp's own first (in IN_TREE's order), then the others by name; sorted() is stable,
    # so among one name's entry points the order importlib.metadata found them stays
    found.sort(key=lambda r: (r.name not in IN_TREE or r.dist not in ("x3drbp", ""),
                              IN_TREE.index(r.name) if r.name in IN_TREE else 0, r.name))
    out: dict[str, Registered] = {}
    notes = []
    for r in found:
        first = out.setdefault(r.name, r)
        if first is not r and first.value != r.value:
            notes.append(f"backend {r.name!r}: entry point {r.value} ({r.dist or 'unknown distribution'}) ignored; "
                         f"the first one registered wins: {first.value} ({first.dist or 'x3drbp'})")
    return out, tuple(notes)


def registry() -> dict[str, Registered]:
    """Every backend declared in the `x3drbp.backends` entry point group, x3drbp's own first
    (in IN_TREE's order), then the others by name. Imports no engine."""
    return dict(_registry()[0])


def registry_notes() -> tuple[str, ...]:
    """One line per entry point that lost to an earlier one of the same name."""
    return _registry()[1]


def engines() -> tuple[str, ...]:
    """The names of every registered backend, in registry() order."""
    return tuple(_registry()[0])


def entry(name: str) -> str:
    """Where the backend of that name is, "module:ATTRIBUTE", found without importing it;
    KeyError naming the known ones where no backend has the name."""
    if name in IN_TREE:  # x3drbp's own wins its name (_registry's order): no entry point need be read
        return f"backends.{name}:BACKEND"
    found = _registry()[0]
    if name not in found:
        raise KeyError(f"no backend {name!r}; known: {', '.join(found)}")
    return found[name].value


def load(name: str) -> Backend:
    """The backend of that name, importing its module alone; KeyError where none has the name
    (entry), ImportError (with the reason) if its engine is missing or its module fails to
    import in any other way."""
    value = entry(name)
    module, _, attr = value.partition(":")
    try:
        backend = importlib.import_module(module)
        for part in filter(None, attr.split(".")):
            backend = getattr(backend, part)
    except ImportError:
        raise
    except Exception as e:  # a module that raises on import is as unusable as a missing engine
        raise ImportError(f"{value}: {type(e).__name__}: {e}") from e
    if not all(callable(getattr(backend, a, None)) for a in ("build", "version", "support", "table")):
        raise ImportError(f"{value} is not a backend (a backends.base.Backend instance): {type(backend).__name__}")
    return backend


def available() -> dict[str, Backend | str]:
    """Each registered backend, or the reason it cannot be used here."""
    out: dict[str, Backend | str] = {}
    for name in engines():
        try:
            out[name] = load(name)
        except ImportError as e:
            out[name] = f"unavailable: {e}"
    return out

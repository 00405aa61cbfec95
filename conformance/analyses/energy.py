"""Mechanical energy that grows with nothing doing work on the scene: a warning per run, for
`x3drbp compare` and `x3drbp stability`.

Where a scene has no motor (MotorJoint, a DoubleAxisHingeJoint's desiredAngularVelocity or
maxTorque), no applied force or torque (RigidBody forces and torques, SliderJoint sliderForce),
no conveyor (a collider's surfaceSpeed or SPEED-1/-2) and no input that changes during a run (a
ROUTE into a physics node, contacts set from outside, a Script that may set a physics node), only
gravity, joints, contacts and damping act on its bodies. Gravity is conservative; a joint does no
work; a contact (bounce at most 1), friction and damping only take energy away. So the energy
E = kinetic + potential (potential from the gravity each body feels: its collection's, none where
useGlobalGravity is FALSE) may not rise: where a run's does, its engine made it. The rule is
conservative: it reads the features a run uses (x3d_core.semantics.analysis.run_features) and claims that
nothing does work only where none of those that may do work is among them.

A rise is growth past its bound: 10% of the energy the motion can exchange, and at least the
energy that lifts every moving body 1 mm against its gravity and sets it moving at 1 cm/s (the
least change a viewer sees at the metre scale of the component's scenes, 1 mm being `x3drbp
compare`'s default position threshold). The exchange is E(0) less the lowest potential energy of
the run: the most kinetic energy a run that keeps E could reach, which energy an engine makes
does not raise (a pendulum released from rest: the potential energy of its fall). The bound is
then the stability suite's (conformance/analyses/stability.py): semi-implicit Euler's energy error
oscillates by about h w / 2 of the exchange for a motion of angular rate w, which it admits up to
12 rad/s at h = 1/60 (48 rad/s at 1/240) without a trend.
"""

from __future__ import annotations

import functools

import numpy as np

from x3d_core.encodings.load import load
from x3d_core.model.scene import Scene
from x3d_core.semantics.analysis import SCRIPT_DIRECT_OUTPUT, run_features
from x3d_core.semantics.world import worlds
from x3d_core.traces.trace import TraceView

from conformance.analyses.motion import Model, Motion
from conformance.results import EnergyGrowth

RISE = 0.10  # of the energy the motion can exchange
# the least rise counted: every moving body lifted this far (m) and set moving this fast (m/s)
LIFT, DRIFT = 1e-3, 1e-2

# run features that may do work on the bodies; besides them, every routed input and set_contacts
WORKING = frozenset({
    "MotorJoint", "RigidBody.forces", "RigidBody.torques", "SliderJoint.sliderForce",
    "DoubleAxisHingeJoint.desiredAngularVelocity1", "DoubleAxisHingeJoint.desiredAngularVelocity2",
    "DoubleAxisHingeJoint.maxTorque1", "DoubleAxisHingeJoint.maxTorque2",
    "CollisionCollection.surfaceSpeed", "CollisionCollection.appliedParameters.SPEED-1",
    "CollisionCollection.appliedParameters.SPEED-2", SCRIPT_DIRECT_OUTPUT})


def working(scene: Scene) -> list[str]:
    """The features of a run of the scene that may do work on its bodies, sorted (none: only
    gravity, joints, contacts and damping act)."""
    return [f for f in run_features(scene)
            if f in WORKING or f.endswith(".routed") or f.startswith("RigidBodyCollection.set_contacts")]


def model(scene: Scene) -> Model | None:
    """The moving bodies of every world, each with the gravity it feels, as the engines got them;
    None where something may do work on them (working) or nothing moves."""
    if working(scene):
        return None
    names, mass, inertia, com, gravity = [], [], [], [], []
    for w in worlds(scene):
        b = w.bodies
        moving = np.flatnonzero(~b.fixed)
        names += [b.names[i] for i in moving]
        mass.append(b.mass[moving])
        inertia.append(b.inertia[moving])
        com.append(b.com[moving])
        gravity.append(w.gravity * b.use_gravity[moving, None])
    if not names:
        return None
    cat = np.concatenate
    return Model(names, cat(mass), cat(inertia), cat(com), np.ones(len(names), dtype=bool), cat(gravity))


@functools.lru_cache(maxsize=None)
def model_at(path: str) -> Model | None:
    """model() of the scene file at path (a stability case's, read once however many runs it has)."""
    return model(load(path))


def growth(view: TraceView, m: Model) -> EnergyGrowth | None:
    """The run's energy growth past its bound (module docstring), None where it kept within it.
    A run that blew up is read to its last finite frame: the blow-up is its verdict already."""
    motion = Motion.read(view, m, m.rows())
    with np.errstate(over="ignore", invalid="ignore"):
        potential = motion.potential(m.gravity)
        e = motion.kinetic() + potential
    bad = np.flatnonzero(~np.isfinite(e))
    end = int(bad[0]) if bad.size else e.size
    if end == 0:
        return None
    t, potential, e = motion.t[:end], potential[:end], e[:end]
    least = float(m.mass @ (np.linalg.norm(m.gravity, axis=1) * LIFT + 0.5 * DRIFT ** 2))
    bound = max(RISE * float(e[0] - potential.min()), least)
    over = np.flatnonzero(e - e[0] > bound)
    if not over.size:
        return None
    k = int(np.argmax(e))
    return EnergyGrowth(float(e[0]), float(e[k]), float(t[k]), float(t[over[0]]), bound)

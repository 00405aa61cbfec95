"""pushed_bodies: RigidBody mass in kilograms, its default of 1 kg, and a linearVelocity given with forces."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ballistic
from conformance.results import Measure, Settings, spec

# pushed_bodies.x3d: no gravity; body -> (start, starting velocity, force, mass); Unweighed gives no mass
PB_BODIES = {"Light": ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), 0.5),
             "Heavy": ((0.0, 1.0, 0.0), (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), 2.0),
             "Unweighed": ((0.0, 2.0, 0.0), (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), 1.0),
             "Launched": ((0.0, 3.0, 0.0), (0.0, 1.0, 0.0), (2.0, 0.0, 0.0), 2.0)}
DEFAULT_MASS = 1.0  # kg

MASS = spec("37.4.10 RigidBody: The mass field indicates the mass of the body in kilograms. All bodies shall have a "
            "non-zero mass, with the default value of 1 kilogram.")
LAUNCH = spec("37.4.10 RigidBody: If both forces and velocity are defined, the velocity is used only on the first "
              "frame that the node is active, and then the forces are applied.")


def _misread(name: str) -> list[np.ndarray]:
    """The accelerations the misreadings of a body's mass give it: the mass ignored (the default 1 kg
    in its place), and no acceleration at all (a body whose mass is read as 0, which Bullet takes for
    a static body); for Launched, whose mass the case does not judge, its velocity held every frame
    (no acceleration: the forces not applied once a velocity is given)."""
    _, _, f, m = PB_BODIES[name]
    force = np.asarray(f)
    if name == "Launched":
        return [np.zeros(3)]
    return [force / DEFAULT_MASS, np.zeros(3)]


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Every body: closed_forms.ballistic, a = F / m from its start (Launched: from its file velocity).
    The acceleration its motion shows is exact to rounding for every one-step scheme (ballistic's
    argument: the accuracy bound); the spec tolerance (closed_forms.honoured) half the nearest
    misreading's error:
    - Light, Heavy (MASS, the kilograms): the mass ignored, the default 1 kg in its place (a = F / 1:
      1 and 0.5 m/s^2 off, so 0.5 and 0.25 m/s^2) or read as 0 (Bullet's static body: a = 0); a mass
      read in grams is a thousand times off;
    - Unweighed (MASS, the default 1 kg): the default read as 0, a static body (a = 0: 1 m/s^2 off, so
      0.5); no mass field, a default of 2/3 or 2 kg would pass, and no implementation found takes
      one;
    - Launched (LAUNCH): the velocity held every frame, the forces never applied (a = 0: 1 m/s^2 off,
      0.5), and, by ballistic's starting velocity (the fit of the second half's velocities at t = 0),
      the velocity ignored once forces are given (1 m/s off, 0.5). Forces that start only after the
      first frame (the velocity alone "on the first frame") move the fitted start by a/60, within the
      sentence's tolerance: that reading fails only the physics clock's convention measures."""
    out = []
    for name, (p0, v0, f, m) in PB_BODIES.items():
        a = np.asarray(f) / m
        out += ballistic(name, p0, v0, a, LAUNCH if name == "Launched" else MASS, misread=_misread(name))(
            traces, settings)
    return out


CASE = Case("pushed_bodies", "pushed_bodies.x3d",
            "RigidBody mass: 1 N accelerates 0.5, 2 kg and a body with no mass at 2, 0.5 and 1 m/s^2 (kilograms, "
            "the default 1 kg); linearVelocity (0 1 0) with forces (2 0 0) on 2 kg: v = (t, 1, 0), the velocity "
            "the start and the force acting from then on",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("RigidBody.mass", "RigidBody.forces", "RigidBody.linearVelocity"),
            mutations=(
                (" mass='2' position='0 1 0'", " position='0 1 0'"),  # Heavy's mass ignored: the default 1 kg
                # the default read as 0: Bullet's static body
                ("DEF='Unweighed' position", "DEF='Unweighed' fixed='true' position"),
                (" forces='2 0 0'", ""),  # Launched's velocity held: no force acts once a velocity is given
                (" linearVelocity='0 1 0'", ""),  # Launched's velocity ignored once forces are given
            ))

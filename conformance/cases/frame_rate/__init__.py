"""frame_rate: Frame-rate independence: 30 Hz and 144 Hz frames at one physics step give one state.

x3drbp's rule, not the spec's: the spec fixes no physics step. It describes the physics once a
frame (RigidBody: forces "applied to the object every frame"; RigidBodyCollection: contacts used
"when the physics model is evaluated at the end of the frame"), and real browsers step by the
frame period (Xj3D, X_ITE) or by a fixed step (FreeWRL, x3drbp). So the bit-equality is a
convention measure, and the case has no spec measure: across frame rates the spec says only that
both runs simulate the same scene, and how far two step sizes may take the motion apart depends
on the integrator's error constant for this scene (a damped, hinged, tumbling body), which the
spec does not bound; each run's own motion is what the other cases hold to closed forms. A
browser that steps by the frame period therefore shows here as "conforms, differs in
conventions", never as violating the spec.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.results import Measure, Settings, convention


FIXED_STEP = convention("a fixed physics step independent of the frame rate: at t = 1 s runs at 30 and 144 "
                        "frames/s have taken the same steps and hold the same state bit for bit (x3drbp; FreeWRL's "
                        "fixed 0.02 s step); alternative: the step is the frame period (Xj3D, X_ITE), the state then "
                        "differing by the integrator's error at each step size")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Tolerance 0: both runs have taken the same floor(1.0/dt) = 240 steps of a deterministic
    engine when t = 1.0 s, and frames only read state (x3d_core.semantics.evaluator's contract). Any
    difference, even in the last digit (traces keep every digit), is frame-dependent physics."""
    t_end = 1.0
    a, b = traces[0].at(t_end), traces[1].at(t_end)
    if not a or set(a) != set(b):
        missing = sorted(set(a) ^ set(b))
        detail = f" (outputs in one run only: {missing[:4]})" if missing else " (no rows at t = 1)"
        return [Measure("state at t = 1 s, 30 Hz vs 144 Hz" + detail, math.inf, 0.0, "", FIXED_STEP)]
    diff = max(float(np.max(np.abs(a[k] - b[k]))) for k in a)
    return [Measure("state at t = 1 s, 30 Hz vs 144 Hz (max difference)", diff, 0.0, "", FIXED_STEP)]


CASE = Case("frame_rate", "frame_rate.x3d",
            "frame-rate independence: 30 Hz and 144 Hz frames, dt 1/240, identical state at t = 1 s",
            (Settings(1.0, 1 / 240, 30.0), Settings(1.0, 1 / 240, 144.0)), expect,
            exercises=("RigidBody.autoDamp", "SingleAxisHingeJoint", "RigidBody.inertia.offDiagonal"),
            mutations=(
                # the scene as it is, stepped as a frame-driven browser steps it (X_ITE: each frame in
                # `iterations`, 10, substeps): the two runs no longer share a step, which the clause
                # allows (the case's one measure is a convention)
                Mutation("", "", runs=(Settings(1.0, 1 / 300, 30.0), Settings(1.0, 1 / 1440, 144.0)), spec=False),
            ))

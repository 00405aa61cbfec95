"""frame_rate: Frame-rate independence: 30 Hz and 144 Hz frames at one physics step give one state."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.results import Measure, Settings


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Tolerance 0: both runs have taken the same floor(1.0/dt) = 240 steps of a deterministic
    engine when t = 1.0 s, and frames only read state (x3d_core.evaluator's contract). Any
    difference, even in the last digit (traces keep every digit), is frame-dependent physics."""
    t_end = 1.0
    a, b = traces[0].at(t_end), traces[1].at(t_end)
    if not a or set(a) != set(b):
        missing = sorted(set(a) ^ set(b))
        detail = f" (outputs in one run only: {missing[:4]})" if missing else " (no rows at t = 1)"
        return [Measure("state at t = 1 s, 30 Hz vs 144 Hz" + detail, math.inf, 0.0)]
    diff = max(float(np.max(np.abs(a[k] - b[k]))) for k in a)
    return [Measure("state at t = 1 s, 30 Hz vs 144 Hz (max difference)", diff, 0.0)]


CASE = Case("frame_rate", "frame_rate.x3d",
            "frame-rate independence: 30 Hz and 144 Hz frames, dt 1/240, identical state at t = 1 s",
            (Settings(1.0, 1 / 240, 30.0), Settings(1.0, 1 / 240, 144.0)), expect,
            exercises=("RigidBody.autoDamp", "SingleAxisHingeJoint", "RigidBody.inertia.offDiagonal"),
            mutations=(
                # the scene as it is, stepped as a frame-driven browser steps it (X_ITE: each frame in
                # `iterations`, 10, substeps): the two runs no longer share a step
                Mutation("", "", runs=(Settings(1.0, 1 / 300, 30.0), Settings(1.0, 1 / 1440, 144.0))),
            ))

"""stop_softness: DoubleAxisHingeJoint stop1ConstantForceMix: 0 hard, the larger the softer (a stop correcting all
its error in a step)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import ROUNDING_ANGLE, honoured, steps
from conformance.results import Measure, Settings, convention, spec

# stop_softness.x3d: each pair (Carrier body1, Knuckle body2, free, isotropic, on the anchor, at rest) starts DEPTH
# past its min stop (minAngle1 +DEPTH, the start 0), stop1ErrorCorrection 1, no gravity
DEPTH = 0.01  # rad
AXIS1 = np.array([0.6, 0.8, 0.0])
I_PAIR = 0.2 * 0.05 / (0.2 + 0.05)  # the pair's reduced moment about axis 1 (kg m^2)
CFM_DEFAULT_STOP = 0.001  # stop1ConstantForceMix default
CFMS = {"Hard": 0.0, "Mid": CFM_DEFAULT_STOP, "Soft": 0.05}
SOLVE = 1e-3  # of a row's correction, what an iterative solve may leave undone (ODE's quick step: 3e-4)
ENDS = ("37.4.8 DoubleAxisHingeJoint: A value of 0 means no correction at all while a value of 1 indicates that all "
        "errors should be corrected in a single step.")
HARD = spec("37.4.8 DoubleAxisHingeJoint: A value of zero indicates hard constraints so that everything is exactly "
            "honoured.", also=(ENDS,))
SOFTER = spec("37.4.8 DoubleAxisHingeJoint: The larger the value, the more soft each of the constraints being "
              "evaluated.")
SOFT_STOP = convention("ODE's soft stop: the stop's row yields by stop1ConstantForceMix times its force, so a step "
                       "correcting depth d at stop1ErrorCorrection 1 leaves d c / (1 + c), c = CFM I / h (I the "
                       "pair's reduced moment about axis 1); the clause says only that the larger value is the softer "
                       "and 0 hard")


def _left(tr: TraceView, h: float, pair: str) -> float:
    """The depth left after the first step: DEPTH less the pair's relative turn about axis 1 then (from
    the bodies' poses: both start unturned and turn about axis 1 only)."""
    t, q1 = tr.series(f"{pair}Carrier", "orientation")
    _, q2 = tr.series(f"{pair}Knuckle", "orientation")
    turn = R.twist_angle(R.multiply(R.conjugate(R.from_axis_angle(q2)), R.from_axis_angle(q1)), AXIS1)
    first = np.flatnonzero(steps(t, h) == 1)
    return abs(DEPTH - abs(float(turn[first[0]]))) if first.size else math.inf


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Each pair's stop at stop1ErrorCorrection 1 corrects its whole depth in the first step, less
    what its softness yields (joint_correction's argument: ODE's row reaches 1 / (1 + c) of its
    target, c = CFM I / h; an iterative solve may leave SOLVE of the correction undone).

    Spec, 0 ("hard constraints so that everything is exactly honoured", with 1's "all errors
    ... corrected in a single step"): Hard leaves nothing, to SOLVE and ROUNDING_ANGLE; the
    tolerance half what the default 0.001 leaves (c / (1 + c), 1 %), the field ignored. "The larger
    the value, the more soft": Soft (0.05) leaves more than Mid (the default 0.001), Mid more than
    Hard, each by more than rounding (a leftover equal to the harder one's: the value not read),
    held to ROUNDING_ANGLE; the clause gives the order, not a law.

    Convention (ODE's soft stop): Soft leaves DEPTH c / (1 + c) (c = 0.48: 32 %), within SOLVE; the
    tolerance half the distance to the default's leftover (the field ignored)."""
    tr, s = traces[0], settings[0]
    h = s.dt
    left = {pair: _left(tr, h, pair) for pair in CFMS}
    c = {pair: cfm * I_PAIR / h for pair, cfm in CFMS.items()}
    hard = DEPTH * SOLVE + ROUNDING_ANGLE
    ode = {pair: DEPTH * c[pair] / (1 + c[pair]) for pair in CFMS}
    short = max(0.0, 2 * ROUNDING_ANGLE - (left["Soft"] - left["Mid"]),
                2 * ROUNDING_ANGLE - (left["Mid"] - left["Hard"]))
    bound = DEPTH * SOLVE / (1 + c["Soft"]) + ROUNDING_ANGLE
    return [Measure("Hard: depth left after the first step (stop1ConstantForceMix 0: none)", left["Hard"],
                    honoured(hard, ode["Mid"]), "rad", HARD, hard),
            Measure("Soft > Mid > Hard: depth left after the first step (shortfall)", short, ROUNDING_ANGLE, "rad",
                    SOFTER),
            Measure(f"Soft: depth left after the first step - DEPTH c / (1 + c) ({ode['Soft']:.3g} rad)",
                    abs(left["Soft"] - ode["Soft"]), honoured(bound, ode["Soft"] - ode["Mid"]), "rad", SOFT_STOP,
                    bound)]


CASE = Case("stop_softness", "stop_softness.x3d",
            "DoubleAxisHingeJoint stop1ConstantForceMix 0, 0.001 (default), 0.05 at stop1ErrorCorrection 1, each "
            "pair started 0.01 rad past minAngle1: 0 leaves no depth after a step, the larger the value the more "
            "left (ODE's: c / (1 + c), c = CFM I / h)",
            (Settings(0.1, 1 / 240, None),), expect,
            exercises=("DoubleAxisHingeJoint.stop1ConstantForceMix", "DoubleAxisHingeJoint.stop1ErrorCorrection",
                       "DoubleAxisHingeJoint.minAngle1"),
            mutations=(
                (" stop1ConstantForceMix='0' ", " "),  # Hard at the default 0.001: 1 % left
                (" stop1ConstantForceMix='0.05'", ""),  # Soft as Mid
                # a larger value read as the stiffer (a stiffness, not a force mix): Soft below Mid
                Mutation(" stop1ConstantForceMix='0.05'", " stop1ConstantForceMix='0.0002'"),
            ))

"""initial_frames: the joints' resting frames are the bodies' initial placement, their axes world
coordinates, and the bodies' position/orientation fields the initial and then the current state."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import (INITIAL, ROUNDING, ROUNDING_ANGLE, G, clock_free_acceleration, honoured,
                                            max_norm, stop_overshoot)
from conformance.results import Measure, Settings, spec

# initial_frames.x3d (its comment states the same numbers): a slider whose Block starts 0.5 m from
# its Rail along the axis, and a hinge whose Arm (and fixed Pivot) start turned about x, the axis world z
AXIS = np.array([0.6, -0.8, 0.0])
RAIL, BLOCK = np.zeros(3), 0.5 * AXIS  # Block starts at (0.3, -0.4, 0)
SLIDE_MIN, SLIDE_MAX, SLIDE_ERP = 0.0, 0.2, 1.0
SLIDE_A = G * float(AXIS @ np.array([0.0, -1.0, 0.0]))  # 0.8 g along the axis
PIVOT, ARM = np.array([2.0, 0.0, 0.0]), np.array([3.0, 0.0, 0.0])  # the anchor at the Pivot, the arm 1 m out
ARM_L, ARM_M, ARM_I = 1.0, 1.0, 0.001
I_P = ARM_I + ARM_M * ARM_L ** 2  # about the anchor
TURN = math.pi / 3  # Arm turned +60 deg about x, Pivot -60 deg
ARM_Q, PIVOT_Q = np.array([1.0, 0.0, 0.0, TURN]), np.array([1.0, 0.0, 0.0, -TURN])
HINGE_AXIS = np.array([0.0, 0.0, 1.0])

RESTING = spec("37.2.5.1 Initial coordinate system: When the two bodies are initially placed in the scene, their "
               "initial positions define the resting coordinate frames for the two bodies on that joint.")
RELATIVE = spec("37.2.5.1 Initial coordinate system: Output values from those joints are then relative to this "
                "initial position.")
WORLD = spec("37.2.5.1 Initial coordinate system: The anchor position and axis values of joints are always specified "
             "in world coordinate positions, regardless of whether the two joining bodies have been offset or not.")
CURRENT = spec("37.4.10 RigidBody: After the initial conditions have been set, these fields are used to report the "
               "current information based on the most recent physics model evaluation.")


def _misread_axis(q: np.ndarray) -> np.ndarray:
    """The hinge axis read in a body's frame turned by q: where world z then points."""
    return R.rotate(R.from_axis_angle(q), HINGE_AXIS)


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Slider (Block body1, Rail body2, axis (0.6,-0.8,0), stops [0, 0.2]): the Block starts 0.5 m
    down the axis from the Rail and slides under 0.8 g along it. Hinge (Arm body1, Pivot body2,
    anchor (2,0,0), axis world z): the Arm, 1 m out along +x and turned 60 deg about x, falls
    from horizontal and swings through the vertical (quarter period 0.59 s, run 1 s).

    37.2.5.1/1 (the stops counted from the initial placement): the Block's travel from its file
    position along the axis ends at a stop counted from there: 0 or 0.2 (which one is the
    output's sign, a convention). Bound: stop_overshoot (the impact speed sqrt(2 a 0.2), a rigid
    stop a step late). Misreading: the stops counted from the bodies' origins (separation 0.5 at
    the start): the Block is pushed back to 0.2 from the Rail (0.3 from its start) or, the other
    sign, to the Rail (0.5): honoured, half the nearer, 0.15 m.

    37.2.5.1/2 (outputs relative to the initial position): the reported separation against the
    Block's displacement along the axis from its file position (either sign), every frame.
    Bound: ROUNDING, plus the slide's off-axis drift the rail's rows leave (v^2 h^2 / ERP with
    ERP 0.8, the joint's). Misreading: separation from the bodies' origins: off by 0.5 m, so
    honoured gives 0.25 m.

    37.2.5.1/3 (axis in world coordinates, the bodies turned): the Arm swings in the plane z = 0
    through the anchor and reaches the bottom, y = -1 (relative to the anchor): its largest |z|
    and its lowest point against -L. Read in the Arm's frame (or the Pivot's) world z is (0,
    -sin 60, +-cos 60): the arm swings about that tilted axis, its lowest point -0.5 and its |z|
    up to 0.87: honoured, half of each. Bounds: the drift a velocity-level joint leaves
    (w_max^2 L h^2 / ERP), and for the lowest point the frame sampling, L (1 - cos(w_max / (2 rate))).

    37.4.10/46 (the initial conditions in world space): each moving body's first frame against
    its file position and orientation, within the motion up to the first frame's physics time
    plus a step (a T^2/2 with the largest acceleration each body can have: 0.8 g; the Arm's
    point g L^2 m / I_p, its turn g L m / I_p T^2/2). Misreading: the field ignored (the body at
    the origin, unturned): |position| and 60 deg, honoured half.

    37.4.10/47 (then the current state): the Block's reported positions against its reported
    velocities while it slides (its displacement from its first frame below half the travel to
    the stop), both taken
    along the axis, where no joint row acts (across it the rows' softness, CFM times the load,
    lets the Block sag: the joint's business, not the fields'): clock_free_acceleration against
    0.8 g, exact to rounding for any one-step scheme (bound 4 ROUNDING-scale velocity / window,
    as closed_forms.ballistic's). Misreading:
    the field left at its initial value (no motion reported): |a| off: honoured, 3.9 m/s^2."""
    tr, s = traces[0], settings[0]
    h = s.dt
    out: list[Measure] = []
    # -- the slider
    t, p = tr.series("Block", "position")
    _, v = tr.series("Block", "linearVelocity")
    _, sep = tr.series("Slide", "separation")
    sep = sep[:, 0]
    along = (p - BLOCK) @ AXIS
    impact = math.sqrt(2 * SLIDE_A * (SLIDE_MAX - SLIDE_MIN))
    stop = stop_overshoot(impact, SLIDE_A, h, SLIDE_ERP)
    end = float(along[-1])
    out.append(Measure("Block travel from its file position along the axis at the end - the nearer stop (0, 0.2)",
                       min(abs(end - SLIDE_MIN), abs(end - SLIDE_MAX)), honoured(stop, 0.3, 0.5), "m", RESTING, stop))
    drift = impact ** 2 * h * h / 0.8 + ROUNDING * (1 + float(np.linalg.norm(BLOCK)))
    rel = min(max_norm(sep - along), max_norm(sep + along))
    out.append(Measure("Slide.separation - the Block's displacement along the axis from its file position (either sign)",
                       rel, honoured(drift, 0.5), "m", RELATIVE, drift))
    # -- the hinge
    _, pa = tr.series("Arm", "position")
    arm = pa - PIVOT
    w_max = math.sqrt(2 * ARM_M * G * ARM_L / I_P)
    held = w_max ** 2 * ARM_L * h * h / 0.8 + ROUNDING * (1 + float(np.linalg.norm(ARM)))
    tilted = [_misread_axis(q) for q in (ARM_Q, PIVOT_Q)]
    # about a tilted axis n the arm (along x, perpendicular to n) circles in the plane spanned by x and n x x = (0, n_z, -n_y)
    low = [abs(n[2]) * ARM_L for n in tilted]  # n has no x: the circle's lowest point is -|n_z| L, at |z| = |n_y| L
    off = [abs(n[1]) * ARM_L for n in tilted]
    out.append(Measure("Arm out of the plane through the anchor perpendicular to world z (largest |z|)",
                       float(np.max(np.abs(arm[:, 2]))), honoured(held, *off), "m", WORLD, held))
    sampled = ARM_L * (1 - math.cos(w_max / (2 * s.rate))) + held
    out.append(Measure("Arm lowest point - (anchor - L) (it swings through the vertical below the anchor)",
                       abs(float(np.min(arm[:, 1])) + ARM_L), honoured(sampled, *(ARM_L - x for x in low)), "m",
                       WORLD, sampled))
    # -- the bodies' fields: the first frame
    t0 = float(t[0]) + h
    for body, start, accel in (("Block", BLOCK, SLIDE_A), ("Arm", ARM, G * ARM_M * ARM_L ** 2 / I_P)):
        _, q = tr.series(body, "position")
        bound = 0.5 * accel * t0 * t0 + ROUNDING * (1 + float(np.linalg.norm(start)))
        out.append(Measure(f"{body} first frame's position - its file position", float(np.linalg.norm(q[0] - start)),
                           honoured(bound, float(np.linalg.norm(start))), "m", INITIAL, bound))
    _, qa = tr.series("Arm", "orientation")
    turn = 0.5 * G * ARM_M * ARM_L / I_P * t0 * t0 + ROUNDING_ANGLE
    first = float(R.angle_between(R.from_axis_angle(qa[:1]), R.from_axis_angle(ARM_Q[None, :]))[0])
    out.append(Measure("Arm first frame's orientation - its file orientation (angle)", first,
                       honoured(turn, TURN), "rad", INITIAL, turn))
    # -- the current state: the Block's positions against its velocities while it slides freely
    free = (p - p[0]) @ AXIS <= 0.5 * SLIDE_MAX  # from its first frame: this measure is not about where it starts
    v_round = ROUNDING * (1 + SLIDE_A * float(s.duration))
    window = max(float(np.ptp(t[free])) if np.count_nonzero(free) > 1 else 0.0, h)
    a_bound = 4 * v_round / window
    if np.count_nonzero(free) >= 3:
        fitted = clock_free_acceleration((p[free] @ AXIS)[:, None], (v[free] @ AXIS)[:, None])
        err = abs(float(fitted[0]) - SLIDE_A)
    else:
        err = math.inf
    out.append(Measure("Block acceleration along the axis its reported positions and velocities show (whatever the "
                       "clock) - 0.8 g", err, honoured(a_bound, SLIDE_A), "m/s^2", CURRENT, a_bound))
    return out


CASE = Case("initial_frames", "initial_frames.x3d",
            "SliderJoint whose Block starts 0.5 m along its axis: separation 0 there, stops counted from there; "
            "SingleAxisHingeJoint whose bodies start turned about x, axis world z: the arm swings about world z; "
            "RigidBody position/orientation: the first frame at the file's, then the current state",
            (Settings(1.0, 1 / 240, None),), expect,
            exercises=("RigidBody.position", "RigidBody.orientation", "SliderJoint.axis",
                       "SingleAxisHingeJoint.axis"),
            mutations=(Mutation(" position='0.3 -0.4 0'", ""),  # /1, /2: the Block starts at the Rail
                       Mutation(" axis='0 0 1'", " axis='0 -0.8660254 0.5'"),  # /3: the axis as the Arm's frame reads it
                       Mutation(" orientation='1 0 0 1.0471976'", ""),  # /46: the Arm starts unturned
                       Mutation("<RigidBody DEF='Block' mass='1'", "<RigidBody DEF='Block' fixed='true' mass='1'")))

"""incline: CollisionCollection frictionCoefficients: a box sticks on a gentle incline and slides down a steep one.

The scene applies FRICTION_COEFFICIENT-2 with equal coefficients: the UOM's table 37.2 reads "Apply
frictionCoefficients values" for it, which X_ITE takes literally (no friction without the flag)
and ODE does not (mu always, mu2 with the flag): with it, every reading applies mu. Friction
without the flag would be a convention (ODE's reading), not the spec's."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import (CFM_DEFAULT, ERP_DEFAULT, FRICTION, ROUNDING, G, honoured, max_norm,
                                           physics_time)
from conformance.results import Measure, Settings


# incline.x3d: boxes (1 kg, 0.1 m thick) on inclines (0.2 m thick) turned about +z by theta; each
# starts at rest 2 m up the slope from the centre of its incline's top face
INC_MU, INC_M, INC_UP, INC_OFFSET = 0.5, 1.0, 2.0, 0.1 + 0.05
INC_BOXES = {"Stuck": (math.radians(20.0), -1.0), "Slider": (math.radians(35.0), 1.0)}
INC_FIT_FROM = 0.25  # s


def incline_frame(theta: float, z: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Start position, downhill unit vector and slope normal of a box on an incline."""
    uphill = np.array([math.cos(theta), math.sin(theta), 0.0])
    normal = np.array([-math.sin(theta), math.cos(theta), 0.0])
    return np.array([0.0, 0.0, z]) + INC_OFFSET * normal + INC_UP * uphill, -uphill, normal


def fitted_acceleration(t: np.ndarray, s: np.ndarray) -> tuple[float, float]:
    """Least-squares a of s = c0 + c1 t + a t^2/2, and how much a bounded velocity disturbance
    moves it: a = sum w_i s_i; a velocity error eps(t) adds int_t0^t_i eps to s_i, so a moves by
    int eps(t) W(t) dt, W(t) = sum over t_i > t of w_i: at most max|eps| int |W| dt (returned)."""
    design = np.column_stack([np.ones_like(t), t - t[0], 0.5 * (t - t[0]) ** 2])
    w = np.linalg.pinv(design)[2]
    tail = np.cumsum(w[::-1])[::-1]  # tail[k] = sum_{i >= k} w_i
    return float(w @ s), float(np.sum(np.abs(tail[1:]) * np.diff(t)))


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Stuck: |p - p0| over 2 s. Static friction holds it exactly in a hard-contact engine; ODE's
    rows yield by CFM times their force: the friction rows creep at CFM m g sin(theta) (the whole
    load on one row) and the normal rows sink to CFM m g cos(theta) h / ERP; a contact acting a step
    late lets the box fall g h^2 once. Bound: CFM m g (sin T + cos h / ERP) + g h^2 (sin + cos).

    Slider: a fitted to the distance down the slope over [0.25 s, 2 s] against
    g (sin theta - mu cos theta). Under a constant acceleration every one-step scheme's positions
    are an exact quadratic in t (semi-implicit Euler: a t^2/2 + a h t/2; the O(h) term is linear
    and the fit's c1 takes it), so the fit is exact; what remains is the contact's departure from
    its steady state: friction's impulse over any interval is mu times the normal impulse, which is
    m g cos(theta) per second up to the change in the box's normal velocity (within g h when
    contacts act at most a step late), and a step without contact adds g sin(theta) h of slide:
    the velocity along the slope strays from the straight line by at most
    eps = g h (2 mu cos theta + sin theta); fitted_acceleration turns that into the bound on a.

    Those are accuracy bounds; the tolerances (closed_forms.honoured) are half the nearest
    misreading's error: friction ignored (X3D's default coefficients, 0): Stuck slides
    g sin(theta) T^2 / 2, Slider speeds up mu g cos(theta) faster; and for Slider the ramp's
    rotation ignored (a flat box: Slider drops onto it and stays, g (sin - mu cos) off)."""
    tr, s = traces[0], settings[0]
    out = []
    h, T = s.dt, s.duration
    for name, (theta, z) in INC_BOXES.items():
        start, down, _ = incline_frame(theta, z)
        t, p = tr.series(name, "position")
        tp = physics_time(t, h)
        sin, cos = math.sin(theta), math.cos(theta)
        if math.tan(theta) <= INC_MU:
            bound = (CFM_DEFAULT * INC_M * G * (sin * T + cos * h / ERP_DEFAULT) + G * h * h * (sin + cos)
                     + ROUNDING * (1 + float(np.linalg.norm(start))))
            out.append(Measure(f"{name} (tan {math.degrees(theta):g} deg <= mu) |position - start|",
                               max_norm(p - start), honoured(bound, 0.5 * G * sin * T * T), "m", FRICTION, bound))
            continue
        a_exact = G * (sin - INC_MU * cos)
        window = tp >= INC_FIT_FROM
        a, spread = fitted_acceleration(tp[window], (p[window] - start) @ down)
        eps = G * h * (2 * INC_MU * cos + sin)
        bound = eps * spread + ROUNDING * (1 + a_exact)
        out.append(Measure(f"{name} (tan {math.degrees(theta):g} deg > mu) fitted acceleration - g (sin - mu cos)",
                           abs(a - a_exact), honoured(bound, INC_MU * G * cos, a_exact), "m/s^2", FRICTION,
                           bound))
    return out


CASE = Case("incline", "incline.x3d",
            "CollisionCollection frictionCoefficients 0.5 on static inclines: at 20 degrees the box sticks; at 35 "
            "it slides at g (sin - mu cos) = 1.6088 m/s^2",
            (Settings(2.0, 1 / 240),), expect,
            exercises=("CollisionCollection.frictionCoefficients", "CollidableShape.rotation",
                       "CollidableShape.geometry.Box", "RigidBody.orientation"),
            mutations=((" frictionCoefficients='0.5 0.5'", ""),
                       # the steep ramp left flat: Slider drops onto it and stays, far from g (sin - mu cos)
                       (" rotation='0 0 1 0.6108652381980153'", "")))

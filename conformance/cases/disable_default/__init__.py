"""disable_default: automatic disabling is off by default, on a RigidBody and on a RigidBodyCollection, and
autoDisable TRUE turns it on."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, honoured, max_norm, physics_time
from conformance.results import Measure, Settings, spec

# disable_default.x3d: every body drifts at V0 and turns at W0, under every threshold (0.1 m/s, 0.1 rad/s, 0.25 s)
DD_V0, DD_W0 = np.array([0.05, 0.0, 0.0]), np.array([0.0, 0.0, 0.05])
DD_TIME = 0.25
DD_SETTLED = DD_TIME + 0.25  # s: a disabled body is at rest from here on, a quarter second after disableTime
BODY_SWITCH = spec("37.4.10 RigidBody: By default, this automatic disabling is turned off. It may be enabled by "
                   "setting the autoDisable field to TRUE.")
COLLECTION_SWITCH = spec("37.4.11 RigidBodyCollection: By default, this automatic disabling is turned off. It may be "
                         "enabled by setting the autoDisable field to TRUE.")
# Brisk, Lively: both speeds above the thresholds (so under either reading of "any one of these values"), autoDisable
# TRUE (Brisk's own, Lively's collection's): never disabled, the thresholds being the conditions
BODY_CONDITIONS = spec("37.4.10 RigidBody: The disable fields define conditions for when the body ceases to "
                       "considered as part of the rigid body calculations and should be considered as at rest.")
COLLECTION_CONDITIONS = spec("37.4.11 RigidBodyCollection: The disable fields define conditions for when the body "
                             "ceases to considered as part of the rigid body calculations and should be considered "
                             "as at rest.")
DD_FAST_V0, DD_FAST_W0 = np.array([0.2, 0.0, 0.0]), np.array([0.0, 0.0, 0.2])
# body -> (the basis its measures are held to, whether it is disabled, its v0 and w0)
DD_BODIES = {"Unset": (COLLECTION_SWITCH, False, DD_V0, DD_W0), "Unasked": (BODY_SWITCH, False, DD_V0, DD_W0),
             "Asked": (BODY_SWITCH, True, DD_V0, DD_W0), "Gathered": (COLLECTION_SWITCH, True, DD_V0, DD_W0),
             "Brisk": (BODY_CONDITIONS, False, DD_FAST_V0, DD_FAST_W0),
             "Lively": (COLLECTION_CONDITIONS, False, DD_FAST_V0, DD_FAST_W0)}


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Nothing acts on any body, so a body no one disables keeps its velocities exactly (rounding:
    ROUNDING, the bound), and a disabled one has none (the evaluator zeroes them: ROUNDING). Both
    speeds are under the thresholds from the start, so a body whose automatic disabling is on is at
    rest once disableTime has passed under either reading of 'any one of these values' (any one
    speed, or both: closed_forms.AT_REST's cases say which is x3drbp's); it is measured from 0.5 s,
    a quarter second after, so that no counting of disableTime's steps matters.
    - Unset, Unasked (drifting: the default off): max |v - v0| and |w - w0| over the run; the
      misreading, the default on, stops them at 0.25 s (|v0| and |w0| off), so the tolerance is
      half that (closed_forms.honoured);
    - Asked, Gathered (autoDisable TRUE, its own or its collection's): max |v| and |w| from 0.5 s;
      the misreading, autoDisable ignored, leaves them drifting (|v0| and |w0|): half that;
    - Brisk, Lively (autoDisable TRUE, its own or its collection's, both speeds 0.2 above the thresholds
      0.1): max |v - v0| and |w - w0| over the run, as Unset's; the misreading, every autoDisable
      body stopped after disableTime whatever its speeds (the thresholds not the conditions), stops
      them (|v0| and |w0| off): half that."""
    tr, s = traces[0], settings[0]
    out = []
    for name, (basis, disabled, v0, w0) in DD_BODIES.items():
        t, v = tr.series(name, "linearVelocity")
        _, w = tr.series(name, "angularVelocity")
        for field, got, start, unit in (("linearVelocity", v, v0, "m/s"), ("angularVelocity", w, w0, "rad/s")):
            size = float(np.linalg.norm(start))
            if disabled:
                late = physics_time(t, s.dt) >= DD_SETTLED
                error = max_norm(got[late]) if late.any() else float("inf")
                what = f"{name} |{field}| from {DD_SETTLED:g} s (disabled: at rest)"
            else:
                error, what = max_norm(got - start), f"{name} |{field} - its start| (not disabled: drifts on)"
            out.append(Measure(what, error, honoured(ROUNDING, size), unit, basis, ROUNDING))
    return out


CASE = Case("disable_default", "disable_default.x3d",
            "autoDisable left FALSE (RigidBody and RigidBodyCollection) with the disable thresholds set: bodies "
            "under them drift on; with autoDisable TRUE (a body's own, or its collection's) they are at rest after "
            "disableTime (0.1 m/s, 0.1 rad/s, 0.25 s); bodies over both thresholds drift on with autoDisable TRUE",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("RigidBody.autoDisable", "RigidBodyCollection.autoDisable", "RigidBody.disableLinearSpeed",
                       "RigidBodyCollection.disableLinearSpeed"),
            mutations=(
                # a body's automatic disabling on by default: Unasked stops
                ("inertia='0.004 0 0 0 0.004 0 0 0 0.004'\n          disableLinearSpeed",
                 "inertia='0.004 0 0 0 0.004 0 0 0 0.004'\n          autoDisable='true' disableLinearSpeed"),
                ("\n          autoDisable='true' disableLinearSpeed", "\n          disableLinearSpeed"),  # Asked drifts
                # a collection's automatic disabling on by default: Unset (and Unasked) stop
                ("DEF='Quiet' gravity='0 0 0'", "DEF='Quiet' gravity='0 0 0' autoDisable='true'"),
                ("DEF='Sleepy' gravity='0 0 0' autoDisable='true'", "DEF='Sleepy' gravity='0 0 0'"),  # Gathered drifts
                # Brisk's thresholds above both its speeds: it stops
                ("disableLinearSpeed='0.1' disableAngularSpeed='0.1'\n          disableTime='0.25' autoDisable='true'",
                 "disableLinearSpeed='0.3' disableAngularSpeed='0.3'\n          disableTime='0.25' autoDisable='true'"),
                # Sleepy's thresholds above both of Lively's speeds: it stops
                ("autoDisable='true' disableLinearSpeed='0.1'\n        disableAngularSpeed='0.1'",
                 "autoDisable='true' disableLinearSpeed='0.3'\n        disableAngularSpeed='0.3'"),
            ))

"""disabled_body: RigidBody.enabled FALSE: the body is left out of the physics, while the one beside it falls.

A body "not submitted to the physics engine for processing" is not moved by it: it reports no
state (x3drbp writes no rows for it), or, where an implementation still reports its fields,
the file's values unchanged. Either way nothing it reports may move."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core import rotation as R
from x3d_core.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import G, GRAVITY, ROUNDING, ROUNDING_ANGLE, ballistic, max_norm
from conformance.results import Measure, Settings, spec


ENABLED = spec("37.4.10 RigidBody: The enabled field controls whether the information in this node is submitted to "
               "the physics engine for processing. If the enabled field is set TRUE, the node is submitted to the "
               "physics engine. If the enabled field is set FALSE, the node is not submitted to the physics engine "
               "for processing.", "V3.3")

# disabled_body.x3d: Off's file state, and On's start
OFF_POSITION, OFF_ORIENTATION = np.array([-1.0, 5.0, 0.0]), np.array([0.0, 0.0, 1.0, 0.3])
ON_START = (1.0, 5.0, 0.0)


def _reported(tr: TraceView, node: str, field: str) -> np.ndarray | None:
    """The node's values of a field over the run, or None where it reports none."""
    return tr.series(node, field)[1] if (node, field) in tr.keys() else None


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Off: whatever it reports against its file state, with no tolerance beyond rounding: a body
    the engine never gets is moved by nothing (a run reporting no rows for it has nothing moved:
    error 0). Ignored, the field lets it fall g T^2/2 = 4.9 m in 1 s. On: closed_forms.ballistic,
    held to the gravity sentence."""
    tr = traces[0]
    held = {"position": (lambda p: max_norm(p - OFF_POSITION), ROUNDING * (1 + float(np.linalg.norm(OFF_POSITION))),
                         "m"),
            "orientation": (lambda q: float(np.max(R.angle_between(R.from_axis_angle(q),
                                                                   R.from_axis_angle(OFF_ORIENTATION)))),
                            ROUNDING_ANGLE, "rad"),
            "linearVelocity": (max_norm, ROUNDING, "m/s"),
            "angularVelocity": (max_norm, ROUNDING, "rad/s")}
    out = []
    for field, (moved, tolerance, unit) in held.items():
        values = _reported(tr, "Off", field)
        out.append(Measure(f"Off.{field} - its file value (where reported at all)",
                           0.0 if values is None else moved(values), tolerance, unit, ENABLED))
    return out + ballistic("On", ON_START, (0, 0, 0), (0, -G, 0), GRAVITY)(traces, settings)


CASE = Case("disabled_body", "disabled_body.x3d",
            "RigidBody.enabled FALSE: Off stays at its file state (or reports nothing) while On falls at g = 9.81",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("RigidBody.enabled", "RigidBodyCollection.gravity"),
            mutations=((" enabled='false'", ""),))

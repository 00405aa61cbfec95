"""disabled_body: RigidBody.enabled FALSE: the body is left out of the physics, while the one beside it falls.

A body "not submitted to the physics engine for processing" is not moved by it: it reports no
state (x3drbp writes no rows for it), or, where an implementation still reports its fields,
the file's values unchanged. Either way nothing it reports may move."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import G, GRAVITY, ballistic, held
from conformance.results import Measure, Settings, spec


ENABLED = spec("37.4.10 RigidBody: The enabled field controls whether the information in this node is submitted to "
               "the physics engine for processing. If the enabled field is set TRUE, the node is submitted to the "
               "physics engine. If the enabled field is set FALSE, the node is not submitted to the physics engine "
               "for processing.")

# disabled_body.x3d: Off's file state, and On's start
OFF_POSITION, OFF_ORIENTATION = np.array([-1.0, 5.0, 0.0]), np.array([0.0, 0.0, 1.0, 0.3])
ON_START = (1.0, 5.0, 0.0)


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Off: closed_forms.held (nothing it reports may move; ignored, the field lets it fall
    g T^2/2 = 4.9 m in 1 s). On: closed_forms.ballistic, held to the gravity sentence."""
    return (held(traces[0], "Off", OFF_POSITION, OFF_ORIENTATION, ENABLED)
            + ballistic("On", ON_START, (0, 0, 0), (0, -G, 0), GRAVITY)(traces, settings))


CASE = Case("disabled_body", "disabled_body.x3d",
            "RigidBody.enabled FALSE: Off stays at its file state (or reports nothing) while On falls at g = 9.81",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("RigidBody.enabled", "RigidBodyCollection.gravity"),
            mutations=((" enabled='false'", ""),))

"""own_collection: each body falls at its own collection's gravity, and a collection inside a turned and moved
Transform moves its bodies in world coordinates as if the Transform were not there."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, ballistic, clock_free_acceleration
from conformance.results import Measure, Settings, spec

# own_collection.x3d: each body's collection gravity and start (world coordinates); the Transform around Moon
EARTH_G, MOON_G = np.array([0.0, -9.81, 0.0]), np.array([0.0, -1.62, 0.0])
DROPPED_START, LUNAR_START = np.array([-1.0, 2.0, 0.0]), np.array([0.0, 2.0, 0.0])
TURN = math.pi / 2  # about z
SHIFT = np.array([3.0, 0.0, 0.0])


def _turned(v: np.ndarray) -> np.ndarray:
    """v turned by the Transform's rotation (TURN about z)."""
    c, s = math.cos(TURN), math.sin(TURN)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]])


# where a browser applying the Transform would start Lunar, and the way it would make it fall
LUNAR_PLACED = _turned(LUNAR_START) + SHIFT  # (1, 0, 0)

OWN = spec("37.4.11 RigidBodyCollection: The bodies field contains a collection of the top-level nodes that comprise "
           "a set of bodies that should be evaluated as a single set of interactions.",
           also=("37.4.11 RigidBodyCollection: The gravity field indicates direction and strength of the local "
                 "gravity vector for this collection of bodies.",))
UNTRANSFORMED = spec("37.2.2.2 Transformation hierarchy: The nodes defined in this component are not part of the "
                     "transformation hierarchy.",
                     also=("37.2.3 Bodies: All bodies exist within the world space of their collection.",))


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Each body: closed_forms.ballistic from rest at its own collection's gravity, held to OWN. Its
    acceleration is exact to rounding for every one-step scheme (ballistic's argument); the tolerance is
    half the nearest misreading's error (closed_forms.honoured): the other collection's gravity in its
    place (every body evaluated in one world: 8.19 m/s^2 off) or none (a collection left out: its own
    gravity's size), 0.81 m/s^2 for Lunar and 4.1 for Dropped.

    Lunar, held to UNTRANSFORMED (the Transform around its collection has no effect):
    - where it starts: the first reported position against the file's, in world coordinates, up to
      the fall to that frame and one step more (1/2 |g| (t1 + h)^2) and ROUNDING: the bound; the
      tolerance half the distance to where the Transform would put it (R p0 + t = (1, 0, 0),
      2.24 m away);
    - which way it falls: the angle between the acceleration its motion shows
      (closed_forms.clock_free_acceleration, whatever the clock) and world -y. The fit is exact to
      rounding, so the bound is ballistic's acceleration bound over |g|; the tolerance half the
      Transform's turn (pi/4): a browser that turned the collection's gravity with it makes Lunar
      fall along world +x. A Lunar that shows no acceleration at all (a collection inside a Transform
      never run) has no direction: error pi."""
    tr, s = traces[0], settings[0]
    out = ballistic("Lunar", LUNAR_START, (0, 0, 0), MOON_G, OWN, misread=[EARTH_G, (0, 0, 0)])(traces, settings)
    out += ballistic("Dropped", DROPPED_START, (0, 0, 0), EARTH_G, OWN, misread=[MOON_G, (0, 0, 0)])(traces, settings)
    t, p = tr.series("Lunar", "position")
    _, v = tr.series("Lunar", "linearVelocity")
    g = float(np.linalg.norm(MOON_G))
    start_bound = 0.5 * g * (float(t[0]) + s.dt) ** 2 + ROUNDING * (1 + float(np.linalg.norm(LUNAR_START)))
    out.append(Measure("Lunar's first position - its file position in world coordinates",
                       float(np.linalg.norm(p[0] - LUNAR_START)),
                       max(start_bound, 0.5 * float(np.linalg.norm(LUNAR_PLACED - LUNAR_START))), "m",
                       UNTRANSFORMED, start_bound))
    fitted = clock_free_acceleration(p, v)
    size = float(np.linalg.norm(fitted))
    angle = math.acos(max(-1.0, min(1.0, float(fitted @ MOON_G) / (size * g)))) if size > 0 else math.pi
    window = max(float(t[-1] - t[0]), s.dt)
    angle_bound = 4 * ROUNDING * (1 + g * float(t[-1])) / window / g
    out.append(Measure("Lunar's fall direction - world -y (angle)", angle, max(angle_bound, 0.5 * TURN), "rad",
                       UNTRANSFORMED, angle_bound))
    return out


# Lunar, the end of its collection and the start of Earth's, and Dropped: what swapping the two bodies' collections
# edits (each collection keeps a body)
LUNAR = "<RigidBody DEF='Lunar' mass='1' position='0 2 0' inertia='0.004 0 0 0 0.004 0 0 0 0.004'/>"
DROPPED = "<RigidBody DEF='Dropped' mass='1' position='-1 2 0' inertia='0.004 0 0 0 0.004 0 0 0 0.004'/>"
BETWEEN = ("\n      </RigidBodyCollection>\n    </Transform>\n    <RigidBodyCollection DEF='Earth' gravity='0 -9.81 0'>"
           "\n      ")

CASE = Case("own_collection", "own_collection.x3d",
            "RigidBodyCollection bodies and gravity: Lunar falls at its Moon collection's 1.62 m/s^2, Dropped at "
            "its Earth collection's 9.81; Moon is inside a Transform (turned 90 degrees about z, moved 3 m): Lunar "
            "starts and falls in world coordinates as if the Transform were not there",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("RigidBodyCollection.gravity",),
            mutations=(
                # each body listed in the other collection's bodies: Lunar falls at 9.81, Dropped at 1.62
                (LUNAR + BETWEEN + DROPPED, DROPPED + BETWEEN + LUNAR),
                # the Transform applied to where Lunar starts (R p0 + t), and to the way its collection's gravity points
                (" position='0 2 0'", " position='1 0 0'"),
                (" gravity='0 -1.62 0'", " gravity='1.62 0 0'"),
            ))

"""disabled_collections: enabled FALSE on a RigidBodyCollection, a CollisionCollection and a CollisionSensor."""

from __future__ import annotations

from collections.abc import Sequence

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import SENSOR_ACTIVE, falls, held, rests, sensor_contacts, steps
from conformance.results import Measure, Settings, description, spec

# disabled_collections.x3d: the bodies' file states and starts
WATCHED, SINKER = (0.0, 0.1, 0.0), (3.0, 0.1, 0.0)
HELD_POSITION, HELD_ORIENTATION = (-3.0, 5.0, 0.0), (0.0, 0.0, 1.0, 0.3)
RUN = spec("37.4.11 RigidBodyCollection: The enabled field is used to control whether the physics model for this "
           "collection should be run this frame.")
COLLIDE = spec("37.4.4 CollisionCollection: The enabled field is used to control whether the collision detection "
               "system for this collection should be run at the end of this frame. A value of TRUE enables it while a "
               "value of FALSE disables it. A CollisionSensor node watching this collection does not report any "
               "outputs for this collection for this frame if it is not enabled.")
SENSOR_ENABLED = description("CollisionSensor enabled: \"Enables/disables node operation.\"")


def _active(tr: TraceView, sensor: str) -> dict[float, bool]:
    """Frame time -> isActive, for the frames the sensor reports it (none: it reports nothing)."""
    try:
        return {t: v == "true" for t, v in zip(*tr.text(sensor, "isActive"))}
    except KeyError:
        return {}


def _reporting(tr: TraceView, sensor: str) -> int:
    """The frames on which the sensor reports a contact or is active."""
    active = _active(tr, sensor)
    return len({t for t, on in active.items() if on} | set(sensor_contacts(tr, sensor)))


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Held: closed_forms.held (no physics moves it; run, it falls 4.9 m). Sinker:
    closed_forms.falls (its collider not run); Watched: closed_forms.rests (the scene's working
    contact, for Watching to report). Counts, exact: the frames on which Late (watching the
    disabled collider) or Blind (disabled) reports a contact or isActive TRUE, and the frames
    after the first step on which Watching (enabled, watching a resting contact) is not active:
    0 each. Blind is held to the UOM's description: no sentence of clause 37 on a sensor's own
    enabled was readable."""
    tr, s = traces[0], settings[0]
    t, _ = tr.series("Watched", "position")
    active = _active(tr, "Watching")
    idle = sum(1 for time, n in zip(t.tolist(), steps(t, s.dt).tolist()) if n >= 1 and not active.get(time, False))
    return (held(tr, "Held", HELD_POSITION, HELD_ORIENTATION, RUN)
            + falls(traces, settings, "Sinker", SINKER, COLLIDE)
            + rests(tr, s, "Watched", WATCHED, SENSOR_ACTIVE)
            + [Measure("frames on which Late (watching a disabled collection) reports", _reporting(tr, "Late"), 0,
                       basis=COLLIDE),
               Measure("frames after the first step with Watching inactive", idle, 0, basis=SENSOR_ACTIVE),
               Measure("frames on which Blind (disabled) reports", _reporting(tr, "Blind"), 0, basis=SENSOR_ENABLED)])


CASE = Case("disabled_collections", "disabled_collections.x3d",
            "enabled FALSE: a RigidBodyCollection's body is not moved; a CollisionCollection's body falls through "
            "its floor and its sensor reports nothing; a disabled CollisionSensor reports nothing where its "
            "enabled twin reports every frame",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("RigidBodyCollection.enabled", "CollisionCollection.enabled", "CollisionSensor.enabled"),
            mutations=(
                (" gravity='0 -9.81 0' enabled='false'", " gravity='0 -9.81 0'"),  # Held falls
                (" containerField='collider' enabled='false'", " containerField='collider'"),  # Sinker rests
                Mutation("<CollisionSensor DEF='Blind' enabled='false'>", "<CollisionSensor DEF='Blind'>", spec=False),
            ))

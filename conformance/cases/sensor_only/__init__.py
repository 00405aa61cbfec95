"""sensor_only: a CollisionSensor reports a collection no RigidBodyCollection collides with; its contacts push nothing."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import (CONTACT_DEPTH, CONTACT_NORMAL, ROUNDING, ROUNDING_ANGLE, SENSOR_ACTIVE,
                                            SENSOR_CONTACTS, SENSOR_INTERSECTIONS, G, physics_time, sensor_contacts)
from conformance.results import Measure, Settings, spec

# sensor_only.x3d: Ball (r 0.1, released at rest at y0 = 2) falls through the static GateShape (y 0.5 to 1.0)
SO_Y0, SO_R, SO_TOP, SO_BOTTOM = 2.0, 0.1, 1.0, 0.5
SO_ENTER, SO_EXIT = SO_TOP + SO_R, SO_BOTTOM - SO_R  # the ball's centre overlaps the gate between these heights
SO_T1, SO_T2 = (math.sqrt(2 * (SO_Y0 - y) / G) for y in (SO_ENTER, SO_EXIT))  # 0.4284 s, 0.5711 s
SO_PAIR = {"BallShape", "GateShape"}
SO_BODY = {"BallShape": "Ball", "GateShape": "NULL"}

# clause 37's text: 37.4.5 CollisionSensor, 37.4.7 Contact
FOR_USER = spec("37.4.5 CollisionSensor: The CollisionSensor node is used to send collision detection information "
                "into the scene graph for user processing. The collision detection system does not require an "
                "instance of this class to be in the scene in order for it to run or affect the physics model. This "
                "class is used to report to the user contact information should the user require this information "
                "for other purposes.")


def _intersections(tr: TraceView, sensor: str) -> dict[float, set[str]]:
    """The collidables a sensor's intersections name, per frame time."""
    out: dict[float, set[str]] = {}
    for k in range(100):
        try:
            for t, name in zip(*tr.text(sensor, f"intersections[{k}]")):
                out.setdefault(t, set()).add(name)
        except KeyError:
            break
    return out


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Free fall through the gate, and the sensor's reports of it frame by frame.

    Free fall, whatever the clock: at every frame the ball moves straight down at the speed of a
    fall from y0 to its height, v = (0, -sqrt(2 g (y0 - y)), 0). Every one-step scheme advances
    the position with a velocity between the step's start and end ones, which leaves v^2 / 2g
    and y0 - y apart by at most |v| h / 2, so the speed within g h of the height's (RK4, and a
    continuous integrator, exactly). The gate's contacts acting on the ball would stop it (a
    speed 4.2 m/s short), slow it, or turn it back.

    The ball's state at a frame is the exact fall at its physics time tp = floor(t/h) h within
    the first-order lag g tp h / 2 (closed_forms' argument), h/2 in time at the speed g tp; an
    engine that detects at its last step's start rather than at the frame's end sees it one step
    (h) earlier. So a frame is judged where tp is more than 2 h from t1 and t2: overlapping there
    (t1 < tp < t2) the sensor must be active, name BallShape and GateShape as its intersections
    and report a contact between them (body1/body2 Ball and NULL); elsewhere none of it. Every
    contact reported, judged or not: contactNormal along the vertical (the gate is 4 m wide and
    the ball over its middle), within ROUNDING_ANGLE; depth the intersection along that normal,
    as the ball's recorded height gives it (from the ball towards the gate downwards, the ball
    leaves through the top: 1.1 - y; upwards, through the bottom: y - 0.4), within what the ball
    moves in one step at the gate's exit speed, g t2 h + g h^2."""
    tr, s = traces[0], settings[0]
    h = s.dt
    times, ball = tr.series("Ball", "position")
    tp = physics_time(times, h)
    try:
        active = dict(zip(*tr.text("Sensor", "isActive")))
    except KeyError:  # no sensor output at all: inactive on every frame
        active = {}
    hits = _intersections(tr, "Sensor")
    contacts = sensor_contacts(tr, "Sensor")
    judged = (np.abs(tp - SO_T1) > 2 * h) & (np.abs(tp - SO_T2) > 2 * h)
    inside = (tp > SO_T1) & (tp < SO_T2)
    wrong_active = wrong_hits = wrong_contacts = 0
    normal_err = depth_err = 0.0
    for frame, t in enumerate(times.tolist()):
        found = contacts.get(t, [])
        pairs = [c for c in found if {c["geometry1"], c["geometry2"]} == SO_PAIR
                 and (c["body1"], c["body2"]) == (SO_BODY[c["geometry1"]], SO_BODY[c["geometry2"]])]
        if judged[frame]:
            wrong_active += (active.get(t) == "true") != inside[frame]  # no isActive row: inactive
            wrong_hits += hits.get(t, set()) != (SO_PAIR if inside[frame] else set())
            wrong_contacts += (not pairs or len(pairs) < len(found)) if inside[frame] else bool(found)
        y = float(ball[frame][1])
        for c in pairs:
            n = c["contactNormal"] * (1.0 if c["geometry1"] == "BallShape" else -1.0)  # from the ball to the gate
            normal_err = max(normal_err, float(np.linalg.norm(n - [0.0, math.copysign(1.0, n[1]), 0.0])))
            along = SO_ENTER - y if n[1] < 0 else y - SO_EXIT
            depth_err = max(depth_err, abs(float(c["depth"]) - along))
    _, v = tr.series("Ball", "linearVelocity")
    fallen = np.maximum(SO_Y0 - ball[:, 1], 0.0)
    free = np.column_stack([np.zeros(len(v)), -np.sqrt(2 * G * fallen), np.zeros(len(v))])
    moved = G * SO_T2 * h + G * h * h + ROUNDING
    return [
        Measure("Ball.linearVelocity - (0, -sqrt(2 g (y0 - y)), 0): the speed of its fall from y0 (worst frame)",
                float(np.linalg.norm(v - free, axis=1).max()), G * h + ROUNDING, "m/s", FOR_USER, G * h),
        Measure("judged frames whose isActive is not TRUE exactly while the ball overlaps the gate", wrong_active, 0,
                basis=SENSOR_ACTIVE),
        Measure("judged frames whose intersections are not BallShape and GateShape while they overlap, none else",
                wrong_hits, 0, basis=SENSOR_INTERSECTIONS),
        Measure("judged frames without a BallShape-GateShape contact (bodies Ball, NULL) while they overlap, or "
                "with any other contact", wrong_contacts, 0, basis=SENSOR_CONTACTS),
        Measure("contactNormal - (0, 1, 0) or (0, -1, 0), the nearer (worst contact)", normal_err, ROUNDING_ANGLE,
                basis=CONTACT_NORMAL),
        Measure("|depth - the overlap along the normal| (worst contact)", depth_err, moved, "m", CONTACT_DEPTH)]


CASE = Case("sensor_only", "sensor_only.x3d",
            "CollisionSensor on a CollisionCollection no RigidBodyCollection uses: isActive, intersections and "
            "contacts exactly while a falling ball overlaps a static gate (t1 = 0.4284 s to t2 = 0.5711 s), the ball "
            "in free fall through it (its speed sqrt(2 g (y0 - y)) at every height)",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("CollisionSensor", "CollisionSensor.collider.watchedOnly", "CollidableShape.geometry.Sphere",
                       "CollidableShape.geometry.Box"),
            mutations=(
                # the collection not run: its sensor reports nothing (37.4.4)
                ("<CollisionCollection DEF='Watched' containerField='collider'>",
                 "<CollisionCollection DEF='Watched' containerField='collider' enabled='false'>"),
                # the collection acting on the bodies: the gate holds the ball
                Mutation("<RigidBodyCollection DEF='World' gravity='0 -9.81 0'>",
                         "<RigidBodyCollection DEF='World' gravity='0 -9.81 0'>"
                         "<CollisionCollection USE='Watched' containerField='collider'/>"),
            ))

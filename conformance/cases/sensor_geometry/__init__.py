"""sensor_geometry: CollisionSensor contacts: normals, names, positions and depths of a ball on a block on the floor."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import (CFM_DEFAULT, CONTACT_DEPTH, CONTACT_NORMAL, ERP_DEFAULT, ROUNDING,
                                            ROUNDING_ANGLE, SENSOR_ACTIVE, SENSOR_CONTACTS, SENSOR_INTERSECTIONS, G,
                                            sensor_contacts, steps)
from conformance.results import Measure, Settings, accuracy, spec


# sensor_geometry.x3d: Ball (0.2 kg, r 0.1) on Block (1 kg, 0.4 x 0.2 x 0.4) on the static Floor
SG_BALL_M, SG_BLOCK_M, SG_R, SG_BLOCK_HALF, SG_WIDTH = 0.2, 1.0, 0.1, 0.1, 0.4
SG_LOWER = {frozenset(("Floor", "BlockShape")): "Floor", frozenset(("BlockShape", "BallShape")): "BlockShape"}
SG_BODY = {"Floor": "NULL", "BlockShape": "Block", "BallShape": "Ball"}

# clause 37's text: 37.4.5 CollisionSensor, 37.4.7 Contact
NAMES = spec("37.4.7 Contact: The body1 and body2 fields specify two top-level nodes that should be evaluated in the "
             "physics model as a single set of interactions with respect to each other. The geometry1 and geometry2 "
             "fields specify information about body1 and body2.")
NORMAL_DIRECTION = spec("37.2.5.3 Collision contact description: When a collision is found between two objects, it is "
                        "described with the following details: 1. a unit vector describing the surface normal from "
                        "body 1 to body 2 at the point of contact, 2. a primary direction of motion for body 1 "
                        "relative to body 2, and 3. a second direction that is perpendicular to both the normal and "
                        "the primary direction is implied for the purposes of providing various sets of "
                        "coefficients.")
POSITION = spec("37.4.7 Contact: The position field indicates the exact location of the contact that was made "
                "between the two objects.")


SINK = accuracy("how far a resting body sinks into what holds it: one step of unresisted fall g h^2 plus ODE's "
                "softness CFM f h / ERP, f the largest load on a contact")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Every contact of every frame after the first step (the sensor reports the last step's).

    Depth (spec): how deep the intersection is, so the ball-block contact's depth is their overlap
    as their positions give it (the block's top face less the ball's bottom), within what the
    bodies move between the step that found the contact and the frame's end: at rest, at most
    g h of speed over a step, each (2 g h^2). How deep they are is no sentence's: the resting
    penetration (no surface layer) is graded accuracy: one step of unresisted fall g h^2 plus
    ODE's softness CFM f h / ERP, f the largest load on a contact (ball and block on the floor).
    Normal: along the vertical (37.4.7: a unit vector along the normal), and pointing from body 1
    to body 2 (37.2.5.3): (0, +-1, 0) by which geometry is lower (ODE's dContactGeom normal, which
    points from geom 2 into geom 1, turned round; Xj3D and X_ITE report ODE's and Bullet's own,
    towards geometry1, which the clause's direction refuses); the block may tilt by uneven sinking of its
    edges, at most twice the depth bound over its width, and its faces' normals with it.
    Ball's contact position: (x, z) of the ball's centre (off by at most r times the tilt) and
    y within the intersection: between the ball's bottom and the block's top face (Block's
    centre + 0.1), as the depth's 2 g h^2 allows (engines put the point on either surface or
    between them). Names: exact."""
    tr, s = traces[0], settings[0]
    h = s.dt
    depth_tol = G * h * h + CFM_DEFAULT * (SG_BALL_M + SG_BLOCK_M) * G * h / ERP_DEFAULT + ROUNDING
    tilt = 2 * depth_tol / SG_WIDTH
    contacts = sensor_contacts(tr, "Sensor")
    times, ball = tr.series("Ball", "position")
    _, block = tr.series("Block", "position")
    try:
        active = dict(zip(*tr.text("Sensor", "isActive")))
    except KeyError:  # no sensor output at all: inactive on every frame
        active = {}
    hits = {}
    for k in range(100):
        try:
            for t, name in zip(*tr.text("Sensor", f"intersections[{k}]")):
                hits.setdefault(t, set()).add(name)
        except KeyError:
            break
    moved = 2 * G * h * h + ROUNDING  # what the bodies move between the contact's step and the frame's end
    normal_err = depth_err = overlap_err = horizontal_err = vertical_err = 0.0
    wrong_names = inactive = no_ball_contact = missing_hits = reversed_normals = 0
    for frame, (t, n) in enumerate(zip(times.tolist(), steps(times, h).tolist())):
        if n < 1:
            continue
        inactive += active.get(t) != "true"
        missing_hits += hits.get(t, set()) != set(SG_BODY)
        ball_contacts = 0
        for c in contacts.get(t, []):
            g1, g2 = c["geometry1"], c["geometry2"]
            lower = SG_LOWER.get(frozenset((g1, g2)))
            if lower is None or g1 == g2:
                wrong_names += 1
                continue
            wrong_names += (c["body1"], c["body2"]) != (SG_BODY[g1], SG_BODY[g2])
            want = np.array([0.0, 1.0 if g1 == lower else -1.0, 0.0])
            n_along = float(c["contactNormal"] @ want)
            normal_err = max(normal_err, float(np.linalg.norm(c["contactNormal"] - math.copysign(1.0, n_along) * want)))
            reversed_normals += n_along <= 0
            depth_err = max(depth_err, abs(c["depth"]))
            if lower == "BlockShape":
                ball_contacts += 1
                d = c["position"] - ball[frame]
                horizontal_err = max(horizontal_err, math.hypot(d[0], d[2]))
                top, bottom = block[frame][1] + SG_BLOCK_HALF, ball[frame][1] - SG_R
                overlap_err = max(overlap_err, abs(abs(c["depth"]) - max(top - bottom, 0.0)))
                y = c["position"][1]
                vertical_err = max(vertical_err, max(y - max(top, bottom), min(top, bottom) - y, 0.0))
        no_ball_contact += ball_contacts == 0
    return [Measure("frames after the first step with isActive FALSE", inactive, 0, basis=SENSOR_ACTIVE),
            Measure("frames whose intersections do not name Floor, BlockShape and BallShape", missing_hits, 0,
                    basis=SENSOR_INTERSECTIONS),
            Measure("contacts whose geometry1/geometry2/body1/body2 are not a touching pair and its bodies",
                    wrong_names, 0, basis=NAMES),
            Measure("frames with no BallShape-BlockShape contact", no_ball_contact, 0, basis=SENSOR_CONTACTS),
            Measure("contactNormal - (0, 1, 0) or (0, -1, 0), the nearer (worst contact)", normal_err,
                    tilt + ROUNDING_ANGLE, basis=CONTACT_NORMAL),
            Measure("contacts whose contactNormal does not point from geometry1 towards geometry2", reversed_normals, 0,
                    basis=NORMAL_DIRECTION),
            Measure("ball-block |depth| - their overlap (worst contact)", overlap_err, moved, "m", CONTACT_DEPTH),
            Measure("|depth| (worst contact)", depth_err, depth_tol, "m", SINK),
            Measure("ball contact position - ball centre, horizontally", horizontal_err, SG_R * tilt + ROUNDING, "m",
                    POSITION),
            Measure("ball contact position outside the intersection, vertically", vertical_err, moved, "m",
                    POSITION)]


CASE = Case("sensor_geometry", "sensor_geometry.x3d",
            "CollisionSensor contacts of a ball on a block on the floor: contactNormal (0, +-1, 0) (37.2.5.3's "
            "direction: from body 1 to body 2), bodies named, position under the ball's centre at the block's top, depth small",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("CollisionSensor", "CollidableShape.geometry.Sphere", "CollidableShape.geometry.Box"),
            mutations=(
                ("<Sphere radius='0.1'/>", "<Sphere/>"),
                ("<CollisionCollection USE='Contacts' containerField='collider'/>", ""),
            ))

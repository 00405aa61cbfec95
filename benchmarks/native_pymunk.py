"""run_overhead.py's hinge chain, which lies in the xy plane, written in pymunk's own API as
backends/pymunk.py builds it: pymunk is planar, and of engine_speed.py's scenes only the chain
stays in a plane (the car's wheels and the pile's turned boxes leave it). Imports pymunk and
numpy and the scene constants beside it, no x3drbp code.

The model, as the backend sets it: gravity along -y, 10 iterations, no damping and no sleeping;
one body per link with its mass and moment about z, at its centre, unturned; per hinge a
PivotJoint at the anchor (the link first, its parent or the space's static body second) and a
RotaryLimitJoint holding the hinge within X3D's default stops, minAngle -3.14159 and maxAngle
3.14159 (narrower than a full turn, so the backend builds them), each with the error bias that
is ODE's ERP 0.8 at the step. Each frame reads every body's position, angle and velocities, a
body at a time, as a pymunk user does (the backend reads them in bulk through pymunk.batch).
"""

from __future__ import annotations

import numpy as np
import pymunk

import car
import run_overhead

ERP = 0.8  # errorCorrection and stopErrorCorrection, X3D's defaults
STOPS = (-3.14159, 3.14159)  # minAngle and maxAngle, X3D's defaults


def chain(duration: float) -> np.ndarray:
    """The links' positions at the end (LINKS, 3), z 0 as the chain's plane."""
    space = pymunk.Space()
    space.gravity = (0.0, -car.GRAVITY)
    space.iterations = 10
    space.damping = 1.0
    space.sleep_time_threshold = float("inf")
    links = run_overhead.LINKS
    bodies = []
    for k in range(links):
        body = pymunk.Body(run_overhead.MASS, run_overhead.MOMENTS[2])
        body.position = tuple(run_overhead.DIRECTION[:2] * (0.35 * k + 0.175))
        bodies.append(body)
    space.add(*bodies)
    bias = float(np.clip(1.0 - ERP, 0.0, 1.0) ** (1.0 / car.DT))  # the error left after a second
    constraints = []
    for k, body in enumerate(bodies):
        parent = bodies[k - 1] if k else space.static_body
        pivot = pymunk.PivotJoint(body, parent, tuple(run_overhead.DIRECTION[:2] * 0.35 * k))
        stops = pymunk.RotaryLimitJoint(body, parent, max(STOPS[0], -np.pi), min(STOPS[1], np.pi))
        for c in (pivot, stops):
            c.error_bias = bias
            constraints.append(c)
    space.add(*constraints)
    frames, per_frame = round(duration * car.FRAME_RATE), round(1 / (car.FRAME_RATE * car.DT))
    out = []
    for _ in range(frames):
        for _ in range(per_frame):
            space.step(car.DT)
        out.append([(b.position, b.angle, b.velocity, b.angular_velocity) for b in bodies])
    return np.array([[p.x, p.y, 0.0] for p, _, _, _ in out[-1]])


NATIVE = {"chain": chain}

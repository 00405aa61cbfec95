"""What the benchmarks' native DART builds with contacts (pile.py, car.py) share: a world set
up as backends/dart.py sets it up. Imports dartpy only, no x3drbp code."""

from __future__ import annotations

import dartpy as dart


def world(dt: float, gravity: float) -> dart.simulation.World:
    """Gravity along -y, sleeping off (DART puts slow bodies to sleep by default), and
    DART's Bullet collision detector, as the backend's."""
    w = dart.simulation.World()
    w.setTimeStep(dt)
    w.setGravity([0, -gravity, 0])
    sleep = w.getDeactivationOptions()
    sleep.mEnabled = False
    w.setDeactivationOptions(sleep)
    w.setCollisionDetector(dart.collision.BulletCollisionDetector())
    return w

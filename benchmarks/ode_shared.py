"""What the benchmarks' native ODE builds (pile.py, car.py) share: the space calls the
backend's binding leaves out, and a world set up as backends/ode.py sets it up. Only
backends/ode_lib.py is imported, no other x3drbp code."""

from __future__ import annotations

import ctypes

from backends import ode_lib as ode

lib = ode.lib
NEAR = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p)  # dNearCallback


def _declare(name: str, restype, argtypes: list):
    """A call the backend's binding leaves out (it has no spaces), declared here only."""
    fn = lib[name]  # a fresh function object: the binding's own declarations are untouched
    fn.restype, fn.argtypes = restype, argtypes
    return fn


hash_space = _declare("dHashSpaceCreate", ctypes.c_void_p, [ctypes.c_void_p])
simple_space = _declare("dSimpleSpaceCreate", ctypes.c_void_p, [ctypes.c_void_p])
space_collide = _declare("dSpaceCollide", None, [ctypes.c_void_p, ctypes.c_void_p, NEAR])
space_destroy = _declare("dSpaceDestroy", None, [ctypes.c_void_p])


def world(gravity: float, erp: float, cfm: float, iterations: int) -> int:
    """A world as the backend makes one: gravity along -y, the collection's ERP and CFM,
    quick-step's iterations, surface layer 0, ODE's random generator seeded (quick-step
    reorders its rows with it)."""
    lib.dAllocateODEDataForThread(ode.ALLOCATE_ALL)
    lib.dRandSetSeed(0)
    w = lib.dWorldCreate()
    lib.dWorldSetGravity(w, 0, -gravity, 0)
    lib.dWorldSetERP(w, erp)
    lib.dWorldSetCFM(w, cfm)
    lib.dWorldSetQuickStepNumIterations(w, iterations)
    lib.dWorldSetContactSurfaceLayer(w, 0.0)
    return w


def read(bodies: list[int]) -> list[tuple]:
    """One frame's state, a body at a time with dBodyGet* calls, as a user of the plain C API
    from Python reads it: position, quaternion, linear and angular velocity."""
    return [(lib.dBodyGetPosition(b)[:3], lib.dBodyGetQuaternion(b)[:4], lib.dBodyGetLinearVel(b)[:3],
             lib.dBodyGetAngularVel(b)[:3]) for b in bodies]


def simulate(world: int, space: int, group: int, collide, bodies: list[int], frames: int, steps_per_frame: int,
             dt: float, before_step=lambda: None, after_frame=lambda: None) -> list[list[tuple]]:
    """Step with quick-step, the contacts found by dSpaceCollide(collide) before each step
    (last step's joints emptied), every frame's state read; then the world, its space and
    geoms and the contact group destroyed. Returns every frame's read()."""
    out = []
    for _ in range(frames):
        for _ in range(steps_per_frame):
            lib.dJointGroupEmpty(group)
            before_step()
            space_collide(space, None, collide)
            lib.dWorldQuickStep(world, dt)
        out.append(read(bodies))
        after_frame()
    lib.dJointGroupDestroy(group)
    space_destroy(space)  # and its geoms
    lib.dWorldDestroy(world)
    return out

"""Benchmark: x3drbp's run against the same scene written directly in each engine's API.

Two scenes, generated here: a 20-link hinge chain hanging from a fixed body, and 100
free boxes (no collider, so no contacts). Each runs for --duration simulated seconds at
dt = 1/240 s with state read at 60 frames per second. x3drbp's side is load + plan +
build + steps + every frame's bulk readback into the trace (kept in memory); the
native side builds the same model with the engine's own calls, with the same step and
solver iterations, steps it, and reads every body's pose and velocity at each frame.
Writing the trace to CSV is timed apart: it is output, not simulation.

    python benchmarks/run_overhead.py [--duration 10] [--repeat 3] [--backends mujoco,...]
"""

from __future__ import annotations

import argparse
import gc
import os
import sys
import tempfile
import time
import tracemalloc

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from backends import base  # noqa: E402
from x3d_core.evaluator import RunSettings, run  # noqa: E402
from x3d_core.load import load  # noqa: E402
from x3d_core.world import worlds  # noqa: E402

DT = 1 / 240
FRAME_RATE = 60
LINKS = 20
BOXES = 100
INERTIA = "0.0104 0 0 0 0.0104 0 0 0 0.0017"  # a 1 kg, 0.1 x 0.1 x 0.35 box, about its centre


# The chain hangs 0.3 rad from the vertical and swings: an undamped chain released from
# the horizontal blows up within seconds at this step on every engine (notes/backends.md)
DIRECTION = np.array([np.sin(0.3), -np.cos(0.3), 0.0])


def _vec(v: np.ndarray) -> str:
    return " ".join(f"{x:.9g}" for x in v)


def chain_x3d() -> str:
    bodies = ["<RigidBody DEF='Base' fixed='true'/>"]
    joints = []
    for k in range(LINKS):
        bodies.append(f"<RigidBody DEF='L{k}' position='{_vec(DIRECTION * (0.35 * k + 0.175))}' "
                      f"inertia='{INERTIA}'/>")
        parent = "Base" if k == 0 else f"L{k - 1}"
        joints.append(f"<SingleAxisHingeJoint anchorPoint='{_vec(DIRECTION * 0.35 * k)}' axis='0 0 1'>"
                      f"<RigidBody USE='{parent}' containerField='body1'/>"
                      f"<RigidBody USE='L{k}' containerField='body2'/></SingleAxisHingeJoint>")
    return _wrap(bodies + joints)


def boxes_x3d() -> str:
    rng = np.random.default_rng(7)
    bodies = []
    for k in range(BOXES):
        x, y, z = rng.uniform(-5, 5, 3)
        vx, vy, vz = rng.uniform(-1, 1, 3)
        wx, wy, wz = rng.uniform(-3, 3, 3)
        bodies.append(f"<RigidBody DEF='B{k}' position='{x:.6f} {y + 10:.6f} {z:.6f}' "
                      f"linearVelocity='{vx:.6f} {vy:.6f} {vz:.6f}' angularVelocity='{wx:.6f} {wy:.6f} {wz:.6f}' "
                      f"inertia='{INERTIA}'/>")
    return _wrap(bodies)


def _wrap(items: list[str]) -> str:
    return ("<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Full' version='4.0'><Scene>"
            "<RigidBodyCollection gravity='0 -9.81 0' iterations='10'>\n" + "\n".join(items) +
            "\n</RigidBodyCollection></Scene></X3D>\n")


# -- the same scenes written directly in each engine's API --------------------------
def native_mujoco(scene: str, duration: float) -> None:
    import mujoco
    spec = mujoco.MjSpec()
    spec.compiler.degree = False
    spec.option.timestep = DT
    spec.option.gravity = [0, -9.81, 0]
    spec.option.iterations = 10
    spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT
    inertia = [0.0104, 0.0104, 0.0017, 0, 0, 0]
    velocities = []
    if scene == "chain":
        parent = spec.worldbody
        for k in range(LINKS):
            body = parent.add_body(pos=DIRECTION * (0.35 if k else 0.175))
            body.explicitinertial, body.mass, body.fullinertia = True, 1.0, inertia
            body.add_joint(type=mujoco.mjtJoint.mjJNT_HINGE, pos=-0.175 * DIRECTION, axis=[0, 0, 1])
            parent = body
    else:
        rng = np.random.default_rng(7)  # the same draws as boxes_x3d
        for _ in range(BOXES):
            x, y, z = rng.uniform(-5, 5, 3)
            velocities.append(np.concatenate([rng.uniform(-1, 1, 3), rng.uniform(-3, 3, 3)]))
            body = spec.worldbody.add_body(pos=[x, y + 10, z])
            body.explicitinertial, body.mass, body.fullinertia = True, 1.0, inertia
            body.add_freejoint()
    m = spec.compile()
    d = mujoco.MjData(m)
    if velocities:  # free joints: linear (world), angular (body frame, here the same)
        d.qvel[:] = np.concatenate(velocities)
    steps_per_frame = round(1 / (FRAME_RATE * DT))
    frames = []
    for _ in range(round(duration * FRAME_RATE)):
        mujoco.mj_step(m, d, nstep=steps_per_frame)
        mujoco.mj_kinematics(m, d)
        mujoco.mj_comPos(m, d)
        mujoco.mj_comVel(m, d)
        frames.append((d.xpos.copy(), d.xquat.copy(), d.cvel.copy()))


NATIVE = {"mujoco": native_mujoco}


def best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        gc.collect()
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def peak_mb(fn) -> float:
    gc.collect()
    tracemalloc.start()
    fn()
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak / 2**20


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=10.0)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--backends", default=",".join(NATIVE))
    args = ap.parse_args(argv)
    folder = tempfile.mkdtemp(prefix="x3drbp-run-bench-")
    paths = {}
    for name, text in (("chain", chain_x3d()), ("boxes", boxes_x3d())):
        paths[name] = os.path.join(folder, f"{name}.x3d")
        with open(paths[name], "w") as f:
            f.write(text)
    settings = RunSettings(duration=args.duration, dt=DT, frame_rate=FRAME_RATE)
    print(f"{args.duration:g} s simulated, dt 1/240 s, state read at {FRAME_RATE} Hz; best of {args.repeat}\n")
    print("| scene | backend | native s | x3drbp run s | ratio | trace write s | peak MB native | peak MB x3drbp |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for name in args.backends.split(","):
        backend = base.load(name)
        for scene, path in paths.items():
            def ours():
                return run(worlds(load(path)), backend, settings)

            def theirs():
                native = NATIVE[name]
                native(scene, args.duration)
            t_native = best(theirs, args.repeat)
            t_ours = best(ours, args.repeat)
            trace = ours()
            out = os.path.join(folder, f"{scene}-{name}.csv")
            t_write = best(lambda: trace.write(out), 1)
            print(f"| {scene} | {name} {backend.version()} | {t_native:.3f} | {t_ours:.3f} | "
                  f"{t_ours / t_native:.2f}x | {t_write:.3f} | {peak_mb(theirs):.1f} | {peak_mb(ours):.1f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())

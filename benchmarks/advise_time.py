"""Benchmark: the wall time of `x3drbp advise FILE` on a five-body scene, against a 60 s target.

The scene, written here into a temporary folder: a 4-link hinge chain hanging from a fixed
base, released 0.3 rad from the vertical, and a ball dropped onto a static floor beside it,
sliding along it: five moving RigidBodies, four SingleAxisHingeJoints and a
CollisionCollection, so `advise` classes it as "joints and contacts". It is planar (every
body, velocity and gravity in the XY plane, hinge axes along z, a sphere and a box centred
on z = 0) and uses no field at a value any of the five backends refuses, so that every
backend runs it (pymunk runs planar scenes only); the script says so where a backend still
"cannot run it" or a run "did not end well".

Timed: the whole command as a subprocess, from its start to its exit (interpreter start,
imports, the backends' probe and declarations, the judgement, the runs at every step with
their repeats, the reference runs, the text), with advise's own defaults unless options are
passed on; --repeat times, each after the one before has ended. Printed: each run's wall
time with the load average before it, then the median and the spread (lowest-highest)
against the target, with the machine's CPU count and load average.

    python benchmarks/advise_time.py [--repeat 3] [--target 60] [--keep DIR] [-- ADVISE OPTIONS...]
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TARGET_S = 60.0  # the wall time advise should stay under for a scene of a few bodies
LINKS = 4
LINK_LENGTH = 0.3  # m
BASE = np.array([0.0, 2.0, 0.0])
DIRECTION = np.array([np.sin(0.3), -np.cos(0.3), 0.0])  # hanging 0.3 rad from the vertical, in the XY plane
INERTIA = "0.004 0 0 0 0.004 0 0 0 0.004"  # no product of inertia with z: planar


def _vec(v) -> str:
    return " ".join(repr(float(x)) for x in v)


def scene_x3d() -> str:
    """The five-body scene (module docstring) in the XML encoding."""
    bodies = ["      <RigidBody DEF='Base' fixed='true' position='" + _vec(BASE) + "'/>"]
    joints = []
    for k in range(LINKS):
        centre = BASE + DIRECTION * LINK_LENGTH * (k + 0.5)
        bodies.append(f"      <RigidBody DEF='Link{k + 1}' mass='0.5' position='{_vec(centre)}' inertia='{INERTIA}'/>")
        parent = "Base" if k == 0 else f"Link{k}"
        joints.append(
            f"      <SingleAxisHingeJoint DEF='Hinge{k + 1}' anchorPoint='{_vec(BASE + DIRECTION * LINK_LENGTH * k)}' "
            "axis='0 0 1'>\n"
            f"        <RigidBody USE='{parent}' containerField='body1'/>\n"
            f"        <RigidBody USE='Link{k + 1}' containerField='body2'/>\n"
            "      </SingleAxisHingeJoint>")
    ball = ("      <RigidBody DEF='Ball' mass='1' position='1.5 0.6 0' linearVelocity='0.5 0 0' "
            f"inertia='{INERTIA}'>\n"
            "        <CollidableShape DEF='BallShape' containerField='geometry'>\n"
            "          <Shape containerField='shape'><Sphere radius='0.1'/></Shape>\n"
            "        </CollidableShape>\n"
            "      </RigidBody>")
    collider = ("      <CollisionCollection DEF='Contacts' containerField='collider'>\n"
                "        <CollidableShape USE='BallShape' containerField='collidables'/>\n"
                "        <CollidableShape DEF='Floor' containerField='collidables' translation='0 -0.1 0'>\n"
                "          <Shape containerField='shape'><Box size='8 0.2 2'/></Shape>\n"
                "        </CollidableShape>\n"
                "      </CollisionCollection>")
    return ("<?xml version='1.0' encoding='UTF-8'?>\n"
            "<!-- benchmarks/advise_time.py: a 4-link hinge chain from a fixed base and a ball dropped on a floor,\n"
            "     all in the XY plane (hinge axes along z), so that every backend runs it. -->\n"
            "<X3D profile='Full' version='4.0'>\n"
            "  <head>\n"
            "    <component name='RigidBodyPhysics' level='2'/>\n"
            "    <meta name='title' content='advise benchmark: chain and ball'/>\n"
            "  </head>\n"
            "  <Scene>\n"
            "    <RigidBodyCollection DEF='World' gravity='0 -9.81 0'>\n"
            + "\n".join([*bodies, ball, *joints, collider]) + "\n"
            "    </RigidBodyCollection>\n"
            "  </Scene>\n"
            "</X3D>\n")


def command() -> list[str]:
    """`x3drbp`, the console script beside this interpreter (the venv's), else the module."""
    script = os.path.join(os.path.dirname(sys.executable), "x3drbp")
    return [script] if os.access(script, os.X_OK) else [sys.executable, "-m", "conformance.cli"]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=3, help="timed runs of the command (default 3)")
    ap.add_argument("--target", type=float, default=TARGET_S, help=f"seconds (default {TARGET_S:g})")
    ap.add_argument("--keep", metavar="DIR", help="also copy the scene (and the last run's output) into DIR")
    ap.add_argument("advise", nargs="*", metavar="ADVISE OPTIONS", help="passed on to x3drbp advise (after --)")
    args = ap.parse_args(argv)
    if args.repeat < 1:
        ap.error("--repeat must be 1 or more")
    walls, loads, out = [], [], None
    with tempfile.TemporaryDirectory(prefix="x3drbp-advise-bench-") as tmp:
        scene = os.path.join(tmp, "chain_and_ball.x3d")
        with open(scene, "w", encoding="utf-8") as f:
            f.write(scene_x3d())
        argv_ = [*command(), "advise", scene, *args.advise]
        print("$ " + " ".join(["x3drbp", "advise", "chain_and_ball.x3d", *args.advise]) +
              f"  ({LINKS} links on hinges from a fixed base and a ball on a floor: 5 moving bodies)\n", flush=True)
        for k in range(args.repeat):
            loads.append(os.getloadavg()[0])
            started = time.perf_counter()
            out = subprocess.run(argv_, cwd=ROOT, capture_output=True, text=True)
            walls.append(time.perf_counter() - started)
            if out.returncode != 0:
                print(f"x3drbp advise exited {out.returncode}:\n{out.stderr}", file=sys.stderr)
                return 1
            print(f"run {k + 1}: {walls[-1]:.1f} s (load average {loads[-1]:.2f} before)", flush=True)
        if args.keep:
            os.makedirs(args.keep, exist_ok=True)
            shutil.copy(scene, args.keep)
            with open(os.path.join(args.keep, "advise.txt"), "w", encoding="utf-8") as f:
                f.write(out.stdout)
    trouble = [line.strip() for line in out.stdout.splitlines()
               if line.strip().startswith(("cannot run it:", "did not end well:"))]
    median = statistics.median(walls)
    print()
    print("| scene | runs | median wall s | spread (s) | target (s) | within | CPUs | load average (1, 5, 15 min) |")
    print("|---|---:|---:|---|---:|---|---:|---|")
    print(f"| chain_and_ball (5 bodies, joints and contacts) | {len(walls)} | {median:.1f} | "
          f"{min(walls):.1f}-{max(walls):.1f} | {args.target:g} | {'yes' if median <= args.target else 'NO'} | "
          f"{os.cpu_count()} | {', '.join(f'{x:.2f}' for x in os.getloadavg())} |")
    print()
    print("The last run's advice:\n")
    print(out.stdout.rstrip())
    if trouble:
        print("\nnot every backend ran the scene: " + "; ".join(trouble), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

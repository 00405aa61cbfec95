"""Benchmark: the wall and CPU time of `x3drbp advise FILE`, against a target, and against an
earlier revision side by side.

Two scenes, written here into a temporary folder (--scene):
- chain_and_ball (the default): a 4-link hinge chain hanging from a fixed base, released 0.3
  rad from the vertical, and a ball dropped onto a static floor beside it, sliding along it:
  five moving RigidBodies, four SingleAxisHingeJoints and a CollisionCollection, so `advise`
  classes it as "joints and contacts". It is planar (every body, velocity and gravity in the
  XY plane, hinge axes along z, a sphere and a box centred on z = 0) and uses no field at a
  value any backend refuses, so that every backend runs it (pymunk runs planar scenes only);
  target 60 s;
- ball_chain: a 10-link BallJoint chain hanging from a fixed base, 0.3 rad from the vertical
  and tilted out of the XY plane (issue 38's scene): joints only, no contacts, so Drake runs
  it error-controlled (its reference, and its costliest runs: about 1 CPU s per simulated s,
  at the default budget); pymunk refuses it (not planar), every other backend runs it;
  target 30 s on 2 quiet cores.
The script says so where a backend still "cannot run it" or a run "did not end well" (beyond
pymunk on ball_chain).

Timed: the whole command as a subprocess, from its start to its exit (interpreter start,
imports, the backends' probe and declarations, the judgement, the runs at every step and
those timed again, the reference runs, the text), with advise's own defaults unless options
are passed on; --repeat times, each after the one before has ended: its wall time, and its
CPU time (user + system of it and every child it waited for: what another load on the machine
barely moves), their ratio (the parallelism: how busy it kept the cores), with the load average
before it. Each run starts with an empty run cache
(X3DRBP_CACHE, a fresh folder: conformance/runner/cache.py), as on a fresh machine, and with
Python's bytecode compiled beforehand (benchmarks/measure.py: compiled_env).

With --against REV, a second side: the same command at revision REV (its files from git
archive, run with `python -m x3drbp` in that tree, `-m conformance.cli` before the command line's package), the two sides taking turns, and
the ratio of this tree's medians to REV's.

    python benchmarks/advise_time.py [--scene chain_and_ball|ball_chain] [--repeat 3] [--target S]
                                     [--against REV] [--keep DIR] [-- ADVISE OPTIONS...]
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

from measure import command_line, compiled_env, packages, tree_at  # noqa: E402  (benchmarks/measure.py, beside this script)

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


def ball_chain_x3d(links: int = 10) -> str:
    """A chain of `links` bodies joined by BallJoints, hanging from a fixed base along a line
    0.3 rad from the vertical and tilted out of the XY plane (issue 38's scene, value for value)."""
    base = np.array([0.0, 2.0, 0.0])
    direction = np.array([np.sin(0.3), -np.cos(0.3), 0.1])
    direction /= np.linalg.norm(direction)
    bodies = [f"<RigidBody DEF='Base' fixed='true' position='{_vec(base)}'/>"]
    joints = []
    for k in range(links):
        bodies.append(f"<RigidBody DEF='L{k + 1}' mass='0.5' position='{_vec(base + direction * LINK_LENGTH * (k + 0.5))}' "
                      f"inertia='{INERTIA}'/>")
        parent = "Base" if k == 0 else f"L{k}"
        joints.append(f"<BallJoint anchorPoint='{_vec(base + direction * LINK_LENGTH * k)}'>"
                      f"<RigidBody USE='{parent}' containerField='body1'/><RigidBody USE='L{k + 1}' "
                      "containerField='body2'/></BallJoint>")
    return ("<?xml version='1.0' encoding='UTF-8'?>\n"
            "<X3D profile='Full' version='4.0'><head><component name='RigidBodyPhysics' level='2'/></head><Scene>\n"
            "<RigidBodyCollection>\n" + "\n".join([*bodies, *joints]) + "\n</RigidBodyCollection></Scene></X3D>\n")


@dataclass(frozen=True)
class Bench:
    write: Callable[[], str]
    said: str  # the scene in a few words
    target: float  # s of wall time advise should stay under
    refusing: tuple[str, ...] = ()  # backends that cannot run it, as expected


SCENES = {
    "chain_and_ball": Bench(scene_x3d, f"{LINKS} links on hinges from a fixed base and a ball on a floor: 5 moving "
                                       "bodies, joints and contacts", 60.0),
    "ball_chain": Bench(ball_chain_x3d, "10 links on ball joints from a fixed base: joints", 30.0, ("pymunk",)),
}


def _cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def _timed(argv: list[str], cwd: str, env: dict[str, str]) -> tuple[float, float, float, subprocess.CompletedProcess]:
    """One run of the command: (load average before, wall s, CPU s of it and its children, what it gave)."""
    load, cpu, started = os.getloadavg()[0], _cpu(), time.perf_counter()
    out = subprocess.run(argv, cwd=cwd, env=env, capture_output=True, text=True)
    return load, time.perf_counter() - started, _cpu() - cpu, out


def _spread(xs: list[float]) -> str:
    return f"{min(xs):.1f}-{max(xs):.1f}"


def _first_line(stdout: str) -> str:
    return next((line for line in stdout.splitlines() if line and not line.startswith(" ")), "")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", choices=tuple(SCENES), default="chain_and_ball", help="the scene (default chain_and_ball)")
    ap.add_argument("--repeat", type=int, default=3, help="timed runs of the command, a side (default 3)")
    ap.add_argument("--target", type=float, help="seconds of wall time (default: the scene's)")
    ap.add_argument("--against", metavar="REV", help="also time advise at this revision (git archive), taking turns")
    ap.add_argument("--keep", metavar="DIR", help="also copy the scene (and the last run's output) into DIR")
    ap.add_argument("advise", nargs="*", metavar="ADVISE OPTIONS", help="passed on to x3drbp advise (after --)")
    args = ap.parse_args(argv)
    if args.repeat < 1:
        ap.error("--repeat must be 1 or more")
    bench = SCENES[args.scene]
    target = bench.target if args.target is None else args.target
    with tempfile.TemporaryDirectory(prefix="x3drbp-advise-bench-") as tmp:
        scene = os.path.join(tmp, f"{args.scene}.x3d")
        with open(scene, "w", encoding="utf-8") as f:
            f.write(bench.write())
        env = compiled_env(tmp, MUJOCO_GL=os.environ.get("MUJOCO_GL", "disable"))
        sides = {"this tree": ROOT}
        if args.against:
            sides[args.against] = tree_at(args.against, ROOT, tmp)
        for tree in sides.values():  # the bytecode cache filled before any run is timed
            subprocess.run([sys.executable, "-m", "compileall", "-q", *packages(tree)],
                           env=env, check=True, stdout=subprocess.DEVNULL)
        print("$ " + " ".join(["x3drbp", "advise", os.path.basename(scene), *args.advise]) + f"  ({bench.said})\n",
              flush=True)
        runs: dict[str, list[tuple[float, float, float]]] = {side: [] for side in sides}
        last: dict[str, str] = {}
        for k in range(args.repeat):
            for side, tree in sides.items():
                fresh = dict(env, X3DRBP_CACHE=os.path.join(tmp, f"cache-{len(runs[side])}-{side.replace('/', '_')}"))
                load, wall, cpu, out = _timed([*command_line(tree), "advise", scene, *args.advise],
                                              tree, fresh)
                if out.returncode != 0:
                    print(f"x3drbp advise ({side}) exited {out.returncode}:\n{out.stderr}", file=sys.stderr)
                    return 1
                runs[side].append((load, wall, cpu))
                last[side] = out.stdout
                print(f"run {k + 1}, {side}: {wall:.1f} s wall, {cpu:.1f} s CPU, parallelism {cpu / wall:.2f} "
                      f"(load average {load:.2f} before)", flush=True)
        if args.keep:
            os.makedirs(args.keep, exist_ok=True)
            shutil.copy(scene, args.keep)
            with open(os.path.join(args.keep, "advise.txt"), "w", encoding="utf-8") as f:
                f.write(last["this tree"])
    print()
    print("| scene | side | runs | median wall s | spread (s) | median CPU s | spread (s) | parallelism | target (s) "
          "| within | CPUs | load average before each run | load average (1, 5, 15 min) after |")
    print("|---|---|---:|---:|---|---:|---|---:|---:|---|---:|---|---|")
    after = ", ".join(f"{x:.2f}" for x in os.getloadavg())
    medians = {}
    for side, rows in runs.items():
        loads, walls, cpus = (list(col) for col in zip(*rows))
        medians[side] = statistics.median(walls), statistics.median(cpus)
        print(f"| {args.scene} | {side} | {len(rows)} | {medians[side][0]:.1f} | {_spread(walls)} | "
              f"{medians[side][1]:.1f} | {_spread(cpus)} | {statistics.median(c / w for c, w in zip(cpus, walls)):.2f} "
              f"| {target:g} | {'yes' if medians[side][0] <= target else 'NO'} "
              f"| {os.cpu_count()} | {', '.join(f'{x:.2f}' for x in loads)} | {after} |")
    if args.against:
        (w, c), (w0, c0) = medians["this tree"], medians[args.against]
        print(f"\nthis tree against {args.against}: CPU {c / c0:.2f}x ({c:.1f} s against {c0:.1f} s), "
              f"wall {w / w0:.2f}x ({w:.1f} s against {w0:.1f} s; under load, read the CPU)")
    for side, text in last.items():
        print(f"\nThe last run's advice ({side}):\n")
        print(text.rstrip())
    trouble = [line.strip() for line in last["this tree"].splitlines()
               if line.strip().startswith(("cannot run it:", "did not end well:"))
               and not any(line.strip().split(": ")[1].startswith(b) for b in bench.refusing)]
    if trouble:
        print("\nnot every backend ran the scene: " + "; ".join(trouble), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

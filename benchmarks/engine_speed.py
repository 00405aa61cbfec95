"""Benchmark: is a backend's speed the engine's? `x3drbp run` against a hand-written native script.

Three scenes, generated here: run_overhead.py's hinge chain with 10 links (no contacts),
car.py's car (a box chassis on four sphere wheels joined by DoubleAxisHingeJoints, rolling
on a floor) and pile.py's pit with 100 boxes falling into a pile (no spheres). Each runs
for --duration simulated seconds (a case in CAPPED at most its cap: an engine slow alike on
both sides) at dt = 1/240 s with a frame every 1/60 s. Both sides are whole processes, cold
interpreter to exit, taking turns (native, x3drbp, for every scene and backend, --repeat
rounds) so that a load shifts both alike:

- x3drbp: `x3drbp run SCENE --backend B --dt 1/240 --duration D --trace OUT.npz`;
- native: benchmarks/native_run.py, which builds the same model in the engine's own API
  (the native_* builds of run_overhead.py, pile.py and car.py, and native_physx.py's and
  native_drake.py's: same step, solver settings, shapes, masses, inertias and contact
  parameters as the backend sets them, Drake in the mode its backend picks), steps it, reads
  every body's pose and velocity at every frame, and saves the positions; it imports no
  x3drbp code.

Both sides run with Python's bytecode cache (measure.compiled_env, filled by an untimed
one-frame run of every command first), as an installed package runs: an environment with
PYTHONDONTWRITEBYTECODE set would have each process compile its Python from source.
Each side's time is the median over the rounds of its process's CPU time (user + system,
from the kernel's accounting of the child, every thread's: numpy's OpenBLAS workers spin on
both sides; a load beside it still moves it by 10-20 % on a shared 2-CPU machine, so compare
within one run), start-up, imports, load and trace writing included; the ratio is x3drbp's
over the native one, and TARGET is 1.15x. Apart, the simulation alone, as each process times its own CPU: x3drbp's
`--timing` simulation_cpu_s (plan, engine build, steps, every frame's readback) against the
native build, steps and reads (native_run.py), and x3drbp's steps alone (step_cpu_s, what
`advise` ranks speed by). Where the process ratio is over TARGET and the simulation ratio
is not, the difference is x3drbp's start-up, not its engine glue: the column "start-up
added" is that fixed cost, x3drbp's process less its simulation, less the native one's.
The traces are checked to agree (exit status 1 where one does not): the chain's and the
car's positions to SAME at every compared frame (the car's every frame, the chain's last);
the pile, being chaotic, as pile.py checks it (every body to pile.AGREE at pile.CHECK_T,
before any contact, and the final mean height to PILE_HEIGHT_SAME, 1 cm). A backend without a
native build of a scene (native_run.SCENES) is listed as such; pymunk (2D) has the chain's only
(native_pymunk.py).

With --against REV, a third side: `x3drbp run` of revision REV (its files from git archive,
run with `python -m x3drbp` in that tree, `-m conformance.cli` before the command line's package), for a before and after in one run: its
process CPU and its simulation CPU, each over the native one.

    python benchmarks/engine_speed.py [--duration 2] [--repeat 5] [--backends mujoco,bullet,dart,ode,physx,drake]
                                      [--scenes chain,car,pile] [--against REV]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path[:0] = [ROOT, HERE]

import car  # noqa: E402  (benchmarks/car.py, beside this script)
import native_run  # noqa: E402
from measure import command_line, compiled_env, process_cpu, tree_at  # noqa: E402
import pile  # noqa: E402
import run_overhead  # noqa: E402
from x3d_core.traces.trace import read_view  # noqa: E402

DT, FRAME_RATE = 1 / 240, 60
TARGET = 1.15
SAME = 1e-6  # m: the chain's and the car's positions on the two sides
# pile.py's HEIGHT_SAME is for its 200 bodies: one body landing elsewhere moves the mean of 100 twice as far
PILE_HEIGHT_SAME = 2 * pile.HEIGHT_SAME
# s: the longest run of a case whose engine is slow alike on both sides: DART's Dantzig solver on the
# settled pile (its 2 s take ~20 s a side, measured), Drake's SAP on 100 compliant boxes (2 s: 24 s)
CAPPED = {("pile", "dart"): 1.0, ("pile", "drake"): 1.0}


def scene_files(folder: str) -> dict[str, str]:
    """The three scenes written into folder, as native_run.py builds them."""
    native_run.sized()
    paths = {}
    for name, text in (("chain", run_overhead.chain_x3d()), ("car", car.car_x3d()), ("pile", pile.pile_x3d(False))):
        paths[name] = os.path.join(folder, f"{name}.x3d")
        with open(paths[name], "w", encoding="utf-8") as f:
            f.write(text)
    return paths


def agreement(scene: str, trace: str, native: str) -> tuple[float, bool, str]:
    """The largest position difference that the scene's check compares, whether it passes, and what was compared."""
    view, theirs = read_view(trace), np.load(native)
    names = sorted(view.bodies(), key=lambda n: (len(n), n)) if scene != "car" else ["Chassis", "W0", "W1", "W2", "W3"]
    names = [n for n in names if n != "Base"]
    ours = np.stack([view.series(n, "position")[1] for n in names], axis=1)[1:]  # frames after t = 0
    if scene == "chain":
        gap = float(np.abs(ours[-1] - theirs).max())
        return gap, gap <= SAME, "last frame"
    if scene == "car":
        gap = float(np.abs(ours - theirs).max())
        return gap, gap <= SAME, "every frame"
    check = round(pile.CHECK_T * FRAME_RATE) - 1
    early = float(np.abs(ours[check] - theirs[check]).max())
    height = float(ours[-1, :, 1].mean() - theirs[-1, :, 1].mean())
    ok = early <= pile.AGREE and abs(height) <= PILE_HEIGHT_SAME
    return early, ok, f"at {pile.CHECK_T:g} s; mean height {height:+.1e} m at the end"


def _load(averages: tuple[float, float, float]) -> str:
    return " ".join(f"{x:.2f}" for x in averages)


def _ratio(ours: float, native: float) -> str:
    return f"{ours / native:.3f}x" + ("" if ours / native <= TARGET else f" (over {TARGET}x)")


def _commands(scene: str, backend: str, path: str, duration: float, out: str,
              before: str | None, size: int | None = None) -> list[tuple[list[str], str, str]]:
    """Each side's command of one case, the folder it runs in and the timing JSON it writes: the native
    script (OUT.npy, OUT-native.json; size: native_run.py's SIZE), `x3drbp run` (OUT.npz, OUT.json)
    and, with before (a tree of an earlier revision), that revision's (OUT-before.npz, OUT-before.json)."""
    run = ["run", path, "--backend", backend, "--dt", repr(DT), "--duration", repr(duration), "--trace"]
    sized = [] if size is None else [str(size)]
    sides = [([sys.executable, os.path.join(HERE, "native_run.py"), backend, scene, repr(duration), out + ".npy",
               out + "-native.json", *sized], ROOT, out + "-native.json"),
             ([os.path.join(os.path.dirname(sys.executable), "x3drbp"), *run, out + ".npz", "--timing",
               out + ".json"], ROOT, out + ".json")]
    if before:
        sides.append(([*command_line(before), *run, out + "-before.npz", "--timing",
                       out + "-before.json"], before, out + "-before.json"))
    return sides


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=2.0)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--backends", default="mujoco,bullet,dart,ode,physx,drake")
    ap.add_argument("--scenes", default="chain,car,pile")
    ap.add_argument("--against", metavar="REV", help="also time `x3drbp run` of this revision (git archive), "
                    "as a third side taking turns with the others")
    args = ap.parse_args(argv)
    cases, missing = [], []
    for scene in args.scenes.split(","):
        for backend in args.backends.split(","):
            (cases if scene in native_run.SCENES.get(backend, ()) else missing).append((scene, backend))
    load_before = os.getloadavg()
    with tempfile.TemporaryDirectory(prefix="x3drbp-engine-speed-") as tmp:
        env = compiled_env(tmp, MUJOCO_GL=os.environ.get("MUJOCO_GL", "disable"))  # what x3drbp sets for itself
        before = tree_at(args.against, ROOT, tmp) if args.against else None
        paths = scene_files(tmp)
        commands = {}
        for scene, backend in cases:
            duration = min(args.duration, CAPPED.get((scene, backend), args.duration))
            out = os.path.join(tmp, f"{scene}-{backend}")
            commands[scene, backend] = (_commands(scene, backend, paths[scene], duration, out, before), duration, out)
            for cmd, cwd, _ in _commands(scene, backend, paths[scene], 1 / FRAME_RATE, out, before):
                process_cpu(cmd, cwd=cwd, env=env)  # the bytecode cache filled
        # per case, per side (native, x3drbp, x3drbp before): per round (process CPU, simulation CPU, steps CPU)
        times = {case: [[] for _ in sides] for case, (sides, _, _) in commands.items()}
        for _ in range(args.repeat):
            for case, (sides, _, _) in commands.items():
                for k, (cmd, cwd, timing) in enumerate(sides):
                    cpu = process_cpu(cmd, cwd=cwd, env=env)
                    with open(timing, encoding="utf-8") as f:
                        own = json.load(f)
                    times[case][k].append((cpu, own["simulation_cpu_s"], own.get("step_cpu_s", 0.0)))
        checks = {case: agreement(case[0], out + ".npz", out + ".npy") for case, (_, _, out) in commands.items()}
    load_after = os.getloadavg()
    print(f"dt 1/240 s, frames at {FRAME_RATE}/s; whole processes taking turns, median of {args.repeat}; "
          f"{os.cpu_count()} CPUs, load average (1, 5, 15 min) {_load(load_before)} before, {_load(load_after)} "
          "after\n")
    earlier = (f" | process CPU s x3drbp at {args.against} | ratio | simulation CPU s x3drbp at {args.against} | ratio"
               if args.against else "")
    print("| scene | backend | simulated s | process CPU s native / x3drbp | ratio | simulation CPU s native / x3drbp "
          f"| ratio | start-up added ms | x3drbp steps CPU s | max position difference{earlier} |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---|" + ("---:|---:|---:|---:|" if args.against else ""))
    failed = False
    for case, sides in times.items():
        (n_cpu, n_sim, _), (o_cpu, o_sim, o_steps), *rest = ([statistics.median(t[k] for t in side)
                                                              for k in (0, 1, 2)] for side in sides)
        gap, ok, what = checks[case]
        failed |= not ok
        then = "".join(f" | {b_cpu:.3f} | {_ratio(b_cpu, n_cpu)} | {b_sim:.3f} | {_ratio(b_sim, n_sim)}"
                       for b_cpu, b_sim, _ in rest)
        print(f"| {case[0]} | {case[1]} | {commands[case][1]:g} | {n_cpu:.3f} / {o_cpu:.3f} | {_ratio(o_cpu, n_cpu)} | "
              f"{n_sim:.3f} / {o_sim:.3f} | {_ratio(o_sim, n_sim)} | {1e3 * ((o_cpu - o_sim) - (n_cpu - n_sim)):.0f} | "
              f"{o_steps:.3f} | "
              f"{gap:.1e} m ({what}){'' if ok else ' NOT THE SAME'}{then} |")
    for scene, backend in missing:
        print(f"| {scene} | {backend} | no native build written | | | | | | | |" + (" | | | |" if args.against else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

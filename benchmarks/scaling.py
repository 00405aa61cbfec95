"""Benchmark: how x3drbp's cost grows with the scene, `x3drbp run` against the native script per engine.

Two scenes at three sizes each: engine_speed.py's hinge chain (run_overhead.py's) at 10, 50
and 100 links, and its pit of boxes (pile.py's, no spheres) at 10, 100 and 1,000 boxes, the
boxes filling pile.py's 5 x 5 grid layer by layer (1,000 boxes: a column 40 layers high whose
lowest layers reach the floor at 0.54 s). Each case is engine_speed.py's pair of whole
processes taking turns, --repeat rounds: `x3drbp run SCENE --backend B --timing` and
benchmarks/native_run.py with the size, which builds the same model in the engine's own API,
steps it and reads every body's pose and velocity at every frame (dt 1/240 s, a frame every
1/60 s), importing no x3drbp code. pymunk (planar) runs the chain only, against
native_pymunk.py: the pile's boxes are turned out of the plane.

The measure is the simulation's CPU time per step, each process timing its own: x3drbp's
`--timing` simulation_cpu_s (the engine build, the steps, and every frame's state read, check
and recording into the trace) and the native script's build, steps and reads, each over the
run's steps; medians of the rounds. The ratio is the median of each round's, x3drbp's over the
native run just before it (a load shifts a pair alike more than it does rounds apart), beside
the rounds' least and greatest; TARGET, 1.05x at AT, 1,000 bodies. "engine steps" is x3drbp's
step_cpu_s, the engine's own share. Peak memory is each process's ru_maxrss
(measure.process_usage), median of the rounds. The traces are
checked to agree as engine_speed.py checks them (exit status 1 where one does not).

Durations shrink with size (DURATION), and further on the engines slow alike on both sides
(CAPPED); a duration covers at least the pile's check at pile.CHECK_T. Both sides run with
Python's bytecode cache, one OpenBLAS thread (measure.compiled_env) and glibc's heap padded
(TOP_PAD).

    python benchmarks/scaling.py [--repeat 5] [--backends mujoco,bullet,dart,ode,physx,drake,pymunk]
                                 [--scenes chain,pile]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [os.path.dirname(HERE), HERE]

import engine_speed  # noqa: E402  (benchmarks/engine_speed.py, beside this script)
import native_run  # noqa: E402
import pile  # noqa: E402
import run_overhead  # noqa: E402
from measure import compiled_env, process_usage  # noqa: E402

TARGET = 1.05
SIZES = {"chain": (10, 50, 100), "pile": (10, 100, 1000)}
# s simulated per case: fewer steps as the scene grows, at least the pile's check (pile.CHECK_T)
DURATION = {("chain", 10): 2.0, ("chain", 50): 1.0, ("chain", 100): 1.0,
            ("pile", 10): 2.0, ("pile", 100): 1.0, ("pile", 1000): 1.0}
# s: the longest run of a case whose engine is slow alike on both sides
CAPPED = {("dart", "pile", 100): 0.6, ("dart", "pile", 1000): 0.6,
          ("drake", "pile", 100): 0.6, ("drake", "pile", 1000): 0.5}
AT = 1000  # bodies: the size the target is set at
# bytes: glibc's heap grown (and trimmed) this far beyond what it needs, on both sides. By default it
# grows in 128 kB steps and gives memory back as soon as it can, and an engine that allocates and frees
# much in every step then faults its pages in again and again: measured, the native Drake pile of 100
# boxes took 104,000 page faults and 0.3 s of system time where `x3drbp run`, its heap already grown by
# the scene's load, took 25,000 (simulation 0.75 s against 0.41); with 64 MB each side takes about 17,000
# (the native simulation 0.38-0.41 s, x3drbp's 0.43). An artefact of the allocator's state, not of either
# side's work.
TOP_PAD = 64 * 2 ** 20


def scene_file(folder: str, scene: str, size: int) -> str:
    """The scene at this size, as native_run.py builds it with SIZE."""
    native_run.sized(**{"links" if scene == "chain" else "boxes": size})
    path = os.path.join(folder, f"{scene}-{size}.x3d")
    with open(path, "w", encoding="utf-8") as f:
        f.write(run_overhead.chain_x3d() if scene == "chain" else pile.pile_x3d(False))
    return path


def _per_step(cpu: float, duration: float) -> str:
    """CPU seconds over the run's steps, in microseconds."""
    return f"{1e6 * cpu / round(duration / engine_speed.DT):,.0f}"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--backends", default="mujoco,bullet,dart,ode,physx,drake,pymunk")
    ap.add_argument("--scenes", default="chain,pile")
    args = ap.parse_args(argv)
    scenes = args.scenes.split(",")
    failed = False
    print("| backend | scene | bodies | simulated s | simulation CPU us/step native / x3drbp | ratio | rounds' ratios "
          "| x3drbp engine steps us/step | peak RSS MB native / x3drbp | max position difference "
          "| load before / after |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---|---|")
    with tempfile.TemporaryDirectory(prefix="x3drbp-scaling-") as tmp:
        env = compiled_env(tmp, MUJOCO_GL=os.environ.get("MUJOCO_GL", "disable"), MALLOC_TOP_PAD_=str(TOP_PAD))
        paths = {(scene, n): scene_file(tmp, scene, n) for scene in scenes for n in SIZES[scene]}
        for backend in args.backends.split(","):
            cases = {}
            for scene in scenes:
                if scene not in native_run.SCENES.get(backend, ()):
                    print(f"| {backend} | {scene} | | | no native build: {backend} is planar, the {scene} is not "
                          "| | | | | | |", flush=True)
                    continue
                for n in SIZES[scene]:
                    duration = min(DURATION[scene, n], CAPPED.get((backend, scene, n), DURATION[scene, n]))
                    out = os.path.join(tmp, f"{backend}-{scene}-{n}")
                    cases[scene, n] = (engine_speed._commands(scene, backend, paths[scene, n], duration, out, None,
                                                              n), duration, out)
                first = engine_speed._commands(scene, backend, paths[scene, SIZES[scene][0]],
                                               1 / engine_speed.FRAME_RATE, os.path.join(tmp, "warm"), None,
                                               SIZES[scene][0])
                for cmd, cwd, _ in first:
                    process_usage(cmd, cwd=cwd, env=env)  # the bytecode cache filled, untimed
            load_before = os.getloadavg()[0]
            # per case, per side (native, x3drbp): per round (simulation CPU, steps CPU, peak RSS MB)
            rounds = {case: ([], []) for case in cases}
            for _ in range(args.repeat):
                for case, (sides, _, _) in cases.items():
                    for k, (cmd, cwd, timing) in enumerate(sides):
                        _, rss = process_usage(cmd, cwd=cwd, env=env)
                        with open(timing, encoding="utf-8") as f:
                            own = json.load(f)
                        rounds[case][k].append((own["simulation_cpu_s"], own.get("step_cpu_s", 0.0), rss))
            load = f"{load_before:.2f} / {os.getloadavg()[0]:.2f}"
            for (scene, n), (_, duration, out) in cases.items():
                (n_sim, _, n_rss), (o_sim, o_steps, o_rss) = ([statistics.median(r[k] for r in side) for k in range(3)]
                                                              for side in rounds[scene, n])
                gap, ok, what = engine_speed.agreement(scene, out + ".npz", out + ".npy")
                failed |= not ok
                ratios = [ours[0] / theirs[0] for theirs, ours in zip(*rounds[scene, n])]  # each round's pair
                ratio = statistics.median(ratios)
                over = f" (over {TARGET}x)" if ratio > TARGET and n == AT else ""
                print(f"| {backend} | {scene} | {n:,} | {duration:g} | {_per_step(n_sim, duration)} / "
                      f"{_per_step(o_sim, duration)} | {ratio:.3f}x{over} | {min(ratios):.2f}-{max(ratios):.2f} | "
                      f"{_per_step(o_steps, duration)} | "
                      f"{n_rss:.0f} / {o_rss:.0f} | {gap:.1e} m ({what}){'' if ok else ' NOT THE SAME'} | {load} |",
                      flush=True)
    print(f"\n{os.cpu_count()} CPUs; CPU time (user + system) of each process's simulation, median of {args.repeat} "
          "rounds taking turns, the ratio the median of each round's (x3drbp's over the native run just before it); "
          "peak RSS: ru_maxrss of each whole process, median")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

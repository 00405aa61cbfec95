"""Benchmark: what one `x3drbp run` process costs before it simulates anything.

Every other command (conformance, compare, stability, sweep, advise) starts `x3drbp run`
children by the hundred, so their start-up is most of the main job's time. Timed, as whole
processes from start to exit, taking turns so that load shifts all alike, each as wall time
and as the process's CPU time (the kernel's count: a load beside it barely moves it): the
interpreter alone (`python -c pass`), numpy and lxml (what any run needs), and `x3drbp run`
of the bundled pendulum for one 1/240 s step on each installed backend (imports, the
backend's judgement, the engine build, one step, the trace written); with --against REV,
the same run from REV's tree (`git archive`) beside it, for a before and after in one run;
and the same run as a command hands it to children.run_child, forked by the warm fork
server (its engine imported by a first run), the way every command but `run` itself starts
its runs. Every process runs with Python's bytecode cache (measure.compiled_env, filled by a
first untimed run of each); --no-cache times them as PYTHONDONTWRITEBYTECODE has them,
compiling every module of the project from source each time. Printed: the median and spread
of each over --repeat runs, and what x3drbp adds over numpy and lxml.

    python benchmarks/run_startup.py [--repeat 7] [--backends mujoco,bullet,dart,ode,pymunk]
                                     [--against REV] [--no-cache]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, ROOT)

from conformance.results import Settings  # noqa: E402
from conformance.runner import children, fork_server  # noqa: E402

from measure import command_line, compiled_env, process_cpu, tree_at  # noqa: E402  (benchmarks/measure.py, beside this script)

SCENE = os.path.join("scenes", "examples", "pendulum.x3d")


def _warm(backend: str, trace: str) -> float:
    started = time.perf_counter()
    out = children.run_child(os.path.join(ROOT, SCENE), backend, Settings(1 / 240, 1 / 240), trace)
    if out.verdict is not None:
        raise SystemExit(f"the warm run on {backend} failed: {out.verdict}: {out.reason}")
    return time.perf_counter() - started


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--backends", default="mujoco,bullet,dart,ode,pymunk")
    ap.add_argument("--against", metavar="REV", help="also time `x3drbp run` from this revision's tree")
    ap.add_argument("--no-cache", action="store_true", help="no bytecode cache: every process compiles from source")
    args = ap.parse_args()
    backends = args.backends.split(",")
    load_before = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1") if args.no_cache else compiled_env(tmp)
        trace = os.path.join(tmp, "t.csv")
        trees = {"": ROOT} | ({f" at {args.against}": tree_at(args.against, ROOT, tmp)} if args.against else {})
        commands = {"python -c pass": ([sys.executable, "-c", "pass"], ROOT),
                    "import numpy, lxml": ([sys.executable, "-c", "import numpy, lxml.etree"], ROOT)}
        for b in backends:
            for label, tree in trees.items():
                commands[f"x3drbp run ({b}){label}"] = ([*command_line(tree), "run", SCENE,
                                                         "--backend", b, "--duration", repr(1 / 240), "--trace",
                                                         trace, "-q"], tree)
        for cmd, cwd in commands.values():  # the bytecode cache filled
            process_cpu(cmd, cwd=cwd, env=env)
        times: dict[str, list[tuple[float, float]]] = {name: [] for name in commands}
        warm = {f"forked warm ({b})": b for b in backends} if fork_server.usable() else {}
        for b in warm.values():
            _warm(b, trace)  # the server started, the engine imported in it
        times.update({name: [] for name in warm})
        for _ in range(args.repeat):  # taking turns
            for name, (cmd, cwd) in commands.items():
                started = time.perf_counter()
                cpu = process_cpu(cmd, cwd=cwd, env=env)
                times[name].append((time.perf_counter() - started, cpu))
            for name, b in warm.items():
                times[name].append((_warm(b, trace), float("nan")))
    floor = [statistics.median(t[k] for t in times["import numpy, lxml"]) for k in (0, 1)]
    load = " ".join(f"{x:.2f}" for x in load_before)
    print(f"{args.repeat} runs each, taking turns; {os.cpu_count()} CPUs, load average (1, 5, 15 min) {load} before, "
          f"{' '.join(f'{x:.2f}' for x in os.getloadavg())} after; "
          f"{'no bytecode cache' if args.no_cache else 'bytecode cached'}\n")
    print("| process | wall median s | wall spread s | CPU median s | CPU spread s | CPU over numpy and lxml s |\n"
          "|---|---:|---|---:|---|---:|")
    for name, ts in times.items():
        wall, cpu = [statistics.median(t[k] for t in ts) for k in (0, 1)]
        cpus = [t[1] for t in ts]
        cpu_text = "" if cpu != cpu else f"{cpu:.3f} | {min(cpus):.3f}-{max(cpus):.3f} | {cpu - floor[1]:+.3f}"
        print(f"| {name} | {wall:.3f} | {min(t[0] for t in ts):.3f}-{max(t[0] for t in ts):.3f} | "
              f"{cpu_text or ' | | '} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())

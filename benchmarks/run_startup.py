"""Benchmark: what one `x3drbp run` process costs before it simulates anything.

Every other command (conformance, compare, stability, sweep, advise) starts `x3drbp run`
children by the hundred, so their start-up is most of the main job's time. Timed, as whole
processes from start to exit, taking turns so that load shifts all alike: the interpreter
alone (`python -c pass`), numpy and lxml (what any run needs), and `x3drbp run` of the
bundled pendulum for one 1/240 s step on each installed backend (imports, the backend's
judgement, the engine build, one step, the trace written); and the same run as a command
hands it to children.run_child, forked by the warm fork server (its engine imported by a
first run), the way every command but `run` itself now starts its runs. Printed: the median
and spread of each over --repeat runs, and what x3drbp adds over numpy and lxml.

    python benchmarks/run_startup.py [--repeat 7] [--backends mujoco,bullet,dart,ode,pymunk]
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

from measure import process_wall  # noqa: E402  (benchmarks/measure.py, beside this script)

SCENE = os.path.join(ROOT, "scenes", "examples", "pendulum.x3d")


def _warm(backend: str, trace: str) -> float:
    started = time.perf_counter()
    out = children.run_child(SCENE, backend, Settings(1 / 240, 1 / 240), trace)
    if out.verdict is not None:
        raise SystemExit(f"the warm run on {backend} failed: {out.verdict}: {out.reason}")
    return time.perf_counter() - started


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--backends", default="mujoco,bullet,dart,ode,pymunk")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        trace = os.path.join(tmp, "t.csv")
        commands = {"python -c pass": [sys.executable, "-c", "pass"],
                    "import numpy, lxml": [sys.executable, "-c", "import numpy, lxml.etree"]}
        for b in args.backends.split(","):
            commands[f"x3drbp run ({b})"] = [sys.executable, "-m", "conformance.cli", "run", SCENE, "--backend", b,
                                             "--duration", repr(1 / 240), "--trace", trace, "-q"]
        times: dict[str, list[float]] = {name: [] for name in commands}
        warm = {f"forked warm ({b})": b for b in args.backends.split(",")} if fork_server.usable() else {}
        for b in warm.values():
            _warm(b, trace)  # the server started, the engine imported in it
        times.update({name: [] for name in warm})
        for _ in range(args.repeat):  # taking turns
            for name, cmd in commands.items():
                times[name].append(process_wall(cmd, cwd=ROOT))
            for name, b in warm.items():
                times[name].append(_warm(b, trace))
    floor = statistics.median(times["import numpy, lxml"])
    print(f"{args.repeat} runs each, taking turns; {os.cpu_count()} CPUs, load average "
          f"{', '.join(f'{x:.2f}' for x in os.getloadavg())}\n")
    print("| process | median s | spread s | over numpy and lxml s |\n|---|---:|---|---:|")
    for name, ts in times.items():
        m = statistics.median(ts)
        print(f"| {name} | {m:.3f} | {min(ts):.3f}-{max(ts):.3f} | {m - floor:+.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())

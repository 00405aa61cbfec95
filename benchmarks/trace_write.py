"""Benchmark: writing a run's trace and reading it back, CSV and .npz, this tree against an
earlier commit, side by side in one run.

Two scenes from run_overhead.py, run on MuJoCo at dt = 1/240 s with a frame every 1/60 s:
the 10-link chain for 5 s (12k rows) and the 100 free boxes for 10 s (240k rows). Each
side (the earlier commit cloned into a temporary folder, and this tree) runs each scene
once in a fresh interpreter and times, best of --repeat: Trace.write of the CSV, read_view
of it, and, where the tree has x3d_core's trace_npz, write_npz of Trace.view() and
read_view of the .npz. The last column checks that the .npz reads as the CSV does.

    python benchmarks/trace_write.py [--before ba3d4dd] [--repeat 5]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import run_overhead  # noqa: E402  (beside this script: the scenes)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BEFORE = "ba3d4dd"  # main before this round: the CSV writer formatting each number alone, no .npz

# run in the tree measured (cwd and PYTHONPATH): argv = scene, folder, repeat
MEASURE = r"""
import importlib.util, json, os, sys, time, warnings
import numpy as np
# x3d_core's flat paths: a tree from before its wings has only those, and a later tree still
# imports them (x3d_core/__init__.py), with the DeprecationWarning silenced here
warnings.simplefilter("ignore", DeprecationWarning)
from backends import base
from x3d_core.load import load
from x3d_core.evaluator import RunSettings, run
from x3d_core.world import worlds
from x3d_core.trace import read_view
scene, folder, repeat = sys.argv[1], sys.argv[2], int(sys.argv[3])
trace = run(worlds(load(scene)), base.load("mujoco"), RunSettings(duration=float(sys.argv[4]), dt=1 / 240,
                                                                  frame_rate=60))


def best(fn):
    times = []
    for _ in range(repeat):
        started = time.perf_counter()
        fn()
        times.append(time.perf_counter() - started)
    return min(times)


csv, npz = os.path.join(folder, "t.csv"), os.path.join(folder, "t.npz")
out = {"rows": sum(1 for _ in trace.events()), "csv_write": best(lambda: trace.write(csv)),
       "csv_read": best(lambda: read_view(csv))}
if importlib.util.find_spec("x3d_core.trace_npz") is not None:  # this tree's own
    from x3d_core.trace_npz import write_npz
    out["npz_write"] = best(lambda: write_npz(trace.view(), npz))
    out["npz_read"] = best(lambda: read_view(npz))
    a, b = read_view(csv), read_view(npz)
    out["same"] = a.keys() == b.keys() and all(
        np.array_equal(a.series(*k)[1], b.series(*k)[1]) and np.array_equal(a.series(*k)[0], b.series(*k)[0])
        for k in a.keys())
print("x3drbp-answer " + json.dumps(out))
"""


def _measure(tree: str, scene: str, duration: float, repeat: int, folder: str) -> dict:
    done = subprocess.run([sys.executable, "-c", MEASURE, scene, folder, str(repeat), repr(duration)], cwd=tree,
                          env=dict(os.environ, PYTHONPATH=tree), capture_output=True, text=True, check=True)
    line = next(ln for ln in done.stdout.splitlines() if ln.startswith("x3drbp-answer "))
    return json.loads(line[len("x3drbp-answer "):])


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", default=BEFORE, help=f"the earlier commit (default {BEFORE})")
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    run_overhead.LINKS = 10
    with tempfile.TemporaryDirectory(prefix="x3drbp-tracebench-") as tmp:
        earlier = os.path.join(tmp, "before")
        subprocess.run(["git", "clone", "-q", ROOT, earlier], check=True)
        subprocess.run(["git", "-C", earlier, "checkout", "-q", args.before], check=True)
        scenes = {"10-link chain, 5 s": (run_overhead.chain_x3d(), 5.0),
                  "100 free boxes, 10 s": (run_overhead.boxes_x3d(), 10.0)}
        print(f"MuJoCo, dt 1/240 s, frames at 60/s; best of {args.repeat} (2 cores, load average "
              f"{os.getloadavg()[0]:.1f})\n")
        print(f"| scene | rows | CSV write, {args.before} | CSV write, now | ratio | .npz write, now | "
              f"ratio to CSV before | CSV read | .npz read | .npz reads as the CSV |")
        print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|")
        for name, (text, duration) in scenes.items():
            scene = os.path.join(tmp, "scene.x3d")
            with open(scene, "w", encoding="utf-8") as f:
                f.write(text)
            before = _measure(earlier, scene, duration, args.repeat, tmp)
            now = _measure(ROOT, scene, duration, args.repeat, tmp)
            print(f"| {name} | {now['rows']:,} | {before['csv_write'] * 1e3:.1f} ms | {now['csv_write'] * 1e3:.1f} ms | "
                  f"{before['csv_write'] / now['csv_write']:.2f}x | {now['npz_write'] * 1e3:.1f} ms | "
                  f"{before['csv_write'] / now['npz_write']:.1f}x | {now['csv_read'] * 1e3:.1f} ms | "
                  f"{now['npz_read'] * 1e3:.2f} ms | {'yes' if now['same'] else 'NO'} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())

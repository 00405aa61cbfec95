"""Benchmark: a whole `x3drbp run` process against a hand-written MuJoCo script doing the same.

The scene is a 10-link hinge chain hanging from a fixed body (run_overhead.py's, shorter),
run for --duration simulated seconds at dt = 1/240 s with a frame every 1/60 s. Both sides
are timed as processes, start-up included, from a cold interpreter to the trace on disk:

- x3drbp: `x3drbp run chain.x3d --backend mujoco --dt 1/240 --duration D --trace T` with T a
  CSV (the contract) and with T an .npz (the binary form, by choice);
- native: benchmarks/native_mujoco_chain.py, the script a MuJoCo user would write: MjSpec
  for the same chain, mj_step, and every frame's position, orientation (axis-angle), linear
  and angular velocity of each link written as the same CSV rows x3drbp writes.

The runs alternate (native, CSV, npz) --repeat times; the table gives each side's median and
its ratio to the native script. The last column checks that both sides computed the same
motion and wrote the same trace: the largest difference between the two traces' values
(m, rad, m/s, rad/s), every link, output and frame, which must be within SAME (exit 1 if not).

    python benchmarks/run_process.py [--duration 5] [--repeat 7]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import run_overhead  # noqa: E402  (benchmarks/run_overhead.py, beside this script: the chain's scene)
from measure import process_wall  # noqa: E402  (benchmarks/measure.py)
from x3d_core.traces.trace import read_view  # noqa: E402

LINKS = 10
SAME = 1e-9  # the two sides' values agree to rounding where they step the same model

def _gap(path: str, native: str) -> float:
    """The largest difference between two traces' values, over every link, field and frame."""
    a, b = read_view(path), read_view(native)
    return max(float(np.abs(a.series(f"L{k}", f)[1] - b.series(f"L{k}", f)[1]).max())
               for k in range(LINKS) for f in ("position", "orientation", "linearVelocity", "angularVelocity"))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=5.0)
    ap.add_argument("--repeat", type=int, default=7)
    args = ap.parse_args()
    run_overhead.LINKS = LINKS
    x3drbp = os.path.join(os.path.dirname(sys.executable), "x3drbp")
    env = dict(os.environ, MUJOCO_GL=os.environ.get("MUJOCO_GL", "disable"))  # what x3drbp sets for itself
    with tempfile.TemporaryDirectory(prefix="x3drbp-bench-") as tmp:
        scene = os.path.join(tmp, "chain.x3d")
        with open(scene, "w", encoding="utf-8") as f:
            f.write(run_overhead.chain_x3d())
        script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "native_mujoco_chain.py")
        out = {name: os.path.join(tmp, name) for name in ("native.csv", "x3drbp.csv", "x3drbp.npz")}
        sides = {
            "native MuJoCo script": [sys.executable, script, out["native.csv"], repr(args.duration), str(LINKS)],
            "x3drbp run, --trace .csv": [x3drbp, "run", scene, "--backend", "mujoco", "--dt", repr(1 / 240),
                                         "--duration", repr(args.duration), "--trace", out["x3drbp.csv"]],
            "x3drbp run, --trace .npz": [x3drbp, "run", scene, "--backend", "mujoco", "--dt", repr(1 / 240),
                                         "--duration", repr(args.duration), "--trace", out["x3drbp.npz"]],
        }
        times: dict[str, list[float]] = {name: [] for name in sides}
        for _ in range(args.repeat):
            for name, cmd in sides.items():
                times[name].append(process_wall(cmd, env=env))
        gaps = {name: _gap(out[file], out["native.csv"]) for name, file in
                zip(sides, ("native.csv", "x3drbp.csv", "x3drbp.npz"))}
    base = statistics.median(times["native MuJoCo script"])
    print(f"{LINKS}-link chain, {args.duration:g} s at 1/240 s, frames at 60/s; whole processes, "
          f"median of {args.repeat} (2 cores, load average {os.getloadavg()[0]:.1f})\n")
    print("| side | median | range | ratio to native | largest difference from native |")
    print("|---|---:|---:|---:|---:|")
    for name, ts in times.items():
        print(f"| {name} | {statistics.median(ts):.3f} s | {min(ts):.3f}–{max(ts):.3f} s | "
              f"{statistics.median(ts) / base:.2f}x | {gaps[name]:.1e} |")
    return 0 if max(gaps.values()) <= SAME else 1


if __name__ == "__main__":
    sys.exit(main())

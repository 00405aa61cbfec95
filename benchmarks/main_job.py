"""Benchmark: the main job (`make report`'s two commands) of an earlier commit and of this tree,
side by side on the same machine, the same content.

The earlier commit is cloned into a temporary folder and run with this tree's virtual
environment from there (its own packages come first on sys.path; every child it starts runs
in its own root). Each side runs `x3drbp check -q conformance/cases scenes` then `x3drbp
report --out TMP`; the sides alternate --repeat times, the earlier first. The table gives each
step's time (report.json's timings_s), the whole job's wall time, and the conformance step's
wall time per (case, backend) pair: the step's time over its pairs, and the median of the
pairs' own wall_s (matrix.json).

    python benchmarks/main_job.py [--before ba3d4dd] [--repeat 1]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BEFORE = "ba3d4dd"  # main before the fork server and the binary traces


def _job(root: str, out: str) -> dict:
    """The main job run from root into out: {"wall": s, "steps": {...}, "pairs": n, "pair_s": [...]}."""
    started = time.perf_counter()
    for argv in (["check", "-q", "conformance/cases", "scenes"], ["report", "-q", "--out", out]):
        subprocess.run([sys.executable, "-m", "conformance.cli", *argv], cwd=root, check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - started
    with open(os.path.join(out, "report.json"), encoding="utf-8") as f:
        steps = json.load(f)["timings_s"]
    with open(os.path.join(out, "conformance", "matrix.json"), encoding="utf-8") as f:
        matrix = json.load(f)
    results = matrix["results"] if isinstance(matrix, dict) else matrix
    return {"wall": wall, "steps": steps, "pair_s": [r["wall_s"] for r in results if r.get("wall_s") is not None]}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", default=BEFORE, help=f"the earlier commit (default {BEFORE})")
    ap.add_argument("--repeat", type=int, default=1)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="x3drbp-mainjob-") as tmp:
        earlier = os.path.join(tmp, "before")
        subprocess.run(["git", "clone", "-q", ROOT, earlier], check=True)
        subprocess.run(["git", "-C", earlier, "checkout", "-q", args.before], check=True)
        sides = {f"before ({args.before})": earlier, "now": ROOT}
        runs: dict[str, list[dict]] = {name: [] for name in sides}
        for k in range(args.repeat):
            for name, root in sides.items():
                runs[name].append(_job(root, os.path.join(tmp, f"{len(runs[name])}-{name.split()[0]}")))
                print(f"{name}: {runs[name][-1]['wall']:.0f} s", file=sys.stderr)
    names = list(sides)
    steps = list(dict.fromkeys(s for rs in runs.values() for r in rs for s in r["steps"]))

    def med(name: str, get) -> float:
        return statistics.median(get(r) for r in runs[name])

    print(f"the main job, median of {args.repeat} (2 cores: {os.cpu_count()} CPUs, load average "
          f"{os.getloadavg()[0]:.1f})\n")
    print(f"| | {' | '.join(names)} | ratio |")
    print("|---|" + "---:|" * (len(names) + 1))
    rows = [("whole job (check + report)", lambda r: r["wall"])]
    rows += [(f"report step {s}", lambda r, s=s: r["steps"].get(s, float("nan"))) for s in steps]
    rows += [("conformance step per pair", lambda r: r["steps"].get("conformance", float("nan")) / len(r["pair_s"])),
             ("conformance pair's own wall (median)", lambda r: statistics.median(r["pair_s"]))]
    for label, get in rows:
        a, b = med(names[0], get), med(names[1], get)
        print(f"| {label} | {a:.2f} s | {b:.2f} s | {a / b:.2f}x |")
    return 0


if __name__ == "__main__":
    sys.exit(main())

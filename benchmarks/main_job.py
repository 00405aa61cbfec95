"""Benchmark: the main job (`make report`'s two commands) of an earlier commit and of this tree,
side by side on the same machine, the same content; or, with --warm, this tree's main job with
an empty run cache (cold) and then again with what that run kept (warm).

The earlier commit is cloned into a temporary folder and run with this tree's virtual
environment from there (its own packages come first on sys.path; every child it starts runs
in its own root). Each side runs `x3drbp check -q conformance/cases scenes` then `x3drbp
report --out TMP`; the sides alternate --repeat times, the earlier (the cold) first. This tree
runs with a run cache of the benchmark's own (conformance/runner/cache.py), emptied before
each run but the warm one, so that no run of the user's own commands is reused. The table
gives each step's time (report.json's timings_s), the whole job's wall time and CPU time (its
processes' and their children's, user and system: what the machine's load inflates far less
than wall time), and the conformance step's wall time per (case, backend) pair: the step's
time over its pairs, and the median of the pairs' own wall_s (matrix.json).

    python benchmarks/main_job.py [--before ba3d4dd | --warm] [--repeat 1]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

from measure import command_line  # noqa: E402  (benchmarks/measure.py, beside this script)
BEFORE = "ba3d4dd"  # main before the fork server and the binary traces


def _cpu() -> float:
    """CPU seconds, user and system, of the children this process has waited for (and of theirs)."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def _job(root: str, out: str, cache: str | None) -> dict:
    """The main job run from root into out, its runs cached in `cache` (None: an earlier tree,
    without a cache): {"wall": s, "cpu": s, "load": (start, end), "steps": {...}, "pair_s": [...]}."""
    env = {**os.environ, **({"X3DRBP_CACHE": cache} if cache else {})}
    started, cpu, load = time.perf_counter(), _cpu(), os.getloadavg()[0]
    for argv in (["check", "-q", "conformance/cases", "scenes"], ["report", "-q", "--out", out]):
        subprocess.run([*command_line(root), *argv], cwd=root, check=True, env=env,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall, cpu = time.perf_counter() - started, _cpu() - cpu
    with open(os.path.join(out, "report.json"), encoding="utf-8") as f:
        steps = json.load(f)["timings_s"]
    with open(os.path.join(out, "conformance", "matrix.json"), encoding="utf-8") as f:
        matrix = json.load(f)
    results = matrix["results"] if isinstance(matrix, dict) else matrix
    return {"wall": wall, "cpu": cpu, "load": (load, os.getloadavg()[0]), "steps": steps,
            "pair_s": [r["wall_s"] for r in results if r.get("wall_s") is not None]}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", default=BEFORE, help=f"the earlier commit (default {BEFORE})")
    ap.add_argument("--warm", action="store_true", help="this tree with an empty run cache against the same "
                    "with what that run kept, instead of an earlier commit against this tree")
    ap.add_argument("--repeat", type=int, default=1)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="x3drbp-mainjob-") as tmp:
        cache = os.path.join(tmp, "cache")
        if args.warm:
            sides = {"cold": ROOT, "warm": ROOT}
        else:
            earlier = os.path.join(tmp, "before")
            subprocess.run(["git", "clone", "-q", ROOT, earlier], check=True)
            subprocess.run(["git", "-C", earlier, "checkout", "-q", args.before], check=True)
            sides = {f"before ({args.before})": earlier, "now": ROOT}
        runs: dict[str, list[dict]] = {name: [] for name in sides}
        for k in range(args.repeat):
            for name, root in sides.items():
                if name != "warm":
                    shutil.rmtree(cache, ignore_errors=True)
                out = os.path.join(tmp, f"{len(runs[name])}-{name.split()[0]}")
                runs[name].append(r := _job(root, out, cache if root == ROOT else None))
                print(f"{name}: {r['wall']:.0f} s wall, {r['cpu']:.0f} s CPU, load average {r['load'][0]:.1f} "
                      f"to {r['load'][1]:.1f}", file=sys.stderr)
    names = list(sides)
    steps = list(dict.fromkeys(s for rs in runs.values() for r in rs for s in r["steps"]))

    def med(name: str, get) -> float:
        return statistics.median(get(r) for r in runs[name])

    print(f"the main job, median of {args.repeat} ({os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.1f} "
          f"at the end; each side's at its start and end: "
          + "; ".join(f"{n} {r['load'][0]:.1f}-{r['load'][1]:.1f}" for n in names for r in runs[n]) + ")\n")
    print(f"| | {' | '.join(names)} | ratio |")
    print("|---|" + "---:|" * (len(names) + 1))
    rows = [("whole job (check + report), wall", lambda r: r["wall"]), ("whole job, CPU", lambda r: r["cpu"])]
    rows += [(f"report step {s}", lambda r, s=s: r["steps"].get(s, float("nan"))) for s in steps]
    rows += [("conformance step per pair", lambda r: r["steps"].get("conformance", float("nan")) / len(r["pair_s"])),
             ("conformance pair's own wall (median)", lambda r: statistics.median(r["pair_s"]))]
    for label, get in rows:
        a, b = med(names[0], get), med(names[1], get)
        print(f"| {label} | {a:.2f} s | {b:.2f} s | {a / b:.2f}x |")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Check: does this tree give the same results as revision REV? For a change that should change no
result (a restructuring, a speed-up): the conformance suite's traces, its matrix and the pins,
from both trees in one run.

Each side, this tree and REV's (its files from git archive), runs with the run cache off:
- `x3drbp conformance --keep-traces --out SIDE/conformance`: every case on every backend, its
  traces and matrix.json;
- `x3drbp expectations --pins SIDE/pins --matrix SIDE/conformance-matrix.md`, on copies of the
  tree's own pins (conformance/expectations) and matrix page (docs/conformance-matrix.md): the
  pins as that tree's code writes them.
Then compares them: every trace byte for byte (the same names on both sides), the pins and the
matrix page byte for byte, and matrix.json less what no two runs share (when it was generated,
and each run's wall time). Prints each difference and exits 1 where there is one, else 0.

    python benchmarks/same_results.py --against REV [--backends LIST] [--cases NAMES] [--keep DIR]
"""

from __future__ import annotations

import argparse
import filecmp
import json
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

from measure import command_line, tree_at  # noqa: E402  (benchmarks/measure.py, beside this script)

PINS, PAGE = os.path.join("conformance", "expectations"), os.path.join("docs", "conformance-matrix.md")
RUN_DEPENDENT = ("generated", "wall_s")  # matrix.json's keys that differ between any two runs


def _side(tree: str, out: str, chosen: list[str]) -> None:
    """One tree's results under out (the module docstring)."""
    env = dict(os.environ, X3DRBP_CACHE="off", MUJOCO_GL=os.environ.get("MUJOCO_GL", "disable"))
    shutil.copytree(os.path.join(tree, PINS), os.path.join(out, "pins"),
                    ignore=shutil.ignore_patterns("*.py", "__pycache__"))
    shutil.copy(os.path.join(tree, PAGE), os.path.join(out, "conformance-matrix.md"))
    for argv in (["conformance", "-q", "--keep-traces", "--out", os.path.join(out, "conformance")],
                 ["expectations", "--pins", os.path.join(out, "pins"),
                  "--matrix", os.path.join(out, "conformance-matrix.md")]):
        done = subprocess.run([*command_line(tree), *argv, *chosen], cwd=tree, env=env, capture_output=True,
                              text=True)
        if done.returncode not in (0, 1):  # expectations: 1 where a pin changed, which the comparison shows
            raise SystemExit(f"{' '.join(argv[:1])} in {tree} exited {done.returncode}:\n{done.stderr}")


def _without(data: object) -> object:
    """matrix.json less its run-dependent keys, at any depth."""
    if isinstance(data, dict):
        return {k: _without(v) for k, v in data.items() if k not in RUN_DEPENDENT}
    if isinstance(data, list):
        return [_without(v) for v in data]
    return data


def _files(folder: str) -> set[str]:
    return {os.path.relpath(os.path.join(d, f), folder) for d, _, fs in os.walk(folder) for f in fs}


def differences(a: str, b: str) -> list[str]:
    """What differs between two sides' results folders (this tree's a, REV's b)."""
    out = []
    for sub in ("conformance/traces", "pins"):
        mine, theirs = _files(os.path.join(a, sub)), _files(os.path.join(b, sub))
        out += [f"{sub}/{f}: only in this tree" for f in sorted(mine - theirs)]
        out += [f"{sub}/{f}: only in the other" for f in sorted(theirs - mine)]
        out += [f"{sub}/{f}: differs" for f in sorted(mine & theirs)
                if not filecmp.cmp(os.path.join(a, sub, f), os.path.join(b, sub, f), shallow=False)]
    if not filecmp.cmp(os.path.join(a, "conformance-matrix.md"), os.path.join(b, "conformance-matrix.md"),
                       shallow=False):
        out.append("conformance-matrix.md: differs")
    matrices = []
    for side in (a, b):
        with open(os.path.join(side, "conformance", "matrix.json"), encoding="utf-8") as f:
            matrices.append(_without(json.load(f)))
    if matrices[0] != matrices[1]:
        out.append(f"conformance/matrix.json: differs (beyond {', '.join(RUN_DEPENDENT)})")
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--against", required=True, metavar="REV", help="the revision to compare with")
    ap.add_argument("--backends", metavar="LIST", help="backends, comma-separated (default: every one)")
    ap.add_argument("--cases", metavar="NAMES", help="cases, comma-separated (default: every one)")
    ap.add_argument("--keep", metavar="DIR", help="keep both sides' results in DIR")
    args = ap.parse_args()
    chosen = [*(["--backends", args.backends] if args.backends else []), *(["--cases", args.cases] if args.cases else [])]
    with tempfile.TemporaryDirectory(prefix="x3drbp-same-results-") as tmp:
        here, there = os.path.join(tmp, "this-tree"), os.path.join(tmp, f"at-{args.against}")
        for tree, out in ((ROOT, here), (tree_at(args.against, ROOT, tmp), there)):
            os.makedirs(out)
            _side(tree, out, chosen)
        found = differences(here, there)
        traces = len(_files(os.path.join(here, "conformance", "traces")))
        pins = len(_files(os.path.join(here, "pins")))
        if args.keep:
            shutil.copytree(tmp, os.path.abspath(args.keep), dirs_exist_ok=True,
                            ignore=shutil.ignore_patterns(f"tree-{args.against}"))
    for line in found:
        print(line)
    print(f"{len(found)} differences against {args.against}: {traces} traces, {pins} pin files, the matrix page, "
          f"matrix.json (less {', '.join(RUN_DEPENDENT)})")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())

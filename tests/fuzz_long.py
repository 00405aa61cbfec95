"""The loaders' mutation fuzzing for as long as you like (CI runs 400 inputs of it):

    .venv/bin/python tests/fuzz_long.py --minutes 30 [--out DIR] [--seed N]

Prints each finding (an exception other than LoadError escaping load(), or an input taking
longer than --seconds) with the failing input kept in DIR, and exits 1 if there was any.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
import warnings

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

import fuzzing  # noqa: E402  (tests/ is this script's folder, the project root is put first)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--minutes", type=float, default=30.0)
    p.add_argument("--out", help="where failing inputs are kept (default: a new temporary folder)")
    p.add_argument("--seed", type=int, default=int(time.time()), help="first seed (default: the time)")
    p.add_argument("--seconds", type=float, default=5.0, help="time bound per input (default 5)")
    args = p.parse_args(argv)
    out = args.out or tempfile.mkdtemp(prefix="x3drbp-fuzz-")
    os.makedirs(out, exist_ok=True)
    warnings.simplefilter("ignore")  # numpy's overflow warnings on huge numbers are expected
    until = time.monotonic() + 60 * args.minutes
    total, found, seed = 0, 0, args.seed
    while time.monotonic() < until:
        tried, findings = fuzzing.fuzz(out, seed, count=10_000, until=until, seconds=args.seconds)
        total += tried
        for f in findings:
            print(f"{f.path}: {f.problem}", flush=True)
        found += len(findings)
        seed += 1
    print(f"{total} inputs (seeds {args.seed}..{seed - 1}), {found} finding(s); failing inputs in {out}")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())

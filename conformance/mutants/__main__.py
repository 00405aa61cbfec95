"""`python -m conformance.mutants`: the mutation score of the conformance suite.

    python -m conformance.mutants [--mutants NAMES] [--cases NAMES] [--jobs N] [--timeout S]
                                  [--out DIR] [-q]

Installs every mutant as a plug-in (DIR/site, put first on PYTHONPATH for the runs), runs each
base on every case and each mutant, the identity mutants too, on the cases its base passes,
and writes DIR/score.md (the markdown table docs/mutation-score.md quotes, also printed) and DIR/score.json
(DIR: out/mutants). Exit status 0 whatever the score; 1 where an identity mutant was killed
(the wrapping changed a verdict: the score means nothing); 2 on bad usage.
"""

from __future__ import annotations

import argparse
import os
import sys

from conformance import cases as C
from conformance.runner import children

from conformance.mutants import report, score, site
from conformance.mutants.table import CONTROLS, MUTANTS

from x3drbp import options


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="python -m conformance.mutants", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--mutants", action="append", metavar="NAMES",
                   help="mutants to run, comma-separated (default: all, see conformance/mutants/table.py)")
    p.add_argument("--cases", action="append", metavar="NAMES", help="cases to run, comma-separated (default: all)")
    p.add_argument("--timeout", type=options.positive, default=children.DEFAULT_TIMEOUT, metavar="S",
                   help=f"time limit per run in seconds (default {children.DEFAULT_TIMEOUT:g})")
    p.add_argument("--jobs", type=options.count, default=None, metavar="N",
                   help="runs in parallel (default: the number of CPUs)")
    p.add_argument("--out", default=os.path.join("out", "mutants"), metavar="DIR",
                   help="folder for score.md, score.json and the plug-in's site (default out/mutants)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    return p


@children.interruptible
def main(args: argparse.Namespace) -> int:
    wanted = options.names(args.mutants)
    mutants = [m for m in MUTANTS if not wanted or m.name in wanted]
    unknown = [n for n in wanted if n not in {m.name for m in MUTANTS}]
    problems = [f"unknown mutant(s) {', '.join(unknown)}; known: those of conformance/mutants/table.py"] if unknown else []
    try:
        cases = C.select(options.names(args.cases))
    except KeyError as e:
        problems.append(e.args[0])
    if problems:
        print(f"python -m conformance.mutants: {'; '.join(problems)}", file=sys.stderr)
        return 2
    controls = [m for m in CONTROLS if any(m.base == x.base for x in mutants)]
    os.environ["PYTHONPATH"] = site.on_path(site.install(os.path.abspath(os.path.join(args.out, "site"))))
    measured = score.measure(mutants, controls, cases, args.timeout, args.jobs, options.progress(args))
    names = [c.name for c in cases]
    options.publish(args.out, "score", report.markdown(measured, len(cases)), report.to_json(measured, names))
    return 1 if any(f.killed for f in measured.controls) else 0


if __name__ == "__main__":
    sys.exit(main(parser().parse_args()))

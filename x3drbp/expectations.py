"""`x3drbp expectations`: pin every conformance verdict from a run, or check the pins.

    x3drbp expectations [--backends LIST] [--cases NAMES] [--check] [--pins DIR]
                        [--matrix FILE] [--timeout S] [--jobs N]

Runs the cases on the backends and rewrites conformance/expectations/BACKEND.toml for
each backend that ran (a `why` is kept while its verdict holds; cases not run keep their
pins), then the conformance matrix page (docs/conformance-matrix.md) from every file.
Prints each pin that changed. With --check it writes nothing and exits 1 when any verdict
differs from its pin: what CI of an engine's adapter runs. Exit 2 on bad usage: a --pins DIR that is no folder, a pin file that
does not read (one line, FILE:LINE: why, before any run), a --matrix that is not one (also before any run).
"""

from __future__ import annotations

import argparse
import os
import sys

from backends import base
from reports.expectations_table import markdown, replace_section
from x3d_core.files import atomic
from x3d_core.files.documents import read_text

from conformance import cases as C
from conformance import expectations as E
from conformance.results import PASS, Expected
from conformance.runner import children, verdicts

from x3drbp import options

EXIT_OK, EXIT_CHANGED, EXIT_USAGE = 0, 1, 2
MATRIX = os.path.join(C.ROOT, "docs", "conformance-matrix.md")


def matrix_page(path: str) -> str:
    """The matrix page's text; ValueError naming the file (and line) where it does not read or
    has no markers (read before any run, and again to write it)."""
    text = read_text(path)
    try:
        replace_section(text, "")
    except ValueError as e:
        raise ValueError(f"{path}: {e}") from None
    return text


def write_matrix(path: str) -> None:
    """The matrix page's table from the pinned verdicts of every backend x3drbp ships; ValueError
    naming the file (and line) where the page or a pin file does not read, or the page has no
    markers."""
    text = matrix_page(path)
    new = replace_section(text, markdown([c.name for c in C.CASES], {b: E.load(b) for b in base.IN_TREE}))
    if new != text:
        atomic.write_text(path, new)


@children.interruptible
def cmd_expectations(args: argparse.Namespace) -> int:
    try:
        cases, info, named = options.chosen(args, C.select)
    except ValueError as e:
        print(f"x3drbp expectations: {e}", file=sys.stderr)
        return EXIT_USAGE
    for b in named:
        if not info[b].usable:
            print(f"skipped {b}, its pins kept: unavailable: {info[b].unavailable}")
    backends = [b for b in named if info[b].usable]
    matrix = args.matrix if args.matrix and args.pins is None and not args.check else None
    try:  # before any run: a pin file or a matrix page that is not one is said at once (the page was
        # read after every run, once the pins were rewritten)
        pins = {b: E.load(b, args.pins) for b in backends}
        if matrix:
            try:
                matrix_page(matrix)
            except ValueError as e:
                raise ValueError(f"--matrix {e}") from None
    except ValueError as e:
        print(f"x3drbp expectations: {e}", file=sys.stderr)
        return EXIT_USAGE
    outcomes = verdicts.run_matrix(cases, backends, args.timeout, args.jobs)
    changed = 0
    for b in backends:
        old = pins[b]
        mine = [r for r in outcomes if r.backend == b]
        for r in mine:
            why = E.mismatch(r, old.get(r.case, Expected(PASS)))
            if why:
                changed += 1
                print(f"changed: {why}")
        if args.check:
            continue
        new = {k: v for k, v in old.items() if k not in {r.case for r in mine}} | E.regenerate(mine, old)
        atomic.write_text(E.path(b, args.pins), E.dumps(b, info[b].version or "", new))
    print(f"{changed} verdict(s) differ from their pins on {', '.join(backends) or 'no backend'}")
    if args.check:
        return EXIT_CHANGED if changed else EXIT_OK
    if matrix:  # the matrix page shows x3drbp's own pins
        try:
            write_matrix(matrix)
        except ValueError as e:  # not a regular file, not UTF-8, or without the matrix's markers
            print(f"x3drbp expectations: --matrix {e}", file=sys.stderr)
            return EXIT_USAGE
    return EXIT_OK


def add_command(sub) -> None:
    p = sub.add_parser("expectations", help="pin every conformance verdict per backend from a run (or --check them)",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    options.add_matrix_options(p, "pin", list(C.BY_NAME), children.DEFAULT_TIMEOUT)
    p.add_argument("--check", action="store_true", help="write nothing; exit 1 when a verdict differs from its pin")
    p.add_argument("--pins", metavar="DIR", help="the folder of BACKEND.toml pins (default conformance/expectations): "
                   "an adapter outside x3drbp keeps its own")
    p.add_argument("--matrix", default=MATRIX if os.path.exists(MATRIX) else None, metavar="FILE",
                   help="the page whose conformance matrix to regenerate, between its markers "
                   "(default: the project's docs/conformance-matrix.md)")
    p.set_defaults(func=cmd_expectations)

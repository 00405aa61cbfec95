"""The x3drbp command line: one module per command, each adding its parser to `main`."""

from __future__ import annotations

import argparse

from conformance.cli.check import add_command as add_check
from conformance.cli.compare import add_command as add_compare
from conformance.cli.conformance import add_command as add_conformance
from conformance.cli.expectations import add_command as add_expectations
from conformance.cli.report import add_command as add_report
from conformance.cli.run import add_commands
from conformance.cli.stability import add_command as add_stability
from conformance.cli.sweep import add_command as add_sweep
from conformance.cli.validate import add_command as add_validate
from conformance.cli.x_ite import add_command as add_x_ite


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="x3drbp", description="Conformance and comparison suite for the X3D RigidBodyPhysics component.")
    sub = parser.add_subparsers(dest="command", required=True)
    add_check(sub)
    add_commands(sub)
    add_compare(sub)
    add_conformance(sub)
    add_expectations(sub)
    add_stability(sub)
    add_sweep(sub)
    add_report(sub)
    add_validate(sub)
    add_x_ite(sub)
    parser.set_defaults(main=main)  # `x3drbp report` runs the other commands through it
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except KeyboardInterrupt:
        return 130


"""What `x3drbp run` imports: its own command's module alone, and no renderer. Every other
command starts it by the hundred (benchmarks/run_startup.py measures the time)."""

from __future__ import annotations

import json
import subprocess
import sys

from conftest import ROOT

from conformance.cli import COMMANDS

PROBE = """
import json, sys
from conformance.cli import main
code = main(sys.argv[1:])
print(json.dumps([code, sorted(m for m in sys.modules if m.startswith("conformance.cli.")),
                  sorted(m for m in ("glfw", "matplotlib", "rerun", "dask", "tqdm") if m in sys.modules)]))
"""


def _imports(*argv: str) -> tuple[int, list[str], list[str]]:
    done = subprocess.run([sys.executable, "-c", PROBE, *argv], cwd=ROOT, capture_output=True, text=True, timeout=120)
    return tuple(json.loads(done.stdout.strip().splitlines()[-1]))


def test_a_command_imports_its_own_module_and_no_other_command_s():
    code, modules, heavy = _imports("backends")  # loads every engine, runs nothing
    commands = {f"conformance.cli.{m}" for m in COMMANDS.values()}
    assert code == 0 and [m for m in modules if m in commands] == ["conformance.cli.run"]
    assert heavy == []  # mujoco without its GL context; no plotting, recording, cluster or bars


def test_help_still_lists_every_command():
    done = subprocess.run([sys.executable, "-m", "conformance.cli", "--help"], cwd=ROOT, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0 and all(name in done.stdout for name in COMMANDS)
    done = subprocess.run([sys.executable, "-m", "conformance.cli", "nope"], cwd=ROOT, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 2 and "invalid choice: 'nope'" in done.stderr and "Traceback" not in done.stderr

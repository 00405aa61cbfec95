"""What `x3drbp run` imports: its own command's module alone, and no renderer. Every other
command starts it by the hundred (benchmarks/run_startup.py measures the time)."""

from __future__ import annotations

import json
import subprocess
import sys

from conftest import ROOT, needs_ode

from x3drbp import COMMANDS

PROBE = """
import json, sys
from x3drbp import main
code = main(sys.argv[1:])
print(json.dumps([code, sorted(m for m in sys.modules if m.startswith("x3drbp.")),
                  sorted(m for m in ("glfw", "matplotlib", "rerun", "dask", "tqdm") if m in sys.modules)]))
"""


def _imports(*argv: str) -> tuple[int, list[str], list[str]]:
    done = subprocess.run([sys.executable, "-c", PROBE, *argv], cwd=ROOT, capture_output=True, text=True, timeout=120)
    return tuple(json.loads(done.stdout.strip().splitlines()[-1]))


def test_a_command_imports_its_own_module_and_no_other_command_s():
    code, modules, heavy = _imports("backends")  # loads every engine, runs nothing
    commands = {f"x3drbp.{m}" for m in COMMANDS.values()}
    assert code == 0 and [m for m in modules if m in commands] == ["x3drbp.run"]
    assert heavy == []  # mujoco without its GL context; no plotting, recording, cluster or bars


def test_help_still_lists_every_command():
    done = subprocess.run([sys.executable, "-m", "x3drbp", "--help"], cwd=ROOT, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0 and all(name in done.stdout for name in COMMANDS)
    done = subprocess.run([sys.executable, "-m", "x3drbp", "nope"], cwd=ROOT, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 2 and "invalid choice: 'nope'" in done.stderr and "Traceback" not in done.stderr


@needs_ode
def test_a_run_reads_no_entry_points_and_its_help_still_names_every_backend(tmp_path):
    """Reading the registry (every package's entry points and metadata) is for --help and plug-ins:
    a run on x3drbp's own backend does without it."""
    probe = ("import json, sys\nfrom x3drbp import main\ncode = main(sys.argv[1:])\n"
             "print(json.dumps([code, 'importlib.metadata' in sys.modules]))\n")
    done = subprocess.run([sys.executable, "-c", probe, "run", "scenes/examples/pendulum.x3d", "--backend", "ode",
                           "--duration", repr(1 / 240), "--trace", str(tmp_path / "t.csv"), "-q"],
                          cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert json.loads(done.stdout.strip().splitlines()[-1]) == [0, False]
    from backends import base
    done = subprocess.run([sys.executable, "-m", "x3drbp", "run", "--help"], cwd=ROOT, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0 and f"one of {', '.join(base.engines())}" in " ".join(done.stdout.split())


BLAS = """
import os, sys
import x3drbp
print(os.environ.get("OPENBLAS_NUM_THREADS"), "numpy" in sys.modules)
"""


def test_one_blas_thread_is_set_before_numpy_loads_unless_the_user_chose():
    """numpy's OpenBLAS reads the variable once, when it loads: set later it does nothing, and
    each process of the hundreds a command starts would spin a thread per core at start and exit."""
    import os
    import resource

    def probe(env: dict[str, str]) -> list[str]:  # bounded in CPU, not in wall time (a busy machine is slow)
        got = subprocess.run([sys.executable, "-c", BLAS], cwd=ROOT, env=env, capture_output=True, text=True,
                             preexec_fn=lambda: resource.setrlimit(resource.RLIMIT_CPU, (60, 60)))
        assert got.returncode == 0, got.stderr
        return got.stdout.split()

    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    assert probe(env) == ["1", "False"]
    assert probe(env | {"OPENBLAS_NUM_THREADS": "4"}) == ["4", "False"]  # a user's own choice stands

"""x3d_core's modules before its wings (x3d_core/__init__.py): an engine written outside the tree
against x3d_core.world's World and x3d_core.engine's Simulation, or any other old path, keeps
working, and is told in one line where each moved."""

from __future__ import annotations

import importlib
import subprocess
import sys

import pytest

from conftest import ROOT
from x3d_core import MOVED

# An adapter's imports as docs/example_adapter/x3drbp_euler.py and the mutants wrote them before
OLD_ADAPTER = """
import warnings
warnings.simplefilter("always", DeprecationWarning)
from backends.base import Backend, native
from x3d_core import rotation as R
from x3d_core.collision import ContactPoints
from x3d_core.engine import Simulation, Unsupported
from x3d_core.model import Node
from x3d_core.world import JOINT_TYPES, STATIC, State, World, worlds
import x3d_core.semantics.world, x3d_core.semantics.engine, x3d_core.model.scene
assert World is x3d_core.semantics.world.World and worlds is x3d_core.semantics.world.worlds
assert Simulation is x3d_core.semantics.engine.Simulation
assert Node is x3d_core.model.scene.Node
assert R is sys.modules["x3d_core.semantics.rotation"]
print("imported")
"""


def _run(code: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", "import sys\n" + code], cwd=ROOT, capture_output=True, text=True)


def test_an_adapter_on_the_old_paths_runs_and_is_told_where_each_moved():
    out = _run(OLD_ADAPTER)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "imported"
    said = [line for line in out.stderr.splitlines() if "DeprecationWarning" in line]
    for old, new in [("x3d_core.rotation", "x3d_core.semantics.rotation"),
                     ("x3d_core.collision", "x3d_core.semantics.collision"),
                     ("x3d_core.engine", "x3d_core.semantics.engine"),
                     ("x3d_core.world", "x3d_core.semantics.world"),
                     ("x3d_core.model.Node", "x3d_core.model.scene.Node")]:
        assert any(f"{old} has moved to {new}: import it from there" in line for line in said), (old, said)


@pytest.mark.parametrize("old", sorted(MOVED))
def test_every_old_path_is_the_module_at_its_new_one(old: str):
    out = _run(f"import importlib\nold = importlib.import_module({old!r})\n"
               f"assert old is importlib.import_module({MOVED[old]!r})\nprint(old.__name__)")
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == MOVED[old]


def test_an_old_path_names_only_a_module_that_moved():
    """Every module of the core is in MOVED under its old flat name, and nothing else is: a new
    module has no old path."""
    new = set(MOVED.values())
    for path in new:
        importlib.import_module(path)
    assert len(new) == len(MOVED)
    assert {old.rpartition(".")[2] for old in MOVED} >= {"world", "engine", "collision", "rotation", "trace"}
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module("x3d_core.world_data")  # world_data is new: it never had a flat path


def test_the_scene_module_names_still_resolve_on_the_model_wing_and_nothing_else_does():
    model = importlib.import_module("x3d_core.model")
    with pytest.warns(DeprecationWarning, match=r"x3d_core\.model\.Scene has moved to x3d_core\.model\.scene\.Scene"):
        assert model.Scene is importlib.import_module("x3d_core.model.scene").Scene
    with pytest.raises(AttributeError):
        model.no_such_name  # noqa: B018

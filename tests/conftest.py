"""Shared paths for the tests."""

from __future__ import annotations

import functools
import os

import pytest

# every run afresh: no test reads a run another test, or the user's own commands, left in the run
# cache (conformance/runner/cache.py); the cache's own tests point it at a folder of theirs
os.environ["X3DRBP_CACHE"] = "off"

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.normpath(os.path.join(ROOT, "..", "shared"))
CORPUS = os.path.join(SHARED, "corpus")
UOM = os.path.join(SHARED, "reference", "X3dUnifiedObjectModel-4.0.xml")
SCENES = os.path.join(ROOT, "scenes")
CASES = os.path.join(ROOT, "conformance", "cases")  # a folder per conformance case


@functools.cache
def _ode_missing() -> str | None:
    """Why the ode backend cannot run here, or None; asked on the first test that needs it (never
    when this module is imported: a test's child process imports it too, and must not load engines)."""
    from backends import base
    try:
        base.load("ode")
    except ImportError as e:
        return f"ODE is unavailable here ({e})"
    return None


# a test that runs ODE itself (an `x3drbp run --backend ode`, a pin of ODE's): skipped, saying why, where the
# ode backend is unavailable (no libode8, or X3DRBP_NO_ODE set, as .ci/run's second run of the tests does)
needs_ode = pytest.mark.needs_ode


def pytest_runtest_setup(item) -> None:
    if item.get_closest_marker("needs_ode") is not None and _ode_missing() is not None:
        pytest.skip(_ode_missing())


def scene_file(folder, body: str, name: str = "s") -> str:
    """An X3D 4.0 XML file NAME.x3d in folder whose Scene holds body."""
    path = os.path.join(str(folder), f"{name}.x3d")
    with open(path, "w", encoding="utf-8") as f:
        f.write(f"<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Full' version='4.0'><Scene>\n{body}\n"
                "</Scene></X3D>\n")
    return path


def loaded_scene(folder, body: str):
    """scene_file's scene, loaded, without errors."""
    from x3d_core.encodings.load import load
    scene = load(scene_file(folder, body))
    assert not scene.errors, [str(e) for e in scene.errors]
    return scene


def case_scene(name: str) -> str:
    """The scene of conformance case NAME: conformance/cases/NAME/NAME.x3d."""
    return os.path.join(CASES, name, f"{name}.x3d")


# An expression for a child's code: its peak RSS in KiB since it started, from VmHWM, which a
# new program starts afresh. Not ru_maxrss: Linux carries that across fork and exec, so a child
# of a pytest process of 400 MB starts at 400 MB (a bound on growth then passes vacuously).
PEAK_KIB = "int(next(ln.split()[1] for ln in open('/proc/self/status') if ln.startswith('VmHWM:')))"

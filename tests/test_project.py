"""The promises the README makes about setting up and running the project."""

from __future__ import annotations

import os
import re

from conftest import ROOT


def read(name: str) -> str:
    with open(os.path.join(ROOT, name), encoding="utf-8") as f:
        return f.read()


def test_readme_gives_the_two_commands_and_ci_runs_the_test_one():
    readme, makefile, ci = read("README.md"), read("Makefile"), read(".ci/run")
    assert "make report" in readme and "make test" in readme
    assert re.search(r"^report:", makefile, re.M) and re.search(r"^test:", makefile, re.M)
    assert re.search(r"^make test$", ci, re.M)


def test_x3d_core_imports_no_engine_and_backends_no_conformance():
    engines = re.compile(r"^\s*(?:import|from)\s+(pybullet|mujoco|dartpy|pymunk|rerun|backends|conformance|reports)\b",
                         re.M)
    upward = re.compile(r"^\s*(?:import|from)\s+(conformance|reports)\b", re.M)
    for folder, pattern in (("x3d_core", engines), ("backends", upward)):
        for name in os.listdir(os.path.join(ROOT, folder)):
            if name.endswith(".py"):
                assert not pattern.search(read(os.path.join(folder, name))), f"{folder}/{name} crosses the layering"

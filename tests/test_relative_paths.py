"""Paths a user gives, resolved against the folder the command was run in (issue 29): the
children run in the project root, so a relative scene path handed on as given named nothing
there ("the scenes could not be judged: ... cannot read file"); and a step that fails makes
`report` fail and says so, never "Not run."."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys

import pytest

from backends import base
from conftest import ROOT, SCENES
from conformance.analyses import advice as A
from x3drbp import main
from x3drbp import report as R

PAIR = [n for n in ("bullet", "pymunk", "mujoco", "ode", "dart") if not isinstance(base.available().get(n, "x"), str)][:2]
needs_two = pytest.mark.skipif(len(PAIR) < 2, reason="advice and comparison need two installed backends")
PENDULUM = os.path.join(SCENES, "examples", "pendulum.x3d")
SMALL = ["--dts", "1/60", "--duration", "0.5", "--window", "0.5", "--repeats", "1", "-q"]


def _x3drbp(cwd: str, *args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": ROOT}
    return subprocess.run([sys.executable, "-m", "x3drbp", *args], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=300)


@needs_two
def test_advise_reads_a_relative_scene_from_any_folder_and_names_it_as_given(tmp_path):
    (tmp_path / "mine").mkdir()
    shutil.copy(PENDULUM, tmp_path / "mine" / "swing.x3d")
    r = _x3drbp(str(tmp_path), "advise", "mine/swing.x3d", "--backends", ",".join(PAIR), *SMALL,
                "--json", "advice.json")
    assert r.returncode == 0 and "could not be judged" not in r.stderr, r.stderr
    doc = json.loads((tmp_path / "advice.json").read_text())  # --json relative to the same folder
    assert [s["scene"] for s in doc["scenes"]] == ["mine/swing.x3d"] and doc["scenes"][0]["recommended"]
    assert r.stdout.startswith("mine/swing.x3d (joints): ")


@needs_two
def test_compare_names_a_relative_scene_as_given(tmp_path):
    shutil.copy(PENDULUM, tmp_path / "swing.x3d")
    r = _x3drbp(str(tmp_path), "compare", "swing.x3d", "--backends", ",".join(PAIR), "--duration", "0.25", "-q",
                "--json", "c.json")
    assert r.returncode == 0, r.stderr
    assert json.loads((tmp_path / "c.json").read_text())["scene"] == "swing.x3d"
    assert r.stdout.startswith("# x3drbp compare swing.x3d") and str(tmp_path) not in r.stderr


def _advise_only(out_dir: str, backends: list[str], quick: bool, x_ite: bool, scenes: list[str]) -> list:
    """report's steps made small: the advice of the user's scenes alone, as report names them."""
    return [("advise", [["advise", *map(os.path.relpath, scenes), "--backends", ",".join(backends), *SMALL,
                         "--json", os.path.join(out_dir, "advice", "advice.json")]])]


@needs_two
def test_report_advises_relative_scenes_from_any_folder(tmp_path, monkeypatch):
    (tmp_path / "mine").mkdir()
    shutil.copy(PENDULUM, tmp_path / "mine" / "swing.x3d")
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(R, "_steps", _advise_only)
    assert main(["report", "--out", "rep", "--backends", ",".join(PAIR), "--scenes", "mine", "-q"]) == 0
    meta = json.loads((tmp_path / "rep" / "report.json").read_text())
    assert meta["failed"] == [] and (tmp_path / "rep" / "advice" / "advice.json").exists()


@needs_two
def test_a_failed_advise_step_fails_the_report_and_is_named(tmp_path, monkeypatch):
    shutil.copy(PENDULUM, tmp_path / "swing.x3d")
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(R, "_steps", _advise_only)
    monkeypatch.setattr(A, "judge", lambda *a: (None, "the judgement's child crashed"))
    assert main(["report", "--out", "rep", "--backends", ",".join(PAIR), "--scenes", "swing.x3d", "-q"]) == 1
    meta = json.loads((tmp_path / "rep" / "report.json").read_text())
    assert meta["failed"] == ["advise"]
    text = (tmp_path / "rep" / "report.md").read_text()
    section = text[text.index("## Which backend"):]
    assert section.split("\n")[2].startswith("FAILED: the advise step could not run")

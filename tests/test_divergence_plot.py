"""reports/divergence_plot.py: the plot of a real `x3drbp compare` JSON (the pendulum on MuJoCo and
Bullet), what it draws, its size and bytes, and the plots of nothing."""

from __future__ import annotations

import importlib.util
import json
import os
import struct
import subprocess
import sys

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from conformance.results import Comparison  # noqa: E402
from conftest import ROOT, SCENES  # noqa: E402
from reports.divergence_plot import FLOOR, divergence_plot, figure  # noqa: E402

PENDULUM = os.path.join(SCENES, "examples", "pendulum.x3d")
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
THRESHOLDS = {"position": 1e-3, "orientation": 1e-3}


@pytest.fixture(scope="module")
def compared(tmp_path_factory) -> str:
    """`x3drbp compare` of the pendulum on MuJoCo and Bullet for 0.5 s: its JSON's path."""
    if not all(importlib.util.find_spec(m) for m in ("mujoco", "pybullet")):
        pytest.skip("needs mujoco and pybullet")
    out = str(tmp_path_factory.mktemp("compare") / "pendulum.json")
    done = subprocess.run([sys.executable, "-m", "conformance.cli", "compare", PENDULUM, "--backends",
                           "mujoco,bullet", "--duration", "0.5", "--json", out], cwd=ROOT, capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return out


def _read(path: str) -> Comparison:
    with open(path, encoding="utf-8") as f:
        return Comparison.from_json(json.load(f))


def _png(path: str) -> tuple[int, int, bytes]:
    """(width, height, the file's bytes) of a PNG, its signature and first chunk checked."""
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == PNG_SIGNATURE and data[12:16] == b"IHDR"
    width, height = struct.unpack(">II", data[16:24])
    return width, height, data


def test_the_plot_of_a_compare_json_is_a_900_by_500_png_and_the_same_bytes_every_time(compared, tmp_path):
    paths = [str(tmp_path / f"{k}.png") for k in range(3)]
    divergence_plot(_read(compared), paths[0])
    divergence_plot(_read(compared), paths[1])
    # a fresh interpreter too: nothing of this process's matplotlib state goes into the bytes
    subprocess.run([sys.executable, "-c", "import json, sys; from conformance.results import Comparison; "
                    "from reports.divergence_plot import divergence_plot; "
                    "divergence_plot(Comparison.from_json(json.load(open(sys.argv[1]))), sys.argv[2])",
                    compared, paths[2]], cwd=ROOT, check=True, timeout=120)
    width, height, first = _png(paths[0])
    assert (width, height) == (900, 500)
    assert all(_png(p)[2] == first for p in paths[1:])
    assert b"Software" not in first and b"Matplotlib" not in first
    assert not [n for n in os.listdir(tmp_path) if not n.endswith(".png")]  # no temporary left


def test_each_panel_draws_the_pair_clipped_at_the_floor_and_its_threshold(compared):
    c = _read(compared)
    (p,) = c.pairs
    fig = figure(c)
    top, bottom = fig.axes[:2]
    for ax, d, unit in ((top, p.position, "m"), (bottom, p.orientation, "rad")):
        pair, threshold = ax.get_lines()
        assert pair.get_label() == "mujoco vs bullet"
        np.testing.assert_array_equal(pair.get_xdata(), p.times)
        np.testing.assert_array_equal(pair.get_ydata(), np.maximum(d.frame_max, FLOOR))
        assert threshold.get_linestyle() == "--" and list(threshold.get_ydata()) == [1e-3, 1e-3]
        assert ax.get_yscale() == "log" and f"({unit})" in ax.get_ylabel()
        # both start together (frame 0: 0 apart), and the axis says where that 0 is drawn
        assert d.frame_max[0] == 0 and f"below {FLOOR:g} drawn at it" in ax.get_ylabel()
    assert bottom.get_xlabel() == "time (s)"
    (legend,) = fig.legends
    assert [t.get_text() for t in legend.get_texts()] == [
        "mujoco vs bullet", "position threshold 0.001 m", "orientation threshold 0.001 rad"]


def test_a_plot_with_no_pair_says_so(tmp_path):
    c = Comparison("s.x3d", 0.5, 1 / 240, 60, THRESHOLDS, [], [])
    path = str(tmp_path / "none.png")
    divergence_plot(c, path)
    assert _png(path)[:2] == (900, 500)
    (ax,) = figure(c).axes
    assert [t.get_text() for t in ax.texts] == ["no pair ran"] and not ax.get_lines()
    assert ax.get_title() == "s.x3d: divergence over time (dt 1/240 s, 60 frames/s)"


def test_a_pair_without_a_body_in_common_is_not_drawn(compared):
    c = _read(compared)
    (p,) = c.pairs
    for d in (p.position, p.orientation):  # as compare_pair leaves a pair that shares no body
        d.frame_max = d.frame_rms = np.empty(0)
    (ax,) = figure(c).axes
    assert [t.get_text() for t in ax.texts] == ["no pair shares a body and a frame time"]


def test_a_scene_named_like_mathematics_is_text_in_the_plots(tmp_path):
    """matplotlib sets $...$ as mathematics: a scene file named `a$\\frac$b.x3d` stopped the plot
    with a parse error, and `a$x^2$.x3d` was drawn as a formula. A name is text on the page."""
    from reports.plots import sweep_plot
    for name in ("a$\\frac$b.x3d", "a$x^2$.x3d"):
        c = Comparison(name, 0.5, 1 / 240, 60, THRESHOLDS, [], [])
        path = str(tmp_path / "none.png")
        divergence_plot(c, path)  # no parse error
        (ax,) = figure(c).axes
        assert ax.get_title().startswith(name.replace("$", "\\$") + ": divergence")
        stem = name[:-4]
        doc = {"backends": {}, "points": [], "scenes": [{"name": stem, "reference": "closed form", "quantity": "q",
                                                          "unit": "m"}]}
        sweep_plot(doc, stem, str(tmp_path / "sweep.png"))
        assert _png(str(tmp_path / "sweep.png"))[0] > 0


def test_a_scene_whose_file_name_is_not_utf_8_is_its_escapes_in_the_plots(tmp_path):
    """A byte that is not UTF-8 reaches Python as a surrogate, which no font takes: the sweep of
    `p\\xffq.x3d` stopped at its plot's title with a TypeError traceback."""
    from reports.plots import sweep_plot
    name = os.fsdecode(b"p\xffq.x3d")
    c = Comparison(name, 0.5, 1 / 240, 60, THRESHOLDS, [], [])
    divergence_plot(c, str(tmp_path / "none.png"))
    (ax,) = figure(c).axes
    assert ax.get_title().startswith("p\\udcffq.x3d: divergence")
    doc = {"backends": {}, "points": [], "scenes": [{"name": name[:-4], "reference": "closed form",
                                                      "quantity": "q", "unit": "m"}]}
    sweep_plot(doc, name[:-4], str(tmp_path / "sweep.png"))
    assert _png(str(tmp_path / "sweep.png"))[0] > 0

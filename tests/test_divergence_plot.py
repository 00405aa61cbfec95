"""reports/divergence_plot.py: the plot of a real `x3drbp compare` JSON (the pendulum on MuJoCo and
Bullet), what it draws, its size and bytes, a panel per pair, and the plots of nothing."""

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

from conformance.results import Comparison, Crossing, Divergence, PairComparison  # noqa: E402
from conftest import ROOT, SCENES  # noqa: E402
from reports.divergence_plot import DPI, divergence_plot, figure, size  # noqa: E402

PENDULUM = os.path.join(SCENES, "examples", "pendulum.x3d")
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
THRESHOLDS = {"position": 1e-3, "orientation": 1e-3}


@pytest.fixture(scope="module")
def compared(tmp_path_factory) -> str:
    """`x3drbp compare` of the pendulum on MuJoCo and Bullet for 0.5 s: its JSON's path."""
    if not all(importlib.util.find_spec(m) for m in ("mujoco", "pybullet")):
        pytest.skip("needs mujoco and pybullet")
    out = str(tmp_path_factory.mktemp("compare") / "pendulum.json")
    done = subprocess.run([sys.executable, "-m", "x3drbp", "compare", PENDULUM, "--backends",
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


def test_the_plot_of_a_compare_json_is_a_png_of_its_size_and_the_same_bytes_every_time(compared, tmp_path):
    paths = [str(tmp_path / f"{k}.png") for k in range(3)]
    divergence_plot(_read(compared), paths[0])
    divergence_plot(_read(compared), paths[1])
    # a fresh interpreter too: nothing of this process's matplotlib state goes into the bytes
    subprocess.run([sys.executable, "-c", "import json, sys; from conformance.results import Comparison; "
                    "from reports.divergence_plot import divergence_plot; "
                    "divergence_plot(Comparison.from_json(json.load(open(sys.argv[1]))), sys.argv[2])",
                    compared, paths[2]], cwd=ROOT, check=True, timeout=120)
    width, height, first = _png(paths[0])
    assert (width, height) == tuple(round(x * DPI) for x in size(2)) == (600, 440)
    assert all(_png(p)[2] == first for p in paths[1:])
    assert b"Software" not in first and b"Matplotlib" not in first
    assert not [n for n in os.listdir(tmp_path) if not n.endswith(".png")]  # no temporary left


def test_a_pair_s_panel_draws_both_quantities_at_the_floor_with_their_thresholds(compared):
    c = _read(compared)
    (p,) = c.pairs
    fig = figure(c)
    (ax,) = fig.axes  # one pair, one panel: row mujoco, column bullet
    assert (ax.get_ylabel(), ax.get_title()) == ("mujoco", "bullet") and ax.get_yscale() == "log"
    position, p_threshold, orientation, o_threshold = ax.get_lines()
    low = 1e-6 * 1e-3  # FLOOR times the smaller threshold
    for line, threshold, d in ((position, p_threshold, p.position), (orientation, o_threshold, p.orientation)):
        np.testing.assert_array_equal(line.get_xdata(), p.times)
        np.testing.assert_array_equal(line.get_ydata(), np.maximum(d.frame_max, low))
        assert threshold.get_linestyle() == "--" and list(threshold.get_ydata()) == [1e-3, 1e-3]
        assert threshold.get_color() == line.get_color()
    assert p.position.frame_max[0] == 0  # frame 0: 0 apart, drawn at the floor, which the legend names
    (legend,) = fig.legends
    assert legend.get_title().get_text() == "row against column; below 1e-09: drawn at it"
    assert [t.get_text() for t in legend.get_texts()] == [
        "position divergence (m), max over bodies", "orientation divergence (rad), max over bodies",
        "position threshold 0.001 m", "orientation threshold 0.001 rad", "shaded: within both for the whole run"]


def _pair(a: str, b: str, parts_at: float | None) -> PairComparison:
    """A pair whose position divergence grows linearly, passing 1 mm at parts_at (None: never)."""
    times = np.linspace(0.0, 1.0, 11)
    gap = (times * 2e-3 / parts_at) if parts_at is not None else times * 1e-4
    crossing = None if parts_at is None else Crossing(parts_at, ["Ball"], [2e-3])
    return PairComparison(a, b, times, ["Ball"], [], [],
                          Divergence("position", "m", 1e-3, first_over=crossing, frame_max=gap),
                          Divergence("orientation", "rad", 1e-3, frame_max=np.zeros_like(times)), [], [], [])


def test_every_pair_has_its_own_panel_row_against_column():
    """21 pairs in one panel, in ten colours that repeat, could not be read: a triangle of small
    panels, row against column, each saying when its pair parts, the pairs that stay together
    shaded."""
    names = ["ode", "bullet", "mujoco", "dart"]
    parts = {("ode", "bullet"): 0.5, ("ode", "mujoco"): None, ("ode", "dart"): 0.25,
             ("bullet", "mujoco"): 0.75, ("bullet", "dart"): None, ("mujoco", "dart"): 0.1}
    c = Comparison("s.x3d", 1.0, 1 / 240, 60, THRESHOLDS, [], [_pair(a, b, t) for (a, b), t in parts.items()])
    fig = figure(c)
    assert fig.get_size_inches().tolist() == list(size(4))
    shown = [ax for ax in fig.axes if ax.axison]
    assert len(shown) == 6 and len(fig.axes) == 9  # a 3 x 3 grid, its lower triangle empty
    grid = np.array(fig.axes).reshape(3, 3)
    for i in range(3):
        for j in range(3):
            ax = grid[i][j]
            assert ax.axison == (j >= i)
            if j < i:
                continue
            when = parts[(names[i], names[j + 1])]
            (said,) = [t.get_text() for t in ax.texts]
            assert said == (f"parts at {when:g} s" if when is not None else "within for 1 s")
            assert (ax.get_facecolor() != (1, 1, 1, 1)) == (when is None)  # shaded where it stays within
            np.testing.assert_array_equal(ax.get_lines()[0].get_ydata(),
                                          np.maximum(_pair("a", "b", when).position.frame_max, 1e-9))
    assert [grid[0][j].get_title() for j in range(3)] == names[1:]  # columns named along the top
    assert [grid[i][i].get_ylabel() for i in range(3)] == names[:-1]  # rows named where each starts
    assert "each pair of backends" in fig.get_suptitle()


def test_a_plot_with_no_pair_says_so(tmp_path):
    c = Comparison("s.x3d", 0.5, 1 / 240, 60, THRESHOLDS, [], [])
    path = str(tmp_path / "none.png")
    divergence_plot(c, path)
    assert _png(path)[:2] == tuple(round(x * DPI) for x in size(0))
    (ax,) = figure(c).axes
    assert [t.get_text() for t in ax.texts] == ["no pair ran"] and not ax.get_lines()
    assert ax.get_title() == "s.x3d: divergence over time, each pair of backends\n(dt 1/240 s, 60 frames/s)"


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

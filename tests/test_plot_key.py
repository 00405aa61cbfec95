"""reports/plot_key.py: a divergence or sweep plot is drawn again only where what it draws
changed (its key, kept in the PNG), and a PNG that is not whole or not keyed so is drawn again."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from conformance.results import Comparison, Crossing, Divergence, PairComparison  # noqa: E402
from reports import divergence_plot as D  # noqa: E402
from reports import plot_key, plots  # noqa: E402

THRESHOLDS = {"position": 1e-3, "orientation": 1e-3}


def _comparison(gap: float = 2e-3, backend: str = "bullet") -> Comparison:
    times = np.linspace(0.0, 1.0, 11)
    pair = PairComparison("mujoco", backend, times, ["Ball"], [], [],
                          Divergence("position", "m", 1e-3, first_over=Crossing(0.5, ["Ball"], [gap]),
                                     frame_max=times * gap),
                          Divergence("orientation", "rad", 1e-3, frame_max=np.zeros_like(times)), [], [], [])
    return Comparison("s.x3d", 1.0, 1 / 240, 60, dict(THRESHOLDS), [], [pair])


@pytest.fixture
def drawings(monkeypatch) -> list[str]:
    """The plots drawn (their kinds), counted where each module starts one."""
    drawn: list[str] = []
    figure, draw = D.figure, plots._draw
    monkeypatch.setattr(D, "figure", lambda c: drawn.append("divergence") or figure(c))
    monkeypatch.setattr(plots, "_draw", lambda *a: drawn.append("sweep") or draw(*a))
    return drawn


def test_a_divergence_plot_of_the_same_data_is_not_drawn_again_and_one_of_other_data_is(tmp_path, drawings):
    path = str(tmp_path / "s.divergence.png")
    D.divergence_plot(_comparison(), path)
    first = open(path, "rb").read()
    D.divergence_plot(_comparison(), path)  # the same data, read again: the same key
    assert drawings == ["divergence"] and open(path, "rb").read() == first
    for changed in (_comparison(gap=3e-3), _comparison(backend="ode")):
        D.divergence_plot(changed, path)
        assert open(path, "rb").read() != first
    assert drawings == ["divergence"] * 3
    thresholds = _comparison()
    thresholds.thresholds["position"] = 1e-2  # a threshold is drawn: another plot
    assert D.key(thresholds) != D.key(_comparison())
    runs = _comparison()
    runs.pairs[0].position.rms = 5.0  # not drawn: the same plot
    assert D.key(runs) == D.key(_comparison())


def test_a_png_cut_short_or_keyed_otherwise_is_drawn_again(tmp_path, drawings):
    path = str(tmp_path / "s.divergence.png")
    c = _comparison()
    D.divergence_plot(c, path)
    whole = open(path, "rb").read()
    assert plot_key.drawn(path, D.key(c)) and not plot_key.drawn(path, D.key(_comparison(gap=3e-3)))
    open(path, "wb").write(whole[:-20])  # IEND lost
    assert not plot_key.drawn(path, D.key(c))
    D.divergence_plot(c, path)
    assert drawings == ["divergence"] * 2 and open(path, "rb").read() == whole
    assert not plot_key.drawn(str(tmp_path / "none.png"), D.key(c))


def _doc(cpu: float) -> dict:
    point = {"scene": "s", "backend": "mujoco", "dt": 1 / 60, "dt_label": "1/60", "label": "mujoco 1/60",
             "iterations": None, "prefer_accuracy": None, "error": 1e-3, "cpu_per_sim_s": cpu, "cpu_low": cpu,
             "cpu_high": cpu, "pareto_scene": True, "tie_scene": None}
    return {"backends": {"mujoco": {}}, "points": [point], "generated": "now",
            "scenes": [{"name": "s", "reference": "closed form", "quantity": "q", "unit": "m"}]}


def test_a_sweep_plot_is_drawn_again_only_where_its_scene_s_points_changed(tmp_path, drawings):
    path = str(tmp_path / "sweep_s.png")
    plots.sweep_plot(_doc(0.01), "s", path)
    later = {**_doc(0.01), "generated": "later", "wall_s": 3.0}  # not drawn: the same plot
    plots.sweep_plot(later, "s", path)
    assert drawings == ["sweep"]
    plots.sweep_plot(_doc(0.02), "s", path)
    assert drawings == ["sweep"] * 2

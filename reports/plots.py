"""Plots of results, as PNG files (matplotlib's Agg backend: no display needed)."""

from __future__ import annotations

import io
import textwrap

from x3d_core.files import atomic

from . import plot_key
from .sweep_tables import NO_RESULTS, measured, variation
from .text import plotted

_MARKERS = "os^Dv<>p*h"
# shown beside its front's table on a 1400 px page (about 560 px there) and at its own size below
# it on a narrower one: 700 x 520 px, its text 8-9 points at 100 dpi (11-12 px at full size)
SIZE, DPI = (7.0, 5.2), 100
# characters a title line holds at 9 points over the axes (the legend beside them): longer ones were cut off
TITLE_WIDTH = 62


def sweep_plot(doc: dict, scene: str, path: str) -> None:
    """Error against CPU time in the engine's steps per simulated second for one scene of a sweep (sweep.json's
    document), both axes logarithmic: a colour per backend, a line per (iterations,
    preferAccuracy) through its steps in order, the scene's Pareto front ringed in black, and
    a common reference's uncertainty as a dotted line (errors below it tie). Points without
    an error (refused, crashed...) are not drawn; errors of exactly 0 are drawn at a tenth of
    the smallest nonzero one, and the title says so. A scene with no point to draw gets a
    plot that says so (log axes of nothing are matplotlib's error). Not drawn again where the
    PNG at path holds the same key (plot_key.py: the scene's entry, its points and the backends
    unchanged)."""
    info = next(s for s in doc["scenes"] if s["name"] == scene)
    points = measured([p for p in doc["points"] if p["scene"] == scene])
    key = plot_key.digest([info, points, list(doc["backends"])], (__name__, variation.__module__, plotted.__module__))
    if plot_key.drawn(path, key):
        return
    plt = pyplot()
    fig, ax = plt.subplots(figsize=SIZE)
    method = info.get("reference_method")
    title = f"{scene}: {info['reference']}" + (f" ({info['reference_backend']}, {method})" if method else "")
    title += f", {info['quantity']}"
    if points:
        title += _draw(ax, doc, points, info["unit"], info.get("reference_error"))
    else:
        ax.axis("off")
        ax.text(0.5, 0.5, f"no results: {NO_RESULTS}", ha="center", va="center", transform=ax.transAxes)
    ax.set_title(textwrap.fill(plotted(title), TITLE_WIDTH), fontsize=9)
    fig.tight_layout()
    png = io.BytesIO()
    fig.savefig(png, format="png", dpi=DPI, metadata=plot_key.metadata(key))
    atomic.write_bytes(path, png.getvalue())
    plt.close(fig)


def pyplot():
    """matplotlib's pyplot on its Agg backend (no display needed), imported when a plot is drawn:
    a sweep whose plots are all unchanged (plot_key.py) does not pay for the import (0.7 s)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _draw(ax, doc: dict, points: list[dict], unit: str, uncertainty: float | None) -> str:
    """The points on log axes, and the reference's uncertainty where it has one above 0; what
    the title adds (the floor that errors of 0 are drawn at). The legend is the code, not a line
    per variation (28 of them ran off a 600 px picture): a colour per backend, a marker per
    iterations value, dashed where preferAccuracy is TRUE."""
    from matplotlib.lines import Line2D
    nonzero = [p["error"] for p in points if p["error"] > 0]
    floor = min(nonzero) / 10 if nonzero else 1e-16
    iterations = list(dict.fromkeys(variation(p).split(" | ")[0] for p in sorted(points, key=_its)))
    legend = []
    for b, backend in enumerate(doc["backends"]):  # a backend keeps its colour in every plot
        mine = [p for p in points if p["backend"] == backend]
        if mine:
            legend.append(Line2D([], [], color=f"C{b}", linewidth=2, label=backend))
        for var in dict.fromkeys(variation(p) for p in mine):
            line = sorted((p for p in mine if variation(p) == var), key=lambda p: -p["dt"])
            its, acc = var.split(" | ")
            x = [p["cpu_per_sim_s"] for p in line]
            spread = [[m - (p.get("cpu_low") or m) for m, p in zip(x, line)],
                      [(p.get("cpu_high") or m) - m for m, p in zip(x, line)]]
            ax.errorbar(x, [max(p["error"], floor) for p in line], xerr=spread, color=f"C{b}",
                        marker=_MARKERS[iterations.index(its) % len(_MARKERS)], markersize=5,
                        linestyle="--" if acc == "TRUE" else "-", linewidth=1.2,
                        label=f"{backend} it={its} acc={acc}", alpha=0.8, capsize=2)
    legend += [Line2D([], [], color="grey", marker=_MARKERS[k % len(_MARKERS)], linestyle="none",
                      label="iterations: the scene's own" if its == "-" else f"iterations {its}")
               for k, its in enumerate(iterations)]
    legend += [Line2D([], [], color="grey", linestyle="-", label="preferAccuracy FALSE"),
               Line2D([], [], color="grey", linestyle="--", label="preferAccuracy TRUE")]
    front = [p for p in points if p["pareto_scene"] and p.get("tie_scene") is None]
    legend.append(ax.scatter([p["cpu_per_sim_s"] for p in front], [max(p["error"], floor) for p in front], s=140,
                             facecolors="none", edgecolors="black", linewidths=1.5, label="Pareto front", zorder=3))
    for p in front:
        ax.annotate(p["dt_label"], (p["cpu_per_sim_s"], max(p["error"], floor)), textcoords="offset points",
                    xytext=(6, 5), fontsize=8)
    if uncertainty:
        legend.append(ax.axhline(uncertainty, color="black", linestyle=":", linewidth=1,
                                 label=f"the reference's uncertainty ({uncertainty:.3g} {unit}): errors below it tie"))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("CPU s in the engine's steps per simulated s (median, spread)", fontsize=9)
    ax.set_ylabel(f"error ({unit})" if unit else "error", fontsize=9)
    ax.tick_params(labelsize=8)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(handles=legend, labels=[_wrapped(h.get_label()) for h in legend], fontsize=8, loc="upper left",
              bbox_to_anchor=(1.01, 1.0))
    return " (0 drawn at the floor)" if any(p["error"] == 0 for p in points) else ""


def _its(p: dict) -> tuple:
    """Iterations values in order, the scene's own ('-') last."""
    return (p["iterations"] is None, p["iterations"] or 0)


def _wrapped(label: str) -> str:
    return textwrap.fill(label, 24)

"""Plots of results, as PNG files (matplotlib's Agg backend: no display needed)."""

from __future__ import annotations

import io
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

from x3d_core import atomic  # noqa: E402

from .sweep_tables import NO_RESULTS, measured, variation  # noqa: E402
from .text import plotted  # noqa: E402

_MARKERS = "os^Dv<>p*h"
TITLE_WIDTH = 80  # characters a title line holds at 10 points over the axes (the legend beside them): longer lines were cut off


def sweep_plot(doc: dict, scene: str, path: str) -> None:
    """Error against CPU time in the engine's steps per simulated second for one scene of a sweep (sweep.json's
    document), both axes logarithmic: a colour per backend, a line per (iterations,
    preferAccuracy) through its steps in order, the scene's Pareto front ringed in black, and
    a common reference's uncertainty as a dotted line (errors below it tie). Points without
    an error (refused, crashed...) are not drawn; errors of exactly 0 are drawn at a tenth of
    the smallest nonzero one, and the title says so. A scene with no point to draw gets a
    plot that says so (log axes of nothing are matplotlib's error)."""
    info = next(s for s in doc["scenes"] if s["name"] == scene)
    points = measured([p for p in doc["points"] if p["scene"] == scene])
    fig, ax = plt.subplots(figsize=(10, 6))
    method = info.get("reference_method")
    title = f"{scene}: {info['reference']}" + (f" ({info['reference_backend']}, {method})" if method else "")
    title += f", {info['quantity']}"
    if points:
        title += _draw(ax, doc, points, info["unit"], info.get("reference_error"))
    else:
        ax.axis("off")
        ax.text(0.5, 0.5, f"no results: {NO_RESULTS}", ha="center", va="center", transform=ax.transAxes)
    ax.set_title(textwrap.fill(plotted(title), TITLE_WIDTH), fontsize=10)
    fig.tight_layout()
    png = io.BytesIO()
    fig.savefig(png, format="png", dpi=110)
    atomic.write_bytes(path, png.getvalue())
    plt.close(fig)


def _draw(ax, doc: dict, points: list[dict], unit: str, uncertainty: float | None) -> str:
    """The points on log axes, and the reference's uncertainty where it has one above 0; what
    the title adds (the floor that errors of 0 are drawn at)."""
    nonzero = [p["error"] for p in points if p["error"] > 0]
    floor = min(nonzero) / 10 if nonzero else 1e-16
    for b, backend in enumerate(doc["backends"]):  # a backend keeps its colour in every plot
        mine = [p for p in points if p["backend"] == backend]
        for v, var in enumerate(dict.fromkeys(variation(p) for p in mine)):
            line = sorted((p for p in mine if variation(p) == var), key=lambda p: -p["dt"])
            its, acc = var.split(" | ")
            x = [p["cpu_per_sim_s"] for p in line]
            spread = [[m - (p.get("cpu_low") or m) for m, p in zip(x, line)],
                      [(p.get("cpu_high") or m) - m for m, p in zip(x, line)]]
            ax.errorbar(x, [max(p["error"], floor) for p in line], xerr=spread, color=f"C{b}",
                        marker=_MARKERS[v % len(_MARKERS)], linestyle="--" if acc == "TRUE" else "-",
                        label=f"{backend} it={its} acc={acc}", alpha=0.8, capsize=2)
    front = [p for p in points if p["pareto_scene"] and p.get("tie_scene") is None]
    ax.scatter([p["cpu_per_sim_s"] for p in front], [max(p["error"], floor) for p in front], s=180,
               facecolors="none", edgecolors="black", linewidths=1.5, label="Pareto front (all backends)", zorder=3)
    for p in front:
        ax.annotate(p["dt_label"], (p["cpu_per_sim_s"], max(p["error"], floor)), textcoords="offset points",
                    xytext=(6, 6), fontsize=8)
    if uncertainty:
        ax.axhline(uncertainty, color="black", linestyle=":", linewidth=1,
                   label=f"the reference's uncertainty ({uncertainty:.3g} {unit}): errors below it tie")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("CPU time in the engine's steps per simulated second (s), median of the repeats and spread")
    ax.set_ylabel(f"error ({unit})" if unit else "error")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="center left", bbox_to_anchor=(1.01, 0.5))
    return " (0 drawn at the floor)" if any(p["error"] == 0 for p in points) else ""

"""Plots of results, as PNG files (matplotlib's Agg backend: no display needed)."""

from __future__ import annotations

import io

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

from x3d_core import atomic  # noqa: E402

from .sweep_tables import variation  # noqa: E402

_MARKERS = "os^Dv<>p*h"


def sweep_plot(doc: dict, scene: str, path: str) -> None:
    """Error against wall time per simulated second for one scene of a sweep (sweep.json's
    document), both axes logarithmic: a colour per backend, a line per (iterations,
    preferAccuracy) through its steps in order, the scene's Pareto front ringed in black.
    Points without an error (refused, crashed...) are not drawn; errors of exactly 0 are
    drawn at a tenth of the smallest nonzero one, and the title says so."""
    info = next(s for s in doc["scenes"] if s["name"] == scene)
    points = [p for p in doc["points"] if p["scene"] == scene and p["error"] is not None
              and p["wall_per_sim_s"] is not None]
    nonzero = [p["error"] for p in points if p["error"] > 0]
    floor = min(nonzero) / 10 if nonzero else 1e-16
    fig, ax = plt.subplots(figsize=(9, 6))
    for b, backend in enumerate(doc["backends"]):  # a backend keeps its colour in every plot
        mine = [p for p in points if p["backend"] == backend]
        for v, var in enumerate(dict.fromkeys(variation(p) for p in mine)):
            line = sorted((p for p in mine if variation(p) == var), key=lambda p: -p["dt"])
            its, acc = var.split(" | ")
            ax.plot([p["wall_per_sim_s"] for p in line], [max(p["error"], floor) for p in line],
                    color=f"C{b}", marker=_MARKERS[v % len(_MARKERS)], linestyle="--" if acc == "TRUE" else "-",
                    label=f"{backend} it={its} acc={acc}", alpha=0.8)
    front = [p for p in points if p["pareto_scene"]]
    ax.scatter([p["wall_per_sim_s"] for p in front], [max(p["error"], floor) for p in front], s=180,
               facecolors="none", edgecolors="black", linewidths=1.5, label="Pareto front (all backends)", zorder=3)
    for p in front:
        ax.annotate(p["dt_label"], (p["wall_per_sim_s"], max(p["error"], floor)), textcoords="offset points",
                    xytext=(6, 6), fontsize=7)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time per simulated second (s)")
    unit = f" ({info['unit']})" if info["unit"] else ""
    ax.set_ylabel(f"error{unit}")
    zeros = " (0 drawn at the floor)" if any(p["error"] == 0 for p in points) else ""
    ax.set_title(f"{scene}: {info['reference']}, {info['quantity']}{zeros}", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    if points:
        ax.legend(fontsize=6, loc="center left", bbox_to_anchor=(1.01, 0.5))
    fig.tight_layout()
    png = io.BytesIO()
    fig.savefig(png, format="png", dpi=110)
    atomic.write_bytes(path, png.getvalue())
    plt.close(fig)

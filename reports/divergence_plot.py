"""How far two runs part over time, as a PNG: the max over bodies of each pair's position and
orientation divergence per frame (`x3drbp compare`'s series), with the thresholds.

Reads a conformance.results.Comparison (or its JSON, through Comparison.from_json); runs
nothing. matplotlib is imported here alone (its Agg canvas, no display and no pyplot state),
so only a command that asks for a plot pays for it. The same comparison gives the same bytes:
the PNG carries no software version or date.
"""

from __future__ import annotations

import io
import os

import numpy as np
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from conformance.results import ORIENTATION, POSITION, Comparison, Divergence, PairComparison, dt_label
from x3d_core import atomic

from .text import num, plotted

FLOOR = 1e-16  # a log axis has no 0: divergences below this (rounding, or none) are drawn at it
SIZE, DPI = (9.0, 5.0), 100  # inches, dots per inch: 900 x 500 px
_PANELS = ((POSITION, "position", "m"), (ORIENTATION, "orientation", "rad"))


def _drawn(p: PairComparison) -> bool:
    """Whether the pair has a series to draw: a body and a frame time in common."""
    return bool(p.position.frame_max.size)


def _panel(ax: Axes, pairs: list[PairComparison], quantity: str, label: str, unit: str, threshold: float) -> None:
    clipped = False
    for k, p in enumerate(pairs):
        d: Divergence = getattr(p, quantity)
        clipped |= bool((d.frame_max < FLOOR).any())
        # each pair thinner than the one before: pairs that agree (two engines against a third) stay visible
        ax.plot(p.times, np.maximum(d.frame_max, FLOOR), color=f"C{k % 10}", linewidth=max(2.4 - 0.4 * k, 0.8),
                label=f"{p.a} vs {p.b}")
    ax.axhline(threshold, color="black", linestyle="--", linewidth=1.0,
               label=f"{label} threshold {num(threshold)} {unit}")
    ax.set_yscale("log")
    ax.set_ylabel(f"{label} divergence ({unit}),\nmax over bodies"
                  + (f"\n(below {FLOOR:g} drawn at it)" if clipped else ""), fontsize=8)
    ax.grid(True, which="major", alpha=0.3)


def figure(comparison: Comparison) -> Figure:
    """Two panels over time, position (m) above orientation (rad), both on log axes: a line per
    pair that shares a body and a frame ("a vs b"), each frame's max over the bodies, and the
    comparison's thresholds dashed; with no pair to draw, a figure that says so (log axes of
    nothing are matplotlib's error)."""
    c = comparison
    fig = Figure(figsize=SIZE, dpi=DPI, layout="constrained")
    FigureCanvasAgg(fig)
    pairs = [p for p in c.pairs if _drawn(p)]
    title = f"{plotted(os.path.basename(c.scene))}: divergence over time (dt {dt_label(c.dt)} s, {c.frame_rate:g} frames/s)"
    if pairs:
        axes = fig.subplots(2, 1, sharex=True)
        for ax, (quantity, label, unit) in zip(axes, _PANELS):
            _panel(ax, pairs, quantity, label, unit, c.thresholds[quantity])
        axes[0].set_title(title, fontsize=10)
        axes[-1].set_xlabel("time (s)")
        (lines, labels), (below, below_labels) = (ax.get_legend_handles_labels() for ax in axes)
        # every pair's line, then both thresholds (the last line of each panel)
        fig.legend(lines + below[-1:], labels + below_labels[-1:], loc="outside right upper", fontsize=8)
    else:
        ax = fig.subplots()
        ax.axis("off")
        why = "no pair ran" if not c.pairs else "no pair shares a body and a frame time"
        ax.text(0.5, 0.5, why, ha="center", va="center", transform=ax.transAxes)
        ax.set_title(title, fontsize=10)
    return fig


def divergence_plot(comparison: Comparison, path: str) -> None:
    """The figure as a PNG of SIZE at DPI, written atomically (x3d_core.atomic), without the
    software tag matplotlib adds: the same comparison gives the same bytes."""
    png = io.BytesIO()
    figure(comparison).savefig(png, format="png", dpi=DPI, metadata={"Software": None})
    atomic.write_bytes(path, png.getvalue())

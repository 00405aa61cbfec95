"""How far two runs part over time, as a PNG: small multiples, one panel per pair of backends in a
triangle (row against column, as a distance table reads), each with the max over bodies of the
pair's position and orientation divergence per frame (`x3drbp compare`'s series), the
thresholds, and when the pair first passes one. One panel of 15 or 21 pairs drawn over each
other, in colours that repeat, could not be read.

Reads a conformance.results.Comparison (or its JSON, through Comparison.from_json); runs
nothing. matplotlib is imported here alone (its Agg canvas, no display and no pyplot state),
when a plot is drawn, so only a command that draws one pays for it. The same comparison gives
the same bytes: the PNG carries no software version or date, only its key (plot_key.py), and
it is not drawn again where the PNG there holds the same key.
"""

from __future__ import annotations

import io
import os
from typing import TYPE_CHECKING

import numpy as np

from conformance.results import ORIENTATION, POSITION, Comparison, Divergence, PairComparison, dt_label
from x3d_core.files import atomic

from . import plot_key
from .text import num, plotted

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

# a log axis has no 0: divergences this far below the smaller threshold (rounding, or none) are drawn
# there, at the panel's foot; what matters, when a pair passes a threshold and how far, keeps the room
FLOOR = 1e-6
DPI = 100
PANEL = (1.75, 1.3)  # inches a pair's panel takes: 175 x 130 px, so 7 backends' 21 pairs make 1000 x 880 px
MARGIN = (1.0, 1.1)  # inches around the panels: the backends' names, the axes' labels, the title
SMALLEST = (6.0, 4.4)  # inches: a figure of one pair or two, the legend below them, or of none
_QUANTITIES = ((POSITION, "position", "m", "C0"), (ORIENTATION, "orientation", "rad", "C3"))
WITHIN_SHADE = "#eef6ee"  # the panel of a pair that stays within both thresholds for the whole run


def _drawn(p: PairComparison) -> bool:
    """Whether the pair has a series to draw: a body and a frame time in common."""
    return bool(p.position.frame_max.size)


def backends(c: Comparison) -> list[str]:
    """The compared backends in the comparison's order (that of its pairs)."""
    return list(dict.fromkeys(name for p in c.pairs for name in (p.a, p.b)))


def parted(p: PairComparison) -> float | None:
    """When the pair first passes either threshold (s), or None."""
    times = [d.first_over.time for d in (p.position, p.orientation) if d.first_over is not None]
    return min(times) if times else None


def floor(c: Comparison) -> float:
    """Where a divergence too small to matter is drawn: FLOOR times the smaller threshold."""
    return FLOOR * min(c.thresholds[q] for q, _, _, _ in _QUANTITIES)


def size(n: int) -> tuple[float, float]:
    """The figure's size (inches) for n backends: a panel per cell of the (n-1) x (n-1) triangle."""
    k = max(n - 1, 1)
    return (max(MARGIN[0] + PANEL[0] * k, SMALLEST[0]), max(MARGIN[1] + PANEL[1] * k, SMALLEST[1]))


def _panel(ax: Axes, p: PairComparison, c: Comparison) -> None:
    """One pair: both quantities against time on a log axis, each threshold dashed in its
    quantity's colour, and when the pair parts (or that it does not)."""
    if not _drawn(p):
        ax.text(0.5, 0.5, "no body and frame\nin common", ha="center", va="center", fontsize=8,
                transform=ax.transAxes)
        return
    for quantity, _, _, colour in _QUANTITIES:
        d: Divergence = getattr(p, quantity)
        ax.plot(p.times, np.maximum(d.frame_max, floor(c)), color=colour, linewidth=1.1)
        ax.axhline(c.thresholds[quantity], color=colour, linestyle="--", linewidth=0.8)
    when = parted(p)
    if when is None:
        ax.set_facecolor(WITHIN_SHADE)
    ax.text(0.97, 0.05, f"parts at {when:.3g} s" if when is not None else f"within for {c.duration:g} s",
            ha="right", va="bottom", fontsize=8, transform=ax.transAxes,
            bbox={"facecolor": "white", "alpha": 0.8, "edgecolor": "none", "pad": 1})


def figure(comparison: Comparison) -> Figure:
    """The triangle of pairs: row i against column j for i < j, sharing both axes (time; log
    divergence, m or rad); each row's first panel names its row and carries the axes' ticks,
    the top row names the columns; the legend (the two quantities, the thresholds, the floor)
    in the empty corner below. With no pair, a figure that says so (log axes of nothing are
    matplotlib's error)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    c = comparison
    names = backends(c)
    n = len(names)
    title = (f"{plotted(os.path.basename(c.scene))}: divergence over time, each pair of backends\n"
             f"(dt {dt_label(c.dt)} s, {c.frame_rate:g} frames/s)")
    fig = Figure(figsize=size(n), dpi=DPI, layout="constrained")
    FigureCanvasAgg(fig)
    if not any(_drawn(p) for p in c.pairs):
        ax = fig.subplots()
        ax.axis("off")
        why = "no pair ran" if not c.pairs else "no pair shares a body and a frame time"
        ax.text(0.5, 0.5, why, ha="center", va="center", transform=ax.transAxes)
        ax.set_title(title, fontsize=10)
        return fig
    k = n - 1
    grid = fig.subplots(k, k, sharex=True, sharey=True, squeeze=False)
    by = {frozenset((p.a, p.b)): p for p in c.pairs}
    for i in range(k):
        for j in range(k):
            ax = grid[i][j]
            pair = by.get(frozenset((names[i], names[j + 1]))) if j >= i else None
            if pair is None:
                ax.axis("off")
                continue
            ax.set_yscale("log")
            ax.grid(True, which="major", alpha=0.3)
            ax.tick_params(labelsize=7, labelleft=j == i, labelbottom=j == i)
            _panel(ax, pair, c)
            if i == 0:
                ax.set_title(names[j + 1], fontsize=9, fontweight="bold")
            if j == i:
                ax.set_ylabel(names[i], fontsize=9, fontweight="bold")
                ax.set_xlabel("time (s)", fontsize=7)
    fig.suptitle(title, fontsize=10)
    handles = [Line2D([], [], color=colour, linewidth=1.5, label=f"{label} divergence ({unit}), max over bodies")
               for _, label, unit, colour in _QUANTITIES]
    handles += [Line2D([], [], color=colour, linestyle="--", linewidth=1,
                       label=f"{label} threshold {num(c.thresholds[quantity])} {unit}")
                for quantity, label, unit, colour in _QUANTITIES]
    handles.append(Patch(facecolor=WITHIN_SHADE, edgecolor="grey", label="shaded: within both for the whole run"))
    note = f"row against column; below {num(floor(c))}: drawn at it"
    grid[0][0].set_ylim(bottom=floor(c) / 2)
    if k > 2:  # the empty corner under the triangle: from 4 backends, a row of empty panels holds it
        fig.legend(handles=handles, loc="lower left", bbox_to_anchor=(0.01, 0.01), fontsize=8, title=note,
                   title_fontsize=8, frameon=False)
    else:
        fig.legend(handles=handles, loc="outside lower center", ncols=2, fontsize=8, title=note, title_fontsize=8)
    return fig


def key(c: Comparison) -> str:
    """The digest of all that figure() draws of a comparison (plot_key.py): the scene's name,
    step, frame rate, duration and thresholds, and each pair's backends, times, per-frame
    maxima and first crossings; not the rest of it (the runs, the per-body series)."""
    data: list = [[os.path.basename(c.scene), c.dt, c.frame_rate, c.duration, c.thresholds]]
    for p in c.pairs:
        data.append([p.a, p.b, *[None if d.first_over is None else d.first_over.time
                                 for d in (p.position, p.orientation)]])
        data += [np.asarray(p.times, dtype=np.float64), np.asarray(p.position.frame_max, dtype=np.float64),
                 np.asarray(p.orientation.frame_max, dtype=np.float64)]
    return plot_key.digest(data, (__name__, num.__module__, dt_label.__module__))


def divergence_plot(comparison: Comparison, path: str) -> None:
    """The figure as a PNG of SIZE at DPI, written atomically (x3d_core.files.atomic), without the
    software tag matplotlib adds: the same comparison gives the same bytes. Not drawn again
    where the PNG at path holds the same key (plot_key.py: what it draws is unchanged)."""
    drawn_from = key(comparison)
    if plot_key.drawn(path, drawn_from):
        return
    png = io.BytesIO()
    figure(comparison).savefig(png, format="png", dpi=DPI, metadata=plot_key.metadata(drawn_from))
    atomic.write_bytes(path, png.getvalue())

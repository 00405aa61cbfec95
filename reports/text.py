"""Number and cell formatting shared by the text and markdown reports."""

from __future__ import annotations

import math

from conformance.results import Measure


def num(x: float | None) -> str:
    """Three significant digits; '-' for no value."""
    if x is None:
        return "-"
    if not math.isfinite(x):
        return str(x)
    return "0" if x == 0 else f"{x:.3g}"


def escape(text: str) -> str:
    """Text safe inside a markdown table cell."""
    return text.replace("|", "\\|").replace("\n", " ")


def basis_cell(m: Measure) -> str:
    """A measure's basis in a table: the spec's words it enforces, or the convention it checks."""
    if m.basis is None:
        return "spec (not quoted)"
    return f"{m.basis.kind}: {escape(m.basis.text)}"

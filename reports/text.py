"""Number and cell formatting shared by the text and markdown reports."""

from __future__ import annotations

import math


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

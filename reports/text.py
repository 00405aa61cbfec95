"""Number and text formatting shared by the text and markdown reports.

Every renderer writes text that came from a user's file (its name, its DEF names, the
reasons that quote them) through escape() and link(): report.md becomes index.html through
Python-Markdown, which passes raw HTML and javascript: links through as they are.
"""

from __future__ import annotations

import html
import math
import re
import urllib.parse
from collections.abc import Callable

from conformance.results import EnergyGrowth, Measure, grade
from x3d_core.files.paths import printable

_MARKDOWN = re.compile(r"([\\`*_\[\]#|])")  # code spans, emphasis, links and images, headings, table cells


def num(x: float | None) -> str:
    """Three significant digits; '-' for no value."""
    if x is None:
        return "-"
    if not math.isfinite(x):
        return str(x)
    return "0" if x == 0 else f"{x:.3g}"


def one_line(text: str) -> str:
    """Text on one line: a line break in a name would end a table row, a list item or a code block."""
    return " ".join(text.splitlines())


def escape(text: str) -> str:
    """Text as text in markdown, anywhere on a line (a table cell, a heading, a list item, a link's
    words): HTML's specials as entities, markdown's backslash-escaped, its lines joined, and what
    does not print (a terminal escape, a byte that is not UTF-8) as its escape (printable())."""
    return _MARKDOWN.sub(r"\\\1", html.escape(printable(one_line(text)), quote=False))


# a file in a run's temporary folder (tempfile's x3drbp-sweep-k2j3h4l5/scene.x3d): gone before any
# reader follows it; at the head of a reason, as its subject, with the line it names in that copy
_TEMPORARY = r"(?:/[^/\s'\"]+)*/x3drbp-[a-z_]+-[a-z0-9_]{8}(?:/[^/\s'\":,;)]+)*"
_TEMPORARY_SUBJECT = re.compile(rf"^{_TEMPORARY}(?::\d+)*: ")
_TEMPORARY_PATH = re.compile(_TEMPORARY)


def untemporary(text: str) -> str:
    """A reason as it reads once its run's temporary files are deleted: a path into them dropped
    where it heads the reason ("/tmp/x3drbp-sweep-.../scene.x3d: blew up at t=2" is "blew up at
    t=2"), elsewhere its file's name alone, said to be temporary."""
    text = _TEMPORARY_SUBJECT.sub("", text)
    return _TEMPORARY_PATH.sub(lambda m: f"{m.group(0).rsplit('/', 1)[1]} (temporary)", text)


def plotted(text: str) -> str:
    """Text as text in a matplotlib title or label: each $ escaped, or a name such as
    `a$x^2$.x3d` is set as mathematics and `a$\\frac$.x3d` stops the plot with a parse error;
    what does not print as its escape (printable(): a file name's byte that is not UTF-8
    reaches Python as a surrogate, which no font takes: a sweep of `p\\xffq.x3d` stopped at
    its plot's title)."""
    return printable(text).replace("$", r"\$")


def energy_grew(run: str, g: EnergyGrowth) -> str:
    """One line for a run (its words, markdown already) whose mechanical energy grew with nothing
    doing work on its scene (conformance/analyses/energy.py)."""
    return (f"{run}: mechanical energy grew with nothing doing work on the scene: {num(g.start)} J at the start, "
            f"{num(g.peak)} J at most (t = {num(g.peak_at)} s); past the start by more than its bound, "
            f"{num(g.bound)} J, from t = {num(g.rose_at)} s")


def link(path: str, text: str | None = None) -> str:
    """A markdown link to a relative path (its words the path's own unless given): the target
    percent-encoded, so a name such as `javascript:x` or `a) b` stays a file's name (a byte
    that is not UTF-8 as itself, %FF)."""
    return f"[{escape(path if text is None else text)}]({urllib.parse.quote(path, errors='surrogateescape')})"


def basis_cell(m: Measure, text: Callable[[str], str] = escape) -> str:
    """A measure's basis in a table: the clause's words it enforces with their edition, the
    convention or description it checks, or the accuracy it grades; its words through `text`
    (escape() for markdown that becomes HTML, printable() for a terminal)."""
    if m.basis is None:
        return "spec (not quoted)"
    further = "".join(f" Also {text(q)}" for q in m.basis.also)
    return f"{m.basis.label()}: {text(m.basis.text)}{further}"


def grade_cell(m: Measure) -> str:
    """A measure's accuracy grade in a table: its bound and the error over it ('-': none graded)."""
    if m.accuracy is None:
        return "-"
    bound = m.tolerance if m.graded else m.bound
    return f"{grade(m.accuracy)} ({num(bound)}{' ' + m.unit if m.unit else ''})"

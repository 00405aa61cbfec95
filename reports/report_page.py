"""The report's page: DIR/report.md and DIR/index.html from what `x3drbp report` wrote in DIR.

Reads results only. Each section is the markdown its own command rendered (headings moved
one level down), in the order a reader asks: do the engines conform, where do they part,
what does speed cost in error, what survives the hard cases, and what each engine
declares against what was measured. The HTML is that markdown through Python-Markdown,
plots shown inline, in one self-contained page beside its PNGs.
"""

from __future__ import annotations

import glob
import html
import json
import os
import re

import markdown as md

from conformance.results import CONVENTIONS, PASS, UNSUPPORTED, Comparison
from x3d_core import atomic

from .compare_text import render as render_comparison
from .text import escape
from .x_ite_text import render as render_x_ite

_STYLE = """
body { font: 15px/1.45 system-ui, sans-serif; margin: 2em auto; max-width: 82em; padding: 0 1em; color: #222; }
table { border-collapse: collapse; margin: 0.6em 0 1.2em; font-size: 13px; }
th, td { border: 1px solid #ccc; padding: 3px 7px; vertical-align: top; }
th { background: #f3f3f3; }
tr:nth-child(even) td { background: #fafafa; }
code { background: #f3f3f3; padding: 0 3px; }
img { max-width: 100%; border: 1px solid #ddd; }
h1 { border-bottom: 2px solid #444; } h2 { border-bottom: 1px solid #aaa; margin-top: 2em; }
"""
_MARK = {"native": "native", "approximate": "approx.", "unsupported": "unsupported"}


def _read(path: str) -> str | None:
    if not os.path.exists(path):
        return None
    with open(path, encoding="utf-8") as f:
        return f.read()


def _section(text: str, prefix: str = "") -> str:
    """A command's markdown as a section's body: its title line dropped, its headings one
    level down, its relative links into the step's folder."""
    lines = text.strip().splitlines()
    if lines and lines[0].startswith("# "):
        lines = lines[1:]
    text = re.sub(r"^(#+) ", r"#\1 ", "\n".join(lines), flags=re.M)
    if prefix:
        text = re.sub(r"\]\((?!https?:|/|#)([^)]+)\)", lambda m: f"]({prefix}/{m.group(1)})", text)
    return text.strip() + "\n"


def _cell(cell: dict) -> str:
    verdicts = [c["verdict"] for c in cell["cases"]]
    failing = [c["case"] for c in cell["cases"] if c["verdict"] not in (PASS, CONVENTIONS, UNSUPPORTED)]
    other = [c["case"] for c in cell["cases"] if c["verdict"] == CONVENTIONS]
    parts = [f"{verdicts.count(PASS)} pass"]
    if other:
        parts.append(f"{len(other)} conforming in other conventions ({', '.join(other)})")
    if failing:
        parts.append(f"{len(failing)} not ({', '.join(failing)})")
    if UNSUPPORTED in verdicts:
        parts.append(f"{verdicts.count(UNSUPPORTED)} refused")
    text = f"{_MARK[cell['support']]}: {', '.join(parts)}"
    if cell["support"] == "native" and failing:
        text = f"**{text}**"  # declared native, measured failing: a finding
    return escape(text)


def _features(data: dict) -> str:
    backends = list(data["declared"])
    lines = ["## Declared against measured", "",
             "Per feature that a conformance case exercises: what each backend declares (`x3drbp backends "
             "--features` gives the reasons) and the verdicts there of the cases exercising it: pass, conforming "
             "in other conventions (only convention measures fail: named), not (fail, blew up, crashed, timed "
             "out, error: named) and refused (the scene needs something "
             "else the backend lacks). **Bold**: declared native yet a case does not pass.", "",
             "| feature | " + " | ".join(backends) + " |", "|---|" + "---|" * len(backends)]
    for row in data["features"]:
        lines.append(f"| {escape(row['feature'])} | " + " | ".join(_cell(row["backends"][b]) for b in backends) + " |")
    lines += ["", "Declared over the whole feature table (features no case exercises included):", "",
              "| backend | native | approximate | unsupported |", "|---|---:|---:|---:|"]
    lines += [f"| {b} | {d['native']} | {d['approximate']} | {d['unsupported']} |" for b, d in data["declared"].items()]
    return "\n".join(lines) + "\n"


def _comparisons(out: str) -> str:
    parts = ["## Where the backends part", "",
             "Each bundled example scene on every backend, every pair compared (`x3drbp compare`): "
             "position and orientation divergence, when it first passes the threshold and which bodies, "
             "the worst joint output difference, and each run's real-time factor."]
    for path in sorted(glob.glob(os.path.join(out, "compare", "*.json"))):
        with open(path, encoding="utf-8") as f:
            comparison = Comparison.from_json(json.load(f))
        parts += ["", f"### {os.path.basename(comparison.scene)}", "", _section(render_comparison(comparison))]
        rrd = os.path.basename(os.path.splitext(path)[0] + ".rrd")
        parted = any(d.first_over is not None for p in comparison.pairs for d in (p.position, p.orientation))
        if parted and os.path.exists(os.path.join(out, "compare", rrd)):
            parts.append(f"Where they part, as a rerun recording: [{rrd}](compare/{rrd}) (open it with `rerun {rrd}`).")
    return "\n".join(parts) + "\n"


def _header(meta: dict) -> str:
    t = meta["timings_s"]
    steps = ", ".join(f"{k} {v:g} s" for k, v in t.items() if k != "total")
    failed = f" Steps that could not run: {', '.join(meta['failed'])} (see logs/)." if meta["failed"] else ""
    return "\n".join([
        "# x3drbp report", "",
        f"Generated {meta['generated']} on {meta['cpus']} CPUs in {t['total']:g} s ({steps}).{failed}", "",
        "Backends: " + "; ".join(f"{b} {v}" for b, v in meta["backends"].items()), "",
        "Sections: [conformance](#conformance), [comparisons](#where-the-backends-part), "
        "[speed against error](#speed-against-error), [stability](#stability), "
        "[declared against measured](#declared-against-measured)"
        + (", [X_ITE](#x_ite)" if "x_ite" in t else "") + ". Every number comes from the JSON files "
        "beside this page."]) + "\n"


def report_markdown(out: str) -> str:
    with open(os.path.join(out, "report.json"), encoding="utf-8") as f:
        meta = json.load(f)
    parts = [_header(meta)]
    matrix = _read(os.path.join(out, "conformance", "matrix.md"))
    parts.append("## Conformance\n\n" + (_section(matrix, "conformance") if matrix else "Not run.\n"))
    parts.append(_comparisons(out))
    sweep = _read(os.path.join(out, "sweep", "sweep.md"))
    body = _section(sweep, "sweep") if sweep else "Not run (`x3drbp report --quick` leaves it out).\n"
    plots = sorted(glob.glob(os.path.join(out, "sweep", "sweep_*.png")))
    shown = "\n".join(f"![{os.path.basename(p)}](sweep/{os.path.basename(p)})" for p in plots)
    parts.append("## Speed against error\n\n" + body + ("\n" + shown + "\n" if shown else ""))
    stability = _read(os.path.join(out, "stability", "stability.md"))
    parts.append("## Stability\n\n" + (_section(stability, "stability") if stability else "Not run.\n"))
    table = _read(os.path.join(out, "features.json"))
    parts.append(_features(json.loads(table)) if table else "## Declared against measured\n\nNot run.\n")
    x_ite = _read(os.path.join(out, "x_ite", "x_ite.json"))
    if x_ite:  # `x3drbp report --x-ite` only
        matrix_json = _read(os.path.join(out, "conformance", "matrix.json"))
        text = render_x_ite(json.loads(x_ite), json.loads(matrix_json) if matrix_json else None)
        parts.append("## X_ITE\n\n" + _section(text, "x_ite"))
    return "\n".join(parts)


def write_report(out: str) -> str:
    """Writes DIR/report.md and DIR/index.html; returns the page's path."""
    text = report_markdown(out)
    atomic.write_text(os.path.join(out, "report.md"), text)
    body = md.markdown(text, extensions=["tables", "toc"])
    page = os.path.join(out, "index.html")
    atomic.write_text(page, "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'>"
                            f"<title>{html.escape('x3drbp report')}</title><style>{_STYLE}</style></head>\n"
                            f"<body>\n{body}\n</body></html>\n")
    return page

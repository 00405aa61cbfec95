"""The report's page: DIR/report.md and DIR/index.html from what `x3drbp report` wrote in DIR.

Reads results only. The page leads with the answers (reports/summary.py: what conforms,
which backend and step for each kind of scene, the findings), then each section is the
markdown its own command rendered (headings moved one level down), the long tables
folded, each comparison's plot first under its heading and each sweep's front beside its
plot: do the engines conform, which backend for which scene, where do they part, what does
speed cost in error, what survives the hard cases, and what each engine declares against
what was measured. The HTML is that markdown through Python-Markdown, in one page beside its
PNGs, each shown where it is read and linked to itself at full size; every link in it points
at a file under DIR. No table runs off a page 900 px wide (tests/test_report_layout.py lays
the page out in Chromium): a table's words break where a name's parts meet (breakable).
"""

from __future__ import annotations

import glob
import html
import json
import os
import re
import urllib.parse

import markdown as md

from conformance.results import CONVENTIONS, PASS, UNSUPPORTED, Comparison
from x3d_core.files import atomic

from .advice_text import markdown as render_advice
from .compare_text import render as render_comparison
from .summary import answers, scene_name, scopes, yours
from .sweep_tables import markdown as render_sweep, plot as sweep_plot, scene_parts
from .text import escape, link
from .x_ite_text import render as render_x_ite

DIVERGENCE = ".divergence.png"  # beside each compare/SCENE.json, its divergence plot
EXTENSIONS = ["tables", "toc", "md_in_html", "fenced_code"]  # Python-Markdown's, for index.html

_STYLE = """
body { font: 15px/1.45 system-ui, sans-serif; margin: 2em auto; max-width: 82em; padding: 0 1em; color: #222; }
table { border-collapse: collapse; margin: 0.6em 0 1.2em; font-size: 12px; }
th, td { border: 1px solid #ccc; padding: 3px 5px; vertical-align: top; }
th { background: #f3f3f3; }
tr:nth-child(even) td { background: #fafafa; }
code { background: #f3f3f3; padding: 0 3px; }
pre { white-space: pre-wrap; overflow-wrap: break-word; font-size: 12px; }
img { max-width: 100%; height: auto; border: 1px solid #ddd; }
h1 { border-bottom: 2px solid #444; } h2 { border-bottom: 1px solid #aaa; margin-top: 2em; }
details { margin: 0.4em 0 1em; } summary { cursor: pointer; color: #245; }
.side { display: flex; flex-wrap: wrap; gap: 1.2em; align-items: flex-start; }
.side > div { flex: 1 1 30em; min-width: min-content; } .side > p { flex: 1 1 28em; margin: 0; }
"""  # no box scrolls or clips a table: a table too wide to stand beside its plot pushes the plot below
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
    if prefix:  # a link's "](", not an escaped "\](" in a name
        text = re.sub(r"(?<!\\)\]\((?!https?:|/|#)([^)]+)\)", lambda m: f"]({prefix}/{m.group(1)})", text)
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
    text = escape(f"{_MARK[cell['support']]}: {', '.join(parts)}")
    return f"**{text}**" if cell["support"] == "native" and failing else text  # declared native, failing: a finding


def _features(data: dict) -> str:
    backends = list(data["declared"])
    lines = ["Per feature that a conformance case exercises: what each backend declares (`x3drbp backends "
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


def _folded(summary: str, body: str) -> str:
    """Markdown folded under a summary line (open it to read)."""
    return f'<details markdown="1"><summary>{html.escape(summary, quote=False)}</summary>\n\n{body.strip()}\n\n</details>\n'


def _picture(image: str, alt: str) -> str:
    """A plot on the page, linked to itself: a click shows it at full size."""
    return f"[!{link(image, alt)}]({urllib.parse.quote(image, errors='surrogateescape')})"


def _beside(body: str, image: str, alt: str) -> str:
    """Markdown with its plot beside it (below it on a narrow screen)."""
    return (f'<div class="side" markdown="1">\n<div markdown="1">\n\n{body.strip()}\n\n</div>\n\n'
            f'{_picture(image, alt)}\n\n</div>\n')


def comparisons(out: str) -> list[tuple[str, Comparison]]:
    """Every compare/SCENE.json in DIR, by file name: (its path without .json, the comparison)."""
    found = []
    for path in sorted(glob.glob(os.path.join(out, "compare", "*.json"))):
        with open(path, encoding="utf-8") as f:
            found.append((os.path.splitext(path)[0], Comparison.from_json(json.load(f))))
    return found


def _comparisons(out: str, found: list[tuple[str, Comparison]]) -> str:
    mine = yours(out)
    parts = ["## Where the backends part", "",
             "Each example scene" + (" and each of yours (marked so)" if mine else "") + " on every backend, "
             "every pair compared (`x3drbp compare`): "
             "position and orientation divergence over time (the plot), when it first passes the threshold and "
             "which bodies, the worst joint output difference, and each run's real-time factor (the tables)."]
    for stem, comparison in found:
        name = os.path.basename(stem)
        text = _folded("The tables", _section(render_comparison(comparison)))  # the heading names the scene
        rrd = name + ".rrd"
        parted = any(d.first_over is not None for p in comparison.pairs for d in (p.position, p.orientation))
        if parted and os.path.exists(os.path.join(out, "compare", rrd)):
            text += f"\nWhere they part, as a rerun recording: {link('compare/' + rrd, rrd)} (open it with `rerun`).\n"
        plot = f"compare/{name}{DIVERGENCE}"
        if os.path.exists(os.path.join(out, plot)):  # first, where the reader looks: the tables say it in figures
            text = _picture(plot, f"{name}: divergence over time, each pair of backends") + "\n\n" + text
        parts += ["", f"### {escape(scene_name(comparison.scene, mine))}", "", text]
    return "\n".join(parts) + "\n"


def _sweep(out: str, meta: dict) -> str:
    """Each swept scene (sweep.json): its Pareto front over every backend beside its plot, each
    backend's own front folded under them (long: a row per point), the runs without an error;
    the notes on what is measured folded before them."""
    path = os.path.join(out, "sweep", "sweep.json")
    if not os.path.exists(path):
        return "## Speed against error\n\n" + (_absent(meta, "sweep") if "sweep" in meta.get("failed", ())
                                                else "Not run (`x3drbp report --quick` leaves it out).\n")
    with open(path, encoding="utf-8") as f:
        doc = json.load(f)
    head = _section(render_sweep(doc)).split("\n### ", 1)[0]
    parts = ["## Speed against error", "", _folded("What is measured, and how", head)]
    for scene in doc["scenes"]:
        name, part = scene["name"], scene_parts(doc, scene)
        plot = f"sweep/{sweep_plot(name)}"
        front = "\n".join(part.front)
        parts += [f"### {escape(name)}", "", part.reference, "",
                  _beside(front, plot, f"{name}: error against speed") if os.path.exists(os.path.join(out, plot))
                  else front, ""]
        if part.own:
            parts += [_folded(f"Each backend's own front ({len(part.own) - 2} points)", "\n".join(part.own)), ""]
        if part.missing:
            parts += ["Without an error:", "", *part.missing, ""]
    return "\n".join(parts) + "\n"


def _logs(meta: dict, out: str) -> str:
    steps = [k for k in meta["timings_s"] if k != "total" and os.path.exists(os.path.join(out, "logs", f"{k}.log"))]
    return "Each step's log: " + ", ".join(link(f"logs/{k}.log", k) for k in steps) + "." if steps else ""


def _absent(meta: dict, step: str) -> str:
    """What a section says without its results: that its step failed (a reader must not take a
    failure for a step left out), else that it was not run."""
    if step in meta.get("failed", ()):
        return f"FAILED: the {step} step could not run (report.json's `failed`; the report's stderr or logs/ say why).\n"
    return "Not run.\n"


def _header(meta: dict, out: str) -> str:
    t = meta["timings_s"]
    steps = ", ".join(f"{k} {v:g} s" for k, v in t.items() if k != "total")
    failed = f" Steps that could not run: {', '.join(meta['failed'])} (see their logs)." if meta["failed"] else ""
    yours = f" Your scenes: {', '.join(map(escape, meta['scenes']))}." if meta.get("scenes") else ""
    left = meta.get("left_out") or {}
    yours += (" Left out of every step, as they do not load or simulate nothing: "
              + "; ".join(escape(why) for why in left.values()) + ".") if left else ""
    return "\n".join([
        "# x3drbp report", "",
        f"Generated {meta['generated']} on {meta['cpus']} CPUs in {t['total']:g} s ({steps}).{failed}{yours}", "",
        "Backends: " + "; ".join(f"{b} {v}" for b, v in meta["backends"].items()), "",
        "Sections: [answers](#answers), [conformance](#conformance), "
        "[which backend for which scene](#which-backend-for-which-scene), [comparisons](#where-the-backends-part), "
        "[speed against error](#speed-against-error), [stability](#stability), "
        "[declared against measured](#declared-against-measured)"
        + (", [X_ITE](#x_ite)" if "x_ite" in t else "") + ". Every number comes from the JSON files "
        "beside this page. " + _logs(meta, out)]) + "\n"


def report_markdown(out: str, found: list[tuple[str, Comparison]] | None = None) -> str:
    """The page's markdown; found: the comparisons in out where the caller has read them already."""
    with open(os.path.join(out, "report.json"), encoding="utf-8") as f:
        meta = json.load(f)
    found = comparisons(out) if found is None else found
    parts = [_header(meta, out), answers(out, [c for _, c in found])]
    matrix = _read(os.path.join(out, "conformance", "matrix.md"))
    parts.append("## Conformance\n\n" + (_folded("The matrix: every case on every backend, and why each verdict",
                                                   _section(matrix, "conformance")) if matrix else _absent(meta, "conformance")))
    advice = _read(os.path.join(out, "advice", "advice.json"))
    parts.append("## Which backend for which scene\n\n" + (render_advice(json.loads(advice), scopes=scopes(out))
                                                          if advice else _absent(meta, "advise")))
    parts.append(_comparisons(out, found))
    parts.append(_sweep(out, meta))
    stability = _read(os.path.join(out, "stability", "stability.md"))
    parts.append("## Stability\n\n" + (_folded("The hard cases on every backend, at each step, and why",
                                                _section(stability, "stability")) if stability else _absent(meta, "stability")))
    table = _read(os.path.join(out, "features.json"))
    parts.append("## Declared against measured\n\n" + (_folded("Every feature a case exercises, per backend",
                                                                _features(json.loads(table)))
                                                        if table else _absent(meta, "features")))
    x_ite = _read(os.path.join(out, "x_ite", "x_ite.json"))
    if x_ite:  # `x3drbp report --x-ite` only
        matrix_json = _read(os.path.join(out, "conformance", "matrix.json"))
        text = render_x_ite(json.loads(x_ite), json.loads(matrix_json) if matrix_json else None)
        parts.append("## X_ITE\n\n" + _section(text, "x_ite"))
    return "\n".join(parts)


# where a long name may break across lines: after a _, or a / or . before a letter (not a step's
# 1/240 nor a number's point), and where a lower-case letter meets a capital (suspension|Error)
_JOINS = re.compile(r"_(?=\w)|[/.](?=[A-Za-z])|(?<=[a-z])(?=[A-Z])")
_TEXT = re.compile(r">([^<]+)<")  # the text between two tags (escaped: no < or > inside)


def breakable(page: str) -> str:
    """HTML whose text may break at the joins of a long name (<wbr>: no character copied, nothing
    drawn where it does not break): the names of features, cases, files and engine calls
    (disableCollisionsBetweenLinkedBodies) set a table's narrowest width, and ran the
    conformance, feature and advice tables off a 900 px page. Only text between tags changes;
    an entity (&lt;) holds none of the joins."""
    return _TEXT.sub(lambda m: ">" + _JOINS.sub(lambda j: j.group(0) + "<wbr>", m.group(1)) + "<", page)


_LINK = re.compile(r"""(?:href|src)=["']([^"'#]+)(?:#[^"']*)?["']""")


def dead_links(out: str, page: str) -> list[str]:
    """The page's links (href, src) that point at no file under out: none may (a byte that is
    not UTF-8, %FF, read back as the file name's own, as text.link wrote it)."""
    targets = dict.fromkeys(html.unescape(m.group(1)) for m in _LINK.finditer(page))
    return [t for t in targets if not re.match(r"[a-z][a-z0-9+.-]*:", t)
            and not os.path.exists(os.path.join(out, urllib.parse.unquote(t, errors="surrogateescape")))]


def write_report(out: str) -> str:
    """Writes DIR/report.md and DIR/index.html, and each comparison's divergence plot beside its
    JSON (matplotlib: only where a page is written); returns the page's path. The comparisons,
    per-frame series and all, are read once for both."""
    from .divergence_plot import divergence_plot
    found = comparisons(out)
    for stem, comparison in found:
        divergence_plot(comparison, stem + DIVERGENCE)
    text = report_markdown(out, found)
    atomic.write_text(os.path.join(out, "report.md"), text)
    body = breakable(md.markdown(text, extensions=EXTENSIONS))
    page = os.path.join(out, "index.html")
    atomic.write_text(page, "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'>"
                            f"<title>{html.escape('x3drbp report')}</title><style>{_STYLE}</style></head>\n"
                            f"<body>\n{body}\n</body></html>\n")
    return page

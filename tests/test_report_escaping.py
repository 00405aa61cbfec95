"""What comes from a user's file (its name, its DEF names, the reasons that quote them) is text
on the report's pages, never markup: a scene named `<img src=x onerror=...>.x3d` or
`[x](javascript:...).x3d` must not put an image, a script or a link into index.html or into
report.md rendered by the same markdown package."""

from __future__ import annotations

import html
import json
import os
from urllib.parse import quote

import lxml.html
import markdown as md
import numpy as np
import pytest

from backends import base
from x3drbp import report as R
from conformance.results import BackendRun, Comparison, Crossing, Divergence, JointDifference, PairComparison
from reports import compare_text, validate_text
from reports.report_page import EXTENSIONS, dead_links, report_markdown
from reports.text import escape, link

INSTALLED = [n for n, b in base.available().items() if not isinstance(b, str)]
IMG = "a <img src=x onerror=alert(1)>"
JS = "[x](javascript:alert(1))"
MARKS = "b`tick`|pipe|*star*_under_"
NEWLINE = "c\n<svg onload=alert(3)>"
HOSTILE = [IMG, JS, MARKS, NEWLINE, "e \\[x\\](javascript:alert(6))",
           "d &lt;b&gt; ![i](x.png) <javascript:alert(5)> <script>alert(7)"]  # names: no "/"
DEF = "<img src=y onerror=alert(2)>"  # a joint's DEF, quoted in a refusal
BODY = "[b](javascript:alert(4))*A*"  # a body's DEF, in the tables' cells


def live_markup(page: str) -> list[str]:
    """What in an HTML page could run or fetch: scripts, on* handlers, javascript: links, and
    images other than the report's own plots (PNG files beside it)."""
    found = []
    for el in lxml.html.fromstring(f"<div>{page}</div>").iter():
        if not isinstance(el.tag, str):
            continue
        if el.tag in ("script", "iframe", "object", "embed"):
            found.append(el.tag)
        for name, value in el.attrib.items():
            if name.lower().startswith("on"):
                found.append(f"{el.tag} {name}")
            if name in ("href", "src") and value.strip().lower().startswith("javascript:"):
                found.append(f"{el.tag} {name}={value}")
        if el.tag == "img" and not (el.get("src", "").endswith(".png") and set(el.attrib) <= {"src", "alt"}):
            found.append(f"img {dict(el.attrib)}")
    return found


def text_of(page: str) -> str:
    """The page's text as a reader sees it, white space runs as one space."""
    return " ".join(lxml.html.fromstring(f"<div>{page}</div>").text_content().split())


def shown(name: str) -> str:
    """A name as it reads on a page: its lines joined by one space."""
    return " ".join(name.split())


def rendered(text: str) -> str:
    return md.markdown(text, extensions=EXTENSIONS)


@pytest.mark.parametrize("name", HOSTILE)
def test_escaped_text_is_text_in_a_cell_a_heading_a_list_and_a_link(name):
    text = "\n".join([f"### {escape(name)}", "", "| a | b |", "|---|---|", f"| {escape(name)} | x |", "",
                      f"- why: {escape(name)}", "", f"see {link(name + '.rrd')} and {link('sweep/' + name + '.png')}"])
    page = rendered(text)
    assert live_markup(page) == []
    assert page.count("<tr>") == 2 and page.count("<td>") == 2  # one row, two cells: no cell break
    assert text_of(page).count(shown(name)) == 5
    for href in lxml.html.fromstring(f"<div>{page}</div>").xpath("//a/@href"):
        assert ":" not in href and " " not in href  # relative, percent-encoded


def _comparison(scene: str) -> Comparison:
    def divergence(quantity: str, unit: str) -> Divergence:
        return Divergence(quantity, unit, 1e-3, 0.1, 0.2, 0.5, BODY, Crossing(0.25, [BODY, "B"], [2e-3, 1e-3]))
    pair = PairComparison("bullet", "mujoco", np.zeros(3), [BODY], [f"{BODY} only"], [], divergence("position", "m"),
                          divergence("orientation", "rad"), [JointDifference(DEF, "body1AnchorPoint", "m", 1e-3,
                                                                             0.1, 0.2, 0.5)], [], [f"{DEF}.angle"])
    runs = [BackendRun("bullet", "ran"), BackendRun("mujoco", "ran"),
            BackendRun("ode", "unsupported", f"UniversalJoint {DEF}: axis1 and axis2 are parallel")]
    return Comparison(scene, 1.0, 1 / 240, 60.0, {"position": 1e-3, "orientation": 1e-3}, runs, [pair])


@pytest.mark.parametrize("name", HOSTILE)
def test_compare_tables_keep_scene_and_def_names_as_text(name):
    page = rendered(compare_text.render(_comparison(f"mine/{name}.x3d")))
    assert live_markup(page) == []
    said = text_of(page)
    assert shown(name) in said and f"UniversalJoint {DEF}: axis1 and axis2 are parallel" in said
    assert f"{BODY} 0.002" in said and f"{DEF}.body1AnchorPoint" in said and f"{BODY} only" in said


def test_validate_s_terminal_text_shows_names_as_they_are_and_control_characters_as_escapes():
    """`x3drbp validate` writes to a terminal, never to a page: `<` read `&lt;` there and `_` read
    `\\_`; a name's escape sequence or newline still prints as its escape (printable())."""
    from conformance.results import Settings, TraceComparison, Validation
    c = _comparison(f"{IMG}.x3d")
    trace = TraceComparison(f"{JS}\x1b[2J\n.csv", Settings(1.0, 1 / 240), c.runs, {"mujoco": c.pairs[0]})
    text = validate_text.render(Validation(f"{IMG}.x3d", [f"{MARKS}.csv"], c.thresholds, None, [trace]))
    assert f"# x3drbp validate {IMG}.x3d\n" in text and f"Traces: {MARKS}.csv;" in text
    assert f"## {JS}\\x1b[2J\\n.csv against the backends" in text and "\x1b" not in text
    assert f"({BODY}, 0.5 s)" in text and f"{DEF}.body1AnchorPoint" in text
    assert f"UniversalJoint {DEF}: axis1 and axis2 are parallel" in text
    assert "&lt;" not in text and "&gt;" not in text and "\\" not in text.replace("\\x1b", "").replace("\\n", "")


def _results(out, scene: str) -> list[tuple[str, Comparison]]:
    """A page's results by hand: the report's metadata naming a hostile scene, and its comparison."""
    (out / "compare").mkdir(parents=True)
    (out / "report.json").write_text(json.dumps({
        "generated": "2026-11-21T00:00:00+00:00", "backends": {"bullet": "1", "mujoco": "2"}, "cpus": 2,
        "timings_s": {"compare": 1.0, "total": 1.0}, "failed": [], "quick": True, "scenes": [scene]}))
    stem = os.path.splitext(os.path.basename(scene))[0]
    for ext in (".rrd", ".divergence.png"):
        (out / "compare" / (stem + ext)).write_bytes(b"")
    return [(str(out / "compare" / stem), _comparison(scene))]


@pytest.mark.parametrize("name", HOSTILE)
def test_the_report_page_keeps_a_hostile_scene_as_text(tmp_path, name):
    found = _results(tmp_path, f"mine/{name}.x3d")
    text = report_markdown(str(tmp_path), found)
    page = rendered(text)
    assert live_markup(page) == [] and dead_links(str(tmp_path), page) == []
    assert text_of(page).count(shown(name)) >= 4  # your scenes, the heading, the findings, the recording's link
    assert any(img.endswith(".divergence.png") for img in lxml.html.fromstring(page).xpath("//img/@src"))


def test_a_scene_whose_file_name_is_not_utf_8_is_its_escapes_on_the_page(tmp_path):
    # its byte reaches Python as a surrogate, which a UTF-8 page cannot hold (UnicodeEncodeError);
    # the links keep the byte itself, so that they reach the file
    found = _results(tmp_path, os.fsdecode(b"mine/p\xffq.x3d"))
    page = rendered(report_markdown(str(tmp_path), found))
    page.encode("utf-8")
    assert "p\\udcffq" in text_of(page) and dead_links(str(tmp_path), page) == []
    assert "compare/p%FFq.rrd" in lxml.html.fromstring(page).xpath("//a/@href")


# end to end: `x3drbp report --scenes DIR`, its steps made small, on scenes with hostile names

SCENE = f"""<?xml version="1.0" encoding="UTF-8"?>
<X3D profile='Full' version='4.0'>
  <Scene>
    <RigidBodyCollection DEF='World'>
      <RigidBody DEF='{BODY}' mass='1' position='0 10 0' inertia='0.004 0 0 0 0.004 0 0 0 0.004'/>
      <RigidBody DEF='B' mass='1' position='1 10 0' inertia='0.004 0 0 0 0.004 0 0 0 0.004'/>
      <UniversalJoint DEF='{html.escape(DEF)}' anchorPoint='0.5 10 0'
                      axis1='1 0 0' axis2='1 0 0'>
        <RigidBody USE='{BODY}' containerField='body1'/>
        <RigidBody USE='B' containerField='body2'/>
      </UniversalJoint>
    </RigidBodyCollection>
  </Scene>
</X3D>
"""
FILES = [IMG, JS, MARKS, NEWLINE]


@pytest.fixture(scope="module")
def report_dir(tmp_path_factory):
    """One small report over the hostile scenes: compare and advise on each, a sweep of one."""
    if not {"bullet", "mujoco", "ode"} <= set(INSTALLED):
        pytest.skip("needs bullet and mujoco to run the scenes and ode to refuse them")
    tmp = tmp_path_factory.mktemp("hostile")
    yours = tmp / "mine"
    yours.mkdir()
    for name in FILES:
        (yours / f"{name}.x3d").write_text(SCENE, encoding="utf-8")
    out = str(tmp / "report")

    def small(out_dir, backends, quick, x_ite, scenes):
        chosen = ["--backends", ",".join(backends)]
        return [("compare", [["compare", path, *chosen, "--duration", "0.5",
                              "--json", os.path.join(out_dir, "compare", f"{stem}.json"),
                              "--rerun", os.path.join(out_dir, "compare", f"{stem}.rrd")]
                             for path, stem in zip(scenes, R.stems(scenes))]),
                ("advise", [["advise", *scenes, *chosen, "--dts", "1/60", "--duration", "0.5", "--repeats", "1",
                             "-q", "--json", os.path.join(out_dir, "advice", "advice.json")]]),
                ("sweep", [["sweep", *chosen, "--scenes", scenes[0], "--dts", "1/60", "--iterations", "10",
                            "--accuracy", "false", "--repeats", "1", "-q", "--out", os.path.join(out_dir, "sweep")]])]

    from x3drbp import main
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(R, "_steps", small)
        main(["report", "--out", out, "--backends", "bullet,mujoco,ode", "--scenes", str(yours), "-q"])
    return out


def _read(out: str, name: str) -> str:
    with open(os.path.join(out, name), encoding="utf-8") as f:
        return f.read()


def test_the_report_command_writes_hostile_names_as_text_in_index_html(report_dir):
    page = _read(report_dir, "index.html")
    assert live_markup(page) == [] and dead_links(report_dir, page) == []
    said = text_of(page)
    for name in FILES:
        assert said.count(shown(name)) >= 3, name  # your scenes, its comparison's heading, the advice
    assert f"UniversalJoint {DEF}: axis1 and axis2 are parallel" in said  # the refusal, quoting the DEF
    # the swept scene (the first, by name): its plot beside its fronts, found under its own name
    plots = {img.get("src"): img.get("alt") for img in lxml.html.fromstring(page).iter("img")}
    assert plots.get("sweep/" + quote(f"sweep_{JS}.png")) == f"{JS}: error against speed"


def test_the_report_command_writes_hostile_names_as_text_in_report_md(report_dir):
    page = rendered(_read(report_dir, "report.md"))
    assert live_markup(page) == []
    said = text_of(page)
    assert all(shown(name) in said for name in FILES)
    assert f"UniversalJoint {DEF}: axis1 and axis2 are parallel" in said

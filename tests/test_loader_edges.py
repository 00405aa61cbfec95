"""Hostile inputs at the loaders' edges: memory per line and per JSON object, columns on a
minified line, lone surrogates in JSON strings, malformed SFImage sizes, and values that a
UNIT factor carries out of the float range. Each ends in one-line diagnostics naming file,
line and field, quickly, in bounded memory, with no traceback and no numpy warning.

Inputs are written by the tests into tmp_path; memory is measured in a subprocess (peak RSS,
VmHWM), against the same subprocess's peak before the load.
"""

from __future__ import annotations

import json
import random
import subprocess
import sys
import time
import warnings

import numpy as np
import pytest

from conftest import PEAK_KIB, ROOT

from x3drbp import main
from x3d_core.encodings.line_index import LineIndex
from x3d_core.encodings.load import load
from x3d_core.model.scene import LoadError

RBP_X3D = ("<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Full' version='4.0'><head>"
           "<component name='RigidBodyPhysics' level='2'/>{head}</head><Scene>{body}</Scene></X3D>\n")
RBP_VRML = "#X3D V4.0 utf8\nPROFILE Full\nCOMPONENT RigidBodyPhysics:2\n{head}\n{body}\n"


def _ode_missing() -> bool:
    try:
        import backends.ode  # noqa: F401
    except ImportError:
        return True
    return False


# `run` loads its backend before the scene: where ODE is missing, only `check` is asked
RUN_BACKEND = "ode" if not _ode_missing() else None


def _write(tmp_path, name: str, text: str) -> str:
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return str(p)


def _load_quietly(path: str):
    """load(), with any numpy RuntimeWarning (or other warning) failing the test."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with np.errstate(all="warn"):
            return load(path)


def _peak_growth(path: str, prelude: str = "") -> int:
    """Bytes by which loading PATH raises a fresh interpreter's peak RSS (file already read)."""
    code = f"""
import gc, json, sys
from x3d_core.encodings.load import load
data = open(sys.argv[1], 'rb').read()
{prelude}
before = {PEAK_KIB}
try:
    load(sys.argv[1])
except LoadError:
    pass
print(({PEAK_KIB} - before) * 1024)
"""
    out = subprocess.run([sys.executable, "-c", code, path], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    return int(out.stdout.split()[-1])


# -- memory per line and per object --------------------------------------------------

def test_vrml_newlines_cost_no_memory_per_line(tmp_path):
    # 8 MB of newlines: ~50 bytes a line (a list of line starts) made this ~400 MB
    path = tmp_path / "lines.x3dv"
    path.write_bytes(b"#X3D V4.0 utf8\n" + b"\n" * 8_000_000 + b"Group {}\n")
    growth = _peak_growth(str(path))
    assert growth < 48 * 2**20, f"peak RSS grew by {growth / 2**20:.0f} MiB for 8 MB of newlines"


def test_json_newlines_cost_no_memory_per_line(tmp_path):
    path = tmp_path / "lines.x3dj"
    path.write_bytes(b'{"X3D": {"@version": "4.0", "Scene": {"-children": []}}' + b"\n" * 8_000_000 + b"}")
    growth = _peak_growth(str(path))
    assert growth < 48 * 2**20, f"peak RSS grew by {growth / 2**20:.0f} MiB for 8 MB of newlines"


def test_json_positions_cost_little_per_object(tmp_path):
    # 2e5 small objects: what json.loads itself makes is the floor; the positions kept per
    # object (tuples, lists, a dict of key offsets: ~450 bytes an object) came on top
    n = 200_000
    junk = ",".join('{"@x":1}' for _ in range(n))
    path = _write(tmp_path, "objects.x3dj",
                  '{"X3D":{"@version":"4.0","Scene":{"-children":[{"WorldInfo":{"@title":"t"}}]},'
                  f'"junk":[{junk}]}}}}')
    over = _peak_growth(path, prelude="json.loads(data); gc.collect()")  # load's peak above json's own
    # measured with VmHWM: ~200 bytes an object now (json.loads's own objects are the floor),
    # ~460 with the per-object tuples and dicts; 300 lies between with room on both sides
    assert over < 300 * n, f"load costs {over / n:.0f} bytes an object more than json.loads"


@pytest.mark.parametrize("name, head, tail", [
    ("s.x3d", b"<X3D version='4.0'><Scene><WorldInfo info='\"", b"\"'/></Scene></X3D>"),
    ("s.x3dv", b'#X3D V4.0 utf8\nWorldInfo { info [ "', b'" ] }\n'),
])
def test_a_long_string_costs_its_bytes_not_a_regex_stack(tmp_path, head, name, tail):
    # 10 MB in one quoted string of 2e6 escapes: an alternation repeated per character took
    # ~140 bytes of backtracking stack a character (1.4 GB here; 50 MB took 7 GB and 11 s)
    path = tmp_path / name
    small = tmp_path / f"small{name}"
    small.write_bytes(head + b"a\\\"b" * 3 + tail)
    assert not load(str(small)).errors  # the string, its escaped quotes included, is read
    path.write_bytes(head + b"a\\\"b" * 2_000_000 + tail)
    growth = _peak_growth(str(path), prelude=f"load({str(small)!r})")  # the loader's imports come first
    # ~4 bytes per byte read is the loader's whole cost (source, decoded text, parsed value,
    # the unescaped copy); 100 MiB is 2.5x that, and a cost per escape (re.sub: 200 MiB) fails
    assert growth < 100 * 2**20, f"peak RSS grew by {growth / 2**20:.0f} MiB for a 10 MB string"


def test_a_file_past_the_size_bound_is_refused_before_a_byte_is_read(tmp_path):
    from x3d_core.encodings.load import MAX_BYTES
    path = tmp_path / "huge.x3d"
    with open(path, "wb") as f:  # sparse: no disk is written
        f.write(b"<X3D>")
        f.truncate(MAX_BYTES + 1)
    started = time.process_time()
    with pytest.raises(LoadError, match=f"file is {MAX_BYTES + 1} bytes; x3drbp reads at most {MAX_BYTES}"):
        load(str(path))
    assert time.process_time() - started < 1  # CPU: the 200 MiB are not read


def test_vrml_locations_across_blocks(tmp_path):
    # a location many blocks of newlines in, on a long line, is still exact
    body = "\n" * 10_000 + "Group { children [ " + "Group { } " * 1000 + "RigidBody { mass -1 } ] }"
    s = load(_write(tmp_path, "far.x3dv", RBP_VRML.format(head="", body=body)))
    (e,) = s.errors
    assert (e.loc.line, e.subject) == (4 + 10_000 + 1, "RigidBody.mass")
    line = (tmp_path / "far.x3dv").read_text().split("\n")[e.loc.line - 1]
    assert line[e.loc.col - 1:].startswith("mass -1")


def test_line_index_agrees_with_counting():
    rng = random.Random(7)
    text = "".join(rng.choice(["a", "b", "\n", "\n\n", "é" * 3, "x" * 5000]) for _ in range(3000))
    for t in (text, text.encode("utf-8")):
        index = LineIndex(t)
        nl = "\n" if isinstance(t, str) else b"\n"
        for offset in [0, len(t), *rng.sample(range(len(t)), 300), *range(4090, 4100), *range(8190, 8194)]:
            line = t.count(nl, 0, offset) + 1
            col = offset - (t.rfind(nl, 0, offset) + 1) + 1
            assert index.locate(offset) == (line, col)
            start = offset - col + 1
            assert index.line_start(line) == start
        assert index.line_start(t.count(nl) + 2) is None


# -- columns on a minified XML line ------------------------------------------------------

def test_minified_xml_with_many_problems_is_fast_and_exact(tmp_path):
    # 20,000 bad masses on one line: finding each column scanned the line (minutes), and
    # every diagnostic named the last RigidBody's column
    n = 20_000
    els = "".join(f"<RigidBody mass='-{i + 1}'/>" for i in range(n))
    text = RBP_X3D.format(head="", body=f"<RigidBodyCollection>{els}</RigidBodyCollection>").replace("\n", "", 1)
    path = _write(tmp_path, "minified.x3d", text)
    t = time.process_time()
    s = load(path)
    took = time.process_time() - t
    assert took < 15, f"{took:.1f} s of CPU"
    errors = [d for d in s.errors if d.subject == "RigidBody.mass"]
    assert len(errors) == n
    assert {d.loc.line for d in errors} == {1}
    assert len({d.loc.col for d in errors}) == n
    line = text.split("\n")[0]
    for d in (errors[0], errors[1], errors[n // 2], errors[-1]):
        value = d.message.split(" ", 1)[0]
        assert line[d.loc.col - 1:].startswith(f"mass='{value}'"), (d, line[d.loc.col - 1:][:30])


class _Counting:
    """A compiled regex that counts its match() calls."""

    def __init__(self, rx):
        self.rx, self.calls = rx, 0

    def match(self, *args):
        self.calls += 1
        return self.rx.match(*args)


def test_many_bad_attributes_of_one_element_each_get_their_column(tmp_path, monkeypatch):
    # one start tag of 3000 attributes, each a diagnostic: the tag is read once, not once a
    # diagnostic (20,000 such attributes took 35 s, 70 s when each re-read the whole tag)
    from x3d_core.encodings import xml_loader
    ends, attributes = _Counting(xml_loader._START_TAG), _Counting(xml_loader._ATTRIBUTE)
    monkeypatch.setattr(xml_loader, "_START_TAG", ends)
    monkeypatch.setattr(xml_loader, "_ATTRIBUTE", attributes)
    n = 3000
    attrs = " ".join(f"bogus{i}='1'" for i in range(n))
    text = RBP_X3D.format(head="", body=f"<RigidBodyCollection><RigidBody {attrs}/></RigidBodyCollection>")
    path = _write(tmp_path, "attrs.x3d", text)
    s = load(path)
    assert ends.calls < 20 and attributes.calls < 2 * n
    errors = [d for d in s.errors if d.subject.startswith("RigidBody.bogus")]
    assert len(errors) == n
    line = text.split("\n")[1]
    for d in errors:
        assert line[d.loc.col - 1:].startswith(d.subject.split(".")[1] + "=")


def test_xml_columns_skip_tags_in_comments_cdata_and_doctype(tmp_path):
    body = ("<!-- <RigidBody mass='-9'/> --><Script><![CDATA[ if (a <RigidBody) {} ]]></Script>"
            "<RigidBodyCollection><RigidBody DEF='A' mass='-1'/><RigidBody\n  DEF='B' mass='-2'/>"
            "</RigidBodyCollection>")
    text = ("<?xml version='1.0' encoding='UTF-8'?>\n<!DOCTYPE X3D PUBLIC 'ISO//Web3D//DTD X3D 4.0//EN' "
            "'https://www.web3d.org/specifications/x3d-4.0.dtd'>\n" + RBP_X3D.format(head="", body=body)
            .split("\n", 1)[1])
    path = _write(tmp_path, "tricky.x3d", text)
    s = load(path)
    lines = text.split("\n")
    got = {d.subject: d.loc for d in s.errors if d.subject.endswith(".mass")}
    a, b = got["RigidBody A.mass"], got["RigidBody B.mass"]
    assert lines[a.line - 1][a.col - 1:].startswith("mass='-1'")
    assert lines[b.line - 1][b.col - 1:].startswith("mass='-2'")
    # an element's own place is where its start tag begins (B's spans two lines)
    body_b = next(n for n in s.nodes() if n.def_name == "B")
    at = s.locate(body_b.loc, body_b.label)
    assert "\n".join(lines[at.line - 1:at.line + 1])[at.col - 1:].startswith("<RigidBody\n  DEF='B'")


# -- lone surrogates in JSON strings -------------------------------------------------------

SURROGATE_JSON = ('{"X3D":{"@version":"4.0","head":{"component":[{"@name":"RigidBodyPhysics","@level":2}]},\n'
                  '"Scene":{"-children":[{"RigidBodyCollection":{"@DEF":"W","-bodies":[\n'
                  '{"RigidBody":{"@DEF":%s,"@mass":1}}]}}]}}}\n')


def test_lone_surrogate_in_a_def_name_is_a_field_error(tmp_path, capsys):
    path = _write(tmp_path, "s.x3dj", SURROGATE_JSON % '"a\\ud800b"')
    s = _load_quietly(path)
    (e,) = s.errors
    assert (e.loc.line, e.subject) == (3, "RigidBody.DEF")
    assert (tmp_path / "s.x3dj").read_text().split("\n")[2][e.loc.col - 1:].startswith("\\ud800")
    assert "\\ud800" in e.message and "UTF-8" in e.message
    assert main(["check", path]) == 1
    if RUN_BACKEND:
        assert main(["run", path, "--backend", RUN_BACKEND, "--trace", str(tmp_path / "t.csv")]) == 1
    out = capsys.readouterr()
    assert "Traceback" not in out.out + out.err
    assert f"{path}:3:" in out.out and (not RUN_BACKEND or f"{path}:3:" in out.err)
    assert not (tmp_path / "t.csv").exists()


@pytest.mark.parametrize("name,bad", [('"ok\\ud83d\\ude00"', 0), ('"\\\\ud800"', 0), ('"\\udc00x"', 1),
                                      ('"x\\ud800\\u0041"', 1), ('"\\ud800\\ud800\\udc00"', 1)])
def test_only_unpaired_surrogate_escapes_are_refused(tmp_path, name, bad):
    s = _load_quietly(_write(tmp_path, "s.x3dj", SURROGATE_JSON % name))
    assert len([d for d in s.errors if "surrogate" in d.message]) == bad


def test_lone_surrogate_in_a_key_is_reported_printably(tmp_path, capsys):
    text = SURROGATE_JSON.replace('"@mass"', '"@m\\udfffass"') % '"A"'
    path = _write(tmp_path, "k.x3dj", text)
    assert main(["check", "-q", path]) == 1
    out = capsys.readouterr().out
    assert "RigidBody.m\\udfffass" in out and "Traceback" not in out


# -- SFImage sizes -------------------------------------------------------------------------------

@pytest.mark.parametrize("image", ["1.5 1 1 0xFF", "1 1.5 1 0xFF", "1 1 1.5 0xFF", '"2" 1 1 0xFF 0xFF'])
def test_vrml_image_size_that_is_no_integer_is_a_field_error(tmp_path, image):
    s = load(_write(tmp_path, "i.x3dv", f"#X3D V4.0 utf8\nShape {{ appearance Appearance {{ texture\n"
                                        f"  PixelTexture {{ image {image} repeatS FALSE }} }} }}\n"))
    (e,) = s.errors
    assert (e.loc.line, e.subject) == (3, "PixelTexture.image")
    assert "not an integer" in e.message or "is a string" in e.message


def test_vrml_image_size_with_a_leading_zero_is_decimal(tmp_path):
    # ClassicVRML's SFInt32 is decimal digits or 0x hex: 08 is eight (not octal, not an error)
    s = load(_write(tmp_path, "i.x3dv",
                    "#X3D V4.0 utf8\nPixelTexture { image 08 1 1 0 1 2 3 4 5 6 7 repeatS FALSE }\n"))
    assert not s.errors
    img = s.roots[0]["image"]
    assert list(img[:3]) == [8, 1, 1] and len(img) == 11 and s.roots[0]["repeatS"] is False


@pytest.mark.parametrize("image,why", [("2 2 1 1 2 3", "4 pixels, got 3"), ("1 1 5 0", "components 0 to 4"),
                                       ("-1 1 1", "at least 0"), ("1 1", "got 2 numbers")])
def test_image_structure_is_checked(tmp_path, image, why):
    s = load(_write(tmp_path, "i.x3d", RBP_X3D.format(head="", body=f"<PixelTexture image='{image}'/>")))
    (e,) = s.errors
    assert e.subject == "PixelTexture.image" and why in e.message


# -- non-finite values after UNIT conversion -----------------------------------------------------

def _unit_scene(tmp_path, ext: str, units: list[tuple[str, str, str]], fields: dict[str, str]) -> str:
    if ext == "x3dv":
        head = "\n".join(f"UNIT {c} {n} {k}" for c, n, k in units)
        body = ("DEF W RigidBodyCollection { bodies [\n  DEF B RigidBody { "
                + " ".join(f"{k} {v}" for k, v in fields.items()) + " } ] }")
        return _write(tmp_path, "u.x3dv", RBP_VRML.format(head=head, body=body))
    if ext == "x3d":
        head = "".join(f"<unit category='{c}' name='{n}' conversionFactor='{k}'/>" for c, n, k in units)
        body = ("<RigidBodyCollection DEF='W'>\n<RigidBody DEF='B' "
                + " ".join(f"{k}='{v}'" for k, v in fields.items()) + "/></RigidBodyCollection>")
        return _write(tmp_path, "u.x3d", RBP_X3D.format(head=head, body=body))
    doc = {"X3D": {"@version": "4.0", "head": {
        "component": [{"@name": "RigidBodyPhysics", "@level": 2}],
        "unit": [{"@category": c, "@name": n, "@conversionFactor": float(k)} for c, n, k in units]},
        "Scene": {"-children": [{"RigidBodyCollection": {"@DEF": "W", "-bodies": [{"RigidBody": {
            "@DEF": "B", **{f"@{k}": [float(x) for x in v.split()] if " " in v else float(v)
                            for k, v in fields.items()}}}]}}]}}}
    return _write(tmp_path, "u.x3dj", json.dumps(doc, indent=1))


@pytest.mark.parametrize("ext", ["x3dv", "x3d", "x3dj"])
@pytest.mark.parametrize("units,field,value", [
    ([("length", "m", "1e300")], "linearVelocity", "0 1e10 0"),
    ([("length", "m", "1e300")], "position", "0 1e300 0"),
    ([("length", "m", "1e200")], "inertia", "1 0 0 0 1 0 0 0 1"),  # (1e200)^2 overflowed in units.factor
    ([("mass", "kg", "1e300"), ("length", "m", "1e10")], "inertia", "1 0 0 0 1 0 0 0 1"),
    ([("angle", "rad", "1e300")], "angularVelocity", "0 1e300 0"),
])
def test_values_carried_out_of_range_by_a_unit_are_field_errors(tmp_path, ext, units, field, value):
    s = _load_quietly(_unit_scene(tmp_path, ext, units, {"mass": "1", field: value}))
    errors = [d for d in s.errors if d.subject == f"RigidBody B.{field}"]
    assert len(errors) == 1, s.diagnostics
    assert "finite" in errors[0].message and units[0][2] in errors[0].message.replace("+", "")
    assert errors[0].loc.line > 1 and errors[0].loc.col > 0
    body = next(n for n in s.nodes() if n.def_name == "B")
    assert np.isfinite(np.asarray(body.get(field), dtype=float)).all()  # dropped: the default stays


@pytest.mark.parametrize("ext", ["x3dv", "x3d", "x3dj"])
def test_large_but_finite_values_and_sentinels_stay_allowed(tmp_path, ext):
    path = _unit_scene(tmp_path, ext, [("length", "cm", "0.01"), ("mass", "t", "1000")],
                       {"mass": "1e300", "position": "0 1e300 0", "linearVelocity": "0 -1 0"})
    s = _load_quietly(path)
    assert not s.errors, s.errors
    body = next(n for n in s.nodes() if n.def_name == "B")
    assert body.get("position")[1] == pytest.approx(1e298)
    # maxCorrectionSpeed -1 (no limit) is a sentinel, scaled or not
    text = (tmp_path / f"u.{ext}").read_text()
    text = text.replace("DEF W RigidBodyCollection {", "DEF W RigidBodyCollection { maxCorrectionSpeed -1")
    text = text.replace("<RigidBodyCollection DEF='W'", "<RigidBodyCollection DEF='W' maxCorrectionSpeed='-1'")
    text = text.replace('"@DEF": "W",', '"@DEF": "W", "@maxCorrectionSpeed": -1,')
    (tmp_path / f"u.{ext}").write_text(text)
    s = _load_quietly(path)
    assert not s.errors, s.errors
    assert next(n for n in s.nodes() if n.def_name == "W").get("maxCorrectionSpeed") < 0


def test_cli_reports_unit_overflow_in_one_line_without_warnings(tmp_path):
    path = _unit_scene(tmp_path, "x3dv", [("length", "m", "1e300")], {"linearVelocity": "0 1e10 0",
                                                                       "inertia": "1 0 0 0 1 0 0 0 1"})
    commands = [["check", "-q", path]]
    if RUN_BACKEND:
        commands.append(["run", path, "--backend", RUN_BACKEND, "--trace", str(tmp_path / "t.csv")])
    for cmd in commands:
        out = subprocess.run([sys.executable, "-c", "import sys; from x3drbp import main; "
                              "sys.exit(main(sys.argv[1:]))", *cmd], cwd=ROOT, capture_output=True, text=True,
                             timeout=120)
        assert out.returncode == 1, out
        text = out.stdout + out.stderr
        assert "Warning" not in text and "Traceback" not in text, text
        lines = [ln for ln in text.splitlines() if ": error: " in ln]
        assert len(lines) == 2 and all(ln.startswith(f"{path}:") for ln in lines), text
        assert {ln.split(": error: ")[1].split(":")[0] for ln in lines} == {"RigidBody B.linearVelocity",
                                                                             "RigidBody B.inertia"}


def test_non_finite_field_values_stay_refused(tmp_path):
    for text in ("0 nan 0", "0 inf 0", "0 1e999 0"):
        s = load(_write(tmp_path, "n.x3d", RBP_X3D.format(
            head="", body=f"<RigidBodyCollection><RigidBody DEF='B' linearVelocity='{text}'/></RigidBodyCollection>")))
        assert [d.subject for d in s.errors] == ["RigidBody B.linearVelocity"]
    s = load(_write(tmp_path, "n.x3dj", SURROGATE_JSON.replace('"@mass":1', '"@mass":1e999') % '"B"'))
    assert [d.subject for d in s.errors] == ["RigidBody B.mass"]
    s = load(_write(tmp_path, "n2.x3dj", SURROGATE_JSON.replace('"@mass":1', '"@mass":NaN') % '"B"'))
    assert [d.subject for d in s.errors] == ["RigidBody B.mass"]


def test_xml_lines_past_65535_are_placed_exactly(tmp_path):
    # lxml reports line 65535 for most elements past it (all of a 100,000-line file's), which
    # makes them look like one line: they are paired with their start tags instead
    groups = "<Group/>\n" * 70_000
    text = RBP_X3D.format(head="", body=f"\n{groups}<RigidBodyCollection>\n<RigidBody DEF='B' mass='-1'/>"
                                        "</RigidBodyCollection>")
    s = load(_write(tmp_path, "long.x3d", text))
    (e,) = s.errors
    line = text.split("\n").index("<RigidBody DEF='B' mass='-1'/></RigidBodyCollection></Scene></X3D>") + 1
    assert (e.subject, e.loc.line, e.loc.col) == ("RigidBody B.mass", line, len("<RigidBody DEF='B' ") + 1)


@pytest.mark.parametrize("attrs, model, says", [
    ("mass='1e308'", "<Box containerField='massDensityModel' size='2 2 2'/>",
     "RigidBody A.massDensityModel: a Box of 1e+308 kg makes an inertia past the largest double"),
    ("mass='1'", "<Sphere containerField='massDensityModel' radius='1e200'/>",  # once an OverflowError traceback
     "RigidBody A.massDensityModel: a Sphere of 1 kg makes an inertia past the largest double"),
    ("mass='1e308'", "<Cone containerField='massDensityModel' bottomRadius='4' height='8'/>",
     "RigidBody A.massDensityModel: a Cone of 1e+308 kg makes an inertia past the largest double"),
    ("mass='1e308' inertia='1e308 0 0 0 1e308 0 0 0 1e308'", "", None),  # huge, still a rigid body's
])
def test_check_of_an_inertia_that_overflows_says_so_in_one_line_without_warnings(tmp_path, attrs, model, says):
    path = tmp_path / "big.x3d"
    path.write_text("<X3D profile='Full' version='4.0'><Scene><RigidBodyCollection>"
                    f"<RigidBody DEF='A' position='0 1 0' {attrs}>{model}</RigidBody></RigidBodyCollection></Scene></X3D>")
    r = subprocess.run([sys.executable, "-m", "x3drbp", "check", str(path)], cwd=ROOT,
                       capture_output=True, text=True, timeout=120)
    text = r.stdout + r.stderr
    assert "Warning" not in text and "Traceback" not in text, text
    errors = [ln for ln in r.stdout.splitlines() if ": error: " in ln]
    if says is None:
        assert r.returncode == 0 and not errors, text
    else:
        assert r.returncode == 1 and len(errors) == 1 and says in errors[0], text

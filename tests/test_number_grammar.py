"""Numbers are read by X3D's grammar (ISO/IEC 19776-1 and -2), not by Python's float().

float() reads `1_000` as 1000, Arabic-Indic `١٠` as 10, full-width `１` and mathematical `𝟗` as
1 and 9, and `inf`/`nan` as numbers; str.split() separates at a no-break space. Every
encoding's loader and every trace reader took those silently. A number is now an optional
sign, ASCII digits with an optional point, an optional exponent; values are separated by
space, tab, CR, LF and commas only; anything else is one line naming file, line, field and
the text (at most x3d_core.files.paths.QUOTE_LIMIT characters of it). A trace's lines may end in a
lone CR, and a UTF-8 BOM before its header is read as nothing.
"""

from __future__ import annotations

import itertools
import re

import numpy as np
import pytest

from conformance.analyses.trace_check import check_trace
from x3d_core.encodings.load import load
from x3d_core.model import fields as F
from x3d_core.model.scene import LoadError
from x3d_core.traces.trace import Trace, read_trace, read_view

from conftest import case_scene
from limited import one_line, x3drbp

# what Python reads as a number and X3D does not
OUTSIDE = ["1_000", "١٠", "１", "𝟗", "inf", "-Infinity", "nan", "1e1_0"]
SAID = r"is not a number \(X3D's grammar"
XML = ("<X3D profile='Full' version='4.0'><Scene><RigidBodyCollection><RigidBody DEF='B' {attr}/>"
       "</RigidBodyCollection><PositionInterpolator key='{key}' keyValue='0 0 0 1 1 1'/></Scene></X3D>")
VRML = ("#X3D V4.0 utf8\nPROFILE Full\nRigidBodyCollection {{ bodies [ DEF B RigidBody {{ {attr} }} ] }}\n"
        "PositionInterpolator {{ key [ {key} ] keyValue [ 0 0 0 1 1 1 ] }}\n")


def _errors(tmp_path, name: str, text: str) -> list[str]:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    try:
        return [str(d) for d in load(str(path)).errors]
    except LoadError as e:
        return [str(d) for d in e.diagnostics if d.severity == "error"]


@pytest.mark.parametrize("text", OUTSIDE)
def test_xml_refuses_sf_and_mf_numbers_outside_the_grammar(tmp_path, text):
    sf = _errors(tmp_path, "sf.x3d", XML.format(attr=f"mass='{text}'", key="0 1"))
    assert len(sf) == 1 and re.search(rf"sf\.x3d:1:\d+: error: RigidBody B\.mass: '{text}' {SAID}", sf[0]), sf
    mf = _errors(tmp_path, "mf.x3d", XML.format(attr="mass='2'", key=f"0 {text}"))
    assert len(mf) == 1 and re.search(rf"mf\.x3d:1:\d+: error: PositionInterpolator\.key: '{text}' {SAID}", mf[0]), mf


@pytest.mark.parametrize("text", OUTSIDE)
def test_vrml_refuses_sf_and_mf_numbers_outside_the_grammar(tmp_path, text):
    sf = _errors(tmp_path, "sf.x3dv", VRML.format(attr=f"mass {text}", key="0 1"))
    assert any(re.search(rf"sf\.x3dv:3:\d+: error: RigidBody B\.mass: '{text}' {SAID}", e) for e in sf), sf
    mf = _errors(tmp_path, "mf.x3dv", VRML.format(attr="mass 2", key=f"0 {text}"))
    assert any(re.search(rf"mf\.x3dv:4:\d+: error: PositionInterpolator\.key: '{text}' {SAID}", e) for e in mf), mf


@pytest.mark.parametrize("blank", ["\u00a0", "\u2003", "\u3000", "\x0c"])
def test_only_ascii_blanks_and_commas_separate_values(tmp_path, blank):
    """A no-break space (or another Unicode space, or a form feed) is not X3D's whitespace:
    `1 2` with one between is one token, not two numbers."""
    escaped = re.escape(repr(blank)[1:-1])
    if blank != "\x0c":  # no character of an XML document
        xml = _errors(tmp_path, "s.x3d", XML.format(attr=f"mass='2' position='1{blank}2 3'", key="0 1"))
        assert len(xml) == 1 and re.search(rf"RigidBody B\.position: '1{escaped}2' {SAID}", xml[0]), xml
    vrml = _errors(tmp_path, "s.x3dv", VRML.format(attr="mass 2", key=f"0{blank}1"))
    assert any(re.search(rf"PositionInterpolator\.key: '0{escaped}1' {SAID}", e) for e in vrml), vrml
    mfint = F.FIELD_TYPES["MFInt32"]
    with pytest.raises(F.FieldError, match="not an integer"):
        F.parse_xml(mfint, f"1{blank}2")
    assert F.parse_xml(mfint, "1,2\t3\r\n4").tolist() == [1, 2, 3, 4]


# X3D's float, as 19776-2 Annex A writes it, independently of x3d_core.model.fields
ANNEX_A = re.compile(r"[+-]?(([0-9]+(\.)?)|([0-9]*\.[0-9]+))([eE][+-]?[0-9]+)?")


def test_the_grammar_is_exactly_annex_a():
    """Every string of up to 5 characters over digits, point, exponent, signs, underscore and
    an inf letter reads as a number (SF and MF, XML and ClassicVRML) exactly when Annex A's
    grammar says."""
    sf, mf = F.FIELD_TYPES["SFFloat"], F.FIELD_TYPES["MFFloat"]
    for n in range(1, 6):
        for chars in itertools.product("01.e+-_n", repeat=n):
            s = "".join(chars)
            want = ANNEX_A.fullmatch(s) is not None
            for read in (lambda: F.parse_xml(sf, s), lambda: F.parse_xml(mf, f"1 {s},2"),
                         lambda: F.parse_vrml(mf, ["1", s])):
                try:
                    read()
                    took = True
                except ValueError:
                    took = False
                assert took == want, s
    assert F.parse_xml(mf, " 1., .5 , -2e+3\n+4E-1 ").tolist() == [1.0, 0.5, -2000.0, 0.4]


@pytest.mark.parametrize("head, said", [
    ("<X3D version='4.0'><head><unit category='length' name='mm' conversionFactor='0_001'/></head><Scene/></X3D>",
     r"s\.x3d:1:\d+: error: UNIT length: conversion factor '0_001' must be a positive number"),
    ("#X3D V4.0 utf8\nUNIT length mm 0_001\n", r"s\.x3dv:2:\d+: error: UNIT length: conversion factor '0_001'"),
    ("<X3D version='4.0'><head><component name='RigidBodyPhysics' level='١'/></head><Scene/></X3D>",
     r"s\.x3d:1:\d+: error: component: level '١' is not an integer"),
    ('{"X3D":{"@version":"4.0","head":{"component":[{"@name":"RigidBodyPhysics","@level":"²"}]},"Scene":{}}}',
     r"s\.x3dj:1:\d+: error: component: level '²' is not an integer"),  # was a traceback: int('²')
])
def test_header_numbers_take_the_grammar_too(tmp_path, head, said):
    ext = ".x3dj" if head.startswith("{") else ".x3dv" if head.startswith("#") else ".x3d"
    errors = _errors(tmp_path, "s" + ext, head)
    assert len(errors) == 1 and re.search(said, errors[0]), errors


def test_a_quoted_value_is_bounded(tmp_path):
    """A value of 100,000 characters that is not a number is quoted in its first QUOTE_LIMIT."""
    from x3d_core.files.paths import QUOTE_LIMIT
    errors = _errors(tmp_path, "s.x3d", XML.format(attr=f"mass='{'x' * 100_000}'", key="0 1"))
    assert len(errors) == 1 and len(errors[0]) < len(str(tmp_path)) + QUOTE_LIMIT + 200, errors[0][:400]
    assert f"'{'x' * QUOTE_LIMIT}'... (100,000 characters) is not a number" in errors[0]


# -- traces ---------------------------------------------------------------------------------------
def _trace_text() -> str:
    trace = Trace()
    for t in (0.0, 0.5, 1.0):
        y = 10 - 4.905 * t * t
        for fld, ftype, value in (("position", "SFVec3f", [0, y, 0]), ("orientation", "SFRotation", [0, 0, 1, 0]),
                                  ("linearVelocity", "SFVec3f", [0, -9.81 * t, 0]),
                                  ("angularVelocity", "SFVec3f", [0, 0, 0])):
            trace.add(t, "Ball", fld, ftype, value)
    return trace.text()


def _problems(path) -> list[str]:
    return [str(p) for p in check_trace(str(path), load(case_scene("free_fall")))[1]]


@pytest.mark.parametrize("row, said", [
    ("1_0,Ball,position,0 10 0", r"t\.csv:14: time '1_0' is not a number \(X3D's grammar"),
    ("1,Ball,position,0 1_0 0", r"t\.csv:14: value '0 1_0 0' is not 3 numbers \(SFVec3f\): '1_0' " + SAID),
    ("1,Ball,position,0 １0 0", r"t\.csv:14: value '0 １0 0' is not 3 numbers"),
    ("1,Ball,position,0\u00a010 0", r"t\.csv:14: value '0\\xa010 0' is not 3 numbers"),
])
def test_validate_reads_trace_numbers_by_the_grammar(tmp_path, row, said):
    path = tmp_path / "t.csv"
    path.write_text(_trace_text() + row + "\n", encoding="utf-8")
    problems = _problems(path)
    assert len(problems) == 1 and re.search(said, problems[0]), problems


@pytest.mark.parametrize("row, said", [
    ("1_0,Ball,position,0 10 0", r"t\.csv:14: time '1_0' " + SAID),
    ("1,Ball,position,0 1_0 0", r"t\.csv:14: '1_0' " + SAID),
    ("1,Ball,position,0 nan 0", r"t\.csv:14: 'nan' " + SAID),
])
def test_our_trace_readers_refuse_what_the_grammar_does(tmp_path, row, said):
    path = tmp_path / "t.csv"
    path.write_text(_trace_text() + row + "\n", encoding="utf-8")
    for read in (read_view, read_trace):
        if read is read_trace and "time" not in said:
            continue  # read_trace keeps values as text
        with pytest.raises(ValueError, match=said):
            read(str(path))


def test_validate_bounds_a_value_it_quotes(tmp_path):
    """A 10,000-number position was a 40 KB line; it is quoted in QUOTE_LIMIT characters."""
    path = tmp_path / "t.csv"
    path.write_text(_trace_text() + "1,Ball,position," + " ".join(["1.5"] * 10_000) + "\n", encoding="utf-8")
    line = one_line(x3drbp("validate", case_scene("free_fall"), "--trace", str(path)), 2,
                    re.escape(f"{path}:14: value '1.5 1.5"))
    assert len(line) < len(str(path)) + 250 and "... (39,999 characters)" in line, line


@pytest.mark.parametrize("end", ["\r", "\r\n"])
def test_a_trace_with_cr_line_ends_reads_as_lines(tmp_path, end):
    lf, cr = tmp_path / "lf.csv", tmp_path / "cr.csv"
    lf.write_bytes(_trace_text().encode())
    cr.write_bytes(_trace_text().replace("\n", end).encode())
    view, problems = check_trace(str(cr), load(case_scene("free_fall")))
    assert problems == [] and len(view) == 12
    a, b = read_view(str(lf)), read_view(str(cr))
    assert a.keys() == b.keys() and all(np.array_equal(a.series(*k)[1], b.series(*k)[1]) for k in a.keys())
    assert read_trace(str(cr)) == read_trace(str(lf))
    cr.write_bytes((_trace_text() + "2_0,Ball,position,0 0 0\n").replace("\n", end).encode())
    assert _problems(cr) == [f"{cr}:14: time '2_0' is not a number "
                             "(X3D's grammar: [+-]digits[.digits][(e|E)[+-]digits], digits 0-9)"]


def test_a_bom_before_the_header_is_read_as_nothing(tmp_path):
    path = tmp_path / "t.csv"
    path.write_bytes(b"\xef\xbb\xbf" + _trace_text().encode())
    view, problems = check_trace(str(path), load(case_scene("free_fall")))
    assert problems == [] and len(view) == 12 and len(read_view(str(path))) == 12
    path.write_bytes(b"\xef\xbb\xbf" + _trace_text().replace("time,", "when,", 1).encode())
    assert _problems(path) == [f"{path}:1: header is 'when,node,field,value', expected 'time,node,field,value'"]


def test_a_long_name_of_digits_is_read_in_one_pass(tmp_path):
    """ClassicVRML tells a name from a number by the grammar; its old pattern backtracked
    quadratically on a name of digits and a letter (10^5 of them: 3 minutes of CPU), now a
    child under limited's CPU bound reads it at once."""
    path = tmp_path / "digits.x3dv"
    path.write_text("#X3D V4.0 utf8\nDEF " + "1" * 100_000 + "x Group {}\n")
    p = x3drbp("check", str(path))
    assert p.returncode == 0 and "Traceback" not in p.stderr, (p.returncode, p.stderr[-500:])

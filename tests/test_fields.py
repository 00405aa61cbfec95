"""Field types read from the three encodings and written back."""

from __future__ import annotations

import math

import numpy as np
import pytest

from x3d_core.model import fields as F
from x3d_core.model.fields import FIELD_TYPES as T

# (type, XML text, ClassicVRML tokens, JSON value, expected value)
CASES = [
    ("SFBool", "true", ["TRUE"], True, True),
    ("MFBool", "true false", ["TRUE", "FALSE"], [True, False], np.array([True, False])),
    ("SFInt32", "-7", ["-7"], -7, -7),
    ("MFInt32", "0, 1, 2, -1", ["0", "1", "2", "-1"], [0, 1, 2, -1], np.array([0, 1, 2, -1])),
    ("SFFloat", "0.1", ["0.1"], 0.1, 0.1),
    ("MFFloat", "1 2.5 1e-3", ["1", "2.5", "1e-3"], [1, 2.5, 0.001], np.array([1, 2.5, 1e-3])),
    ("SFDouble", "3.141592653589793", ["3.141592653589793"], math.pi, math.pi),
    ("SFTime", "10", ["10"], 10, 10.0),
    ("SFString", "a \"b\"", ['"a \\"b\\""'], 'a "b"', 'a "b"'),
    ("MFString", '"ALL" "a b"', ['"ALL"', '"a b"'], ["ALL", "a b"], ["ALL", "a b"]),
    ("SFVec2f", "0.5 0", ["0.5", "0"], [0.5, 0], np.array([0.5, 0])),
    ("SFVec3f", "0 -9.8 0", ["0", "-9.8", "0"], [0, -9.8, 0], np.array([0, -9.8, 0])),
    ("SFVec3d", "1e300 0 0", ["1e300", "0", "0"], [1e300, 0, 0], np.array([1e300, 0, 0])),
    ("MFVec3f", "0 0 0, 1 2 3", ["0", "0", "0", "1", "2", "3"], [0, 0, 0, 1, 2, 3],
     np.array([[0, 0, 0], [1, 2, 3]])),
    ("SFRotation", "0 0 1 1.57", ["0", "0", "1", "1.57"], [0, 0, 1, 1.57], np.array([0, 0, 1, 1.57])),
    ("MFRotation", "0 1 0 0, 1 0 0 3", list("01001003"), [0, 1, 0, 0, 1, 0, 0, 3],
     np.array([[0, 1, 0, 0], [1, 0, 0, 3]])),
    ("SFColor", "1 0.5 0", ["1", "0.5", "0"], [1, 0.5, 0], np.array([1, 0.5, 0])),
    ("SFColorRGBA", "1 0.5 0 1", ["1", "0.5", "0", "1"], [1, 0.5, 0, 1], np.array([1, 0.5, 0, 1])),
    ("SFMatrix3f", "1 0 0 0 2 0 0 0 3", list("100020003"), [1, 0, 0, 0, 2, 0, 0, 0, 3],
     np.array([1, 0, 0, 0, 2, 0, 0, 0, 3])),
    ("SFVec4f", "1 2 3 4", ["1", "2", "3", "4"], [1, 2, 3, 4], np.array([1, 2, 3, 4])),
    ("SFImage", "2 1 1 0xFF 0x00", ["2", "1", "1", "0xFF", "0x00"], [2, 1, 1, 255, 0],
     np.array([2, 1, 1, 255, 0])),
]


def same(a, b):
    if isinstance(b, np.ndarray):
        return isinstance(a, np.ndarray) and np.array_equal(a, b)
    return type(a) is type(b) and a == b


@pytest.mark.parametrize("tname,xml,vrml,js,expected", CASES, ids=[c[0] for c in CASES])
def test_three_encodings_read_the_same_value(tname, xml, vrml, js, expected):
    t = T[tname]
    assert same(F.parse_xml(t, xml), expected)
    assert same(F.parse_vrml(t, vrml), expected)
    assert same(F.parse_json(t, js), expected)


@pytest.mark.parametrize("tname,xml,vrml,js,expected", CASES, ids=[c[0] for c in CASES])
def test_written_text_reads_back_exactly(tname, xml, vrml, js, expected):
    t = T[tname]
    assert same(F.parse_xml(t, F.format_xml(t, expected)), expected)
    text = F.format_vrml(t, expected)
    from x3d_core.model.schema import _TOKEN
    assert same(F.parse_vrml(t, _TOKEN.findall(text)), expected)


def test_numbers_keep_every_digit():
    v = np.array([0.1, 1 / 3, 2.5e-17])
    assert np.array_equal(F.parse_xml(T["MFDouble"], F.format_xml(T["MFDouble"], v)), v)
    assert F.format_xml(T["SFFloat"], 1.0) == "1"


@pytest.mark.parametrize("tname,text,fragment", [
    ("SFFloat", "heavy", "'heavy' is not a number"),
    ("SFVec3f", "1 2", "expected 3 numbers"),
    ("MFVec3f", "1 2 3 4", "not a whole number of 3-tuples"),
    ("SFInt32", "1.5", "not an integer"),
    ("SFInt32", "4294967296", "32-bit"),
    ("SFBool", "yes", "not a boolean"),
    ("SFFloat", "nan", "'nan' is not a number"),  # no word of X3D's grammar
    ("SFFloat", "1e999", "non-finite"),  # X3D's grammar, past the float range
    ("MFString", '"open', "quoted string"),
])
def test_bad_text_is_a_field_error(tname, text, fragment):
    with pytest.raises(F.FieldError, match=fragment):
        F.parse_xml(T[tname], text)


def test_xml_mfstring_accepts_one_unquoted_string():
    assert F.parse_xml(T["MFString"], "NONE") == ["NONE"]


def test_json_rejects_wrong_json_types():
    with pytest.raises(F.FieldError):
        F.parse_json(T["SFFloat"], "1")
    with pytest.raises(F.FieldError):
        F.parse_json(T["SFBool"], 1)
    with pytest.raises(F.FieldError):
        F.parse_json(T["MFString"], "a")


@pytest.mark.parametrize("tname,value", [("SFInt32", "99999999999999999999"), ("MFInt32", "1 -99999999999")])
def test_huge_integers_are_field_errors(tname, value):
    with pytest.raises(F.FieldError, match="32-bit"):
        F.parse_xml(T[tname], value)
    with pytest.raises(F.FieldError, match="32-bit"):
        F.parse_json(T["SFInt32"], -1e300)

"""X3D field types: parsing from the three encodings and writing back.

Values are plain data: bool, int, float, str, numpy arrays for every numeric
vector or array (float64 for the f and d types alike, so a value written back
reads as the file said it; shape (n, width) for MF vectors, (width,) for SF
vectors, flat (9,) and (16,) for matrices), list[str] for MFString, and Node
references for SFNode and MFNode.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass
from typing import Any

import numpy as np

from x3d_core.files.paths import clipped, quoted


class FieldError(ValueError):
    """A value that does not read as its field's type; the message says what is allowed."""


@dataclass(frozen=True)
class FieldType:
    name: str
    multi: bool
    kind: str  # bool | int | float | string | node
    width: int = 1  # numbers per element for numeric kinds
    rotation: bool = False  # last number of each element is an angle

    @property
    def numeric(self) -> bool:
        return self.kind in ("int", "float")

    @property
    def vector(self) -> bool:
        """An SF value held as an array (SFVec3f, SFRotation, SFMatrix3f, ...)."""
        return self.numeric and not self.multi and self.width > 1

    def describe(self) -> str:
        if self.name == "SFImage":
            return "integers width height components, then width*height pixels (SFImage)"
        if self.name == "MFImage":
            return "integers: images, each width height components then width*height pixels (MFImage)"
        what = {"bool": "a boolean", "int": "an integer", "float": "a number",
                "string": "a string", "node": "a node"}[self.kind]
        if self.numeric and self.width > 1:
            what = f"{self.width} numbers"
        return f"{'a list of ' if self.multi else ''}{what} ({self.name})"


def _types() -> dict[str, FieldType]:
    out: dict[str, FieldType] = {}

    def add(suffix: str, kind: str, width: int = 1, rotation: bool = False) -> None:
        for multi in (False, True):
            name = ("MF" if multi else "SF") + suffix
            out[name] = FieldType(name, multi, kind, width, rotation)

    add("Bool", "bool")
    add("Int32", "int")
    for s in ("Float", "Double", "Time"):
        add(s, "float")
    add("String", "string")
    add("Node", "node")
    add("Image", "int")  # width height components pixels..., pixels often in hex
    for s, w in (("Vec2f", 2), ("Vec2d", 2), ("Vec3f", 3), ("Vec3d", 3), ("Vec4f", 4), ("Vec4d", 4),
                 ("Color", 3), ("ColorRGBA", 4), ("Matrix3f", 9), ("Matrix3d", 9),
                 ("Matrix4f", 16), ("Matrix4d", 16)):
        add(s, "float", w)
    add("Rotation", "float", 4, rotation=True)
    # SFImage is one flat int array, not pairs; MFImage is a list of them, kept flat too
    out["SFImage"] = FieldType("SFImage", True, "int")
    out["MFImage"] = FieldType("MFImage", True, "int")
    return out


FIELD_TYPES: dict[str, FieldType] = _types()

# X3D's numbers (ISO/IEC 19776-2 Annex A; 19776-1's attribute values are the same): a sign,
# ASCII digits with an optional point, an optional exponent, each value apart from the next by
# space, tab, CR, LF or a comma. Python's float() reads more (1_000, Arabic-Indic and full-width
# digits, inf, nan) and str.split() separates at a no-break space: neither is X3D. Over X3D's
# characters (ASCII digits . e E + -) float() and numpy read exactly this grammar
# (tests/test_number_grammar.py), so a value that matches is then parsed by them, in bulk.
# Possessive throughout: a token of 10^7 digits that fails costs one pass.
NUMBER = r"[+-]?+(?:[0-9]++(?:\.[0-9]*+)?+|\.[0-9]++)(?:[eE][+-]?+[0-9]++)?+"
_BLANKS = " \t\r\n,"
_NUMBERS = re.compile(rf"[{_BLANKS}]*+(?:{NUMBER}(?:[{_BLANKS}]++{NUMBER})*+[{_BLANKS}]*+)?+\Z")
GRAMMAR = "X3D's grammar: [+-]digits[.digits][(e|E)[+-]digits], digits 0-9"
_SPLIT = re.compile(rf"[{_BLANKS}]+")
_INT_TEXT = re.compile(r"[+-]?(?:0[xX][0-9a-fA-F]{1,4000}|[0-9]{1,4000})\Z")  # int() reads at most 4300 digits
_INT32 = (-(2**31), 2**31 - 1)


def not_a_number(text: str) -> str:
    """The words for a text that X3D's grammar does not read as a number."""
    return f"{quoted(text)} is not a number ({GRAMMAR})"


def number(text: str) -> float:
    """One number in X3D's grammar (blanks around it allowed), as a trace's time is; FieldError
    saying so otherwise."""
    if _NUMBERS.match(text) is not None:
        try:
            return float(text)
        except ValueError:  # no number, or several
            pass
    raise FieldError(not_a_number(text))


def numbers_problem(text: str) -> str | None:
    """None where text is numbers in X3D's grammar apart by blanks or commas (or none at all);
    else the words for the first that is not."""
    if _NUMBERS.match(text) is not None:
        return None
    return not_a_number(next(t for t in _tokens(text) if _NUMBERS.match(t) is None))


def reads_as_float(text: str) -> bool:
    """Whether Python's float() reads text: every number of X3D's grammar, and what a loader is
    to refuse as one (1_000, inf), not to take for a name."""
    try:
        float(text)
        return True
    except ValueError:
        return False


def _tokens(text: str) -> list[str]:
    inner = text.strip(_BLANKS)
    return _SPLIT.split(inner) if inner else []


def _not_numbers(tokens: list[str], ftype: FieldType) -> str:
    """Why tokens that do not all match X3D's grammar are no value of a float type: the first
    that does not."""
    bad = next(t for t in tokens if _NUMBERS.match(t) is None)
    if bad[:1] == '"':
        return f"{clipped(bad)} is a string; expected {ftype.describe()}"
    return f"{not_a_number(bad)}; expected {ftype.describe()}"


def _numbers(ftype: FieldType, text: str) -> Any:
    if ftype.kind != "float":
        return _from_tokens(ftype, _tokens(text))
    if _NUMBERS.match(text) is None:
        raise FieldError(_not_numbers(_tokens(text), ftype))
    tokens = text.replace(",", " ").split()  # str.split, faster than _tokens' regex: only X3D's blanks are left
    if not ftype.multi:
        fast = _sf_floats(ftype, tokens)
        if fast is not None:
            return fast
    return _from_tokens(ftype, tokens)


def _sf_floats(ftype: FieldType, tokens: list[str]) -> Any:
    """The common case, an SF number or vector of tokens in X3D's grammar, without numpy's string
    parsing; None sends a wrong count, or a number beyond the float range, to the general path
    and its messages."""
    if len(tokens) != ftype.width:
        return None
    vals = [float(t) for t in tokens]
    if not all(map(math.isfinite, vals)):
        return None
    return vals[0] if ftype.width == 1 else np.array(vals)


def _from_tokens(ftype: FieldType, tokens: list) -> Any:
    n = len(tokens)
    w = ftype.width
    if ftype.multi:
        if n % w:
            raise FieldError(f"{n} numbers is not a whole number of {w}-tuples for {ftype.name}")
    elif n != w:
        raise FieldError(f"expected {ftype.describe()}, got {n} values")
    if ftype.kind == "float":  # tokens in X3D's grammar, or JSON's numbers
        try:
            arr = np.array(tokens, dtype=np.float64)
        except OverflowError:  # a JSON integer beyond the float range
            raise FieldError(f"number beyond the float range; expected {ftype.describe()}") from None
        if not np.isfinite(arr).all():
            raise FieldError(f"non-finite number; expected {ftype.describe()}")
    else:
        arr = np.array([_int(t, ftype) for t in tokens], dtype=np.int64)
        if ftype.name in ("SFImage", "MFImage"):
            _check_images(arr, ftype)
        else:
            if arr.size and (arr.min() < _INT32[0] or arr.max() > _INT32[1]):
                raise FieldError(f"integer outside the 32-bit range; expected {ftype.describe()}")
            arr = arr.astype(np.int32)
    if ftype.multi:
        return arr.reshape(-1, w) if w > 1 else arr
    return arr if w > 1 else arr[0].item()


def _check_images(arr: np.ndarray, ftype: FieldType) -> None:
    """An SFImage is width height components (0 to 4), then width*height pixels; an MFImage
    is such images one after the other."""
    values = arr.tolist()
    at = 0
    while at < len(values) or (at == 0 and ftype.name == "SFImage"):
        head = values[at:at + 3]
        if len(head) < 3:
            raise FieldError(f"an image starts with its width, height and number of components, got "
                             f"{len(head)} number{'' if len(head) == 1 else 's'}; expected {ftype.describe()}")
        w, h, c = head
        if w < 0 or h < 0 or not 0 <= c <= 4:
            raise FieldError(f"an image of width {w}, height {h} and {c} components: width and height must be "
                             f"at least 0, components 0 to 4; expected {ftype.describe()}")
        pixels = len(values) - at - 3 if ftype.name == "SFImage" else min(w * h, len(values) - at - 3)
        if pixels != w * h:
            raise FieldError(f"a {w}x{h} image has {w * h} pixels, got {pixels}; expected {ftype.describe()}")
        at += 3 + pixels


def _any_int(t: Any, ftype: FieldType) -> int:
    if isinstance(t, bool):
        raise FieldError(f"{t!r} is not an integer; expected {ftype.describe()}")
    if isinstance(t, int):
        return t
    if isinstance(t, float):
        if t.is_integer():
            return int(t)
        raise FieldError(f"{t!r} is not an integer; expected {ftype.describe()}")
    s = str(t)
    if not _INT_TEXT.match(s):  # int() alone would take 1_000 and blanks around the digits
        raise FieldError(f"{quoted(s)} is not an integer; expected {ftype.describe()}")
    return int(s, 16) if s.lower().startswith(("0x", "-0x", "+0x")) else int(s)


def _int(t: Any, ftype: FieldType) -> int:
    v = _any_int(t, ftype)
    if not _INT32[0] <= v <= 2 * _INT32[1] + 1:  # SFImage pixels reach 0xFFFFFFFF
        raise FieldError(f"integer outside the 32-bit range; expected {ftype.describe()}")
    return v


_BOOLS = {"true": True, "false": False, "TRUE": True, "FALSE": False}


def _bool(t: str, ftype: FieldType) -> bool:
    try:
        return _BOOLS[t]
    except KeyError:
        raise FieldError(f"{quoted(t)} is not a boolean; expected true or false ({ftype.name})") from None


_STRING = re.compile(r'"([^"\\]*+(?:\\.[^"\\]*+)*+)"', re.S)  # unrolled and possessive: a per-character alternation cost ~140 bytes of backtracking stack a character
_BLOCK = 8192  # unescaped pieces joined at a time


def _unescape(text: str) -> str:
    """X3D's string escapes (\\x is x) removed; pieces are joined in blocks, so that a string of
    millions of escapes costs about its own size (re.sub kept two objects per escape: 100 bytes)."""
    if "\\" not in text:
        return text
    blocks: list[str] = []
    parts: list[str] = []
    pos, find = 0, text.find
    while (k := find("\\", pos)) >= 0:  # the quoted-string pattern gave every backslash its character
        parts += (text[pos:k], text[k + 1:k + 2])
        pos = k + 2
        if len(parts) >= _BLOCK:
            blocks.append("".join(parts))
            parts.clear()
    parts.append(text[pos:])
    blocks.append("".join(parts))
    return "".join(blocks)


def split_quoted(text: str, ftype: FieldType) -> list[str]:
    """MFString in XML and VRML encodings: a sequence of "quoted" strings with \\ escapes."""
    out = []
    pos = 0
    text = text.strip()
    while pos < len(text):
        m = _STRING.match(text, pos)
        if not m:
            raise FieldError(f"expected a quoted string at {text[pos:pos + 20]!r} ({ftype.name})")
        out.append(_unescape(m.group(1)))
        pos = m.end()
        while pos < len(text) and text[pos] in _BLANKS:
            pos += 1
    return out


def parse_xml(ftype: FieldType, text: str) -> Any:
    """A value from its X3D XML attribute text."""
    k = ftype.kind
    if k == "string":
        if not ftype.multi:
            return text
        stripped = text.strip()
        if stripped and not stripped.startswith('"'):
            return [stripped]  # an unquoted single string, as browsers accept
        return split_quoted(text, ftype)
    if k == "bool":
        toks = _tokens(text)
        if ftype.multi:
            return np.array([_bool(t, ftype) for t in toks], dtype=bool)
        if len(toks) != 1:
            raise FieldError(f"expected one boolean (true or false), got {quoted(text)}")
        return _bool(toks[0], ftype)
    if k == "node":
        raise FieldError(f"{ftype.name} fields hold nodes, not text")
    return _numbers(ftype, text)


def parse_vrml(ftype: FieldType, tokens: list[str]) -> Any:
    """A value from ClassicVRML tokens (brackets already removed; strings keep their quotes)."""
    k = ftype.kind
    if k == "string":
        vals = []
        for t in tokens:
            if not t.startswith('"'):
                raise FieldError(f"{quoted(t)} is not a quoted string; expected {ftype.describe()}")
            vals.append(_unescape(t[1:-1]))
        if ftype.multi:
            return vals
        if len(vals) != 1:
            raise FieldError(f"expected one quoted string, got {len(vals)} ({ftype.name})")
        return vals[0]
    if k == "bool":
        vals = [_bool_vrml(t, ftype) for t in tokens]
        if ftype.multi:
            return np.array(vals, dtype=bool)
        if len(vals) != 1:
            raise FieldError(f"expected one boolean (TRUE or FALSE), got {len(vals)} values")
        return vals[0]
    if ftype.kind == "float":
        if _NUMBERS.match(" ".join(tokens)) is None:  # one match, not one per token
            raise FieldError(_not_numbers(tokens, ftype))
        if not ftype.multi:
            fast = _sf_floats(ftype, tokens)
            if fast is not None:
                return fast
    else:
        for t in tokens:
            if t[0] == '"':
                raise FieldError(f"{clipped(t)} is a string; expected {ftype.describe()}")
    return _from_tokens(ftype, tokens)


def _bool_vrml(t: str, ftype: FieldType) -> bool:
    if t == "TRUE":
        return True
    if t == "FALSE":
        return False
    raise FieldError(f"{quoted(t)} is not a boolean; expected TRUE or FALSE ({ftype.name})")


def parse_json(ftype: FieldType, value: Any) -> Any:
    """A value from the X3D JSON encoding (numbers as arrays, MF vectors flattened)."""
    k = ftype.kind
    many = isinstance(value, list)
    if k == "string":
        if ftype.multi:
            if not many or not all(isinstance(v, str) for v in value):
                raise FieldError(f"expected a JSON array of strings ({ftype.name})")
            return list(value)
        if not isinstance(value, str):
            raise FieldError(f"expected a JSON string ({ftype.name})")
        return value
    if k == "bool":
        vals = value if many else [value]
        if not all(isinstance(v, bool) for v in vals):
            raise FieldError(f"expected JSON true or false ({ftype.name})")
        if ftype.multi:
            return np.array(vals, dtype=bool)
        if len(vals) != 1:
            raise FieldError(f"expected one boolean ({ftype.name})")
        return vals[0]
    vals = value if many else [value]
    if ftype.multi and vals and isinstance(vals[0], list):
        vals = [x for v in vals for x in (v if isinstance(v, list) else [v])]
    for v in vals:
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            if not (k == "int" and isinstance(v, str)):
                raise FieldError(f"{clipped(json.dumps(v))} is not a number; expected {ftype.describe()}")
    return _from_tokens(ftype, vals)


def _num(x: float) -> str:
    s = repr(float(x))
    return s[:-2] if s.endswith(".0") else s


def _numbers_text(value: Any, ftype: FieldType, sep: str) -> str:
    if ftype.kind == "int":
        flat = np.asarray(value).ravel().tolist() if not isinstance(value, int) else [value]
        return " ".join(str(v) for v in flat)
    if isinstance(value, float):
        return _num(value)
    if isinstance(value, list) and not (value and isinstance(value[0], list)):
        return " ".join(map(_num, value))  # one SF vector, as a trace hands it over
    arr = np.asarray(value, dtype=np.float64)
    if arr.ndim == 2:
        return sep.join(" ".join(map(_num, row)) for row in arr.tolist())
    return " ".join(map(_num, arr.tolist()))


def _quote(s: str) -> str:
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


def format_xml(ftype: FieldType, value: Any) -> str:
    """The XML attribute text of a value (full precision: a trace needs every digit)."""
    k = ftype.kind
    if k == "string":
        return " ".join(_quote(s) for s in value) if ftype.multi else value
    if k == "bool":
        if ftype.multi:
            return " ".join("true" if v else "false" for v in value)
        return "true" if value else "false"
    return _numbers_text(value, ftype, ", ")


def format_vrml(ftype: FieldType, value: Any) -> str:
    """The ClassicVRML text of a value (MF values in brackets; an SFImage, held as an array, not)."""
    k = ftype.kind
    if k == "string":
        text = " ".join(_quote(s) for s in value) if ftype.multi else _quote(value)
    elif k == "bool":
        vals = value if ftype.multi else [value]
        text = " ".join("TRUE" if v else "FALSE" for v in vals)
    else:
        text = _numbers_text(value, ftype, ", ")
    return f"[ {text} ]" if ftype.multi and ftype.name != "SFImage" else text


def empty(ftype: FieldType) -> Any:
    """The value of a field whose definition gives no default."""
    if ftype.multi:
        if ftype.kind == "string":
            return []
        if ftype.kind == "node":
            return []
        if ftype.kind == "bool":
            return np.zeros(0, dtype=bool)
        shape = (0, ftype.width) if ftype.width > 1 else (0,)
        return np.zeros(shape, dtype=np.float64 if ftype.kind == "float" else np.int32)
    if ftype.vector:
        return np.zeros(ftype.width)
    return {"bool": False, "int": 0, "float": 0.0, "string": "", "node": None}[ftype.kind]


def values_equal(ftype: FieldType, a: Any, b: Any) -> bool:
    """Equality of two non-node values of one type (exact: a round trip must not move a bit)."""
    if ftype.numeric or ftype.kind == "bool":
        return np.array_equal(np.asarray(a), np.asarray(b))
    return a == b

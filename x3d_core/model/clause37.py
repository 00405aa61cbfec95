"""Generates x3d_core/model/clause37_nodes.py from the node signatures of clause 37's own text.

    .venv/bin/python -m x3d_core.model.clause37 [PATH_TO_CLAUSE_TEXT]

(default ../shared/reference/clause37-rigid-body-physics.txt). The text is a V3 edition of
ISO/IEC 19775-1 clause 37; it ships with the project's shared folder, not with x3drbp, so
the table it yields is kept in the project, and X3D 3.x files take their clause 37 node
types from it (x3d_core/model/editions.py). A signature reads

    DoubleAxisHingeJoint : X3DRigidJointNode {
      SFFloat  [in,out] stopBounce1               0      [0,1]
      ...
    }

Where the text writes something its own way, it is read as it means: a tab inside a row as
a space; π, -π, ∞ and -∞ as numbers; "[0,∞) or -1" as an interval with one more value
allowed; a default or a list of node types that goes on over the next lines (RigidBody's
inertia, the collidables fields) as one row; a node field's bracketed types as the types it
accepts; a string field's bracketed values (forceOutput's ["ALL","NONE",...],
appliedParameters' []) as no range: validate.py checks those against the node and
x3d_core/semantics/applied.py. The text's slips are kept as it has them: the table is what the text
says, and editions.py decides what each slip means.
"""

from __future__ import annotations

import math
import os
import re
import sys
from dataclasses import dataclass

from x3d_core.files import atomic

from . import fields as F
from .schema import Range

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))  # the project's folder
TEXT = os.path.normpath(os.path.join(ROOT, "..", "shared", "reference", "clause37-rigid-body-physics.txt"))
TABLE = os.path.join(HERE, "clause37_nodes.py")

ACCESS = {"[in,out]": "inputOutput", "[in]": "inputOnly", "[out]": "outputOnly", "[]": "initializeOnly"}
_NUMBERS = {"π": repr(math.pi), "-π": repr(-math.pi), "∞": "inf", "-∞": "-inf"}

_HEAD = re.compile(r"^(\w+) : ([\w, ]+?)\s*\{\s*$")
_ROW = re.compile(r"^\s+([SM]F\w+)\s+(\[(?:in,out|in|out|)\])\s+(\w+)\s*(.*?)\s*$")
# a quoted string, a bracketed group (a range, or a list of types or values), or a word
_TOKEN = re.compile(r'"[^"]*"|[\[(][^\])]*[\])]|\S+')
_INTERVAL = re.compile(r"^([\[(])([^,]+),([^\])]+)([\])])$")


@dataclass(frozen=True)
class Row:
    """One field of a signature, as the text gives it."""
    name: str
    type: F.FieldType
    access: str
    default: object
    range: Range | None
    accepts: tuple[str, ...]


@dataclass(frozen=True)
class Signature:
    name: str
    parents: tuple[str, ...]
    rows: tuple[Row, ...]

    @property
    def abstract(self) -> bool:
        """The abstract types are the X3D... ones (37.3): the text marks them no other way."""
        return self.name.startswith("X3D")


class TextError(ValueError):
    """A signature row the reader cannot take: the message names the file, line and field."""


def signatures(text: str, path: str = TEXT) -> list[Signature]:
    """Every node signature of the text, in its order."""
    out: list[Signature] = []
    lines = text.replace("\t", " ").splitlines()
    i = 0
    while i < len(lines):
        head = _HEAD.match(lines[i])
        i += 1
        if not head:
            continue
        rows: list[tuple[int, list[str]]] = []
        while i < len(lines) and lines[i].strip() != "}":
            if _ROW.match(lines[i]):
                rows.append((i + 1, [lines[i]]))
            elif lines[i].strip():
                if not rows:
                    raise TextError(f"{path}:{i + 1}: {head.group(1)}: {lines[i].strip()!r} is no field row")
                rows[-1][1].append(lines[i].strip())  # a row going on over the next line
            i += 1
        parents = tuple(p.strip() for p in head.group(2).split(","))
        out.append(Signature(head.group(1), parents,
                             tuple(_row(" ".join(parts), path, line, head.group(1)) for line, parts in rows)))
    return out


def _row(text: str, path: str, line: int, node: str) -> Row:
    type_name, access, name, rest = _ROW.match(text).groups()
    where = f"{path}:{line}: {node}.{name}"
    ftype = F.FIELD_TYPES.get(type_name)
    if ftype is None:
        raise TextError(f"{where}: unknown field type {type_name!r}")
    tokens = _TOKEN.findall(rest)
    given, tokens = _default_tokens(ftype, ACCESS[access], tokens)
    try:
        default = F.empty(ftype) if ftype.kind == "node" or not given else \
            F.parse_vrml(ftype, [_NUMBERS.get(t, t) for t in given])
    except F.FieldError as e:
        raise TextError(f"{where}: default {' '.join(given)!r}: {e}") from None
    rng, accepts = None, ()
    if tokens and tokens[0].startswith(("[", "(")):
        group, tokens = tokens[0], tokens[1:]
        if ftype.kind == "node":
            accepts = tuple(t.strip() for t in group[1:-1].split(","))
        elif ftype.numeric:
            rng, tokens = _range(group, tokens, where)
        # a string field's list of values is no range (the module's docstring says why)
    if tokens:
        raise TextError(f"{where}: cannot read {' '.join(tokens)!r}")
    return Row(name, ftype, ACCESS[access], default, rng, accepts)


def _default_tokens(ftype: F.FieldType, access: str, tokens: list[str]) -> tuple[list[str], list[str]]:
    """The tokens of a row's default (an output has none), and what follows them."""
    if access == "outputOnly" or not tokens:
        return [], tokens
    if ftype.multi or ftype.kind == "node":
        if tokens[0] in ("[]", "NULL"):
            return [], tokens[1:]
        n = next((k for k, t in enumerate(tokens) if not t.startswith('"')), len(tokens))
        return tokens[:n], tokens[n:]
    return tokens[:ftype.width], tokens[ftype.width:]


def _range(group: str, tokens: list[str], where: str) -> tuple[Range, list[str]]:
    """An interval, and the value "or" allows besides it ("[0,∞) or -1 -1 -1")."""
    m = _INTERVAL.match(group)
    if not m:
        raise TextError(f"{where}: {group!r} is no range")
    alone: tuple[float, ...] = ()
    if tokens[:1] == ["or"]:
        alone, tokens = tuple(float(_NUMBERS.get(t, t)) for t in tokens[1:]), []
    lo, hi = (float(_NUMBERS.get(b.strip(), b.strip())) for b in (m.group(2), m.group(3)))
    return Range(lo, hi, m.group(1) == "(", m.group(4) == ")", alone), tokens


_HEADER = '''"""Clause 37's node signatures as its own text gives them (a V3 edition: X3D 3.x's names,
defaults and ranges), generated from ../shared/reference/clause37-rigid-body-physics.txt by
.venv/bin/python -m x3d_core.model.clause37 (do not edit): node_defs.py's text form, with no units
or containerFields (node_defs.py gives those). x3d_core/model/editions.py reads it for 3.x files.
"""

DEFINITIONS = r"""
'''


def _line(row: Row) -> str:
    line = f"  {row.name} {row.type.name} {row.access}"
    if row.range is not None:
        line += f" {row.range.token()}"
    if row.accepts:
        line += f" <{'|'.join(row.accepts)}>"
    if row.type.kind != "node" and not F.values_equal(row.type, row.default, F.empty(row.type)):
        line += " = " + F.format_vrml(row.type, row.default).removeprefix("[ ").removesuffix(" ]")
    return line


def generate(text: str, path: str = TEXT) -> str:
    """The text of clause37_nodes.py for clause 37's text (read from path)."""
    lines: list[str] = []
    for sig in signatures(text, path):
        lines.append(f"{'abstract' if sig.abstract else 'node'} {sig.name} : {' '.join(sig.parents)}")
        lines += [_line(r) for r in sig.rows]
    return _HEADER + "\n".join(lines) + '\n"""\n'


def main(source: str) -> int:
    try:
        with open(source, encoding="utf-8") as f:
            table = generate(f.read(), source)
    except (OSError, TextError) as e:  # one line, never a traceback
        print(f"x3d_core.model.clause37: {e}", file=sys.stderr)
        return 1
    atomic.write_text(TABLE, table)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else TEXT))

"""Which case turns a verdict on each field of clause 37's nodes: docs/field-coverage.md.

    .venv/bin/python -m conformance.coverage

Every field of every RigidBodyPhysics node of the X3D Unified Object Model 4.0 is accounted for
(KINDS, the first that applies). Found from the cases themselves, so the table cannot drift:
- covered: a case's mutation (a scene edit tests/test_conformance.py checks the case fails on)
  changes or removes what the case's scene sets for the field; or, for a field no scene edit can
  show, a mutant engine misreading it (Mutant.fields) fails a case that sets it (mutant_covers);
- judged: an output (outputOnly, or a field of the Contact nodes a CollisionSensor reports) that
  a case's scene reports and its expectation reads by name;
- exercised: a case sets it (Case.exercises), but no mutation of that case edits it.
Written here: pending (PENDING: a case is being written), a reason no verdict can turn on it
(REASONS, and _ANY for the fields every node has), and uncovered (UNCOVERED: observable, no
mutation shows it, with what would). tests/test_field_coverage.py fails while a field is none of
these, or still pending.
"""

from __future__ import annotations

import ast
import difflib
import importlib
import inspect
import os
import re
from collections.abc import Iterator
from dataclasses import dataclass, field

from lxml import etree

from x3d_core.files import atomic
from x3d_core.model import schema
from x3d_core.model import uom
from x3d_core.semantics.world import forced_outputs

from conformance.cases import BY_NAME, CASES, ROOT, closed_forms
from conformance.cases.case import Case, Mutation
from conformance.mutants.table import MUTANTS, Mutant

TABLE = os.path.join(ROOT, "docs", "field-coverage.md")
Field = tuple[str, str]  # (node type, field name)

# Fields a case is being written for (what it must show): a field, or with a third part a feature
# (x3d_core/semantics/analysis.py); answered once a case exercises it or a mutation covers it.
PENDING: dict[str, str] = {
    "RigidBody.fixed": "a fixed body's state: it stays where it is put, whatever acts on it",
    "CollisionCollection.slipFactors": "SLIP-1/SLIP-2 in appliedParameters apply slipFactors",
}

# Why no verdict can turn on a field no case covers or judges: nothing observable depends on it,
# or (argued from the case, not run) every browser that ignored it would already fail a case.
_BBOX = "a bounding-box hint for culling and display, never physics"
_ANY: dict[str, str] = {
    "metadata": "X3DMetadataObject nodes carry data for authors and scripts, never physics",
    "bboxCenter": _BBOX, "bboxSize": _BBOX, "bboxDisplay": _BBOX,
    "visible": "rendering only: whether the node's geometry is drawn",
    "description": "X3D 4.0's author prose about the node, never physics",
}
_NO_STOPS = "{} has no stop angles (no min/max field), so there is no stop for this to act at"
REASONS: dict[str, str] = {
    "RigidBody.finiteRotationAxis": "finite_rotation sets it (0 0 1, the wheel's spin axis, useFiniteRotation "
                                    "TRUE), but no edit of it shows: a body spinning about the axis turns by the "
                                    "same exact rotation whether the finite update is made about the axis or whole "
                                    "(ODE), and MuJoCo turns every body by the exponential map whatever it says",
    "RigidBodyCollection.iterations": "no verdict can turn on it: the clause asks only that more iterations be more "
                                      "stable, and where a closed form assumes a converged solve the spec "
                                      "tolerance is honoured() and the converged bound graded "
                                      "(docs/spec-loose-ends.md 20)",
    "RigidBodyCollection.preferAccuracy": "a performance hint (\"a performance hint to the underlying evaluation\"): "
                                          "no result is wrong under either value",
    "UniversalJoint.stop1Bounce": _NO_STOPS.format("UniversalJoint"),
    "UniversalJoint.stop1ErrorCorrection": _NO_STOPS.format("UniversalJoint"),
    "UniversalJoint.stop2Bounce": _NO_STOPS.format("UniversalJoint"),
    "UniversalJoint.stop2ErrorCorrection": _NO_STOPS.format("UniversalJoint"),
    **{f"MotorJoint.stop{i}{f}": _NO_STOPS.format("MotorJoint") for i in (1, 2, 3)
       for f in ("Bounce", "ErrorCorrection")},
}

# Observable fields no mutation shows a verdict turn on, and no case is being written for: what
# a case (or a mutation of one) would have to show.
UNCOVERED: dict[str, str] = {
}


@dataclass
class Row:
    """One field and what accounts for it."""
    node: str
    name: str
    access: str
    covered: list[str] = field(default_factory=list)  # 'case: edit' of each mutation that changes it (or mutant)
    judged: list[str] = field(default_factory=list)  # cases that read it as an output
    exercised: list[str] = field(default_factory=list)  # cases exercising it whose mutations edit other fields
    pending: str = ""
    reason: str = ""
    gap: str = ""

    @property
    def key(self) -> str:
        return f"{self.node}.{self.name}"


def catalogue() -> list[Row]:
    """Every field of every concrete RigidBodyPhysics node in the UOM, in the UOM's order."""
    rows = []
    for el in etree.parse(uom.UOM).iter("ConcreteNode"):
        if el.find("InterfaceDefinition/componentInfo").get("name") == "RigidBodyPhysics":
            rows += [Row(el.get("name"), name, f.get("accessType")) for name, f in uom.interface_fields(el).items()]
    return rows


# -- mutations: which fields a scene edit changes -----------------------------------------------

def _children(el: etree._Element) -> list[etree._Element]:
    return [c for c in el if isinstance(c.tag, str)]


def _slot(child: etree._Element) -> str:
    """The field of its parent a child node fills: its containerField, else its type's default."""
    t = schema.definition(child.tag)
    return child.get("containerField") or (t.container_field if t is not None else "children")


def _route_ends(route: etree._Element, defs: dict[str, str]) -> Iterator[Field]:
    yield defs.get(route.get("fromNode"), ""), route.get("fromField")
    yield defs.get(route.get("toNode"), ""), route.get("toField")


def _diff(a: etree._Element, b: etree._Element, defs: dict[str, str]) -> Iterator[Field]:
    """The fields where element b differs from a: attributes a sets that b drops or changes, and
    node fields whose children differ. An attribute b adds is not a change of what a sets."""
    if a.tag == "ROUTE":
        if dict(a.attrib) != dict(b.attrib):
            yield from _route_ends(a, defs)
        return
    for name, value in a.attrib.items():
        if b.get(name) != value and name not in ("DEF", "USE", "containerField"):
            yield a.tag, name
    ca, cb = _children(a), _children(b)
    sign = [[(c.tag, c.get("DEF"), c.get("USE"), _slot(c)) for c in cs] for cs in (ca, cb)]
    for op, i1, i2, j1, j2 in difflib.SequenceMatcher(None, *sign, autojunk=False).get_opcodes():
        if op == "equal":
            for x, y in zip(ca[i1:i2], cb[j1:j2]):
                yield from _diff(x, y, defs)
            continue
        for c in ca[i1:i2] + cb[j1:j2]:
            yield from _route_ends(c, defs) if c.tag == "ROUTE" else [(a.tag, _slot(c))]


def touched(case: Case, mutation: Mutation) -> set[Field]:
    """The fields a mutation changes or removes in the case's scene (none for a change of runs)."""
    with open(case.path, encoding="utf-8") as f:
        text = f.read()
    if not mutation.old:
        return set()
    a = etree.fromstring(text.encode())
    b = etree.fromstring(mutation.apply(text).encode())
    defs = {e.get("DEF"): e.tag for e in a.iter() if isinstance(e.tag, str) and e.get("DEF")}
    return set(_diff(a, b, defs))


def edit(mutation: Mutation) -> str:
    """A scene edit as the tables show it (this one, and docs/clause-coverage.md's): the text it
    replaces, and by what."""
    old, new = (" ".join(s.split()) for s in (mutation.old, mutation.new))
    return (f"`{old}` → " + (f"`{new}`" if new else "removed") + ("" if mutation.spec else " (conventions)")
            + (f" (on {mutation.on})" if mutation.on else ""))


# -- mutants: fields no scene edit shows --------------------------------------------------------

def credited(mutant: Mutant) -> list[str]:
    """The cases that cover the fields a mutant names (Mutant.fields): those of its kills that
    set one (Case.exercises), each of which tests/test_mutants.py holds to a FAIL on it."""
    return [c for c in mutant.kills
            if set(mutant.fields) & {".".join(f.split(".")[:2]) for f in BY_NAME[c].exercises}]


def mutant_covers() -> Iterator[tuple[Field, str, str]]:
    """(field, case, what the tables show) for each field an own-set mutant names and each case
    credited with it: where every engine here reads a field one way (useGeometry: the geometry, which
    FALSE allows and TRUE asks), a bug misreading it is shown by the engine, not by a scene edit."""
    for m in MUTANTS:
        for c in credited(m):
            for key in m.fields:
                node, name = key.split(".")
                yield (node, name), c, f"mutant `{m.name}` ({m.bug}) fails it"


# -- outputs: which a case reads --------------------------------------------------------------

def _path(node: ast.expr) -> str:
    """A string argument as written (an f-string's fields as {}); '' for anything else."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if isinstance(node, ast.JoinedStr):
        return "".join(v.value if isinstance(v, ast.Constant) else "{}" for v in node.values)
    return ""


def _reads(case: Case) -> tuple[set[str], set[str]]:
    """What the case's expectation reads: the outputs its trace reads name (the series() and
    text() calls of its module and of the closed_forms helpers it imports), and the keys it takes
    from the contacts closed_forms.sensor_contacts returns."""
    own = ast.parse(inspect.getsource(importlib.import_module(f"conformance.cases.{case.name}")))
    helpers = [getattr(closed_forms, a.name) for n in ast.walk(own)
               if isinstance(n, ast.ImportFrom) and n.module == closed_forms.__name__ for a in n.names
               if inspect.isfunction(getattr(closed_forms, a.name, None))]
    trees = [own, *(ast.parse(inspect.getsource(h)) for h in helpers)]
    outputs = {re.match(r"\w*", _path(c.args[1])).group() for t in trees for c in ast.walk(t)
               if isinstance(c, ast.Call) and isinstance(c.func, ast.Attribute) and c.func.attr in ("series", "text")
               and len(c.args) > 1}
    keys = {n.slice.value for n in ast.walk(own) if isinstance(n, ast.Subscript) and
            isinstance(n.slice, ast.Constant) and isinstance(n.slice.value, str)}
    return outputs, keys if closed_forms.sensor_contacts in helpers else set()


def _reported(case: Case) -> set[Field]:
    """The outputs the case's scene has reported: joints' forceOutput selections, and a
    CollisionSensor's outputs and its Contact nodes' fields."""
    root = etree.parse(case.path).getroot()
    out: set[Field] = set()
    for el in root.iter():
        t = schema.definition(el.tag) if isinstance(el.tag, str) else None
        if t is None or el.get("USE"):
            continue
        if t.is_a("X3DRigidJointNode"):
            chosen = re.findall(r'"([^"]*)"', el.get("forceOutput", ""))
            outputs = tuple(f for f, d in t.fields.items() if d.access == "outputOnly")
            out |= {(el.tag, f) for f in forced_outputs(outputs, chosen)}
        elif el.tag == "CollisionSensor":
            out |= {(el.tag, f) for f, d in t.fields.items() if d.access == "outputOnly"}
            out |= {("Contact", f) for f in schema.definition("Contact").fields}
    return out


def judged(case: Case) -> set[Field]:
    """The outputs the case reads (reported by its scene and named in its expectation), and the
    forceOutput of each joint type whose outputs it reads: the selection that reports them."""
    outputs, keys = _reads(case)
    read = {(node, name) for node, name in _reported(case) if name in (keys if node == "Contact" else outputs)}
    return read | {(node, "forceOutput") for node, _ in read if schema.definition(node).is_a("X3DRigidJointNode")}


# -- the table --------------------------------------------------------------------------------

def _exercising() -> dict[str, list[str]]:
    """Field key -> the cases whose exercises name it (the field, or a feature of it)."""
    out: dict[str, list[str]] = {}
    for case in CASES:
        for key in sorted({".".join(f.split(".")[:2]) for f in case.exercises}):
            out.setdefault(key, []).append(case.name)
    return out


def open_pending(table: list[Row]) -> list[str]:
    """The PENDING keys no case answers yet: no case exercises them and no mutation covers them."""
    answered = {r.key for r in table if r.covered} | {f for c in CASES for f in c.exercises}
    return [k for k in PENDING if k not in answered]


def rows() -> list[Row]:
    """The catalogue with what accounts for each field."""
    table = catalogue()
    by_key = {(r.node, r.name): r for r in table}
    for case in CASES:
        for m in case.mutations:
            for f in sorted(touched(case, m)):
                if f in by_key:
                    by_key[f].covered.append(f"{case.name}: {edit(m)}")
        for f in sorted(judged(case)):
            if f in by_key:
                by_key[f].judged.append(case.name)
    for f, case_name, shown in mutant_covers():
        by_key[f].covered.append(f"{case_name}: {shown}")
    exercising = _exercising()
    waiting = set(open_pending(table))
    for r in table:
        mutated = {c.split(":")[0] for c in r.covered}
        r.exercised = [c for c in exercising.get(r.key, []) if c not in mutated and not r.judged]
        r.pending = PENDING[r.key] if r.key in waiting else ""
        r.reason = REASONS.get(r.key) or _ANY.get(r.name, "")
        r.gap = UNCOVERED.get(r.key, "")
    return table


def _cell(text: str) -> str:
    return text.replace("|", "\\|")


KINDS = ("covered", "judged", "pending", "reason", "uncovered", "exercised")


def kind(r: Row) -> str:
    """What accounts for a field, the first that applies in KINDS' order ('' for nothing)."""
    found = (r.covered, r.judged, r.pending, r.reason, r.gap, r.exercised)
    return next((k for k, f in zip(KINDS, found) if f), "")


def _standing(r: Row) -> str:
    """The last column: the word a pending, explained or uncovered field needs."""
    return {"pending": f"pending: {r.pending}", "reason": r.reason, "uncovered": f"uncovered: {r.gap}"}.get(
        kind(r), "")


def render(table: list[Row]) -> str:
    """docs/field-coverage.md's text."""
    kinds = [kind(r) for r in table]
    lines = ["# Field coverage: which case turns a verdict on each field of clause 37",
             "",
             "Generated by `.venv/bin/python -m conformance.coverage` from the X3D Unified Object Model 4.0",
             "and `conformance/cases/` (do not edit; `tests/test_field_coverage.py` checks it is current).",
             "**Covered**: a case's mutation, a scene edit on which the case must fail",
             "(`tests/test_conformance.py::test_case_fails_when_mutated`), changes or removes what its scene",
             "sets for the field; \"(conventions)\" marks an edit that turns the verdict only to \"conforms,",
             "differs in conventions\", \"(on BACKEND)\" one judged there, where the reference cannot show it;",
             "or, for a field no scene edit shows, a mutant engine misreading it fails the case",
             "(`tests/test_mutants.py`). **Judged**: an output the case's scene reports and its expectation",
             "reads. **Exercised**: a case sets the field at a non-default value (its `exercises`), but no",
             "mutation of that case edits it. **Pending**: a case is being written for it. **Uncovered**: a",
             "field a scene could observe, on which no mutation shows a verdict turn, and what would show it.",
             "Otherwise the reason no verdict can turn on it.",
             "",
             f"{len(table)} fields: " + ", ".join(f"{kinds.count(k)} {k}" for k in KINDS) + "."]
    pending = open_pending(table)
    if pending:
        lines += ["", "Still pending: " + ", ".join(f"`{k}`" for k in pending) + "."]
    node = None
    for r in table:
        if r.node != node:
            node = r.node
            lines += ["", f"## {node}", "", "| field | access | covered by (case: mutation) | judged by | "
                      "exercised by | pending, uncovered, or why no verdict |", "|---|---|---|---|---|---|"]
        lines.append(f"| `{r.name}` | {r.access} | {_cell('<br>'.join(r.covered))} | "
                     f"{', '.join(r.judged)} | {', '.join(r.exercised)} | {_cell(_standing(r))} |")
    return "\n".join(lines) + "\n"


def main() -> None:
    atomic.write_text(TABLE, render(rows()))


if __name__ == "__main__":
    main()

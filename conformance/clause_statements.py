"""Every statement of clause 37's text, each with a stable id: what docs/clause-coverage.md
accounts for, one by one.

What counts as a statement (the page's header says the same):
- each prose sentence of a subclause, as conformance.clause_text cuts it (a numbered list goes on
  the sentence whose colon introduces it); EXAMPLE and NOTE paragraphs are sentences too: they
  are informative as ISO writes them, but one may still fix a reading a case holds to;
- each row of a node signature (x3d_core.model.clause37): node, field, access, type, default, range;
- each row of Table 37.3, the support levels: a node's support at a level, and a level's
  prerequisite components taken together as one.
Headings and table titles are not statements: a heading numbers and names the subclause its
statements are listed under, a title names a table (Tables 37.1 and 37.2 print no rows; the
sentences that point to them are statements). The text's preamble (its part and clause titles)
says nothing.

Ids: "37.4.10 RigidBody/12" for the twelfth sentence of 37.4.10 (the subclause's number and name
as the text prints them, so the twice-printed 37.3.1 stays two subclauses), "RigidBody.mass" for
a signature row, "Table 37.3/1 CollisionSensor" and "Table 37.3/1 prerequisites" for the table's
rows. The text is fixed, so the ids are stable; and an id names no sentence by its words, so the
entries keyed by them keep the clause's text out of the project.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from x3d_core.model import clause37

from conformance import clause_text

TITLE = re.compile(r"^Table (37\.\d+) \u2014 ")
_LEVEL = re.compile(r"^(\d+) (.*)$")
_PREREQUISITE = re.compile(r"^\S+ \d+$")  # a component and its level: "Geometry3D 1"


@dataclass(frozen=True)
class Statement:
    """One statement, under the subclause (number, name) the text prints it in."""
    id: str
    number: str
    name: str
    text: str  # the sentence, whitespace-normalised; a signature row: its field's name
    node: str = ""  # a signature row's node type
    row: clause37.Row | None = None  # a signature row's columns


@dataclass(frozen=True)
class Clause:
    """The statements of the text in its order, and each subclause's prose paragraphs (what a
    spec basis's quote is matched against, so a quote finds the very sentences listed)."""
    statements: tuple[Statement, ...]
    prose: dict[tuple[str, str], tuple[str, ...]]

    def quoted(self, basis_text: str) -> list[str]:
        """The ids of the sentences a spec basis quotes ([] where it quotes none whole)."""
        split = clause_text.split_basis(basis_text)
        if split is None or split[0] not in self.prose:
            return []
        (number, name), quote = split
        return [f"{number} {name}/{k + 1}" for k in clause_text.quoted(quote, self.prose[number, name]) or []]


def read(text: str) -> Clause:
    """The clause's statements, from its text."""
    signatures = {s.name: s for s in clause37.signatures(text)}
    statements: list[Statement] = []
    prose: dict[tuple[str, str], tuple[str, ...]] = {}
    for sub in clause_text.subclauses(text):
        rows: list[Statement] = []
        tables: list[Statement] = []
        kept: list[str] = []
        table = ""  # the number of the table whose title the last paragraph was
        for printed, paragraph in zip(sub.printed, sub.paragraphs):
            signature = signatures.get(paragraph.split(" : ", 1)[0]) if " : " in paragraph else None
            title = TITLE.match(paragraph)
            if signature is not None:
                rows += _rows(sub, signature)
            elif table:
                tables += _table(sub, table, printed)
            elif not title:
                kept.append(paragraph)
            table = title.group(1) if title else ""
        prose[sub.key] = tuple(kept)
        # in the text's order: a node's signature heads its subclause, Table 37.3 ends 37.5
        statements += rows + [Statement(f"{sub.number} {sub.name}/{k}", sub.number, sub.name, s)
                              for k, s in enumerate(clause_text.sentences(kept), 1)] + tables
    return Clause(tuple(statements), prose)


def _rows(sub: clause_text.Subclause, signature: clause37.Signature) -> list[Statement]:
    return [Statement(f"{signature.name}.{r.name}", sub.number, sub.name, r.name, signature.name, r)
            for r in signature.rows]


def _table(sub: clause_text.Subclause, table: str, printed: str) -> list[Statement]:
    """The rows of a table the text prints one a line under its title (Table 37.3, the only one
    with rows): its first line the column titles, a level's first row starting with the level,
    then its prerequisite components, then its nodes."""
    out: list[Statement] = []
    level, needs = "", []
    for line in [line.strip() for line in printed.splitlines() if line.strip()][1:]:
        m = _LEVEL.match(line)
        if m:
            level, line = m.groups()
        if _PREREQUISITE.match(line):
            needs.append(line)
            continue
        if needs:
            out.append(Statement(f"Table {table}/{level} prerequisites", sub.number, sub.name,
                                 f"Level {level} prerequisites: {', '.join(needs)}"))
            needs = []
        node = line.split()[0]
        out.append(Statement(f"Table {table}/{level} {node}", sub.number, sub.name, f"Level {level}: {line}"))
    return out

"""Clause 37's text cut as a quote is held to it: subclauses, as its headings number and name
them, their paragraphs, and the sentences of those.

One cut serves both readers of the text: tests/test_spec_quotes.py, which holds each spec basis
to whole sentences of its subclause, and conformance/clause_coverage.py, which accounts for every
sentence; so a sentence a basis quotes is the very sentence the coverage page lists. The text
ships with the project's shared folder (x3d_core.model.clause37.TEXT), not with x3drbp: read() gives
None where it is absent, and the tests that need it skip.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass

from x3d_core.model.clause37 import TEXT

# a heading line of the text: "37.4.1 BallJoint", " cube 37.2 Concepts"
HEADING = re.compile(r"^[ \t]*(?:cube )?(37(?:\.\d+)+) (\S.*?)[ \t]*$", re.M)
# where a sentence ends: a stop, then perhaps a closing bracket or quote
STOP = re.compile(r"[.?!][)\"\u2019]?$")
# how a spec basis heads its quote (conformance.results.Basis): "37.4.10 RigidBody: " and a sentence
HEAD = re.compile(r"^(37(?:\.\d+)+) ([A-Za-z][A-Za-z0-9 ]*?): \S")
# a paragraph that is a numbered list ("1. mass, 2. density model, ..."): it goes on the sentence
# of the paragraph before it, which introduces it with a colon
LIST = re.compile(r"^\d+\. ")


@dataclass(frozen=True)
class Subclause:
    """A subclause as the text heads it, and its paragraphs up to the next heading of any level,
    as printed (a table's rows are its lines)."""
    number: str
    name: str
    printed: tuple[str, ...]

    @property
    def key(self) -> tuple[str, str]:
        return self.number, self.name

    @property
    def paragraphs(self) -> tuple[str, ...]:
        """The paragraphs whitespace-normalised, as a quote is matched against them."""
        return tuple(" ".join(p.split()) for p in self.printed)


def read(path: str = TEXT) -> str | None:
    """The clause's text, or None where it is not there."""
    if not os.path.isfile(path):
        return None
    with open(path, encoding="utf-8") as f:
        return f.read()


def subclauses(text: str) -> list[Subclause]:
    """The text's subclauses in its order (the preamble before the first heading is its titles)."""
    heads = list(HEADING.finditer(text))
    ends = [h.start() for h in heads[1:]] + [len(text)]
    return [Subclause(h.group(1), h.group(2),
                      tuple(p.strip("\n") for p in re.split(r"\n\s*\n", text[h.end():end]) if p.strip()))
            for h, end in zip(heads, ends)]


def split_basis(text: str) -> tuple[tuple[str, str], str] | None:
    """A spec basis's text as the subclause it names (number, name) and its quote; None where it
    has no such head."""
    m = HEAD.match(text)
    return (m.groups(), text[m.end(2) + 2:]) if m else None


def _joined(paragraphs: tuple[str, ...] | list[str]) -> tuple[str, list[int]]:
    """The paragraphs as one line, and where each sentence starts in it: a paragraph's start (but
    a list's, which goes on its colon), or after a stop and a space and not in lower case (so none
    starts at the "g" of "e. g.")."""
    text, starts, at = " ".join(paragraphs), [], 0
    for k, p in enumerate(paragraphs):
        if not (k and LIST.match(p) and paragraphs[k - 1].endswith(":")):
            starts.append(at)
        starts += [at + m.end() for m in re.finditer(r"(?<=\S) (?=\S)", p)
                   if STOP.search(p, 0, m.start()) and not p[m.end()].islower()]
        at += len(p) + 1
    return text, sorted(starts)


def sentences(paragraphs: tuple[str, ...] | list[str]) -> list[str]:
    """The paragraphs' sentences, in order."""
    text, starts = _joined(paragraphs)
    return [text[a:b].strip() for a, b in zip(starts, starts[1:] + [len(text)])]


def quoted(quote: str, paragraphs: tuple[str, ...] | list[str]) -> list[int] | None:
    """The indices (into sentences()) of the run of whole sentences `quote` is, whitespace-
    normalised; None where it is no such run (cut, or not there)."""
    text, starts = _joined(paragraphs)
    q = " ".join(quote.split())
    if not q or STOP.search(q) is None:
        return None
    at = set(starts)
    i = text.find(q)
    while i >= 0:
        j = i + len(q)
        if i in at and (j == len(text) or (text[j] == " " and j + 1 in at)):
            return [k for k, s in enumerate(starts) if i <= s < j]
        i = text.find(q, i + 1)
    return None

"""Conformance cases: one folder each, found here by discovery.

A case is one scene file, the run settings (one run, or several that must agree), and an
expectation: a function of the traces that returns Measures, each a measured error with
the tolerance it must not exceed. Every tolerance is argued in the case's docstrings from
the step size and the order of the integrators the engines use, never tuned until a
backend passes (closed_forms.py states the conventions of the argument and holds what
several cases share; case.py says what a Case is).

To add a case, add one folder, conformance/cases/NAME/, holding
- NAME.x3d, the scene, whose leading comment (<!-- Conformance: ... -->) says what it
  checks and the closed form, exercising its field at a non-default value;
- __init__.py, defining CASE = Case("NAME", "NAME.x3d", ...): the expectation with its
  tolerance argued in the docstring, the closed form's parameters written out (not read
  from the scene), the features it exercises (tests/test_conformance.py checks the scene
  uses them, and runs it everywhere), and at least one mutation: a scene edit standing for
  a backend that ignores the case's field, on which the case must fail.
Nothing else changes: the folder is found, imported and listed here, sorted by name. A case
imports only x3d_core, numpy, conformance.results and this package's case.py and
closed_forms.py: expectations are pure functions of traces.
"""

from __future__ import annotations

import dataclasses
import importlib
import itertools
import os
import pkgutil
import sys
import types
from collections.abc import Sequence

from conformance.cases.case import Case

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CONVERGENCE_DTS = (1 / 60, 1 / 120, 1 / 240, 1 / 480)


class CaseError(ImportError):
    """A case folder that is not a case: it does not import, or defines no proper CASE."""


_elsewhere = itertools.count()


def discover(folder: str | None = None) -> tuple[Case, ...]:
    """The cases of a folder of case packages (default: this package's), sorted by name: each
    subfolder with an __init__.py defining CASE, a Case named as the folder, whose scene is
    found in that folder. CaseError naming the folder for one that is not such a case."""
    if folder is None:
        here, package = __path__[0], __name__
    else:
        here = os.path.abspath(folder)
        package = f"_x3drbp_cases_{next(_elsewhere)}"  # fresh each call: the folder's current code
        parent = types.ModuleType(package)
        parent.__path__ = [here]
        sys.modules[package] = parent
        importlib.invalidate_caches()
    packages = {m.name for m in pkgutil.iter_modules([here]) if m.ispkg}
    for entry in sorted(os.listdir(here)):
        path = os.path.join(here, entry)
        if os.path.isdir(path) and entry not in packages and not entry.startswith(("_", ".")):
            raise CaseError(f"{path}: a case folder needs an __init__.py defining CASE")
    found = []
    for name in sorted(packages):
        path = os.path.join(here, name)
        try:
            module = importlib.import_module(f"{package}.{name}")
        except Exception as e:
            raise CaseError(f"{path}: the case does not import: {type(e).__name__}: {e}") from e
        case = getattr(module, "CASE", None)
        if not isinstance(case, Case):
            raise CaseError(f"{path}/__init__.py defines no CASE = Case(...)")
        if case.name != name:
            raise CaseError(f"{path}: the case is named {case.name!r}, not after its folder")
        found.append(dataclasses.replace(case, folder=path))
    return tuple(found)


CASES: tuple[Case, ...] = discover()
BY_NAME = {c.name: c for c in CASES}


def select(names: Sequence[str] | None) -> list[Case]:
    """The named cases (all when None); KeyError naming the unknown ones."""
    if not names:
        return list(CASES)
    unknown = [n for n in names if n not in BY_NAME]
    if unknown:
        raise KeyError(f"unknown case(s) {', '.join(unknown)}; known: {', '.join(BY_NAME)}")
    return [BY_NAME[n] for n in names]


def exercising() -> dict[str, list[str]]:
    """Feature -> the cases that exercise it with non-default values, in case order: what a
    verdict says about a feature a scene uses."""
    out: dict[str, list[str]] = {}
    for case in CASES:
        for f in case.exercises:
            out.setdefault(f, []).append(case.name)
    return out

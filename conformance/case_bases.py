"""Which bases a case's measures are held to, read from its code: what docs/clause-coverage.md
credits a case with checking.

A measure takes its basis from a module-level Basis constant (tests/test_spec_quotes.py holds
every spec one to whole sentences of the clause), named either in the case's own module or in a
closed_forms helper its expectation calls. So a case is held to each constant its module names,
and those of the closed_forms functions it names, and of the functions they name in turn
(ballistic's clock, kept_rests_ghost_falls' rests and falls). Read, not run: no backend is needed,
and a branch of a helper the case's scene never takes still counts.
"""

from __future__ import annotations

import ast
import importlib
import inspect
import types

from conformance.cases import closed_forms
from conformance.cases.case import Case
from conformance.results import Basis


def held_to(case: Case) -> dict[str, Basis]:
    """'module.NAME' (where the constant is defined: closed_forms or the case's module) -> the
    Basis, for every basis the case's measures may be held to."""
    module = importlib.import_module(f"conformance.cases.{case.name}")
    out: dict[str, Basis] = {}
    seen: set[types.FunctionType] = set()
    todo: list[tuple[object, types.ModuleType]] = [(module, module)]
    while todo:
        source, home = todo.pop()
        for node in ast.walk(ast.parse(inspect.getsource(source))):
            if not (isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load)):
                continue
            value = vars(home).get(node.id)
            if isinstance(value, Basis):
                where = closed_forms if vars(closed_forms).get(node.id) is value else home
                out[f"{where.__name__.rsplit('.', 1)[-1]}.{node.id}"] = value
            elif inspect.isfunction(value) and value.__module__ == closed_forms.__name__ and value not in seen:
                seen.add(value)
                todo.append((value, closed_forms))
    return out

"""The conformance suite inside any pytest run: `pytest --x3drbp-backend NAME`.

Registered as the pytest11 entry point `x3drbp` (pyproject.toml), so an engine's own test
run in an environment with x3drbp installed can check the engine's adapter. Without
--x3drbp-backend it adds nothing and imports nothing beyond pytest.

    --x3drbp-backend NAME     a registered backend (repeatable)
    --x3drbp-cases NAMES      comma-separated cases (default: all)
    --x3drbp-expectations DIR the BACKEND.toml pins (default: conformance/expectations/);
                              a DIR that is no folder, or a pin file that does not read
                              (FILE:LINE: why), is a usage error before any run

Each (case, backend) is one test item, `x3drbp::CASE[BACKEND]`; the items left after
selection (-k, deselection) run together in parallel at the first one's turn
(conformance.runner.verdicts.run_many, each pair in child processes), and an item fails
when its result differs from its pin (conformance/expectations: a case a file does not
name must pass), with the difference as its message.
"""

from __future__ import annotations

import pytest

_RESULTS = pytest.StashKey[dict]()


def pytest_addoption(parser: pytest.Parser) -> None:
    group = parser.getgroup("x3drbp", "x3drbp conformance suite")
    group.addoption("--x3drbp-backend", action="append", default=[], metavar="NAME",
                    help="run the X3D RigidBodyPhysics conformance cases on this registered backend (repeatable)")
    group.addoption("--x3drbp-cases", action="append", default=[], metavar="NAMES",
                    help="comma-separated conformance cases to run (default: all)")
    group.addoption("--x3drbp-expectations", default=None, metavar="DIR",
                    help="folder of BACKEND.toml pinned verdicts (default: x3drbp's conformance/expectations/)")


def _names(values: list[str]) -> list[str]:
    return [n.strip() for v in values for n in v.split(",") if n.strip()]


def pytest_configure(config: pytest.Config) -> None:
    backends = _names(config.getoption("x3drbp_backend"))
    if not backends:
        return
    from backends import base
    from conformance import cases as C
    from conformance import expectations as E

    known = base.engines()
    unknown = [b for b in backends if b not in known]
    if unknown:
        raise pytest.UsageError(f"--x3drbp-backend: unknown backend(s) {', '.join(unknown)}; "
                                f"known: {', '.join(known)}")
    try:
        cases = C.select(_names(config.getoption("x3drbp_cases")))
    except KeyError as e:
        raise pytest.UsageError(f"--x3drbp-cases: {e.args[0]}") from None
    folder = config.getoption("x3drbp_expectations")
    try:
        pins = {b: E.load(b, folder) for b in dict.fromkeys(backends)}
    except ValueError as e:
        raise pytest.UsageError(f"--x3drbp-expectations: {e}") from None
    config.stash[_RESULTS] = {"cases": cases, "backends": list(dict.fromkeys(backends)), "pins": pins,
                              "results": None}


@pytest.hookimpl(tryfirst=True)  # before -k and -m deselect
def pytest_collection_modifyitems(session: pytest.Session, config: pytest.Config, items: list[pytest.Item]) -> None:
    plan = config.stash.get(_RESULTS, None)
    if plan is None:
        return
    suite = Suite.from_parent(session, name="x3drbp", nodeid="x3drbp")
    items.extend(ConformanceItem.from_parent(suite, name=f"{c.name}[{b}]", case=c, backend=b)
                 for c in plan["cases"] for b in plan["backends"])


class Suite(pytest.Collector):
    """The parent of the conformance items (nodeid `x3drbp`)."""

    def collect(self):
        return []


class ConformanceFailure(Exception):
    """A result that is not its pin."""


class ConformanceItem(pytest.Item):
    def __init__(self, *, case, backend: str, **kw):
        super().__init__(**kw)
        self.case, self.backend = case, backend

    def _results(self) -> dict:
        """Every selected pair's result, run in parallel once, at the first item's turn."""
        plan = self.config.stash[_RESULTS]
        if plan["results"] is None:
            from conformance.runner import verdicts
            wanted = [(i.case, i.backend) for i in self.session.items if isinstance(i, ConformanceItem)]
            done = verdicts.run_many([lambda c=c, b=b: verdicts.run_pair(c, b) for c, b in wanted])
            plan["results"] = {(c.name, b): r for (c, b), r in zip(wanted, done)}
        return plan["results"]

    def runtest(self) -> None:
        from conformance import expectations as E
        from conformance.results import PASS, Expected
        from conformance.runner import verdicts

        r = self._results().get((self.case.name, self.backend)) or verdicts.run_pair(self.case, self.backend)
        pin = self.config.stash[_RESULTS]["pins"][self.backend].get(self.case.name, Expected(PASS))
        self.user_properties.append(("verdict", r.verdict))
        why = E.mismatch(r, pin)
        if why is not None:
            raise ConformanceFailure(why)

    def repr_failure(self, excinfo, style=None):
        if isinstance(excinfo.value, ConformanceFailure):
            return str(excinfo.value)
        return super().repr_failure(excinfo, style)

    def reportinfo(self):
        return self.case.path, None, f"x3drbp: {self.case.name} on {self.backend}"

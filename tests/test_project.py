"""The promises the README makes about setting up and running the project."""

from __future__ import annotations

import ast
import os
import re

from conftest import ROOT


def read(name: str) -> str:
    with open(os.path.join(ROOT, name), encoding="utf-8") as f:
        return f.read()


def test_readme_gives_the_two_commands_and_ci_runs_the_test_one():
    readme, makefile, ci = read("README.md"), read("Makefile"), read(".ci/run")
    assert "make report" in readme and "make test" in readme
    assert re.search(r"^report:", makefile, re.M) and re.search(r"^test:", makefile, re.M)
    assert re.search(r"^make test$", ci, re.M)


def test_readme_says_how_long_the_two_commands_take_and_at_what_load():
    readme = read("README.md")
    timings = readme[readme.index("<!-- timings:"):readme.index("<!-- end of timings -->")]
    rows = [r for r in timings.splitlines() if r.startswith("| `")]
    for command in ("`make test`", "`.ci/run`", "`make report`"):
        mine = [r for r in rows if command in r.split("|")[1]]
        assert mine, f"README states no time for {command}"
        for r in mine:  # | command | took | load average |
            took, load = [c.strip() for c in r.strip("|").split("|")][-2:]
            assert re.search(r"\b(\d+ min( \d+ s)?|\d+ s)\b", took) and re.search(r"\d", load), r


# What each part of the project may import of the others (docs/layout.md: x3d_core's wings,
# files <- model <- traces <- semantics <- encodings, each importing only those before it; then
# backends <- conformance; reports render the suite's results; the command line, x3drbp, on top,
# the only importer of reports). A module's own package may always import itself.
ALLOWED = {
    "x3d_core": set(),
    "x3d_core.files": set(),
    "x3d_core.model": {"x3d_core.files"},
    "x3d_core.traces": {"x3d_core.files", "x3d_core.model"},
    "x3d_core.semantics": {"x3d_core.files", "x3d_core.model", "x3d_core.traces"},
    "x3d_core.encodings": {"x3d_core.files", "x3d_core.model", "x3d_core.traces", "x3d_core.semantics"},
    "backends": {"x3d_core"},
    "conformance": {"x3d_core", "backends"},  # its loose modules (coverage, clause text): any of the suite
    "conformance.results": {"x3d_core"},
    "conformance.cases": {"x3d_core", "conformance.results"},
    "conformance.expectations": {"x3d_core", "conformance.results"},  # x3d_core: the input guards
    "conformance.runner": {"x3d_core", "backends", "conformance.results", "conformance.cases"},
    "conformance.analyses": {"x3d_core", "backends", "conformance.results", "conformance.cases", "conformance.runner"},
    "conformance.browsers": {"x3d_core", "conformance.results", "conformance.cases", "conformance.runner",
                             "conformance.analyses"},
    "conformance.pytest_plugin": {"conformance.results", "conformance.cases", "conformance.runner",
                                  "conformance.expectations", "backends"},
    "reports": {"x3d_core", "conformance.results"},
    "x3drbp": {"x3d_core", "backends", "conformance", "reports"},
    # a command of its own (`python -m conformance.mutants`), on top as x3drbp's are: their option types
    "conformance.mutants.__main__": {"x3d_core", "backends", "conformance", "x3drbp"},
}
PACKAGES = ("x3d_core", "backends", "conformance", "reports", "x3drbp")
ENGINES = ("pybullet", "mujoco", "dartpy", "pymunk", "rerun", "matplotlib", "dask")


def _modules() -> dict[str, str]:
    """Every project module's dotted name and path."""
    out = {}
    for top in PACKAGES:
        for folder, _, files in os.walk(os.path.join(ROOT, top)):
            for name in files:
                if name.endswith(".py") and "node_modules" not in folder:
                    rel = os.path.relpath(os.path.join(folder, name), ROOT)[:-3].replace(os.sep, ".")
                    out[rel.removesuffix(".__init__")] = os.path.join(folder, name)
    return out


def _imports(path: str, module: str, modules: dict[str, str]) -> set[str]:
    """What a module imports, at any depth of its code (lazy imports count too): `from P
    import M` is M where M is a module, else P."""
    tree = ast.parse(read(path))
    for node in ast.walk(tree):  # imports for type checkers only are no dependency
        if isinstance(node, ast.If) and getattr(node.test, "id", None) == "TYPE_CHECKING":
            node.body = []
    package = module if path.endswith("__init__.py") else module.rpartition(".")[0]
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = ".".join(package.split(".")[:len(package.split(".")) - node.level + 1] + ([base] if base else []))
            out.update(f"{base}.{a.name}" if f"{base}.{a.name}" in modules else base for a in node.names)
    return out


def _rule(module: str) -> str:
    """The most specific entry of ALLOWED the module falls under."""
    return max((k for k in ALLOWED if module == k or module.startswith(k + ".")), key=len)


def _within(name: str, allowed: set[str]) -> bool:
    return any(name == a or name.startswith(a + ".") for a in allowed)


def test_each_part_imports_only_what_it_may():
    modules = _modules()
    for module, path in modules.items():
        rule = _rule(module)
        for name in _imports(path, module, modules):
            top = name.split(".")[0]
            if top in ENGINES and _within(rule, {"x3d_core", "conformance.results", "conformance.cases"}):
                raise AssertionError(f"{module} imports {name}: no engine or renderer below the backends")
            if top in PACKAGES and not _within(name, ALLOWED[rule] | {rule}):
                raise AssertionError(f"{module} imports {name}, outside what {rule} may import")


def test_the_import_graph_has_no_cycle():
    modules = _modules()
    graph = {m: {n for n in (_known(i, modules) for i in _imports(p, m, modules)) if n and n != m} for m, p in modules.items()}
    state: dict[str, int] = {}

    def visit(m: str, path: list[str]) -> None:
        state[m] = 1
        for n in sorted(graph[m]):
            if state.get(n) == 1:
                raise AssertionError("import cycle: " + " -> ".join(path[path.index(n):] + [m, n]))
            if n not in state:
                visit(n, path + [m])
        state[m] = 2

    for m in sorted(graph):
        if m not in state:
            visit(m, [])


def _known(name: str, modules: dict[str, str]) -> str | None:
    """The project module an imported name is (a name imported from a module is that module)."""
    while name and name not in modules:
        name = name.rpartition(".")[0]
    return name or None

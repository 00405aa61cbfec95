"""Engines as installable modules, and the conformance suite as a pytest plugin.

A backend outside the tree is made discoverable the way an installed distribution is,
without pip and without touching the virtualenv: a `*.dist-info` folder (METADATA and
entry_points.txt) beside the module, in a folder on PYTHONPATH. The runner's child
processes inherit the environment, so they find it too.
"""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
import tomllib

import pytest

from backends import base
from conformance import cases as C
from conformance.results import PASS, UNSUPPORTED
from conformance.runner import probe, verdicts

from conftest import ROOT, needs_ode

pytest_plugins = ["pytester"]

ADAPTER = os.path.join(ROOT, "docs", "example_adapter")
MUJOCO = importlib.util.find_spec("mujoco") is not None


def install(site, dist: str, modules: dict[str, str], entry_points: dict[str, str]) -> None:
    """A distribution `dist` in the folder `site`, as pip leaves one: the modules (name:
    source file, linked) and a dist-info declaring the x3drbp.backends entry points."""
    site.mkdir(exist_ok=True)
    for name, source in modules.items():
        (site / f"{name}.py").symlink_to(source)
    info = site / f"{dist.replace('-', '_')}-0.1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {dist}\nVersion: 0.1.0\n")
    lines = [f"{name} = {value}" for name, value in entry_points.items()]
    (info / "entry_points.txt").write_text("\n".join([f"[{base.GROUP}]", *lines, ""]))


def on_path(monkeypatch, *folders) -> None:
    """The folders first on the PYTHONPATH the runner's children inherit."""
    kept = [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([*map(str, folders), *kept]))


@pytest.fixture
def euler(tmp_path, monkeypatch):
    """docs/example_adapter installed (its own pyproject.toml's entry points) in tmp_path/site."""
    with open(os.path.join(ADAPTER, "pyproject.toml"), "rb") as f:
        declared = tomllib.load(f)["project"]["entry-points"][base.GROUP]
    assert declared == {"euler": "x3drbp_euler:BACKEND"}
    site = tmp_path / "site"
    install(site, "x3drbp-euler", {"x3drbp_euler": os.path.join(ADAPTER, "x3drbp_euler.py")}, declared)
    on_path(monkeypatch, site)
    return site


@pytest.fixture
def fresh_registry():
    """base's registry read again now, and again after the test (sys.path back as it was)."""
    base._registry.cache_clear()
    yield
    base._registry.cache_clear()


def cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "x3drbp", *args], cwd=ROOT, capture_output=True,
                          text=True, timeout=120, stdin=subprocess.DEVNULL)


# -- the registry ----------------------------------------------------------------------

def test_the_in_tree_backends_come_first_from_their_entry_points():
    reg = base.registry()
    assert base.engines()[:len(base.IN_TREE)] == base.IN_TREE
    assert all(reg[n].value == f"backends.{n}:BACKEND" for n in base.IN_TREE)
    with open(os.path.join(ROOT, "pyproject.toml"), "rb") as f:
        declared = tomllib.load(f)["project"]["entry-points"][base.GROUP]
    assert declared == {n: f"backends.{n}:BACKEND" for n in base.IN_TREE}


@needs_ode
def test_loading_one_backend_imports_no_other_engine():
    code = ("import sys; from backends import base; base.engines(); base.load('ode'); "
            "print(sorted(m for m in ('pybullet', 'mujoco', 'dartpy', 'pymunk') if m in sys.modules))")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert done.stdout.strip().splitlines()[-1] == "[]", done.stderr


def test_an_installed_adapter_is_listed_and_runs(euler, tmp_path):
    listed = cli("backends")
    assert listed.returncode == 0, listed.stderr
    lines = listed.stdout.splitlines()
    assert any(ln.startswith("euler 0.1.0 (numpy ") for ln in lines), lines
    assert [ln.split()[0].rstrip(":") for ln in lines if ln and not ln.startswith(" ")][:len(base.IN_TREE)] == \
        list(base.IN_TREE)
    trace = tmp_path / "free_fall.csv"
    ran = cli("run", C.BY_NAME["free_fall"].path, "--backend", "euler", "--trace", str(trace))
    assert ran.returncode == 0, ran.stderr
    assert trace.read_text().count("\n") > 10
    assert "euler" in cli("run", "--help").stdout


def test_an_installed_adapter_gets_verdicts(euler):
    free_fall = verdicts.run_pair(C.BY_NAME["free_fall"], "euler")
    assert free_fall.verdict == PASS, free_fall.reason
    hinge = verdicts.run_pair(C.BY_NAME["pendulum_period"], "euler")
    assert hinge.verdict == UNSUPPORTED
    assert "SingleAxisHingeJoint, SingleAxisHingeJoint.axis = 0 0 1 (2 uses): this engine integrates free bodies " \
        "only: it builds no joints" in hinge.reason


def test_an_entry_point_that_fails_to_import_is_unavailable_and_the_others_load(euler, tmp_path, monkeypatch):
    broken = tmp_path / "x3drbp_broken.py"
    broken.write_text("raise RuntimeError('no licence for this engine')\n")
    other = tmp_path / "other"
    install(other, "x3drbp-broken", {"x3drbp_broken": str(broken)},
            {"broken": "x3drbp_broken:BACKEND", "absent": "x3drbp_absent_module:BACKEND"})
    on_path(monkeypatch, euler, other)
    listed = cli("backends")
    assert listed.returncode == 0, listed.stderr
    lines = listed.stdout.splitlines()
    assert "broken: unavailable: x3drbp_broken:BACKEND: RuntimeError: no licence for this engine" in lines
    assert "absent: unavailable: No module named 'x3drbp_absent_module'" in lines
    assert any(ln.startswith("euler 0.1.0") for ln in lines)
    if MUJOCO:
        assert any(ln.startswith("mujoco ") for ln in lines)
    table = probe.backend_table()
    assert table["broken"].unavailable == "x3drbp_broken:BACKEND: RuntimeError: no licence for this engine"
    assert table["euler"].usable
    r = verdicts.run_pair(C.BY_NAME["free_fall"], "broken")
    assert r.verdict != PASS and "no licence for this engine" in r.reason


def test_two_entry_points_of_one_name_the_first_wins_with_a_note(euler, tmp_path, monkeypatch, fresh_registry):
    late = tmp_path / "late"
    install(late, "x3drbp-late", {}, {"euler": "x3drbp_late:BACKEND", "mujoco": "x3drbp_late:MUJOCO"})
    for folder in (late, euler):  # euler's folder first on sys.path, as on PYTHONPATH
        monkeypatch.syspath_prepend(str(folder))
    base._registry.cache_clear()
    reg = base.registry()
    assert reg["euler"].value == "x3drbp_euler:BACKEND" and reg["mujoco"].value == "backends.mujoco:BACKEND"
    notes = base.registry_notes()
    assert len(notes) == 2
    assert any("'mujoco'" in n and "x3drbp_late:MUJOCO (x3drbp-late) ignored" in n for n in notes), notes
    on_path(monkeypatch, euler, late)
    listed = cli("backends")
    assert "note: backend 'euler': entry point x3drbp_late:BACKEND (x3drbp-late) ignored" in listed.stderr


def test_an_unknown_backend_names_the_known_ones():
    with pytest.raises(KeyError, match="known: bullet, mujoco, dart, ode, pymunk"):
        base.load("nope")


# -- the pytest plugin -----------------------------------------------------------------

def test_the_plugin_adds_nothing_unless_asked(pytester):
    pytester.makepyfile("def test_one():\n    pass\n")
    result = pytester.runpytest("--co", "-q", "-p", "no:cacheprovider")
    assert result.ret == 0
    assert "x3drbp" not in result.stdout.str()
    assert "--x3drbp-backend" in pytester.runpytest("--help").stdout.str()


@pytest.mark.skipif(not MUJOCO, reason="mujoco is not installed")
def test_the_plugin_runs_cases_on_a_backend(pytester):
    pytester.makepyfile("def test_one():\n    pass\n")
    result = pytester.runpytest("-v", "-p", "no:cacheprovider", "--x3drbp-backend", "mujoco",
                                "--x3drbp-cases", "free_fall,gravity_off")
    result.assert_outcomes(passed=3)
    result.stdout.fnmatch_lines(["*x3drbp::free_fall[[]mujoco[]] PASSED*", "*x3drbp::gravity_off[[]mujoco[]] PASSED*"])


def test_the_plugin_with_an_installed_adapter(pytester, euler):
    args = ["-v", "-p", "no:cacheprovider", "--x3drbp-backend", "euler",
            "--x3drbp-cases", "free_fall,pendulum_period,box_stack"]
    pinned = pytester.runpytest_subprocess(*args, "--x3drbp-expectations", os.path.join(ADAPTER, "expectations"))
    pinned.assert_outcomes(passed=3)
    pinned.stdout.fnmatch_lines(["*x3drbp::pendulum_period[[]euler[]] PASSED*"])
    unpinned = pytester.runpytest_subprocess(*args, "-k", "pendulum")  # x3drbp's own pins: none for euler
    unpinned.assert_outcomes(failed=1)
    unpinned.stdout.fnmatch_lines(["pendulum_period on euler: expected pass, got unsupported: "
                                   "SingleAxisHingeJoint, SingleAxisHingeJoint.axis = 0 0 1 (2 uses): this engine integrates "
                                   "free bodies only*"])


def test_the_plugin_refuses_an_unknown_backend(pytester):
    result = pytester.runpytest("--x3drbp-backend", "nope")
    assert result.ret == pytest.ExitCode.USAGE_ERROR
    result.stderr.fnmatch_lines(["*--x3drbp-backend: unknown backend(s) nope; known: bullet, mujoco, dart, ode, pymunk*"])


# -- plug-ins that crash, hang or cannot say their version ------------------------------------

NO_VERSION = """from backends import base
class Backend(base.Backend):
    name, declared = "noversion", {}
    def version(self):
        raise RuntimeError("no licence server")
    def build(self, world, dt):
        raise NotImplementedError
BACKEND = Backend()
"""


@pytest.fixture
def faulty(tmp_path, monkeypatch):
    """Three plug-ins: `segv` crashes the interpreter on import, `hang` sleeps on import (having
    left the file tmp_path/hang-imported), `noversion` imports but its version() raises."""
    sources = {"x3drbp_segv": "import ctypes\nctypes.string_at(0)\n",
               "x3drbp_hang": f"import time\nopen({str(tmp_path / 'hang-imported')!r}, 'w').close()\ntime.sleep(600)\n",
               "x3drbp_noversion": NO_VERSION}
    for module, source in sources.items():
        (tmp_path / f"{module}.py").write_text(source)
    site = tmp_path / "site"
    install(site, "x3drbp-faulty", {m: str(tmp_path / f"{m}.py") for m in sources},
            {m.split("_")[1]: f"{m}:BACKEND" for m in sources})
    on_path(monkeypatch, site)
    monkeypatch.syspath_prepend(str(site))  # for this process's registry too (fresh_registry)
    return tmp_path / "hang-imported"


def test_backends_lists_a_plug_in_that_crashes_hangs_or_cannot_say_its_version(faulty):
    listed = cli("backends", "--timeout", "5")
    assert listed.returncode == 0 and "Traceback" not in listed.stderr, listed
    lines = listed.stdout.splitlines()
    assert [ln.split()[0].rstrip(":") for ln in lines][:len(base.IN_TREE)] == list(base.IN_TREE)
    assert "hang: unavailable: the backend probe gave no answer within 5 s (importing it or asking its version)" in lines
    assert "noversion: unavailable: version() failed: RuntimeError: no licence server" in lines
    assert any(ln.startswith("segv: unavailable: killed by SIGSEGV") for ln in lines), lines
    if MUJOCO:
        assert any(ln.startswith("mujoco ") and "unavailable" not in ln for ln in lines)


def test_a_command_whose_backends_leave_a_hanging_plug_in_out_never_imports_it(faulty, tmp_path, fresh_registry):
    ran = cli("conformance", "--cases", "free_fall", "--backends", "pymunk", "--out", str(tmp_path / "out"), "-q")
    assert ran.returncode == 0, ran.stderr
    assert not faulty.exists()  # its import never ran: it cost the command nothing
    info = probe.backend_table(5, ["hang", "pymunk"])  # named, it costs one probe of at most 5 s
    assert faulty.exists() and not info["hang"].usable and info["pymunk"].usable


WANDER = """import os
from backends.pymunk import BACKEND as _REAL
AWAY = {away!r}
os.chdir(AWAY)


class Wander:
    \"\"\"pymunk, changing directory on import and at every build.\"\"\"

    def __getattr__(self, name):
        return getattr(_REAL, name)

    def build(self, world, dt):
        os.chdir(AWAY)
        return _REAL.build(world, dt)


BACKEND = Wander()
"""


def test_outputs_go_where_the_command_was_run_whatever_directory_a_plug_in_moves_to(tmp_path, monkeypatch):
    pytest.importorskip("pymunk")
    away, here = tmp_path / "away", tmp_path / "here"
    away.mkdir()
    here.mkdir()
    (tmp_path / "x3drbp_wander.py").write_text(WANDER.format(away=str(away)))
    site = tmp_path / "site"
    install(site, "x3drbp-wander", {"x3drbp_wander": str(tmp_path / "x3drbp_wander.py")},
            {"wander": "x3drbp_wander:BACKEND"})
    on_path(monkeypatch, site, ROOT)
    (here / "fall.x3d").write_bytes(open(C.BY_NAME["free_fall"].path, "rb").read())
    ran = subprocess.run([sys.executable, "-m", "x3drbp", "run", "fall.x3d", "--backend", "wander",
                          "--trace", "t.csv", "--timing", "timing.json", "--rerun", "r.rrd"],
                         cwd=here, capture_output=True, text=True, timeout=120, stdin=subprocess.DEVNULL)
    assert ran.returncode == 0, ran.stderr
    assert sorted(os.listdir(here)) == ["fall.x3d", "r.rrd", "t.csv", "timing.json"]
    assert os.listdir(away) == []

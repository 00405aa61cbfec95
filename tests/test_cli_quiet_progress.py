"""`x3drbp --version`; `run -q/-v` and the notes of the runs a command starts, said once per
scene and backend; the progress bar of the commands that run many children, on a terminal
only; and the traces stability's reasons cite, kept under its output folder."""

from __future__ import annotations

import importlib.metadata
import io
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import tomllib

import pytest

from backends import base
from conftest import ROOT, SCENES
from conformance import cases as C
import x3drbp as cli
from conformance import results
from conformance.analyses import stability as S
from x3drbp import main as cli_main
from x3drbp.run import LEAD, NAMED, approximation
from conformance.results import Settings
from conformance.runner import children, verdicts
from reports.text import link
from x3d_core.encodings.load import load
from x3d_core.semantics.analysis import Use

from fake_child import fake_python

BACKEND = "mujoco"  # a dependency, installed wherever the project is
BALL = os.path.join(SCENES, "examples", "bouncing_ball.x3dj")  # mujoco: one note for two uses
IMPACT = S.BY_NAME["thin_wall_impact"]  # 0.25 s; mujoco notes its BOUNCE; it tunnels at 1/60 and 1/240


class Terminal(io.StringIO):
    """A standard error that says it is a terminal, keeping what was written."""

    def isatty(self) -> bool:
        return True


def _approximated(backend: str, path: str) -> dict[str, list[Use]]:
    """The backend's notes on the scene, each with the uses it covers (what `x3drbp run` groups)."""
    out: dict[str, list[str]] = {}
    for use, d in base.judged(base.load(backend), load(path)):
        if d.support is base.Support.APPROXIMATE:
            out.setdefault(d.note, []).append(use)
    return out


def _note_lines(text: str) -> list[str]:
    return [ln for ln in text.splitlines() if ": note: " in ln]


def _run(argv: list[str], monkeypatch: pytest.MonkeyPatch) -> tuple[int, str]:
    """A command in this process, its stderr a terminal: (exit status, what it wrote there)."""
    err = Terminal()
    with monkeypatch.context() as m:
        m.setattr(sys, "stderr", err)
        m.setattr(sys, "stdout", io.StringIO())
        code = cli_main(argv)
    return code, err.getvalue()


# -- --version ------------------------------------------------------------------------------------

def test_version_is_the_installed_distributions(capsys):
    with pytest.raises(SystemExit) as e:
        cli_main(["--version"])
    assert e.value.code == 0
    assert capsys.readouterr().out == f"x3drbp {importlib.metadata.version('x3drbp')}\n"
    done = subprocess.run([sys.executable, "-m", "x3drbp", "--version"], cwd=ROOT, capture_output=True,
                          text=True, timeout=60)
    assert (done.returncode, done.stdout, done.stderr) == (0, f"x3drbp {importlib.metadata.version('x3drbp')}\n", "")


def test_version_without_installed_metadata_is_pyprojects(tmp_path, monkeypatch, capsys):
    def missing(name: str) -> str:
        raise importlib.metadata.PackageNotFoundError(name)

    monkeypatch.setattr(importlib.metadata, "version", missing)
    with open(os.path.join(ROOT, "pyproject.toml"), "rb") as f:
        assert cli.version() == tomllib.load(f)["project"]["version"]
    other = tmp_path / "pyproject.toml"
    other.write_text('[project]\nname = "x3drbp"\nversion = "9.8.7"\n')
    monkeypatch.setattr(cli, "PYPROJECT", str(other))
    with pytest.raises(SystemExit) as e:
        cli_main(["--version"])
    assert e.value.code == 0 and capsys.readouterr().out == "x3drbp 9.8.7\n"


# -- run -q / -v ------------------------------------------------------------------------------------

def test_run_says_each_note_in_one_bounded_line_and_each_refusal_reason_once(tmp_path, capsys):
    """DART's notes on a scene ran to 1,900 characters, every use with its value and the whole
    note; ODE's hinge2 refused by pymunk was 10 to 15 lines of one reason, one per field."""
    pytest.importorskip("dartpy")
    pytest.importorskip("pymunk")
    bound = len(BALL) + 40 + NAMED * 60 + LEAD + 30  # the scene, the words, the features, the note's lead
    lines = {}
    for flags in ((), ("-v",)):
        code = cli_main(["run", BALL, "--backend", "dart", "--duration", "0.02", "--trace", str(tmp_path / "t.csv"),
                         *flags])
        assert code == 0
        lines[flags] = _note_lines(capsys.readouterr().err)
    assert lines[()] and all(len(line) <= bound for line in lines[()])
    notes = _approximated("dart", BALL)
    assert any(len(note) > LEAD for note in notes)  # a note the default line cuts: -v says it whole
    assert all(any(line.endswith(f": {note}") for line in lines[("-v",)]) for note in notes)
    hinge2 = C.BY_NAME["hinge2_steering"].path
    assert cli_main(["run", hinge2, "--backend", "pymunk", "--trace", str(tmp_path / "u.csv")]) == 3
    (refusal,) = [ln for ln in capsys.readouterr().err.splitlines() if "unsupported by pymunk" in ln]
    assert re.search(r"DoubleAxisHingeJoint, .* \(\d+ uses\): ODE's hinge2", refusal) and refusal.count("hinge2:") == 1


def test_run_notes_once_per_approximation_every_use_with_v_none_with_q(tmp_path, capsys):
    groups = _approximated(BACKEND, BALL)
    assert any(len(uses) > 1 for uses in groups.values())  # a note two uses share: grouping shows
    prefix = f"{BALL}: note: {BACKEND} approximates"
    wanted = {(): [f"{prefix} {approximation(uses, note)}" for note, uses in groups.items()],
              ("-v",): [f"{prefix} {use}: {note}" for note, uses in groups.items() for use in uses],
              ("-q",): []}
    for flags, lines in wanted.items():
        trace = tmp_path / f"t{len(flags)}{''.join(flags)}.csv"
        assert cli_main(["run", BALL, "--backend", BACKEND, "--duration", "0.05", "--trace", str(trace), *flags]) == 0
        assert _note_lines(capsys.readouterr().err) == lines, flags
        assert trace.read_text().startswith("time,node,field,value")  # -q changes what is said, not the run


def test_run_q_and_v_together_is_one_line_of_usage(capsys):
    with pytest.raises(SystemExit) as e:
        cli_main(["run", BALL, "--backend", BACKEND, "-q", "-v"])
    err = capsys.readouterr().err
    assert e.value.code == 2 and "not allowed with" in err and "Traceback" not in err


# -- the notes of a command's children --------------------------------------------------------------

# an `x3drbp run` that notes an approximation, then fails: $4 is the scene, $6 the backend
NOTING = """echo "$*" >> {log}
echo "$4: note: $6 approximates A.b: how it is approximated" >&2
echo "$4: $6 failed: RuntimeError: boom" >&2
exit 1
"""


@pytest.mark.skipif(sys.platform == "win32", reason="shell scripts")
def test_childrens_notes_once_per_command_every_one_with_v_none_with_q(tmp_path, monkeypatch, capsys):
    log = tmp_path / "argv.log"
    monkeypatch.setattr(children.sys, "executable", fake_python(tmp_path, NOTING.format(log=log)))
    note = "s.x3d: note: fake approximates A.b: how it is approximated"

    def two_runs() -> list[children.Outcome]:
        return [children.run_child("s.x3d", "fake", Settings(0.1, 1 / 60), str(tmp_path / f"{k}.csv"))
                for k in range(2)]

    for verbosity, flag, said in ((children.DEFAULT, None, [note]), (children.VERBOSE, "-v", [note, note]),
                                  (children.QUIET, "-q", [])):
        log.write_text("")
        with children.notes_shown(verbosity):
            outs = two_runs()
            assert capsys.readouterr().err == ""  # said after the runs, not as they end
        assert capsys.readouterr().err.splitlines() == said
        # the note is no part of the verdict's reason: that is the run's failure alone
        assert [(o.verdict, o.reason) for o in outs] == [(results.ERROR, "s.x3d: fake failed: RuntimeError: boom")] * 2
        told = [line.split() for line in log.read_text().splitlines()]
        assert len(told) == 2 and all(("-q" in t, "-v" in t) == (flag == "-q", flag == "-v") for t in told)
    log.write_text("")
    two_runs()  # no command to say them: the children are told -q
    assert capsys.readouterr().err == "" and all("-q" in ln.split() for ln in log.read_text().splitlines())


# -- stability: one run of the command, read by several tests ----------------------------------------

@pytest.fixture(scope="module")
def stability(tmp_path_factory) -> tuple[str, str]:
    """`x3drbp stability` of the impact on mujoco at two steps, stderr a terminal: (out, stderr)."""
    out = str(tmp_path_factory.mktemp("stability"))
    with pytest.MonkeyPatch.context() as m:
        code, err = _run(["stability", "--cases", IMPACT.name, "--backends", BACKEND, "--dts", "1/60,1/240",
                          "--out", out], m)
    assert code == 0, err
    return out, err


def _shown(path: str) -> str:
    """A scene's path as a command's notes name it: from where the command runs (the tests: the root)."""
    return os.path.relpath(path)


def _impact_notes() -> list[str]:
    return [f"{_shown(IMPACT.path)}: note: {BACKEND} approximates {approximation(uses, note)}"
            for note, uses in _approximated(BACKEND, IMPACT.path).items()]


def test_stability_says_a_scenes_notes_once_for_its_runs_at_every_step(stability):
    notes = _impact_notes()
    assert notes and sorted(_note_lines(stability[1])) == sorted(notes)


def test_stability_v_says_every_runs_notes_and_q_none_and_no_bar(tmp_path, monkeypatch):
    argv = ["stability", "--cases", IMPACT.name, "--backends", BACKEND, "--dts", "1/60,1/240"]
    code, err = _run([*argv, "--out", str(tmp_path / "v"), "-v"], monkeypatch)
    one_per_use = [f"{_shown(IMPACT.path)}: note: {BACKEND} approximates {use}: {note}"
                   for note, uses in _approximated(BACKEND, IMPACT.path).items() for use in uses]
    assert code == 0 and sorted(_note_lines(err)) == sorted(one_per_use * 2)  # two runs, each its notes
    code, err = _run([*argv, "--out", str(tmp_path / "q"), "-q"], monkeypatch)
    assert code == 0 and _note_lines(err) == [] and "2/2" not in err


def test_stability_draws_a_bar_of_runs_done_on_a_terminal_only(stability, tmp_path, capsys):
    assert re.search(r"2/2 \[", stability[1])
    assert cli_main(["stability", "--cases", IMPACT.name, "--backends", BACKEND, "--dts", "1/60",
                     "--out", str(tmp_path)]) == 0
    assert "1/1" not in capsys.readouterr().err  # stderr not a terminal: no bar


def test_stability_links_the_traces_its_reasons_cite_and_they_exist(stability):
    out = stability[0]
    with open(os.path.join(out, "stability.json"), encoding="utf-8") as f:
        data = json.load(f)
    with open(os.path.join(out, "stability.md"), encoding="utf-8") as f:
        text = f.read()
    broke = [r for r in data["results"] if r["verdict"] not in S.HELD]
    assert broke, "the impact tunnels: a reason to cite its trace"
    for r in broke:
        assert r["trace"] == S.trace_name(r["case"], r["backend"], r["dt"])
        assert link(r["trace"]) in text
    links = re.findall(r"\]\(([^)]+)\)", text)
    assert sorted(links) == sorted(r["trace"] for r in broke)
    for target in links:
        with open(os.path.join(out, target), encoding="utf-8") as f:  # relative to stability.md, whole
            assert f.readline() == "time,node,field,value\n"
    assert sorted(os.listdir(os.path.join(out, S.TRACES))) == sorted(os.path.basename(r["trace"]) for r in broke)
    assert tempfile.gettempdir() not in text.replace(out, "")


# an `x3drbp run` that writes a frame and blows up, saying where it wrote the frames before
BLOWS_UP = """while [ "$1" != "--trace" ]; do shift; done
printf 'time,node,field,value\\n0,Pellet,position,0 0 0\\n' > "$2"
echo "s.x3d: fake: blew up by t=0.35: huge (the frames before it written to $2)" >&2
exit 1
"""


@pytest.mark.skipif(sys.platform == "win32", reason="shell scripts")
def test_a_blown_up_runs_frames_are_kept_and_removed_once_a_later_run_leaves_none(tmp_path, monkeypatch):
    out = tmp_path / "out"
    monkeypatch.setattr(children.sys, "executable", fake_python(tmp_path, BLOWS_UP))
    r = S.run_one(IMPACT, "fake", 1 / 60, timeout=10, out=str(out))
    assert (r.verdict, r.at, r.reason) == (results.BLEW_UP, 0.35, "blew up by t=0.35: huge")
    assert r.trace == "traces/thin_wall_impact-fake-1_60.csv" and r.to_json()["trace"] == r.trace
    assert (out / r.trace).read_text() == "time,node,field,value\n0,Pellet,position,0 0 0\n"
    monkeypatch.setattr(children.sys, "executable",
                        fake_python(tmp_path, "echo 's.x3d: unsupported by fake: no' >&2; exit 3\n"))
    again = S.run_one(IMPACT, "fake", 1 / 60, timeout=10, out=str(out))
    assert again.verdict == results.UNSUPPORTED and again.trace is None
    assert os.listdir(out / S.TRACES) == []  # no file that no result cites


# -- progress of conformance and compare ------------------------------------------------------------

def test_run_many_draws_its_bar_only_when_asked(monkeypatch):
    err = Terminal()
    monkeypatch.setattr(sys, "stderr", err)
    assert verdicts.run_many([lambda k=k: k for k in range(3)], 2) == [0, 1, 2]
    assert err.getvalue() == ""
    assert verdicts.run_many([lambda k=k: k for k in range(3)], 2, progress=True) == [0, 1, 2]
    assert re.search(r"3/3 \[", err.getvalue())


def test_conformance_draws_its_bar_on_a_terminal_and_not_with_q(tmp_path, monkeypatch):
    argv = ["conformance", "--cases", "free_fall,projectile", "--backends", BACKEND, "--out", str(tmp_path)]
    code, err = _run(argv, monkeypatch)
    assert code == 0 and re.search(r"2/2 \[", err)
    code, err = _run([*argv, "--quiet"], monkeypatch)
    assert code == 0 and "2/2" not in err


def test_compare_draws_its_bar_on_a_terminal_and_says_each_backends_notes_once(monkeypatch):
    pair = [BACKEND, "bullet"]  # both dependencies; each notes the ball's bounce
    argv = ["compare", BALL, "--backends", ",".join(pair), "--duration", "0.1"]
    code, err = _run(argv, monkeypatch)
    assert code == 0 and re.search(r"2/2 \[", err)
    assert sorted(_note_lines(err)) == sorted(f"{_shown(BALL)}: note: {b} approximates {approximation(uses, note)}"
                                              for b in pair for note, uses in _approximated(b, BALL).items())
    code, err = _run([*argv, "-q"], monkeypatch)
    assert code == 0 and "2/2" not in err and _note_lines(err) == []


def test_the_report_page_links_stabilitys_traces_where_they_are(stability, tmp_path):
    """The report gathers stability.md under DIR/stability: its trace links, moved into that
    folder, still lead to the files."""
    from reports.report_page import report_markdown
    shutil.copytree(stability[0], tmp_path / "stability")
    (tmp_path / "report.json").write_text(json.dumps({"generated": "now", "cpus": 2, "backends": {},
                                                      "timings_s": {"total": 1.0}, "failed": []}))
    text = report_markdown(str(tmp_path))
    links = [link for link in re.findall(r"\]\(([^)#]+)\)", text) if link.endswith(".csv")]
    assert links and all(link.startswith(f"stability/{S.TRACES}/") for link in links)
    assert all((tmp_path / link).is_file() for link in links)

"""The run cache (conformance/runner/cache.py): a run reused is the run made, to the byte and
the verdict; anything the run depends on changed is a new run; an entry that does not read
back whole is a miss, never an error; --no-cache and X3DRBP_CACHE=off run every run afresh."""

from __future__ import annotations

import os
import shutil

import numpy as np
import pytest

from conftest import ROOT
from conformance import results
from x3drbp import main
from x3drbp import report as R
from conformance.results import Settings
from conformance.runner import cache, children, probe

PENDULUM = os.path.join(ROOT, "scenes", "examples", "pendulum.x3d")
SHORT = Settings(0.25, 1 / 240)


@pytest.fixture
def cached(tmp_path, monkeypatch):
    """The cache on, in a folder of the test's own (the suite runs with it off: conftest.py)."""
    folder = tmp_path / "cache"
    monkeypatch.setenv(cache.ENV, str(folder))
    # what a test learns stays in it, and none an earlier test learned (a plug-in: no key) reaches it
    monkeypatch.setattr(cache, "_versions", {})
    return folder


@pytest.fixture
def counted(monkeypatch):
    """The runs actually started (children._started), by their command lines."""
    started: list[list[str]] = []
    real = children._started

    def start(cmd, timeout, backend):
        started.append(cmd)
        return real(cmd, timeout, backend)
    monkeypatch.setattr(children, "_started", start)
    return started


@pytest.fixture(scope="module")
def bullet() -> str:
    if not probe.backend_table(names=["bullet"])["bullet"].usable:
        pytest.skip("bullet is not installed")
    return "bullet"


def _entries(folder) -> list[str]:
    return sorted(os.path.join(d, n) for d, _, names in os.walk(folder) for n in names)


def test_a_reused_run_gives_the_very_trace_timing_and_verdict_the_run_gave(tmp_path, cached, counted, bullet):
    first, second = tmp_path / "a.npz", tmp_path / "b.npz"
    timing = [tmp_path / "a.timing.json", tmp_path / "b.timing.json"]
    made = children.run_child(PENDULUM, bullet, SHORT, str(first), extra=("--timing", str(timing[0])))
    again = children.run_child(PENDULUM, bullet, SHORT, str(second), extra=("--timing", str(timing[1])))
    assert len(counted) == 1 and len(_entries(cached)) == 1  # the second was read back, not run
    assert made == again == children.Outcome(None)
    assert first.read_bytes() == second.read_bytes()
    assert timing[0].read_bytes() == timing[1].read_bytes()  # the timing measured when it ran


def test_the_scene_s_bytes_the_settings_and_the_backend_each_make_a_new_run(tmp_path, cached, counted, bullet):
    scene = tmp_path / "pendulum.x3d"
    shutil.copy(PENDULUM, scene)
    trace = str(tmp_path / "t.npz")
    children.run_child(str(scene), bullet, SHORT, trace)
    children.run_child(PENDULUM, bullet, SHORT, trace)  # another path, the same bytes: reused
    assert len(counted) == 1
    scene.write_text(scene.read_text().replace("<Scene>", "<Scene><WorldInfo title='moved'/>", 1))
    children.run_child(str(scene), bullet, SHORT, trace)
    children.run_child(PENDULUM, bullet, SHORT.with_dt(1 / 120), trace)
    children.run_child(PENDULUM, bullet, SHORT, trace, extra=("--repeat", "2"))
    assert len(counted) == 4
    cache.learn({"bullet": "3.2.7", "mujoco": "3.0.0"})
    argv = ["run", PENDULUM, "--backend", "bullet", "--trace", trace]
    keys = {cache.entry(argv, "bullet", ROOT).path, cache.entry([*argv[:3], "mujoco", *argv[4:]], "mujoco", ROOT).path}
    cache.learn({"bullet": "3.2.8"})  # a new engine version
    keys.add(cache.entry(argv, "bullet", ROOT).path)
    assert len(keys) == 3


def test_a_run_blown_up_is_reused_naming_this_run_s_scene_and_trace(tmp_path, cached):
    """A kept run's stderr names the paths of the run that reuses it (the frames before a blow-up are
    'written to' its own trace; a note names its own scene), and a refusal's absent trace stays absent."""
    cache.learn({"bullet": "3.2.7"})
    copies = [tmp_path / "one" / "s.x3d", tmp_path / "two" / "s.x3d"]
    for c in copies:
        c.parent.mkdir()
        shutil.copy(PENDULUM, c)
    traces = [str(c.parent / "trace.csv") for c in copies]

    def said(k: int) -> str:
        return f"{copies[k]}: bullet: blew up at t=0.5 (the frames before it written to {traces[k]})\n"
    run = [cache.entry(["run", str(c), "--backend", "bullet", "--trace", t], "bullet", ROOT) for c, t in zip(copies, traces)]
    with open(traces[0], "w") as f:
        f.write("time,node,field,value\n")
    run[0].keep(1, said(0), 60.0)
    assert run[1].reused(60.0) == (1, said(1))
    assert open(traces[1]).read() == "time,node,field,value\n"
    os.unlink(traces[0])  # a refusal writes no trace: its reuse removes one a run before left
    run[0].keep(3, "refused\n", 60.0)
    assert run[1].reused(60.0) == (3, "refused\n") and not os.path.exists(traces[1])


def test_a_crash_is_run_again_and_a_time_out_only_under_a_longer_limit(tmp_path, cached, monkeypatch):
    """A crash (a signal: the machine's doing as likely as the engine's) is never kept; a time-out is,
    with its limit: a run that passed 60 s passes 30 s, but may end within 120 s."""
    cache.learn({"bullet": "3.2.7"})
    trace = str(tmp_path / "t.npz")
    started: list[float] = []

    def ends(e: children.Ended):
        monkeypatch.setattr(children, "_started", lambda cmd, timeout, backend: started.append(timeout) or e)
    ends(children.Ended(-9, "", ""))
    assert children.run_child(PENDULUM, "bullet", SHORT, trace).verdict == results.CRASHED
    assert _entries(cached) == []
    ends(children.Ended(None, "", ""))
    assert children.run_child(PENDULUM, "bullet", SHORT, trace, 60.0).verdict == results.TIMED_OUT
    ends(children.Ended(0, "", ""))  # a run would end well now: a reuse says what the kept run did
    out = children.run_child(PENDULUM, "bullet", SHORT, trace, 30.0)
    assert out == children.Outcome(results.TIMED_OUT, "no result within 30 s") and started == [60.0, 60.0]
    ends(children.Ended(None, "", ""))
    assert children.run_child(PENDULUM, "bullet", SHORT, trace, 120.0).verdict == results.TIMED_OUT
    assert started == [60.0, 60.0, 120.0]


def test_two_threads_that_want_one_run_run_it_once(tmp_path, cached, counted, bullet):
    """Stability's two spinning-wheel cases run one scene: the second waits for the first's run."""
    from conformance.runner import verdicts
    traces = [str(tmp_path / f"{k}.npz") for k in range(4)]
    outs = verdicts.run_many([lambda t=t: children.run_child(PENDULUM, bullet, SHORT, t) for t in traces], 4)
    assert outs == [children.Outcome(None)] * 4 and len(counted) == 1
    assert len({open(t, "rb").read() for t in traces}) == 1


def _replaced(data: bytes) -> bytes:
    """The entry with its trace swapped for another trace's (whole, and the size said for it), its digest kept."""
    import json
    import zlib
    line, _, body = data[len(cache.FORMAT):].partition(b"\n")
    header = json.loads(line)
    (size, digest), = header["files"].values()
    other = zlib.compress(b"Q" + zlib.decompress(body)[1:], cache.LEVEL)  # "PK" no more
    header["files"]["--trace"] = [len(other), digest]
    return cache.FORMAT + json.dumps(header).encode() + b"\n" + other


@pytest.mark.parametrize("damage", ["cut", "flipped", "empty", "other format", "replaced"])
def test_an_entry_that_does_not_read_back_whole_is_a_miss_and_is_made_again(tmp_path, cached, counted, bullet,
                                                                           damage):
    trace = tmp_path / "t.npz"
    children.run_child(PENDULUM, bullet, SHORT, str(trace))
    made = trace.read_bytes()
    (entry,) = _entries(cached)
    data = open(entry, "rb").read()
    damaged = {"cut": data[:-100], "flipped": data[:-50] + bytes([data[-50] ^ 1]) + data[-49:], "empty": b"",
               "other format": data.replace(cache.FORMAT, b"x3drbp-run-cache 0\n", 1)}.get(damage) \
        if damage != "replaced" else _replaced(data)
    with open(entry, "wb") as f:
        f.write(damaged)
    trace.unlink()
    assert children.run_child(PENDULUM, bullet, SHORT, str(trace)) == children.Outcome(None)
    assert len(counted) == 2 and trace.read_bytes() == made
    trace.unlink()
    assert children.run_child(PENDULUM, bullet, SHORT, str(trace)) == children.Outcome(None)
    assert len(counted) == 2 and trace.read_bytes() == made  # made again whole: read back


def test_no_cache_runs_afresh_and_keeps_nothing(tmp_path, cached, counted, bullet, monkeypatch):
    trace = str(tmp_path / "t.npz")
    with cache.turned_off(True):
        children.run_child(PENDULUM, bullet, SHORT, trace)
        with cache.turned_off(False):  # a command inside one run with --no-cache (report's steps)
            children.run_child(PENDULUM, bullet, SHORT, trace)
    assert len(counted) == 2 and _entries(cached) == []
    assert main(["conformance", "--backends", bullet, "--cases", "free_fall", "--out", str(tmp_path / "c"), "-q",
                 "--no-cache"]) == 0
    assert len(counted) > 2 and _entries(cached) == []
    del counted[:]
    monkeypatch.setenv(cache.ENV, "off")
    children.run_child(PENDULUM, bullet, SHORT, trace)
    assert len(counted) == 1 and _entries(cached) == []


def test_report_passes_no_cache_to_each_step_that_takes_it():
    steps = R.uncached(R._steps("out", ["bullet", "mujoco"], False, True, []))
    for step, commands in steps:
        for argv in commands:
            assert ("--no-cache" in argv) == (step != "x_ite"), argv  # x-ite runs a browser, no cached run


def test_the_folder_is_x3drbp_cache_else_xdg_s(monkeypatch, tmp_path):
    monkeypatch.delenv(cache.ENV)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert cache.folder() == os.path.join(str(tmp_path), "x3drbp", "runs")
    monkeypatch.setenv("XDG_CACHE_HOME", "relative")  # ignored, as the XDG rule says
    assert cache.folder() == os.path.join(os.path.expanduser("~"), ".cache", "x3drbp", "runs")
    monkeypatch.setenv(cache.ENV, str(tmp_path / "mine"))
    assert cache.folder() == str(tmp_path / "mine")


def test_inside_remembered_the_backends_are_probed_once(monkeypatch):
    """x3drbp report's steps ask the backends the report asked: one child answers them all."""
    asked = []
    real = probe.answers
    monkeypatch.setattr(probe, "answers", lambda *a: asked.append(a[0]) or real(*a))
    with probe.remembered():
        every = probe.backend_table()
        one = probe.backend_table(names=["bullet"])
        assert probe.backend_table() == every and one == {"bullet": every["bullet"]}
        script = "import json; print('x3drbp-answer ' + json.dumps(42))"
        assert probe.ask(script, [], 10.0, "a question") == probe.ask(script, [], 10.0, "a question") == (42, "")
    assert len(asked) == 2
    probe.backend_table(names=["bullet"])
    assert len(asked) == 3  # outside the block, asked afresh


def test_past_its_limit_the_least_recently_used_entries_go(tmp_path):
    """Every edit of the source makes every run a new one: the folder is held to a size, the
    entries used last kept, and a writer's unfinished file left alone."""
    for k in range(10):
        path = tmp_path / f"{k:02d}" / "entry"
        path.parent.mkdir()
        path.write_bytes(b"x" * 100)
        os.utime(path, (1000 + k, 1000 + k))  # entry k used at time k
    writing = tmp_path / "00" / f"{cache.atomic.PREFIX}1-entry-x{cache.atomic.SUFFIX}"
    writing.write_bytes(b"x" * 100)
    os.utime(writing, (0, 0))
    assert cache.prune(str(tmp_path), 1000) == []  # within the limit: nothing goes
    removed = cache.prune(str(tmp_path), 900)
    assert sorted(os.path.relpath(p, tmp_path) for p in removed) == [f"{k:02d}/entry" for k in range(4)]
    assert writing.exists() and len(_entries(tmp_path)) == 7


def _same(a, b) -> bool:
    from x3d_core.traces.trace_npz import arrays
    x, y = arrays(a), arrays(b)
    return x.keys() == y.keys() and all(np.array_equal(x[k], y[k]) for k in x)


def test_a_csv_trace_read_again_is_the_view_its_parse_gave(tmp_path, cached, bullet, monkeypatch):
    """Stability's CSV traces are read back from their kept .npz: the very arrays the parse gives."""
    from x3d_core.traces import trace
    csv = str(tmp_path / "t.csv")
    assert children.run_child(PENDULUM, bullet, SHORT, csv) == children.Outcome(None)
    parsed, parses = trace.read_view(csv), []
    monkeypatch.setattr(trace, "read_view", lambda path, real=trace.read_view: parses.append(path) or real(path))
    assert _same(cache.read_view(csv), parsed) and parses == [csv]
    assert _same(cache.read_view(csv), parsed) and parses == [csv]  # read back, not parsed again
    with open(csv, "a", encoding="utf-8") as f:
        f.write("9,Extra,position,1 2 3\n")
    changed = cache.read_view(csv)
    assert parses == [csv, csv] and not _same(changed, parsed) and _same(changed, trace.read_view(csv))


def test_a_question_asked_of_the_same_code_engines_and_files_is_answered_without_a_child(tmp_path, cached,
                                                                                         monkeypatch):
    """The backends' declarations and their judgement of scenes (probe.ask's children, each importing
    every engine) are answered again from the cache; a file it reads that changed asks anew."""
    cache.learn({"bullet": "3.2.7"})
    asked = []
    real = probe.answers
    monkeypatch.setattr(probe, "answers", lambda *a: asked.append(a[1]) or real(*a))
    scene = tmp_path / "s.x3d"
    scene.write_text("one")
    script = "import sys; print('x3drbp-answer ' + open(sys.argv[1]).read().__repr__().replace(\"'\", '\"'))"
    assert probe.ask(script, [str(scene)], 10.0, "a question") == ("one", "")
    assert probe.ask(script, [str(scene)], 10.0, "a question") == ("one", "") and len(asked) == 1
    scene.write_text("two")
    assert probe.ask(script, [str(scene)], 10.0, "a question") == ("two", "") and len(asked) == 2
    cache.learn({"bullet": "3.2.8"})  # another engine: its declarations may differ
    assert probe.ask(script, [str(scene)], 10.0, "a question") == ("two", "") and len(asked) == 3

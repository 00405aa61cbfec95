"""Where x3drbp's outputs go, and what it reads as a trace, when the path is not a plain file:

- an output that cannot be written (no such folder, a folder, under a file, disk full) is one
  line `x3drbp COMMAND: cannot write PATH: REASON`, exit 1, and nothing half-written;
- standard output closed by its reader (`| head -1`) ends quietly, exit 141;
- a symbolic link is written through (the link stays), a device or named pipe is written
  into (never replaced by a regular file);
- a new output has 0666 less the umask, a replaced one keeps its mode;
- a temporary file a killed writer left is cleaned by the next write beside it;
- a trace given to `validate` that is a named pipe is refused at once; a long one is read in
  bounded memory.

Devices are reached through symbolic links in tmp_path only: code that replaced what a path
names would replace the link, never /dev/null or /dev/full themselves.
"""

from __future__ import annotations

import os
import stat
import subprocess
import sys
import textwrap
import threading
import time

import pytest

from conftest import PEAK_KIB, ROOT, SCENES
from x3d_core.files import atomic
from x3d_core.traces.trace import HEADER, Trace, read_trace

PENDULUM = os.path.join(SCENES, "examples", "pendulum.x3d")
CRADLE = os.path.join(ROOT, "conformance", "cases", "newtons_cradle", "newtons_cradle.x3d")
RUN = ("run", PENDULUM, "--backend", "pymunk", "--duration", "0.1")
pytest.importorskip("pymunk")


def x3drbp(*args: str, umask: int | None = None, timeout: float = 120, **kw) -> subprocess.CompletedProcess:
    def child() -> None:
        if umask is not None:
            os.umask(umask)
    kw.setdefault("stdout", subprocess.PIPE)
    return subprocess.run([sys.executable, "-m", "x3drbp", *args], cwd=ROOT, stderr=subprocess.PIPE,
                          text=True, timeout=timeout, preexec_fn=child, **kw)


def _one_line(p: subprocess.CompletedProcess, command: str, path: str) -> str:
    """The last line of stderr (a scene's own warnings come before it), checked."""
    assert "Traceback" not in p.stderr, p.stderr
    last = p.stderr.strip().splitlines()[-1]
    assert last.startswith(f"x3drbp {command}: cannot write {path}: "), p.stderr
    return last


def _devices_intact() -> None:
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode) and stat.S_ISCHR(os.stat("/dev/full").st_mode)


@pytest.mark.parametrize("where", ["missing folder", "a folder", "under a file", "disk full"])
def test_an_unwritable_trace_is_one_line_exit_1_and_nothing_half_written(where, tmp_path):
    (tmp_path / "file").write_text("a file\n")
    path = {"missing folder": tmp_path / "missing" / "t.csv", "a folder": tmp_path,
            "under a file": tmp_path / "file" / "t.csv", "disk full": tmp_path / "full.csv"}[where]
    if where == "disk full":
        os.symlink("/dev/full", path)
    before = sorted(os.listdir(tmp_path))
    p = x3drbp(*RUN, "--trace", str(path))
    assert p.returncode == 1
    line = _one_line(p, "run", str(path))
    assert {"missing folder": "No such file", "a folder": "folder", "under a file": "Not a directory",
            "disk full": "No space left"}[where] in line
    assert sorted(os.listdir(tmp_path)) == before and p.stdout == ""
    _devices_intact()


@pytest.mark.parametrize("option, name", [("--timing", "timing.json"), ("--rerun", "run.rrd")])
def test_every_output_of_run_fails_the_same_way(tmp_path, option, name):
    (tmp_path / "file").write_text("a file\n")
    out = tmp_path / "file" / name
    p = x3drbp(*RUN, "--trace", str(tmp_path / "t.csv"), option, str(out))
    assert p.returncode == 1
    _one_line(p, "run", str(out))
    assert os.listdir(tmp_path) == ["file"]  # said before the run: the trace was written, then this refused


@pytest.mark.parametrize("args", [
    ("compare", PENDULUM, "--backends", "pymunk,mujoco", "--json", "{ok}/c.json", "--rerun", "{bad}/c.rrd"),
    ("advise", PENDULUM, "--backends", "pymunk,mujoco", "--dts", "1/60,1/120", "--json", "{bad}/a.json"),
    ("sweep", "--scenes", "projectile", "--backends", "pymunk", "--out", "{file}"),
    ("stability", "--cases", "mass_ratio_pendulum", "--backends", "pymunk", "--out", "{file}/deeper/still"),
])
def test_an_output_that_cannot_be_written_is_said_before_any_run(args, tmp_path, monkeypatch, capsys):
    """compare, advise and run said it after every run (compare's --json left written where its
    --rerun was refused); sweep and conformance said "File exists" of an --out that is a file.
    Before any run: not even the backends are probed, the first thing each of them asks."""
    from x3drbp import main as cli_main
    from conformance.runner import probe

    def probed(*_args, **_kwargs):
        raise AssertionError("the backends were probed before the outputs were checked")
    monkeypatch.setattr(probe, "backend_table", probed)
    (tmp_path / "file").write_text("")
    paths = {"ok": str(tmp_path), "bad": str(tmp_path / "missing"), "file": str(tmp_path / "file")}
    argv = [a.format(**paths) for a in args]
    status = cli_main([*argv, "-q"])
    out, err = capsys.readouterr()
    assert status == 1 and out == ""
    refused = next(a for a, b in zip(argv, args) if "{bad}" in b or "{file}" in b)
    line = _one_line(subprocess.CompletedProcess(argv, status, out, err), args[0], refused)
    assert line.endswith(("No such file or directory", "is a file, not a folder")), line
    assert os.listdir(tmp_path) == ["file"]


def test_standard_output_closed_by_its_reader_ends_quietly_with_141():
    # as `x3drbp run SCENE | head -0`: the reader is gone before the trace is written
    r, w = os.pipe()
    os.close(r)
    try:
        p = x3drbp(*RUN, stdout=w)
    finally:
        os.close(w)
    assert p.returncode == 141
    assert "Traceback" not in p.stderr and "BrokenPipe" not in p.stderr and "Exception ignored" not in p.stderr


def test_a_symbolic_link_is_written_through_and_stays_a_link(tmp_path):
    target = tmp_path / "data" / "trace.csv"
    target.parent.mkdir()
    target.write_text("old\n")
    target.chmod(0o640)
    link = tmp_path / "link.csv"
    os.symlink(os.path.join("data", "trace.csv"), link)
    p = x3drbp(*RUN, "--trace", str(link))
    assert p.returncode == 0, p.stderr
    assert os.path.islink(link) and os.readlink(link) == os.path.join("data", "trace.csv")
    assert target.read_text().startswith(",".join(HEADER)) and len(read_trace(str(link))) > 10
    assert stat.S_IMODE(target.stat().st_mode) == 0o640  # the file it replaced kept its mode
    assert sorted(os.listdir(tmp_path)) == ["data", "link.csv"] and os.listdir(target.parent) == ["trace.csv"]


def test_a_dangling_link_creates_its_target(tmp_path):
    link = tmp_path / "link.csv"
    os.symlink("made.csv", link)
    assert x3drbp(*RUN, "--trace", str(link)).returncode == 0
    assert os.path.islink(link) and (tmp_path / "made.csv").read_text().startswith(",".join(HEADER))


def test_dev_null_discards_and_stays_a_device(tmp_path):
    link = tmp_path / "null.csv"
    os.symlink("/dev/null", link)
    p = x3drbp(*RUN, "--trace", str(link), "--timing", str(link))
    assert p.returncode == 0, p.stderr
    assert os.path.islink(link) and os.readlink(link) == "/dev/null"
    _devices_intact()
    assert os.listdir(tmp_path) == ["null.csv"]


def test_dev_stdout_on_a_pipe_is_written_into():
    p = x3drbp(*RUN, "--trace", "/dev/stdout")
    assert p.returncode == 0, p.stderr
    assert p.stdout.startswith("time,node,field,value\n") and len(p.stdout.splitlines()) > 10


def test_a_named_pipe_is_written_into(tmp_path):
    fifo = tmp_path / "trace.fifo"
    os.mkfifo(fifo)
    got = []
    reader = threading.Thread(target=lambda: got.append(open(fifo, "rb").read()), daemon=True)
    reader.start()
    p = x3drbp(*RUN, "--trace", str(fifo))
    reader.join(30)
    assert p.returncode == 0, p.stderr
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode) and got and got[0].startswith(b"time,node,field,value\n")
    assert os.listdir(tmp_path) == ["trace.fifo"]


@pytest.mark.parametrize("umask, mode", [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664)])
def test_a_new_output_has_0666_less_the_umask(tmp_path, umask, mode):
    trace, timing = tmp_path / "t.csv", tmp_path / "timing.json"
    assert x3drbp(*RUN, "--trace", str(trace), "--timing", str(timing), umask=umask).returncode == 0
    assert stat.S_IMODE(trace.stat().st_mode) == mode and stat.S_IMODE(timing.stat().st_mode) == mode


def test_a_replaced_output_keeps_its_mode(tmp_path):
    trace = tmp_path / "t.csv"
    trace.write_text("old\n")
    trace.chmod(0o604)
    assert x3drbp(*RUN, "--trace", str(trace), umask=0o077).returncode == 0
    assert stat.S_IMODE(trace.stat().st_mode) == 0o604 and trace.read_text().startswith("time,")


def test_umask_is_read_without_changing_it():
    before = os.umask(0o027)
    try:
        atomic._umask = None
        assert atomic.umask() == 0o027 and atomic.new_file_mode() == 0o640
        now = os.umask(0o027)
        assert now == 0o027
    finally:
        os.umask(before)
        atomic._umask = None


def _dead_pid() -> int:
    p = subprocess.Popen([sys.executable, "-c", "pass"])
    p.wait()
    return p.pid


def test_a_killed_writer_leaves_the_old_file_and_its_temporary_is_cleaned_by_the_next_write(tmp_path):
    out = tmp_path / "matrix.json"
    out.write_text("old\n")
    script = textwrap.dedent(f"""
        import os, sys, time
        from x3d_core.files import atomic
        def chunks():
            yield b"half of the new"
            print("writing", flush=True)
            time.sleep(60)
            yield b" file"
        atomic.write_chunks({str(out)!r}, chunks())
    """)
    p = subprocess.Popen([sys.executable, "-c", script], cwd=ROOT, stdout=subprocess.PIPE, text=True)
    assert p.stdout.readline() == "writing\n"
    p.kill()
    p.wait()
    assert out.read_text() == "old\n"  # never torn
    left = [n for n in os.listdir(tmp_path) if n != "matrix.json"]
    assert len(left) == 1 and left[0].startswith(f".x3drbp-{p.pid}-matrix.json-") and left[0].endswith(".tmp")
    old = time.time() - 2 * atomic.DEAD_GRACE_S
    os.utime(tmp_path / left[0], (old, old))
    fresh = tmp_path / f".x3drbp-{_dead_pid()}-other.json-abc.tmp"  # a dead writer's, but just now: kept
    fresh.write_text("")
    mine = tmp_path / f".x3drbp-{os.getpid()}-x.json-abc.tmp"  # a live process's, however old: kept
    mine.write_text("")
    os.utime(mine, (old, old))
    atomic.write_json(str(out), {"new": 1})
    assert sorted(os.listdir(tmp_path)) == sorted(["matrix.json", fresh.name, mine.name])
    ancient = time.time() - 2 * atomic.STALE_S  # untouched for hours: gone, whoever wrote it
    os.utime(mine, (ancient, ancient))
    atomic.write_json(str(out), {"new": 2})
    assert sorted(os.listdir(tmp_path)) == sorted(["matrix.json", fresh.name])


def test_a_recording_gets_the_usual_mode_and_cleans_a_killed_recordings_temporary(tmp_path):
    pytest.importorskip("rerun")
    from reports.rerun_recording import write_recording
    from x3d_core.encodings.load import load
    from x3d_core.traces.trace import TraceView

    trace = tmp_path / "t.csv"
    assert x3drbp(*RUN, "--trace", str(trace)).returncode == 0
    stale = tmp_path / f".x3drbp-{_dead_pid()}-run.rrd-k1ll3d.tmp"
    stale.write_bytes(b"a truncated recording")
    old = time.time() - 2 * atomic.DEAD_GRACE_S
    os.utime(stale, (old, old))
    rrd = tmp_path / "run.rrd"
    before = os.umask(0o022)
    try:
        atomic._umask = None
        write_recording(str(rrd), load(PENDULUM), [("pymunk", TraceView(read_trace(str(trace))))])
    finally:
        os.umask(before)
        atomic._umask = None
    assert sorted(os.listdir(tmp_path)) == ["run.rrd", "t.csv"]
    assert stat.S_IMODE(rrd.stat().st_mode) == 0o644 and rrd.stat().st_size > 1000


def test_a_recording_to_dev_null_is_discarded(tmp_path):
    link = tmp_path / "null.rrd"
    os.symlink("/dev/null", link)
    p = x3drbp(*RUN, "--trace", str(tmp_path / "t.csv"), "--rerun", str(link))
    assert p.returncode == 0, p.stderr
    assert os.path.islink(link)
    _devices_intact()


def test_names_that_spreadsheets_read_as_formulas_are_written_as_they_are(tmp_path):
    # the trace is a contract read by programs: a name is never rewritten (docs/commands/run.md: "Traces and spreadsheets")
    trace = Trace()
    trace.add_text(0.0, "=HYPERLINK(1)", "isActive", "TRUE")
    trace.add(0.0, "@Body", "position", "SFVec3f", [-1.0, 2.0, 3.0])
    path = str(tmp_path / "t.csv")
    trace.write(path)
    assert [(r.node, r.value) for r in read_trace(path)] == [("=HYPERLINK(1)", "TRUE"), ("@Body", "-1 2 3")]


def test_validate_refuses_a_named_pipe_as_their_trace_at_once(tmp_path):
    fifo = tmp_path / "theirs.csv"
    os.mkfifo(fifo)
    p = x3drbp("validate", PENDULUM, "--trace", str(fifo), "--against", "pymunk", timeout=300)  # a hang guard
    assert p.returncode == 2 and "Traceback" not in p.stderr  # 2: the trace cannot be judged
    assert p.stderr.strip().splitlines() == [f"{fifo}: cannot read: a named pipe, not a regular file"]


def test_validate_refuses_a_folder_as_their_trace(tmp_path):
    p = x3drbp("validate", PENDULUM, "--trace", str(tmp_path), "--against", "pymunk")
    assert p.returncode == 2 and p.stderr.strip().splitlines() == [f"{tmp_path}: cannot read: a folder, not a regular file"]


def write_long_trace(src: str, out: str, rows: int) -> None:
    """A valid trace of about `rows` rows: the frames of a real one repeated, 1/60 s apart."""
    lines = open(src).read().splitlines()
    frames: dict[str, list[str]] = {}
    for ln in lines[1:]:
        t, rest = ln.split(",", 1)
        frames.setdefault(t, []).append(rest)
    blocks = list(frames.values())
    with open(out, "w") as f:
        f.write(lines[0] + "\n")
        k = written = 0
        while written < rows:
            block = blocks[k % len(blocks)]
            t = repr(k / 60)
            f.write("".join(f"{t},{r}\n" for r in block))
            written += len(block)
            k += 1


MEASURE = f"""
import sys, time
import numpy as np
from x3d_core.encodings.load import load
from conformance.analyses.trace_check import check_trace
from conformance.analyses import validation
from x3d_core.traces.trace import TraceView
scene = load(sys.argv[1])
started = time.process_time()
view, problems = check_trace(sys.argv[2], scene)
TraceView(view)
validation.trace_settings(view, 1 / 240)
validation._aligned(view, np.arange(0, 60, 1 / 60))
print(len(view), len(problems), time.process_time() - started, {PEAK_KIB})
"""


def _measure(tmp_path, rows: int) -> tuple[int, int, float, float]:
    """(rows read, problems, CPU seconds, peak RSS in MiB) of reading a long trace as validate does."""
    short = tmp_path / "short.csv"
    assert x3drbp("run", CRADLE, "--backend", "pymunk", "--duration", "1", "--trace", str(short)).returncode in (0,)
    long = tmp_path / "long.csv"
    write_long_trace(str(short), str(long), rows)
    out = subprocess.run([sys.executable, "-c", MEASURE, CRADLE, str(long)], cwd=ROOT, capture_output=True,
                         text=True, timeout=1800)
    assert out.returncode == 0, out.stderr
    n, problems, seconds, kib = out.stdout.split()
    return int(n), int(problems), float(seconds), int(kib) / 1024


def test_a_long_trace_is_read_in_arrays_not_rows(tmp_path):
    # 10^6 rows: the reader that made an object per row took ~40 s and ~850 MiB here
    n, problems, seconds, mib = _measure(tmp_path, 10**6)
    assert n >= 10**6 and problems == 0
    assert mib < 400, mib
    assert seconds < 60, seconds


@pytest.mark.slow  # 10^7 rows: 600 MB written, about a minute
def test_ten_million_rows_validate_within_a_gib(tmp_path):
    n, problems, seconds, mib = _measure(tmp_path, 10**7)
    assert n >= 10**7 and problems == 0
    assert mib < 1024, mib


def test_an_out_folder_under_a_file_is_one_line(tmp_path):
    (tmp_path / "file").write_text("")
    out = tmp_path / "file" / "matrix"
    p = x3drbp("conformance", "--cases", "free_fall", "--backends", "pymunk", "--out", str(out))
    assert p.returncode == 1
    _one_line(p, "conformance", str(out))
    assert os.listdir(tmp_path) == ["file"]


def test_validate_json_that_cannot_be_written_is_one_line(tmp_path):
    trace = tmp_path / "t.csv"
    assert x3drbp(*RUN, "--trace", str(trace)).returncode == 0
    (tmp_path / "file").write_text("")
    out = tmp_path / "file" / "v.json"
    p = x3drbp("validate", PENDULUM, "--trace", str(trace), "--against", "pymunk", "--json", str(out))
    assert p.returncode == 1
    _one_line(p, "validate", str(out))


SENSOR = os.path.join(ROOT, "conformance", "cases", "sensor_geometry", "sensor_geometry.x3d")


@pytest.mark.parametrize("scene, backend", [(SENSOR, "bullet"), (CRADLE, "mujoco")])
def test_the_checked_view_is_the_view_of_the_rows(tmp_path, scene, backend, monkeypatch):
    # bulk (chunks of plain rows) and row by row (text rows, a quoted value) read alike
    import numpy as np
    from conformance.analyses import trace_check
    from x3d_core.traces import trace as T
    from x3d_core.encodings.load import load

    pytest.importorskip({"bullet": "pybullet"}.get(backend, backend))
    path = tmp_path / "t.csv"
    assert x3drbp("run", scene, "--backend", backend, "--duration", "0.5", "--trace", str(path)).returncode == 0
    monkeypatch.setattr(T, "CHUNK_BYTES", 4096)  # many chunks, some bulk, some not
    view, problems = trace_check.check_trace(str(path), load(scene))
    assert problems == []
    rows = read_trace(str(path))
    old = T.TraceView(rows)
    assert len(view) == len(rows) and view.keys() == old.keys() and view.text_keys() == old.text_keys()
    for k in old.keys():
        assert all(np.array_equal(a, b) for a, b in zip(view.series(*k), old.series(*k)))
    for k in old.text_keys():
        assert np.array_equal(view.text(*k)[0], old.text(*k)[0]) and view.text(*k)[1] == old.text(*k)[1]
    assert np.array_equal(view.times(), np.unique([r.time for r in rows]))
    streamed = T.read_view(str(path))
    assert streamed.keys() == old.keys() and len(streamed) == len(rows)


def test_a_problem_deep_in_a_long_trace_is_found_at_its_line(tmp_path, monkeypatch):
    from conformance.analyses import trace_check
    from x3d_core.traces import trace as T
    from x3d_core.encodings.load import load

    path = tmp_path / "t.csv"
    assert x3drbp("run", CRADLE, "--backend", "pymunk", "--duration", "2", "--trace", str(path)).returncode == 0
    lines = path.read_text().splitlines()
    lines[1000] = lines[1000].split(",")[0] + ",Ball1,positon,0 0 0"
    lines[1500] = lines[1500].split(",")[0] + ",Ball1,orientation,0 1 0 nan"
    path.write_text("\n".join(lines) + "\n")
    monkeypatch.setattr(T, "CHUNK_BYTES", 4096)
    _, problems = trace_check.check_trace(str(path), load(CRADLE))
    assert [p.line for p in problems] == [1001, 1501]
    monkeypatch.setattr(trace_check, "MAX_PROBLEMS", 1)
    _, problems = trace_check.check_trace(str(path), load(CRADLE))
    assert [p.line for p in problems] == [1001, 0] and "stopped reading after 1 problems" in problems[1].message

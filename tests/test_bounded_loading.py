"""Inputs that would make loading unbounded are refused at once, in one line, exit 1.

- PROTOs nested in PROTO bodies multiply: a 1 KB file whose PROTO Pk instantiates P(k-1)
  twice, 30 deep, would expand to 2^31 nodes. x3d_core.encodings.build bounds what expansion copies
  (MAX_EXPANDED_NODES nodes, MAX_EXPANDED_BYTES of array values) and stops at the instance
  that passes a bound; a modest PROTO scene still expands.
- A named pipe would block a reader forever and /dev/zero never ends: x3d_core.encodings.load reads
  through x3d_core.files.inputs.read_regular, which refuses what is not a regular file before a
  byte is read, as a scene given to `check` or `run` and as an entry of a folder given to
  `check` (reported as one error line; the rest of the folder is still checked).

Every command runs in a subprocess with a timeout, so that a hang fails a test rather than
hangs the suite, and the nested-PROTO bombs run under a 1 GiB address-space limit.
"""

from __future__ import annotations

import os
import re
import resource
import subprocess
import sys

import pytest

from limited import cpu_of

from x3d_core.encodings import build
from x3d_core.encodings.load import load
from x3d_core.model.scene import LoadError

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TIMEOUT_S = 300  # a hang guard only, far past a busy machine's slowest: the bound is CPU_S
CPU_S = 10.0  # CPU seconds a refusal may take, python start-up included (~1 s measured)
ENV = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")

GOOD_SCENE = """#X3D V4.0 utf8
PROFILE Full
COMPONENT RigidBodyPhysics:2
RigidBodyCollection {
  bodies [ DEF BALL RigidBody { mass 1 position 0 1 0 } ]
}
"""


# -- scene generators -------------------------------------------------------------------

def nested_vrml(depth: int) -> str:
    """PROTO Pk's body is a Group holding two instances of P(k-1); the scene one of P<depth>."""
    lines = ["#X3D V3.3 utf8", "PROFILE Immersive", "PROTO P0 [] { Group {} }"]
    lines += [f"PROTO P{k} [] {{ Group {{ children [ P{k - 1} {{}} P{k - 1} {{}} ] }} }}" for k in range(1, depth + 1)]
    lines.append(f"P{depth} {{}}")
    return "\n".join(lines) + "\n"


def nested_xml(depth: int) -> str:
    lines = ['<?xml version="1.0" encoding="UTF-8"?>', '<X3D profile="Immersive" version="3.3">', "<Scene>",
             '<ProtoDeclare name="P0"><ProtoBody><Group/></ProtoBody></ProtoDeclare>']
    lines += [f'<ProtoDeclare name="P{k}"><ProtoBody><Group><ProtoInstance name="P{k - 1}"/>'
              f'<ProtoInstance name="P{k - 1}"/></Group></ProtoBody></ProtoDeclare>' for k in range(1, depth + 1)]
    lines += [f'<ProtoInstance name="P{depth}"/>', "</Scene>", "</X3D>"]
    return "\n".join(lines) + "\n"


def nested_json(depth: int) -> str:
    lines = ['{"X3D": {"@profile": "Immersive", "@version": "3.3", "Scene": {"-children": [',
             ' {"ProtoDeclare": {"@name": "P0", "ProtoBody": {"-children": [{"Group": {}}]}}},']
    for k in range(1, depth + 1):
        inst = f'{{"ProtoInstance": {{"@name": "P{k - 1}"}}}}'
        lines.append(f' {{"ProtoDeclare": {{"@name": "P{k}", "ProtoBody": {{"-children": '
                     f'[{{"Group": {{"-children": [{inst}, {inst}]}}}}]}}}}}},')
    lines += [f' {{"ProtoInstance": {{"@name": "P{depth}"}}}}', "]}}}"]
    return "\n".join(lines) + "\n"


NESTED = {".x3dv": nested_vrml, ".x3d": nested_xml, ".x3dj": nested_json}


def nested(tmp_path, ext: str, depth: int) -> str:
    path = tmp_path / f"nested{depth}{ext}"
    path.write_text(NESTED[ext](depth))
    return str(path)


def expanded_nodes(depth: int) -> int:
    """Nodes copied by expansion in nested(depth): P(k-1)'s body twice into Pk's, then P<depth>'s
    into the scene; Pk's body holds 2^(k+1) - 1 nodes."""
    body = [2 ** (k + 1) - 1 for k in range(depth + 1)]
    return sum(2 * body[k - 1] for k in range(1, depth + 1)) + body[depth]


# -- helpers ------------------------------------------------------------------------------

def _limit_memory():
    one_gib = 1 << 30
    resource.setrlimit(resource.RLIMIT_AS, (one_gib, one_gib))


def cli(*args: str, limit_memory: bool = False) -> tuple[subprocess.CompletedProcess, float]:
    """x3drbp ARGS and the CPU seconds it spent."""
    try:
        return cpu_of(lambda: subprocess.run([sys.executable, "-m", "x3drbp", *args], cwd=ROOT,
                                             capture_output=True, text=True, errors="replace", timeout=TIMEOUT_S,
                                             env=ENV, preexec_fn=_limit_memory if limit_memory else None))
    except subprocess.TimeoutExpired:
        pytest.fail(f"x3drbp {' '.join(args)} did not return within {TIMEOUT_S} s")


def lines(p: subprocess.CompletedProcess) -> list[str]:
    return [line for line in (p.stdout + p.stderr).splitlines() if line.strip()]


def one_error_line(p: subprocess.CompletedProcess, path: str) -> str:
    """The one line the command printed, checked to be an error about path (exit 1)."""
    out = p.stdout + p.stderr
    assert "Traceback" not in out and "MemoryError" not in out, out
    assert p.returncode == 1, f"exit {p.returncode}:\n{out}"
    printed = lines(p)
    assert len(printed) == 1, out
    assert re.match(rf"^{re.escape(path)}:\d+:\d+: error: ", printed[0]), printed[0]
    return printed[0]


# -- PROTO expansion ----------------------------------------------------------------------

@pytest.mark.parametrize("ext", list(NESTED))
def test_nested_protos_are_refused_fast_and_small(tmp_path, ext):
    """30 deep would be 2^31 nodes: refused at the instance that passes the bound, within
    seconds and under 1 GiB, in one line naming file, line and the ProtoInstance."""
    path = nested(tmp_path, ext, 30)
    p, cpu = cli("check", path, limit_memory=True)
    line = one_error_line(p, path)
    assert f"past {build.MAX_EXPANDED_NODES:,} nodes" in line, line
    m = re.match(rf"^{re.escape(path)}:(\d+):\d+: error: ProtoInstance P(\d+): ", line)
    assert m, line
    # the instance named stands on the line the error names (each PROTO is on its own line)
    source_line = NESTED[ext](30).splitlines()[int(m.group(1)) - 1]
    assert re.search(rf"\bP{m.group(2)}\b", source_line), (line, source_line)
    assert cpu < CPU_S, f"took {cpu:.2f} s of CPU"


def test_nested_protos_are_refused_by_run(tmp_path):
    """`run` loads before it looks for the backend: the same one line, exit 1."""
    path = nested(tmp_path, ".x3dv", 20)
    p, cpu = cli("run", path, "--backend", "ode", limit_memory=True)
    assert "expand the scene past" in one_error_line(p, path)
    assert cpu < CPU_S, f"took {cpu:.2f} s of CPU"


@pytest.mark.parametrize("ext", list(NESTED))
def test_modest_proto_scene_expands(tmp_path, ext):
    scene = load(nested(tmp_path, ext, 8))
    assert not scene.errors, scene.errors
    assert sum(1 for _ in scene.nodes()) == 2 ** 9 - 1  # the instance of P8: a binary tree of Groups


@pytest.mark.parametrize("ext", list(NESTED))
def test_bound_is_exact(tmp_path, ext, monkeypatch):
    """A scene that expands exactly the bound loads; one node more is refused."""
    path = nested(tmp_path, ext, 3)
    monkeypatch.setattr(build, "MAX_EXPANDED_NODES", expanded_nodes(3))
    assert not load(path).errors
    monkeypatch.setattr(build, "MAX_EXPANDED_NODES", expanded_nodes(3) - 1)
    with pytest.raises(LoadError, match=f"past {expanded_nodes(3) - 1:,} nodes"):
        load(path)


def test_copied_arrays_are_bounded(tmp_path):
    """Few nodes, each holding a large array: a 290 KB file doubling a 30,000-point Coordinate
    12 times wanted 2.9 GB; the bytes bound refuses it."""
    points = " ".join(f"{i} 1 2" for i in range(30000))
    text = ["#X3D V3.3 utf8", "PROFILE Immersive",
            f"PROTO P0 [] {{ Shape {{ geometry PointSet {{ coord Coordinate {{ point [ {points} ] }} }} }} }}"]
    text += [f"PROTO P{k} [] {{ Group {{ children [ P{k - 1} {{}} P{k - 1} {{}} ] }} }}" for k in range(1, 13)]
    text.append("P12 {}")
    path = tmp_path / "arrays.x3dv"
    path.write_text("\n".join(text) + "\n")
    p, cpu = cli("check", str(path), limit_memory=True)
    assert "MiB of field values" in one_error_line(p, str(path))
    assert cpu < CPU_S, f"took {cpu:.2f} s of CPU"


# -- what is not a regular file -------------------------------------------------------------

needs_fifo = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="named pipes are POSIX")


@needs_fifo
@pytest.mark.parametrize("command", [["check"], ["run", "--backend", "ode"]])
def test_named_pipe_scene_is_refused(tmp_path, command):
    """Nobody writes to the pipe: reading it would block forever."""
    pipe = str(tmp_path / "pipe.x3d")
    os.mkfifo(pipe)
    p, cpu = cli(command[0], pipe, *command[1:])
    assert one_error_line(p, pipe) == f"{pipe}:1:1: error: a named pipe, not a regular file"
    assert cpu < CPU_S, f"took {cpu:.2f} s of CPU"


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="no /dev/zero")
@pytest.mark.parametrize("command", [["check"], ["run", "--backend", "ode"]])
def test_dev_zero_is_refused(command):
    """/dev/zero never ends (and has size 0 to fstat): refused as a character device."""
    p, cpu = cli(command[0], "/dev/zero", *command[1:], limit_memory=True)
    assert one_error_line(p, "/dev/zero") == "/dev/zero:1:1: error: a character device, not a regular file"
    assert cpu < CPU_S, f"took {cpu:.2f} s of CPU"


@needs_fifo
def test_folder_with_a_pipe_and_a_device_is_still_checked(tmp_path):
    """A pipe (and a link to /dev/zero) named like scenes in a folder: each is one error line,
    the good scene and a link to it are still checked, and the exit status is 1."""
    folder = tmp_path / "scenes"
    folder.mkdir()
    (folder / "good.x3dv").write_text(GOOD_SCENE)
    os.symlink("good.x3dv", folder / "link.x3dv")
    os.mkfifo(folder / "a_pipe.x3d")
    if os.path.exists("/dev/zero"):
        os.symlink("/dev/zero", folder / "zero.x3dj")
    p, cpu = cli("check", str(folder))
    out = p.stdout + p.stderr
    assert "Traceback" not in out, out
    assert p.returncode == 1, out
    assert f"{folder / 'a_pipe.x3d'}:1:1: error: a named pipe, not a regular file" in lines(p), out
    if os.path.exists("/dev/zero"):
        assert f"{folder / 'zero.x3dj'}:1:1: error: a character device, not a regular file" in lines(p), out
    assert re.search(rf"^{re.escape(str(folder / 'good.x3dv'))}: ok ", out, re.M), out
    assert re.search(rf"^{re.escape(str(folder / 'link.x3dv'))}: ok ", out, re.M), out
    total = 4 if os.path.exists("/dev/zero") else 3
    assert f"2 of {total} files ok" in out, out
    assert cpu < CPU_S, f"took {cpu:.2f} s of CPU"


@needs_fifo
def test_load_refuses_a_pipe_without_blocking(tmp_path):
    pipe = str(tmp_path / "pipe.x3dv")
    os.mkfifo(pipe)
    with pytest.raises(LoadError) as e:
        load(pipe)
    assert str(e.value.diagnostic) == f"{pipe}:1:1: error: a named pipe, not a regular file"


def test_load_follows_a_link_to_a_regular_file(tmp_path):
    (tmp_path / "good.x3dv").write_text(GOOD_SCENE)
    os.symlink("good.x3dv", tmp_path / "link.x3dv")
    scene = load(str(tmp_path / "link.x3dv"))
    assert not scene.errors and [n.def_name for n in scene.of_type("RigidBody")] == ["BALL"]


def test_reading_a_small_file_allocates_its_size_not_the_limit(tmp_path):
    """read_regular asks for what fstat says (read(n) allocates n bytes up front: reading
    limit + 1 cost every load 200 MiB); a file that grows while read is still bounded."""
    import tracemalloc
    from x3d_core.files.inputs import InputRefused, read_regular
    small = tmp_path / "small.x3d"
    small.write_bytes(b"<X3D/>" * 100)
    tracemalloc.start()
    try:
        assert read_regular(str(small), 200 * 1024 * 1024) == b"<X3D/>" * 100
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 1024 * 1024
    with pytest.raises(InputRefused, match="file is 600 bytes; x3drbp reads at most 100"):
        read_regular(str(small), 100)

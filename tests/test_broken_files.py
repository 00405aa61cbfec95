"""Every file in tests/broken/ is broken in one way: `x3drbp check` must say so, on the
right line, without a traceback, and without ever touching anything outside the file.

Each file is run through the real command line in a subprocess, as a user would run it.
EXPECTED names, for each file, the lines an error may be reported on (more than one
where two places are defensible: the end of a truncated file is its last line or the
line after it; an entity attack may be reported at its declaration or at its use) and a
substring (case-insensitive) that at least one error message must contain.
"""

from __future__ import annotations

import os
import re
import resource
import subprocess
import sys

import pytest

from limited import cpu_of

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BROKEN = os.path.join(REPO, "tests", "broken")
TIMEOUT_S = 20

# file name -> (lines an error may name, substring one error message must contain)
EXPECTED: dict[str, tuple[tuple[int, ...], str]] = {
    # XML encoding
    "truncated.x3d": ((9, 10), "malformed XML"),
    "mass_heavy.x3d": ((8,), "mass"),
    "vec3f_two_numbers.x3d": ((7,), "position"),
    "mass_zero.x3d": ((6,), "mass"),
    "error_correction_high.x3d": ((7,), "errorCorrection"),
    "unknown_field.x3d": ((7,), "fooBar"),
    "use_undefined.x3d": ((9,), "NOWHERE"),
    "use_cycle.x3d": ((6,), "cycle"),
    "box_in_bodies.x3d": ((7,), "Box"),
    "route_unknown_node.x3d": ((9,), "GHOST"),
    "applied_parameters_unknown.x3d": ((7,), "WOBBLE"),
    "force_output_unknown.x3d": ((9,), "angle"),
    "empty.x3d": ((1,), "empty"),
    "binary_junk.x3d": ((1,), "binary data"),
    "xxe.x3d": ((2, 6), "entit"),
    "xxe_utf16.x3d": ((2, 6), "entit"),
    "billion_laughs.x3d": ((2, 3, 18), "entit"),
    "billion_laughs_utf16.x3d": ((2, 3, 18), "entit"),
    # ClassicVRML encoding
    "mass_negative.x3dv": ((10,), "mass"),
    "sphere_radius_negative.x3dv": ((11,), "radius"),
    "vec3f_two_numbers.x3dv": ((7,), "gravity"),
    "use_cycle.x3dv": ((7,), "cycle"),
    "header_x3d_v9.x3dv": ((1,), "header"),
    "header_vrml_v1.x3dv": ((1,), "header"),
    "vrml_missing_brace.x3dv": ((11, 12), "}"),
    "vrml_unterminated_string.x3dv": ((6,), "string"),
    "vrml_eof_in_list.x3dv": ((8, 9), "]"),
    "vrml_externproto_no_url.x3dv": ((7, 8), "url"),
    "binary_junk.x3dv": ((1,), "binary data"),
    # JSON encoding
    "json_trailing_comma.x3dj": ((13, 14), "JSON"),
    "json_node_not_object.x3dj": ((11,), "RigidBody"),
    "mass_heavy.x3dj": ((13,), "mass"),
    "error_correction_high.x3dj": ((10,), "errorCorrection"),
    "use_undefined.x3dj": ((12,), "NOWHERE"),
    "binary_junk.x3dj": ((1,), "binary data"),
}

ENTITY_ATTACKS = ("xxe.x3d", "xxe_utf16.x3d")
ENTITY_BOMBS = ("billion_laughs.x3d", "billion_laughs_utf16.x3d")


def broken_files() -> list[str]:
    return sorted(f for f in os.listdir(BROKEN) if not f.startswith("."))


def rel(name: str) -> str:
    return os.path.join("tests", "broken", name)


def check(*args: str, **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "x3drbp", "check", *args], cwd=REPO,
                          capture_output=True, text=True, errors="replace", timeout=TIMEOUT_S, **kwargs)


def output_lines(p: subprocess.CompletedProcess) -> list[str]:
    return [line for line in (p.stdout + p.stderr).splitlines() if line.strip()]


def test_every_broken_file_has_an_expectation():
    files = set(broken_files())
    assert len(files) >= 20
    assert files - set(EXPECTED) == set(), "files in tests/broken/ without an entry in EXPECTED"
    assert set(EXPECTED) - files == set(), "entries in EXPECTED without a file in tests/broken/"


@pytest.mark.parametrize("name", broken_files())
def test_broken_file_is_reported(name):
    path = rel(name)
    p = check(path)
    out = p.stdout + p.stderr
    assert "Traceback" not in out, out
    assert "internal error" not in out, f"the loader crashed (the CLI caught the exception):\n{out}"
    assert "object at 0x" not in out, f"a Python repr leaked into a message:\n{out}"
    assert p.returncode == 1, f"exit {p.returncode}, expected 1:\n{out}"

    error = re.compile(rf"^{re.escape(path)}:(\d+):(\d+): error: ")
    warning = re.compile(rf"^{re.escape(path)}:\d+:\d+: warning: ")
    errors = []
    for line in output_lines(p):
        if warning.match(line):
            continue
        m = error.match(line)
        assert m, f"an output line that is neither an error nor a warning in the expected form:\n{line}"
        errors.append((int(m.group(1)), line))
    assert errors, f"exit 1 but no error line:\n{out}"

    lines, needle = EXPECTED[name]
    wrong = [line for n, line in errors if n not in lines]
    assert not wrong, f"error(s) on the wrong line (expected line {' or '.join(map(str, lines))}):\n" + \
        "\n".join(wrong)
    assert any(needle.lower() in line.lower() for _, line in errors), \
        f"no error message mentions {needle!r}:\n{out}"


@pytest.mark.parametrize("name", broken_files())
def test_columns_are_one_based(name):
    """LINE:COL as compilers print it: the column counts from 1 (0 would mean 'unknown')."""
    path = rel(name)
    p = check(path)
    cols = [(int(m.group(1)), line) for line in output_lines(p)
            if (m := re.match(rf"^{re.escape(path)}:\d+:(\d+): ", line))]
    bad = [line for c, line in cols if c < 1]
    assert not bad, "diagnostics with column 0:\n" + "\n".join(bad)


@pytest.mark.parametrize("name", ENTITY_ATTACKS)
def test_external_entity_is_never_read(name):
    p = check(rel(name))
    out = p.stdout + p.stderr
    assert p.returncode == 1, out
    assert "root:" not in out
    try:
        with open("/etc/passwd", encoding="utf-8", errors="replace") as f:
            secrets = [line.strip() for line in f if len(line.strip()) >= 8]
    except OSError:
        secrets = []
    leaked = [s for s in secrets if s in out]
    assert not leaked, f"output holds text of /etc/passwd: {leaked[:3]}"


def _limit_memory():
    one_gib = 1 << 30
    resource.setrlimit(resource.RLIMIT_AS, (one_gib, one_gib))


@pytest.mark.parametrize("name", ENTITY_BOMBS)
def test_entity_bomb_is_refused_fast_and_small(name):
    """10 levels of 10x expansion would be 3*10^10 characters: it must be refused, not
    expanded, within 2 s of CPU (python start-up included, ~0.5 s) and under 1 GiB."""
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    p, cpu = cpu_of(lambda: check(rel(name), preexec_fn=_limit_memory, env=env))
    out = p.stdout + p.stderr
    assert "Traceback" not in out, out
    assert "MemoryError" not in out, out
    assert p.returncode == 1, f"exit {p.returncode}:\n{out}"
    assert cpu < 2.0, f"took {cpu:.2f} s of CPU"


def test_no_paths_is_bad_usage():
    p = check()
    assert p.returncode == 2, p.stdout + p.stderr
    assert "Traceback" not in p.stdout + p.stderr


def test_nonexistent_file_is_one_error_line():
    path = rel("does_not_exist.x3d")
    assert not os.path.exists(os.path.join(REPO, path))
    p = check(path)
    out = p.stdout + p.stderr
    assert p.returncode == 1, out
    assert "Traceback" not in out, out
    lines = output_lines(p)
    assert len(lines) == 1, out
    assert re.match(rf"^{re.escape(path)}:\d+:\d+: error: ", lines[0]), lines[0]

"""A pin file (conformance/expectations/BACKEND.toml, or one of `--pins DIR`,
`--x3drbp-expectations DIR`) that does not read is one line naming the file and the line:
a TOML syntax error, a key given twice, bytes that are not UTF-8, a `failing` or
`over_bound` that is not a list of names, 10^5 nested arrays (once a RecursionError, an
uncaught UnicodeDecodeError, or a message without a line). `expectations` says it before
any run (exit 2), the plugin as a usage error.
"""

from __future__ import annotations

import re
import sys

import pytest

from conformance import expectations as E

from limited import leftovers, one_line, run, x3drbp

HEAD = '# pins\n\n[box_stack]\nverdict = "fail"\n'  # the entry's key lines start at line 4
BROKEN = {  # name -> (the file's bytes, the line named, what the message says)
    "syntax": (HEAD.encode() + b'why = unquoted\n', 5, "malformed TOML: Invalid value$"),
    "duplicate key": (HEAD.encode() + b'why = "w"\nverdict = "fail"\n', 6, r"malformed TOML: Cannot overwrite a value \(a key given twice\)"),
    "not UTF-8": (HEAD.encode() + b'why = "caf\xe9"\n', 5, "not UTF-8 text"),
    "failing of mixed types": (HEAD.encode() + b'why = "w"\nfailing = ["Box1.displacement", 2]\n', 6,
                               r"\[box_stack\]: failing must be a list of measure names"),
    "over_bound of mixed types": (HEAD.encode() + b'failing = ["a"]\n\nover_bound = [["nested"], "b"]\n', 7,
                                  r"\[box_stack\]: over_bound must be a list of measure names"),
    "deep array": (HEAD.encode() + b"failing = " + b"[" * 100_000 + b"]" * 100_000 + b"\n", 5,
                   r"nested 100000 levels deep \(arrays and objects\), deeper than can be read$"),
}


def _pins(tmp_path, name: str, backend: str = "ode") -> str:
    data, _, _ = BROKEN[name]
    (tmp_path / f"{backend}.toml").write_bytes(data)
    return str(tmp_path / f"{backend}.toml")


@pytest.mark.parametrize("name", list(BROKEN))
def test_a_pin_file_that_does_not_read_names_file_and_line(tmp_path, name):
    file = _pins(tmp_path, name)
    _, line, said = BROKEN[name]
    with pytest.raises(ValueError) as e:
        E.load("ode", str(tmp_path))
    assert re.match(rf"{re.escape(file)}:{line}: {said}", str(e.value)), str(e.value)
    assert "\n" not in str(e.value)


def test_expectations_check_says_a_broken_pin_before_any_run(tmp_path):
    from backends import base
    installed = [b for b in base.IN_TREE if not isinstance(base.available().get(b), str)]
    if not installed:
        pytest.skip("no engine is installed")
    for name in ("deep array", "duplicate key"):
        file = _pins(tmp_path, name, installed[0])
        before = (tmp_path / f"{installed[0]}.toml").read_bytes()
        p = x3drbp("expectations", "--backends", installed[0], "--cases", "free_fall", "--check", "--pins", str(tmp_path))
        one_line(p, 2, rf"x3drbp expectations: {re.escape(file)}:{BROKEN[name][1]}: {BROKEN[name][2]}")
        assert (tmp_path / f"{installed[0]}.toml").read_bytes() == before and not leftovers(str(tmp_path))


def test_the_plugin_says_a_broken_pin_as_a_usage_error(tmp_path):
    pins = tmp_path / "pins"
    pins.mkdir()
    file = _pins(pins, "failing of mixed types")
    (tmp_path / "test_one.py").write_text("def test_one():\n    pass\n")
    p = run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "--x3drbp-backend", "ode",
             "--x3drbp-expectations", str(pins)], cwd=str(tmp_path))
    one_line(p, pytest.ExitCode.USAGE_ERROR,
             rf"ERROR: --x3drbp-expectations: {re.escape(file)}:6: \[box_stack\]: failing must be a list")

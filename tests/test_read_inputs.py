"""Every data file a command or the pytest plugin reads goes through the checks a scene does
(x3d_core.files.inputs: a regular file of bounded size; x3d_core.files.documents: nesting past what a
parser recurses into said at its line): advise's --verdicts, the pins of `expectations --pins DIR` and
--x3drbp-expectations DIR (a folder that is missing is an error, not "no pins"), and
expectations' --matrix page. Each is refused in one line naming the file (and line), in bounded memory and CPU.
"""

from __future__ import annotations

import sys

import pytest

from x3d_core.files import documents

from conftest import case_scene
from limited import fed, leftovers, one_line, run, x3drbp

SCENE = case_scene("free_fall")


def _advise_verdicts(tmp_path, verdicts: str):
    out = tmp_path / "advice.json"
    p = x3drbp("advise", SCENE, "--verdicts", verdicts, "--json", str(out))
    assert not out.exists() and not leftovers(str(tmp_path))  # nothing written, not even a part
    return p


@pytest.mark.parametrize("kind", ["/dev/zero", "fifo", "folder"])
def test_advise_refuses_verdicts_that_are_no_regular_file(tmp_path, kind):
    """/dev/zero once grew advise to 23.8 GB; a named pipe blocked it forever."""
    if kind == "fifo":
        with fed(str(tmp_path / "matrix.json")) as path:
            p = _advise_verdicts(tmp_path, path)
        what = "a named pipe"
    else:
        path = str(tmp_path) if kind == "folder" else kind
        p = _advise_verdicts(tmp_path, path)
        what = "a character device" if kind == "/dev/zero" else "a folder"
    one_line(p, 2, rf"x3drbp advise: --verdicts {path}: {what}, not a regular file$")


def test_advise_refuses_verdicts_nested_too_deep_at_their_line(tmp_path):
    """10^5 levels of arrays were a RecursionError traceback."""
    deep = tmp_path / "matrix.json"
    deep.write_text('{"results":\n' + "[" * 100_000 + "]" * 100_000 + "}\n")
    one_line(_advise_verdicts(tmp_path, str(deep)), 2,
             rf"x3drbp advise: --verdicts {deep}:2: nested 100001 levels deep \(arrays and objects\), deeper than can be read$")


def test_advise_refuses_large_or_malformed_verdicts_at_their_line(tmp_path):
    big = tmp_path / "big.json"
    with open(big, "wb") as f:
        f.truncate(documents.DOCUMENT_LIMIT + 1)
    one_line(_advise_verdicts(tmp_path, str(big)), 2,
             rf"x3drbp advise: --verdicts {big}: file is {documents.DOCUMENT_LIMIT + 1} bytes; x3drbp reads at most")
    bad = tmp_path / "bad.json"
    bad.write_bytes(b'{"results": [\n  {"case": "free_fall",\n   "backend": "ode" "verdict": 1}]}\n')
    one_line(_advise_verdicts(tmp_path, str(bad)), 2, rf"x3drbp advise: --verdicts {bad}:3: malformed JSON: ")
    latin = tmp_path / "latin.json"
    latin.write_bytes(b'{"results": [],\n "note": "caf\xe9"}\n')
    one_line(_advise_verdicts(tmp_path, str(latin)), 2, rf"x3drbp advise: --verdicts {latin}:2: not UTF-8 text")


def _installed_backend() -> str:
    from backends import base
    installed = [b for b in base.IN_TREE if not isinstance(base.available().get(b), str)]
    if not installed:
        pytest.skip("no engine is installed")
    return installed[0]


def test_expectations_refuses_a_pins_folder_that_is_none(tmp_path):
    """--pins naming nothing was read as a folder of no pins: every case must pass."""
    b = _installed_backend()
    for missing in (tmp_path / "nope", tmp_path / "file.toml"):
        if missing.name == "file.toml":
            missing.write_text("")
        p = x3drbp("expectations", "--backends", b, "--cases", "free_fall", "--check", "--pins", str(missing))
        what = "cannot read folder: No such file or directory" if missing.name == "nope" else "a regular file, not a folder"
        one_line(p, 2, rf"x3drbp expectations: {missing}: {what}$")


def test_expectations_refuses_a_pin_file_that_is_a_pipe(tmp_path):
    b = _installed_backend()
    with fed(str(tmp_path / f"{b}.toml")) as pipe:
        p = x3drbp("expectations", "--backends", b, "--cases", "free_fall", "--pins", str(tmp_path))
    one_line(p, 2, rf"x3drbp expectations: {pipe}: a named pipe, not a regular file$")
    assert not leftovers(str(tmp_path))


def test_expectations_refuses_a_matrix_page_that_does_not_read(tmp_path):
    """--matrix is read to regenerate its table, as any input: a folder, or text that is not
    UTF-8, is one line naming it (and the line), not an OSError or UnicodeDecodeError."""
    from x3drbp.expectations import write_matrix
    with pytest.raises(ValueError, match=f"^{tmp_path}: a folder, not a regular file$"):
        write_matrix(str(tmp_path))
    latin = tmp_path / "conformance-matrix.md"
    latin.write_bytes(b"# x3drbp\n\nCaf\xe9\n")
    with pytest.raises(ValueError, match=f"^{latin}:3: not UTF-8 text"):
        write_matrix(str(latin))


def _plugin(tmp_path, pins: str):
    """pytest with the plugin on ode, pins from `pins`, in a folder of one test: the usage error."""
    (tmp_path / "test_one.py").write_text("def test_one():\n    pass\n")
    return run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "--x3drbp-backend", "ode",
                "--x3drbp-expectations", pins], cwd=str(tmp_path))


def test_the_plugin_refuses_a_missing_expectations_folder(tmp_path):
    """--x3drbp-expectations naming no folder made every case "must pass"; a usage error now,
    before any run."""
    missing = tmp_path / "nope"
    one_line(_plugin(tmp_path, str(missing)), pytest.ExitCode.USAGE_ERROR,
             rf"ERROR: --x3drbp-expectations: {missing}: cannot read folder: No such file or directory$")


def test_the_plugin_refuses_a_pin_file_that_is_a_pipe(tmp_path):
    pins = tmp_path / "pins"
    pins.mkdir()
    with fed(str(pins / "ode.toml")) as pipe:
        p = _plugin(tmp_path, str(pins))
    one_line(p, pytest.ExitCode.USAGE_ERROR, rf"ERROR: --x3drbp-expectations: {pipe}: a named pipe, not a regular file$")


def test_expectations_refuses_a_matrix_page_before_any_run(tmp_path, monkeypatch, capsys):
    """A --matrix page that does not read was said after every case had run and the pins had
    been rewritten: now at once, nothing run, nothing written."""
    from x3drbp import main as cli_main
    from conformance.runner import verdicts

    def ran(*args, **kwargs):
        raise AssertionError("the cases ran")
    monkeypatch.setattr(verdicts, "run_matrix", ran)
    b = _installed_backend()
    page = tmp_path / "matrix.md"
    page.write_text("# no markers\n")
    for bad, why in ((page, "no matrix markers"), (tmp_path, "a folder, not a regular file"),
                     (tmp_path / "nope" / "m.md", "cannot read file: No such file or directory")):
        assert cli_main(["expectations", "--backends", b, "--cases", "free_fall", "--matrix", str(bad)]) == 2
        err = capsys.readouterr().err.splitlines()
        assert len(err) == 1 and err[0].startswith(f"x3drbp expectations: --matrix {bad}: {why}"), err

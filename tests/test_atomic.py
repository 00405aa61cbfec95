"""Output files are written whole or not at all (x3d_core.files.atomic), by every writer."""

from __future__ import annotations

import os
import re

import pytest

from conftest import ROOT
from x3d_core.files import atomic

# the one file opened for writing elsewhere: a log the report's child commands append to as they run
LOGS = {os.path.join("x3drbp", "report.py")}


def test_an_interrupted_write_leaves_the_old_file_and_no_temporary(tmp_path, monkeypatch):
    path = tmp_path / "matrix.json"
    path.write_text("old\n")

    def interrupted(src, dst):
        raise KeyboardInterrupt

    monkeypatch.setattr(atomic.os, "replace", interrupted)
    with pytest.raises(KeyboardInterrupt):
        atomic.write_json(str(path), {"new": 1})
    assert path.read_text() == "old\n"
    assert os.listdir(tmp_path) == ["matrix.json"]


def test_a_writer_given_a_temporary_name_replaces_the_file_only_when_it_is_done(tmp_path):
    path = tmp_path / "run.rrd"
    path.write_bytes(b"old")
    with pytest.raises(OSError, match="disk full"), atomic.replacing(str(path)) as tmp:
        assert os.path.dirname(tmp) == str(tmp_path) and tmp != str(path)
        with open(tmp, "wb") as f:  # as a library writes the name it is given
            f.write(b"half of the new")
        raise OSError("disk full")
    assert path.read_bytes() == b"old" and os.listdir(tmp_path) == ["run.rrd"]
    with atomic.replacing(str(path)) as tmp:
        os.remove(tmp)  # a writer that creates the file itself
        with open(tmp, "wb") as f:
            f.write(b"new")
        assert path.read_bytes() == b"old"  # not yet
    assert path.read_bytes() == b"new" and os.listdir(tmp_path) == ["run.rrd"]


def test_a_writer_that_fails_before_writing_leaves_no_temporary(tmp_path):
    with pytest.raises(KeyboardInterrupt), atomic.replacing(str(tmp_path / "new.rrd")) as tmp:
        os.remove(tmp)
        raise KeyboardInterrupt
    assert os.listdir(tmp_path) == []


def test_write_json_ends_with_a_line_break(tmp_path):
    atomic.write_json(str(tmp_path / "a.json"), {"a": [1, 2]})
    assert (tmp_path / "a.json").read_text() == '{\n "a": [\n  1,\n  2\n ]\n}\n'


def _modules(package: str) -> list[str]:
    """Every .py file of a package, its subpackages included, relative to the project."""
    return sorted(os.path.relpath(os.path.join(folder, name), ROOT)
                  for folder, _, names in os.walk(os.path.join(ROOT, package)) for name in names if name.endswith(".py"))


def test_no_writer_opens_its_output_in_place():
    # a library's own save must be handed atomic.replacing's temporary name, tmp
    writing = re.compile(r"""open\([^)]*,\s*["'][wa]b?["']|\.savefig\(\s*path|write_text\(|write_bytes\("""
                         r"""|\.save\((?!tmp\b)""")
    found = []
    for package in ("x3d_core", "conformance", "reports", "x3drbp"):
        for rel in _modules(package):
            if rel == os.path.join("x3d_core", "files", "atomic.py"):
                continue
            with open(os.path.join(ROOT, rel), encoding="utf-8") as f:
                for k, line in enumerate(f, 1):
                    if writing.search(line) and "atomic." not in line and rel not in LOGS:
                        found.append(f"{rel}:{k}: {line.strip()}")
    assert not found

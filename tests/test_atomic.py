"""Output files are written whole or not at all (x3d_core.atomic), by every writer."""

from __future__ import annotations

import os
import re

import pytest

from conftest import ROOT
from x3d_core import atomic

# the one file opened for writing elsewhere: a log the report's child commands append to as they run
LOGS = {os.path.join("conformance", "report_command.py")}


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


def test_write_json_ends_with_a_line_break(tmp_path):
    atomic.write_json(str(tmp_path / "a.json"), {"a": [1, 2]})
    assert (tmp_path / "a.json").read_text() == '{\n "a": [\n  1,\n  2\n ]\n}\n'


def test_no_writer_opens_its_output_in_place():
    writing = re.compile(r"""open\([^)]*,\s*["'][wa]b?["']|\.savefig\(\s*path|write_text\(|write_bytes\(""")
    found = []
    for package in ("x3d_core", "conformance", "reports"):
        for name in sorted(os.listdir(os.path.join(ROOT, package))):
            rel = os.path.join(package, name)
            if not name.endswith(".py") or rel == os.path.join("x3d_core", "atomic.py"):
                continue
            with open(os.path.join(ROOT, rel), encoding="utf-8") as f:
                for k, line in enumerate(f, 1):
                    if writing.search(line) and "atomic." not in line and rel not in LOGS:
                        found.append(f"{rel}:{k}: {line.strip()}")
    assert not found

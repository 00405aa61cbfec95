"""Fuzzing the three loaders, bounded for CI (tests/fuzz_long.py runs the same for longer):
whatever the bytes, load() returns a scene or raises LoadError, in bounded time and memory.
Regression tests for what the fuzzing found come last."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import ROOT
from x3d_core.encodings.load import load
from x3d_core.encodings.vrml_loader import MAX_TOKENS
from x3d_core.model.scene import LoadError

import fuzzing as Z

EXT = {"xml": ".x3d", "vrml": ".x3dv", "json": ".x3dj"}
HEADS = {"xml": b"<X3D profile='Full' version='4.0'><Scene>", "vrml": b"#X3D V4.0 utf8\nPROFILE Full\n",
         "json": b'{"X3D": {"Scene": {"-children": ['}
FUZZ = settings(max_examples=150, deadline=None, database=None, derandomize=True,
                suppress_health_check=[HealthCheck.too_slow])


def holds(data: bytes, encoding: str) -> None:
    """The property, on one input written to a file of the encoding's extension."""
    with tempfile.TemporaryDirectory(prefix="x3drbp-fuzz-") as d:
        path = os.path.join(d, "input" + EXT[encoding])
        with open(path, "wb") as f:
            f.write(data)
        problem = Z.check(path, seconds=5)
    assert problem is None, f"{problem}: {data[:300]!r}"


@pytest.mark.parametrize("encoding", EXT)
@FUZZ
@given(tail=st.binary(max_size=400))
def test_any_bytes_after_a_header(encoding, tail):
    holds(HEADS[encoding] + tail, encoding)


_WORDS = ["DEF", "USE", "ROUTE", "TO", "PROTO", "EXTERNPROTO", "IS", "NULL", "[", "]", "{", "}", "RigidBody",
          "RigidBodyCollection", "BallJoint", "CollidableShape", "Shape", "Box", "bodies", "joints", "mass",
          "position", "children", "geometry", "1", "-1e308", "nan", "0x7fffffff", '"s"', '"', "#", ",", "TRUE"]


@FUZZ
@given(words=st.lists(st.sampled_from(_WORDS), max_size=60))
def test_vrml_token_soup(words):
    holds(HEADS["vrml"] + " ".join(words).encode(), "vrml")


_JSON = st.recursive(st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=8),
                     lambda kids: st.lists(kids, max_size=4) | st.dictionaries(
                         st.sampled_from(["@DEF", "@USE", "@mass", "@position", "-children", "-bodies",
                                          "RigidBody", "Group", "Box", "@size", "#comment"]), kids, max_size=4),
                     max_leaves=20)


@FUZZ
@given(node=_JSON)
def test_json_any_value_where_a_node_goes(node):
    doc = {"X3D": {"@version": "4.0", "Scene": {"-children": [node, {"RigidBodyCollection": {"-bodies": [node]}}]}}}
    holds(json.dumps(doc).encode(), "json")


@FUZZ
@given(field=st.sampled_from(["mass", "position", "orientation", "inertia", "forces", "DEF", "USE", "enabled"]),
       value=st.text(max_size=40))
def test_xml_any_attribute_value(field, value):
    quoted = value.replace("&", "&amp;").replace("'", "&apos;").replace("<", "&lt;")
    holds(HEADS["xml"] + f"<RigidBodyCollection><RigidBody {field}='{quoted}'/></RigidBodyCollection>"
          "</Scene></X3D>".encode("utf-8", "surrogatepass"), "xml")


def test_mutants_of_the_corpus_and_scenes(tmp_path):
    """A fixed seed: the same 400 mutants every run (byte flips, token deletions and
    duplications, huge/NaN/negative numbers, truncations)."""
    tried, findings = Z.fuzz(str(tmp_path), seed=20250607, count=400)
    assert tried == 400
    assert not findings, "\n".join(f"{f.path}: {f.problem}" for f in findings)


@pytest.mark.parametrize("encoding", EXT)
def test_deep_nesting_loads_or_is_refused_cleanly(tmp_path, encoding):
    path = tmp_path / f"deep{EXT[encoding]}"
    path.write_text(Z.deep(encoding, 10_000))
    assert Z.check(str(path), seconds=10) is None


def _peak(kind: str, encoding: str, n: int, tmp_path) -> tuple[float, int, str]:
    """(CPU seconds, peak MiB, problem) of loading one generated scene in a child of its own."""
    path = tmp_path / f"{kind}{EXT[encoding]}"
    path.write_text(getattr(Z, kind)(encoding, n))
    code = "import sys, fuzzing; print(fuzzing.check(sys.argv[1], 10))"
    proc = subprocess.Popen([sys.executable, "-c", code, str(path)], cwd=os.path.join(ROOT, "tests"),
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    _, _, usage = os.wait4(proc.pid, 0)
    return usage.ru_utime + usage.ru_stime, usage.ru_maxrss // 1024, proc.stdout.read().strip()


@pytest.mark.parametrize("kind,n", [("huge_array", 10**7), ("long_string", 10**7)])
@pytest.mark.parametrize("encoding", EXT)
def test_huge_inputs_load_or_are_refused_in_bounds(tmp_path, kind, n, encoding):
    """10^7 numbers in one MFVec3f, a string of 10^7 characters: < 10 s of CPU and < 1 GiB."""
    seconds, mib, problem = _peak(kind, encoding, n, tmp_path)
    assert problem == "None"
    assert seconds < 10 and mib < 1024, (seconds, mib)


# -- what fuzzing found ------------------------------------------------------------------
def test_vrml_file_ending_in_a_run_of_blanks(tmp_path):
    """Was a hang: the tokenizer tried every split of trailing blanks (2^n)."""
    path = tmp_path / "blanks.x3dv"
    path.write_bytes(HEADS["vrml"] + b"Group {}\n" + b" \t,\n" * 20)
    assert Z.check(str(path), seconds=5) is None


def test_json_integer_beyond_the_float_range(tmp_path):
    """Was OverflowError escaping load()."""
    path = tmp_path / "big.x3dj"
    path.write_text('{"X3D": {"Scene": {"-children": [{"RigidBodyCollection": {"-bodies": '
                    '[{"RigidBody": {"@mass": ' + "1" * 400 + "}}]}}]}}}")
    assert any("beyond the float range" in d.message for d in load(str(path)).errors)


def test_vrml_beyond_the_token_limit_is_refused(tmp_path):
    """Was 20 s and 3 GiB for 10^7 numbers; now a LoadError that says why."""
    path = tmp_path / "many.x3dv"
    path.write_text(Z.huge_array("vrml", MAX_TOKENS + 3))
    with pytest.raises(LoadError, match="more than 2000000 tokens"):
        load(str(path))

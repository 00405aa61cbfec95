"""A trace's two forms: the CSV (x3d_core/traces/trace.py), written as the csv module writes the
trace's rows, and the .npz (x3d_core/traces/trace_npz.py), what read_view makes of that CSV, array
for array.

Each run's trace is written both ways from one simulation and read back: the .npz must give
the same keys in the same order, the same times and values to the bit, the same text rows,
times and row count, on every installed backend, for scenes with bodies, joint outputs, a
CollisionSensor's contact tables and its text rows (isActive, SFNode names)."""

from __future__ import annotations

import csv
import io
import os
import subprocess
import sys
import zipfile

import numpy as np
import pytest

from conftest import ROOT, case_scene
from backends import base
from x3d_core.encodings.load import load
from x3d_core.model import fields as F
from x3d_core.semantics.engine import Unsupported
from x3d_core.semantics.evaluator import RunSettings, run
from x3d_core.semantics.world import worlds
from x3d_core.traces.trace import read_view
from x3d_core.traces.trace_npz import FORMAT, arrays, read_npz, write_npz

INSTALLED = [n for n, b in base.available().items() if not isinstance(b, str)]
SCENES = [case_scene("sensor_geometry"), case_scene("routed_contacts"), case_scene("hinge_limits"),
          os.path.join(ROOT, "scenes", "examples", "newtons_cradle.x3dv")]


def assert_same(got, want) -> None:
    assert got.keys() == want.keys()
    assert got.text_keys() == want.text_keys()
    for key in want.keys():
        (tg, vg), (tw, vw) = got.series(*key), want.series(*key)
        assert vg.shape == vw.shape and vg.dtype == vw.dtype, key
        assert np.array_equal(tg, tw) and np.array_equal(vg, vw, equal_nan=True), key
    for key in want.text_keys():
        (tg, sg), (tw, sw) = got.text(*key), want.text(*key)
        assert np.array_equal(tg, tw) and sg == sw, key
    assert np.array_equal(got.times(), want.times()) and len(got) == len(want)


@pytest.mark.parametrize("backend", INSTALLED)
def test_the_npz_holds_what_the_csv_reads_as(tmp_path, backend):
    b = base.load(backend)
    tried = 0
    for path in SCENES:
        scene = load(path)
        if any(d.support is base.Support.UNSUPPORTED for _, d in base.judged(b, scene, worlds(scene))):
            continue  # pymunk: planar scenes only
        try:
            trace = run(worlds(scene), b, RunSettings(duration=0.5))
        except Unsupported:  # pymunk: a scene that is not planar after all
            continue
        trace.write(str(tmp_path / "t.csv"))
        write_npz(trace.view(), str(tmp_path / "t.npz"))
        want = read_view(str(tmp_path / "t.csv"))
        assert_same(trace.view(), want)
        assert_same(read_view(str(tmp_path / "t.npz")), want)
        tried += 1
    assert tried >= 2, f"{backend} ran too few of the scenes to compare"


@pytest.mark.parametrize("backend", INSTALLED)
def test_the_csv_is_what_the_csv_module_writes_of_the_rows(backend):
    """Trace.text formats an SF float field's numbers in bulk (one repr of every row): it must
    still write each row as fields.format_xml gives it, quoted as the csv module quotes."""
    b = base.load(backend)
    for path in SCENES:
        scene = load(path)
        if any(d.support is base.Support.UNSUPPORTED for _, d in base.judged(b, scene, worlds(scene))):
            continue
        try:
            trace = run(worlds(scene), b, RunSettings(duration=0.5))
        except Unsupported:
            continue
        want = io.StringIO()
        writer = csv.writer(want, lineterminator="\n")
        writer.writerow(["time", "node", "field", "value"])
        writer.writerows((F._num(t), node, fld, value) for t, node, fld, value in trace.events())
        assert trace.text() == want.getvalue()


def test_bulk_float_rows_are_format_xmls(tmp_path):
    """Whole numbers lose their .0 (also the last of a row, and -0.0), others keep every digit."""
    from x3d_core.traces.trace import _float_rows
    rows = np.array([[1.0, -0.0, 2.5], [10.0, 1e-05, 100.0], [np.inf, -np.nan, 0.1]])
    assert _float_rows(rows) == [F.format_xml(F.FIELD_TYPES["SFVec3f"], r) for r in rows.tolist()]
    assert _float_rows(np.array([3.0, 0.25])) == ["3", "0.25"]
    assert _float_rows(np.empty((0, 3))) == []


def test_the_scenes_cover_tables_and_text_rows(tmp_path):
    """The comparison above is only as good as its scenes: contacts tables and text rows are in them."""
    b = base.load(INSTALLED[0])
    view = run(worlds(load(case_scene("sensor_geometry"))), b, RunSettings(duration=0.5)).view()
    assert any("contacts[" in f for _, f in view.keys())
    assert view.text_keys()


def test_run_writes_npz_by_its_name(tmp_path):
    """`x3drbp run --trace OUT.npz`: the same rows as `--trace OUT.csv`, in arrays."""
    scene = os.path.join(ROOT, "scenes", "examples", "pendulum.x3d")
    for name in ("t.csv", "t.npz"):
        subprocess.run([sys.executable, "-m", "x3drbp", "run", scene, "--backend", INSTALLED[0],
                        "--duration", "1", "--trace", str(tmp_path / name), "-q"], cwd=ROOT, check=True)
    assert zipfile.is_zipfile(tmp_path / "t.npz")
    assert_same(read_view(str(tmp_path / "t.npz")), read_view(str(tmp_path / "t.csv")))


def test_an_npz_that_is_not_a_trace_is_refused_naming_it(tmp_path):
    junk = tmp_path / "junk.npz"
    junk.write_bytes(b"not a zip at all")
    with pytest.raises(ValueError, match="junk.npz: not an x3drbp trace"):
        read_npz(str(junk))
    other = tmp_path / "other.npz"
    np.savez(other, a=np.arange(3))
    with pytest.raises(ValueError, match=f"other.npz: not an x3drbp trace \\({FORMAT}\\): no format"):
        read_npz(str(other))


def test_an_npz_whose_arrays_disagree_is_refused(tmp_path):
    b = base.load(INSTALLED[0])
    view = run(worlds(load(os.path.join(ROOT, "scenes", "examples", "pendulum.x3d"))), b,
               RunSettings(duration=0.1)).view()
    a = arrays(view)
    a["lengths"] = a["lengths"] + 1
    bad = tmp_path / "bad.npz"
    np.savez(bad, **a)
    with pytest.raises(ValueError, match="bad.npz: the trace's arrays disagree on their lengths"):
        read_npz(str(bad))


def test_the_npz_needs_no_pickle(tmp_path):
    """Every array plain: np.load with allow_pickle=False reads it (a trace is data, never code)."""
    b = base.load(INSTALLED[0])
    view = run(worlds(load(case_scene("sensor_geometry"))), b, RunSettings(duration=0.2)).view()
    write_npz(view, str(tmp_path / "t.npz"))
    with np.load(tmp_path / "t.npz", allow_pickle=False) as npz:
        assert all(npz[name].dtype != object for name in npz.files)
        assert str(npz["format"]) == FORMAT


def test_an_npz_with_object_arrays_is_refused_not_unpickled(tmp_path):
    b = base.load(INSTALLED[0])
    a = arrays(run(worlds(load(os.path.join(ROOT, "scenes", "examples", "pendulum.x3d"))), b,
                   RunSettings(duration=0.1)).view())
    a["text_v"] = np.array([object()], dtype=object)
    bad = tmp_path / "pickled.npz"
    np.savez(bad, **a)
    with pytest.raises(ValueError, match="pickled.npz: text_v: object values; a trace holds text there"):
        read_npz(str(bad))

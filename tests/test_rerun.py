"""Rerun recordings (`--rerun`), read back with rerun's own reader: the entities, the
frames on the timeline, and the divergence series against compare's JSON."""

from __future__ import annotations

import errno
import json
import os

import numpy as np
import pyarrow as pa
import pytest
from rerun.chunk import RrdReader

from x3drbp import main as cli_main
from conftest import SCENES
from reports.report_page import _comparisons, comparisons
from reports.rerun_recording import TIMELINE
from reports.rerun_shapes import cone_mesh, grid_triangles

CRADLE = os.path.join(SCENES, "examples", "newtons_cradle.x3dv")  # contacts, a joint output, and pairs that part


def _entities(path: str) -> dict[str, list[pa.RecordBatch]]:
    """Each entity's chunks as record batches."""
    out: dict[str, list[pa.RecordBatch]] = {}
    for chunk in RrdReader(path).stream():
        out.setdefault(chunk.entity_path, []).append(chunk.to_record_batch())
    return out


def _column(batches: list[pa.RecordBatch], name: str) -> list:
    return [x for b in batches for x in b.column(name).to_pylist()]


def _times(batches: list[pa.RecordBatch]) -> np.ndarray:
    return np.array([b.column(TIMELINE).cast(pa.int64()).to_numpy() for b in batches]).ravel() * 1e-9


def test_compare_recording_holds_each_backend_its_bodies_and_compares_divergence(tmp_path):
    (tmp_path / "compare").mkdir()
    rrd, js = tmp_path / "compare" / "cradle.rrd", tmp_path / "compare" / "cradle.json"
    assert cli_main(["compare", CRADLE, "--backends", "bullet,mujoco", "--duration", "2", "--json", str(js),
                     "--rerun", str(rrd)]) == 0
    pair = json.loads(js.read_text())["pairs"][0]
    entities = _entities(str(rrd))
    roots = {e.split("/")[1] for e in entities}
    assert roots == {"__properties", "bullet", "mujoco", "joints", "divergence"}
    times = np.asarray(pair["times"])
    for backend in ("bullet", "mujoco"):
        for body in pair["bodies"]:
            batches = entities[f"/{backend}/bodies/{body}"]
            assert np.allclose(_times(batches), times, atol=1e-9)  # a row per frame
        assert f"/{backend}/contacts/Sensor" in entities
        assert any(e.startswith(f"/{backend}/bodies/Ball1/") for e in entities)  # its collision shape
    where = f"/divergence/{pair['a']}_vs_{pair['b']}"
    for quantity in ("position", "orientation"):
        for stat in ("max", "rms"):
            values = _column(entities[f"{where}/{quantity}_{stat}"], "Scalars:scalars")
            assert np.array_equal(np.ravel(values), pair[quantity][f"frame_{stat}"])
    first = pair["position"]["first_over"]
    assert first is not None
    events = entities[f"{where}/events"]
    assert any(abs(t - first["time"]) < 1e-9 for t in _times(events))
    assert all(level == "WARN" for level in np.ravel(_column(events, "TextLog:level")))
    assert _column(entities[f"{where}/position_first_over"], "Scalars:scalars") == [[first["bodies"][0]["value"]]]
    assert RrdReader(str(rrd)).blueprints()  # the layout travels with the recording
    assert "[cradle.rrd](compare/cradle.rrd)" in _comparisons(str(tmp_path), comparisons(str(tmp_path)))  # the report links it


def test_run_recording_has_one_backend_and_no_divergence(tmp_path):
    rrd = tmp_path / "run.rrd"
    assert cli_main(["run", CRADLE, "--backend", "mujoco", "--duration", "0.25", "--trace", str(tmp_path / "t.csv"),
                     "--rerun", str(rrd)]) == 0
    entities = _entities(str(rrd))
    assert {e.split("/")[1] for e in entities} == {"__properties", "mujoco", "joints"}
    assert len(_times(entities["/mujoco/bodies/Ball3"])) == 16  # frames at 60 Hz over 0.25 s, both ends


def test_a_failed_recording_keeps_the_previous_file_and_leaves_no_partial_one(tmp_path, monkeypatch):
    from reports.rerun_recording import write_recording
    from x3d_core.files import atomic
    from x3d_core.encodings.load import load
    from x3d_core.traces.trace import TraceView, read_trace

    trace = tmp_path / "t.csv"
    assert cli_main(["run", CRADLE, "--backend", "mujoco", "--duration", "0.25", "--trace", str(trace)]) == 0
    rrd = tmp_path / "run.rrd"
    rrd.write_bytes(b"the previous recording")

    def fails_once_written(src, dst):  # the recording is written beside it, then the write fails
        assert os.path.getsize(src) > 1000 and os.path.dirname(src) == str(tmp_path)
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(atomic.os, "replace", fails_once_written)
    runs = [("mujoco", TraceView(read_trace(str(trace))))]
    with pytest.raises(atomic.CannotWrite, match=f"cannot write {rrd}: No space left"):
        write_recording(str(rrd), load(CRADLE), runs)
    assert rrd.read_bytes() == b"the previous recording"
    assert sorted(os.listdir(tmp_path)) == ["run.rrd", "t.csv"]
    monkeypatch.undo()
    write_recording(str(rrd), load(CRADLE), runs)  # and once it succeeds, the new one replaces it whole
    assert sorted(os.listdir(tmp_path)) == ["run.rrd", "t.csv"]
    assert len(_times(_entities(str(rrd))["/mujoco/bodies/Ball3"])) == 16


def test_tessellations_close_their_surfaces():
    vertices, triangles = cone_mesh(0.5, 2.0, segments=8)
    assert len(vertices) == 10 and len(triangles) == 16 and triangles.max() == 9
    assert np.allclose(vertices[:, 1].max(), 1.0) and np.allclose(vertices[:, 1].min(), -1.0)
    grid = grid_triangles(3, 4)
    assert grid.shape == (2 * 2 * 3, 3) and grid.max() == 11
    edges = np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    assert np.all(counts == 2)  # every edge shared by two triangles: closed

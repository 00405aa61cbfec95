"""Every third-party scene under ../shared/corpus loads, validates and writes back unchanged."""

from __future__ import annotations

import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import pytest

from backends import base
from conftest import CORPUS, ROOT, SCENES
from x3d_core.analysis import summarize
from x3d_core.load import load
from x3d_core.model_diff import differences
from x3d_core.paths import scene_files
from x3d_core.vrml_writer import write_vrml
from x3d_core.xml_writer import write_xml

# (bodies, joints by type): counted by hand from the files (double_hinge_joint and
# motor_joint really hold a SliderJoint, a copy/paste in the originals)
EXPECTED = {
    "cobweb/BallBounceSimple.x3d": (2, {}),
    "cobweb/Hierarchy.x3d": (2, {}),
    "x_ite_media/CollisionCollection.x3d": (3, {}),
    "x_ite_media/SingleAxisHingeJoint.x3d": (10, {"SingleAxisHingeJoint": 5}),
    "x_ite_media/SliderJoint.x3d": (3, {"SliderJoint": 1}),
    "xj3d/combined__cannon.x3dv": (1, {}),
    "xj3d/combined__toy_car.x3dv": (5, {"DoubleAxisHingeJoint": 4}),
    "xj3d/physics__ball_bounce.x3dv": (1, {}),
    "xj3d/physics__ball_bounce_simple.x3dv": (1, {}),
    "xj3d/physics__ball_joint.x3dv": (3, {"BallJoint": 2}),
    "xj3d/physics__body_basic.x3dv": (2, {}),
    "xj3d/physics__body_geom.x3dv": (2, {}),
    "xj3d/physics__bounce_trimesh.x3dv": (1, {}),
    "xj3d/physics__double_hinge_joint.x3dv": (2, {"SliderJoint": 1}),
    "xj3d/physics__motor_joint.x3dv": (2, {"SliderJoint": 1}),
    "xj3d/physics__moving_body.x3dv": (1, {}),
    "xj3d/physics__single_hinge_joint.x3dv": (3, {"SingleAxisHingeJoint": 2}),
    "xj3d/physics__slider_joint.x3dv": (2, {"SliderJoint": 1}),
    "xj3d/physics__universal_joint.x3dv": (2, {"UniversalJoint": 1}),
}

needs_corpus = pytest.mark.skipif(not os.path.isdir(CORPUS), reason=f"no corpus at {CORPUS}")

# Scenes whose motion a ROUTE from a Script or an input device drives: refused on every
# backend by naming the routed input (x3drbp runs no Scripts). Every other scene runs,
# except where a backend declares a feature it uses unsupported.
SCRIPTED = {"xj3d/combined__cannon.x3dv", "xj3d/combined__toy_car.x3dv", "xj3d/physics__ball_bounce.x3dv",
            "xj3d/physics__bounce_trimesh.x3dv", "xj3d/physics__double_hinge_joint.x3dv",
            "xj3d/physics__motor_joint.x3dv", "xj3d/physics__moving_body.x3dv", "xj3d/physics__slider_joint.x3dv"}
RUN_SECONDS = 5
BACKENDS = [n for n, b in base.available().items() if not isinstance(b, str)]


@needs_corpus
def test_every_corpus_file_is_expected():
    found = {os.path.relpath(p, CORPUS) for p in scene_files([CORPUS])}
    assert found == set(EXPECTED)


@needs_corpus
@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_corpus_scene_loads_with_right_counts(name):
    scene = load(os.path.join(CORPUS, name))
    assert not scene.errors, [str(e) for e in scene.errors]
    s = summarize(scene)
    bodies, joints = EXPECTED[name]
    assert s.bodies == bodies
    assert dict(s.joints) == joints


@needs_corpus
def test_check_command_exits_zero_on_the_corpus():
    r = subprocess.run([sys.executable, "-m", "conformance.cli", "check", CORPUS], cwd=ROOT,
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr
    assert f"{len(EXPECTED)} of {len(EXPECTED)} files ok" in r.stdout
    assert "Traceback" not in r.stderr


def all_scenes():
    return scene_files([CORPUS] if os.path.isdir(CORPUS) else []) + scene_files([SCENES])


@pytest.mark.parametrize("path", all_scenes(), ids=lambda p: os.path.relpath(p, os.path.dirname(p) + "/.."))
@pytest.mark.parametrize("writer,ext", [(write_xml, ".x3d"), (write_vrml, ".x3dv")], ids=["xml", "vrml"])
def test_round_trip_gives_an_equal_model(path, writer, ext, tmp_path):
    a = load(path)
    out = tmp_path / f"out{ext}"
    out.write_bytes(writer(a))
    b = load(str(out))
    assert not b.errors, [str(e) for e in b.errors]
    assert differences(a, b) == []
    # and writing again gives the same bytes: the writer is deterministic and stable
    assert writer(b) == out.read_bytes()


@pytest.fixture(scope="module")
def corpus_runs(tmp_path_factory):
    """Every corpus scene for 5 simulated seconds on every installed backend, through the CLI,
    two at a time: (scene, backend) -> (exit status, stderr, the trace's last time or None)."""
    folder = tmp_path_factory.mktemp("corpus_runs")

    def one(pair):
        name, backend = pair
        out = folder / f"{name.replace('/', '_')}.{backend}.csv"
        r = subprocess.run([sys.executable, "-m", "conformance.cli", "run", os.path.join(CORPUS, name),
                            "--backend", backend, "--duration", str(RUN_SECONDS), "--trace", str(out)],
                           cwd=ROOT, capture_output=True, text=True, timeout=300)
        last = max(float(line.split(",", 1)[0]) for line in out.read_text().splitlines()[1:]) if out.exists() else None
        return pair, (r.returncode, r.stderr, last)

    with ThreadPoolExecutor(max_workers=max(2, os.cpu_count() or 1)) as pool:
        return dict(pool.map(one, [(n, b) for n in EXPECTED for b in BACKENDS]))


@needs_corpus
@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_corpus_scene_runs_five_seconds_or_names_what_it_lacks(name, backend, corpus_runs):
    status, stderr, last = corpus_runs[(name, backend)]
    assert "Traceback" not in stderr and "blew up" not in stderr, stderr
    refused = [line.split(f"unsupported by {backend}: ", 1)[1].split(":", 1)[0]
               for line in stderr.splitlines() if f"unsupported by {backend}: " in line]
    if status == 0:
        assert name not in SCRIPTED, "a scene its Scripts drive ran as if they were not there"
        assert last == pytest.approx(RUN_SECONDS) and not refused
        return
    assert status == 3 and refused, stderr
    table = base.load(backend)
    assert all(table.support(f).support is base.Support.UNSUPPORTED for f in refused), refused
    if name in SCRIPTED:
        assert any(f.endswith(".routed") for f in refused), refused
    else:  # nothing routed: only what this backend itself declares it cannot do
        assert not any(f.endswith(".routed") for f in refused), refused

"""Every third-party scene under ../shared/corpus loads, validates and writes back unchanged,
and runs or names what it lacks (a routed input, a Script that writes fields directly)."""

from __future__ import annotations

import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import pytest

from backends import base
from conftest import CASES, CORPUS, ROOT, SCENES
from x3d_core.encodings.load import load
from x3d_core.encodings.model_diff import differences
from x3d_core.encodings.vrml_writer import write_vrml
from x3d_core.encodings.xml_writer import write_xml
from x3d_core.files.paths import scene_files
from x3d_core.semantics.analysis import SCRIPT_DIRECT_OUTPUT, features, run_features, summarize

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

# Scenes whose motion a ROUTE from a Script or an input device drives, or a Script with
# directOutput TRUE that holds a physics node (x_ite_media/CollisionCollection.x3d: its
# initialize() sets the ball's position and velocities through an SFNode field): refused on
# every backend by naming the routed input or the Script (x3drbp runs no Scripts). Every
# other scene runs, except where a backend declares a feature it uses unsupported.
SCRIPTED = {"xj3d/combined__cannon.x3dv", "xj3d/combined__toy_car.x3dv", "xj3d/physics__ball_bounce.x3dv",
            "xj3d/physics__bounce_trimesh.x3dv", "xj3d/physics__double_hinge_joint.x3dv",
            "xj3d/physics__motor_joint.x3dv", "xj3d/physics__moving_body.x3dv", "xj3d/physics__slider_joint.x3dv",
            "x_ite_media/CollisionCollection.x3d"}
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
    r = subprocess.run([sys.executable, "-m", "x3drbp", "check", CORPUS], cwd=ROOT,
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr
    assert f"{len(EXPECTED)} of {len(EXPECTED)} files ok" in r.stdout
    assert "Traceback" not in r.stderr


def all_scenes():
    return scene_files([CORPUS] if os.path.isdir(CORPUS) else []) + scene_files([SCENES, CASES])


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


# both bodies enabled FALSE: `run` says there is nothing to simulate (exit 1, no trace)
EMPTY = {"cobweb/Hierarchy.x3d"}


@pytest.fixture(scope="module")
def corpus_runs(tmp_path_factory):
    """Every corpus scene for 5 simulated seconds on every installed backend, through the CLI,
    two at a time: (scene, backend) -> (exit status, stderr, the trace's last time or None)."""
    folder = tmp_path_factory.mktemp("corpus_runs")

    def one(pair):
        name, backend = pair
        out = folder / f"{name.replace('/', '_')}.{backend}.csv"
        r = subprocess.run([sys.executable, "-m", "x3drbp", "run", os.path.join(CORPUS, name),
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
    refused = [line.split(f"unsupported by {backend}: ", 1)[1].split(":", 1)[0].split(" = ", 1)[0].split(" (", 1)[0]
               for line in stderr.splitlines() if f"unsupported by {backend}: " in line]
    if name in EMPTY:
        assert status == 1 and "nothing to simulate" in stderr and last is None, stderr
        return
    if status == 0:
        assert name not in SCRIPTED, "a scene its Scripts drive ran as if they were not there"
        assert last == pytest.approx(RUN_SECONDS) and not refused
        return
    assert status == 3 and refused, stderr
    table = base.load(backend)
    assert all(table.support(f).support is base.Support.UNSUPPORTED for f in refused), refused
    scripted = [f for f in refused if f.endswith(".routed") or f == SCRIPT_DIRECT_OUTPUT]
    if name in SCRIPTED:
        assert scripted, refused
    else:  # nothing routed: only what this backend itself declares it cannot do
        assert not scripted, refused


# -- Scripts, in scenes written here: one with directOutput TRUE that holds a physics node, or a
# node holding one, may write its fields itself, with no ROUTE, so it is refused by name; one
# that holds none, or has directOutput FALSE and no ROUTE into a physics node, runs

BODY = "#X3D V4.0 utf8\nDEF World RigidBodyCollection { bodies DEF Ball RigidBody { position 0 1 0 } }\n"
HELD = "#X3D V4.0 utf8\nDEF Top Group { children [ DEF World RigidBodyCollection { bodies DEF Ball RigidBody { } } ] }\n"
SETS_THE_BALL = 'url "ecmascript: function initialize() { ball.position = new SFVec3f(0, 5, 0); }"'
BY_NAME = ("directOutput TRUE url \"ecmascript: function initialize() { "
           "Browser.currentScene.getNamedNode('Ball').position = new SFVec3f(0, 5, 0); }\"")


def _script(tmp_path, script: str, route: str = "", body: str = BODY) -> str:
    path = tmp_path / "s.x3dv"
    path.write_text(f"{body}DEF Mover Script {{ {script} }}\n{route}")
    return str(path)


def _x3drbp(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "x3drbp", *args], cwd=ROOT, capture_output=True, text=True,
                          timeout=120)


@pytest.mark.parametrize("script,body,held", [
    (f"directOutput TRUE initializeOnly SFNode ball USE Ball {SETS_THE_BALL}", BODY, "RigidBody Ball in its field ball"),
    ("directOutput TRUE inputOutput MFNode top [ USE Top ]", HELD,
     "Group Top (holding RigidBodyCollection World) in its field top")],
    ids=["the-body", "an-ancestor"])
def test_a_script_with_direct_output_holding_physics_is_refused_naming_what_it_holds(tmp_path, script, body, held):
    path = _script(tmp_path, script, body=body)
    assert SCRIPT_DIRECT_OUTPUT in run_features(load(path))
    refusal = f"{SCRIPT_DIRECT_OUTPUT} (Script Mover holds {held}): x3drbp runs no Scripts, and with directOutput TRUE"
    for backend in BACKENDS:
        assert base.load(backend).support(SCRIPT_DIRECT_OUTPUT).support is base.Support.UNSUPPORTED
        out = tmp_path / f"{backend}.csv"
        r = _x3drbp("run", path, "--backend", backend, "--duration", "0.1", "--trace", str(out))
        assert r.returncode == 3, (backend, r.stderr)
        assert f"unsupported by {backend}: {refusal}" in r.stderr and "routed" not in r.stderr and not out.exists()


@pytest.mark.parametrize("script", [BY_NAME, "directOutput TRUE initializeOnly SFNode look Shape { }"],
                         ids=["by-name", "holds-no-physics"])
def test_a_script_with_direct_output_holding_no_physics_runs_saying_what_it_ignores(tmp_path, script):
    path = _script(tmp_path, script)
    assert SCRIPT_DIRECT_OUTPUT not in features(load(path))
    check = _x3drbp("check", path)
    assert check.returncode == 0 and "Script Mover.directOutput: TRUE, but none of its SFNode/MFNode fields holds " \
        "a physics node or a node that holds one, so a run goes on without it" in check.stdout, check.stdout
    for backend in BACKENDS:
        out = tmp_path / f"{backend}.csv"
        r = _x3drbp("run", path, "--backend", backend, "--duration", "0.1", "--trace", str(out))
        assert r.returncode == 0 and out.exists(), (backend, r.stderr)


def test_a_script_without_direct_output_or_a_route_into_physics_runs_with_a_warning(tmp_path):
    path = _script(tmp_path, f"initializeOnly SFNode ball USE Ball {SETS_THE_BALL}")  # directOutput FALSE
    assert not [f for f in run_features(load(path)) if f.endswith(".routed")]
    check = _x3drbp("check", path)
    assert check.returncode == 0 and "Script is kept in the model but does not run" in check.stdout, check.stdout
    for backend in BACKENDS:
        out = tmp_path / f"{backend}.csv"
        r = _x3drbp("run", path, "--backend", backend, "--duration", "0.1", "--trace", str(out))
        assert r.returncode == 0 and out.exists(), (backend, r.stderr)


def test_only_a_script_s_route_into_physics_or_its_direct_output_counts(tmp_path):
    routed = _script(tmp_path, "outputOnly SFVec3f p", "ROUTE Mover.p TO Ball.set_position\n")
    assert {"RigidBody.set_position.routed"} == {f for f in features(load(routed)) if f.endswith(".routed")}
    no_physics = _script(tmp_path, f"directOutput TRUE {SETS_THE_BALL}", body="#X3D V4.0 utf8\nDEF Ball Transform { }\n")
    assert features(load(no_physics)) == []  # nothing of the component for it to write

"""The bundled example scenes a new user starts from say what they do: the car is the model the
engine-speed benchmark times, and the limited pendulum reaches the stops its advice weighs."""

from __future__ import annotations

import dataclasses
import os
import sys

import numpy as np
import pytest

from conftest import ROOT, SCENES
from x3d_core.encodings.load import load
from x3d_core.model.scene import Node
from x3d_core.semantics.evaluator import RunSettings, run
from x3d_core.semantics.world import worlds

sys.path.insert(0, os.path.join(ROOT, "benchmarks"))
import car  # noqa: E402  (the benchmark's scene, beside the tests' path)

EXAMPLES = os.path.join(SCENES, "examples")


def _plain(value):
    """A world as nested plain values, its nodes left out (they hold where in which file each came from)."""
    if dataclasses.is_dataclass(value):
        return {f.name: _plain(getattr(value, f.name)) for f in dataclasses.fields(value)
                if not isinstance(getattr(value, f.name), Node)}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value if not isinstance(v, Node)]
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, np.ndarray):
        return value.tolist()
    return value


def test_the_car_example_is_the_benchmark_s_car(tmp_path):
    """Readable for a user, and the same model to the last digit as the one engine_speed times."""
    example = worlds(load(os.path.join(EXAMPLES, "car.x3d")))
    generated = tmp_path / "car.x3d"
    generated.write_text(car.car_x3d())
    benchmark = worlds(load(str(generated)))
    assert len(example) == len(benchmark) == 1
    assert _plain(example[0]) == _plain(benchmark[0])
    assert len(example[0].joints) == 4 and example[0].collisions is not None


def test_the_limited_pendulum_meets_every_stop_it_states():
    """Its comment promises each hinge meets a stop within the first 0.6 s and the wrist both; a
    backend that ignored the limits would swing the shoulder to -pi/2 and past."""
    mujoco = pytest.importorskip("backends.mujoco", reason="mujoco is not installed")
    scene = worlds(load(os.path.join(EXAMPLES, "limited_pendulum.x3d")))
    trace = run(scene, mujoco.BACKEND, RunSettings(0.6, 1 / 240, 240))
    angles: dict[str, list[float]] = {}
    for r in trace.rows:
        if r.field == "angle":
            angles.setdefault(r.node, []).append(float(r.value))
    # met: within reach of the 0.8 rad stop (a 1/240 s step at up to 6 rad/s moves 0.025 rad)
    met = {name: (min(a) <= -0.8 + 0.03, max(a) >= 0.8 - 0.03) for name, a in angles.items()}
    assert met["Shoulder"][0] and met["Elbow"][0] and met["Wrist"] == (True, True), met
    # MuJoCo's soft limits let a stop be passed by a few hundredths of a radian, never more
    assert max(abs(v) for a in angles.values() for v in a) <= 0.85

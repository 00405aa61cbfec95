"""A run's work grows linearly with the number of bodies (issue 17: 3e4 bodies took 76 s, 1e5
did not finish in 120 s: `worlds` kept a body list unique by scanning it, validate found each
body again in its collection's list).

Counted, not timed: the Python calls (builtins included) of load, check, worlds, the scene's
warnings, a backend's judgement, one frame's run and the trace's text are deterministic, and
for 4x the bodies a linear pipeline makes about 4x the calls where a quadratic one makes 16x.
"""

from __future__ import annotations

import cProfile
import pstats

import pytest

from backends import base
from x3d_core.encodings.load import load
from x3d_core.semantics.analysis import run_uses
from x3d_core.semantics.evaluator import RunSettings, run
from x3d_core.semantics.outcome import outcome_warnings
from x3d_core.semantics.world import worlds

ENGINES = [n for n in ("ode", "bullet", "mujoco", "dart") if not isinstance(base.available().get(n, "absent"), str)]


def _scene(tmp_path, n: int) -> str:
    """n spheres apart in one collection with a collider."""
    bodies = "\n".join(f"<RigidBody DEF='B{i}' position='{3 * i} 0 0'><Sphere containerField='massDensityModel' "
                       f"radius='0.5'/><CollidableShape DEF='C{i}' containerField='geometry'><Shape "
                       f"containerField='shape'><Sphere radius='0.5'/></Shape></CollidableShape></RigidBody>"
                       for i in range(n))
    shapes = "\n".join(f"<CollidableShape USE='C{i}' containerField='collidables'/>" for i in range(n))
    path = tmp_path / f"many_{n}.x3d"
    path.write_text(f"<X3D profile='Full' version='4.0'><Scene><RigidBodyCollection DEF='W'>{bodies}"
                    f"<CollisionCollection containerField='collider'>{shapes}</CollisionCollection>"
                    f"</RigidBodyCollection></Scene></X3D>")
    return str(path)


def _calls(path: str, engine: base.Backend) -> int:
    profile = cProfile.Profile()
    profile.enable()
    scene = load(path)
    ws = worlds(scene)
    outcome_warnings(scene, ws)
    run_uses(scene, ws)
    trace = run(ws, engine, RunSettings(duration=1 / 60, dt=1 / 60, frame_rate=60))
    trace.text()
    profile.disable()
    assert not scene.errors and len(ws[0].bodies.names) == len(scene.of_type("RigidBody"))
    return pstats.Stats(profile).total_calls


@pytest.mark.skipif(not ENGINES, reason="no 3D engine installed")
def test_calls_grow_linearly_with_bodies(tmp_path):
    engine = base.load(ENGINES[0])
    small, large = (_calls(_scene(tmp_path, n), engine) for n in (200, 1600))
    assert large / small < 10, f"{large / small:.1f}x the calls for 8x the bodies: quadratic somewhere"

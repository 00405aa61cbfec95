"""What benchmarks/scaling.py relies on: a process's peak memory read as its own, the builds of a still
scene doing no work that grows faster than its bodies, and bulk state reads that give the very numbers a
body-by-body read gives."""

from __future__ import annotations

import os
import sys

import numpy as np
import pytest

from conftest import ROOT
from engine_run import ODD_BODY, scene_worlds

sys.path.insert(0, os.path.join(ROOT, "benchmarks"))
from measure import process_usage  # noqa: E402  (benchmarks/measure.py)

MB = 2 ** 20

# a hinge chain of three links hanging from a fixed base: `still` at rest, else its last link turning
CHAIN = """<RigidBodyCollection gravity='0 -9.81 0'><RigidBody DEF='Base' fixed='true'/>
  <RigidBody DEF='L0' position='0 -0.5 0'/><RigidBody DEF='L1' position='0 -1.5 0'/>
  <RigidBody DEF='L2' position='0 -2.5 0' {spin}/>
  <SingleAxisHingeJoint anchorPoint='0 0 0' axis='0 0 1'><RigidBody USE='Base' containerField='body1'/>
    <RigidBody USE='L0' containerField='body2'/></SingleAxisHingeJoint>
  <SingleAxisHingeJoint anchorPoint='0 -1 0' axis='0 0 1'><RigidBody USE='L0' containerField='body1'/>
    <RigidBody USE='L1' containerField='body2'/></SingleAxisHingeJoint>
  <SingleAxisHingeJoint anchorPoint='0 -2 0' axis='0 0 1'><RigidBody USE='L1' containerField='body1'/>
    <RigidBody USE='L2' containerField='body2'/></SingleAxisHingeJoint></RigidBodyCollection>"""


def test_a_process_s_peak_memory_is_its_own_not_its_parent_s():
    # Linux keeps in a child's ru_maxrss the size of the memory it replaced at exec: a child of this
    # process, once it holds 300 MB, would read 300 MB for a bare interpreter
    held = np.ones(300 * MB // 8)
    _, bare = process_usage([sys.executable, "-c", "pass"])
    assert bare < 100
    _, big = process_usage([sys.executable, "-c", f"import numpy; numpy.ones({200 * MB // 8}).sum()"])
    assert big > 200
    assert held.sum() == len(held)  # held until here


@pytest.mark.parametrize("engine", ["bullet", "dart"])
def test_a_still_tree_is_built_without_a_velocity_fit(tmp_path, monkeypatch, engine):
    # the fit (a Jacobian per link over its ancestors, and least squares) is quadratic to cubic in a
    # chain's links; at rest its answer is zero, set without it, and a moving tree still gets it
    backend = pytest.importorskip(f"backends.{engine}").BACKEND
    fits = []
    lstsq = np.linalg.lstsq
    monkeypatch.setattr(np.linalg, "lstsq", lambda *a, **k: fits.append(1) or lstsq(*a, **k))
    still = backend.build(scene_worlds(tmp_path, CHAIN.format(spin=""))[0], 1 / 240)
    assert not fits
    s = still.state()
    assert not s.linear_velocity.any() and not s.angular_velocity.any()
    moving = backend.build(scene_worlds(tmp_path, CHAIN.format(spin="angularVelocity='0 0 1'"))[0], 1 / 240)
    assert fits
    assert moving.state().angular_velocity[1:, 2].all()  # the fit's: least squares through the chain


def test_drake_s_bulk_state_is_its_body_by_body_reading_to_the_bit(tmp_path):
    # a body with its centre of mass off its origin (the v + w x (R com) term) beside one without
    drake = pytest.importorskip("backends.drake").BACKEND
    body = (f"<RigidBodyCollection gravity='0 -9.81 0'><RigidBody DEF='A' {ODD_BODY} linearVelocity='0.5 0 -1' "
            "angularVelocity='0 2 1'/><RigidBody DEF='B' position='0 1 0' orientation='0 0 1 0.4' "
            "angularVelocity='1 -2 0.5'/></RigidBodyCollection>")
    sim = drake.build(scene_worlds(tmp_path, body)[0], 1 / 240)
    sim.step(30)
    com = sim.world.bodies.com
    poses = sim.plant.get_body_poses_output_port().Eval(sim.context)
    vels = sim.plant.get_body_spatial_velocities_output_port().Eval(sim.context)
    s = sim.state()
    for i, b in enumerate(sim.bodies):
        X, V = poses[int(b.index())], vels[int(b.index())]
        q = X.rotation().ToQuaternion()
        ang = V.rotational()
        for got, want in ((s.position[i], X.translation()), (s.orientation[i], [q.w(), q.x(), q.y(), q.z()]),
                          (s.angular_velocity[i], ang),
                          (s.linear_velocity[i], V.translational() + np.cross(ang, X.rotation().matrix() @ com[i]))):
            assert np.asarray(got).tobytes() == np.asarray(want, dtype=np.float64).tobytes()

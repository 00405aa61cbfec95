"""A backend refuses only what it cannot honour: by the value a scene gives a field, and only
where what the field governs exists (x3d_core/semantics/analysis.py, run_uses; backends/base.py, judged).
Each class has a scene the backend now runs and a counter-scene whose refusal stays, naming
field and value."""

from __future__ import annotations

import numpy as np
import pytest

from backends import base
from x3drbp import main as cli_main
from conformance.results import UNSUPPORTED, Expected
from engine_run import G, shape
from reports.expectations_table import markdown
from x3d_core.encodings.load import load
from x3d_core.model.schema import node_type
from x3d_core.semantics.analysis import Use, run_features, run_uses
from x3d_core.semantics.world import worlds
from x3d_core.traces.trace import read_trace

CFM = "RigidBodyCollection.constantForceMix"
MIN_BOUNCE = "CollisionCollection.minBounceSpeed"
FRICTION_2 = "CollisionCollection.appliedParameters.FRICTION_COEFFICIENT-2"

BALL = ("<RigidBody DEF='Ball' position='0 1 0'>"
        + shape("<Sphere radius='0.1'/>", "BallShape", container="geometry") + "</RigidBody>")
ANCHOR = "<RigidBody DEF='Anchor' fixed='true'/>"
HANG = ("<BallJoint anchorPoint='0 2 0'><RigidBody USE='Anchor' containerField='body1'/>"
        "<RigidBody USE='Ball' containerField='body2'/></BallJoint>")
PUSH = "<MotorJoint><RigidBody USE='Ball' containerField='body1'/></MotorJoint>"  # pushes, constrains nothing
BALL_SHAPE = "<CollidableShape USE='BallShape' containerField='collidables'/>"
FLOOR = shape("<Box size='4 0.2 4'/>", "Floor", "translation='0 -0.1 0'", container="collidables")
WALL = shape("<Box size='0.2 4 4'/>", "Wall", "translation='3 0 0'", container="collidables")
BLOCK = ("<RigidBody DEF='Block' position='0 0.5 0'>"
         + shape("<Box size='0.2 0.2 0.2'/>", "BlockShape", container="geometry") + "</RigidBody>")
BLOCK_SHAPE = "<CollidableShape USE='BlockShape' containerField='collidables'/>"
BALL_ON_BLOCK = ("<BallJoint anchorPoint='0 0.7 0'><RigidBody USE='Block' containerField='body1'/>"
                 "<RigidBody USE='Ball' containerField='body2'/></BallJoint>")


def collection(body: str, attributes: str = "", params: str = "", collidables: str = "") -> str:
    """A RigidBodyCollection of the bodies and joints in `body`, with a collider of
    `collidables` (its attributes `params`) where any are given."""
    collider = (f"<CollisionCollection containerField='collider' {params}>{collidables}</CollisionCollection>"
                if collidables else "")
    return f"<RigidBodyCollection gravity='0 -9.81 0' {attributes}>{body}{collider}</RigidBodyCollection>"


def scene_file(tmp_path, *collections: str) -> str:
    path = tmp_path / "s.x3d"
    path.write_text("<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Full' version='4.0'><Scene>\n"
                    + "\n".join(collections) + "\n</Scene></X3D>\n")
    assert not load(str(path)).errors
    return str(path)


def uses(tmp_path, *args: str) -> dict[str, list[str]]:
    """Each feature a run needs, with the values it is needed at (as a refusal writes them)."""
    out: dict[str, list[str]] = {}
    for u in run_uses(load(scene_file(tmp_path, collection(*args)))):
        out.setdefault(u.feature, []).append(str(u))
    return out


def run(tmp_path, capsys, backend: str, *args: str) -> tuple[int, str, dict[tuple[str, str], list[str]]]:
    """`x3drbp run` on the scene for 0.25 s: exit status, standard error, trace (node, field) -> values."""
    pytest.importorskip({"dart": "dartpy", "bullet": "pybullet"}.get(backend, backend))
    out = tmp_path / "t.csv"
    code = cli_main(["run", scene_file(tmp_path, collection(*args)), "--backend", backend, "--duration", "0.25",
                     "--trace", str(out)])
    trace: dict[tuple[str, str], list[str]] = {}
    for row in read_trace(str(out)) if out.exists() else []:
        trace.setdefault((row.node, row.field), []).append(row.value)
    return code, capsys.readouterr().err, trace


def fell_freely(trace: dict[tuple[str, str], list[str]]) -> bool:
    """Whether the trace's Ball fell from y = 1 under gravity alone for the run's 0.25 s."""
    y = float(trace[("Ball", "position")][-1].split()[1])
    return y == pytest.approx(1 - G * 0.25 ** 2 / 2, abs=0.01)


# -- what a field governs ------------------------------------------------------------------

@pytest.mark.parametrize("body, needed", [
    (BALL, False),  # a free body: no rows for a CFM to soften
    (BALL + PUSH, False),
    (BALL + ANCHOR + HANG, True)], ids=["free", "motor only", "joined"])
def test_joint_softness_counts_where_the_collection_has_a_joint(tmp_path, body, needed):
    found = uses(tmp_path, body, "constantForceMix='0.001' errorCorrection='0.5'")
    assert (CFM in found, "RigidBodyCollection.errorCorrection" in found) == (needed, needed)


def test_joint_softness_counts_where_the_collection_has_contacts(tmp_path):
    found = uses(tmp_path, BALL, "constantForceMix='0.001'", "", BALL_SHAPE + FLOOR)
    assert found[CFM] == [f"{CFM} = 0.001"]


@pytest.mark.parametrize("body, collidables", [
    (BALL, BALL_SHAPE),  # one collidable
    (BALL, FLOOR + WALL),  # two, both static
    (BALL.replace("<RigidBody DEF='Ball'", "<RigidBody DEF='Ball' fixed='true'"), BALL_SHAPE + FLOOR),
    (BALL.replace("<RigidBody DEF='Ball'", "<RigidBody DEF='Ball' enabled='false'"), BALL_SHAPE + FLOOR),
    (BALL + BLOCK + BALL_ON_BLOCK, BALL_SHAPE + BLOCK_SHAPE)],  # the only pair is joined: never tested
    ids=["one", "static pair", "fixed ball", "disabled ball", "joined pair"])
def test_contact_parameters_count_only_where_two_collidables_can_touch(tmp_path, body, collidables):
    params = ("minBounceSpeed='0.05' bounce='0.5' frictionCoefficients='0.2 0.6' "
              "appliedParameters='\"BOUNCE\" \"FRICTION_COEFFICIENT-2\" \"SLIP-1\"'")
    found = run_features(load(scene_file(tmp_path, collection(body, "contactSurfaceThickness='0.01'", params,
                                                                collidables))))
    assert "CollisionCollection" in found  # the collider is still built
    assert not [f for f in found if f.startswith(("CollisionCollection.", "RigidBodyCollection.contactSurface"))]


def test_contact_parameters_count_where_a_moving_body_meets_a_static_collidable(tmp_path):
    params = "minBounceSpeed='0.05' frictionCoefficients='0.2 0.6' appliedParameters='\"FRICTION_COEFFICIENT-2\"'"
    found = uses(tmp_path, BALL, "contactSurfaceThickness='0.01'", params, BALL_SHAPE + FLOOR)
    assert found[MIN_BOUNCE] == [f"{MIN_BOUNCE} = 0.05"]
    assert found[FRICTION_2] == [FRICTION_2]  # the flag is the value
    layer = "RigidBodyCollection.contactSurfaceThickness"
    assert found[layer] == [f"{layer} = 0.01"]


def test_one_feature_at_two_values_is_two_uses(tmp_path):
    second = ("<RigidBody DEF='Bob' position='0 1 0'/><RigidBody DEF='Pin' fixed='true'/><BallJoint>"
              "<RigidBody USE='Pin' containerField='body1'/><RigidBody USE='Bob' containerField='body2'/></BallJoint>")
    path = scene_file(tmp_path, collection(BALL + ANCHOR + HANG, "constantForceMix='0'"),
                      collection(second, "constantForceMix='0.001'"),
                      collection("<RigidBody DEF='Free'/>", "constantForceMix='0.5'"))
    # the third collection has no joint (its CFM softens nothing): it asks for nothing
    assert [str(u) for u in run_uses(load(path)) if u.feature == CFM] == [f"{CFM} = 0", f"{CFM} = 0.001"]


@pytest.mark.parametrize("low, high, stops", [(0.3, 0, False), (0, 0.3, True), (0.3, 0.3, True)],
                         ids=["min above max", "min below max", "equal"])
def test_a_slider_has_stops_only_where_min_is_not_above_max(tmp_path, low, high, stops):
    """37.4.13: "If minSeparation is greater than maxSeparation, the stops become ineffective as if the
    object has no stops at all": no stops to build (Joint.stops, the limits feature), nothing for a
    stop's bounce or correction to act on. The backends once swapped the two into stops."""
    slide = (f"<SliderJoint minSeparation='{low}' maxSeparation='{high}' stopBounce='0.5' "
             "stopErrorCorrection='0.2'><RigidBody USE='Ball' containerField='body1'/>"
             "<RigidBody USE='Anchor' containerField='body2'/></SliderJoint>")
    found = uses(tmp_path, BALL + ANCHOR + slide)
    needed = ("SliderJoint.limits", "SliderJoint.stopBounce", "SliderJoint.stopErrorCorrection")
    assert [f in found for f in needed] == [stops] * 3
    joint = worlds(load(scene_file(tmp_path, collection(BALL + ANCHOR + slide))))[0].joints[0]
    assert joint.stops == ((low, high) if stops else None)


# -- a value the engine holds anyway --------------------------------------------------------

def _cfm(value: float) -> Use:
    return Use(CFM, value, node_type("RigidBodyCollection").fields["constantForceMix"].type)


@pytest.mark.parametrize("name", ["bullet", "pymunk"])
def test_a_rigid_engine_honours_cfm_0_and_refuses_any_other(name):
    backend = base.load(name)
    assert base.judge(backend, _cfm(0.0)).support is base.Support.NATIVE
    assert base.judge(backend, _cfm(-0.0)).support is base.Support.NATIVE
    assert base.judge(backend, _cfm(1e-9)).support is base.Support.UNSUPPORTED


def test_a_declaration_without_native_at_holds_at_every_value():
    backend = base.load("dart")
    assert base.judge(backend, Use(MIN_BOUNCE, 0.0, node_type("CollisionCollection").fields["minBounceSpeed"].type)
                      ).support is base.Support.UNSUPPORTED
    assert base.judge(backend, Use(FRICTION_2)).support is base.Support.UNSUPPORTED


# -- the three classes, run -----------------------------------------------------------------

def test_dart_runs_the_second_friction_flag_with_equal_coefficients(tmp_path, capsys):
    params = "frictionCoefficients='0.4 0.4' appliedParameters='\"FRICTION_COEFFICIENT-2\"'"
    code, err, trace = run(tmp_path, capsys, "dart", BALL, "", params, BALL_SHAPE + FLOOR)
    assert code == 0, err
    assert fell_freely(trace)


def test_dart_refuses_the_second_friction_flag_with_two_coefficients(tmp_path, capsys):
    params = "frictionCoefficients='0.4 0.6' appliedParameters='\"FRICTION_COEFFICIENT-2\"'"
    code, err, trace = run(tmp_path, capsys, "dart", BALL, "", params, BALL_SHAPE + FLOOR)
    assert code == 3 and not trace
    assert f"unsupported by dart: {FRICTION_2}: dartpy binds one friction coefficient" in err


@pytest.mark.parametrize("body, cfm", [(BALL, "0.001"), (BALL, "0"), (BALL + ANCHOR + HANG, "0")],
                         ids=["no joints", "no joints, cfm 0", "joined, cfm 0"])
def test_bullet_runs_a_cfm_with_nothing_to_soften_or_its_own(tmp_path, capsys, body, cfm):
    code, err, trace = run(tmp_path, capsys, "bullet", body, f"constantForceMix='{cfm}'")
    assert code == 0, err
    assert CFM not in err  # not even noted: native, or no use
    if "Anchor" not in body:
        assert fell_freely(trace)
    else:  # hanging 1 m below its anchor, at rest
        assert np.allclose([float(x) for x in trace[("Ball", "position")][-1].split()], [0, 1, 0], atol=1e-6)


@pytest.mark.parametrize("body, collidables", [(BALL + ANCHOR + HANG, ""), (BALL, BALL_SHAPE + FLOOR)],
                         ids=["joined", "contacts"])
def test_bullet_refuses_another_cfm_where_it_acts_naming_the_value(tmp_path, capsys, body, collidables):
    code, err, trace = run(tmp_path, capsys, "bullet", body, "constantForceMix='0.001'", "", collidables)
    assert code == 3 and not trace
    assert f"unsupported by bullet: {CFM} = 0.001: pybullet's multibody constraint rows" in err


@pytest.mark.parametrize("body, collidables", [(BALL, BALL_SHAPE), (BALL + BLOCK + BALL_ON_BLOCK,
                                                                     BALL_SHAPE + BLOCK_SHAPE)],
                         ids=["one collidable", "joined pair"])
def test_dart_runs_a_min_bounce_speed_where_no_contact_can_occur(tmp_path, capsys, body, collidables):
    code, err, trace = run(tmp_path, capsys, "dart", body, "", "minBounceSpeed='0.05'", collidables)
    assert code == 0, err
    assert MIN_BOUNCE not in err
    assert fell_freely(trace)  # the ball, and the block it hangs from


def test_dart_refuses_a_min_bounce_speed_where_a_ball_meets_a_floor(tmp_path, capsys):
    code, err, trace = run(tmp_path, capsys, "dart", BALL, "", "minBounceSpeed='0.05'", BALL_SHAPE + FLOOR)
    assert code == 3 and not trace
    assert f"unsupported by dart: {MIN_BOUNCE} = 0.05: DART's bounce threshold" in err


def test_the_readme_matrix_names_a_refused_feature_without_its_value():
    pins = {"dart": {"c": Expected(UNSUPPORTED, reason=f"{MIN_BOUNCE} = 0.05: no; {FRICTION_2}: none")}}
    assert f"| c | unsupported ({MIN_BOUNCE}, {FRICTION_2}) |" in markdown(["c"], pins)

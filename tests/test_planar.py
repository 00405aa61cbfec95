"""x3d_core.planar: planar worlds and each reason a world is not."""

from __future__ import annotations

import pytest

from engine_run import scene_worlds
from x3d_core.planar import NotPlanar, analyse

BOX = "<CollidableShape DEF='{n}' {x}><Shape containerField='shape'><{g}/></Shape></CollidableShape>"


def world(tmp_path, bodies: str, extra: str = "", collidables: str = "", params: str = ""):
    collider = (f"<CollisionCollection containerField='collider' {params}>{collidables}</CollisionCollection>"
                if collidables else "")
    return scene_worlds(tmp_path, f"<RigidBodyCollection {extra}>{bodies}{collider}</RigidBodyCollection>")[0]


def reasons(w) -> list[str]:
    with pytest.raises(NotPlanar) as e:
        analyse(w)
    return e.value.reasons


def test_a_pendulum_on_a_floor_is_planar_with_its_sections(tmp_path):
    bodies = ("<RigidBody DEF='Bob' position='1 0 0.5' orientation='0 0 1 0.3' linearVelocity='1 2 0' "
              "angularVelocity='0 0 3'><CollidableShape DEF='BobS' containerField='geometry'>"
              "<Shape containerField='shape'><Sphere radius='0.1'/></Shape></CollidableShape></RigidBody>"
              "<SingleAxisHingeJoint axis='0 0 -1' anchorPoint='0 0 7'><RigidBody USE='Bob' containerField='body1'/>"
              "</SingleAxisHingeJoint>")
    floor = BOX.format(n="Floor", x="translation='0 -1 0.5'", g="Box size='4 0.2 1'")
    p = analyse(world(tmp_path, bodies, collidables="<CollidableShape USE='BobS'/>" + floor))
    assert p.z == 0.5
    bob, ground = p.sections
    assert bob.radius == 0.1 and bob.centre.tolist() == [1, 0]
    assert sorted(map(tuple, ground.vertices.round(12))) == [(-2, -1.1), (-2, -0.9), (2, -1.1), (2, -0.9)]


@pytest.mark.parametrize("fields,expected", [
    ("linearVelocity='0 0 1'", "RigidBody B linearVelocity (0 0 1) leaves the plane"),
    ("angularVelocity='0 1 0'", "RigidBody B angularVelocity (0 1 0) is not along z"),
    ("orientation='1 0 0 0.5'", "RigidBody B orientation (1 0 0 0.5) does not turn about z"),
    ("forces='0 0 2'", "RigidBody B forces (0 0 2) leave the plane"),
    ("torques='1 0 0'", "RigidBody B torques (1 0 0) are not along z"),
    ("inertia='1 0 0.1 0 1 0 0.1 0 1'", "RigidBody B inertia (1 0 0.1 0 1 0 0.1 0 1) couples spin about z"),
    ("centerOfMass='0 0 0.2'", None),  # the first body sets the plane: no reason alone
])
def test_each_body_field_that_leaves_the_plane_is_named(tmp_path, fields, expected):
    w = world(tmp_path, f"<RigidBody DEF='B' {fields}/>")
    if expected is None:
        assert analyse(w).z == pytest.approx(0.2)
    else:
        assert reasons(w)[0].startswith(expected)


def test_bodies_in_two_planes_and_gravity_out_of_plane(tmp_path):
    r = reasons(world(tmp_path, "<RigidBody DEF='A'/><RigidBody DEF='B' position='0 0 1'/>", "gravity='0 -9.8 1'"))
    assert r[0].startswith("RigidBodyCollection") and "gravity (0 -9.8 1)" in r[0]
    assert r[1] == "RigidBody B centre of mass (0 0 1) is off the plane z = 0"


@pytest.mark.parametrize("joint,expected", [
    ("<SingleAxisHingeJoint DEF='J' axis='1 0 0'>", "SingleAxisHingeJoint J axis (1 0 0) is not along z"),
    ("<SliderJoint DEF='J' axis='0 0 1'>", "SliderJoint J axis (0 0 1) leaves the plane"),
    ("<BallJoint DEF='J' anchorPoint='0 0 1'>", "BallJoint J anchorPoint (0 0 1) is off the plane z = 0"),
    ("<UniversalJoint DEF='J' axis1='1 0 0' axis2='0 1 0'>", "UniversalJoint J axis1 (1 0 0), axis2 (0 1 0)"),
    ("<MotorJoint DEF='J' enabledAxes='1' motor1Axis='1 0 0' axis1Torque='2'>", "MotorJoint J motor1Axis (1 0 0)"),
])
def test_each_joint_out_of_plane_is_named(tmp_path, joint, expected):
    tag = joint.split()[0][1:]
    r = reasons(world(tmp_path, f"<RigidBody DEF='B'/>{joint}<RigidBody USE='B' containerField='body1'/></{tag}>"))
    assert r[0].startswith(expected)


def test_planar_joints_pass(tmp_path):
    w = world(tmp_path, "<RigidBody DEF='B'/><SliderJoint axis='1 1 0'><RigidBody USE='B' containerField='body1'/>"
                        "</SliderJoint><UniversalJoint axis1='0 0 1' axis2='1 0 0'>"
                        "<RigidBody USE='B' containerField='body1'/></UniversalJoint>")
    assert analyse(w).z == 0


@pytest.mark.parametrize("geometry,extra,expected", [
    ("Sphere radius='1'", "translation='0 0 0.5'", "(sphere) is not centred on the plane z = 0 (0.5 off)"),
    ("Box size='1 1 1'", "rotation='1 1 0 0.5'", "(box) has no axis along z"),
    ("Box size='1 1 0.5'", "translation='0 -2 0.3'", "(box) is not centred on the plane z = 0 (0.3 off) nor reaches"),
    ("Cylinder radius='1' height='1'", "rotation='1 1 0 0.5'", "(cylinder) axis is neither along z"),
    ("Cone bottomRadius='1' height='1'", "rotation='1 0 0 1.5707963267948966'", "(cone) axis is neither along z"),
    ("IndexedFaceSet coordIndex='0 1 2'><Coordinate point='0 0 0 1 0 0 0 1 0'/></IndexedFaceSet",
     "", "(mesh) has no section known exact"),
])
def test_each_shape_without_an_exact_section_is_named(tmp_path, geometry, extra, expected):
    tag = geometry.split()[0]
    g = f"<{geometry}/>" if "><" not in geometry else f"<{geometry}>"
    static = f"<CollidableShape DEF='S' {extra}><Shape containerField='shape'>{g}</Shape></CollidableShape>"
    r = reasons(world(tmp_path, "<RigidBody DEF='B'/>", collidables=static))
    assert r[0].startswith(f"CollidableShape S {expected}"), (tag, r)


def test_static_prism_through_the_plane_and_sideways_cylinder_pass(tmp_path):
    floor = BOX.format(n="F", x="translation='0 -2 0.3'", g="Box size='4 1 4'")
    wheel = BOX.format(n="W", x="rotation='0 0 1 1.5707963267948966'", g="Cylinder radius='1' height='0.5'")
    p = analyse(world(tmp_path, "<RigidBody DEF='B'/>", collidables=floor + wheel))
    assert len(p.sections[1].vertices) == 4


def test_second_surface_speed_drives_out_of_plane(tmp_path):
    floor = BOX.format(n="F", x="", g="Box size='4 1 4'")
    r = reasons(world(tmp_path, "<RigidBody DEF='B'/>",
                      collidables=floor,
                      params="surfaceSpeed='0 1' appliedParameters='\"SPEED-2\"'"))
    assert r[0].startswith("CollisionCollection surfaceSpeed (0 1)")

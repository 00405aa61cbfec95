"""x3d_core.semantics.planar: planar worlds and each reason a world is not."""

from __future__ import annotations

import numpy as np
import pytest

from engine_run import scene_worlds
from x3d_core.semantics.planar import NotPlanar, analyse

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
    assert p.planes.tolist() == [0.5] and p.contact_z[0] == 0.5 and not p.apart
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
    ("centerOfMass='0 0 0.2'", None),  # the centre of mass sets the body's plane
])
def test_each_body_field_that_leaves_the_plane_is_named(tmp_path, fields, expected):
    w = world(tmp_path, f"<RigidBody DEF='B' {fields}/>")
    if expected is None:
        assert analyse(w).planes.tolist() == pytest.approx([0.2])
    else:
        assert reasons(w)[0].startswith(expected)


def test_gravity_out_of_plane(tmp_path):
    r = reasons(world(tmp_path, "<RigidBody DEF='A'/>", "gravity='0 -9.8 1'"))
    assert r[0].startswith("RigidBodyCollection") and "gravity (0 -9.8 1)" in r[0]


def ball(name: str, z: float, radius: float = 0.1) -> str:
    return (f"<RigidBody DEF='{name}' position='0 1 {z}'><CollidableShape DEF='{name}S' containerField='geometry'>"
            f"<Shape containerField='shape'><Sphere radius='{radius}'/></Shape></CollidableShape></RigidBody>")


def test_bodies_in_parallel_planes_are_kept_apart_where_they_never_meet(tmp_path):
    floor = BOX.format(n="Floor", x="translation='0 -0.5 0.5'", g="Box size='4 1 2'")  # reaches z -0.5 .. 1.5
    post = BOX.format(n="Post", x="translation='2 0 1'", g="Sphere radius='0.2'")  # clear of plane 0, on plane 1
    p = analyse(world(tmp_path, ball("A", 0) + ball("B", 0.25) + ball("C", 1),
                      collidables="<CollidableShape USE='AS'/><CollidableShape USE='BS'/><CollidableShape USE='CS'/>"
                                  + floor + post))
    assert p.planes.tolist() == [0, 0.25, 1]
    assert p.contact_z[:3].tolist() == [0, 0.25, 1] and np.isnan(p.contact_z[3:]).all()
    # A and B (0.25 apart, radii 0.1) never meet, nor A/B and C; the post only reaches C's plane
    assert p.apart == {(0, 1), (0, 2), (1, 2), (0, 4), (1, 4)}
    assert p.sections[4].radius == 0.2


def test_shapes_that_could_touch_across_planes_are_named(tmp_path):
    r = reasons(world(tmp_path, ball("A", 0) + ball("B", 0.15),
                      collidables="<CollidableShape USE='AS'/><CollidableShape USE='BS'/>"))
    assert r == ["CollidableShape AS (plane z = 0) and BS (plane z = 0.15) can touch out of the plane"]
    post = BOX.format(n="Post", x="translation='2 0 0.25'", g="Sphere radius='0.2'")  # reaches into plane 0
    assert reasons(world(tmp_path, ball("A", 0), collidables="<CollidableShape USE='AS'/>" + post))[0].startswith(
        "CollidableShape Post (sphere) is not centred on the plane z = 0")
    ledge = BOX.format(n="Ledge", x="translation='0 -2 0.3'", g="Box size='1 1 0.5'")  # z 0.05 .. 0.55
    assert reasons(world(tmp_path, ball("A", 0), collidables="<CollidableShape USE='AS'/>" + ledge)) == [
        "CollidableShape Ledge (box) is not centred on the plane z = 0 (0.3 off) nor reaches 0.1 past it on both sides"]


def test_a_ball_joint_must_sit_on_both_bodies_planes(tmp_path):
    joint = ("<BallJoint DEF='J' anchorPoint='0 1 0'><RigidBody USE='A' containerField='body1'/>"
             "<RigidBody USE='B' containerField='body2'/></BallJoint>")
    assert reasons(world(tmp_path, ball("A", 0) + ball("B", 1) + joint)) == [
        "BallJoint J anchorPoint (0 1 0) is off the plane z = 1"]
    hinge = joint.replace("BallJoint", "SingleAxisHingeJoint").replace("anchorPoint", "axis='0 0 1' anchorPoint")
    assert analyse(world(tmp_path, ball("A", 0) + ball("B", 1) + hinge)).planes.tolist() == [0, 1]


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
    assert analyse(w).planes.tolist() == [0]


@pytest.mark.parametrize("geometry,extra,expected", [
    ("Sphere radius='1'", "translation='0 0 0.5'", "(sphere) is not centred on the plane z = 0 (0.5 off)"),
    ("Box size='1 1 1'", "rotation='1 1 0 0.5'", "(box) has no axis along z"),
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

"""What only the pybullet backend does with collisions: shapes built as pybullet's (cylinders turned
from its z axis, cones and moving meshes as hulls with their margin, heightfields, offsets and
several shapes on massless fixed links, fixed bodies as static multibodies), which pairs it filters,
the collection's contact parameters as the per-body values pybullet combines (product for friction
and restitution, springs in series), and the declared approximations the cases measure as fails
(contactSlop, anisotropic friction). The shared contact physics (bounce apex and threshold,
incline, filtering, sensor contacts) is in the conformance cases (conformance/cases/).

Tolerances come from what the engine does, measured with pybullet 3.2.7 (see backends/bullet.py):
semi-implicit Euler at dt = 1/240, contacts found at the start of a step (so an impact has
penetrated up to v dt), restitution applied to the approach speed after the step's gravity."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("pybullet")

from backends.bullet import BACKEND  # noqa: E402
from engine_run import DT, G, scene_worlds  # noqa: E402
from x3d_core.semantics import rotation as R  # noqa: E402
from x3d_core.semantics.collision import ContactPoints  # noqa: E402

FLOOR = ("<Group><CollidableShape DEF='Floor' translation='0 -0.5 0'><Shape containerField='shape'>"
         "<Box size='20 1 20'/></Shape></CollidableShape></Group>")


def build(tmp_path, body: str, dt: float = DT):
    """The scene's first world and its pybullet simulation."""
    world = scene_worlds(tmp_path, body)[0]
    return world, BACKEND.build(world, dt)


def shape(name: str, geometry: str, fields: str = "", container: str = "geometry") -> str:
    return (f"<CollidableShape DEF='{name}' containerField='{container}' {fields}><Shape containerField='shape'>"
            f"{geometry}</Shape></CollidableShape>")


def ball_on_floor(collection: str = "", body: str = "", radius: float = 0.2, y: float | None = None,
                  world: str = "") -> str:
    y = radius if y is None else y
    ball = shape("BallShape", f"<Sphere radius='{radius}'/>")
    return (FLOOR + f"<RigidBodyCollection gravity='0 -9.81 0' {world}>"
            f"<RigidBody DEF='Ball' position='0.3 {y} -0.1' {body}>{ball}"
            f"</RigidBody><CollisionCollection {collection}><CollidableShape USE='BallShape'/>"
            "<CollidableShape USE='Floor'/></CollisionCollection></RigidBodyCollection>")


def names(world, contacts: ContactPoints) -> list[tuple[str, str]]:
    g = world.collisions.geometries
    return [(g[a].name, g[b].name) for a, b in zip(contacts.geometry1, contacts.geometry2)]


# -- where shapes are, and what contact points say -------------------------------------------------

def test_soft_contact_sinks_by_weight_over_odes_spring(tmp_path):
    # ERROR_REDUCTION and CONSTANT_FORCE: ODE's spring k = ERP/(h CFM); per body pybullet puts two
    # springs in series and adds dampers, and the backend gives each body 2k and c/2
    erp, cfm, mass = 0.5, 0.01, 2.0
    world, sim = build(tmp_path, ball_on_floor(
        "appliedParameters='\"BOUNCE\" \"ERROR_REDUCTION\" \"CONSTANT_FORCE\"' "
        f"softnessErrorCorrection='{erp}' softnessConstantForceMix='{cfm}'", f"mass='{mass}'"))
    sim.step(720)
    sink = mass * G / (erp / (DT * cfm))
    assert sim.contacts().depth == pytest.approx([sink], rel=1e-6)
    assert sim.state().position[0, 1] == pytest.approx(0.2 - sink, rel=1e-6)


def test_surface_thickness_is_the_resting_penetration(tmp_path):
    world, sim = build(tmp_path, ball_on_floor(world="contactSurfaceThickness='0.004'", y=0.3))
    sim.step(480)
    assert sim.contacts().depth == pytest.approx([0.004], abs=1e-6)
    assert sim.state().position[0, 1] == pytest.approx(0.2 - 0.004, abs=1e-6)


@pytest.mark.parametrize("geometry, turn, height", [
    ("<Box size='0.2 0.3 0.4'/>", "0 0 1 0", 0.15),
    ("<Cylinder radius='0.1' height='0.4'/>", "0 0 1 0", 0.2),  # pybullet's z axis turned to X3D's y
    ("<Cylinder radius='0.1' height='0.4'/>", "0 0 1 1.5707963267948966", 0.1),  # on its side
    ("<Cone bottomRadius='0.2' height='0.3'/>", "0 0 1 0", 0.15),  # on its base: hull, 0.1 mm margin
    ("<IndexedFaceSet coordIndex='0 1 2 3 -1 4 5 6 7 -1'><Coordinate point='-0.1 -0.1 -0.1 0.1 -0.1 -0.1 "
     "0.1 -0.1 0.1 -0.1 -0.1 0.1 -0.1 0.1 -0.1 0.1 0.1 -0.1 0.1 0.1 0.1 -0.1 0.1 0.1'/></IndexedFaceSet>",
     "0 0 1 0", 0.1),  # a moving mesh collides as its hull (a cube from two faces), 0.1 mm margin
])
def test_shapes_rest_at_their_height(tmp_path, geometry, turn, height):
    world, sim = build(tmp_path, FLOOR + "<RigidBodyCollection gravity='0 -9.81 0' errorCorrection='0.2'>"
                       f"<RigidBody DEF='B' position='0 {height + 0.001} 0' orientation='{turn}' "
                       "inertia='0.01 0 0 0 0.01 0 0 0 0.01'>" + shape("S", geometry) + "</RigidBody>"
                       "<CollisionCollection><CollidableShape USE='S'/><CollidableShape USE='Floor'/>"
                       "</CollisionCollection></RigidBodyCollection>")
    sim.step(360)
    hull = "Cone" in geometry or "IndexedFaceSet" in geometry
    assert sim.state().position[0, 1] == pytest.approx(height, abs=2e-4 if hull else 1e-5)
    c = sim.contacts()
    assert len(c.depth) >= 1 and np.allclose(c.normal, [0, -1, 0], atol=1e-6)


def test_static_elevation_grid_and_mesh_are_where_the_scene_puts_them(tmp_path):
    # a tilted plane as an ElevationGrid (heights 0.1 i + 0.05 j on a 0.5 x 0.4 grid), turned and moved;
    # a ball dropped onto it along its normal touches at the point under it, with the plane's normal
    nx, nz = 5, 4
    heights = " ".join(str(0.1 * i + 0.05 * j) for j in range(nz) for i in range(nx))
    turn = np.array([0, 1, 0, 0.7])
    q = R.from_axis_angle(turn)
    normal = R.rotate(q, np.array([-0.2, 1, -0.125]) / np.linalg.norm([-0.2, 1, -0.125]))
    grid = f"<ElevationGrid xDimension='{nx}' zDimension='{nz}' xSpacing='0.5' zSpacing='0.4' height='{heights}'/>"
    mesh = ("<IndexedFaceSet coordIndex='0 3 2 1 -1'><Coordinate point='0 0 0 2 0.4 0 2 0.55 1.2 0 0.15 1.2'/>"
            "</IndexedFaceSet>")  # the same plane as two triangles
    for geometry in (grid, mesh):
        local = np.array([1.6, 0.2 * 1.6 + 0.125 * 0.9, 0.9])
        touch = np.array([1, 0.5, -0.3]) + R.rotate(q, local)
        start = touch + 0.101 * normal
        v = -0.2 * normal
        world, sim = build(tmp_path, "<Group>" + shape("Ground", geometry, "translation='1 0.5 -0.3' rotation='"
                                                        + " ".join(map(str, turn)) + "'", "children")
                           + "</Group><RigidBodyCollection gravity='0 0 0'><RigidBody DEF='Ball' position='"
                           + " ".join(map(str, start)) + "' linearVelocity='" + " ".join(map(str, v)) + "'>"
                           + shape("BallShape", "<Sphere radius='0.1'/>") + "</RigidBody><CollisionCollection>"
                           "<CollidableShape USE='BallShape'/><CollidableShape USE='Ground'/></CollisionCollection>"
                           "</RigidBodyCollection>")
        sim.step(3)  # the last step's contacts are found where two steps put the ball: 0.67 mm in
        c = sim.contacts()
        assert names(world, c) == [("BallShape", "Ground")]
        assert c.normal[0] == pytest.approx(-normal, abs=1e-6)
        assert c.depth[0] == pytest.approx(2 * 0.2 * DT - 0.001, abs=1e-6)
        # the contact position is midway between the two bodies' points
        assert c.position[0] == pytest.approx(touch - c.depth[0] / 2 * normal, abs=1e-4)


def test_collidable_offset_and_several_collidables_on_one_body(tmp_path):
    # a dumbbell turned a quarter about y: two balls at x = -+0.5 below offsets in the body frame (so
    # z = +-0.5 in the world), and a bar between them that touches nothing; each contact point
    # names the ball it belongs to (pybullet: each further shape rides on a massless fixed link)
    body = ("<RigidBody DEF='Bell' position='0 0.2 0' orientation='0 1 0 1.5707963267948966' "
            "inertia='0.1 0 0 0 0.1 0 0 0 0.1'>"
            "<CollidableOffset DEF='LeftOffset' containerField='geometry'>"
            + shape("Left", "<Sphere radius='0.2'/>", "translation='-0.5 0 0'", "collidable") + "</CollidableOffset>"
            "<CollidableOffset DEF='RightOffset' containerField='geometry'>"
            + shape("Right", "<Sphere radius='0.2'/>", "translation='0.5 0 0'", "collidable") + "</CollidableOffset>"
            + shape("Bar", "<Box size='1 0.1 0.1'/>") + "</RigidBody>")
    world, sim = build(tmp_path, FLOOR + "<RigidBodyCollection gravity='0 -9.81 0'>" + body
                       + "<CollisionCollection><CollidableOffset USE='LeftOffset'/>"
                       "<CollidableOffset USE='RightOffset'/>"
                       "<CollidableShape USE='Bar'/><CollidableShape USE='Floor'/></CollisionCollection>"
                       "</RigidBodyCollection>")
    sim.step(240)
    c = sim.contacts()
    found = dict(zip((a for a, _ in names(world, c)), c.position))
    assert sorted(found) == ["Left", "Right"] and all(b == "Floor" for _, b in names(world, c))
    assert found["Left"] == pytest.approx([0, 0, 0.5], abs=1e-5)  # body x = -0.5 is world z = +0.5
    assert found["Right"] == pytest.approx([0, 0, -0.5], abs=1e-5)
    s = sim.state()
    assert s.position[0] == pytest.approx([0, 0.2, 0], abs=1e-5)
    assert s.linear_velocity[0] == pytest.approx([0, 0, 0], abs=1e-5)


def test_fixed_body_shapes_are_static_where_the_body_is(tmp_path):
    world, sim = build(tmp_path, "<RigidBodyCollection gravity='0 -9.81 0'>"
                       "<RigidBody DEF='Table' fixed='true' position='2 1 0' orientation='0 1 0 0.3'>"
                       + shape("Top", "<Box size='1 0.2 1'/>", "") + "</RigidBody>"
                       "<RigidBody DEF='Ball' position='2 1.3 0'>" + shape("BallShape", "<Sphere radius='0.2'/>")
                       + "</RigidBody><CollisionCollection><CollidableShape USE='Top'/>"
                       "<CollidableShape USE='BallShape'/>"
                       "</CollisionCollection></RigidBodyCollection>")
    sim.step(240)
    assert sim.state().position[1] == pytest.approx([2, 1.3, 0], abs=1e-5)
    assert names(world, sim.contacts()) == [("Top", "BallShape")]
    assert sim.contacts().normal[0] == pytest.approx([0, 1, 0], abs=1e-9)  # from the table up to the ball


# -- what collides with what -----------------------------------------------------------------------

def test_joined_bodies_never_collide_but_others_in_one_tree_do(tmp_path):
    # a chain A - B - C hanging from nothing, in zero gravity: A and B overlap and are joined, so never
    # touch; C overlaps A but is joined only to B, so A and C touch and push apart (pybullet: links of
    # one multibody, self collision on, the joined pair filtered)
    balls = "".join(f"<RigidBody DEF='{n}' position='{x} 0 0'>" + shape(f"{n}Shape", "<Sphere radius='0.3'/>")
                    + "</RigidBody>" for n, x in (("A", 0.0), ("B", 0.5), ("C", 0.4)))
    joints = ("<BallJoint anchorPoint='0.25 0 0'><RigidBody USE='A' containerField='body1'/>"
              "<RigidBody USE='B' containerField='body2'/></BallJoint>"
              "<BallJoint anchorPoint='0.45 0 0'><RigidBody USE='B' containerField='body1'/>"
              "<RigidBody USE='C' containerField='body2'/></BallJoint>")
    collider = "".join(f"<CollidableShape USE='{n}Shape'/>" for n in "ABC")
    world, sim = build(tmp_path, f"<RigidBodyCollection gravity='0 0 0'>{balls}{joints}"
                       f"<CollisionCollection>{collider}</CollisionCollection></RigidBodyCollection>")
    sim.step(1)
    assert sorted(set(names(world, sim.contacts()))) == [("AShape", "CShape")]


def test_a_further_shape_of_a_body_hinged_to_the_world_meets_static_shapes(tmp_path):
    # pybullet flags a link static where every joint between it and link 0 is fixed, never testing
    # link 0's own (URDF2Bullet): the ball in an offset of a pendulum hinged to the world rode, static,
    # on a fixed link of link 0 and went through a static wall (static pairs never touch) until its
    # rod met it. The pendulum (a 0.5 m rod, the ball at its end, 1 kg, I = 0.01 kg m^2 about its
    # middle) falls from horizontal onto a wall whose face stops the ball 0.1 rad before the bottom,
    # at 4 m/s: the ball's centre may pass where it touches by one step's approach at most, and the
    # wall turns it back (bounce 0) with what ERP's push out of that penetration gives, erp d / h <=
    # erp v (measured: 0.71 v)
    rod = shape("Rod", "<Cylinder radius='0.01' height='0.5'/>")
    ball = shape("Ball", "<Sphere radius='0.1'/>", "translation='0 -0.25 0'", "collidable")
    wall = shape("Wall", "<Box size='0.4 0.4 0.4'/>", "translation='0.25 0.5 0'", "children")
    world, sim = build(tmp_path, f"<Group>{wall}</Group><RigidBodyCollection>"
                       "<RigidBody DEF='Arm' position='-0.25 1 0' orientation='0 0 -1 1.5707963267948966' "
                       f"inertia='0.01 0 0 0 0.01 0 0 0 0.01'>{rod}<CollidableOffset DEF='Offset' "
                       f"containerField='geometry'>{ball}</CollidableOffset></RigidBody>"
                       "<SingleAxisHingeJoint anchorPoint='0 1 0' axis='0 0 1'><RigidBody USE='Arm' "
                       "containerField='body2'/></SingleAxisHingeJoint><CollisionCollection>"
                       "<CollidableShape USE='Rod'/><CollidableOffset USE='Offset'/><CollidableShape USE='Wall'/>"
                       "</CollisionCollection></RigidBodyCollection>")
    rate = np.sqrt(2 * 9.8 * 0.25 / (0.01 + 0.25 ** 2))  # at the bottom: m g d = I w^2 / 2 about the hinge
    furthest, back = -np.inf, 0.0
    for _ in range(120):  # 0.5 s: the swing's quarter takes 0.3 s
        sim.step()
        s = sim.state()
        furthest = max(furthest, (s.position[0] + R.rotate(s.orientation[0], np.array([0.0, -0.25, 0.0])))[0])
        back = min(back, s.angular_velocity[0, 2])
    assert -0.05 - 1e-3 < furthest <= -0.05 + 0.5 * rate * DT
    assert -0.8 * rate <= back < 0


# -- contact parameters ----------------------------------------------------------------------------

@pytest.mark.parametrize("mu1, mu2", [(0.2, 0.6), (0.6, 0.2), (0.0, 0.4)])
def test_second_friction_coefficient_on_level_ground(tmp_path, mu1, mu2):
    # ODE's directions for an upward normal are -x and +z; the static floor's anisotropic friction
    # scales the second: a block sliding along x slows at mu1 g, along z at mu2 g (measured within 1%)
    for v, mu in (("3 0 0", mu1), ("0 0 3", mu2)):
        world, sim = build(tmp_path, FLOOR + "<RigidBodyCollection gravity='0 -9.81 0'>"
                           f"<RigidBody DEF='Block' position='0 0.05 0' linearVelocity='{v}' "
                           "inertia='0.014 0 0 0 0.027 0 0 0 0.014'>" + shape("BlockShape", "<Box size='0.4 0.1 0.4'/>")
                           + f"</RigidBody><CollisionCollection frictionCoefficients='{mu1} {mu2}' "
                           "appliedParameters='\"BOUNCE\" \"FRICTION_COEFFICIENT-2\"'>"
                           "<CollidableShape USE='BlockShape'/>"
                           "<CollidableShape USE='Floor'/></CollisionCollection></RigidBodyCollection>")
        sim.step(72)  # 0.3 s: still sliding
        speed = np.linalg.norm(sim.state().linear_velocity[0])
        assert 3 - speed == pytest.approx(mu * G * 0.3, abs=0.02 * G * 0.3 + 1e-3)


def test_bounce_rebounds_at_e_times_the_approach_speed(tmp_path):
    # restitution sqrt(e) on both bodies (pybullet multiplies). Bullet applies e to the approach speed
    # after the step's gravity: the rebound is e (v + g dt), v the speed before the contact step, exactly
    for e in (0.2, 0.5, 0.8):
        world, sim = build(tmp_path, ball_on_floor(f"bounce='{e}'", y=1.2))
        before = 0.0
        for _ in range(240):
            sim.step()
            v = sim.state().linear_velocity[0, 1]
            if v > 0:
                assert v == pytest.approx(e * (-before + G * DT), rel=1e-12)
                break
            before = v
        else:
            pytest.fail("no rebound")


@pytest.mark.parametrize("dt, accurate", [(1 / 32000, False), (1 / 8000, True)])
def test_bounce_holds_at_fine_steps(tmp_path, dt, accurate):
    """At a step short enough that a falling ball comes within the contact processing threshold
    before it touches, pybullet took the contact as a speculative one and stopped the ball at the
    surface: at dt 1/32000 an e = 0.8 rebound left at 0.5 of the approach speed. The rebound is
    still e (v + g h) with h the internal step (preferAccuracy: 4 substeps a step)."""
    e = 0.8
    world, sim = build(tmp_path, ball_on_floor(f"bounce='{e}' minBounceSpeed='0.1'", y=0.5,
                                               world=f"preferAccuracy='{str(accurate).lower()}'"), dt)
    before = 0.0
    for _ in range(int(0.5 / dt)):
        sim.step()
        v = sim.state().linear_velocity[0, 1]
        if v > 0:
            # the internal substeps of the contact step are not read: the rebound is e times the
            # approach at most one step's gravity apart
            assert v == pytest.approx(e * -before, abs=e * G * dt + 1e-9)
            break
        before = v
    else:
        pytest.fail("no rebound")


def test_no_collider_no_contacts(tmp_path):
    world, sim = build(tmp_path, "<RigidBodyCollection><RigidBody DEF='B'>"
                       + shape("S", "<Sphere/>") + "</RigidBody></RigidBodyCollection>")
    assert world.collisions is None
    sim.step(2)
    assert len(sim.contacts().depth) == 0

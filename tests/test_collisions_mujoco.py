"""What only the MuJoCo backend does with collisions: geometry built in its model (offsets, a
cylinder's y axis, cones, meshes, height fields, bboxSize), the resting sink of its soft contact,
the surface layer as margin and gap, which pairs collide (explicit pairs and the contype
fallback), friction where X3D's default differs from MuJoCo's, and the bounds its declared
approximations keep where the cases measure a fail (conveyor, restitution). The shared contact
physics (incline, filtering, sensor contacts, resting depth) is in the conformance cases
(conformance/cases/)."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("mujoco")

import backends.mujoco as mj  # noqa: E402
from backends.mujoco import BACKEND  # noqa: E402
from engine_run import DT, G, scene_worlds  # noqa: E402
from x3d_core.semantics.collision import friction_directions  # noqa: E402

FLOOR = "<CollidableShape DEF='Floor' translation='0 -0.5 0'><Shape><Box size='20 1 20'/></Shape></CollidableShape>"


def world(tmp_path, body: str):
    return scene_worlds(tmp_path, body)[0]


def body(name: str, position: str, shape: str, extra: str = "") -> str:
    return (f"<RigidBody DEF='{name}' position='{position}' {extra}><CollidableShape DEF='{name}S' "
            f"containerField='geometry'><Shape>{shape}</Shape></CollidableShape></RigidBody>")


def collection(bodies: str, collidables: str, collider: str = "", gravity: str = "0 -9.81 0") -> str:
    return (f"<RigidBodyCollection gravity='{gravity}'>{bodies}<CollisionCollection containerField='collider' "
            f"{collider}>{collidables}</CollisionCollection></RigidBodyCollection>")


def uses(*names: str) -> str:
    return "".join(f"<CollidableShape USE='{n}'/>" for n in names)


def build(tmp_path, text: str, dt: float = DT):
    w = world(tmp_path, text)
    return w, BACKEND.build(w, dt)


def index(w, name: str) -> int:
    return [g.name for g in w.collisions.geometries].index(name)


# -- placement and contact points ----------------------------------------------
def test_resting_sink_is_the_impedance_share_of_gravity(tmp_path):
    _, sim = build(tmp_path, collection(body("Ball", "0 0.3 0", "<Sphere radius='0.1'/>"), uses("BallS") + FLOOR))
    sim.step(round(1.5 / DT))
    # resting sink: the impedance d = 0.99 leaves (1-d)/d of g on the contact's spring
    # k = ERP/dt^2 (X3D's ERP 0.8 capped at 0.25): 0.01 * 9.81 * dt^2 / 0.25 = 7 micrometres
    assert sim.state().position[0, 1] == pytest.approx(0.1, abs=2e-5)
    c = sim.contacts()
    assert len(c.depth) == 1 and 0 < c.depth[0] < 2e-5


def test_no_collider_no_contacts_and_nothing_built(tmp_path):
    w, sim = build(tmp_path, "<RigidBodyCollection>" + body("B", "0 1 0", "<Sphere/>") + "</RigidBodyCollection>")
    assert w.collisions is None and sim.model.ngeom == 0
    sim.step(10)
    assert len(sim.contacts().depth) == 0


def test_collidable_offset_places_the_shape_off_the_body_origin(tmp_path):
    # the body sets the offset's own pose; the shape inside sits 0.5 m below the body's origin
    # (and centre of mass), so the origin rests at 0.5 + r
    ball = ("<RigidBody DEF='B' position='0 1 0'><CollidableOffset DEF='O' containerField='geometry'>"
            "<CollidableShape DEF='S' containerField='collidable' translation='0 -0.5 0'><Shape>"
            "<Sphere radius='0.1'/></Shape></CollidableShape></CollidableOffset></RigidBody>")
    w, sim = build(tmp_path, collection(ball, "<CollidableOffset USE='O'/>" + FLOOR))
    sim.step(round(1.5 / DT))
    assert sim.state().position[0] == pytest.approx([0, 0.6, 0], abs=1e-3)
    c = sim.contacts()
    assert len(c.depth) == 1 and c.position[0] == pytest.approx([0, 0, 0], abs=1e-3)


@pytest.mark.parametrize("rotation, height", [("0 0 1 0", 0.4), ("0 0 1 1.5707963267948966", 0.1)])
def test_cylinder_axis_is_y(tmp_path, rotation, height):
    # standing (axis y) it rests on its base at h/2; turned onto its side, on its radius
    text = collection(body("C", f"0 {height + 0.01} 0", "<Cylinder radius='0.1' height='0.8'/>",
                           f"orientation='{rotation}'"), uses("CS") + FLOOR)
    w, sim = build(tmp_path, text)
    sim.step(round(1.0 / DT))
    assert sim.state().position[0, 1] == pytest.approx(height, abs=1e-3)


def test_cone_stands_on_its_base(tmp_path):
    # centred between apex and base: the centre rests h/2 above the floor; the base is a
    # 64-gon, so four or more contacts on its rim (radius 0.2, 0.12 % short between corners)
    w, sim = build(tmp_path, collection(body("K", "0 0.31 0", "<Cone bottomRadius='0.2' height='0.6'/>"),
                                        uses("KS") + FLOOR))
    sim.step(round(1.0 / DT))
    assert sim.state().position[0, 1] == pytest.approx(0.3, abs=1e-3)
    c = sim.contacts()
    assert len(c.depth) >= 3
    assert np.hypot(c.position[:, 0], c.position[:, 2]) == pytest.approx(0.2, abs=1e-3)


def test_flat_triangle_mesh_floor_and_a_convex_mesh_body(tmp_path):
    # a flat TriangleSet (MuJoCo cannot hull a plane: it becomes a slab behind its faces) and a
    # cube given as an IndexedFaceSet on a moving body
    floor = ("<CollidableShape DEF='Ground'><Shape><TriangleSet><Coordinate point='-10 0 10 10 0 10 10 0 -10 "
             "-10 0 10 10 0 -10 -10 0 -10'/></TriangleSet></Shape></CollidableShape>")
    cube = ("<IndexedFaceSet coordIndex='0 1 2 3 -1 4 7 6 5 -1 0 4 5 1 -1 1 5 6 2 -1 2 6 7 3 -1 3 7 4 0 -1'>"
            "<Coordinate point='-0.1 -0.1 -0.1 0.1 -0.1 -0.1 0.1 -0.1 0.1 -0.1 -0.1 0.1 -0.1 0.1 -0.1 0.1 0.1 -0.1 "
            "0.1 0.1 0.1 -0.1 0.1 0.1'/></IndexedFaceSet>")
    text = collection(body("Ball", "0 0.5 0", "<Sphere radius='0.1'/>") + body("Cube", "1 0.5 0", cube),
                      uses("BallS", "CubeS") + floor)
    w, sim = build(tmp_path, text)
    sim.step(round(1.5 / DT))
    s = sim.state()
    assert s.position[:, 1] == pytest.approx([0.1, 0.1], abs=1e-3)
    c = sim.contacts()
    cube_contacts = (c.geometry1 == index(w, "CubeS")) | (c.geometry2 == index(w, "CubeS"))
    assert cube_contacts.sum() >= 4  # a face on the floor


def test_elevation_grid_is_a_height_field_in_x3d_axes(tmp_path):
    # a plane y = 0.1 x + 0.2 z - 1 over a 3 x 3 grid (spacing 1): without gravity, a ball put
    # 5 mm into it at (1.2, 0.7) touches it along the plane's normal
    heights = " ".join(f"{0.1 * i + 0.2 * j - 1:g}" for j in range(3) for i in range(3))
    grid = (f"<CollidableShape DEF='Grid'><Shape><ElevationGrid xDimension='3' zDimension='3' xSpacing='1' "
            f"zSpacing='1' height='{heights}'/></Shape></CollidableShape>")
    n = np.array([-0.1, 1.0, -0.2]) / np.linalg.norm([-0.1, 1.0, -0.2])
    surface = np.array([1.2, 0.1 * 1.2 + 0.2 * 0.7 - 1, 0.7])
    centre = surface + n * (0.1 - 0.005)
    text = collection(body("Ball", " ".join(f"{x:.12g}" for x in centre), "<Sphere radius='0.1'/>"),
                      uses("BallS") + grid, gravity="0 0 0")
    w, sim = build(tmp_path, text)
    sim.step(1)
    c = sim.contacts()
    assert len(c.depth) >= 1
    sign = 1 if c.geometry1[0] == index(w, "Grid") else -1  # from the grid into the ball, or back
    assert sign * c.normal[0] == pytest.approx(n, abs=1e-6)
    assert c.depth[0] == pytest.approx(0.005, abs=1e-4)


def test_bbox_size_collides_as_that_box_and_a_space_keeps_the_geometry(tmp_path):
    # a Shape with an explicit bboxSize collides as that box: four corner contacts on the floor
    # at x, z = +-r, where the sphere itself touches once, under its centre. A CollisionSpace
    # with useGeometry FALSE still tests the geometry (x3d_core reads the field as a hint)
    def ball(name, x, bbox=""):
        return (f"<RigidBody DEF='{name}' position='{x} 0.3 0'><CollidableShape DEF='{name}S' "
                f"containerField='geometry'><Shape {bbox}><Sphere radius='0.1'/></Shape></CollidableShape></RigidBody>")
    space = "<CollisionSpace useGeometry='false'><CollidableShape USE='BS'/></CollisionSpace>"
    bodies = ball("A", 0, "bboxSize='0.2 0.2 0.2'") + ball("B", 1)
    w, sim = build(tmp_path, collection(bodies, uses("AS") + space + FLOOR))
    sim.step(round(1.0 / DT))
    c = sim.contacts()
    boxed = (c.geometry1 == index(w, "AS")) | (c.geometry2 == index(w, "AS"))
    assert boxed.sum() == 4
    assert np.abs(c.position[boxed][:, [0, 2]]) == pytest.approx(np.full((4, 2), 0.1), abs=1e-6)
    assert (~boxed).sum() == 1 and c.position[~boxed][0] == pytest.approx([1, 0, 0], abs=1e-3)
    assert sim.state().position[:, 1] == pytest.approx([0.1, 0.1], abs=1e-3)


def test_surface_layer_does_not_hold_a_body_deeper_than_the_layer(tmp_path):
    # resting_penetration puts boxes at depth 0 and 1 cm (the layer); one put 2 cm into a 1 cm
    # layer is pushed back into it (where in it depends on how fast it comes out, in ODE too)
    text = collection(body("Deep", "0 0.08 0", "<Box size='0.2 0.2 0.2'/>"), uses("DeepS") + FLOOR).replace(
        "<RigidBodyCollection ", "<RigidBodyCollection contactSurfaceThickness='0.01' ")
    _, sim = build(tmp_path, text)
    sim.step(round(2.0 / DT))
    assert -1e-4 < 0.1 - sim.state().position[0, 1] < 0.0101


# -- filtering ---------------------------------------------------------------------
@pytest.mark.parametrize("cap", [mj.PAIR_CAP, 0])  # explicit pairs, and the contype/exclude fallback
def test_only_collider_geometry_collides_and_joined_bodies_never(tmp_path, monkeypatch, cap):
    monkeypatch.setattr(mj, "PAIR_CAP", cap)
    # In falls onto the floor; Out's shape is not in the collider and falls through it
    bodies = body("In", "0 0.3 0", "<Sphere radius='0.1'/>") + body("Out", "1 0.3 0", "<Sphere radius='0.1'/>")
    # two pairs of overlapping boxes without gravity: A-B, joined by a joint, stay put; C-D
    # are pushed apart (some 3 m/s: far from the rest)
    weightless = "useGlobalGravity='false'"
    boxes = "".join(body(n, f"{x} 5 0", "<Box size='0.4 0.4 0.4'/>", weightless)
                    for n, x in (("A", 3), ("B", 3.3), ("C", 20), ("D", 20.3)))
    joint = ("<BallJoint anchorPoint='3.15 5 0'><RigidBody USE='A' containerField='body1'/>"
             "<RigidBody USE='B' containerField='body2'/></BallJoint>")
    text = ("<RigidBodyCollection gravity='0 -9.81 0'>" + bodies + boxes + joint +
            "<CollisionCollection containerField='collider'>" + uses("InS", "AS", "BS", "CS", "DS") + FLOOR +
            "</CollisionCollection></RigidBodyCollection>")
    w, sim = build(tmp_path, text)
    assert sim.pair_mode == (cap > 0)
    sim.step(round(1.0 / DT))
    s = sim.state()
    assert s.position[0, 1] == pytest.approx(0.1, abs=1e-3)
    assert s.position[1, 1] < -3  # fell freely: 0.3 - g/2 = -4.6
    assert s.position[2:4, 0] == pytest.approx([3, 3.3], abs=1e-9)
    assert s.position[5, 0] - s.position[4, 0] > 0.399
    c = sim.contacts()
    names = {frozenset((w.collisions.geometries[a].name, w.collisions.geometries[b].name))
             for a, b in zip(c.geometry1, c.geometry2)}
    assert frozenset(("AS", "BS")) not in names and not any("OutS" in n for n in names)


# -- friction ----------------------------------------------------------------------
def test_default_friction_is_none(tmp_path):
    # frictionCoefficients 0 0 (X3D's default): a sliding box keeps its speed
    text = collection(body("B", "0 0.1001 0", "<Box size='0.2 0.2 0.2'/>", "linearVelocity='2 0 0'"),
                      uses("BS") + FLOOR)
    w, sim = build(tmp_path, text)
    sim.step(round(1.0 / DT))
    assert sim.state().linear_velocity[0, 0] == pytest.approx(2.0, abs=1e-6)


def test_surface_speed_carries_a_box_along_odes_first_friction_direction(tmp_path):
    # SPEED-1 on a horizontal floor: the box is carried at 1 m/s along ODE's first friction
    # direction of the upward normal (-x); friction makes it match the surface
    text = collection(body("B", "0 0.1001 0", "<Box size='0.2 0.2 0.2'/>"), uses("BS") + FLOOR,
                      "frictionCoefficients='0.5 0.5' surfaceSpeed='1 0' appliedParameters='\"SPEED-1\"'")
    w, sim = build(tmp_path, text)
    sim.step(round(1.0 / DT))
    t1, _ = friction_directions(np.array([0.0, 1.0, 0.0]))
    assert sim.state().linear_velocity[0] == pytest.approx(t1[0], abs=1e-3)


# -- bounce ------------------------------------------------------------------------
# MuJoCo has no restitution: the backend's spring-damper contact was measured (declared in
# backends/mujoco.py) for drops of 4.4 m/s at dt 1/240 at e 0.2: -0.089..+0.012, e 0.5:
# -0.049..+0.030, e 0.8: -0.016..+0.022 from rebound heights, over where in a step the ball
# lands. The tolerances take those bounds with a little room.
@pytest.mark.parametrize("e, low, high", [(0.5, 0.06, 0.04), (0.2, 0.10, 0.03), (0.8, 0.025, 0.03)])
def test_bounce_height_follows_restitution(tmp_path, e, low, high):
    h, r = 1.0, 0.1
    text = collection(body("B", f"0 {h + r} 0", f"<Sphere radius='{r}'/>"), uses("BS") + FLOOR,
                      f"bounce='{e}' minBounceSpeed='0'")
    w, sim = build(tmp_path, text)
    fall = math.sqrt(2 * h / G)
    ys, vs = [], []
    for _ in range(round((fall * (1 + 2 * e) + 0.2) / DT)):
        sim.step()
        s = sim.state()
        ys.append(s.position[0, 1])
        vs.append(s.linear_velocity[0, 1])
    up = int(np.argmax(np.array(vs) > 0))  # the rebound
    apex = max(ys[up:]) - r
    assert e - low < math.sqrt(apex / h) < e + high

"""What only the DART backend does with collisions: shapes built in its skeletons (offsets,
cylinders and cones, meshes as triangle soups with one contact per corner, elevation grids as
triangles, fixed bodies kept mobile), the normal's direction whichever order DART lists a pair in,
which pairs it filters, and the bounce it gives where the cases cannot run (minBounceSpeed is
unsupported: bounce_apex and newtons_cradle are refused). The shared contact physics (incline,
filtering, sensor contacts) is in the conformance cases (conformance/cases/).

Tolerances are argued from the step and from DART's fixed contact constants (see
backends/dart.py): a contact found at the start of a step stops the approach in that step, so a
body lands up to one step's travel v*dt deep and rises out at DART's fixed 1 mm/s (its contact ERP
0.01, capped); a body set down gently rests within a step's fall under gravity, g*dt^2."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("dartpy")

from backends import base  # noqa: E402
from backends.dart import BACKEND, _grid_triangles  # noqa: E402
from engine_run import DT, G, run_x3d, scene_worlds, shape, values  # noqa: E402


def simulate(tmp_path, body: str, *args, **kwargs):
    return run_x3d(tmp_path, body, *args, **{"backend": BACKEND, **kwargs})


def build(tmp_path, body: str, dt: float = DT):
    world = scene_worlds(tmp_path, body)[0]
    return world, BACKEND.build(world, dt)


FLOOR = shape("<Box size='10 1 10'/>", "Floor", "translation='0 -0.5 0'")  # top face at y = 0


def collection(bodies: str, collidables: str, params: str = "", gravity: str = "0 -9.81 0") -> str:
    return (f"<RigidBodyCollection gravity='{gravity}'>{bodies}"
            f"<CollisionCollection containerField='collider' {params}>{collidables}</CollisionCollection>"
            "</RigidBodyCollection>")


def ball(name: str, y: float, r: float, extra: str = "", x: float = 0) -> str:
    return (f"<RigidBody DEF='{name}' position='{x} {y} 0' {extra}>"
            f"{shape(f'<Sphere radius={chr(39)}{r}{chr(39)}/>', name + 'S', container='geometry')}</RigidBody>")


def settle_depth(v_impact: float, t_after: float) -> float:
    """How deep a body may still be, t_after seconds after landing at v_impact: one step's
    travel, less DART's 1 mm/s correction since, plus a step's fall under gravity."""
    return max(v_impact * DT - 1e-3 * t_after, 0) + G * DT * DT + 1e-6


def test_contact_normal_runs_from_geometry1_to_geometry2_sideways(tmp_path):
    """Two spheres meeting along x, no gravity: the normal points from geometry1's centre
    towards geometry2's, whichever order DART lists them in."""
    bodies = ball("L", 0, 0.5, "linearVelocity='1 0 0'", x=-0.6) + ball("R", 0, 0.5, x=0.6)
    world, sim = build(tmp_path, collection(bodies, "<CollidableShape USE='LS'/><CollidableShape USE='RS'/>",
                                            gravity="0 0 0"))
    centre = {0: "L", 1: "R"}
    for _ in range(80):
        sim.step()
        c = sim.contacts()
        if len(c.depth):
            break
    assert len(c.depth) == 1
    s = sim.state()
    names = world.bodies.names
    rows = {g: names.index(centre[g]) for g in (0, 1)}
    a, b = rows[int(c.geometry1[0])], rows[int(c.geometry2[0])]
    # contacts are found at the start of the step, before it moves the bodies
    towards = np.sign(s.position[b, 0] - s.position[a, 0])
    assert c.normal[0] == pytest.approx([towards, 0, 0], abs=1e-9)
    assert 0 < c.depth[0] <= DT * 1.0 + 1e-9  # at most one step's closing travel


def overlapping_pair(joint: str) -> str:
    a = ball("A", 0, 0.5, x=-0.3)
    b = ball("B", 0, 0.5, x=0.3)
    return collection(a + b + joint, "<CollidableShape USE='AS'/><CollidableShape USE='BS'/>", gravity="0 0 0")


def test_joined_bodies_do_not_collide(tmp_path):
    joint = ("<BallJoint anchorPoint='0 0 0'><RigidBody USE='A' containerField='body1'/>"
             "<RigidBody USE='B' containerField='body2'/></BallJoint>")
    _, sim = build(tmp_path, overlapping_pair(joint))
    sim.step(60)
    assert len(sim.contacts().depth) == 0
    assert sim.state().position[:, 0] == pytest.approx([-0.3, 0.3], abs=1e-12)
    _, free = build(tmp_path, overlapping_pair(""))  # the same bodies unjoined do touch
    free.step(1)
    assert len(free.contacts().depth) == 1


def test_bodies_of_one_tree_collide_unless_joined(tmp_path):
    """A chain A - B - C is one DART skeleton: A and C, not joined to each other, overlap and
    collide; the joined pairs (A, B) and (B, C) overlap too and do not."""
    bodies = "".join(ball(n, 0, 0.5, x=x) for n, x in (("A", -0.2), ("B", 0), ("C", 0.2)))
    joints = "".join(f"<BallJoint anchorPoint='{x} 0 0'><RigidBody USE='{p}' containerField='body1'/>"
                     f"<RigidBody USE='{q}' containerField='body2'/></BallJoint>"
                     for p, q, x in (("A", "B", -0.1), ("B", "C", 0.1)))
    world, sim = build(tmp_path, collection(bodies + joints, "".join(f"<CollidableShape USE='{n}S'/>" for n in "ABC"),
                                            gravity="0 0 0"))
    assert len(set(map(id, sim.skeletons))) == 1 and sim.skeletons[0].getNumBodyNodes() == 3
    sim.step(1)
    c = sim.contacts()
    pairs = {tuple(sorted((int(a), int(b)))) for a, b in zip(c.geometry1, c.geometry2)}
    assert pairs == {(0, 2)}


@pytest.mark.parametrize("e", [0.2, 0.5, 0.8])
def test_bounce_apex(tmp_path, e):
    """Dropped from h = 1 m (its bottom), a sphere rebounds to e^2 h. DART multiplies the
    shapes' restitutions and each carries sqrt(e), so the rebound speed is e times the
    approach speed of the contact step, whose gravity increment g dt is in it: the rebound
    is up to e g dt faster than e v (v = sqrt(2 g h)), and the impact is caught up to one
    step's travel v dt deep. So the apex may sit above e^2 h by up to
    2 (e v)(e g dt) / (2 g) + v dt (measured 0.1, 5.1, 12.5 mm for e = 0.2, 0.5, 0.8 against
    bounds of 2.0, 2.8, 4.2 cm: the first term, e^2 v dt, is nearly all of it)."""
    r, h = 0.1, 1.0
    s = simulate(tmp_path, collection(ball("B", r + h, r), FLOOR + "<CollidableShape USE='BS'/>",
                                      f"bounce='{e}'"), duration=1.2, frame_rate=240)
    y = values(s, "B", "position")[:, 1]
    vy = values(s, "B", "linearVelocity")[:, 1]
    after = np.flatnonzero(vy > 0)[0]
    apex = y[after:].max() - r
    v = math.sqrt(2 * G * h)
    assert abs(apex - e * e * h) <= e * v * e * G * DT / G * 2 + v * DT
    # the rebound speed itself: e times the approach speed of the contact step
    # (measured within 6e-5 relative: DART's contact CFM, 1e-5 relative to the row's diagonal)
    assert vy[after] == pytest.approx(-e * (vy[after - 1] - G * DT), rel=1e-4)


def test_slow_impacts_do_not_bounce_below_dart_threshold(tmp_path):
    """DART bounces only where e times the approach speed exceeds 0.1 m/s, whatever
    minBounceSpeed says: the declared reason minBounceSpeed is unsupported."""
    e = 0.5
    out = {}
    for v in (0.15, 0.25):  # e v = 0.075 and 0.125
        _, sim = build(tmp_path, collection(ball("B", 0.1 + v * DT / 2, 0.1, f"linearVelocity='0 {-v} 0'"),
                                            FLOOR + "<CollidableShape USE='BS'/>",
                                            f"bounce='{e}' minBounceSpeed='0'", gravity="0 0 0"))
        sim.step(10)
        out[v] = sim.state().linear_velocity[0, 1]
    assert out[0.15] < 0.01
    assert out[0.25] == pytest.approx(e * 0.25, rel=1e-4)  # measured 3e-5 (DART's contact CFM)


def test_collidable_offset_places_the_shape_in_the_body(tmp_path):
    """A sphere 0.3 below its body's origin and a cylinder turned onto its side, each placed by
    its own translation and rotation under a CollidableOffset (the offset's own are the
    body's, at the top of its geometry list): the first body rests on the sphere, 0.3 + r
    high, the second on the lying cylinder, at its radius."""
    sphere = shape("<Sphere radius='0.2'/>", "Inner", "translation='0 -0.3 0'", container="collidable")
    offset = f"<CollidableOffset DEF='Off' containerField='geometry'>{sphere}</CollidableOffset>"
    body = f"<RigidBody DEF='B' position='3 0.55 0'>{offset}</RigidBody>"
    lying = shape("<Cylinder radius='0.25' height='2'/>", "Lying",
                  "rotation='0 0 1 1.5707963267948966' translation='0 0 0'", container="collidable")
    roll = (f"<RigidBody DEF='C' position='0 0.3 0'><CollidableOffset DEF='Off2' containerField='geometry'>"
            f"{lying}</CollidableOffset></RigidBody>")
    world, sim = build(tmp_path, collection(body + roll, FLOOR + "<CollidableOffset USE='Off'/>"
                                                               "<CollidableOffset USE='Off2'/>"))
    sim.step(480)
    s = sim.state()
    v = math.sqrt(2 * G * 0.05)
    assert 0.5 - settle_depth(v, 1.5) <= s.position[0, 1] <= 0.5 + 1e-9
    assert 0.25 - settle_depth(v, 1.5) <= s.position[1, 1] <= 0.25 + 1e-9
    # a cylinder on its side rolls if pushed: it rests on a line, so its contacts span x
    c = sim.contacts()
    on_cylinder = np.isin(c.geometry1, [2]) | np.isin(c.geometry2, [2])
    xs = c.position[on_cylinder, 0]
    assert xs.max() - xs.min() > 1.5  # along the 2 m axis, now along x


def test_standing_cylinder_and_cone_rest_on_their_bases(tmp_path):
    cyl = ("<RigidBody DEF='Cyl' position='-2 0.52 0'>"
           + shape("<Cylinder radius='0.3' height='1'/>", "CylS", container="geometry") + "</RigidBody>")
    cone = ("<RigidBody DEF='Cone' position='2 0.52 0'>"
            + shape("<Cone bottomRadius='0.4' height='1'/>", "ConeS", container="geometry") + "</RigidBody>")
    _, sim = build(tmp_path, collection(cyl + cone, FLOOR + "<CollidableShape USE='CylS'/>"
                                        "<CollidableShape USE='ConeS'/>"))
    sim.step(480)
    s = sim.state()
    v = math.sqrt(2 * G * 0.02)
    for row in (0, 1):  # base at -h/2 on the floor: the centre at h/2, upright
        assert 0.5 - settle_depth(v, 1.8) <= s.position[row, 1] <= 0.5 + 1e-9
        assert np.abs(s.orientation[row, 1:]).max() < 1e-4  # measured 6e-6 (the cone)
    c = sim.contacts()
    on_cone = (c.geometry1 == 2) | (c.geometry2 == 2)
    assert on_cone.any() and np.all(np.abs(c.position[on_cone, 1]) < 1e-3)  # touching at its base


def test_cone_apex_points_up(tmp_path):
    """X3D's cone has its apex at +h/2: a ball dropped on a static cone's tip stays there, at
    h/2 + r (held on a point, so balanced: dropped straight down)."""
    cone = shape("<Cone bottomRadius='0.5' height='1'/>", "Tip", "translation='0 0.5 0'")
    _, sim = build(tmp_path, collection(ball("B", 1.0 + 0.1 + 0.02, 0.1), FLOOR + cone
                                        + "<CollidableShape USE='BS'/>"))
    sim.step(240)
    y = sim.state().position[0, 1]
    v = math.sqrt(2 * G * 0.02)
    assert 1.1 - settle_depth(v, 0.9) <= y <= 1.1 + 1e-9
    c = sim.contacts()
    assert len(c.depth) == 1 and c.position[0, 1] == pytest.approx(1.0, abs=1e-3)


V_TROUGH = ("<IndexedFaceSet coordIndex='0 1 3 2 -1 2 3 5 4 -1'>"
            "<Coordinate point='-1 1 -1 -1 1 1 0 0 -1 0 0 1 1 1 -1 1 1 1'/></IndexedFaceSet>")


def test_ball_settles_in_a_concave_mesh(tmp_path):
    """A static V trough (two faces meeting along z at y = 0, rising 45 degrees): a ball of
    radius r comes to rest on both faces, its centre r sqrt(2) above the crease. DART's
    Bullet detector would take the mesh's convex hull and hold the ball at its top (y = 0.9
    here, measured); built triangle by triangle it is a triangle soup, as ODE's trimesh. Each
    face holds the ball up to settle_depth deep along its normal, sqrt(2) times that in
    height or sideways."""
    r, y0 = 0.1, 0.3
    _, sim = build(tmp_path, collection(ball("B", y0, r, x=0.05), shape(V_TROUGH, "V") + "<CollidableShape USE='BS'/>"))
    sim.step(720)
    p = sim.state().position[0]
    fall = y0 - r * math.sqrt(2)
    slack = math.sqrt(2) * settle_depth(math.sqrt(2 * G * fall), 3 - math.sqrt(2 * fall / G))
    assert r * math.sqrt(2) - slack <= p[1] <= r * math.sqrt(2) + 1e-9  # measured 4e-4 below
    assert abs(p[0]) <= slack
    c = sim.contacts()
    assert set(c.geometry1.tolist() + c.geometry2.tolist()) == {0, 1}  # every triangle maps to its geometry
    assert len(c.depth) == 2  # one on each face
    assert sorted(np.round(np.abs(c.normal[:, 0]), 9)) == [round(math.sqrt(0.5), 9)] * 2


def test_moving_mesh_box_rests_on_a_mesh_floor(tmp_path):
    """A closed cube as an IndexedFaceSet on a body, on a static TriangleSet floor."""
    cube = ("<IndexedFaceSet coordIndex='0 1 3 2 -1 4 6 7 5 -1 0 4 5 1 -1 2 3 7 6 -1 0 2 6 4 -1 1 5 7 3 -1'>"
            "<Coordinate point='-0.25 -0.25 -0.25 -0.25 -0.25 0.25 -0.25 0.25 -0.25 -0.25 0.25 0.25 "
            "0.25 -0.25 -0.25 0.25 -0.25 0.25 0.25 0.25 -0.25 0.25 0.25 0.25'/></IndexedFaceSet>")
    floor = ("<TriangleSet><Coordinate point='-5 0 -5 5 0 5 5 0 -5 -5 0 -5 -5 0 5 5 0 5'/></TriangleSet>")
    body = f"<RigidBody DEF='M' position='0.1 0.27 0'>{shape(cube, 'MS', container='geometry')}</RigidBody>"
    _, sim = build(tmp_path, collection(body, shape(floor, "F") + "<CollidableShape USE='MS'/>"))
    sim.step(480)
    s = sim.state()
    v = math.sqrt(2 * G * 0.02)
    assert 0.25 - settle_depth(v, 1.9) <= s.position[0, 1] <= 0.25 + 1e-9
    assert np.abs(s.orientation[0, 1:]).max() < 1e-6


def test_a_mesh_corner_is_one_contact(tmp_path):
    """A tetrahedron standing on the floor: each corner is in three of its triangles (each
    its own DART shape), and each triangle reports it; contacts() reports it once. (Its
    bottom face, flat on the floor, adds points of Bullet's face manifold as well.)"""
    tetra = ("<IndexedFaceSet coordIndex='0 1 2 -1 0 3 1 -1 1 3 2 -1 2 3 0 -1'>"
             "<Coordinate point='0 0.5 0 -0.5 -0.3 0.3 0.5 -0.3 0.3 0 -0.3 -0.5'/></IndexedFaceSet>")
    body = f"<RigidBody DEF='T' position='0 0.31 0'>{shape(tetra, 'TS', container='geometry')}</RigidBody>"
    _, sim = build(tmp_path, collection(body, FLOOR + "<CollidableShape USE='TS'/>"))
    sim.step(240)
    c = sim.contacts()
    gaps = np.linalg.norm(c.position[:, None] - c.position[None], axis=2) + np.eye(len(c.depth))
    assert gaps.min() > 1e-6  # no point twice
    for corner in ([-0.5, 0.3], [0.5, 0.3], [0, -0.5]):
        assert np.min(np.linalg.norm(c.position[:, [0, 2]] - corner, axis=1)) < 1e-6
    assert set(c.geometry1.tolist() + c.geometry2.tolist()) == {0, 1}
    assert sim.dart_world.getLastCollisionResult().getNumContacts() > len(c.depth)  # DART's own list repeats them


def test_elevation_grid_as_triangles(tmp_path):
    """A static 3 x 3 ElevationGrid, 1 m spacing, all at height 0.2 except one raised corner
    point; a ball over the flat part rests at 0.2 + r."""
    grid = ("<ElevationGrid xDimension='3' zDimension='3' xSpacing='1' zSpacing='1' "
            "height='0.2 0.2 0.2 0.2 0.2 0.2 0.2 0.2 1.0'/>")
    r = 0.1
    body = (f"<RigidBody DEF='B' position='0.5 {0.2 + r + 0.02} 0.5'>"
            f"{shape(f'<Sphere radius={chr(39)}{r}{chr(39)}/>', 'BS', container='geometry')}</RigidBody>")
    _, sim = build(tmp_path, collection(body, shape(grid, "Grid") + "<CollidableShape USE='BS'/>"))
    sim.step(240)
    p = sim.state().position[0]
    v = math.sqrt(2 * G * 0.02)
    assert 0.2 + r - settle_depth(v, 0.9) <= p[1] <= 0.2 + r + 1e-9
    assert p[[0, 2]] == pytest.approx([0.5, 0.5], abs=1e-9)


def test_grid_triangles_face_up_and_cover_every_cell():
    nx, nz = 4, 3
    t = _grid_triangles(nx, nz)
    assert len(t) == 2 * (nx - 1) * (nz - 1)
    i, j = np.meshgrid(np.arange(nx), np.arange(nz))
    points = np.stack([i.ravel(), np.zeros(nx * nz), j.ravel()], axis=1).astype(float)
    n = np.cross(points[t[:, 1]] - points[t[:, 0]], points[t[:, 2]] - points[t[:, 0]])
    assert np.all(n[:, 1] > 0) and np.allclose(n[:, [0, 2]], 0)
    assert np.abs(n[:, 1]).sum() / 2 == pytest.approx((nx - 1) * (nz - 1))  # the grid's area


def test_fixed_body_touching_static_geometry_is_reported(tmp_path):
    """x3d_core tests a fixed body's geometry against the static environment's; DART skips
    two immobile skeletons, so fixed bodies stay mobile (with no degrees of freedom)."""
    box = shape("<Box size='1 1 1'/>", "FS", container="geometry")
    body = f"<RigidBody DEF='F' fixed='true' position='0 0.2 0'>{box}</RigidBody>"
    _, sim = build(tmp_path, collection(body, FLOOR + "<CollidableShape USE='FS'/>"))
    sim.step(10)
    assert sim.state().position[0] == pytest.approx([0, 0.2, 0], abs=0)
    c = sim.contacts()
    assert len(c.depth) >= 1 and c.depth == pytest.approx(0.3, abs=1e-9)


def test_no_collider_builds_no_shapes(tmp_path):
    world, sim = build(tmp_path, "<RigidBodyCollection><RigidBody DEF='B'>"
                       + shape("<Sphere/>", "S", container="geometry") + "</RigidBody></RigidBodyCollection>")
    assert world.collisions is None
    assert sim.nodes[0].getNumShapeNodes() == 0
    sim.step(2)
    assert len(sim.contacts().depth) == 0


def test_collision_declarations():
    d = BACKEND.support
    for f in ("CollidableShape.geometry.Box", "CollidableShape.geometry.Sphere", "CollidableShape.geometry.Cylinder",
              "CollidableShape.geometry.Cone", "CollisionSensor", "CollisionCollection.appliedParameters"):
        assert d(f).support is base.Support.NATIVE, f
    for f in ("CollisionCollection", "CollisionCollection.bounce", "CollisionCollection.appliedParameters.BOUNCE",
              "CollisionCollection.frictionCoefficients", "CollidableShape.geometry.IndexedFaceSet",
              "CollidableShape.geometry.TriangleSet", "CollidableShape.geometry.IndexedTriangleSet",
              "CollidableShape.geometry.ElevationGrid", "RigidBodyCollection.errorCorrection"):
        assert d(f).support is base.Support.APPROXIMATE and d(f).note, f
    for f in ("CollisionCollection.minBounceSpeed", "CollisionCollection.appliedParameters.FRICTION_COEFFICIENT-2",
              "CollisionCollection.appliedParameters.USER_FRICTION", "CollisionCollection.appliedParameters.SLIP-1",
              "CollisionCollection.appliedParameters.SLIP-2", "CollisionCollection.appliedParameters.SPEED-1",
              "CollisionCollection.appliedParameters.SPEED-2",
              "CollisionCollection.appliedParameters.ERROR_REDUCTION",
              "CollisionCollection.appliedParameters.CONSTANT_FORCE"):
        assert d(f).support is base.Support.UNSUPPORTED and d(f).note != base.NOT_YET, f
    for f in ("RigidBodyCollection.contactSurfaceThickness", "RigidBodyCollection.maxCorrectionSpeed"):
        assert BACKEND.declared[f].support is base.Support.UNSUPPORTED, f  # base.EVALUATOR answers first for now

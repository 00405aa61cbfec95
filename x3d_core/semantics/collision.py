"""What collides, with what shape, and with which contact parameters: written once.

The rules (clause 37.4), as x3drbp reads them:
- Only collidables reachable from a RigidBodyCollection's collider collide, through
  CollisionSpace nesting; a disabled collection, space or collidable drops out.
- A collidable in a RigidBody's geometry moves with the body. At the top of that list its
  own translation and rotation are outputs (the body sets them), so it sits at the body's
  frame; below a CollidableOffset, translation and rotation place it relative to the
  offset. A collidable on no body is static, placed by its own translation and rotation.
- A Shape with an explicit bboxSize collides as that box (the spec's approximation).
  CollisionSpace useGeometry is read as the speed hint it describes ("only make
  approximations using the bounds... using the geometry will be more accurate"): the
  geometry itself is always used, as every browser does (what TRUE asks for, and what
  FALSE allows without requiring it); a literal reading would turn
  the wheels of Xj3D's own toy car (in a space, useGeometry left FALSE) into boxes.
- Collidables of one body never collide with each other, and neither do the collidables
  of two bodies joined by a joint (ODE's usual rule, and Xj3D's).
- Contact parameters come from the CollisionCollection; appliedParameters decides which
  apply (either spelling), as ODE's contact mode bits do.
- A RigidBodyCollection with no collider still collides where a CollisionSensor's
  contacts are ROUTEd straight into its set_contacts (Xj3D's and Cobweb's own examples
  do this): those contacts are the sensor's collider's, with its parameters, so the
  sensor's collider acts as the collection's. A browser applies them a frame late, in
  the steps of the next frame; here each step finds them itself, from the same state at
  a frame's first step. Routed into a collection whose own collider is the same, they
  are the contacts it has already. Contacts from a collider other than the collection's
  own, or from two colliders, are refused (analysis names the feature): x3drbp gives a
  collection one collision set.
- A CollisionCollection that an enabled CollisionSensor watches and that no enabled
  RigidBodyCollection collides with is still detected, for the sensor alone: the sensor "is
  used to send collision detection information into the scene graph for user processing"
  (37.4.5), and nothing in the clause makes such contacts act. It is planned once (watch),
  into the first world whose bodies carry one of its collidables (the first world where none
  does; a collidable on another world's body is static there, as in any set), as one of that
  world's watched sets: each frame's end the engine detects its contacts where the bodies
  are, its sensors report them, and no body feels them. Disabled, it is not run and its
  sensors report nothing (37.4.4).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from x3d_core.model.scene import Node, Route

from . import rotation as R
from .applied import applied
from .world_data import STATIC, State, World

KINDS = ("box", "sphere", "cylinder", "cone", "mesh", "heightfield")


@dataclass
class Geometry:
    """One collision shape, fixed to a body (or to the static environment)."""
    name: str  # the CollidableShape's trace name
    node: Node  # the CollidableShape
    body: int  # row in world.bodies, or STATIC
    kind: str  # one of KINDS
    size: np.ndarray  # box: full extents (3,); sphere: (r,); cylinder and cone: (r, h), axis y
    position: np.ndarray  # in the body's frame (world for STATIC)
    orientation: np.ndarray  # quaternion, in the body's frame
    vertices: np.ndarray | None = None  # mesh: (n, 3); heightfield: (nx*nz, 3) grid points
    triangles: np.ndarray | None = None  # mesh: (m, 3) vertex indices
    grid: tuple[int, int] | None = None  # heightfield: (xDimension, zDimension)


@dataclass
class ContactParameters:
    """The parameters a contact gets, already resolved through appliedParameters."""
    bounce: float  # 0 unless BOUNCE applies
    min_bounce_speed: float
    friction: np.ndarray  # (mu1, mu2): mu2 = mu1 unless FRICTION_COEFFICIENT-2 applies
    user_friction: bool  # USER_FRICTION: the first friction direction is the scene's
    slip: np.ndarray  # (2,), each 0 unless SLIP-n applies
    surface_speed: np.ndarray  # (2,), each 0 unless SPEED-n applies
    softness_erp: float | None  # None unless ERROR_REDUCTION applies
    softness_cfm: float | None  # None unless CONSTANT_FORCE applies
    surface_thickness: float  # the collection's contactSurfaceThickness
    applied: frozenset[str] = field(default_factory=frozenset)

    @property
    def frictionless(self) -> bool:
        """Whether these contacts apply no friction (37.4.7: "If there is no friction, the
        direction should be set to 0, 0, 0."): both coefficients in effect are 0, mu1 being
        frictionCoefficients[0] always and mu2 frictionCoefficients[1] where
        FRICTION_COEFFICIENT-2 applies, else mu1 (docs/spec-loose-ends.md, section 3).
        surfaceSpeed and slip act through friction, so without it they apply nothing either."""
        return not np.any(self.friction)


# 37.4.4: the collection's parameters "specify default values that will be assigned to all
# Contact nodes generated from the CollisionSensor node": each Contact field (key) carries the
# collection's field (value) as given, whatever appliedParameters applies (a Contact carries
# that too, to say which apply)
CONTACT_DEFAULTS = {f: f for f in ("bounce", "minBounceSpeed", "frictionCoefficients", "surfaceSpeed",
                                   "softnessConstantForceMix", "softnessErrorCorrection")} | {
    "slipCoefficients": "slipFactors"}


@dataclass
class ContactPoints:
    """Every contact point of a step, in bulk, world frame: the engine's own points."""
    position: np.ndarray  # (k, 3)
    normal: np.ndarray  # (k, 3) unit, pointing from geometry1 towards geometry2
    depth: np.ndarray  # (k,) penetration, positive when overlapping
    geometry1: np.ndarray  # (k,) index into Collisions.geometries
    geometry2: np.ndarray  # (k,)

    @classmethod
    def none(cls) -> ContactPoints:
        return cls(np.zeros((0, 3)), np.zeros((0, 3)), np.zeros(0), np.zeros(0, dtype=int), np.zeros(0, dtype=int))


@dataclass
class Collisions:
    geometries: list[Geometry]
    excluded: set[tuple[int, int]]  # body-row pairs (low, high) that never touch (joined bodies)
    parameters: ContactParameters
    collider: Node
    sensors: list[tuple[str, Node]] = field(default_factory=list)  # enabled CollisionSensors on this collider

    def may_touch(self, first: np.ndarray, second: np.ndarray) -> np.ndarray:
        """Whether each pair of geometries (index arrays into geometries) is tested: not one
        body's, not a joined pair. In bulk: a scene of n geometries has n^2/2 pairs."""
        body, span, joined = self._pair_keys
        a, b = body[np.asarray(first, dtype=np.int64)], body[np.asarray(second, dtype=np.int64)]
        out = a != b
        if len(joined):
            out &= ~np.isin((np.minimum(a, b) + 1) * span + np.maximum(a, b) + 1, joined)
        return out

    def touchable(self) -> np.ndarray:
        """Whether each geometry may touch any other of the set: some geometry is neither its
        body's nor a joined body's. Counted per body, in linear time."""
        body, _, _ = self._pair_keys
        count = np.bincount(body + 1, minlength=int(body.max(initial=STATIC)) + 2)
        blocked = count.copy()  # per body (shifted by 1): its geometries and its joined bodies'
        pairs = np.array([p for p in self.excluded if p[0] != p[1]], dtype=np.int64).reshape(-1, 2) + 1
        pairs = pairs[(pairs < len(count)).all(axis=1)]  # a joined body with no geometry blocks none
        np.add.at(blocked, pairs[:, 0], count[pairs[:, 1]])
        np.add.at(blocked, pairs[:, 1], count[pairs[:, 0]])
        return len(body) - blocked[body + 1] > 0

    def placed(self, s: State) -> tuple[np.ndarray, np.ndarray]:
        """Each geometry's world position and orientation with the bodies where state s has them
        (a static one where the plan put it): for an engine that tests shapes at poses it is given
        rather than on its own bodies (a watched set's)."""
        body, _, _ = self._pair_keys
        position, orientation = self._local
        on = body != STATIC
        if not on.any():
            return position.copy(), orientation.copy()
        row = np.maximum(body, 0)
        q = np.where(on[:, None], s.orientation[row], R.IDENTITY)
        return np.where(on[:, None], s.position[row], 0.0) + R.rotate(q, position), R.multiply(q, orientation)

    @cached_property
    def _local(self) -> tuple[np.ndarray, np.ndarray]:
        """Every geometry's position and orientation in its body's frame (the world's for STATIC)."""
        return (np.array([g.position for g in self.geometries], dtype=np.float64).reshape(-1, 3),
                np.array([g.orientation for g in self.geometries], dtype=np.float64).reshape(-1, 4))

    @cached_property
    def _pair_keys(self) -> tuple[np.ndarray, int, np.ndarray]:
        """Each geometry's body row, and the joined body pairs as integer keys (rows and STATIC
        shifted to 0.. as the digits of base `span`)."""
        body = np.array([g.body for g in self.geometries], dtype=np.int64)
        span = int(max(body.max(initial=STATIC), *(hi for _, hi in self.excluded), STATIC)) + 2
        joined = np.array(sorted((lo + 1) * span + hi + 1 for lo, hi in self.excluded), dtype=np.int64)
        return body, span, joined


def friction_directions(normal: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The two friction directions of contacts with these unit normals (n, 3), as ODE's
    dPlaneSpace makes them: surfaceSpeed and slipFactors components 1 and 2 act along
    these unless USER_FRICTION gives the first. For an upward normal: -x and +z."""
    n = np.atleast_2d(np.asarray(normal, dtype=np.float64))
    p, q = np.zeros_like(n), np.zeros_like(n)
    steep = np.abs(n[:, 2]) > np.sqrt(0.5)
    a = n[:, 1] ** 2 + n[:, 2] ** 2  # in the y-z plane
    k = 1 / np.sqrt(np.where(steep, a, 1))
    p[steep] = np.stack([np.zeros_like(k), -n[:, 2] * k, n[:, 1] * k], axis=1)[steep]
    q[steep] = np.stack([a * k, -n[:, 0] * p[:, 2], n[:, 0] * p[:, 1]], axis=1)[steep]
    a2 = n[:, 0] ** 2 + n[:, 1] ** 2  # in the x-y plane
    k2 = 1 / np.sqrt(np.where(~steep, a2, 1))
    flat = ~steep
    p[flat] = np.stack([-n[:, 1] * k2, n[:, 0] * k2, np.zeros_like(k2)], axis=1)[flat]
    q[flat] = np.stack([-n[:, 2] * p[:, 1], n[:, 2] * p[:, 0], a2 * k2], axis=1)[flat]
    return p, q


def parameters(collection: Node, thickness: float) -> ContactParameters:
    """The contact parameters of a CollisionCollection or a Contact node."""
    on = applied(collection.get("appliedParameters"))
    fc = np.asarray(collection.get("frictionCoefficients"), dtype=np.float64)
    slip_field = "slipFactors" if collection.type_name == "CollisionCollection" else "slipCoefficients"
    slip = np.asarray(collection.get(slip_field), dtype=np.float64)
    speed = np.asarray(collection.get("surfaceSpeed"), dtype=np.float64)
    return ContactParameters(
        bounce=float(collection.get("bounce")) if "BOUNCE" in on else 0.0,
        min_bounce_speed=float(collection.get("minBounceSpeed")),
        friction=np.array([fc[0], fc[1] if "FRICTION_COEFFICIENT-2" in on else fc[0]]),
        user_friction="USER_FRICTION" in on,
        slip=np.array([slip[0] if "SLIP-1" in on else 0.0, slip[1] if "SLIP-2" in on else 0.0]),
        surface_speed=np.array([speed[0] if "SPEED-1" in on else 0.0, speed[1] if "SPEED-2" in on else 0.0]),
        softness_erp=float(collection.get("softnessErrorCorrection")) if "ERROR_REDUCTION" in on else None,
        softness_cfm=float(collection.get("softnessConstantForceMix")) if "CONSTANT_FORCE" in on else None,
        surface_thickness=thickness, applied=on)


def routed_colliders(collection: Node, routes: list[Route]) -> list[Node | None]:
    """The colliders of the enabled CollisionSensors whose contacts are routed straight into
    the collection's set_contacts, once each (None for a sensor watching nothing)."""
    out: list[Node | None] = []
    for r in routes:
        if (r.to_node is collection and r.to_field == "set_contacts" and r.from_field == "contacts"
                and r.from_node.type_name == "CollisionSensor" and r.from_node.get("enabled")):
            c = r.from_node.get("collider")
            if all(c is not o for o in out):
                out.append(c)
    return out


def collider(collection: Node, routes: list[Route]) -> Node | None:
    """The CollisionCollection whose contacts act on a RigidBodyCollection: its collider, else
    the one collider of the sensors routed into its set_contacts (module docstring)."""
    own = collection.get("collider")
    if own is not None:
        return own
    watched = [c for c in routed_colliders(collection, routes) if c is not None]
    return watched[0] if len(watched) == 1 else None


def foreign_contacts(collection: Node, routes: list[Route]) -> bool:
    """Whether contacts routed into set_contacts come from a collider other than collider()."""
    chosen = collider(collection, routes)
    return any(c is not None and c is not chosen for c in routed_colliders(collection, routes))


def plan(world: World, names: dict[int, str], routes: list[Route]) -> Collisions | None:
    """The world's collision set, or None where nothing collides in it."""
    collider_node = collider(world.node, routes)
    if collider_node is None or not collider_node.get("enabled"):
        return None
    return gather(world, collider_node, names)


def watch(worlds: list[World], sensors: list[Node], names: dict[int, str], routes: list[Route]) -> None:
    """Each enabled collection the sensors (the enabled ones) watch that none of the worlds
    collides with (collider() names it for none), planned once for reporting only (the module's
    docstring) into the first world whose bodies carry one of its collidables, else the first
    world: appended to that world's watched, with its sensors."""
    if not worlds:
        return
    used = {id(collider(w.node, routes)) for w in worlds}
    watched = {id(c): c for c in (s.get("collider") for s in sensors) if c is not None}
    for node in watched.values():
        if id(node) in used or not node.get("enabled"):
            continue
        sets = [gather(w, node, names) for w in worlds]
        k = next((k for k, c in enumerate(sets) if any(g.body != STATIC for g in c.geometries)), 0)
        sets[k].sensors = [(names[id(s)], s) for s in sensors if s.get("collider") is node]
        worlds[k].watched.append(sets[k])


def gather(world: World, collider_node: Node, names: dict[int, str]) -> Collisions:
    """One CollisionCollection's collision set as the world's bodies carry it."""
    owner: dict[int, int] = {}  # top-level collidable -> body row
    for row, body in enumerate(world.bodies.nodes):
        for g in body.get("geometry"):
            owner.setdefault(id(g), row)
    out: list[Geometry] = []
    seen: set[int] = set()

    def collidable(node: Node) -> None:
        if id(node) in seen or not node.get("enabled"):
            return
        seen.add(id(node))
        if node.type_name == "CollisionSpace":
            for child in node.get("collidables"):
                collidable(child)
            return
        row = owner.get(id(node), STATIC)
        if row != STATIC and not world.bodies.enabled[row]:
            return
        if row == STATIC:  # a static collidable is where its own fields put it
            pose = (np.asarray(node.get("translation"), dtype=np.float64), R.from_axis_angle(node.get("rotation")))
        else:  # the body sets a top-level collidable's translation and rotation
            pose = (np.zeros(3), R.IDENTITY.copy())
        _shapes(node, row, pose, names, out)

    for node in collider_node.get("collidables"):
        collidable(node)
    # joined bodies never touch: the pair of the bodies' own rows. World.joints ties a fixed
    # body's end to the static world, but excluding (STATIC, body) would keep the body off every
    # static shape (it would fall through the floor) and on the fixed body it is joined to
    rows = {id(b): i for i, b in enumerate(world.bodies.nodes)}
    excluded = set()
    for j in world.joints:
        ends = [rows.get(id(j.node.get(f)), STATIC) for f in ("body1", "body2")]
        if STATIC not in ends and ends[0] != ends[1]:
            excluded.add((min(ends), max(ends)))
    return Collisions(out, excluded, parameters(collider_node, world.contact_surface_thickness), collider_node)


def _shapes(node: Node, row: int, pose: tuple[np.ndarray, np.ndarray], names: dict[int, str],
            out: list[Geometry]) -> None:
    """The shapes under a collidable, posed in its body's frame."""
    position, orientation = pose
    if node.type_name == "CollidableOffset":
        inner = node.get("collidable")
        if inner is None or not inner.get("enabled"):
            return
        local = np.asarray(inner.get("translation"), dtype=np.float64)
        turn = R.from_axis_angle(inner.get("rotation"))
        _shapes(inner, row, (position + R.rotate(orientation, local), R.multiply(orientation, turn)), names, out)
        return
    shape = node.get("shape")
    geometry = shape.get("geometry") if shape is not None else None
    if geometry is None:
        return
    g = _geometry(geometry, shape)
    if g is None:
        return
    kind, size, centre, vertices, triangles, grid = g
    out.append(Geometry(names[id(node)], node, row, kind, size, position + R.rotate(orientation, centre),
                        orientation, vertices, triangles, grid))


def _geometry(geometry: Node, shape: Node):
    """(kind, size, centre in the shape's frame, vertices, triangles, grid), or None for a
    geometry that does not collide (no points)."""
    bbox = np.asarray(shape.get("bboxSize"), dtype=np.float64)
    if np.all(bbox >= 0):  # the spec: an explicit bounding box approximates the geometry
        return "box", bbox, np.asarray(shape.get("bboxCenter"), dtype=np.float64), None, None, None
    t = geometry.type_name
    zero = np.zeros(3)
    if t == "Box":
        return ("box", np.asarray(geometry.get("size"), dtype=np.float64), zero, None, None, None)
    if t == "Sphere":
        return ("sphere", np.array([geometry.get("radius")]), zero, None, None, None)
    if t == "Cylinder":
        return ("cylinder", np.array([geometry.get("radius"), geometry.get("height")]), zero, None, None, None)
    if t == "Cone":
        return ("cone", np.array([geometry.get("bottomRadius"), geometry.get("height")]), zero, None, None, None)
    if t in ("IndexedFaceSet", "IndexedTriangleSet", "TriangleSet"):
        mesh = _mesh(geometry)
        if mesh is None:
            return None
        return ("mesh", np.zeros(3), zero, mesh[0], mesh[1], None)
    if t == "ElevationGrid":
        nx, nz = int(geometry.get("xDimension")), int(geometry.get("zDimension"))
        heights = np.asarray(geometry.get("height"), dtype=np.float64)
        if nx < 2 or nz < 2 or heights.size != nx * nz:
            return None
        xs = np.arange(nx) * geometry.get("xSpacing")
        zs = np.arange(nz) * geometry.get("zSpacing")
        gx, gz = np.meshgrid(xs, zs)
        points = np.stack([gx.ravel(), heights, gz.ravel()], axis=1)
        return ("heightfield", np.zeros(3), zero, points, None, (nx, nz))
    return None


def _mesh(geometry: Node) -> tuple[np.ndarray, np.ndarray] | None:
    coord = geometry.get("coord")
    if coord is None:
        return None
    points = np.asarray(coord.get("point"), dtype=np.float64).reshape(-1, 3)
    t = geometry.type_name
    if t == "TriangleSet":
        tris = np.arange(len(points) - len(points) % 3).reshape(-1, 3)
    elif t == "IndexedTriangleSet":
        index = np.asarray(geometry.get("index"), dtype=np.int64)
        tris = index[:len(index) - len(index) % 3].reshape(-1, 3)
    else:  # IndexedFaceSet: each polygon (ended by -1) as a fan of triangles
        index = np.asarray(geometry.get("coordIndex"), dtype=np.int64)
        tris_list = []
        face: list[int] = []
        for i in list(index) + [-1]:
            if i < 0:
                tris_list.extend((face[0], face[k], face[k + 1]) for k in range(1, len(face) - 1))
                face = []
            else:
                face.append(int(i))
        tris = np.array(tris_list, dtype=np.int64).reshape(-1, 3)
    if not len(tris) or tris.max() >= len(points) or tris.min() < 0:
        return None
    return points, tris


"""DART backend (dartpy): each tree of the joint forest is one Skeleton; loops become constraints.

A tree's root gets a FreeJoint (a free root) or its tree joint to the world (a root
hanging from the static environment); every other body gets its tree joint to its
parent (BallJoint, RevoluteJoint, PrismaticJoint, UniversalJoint; a DoubleAxisHingeJoint is
a UniversalJoint, or with its suspension a chain of revolute, prismatic and revolute
joints through links of negligible mass). A joint's frame sits
at the anchor with the child's starting orientation, so the child starts at its X3D
pose with every joint coordinate zero and axes are the child's local axes. DART
measures a child's joint coordinate relative to its parent; x3d_core's outputs
measure body1 relative to body2, so limits are mirrored where the child is body2 (as
in backends/mujoco.py). A fixed body is an immobile skeleton welded to the world.
Joints closing loops become BallJointConstraints (two along a hinge's axis).

DART facts this relies on (measured with dartpy 6.20, see tests/test_backend_dart.py):
deactivation (sleeping) is enabled by default, and X3D bodies sleep only where
autoDisable asks, so it is turned off; external forces are cleared after every step,
so the loads are added before each one; joint limits are predictive (a step ends on
the stop) and ignore the limit ERP;
getCOMLinearVelocity() is the centre of mass's velocity in world coordinates (X3D's
linearVelocity); FreeJoint velocities are world-frame [angular; linear at the origin],
not body-frame, so velocities are set through world Jacobians at the centre of mass,
which needs no convention at all; the loop constraints' ERP, CFM and correction cap are
class-wide (static), so each simulation sets its own before it steps; a joint's spring
and damper are integrated implicitly (f = -k (q + h v') - c v', v' the velocity after the
step), but constraint impulses (stops, servos, loops) move its joint without them; a
stop's row takes priority over a SERVO actuator on the same degree of freedom (so hinge2
motors are joint forces computed here, see _Drives); per-degree-of-freedom actuator types
are refused except MIMIC.

Collisions (where world.collisions is not None) go through DART's Bullet collision
detector, measured against the others dartpy offers: the default FCL detector misses
sphere-versus-mesh contacts, the ODE detector turns a cone into a 1 cm sphere and lets
crossed cylinders sink (ODE has no cylinder-cylinder test), DART's own detector sinks
boxes 6 cm into meshes. Bullet takes a mesh's convex hull (measured: a ball is held at
the hull's top over a V trough), so a mesh is built triangle by triangle, each its own
shape: a triangle soup, as ODE's trimesh. Each geometry is a ShapeNode on its body's node
(the static ones on one welded node at the origin). DART combines friction by MIN and
restitution by PRODUCT, so every shape gets mu and sqrt(bounce): each contact gets the
collection's values exactly. Its contact normal points from collisionObject2 towards
collisionObject1 (measured), the point lies on object 1, the depth is positive when
overlapping. Its contact error correction is fixed (ERP 0.01, at most 1 mm/s, no surface
layer) and it bounces only where e times the approach speed exceeds 0.1 m/s: constants
of its ContactConstraint, which dartpy does not bind. A set only sensors watch (world.watched)
is ShapeNodes without a collision aspect, in a collision group of their own collided at each
frame's end (_Watched): nothing in the world's step meets them.
"""

from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass

import dartpy as dart
import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.semantics.collision import Collisions, ContactPoints, Geometry
from x3d_core.semantics.engine import BlewUp, Unsupported
from x3d_core.semantics.world import STATIC, Joint, State, World

from .base import BODIES, JOINTS, SEMI_IMPLICIT, SMALLEST_NORMAL, Backend, approximate, below, native, unsupported

_FULL_TURN = np.pi - 1e-9  # an angle range this wide is no limit at all
_LOOPS = dart.constraint.DynamicJointConstraint  # holds the loop constraints' class-wide parameters
# the mass of a link between a hinge2's degrees of freedom, relative to its child's (its
# inertia likewise): DART warns that a massless body node may misbehave. Measured against
# MuJoCo's massless stack of joints, outputs move by about 10 * _LINK_MASS (rad/s over
# 1 s; 3e-14 with massless links): linear in it, so no rounding trouble down to here
_LINK_MASS = 1e-12
_Z_TO_Y = np.array([[1.0, 0, 0], [0, 0, 1], [0, -1, 0]])  # DART's cylinders and cones lie along z, X3D's along y
_WATCHED_CAP = 1 << 16  # contacts a watched set's collision group returns at most (set on its own option)
_MAX_CONTACTS = 1000  # DART's CollisionOption.maxNumContacts: dartpy returns the option by value, so it stays


def _isometry(q: np.ndarray, p: np.ndarray) -> dart.math.Isometry3:
    t = dart.math.Isometry3()
    t.set_rotation(R.matrix(q))
    t.set_translation(np.asarray(p, dtype=np.float64))
    return t


@dataclass
class _Motor:
    """ODE's hinge2 motor: the rate sum(weight * joint velocity) driven to target, |torque| <= limit."""
    skeleton: dart.dynamics.Skeleton
    row: list[tuple[dart.dynamics.Joint, int, float]]  # (joint, degree of freedom, weight)
    target: float
    limit: float


class _Drives:
    """The motors of one skeleton, as ODE solves them: each motor's torque is the one that
    brings its rate to the target in this step if no more than its limit does, else the
    limit (all of the skeleton's motors at once, a box-bounded linear problem).

    DART's own SERVO actuator is not used, though its ramp and hold are ODE's: its row goes
    through DART's constraint solver, where a stop's row on the same degree of freedom
    takes priority, so a joint that a load presses on a stop stays there however much
    stronger the motor pulling it off (measured: 0.2 N m against 0.1), and its impulse
    moves the joint without a suspension's implicit spring-damper (measured: 20% more
    speed in a step under c h / m = 0.4). Here the torques are joint forces (FORCE
    actuators, the default) found from DART's own next-step velocity, which these
    quantities reproduce to rounding (measured): v' = v + h A^-1 f, with A = M + h D + h^2 K
    and f = Fext - (Coriolis and gravity) - K (q + h v - q0) - D v. DART's stops and loops
    then act on the result in its constraint solve, after the motors, so a motor answers
    their impulses at the next step (ODE solves them together)."""

    def __init__(self, skeleton: dart.dynamics.Skeleton, motors: list[_Motor], dt: float):
        self.skeleton, self.dt = skeleton, dt
        n = skeleton.getNumDofs()
        dofs = [skeleton.getDof(i) for i in range(n)]
        self.stiffness = np.array([d.getSpringStiffness() for d in dofs])
        self.damping = np.array([d.getDampingCoefficient() for d in dofs])
        self.rest = np.array([d.getRestPosition() for d in dofs])
        self.implicit = np.diag(dt * self.damping + dt * dt * self.stiffness)
        self.rows = np.zeros((len(motors), n))
        self.actuated: dict[int, tuple[dart.dynamics.Joint, int]] = {}
        for k, m in enumerate(motors):
            for joint, i, weight in m.row:
                column = joint.getIndexInSkeleton(i)
                self.rows[k, column] += weight
                self.actuated[column] = (joint, i)
        self.target = np.array([m.target for m in motors])
        self.limit = np.array([m.limit for m in motors])
        self.rhs = np.column_stack([np.zeros(n), self.rows.T])  # the forces, then each motor's unit torque

    def command(self) -> None:
        s, h = self.skeleton, self.dt
        q, v = s.getPositions(), s.getVelocities()
        f = (s.getExternalForces() - s.getCoriolisAndGravityForces()
             - self.stiffness * (q + h * v - self.rest) - self.damping * v)
        self.rhs[:, 0] = f
        x = np.linalg.solve(s.getMassMatrix() + self.implicit, self.rhs)
        free = self.rows @ (v + h * x[:, 0])  # each motor's rate next step without it
        torque = _box(h * self.rows @ x[:, 1:], self.target - free, self.limit)
        force = self.rows.T @ torque
        for column, (joint, i) in self.actuated.items():
            joint.setCommand(i, float(force[column]))  # a FORCE actuator's command is its force; reset every step


def _box(s: np.ndarray, r: np.ndarray, limit: np.ndarray) -> np.ndarray:
    """The x with s x = r where |x| < limit allows, x = +-limit elsewhere (s symmetric positive
    definite: the minimum of x.s.x/2 - x.r over the box, found by moving torques onto and
    off their limits until its optimality conditions hold)."""
    x = np.linalg.solve(s, r)
    at = np.abs(x) > limit  # the torques held at a limit
    if not at.any():
        return x  # the usual case once the motors have reached their targets
    x = np.minimum(np.maximum(x, -limit), limit)  # np.clip costs more on a few numbers
    for _ in range(4 * len(r) + 4):
        free = ~at
        if free.any():
            rows = s[free]
            x[free] = np.linalg.solve(rows[:, free], r[free] - rows[:, at] @ x[at])
            over = free & (np.abs(x) > limit)
            if over.any():
                x[over] = np.copysign(limit[over], x[over])
                at |= over
                continue
        back = at & ((r - s @ x) * x < 0)  # r - s x: where more torque lowers the objective
        if not back.any():
            break
        at &= ~back
    return x


def _shapes(g: Geometry) -> list[tuple[dart.dynamics.Shape, np.ndarray]]:
    """The DART shapes of one geometry, each with the turn from its frame to the geometry's."""
    if g.kind == "box":
        return [(dart.dynamics.BoxShape(np.asarray(g.size, dtype=np.float64)), np.eye(3))]
    if g.kind == "sphere":
        return [(dart.dynamics.SphereShape(float(g.size[0])), np.eye(3))]
    if g.kind == "cylinder":
        return [(dart.dynamics.CylinderShape(float(g.size[0]), float(g.size[1])), _Z_TO_Y)]
    if g.kind == "cone":  # DART's (and Bullet's) cone is centred, apex at +z: X3D's, turned
        return [(dart.dynamics.ConeShape(float(g.size[0]), float(g.size[1])), _Z_TO_Y)]
    if g.kind == "mesh":
        return [(shape, np.eye(3)) for shape in _triangles(g.vertices, g.triangles)]
    if g.kind == "heightfield":
        return [(shape, np.eye(3)) for shape in _triangles(g.vertices, _grid_triangles(*g.grid))]
    raise Unsupported(f"{g.name}: no DART shape for a {g.kind}")


def _shape_node(node: dart.dynamics.BodyNode, shape, turn: np.ndarray, g: Geometry,
                name: str) -> dart.dynamics.ShapeNode:
    """A shape on its body's node, posed where the geometry sits in the body's frame (turn: the
    shape's own axes onto X3D's)."""
    frame = node.createShapeNode(shape, name)
    pose = dart.math.Isometry3()
    pose.set_rotation(R.matrix(g.orientation) @ turn)
    pose.set_translation(np.asarray(g.position, dtype=np.float64))
    frame.setRelativeTransform(pose)
    return frame


def _grid_triangles(nx: int, nz: int) -> np.ndarray:
    """An ElevationGrid's cells as two triangles each, facing +y, split along the diagonal
    from (i+1, j) to (i, j+1); point (i, j) is row j * nx + i."""
    i, j = np.meshgrid(np.arange(nx - 1), np.arange(nz - 1))
    a = (j * nx + i).ravel()
    return np.concatenate([np.stack([a, a + nx, a + 1], axis=1), np.stack([a + 1, a + nx, a + nx + 1], axis=1)])


def _triangles(vertices: np.ndarray, triangles: np.ndarray) -> list[dart.dynamics.MeshShape]:
    """One MeshShape per (non-degenerate) triangle. DART's Bullet detector takes a mesh's
    convex hull, which for a single triangle is the triangle. dartpy builds a MeshShape only
    from a file (through assimp), so each triangle is a small OBJ file, all loaded through
    one URDF string."""
    v = np.asarray(vertices, dtype=np.float64)
    t = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    area = np.linalg.norm(np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]]), axis=1)
    scale = max(float(np.ptp(v, axis=0).max()), 1e-300) if len(v) else 1.0
    t = t[area > 1e-12 * scale * scale]  # assimp drops degenerate faces: leave them out here
    if not len(t):
        return []
    with tempfile.TemporaryDirectory(prefix="x3drbp-dart-") as folder:
        parts = []
        for n, tri in enumerate(t):
            path = os.path.join(folder, f"t{n}.obj")
            with open(path, "w") as f:
                f.write("".join("v %.17g %.17g %.17g\n" % tuple(p) for p in v[tri]) + "f 1 2 3\n")
            parts.append(f'<collision><geometry><mesh filename="{path}"/></geometry></collision>')
        urdf = f'<robot name="mesh"><link name="mesh">{"".join(parts)}</link></robot>'
        loaded = dart.utils.DartLoader().parseSkeletonString(urdf, dart.common.Uri("file:///"))
        if loaded is None or loaded.getNumBodyNodes() != 1:
            raise Unsupported("DART could not load a mesh's triangles")
        body = loaded.getBodyNode(0)
        shapes = [body.getShapeNode(k).getShape() for k in range(body.getNumShapeNodes())]
    if len(shapes) != len(t):
        raise Unsupported(f"DART loaded {len(shapes)} of a mesh's {len(t)} triangles")
    return shapes


def _points(result: dart.collision.CollisionResult, geometry_of: dict[str, int], split: bool) -> ContactPoints:
    """A collision result's contacts, copied out at once (DART's objects must not outlive the
    world), each named by its geometries; DART's normal points from object 2 towards object 1:
    turned round. split: some geometry is several shapes (a mesh's triangles meeting at a point
    each report it: kept once)."""
    found = result.getContacts()
    k = len(found)
    position, normal, depth = np.empty((k, 3)), np.empty((k, 3)), np.empty(k)
    first, second = np.empty(k, dtype=int), np.empty(k, dtype=int)
    for i, c in enumerate(found):
        position[i] = c.point
        normal[i] = c.normal
        depth[i] = c.penetrationDepth
        first[i] = geometry_of[c.collisionObject1.getShapeFrame().getName()]
        second[i] = geometry_of[c.collisionObject2.getShapeFrame().getName()]
    del found
    if split and k > 1:
        key = np.column_stack([first, second, np.round(position * 1e9), np.round(normal * 1e9)])
        _, keep = np.unique(key, axis=0, return_index=True)
        keep.sort()
        position, normal, depth = position[keep], normal[keep], depth[keep]
        first, second = first[keep], second[keep]
    return ContactPoints(position, -normal, depth, first, second)


class _Watched:
    """A set only sensors watch (world.watched): ShapeNodes with no collision aspect (the world's
    detector never meets them) on the bodies' nodes, the static ones on a node of a skeleton of
    their own outside the world, collided where the bodies are when asked in a collision group of
    a Bullet detector of its own, made afresh each time: a kept group keeps Bullet's persistent
    manifold, whose points outlive the overlap (measured: a ball 8 cm out of a box still reported
    at the depth its old normal gives, 0.78 m). The pairs may_touch rules out are dropped after."""

    def __init__(self, sim: DartSimulation, n: int, c: Collisions):
        self.collisions = c
        self.detector = dart.collision.BulletCollisionDetector()
        self.frames: list[dart.dynamics.ShapeNode] = []
        self.option = dart.collision.CollisionOption(True, _WATCHED_CAP)
        self.geometry_of: dict[str, int] = {}
        self.split = False
        self.static = dart.dynamics.Skeleton(f"watched{n}")  # held: its node holds the static shapes
        _, static = self.static.createWeldJointAndBodyNodePair(None)
        for k, g in enumerate(c.geometries):
            node = static if g.body == STATIC else sim.nodes[g.body]
            for m, (shape, turn) in enumerate(_shapes(g)):
                frame = _shape_node(node, shape, turn, g, f"w{n}.{k}" if m == 0 else f"w{n}.{k}.{m}")
                self.frames.append(frame)
                self.geometry_of[frame.getName()] = k
                self.split |= m > 0

    def contacts(self) -> ContactPoints:
        result = dart.collision.CollisionResult()
        group = self.detector.createCollisionGroup()
        for frame in self.frames:
            group.addShapeFrame(frame)
        group.collide(self.option, result)
        if result.getNumContacts() >= _WATCHED_CAP:
            raise BlewUp(f"{_WATCHED_CAP} contacts in a watched collection: the cap set on its collision group "
                         "leaves the others out")
        pts = _points(result, self.geometry_of, self.split)
        keep = self.collisions.may_touch(pts.geometry1, pts.geometry2)
        return ContactPoints(pts.position[keep], pts.normal[keep], pts.depth[keep], pts.geometry1[keep],
                             pts.geometry2[keep])


class DartSimulation:
    def __init__(self, world: World, dt: float):
        self.world = world
        b = world.bodies
        self.dart_world = dart.simulation.World(world.name)
        self.dart_world.setTimeStep(dt)
        self.dart_world.setGravity(np.asarray(world.gravity, dtype=np.float64))
        self.dt = dt
        self.motors: list[_Motor] = []  # hinge2 motors, as they are built
        sleep = self.dart_world.getDeactivationOptions()
        sleep.mEnabled = False  # on by default (under 1 cm/s and 0.05 rad/s for 0.5 s)
        self.dart_world.setDeactivationOptions(sleep)
        self.nodes: list[dart.dynamics.BodyNode] = [None] * len(b)  # filled in tree order below
        self.skeletons: list[dart.dynamics.Skeleton] = []  # one per tree and one per fixed body
        self.members: list[list[int]] = []  # the body rows of each skeleton
        tree: dict[int, int] = {}  # body row -> index in self.skeletons
        for i in world.order:
            p = world.parent[i]
            if b.fixed[i]:
                self._fixed(i)
                continue
            if p < 0:  # a tree's root: free, or hanging from the static environment
                tree[i] = len(self.skeletons)
                skeleton = dart.dynamics.Skeleton(f"tree{i}")
                self.skeletons.append(skeleton)
                self.members.append([i])
            else:
                tree[i] = tree[p]
                skeleton = self.skeletons[tree[i]]
                self.members[tree[i]].append(i)
            if p == World.FREE:
                joint, node = skeleton.createFreeJointAndBodyNodePair(None)
                joint.setPositions(dart.dynamics.FreeJoint.convertToPositions(
                    _isometry(b.orientation[i], b.position[i])))
            else:
                node = self._tree_joint(skeleton, i, world.joints[world.parent_joint[i]])
            self._body(node, i)
        self.geometry_of: dict[str, int] = {}  # shape node name -> index in world.collisions.geometries
        self.split = False  # whether some geometry is built of several shapes (a mesh's triangles)
        if world.collisions is not None:
            self._collide(world.collisions)
        self.watched = [_Watched(self, n, c) for n, c in enumerate(world.watched)]
        for skeleton in self.skeletons:
            self.dart_world.addSkeleton(skeleton)
        self.drives = [_Drives(s, [m for m in self.motors if m.skeleton is s], dt) for s in self.skeletons
                       if any(m.skeleton is s for m in self.motors)]
        self.loops = [c for k in world.loop_joints for c in self._loop(world.joints[k])]
        for c in self.loops:
            self.dart_world.getConstraintSolver().addConstraint(c)
        # ODE's CFM adds CFM/dt to each row's diagonal; DART's is relative (measured: a row's
        # diagonal A becomes A*(1 + cfm) + cfm), so they agree for a unit effective mass
        self.cfm = max(world.constant_force_mix / (2.0 * dt), 1e-9)  # DART warns and clamps below 1e-9
        self.moving = [k for k, s in enumerate(self.skeletons) if s.getNumDofs() > 0]
        self.set_loads(b.forces, b.torques)
        self.set_velocities(b.linear_velocity, b.angular_velocity)

    # -- building -----------------------------------------------------------
    def _body(self, node: dart.dynamics.BodyNode, i: int) -> None:
        b = self.world.bodies
        node.setName(f"b{i}")
        node.setInertia(dart.dynamics.Inertia(float(b.mass[i]), b.com[i], b.inertia[i]))
        node.setGravityMode(bool(b.use_gravity[i]))
        self.nodes[i] = node

    def _fixed(self, i: int) -> None:
        """A fixed body: its own skeleton, welded to the world at its pose, immobile."""
        b = self.world.bodies
        skeleton = dart.dynamics.Skeleton(f"fixed{i}")
        joint, node = skeleton.createWeldJointAndBodyNodePair(None)
        joint.setTransformFromParentBodyNode(_isometry(b.orientation[i], b.position[i]))
        self._body(node, i)
        # no degrees of freedom, so nothing moves it; left "mobile" because DART never tests
        # two immobile skeletons against each other, and x3d_core tests a fixed body's
        # geometry against the static environment's (contacts that move nothing)
        self.skeletons.append(skeleton)
        self.members.append([i])

    def _collide(self, c: Collisions) -> None:
        """A ShapeNode per geometry (colliding, with the collection's friction and bounce), the
        Bullet detector, and the pairs x3d_core's may_touch rules out blacklisted."""
        self.dart_world.setCollisionDetector(dart.collision.BulletCollisionDetector())
        static = None
        if any(g.body == STATIC for g in c.geometries):
            skeleton = dart.dynamics.Skeleton("static")
            _, static = skeleton.createWeldJointAndBodyNodePair(None)
            static.setName("static")
            skeleton.setMobile(False)
            self.dart_world.addSkeleton(skeleton)
        p = c.parameters
        mu, e = float(p.friction[0]), float(np.sqrt(p.bounce))  # DART: min(mu, mu) = mu, e * e = bounce
        for k, g in enumerate(c.geometries):
            node = static if g.body == STATIC else self.nodes[g.body]
            for n, (shape, turn) in enumerate(_shapes(g)):
                frame = _shape_node(node, shape, turn, g, f"g{k}" if n == 0 else f"g{k}.{n}")
                frame.createCollisionAspect()
                surface = frame.createDynamicsAspect()
                surface.setFrictionCoeff(mu)
                surface.setRestitutionCoeff(e)
                self.geometry_of[frame.getName()] = k
                self.split |= n > 0
        # bodies of one tree are one skeleton: test them against each other (DART's default
        # skips them all) and leave out exactly the joined pairs, as everywhere else
        for skeleton in self.skeletons:
            if skeleton.getNumBodyNodes() > 1:
                skeleton.enableSelfCollisionCheck()
                skeleton.enableAdjacentBodyCheck()
        keep_apart = self.dart_world.getConstraintSolver().getCollisionOption().collisionFilter  # shared
        for a, b in c.excluded:
            ends = [static if r == STATIC else self.nodes[r] for r in (a, b)]
            if ends[0] is not None and ends[1] is not None:
                keep_apart.addBodyNodePairToBlackList(*ends)

    def _tree_joint(self, skeleton: dart.dynamics.Skeleton, child: int, j: Joint) -> dart.dynamics.BodyNode:
        """The child's body node, joined to its parent (or the world) at the joint's anchor."""
        b = self.world.bodies
        p = self.world.parent[child]
        pp, pq = (np.zeros(3), R.IDENTITY) if p < 0 else (b.position[p], b.orientation[p])
        cq = R.conjugate(b.orientation[child])
        parent = None if p < 0 else self.nodes[p]
        axes = R.rotate(cq, j.axes)  # joint frame = the child's starting orientation
        sign = -1.0 if child == j.body2 else 1.0  # DART: child relative to parent
        to_parent = _isometry(R.multiply(R.conjugate(pq), b.orientation[child]),
                              R.rotate(R.conjugate(pq), j.anchor - pp))
        to_child = _isometry(R.IDENTITY, R.rotate(cq, j.anchor - b.position[child]))
        if j.type == "DoubleAxisHingeJoint":
            return self._hinge2(skeleton, parent, child, j, axes, sign, to_parent, to_child)
        if j.type == "BallJoint":
            joint, node = skeleton.createBallJointAndBodyNodePair(parent)
        elif j.type == "SingleAxisHingeJoint":
            joint, node = skeleton.createRevoluteJointAndBodyNodePair(parent)
            joint.setAxis(axes[0])
            self._limit(joint, 0, j.params["minAngle"], j.params["maxAngle"], sign, angular=True)
        elif j.type == "SliderJoint":
            joint, node = skeleton.createPrismaticJointAndBodyNodePair(parent)
            joint.setAxis(axes[0])
            if j.stops is not None:
                self._limit(joint, 0, *j.stops, sign, angular=False)
        elif j.type == "UniversalJoint":
            joint, node = skeleton.createUniversalJointAndBodyNodePair(parent)
            first, second = (axes[0], axes[1]) if child == j.body2 else (axes[1], axes[0])
            joint.setAxis1(first)  # fixed in the parent
            joint.setAxis2(second)  # carried by the child
        else:
            raise Unsupported(f"{j.type} {j.name}: not built by the dart backend yet")
        joint.setTransformFromParentBodyNode(to_parent)
        joint.setTransformFromChildBodyNode(to_child)
        return node

    def _hinge2(self, skeleton: dart.dynamics.Skeleton, parent: dart.dynamics.BodyNode | None, child: int, j: Joint,
                axes: np.ndarray, sign: float, to_parent: dart.math.Isometry3,
                to_child: dart.math.Isometry3) -> dart.dynamics.BodyNode:
        """ODE's hinge2: a hinge about axis 1 (carried by body1, with its limits and motor), a
        suspension spring along axis 1 (k = ERP/(h*CFM), c = (1-ERP)/CFM; none when
        suspensionForce is 0) and a hinge about axis 2 (carried by body2, with its motor).

        Degrees of freedom from the parent outwards, as in backends/mujoco.py: hinge 1,
        slide, hinge 2 when the child is body2; hinge 2, hinge 1, slide when it is body1.
        Without suspension the two hinges are one UniversalJoint; with it they are a chain of
        single-dof joints through bodies of _LINK_MASS times the child's mass (and inertia),
        without gravity. DART's joint spring is implicit, f = -k (q + h v') - c v' with v' the
        velocity after the step: ODE's soft constraint row, term for term."""
        p = j.params
        b = self.world.bodies
        spring = p["suspensionForce"] > 0
        order = [1, 0, 2] if child == j.body2 else [2, 1, 0]  # hinge number; 0: the suspension slide
        if not spring:
            order.remove(0)
            joint, node = skeleton.createUniversalJointAndBodyNodePair(parent)
            joint.setAxis1(axes[order[0] - 1])  # fixed in the parent
            joint.setAxis2(axes[order[1] - 1])  # carried by the child
            joint.setTransformFromParentBodyNode(to_parent)
            joint.setTransformFromChildBodyNode(to_child)
            dof = {k: (joint, n) for n, k in enumerate(order)}
        else:
            dof = {}
            link_inertia = _LINK_MASS * np.trace(b.inertia[child]) / 3 * np.eye(3)
            for n, k in enumerate(order):
                if k == 0:
                    joint, node = skeleton.createPrismaticJointAndBodyNodePair(parent)
                    joint.setAxis(axes[0])
                    cfm, erp = p["suspensionForce"], p["suspensionErrorCorrection"]
                    joint.setSpringStiffness(0, erp / (self.dt * cfm))
                    joint.setDampingCoefficient(0, (1 - erp) / cfm)
                    joint.setRestPosition(0, 0.0)
                else:
                    joint, node = skeleton.createRevoluteJointAndBodyNodePair(parent)
                    joint.setAxis(axes[k - 1])
                joint.setName(f"{j.name}:{k}")
                if n == 0:
                    joint.setTransformFromParentBodyNode(to_parent)
                if n < len(order) - 1:  # a link between two degrees of freedom, at the anchor
                    node.setName(f"{j.name}:link{n}")
                    node.setInertia(dart.dynamics.Inertia(_LINK_MASS * float(b.mass[child]), np.zeros(3),
                                                          link_inertia))
                    node.setGravityMode(False)
                    parent = node
                else:
                    joint.setTransformFromChildBodyNode(to_child)
                dof[k] = (joint, 0)
        joint, index = dof[1]
        self._limit(joint, index, p["minAngle1"], p["maxAngle1"], sign, angular=True)
        for k in (1, 2):
            if p[f"maxTorque{k}"] > 0:
                # its rate in joint space: the motor's axis against each hinge's (constant: each
                # hinge turns about its own axis, and the other hinge's axis is carried across it)
                row = [(dof[h][0], dof[h][1], float(axes[h - 1] @ axes[k - 1])) for h in (1, 2)]
                self.motors.append(_Motor(skeleton, row, sign * p[f"desiredAngularVelocity{k}"], p[f"maxTorque{k}"]))
        return node

    @staticmethod
    def _limit(joint: dart.dynamics.Joint, index: int, lo: float, hi: float, sign: float, angular: bool) -> None:
        if angular and lo <= -_FULL_TURN and hi >= _FULL_TURN:
            return
        a, b = sorted((sign * lo, sign * hi))
        joint.setPositionLowerLimit(index, a)
        joint.setPositionUpperLimit(index, b)
        joint.setLimitEnforcement(True)

    def _loop(self, j: Joint) -> list[dart.constraint.BallJointConstraint]:
        """A joint closing a loop, as ball-joint constraints between body nodes (anchors in
        world coordinates): one at the anchor and, for a hinge, one more a metre along its
        axis, as backends/mujoco.py does. DART's RevoluteJointConstraint is not used: it blew
        up a four-bar linkage and misplaced the axis of a turned body (measured)."""
        if j.body1 == j.body2:
            return []  # a body joined to itself, or the static environment to itself: nothing moves
        if j.type not in ("BallJoint", "SingleAxisHingeJoint"):
            raise Unsupported(f"{j.type} {j.name} closes a loop of joints; the dart backend closes loops "
                              "with BallJoint and SingleAxisHingeJoint only")
        ends = [self.nodes[r] for r in (j.body1, j.body2) if r != STATIC]
        points = [j.anchor] if j.type == "BallJoint" else [j.anchor, j.anchor + j.axes[0]]
        return [dart.constraint.BallJointConstraint(*ends, np.asarray(p, dtype=np.float64)) for p in points]

    # -- running ------------------------------------------------------------
    def step(self, n: int = 1) -> None:
        if self.loops:  # class-wide: another world may have set its own
            _LOOPS.setErrorReductionParameter(self.world.error_correction)
            _LOOPS.setConstraintForceMixing(self.cfm)
            _LOOPS.setMaxErrorReductionVelocity(np.inf)  # ODE does not cap joint error correction
        for _ in range(n):
            for node, force, com, torque in self.pushed:  # DART clears them after every step
                node.addExtForce(force, com, False, True)
                node.addExtTorque(torque, False)
            for drives in self.drives:  # after the loads: the motors answer them
                drives.command()
            self.dart_world.step()
            if self.geometry_of and self.dart_world.getLastCollisionResult().getNumContacts() >= _MAX_CONTACTS:
                raise BlewUp(f"{_MAX_CONTACTS} contacts in one step: DART's cap (not settable from Python) "
                             "leaves the others out")

    def contacts(self) -> ContactPoints:
        """DART's contacts of the last step, copied out at once (its objects must not outlive
        the world). DART's normal points from object 2 towards object 1: turned round."""
        if not self.geometry_of:
            return ContactPoints.none()
        return _points(self.dart_world.getLastCollisionResult(), self.geometry_of, self.split)

    def watched_contacts(self, k: int) -> ContactPoints:
        return self.watched[k].contacts()

    def state(self) -> State:
        n = len(self.nodes)
        m = np.empty((n, 4, 4))
        lin, ang = np.empty((n, 3)), np.empty((n, 3))
        for i, node in enumerate(self.nodes):
            m[i] = node.getWorldTransform().matrix()
            lin[i] = node.getCOMLinearVelocity()  # world coordinates
            ang[i] = node.getAngularVelocity()
        return State(m[:, :3, 3].copy(), R.from_matrix(m[:, :3, :3]), lin, ang)

    def set_velocities(self, linear: np.ndarray, angular: np.ndarray) -> None:
        """Per skeleton, the joint velocities whose body velocities come closest to those asked
        for: a least-squares fit through the world Jacobians at the centres of mass, exact
        for a free body."""
        com = self.world.bodies.com
        for k in self.moving:
            skeleton, rows = self.skeletons[k], self.members[k]
            if not (linear[rows].any() or angular[rows].any()):
                # at rest (every build of a scene that starts still): the fit's answer is +0.0 exactly
                # (LAPACK's gelsd sets x to zero for a zero right-hand side), without its least squares,
                # cubic in a chain's links
                skeleton.setVelocities(np.zeros(skeleton.getNumDofs()))
                continue
            jac = np.concatenate([skeleton.getWorldJacobian(self.nodes[i], com[i]) for i in rows])  # [ang; lin]
            target = np.concatenate([np.concatenate([angular[i], linear[i]]) for i in rows])
            skeleton.setVelocities(np.linalg.lstsq(jac, target, rcond=None)[0])

    def set_loads(self, forces: np.ndarray, torques: np.ndarray) -> None:
        """Kept and added before every step (DART clears external forces after each), to the
        bodies that get any: a force at the centre of mass, world frame."""
        b = self.world.bodies
        pushed = (np.abs(forces).sum(axis=1) + np.abs(torques).sum(axis=1) > 0) & ~b.fixed
        self.pushed = [(self.nodes[i], forces[i].copy(), b.com[i].copy(), torques[i].copy())
                       for i in np.flatnonzero(pushed)]


class DartBackend(Backend):
    name = "dart"
    integration = SEMI_IMPLICIT
    # measured (dartpy 6.20): a free body of 1e-308 kg (subnormal) stays where it is, 1e-307 falls
    limits = {"RigidBody.mass": below(SMALLEST_NORMAL, f"DART inverts the mass: under {SMALLEST_NORMAL:.4g} kg (a "
                                      "subnormal) the inverse overflows and the body would not move")}
    declared = {
        **native(*BODIES, *JOINTS, "RigidBody.useGlobalGravity"),
        **approximate("set on the loop constraints (DART's tree joints and predictive stops need none); DART's "
                      "contacts keep their own fixed ERP 0.01, correcting at most 1 mm/s (constants of its "
                      "ContactConstraint, which dartpy does not bind), where ODE corrects contacts by "
                      "errorCorrection too",
                      "RigidBodyCollection.errorCorrection"),
        **approximate("DART's CFM is relative to each constraint row (its diagonal A becomes A*(1+cfm)+cfm), "
                      "ODE's adds CFM/dt: converted as cfm = CFM/(2*dt), exact for a unit effective mass; "
                      "it acts on loop constraints only (tree joints are exact; contacts keep DART's fixed "
                      "1e-5, dartpy binds no setter)",
                      "RigidBodyCollection.constantForceMix"),
        # -- collisions (world.collisions): DART's Bullet detector, see the module's docstring
        **native("CollidableShape.geometry.Box", "CollidableShape.geometry.Sphere",
                 "CollidableShape.geometry.Cylinder", "CollidableShape.geometry.Cone",
                 # DART's own contact points (Bullet's: the point on geometry1's surface), copied out;
                 # a point several of a mesh's triangles report once
                 "CollisionSensor",
                 # a set only sensors watch: shapes no world collision group holds, in a group of its own (_Watched)
                 "CollisionSensor.collider.watchedOnly",
                 # resolved by x3d_core; each parameter it applies is declared below
                 "CollisionCollection.appliedParameters",
                 # these act only where appliedParameters names SLIP-n, SPEED-n, ERROR_REDUCTION or
                 # CONSTANT_FORCE (declared unsupported, so such a scene is refused): alone they have
                 # no effect, in ODE as here
                 "CollisionCollection.slipFactors", "CollisionCollection.surfaceSpeed",
                 "CollisionCollection.softnessErrorCorrection", "CollisionCollection.softnessConstantForceMix"),
        **approximate("DART's contacts: each step's contacts are found before it moves the bodies and stop the "
                      "approach in that step, so a body lands up to one step's travel (v*dt) deep; DART then "
                      "undoes penetration at its fixed contact ERP 0.01, at most 1 mm/s, without a surface layer "
                      "(ODE: errorCorrection, contactSurfaceThickness, maxCorrectionSpeed); dartpy binds none of "
                      "these. So a landing that stops dead stays up to v*dt deep (measured 1.1 cm from 0.5 m at "
                      "1/240 s), rising out at 1 mm/s; a body set down gently rests within g*dt^2. At most 1000 "
                      "contacts a step (DART's cap, not settable from Python): a run that reaches it stops as "
                      "blown up rather than drop contacts",
                      "CollisionCollection"),
        **approximate("each shape gets restitution sqrt(bounce) and DART multiplies the two: the rebound speed "
                      "is bounce times the approach speed of the contact step (measured within 6e-5 relative), a "
                      "speed that already holds that step's gravity g*dt, so a rebound is up to bounce*g*dt fast "
                      "(apex after a 1 m drop above bounce^2 m by 0.1, 5.1, 12.5 mm for bounce 0.2, 0.5, 0.8 at "
                      "1/240 s: about bounce^2*v*dt; with bounce 1 a ball "
                      "rises about v*dt higher each bounce: measured 2.9 cm from 2.4 m at 1/240 s, Xj3D's "
                      "ball_bounce). And DART bounces only "
                      "where bounce times the approach speed exceeds 0.1 m/s, a constant (ODE: the approach speed "
                      "exceeds minBounceSpeed, 0.1 m/s by default): impacts between the two thresholds differ",
                      "CollisionCollection.bounce", "CollisionCollection.appliedParameters.BOUNCE"),
        **unsupported("DART's bounce threshold is a constant of its ContactConstraint (it bounces where bounce "
                      "times the approach speed exceeds 0.1 m/s, measured), not settable from Python: "
                      "minBounceSpeed would have no effect",
                      "CollisionCollection.minBounceSpeed"),
        **approximate("each shape gets mu and DART takes the smaller of two, so every contact has exactly mu "
                      "(measured: a block slides down 30 and 45 degree inclines at g(sin - mu cos) within 2e-5 "
                      "relative, and sticks where tan <= mu, creeping under 0.1 mm while it settles). Friction "
                      "is a pyramid along two directions, as ODE's: DART's are ODE's own (negated) wherever the "
                      "normal's z component is at most sqrt(1/2) or the normal is along z, and turned about the "
                      "normal for other normals near z (sliding between the directions meets up to sqrt(2) mu in "
                      "both engines, along different diagonals there). DART turns friction off below mu = 1e-3",
                      "CollisionCollection.frictionCoefficients"),
        **unsupported("dartpy binds one friction coefficient per shape (DynamicsAspect.setFrictionCoeff sets "
                      "both directions), no second one",
                      "CollisionCollection.appliedParameters.FRICTION_COEFFICIENT-2"),
        **unsupported("dartpy binds no friction direction (DynamicsAspect.setFirstFrictionDirection)",
                      "CollisionCollection.appliedParameters.USER_FRICTION"),
        **unsupported("DART's slip compliance (ODE's force-dependent slip) is not bound in dartpy",
                      "CollisionCollection.appliedParameters.SLIP-1", "CollisionCollection.appliedParameters.SLIP-2"),
        **unsupported("DART 6 has no contact surface velocity reachable from Python",
                      "CollisionCollection.appliedParameters.SPEED-1", "CollisionCollection.appliedParameters.SPEED-2"),
        **unsupported("DART's contact ERP and CFM are fixed constants of its ContactConstraint (0.01 and 1e-5), "
                      "class-wide and not bound in dartpy: no per-collection softness",
                      "CollisionCollection.appliedParameters.ERROR_REDUCTION",
                      "CollisionCollection.appliedParameters.CONSTANT_FORCE"),
        **unsupported("DART's contacts allow no penetration before correcting (its ContactConstraint's error "
                      "allowance is 0, class-wide, not bound in dartpy)",
                      "RigidBodyCollection.contactSurfaceThickness"),
        **unsupported("DART's contacts correct penetration at most 1 mm/s, a constant of its ContactConstraint "
                      "not bound in dartpy", "RigidBodyCollection.maxCorrectionSpeed"),
        **approximate("a triangle soup, as ODE's trimesh: each triangle its own convex shape (DART's Bullet "
                      "detector takes a whole mesh's convex hull: measured, it held a ball at the top of a V "
                      "trough's hull); surfaces without volume, so a body moving more than its own thickness in "
                      "a step passes through; a ball rests in a V trough at r sqrt(2) (measured 4e-4 m deep, "
                      "DART's contact settling)",
                      "CollidableShape.geometry.IndexedFaceSet", "CollidableShape.geometry.IndexedTriangleSet",
                      "CollidableShape.geometry.TriangleSet"),
        **approximate("dartpy binds no HeightmapShape: the grid is a triangle soup, two triangles a cell (split "
                      "from point (i+1, j) to (i, j+1)), a surface without volume below it (ODE's heightfield "
                      "is solid below)",
                      "CollidableShape.geometry.ElevationGrid"),
        **approximate("DART solves the joint constraints (loops, limits) with a direct Dantzig LCP solver, "
                      "as if iterations were unlimited; tree joints need none",
                      "RigidBodyCollection.iterations"),
        **approximate("DART has one integrator (semi-implicit Euler) and its constraint solver is already "
                      "the accurate direct one: nothing to switch",
                      "RigidBodyCollection.preferAccuracy"),
        **native("DoubleAxisHingeJoint", "DoubleAxisHingeJoint.anchorPoint", "DoubleAxisHingeJoint.axis1",
                 "DoubleAxisHingeJoint.axis2", "DoubleAxisHingeJoint.limits", "DoubleAxisHingeJoint.minAngle1",
                 "DoubleAxisHingeJoint.maxAngle1"),
        **approximate("ODE's motor rows solved here before each step from DART's own next-step dynamics, "
                      "applied as joint forces: a motor reaches its target in one step when maxTorque allows "
                      "and ramps at maxTorque otherwise (measured exact), and leaves a stop a load presses it "
                      "on when it is the stronger; DART solves stops and loop constraints after, so in a step "
                      "where one acts on the same tree the motors answer its impulse a step late (ODE solves "
                      "them together)",
                      "DoubleAxisHingeJoint.desiredAngularVelocity1", "DoubleAxisHingeJoint.desiredAngularVelocity2",
                      "DoubleAxisHingeJoint.maxTorque1", "DoubleAxisHingeJoint.maxTorque2"),
        **approximate("a prismatic joint along axis 1 between the two hinges, with DART's implicit spring-damper "
                      "k = ERP/(h*CFM), c = (1-ERP)/CFM: ODE's soft row term for term (measured against its "
                      "recurrence to 1e-12 m), through links of 1e-12 the child's mass; DART's stop and loop "
                      "impulses move it without the spring-damper's implicit terms in their step",
                      "DoubleAxisHingeJoint.suspensionForce", "DoubleAxisHingeJoint.suspensionErrorCorrection"),
        **unsupported("DART's joint limits are hard constraints without a restitution coefficient",
                      "SingleAxisHingeJoint.stopBounce", "SliderJoint.stopBounce", "DoubleAxisHingeJoint.stop1Bounce"),
        **unsupported("DART's joint limits are predictive and exact (a step ends on the stop, measured); the "
                      "limit ERP has no effect, so a stop's error correction cannot be set",
                      "SingleAxisHingeJoint.stopErrorCorrection", "SliderJoint.stopErrorCorrection",
                      "DoubleAxisHingeJoint.stop1ErrorCorrection"),
        **unsupported("DART's joint limits are hard: their rows' CFM is one class-wide relative value (1e-9), "
                      "not a per-stop softness", "DoubleAxisHingeJoint.stop1ConstantForceMix"),
    }

    def version(self) -> str:
        return dart.__version__

    def build(self, world: World, dt: float) -> DartSimulation:
        b = world.bodies
        with np.errstate(over="ignore", invalid="ignore"):
            weight = b.mass * np.abs(world.gravity).max(initial=0.0) * b.use_gravity
        heavy = np.flatnonzero(~np.isfinite(weight) & ~b.fixed)
        if len(heavy):  # measured: 1e308 kg under 9.8 m/s^2 stays where it is, 1e307 kg falls
            i = int(heavy[0])
            raise Unsupported(f"RigidBody {b.names[i]}: mass {b.mass[i]:g} under gravity {world.gravity.tolist()}: "
                              "its weight overflows, and DART zeroes a non-finite force (the body would not fall)")
        return DartSimulation(world, dt)


BACKEND = DartBackend()

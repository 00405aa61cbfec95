"""pybullet backend: joints become multibody trees; ball joints closing loops become constraints.

Each tree of the world's joint forest is one multibody, in a DIRECT client of its own
per simulation: a free root is a free base, a root hanging from the static environment
is a link of a massless (so fixed) base at the world origin, and a body whose parent
joint is in the tree is a link with that joint's degrees of freedom (spherical,
revolute, prismatic; a universal joint or a hinge2 is two revolute links through a
massless link). A link's frame sits at the joint's anchor, turned as its body is at the
start, so the body frame is a fixed offset in it. pybullet measures a child's joint
coordinate relative to its parent; x3d_core's outputs measure body1 relative to body2,
so limits and motor targets are mirrored where the child is body2. pybullet reports
each link's centre of mass and principal axes (its link frame poses only in single
precision): state() turns them back into the body frame's origin and orientation, with
the centre of mass's velocity, for every body in one pass.

pybullet facts this relies on (measured with pybullet 3.2.7):
createMultiBody's linkParentIndices count the base as 0; its joints carry velocity
motors that hold them still until given zero force; multibodies are damped and joint
speeds clamped to 100 rad/s by default; a free base or a ball joint turns at most pi/4
per step (faster spins are clamped: 188 rad/s at dt = 1/240; state() calls one blown up),
a revolute joint exactly;
a multibody's links hold at most 122 degrees of freedom that read back right (_MAX_LINK_DOFS).

Collisions (where the world has a collider): a moving body's first geometry is its link's
collision shape, each further one rides on a massless link fixed to it, so contact points
name their geometry exactly; a static geometry (or a fixed body's) is a massless multibody
of its own. pybullet makes a fixed link static when the joints between it and link 0 are fixed,
never testing link 0's own, so a root body hanging from the static environment with further
shapes sits behind a massless link 0 fixed to the base: its further shapes would pass through
every static shape and each other (x_ite_media/SingleAxisHingeJoint.x3d's pendulums gained
13-fold). Links of one multibody collide (self collision on; pybullet never tests a link
against its parent, which is a joint anyway); the plan's other excluded pairs are filtered
pair by pair. Contact parameters are per body and pybullet combines them: friction and
restitution multiply (every shape gets the square root), contact springs go in series and
dampers add (every shape gets 2k and c/2). Measured: collision shape frames are relative to
the link frame (not the inertial frame); pybullet ignores a heightfield's frame; convex
hulls collide a margin (1 mm unless changed) outside their points, boxes and cylinders
within theirs (edges rounded by it); createCollisionShapeArray takes no vertices; friction
is a pyramid along btPlaneSpace1's directions, ODE's, once cone friction is off; restitution
needs a contactProcessingThreshold under the way a bouncing body goes in one step (a contact
taken before it touches is speculative, and brought to rest: _processing) and no contact ERP
(which it would add to). A set only sensors watch (world.watched) is shapes in no body, tested
by pybullet's shape query where the bodies are at each frame's end (_Watched).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from itertools import chain

import numpy as np
import pybullet as p

from x3d_core.semantics import rotation as R
from x3d_core.semantics.collision import Collisions, ContactPoints, friction_directions
from x3d_core.semantics.engine import BlewUp, Unsupported
from x3d_core.semantics.world import STATIC, Joint, State, World

from .base import BODIES, JOINTS, SEMI_IMPLICIT, Backend, in_substeps, approximate, native, unsupported

_FULL_TURN = np.pi - 1e-9  # an angle range this wide is no limit at all
# pybullet clamps joint speeds to 100 rad/s unless told otherwise; the clamp set instead holds every
# generalized velocity component (a free base's too: measured, gravity -1e308 stops at -1e6 m/s), so
# state() calls a body at it blown up
_MAX_SPEED = 1e6
# Bullet's integrateTransform turns a free base or a ball joint at most pi/4 per step (its
# ANGULAR_MOTION_THRESHOLD) whatever the angular velocity: measured, a ball spinning at 1000 rad/s
# at dt = 1/240 turns 2.29 rad in 1/60 s, not 2.12
_MAX_TURN = np.pi / 4
# pybullet takes a free body lighter than this (DBL_EPSILON) as static: measured, a body of
# 2.2e-16 kg stays where it is, one of 2.3e-16 kg falls
_MIN_FREE_MASS = float(np.finfo(np.float64).eps)
_MAX_FORCE = 1e12  # a loop constraint's impulse bound (pybullet's default is 500 N)
_SUBSTEPS_ACCURATE = 4  # internal steps per step when preferAccuracy asks for more
# the gap within which pybullet's solver takes a contact point (its contactProcessingThreshold): 0
# (as restitution needs, against speculative contacts) lets a resting contact drop out whenever
# rounding makes its distance positive, and the body fall for a step; 0.1 mm keeps it
_PROCESSING = 1e-4
_PROCESSING_FLOOR = 1e-6  # ... and the least it is made where contacts bounce (below)
_THIN = 1e-6  # the least size a collision shape gets (pybullet refuses empty ones)
_HULL_MARGIN = 1e-4  # the collision margin of convex hulls: they collide this far outside their vertices
_CONE_SIDES = 64  # a cone is the convex hull of a 64-gon and its apex
# pybullet's state read-back holds 128 degrees of freedom a multibody (MAX_DEGREE_OF_FREEDOM), 6 of
# them the base's: past 122 in its links it reports wrong link states, or refuses a joint index
# (measured: 40 ball joints or 122 hinges read back exactly, 41 or 123 do not)
_MAX_LINK_DOFS = 122
_Z_TO_Y = np.array([np.cos(-np.pi / 4), np.sin(-np.pi / 4), 0.0, 0.0])  # turns pybullet's z axis to X3D's y


def _xyzw(q: np.ndarray) -> list[float]:
    return [float(q[1]), float(q[2]), float(q[3]), float(q[0])]


def _wxyz(q: np.ndarray) -> np.ndarray:
    """pybullet's (x, y, z, w) quaternions, in bulk, as x3d_core's (w, x, y, z)."""
    return np.asarray(q, dtype=np.float64)[..., [3, 0, 1, 2]]


def _principal(inertia: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Principal moments and the principal frame's orientation in the body frame: pybullet
    takes a diagonal inertia in a turned inertial frame, not a full tensor."""
    if not np.any(inertia - np.diag(np.diag(inertia))):  # already principal: keep the body's axes
        return np.maximum(np.diag(inertia), 0.0), R.IDENTITY.copy()
    moments, axes = np.linalg.eigh(inertia)
    if np.linalg.det(axes) < 0:
        axes[:, 2] = -axes[:, 2]
    return np.maximum(moments, 0.0), R.from_matrix(axes[None])[0]


def _angle_limits(lo: float, hi: float, sign: float) -> tuple[float, float] | None:
    """A hinge's stops as pybullet's joint range (None: no stops), mirrored when sign is -1."""
    if lo <= -_FULL_TURN and hi >= _FULL_TURN:
        return None
    return tuple(sorted((sign * lo, sign * hi)))


def _cone(radius: float, height: float) -> np.ndarray:
    """A cone's hull points: X3D's cone, axis y, apex at +height/2, base at -height/2."""
    a = 2 * np.pi * np.arange(_CONE_SIDES) / _CONE_SIDES
    rim = np.stack([radius * np.cos(a), np.full(_CONE_SIDES, -height / 2), radius * np.sin(a)], axis=1)
    return np.vstack([rim, [[0.0, height / 2, 0.0]]])


def _spacing(g) -> tuple[float, float]:
    """An elevation grid's xSpacing and zSpacing, from its grid points."""
    nx = g.grid[0]
    return float(g.vertices[1, 0] - g.vertices[0, 0]), float(g.vertices[nx, 2] - g.vertices[0, 2])


def _grid_centre(g) -> np.ndarray:
    """Where pybullet centres an elevation grid's heightfield, in the grid's frame: pybullet ignores
    a heightfield's frame, so what holds it is posed there, turned by _Z_TO_Y."""
    nx, nz = g.grid
    xs, zs = _spacing(g)
    heights = g.vertices[:, 1]
    return np.array([(nx - 1) * xs / 2, (heights.min() + heights.max()) / 2, (nz - 1) * zs / 2])


def _friction_frame(up: np.ndarray) -> np.ndarray:
    """The orientation whose y is the unit normal up and whose z and x are ODE's second and (but for
    its sign) first friction directions for that normal."""
    _, second = friction_directions(up)
    axes = np.stack([np.cross(up, second[0]), up, second[0]], axis=1)
    return R.from_matrix(axes[None])[0]


def _processing(world: World, h: float) -> float:
    """pybullet's contactProcessingThreshold for the world, at internal step h: _PROCESSING, or where
    contacts bounce, less than half the way a bouncing approach (at minBounceSpeed or faster) goes
    in one step. A contact taken before it touches is a speculative one, which pybullet's solver
    brings to rest at the surface with no restitution: measured, bounce_apex's e = 0.8 ball rose
    0.345 m after its first bounce at dt 1/32000 (preferAccuracy's 4 substeps), against 0.691 m at
    1/1920; 0.690 m with this threshold."""
    col = world.collisions
    if col is None or col.parameters.bounce <= 0:
        return _PROCESSING
    return max(_PROCESSING_FLOOR, min(_PROCESSING, 0.5 * col.parameters.min_bounce_speed * h))


def _skew(v: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


@dataclass
class _Part:
    """A free base or one link of a multibody: what createMultiBody takes, and what reading it back needs."""
    row: int  # body row, or -1 for the massless link between two hinges
    parent: int  # the parent part, -1 for none (a free base, or a link on a fixed base)
    joint_type: int  # p.JOINT_FIXED for a free base
    axis: np.ndarray  # in the link frame
    position: np.ndarray  # link frame in the parent's link frame (for a base: in the world)
    orientation: np.ndarray  # w x y z
    offset: np.ndarray  # the body frame's origin in the link frame (the link frame is turned as the body)
    inertial: np.ndarray  # the centre of mass in the link frame
    principal: np.ndarray  # the principal axes in the link frame (the inertial frame's orientation)
    mass: float
    moments: np.ndarray  # principal moments of inertia
    limits: tuple[float, float] | None = None
    motor: tuple[float, float] | None = None  # target joint velocity, torque limit
    shape: int = -1  # pybullet collision shape, -1 for none
    geometry: int = -1  # the index in world.collisions.geometries that shape is


def _pad() -> _Part:
    """A massless link without a shape, fixed to a fixed base at the world origin (see _place)."""
    return _Part(row=-1, parent=-1, joint_type=p.JOINT_FIXED, axis=np.array([0.0, 0.0, 1.0]), position=np.zeros(3),
                 orientation=R.IDENTITY.copy(), offset=np.zeros(3), inertial=np.zeros(3), principal=R.IDENTITY.copy(),
                 mass=0.0, moments=np.zeros(3))


@dataclass
class _Tree:
    """One multibody: a free body as its base (parts[0]), or a fixed base at the world origin."""
    free: bool
    parts: list[_Part] = field(default_factory=list)
    uid: int = -1
    dofs: int = 0  # generalized velocities, the free base's six included
    columns: list[int] = field(default_factory=list)  # each part's first velocity column

    @property
    def links(self) -> list[_Part]:
        return self.parts[1:] if self.free else self.parts

    def link(self, part: int) -> int:
        """pybullet's link index of a part (-1: the base)."""
        return part - 1 if self.free else part

    def joints(self, part: int) -> list[int]:
        """The parts whose joints move this one: itself and its ancestors, base excluded."""
        out = []
        while part >= 0 and self.parts[part].joint_type != p.JOINT_FIXED:
            out.append(part)
            part = self.parts[part].parent
        return out


class _Watched:
    """A set only sensors watch (world.watched): a collision shape per geometry in no body, so the
    simulation never meets it, tested where the bodies are by pybullet's shape query
    (getClosestPoints on two shapes at given poses), every pair may_touch allows, once a frame."""

    def __init__(self, sim: BulletSimulation, c: Collisions):
        b = sim.world.bodies
        self.collisions = c
        still = [g.body == STATIC or bool(b.fixed[g.body]) for g in c.geometries]
        self.shapes = [sim._shape(g, np.zeros(3), R.IDENTITY, moving=not s) for g, s in zip(c.geometries, still)]
        grid = [g.kind == "heightfield" and s for g, s in zip(c.geometries, still)]  # posed as _contacts_setup does
        self.shift = np.array([_grid_centre(g) if on else np.zeros(3) for g, on in zip(c.geometries, grid)]).reshape(-1, 3)
        self.turn = np.array([_Z_TO_Y if on else R.IDENTITY for on in grid]).reshape(-1, 4)
        i, j = np.triu_indices(len(c.geometries), 1)
        kept = c.may_touch(i, j)
        self.pairs = list(zip(i[kept].tolist(), j[kept].tolist()))

    def contacts(self, client: int, s: State) -> ContactPoints:
        """The points where two of the set's shapes meet in state s (lower index first, the
        normal from it towards the other, depth minus pybullet's distance), as contacts() reads them."""
        position, orientation = self.collisions.placed(s)
        where = (position + R.rotate(orientation, self.shift)).tolist()
        turned = R.multiply(orientation, self.turn)[:, [1, 2, 3, 0]].tolist()  # pybullet's x y z w
        shapes, rows = self.shapes, []
        for a, b in self.pairs:
            for cp in p.getClosestPoints(-1, -1, 0.0, collisionShapeA=shapes[a], collisionShapeB=shapes[b],
                                         collisionShapePositionA=where[a], collisionShapePositionB=where[b],
                                         collisionShapeOrientationA=turned[a], collisionShapeOrientationB=turned[b],
                                         physicsClientId=client):
                rows.append((a, b, *cp[5], *cp[6], *cp[7], -cp[8]))  # cp[7]: on B, from B towards A
        if not rows:
            return ContactPoints.none()
        m = np.array(rows, dtype=np.float64)
        return ContactPoints(position=(m[:, 2:5] + m[:, 5:8]) / 2, normal=-m[:, 8:11], depth=m[:, 11],
                             geometry1=m[:, 0].astype(int), geometry2=m[:, 1].astype(int))


class BulletSimulation:
    def __init__(self, world: World, dt: float):
        self.world = world
        b = world.bodies
        self.client = p.connect(p.DIRECT)
        c = self.client
        p.setGravity(*world.gravity, physicsClientId=c)
        # erp corrects joint limits by a velocity that stays once the depth is gone: a limit reached a
        # step late sends the body back at erp x depth / h, with stopBounce 0 too (slider_stops fails
        # here: docs/spec-loose-ends.md, 13); split impulse, which would take it off, leaves a multibody
        # limit's depth uncorrected (measured: a slider 5 mm past its stop stays there)
        p.setPhysicsEngineParameter(
            fixedTimeStep=dt, numSubSteps=_SUBSTEPS_ACCURATE if world.prefer_accuracy else 0,
            numSolverIterations=max(1, world.iterations), erp=world.error_correction, useSplitImpulse=0,
            physicsClientId=c)
        self.trees: list[_Tree] = []
        self.where: dict[int, tuple[int, int]] = {}  # body row -> (tree, part)
        self.frames: dict[int, tuple[np.ndarray, np.ndarray]] = {}  # body row -> its link frame at the start
        for i in world.order:
            if not b.fixed[i]:
                self._place(i)
        self.dt = dt
        self.processing = _processing(world, dt / (_SUBSTEPS_ACCURATE if world.prefer_accuracy else 1))
        self.geometry_at: dict[tuple[int, int], int] = {}  # (multibody, link) -> geometry index
        self.objects: dict[int, list[tuple[int, int]]] = {}  # body row (STATIC too) -> its (multibody, link)s
        self.hulls: set[int] = set()  # collision shapes that are convex hulls
        self.hull_objects: set[tuple[int, int]] = set()
        self.second_axis: dict[int, int] = {}  # static geometry -> its body's axis along ODE's second direction
        if world.collisions is not None:
            self._shapes()
        for tree in self.trees:
            self._create(tree)
        # what _read asks pybullet of each tree, worked out once: its multibody, whether its base is
        # free, its link indices (None: no links)
        self.reading = [(tree.uid, tree.free, list(range(len(tree.links))) if tree.links else None)
                        for tree in self.trees]
        # every part of every tree, flat, in the order _read returns them
        parts = [pt for tree in self.trees for pt in tree.parts]
        self.first = np.cumsum([0] + [len(tree.parts) for tree in self.trees])  # each tree's first part
        self.rows = np.array([pt.row for pt in parts], dtype=int)
        self.bodies = self.rows >= 0
        # the parts pybullet turns at most pi/4 a step (a free base, a ball joint's child), and what
        # each turns relative to (a ball joint's parent part; -1: the world)
        turning = np.array([(self.first[t] + k, self.first[t] + pt.parent if pt.parent >= 0 else -1)
                            for t, tree in enumerate(self.trees) for k, pt in enumerate(tree.parts)
                            if (tree.free and k == 0) or pt.joint_type == p.JOINT_SPHERICAL], dtype=int).reshape(-1, 2)
        self.turning, self.turning_from = turning[:, 0], turning[:, 1]
        self.unturn = R.conjugate(np.array([pt.principal for pt in parts]).reshape(-1, 4))
        self.inertial = np.array([pt.inertial for pt in parts]).reshape(-1, 3)
        self.offset = np.array([pt.offset for pt in parts]).reshape(-1, 3)
        # per frame: the body origin is the centre of mass less the turned local offset between
        # them; most scenes have neither a turned principal frame nor an offset, and skip the maths
        self.turned = bool(np.any(self.unturn != R.IDENTITY))
        self.com_local = self.inertial - self.offset
        self.shifted = bool(np.any(self.com_local))
        self.static_anchor: int | None = None
        for k in world.loop_joints:
            self._loop(world.joints[k])
        if world.collisions is not None:
            self._contacts_setup()
        self.watched = [_Watched(self, c) for c in world.watched]
        self.moving = np.flatnonzero(~b.fixed)
        with np.errstate(over="ignore", invalid="ignore"):  # an overflowing weight blows up as a non-finite state
            self.weight = -b.mass[:, None] * world.gravity * ~b.use_gravity[:, None]  # cancels gravity where it is off
        self.set_loads(b.forces, b.torques)
        self.set_velocities(b.linear_velocity, b.angular_velocity)

    # -- building -----------------------------------------------------------
    def _place(self, i: int) -> None:
        """Body i as the base or a link of a tree, after its parent."""
        w, b = self.world, self.world.bodies
        parent = int(w.parent[i])
        moments, principal = _principal(b.inertia[i])
        q = b.orientation[i]
        if parent == World.FREE:
            if 0 < b.mass[i] < _MIN_FREE_MASS:
                raise Unsupported(f"RigidBody {b.names[i]}: mass {b.mass[i]:g}: pybullet takes a free body lighter "
                                  f"than {_MIN_FREE_MASS:.4g} kg as static (it would not move)")
            self.trees.append(_Tree(free=True, parts=[_Part(
                row=i, parent=-1, joint_type=p.JOINT_FIXED, axis=np.zeros(3), position=b.position[i], orientation=q,
                offset=np.zeros(3), inertial=b.com[i], principal=principal, mass=b.mass[i], moments=moments)]))
            self.where[i] = (len(self.trees) - 1, 0)
            self.frames[i] = (b.position[i], q)
            return
        j = w.joints[w.parent_joint[i]]
        if parent == STATIC:
            col = w.collisions
            shapes = 0 if col is None else sum(g.body == i for g in col.geometries)
            # pybullet flags a fixed-joint link static when every joint between it and link 0 is fixed,
            # never testing link 0's own (URDF2Bullet's `while (testLinkIndex > 0)`): a further shape
            # of a root body on link 0 would be static, and two static objects never touch. A massless,
            # shapeless link 0 fixed at the origin keeps the root's joint inside that test.
            self.trees.append(_Tree(free=False, parts=[_pad()] if shapes > 1 else []))
            t, parent_part = len(self.trees) - 1, len(self.trees[-1].parts) - 1
            ppos, pq = np.zeros(3), R.IDENTITY
        else:
            t, parent_part = self.where[parent]
            ppos, pq = self.frames[parent]
        tree = self.trees[t]
        cq = R.conjugate(q)
        offset = R.rotate(cq, b.position[i] - j.anchor)
        axes = R.rotate(cq, j.axes)
        sign = -1.0 if i == j.body2 else 1.0  # pybullet: child relative to parent
        link = dict(row=i, parent=parent_part, position=R.rotate(R.conjugate(pq), j.anchor - ppos),
                    orientation=R.multiply(R.conjugate(pq), q), offset=offset, inertial=offset + b.com[i],
                    principal=principal, mass=b.mass[i], moments=moments)
        par = j.params
        if j.type == "BallJoint":
            tree.parts.append(_Part(joint_type=p.JOINT_SPHERICAL, axis=np.array([0.0, 0.0, 1.0]), **link))
        elif j.type == "SingleAxisHingeJoint":
            tree.parts.append(_Part(joint_type=p.JOINT_REVOLUTE, axis=axes[0],
                                    limits=_angle_limits(par["minAngle"], par["maxAngle"], sign), **link))
        elif j.type == "SliderJoint":
            limits = None if j.stops is None else tuple(sorted(sign * s for s in j.stops))
            tree.parts.append(_Part(joint_type=p.JOINT_PRISMATIC, axis=axes[0], limits=limits, **link))
        elif j.type in ("UniversalJoint", "DoubleAxisHingeJoint"):
            if par.get("suspensionForce", 0.0) > 0:
                raise Unsupported(f"{j.type} {j.name}: suspensionForce (a soft joint) is not built by the bullet "
                                  "backend: pybullet's multibody joints have no compliance")
            hinges = [{"axis": axes[0]}, {"axis": axes[1]}]  # axis1 is carried by body1, axis2 by body2
            if j.type == "DoubleAxisHingeJoint":
                hinges[0]["limits"] = _angle_limits(par["minAngle1"], par["maxAngle1"], sign)
                for k, h in enumerate(hinges, 1):
                    if par[f"maxTorque{k}"] > 0:  # ODE's motor: a velocity constraint of bounded torque
                        h["motor"] = (sign * par[f"desiredAngularVelocity{k}"], par[f"maxTorque{k}"])
            first, second = hinges if i == j.body2 else hinges[::-1]  # the parent's hinge first
            # the link between the hinges is massless: two hinges in series, as in MuJoCo's body with two joints
            tree.parts.append(_Part(**{**link, "row": -1, "offset": np.zeros(3), "inertial": np.zeros(3),
                                       "principal": R.IDENTITY, "mass": 0.0, "moments": np.zeros(3)},
                                    joint_type=p.JOINT_REVOLUTE, **first))
            link.update(parent=len(tree.parts) - 1, position=np.zeros(3), orientation=R.IDENTITY)
            tree.parts.append(_Part(joint_type=p.JOINT_REVOLUTE, **link, **second))
        else:
            raise Unsupported(f"{j.type} {j.name}: not built by the bullet backend yet")
        self.where[i] = (t, len(tree.parts) - 1)
        self.frames[i] = (j.anchor, q)

    def _create(self, tree: _Tree) -> None:
        c = self.client
        base = tree.parts[0] if tree.free else None
        links = tree.links
        dofs = sum({p.JOINT_SPHERICAL: 3, p.JOINT_REVOLUTE: 1, p.JOINT_PRISMATIC: 1}.get(lk.joint_type, 0)
                   for lk in links)
        if dofs > _MAX_LINK_DOFS:
            raise Unsupported(f"a tree of joints with {dofs} degrees of freedom: pybullet reads back at most "
                              f"{_MAX_LINK_DOFS} in one multibody's links (its MAX_DEGREE_OF_FREEDOM)")
        tree.uid = p.createMultiBody(
            baseMass=base.mass if base else 0.0, baseCollisionShapeIndex=base.shape if base else -1,
            baseVisualShapeIndex=-1,
            basePosition=base.position if base else [0, 0, 0],
            baseOrientation=_xyzw(base.orientation if base else R.IDENTITY),
            baseInertialFramePosition=base.inertial if base else [0, 0, 0],
            baseInertialFrameOrientation=_xyzw(base.principal if base else R.IDENTITY),
            linkMasses=[lk.mass for lk in links], linkCollisionShapeIndices=[lk.shape for lk in links],
            linkVisualShapeIndices=[-1] * len(links), linkPositions=[lk.position for lk in links],
            linkOrientations=[_xyzw(lk.orientation) for lk in links],
            linkInertialFramePositions=[lk.inertial for lk in links],
            linkInertialFrameOrientations=[_xyzw(lk.principal) for lk in links],
            linkParentIndices=[tree.link(lk.parent) + 1 for lk in links],  # pybullet counts the base as 0 here
            linkJointTypes=[lk.joint_type for lk in links], linkJointAxis=[lk.axis for lk in links],
            # links of one multibody collide only when asked (parent and child never do)
            flags=p.URDF_USE_SELF_COLLISION if self.world.collisions is not None else 0, physicsClientId=c)
        if tree.uid < 0:
            raise Unsupported("pybullet refused to build a multibody")
        # pybullet damps multibodies and clamps their joint speeds by default
        p.changeDynamics(tree.uid, -1, linearDamping=0.0, angularDamping=0.0, maxJointVelocity=_MAX_SPEED,
                         physicsClientId=c)
        for k, part in enumerate(tree.parts):
            link = tree.link(k)
            tree.columns.append(tree.dofs)
            # without a collision shape a body has no inertia until given one, with its mass alongside
            p.changeDynamics(tree.uid, link, mass=part.mass, localInertiaDiagonal=part.moments, physicsClientId=c)
            if link < 0:
                tree.dofs += 6
                continue
            p.changeDynamics(tree.uid, link, jointDamping=0.0, physicsClientId=c)
            if part.limits is not None:
                p.changeDynamics(tree.uid, link, jointLowerLimit=part.limits[0], jointUpperLimit=part.limits[1],
                                 physicsClientId=c)
            if part.joint_type == p.JOINT_FIXED:  # a further collision shape of its parent's body
                continue
            if part.joint_type == p.JOINT_SPHERICAL:  # createMultiBody's joint motors hold every joint still
                p.setJointMotorControlMultiDof(tree.uid, link, p.POSITION_CONTROL, targetPosition=[0, 0, 0, 1],
                                               force=[0, 0, 0], physicsClientId=c)
                tree.dofs += 3
            else:
                target, limit = part.motor or (0.0, 0.0)
                p.setJointMotorControl2(tree.uid, link, p.VELOCITY_CONTROL, targetVelocity=target, force=limit,
                                        physicsClientId=c)
                tree.dofs += 1

    def _loop(self, j: Joint) -> None:
        """A ball joint closing a loop, as a point-to-point constraint (pybullet's createConstraint
        refuses revolute and spherical joints). Its pivots are in the centre-of-mass frames."""
        if j.body1 == j.body2 == STATIC:
            return  # it joins the static environment to itself: nothing moves
        if j.type != "BallJoint":
            raise Unsupported(f"{j.type} {j.name} closes a loop of joints; the bullet backend closes loops "
                              "with BallJoint only (pybullet's createConstraint refuses revolute joints)")
        ends, pivots = [], []
        com, q_com, _, _ = self._read(velocities=False)
        for row in (j.body1, j.body2):
            if row == STATIC:  # pybullet refuses a constraint from a free body to the world itself
                if self.static_anchor is None:
                    self.static_anchor = p.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=-1,
                                                           physicsClientId=self.client)
                ends.append((self.static_anchor, -1))
                pivots.append(j.anchor)
                continue
            t, k = self.where[row]
            n = self.first[t] + k
            ends.append((self.trees[t].uid, self.trees[t].link(k)))
            pivots.append(R.rotate(R.conjugate(q_com[n]), j.anchor - com[n]))
        cid = p.createConstraint(*ends[0], *ends[1], p.JOINT_POINT2POINT, [0, 0, 0], pivots[0], pivots[1],
                                 physicsClientId=self.client)
        p.changeConstraint(cid, maxForce=_MAX_FORCE, physicsClientId=self.client)

    # -- collisions ---------------------------------------------------------
    def _shapes(self) -> None:
        """Every moving body's collision shapes: its first geometry on its own link (at the geometry's
        pose in the link frame), each further one on a massless link fixed to it, so that pybullet's
        contact points name the geometry itself (createCollisionShapeArray takes no vertices)."""
        col = self.world.collisions
        for gi, g in enumerate(col.geometries):
            if g.body == STATIC or self.world.bodies.fixed[g.body]:
                continue
            t, k = self.where[g.body]
            tree = self.trees[t]
            part = tree.parts[k]
            position = part.offset + g.position  # the link frame is turned as the body, at its offset
            if part.shape < 0:
                part.shape, part.geometry = self._shape(g, position, g.orientation, moving=True), gi
                continue
            tree.parts.append(_Part(
                row=-1, parent=k, joint_type=p.JOINT_FIXED, axis=np.array([0.0, 0.0, 1.0]), position=position,
                orientation=g.orientation, offset=np.zeros(3), inertial=np.zeros(3), principal=R.IDENTITY.copy(),
                mass=0.0, moments=np.zeros(3), shape=self._shape(g, np.zeros(3), R.IDENTITY, moving=True),
                geometry=gi))

    def _shape(self, g, position: np.ndarray, orientation: np.ndarray, moving: bool) -> int:
        """A pybullet collision shape for one geometry, posed in its link frame (but a static elevation
        grid: pybullet ignores a heightfield's frame, so _contacts_setup poses its body instead)."""
        kw: dict = {}
        turn = orientation
        if g.kind == "box":
            kw = dict(shapeType=p.GEOM_BOX, halfExtents=(np.maximum(g.size, _THIN) / 2).tolist())
        elif g.kind == "sphere":
            kw = dict(shapeType=p.GEOM_SPHERE, radius=max(float(g.size[0]), _THIN))
        elif g.kind == "cylinder":  # pybullet's cylinder axis is its z, X3D's is y
            kw = dict(shapeType=p.GEOM_CYLINDER, radius=max(float(g.size[0]), _THIN),
                      height=max(float(g.size[1]), _THIN))
            turn = R.multiply(orientation, _Z_TO_Y)
        elif g.kind == "cone":
            kw = dict(shapeType=p.GEOM_MESH, vertices=_cone(float(g.size[0]), float(g.size[1])).tolist())
        elif g.kind == "mesh" and not moving:  # static: the triangles themselves
            kw = dict(shapeType=p.GEOM_MESH, vertices=g.vertices.tolist(), indices=g.triangles.ravel().tolist(),
                      flags=p.GEOM_FORCE_CONCAVE_TRIMESH)
        elif g.kind == "heightfield" and not moving:
            nx, nz = g.grid
            heights = g.vertices[:, 1].reshape(nz, nx)
            # pybullet's heightfield: heights along its z, rows (x) and columns (y) centred on its bounds;
            # turned so that its z is X3D's y, its y is X3D's -z, so the columns run backwards
            kw = dict(shapeType=p.GEOM_HEIGHTFIELD, meshScale=[*_spacing(g), 1.0],
                      heightfieldData=heights[::-1].ravel().tolist(), numHeightfieldRows=nx, numHeightfieldColumns=nz)
        else:  # a mesh or an elevation grid on a moving body: pybullet collides its convex hull
            kw = dict(shapeType=p.GEOM_MESH, vertices=g.vertices.tolist())
        if kw["shapeType"] != p.GEOM_HEIGHTFIELD:
            kw.update(collisionFramePosition=np.asarray(position, dtype=float).tolist(),
                      collisionFrameOrientation=_xyzw(turn))
        shape = p.createCollisionShape(**kw, physicsClientId=self.client)
        if shape < 0:
            raise Unsupported(f"pybullet refused the collision shape of {g.name} ({g.kind})")
        if kw["shapeType"] == p.GEOM_MESH and "flags" not in kw:
            self.hulls.add(shape)
        return shape

    def _contacts_setup(self) -> None:
        """Static shapes as fixed multibodies, the pairs that never touch filtered out, and every
        collision object's contact parameters set so that pybullet's combinations of two bodies'
        values give the collection's own."""
        c, w, b = self.client, self.world, self.world.bodies
        col = w.collisions
        for tree in self.trees:
            for k, part in enumerate(tree.parts):
                if part.geometry >= 0:
                    self._object(tree.uid, tree.link(k), part.geometry, part.shape)
        for gi, g in enumerate(col.geometries):
            if g.body == STATIC:
                position, orientation = g.position, g.orientation
            elif b.fixed[g.body]:  # a fixed body's shapes: static, where the body is
                position = b.position[g.body] + R.rotate(b.orientation[g.body], g.position)
                orientation = R.multiply(b.orientation[g.body], g.orientation)
            else:
                continue
            up = R.rotate(orientation, np.array([0.0, 1.0, 0.0]))
            if g.kind == "heightfield":  # its frame is its body's
                shape = self._shape(g, np.zeros(3), R.IDENTITY, moving=False)
                position, frame = position + R.rotate(orientation, _grid_centre(g)), R.multiply(orientation, _Z_TO_Y)
                # the frame axis nearest ODE's second friction direction there takes mu2 (below)
                second = R.rotate(R.conjugate(frame), friction_directions(up)[1][0])
                self.second_axis[gi] = int(np.argmax(np.abs(second)))
            else:
                # the static body's frame: its y along the geometry's up, its z along ODE's second
                # friction direction there, the axis pybullet's anisotropic friction scales (mu2 below)
                frame = _friction_frame(up)
                shape = self._shape(g, np.zeros(3), R.multiply(R.conjugate(frame), orientation), moving=False)
            uid = p.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=shape, basePosition=position.tolist(),
                                    baseOrientation=_xyzw(frame), physicsClientId=c)
            if uid < 0:
                raise Unsupported(f"pybullet refused the static shape of {g.name}")
            self._object(uid, -1, gi, shape)
        # never together: shapes of one body (siblings on fixed links), bodies joined by a joint
        for row, objs in self.objects.items():
            if row != STATIC and not b.fixed[row]:
                for n, (ua, la) in enumerate(objs):
                    for ub, lb in objs[n + 1:]:
                        p.setCollisionFilterPair(ua, ub, la, lb, 0, physicsClientId=c)
        for first, second in col.excluded:
            for ua, la in self.objects.get(first, ()):
                for ub, lb in self.objects.get(second, ()):
                    p.setCollisionFilterPair(ua, ub, la, lb, 0, physicsClientId=c)
        # the contact parameters
        par = col.parameters
        mu1, mu2 = (float(m) for m in par.friction)
        base = mu1 if mu1 > 0 else mu2  # pybullet multiplies the two bodies' lateral friction
        erp = par.softness_erp if par.softness_erp is not None else w.error_correction
        # contacts are rigid unless CONSTANT_FORCE applies: the world's constantForceMix, which ODE would
        # use, reaches no constraint row in this backend (declared so)
        cfm = par.softness_cfm if par.softness_cfm is not None else 0.0
        if par.bounce > 0 and par.softness_erp is None:
            erp = 0.0  # pybullet adds the position correction to the bounce (ODE takes the larger)
        # ODE's soft contact as a spring and damper, k = ERP/(h CFM) and c = (1-ERP)/CFM with h the
        # scene's step (pybullet's substeps keep the spring), both given per body: pybullet puts two
        # bodies' springs in series and adds their dampers
        soft = cfm > 0
        stiffness, damping = (2 * erp / (self.dt * cfm), (1 - erp) / cfm / 2) if soft else (-1.0, -1.0)
        p.setPhysicsEngineParameter(
            restitutionVelocityThreshold=par.min_bounce_speed, contactSlop=par.surface_thickness,
            enableConeFriction=0, contactERP=erp, physicsClientId=c)
        for (uid, link), gi in self.geometry_at.items():
            # no frictionAnchor: it would hold static friction but pin contact points (see _FRICTION)
            kw = dict(lateralFriction=float(np.sqrt(base)), restitution=float(np.sqrt(par.bounce)),
                      rollingFriction=0.0, spinningFriction=0.0, contactProcessingThreshold=self.processing)
            if soft:
                kw.update(contactStiffness=stiffness, contactDamping=damping)
            static = col.geometries[gi].body == STATIC or b.fixed[col.geometries[gi].body]
            if static and mu1 != mu2 and base > 0:  # scaled along the axis of ODE's second direction
                scale = [mu1 / base] * 3
                scale[self.second_axis.get(gi, 2)] = mu2 / base
                kw.update(anisotropicFriction=scale)
            if (uid, link) in self.hull_objects:  # pybullet's hulls grow by their margin (1 mm by default)
                kw.update(collisionMargin=_HULL_MARGIN)
            p.changeDynamics(uid, link, **kw, physicsClientId=c)

    def _object(self, uid: int, link: int, geometry: int, shape: int) -> None:
        self.geometry_at[(uid, link)] = geometry
        if shape in self.hulls:
            self.hull_objects.add((uid, link))
        self.objects.setdefault(self.world.collisions.geometries[geometry].body, []).append((uid, link))

    def contacts(self) -> ContactPoints:
        """pybullet's contact points of the last step (found at its start) that its solver took, those
        within its processing threshold (_processing) of touching, each named by its geometries (the
        lower index first), at the middle of the two bodies' points, the normal from the first
        geometry towards the second and the depth minus pybullet's distance (so down to minus the
        threshold, at most 0.1 mm, for a point not quite touching)."""
        if self.world.collisions is None:
            return ContactPoints.none()
        rows = []
        at = self.geometry_at
        for cp in p.getContactPoints(physicsClientId=self.client):
            if cp[8] > self.processing:
                continue
            a, b = at.get((cp[1], cp[3])), at.get((cp[2], cp[4]))
            if a is None or b is None:
                continue
            n = cp[7]  # on B, pointing from B towards A
            if a < b:
                rows.append((a, b, *cp[5], *cp[6], -n[0], -n[1], -n[2], -cp[8]))
            else:
                rows.append((b, a, *cp[5], *cp[6], n[0], n[1], n[2], -cp[8]))
        if not rows:
            return ContactPoints.none()
        m = np.array(rows, dtype=np.float64)
        return ContactPoints(position=(m[:, 2:5] + m[:, 5:8]) / 2, normal=m[:, 8:11], depth=m[:, 11],
                             geometry1=m[:, 0].astype(int), geometry2=m[:, 1].astype(int))

    def watched_contacts(self, k: int) -> ContactPoints:
        return self.watched[k].contacts(self.client, self.state())

    # -- running ------------------------------------------------------------
    def step(self, n: int = 1) -> None:
        """n steps; pybullet forgets applied forces after each, so loads are applied before every one."""
        c = self.client
        forces, torques = self.forces, self.torques
        for _ in range(n):
            if self.loaded:
                com = np.zeros((len(forces), 3))
                com[self.rows[self.bodies]] = self._read(velocities=False)[0][self.bodies]
                for i in self.moving:
                    t, k = self.where[i]
                    uid, link = self.trees[t].uid, self.trees[t].link(k)
                    if forces[i].any():
                        p.applyExternalForce(uid, link, forces[i], com[i], p.WORLD_FRAME, physicsClientId=c)
                    if torques[i].any():
                        p.applyExternalTorque(uid, link, torques[i], p.WORLD_FRAME, physicsClientId=c)
            p.stepSimulation(physicsClientId=c)

    def _read(self, velocities: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Every part's centre of mass, principal frame orientation (w x y z), and with
        velocities, centre-of-mass velocity and angular velocity, in bulk, parts in order.
        (pybullet's link frame poses come rounded to single precision; these do not.)"""
        c = self.client
        # pybullet answers in tuples, a call per free base: the calls are the engine's one way in, and
        # the Python around them is kept to joining each part's tuples into one row
        pose, speed, links_of = p.getBasePositionAndOrientation, p.getBaseVelocity, p.getLinkStates
        rows: list[tuple[float, ...]] = []
        still = ((0.0,) * 6, ())
        for uid, free, links in self.reading:
            if free:
                x = pose(uid, physicsClientId=c)
                v = speed(uid, physicsClientId=c) if velocities else still
                rows.append(x[0] + x[1] + v[0] + v[1])
            if links:
                states = links_of(uid, links, computeLinkVelocity=int(velocities), computeForwardKinematics=1,
                                  physicsClientId=c)
                rows += ([s[0] + s[1] + s[6] + s[7] for s in states] if velocities else
                         [s[0] + s[1] + still[0] for s in states])
        a = np.fromiter(chain.from_iterable(rows), np.float64, 13 * len(rows)).reshape(-1, 13)
        return a[:, :3], _wxyz(a[:, 3:7]), a[:, 7:10], a[:, 10:13]

    def _frames(self, com: np.ndarray, q_com: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Every part's link frame (position, orientation) from its centre-of-mass frame."""
        q = R.multiply(q_com, self.unturn) if self.turned else q_com
        return com - R.rotate(q, self.inertial), q

    def state(self) -> State:
        b = self.world.bodies
        s = State.initial(b)
        s.linear_velocity[b.fixed] = 0.0
        s.angular_velocity[b.fixed] = 0.0
        com, q, v, w = self._read(velocities=True)
        if len(v) and max(np.abs(v).max(), np.abs(w).max()) >= _MAX_SPEED:
            raise BlewUp(f"a body reached pybullet's speed clamp ({_MAX_SPEED:g} m/s or rad/s in a component), "
                         "where pybullet holds it: its motion since is not the physics")
        if len(self.turning):
            relative = w[self.turning] - np.where(self.turning_from[:, None] >= 0, w[self.turning_from], 0.0)
            spin = float(np.linalg.norm(relative, axis=1).max())
            if spin * self.dt > _MAX_TURN:
                raise BlewUp(f"a free body or ball joint spins at {spin:.4g} rad/s, past what pybullet turns in a step "
                             f"(pi/4: {_MAX_TURN / self.dt:.4g} rad/s at dt {self.dt:g}): its orientation lags the physics")
        if self.turned:
            q = R.multiply(q, self.unturn)
        rows, on = self.rows[self.bodies], self.bodies
        s.position[rows] = (com - R.rotate(q, self.com_local) if self.shifted else com)[on]
        s.orientation[rows], s.linear_velocity[rows], s.angular_velocity[rows] = q[on], v[on], w[on]
        return s

    def set_loads(self, forces: np.ndarray, torques: np.ndarray) -> None:
        self.forces = forces + self.weight
        self.torques = np.array(torques, dtype=np.float64)
        self.loaded = bool(self.forces[self.moving].any() or self.torques[self.moving].any())

    def set_velocities(self, linear: np.ndarray, angular: np.ndarray) -> None:
        """The joint velocities whose body velocities come closest to those asked for (exact
        for free bodies): a least-squares fit through each tree's Jacobian at the centres of
        mass, built from the joints' current axes and pivots."""
        c = self.client
        all_com, q_com, _, _ = self._read(velocities=False)
        all_pos, q = self._frames(all_com, q_com)
        all_turn = R.matrix(q)
        for tree, first in zip(self.trees, self.first):
            if tree.free and tree.dofs == 6:  # a free body (its further collision shapes ride on fixed links)
                row = tree.parts[0].row
                p.resetBaseVelocity(tree.uid, linear[row], angular[row], physicsClientId=c)
                continue
            mine = slice(first, first + len(tree.parts))
            com, frame_pos, turn = all_com[mine], all_pos[mine], all_turn[mine]
            bodies = [k for k, pt in enumerate(tree.parts) if pt.row >= 0]
            rows = [tree.parts[k].row for k in bodies]
            if not (linear[rows].any() or angular[rows].any()):
                # at rest (every build of a scene that starts still): the fit's answer is +0.0 exactly
                # (LAPACK's gelsd sets x to zero for a zero right-hand side), without its Jacobian,
                # quadratic in a chain's links, and its least squares
                self._reset_joints(tree, np.zeros(tree.dofs))
                continue
            jac = np.zeros((6 * len(bodies), tree.dofs))
            target = np.zeros(6 * len(bodies))
            for n, k in enumerate(bodies):
                v, wv = slice(6 * n, 6 * n + 3), slice(6 * n + 3, 6 * n + 6)
                target[v], target[wv] = linear[tree.parts[k].row], angular[tree.parts[k].row]
                if tree.free:  # the base's centre-of-mass velocity and its angular velocity
                    jac[v, 0:3] = np.eye(3)
                    jac[v, 3:6] = -_skew(com[k] - com[0])
                    jac[wv, 3:6] = np.eye(3)
                for a in tree.joints(k):
                    part, col = tree.parts[a], tree.columns[a]
                    arm = com[k] - frame_pos[a]
                    if part.joint_type == p.JOINT_SPHERICAL:  # pybullet: angular velocity in the link frame
                        jac[wv, col:col + 3] = turn[a]
                        jac[v, col:col + 3] = -_skew(arm) @ turn[a]
                    elif part.joint_type == p.JOINT_REVOLUTE:
                        axis = turn[a] @ part.axis
                        jac[wv, col] = axis
                        jac[v, col] = np.cross(axis, arm)
                    else:
                        jac[v, col] = turn[a] @ part.axis
            self._reset_joints(tree, np.linalg.lstsq(jac, target, rcond=None)[0])

    def _reset_joints(self, tree: _Tree, qd: np.ndarray) -> None:
        """A tree's joint velocities qd (its columns), each joint's position kept."""
        c = self.client
        for k, part in enumerate(tree.parts):
            link, col = tree.link(k), tree.columns[k]
            if link < 0:
                p.resetBaseVelocity(tree.uid, qd[0:3], qd[3:6], physicsClientId=c)
            elif part.joint_type == p.JOINT_FIXED:
                continue
            elif part.joint_type == p.JOINT_SPHERICAL:
                position = p.getJointStateMultiDof(tree.uid, link, physicsClientId=c)[0]
                p.resetJointStateMultiDof(tree.uid, link, position, qd[col:col + 3], physicsClientId=c)
            else:
                position = p.getJointState(tree.uid, link, physicsClientId=c)[0]
                p.resetJointState(tree.uid, link, position, qd[col], physicsClientId=c)

    def close(self) -> None:
        """Free the pybullet client (each simulation holds one)."""
        if self.client >= 0 and p.isConnected(self.client):
            p.disconnect(self.client)
        self.client = -1

    def __del__(self) -> None:
        try:
            self.close()
        except Exception:  # at interpreter exit pybullet may be gone already
            pass


_BOUNCE = ("restitution sqrt(e) on every shape (pybullet multiplies two bodies'), minBounceSpeed as its "
           "restitutionVelocityThreshold; Bullet applies e to the approach speed after the step's gravity, "
           "+e g dt (rebound speed +0.9% at 4.4 m/s, dt 1/240); no position correction where a bounce applies "
           "(pybullet would add it to the rebound): an impact's penetration (up to v dt) stays. Apex of a 1 m "
           "drop, dt 1/240: e = 0.2, 0.5, 0.8 within -0.4%, +2.0%, +1.9% of e^2 h")
_FRICTION = ("pybullet multiplies two bodies' lateral friction: every shape gets sqrt(mu), so contacts get mu, on "
             "ODE's friction pyramid along the same two directions (incline slides within 0.6% of g(sin - mu cos)); "
             "Bullet clamps the combined coefficient at 10, so larger ones act as 10. Static friction is a velocity "
             "row without position correction (pybullet's frictionAnchor is left off), so a sideways load makes "
             "resting contacts creep: box_stack (dt 1/240, 10 s) moves Box1 5.8 mm and Box5 29.9 mm, tilting them "
             "8.9 to 19.3 mrad (bounds 1.2 to 4.0 mm, 0.9 to 4.3 mrad). frictionAnchor would hold that stack (Box5 "
             "1.3 mm, 0.86 of its bound) but pins contact points where they were made: resting balls lose contact "
             "for a step now and then (bounce_apex, dt 1/2000: |v| at rest up to 0.013 m/s, bound g dt = 0.0049) "
             "and CollisionSensor reports the stale point (sensor_geometry: 1.1 mm off under the ball, bound "
             "0.088 mm), so the bounce and the contact points are kept instead")


class BulletBackend(Backend):
    name = "bullet"
    integration = SEMI_IMPLICIT
    accurate_integration = in_substeps(SEMI_IMPLICIT, _SUBSTEPS_ACCURATE)  # preferAccuracy: substeps
    declared = {
        **native(*BODIES, *JOINTS, "RigidBodyCollection.iterations", "DoubleAxisHingeJoint",
                 "DoubleAxisHingeJoint.anchorPoint", "DoubleAxisHingeJoint.axis1", "DoubleAxisHingeJoint.axis2",
                 "DoubleAxisHingeJoint.limits", "DoubleAxisHingeJoint.minAngle1",
                 "DoubleAxisHingeJoint.maxAngle1", "DoubleAxisHingeJoint.desiredAngularVelocity1",
                 "DoubleAxisHingeJoint.desiredAngularVelocity2", "DoubleAxisHingeJoint.maxTorque1",
                 "DoubleAxisHingeJoint.maxTorque2"),
        **approximate("pybullet has no per-body gravity switch: -m*g is applied at the centre of mass each step "
                      "(it cancels gravity to rounding)", "RigidBody.useGlobalGravity"),
        **approximate("tree joints are exact (reduced coordinates); errorCorrection sets pybullet's erp, which "
                      "acts on joint limits and loop constraints, and its contactERP, ODE's position correction of "
                      "contacts (none where a bounce applies: see CollisionCollection.bounce)",
                      "RigidBodyCollection.errorCorrection"),
        **unsupported("pybullet's multibody constraint rows (limits, loop joints) carry no CFM: the value cannot "
                      "reach them (tree joints are exact either way); 0, rigid, is pybullet's own",
                      "RigidBodyCollection.constantForceMix", native_at=0.0),
        **approximate(f"pybullet has one first-order integrator: {_SUBSTEPS_ACCURATE} internal substeps per step",
                      "RigidBodyCollection.preferAccuracy"),
        **unsupported("pybullet's multibody joints have no compliance and its constraint rows no CFM: ODE's "
                      "suspension spring cannot be expressed", "DoubleAxisHingeJoint.suspensionForce",
                      "DoubleAxisHingeJoint.suspensionErrorCorrection"),
        **unsupported("pybullet's joint limits are inelastic, with one global ERP and no CFM",
                      "SingleAxisHingeJoint.stopBounce", "SliderJoint.stopBounce",
                      "SingleAxisHingeJoint.stopErrorCorrection", "SliderJoint.stopErrorCorrection",
                      "DoubleAxisHingeJoint.stop1Bounce",
                      "DoubleAxisHingeJoint.stop1ErrorCorrection", "DoubleAxisHingeJoint.stop1ConstantForceMix"),
        # collisions (measured with pybullet 3.2.7; tests/test_collisions_bullet.py)
        **native("CollisionCollection", "CollisionCollection.appliedParameters", "CollidableShape.geometry.Box",
                 "CollidableShape.geometry.Sphere", "CollidableShape.geometry.Cylinder",
                 "CollisionCollection.minBounceSpeed", "CollisionCollection.softnessErrorCorrection",
                 "CollisionCollection.softnessConstantForceMix", "CollisionCollection.appliedParameters.CONSTANT_FORCE",
                 "CollisionSensor"),
        **approximate(_BOUNCE, "CollisionCollection.bounce", "CollisionCollection.appliedParameters.BOUNCE"),
        **approximate(_FRICTION, "CollisionCollection.frictionCoefficients"),
        **approximate("pybullet's anisotropic friction scales the static shape's friction along ODE's second "
                      "direction for the normal of that shape's up (+y) face: exact there (slides along x and z "
                      "within 1%), approximate for other normals; contacts between two moving bodies get mu1 both "
                      "ways (mu2 both ways when mu1 is 0)",
                      "CollisionCollection.appliedParameters.FRICTION_COEFFICIENT-2"),
        **approximate("ODE's ERP as pybullet's contact ERP, or as k = ERP/(h CFM) with CONSTANT_FORCE: exact at rest "
                      "(penetration m g / k to 1e-9 m); where a bounce applies pybullet adds the correction to the "
                      "bounce velocity, where ODE takes the larger",
                      "CollisionCollection.appliedParameters.ERROR_REDUCTION"),
        **approximate(f"the convex hull of a {_CONE_SIDES}-gon and the apex (radius within 0.12%), "
                      f"{_HULL_MARGIN * 1000:g} mm collision margin outside", "CollidableShape.geometry.Cone"),
        **approximate(f"static: pybullet's triangle mesh, exact; on a moving body: the convex hull of its points "
                      f"(pybullet collides no concave moving shape), {_HULL_MARGIN * 1000:g} mm margin outside",
                      "CollidableShape.geometry.IndexedFaceSet", "CollidableShape.geometry.IndexedTriangleSet",
                      "CollidableShape.geometry.TriangleSet"),
        **approximate("static: pybullet's heightfield (on a planar grid, contact normals to 1e-6 and points to "
                      "0.1 mm; each quad split along pybullet's own diagonal); on a moving body: the convex hull "
                      "of its grid points",
                      "CollidableShape.geometry.ElevationGrid"),
        **approximate("pybullet's contactSlop: resting penetration equals the thickness (to 1e-6 m); ODE lets a "
                      "body that lands within the layer stay where it landed, pybullet lets it sink to the full "
                      "thickness", "RigidBodyCollection.contactSurfaceThickness"),
        **unsupported("pybullet has no limit on the speed that corrects a contact's penetration (without a "
                      "collider the value has no effect)",
                      "RigidBodyCollection.maxCorrectionSpeed"),
        # a set only sensors watch: its shapes in no body, tested by pybullet's shape query (_Watched)
        **native("CollisionSensor.collider.watchedOnly"),
        **unsupported("pybullet picks its contacts' friction directions itself (ODE's, from the normal)",
                      "CollisionCollection.appliedParameters.USER_FRICTION"),
        **unsupported("pybullet's contacts have no surface velocity (no conveyor)",
                      "CollisionCollection.appliedParameters.SPEED-1", "CollisionCollection.appliedParameters.SPEED-2"),
        **unsupported("pybullet's friction has no force-dependent slip",
                      "CollisionCollection.appliedParameters.SLIP-1", "CollisionCollection.appliedParameters.SLIP-2"),
        **approximate("no effect unless appliedParameters holds SPEED-1 or SPEED-2 (unsupported here)",
                      "CollisionCollection.surfaceSpeed"),
        **approximate("no effect unless appliedParameters holds SLIP-1 or SLIP-2 (unsupported here)",
                      "CollisionCollection.slipFactors"),
    }

    def version(self) -> str:
        import importlib.metadata  # here: a run never asks, and the import costs it 30 ms
        return importlib.metadata.version("pybullet")

    def build(self, world: World, dt: float) -> BulletSimulation:
        return BulletSimulation(world, dt)


BACKEND = BulletBackend()

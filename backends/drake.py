"""Drake backend (pydrake's MultibodyPlant): the joint forest as Drake's kinematic tree.

Two modes, chosen per world:
- discrete (the plant's time_step = dt, Drake's SAP solver) where the world collides
  (world.collisions is not None) or a tree joint has a stop (Drake's continuous plant ignores
  joint limits): one discrete update per step, velocity first and position from the new
  velocity (free motion as semi-implicit Euler);
- continuous (time_step 0) where nothing collides: Drake's error-controlled third-order
  Runge-Kutta integrator (RungeKutta3Integrator, target accuracy ACCURACY, or ACCURATE where
  the collection's preferAccuracy is TRUE) advanced to each step boundary (dt caps its step),
  so free motion, pendulums and tumbling bodies follow the equations of motion to that
  accuracy whatever dt is. The simulation says which (target_accuracy: None in discrete
  mode), as the sweep's reference run must be error-controlled (conformance/analyses/sweep.py).
  ACCURACY is loose because clause 37 says of preferAccuracy "The default setting is to
  optimize for speed rather than accuracy"; even so it is far tighter than any fixed step.
  Measured on the double pendulum over 1 s at dt 1/240: 437 integrator steps and 5.8e-8 m
  from a run at 1e-13 at ACCURACY; 3,300 steps and 7e-11 m at 1e-9; 14,600 steps and 1.3e-12 m
  (rounding) at ACCURATE: the error scales with the target, and 100x tighter costs about 4.6x
  the steps (100^(1/3)). ACCURATE is 1e5 times tighter, so that its run still steps finer
  than the looser one where the sweep's finest step (1/4000 s) caps that: the sweep's
  reference, the run at ACCURATE, has its own error bounded by its distance from the run at
  ACCURACY (conformance/analyses/sweep.py). At 1e-9, this
  backend's target before, the 50-link chain of scenes/stability took 46,000 steps over its
  first 0.5 s (11.7 s of CPU), and did not end its 5 s within the stability's 60 s.

Bodies: every RigidBody is a Drake RigidBody whose frame is the X3D body frame, its spatial
inertia from mass, centre of mass and the full inertia tensor about it. A fixed body is
welded to the world at its pose. A free root gets Drake's QuaternionFloatingJoint (added at
Finalize, its default pose the X3D one). Every other body gets its tree joint to its parent
(x3d_core's forest): RevoluteJoint (SingleAxisHingeJoint), PrismaticJoint (SliderJoint),
BallRpyJoint (BallJoint), Drake's UniversalJoint (UniversalJoint with perpendicular axes),
and two RevoluteJoints through a link of negligible mass (DoubleAxisHingeJoint, and a
UniversalJoint whose axes are not perpendicular); a DoubleAxisHingeJoint with a suspension has
a PrismaticJoint along axis 1 between them, ODE's spring k = ERP/(h CFM) as a PrismaticSpring
and its damper (1-ERP)/CFM as the joint's damping. BallRpyJoint is singular where its pitch
reaches 90 degrees (Drake has no quaternion ball joint). Each joint's frames sit at the anchor with
the child's starting orientation, so every joint coordinate starts at zero. Drake measures
the child relative to the parent; x3d_core's outputs measure body1 relative to body2, so
limits are mirrored where the child is body2 (as backends/mujoco.py). Joints closing loops
are refused (Drake's plant has no loop joint of these kinds that this backend builds).

Loads: the forces and torques fields (and the evaluator's, set_loads) are world-frame
ExternallyAppliedSpatialForces at each body's centre of mass; a body with useGlobalGravity
FALSE gets -m g there too. DoubleAxisHingeJoint motors are a velocity servo applied as
generalized forces before each step (as MuJoCo's).

Contacts: every Geometry is registered on its body (the static ones on the world body) with
Drake's hydroelastic contact: geometry on moving bodies compliant (modulus
HYDROELASTIC_MODULUS), on the static environment and fixed bodies rigid; pairs hydroelastics
cannot take fall back to point contact (stiffness from RESTING_DEPTH). Measured why: with point
contact, box on box is one point at the deepest corner, and a stack of five boxes rocked, sank
and fell apart (3.7 cm deep in 0.12 s); compliant against compliant (floor too) held a box
stuck on a 35 degree incline with mu 0.5 (tan 35 = 0.70 > mu); rigid against compliant at
E = 1e8 let the box on the 20 degree incline tumble; at E = 1e7 both incline boxes behave
(sliding at 1.5-1.6 m/s^2 against g (sin - mu cos) = 1.61) and the stack holds. Each geometry
gets Coulomb friction mu (Drake combines two as 2 mu1 mu2 / (mu1 + mu2), so each contact gets
exactly mu; its discrete solver uses the dynamic one). The plant filters joined (adjacent)
bodies; x3d_core's excluded pairs are filtered through SceneGraph as well. contacts() reports
SceneGraph's point-pair penetrations at the current state (a point, a normal, a depth per
touching pair), not the hydroelastic surfaces the dynamics used. Boxes, spheres and cylinders
are Drake's own shapes; a cone is a Convex (the hull of its apex and a 64-gon, an OBJ written
in memory); meshes and elevation grids are refused. Restitution is not in Drake's
contact model (compliant contact with Hunt-Crossley dissipation): bounce is refused.

A trap at coarse steps, measured and left as the engine's: the discrete step finds a contact
only once the bodies overlap, and an impact faster than the geometry's depth a step overshoots
it. At dt 1/60 a 0.2 m box dropped 0.3 m (2.4 m/s, 4 cm a step) is first seen 4 cm deep and
launched: 58.9 m up after 1 s (at 1/240 it rests). Drake's hydroelastic "margin" (contact seen
that far ahead) cures the drop at 3 m/s x dt, but moves momentum between two moving bodies
before they touch (auto_disable's striker: 1.96 kg m/s off, tolerance 0.024), so none is set;
x3drbp stability shows it at 1/60 (box_stack_10 and mass_ratio_stack drift), the sweep's
errors at coarse steps show it on any impact.
"""

from __future__ import annotations

import numpy as np
from pydrake.common import MemoryFile
from pydrake.geometry import (AddCompliantHydroelasticProperties, AddContactMaterial, AddRigidHydroelasticProperties,
                              Box, CollisionFilterDeclaration, Convex, Cylinder, FramePoseVector, GeometryFrame,
                              GeometryInstance, GeometrySet, InMemoryMesh, MeshSource, ProximityProperties,
                              SceneGraph, Sphere)
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.common.eigen_geometry import Quaternion
from pydrake.multibody.math import SpatialForce, SpatialVelocity
from pydrake.multibody.plant import (AddMultibodyPlantSceneGraph, ContactModel, CoulombFriction,
                                     DiscreteContactApproximation, ExternallyAppliedSpatialForce, MultibodyPlant)
from pydrake.multibody.tree import (BallRpyJoint, FixedOffsetFrame, JacobianWrtVariable, PrismaticJoint,
                                    PrismaticSpring, RevoluteJoint, RotationalInertia, SpatialInertia, UniversalJoint)
from pydrake.systems.analysis import ResetIntegratorFromFlags, Simulator
from pydrake.systems.framework import DiagramBuilder

from x3d_core.semantics import rotation as R
from x3d_core.semantics.collision import Collisions, ContactPoints, Geometry
from x3d_core.semantics.engine import BlewUp, Unsupported
from x3d_core.semantics.world import STATIC, Joint, State, World

from .base import BODIES, JOINTS, Backend, approximate, native, unsupported

ACCURACY = 1e-6  # the continuous integrator's target accuracy (Drake's relative error norm)
ACCURATE = 1e-11  # ... where preferAccuracy is TRUE
PERPENDICULAR = 1e-9  # |axis1 . axis2| under which a UniversalJoint is Drake's own
LINK_MASS = 1e-9  # the link between a two-axis joint's revolutes, as a fraction of the child's mass
MOTOR_STEPS = 0.5  # a hinge2 motor's servo closes this fraction of its speed gap a step (backends/mujoco.py)
HYDROELASTIC_MODULUS = 1e7  # Pa: a box 0.2 m thick sinks about p/E * 0.1 m under pressure p (1e-7 m at 100 Pa)
HYDRO_RESOLUTION = 0.25  # a sphere's or cylinder's hydroelastic mesh resolution, as a fraction of its least size
RESTING_DEPTH = 1e-4  # point contact stiffness: the world's whole weight on one contact rests this deep
CONE_EDGES = 64  # a cone collides as the hull of its apex and a 64-gon: radius 0.12 % short between corners
_FULL_TURN = np.pi - 1e-9
_Z_TO_Y = RotationMatrix.MakeXRotation(-np.pi / 2)  # Drake's cylinder axis z onto X3D's y


def _pose(position, quaternion) -> RigidTransform:
    q = np.asarray(quaternion, dtype=np.float64)
    return RigidTransform(Quaternion(q / np.linalg.norm(q)), np.asarray(position, dtype=np.float64))


def _frame(axes: list[np.ndarray]) -> RotationMatrix:
    """A rotation whose x axis is the first axis given and whose y axis is the second's part
    perpendicular to it (any perpendicular where none is given)."""
    x = axes[0] / np.linalg.norm(axes[0])
    y = axes[1] - x * (x @ axes[1]) if len(axes) > 1 else np.zeros(3)
    if np.linalg.norm(y) < 1e-12:
        y = np.cross(x, [1.0, 0, 0] if abs(x[0]) < 0.9 else [0, 1.0, 0])
    y /= np.linalg.norm(y)
    return RotationMatrix(np.column_stack([x, y, np.cross(x, y)]))


def _cone(r: float, h: float, name: str) -> Convex:
    """X3D's cone (axis y, centred halfway up) as Drake's Convex: the hull of its apex and a
    CONE_EDGES-gon, from an OBJ written in memory."""
    a = 2 * np.pi * np.arange(CONE_EDGES) / CONE_EDGES
    lines = [f"v {r * np.cos(t):.17g} {-h / 2:.17g} {r * np.sin(t):.17g}" for t in a] + [f"v 0 {h / 2:.17g} 0"]
    n = CONE_EDGES
    lines += [f"f {k + 1} {(k + 1) % n + 1} {n + 1}" for k in range(n)]
    lines += ["f " + " ".join(str(k + 1) for k in reversed(range(n)))]
    mesh = InMemoryMesh(mesh_file=MemoryFile("\n".join(lines) + "\n", ".obj", f"{name}.obj"))
    return Convex(MeshSource(mesh))


def _limited(world: World) -> bool:
    """Whether a tree joint of the world has a stop."""
    for i in range(len(world.bodies)):
        k = world.parent_joint[i]
        if k < 0 or world.bodies.fixed[i]:
            continue
        j = world.joints[k]
        p = j.params
        if j.type == "SliderJoint" and j.stops is not None:
            return True
        for lo, hi in (("minAngle", "maxAngle"), ("minAngle1", "maxAngle1")):
            if lo in p and not (p[lo] <= -_FULL_TURN and p[hi] >= _FULL_TURN):
                return True
    return False


def _point_pairs(pairs, geometry_of: dict) -> ContactPoints:
    """SceneGraph's point-pair penetrations between geometries geometry_of names, as ContactPoints:
    the point midway between the two, Drake's normal (from B into A) turned round."""
    pairs = [pp for pp in pairs if pp.id_A in geometry_of and pp.id_B in geometry_of]
    n = len(pairs)
    if n == 0:
        return ContactPoints.none()
    pos, nrm, depth = np.zeros((n, 3)), np.zeros((n, 3)), np.zeros(n)
    g1, g2 = np.zeros(n, dtype=int), np.zeros(n, dtype=int)
    for k, pp in enumerate(pairs):
        pos[k] = 0.5 * (np.asarray(pp.p_WCa) + np.asarray(pp.p_WCb))
        nrm[k] = -np.asarray(pp.nhat_BA_W)
        depth[k] = pp.depth
        g1[k], g2[k] = geometry_of[pp.id_A], geometry_of[pp.id_B]
    return ContactPoints(pos, nrm, depth, g1, g2)


class _Watched:
    """A set only sensors watch (world.watched): its shapes in a SceneGraph of their own, outside
    the plant's diagram (every proximity geometry of the plant's SceneGraph is in its contact
    model, so one there would push the bodies), a frame per body posed from the state when asked,
    SceneGraph's point pairs from its query object. Geometries on one frame, and two anchored ones,
    are never paired (SceneGraph's own filter); joined bodies' are filtered out."""

    def __init__(self, sim: DrakeSimulation, c: Collisions):
        graph = self.scene_graph = SceneGraph()
        self.source = graph.RegisterSource("watched")
        self.frames = {}  # body row -> its FrameId
        self.geometry_of: dict = {}
        for k, g in enumerate(c.geometries):
            shape, X = sim._shape(g)
            instance = GeometryInstance(X, shape, f"w{k}")
            if g.body == STATIC:
                gid = graph.RegisterAnchoredGeometry(self.source, instance)
            else:
                if g.body not in self.frames:
                    self.frames[g.body] = graph.RegisterFrame(self.source, GeometryFrame(f"b{g.body}"))
                gid = graph.RegisterGeometry(self.source, self.frames[g.body], instance)
            graph.AssignRole(self.source, gid, ProximityProperties())
            self.geometry_of[gid] = k
        self.context = graph.CreateDefaultContext()
        manager = graph.collision_filter_manager(self.context)
        for lo, hi in c.excluded:
            if lo in self.frames and hi in self.frames:
                manager.Apply(CollisionFilterDeclaration().ExcludeBetween(GeometrySet(self.frames[lo]),
                                                                          GeometrySet(self.frames[hi])))

    def contacts(self, s: State) -> ContactPoints:
        poses = FramePoseVector()
        for row, frame in self.frames.items():
            poses.set_value(frame, _pose(s.position[row], s.orientation[row]))
        self.scene_graph.get_source_pose_port(self.source).FixValue(self.context, poses)
        query = self.scene_graph.get_query_output_port().Eval(self.context)
        return _point_pairs(query.ComputePointPairPenetration(), self.geometry_of)


class DrakeSimulation:
    def __init__(self, world: World, dt: float):
        self.world, self.dt = world, dt
        b = world.bodies
        # Drake enforces joint limits in discrete plants only (its continuous plant ignores them)
        self.discrete = world.collisions is not None or _limited(world)
        # x3d_core.semantics.engine.target_accuracy: what a run reports of its integration
        self.target_accuracy = None if self.discrete else ACCURATE if world.prefer_accuracy else ACCURACY
        for k in world.loop_joints:
            j = world.joints[k]
            if j.body1 != j.body2 and not (j.body1 == STATIC and j.body2 == STATIC):
                raise Unsupported(f"{j.type} {j.name} closes a loop of joints: the drake backend builds joints "
                                  "as Drake's kinematic tree only (no loop constraints)")
        if self.discrete:
            builder = DiagramBuilder()
            self.plant, self.scene_graph = AddMultibodyPlantSceneGraph(builder, time_step=dt)
            self.plant.set_discrete_contact_approximation(DiscreteContactApproximation.kSap)
            self.plant.set_contact_model(ContactModel.kHydroelasticWithFallback)
        else:
            self.plant, self.scene_graph = MultibodyPlant(0.0), None
        plant = self.plant
        plant.mutable_gravity_field().set_gravity_vector(np.asarray(world.gravity, dtype=np.float64))
        self.bodies = []
        for i in range(len(b)):
            self.bodies.append(plant.AddRigidBody(f"b{i}", self._inertia(i)))
        self.motors: list[tuple[int, float, float, float]] = []  # (velocity index later, target, limit, gain)
        self._motor_joints = []
        self._links = 0
        for i in world.order:
            p = world.parent[i]
            if b.fixed[i]:
                plant.WeldFrames(plant.world_frame(), self.bodies[i].body_frame(),
                                 _pose(b.position[i], b.orientation[i]))
            elif p == World.FREE:
                plant.SetDefaultFloatingBaseBodyPose(self.bodies[i], _pose(b.position[i], b.orientation[i]))
            else:
                self._tree_joint(i, world.joints[world.parent_joint[i]])
        self.geometry_of: dict = {}
        if world.collisions is not None:
            self._collisions(world.collisions)
        self.watched = [_Watched(self, c) for c in world.watched]
        plant.Finalize()
        if self.discrete:
            self.diagram = builder.Build()
            self.root = self.diagram.CreateDefaultContext()
            self.context = plant.GetMyMutableContextFromRoot(self.root)
            if world.collisions is not None:
                self._filter(world.collisions)
            self.simulator = Simulator(self.diagram, self.root)
            self.simulator.Initialize()
        else:
            self.root = self.context = plant.CreateDefaultContext()
            self.simulator = Simulator(plant, self.context)
            integrator = ResetIntegratorFromFlags(self.simulator, "runge_kutta3", dt)
            integrator.set_target_accuracy(self.target_accuracy)
            integrator.set_maximum_step_size(dt)
            self.simulator.Initialize()
        self.steps = 0
        self.motor_dofs = [(plant.get_joint(jid).velocity_start(), t, lim, gain)
                           for jid, t, lim, gain in self._motor_joints]
        self.force_port = plant.get_applied_spatial_force_input_port()
        self.tau_port = plant.get_applied_generalized_force_input_port()
        self.tau_port.FixValue(self.context, np.zeros(plant.num_velocities()))
        self.moving = np.flatnonzero(~b.fixed)
        self.index = [int(body.index()) for body in self.bodies]  # each body's place in the plant's port values
        self.offset = np.flatnonzero(np.any(b.com != 0.0, axis=1))  # the bodies whose centre of mass is off the origin
        lone = np.array([world.parent[i] == World.FREE and not np.any(world.parent == i) for i in range(len(b))],
                        dtype=bool)
        self.direct = bool(np.array_equal(lone, ~b.fixed))
        self.set_velocities(b.linear_velocity, b.angular_velocity)
        self.set_loads(b.forces, b.torques)

    # -- building -----------------------------------------------------------
    def _inertia(self, i: int) -> SpatialInertia:
        b = self.world.bodies
        if b.fixed[i]:
            return SpatialInertia.Zero() if hasattr(SpatialInertia, "Zero") else \
                SpatialInertia.MakeFromCentralInertia(0.0, np.zeros(3), RotationalInertia(0.0, 0.0, 0.0))
        m, I = float(b.mass[i]), b.inertia[i]
        try:
            return SpatialInertia.MakeFromCentralInertia(
                m, b.com[i], RotationalInertia(I[0, 0], I[1, 1], I[2, 2], I[0, 1], I[0, 2], I[1, 2]))
        except Exception as e:  # Drake checks mass > 0 and the triangle inequality of the moments
            raise Unsupported(f"RigidBody {b.names[i]}: mass {m:g} kg, inertia {I.ravel().tolist()}: Drake refuses "
                              f"it as physically invalid ({str(e).splitlines()[0]})") from None

    def _joint_frames(self, child: int, parent_body, X_WP: RigidTransform, X_WJ: RigidTransform, name: str):
        plant = self.plant
        X_WC = _pose(self.world.bodies.position[child], self.world.bodies.orientation[child])
        F = plant.AddFrame(FixedOffsetFrame(f"{name}:F", parent_body.body_frame(), X_WP.inverse() @ X_WJ))
        M = plant.AddFrame(FixedOffsetFrame(f"{name}:M", self.bodies[child].body_frame(), X_WC.inverse() @ X_WJ))
        return F, M

    def _tree_joint(self, child: int, j: Joint) -> None:
        plant, b, w = self.plant, self.world.bodies, self.world
        p = w.parent[child]
        parent_body = plant.world_body() if p == STATIC else self.bodies[p]
        X_WP = RigidTransform() if p == STATIC else _pose(b.position[p], b.orientation[p])
        q = b.orientation[child]
        X_WJ = _pose(j.anchor, q)  # the joint frame: at the anchor, the child's start orientation
        local = R.rotate(R.conjugate(q), j.axes)  # the joint's axes in that frame
        sign = -1.0 if child == j.body2 else 1.0
        name = f"j{child}"
        if j.type == "SingleAxisHingeJoint":
            F, M = self._joint_frames(child, parent_body, X_WP, X_WJ, name)
            jt = plant.AddJoint(RevoluteJoint(name, F, M, local[0]))
            self._limits(jt, j.params["minAngle"], j.params["maxAngle"], sign)
        elif j.type == "SliderJoint":
            F, M = self._joint_frames(child, parent_body, X_WP, X_WJ, name)
            jt = plant.AddJoint(PrismaticJoint(name, F, M, local[0]))
            if j.stops is not None:
                self._limits(jt, *j.stops, sign, angular=False)
        elif j.type == "BallJoint":
            F, M = self._joint_frames(child, parent_body, X_WP, X_WJ, name)
            plant.AddJoint(BallRpyJoint(name, F, M))
        elif j.type in ("UniversalJoint", "DoubleAxisHingeJoint"):
            # axis1 is carried by body1, axis2 by body2: the parent's axis first
            first, second = (0, 1) if child == j.body2 else (1, 0)
            if j.type == "UniversalJoint" and abs(j.axes[0] @ j.axes[1]) < PERPENDICULAR:
                X = RigidTransform(_frame([j.axes[first], j.axes[second]]), j.anchor)
                F, M = self._joint_frames(child, parent_body, X_WP, X, name)
                plant.AddJoint(UniversalJoint(name, F, M))
                return
            # two revolutes (and a hinge2's suspension, a sprung slide along axis 1) through links of
            # negligible mass at the anchor, in the order ODE's hinge2 chains them from body1
            prm = j.params
            sprung = j.type == "DoubleAxisHingeJoint" and prm["suspensionForce"] > 0
            chain = [("rev", 0), ("slide", 0), ("rev", 1)] if sprung else [("rev", 0), ("rev", 1)]
            if child != j.body2:
                chain = chain[::-1]
            m = float(b.mass[child]) * LINK_MASS
            r = max(float(np.sqrt(np.max(np.linalg.eigvalsh(b.inertia[child])) / max(b.mass[child], 1e-300))), 1e-3)
            outer = plant.AddFrame(FixedOffsetFrame(f"{name}:F", parent_body.body_frame(), X_WP.inverse() @ X_WJ))
            X_WC = _pose(b.position[child], q)
            M = plant.AddFrame(FixedOffsetFrame(f"{name}:M", self.bodies[child].body_frame(), X_WC.inverse() @ X_WJ))
            by_axis = {}
            for n, (kind, k) in enumerate(chain):
                if n + 1 < len(chain):
                    inner = plant.AddRigidBody(f"{name}:link{n}", SpatialInertia.SolidSphereWithMass(m, r)).body_frame()
                else:
                    inner = M
                if kind == "rev":
                    by_axis[k] = plant.AddJoint(RevoluteJoint(f"{name}:{k + 1}", outer, inner, local[k]))
                else:  # ODE's soft row: k = ERP/(h CFM), c = (1 - ERP)/CFM
                    cfm, erp = prm["suspensionForce"], prm["suspensionErrorCorrection"]
                    slide = plant.AddJoint(PrismaticJoint(f"{name}:s", outer, inner, local[0],
                                                          damping=max(1.0 - erp, 0.0) / cfm))
                    plant.AddForceElement(PrismaticSpring(slide, 0.0, erp / (self.dt * cfm)))
                outer = inner
            if j.type == "DoubleAxisHingeJoint":
                self._limits(by_axis[0], prm["minAngle1"], prm["maxAngle1"], sign)
                com = b.com[child]
                for k in (0, 1):
                    if prm[f"maxTorque{k + 1}"] > 0:
                        a = local[k]
                        arm = R.rotate(R.conjugate(q), b.position[child] - j.anchor) + com
                        arm = arm - a * (a @ arm)
                        inertia = a @ b.inertia[child] @ a + b.mass[child] * (arm @ arm)
                        self._motor_joints.append((by_axis[k].index(), sign * prm[f"desiredAngularVelocity{k + 1}"],
                                                   prm[f"maxTorque{k + 1}"], MOTOR_STEPS * inertia / self.dt))
        else:
            raise Unsupported(f"{j.type} {j.name}: not built by the drake backend")

    def _limits(self, jt, lo: float, hi: float, sign: float, angular: bool = True) -> None:
        if angular and lo <= -_FULL_TURN and hi >= _FULL_TURN:
            return
        a, c = sorted((sign * lo, sign * hi))
        jt.set_position_limits([a], [c])

    def _collisions(self, col: Collisions) -> None:
        plant, b, p = self.plant, self.world.bodies, col.parameters
        mu = float(p.friction[0])
        weight = float(np.sum(b.mass[~b.fixed])) * max(float(np.linalg.norm(self.world.gravity)), 1.0)
        stiffness = 2.0 * weight / RESTING_DEPTH  # two in series: the whole weight rests RESTING_DEPTH deep
        for k, g in enumerate(col.geometries):
            shape, X = self._shape(g)
            props = ProximityProperties()
            AddContactMaterial(point_stiffness=stiffness, friction=CoulombFriction(mu, mu), properties=props)
            if g.body == STATIC or b.fixed[g.body]:  # Drake's best supported pairing: rigid against compliant
                AddRigidHydroelasticProperties(HYDRO_RESOLUTION * float(np.min(g.size)), props)
            else:
                AddCompliantHydroelasticProperties(HYDRO_RESOLUTION * float(np.min(g.size)), HYDROELASTIC_MODULUS,
                                                   props)
            body = plant.world_body() if g.body == STATIC else self.bodies[g.body]
            gid = plant.RegisterCollisionGeometry(body, X, shape, f"c{k}", props)
            self.geometry_of[gid] = k

    def _shape(self, g: Geometry):
        X = _pose(g.position, g.orientation)
        if g.kind == "box":
            return Box(*map(float, g.size)), X
        if g.kind == "sphere":
            return Sphere(float(g.size[0])), X
        if g.kind == "cylinder":
            return Cylinder(float(g.size[0]), float(g.size[1])), X @ RigidTransform(_Z_TO_Y, np.zeros(3))
        if g.kind == "cone":
            return _cone(float(g.size[0]), float(g.size[1]), g.name), X
        raise Unsupported(f"CollidableShape {g.name}: a {g.kind} is not built by the drake backend")

    def _filter(self, col: Collisions) -> None:
        if not col.excluded:
            return
        by_body: dict[int, list] = {}
        for gid, k in self.geometry_of.items():
            by_body.setdefault(col.geometries[k].body, []).append(gid)
        manager = self.scene_graph.collision_filter_manager(
            self.scene_graph.GetMyMutableContextFromRoot(self.root))
        for lo, hi in col.excluded:
            if lo in by_body and hi in by_body:
                manager.Apply(CollisionFilterDeclaration().ExcludeBetween(GeometrySet(by_body[lo]),
                                                                          GeometrySet(by_body[hi])))

    # -- running ------------------------------------------------------------
    def _motors(self) -> None:
        if not self.motor_dofs:
            return
        v = self.plant.GetVelocities(self.context)
        tau = np.zeros(self.plant.num_velocities())
        for dof, target, limit, gain in self.motor_dofs:
            tau[dof] = np.clip(gain * (target - v[dof]), -limit, limit)
        self.tau_port.FixValue(self.context, tau)

    def step(self, n: int = 1) -> None:
        try:
            for _ in range(n):
                self._motors()
                self.steps += 1
                self.simulator.AdvanceTo(self.steps * self.dt)
        except RuntimeError as e:
            raise BlewUp(f"Drake gave up: {str(e).splitlines()[0]}") from None
        x = self.plant.GetPositionsAndVelocities(self.context)
        if not np.all(np.isfinite(x)):
            raise BlewUp("Drake's state is no longer finite")

    def state(self) -> State:
        """Every body's pose and velocity: Drake's objects read a body at a time (pydrake has no bulk
        form), with no numpy call per body; the centre of mass's velocity v + w x (R com) in bulk, R com
        worked out only where com is not zero (elsewhere it is +0.0 exactly, as numpy's R @ 0)."""
        b, plant, ctx = self.world.bodies, self.plant, self.context
        poses = plant.get_body_poses_output_port().Eval(ctx)
        vels = plant.get_body_spatial_velocities_output_port().Eval(ctx)
        X = [poses[k] for k in self.index]
        pos = np.array([x.translation() for x in X]).reshape(-1, 3)
        quat = np.array([x.rotation().ToQuaternion().wxyz() for x in X]).reshape(-1, 4)
        v = np.array([vels[k].get_coeffs() for k in self.index]).reshape(-1, 6)  # [angular; translational]
        arm = np.zeros((len(X), 3))
        for i in self.offset:
            arm[i] = X[i].rotation().matrix() @ b.com[i]
        ang = v[:, :3].copy()
        return State(pos, quat, v[:, 3:] + R.cross(ang, arm), ang)

    def set_velocities(self, linear: np.ndarray, angular: np.ndarray) -> None:
        plant, ctx, b = self.plant, self.context, self.world.bodies
        nv = plant.num_velocities()
        if nv == 0:
            return
        if not (np.any(linear[self.moving]) or np.any(angular[self.moving])):
            plant.SetVelocities(ctx, np.zeros(nv))
            return
        if self.direct:
            for i in self.moving:
                body = self.bodies[i]
                Rm = plant.EvalBodyPoseInWorld(ctx, body).rotation().matrix()
                v_origin = linear[i] - np.cross(angular[i], Rm @ b.com[i])
                plant.SetFreeBodySpatialVelocity(ctx, body, SpatialVelocity(angular[i], v_origin))
            return
        jac = np.zeros((6 * len(self.moving), nv))
        target = np.zeros(6 * len(self.moving))
        world = plant.world_frame()
        for r, i in enumerate(self.moving):
            jac[6 * r:6 * r + 6] = plant.CalcJacobianSpatialVelocity(
                ctx, JacobianWrtVariable.kV, self.bodies[i].body_frame(), b.com[i], world, world)
            target[6 * r:6 * r + 3], target[6 * r + 3:6 * r + 6] = angular[i], linear[i]
        plant.SetVelocities(ctx, np.linalg.lstsq(jac, target, rcond=None)[0])

    def set_loads(self, forces: np.ndarray, torques: np.ndarray) -> None:
        b = self.world.bodies
        g = np.asarray(self.world.gravity, dtype=np.float64)
        out = []
        for i in self.moving:
            f = np.asarray(forces[i], dtype=np.float64)
            if not b.use_gravity[i]:
                f = f - b.mass[i] * g
            t = np.asarray(torques[i], dtype=np.float64)
            if not (f.any() or t.any()):
                continue
            load = ExternallyAppliedSpatialForce()
            load.body_index = self.bodies[i].index()
            load.p_BoBq_B = b.com[i]
            load.F_Bq_W = SpatialForce(t, f)
            out.append(load)
        self.force_port.FixValue(self.context, out)

    def contacts(self) -> ContactPoints:
        if self.world.collisions is None:
            return ContactPoints.none()
        query = self.plant.get_geometry_query_input_port().Eval(self.context)
        return _point_pairs(query.ComputePointPairPenetration(), self.geometry_of)

    def watched_contacts(self, k: int) -> ContactPoints:
        return self.watched[k].contacts(self.state())


def _scheme(accuracy: float) -> str:
    """How a world is stepped, in words, at the continuous integrator's target accuracy."""
    return ("discrete SAP (semi-implicit Euler in free motion) where the world collides or has a stop; "
            f"error-controlled third-order Runge-Kutta at target accuracy {accuracy:g} to each step boundary where not")


class DrakeBackend(Backend):
    name = "drake"
    integration = _scheme(ACCURACY)
    accurate_integration = _scheme(ACCURATE)
    declared = {
        **native(*BODIES, *JOINTS, "RigidBody.useGlobalGravity",
                 "CollidableShape.geometry.Box", "CollidableShape.geometry.Sphere",
                 "CollidableShape.geometry.Cylinder", "CollisionCollection.appliedParameters",
                 "DoubleAxisHingeJoint", "DoubleAxisHingeJoint.anchorPoint", "DoubleAxisHingeJoint.axis1",
                 "DoubleAxisHingeJoint.axis2", "DoubleAxisHingeJoint.limits", "DoubleAxisHingeJoint.minAngle1",
                 "DoubleAxisHingeJoint.maxAngle1"),
        **approximate(f"a velocity servo applied as a joint force before each step, closing {MOTOR_STEPS:g} of the "
                      "speed gap a step, clipped to maxTorque, for ODE's velocity constraint",
                      "DoubleAxisHingeJoint.desiredAngularVelocity1", "DoubleAxisHingeJoint.desiredAngularVelocity2",
                      "DoubleAxisHingeJoint.maxTorque1", "DoubleAxisHingeJoint.maxTorque2"),
        **approximate("a PrismaticJoint along axis 1 between the two revolutes, with ODE's spring k = ERP/(h CFM) "
                      "as a PrismaticSpring (explicit in Drake's discrete step) and damping c = (1-ERP)/CFM as the "
                      "joint's damping (implicit), through links of 1e-9 the child's mass",
                      "DoubleAxisHingeJoint.suspensionForce", "DoubleAxisHingeJoint.suspensionErrorCorrection"),
        **unsupported("Drake's contact model (compliant hydroelastic or point contact, Hunt-Crossley "
                      "dissipation) has no coefficient of restitution", "CollisionCollection.bounce", native_at=0.0),
        **approximate("no effect: bounce above 0 is refused (CollisionCollection.bounce), and with bounce 0 BOUNCE "
                      "asks for nothing", "CollisionCollection.appliedParameters.BOUNCE"),
        **unsupported("Drake's Coulomb friction is isotropic: one coefficient per contact",
                      "CollisionCollection.appliedParameters.FRICTION_COEFFICIENT-2",
                      "CollisionCollection.appliedParameters.USER_FRICTION"),
        **unsupported("Drake's contacts have no force-dependent slip", "CollisionCollection.appliedParameters.SLIP-1",
                      "CollisionCollection.appliedParameters.SLIP-2"),
        **unsupported("Drake's contacts have no surface velocity", "CollisionCollection.appliedParameters.SPEED-1",
                      "CollisionCollection.appliedParameters.SPEED-2"),
        **unsupported("contact softness (ERP/CFM) is not mapped onto Drake's contact stiffness and dissipation "
                      "by this backend", "CollisionCollection.appliedParameters.ERROR_REDUCTION",
                      "CollisionCollection.appliedParameters.CONSTANT_FORCE"),
        # alone (without SLIP-n, SPEED-n, ERROR_REDUCTION, CONSTANT_FORCE, refused above) these have no effect
        **native("CollisionCollection.slipFactors", "CollisionCollection.surfaceSpeed",
                 "CollisionCollection.softnessErrorCorrection", "CollisionCollection.softnessConstantForceMix"),
        **approximate(f"Drake has no cone primitive: a Convex, the hull of the apex and a {CONE_EDGES}-gon (radius "
                      "0.12 % short between its corners)", "CollidableShape.geometry.Cone"),
        **approximate("Drake's BallRpyJoint (roll, pitch, yaw from the start): singular where the pitch reaches "
                      "90 degrees from the starting pose (Drake has no quaternion ball joint); a run that reaches it "
                      "stops as blown up", "BallJoint"),
        **unsupported("meshes and height fields are not built by this backend",
                      "CollidableShape.geometry.IndexedFaceSet", "CollidableShape.geometry.IndexedTriangleSet",
                      "CollidableShape.geometry.TriangleSet", "CollidableShape.geometry.ElevationGrid"),
        **unsupported("Drake's joint limits have no restitution", "SingleAxisHingeJoint.stopBounce",
                      "SliderJoint.stopBounce", "DoubleAxisHingeJoint.stop1Bounce", native_at=0.0),
        **approximate("Drake's SAP solver holds a stop as a near-rigid constraint (it needs no error correction); "
                      "a world with a stop is stepped in discrete mode (Drake's continuous plant ignores joint "
                      "limits)", "SingleAxisHingeJoint.stopErrorCorrection", "SliderJoint.stopErrorCorrection",
                      "DoubleAxisHingeJoint.stop1ErrorCorrection"),
        **unsupported("Drake's joint limits take no CFM", "DoubleAxisHingeJoint.stop1ConstantForceMix",
                      native_at=0.0),
        **approximate("no effect: Drake's contacts do not bounce", "CollisionCollection.minBounceSpeed"),
        **approximate("Drake's hydroelastic contact (moving geometry compliant, modulus 1e7 Pa; static and fixed "
                      "geometry rigid; point contact where hydroelastics cannot pair two shapes): a compliant contact, "
                      "not ODE's rigid one with ERP and CFM. Measured at 1/240 s: a stack of five 0.2 kg boxes sinks "
                      "0.2-0.35 mm per interface and holds 10 s",
                      "CollisionCollection"),
        **approximate("Coulomb friction mu on every contact (Drake's combination 2 mu1 mu2 / (mu1 + mu2) of equal "
                      "values); Drake's discrete solver uses the dynamic coefficient and regularizes stiction. "
                      "Measured at 1/240 s, mu 0.5: a box on a 20 degree incline stays stuck, one on a 35 degree "
                      "incline slides at 1.5-1.6 m/s^2 against g (sin - mu cos) = 1.61",
                      "CollisionCollection.frictionCoefficients"),
        **approximate("SceneGraph's point-pair penetrations at the state after each step (one point, normal and "
                      "depth per touching pair), not the hydroelastic contact surfaces the dynamics used",
                      "CollisionSensor"),
        # a set only sensors watch: its shapes in a SceneGraph of their own, queried at frame ends (_Watched)
        **native("CollisionSensor.collider.watchedOnly"),
        **approximate("Drake has no ERP or CFM: tree joints are exact (generalized coordinates); contacts are "
                      "Drake's compliant hydroelastic contact (see CollisionCollection)",
                      "RigidBodyCollection.errorCorrection", "RigidBodyCollection.constantForceMix",
                      "RigidBodyCollection.maxCorrectionSpeed"),
        **approximate("Drake's SAP solver iterates to convergence; tree joints need none",
                      "RigidBodyCollection.iterations"),
        **approximate(f"in a world that neither collides nor has a stop (continuous mode), TRUE tightens the "
                      f"error-controlled integrator's target accuracy from {ACCURACY:g} to {ACCURATE:g} (on the double "
                      "pendulum at 1/240 s, 33x the integrator's steps for 1/40,000 the error); no effect in discrete mode", "RigidBodyCollection.preferAccuracy"),
        **unsupported("Drake's contacts have no surface layer", "RigidBodyCollection.contactSurfaceThickness",
                      native_at=0.0),
    }

    def version(self) -> str:
        from importlib.metadata import version
        return version("drake")

    def build(self, world: World, dt: float) -> DrakeSimulation:
        return DrakeSimulation(world, dt)


BACKEND = DrakeBackend()

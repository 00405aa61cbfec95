"""engine_speed.py's three scenes written in pydrake's own API (MultibodyPlant), as
backends/drake.py builds them: the 10-link chain (run_overhead.py's), the car (car.py's) and
the 100-box pile (pile.py's). Imports pydrake and numpy and the scene constants beside it, no
x3drbp code.

The model, as the backend sets it, in the mode it chooses: the chain (nothing collides, no
stops) a continuous plant integrated by Drake's error-controlled RungeKutta3 (target accuracy
1e-6, steps of at most dt) advanced to each step boundary, its links on RevoluteJoints (the
first to the world) whose frames sit at the anchor; the car and the pile discrete plants
(time_step dt, SAP, hydroelastic contact with point-contact fallback), advanced one step at a
time: the chassis and every box a floating body, each wheel joined to the chassis by two
RevoluteJoints (steering axis, then axle) through a link of 1e-9 the wheel's mass; moving
geometry compliant hydroelastic (modulus 1e7 Pa), the floor and walls rigid, each mesh's
resolution a quarter of the shape's least size, Coulomb friction mu on every geometry, point
stiffness twice the moving bodies' weight over 1e-4 m. Bodies are added first, then joints,
then geometry, in the scene's order. Each frame reads every body's pose and spatial velocity.
"""

from __future__ import annotations

import numpy as np
from pydrake.common.eigen_geometry import Quaternion
from pydrake.geometry import (AddCompliantHydroelasticProperties, AddContactMaterial, AddRigidHydroelasticProperties,
                              Box, ProximityProperties, Sphere)
from pydrake.math import RigidTransform
from pydrake.multibody.math import SpatialVelocity
from pydrake.multibody.plant import (AddMultibodyPlantSceneGraph, ContactModel, CoulombFriction,
                                     DiscreteContactApproximation, MultibodyPlant)
from pydrake.multibody.tree import FixedOffsetFrame, RevoluteJoint, RotationalInertia, SpatialInertia
from pydrake.systems.analysis import ResetIntegratorFromFlags, Simulator
from pydrake.systems.framework import DiagramBuilder

import car
import pile
import run_overhead

ACCURACY = 1e-6  # the continuous integrator's target accuracy (the backend's default)
LINK_MASS = 1e-9  # a two-axis joint's link, as a fraction of the child's mass
MODULUS = 1e7  # Pa: moving geometry's hydroelastic modulus
RESOLUTION = 0.25  # a hydroelastic mesh's resolution, as a fraction of the shape's least size
RESTING_DEPTH = 1e-4  # m: point contact stiffness, the whole weight on one contact resting this deep


def _inertia(mass: float, moments) -> SpatialInertia:
    return SpatialInertia.MakeFromCentralInertia(mass, np.zeros(3), RotationalInertia(*moments, 0.0, 0.0, 0.0))


def _at(position, quaternion=(1.0, 0.0, 0.0, 0.0)) -> RigidTransform:
    q = np.asarray(quaternion, dtype=np.float64)
    return RigidTransform(Quaternion(q / np.linalg.norm(q)), np.asarray(position, dtype=np.float64))


class Discrete:
    """A discrete plant with SceneGraph: SAP, hydroelastic contact with point-contact fallback."""

    def __init__(self, dt: float, gravity: float):
        self.builder = DiagramBuilder()
        self.plant, _ = AddMultibodyPlantSceneGraph(self.builder, time_step=dt)
        self.plant.set_discrete_contact_approximation(DiscreteContactApproximation.kSap)
        self.plant.set_contact_model(ContactModel.kHydroelasticWithFallback)
        self.plant.mutable_gravity_field().set_gravity_vector([0.0, -gravity, 0.0])

    def collide(self, geometries, mu: float, weight: float) -> None:
        """geometries: (body, or None for the world; pose; shape; least size), compliant on a body, rigid on
        the world."""
        stiffness = 2.0 * weight / RESTING_DEPTH
        plant = self.plant
        for k, (body, pose, shape, least) in enumerate(geometries):
            props = ProximityProperties()
            AddContactMaterial(point_stiffness=stiffness, friction=CoulombFriction(mu, mu), properties=props)
            if body is None:
                AddRigidHydroelasticProperties(RESOLUTION * least, props)
            else:
                AddCompliantHydroelasticProperties(RESOLUTION * least, MODULUS, props)
            plant.RegisterCollisionGeometry(plant.world_body() if body is None else body, pose, shape, f"c{k}", props)

    def simulator(self) -> tuple[Simulator, object]:
        self.plant.Finalize()
        diagram = self.builder.Build()
        root = diagram.CreateDefaultContext()
        simulator = Simulator(diagram, root)
        simulator.Initialize()
        return simulator, self.plant.GetMyMutableContextFromRoot(root)


def _run(plant: MultibodyPlant, simulator: Simulator, context, bodies, dt: float, frames: int,
         steps_per_frame: int) -> np.ndarray:
    """Advanced to each step boundary; every frame's positions (frames, bodies, 3), every body's pose and
    spatial velocity read."""
    out, steps = [], 0
    poses, velocities = plant.get_body_poses_output_port(), plant.get_body_spatial_velocities_output_port()
    for _ in range(frames):
        for _ in range(steps_per_frame):
            steps += 1
            simulator.AdvanceTo(steps * dt)
        X, V = poses.Eval(context), velocities.Eval(context)
        out.append([(X[int(b.index())], V[int(b.index())]) for b in bodies])
    return np.array([[x.translation() for x, v in frame] for frame in out])


def chain(duration: float) -> np.ndarray:
    """The chain: a continuous plant, the fixed base welded where it is, each link on a RevoluteJoint
    about z (the first to the world). The links' positions at the end (LINKS, 3)."""
    links = run_overhead.LINKS
    plant = MultibodyPlant(0.0)
    plant.mutable_gravity_field().set_gravity_vector([0.0, -car.GRAVITY, 0.0])
    base = plant.AddRigidBody("b0", SpatialInertia.Zero())
    bodies = [plant.AddRigidBody(f"b{k + 1}", _inertia(run_overhead.MASS, run_overhead.MOMENTS))
              for k in range(links)]
    plant.WeldFrames(plant.world_frame(), base.body_frame(), RigidTransform())
    centres = [run_overhead.DIRECTION * (0.35 * k + 0.175) for k in range(links)]
    for k, body in enumerate(bodies):
        parent, X_WP = (plant.world_body(), RigidTransform()) if k == 0 else (bodies[k - 1], _at(centres[k - 1]))
        X_WJ = _at(run_overhead.DIRECTION * 0.35 * k)
        name = f"j{k + 1}"
        F = plant.AddFrame(FixedOffsetFrame(f"{name}:F", parent.body_frame(), X_WP.inverse() @ X_WJ))
        M = plant.AddFrame(FixedOffsetFrame(f"{name}:M", body.body_frame(), _at(centres[k]).inverse() @ X_WJ))
        plant.AddJoint(RevoluteJoint(name, F, M, [0.0, 0.0, 1.0]))
    plant.Finalize()
    context = plant.CreateDefaultContext()
    simulator = Simulator(plant, context)
    integrator = ResetIntegratorFromFlags(simulator, "runge_kutta3", car.DT)
    integrator.set_target_accuracy(ACCURACY)
    integrator.set_maximum_step_size(car.DT)
    simulator.Initialize()
    frames, per_frame = round(duration * car.FRAME_RATE), round(1 / (car.FRAME_RATE * car.DT))
    return _run(plant, simulator, context, [base] + bodies, car.DT, frames, per_frame)[-1, 1:]


def car_run(duration: float) -> np.ndarray:
    """The car: the chassis floating, each wheel on two RevoluteJoints (steering, then axle) through a
    link; the wheels' spheres compliant, the floor rigid. Every frame's positions (frames, 5, 3)."""
    d = Discrete(car.DT, car.GRAVITY)
    plant = d.plant
    chassis = plant.AddRigidBody("b0", _inertia(car.CHASSIS_MASS, car.CHASSIS_MOMENTS))
    wheels = [plant.AddRigidBody(f"b{k + 1}", _inertia(car.WHEEL_MASS, [car.WHEEL_MOMENT] * 3))
              for k in range(len(car.WHEELS))]
    plant.SetDefaultFloatingBaseBodyPose(chassis, _at(car.START))
    radius = max(float(np.sqrt(car.WHEEL_MOMENT / car.WHEEL_MASS)), 1e-3)  # the link's: its mass is what counts
    axles = []
    for k, (centre, wheel) in enumerate(zip(car.WHEELS, wheels)):
        name, X_WJ = f"j{k + 1}", _at(centre)
        outer = plant.AddFrame(FixedOffsetFrame(f"{name}:F", chassis.body_frame(), _at(car.START).inverse() @ X_WJ))
        M = plant.AddFrame(FixedOffsetFrame(f"{name}:M", wheel.body_frame(), _at(centre).inverse() @ X_WJ))
        link = plant.AddRigidBody(f"{name}:link0", SpatialInertia.SolidSphereWithMass(car.WHEEL_MASS * LINK_MASS,
                                                                                       radius))
        plant.AddJoint(RevoluteJoint(f"{name}:1", outer, link.body_frame(), [0.0, 1.0, 0.0]))
        axles.append(plant.AddJoint(RevoluteJoint(f"{name}:2", link.body_frame(), M, [0.0, 0.0, 1.0])))
    weight = (car.CHASSIS_MASS + car.WHEEL_MASS * len(wheels)) * car.GRAVITY
    d.collide([(w, _at(np.zeros(3)), Sphere(car.RADIUS), car.RADIUS) for w in wheels]
              + [(None, _at(car.FLOOR_CENTRE), Box(*car.FLOOR_SIZE), min(car.FLOOR_SIZE))], car.MU, weight)
    simulator, context = d.simulator()
    plant.SetFreeBodySpatialVelocity(context, chassis, SpatialVelocity(np.zeros(3), [car.SPEED, 0.0, 0.0]))
    for axle in axles:
        axle.set_angular_rate(context, car.SPIN[2])
    return _run(plant, simulator, context, [chassis] + wheels, car.DT, *car._frames(duration))


def pile_run(duration: float) -> np.ndarray:
    """The pile: a floating body per box, turned as drawn, its box compliant; the floor and walls
    rigid on the world. Every frame's positions (frames, 100, 3)."""
    d = Discrete(pile.DT, pile.GRAVITY)
    plant = d.plant
    drawn = pile.draws()
    bodies = [plant.AddRigidBody(f"b{k}", _inertia(pile.MASS, [pile.BOX_MOMENT] * 3)) for k in range(len(drawn))]
    for body, (_, position, axis, angle) in zip(bodies, drawn):
        plant.SetDefaultFloatingBaseBodyPose(body, _at(position, pile._quaternion(axis, angle)))
    box = [pile.EDGE] * 3
    d.collide([(b, _at(np.zeros(3)), Box(*box), min(box)) for b in bodies]
              + [(None, _at(centre), Box(*size), min(size)) for _, size, centre in pile.STATIC],
              pile.MU, pile.MASS * len(bodies) * pile.GRAVITY)
    simulator, context = d.simulator()
    return _run(plant, simulator, context, bodies, pile.DT, *pile._frames(duration))


NATIVE = {"chain": chain, "car": car_run, "pile": pile_run}

"""An x3drbp backend outside x3drbp's tree: free rigid bodies integrated with NumPy.

The whole engine is this module; pyproject.toml beside it declares `euler =
"x3drbp_euler:BACKEND"` in the entry point group `x3drbp.backends`, and that is all
x3drbp needs to find it (backends/base.py).

Each step, for every moving body (ODE's order): the linear velocity gains dt F/m (gravity
and the forces field), the angular velocity dt I^-1 (tau - w x I w) with the world inertia
at the start of the step (the gyroscopic term explicit, as ODE's), the centre of mass moves
dt v with the new velocity (semi-implicit Euler), and the body turns by the exponential
map of dt w (ODE's finite rotation). It builds no joints and detects no collisions: it
declares natively only what it does, and refuses every scene with joints or contacts.
"""

from __future__ import annotations

import numpy as np

from backends.base import BODIES, NOT_YET, Backend, Declared, Support, approximate, native
from x3d_core.semantics import rotation as R
from x3d_core.semantics.collision import ContactPoints
from x3d_core.semantics.engine import Unsupported
from x3d_core.semantics.world import JOINT_TYPES, State, World

NO_JOINTS = "this engine integrates free bodies only: it builds no joints"
NO_CONTACTS = "this engine detects no collisions"


class EulerSimulation:
    def __init__(self, world: World, dt: float):
        b = world.bodies
        built = [j for j in world.joints if j.type != "MotorJoint"]  # a motor is loads (the evaluator's)
        if built:
            raise Unsupported(f"{built[0].type} {built[0].name}: {NO_JOINTS}")
        if world.collisions is not None:
            raise Unsupported(f"RigidBodyCollection {world.name}: {NO_CONTACTS}")
        self.dt, self.gravity = dt, world.gravity
        self.moving = ~b.fixed
        bad = [n for n, m, i, moving in zip(b.names, b.mass, b.inertia, self.moving)
               if moving and not (m > 0 and np.all(np.linalg.eigvalsh(i) > 0))]
        if bad:
            raise Unsupported(f"RigidBody {bad[0]}: needs a positive mass and a positive definite inertia")
        self.mass, self.inertia, self.com = b.mass, b.inertia, b.com
        self.inverse_inertia = np.where(self.moving[:, None, None], np.linalg.inv(
            np.where(self.moving[:, None, None], b.inertia, np.eye(3))), 0.0)
        self.use_gravity = b.use_gravity
        self.orientation = b.orientation / np.linalg.norm(b.orientation, axis=1, keepdims=True)
        self.centre = b.position + R.rotate(self.orientation, b.com)  # the centre of mass, world
        self.linear = np.where(self.moving[:, None], b.linear_velocity, 0.0)
        self.angular = np.where(self.moving[:, None], b.angular_velocity, 0.0)
        self.set_loads(b.forces, b.torques)

    def step(self, n: int = 1) -> None:
        dt, moving = self.dt, self.moving[:, None]
        for _ in range(n):
            rot = R.matrix(self.orientation)
            i_world = rot @ self.inertia @ np.swapaxes(rot, 1, 2)
            inv_world = rot @ self.inverse_inertia @ np.swapaxes(rot, 1, 2)
            spin = np.einsum("nij,nj->ni", i_world, self.angular)
            torque = self.torques - R.cross(self.angular, spin)
            self.linear = self.linear + dt * moving * self.acceleration
            self.angular = self.angular + dt * np.einsum("nij,nj->ni", inv_world, torque)
            self.centre = self.centre + dt * self.linear
            turn = np.column_stack([self.angular, dt * np.linalg.norm(self.angular, axis=1)])
            q = R.multiply(R.from_axis_angle(turn), self.orientation)  # world-frame w: on the left
            self.orientation = q / np.linalg.norm(q, axis=1, keepdims=True)

    def state(self) -> State:
        origin = self.centre - R.rotate(self.orientation, self.com)
        return State(origin, self.orientation.copy(), self.linear.copy(), self.angular.copy())

    def set_velocities(self, linear: np.ndarray, angular: np.ndarray) -> None:
        moving = self.moving[:, None]
        self.linear = np.where(moving, linear, 0.0)
        self.angular = np.where(moving, angular, 0.0)

    def set_loads(self, forces: np.ndarray, torques: np.ndarray) -> None:
        safe = np.where(self.mass > 0, self.mass, 1.0)[:, None]
        self.acceleration = forces / safe + self.use_gravity[:, None] * self.gravity
        self.torques = np.where(self.moving[:, None], torques, 0.0)

    def contacts(self) -> ContactPoints:
        return ContactPoints.none()


class EulerBackend(Backend):
    name = "euler"
    declared = native(*BODIES, "RigidBody.useGlobalGravity") | approximate(
        "no effect: this engine has no joints or contacts for a solver to act on",
        *(f"RigidBodyCollection.{f}" for f in ("iterations", "errorCorrection", "constantForceMix",
                                                "maxCorrectionSpeed", "preferAccuracy", "contactSurfaceThickness")))

    def version(self) -> str:
        return f"0.1.0 (numpy {np.__version__})"

    def support(self, feature: str) -> Declared:
        d = super().support(feature)
        if d.support is Support.UNSUPPORTED and d.note == NOT_YET:  # say why, not "not yet"
            node = feature.split(".", 1)[0]
            if node in JOINT_TYPES:
                return Declared(Support.UNSUPPORTED, NO_JOINTS)
            if node.startswith(("Collision", "Collidable", "Contact")):
                return Declared(Support.UNSUPPORTED, NO_CONTACTS)
        return d

    def build(self, world: World, dt: float) -> EulerSimulation:
        return EulerSimulation(world, dt)


BACKEND = EulerBackend()

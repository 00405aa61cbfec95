"""The plain data an engine builds from: one RigidBodyCollection's bodies (rows of bulk arrays),
its joints and the World that holds them, and the body states a run reads and writes.

Defined apart from world.py, which builds them from a scene, so that collision.py (which plans
collisions on a World, and which world.py calls) imports the types without importing world.py.
Engines import them from world.py, as before.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from x3d_core.model.scene import Node

STATIC = -1  # body index of the static environment (a NULL body, or a fixed RigidBody)
JOINT_TYPES = ("BallJoint", "SingleAxisHingeJoint", "DoubleAxisHingeJoint", "SliderJoint", "UniversalJoint",
               "MotorJoint")


@dataclass
class Bodies:
    """Rows are the collection's RigidBody nodes, in the order of its bodies field."""
    names: list[str]
    nodes: list[Node]
    mass: np.ndarray  # (n,)
    inertia: np.ndarray  # (n, 3, 3), about the centre of mass, body axes
    com: np.ndarray  # (n, 3) local
    position: np.ndarray  # (n, 3) of the body frame's origin
    orientation: np.ndarray  # (n, 4) quaternions w x y z
    linear_velocity: np.ndarray  # (n, 3) of the centre of mass (as in ODE and every engine)
    angular_velocity: np.ndarray  # (n, 3)
    fixed: np.ndarray  # (n,) bool: fixed, or not enabled (out of the physics, held where it is)
    enabled: np.ndarray  # (n,) bool: in the physics and in the trace
    use_gravity: np.ndarray  # (n,) bool
    auto_damp: np.ndarray  # (n,) bool
    linear_damping: np.ndarray  # (n,)
    angular_damping: np.ndarray  # (n,)
    forces: np.ndarray  # (n, 3) the sum of the forces field, applied at the centre of mass
    torques: np.ndarray  # (n, 3) the sum of the torques field
    finite_rotation: np.ndarray  # (n,) bool
    finite_rotation_axis: np.ndarray  # (n, 3)
    auto_disable: np.ndarray  # (n,) bool
    disable_thresholds: np.ndarray  # (n, 3): linear speed, angular speed, time

    def __len__(self) -> int:
        return len(self.names)


@dataclass
class State:
    """Body states, rows as in Bodies, in world coordinates: the body frame's origin and
    orientation (X3D's position and orientation), and the velocity of the centre of mass
    (X3D's linearVelocity: the rigid body's velocity, whatever point its frame starts at)."""
    position: np.ndarray  # (n, 3)
    orientation: np.ndarray  # (n, 4) w x y z
    linear_velocity: np.ndarray  # (n, 3)
    angular_velocity: np.ndarray  # (n, 3)
    # the one (n, 13) array the four are column views of, where a backend read them so: the
    # evaluator's soundness check is then one pass over it, not a concatenation of copies
    whole: np.ndarray | None = field(default=None, repr=False, compare=False)

    @classmethod
    def initial(cls, bodies: Bodies) -> State:
        return cls(bodies.position.copy(), bodies.orientation.copy(), bodies.linear_velocity.copy(),
                   bodies.angular_velocity.copy())


@dataclass
class Joint:
    name: str
    type: str
    node: Node
    body1: int  # row in Bodies, or STATIC
    body2: int
    anchor: np.ndarray  # (3,) world, at the start
    axes: np.ndarray  # (3, 3) rows: axis, axis1/2, or motor axes 1..3 (unit, world, at the start)
    params: dict[str, float]  # the joint's numeric input fields, SI
    outputs: tuple[str, ...]  # the output fields forceOutput selects
    stops: tuple[float, float] | None = None  # a SliderJoint's (minSeparation, maxSeparation); None: no stops


@dataclass
class World:
    name: str
    node: Node
    gravity: np.ndarray
    iterations: int
    error_correction: float
    constant_force_mix: float
    max_correction_speed: float
    prefer_accuracy: bool
    contact_surface_thickness: float
    bodies: Bodies
    joints: list[Joint]
    # the joint graph as a forest over bodies: parent row (STATIC for a body on the
    # static environment, -2 for a free root), the joint that makes the edge, and the
    # joints left over (closing loops, or joining two static ends) as constraints
    parent: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    parent_joint: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    order: list[int] = field(default_factory=list)  # bodies, every parent before its children
    loop_joints: list[int] = field(default_factory=list)
    collisions: Any = None  # x3d_core.semantics.collision.Collisions, or None: nothing collides
    # collision sets only CollisionSensors watch (collision.watch): detected each frame's end, never acted on
    watched: list[Any] = field(default_factory=list)

    FREE = -2

"""The mutants: one realistic X3D-browser bug each, on the backend that passes the most cases.

Each row names the bug in one line, the browser or the class of bug it stands for (what
../shared/notes/spec-and-peers.md read in X_ITE's and FreeWRL's sources, or a bug any port of an
engine makes: a field ignored, read in the wrong units, sign or frame, bodies swapped, outputs
late), its edit (edits.py: of the World, or a relay of the simulation), and the cases that kill
it (tests/test_mutants.py runs those), or, where none does, the gap: the case that would. Every
mutant wraps ode, which passes the most cases and honours every field a row edits (Bullet
refuses surfaceSpeed, CFM and stopBounce); `base` could name another.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from x3d_core.model.scene import Node
from x3d_core.semantics import rotation as R
from x3d_core.semantics.collision import Collisions, Geometry, _geometry
from x3d_core.semantics.engine import Simulation
from x3d_core.semantics.world import STATIC, Joint, World

from conformance.mutants.edits import (BodyFrameLoads, BodyFrameSpin, FlippedNormals, LateState, Relay, WorldEdit,
                                       every_body_collides, geometries, hold, joints, params, reset)

HINGE, SLIDER, DOUBLE, MOTOR = "SingleAxisHingeJoint", "SliderJoint", "DoubleAxisHingeJoint", "MotorJoint"
BALL, UNIVERSAL = "BallJoint", "UniversalJoint"
BASE = "ode"  # passes the most cases; the engine of FreeWRL and Xj3D, and of the clause's own parameters
X_ITE, FREEWRL, IGNORED = "X_ITE 15", "FreeWRL", "ignored field"  # the browsers as spec-and-peers.md read them


@dataclass(frozen=True)
class Mutant:
    name: str
    bug: str  # what goes wrong, in one line
    models: str  # the real browser, or the class of bug, it stands for
    world: WorldEdit | None = None  # made on the World before the engine builds it
    relay: Callable[[Simulation, World], Simulation] | None = None  # wraps the built simulation
    kills: tuple[str, ...] = ()  # the cases that kill it (a short list: the tests run them)
    gap: str = ""  # where no case kills it yet: the case that would
    base: str = BASE  # the backend it wraps
    # where its kills turn conventions alone: why no sentence of the clause judges the bug (an implementer
    # with it is told it differs in conventions, which is then all the clause allows anyone to say)
    silent: str = ""
    # the fields (NODE.field) whose misreading it stands for, where no scene edit shows them (every engine
    # here reads them one way): of its kills, those that set one cover it (conformance.coverage.mutant_covers),
    # and tests/test_mutants.py holds each of those to a FAIL
    fields: tuple[str, ...] = ()

    @property
    def backend(self) -> str:
        """Its name as a backend (the entry point's name)."""
        return f"mutant-{self.name}"

    @property
    def attribute(self) -> str:
        """The attribute of conformance.mutants.plugin that is its backend."""
        return self.name.replace("-", "_")


def _default_axis(j: Joint) -> None:
    j.axes[0] = (0.0, 1.0, 0.0)


def _flip_axes(j: Joint) -> None:
    j.axes = -j.axes


def _colinear(j: Joint) -> None:
    j.axes[1] = j.axes[0]


def _default_stops(j: Joint) -> None:
    j.stops = (0.0, 1.0)


def _stops_swapped(j: Joint) -> None:
    j.stops = tuple(sorted((j.params["minSeparation"], j.params["maxSeparation"])))


def _stops_other_sense(j: Joint) -> None:
    j.params["minAngle"], j.params["maxAngle"] = -j.params["maxAngle"], -j.params["minAngle"]


def _outputs(j: Joint) -> tuple[str, ...]:
    return tuple(f for f, fd in j.node.spec.fields.items() if fd.access == "outputOnly")


def _names_beside_none(j: Joint) -> None:
    wanted = j.node.get("forceOutput")
    if "NONE" in wanted and "ALL" not in wanted:
        j.outputs = tuple(f for f in _outputs(j) if f in wanted)


def _every_output(j: Joint) -> None:
    j.outputs = _outputs(j)


def _at_origin(j: Joint) -> None:
    j.anchor = np.zeros(3)


def _swap_bodies(j: Joint) -> None:
    j.body1, j.body2 = j.body2, j.body1


def _no_reaction(j: Joint) -> None:
    j.body2 = STATIC


def _density_model_ignored(world: World) -> None:
    b = world.bodies
    for row, node in enumerate(b.nodes):
        if node.get("massDensityModel") is not None:
            b.inertia[row] = np.asarray(node.get("inertia"), dtype=np.float64).reshape(3, 3)


def _enabled_ignored(world: World) -> None:
    world.bodies.enabled[:] = True
    hold(lambda w: np.array([bool(n.get("fixed")) for n in w.bodies.nodes], dtype=bool))(world)


def _friction_from_slip(c: Collisions) -> Collisions:
    slip = np.asarray(c.collider.get("slipFactors"), dtype=np.float64)
    return replace(c, parameters=replace(c.parameters, friction=slip))


def _along_z(g: Geometry) -> Geometry:
    if g.kind not in ("cylinder", "cone"):
        return g
    return replace(g, orientation=R.multiply(g.orientation, R.from_axis_angle(np.array([1.0, 0.0, 0.0, math.pi / 2]))))


def _as_box(g: Geometry) -> Geometry:
    if g.kind not in ("cylinder", "cone"):
        return g
    r, h = g.size
    return replace(g, kind="box", size=np.array([2 * r, h, 2 * r]))


class _Unbounded:
    """A Shape as collision.py reads it, but with no bboxSize given."""

    def __init__(self, shape: Node):
        self.shape = shape

    def get(self, name: str) -> Any:
        return (-1.0, -1.0, -1.0) if name == "bboxSize" else self.shape.get(name)


def _bbox_ignored(g: Geometry) -> Geometry:
    """The geometry itself in place of the box its Shape's explicit bboxSize gives."""
    shape = g.node.get("shape")
    if shape is None or np.any(np.asarray(shape.get("bboxSize"), dtype=np.float64) < 0):
        return g
    found = _geometry(shape.get("geometry"), _Unbounded(shape))
    if found is None:
        return g
    kind, size, centre, vertices, triangles, grid = found
    at = g.position + R.rotate(g.orientation, centre - np.asarray(shape.get("bboxCenter"), dtype=np.float64))
    return replace(g, kind=kind, size=size, position=at, vertices=vertices, triangles=triangles, grid=grid)


def _nested_spaces_ignored(c: Collisions) -> Collisions:
    """The collider's collidables and its spaces' own: what a space within a space holds drops out."""
    deep: set[int] = set()

    def walk(node: Node, depth: int) -> None:
        if node.type_name == "CollisionSpace":
            for child in node.get("collidables"):
                walk(child, depth + 1)
            return
        while depth >= 2 and node is not None:  # a CollidableOffset's collidable with it
            deep.add(id(node))
            node = node.get("collidable") if node.type_name == "CollidableOffset" else None

    for top in c.collider.get("collidables"):
        walk(top, 0)
    return replace(c, geometries=[g for g in c.geometries if id(g.node) not in deep])


def _thickness_ignored(world: World) -> None:
    world.contact_surface_thickness = 0.0
    reset("collisions.parameters.surface_thickness", lambda _: 0.0)(world)


def _routed_contacts_ignored(world: World) -> None:
    if world.node.get("collider") is None:  # only a sensor's ROUTE into set_contacts made it collide
        world.collisions = None


MUTANTS: tuple[Mutant, ...] = (
    # -- bodies: mass properties, initial state, gravity, damping, what takes part
    Mutant("center-of-mass-ignored", "RigidBody.centerOfMass ignored: the mass sits at the body's origin",
           f"{X_ITE} (in effect)", reset("bodies.com", np.zeros_like), kills=("center_of_mass",),
           silent="37.4.10 gives centerOfMass a signature row and no sentence: what it does is the UOM's and ODE's"),
    Mutant("mass-ignored", "RigidBody.mass ignored: every body weighs the default 1 kg", IGNORED,
           reset("bodies.mass", np.ones_like), kills=("constant_force",)),
    Mutant("mass-in-grams", "RigidBody.mass read in grams: a thousandth of the mass", "wrong units",
           reset("bodies.mass", lambda m: m / 1000.0), kills=("constant_force",)),
    Mutant("inertia-ignored", "RigidBody.inertia ignored: the default identity tensor", f"{X_ITE} (in effect)",
           reset("bodies.inertia", lambda i: np.broadcast_to(np.eye(3), i.shape).copy()), kills=("constant_torque",)),
    Mutant("inertia-off-diagonal-ignored", "RigidBody.inertia's products of inertia dropped: the diagonal alone",
           f"{FREEWRL} misindexes the tensor", reset("bodies.inertia", lambda i: i * np.eye(3)),
           kills=("torque_free",)),
    Mutant("mass-density-model-ignored", "RigidBody.massDensityModel ignored: the inertia field is used instead",
           IGNORED, _density_model_ignored, kills=("mass_density_model",)),
    Mutant("gravity-default", "RigidBodyCollection.gravity ignored: the browser's own 0 -9.8 0", IGNORED,
           reset("gravity", lambda g: np.array([0.0, -9.8, 0.0])), kills=("free_fall",)),
    Mutant("gravity-sign", "RigidBodyCollection.gravity applied with its sign flipped", "wrong sign",
           reset("gravity", np.negative), kills=("free_fall",)),
    Mutant("use-global-gravity-ignored", "RigidBody.useGlobalGravity FALSE ignored: every body falls", IGNORED,
           reset("bodies.use_gravity", np.ones_like), kills=("gravity_off",)),
    Mutant("damping-ignored", "RigidBody.autoDamp and its damping factors ignored", IGNORED,
           reset("bodies.auto_damp", np.zeros_like), kills=("damping",)),
    Mutant("linear-velocity-ignored", "RigidBody.linearVelocity's initial value ignored: bodies start at rest",
           IGNORED, reset("bodies.linear_velocity", np.zeros_like), kills=("projectile",)),
    Mutant("angular-velocity-ignored", "RigidBody.angularVelocity's initial value ignored", IGNORED,
           reset("bodies.angular_velocity", np.zeros_like), kills=("torque_free",)),
    Mutant("torques-two-thirds", "RigidBody.torques applied at two thirds of their size",
           "a load misscaled on its way to the engine (any error under half the load, which constant_torque passes)",
           reset("bodies.torques", lambda t: t * (2.0 / 3.0)), kills=("load_magnitude",)),
    Mutant("fixed-as-dynamic", "RigidBody.fixed TRUE ignored: the body is integrated, and falls with what hangs "
           "on it", IGNORED, hold(lambda w: ~w.bodies.enabled), kills=("pendulum_period",)),
    Mutant("enabled-ignored", "RigidBody.enabled FALSE ignored: the body takes part in the physics", IGNORED,
           _enabled_ignored, kills=("disabled_body",)),
    Mutant("auto-disable-ignored", "RigidBody.autoDisable ignored: a resting body is never disabled",
           f"{X_ITE} ignores disableTime", reset("bodies.auto_disable", np.zeros_like), kills=("auto_disable",)),
    # -- joints
    Mutant("hinge-limits-ignored", "SingleAxisHingeJoint minAngle/maxAngle ignored: a free hinge",
           f"{X_ITE} has no hinge limits",
           params((HINGE,), minAngle=lambda _: -math.pi, maxAngle=lambda _: math.pi), kills=("hinge_limits",)),
    Mutant("hinge-limits-in-degrees", "hinge minAngle/maxAngle read as degrees", "wrong units",
           params((HINGE, DOUBLE), minAngle=math.radians, maxAngle=math.radians, minAngle1=math.radians,
                  maxAngle1=math.radians), kills=("hinge_limits",)),
    Mutant("slider-stops-ignored", "SliderJoint minSeparation/maxSeparation ignored: the stops stay at 0 and 1",
           IGNORED, joints((SLIDER,), _default_stops), kills=("slider_stops",)),
    Mutant("slider-stops-swapped", "SliderJoint minSeparation > maxSeparation taken as stops, the two swapped",
           "stops sorted for the engine (x3drbp's five adapters sorted them)",
           joints((SLIDER,), _stops_swapped), kills=("slider_unstopped",)),
    Mutant("stop-bounce-ignored", "stopBounce ignored: a joint stop never bounces", IGNORED,
           params((HINGE, SLIDER, DOUBLE), stopBounce=lambda _: 0.0, stop1Bounce=lambda _: 0.0),
           gap="hinge_bounce run with preferAccuracy TRUE: ode's quick-step meets the stop 0.5 rad late, and its "
               "error correction throws the arm back part way with stopBounce 0 as with 0.5; with dWorldStep ode "
               "passes and this mutant fails the spec measure"),
    Mutant("anchor-ignored", "joint anchorPoint ignored: every joint at the origin", IGNORED,
           joints((HINGE, DOUBLE, BALL, UNIVERSAL), _at_origin), kills=("motor_speed",)),
    Mutant("axis-ignored", "SingleAxisHingeJoint/SliderJoint axis ignored: the default 0 1 0", IGNORED,
           joints((HINGE, SLIDER), _default_axis), kills=("pendulum_period",)),
    Mutant("axis-flipped", "every joint axis taken with its sense flipped", "wrong sign",
           joints((HINGE, SLIDER, DOUBLE, UNIVERSAL), _flip_axes), kills=("hinge_limits", "slider_stops", "hinge2_steering")),
    Mutant("hinge-stops-other-sense", "SingleAxisHingeJoint stops enforced in the other sense from the angle it "
           "reports: the limits -maxAngle..-minAngle", "limits handed to an engine that measures the hinge angle the "
           "other way (body2 relative to body1), the angle reported in the scene's sense",
           joints((HINGE,), _stops_other_sense), kills=("hinge_limit_sense",)),
    Mutant("joint-bodies-swapped", "joint body1 and body2 swapped", "swapped bodies",
           joints((HINGE, SLIDER, DOUBLE, MOTOR, BALL, UNIVERSAL), _swap_bodies),
           kills=("hinge_limits", "motor_joint_torque", "motor_anchoring")),
    Mutant("double-axis-colinear", "DoubleAxisHingeJoint axis2 made axis1", f"{X_ITE} forces the axes colinear",
           joints((DOUBLE,), _colinear), kills=("motor_speed",)),
    Mutant("motor-max-torque-ignored", "DoubleAxisHingeJoint maxTorque1/2 ignored: the motors never drive",
           IGNORED, params((DOUBLE,), maxTorque1=lambda _: 0.0, maxTorque2=lambda _: 0.0), kills=("motor_speed",)),
    Mutant("motor-reaction-missing", "MotorJoint torques body1 alone: no reaction on body2", "missing reaction",
           joints((MOTOR,), _no_reaction), kills=("motor_joint_torque",)),
    Mutant("force-output-beside-none", "forceOutput's names beside NONE reported: NONE heeded only alone", X_ITE,
           joints((HINGE, SLIDER, DOUBLE, MOTOR, BALL, UNIVERSAL), _names_beside_none), kills=("force_output",)),
    Mutant("force-output-ignored", "forceOutput ignored: every joint reports every output", IGNORED,
           joints((HINGE, SLIDER, DOUBLE, MOTOR, BALL, UNIVERSAL), _every_output), kills=("force_output",)),
    # -- contacts
    Mutant("bounce-ignored", "CollisionCollection.bounce ignored: contacts never bounce", IGNORED,
           reset("collisions.parameters.bounce", lambda _: 0.0), kills=("newtons_cradle",)),
    Mutant("min-bounce-speed-ignored", "CollisionCollection.minBounceSpeed ignored: every impact bounces",
           IGNORED, reset("collisions.parameters.min_bounce_speed", lambda _: 0.0), kills=("bounce_apex",)),
    Mutant("friction-from-slip-factors", "friction read from slipFactors instead of frictionCoefficients",
           FREEWRL, reset("collisions", _friction_from_slip), kills=("incline", "conveyor")),
    Mutant("friction-second-ignored", "FRICTION_COEFFICIENT-2 ignored: the first coefficient both ways",
           IGNORED, reset("collisions.parameters.friction", lambda f: f[[0, 0]]),
           kills=("anisotropic_friction",),
           silent="the clause contradicts itself on the primary direction (docs/spec-loose-ends.md, 22): taken as "
                  "37.2.5.3's 'primary direction of motion', a sliding box always meets the first coefficient"),
    Mutant("surface-speed-ignored", "CollisionCollection.surfaceSpeed ignored: no conveyor", IGNORED,
           reset("collisions.parameters.surface_speed", np.zeros_like), kills=("conveyor",)),
    Mutant("slip-ignored", "CollisionCollection.slipFactors ignored (SLIP-1/2)", IGNORED,
           reset("collisions.parameters.slip", np.zeros_like), kills=("contact_slip",),
           silent="slipFactors and slipCoefficients have signature rows and no sentence, and Table 37.2 no rows"),
    Mutant("contact-softness-ignored", "softnessErrorCorrection/softnessConstantForceMix ignored: rigid contacts",
           f"{X_ITE} ignores ERP and CFM",
           reset("collisions.parameters", lambda p: replace(p, softness_erp=None, softness_cfm=None)),
           kills=("contact_softness",)),
    Mutant("constant-force-mix-ignored", "RigidBodyCollection.constantForceMix ignored: rigid joints",
           f"{X_ITE} ignores ERP and CFM", reset("constant_force_mix", lambda _: 0.0), kills=("erp_cfm_spring",)),
    Mutant("error-correction-ignored", "RigidBodyCollection.errorCorrection ignored: X3D's default 0.8",
           f"{X_ITE} ignores ERP and CFM", reset("error_correction", lambda _: 0.8), kills=("bounce_apex",)),
    Mutant("surface-thickness-ignored", "RigidBodyCollection.contactSurfaceThickness ignored", IGNORED,
           _thickness_ignored, kills=("resting_penetration",)),
    # -- collision layout
    Mutant("collidable-translation-ignored", "CollidableShape/CollidableOffset translation ignored: each "
           "collidable at its parent's origin", IGNORED, geometries(lambda g: replace(g, position=np.zeros(3))),
           kills=("collision_filtering",)),
    Mutant("collidable-rotation-ignored", "CollidableShape/CollidableOffset rotation ignored", IGNORED,
           geometries(lambda g: replace(g, orientation=R.IDENTITY.copy())), kills=("incline",)),
    Mutant("round-shapes-along-z", "Cylinder and Cone collide with their axis along z, not y",
           "a port to ODE, whose cylinder's axis is z", geometries(_along_z), kills=("cylinder_cone_rest",),
           silent="37.4.3: 'If there is no bounding box, the results are implementation-dependent.'"),
    Mutant("cylinder-cone-as-boxes", "Cylinder and Cone collide as their bounding boxes",
           "an engine without cylinders or cones (a reading the clause allows outside a CollisionSpace with "
           "useGeometry TRUE: cylinder_cone_shape's conventions)",
           geometries(_as_box), kills=("cylinder_cone_shape", "collision_spaces"),
           fields=("CollisionSpace.useGeometry",)),
    Mutant("shape-bbox-ignored", "a collidable Shape's explicit bboxSize ignored: its geometry collides instead",
           IGNORED, geometries(_bbox_ignored), kills=("cylinder_cone_shape",)),
    Mutant("collider-not-filtering", "the collider does not filter: every body's collidables collide",
           X_ITE, every_body_collides, kills=("collision_filtering",)),
    Mutant("routed-contacts-ignored", "contacts ROUTEd into set_contacts ignored", f"{X_ITE} ignores set_contacts",
           _routed_contacts_ignored, kills=("routed_contacts",)),
    Mutant("joined-bodies-collide", "the collidables of two joined bodies collide", "missing exclusion",
           reset("collisions", lambda c: replace(c, excluded=set())), kills=("joined_overlap",),
           silent="the clause says nothing of whether two joined bodies' collidables collide (ODE's rule, Xj3D's)"),
    Mutant("watched-collections-unrun", "a collection only a CollisionSensor watches is never run: the sensor "
           "reports nothing", "collision detection run only for the colliders bodies use (x3drbp before issue 35)",
           reset("watched", lambda _: []), kills=("sensor_only",)),
    Mutant("nested-spaces-ignored", "a CollisionSpace inside another CollisionSpace ignored: one level of spaces "
           "traversed", "a collision traversal one level deep", reset("collisions", _nested_spaces_ignored),
           kills=("collision_spaces",)),
    # -- what the simulation reports or receives
    Mutant("forces-in-body-frame", "RigidBody.forces applied in the body's frame, not the world's", "wrong frame",
           relay=functools.partial(BodyFrameLoads, forces=True), kills=("world_frame_loads", "load_magnitude")),
    Mutant("torques-in-body-frame", "RigidBody.torques applied in the body's frame, not the world's",
           "wrong frame", relay=functools.partial(BodyFrameLoads, torques=True),
           kills=("world_frame_loads", "motor_anchoring")),
    Mutant("angular-velocity-in-body-frame", "angularVelocity reported in the body's frame", "wrong frame",
           relay=BodyFrameSpin, kills=("torque_free",)),
    Mutant("outputs-late", "body states reported one step late (before the last step call)", "late output",
           relay=LateState, kills=("free_fall", "auto_disable")),
    Mutant("contact-normal-flipped", "Contact.contactNormal points from geometry2 towards geometry1",
           "Xj3D and X_ITE (37.2.5.3: from body 1 to body 2)", relay=FlippedNormals, kills=("sensor_geometry",)),
)

BASES = tuple(dict.fromkeys(m.base for m in MUTANTS))
# per base, the mutant that injects nothing (the World untouched, the plain Relay): the wrapping
# alone, which must change no verdict
CONTROLS = tuple(Mutant(f"identity-{b}", "no bug: the wrapping alone", "none", relay=Relay, base=b) for b in BASES)
BY_NAME = {m.name: m for m in (*MUTANTS, *CONTROLS)}

"""Which case checks each statement of clause 37's text: docs/clause-coverage.md.

    .venv/bin/python -m conformance.clause_coverage

Every statement (conformance.clause_statements: the prose sentences, the signature rows and the
rows of Table 37.3) has one standing, the first that applies:
- checked: a sentence a spec basis quotes that a case is held to (conformance.case_bases reads
  which from the case's code; the basis's sentences are matched to the clause's, cut alike); a
  signature row whose field conformance.coverage finds a case covering or judging (an abstract
  type's row: the field of a concrete node of that type);
- unchecked: GAPS says what would show it, "a quote: ..." where a case's measure shows it
  already and its basis could quote it too (a measure held, as it should be, to a sentence it
  enforces more directly is named in what would be this statement's own);
- needs input events: INPUT_EVENTS says why only a field changed during a run would show it;
- not observable: REASONS says why;
- a row in none of these: coverage's standing for the field, its reason (not observable) or the
  case it awaits (pending, uncovered, exercised: unchecked).
The three dicts are keyed by the statements' ids; tests/test_clause_coverage.py fails while a
statement has no standing, an entry names no statement, or one outlives a check that came.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

from x3d_core import atomic, editions, schema
from x3d_core import fields as F

from conformance import case_bases, clause_statements, clause_text, coverage
from conformance.cases import BY_NAME, CASES, ROOT
from conformance.cases.case import Case, Mutation
from conformance.clause_statements import Clause, Statement
from conformance.results import SPEC

PAGE = os.path.join(ROOT, "docs", "clause-coverage.md")
CHECKED, UNCHECKED, INPUT, UNOBSERVABLE = "checked", "unchecked", "needs input events", "not observable"


def _ids(subclause: str, *places: int) -> tuple[str, ...]:
    """The ids of the sentences at those places of a subclause ("37.4.10 RigidBody", 12)."""
    return tuple(f"{subclause}/{k}" for k in places)


def _quote(what: str) -> str:
    return (f"a quote: shown already by {what}, a measure held to another sentence; a spec basis quoting this one "
            "checks it")


# -- not observable: why no verdict can turn on the statement ------------------------------------
_INTRO = "introduces: what the component, node or field is for; the sentences after it say what it does"
_MOTIVE = "motivates: why the model or the field is as it is, or what authors use it for; nothing a run does"
_ADVICE = "advice to authors (what to give, what to avoid): it asks nothing of an implementation"
_NOTE = "informative (a NOTE), and advice to authors: it asks nothing of an implementation"
_EXAMPLE = "informative (an EXAMPLE): it illustrates the sentence before it and asks nothing"
_INEXACT = ("says floating point and discrete steps make results inexact: the premise every tolerance is argued "
            "from (closed_forms), no behaviour of its own")
_TRADE = ("accuracy traded against stability: the clause prescribes no result for either, which is why a spec "
          "tolerance is honoured() and a rigid bound only graded (closed_forms)")
_RENDER = "rendering: what is drawn, and where, which no trace holds and x3drbp does not judge"
_RANGE = ("the field's range said again: its signature row gives it, and what an implementation does with a value "
          "outside it the clause does not say")
_UNDEFINED = "the clause's own words leave the result undefined: no result is wrong"
_IMPLEMENTATION = "implementation-dependent by the clause's own words: no result is wrong"
_NO_STOPS = ("{} has no limit fields (no minimum or maximum angle), so its joint limit is never reached and "
             "nothing here can act")
_LEVELS = ("support levels: x3drbp holds every implementation to level 2, all of Table 37.3, so what level 1 may "
           "leave out never shows")
_OFFSET = ("for a collidable on a body the clause contradicts itself (37.4.10: it sits at the body's location; "
           "docs/spec-loose-ends.md 22): both readings conform, and no case gives a body's collidable an offset; "
           "a collidable on no body has no body's center, and 37.4.2's sentence places it (checked)")
_FINITE_AXIS = ("says the axis is one the body rotates around, not how it enters the rotation's calculation (a body "
                "turns by its angular velocity, whatever this vector is): ODE's reading, finite about this axis only, "
                "is one implementation's, and no result follows from the clause (docs/spec-loose-ends.md 14)")
_SUPPORTED = ("'All fields fully supported': nothing of its own beyond the node's statements (its signature rows and "
              "sentences), each accounted for in its subclause")
REASONS: dict[str, str] = {
    **dict.fromkeys(_ids("37.1.1 Name", 1, 2), "names the component for a file's COMPONENT statement (7.2.5.4): how "
                    "a loader reads a file's header, on which no output of a run depends"),
    "37.1.2 Overview/1": _INTRO,
    "37.1.2 Overview/2": "points to a table of links (Table 37.1, which the text prints without rows)",
    **dict.fromkeys(_ids("37.2.1 Overview", 1, 2, 4), _INTRO),
    "37.2.1 Overview/3": ("the model every case assumes: a body's state is a pose and its velocities, all a trace "
                          "holds, so nothing in one could show a body deform"),
    "37.2.1 Overview/5": "how solvers go about it (many factors in parallel): no result of a run",
    **dict.fromkeys(_ids("37.2.1 Overview", 6, 8), _INEXACT),
    "37.2.1 Overview/7": _ADVICE,
    **dict.fromkeys(_ids("37.2.1 Overview", 9, 10, 11), _TRADE),
    "37.2.1 Overview/12": _RENDER,
    "37.2.1 Overview/13": _ADVICE,
    "37.2.1 Overview/14": ("the physics model and the visual one are separate models: which visual a body drives is "
                           "rendering"),
    "37.2.2.1 Event model evaluation/1": _MOTIVE,
    "37.2.2.1 Event model evaluation/2": "names the technique: no behaviour",
    "37.2.2.1 Event model evaluation/3": ("how often the physics runs within a frame's work: a trace holds one state a "
                                          "frame, and that the physics keeps pace with the frames is sentence 9, "
                                          "checked"),
    "37.2.2.1 Event model evaluation/6": ("the results modify the scene graph just before rendering: the order of the "
                                          "event cascade and rendering, neither of which a trace holds"),
    **dict.fromkeys(_ids("37.2.2.1 Event model evaluation", 7, 8), _MOTIVE),
    "37.2.2.1 Event model evaluation/10": _INTRO,
    "37.2.2.1 Event model evaluation/11": ("when in the cascade outputs are sent (the start of the next frame): a "
                                           "trace holds one state a frame, and the one frame this allows is in the "
                                           "clock measure's tolerance (closed_forms.ballistic)"),
    "37.2.2.2 Transformation hierarchy/2": ("authors may ROUTE outputs to the transformation hierarchy to move "
                                            "visuals: the event cascade and rendering"),
    "37.2.2.2 Transformation hierarchy/3": _INTRO,
    **dict.fromkeys(_ids("37.2.3 Bodies", 1, 3, 4), _INTRO),
    "37.2.3 Bodies/2": "lists the properties a body's fields hold; each field's sentences say what it does",
    "37.2.3 Bodies/7": "a RigidBody has no field that holds another body, so no scene can nest one",
    **dict.fromkeys(_ids("37.2.4.1 What a joint describes", 1, 2), _INTRO),
    **dict.fromkeys(_ids("37.2.4.2 Range of motion limits", 1, 2, 7, 8, 9), _INTRO),
    "37.2.4.2 Range of motion limits/3": ("'typically': it describes, prescribing nothing (each joint's limits are "
                                          "its own)"),
    **dict.fromkeys(_ids("37.2.4.2 Range of motion limits", 4, 10), _EXAMPLE),
    "37.2.4.2 Range of motion limits/5": ("introduces the limit fields, which have their own sentences where a joint "
                                          "has them (BallJoint, UniversalJoint and MotorJoint have none)"),
    "37.2.4.2 Range of motion limits/6": "names the limit fields: no behaviour",
    **dict.fromkeys(_ids("37.2.5.1 Initial coordinate system", 5, 6, 7), _ADVICE),
    "37.3.1 X3DNBodyCollidableNode/1": _INTRO,
    **dict.fromkeys(_ids("37.3.1 X3DNBodyCollidableNode", 3, 4), _OFFSET),
    "37.3.1 X3DNBodyCollisionSpaceNode/1": _INTRO,
    "37.3.1 X3DNBodyCollisionSpaceNode/2": ("optimisation: which kinds of space an implementation offers, and how it "
                                            "organises them, changes no contact"),
    "37.3.3 X3DRigidJointNode/1": "the type hierarchy: which fields a joint has (the signatures), no behaviour",
    **dict.fromkeys(_ids("37.3.3 X3DRigidJointNode", 3, 4), _MOTIVE),
    "37.3.3 X3DRigidJointNode/7": "introduces sentences 8 and 9, which say what the two values do",
    "37.3.3 X3DRigidJointNode/12": _INEXACT,
    "37.3.3 X3DRigidJointNode/13": _EXAMPLE,
    **dict.fromkeys(_ids("37.3.3 X3DRigidJointNode", 14, 15, 16),
                    "introduces the joints' error correction fields, which have their own sentences where a joint "
                    "has them (BallJoint has none)"),
    "37.3.3 X3DRigidJointNode/17": _ADVICE,
    "37.4.2 CollidableOffset/2": ("what the field holds, which its signature row gives (one X3DNBodyCollidableNode), "
                                  "accounted for there"),
    "37.4.2 CollidableOffset/3": _UNDEFINED,
    **dict.fromkeys(_ids("37.4.3 CollidableShape", 1), _INTRO),
    "37.4.3 CollidableShape/2": _RENDER,
    "37.4.3 CollidableShape/4": _RENDER,
    "37.4.3 CollidableShape/6": _NOTE,
    "37.4.3 CollidableShape/7": "leaves which geometry types collide to the implementation: none is wrong to refuse",
    "37.4.3 CollidableShape/8": _EXAMPLE,
    "37.4.3 CollidableShape/10": _IMPLEMENTATION,
    "37.4.4 CollisionCollection/14": _EXAMPLE,
    "37.4.4 CollisionCollection/17": _RANGE,
    "37.4.4 CollisionCollection/22": ("introduces a list the text does not print (Table 37.2's values; the UOM's are a "
                                      "description, not the clause)"),
    "37.4.5 CollisionSensor/4": ("speaks of a collidables field that CollisionSensor does not have (its signature has "
                                 "collider)"),
    **dict.fromkeys(_ids("37.4.5 CollisionSensor", 7, 8), _NOTE),
    "37.4.5 CollisionSensor/9": _UNDEFINED,
    "37.4.5 CollisionSensor/10": _LEVELS,
    "37.4.6 CollisionSpace/3": "optimisation: grouping for efficiency changes no contact",
    "37.4.6 CollisionSpace/4": ("the broad phase: how an implementation finds candidate pairs shows only in which "
                                "objects collide (sentence 5)"),
    "37.4.6 CollisionSpace/7": "a cost (more accurate, but slower): speed is no output",
    "37.4.6 CollisionSpace/8": _ADVICE,
    "37.4.7 Contact/1": _INTRO,
    **dict.fromkeys(_ids("37.4.7 Contact", 15, 16), _EXAMPLE),
    "37.4.7 Contact/23": "points to Table 37.2, which the text prints without rows",
    "37.4.8 DoubleAxisHingeJoint/9": _RANGE,
    "37.4.8 DoubleAxisHingeJoint/15": _MOTIVE,
    "37.4.9 MotorJoint/2": _MOTIVE,
    "37.4.9 MotorJoint/8": ("the clause says the angles are given, not what they do to the motion (MotorJoint has no "
                            "stops for them to act at): motor_axes checks ODE's echo of them in motorNAngle as a "
                            "convention (docs/spec-loose-ends.md 6)"),
    **dict.fromkeys(_ids("37.4.9 MotorJoint", 14, 15, 16, 17), _NO_STOPS.format("MotorJoint")),
    **dict.fromkeys(_ids("37.4.10 RigidBody", 1, 2, 3, 5), _INTRO),
    "37.4.10 RigidBody/7": ("unclear whose position, relative to what: with sentence 6 and 37.3.1's offset the clause "
                            "contradicts itself (docs/spec-loose-ends.md 22); both readings conform"),
    "37.4.10 RigidBody/9": _RENDER,
    "37.4.10 RigidBody/10": ("not rendered: rendering; nor modified by the physics: the model's own fields are in no "
                             "trace"),
    "37.4.10 RigidBody/11": _FINITE_AXIS,
    "37.4.10 RigidBody/20": ("a RigidBody holds no other body (no field for one; 37.2.3: no bodies within bodies), so "
                             "there are no sub-bodies to affect"),
    "37.4.10 RigidBody/22": _IMPLEMENTATION + " (and an SFMatrix3f always has nine values)",
    "37.4.10 RigidBody/23": ("an SFMatrix3f always holds nine values, and using only the first six would drop a "
                             "diagonal term, which no implementation found does (docs/spec-loose-ends.md 10); "
                             "torque_free's symmetric tensor passes every layout found"),
    "37.4.10 RigidBody/31": _MOTIVE,
    **dict.fromkeys(_ids("37.4.10 RigidBody", 36, 37, 38),
                    "informative (an EXAMPLE): it shows one reading of sentence 30 (a force -d v), which damping "
                    "accepts among the others found (docs/spec-loose-ends.md 1)"),
    "37.4.10 RigidBody/41": ("read as written (a velocity imposed every frame) it contradicts sentence 43, which "
                             "projectile checks (the velocity fields report the changed values); read as the starting "
                             "velocity, it is sentence 42's"),
    **dict.fromkeys(_ids("37.4.10 RigidBody", 45, 49), _ADVICE),
    "37.4.10 RigidBody/51": _MOTIVE,
    "37.4.11 RigidBodyCollection/1": _INTRO,
    "37.4.11 RigidBodyCollection/2": _RENDER,
    **dict.fromkeys(_ids("37.4.11 RigidBodyCollection", 5, 6), _IMPLEMENTATION),
    "37.4.11 RigidBodyCollection/10": _MOTIVE,
    "37.4.11 RigidBodyCollection/12": _NOTE,
    "37.4.11 RigidBodyCollection/19": coverage.REASONS["RigidBodyCollection.preferAccuracy"],
    "37.4.11 RigidBodyCollection/20": "a cost in speed and memory: no output",
    "37.4.11 RigidBodyCollection/21": "the performance hint's default: no result is wrong under either value",
    "37.4.11 RigidBodyCollection/22": ("how many solver iterations run is inside the solver: the clause prescribes no "
                                       "result for any number of them (docs/spec-loose-ends.md 20)"),
    "37.4.11 RigidBodyCollection/23": _INTRO,
    "37.4.11 RigidBodyCollection/24": coverage.REASONS["RigidBodyCollection.iterations"],
    "37.4.11 RigidBodyCollection/25": _MOTIVE,
    "37.4.11 RigidBodyCollection/27": _RANGE,
    "37.4.11 RigidBodyCollection/33": ("says what combining the two can emulate: erp_cfm_spring's spring is one such, "
                                       "held to sentences 29 to 32"),
    "37.4.11 RigidBodyCollection/36": _MOTIVE,
    "37.4.12 SingleAxisHingeJoint/2": _INTRO,
    "37.4.13 SliderJoint/3": ("advice to authors ('should'): what an implementation does with an axis not of unit "
                              "length the clause does not say"),
    "37.4.14 UniversalJoint/4": ("a rule for the scene's author (sentence 5 leaves any other scene undefined): no run "
                                 "of a scene that keeps it can break it"),
    "37.4.14 UniversalJoint/5": _UNDEFINED,
    **dict.fromkeys(_ids("37.4.14 UniversalJoint", 6, 7, 8, 9), _NO_STOPS.format("UniversalJoint")),
    "37.5 Support levels/1": _INTRO,
    **dict.fromkeys(("Table 37.3/1 prerequisites", "Table 37.3/2 prerequisites"),
                    "the components a level needs besides this one: their clauses' to define and judge (every "
                    "case's scene uses Grouping, Shape and Geometry3D nodes)"),
    **dict.fromkeys(("Table 37.3/1 X3DNBodyCollidableNode", "Table 37.3/1 X3DNBodyCollisionSpaceNode",
                     "Table 37.3/2 X3DRigidJointNode"), "an abstract type: no support of its own (n/a)"),
    **dict.fromkeys((f"Table 37.3/1 {n}" for n in ("CollidableOffset", "CollidableShape", "CollisionCollection",
                                                   "CollisionSensor", "CollisionSpace")), _LEVELS),
    **dict.fromkeys((f"Table 37.3/2 {n}" for n in ("BallJoint", "CollisionSensor", "Contact", "DoubleAxisHingeJoint",
                                                   "MotorJoint", "RigidBody", "RigidBodyCollection",
                                                   "SingleAxisHingeJoint", "SliderJoint", "UniversalJoint")),
                    _SUPPORTED),
    # a row whose coverage reason is another field's: the sentence's own reason
    "RigidBody.finiteRotationAxis": _FINITE_AXIS,
}

# -- needs input events: only a field changed during a run shows it ----------------------------
_SCRIPT = ("a Contact's own value differs from its collection's, which every Contact a collision makes carries "
           "(37.4.4), only where a Script changes the contact on its way to set_contacts: input events x3drbp "
           "does not send; the collection's twin sentence of 37.4.4 is where the value is accounted for")
INPUT_EVENTS: dict[str, str] = {
    "37.2.2.1 Event model evaluation/4": ("that the physics runs after a frame's user input shows only in the frame "
                                          "in which a field an event sets takes effect"),
    "37.2.2.1 Event model evaluation/5": ("where in the execution model's steps (4.4.8.3) the physics runs shows only "
                                          "in the frame in which an event's change takes effect"),
    "37.4.4 CollisionCollection/4": ("a Script between the sensor and set_contacts changing contacts: Scripts and "
                                     "their events, which x3drbp does not run"),
    **dict.fromkeys(_ids("37.4.7 Contact", *range(9, 15), *range(17, 23)), _SCRIPT),
    "37.4.10 RigidBody/44": "a velocity set during the run: an input event",
    "37.4.10 RigidBody/48": "a position or orientation set during the run: an input event",
    "37.4.11 RigidBodyCollection/7": ("a joint outside every collection's joints is made only by an event taking it "
                                      "out (set_joints) during a run: a file puts each joint in a joints field, a "
                                      "joint node being no child node"),
    **dict.fromkeys(_ids("37.4.11 RigidBodyCollection", 17, 18),
                    "Contact instances a Script reuses from frame to frame, with new values, sent to set_contacts: "
                    "input events x3drbp does not send"),
}

# -- unchecked: observable, and what would show it --------------------------------------------
_TRANSFORMED = ("a case: a RigidBodyCollection inside a turned and translated Transform: its bodies start where the "
                "file puts them in world coordinates and fall along world -y, unmoved by the Transform")
_BREAK = ("a measure: body1AnchorPoint held to body2AnchorPoint while the joint holds, as ball_chain's is for "
          "BallJoint; {} reads them only by a convention (closed_forms.ANCHOR_OUTPUTS)")
_SOFT_CONTACT = ("a case: a ball started into a floor with ERROR_REDUCTION applied: the depth closes by the fraction "
                 "softnessErrorCorrection each step, none at 0, all at once at 1 (contact_defaults reads the field "
                 "only as what the Contacts carry)")
_STOP_CORRECTION = ("a case: a {} started past its stop: the error closes by the fraction {} each step, none at 0, "
                    "all at once at 1 ({})")
_BODY_CORRECTION = ("a case: a ball started into a floor, no maxCorrectionSpeed cap: the depth closes by the fraction "
                    "errorCorrection each step, none at 0, all at once at 1 (correction_speed's ball rises at the "
                    "cap, a convention; erp_cfm_spring reads errorCorrection only in the spring it makes with "
                    "constantForceMix)")
_SPACE_GEOMETRY = ("a case: a CollisionSpace with useGeometry TRUE holding a sphere that passes a box's corner within "
                   "its bounding box but clear of it: no contact (coverage.REASONS calls the field a hint, which "
                   "holds for FALSE, allowing bounds, not for TRUE)")
_COLLECTIONS = ("a case: two collections with different gravity, a body in each one's bodies: each falls at its own "
                "collection's gravity (every case has one collection, so evaluating every RigidBody whatever its "
                "collection passes them all)")
# statements a measure shows in part, or shows but is held (a measure has one basis) to a sentence it
# enforces more directly: what would be each one's own
_ANCHOR_KINDS = ("a measure over every joint kind with anchor outputs (BallJoint, SingleAxisHingeJoint, "
                 "DoubleAxisHingeJoint, UniversalJoint): body1AnchorPoint held to body2AnchorPoint while each holds, "
                 "apart for one pulled apart (ball_chain's anchor gap shows it for BallJoint alone, held to 37.4.1's "
                 "like sentences, the more specific; the others' outputs are read only by a convention, "
                 "closed_forms.ANCHOR_OUTPUTS)")
_ENABLED_AXES = ("a case: MotorJoints with autoCalc FALSE, enabledAxes 1 and 2, and a torque on every axis: only the "
                 "enabled axes turn their bodies (motor_axes and motor_anchoring give torques on enabled axes only, "
                 "so their enabledAxes edits show an axis needed and lost, never a disabled one left acting)")
_DAMPING_SWITCH = ("a case: two bodies with the same damping factors, autoDamp TRUE and FALSE: the first loses a "
                   "share of each velocity, linear and angular, in proportion to it, the second none, held to "
                   "sentences 32 to 35 (damping's measures show TRUE's, held to sentences 29 and 30, which they "
                   "enforce more directly; free_fall's and projectile's bodies FALSE's, at X3D's default factors, "
                   "held to their motion's own sentences)")
_DISABLE_CONDITIONS = ("a case: a drifting body whose speeds both stay above disableLinearSpeed and "
                       "disableAngularSpeed is never disabled, under either reading of 'any one of these values', "
                       "beside one under both that is: the fields are the conditions ({} bodies are each under one "
                       "threshold at least, and its at-rest measures, held to sentences {}, show only that a body "
                       "meeting them is at rest; a basis joining this sentence to those takes in the motive "
                       "between)")
_DISABLE_SWITCH = ("a case, with sentence {0}'s: like bodies under the disable thresholds, autoDisable TRUE on one "
                   "only: it alone is held still from disableTime, the other never, held to sentences {0} and {1} "
                   "({2}'s at-rest measures show TRUE's effect, held to sentences {3}, which they enforce more "
                   "directly)")
_MASS = ("a case: one force on bodies of 0.5 and 2 kg and one that gives no mass: each accelerates at F/m, m in "
         "kilograms and 1 kg by default, held to sentences 27 and 28 (constant_force's acceleration, F/m with "
         "m = 2 kg, shows the unit, held to the forces sentences its case is for; every scene that pushes a body "
         "gives its mass)")
GAPS: dict[str, str] = {
    "37.2.2.2 Transformation hierarchy/1": _TRANSFORMED,
    "37.2.3 Bodies/5": ("a case: a body no joint holds beside a jointed pair in one collection: it moves as a free "
                        "body (a ballistic fall) while the pair swings (free_fall's ball, alone and jointless, shows "
                        "it, held to the collection's gravity sentences, the ones its case is for)"),
    "37.2.3 Bodies/6": _TRANSFORMED,
    **dict.fromkeys(_ids("37.2.5.1 Initial coordinate system", 1, 2),
                    ("a case: a SliderJoint whose bodies start apart along its axis, or a hinge whose body starts "
                     "turned about it, its angle read: separation (angle) 0 at the start and the stops counted from "
                     "there (every slider case starts its bodies coincident, and every hinge whose angle is read "
                     "unturned, so outputs taken from the world frame read alike: slider_bounce's separation measure "
                     "cannot tell them apart)")),
    "37.2.5.1 Initial coordinate system/3": (
        "a case: a joint whose bodies start turned about another direction than its axes, given in world "
        "coordinates: the bodies turn about the world axes (every joint with an axis joins bodies that start "
        "unturned, or turned about that axis as newtons_cradle's Ball1, so an axis read in a body's frame passes; "
        "the anchor half is shown: ball_chain, hinge2_steering and universal_joint fail when their anchorPoint is "
        "edited, and pendulum_period holds the hinge's own 'centered on the anchorPoint described in world "
        "coordinates')"),
    "37.2.5.1 Initial coordinate system/4": (
        "a measure held to it: constant_force's acceleration (F/m with m = 2 kg) shows a mass in kilograms, held "
        "to the forces sentences its case is for, and a mass case (37.4.10 RigidBody/27's) would quote the mass "
        "field's own 'in kilograms', the more specific"),
    **dict.fromkeys(_ids("37.2.5.2 Breaking joints", 1, 2, 3), _ANCHOR_KINDS),
    "37.3.3 X3DRigidJointNode/2": ("a measure held to it: force_output's Named and Pair measures (each hinge reports "
                                   "exactly the outputs its forceOutput names) show it, held to sentence 6, which "
                                   "says it more precisely; a basis joining the two takes in the motives 3 and 4"),
    "37.3.3 X3DRigidJointNode/5": _quote("force_output's Named and Pair measures (each hinge reports exactly the "
                                         "outputs its forceOutput names; their basis, sentence 6, can quote 5 and "
                                         "6)"),
    "37.4.3 CollidableShape/3": ("a measure held to it: a ball dropped onto a floor meets it where its body has "
                                 "carried its shape, first at t = sqrt(2 h0 / g) (bounce_apex's impacts and "
                                 "sensor_geometry's contact positions show it, held to the bounce and the Contact "
                                 "sentences, the ones their measures are for)"),
    "37.4.3 CollidableShape/5": ("a measure held to it alone: the clause fixes which geometry collides only for a "
                                 "Shape with an explicit bboxSize, where cylinder_cone_shape's OnBox shows it, held "
                                 "to sentence 9, which says it more precisely (a basis joining the two takes in the "
                                 "NOTE, sentence 7 and the EXAMPLE between); cylinder_cone_rest's rest heights are "
                                 "a convention, sentence 10 leaving a shape without one implementation-dependent"),
    "37.4.4 CollisionCollection/2": ("a case: a ball whose shape is in one CollisionSpace resting on a box in "
                                     "another, both spaces in the collider: spaces collide against each other "
                                     "(collidable_layout's OnSpace meets a space's box with a bare collidable, held "
                                     "to 37.4.6's CollisionSpace sentence, the more specific for a space's box)"),
    "37.4.4 CollisionCollection/15": ("a case: a box resting on a floor with CONSTANT_FORCE applied sinks deeper the "
                                      "larger softnessConstantForceMix (contact_defaults reads the field only as what "
                                      "the Contacts carry)"),
    **dict.fromkeys(_ids("37.4.4 CollisionCollection", 16, 18), _SOFT_CONTACT),
    "37.4.6 CollisionSpace/2": ("a case: a CollisionSpace nested in another in the collider: its box holds a ball, as "
                                "collidable_layout's space does"),
    "37.4.6 CollisionSpace/5": ("a case: a CollisionSensor on a collection holding a space: its contacts name the "
                                "space's own collidables (geometry1, geometry2), and a ball within the space's bounds "
                                "but clear of its boxes touches nothing"),
    "37.4.6 CollisionSpace/6": _SPACE_GEOMETRY,
    **dict.fromkeys(_ids("37.4.8 DoubleAxisHingeJoint", 8, 10), _STOP_CORRECTION.format(
        "double hinge", "stopErrorCorrection1 (suspensionErrorCorrection, off the suspension's rest)",
        "hinge2_stop_bounce's and hinge2_suspension's edits of them turn only conventions")),
    "37.4.8 DoubleAxisHingeJoint/13": ("a case: hinge2_suspension at two suspensionForce values: the larger sinks "
                                       "further"),
    "37.4.8 DoubleAxisHingeJoint/14": ("a case: a loaded double hinge with suspensionForce 0: the wheel keeps its "
                                       "place along axis 1 (hinge2_suspension holds only its sink at 0.01)"),
    **dict.fromkeys(_ids("37.4.8 DoubleAxisHingeJoint", 19, 20), _BREAK.format("hinge2_steering")),
    **dict.fromkeys(_ids("37.4.9 MotorJoint", 9, 11), _ENABLED_AXES),
    "37.4.9 MotorJoint/10": "a case: a MotorJoint with enabledAxes 0 and axis torques set: neither body turns",
    "37.4.10 RigidBody/4": ("a measure held to it: a body rests on a floor through its geometry field's collidable "
                            "(collision_filtering's Kept shows it, the edit taking its shape away failing the case, "
                            "held to 37.4.4's collidables sentence, the one its case is for)"),
    "37.4.10 RigidBody/6": ("a measure held to it: a body's collidable, given no offset, collides at the body's place "
                            "(sensor_geometry's contact positions under the ball's centre, and every contact case, "
                            "show it under both of the clause's readings, held to the Contact's and the contacts' "
                            "own sentences)"),
    "37.4.10 RigidBody/19": ("a case: a body with useGlobalGravity FALSE in a collection of non-default gravity: its "
                             "neighbour falls at that gravity, held to sentences 17 to 19 (gravity_off's Falling "
                             "shows it, held to 37.4.11's gravity sentences: the only one of their measures at the "
                             "default 9.8 m/s2)"),
    **dict.fromkeys(_ids("37.4.10 RigidBody", 27, 28), _MASS),
    **dict.fromkeys(_ids("37.4.10 RigidBody", 32, 33, 34, 35), _DAMPING_SWITCH),
    "37.4.10 RigidBody/42": ("a case: a body given both linearVelocity and forces: v = v0 + (F/m + g) t, not v0 held "
                             "every frame"),
    "37.4.10 RigidBody/46": ("a measure: each body's first frame against the file's position and orientation, "
                             "within one step's motion (every closed form starts there, and the edits of them fail "
                             "torque_free and pendulum_period, held to the inertia's and the hinge's sentences)"),
    "37.4.10 RigidBody/47": ("a measure: the reported positions against the motion the reported velocities show, "
                             "with no clock (closed_forms.clock_free_acceleration fits the two): every case reads "
                             "position and orientation as the current state, held to what moves its bodies, and "
                             "ballistic's own position measure is the physics clock's convention"),
    "37.4.10 RigidBody/50": _DISABLE_CONDITIONS.format("auto_disable's", "52 and 53"),
    "37.4.10 RigidBody/54": ("a case: a drifting body with disableLinearSpeed, disableAngularSpeed and disableTime set "
                             "and autoDisable left FALSE: it never stops (auto_disable's edit dropping autoDisable "
                             "turns only a convention)"),
    "37.4.10 RigidBody/55": _DISABLE_SWITCH.format(54, 55, "auto_disable", "52 and 53"),
    "37.4.11 RigidBodyCollection/3": _COLLECTIONS,
    "37.4.11 RigidBodyCollection/4": ("a measure held to it: every joint case's joint, listed in joints, acts "
                                      "between its bodies (pendulum_period's arm swings on its hinge), each measure "
                                      "held to its joint's own sentence, the more specific"),
    "37.4.11 RigidBodyCollection/11": ("a case: a box started 1 cm into a floor in a collection that sets no "
                                       "contactSurfaceThickness: it is pushed out to the surface "
                                       "(resting_penetration's edit dropping the field turns only a convention)"),
    **dict.fromkeys(_ids("37.4.11 RigidBodyCollection", 26, 28), _BODY_CORRECTION),
    "37.4.11 RigidBodyCollection/34": ("a measure held to it: the collider's contacts act with no ROUTE "
                                       "(collision_filtering's Kept rests on the floor through the collider alone, "
                                       "the edit taking it away failing the case, held to 37.4.4's collidables "
                                       "sentence, the one its case is for; routed_contacts routes its contacts)"),
    "37.4.11 RigidBodyCollection/35": _DISABLE_CONDITIONS.format("collection_auto_disable's", "37 and 38"),
    "37.4.11 RigidBodyCollection/39": ("a case: a collection setting disableLinearSpeed, disableAngularSpeed and "
                                       "disableTime with autoDisable left FALSE: its drifting bodies never stop "
                                       "(collection_auto_disable's edit dropping autoDisable fails the case only "
                                       "because its bodies then keep moving, which no measure holds as right)"),
    "37.4.11 RigidBodyCollection/40": _DISABLE_SWITCH.format(39, 40, "collection_auto_disable", "37 and 38"),
    "37.4.12 SingleAxisHingeJoint/4": ("a measure held to sentences 3 and 4 of a hinge between two moving bodies: "
                                       "pendulum_period's period (sentence 3) fails with Bob off the hinge, but its "
                                       "body2 is fixed, so a hinge ignoring body2 (body1 hinged to the world) passes "
                                       "it; double_pendulum_energy's Elbow and newtons_cradle's hinges (body2 the "
                                       "ball) show both sides, held to sentence 1 and to the bounce sentence"),
    **dict.fromkeys(_ids("37.4.12 SingleAxisHingeJoint", 9, 10), _STOP_CORRECTION.format(
        "hinge", "stopErrorCorrection", "hinge_bounce's rebound fails only where the correction throws the arm "
        "past its start, as the default 0.8 does, and passes one that corrects nothing")),
    "37.4.12 SingleAxisHingeJoint/11": ("a measure: |angle| the arm's turn from its start and |angleRate| its rate, "
                                        "from the bodies' poses, as hinge2_steering's is for the double hinge "
                                        "(hinge_limits reads angle only against the limits, hinge_bounce angleRate "
                                        "only for a graded rebound)"),
    **dict.fromkeys(_ids("37.4.12 SingleAxisHingeJoint", 12, 13), _BREAK.format("pendulum_period")),
    "37.4.13 SliderJoint/2": ("a measure: the bodies' relative motion across axis stays 0 (slider_bounce's rebound "
                              "and minimum stop and slider_force's rate fail with axis ignored, held to their own "
                              "fields' sentences; slider_bounce's momentum, held to sentence 1, holds for any axis)"),
    **dict.fromkeys(_ids("37.4.13 SliderJoint", 10, 11), _STOP_CORRECTION.format(
        "slider", "stopErrorCorrection", "slider_bounce's edit of it turns only a convention")),
    "37.4.14 UniversalJoint/3": ("a measure: the two bodies' turns about axis1 x axis2 agree (universal_joint holds "
                                 "only the axes perpendicular)"),
    **dict.fromkeys(_ids("37.4.14 UniversalJoint", 10, 11), _BREAK.format("universal_joint")),
    # rows coverage accounts for by a reason that is an argument from a case, not a field nothing shows
    "RigidBody.useFiniteRotation": ("a mutation that edits it, judged where the rotation update follows it (ODE): "
                                    "finite_rotation sets it and its spec measure fails the first-order update, but "
                                    "MuJoCo, the reference, turns every body by the exponential map whatever it says, "
                                    "so no edit of the scene shows there"),
    "RigidBodyCollection.bodies": _COLLECTIONS,
    "CollisionSpace.useGeometry": _SPACE_GEOMETRY,
}


# -- the accounting ---------------------------------------------------------------------------

@dataclass
class Standing:
    """A statement, its standing, and what it rests on."""
    statement: Statement
    kind: str = ""  # CHECKED, UNCHECKED, INPUT, UNOBSERVABLE; "" for none
    by: list[str] = field(default_factory=list)  # what checks it, as the page shows it
    mutations: list[str] = field(default_factory=list)  # 'case: edit' of the spec mutations
    note: str = ""  # the reason, or what would show it


def read() -> Clause | None:
    """The clause's statements, or None where its text is not here."""
    text = clause_text.read()
    return None if text is None else clause_statements.read(text)


def _edit(mutation: Mutation) -> str:
    return coverage.edit(mutation) if mutation.old else "its runs replaced"


def _spec_mutations(case: Case) -> list[str]:
    """'case: edit' for each mutation that must turn the case's verdict to a spec violation (not
    the graded ones, which push an accuracy grade past its bound)."""
    return [f"{case.name}: {_edit(m)}" for m in case.mutations if m.spec and not m.grades]


def _quoting(clause: Clause) -> dict[str, dict[str, list[Case]]]:
    """Sentence id -> basis name -> the cases held to that spec basis, which quotes the sentence."""
    out: dict[str, dict[str, list[Case]]] = {}
    for case in CASES:
        for name, basis in case_bases.held_to(case).items():
            if basis.kind == SPEC:
                for sid in (sid for quote in basis.quotes for sid in clause.quoted(quote)):
                    out.setdefault(sid, {}).setdefault(name, []).append(case)
    return out


@dataclass
class _Fields:
    """What conformance.coverage finds for each field of a concrete node."""
    rows: dict[tuple[str, str], coverage.Row]
    covering: dict[tuple[str, str], list[str]]  # the cases with a mutation that changes the field
    edits: dict[tuple[str, str], list[str]]  # its spec edits, 'case: edit'


def _fields() -> _Fields:
    found = _Fields({(r.node, r.name): r for r in coverage.rows()}, {}, {})
    for case in CASES:
        for m in case.mutations:
            for f in coverage.touched(case, m):
                if case.name not in found.covering.setdefault(f, []):
                    found.covering[f].append(case.name)
                if m.spec and not m.grades:
                    found.edits.setdefault(f, []).append(f"{case.name}: {_edit(m)}")
    return found


def _concrete(node: str) -> list[str]:
    """The node itself, or for an abstract type the concrete RigidBodyPhysics nodes of it."""
    t = schema.definition(node)
    if not t.abstract:
        return [node]
    return sorted(n for n, d in schema.NODE_TYPES.items()
                  if d.component.startswith("RigidBodyPhysics") and not d.abstract and d.is_a(node))


def _field_name(st: Statement) -> str:
    """A signature row's field by its X3D 4.0 name, which coverage keys it by."""
    renamed = editions.RENAMED.get(st.node, {}) | editions.MISPRINTS.get(st.node, {})
    return renamed.get(st.row.name, st.row.name)


def _coverage_rows(st: Statement, found: _Fields) -> list[coverage.Row]:
    return [found.rows[(n, _field_name(st))] for n in _concrete(st.node) if (n, _field_name(st)) in found.rows]


def _check_row(s: Standing, found: _Fields) -> None:
    """Checked where a case covers or judges the field (of any concrete node, for an abstract row)."""
    for r in _coverage_rows(s.statement, found):
        covering = found.covering.get((r.node, r.name), [])
        if covering:
            s.by.append(f"covered ({r.node}): {', '.join(covering)}")
        if r.judged:
            s.by.append(f"judged ({r.node}): {', '.join(r.judged)}")
        s.mutations += found.edits.get((r.node, r.name), [])
        s.mutations += [m for c in r.judged for m in _spec_mutations(BY_NAME[c])]
    if s.by:
        s.kind = CHECKED


def _row_otherwise(s: Standing, found: _Fields) -> None:
    """An unchecked row's standing as coverage gives it: its reason, or the case it awaits."""
    rows = _coverage_rows(s.statement, found)
    if not rows:
        return
    r = rows[0]
    s.kind, s.note = {"reason": (UNOBSERVABLE, r.reason),
                      "pending": (UNCHECKED, f"a case is being written: {r.pending}"),
                      "uncovered": (UNCHECKED, r.gap),
                      "exercised": (UNCHECKED, f"{', '.join(r.exercised)} sets it, but no mutation edits it"),
                      }.get(coverage.kind(r), ("", ""))


def _check_sentence(s: Standing, quoting: dict[str, dict[str, list[Case]]]) -> None:
    for name, cases in sorted(quoting.get(s.statement.id, {}).items()):
        s.kind = CHECKED
        s.by.append(f"`{name}`: {', '.join(c.name for c in cases)}")
        s.mutations += [m for c in cases for m in _spec_mutations(c)]


ENTRIES = ((UNCHECKED, GAPS), (INPUT, INPUT_EVENTS), (UNOBSERVABLE, REASONS))


def standings(clause: Clause) -> list[Standing]:
    """Every statement with its standing, in the text's order: checked, else the module's entry for
    it, else (a row) coverage's."""
    quoting, found = _quoting(clause), _fields()
    out = []
    for st in clause.statements:
        s = Standing(st)
        if st.row is not None:
            _check_row(s, found)
        else:
            _check_sentence(s, quoting)
        s.mutations = list(dict.fromkeys(s.mutations))
        if not s.kind:
            s.kind, s.note = next(((k, d[st.id]) for k, d in ENTRIES if st.id in d), ("", ""))
        if not s.kind and st.row is not None:
            _row_otherwise(s, found)
        out.append(s)
    return out


# -- the page ---------------------------------------------------------------------------------

def _cell(text: str) -> str:
    return text.replace("|", "\\|")


def _default(row) -> str:
    if row.access == "outputOnly":
        return ""
    if row.type.kind == "node" or (row.type.multi and F.values_equal(row.type, row.default, F.empty(row.type))):
        return "`[]`" if row.type.multi else "`NULL`"
    return f"`{F.format_vrml(row.type, row.default)}`"


def _range(row) -> str:
    return row.range.token() if row.range is not None else ", ".join(row.accepts)


def _place(st: Statement) -> str:
    """A statement's id within its subclause: a sentence's place, a table row's id."""
    return st.id.removeprefix(f"{st.number} {st.name}/")


HEADER = """\
Generated by `.venv/bin/python -m conformance.clause_coverage` from the clause's text
(`../shared/reference/clause37-rigid-body-physics.txt`), the cases and `conformance/coverage.py`
(do not edit; `tests/test_clause_coverage.py` checks it is current and that every statement has a
standing). The {o} not observable include {i} that **need input events**: only a field changed
during a run (by an event, a Script, a user) would show them, and x3drbp's runs send none.

**Statements.** Every prose sentence of each subclause, numbered within it, under the subclause's
number and name as the text prints them (an id reads `37.4.10 RigidBody/12`); a numbered list goes
on the sentence whose colon introduces it. EXAMPLE and NOTE paragraphs are sentences too: being
informative they ask nothing, so they are not observable unless a case holds a reading one of them
fixes. Every row of a node signature (field, access, type, default, range, as
`x3d_core/clause37.py` reads them; an id reads `RigidBody.mass`), and every row of Table 37.3, a
level's prerequisite components taken as one. Headings and table titles are not statements: a
heading names the subclause its statements are listed under (one that only heads further
subclauses, such as 37.2.2, lists none), a title names a table (Tables 37.1 and 37.2 print no
rows; the sentences pointing to them are statements).

**Checked**: a sentence, where a case is held to a spec basis that quotes it (a basis quotes whole
sentences verbatim; its sentences are matched to the clause's, both cut by
`conformance/clause_text.py`; the bases a case is held to are read from its code by
`conformance/case_bases.py`), named by the basis constant and the cases held to it; a signature
row, where `conformance/coverage.py` finds a case that covers the field (a mutation of the case's
scene changes it) or judges it (an output the case reads); an abstract type's row, by that field
of its concrete nodes.

**Spec mutations**: the mutations of those cases with `Mutation.spec` True, the graded ones left
out; `tests/test_conformance.py::test_case_fails_when_mutated` checks that each turns the case's
verdict to "violates the spec" where the case is judged (where no backend passes the case: that it
makes a measure fail that passed). For a sentence, every spec mutation of the cases held to its
basis: the verdict turns through whichever measure fails, not necessarily the one quoting the
sentence. For a covered row, the spec mutations that change the field; for a judged row, also
the judging cases' spec mutations. An empty cell on a checked statement means no spec mutation
turns a verdict there, only a convention's edit ({e} statements: {empty}).

**Unchecked**: a trace or an output could show it, and no case does: what would. "a quote" marks
one that a case's measure shows already, held to another sentence: a spec basis quoting this one
checks it; "a case" or "a measure", one that needs a scene or a measure still to write (a measure
has one basis, the sentence it enforces most directly: one that shows this statement too, but is
held to a more specific sentence, is named there, not moved). **Not
observable**: why no verdict can turn on it (rendering, the X3D event cascade, what the clause
leaves undefined or to the implementation, a sentence that only introduces, motivates or advises).
"""


WHY = "checked by; or why not, or what would check it"


def render(table: list[Standing]) -> str:
    """docs/clause-coverage.md's text."""
    kinds = [s.kind for s in table]
    empty = [s.statement.id for s in table if s.kind == CHECKED and not s.mutations]
    lines = ["# Clause coverage: which case checks each statement of clause 37", "",
             f"{len(table)} statements: {kinds.count(CHECKED)} checked, {kinds.count(UNCHECKED)} unchecked, "
             f"{kinds.count(UNOBSERVABLE) + kinds.count(INPUT)} not observable", "",
             HEADER.format(o=kinds.count(UNOBSERVABLE) + kinds.count(INPUT), i=kinds.count(INPUT), e=len(empty),
                           empty=", ".join(f"`{k}`" for k in empty) or "none").rstrip()]
    heading = None
    for s in table:
        st = s.statement
        if (st.number, st.name) != heading:
            heading, kind = (st.number, st.name), None
            lines += ["", f"## {st.number} {st.name}"]
        if (st.row is not None) != kind:
            kind = st.row is not None
            lines += ["", f"| field | access | type | default | range | standing | {WHY} | spec mutations |",
                      "|---|---|---|---|---|---|---|---|"] if kind else \
                     ["", f"| | statement | standing | {WHY} | spec mutations |", "|---|---|---|---|---|"]
        tail = f"{s.kind} | {_cell('<br>'.join(s.by) or s.note)} | {_cell('<br>'.join(s.mutations))} |"
        if st.row is not None:
            lines.append(f"| `{st.row.name}` | {st.row.access} | {st.row.type.name} | {_cell(_default(st.row))} | "
                         f"{_cell(_range(st.row))} | " + tail)
        else:
            lines.append(f"| {_place(st)} | {_cell(st.text)} | " + tail)
    return "\n".join(lines) + "\n"


def main() -> int:
    clause = read()
    if clause is None:
        print(f"conformance.clause_coverage: clause 37's text is not at {clause_text.TEXT}")
        return 1
    atomic.write_text(PAGE, render(standings(clause)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

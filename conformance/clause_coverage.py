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

from x3d_core.files import atomic
from x3d_core.model import editions
from x3d_core.model import schema
from x3d_core.model import fields as F

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
# a joint's two anchor outputs tell a break only compared, which the clause's other reading of them rules out
_FRAME_UNDEFINED = ("the clause leaves the anchor outputs' frame undefined (docs/spec-loose-ends.md 22.1): compared, "
                    "the two values show a break only in the world reading (x3drbp's, judged by the convention "
                    "closed_forms.ANCHOR_OUTPUTS), and in each body's own frame, the clause's other reading, they "
                    "differ while the joint holds, so no measure both readings pass holds them to it (what both "
                    "share, each value the anchor as its own body carries it, joint_anchor_outputs checks): both "
                    "readings conform")
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
    "37.4.1 BallJoint/3": _FRAME_UNDEFINED,
    "37.2.5.2 Breaking joints/2": _FRAME_UNDEFINED,
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
    "37.4.8 DoubleAxisHingeJoint/20": _FRAME_UNDEFINED,
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
    **dict.fromkeys(_ids("37.4.12 SingleAxisHingeJoint", 13), _FRAME_UNDEFINED),
    "37.4.13 SliderJoint/3": ("advice to authors ('should'): what an implementation does with an axis not of unit "
                              "length the clause does not say"),
    "37.4.14 UniversalJoint/4": ("a rule for the scene's author (sentence 5 leaves any other scene undefined): no run "
                                 "of a scene that keeps it can break it"),
    "37.4.14 UniversalJoint/5": _UNDEFINED,
    "37.4.14 UniversalJoint/11": _FRAME_UNDEFINED,
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
    "37.2.5.2 Breaking joints/3": ("a break, which sentence 2 ties to 'the input from the last frame': an event moving "
                                   "a body past what its joint holds; a file's own scene only lets a joint yield as "
                                   "its softness allows, which the clause does not call broken (ball_chain's edit "
                                   "fixing Link5, a loop a soft joint closes, is graded)"),
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
# statements a measure shows in part, or shows but is held (a measure has one basis) to a sentence it
# enforces more directly: what would be each one's own
GAPS: dict[str, str] = {
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
    for f, case_name, shown in coverage.mutant_covers():
        if case_name not in found.covering.setdefault(f, []):
            found.covering[f].append(case_name)
        found.edits.setdefault(f, []).append(f"{case_name}: {shown}")
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
`x3d_core/model/clause37.py` reads them; an id reads `RigidBody.mass`), and every row of Table 37.3, a
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

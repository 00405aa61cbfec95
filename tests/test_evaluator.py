"""The evaluator's own semantics, independent of any engine: naming, the joint forest,
frame times, joint outputs from given states, and the trace file."""

from __future__ import annotations

import math
import re
import os

import numpy as np
import pytest

from x3d_core.encodings.load import load
from x3d_core.semantics import rotation as R
from x3d_core.semantics.evaluator import RunSettings
from x3d_core.semantics.joint_outputs import JointOutputs
from x3d_core.semantics.world import STATIC, State, World, node_names, worlds
from x3d_core.traces.trace import Trace, read_trace


def scene(tmp_path, body: str, name: str = "s.x3d"):
    p = tmp_path / name
    p.write_text("<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Full' version='4.0'><Scene>\n"
                 f"{body}\n</Scene></X3D>\n")
    s = load(str(p))
    assert not s.errors, [str(e) for e in s.errors]
    return s


CHAIN = """
<RigidBodyCollection DEF='C'>
  <RigidBody DEF='Base' fixed='true'/>
  <RigidBody DEF='L1' position='1 0 0'/><RigidBody position='2 0 0'/><RigidBody DEF='L3' position='3 0 0'/>
  <BallJoint anchorPoint='0 0 0'><RigidBody USE='Base' containerField='body1'/><RigidBody USE='L1' containerField='body2'/></BallJoint>
  <BallJoint DEF='J2' anchorPoint='1.5 0 0'><RigidBody USE='L1' containerField='body1'/>
    <RigidBody USE='L3' containerField='body2'/></BallJoint>
  <BallJoint DEF='Close' anchorPoint='0 0 0'><RigidBody USE='Base' containerField='body1'/>
    <RigidBody USE='L3' containerField='body2'/></BallJoint>
</RigidBodyCollection>
<RigidBodyCollection enabled='false'/>
"""


def test_nodes_without_def_get_stable_names(tmp_path):
    s = scene(tmp_path, CHAIN)
    names = node_names(s)
    bodies = s.of_type("RigidBody")
    assert [names[id(b)] for b in bodies] == ["Base", "L1", "RigidBody_1", "L3"]
    assert [names[id(j)] for j in s.of_type("BallJoint")] == ["BallJoint_1", "J2", "Close"]
    assert node_names(scene(tmp_path, CHAIN, "again.x3d")) is not names  # and the same on every load
    assert list(node_names(scene(tmp_path, CHAIN, "again.x3d")).values()) == list(names.values())


def test_joint_graph_becomes_a_forest_and_a_loop(tmp_path):
    (w,) = worlds(scene(tmp_path, CHAIN))  # the disabled collection makes no world
    # breadth first from the static environment: L1 and L3 both hang from it (Base is
    # fixed, so part of it), and J2, between them, closes the loop
    assert w.parent.tolist() == [STATIC, STATIC, World.FREE, STATIC]
    assert [w.joints[k].name for k in w.loop_joints] == ["J2"]
    tree = {int(k) for k in w.parent_joint if k >= 0}
    assert tree | set(w.loop_joints) == set(range(len(w.joints))) and not tree & set(w.loop_joints)
    assert sorted(w.order) == [0, 1, 2, 3]
    assert all(w.parent[i] < 0 or w.order.index(w.parent[i]) < w.order.index(i) for i in w.order)
    assert w.joints[0].body1 == STATIC  # a joint to a fixed body joins the static environment


def test_mass_density_model_gives_the_shapes_inertia(tmp_path):
    s = scene(tmp_path, "<RigidBodyCollection><RigidBody mass='2'><Box size='1 2 3' containerField='massDensityModel'/>"
                        "</RigidBody><RigidBody mass='3'><Cone bottomRadius='1' height='2' "
                        "containerField='massDensityModel'/></RigidBody></RigidBodyCollection>")
    (w,) = worlds(s)
    assert np.diag(w.bodies.inertia[0]) == pytest.approx([2 * 13 / 12, 2 * 10 / 12, 2 * 5 / 12])
    assert np.diag(w.bodies.inertia[1]) == pytest.approx([3 * (3 / 20 + 3 / 80 * 4), 0.9, 3 * (3 / 20 + 3 / 80 * 4)])


def test_frame_times_end_at_the_duration():
    assert RunSettings(duration=1.0, frame_rate=4).frame_times().tolist() == [0.25, 0.5, 0.75, 1.0]
    assert RunSettings(duration=0.6, frame_rate=4).frame_times().tolist() == [0.25, 0.5, 0.6]


HINGE = """
<RigidBodyCollection>
  <RigidBody DEF='A' position='0 0 0'/><RigidBody DEF='B' position='1 0 0'/>
  <SingleAxisHingeJoint DEF='H' anchorPoint='0.5 0 0' axis='0 0 1' forceOutput='"ALL"'>
    <RigidBody USE='A' containerField='body1'/><RigidBody USE='B' containerField='body2'/></SingleAxisHingeJoint>
  <SliderJoint DEF='S' axis='1 0 0' forceOutput='"separation" "separationRate"'>
    <RigidBody USE='A' containerField='body1'/><RigidBody USE='B' containerField='body2'/></SliderJoint>
</RigidBodyCollection>
"""


def test_hinge_angle_and_rate_measure_body1_relative_to_body2(tmp_path):
    (w,) = worlds(scene(tmp_path, HINGE))
    out = JointOutputs(w.joints, w.bodies)
    s = State.initial(w.bodies)
    theta = 0.3
    s.orientation[0] = R.from_axis_angle([0, 0, 1, theta])  # body1 turns +theta about the axis
    s.angular_velocity[0] = [0, 0, 2.0]
    s.linear_velocity[0] = [0.5, 0, 0]
    s.position[0] = [0.25, 0, 0]
    values = {(j, f): v for j, f, v in out.values(s)}
    assert values[("H", "angle")] == pytest.approx(theta)
    assert values[("H", "angleRate")] == pytest.approx(2.0)
    # body1's anchor turned with it about its origin; body2's stays put
    assert values[("H", "body2AnchorPoint")] == pytest.approx([0.5, 0, 0])
    assert values[("H", "body1AnchorPoint")] == pytest.approx(
        [0.25 + 0.5 * math.cos(theta), 0.5 * math.sin(theta), 0])
    # ODE's slider: axis(t) . (p1 - p2 - R1 * offset0), offset0 = body1 - body2 at the start, in body1's frame
    assert values[("S", "separation")] == pytest.approx(1 - 0.75 * math.cos(theta))
    assert values[("S", "separationRate")] == pytest.approx(0.5 * math.cos(theta))
    assert ("S", "body1AnchorPoint") not in values  # only what forceOutput selects


def test_outputs_are_zero_in_the_initial_configuration(tmp_path):
    (w,) = worlds(scene(tmp_path, HINGE))
    values = JointOutputs(w.joints, w.bodies).values(State.initial(w.bodies))
    scalars = [v for _, f, v in values if not f.startswith("body")]
    assert scalars == [0.0] * len(scalars)


def test_trace_is_written_whole_with_every_digit(tmp_path):
    t = Trace()
    t.add(0.1, "B", "position", "SFVec3f", np.array([1 / 3, 0.0, -2.5e-17]))
    t.add(0.1, "B", "orientation", "SFRotation", np.array([0, 0, 1, math.pi]))
    path = tmp_path / "t.csv"
    t.write(str(path))
    rows = read_trace(str(path))
    assert [float(x) for x in rows[0].value.split()] == [1 / 3, 0.0, -2.5e-17]
    assert rows[1].value == "0 0 1 3.141592653589793" and rows[0].time == 0.1
    assert os.listdir(tmp_path) == ["t.csv"]


def test_a_failed_trace_write_leaves_nothing(tmp_path, monkeypatch):
    t = Trace()
    t.add(0, "B", "position", "SFVec3f", np.zeros(3))
    monkeypatch.setattr(Trace, "text", lambda self: (_ for _ in ()).throw(OSError("disk full")))
    with pytest.raises(OSError):
        t.write(str(tmp_path / "t.csv"))
    assert os.listdir(tmp_path) == []


def test_quaternion_round_trips():
    rot = np.array([[1, 2, 3, 0.7], [0, 0, 1, 0], [0, 1, 0, math.pi - 1e-9]])
    back = R.to_axis_angle(R.from_axis_angle(rot))
    unit = rot[:, :3] / np.linalg.norm(rot[:, :3], axis=1, keepdims=True)
    assert back[0] == pytest.approx(np.append(unit[0], 0.7))
    assert back[2] == pytest.approx(np.append(unit[2], math.pi - 1e-9))
    assert R.matrix(R.from_axis_angle([0, 0, 1, math.pi / 2])) @ [1, 0, 0] == pytest.approx([0, 1, 0])


class _FakeEngine:
    """A simulation that stands still and reports one contact, to see the sensor's rows."""
    name = "fake"

    def build(self, world, dt):
        from x3d_core.semantics.collision import ContactPoints

        class Sim:
            def step(self, n=1):
                pass

            def state(self):
                return State.initial(world.bodies)

            def contacts(self):
                return ContactPoints(np.array([[0, 0.5, 0]]), np.array([[0, 1.0, 0]]), np.array([0.001]),
                                     np.array([1]), np.array([0]))
        return Sim()


# a ball on a floor, both in collection C, which Sensor watches: {collection} is C's own attributes
_SENSED_BALL = """
<Group><CollidableShape DEF='BallShape'><Shape containerField='shape'><Sphere radius='0.5'/></Shape></CollidableShape>
  <CollidableShape DEF='Floor' translation='0 -0.5 0'><Shape containerField='shape'><Box size='4 1 4'/></Shape>
  </CollidableShape></Group>
<RigidBodyCollection><RigidBody DEF='Ball' position='0 1 0'><CollidableShape USE='BallShape' containerField='geometry'/>
  </RigidBody>
  <CollisionCollection DEF='C' {collection}><CollidableShape USE='BallShape'/><CollidableShape USE='Floor'/>
  </CollisionCollection></RigidBodyCollection>
<CollisionSensor DEF='Sensor'><CollisionCollection USE='C' containerField='collider'/></CollisionSensor>"""


def test_collision_sensor_rows_name_bodies_collidables_and_parameters(tmp_path):
    from x3d_core.semantics.evaluator import run
    s = scene(tmp_path, _SENSED_BALL.format(
        collection="""bounce='0.4' appliedParameters='"BOUNCE" "FRICTION_COEFFICIENT_2"'"""
                   " frictionCoefficients='0.3 0.6'"))
    (w,) = worlds(s)
    assert [(g.name, g.body, g.kind) for g in w.collisions.geometries] == [("BallShape", 0, "sphere"),
                                                                          ("Floor", STATIC, "box")]
    rows = {(r.field): r.value for r in run([w], _FakeEngine(), RunSettings(0.1, 0.05, 10)).rows
            if r.node == "Sensor" and r.time == 0.1}
    assert rows["isActive"] == "true"
    assert (rows["contacts[0].body1"], rows["contacts[0].body2"]) == ("NULL", "Ball")
    assert (rows["contacts[0].geometry1"], rows["contacts[0].geometry2"]) == ("Floor", "BallShape")
    assert rows["contacts[0].contactNormal"] == "0 1 0" and rows["contacts[0].depth"] == "0.001"
    assert rows["contacts[0].frictionDirection"] == "-1 0 0"  # ODE's first direction for an upward normal
    assert rows["contacts[0].appliedParameters"] == '"BOUNCE" "FRICTION_COEFFICIENT-2"'
    assert (rows["contacts[0].bounce"], rows["contacts[0].frictionCoefficients"]) == ("0.4", "0.3 0.6")
    assert (rows["intersections[0]"], rows["intersections[1]"]) == ("Floor", "BallShape")


def test_sensor_contacts_carry_the_collections_values_that_it_does_not_apply(tmp_path):
    """37.4.4: a Contact carries the collection's parameters, applied or not, and its
    appliedParameters; frictionCoefficients 0 0 both ways is no friction: frictionDirection 0 0 0."""
    from x3d_core.semantics.evaluator import run
    s = scene(tmp_path, _SENSED_BALL.format(collection="""bounce='0.5' surfaceSpeed='0.3 -0.7' slipFactors='0.01 0.02'
      appliedParameters='"FRICTION_COEFFICIENT_2"'"""))
    (w,) = worlds(s)
    p = w.collisions.parameters  # what the physics applies: none of them
    assert p.bounce == 0.0 and not p.surface_speed.any() and not p.slip.any() and p.frictionless
    rows = {(r.field): r.value for r in run([w], _FakeEngine(), RunSettings(0.1, 0.05, 10)).rows
            if r.node == "Sensor" and r.time == 0.1}
    assert {f: rows[f"contacts[0].{f}"] for f in ("bounce", "surfaceSpeed", "slipCoefficients", "minBounceSpeed",
                                                  "frictionCoefficients", "softnessErrorCorrection",
                                                  "softnessConstantForceMix", "appliedParameters",
                                                  "frictionDirection")} == {
        "bounce": "0.5", "surfaceSpeed": "0.3 -0.7", "slipCoefficients": "0.01 0.02", "minBounceSpeed": "0.1",
        "frictionCoefficients": "0 0", "softnessErrorCorrection": "0.8", "softnessConstantForceMix": "0.0001",
        "appliedParameters": '"FRICTION_COEFFICIENT-2"', "frictionDirection": "0 0 0"}


def test_collision_plan_follows_the_collider_spaces_and_offsets(tmp_path):
    s = scene(tmp_path, """
<Group>
  <CollidableShape DEF='A'><Shape containerField='shape'><Box size='1 2 3'/></Shape></CollidableShape>
  <CollidableOffset DEF='O' translation='9 9 9'>
    <CollidableShape containerField='collidable' translation='0 -2 0' rotation='0 0 1 1.5707963267948966'>
      <Shape containerField='shape'><Cylinder radius='0.1' height='1'/></Shape></CollidableShape></CollidableOffset>
  <CollidableShape DEF='Bounded'><Shape containerField='shape' bboxSize='1 1 1'><Sphere radius='5'/></Shape>
  </CollidableShape>
  <CollidableShape DEF='InSpace'><Shape containerField='shape'><Sphere radius='0.25'/></Shape></CollidableShape>
  <CollidableShape DEF='Off' enabled='false'><Shape containerField='shape'><Sphere/></Shape></CollidableShape>
  <CollidableShape DEF='Outside'><Shape containerField='shape'><Sphere/></Shape></CollidableShape>
</Group>
<RigidBodyCollection>
  <RigidBody DEF='B1' position='5 0 0'><CollidableShape USE='A' containerField='geometry'/>
    <CollidableOffset USE='O' containerField='geometry'/></RigidBody>
  <RigidBody DEF='B2'><CollidableShape USE='Outside' containerField='geometry'/></RigidBody>
  <RigidBody DEF='B3'><CollidableShape USE='InSpace' containerField='geometry'/></RigidBody>
  <BallJoint><RigidBody USE='B1' containerField='body1'/><RigidBody USE='B3' containerField='body2'/></BallJoint>
  <CollisionCollection><CollidableShape USE='A'/><CollidableOffset USE='O'/><CollidableShape USE='Bounded'/>
    <CollidableShape USE='Off'/><CollisionSpace><CollidableShape USE='InSpace'/></CollisionSpace>
  </CollisionCollection></RigidBodyCollection>""")
    (w,) = worlds(s)
    c = w.collisions
    geoms = {g.name: g for g in c.geometries}
    assert set(geoms) == {"A", "CollidableShape_1", "Bounded", "InSpace"}  # not Off, not Outside
    assert geoms["A"].position.tolist() == [0, 0, 0]  # the body sets a top-level collidable's pose
    inner = geoms["CollidableShape_1"]  # the offset's own fields are the body's; the shape hangs below it
    assert inner.body == 0 and inner.position == pytest.approx([0, -2, 0])
    assert R.rotate(inner.orientation, [0, 1, 0]) == pytest.approx([-1, 0, 0])
    assert (geoms["Bounded"].kind, geoms["Bounded"].size.tolist(), geoms["Bounded"].body) == ("box", [1, 1, 1], STATIC)
    assert (geoms["InSpace"].kind, geoms["InSpace"].size.tolist()) == ("sphere", [0.25])  # useGeometry: a hint
    at = {g.name: k for k, g in enumerate(c.geometries)}
    first = [at["A"]] * 3
    second = [at["CollidableShape_1"], at["InSpace"], at["Bounded"]]
    # one body; joined by the ball joint; free to touch
    assert c.may_touch(first, second).tolist() == [False, False, True]
    assert c.parameters.bounce == 0 and c.parameters.friction.tolist() == [0, 0]  # X3D's defaults: BOUNCE, no friction


def _routed_contacts_scene(tmp_path, own_collider: str, route: bool):
    return scene(tmp_path, f"""
<Group><CollidableShape DEF='BallShape'><Shape containerField='shape'><Sphere radius='0.5'/></Shape></CollidableShape>
  <CollidableShape DEF='Floor' translation='0 -0.5 0'><Shape containerField='shape'><Box size='4 1 4'/></Shape>
  </CollidableShape></Group>
<CollisionSensor DEF='Sensor'><CollisionCollection DEF='Watched' containerField='collider' bounce='0.4'>
  <CollidableShape USE='BallShape'/><CollidableShape USE='Floor'/></CollisionCollection></CollisionSensor>
<RigidBodyCollection DEF='Bodies'><RigidBody DEF='Ball' position='0 1 0'>
  <CollidableShape USE='BallShape' containerField='geometry'/></RigidBody>{own_collider}</RigidBodyCollection>
{"<ROUTE fromNode='Sensor' fromField='contacts' toNode='Bodies' toField='set_contacts'/>" if route else ""}""")


def test_contacts_routed_from_a_sensor_collide_with_its_collider(tmp_path):
    from x3d_core.semantics.analysis import run_features
    s = _routed_contacts_scene(tmp_path, "", route=True)
    (w,) = worlds(s)
    assert w.collisions.collider.def_name == "Watched"  # the sensor's collection, with its parameters
    assert w.collisions.parameters.bounce == 0.4 and [n for n, _ in w.collisions.sensors] == ["Sensor"]
    assert {"RigidBodyCollection.set_contacts.fromSensor", "CollisionCollection.bounce"} <= set(run_features(s))
    routed_into_own = _routed_contacts_scene(tmp_path, "<CollisionCollection USE='Watched' containerField='collider'/>",
                                             route=True)
    assert "RigidBodyCollection.set_contacts.fromSensor" in run_features(routed_into_own)  # its own contacts again


def test_without_the_route_or_from_another_collider_nothing_new_collides(tmp_path):
    from x3d_core.semantics.analysis import run_features
    s = _routed_contacts_scene(tmp_path, "", route=False)
    (w,) = worlds(s)
    assert w.collisions is None  # the sensor's collection acts on nothing: it is only watched
    assert [c.collider.def_name for c in w.watched] == ["Watched"]
    needed = run_features(s)
    assert "CollisionSensor.collider.watchedOnly" in needed and "CollisionCollection.bounce" not in needed
    other = _routed_contacts_scene(tmp_path, "<CollisionCollection DEF='Own' containerField='collider'>"
                                             "<CollidableShape USE='BallShape'/></CollisionCollection>", route=True)
    assert worlds(other)[0].collisions.collider.def_name == "Own"
    assert "RigidBodyCollection.set_contacts.fromOtherCollider" in run_features(other)  # refused: one set each


def test_a_table_of_records_becomes_rows_per_record_then_field(tmp_path):
    from x3d_core.model import fields as F
    from x3d_core.traces.trace import Column
    t = Trace()
    t.add_table(0.5, "S", "contacts", 2, [Column("depth", F.FIELD_TYPES["SFFloat"], np.array([0.25, 1e-17])),
                                          Column("body1", None, np.array(["A", "NULL"], dtype=object)),
                                          Column("bounce", F.FIELD_TYPES["SFFloat"], 0.5, True)])
    t.add_table(0.5, "S", "intersections", 1, [Column("", None, np.array(["G"], dtype=object))])
    t.add_table(0.5, "S", "contacts", 0, [])  # no contacts: no rows
    assert [(r.field, r.value) for r in t.rows] == [
        ("contacts[0].depth", "0.25"), ("contacts[0].body1", "A"), ("contacts[0].bounce", "0.5"),
        ("contacts[1].depth", "1e-17"), ("contacts[1].body1", "NULL"), ("contacts[1].bounce", "0.5"),
        ("intersections[0]", "G")]
    assert [b.count for b in t.tables_of("contacts")] == [2]
    t.add_text(0.5, "S", "contacts[0].appliedParameters", '"BOUNCE" "SLIP-1"')  # quotes: CSV-quoted
    t.add_text(0.5, "S, odd", "x", "a\nb")
    t.write(str(tmp_path / "t.csv"))
    assert read_trace(str(tmp_path / "t.csv")) == t.rows


def test_a_rotation_axis_of_huge_components_is_normalised_without_overflow():
    """An axis of 1e308s once overflowed its norm: a non-unit quaternion read back as no
    rotation, with a RuntimeWarning; its direction is all that counts."""
    with np.errstate(all="raise"):
        q = R.from_axis_angle(np.array([[1e308, 1e308, 0.0, 1.0], [1e-320, 0.0, 0.0, 1.0]]))
    expected = R.from_axis_angle(np.array([[1.0, 1.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0]]))
    assert np.allclose(q, expected, rtol=0, atol=1e-15)


class _Turned:
    """An engine that stands still with body row 0 turned a quarter about z, keeping every load it is given."""
    name = "turned"

    def __init__(self):
        self.loads: list[tuple[np.ndarray, np.ndarray]] = []

    def build(self, world, dt):
        loads = self.loads

        class Sim:
            def step(self, n=1):
                pass

            def state(self):
                s = State.initial(world.bodies)
                s.orientation[0] = R.from_axis_angle(np.array([[0.0, 0.0, 1.0, math.pi / 2]]))[0]
                return s

            def set_loads(self, forces, torques):
                loads.append((forces.copy(), torques.copy()))
        return Sim()


def test_slider_force_pushes_body1_along_the_axis_it_carries_and_turns_neither(tmp_path):
    """sliderForce as ODE's dJointAddSliderForce: +F along the axis as body1 carries it (turned
    from 1 0 0 to 0 1 0) on body1, -F on body2, and the decoupling torque that puts the two
    forces on one line: the pair gets no net force and no net torque, though their centres of
    mass (body1's off its origin) are not on the axis."""
    from x3d_core.semantics.evaluator import run
    s = scene(tmp_path, """
<RigidBodyCollection gravity='0 0 0'>
  <RigidBody DEF='Block' position='0 0 1' centerOfMass='0.3 0 0'/><RigidBody DEF='Carriage'/>
  <SliderJoint axis='1 0 0' minSeparation='-1' maxSeparation='1' sliderForce='2'>
    <RigidBody USE='Block' containerField='body1'/><RigidBody USE='Carriage' containerField='body2'/></SliderJoint>
</RigidBodyCollection>""")
    engine = _Turned()
    run(worlds(s), engine, RunSettings(2 / 240, 1 / 240, 240))
    assert len(engine.loads) == 2  # before every step
    forces, torques = engine.loads[-1]
    assert np.allclose(forces, [[0, 2, 0], [0, -2, 0]], rtol=0, atol=1e-15)
    centres = np.array([[0.0, 0.3, 1.0], [0.0, 0.0, 0.0]])  # Block's centre of mass turned with it
    assert np.allclose(np.cross(centres, forces).sum(axis=0) + torques.sum(axis=0), 0, rtol=0, atol=1e-15)
    assert not np.allclose(torques, 0)


class _Unsound:
    """An engine that stands still until its second frame, then reads `value` into one component of
    body row 1's `column` (of position 0-2, orientation 3-6, velocities 7-12): its state as four
    arrays, or, with whole, as views of one (n, 13) array (State.whole), as PhysX's backend reads it."""
    name = "unsound"

    def __init__(self, column: int, value: float, whole: bool):
        self.column, self.value, self.whole = column, value, whole

    def build(self, world, dt):
        engine, steps = self, [0]

        class Sim:
            def step(self, n=1):
                steps[0] += n

            def state(self):
                s = State.initial(world.bodies)
                a = np.hstack([s.position, s.orientation, s.linear_velocity, s.angular_velocity])
                if steps[0] >= 2:
                    a[1, engine.column] = engine.value
                if engine.whole:
                    return State(a[:, 0:3], a[:, 3:7], a[:, 7:10], a[:, 10:13], whole=a)
                return State(a[:, 0:3].copy(), a[:, 3:7].copy(), a[:, 7:10].copy(), a[:, 10:13].copy())
        return Sim()


@pytest.mark.parametrize("whole", [False, True], ids=["four arrays", "one array"])
@pytest.mark.parametrize("column,value,said", [
    (1, np.nan, "B has a non-finite state"), (4, np.inf, "B has a non-finite state"),
    (3, np.nan, "B has a non-finite state"), (8, 2e12, "B's linear velocity is beyond 1e+12"),
    (0, -2e12, "B's position is beyond 1e+12")])
def test_an_unsound_state_stops_the_run_at_its_frame_however_the_engine_read_it(tmp_path, column, value, said, whole):
    """The soundness check is one reduction over a state read whole (its unit quaternions within the
    bound) and over the three bounded fields plus the orientation's finiteness otherwise: either
    way a NaN, an infinity or a value past STATE_BOUND anywhere stops the run at that frame."""
    from x3d_core.semantics.engine import BlewUp
    from x3d_core.semantics.evaluator import run
    s = scene(tmp_path, "<RigidBodyCollection><RigidBody DEF='A'/><RigidBody DEF='B' position='0 1 0'/>"
                        "</RigidBodyCollection>")
    with pytest.raises(BlewUp, match=re.escape(f"blew up at t=0.1: {said}")):
        run(worlds(s), _Unsound(column, value, whole), RunSettings(0.3, 0.05, 10))
    trace = run(worlds(s), _Unsound(column, 1.0 if column < 3 else 0.0, whole), RunSettings(0.3, 0.05, 10))
    assert sorted({r.time for r in trace.rows}) == pytest.approx([0.0, 0.1, 0.2, 0.3])  # sound values run on

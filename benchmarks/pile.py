"""Benchmark: a pile of 200 colliding bodies, x3drbp's run against each engine's own API.

The scene, generated here: 100 spheres (radius 0.1 m) and 100 boxes (0.2 m cubes), 1 kg
each, each with an explicit inertia equal to its shape's solid inertia (x3drbp uses the
scene's inertia field, engines computing inertia from shapes would agree), no joints,
turned at random and at rest, on a jittered 5 x 5 x 8
grid in a column above a static floor box (top face y = 0) inside four static walls (a
pit 3 m square: spheres have no rolling resistance and would roll off any floor). Every
collidable, the floor and the walls are in one CollisionCollection, frictionCoefficients
0.5 0.5, bounce 0 (the defaults otherwise: appliedParameters BOUNCE, minBounceSpeed 0.1,
errorCorrection 0.8, contactSurfaceThickness 0, iterations 10): parameters all four
backends build. The bodies fall into a pile for --duration simulated seconds (DART: at
most --dart-duration, see DART_DURATION) at dt = 1/240 s, state read at 60 frames per
second.

x3drbp's side is load + plan + build + steps + every frame's state readback into the
trace, kept in memory. There is NO CollisionSensor in the timed scene, so contacts are
never read (x3drbp reads them only when a sensor or the trace needs them). The native
side builds the same model with the engine's own calls (same shapes, masses, inertias,
friction, restitution, solver settings and step, each as the backend sets them: see
each native_* function), steps it and reads every body's pose and velocity at each
frame, keeping them. A second row per engine adds a CollisionSensor to the scene
(contacts read into the trace every frame) and has the native side read the engine's
contact points every frame too: what reading contacts costs.

Sanity: a pile is chaotic (a difference of 1e-15 m in where a body starts grows to
bodies landing elsewhere: measured, up to 0.6 m apart after 5 s and the mean height moved
by up to 3 mm), so the two sides need not agree body by body at the end; they are
compared by an aggregate: the pile's final mean height (mean centre height over all
bodies) must agree within HEIGHT_SAME (5 mm). Before the first contact (t = 0.5 s: the
lowest body is 1.43 m up, and the bodies keep their spacing while they fall together)
every position must agree to AGREE (1e-9 m). Either failing means the two sides are not
the same model (a change in a backend's contact parameters, say), and the exit status
is 1. The final body-by-body difference is printed too: as written (bodies at rest,
unit axes exact to the last bit, the floor and walls created after the bodies as the
backends do) every engine's native build was measured to give x3drbp's run to the last
bit, 0 m, so both sides also do the same work; a difference there with agreeing mean
heights is rounding grown by the pile. ODE's native side is the exception by design: it
finds contacts through ODE's own space, in another order than the backend's (see
native_ode), so its pile differs from the first contact on (with the backend's order it
was measured bit for bit too).

    python benchmarks/pile.py [--duration 5] [--dart-duration 1.5] [--repeat 3] [--backends mujoco,bullet,dart,ode]
                              [--profile]

--backends defaults to every engine that runs the scene without refusing it (the
refusal `x3drbp run` answers with exit status 3). --profile prints cProfile's top 15
of x3drbp's run wherever it takes more than 1.15x the native time.
"""

from __future__ import annotations

import argparse
import cProfile
import io
import os
import pstats
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from measure import peak_mb, timed  # noqa: E402  (benchmarks/measure.py, beside this script)

DT = 1 / 240
FRAME_RATE = 60
GRAVITY = 9.81
SPHERES = BOXES = 100
RADIUS = 0.1  # m
EDGE = 0.2  # m
MASS = 1.0  # kg
SPHERE_MOMENT = 0.4 * MASS * RADIUS ** 2  # solid sphere
BOX_MOMENT = MASS * (EDGE ** 2 + EDGE ** 2) / 12  # solid cube
MU = 0.5
ITERATIONS = 10
ERP = 0.8  # RigidBodyCollection errorCorrection, written explicitly (it is the default)
MIN_BOUNCE_SPEED = 0.1  # CollisionCollection minBounceSpeed's default (no effect with bounce 0)
PER_PAIR = 16  # the most contacts ODE's dCollide may return for one pair (the ODE backend's bound)
# The static boxes (name, size, centre): a floor (top face y = 0) and four walls round a pit
# 3 m square inside, 2 m high. Spheres have no rolling resistance (X3D has none): on an open
# floor they roll away from the pile at up to 3 m/s and off any floor in time, and bodies
# landing on the pile kick some spheres over a 0.6 m wall.
PIT, WALL, WALL_HEIGHT = 3.0, 0.2, 2.0
STATIC = (("Floor", (PIT + 2 * WALL + 1.0, 0.2, PIT + 2 * WALL + 1.0), (0.0, -0.1, 0.0)),
          ("WallXMinus", (WALL, WALL_HEIGHT, PIT + 2 * WALL), (-(PIT + WALL) / 2, WALL_HEIGHT / 2, 0.0)),
          ("WallXPlus", (WALL, WALL_HEIGHT, PIT + 2 * WALL), ((PIT + WALL) / 2, WALL_HEIGHT / 2, 0.0)),
          ("WallZMinus", (PIT, WALL_HEIGHT, WALL), (0.0, WALL_HEIGHT / 2, -(PIT + WALL) / 2)),
          ("WallZPlus", (PIT, WALL_HEIGHT, WALL), (0.0, WALL_HEIGHT / 2, (PIT + WALL) / 2)))
GRID, LAYERS, SPACING = 5, 8, 0.4  # 5 x 5 bodies a layer, 8 layers, 0.4 m apart (+- JITTER)
JITTER = 0.02  # m: centres at least 0.36 m apart, more than a cube's circumscribed diameter (0.346 m)
BOTTOM = 1.6  # m: the lowest layer's centres; at least 1.43 m clear of the floor
CHECK_T = 0.5  # s: every body still in the air (it has fallen 1.23 m), none touching another
AGREE = 1e-9  # m: positions at CHECK_T on the two sides
HEIGHT_SAME = 0.005  # m: the final mean heights on the two sides
SLOW = 1.15  # x3drbp/native ratio past which --profile profiles
PAIR_CAP = 20000  # backends/mujoco.py's: up to this many pairs it lists each pair explicitly
FRICTION_BDT = 0.15  # backends/mujoco.py's: an explicit pair's friction rows' damping, times 1/dt
# DART's default solver (Dantzig's, direct) on the pile's one island of 500-600 contacts takes
# about 0.2 s a step once the pile has settled (measured: its first 2 s take 1 min, its first 4 s
# 8 min): a 5 s run would take some 12 minutes, so DART runs this long by default; the pile has
# formed by then (mean height 0.17 m, settling to 0.155 m)
DART_DURATION = 1.5


def _vec(v) -> str:
    """Every digit, so that the native builds get the very numbers x3drbp reads."""
    return " ".join(repr(float(x)) for x in v)


def draws() -> list[tuple[str, np.ndarray, np.ndarray, float]]:
    """Each body's (kind, position, unit turn axis, turn angle): the scene file and every
    native build use these. Each axis is a unit vector to the last bit, so that an X3D
    reader's normalisation leaves it as it is. The grid fills layer by layer, up to SPHERES +
    BOXES bodies (a top layer may be part full)."""
    rng = np.random.default_rng(20250607)
    kinds = rng.permutation(["sphere"] * SPHERES + ["box"] * BOXES)
    out = []
    k = 0
    for layer in range(LAYERS):
        for i in range(GRID):
            for j in range(GRID):
                if k == len(kinds):
                    return out
                centre = np.array([(i - (GRID - 1) / 2) * SPACING, BOTTOM + layer * SPACING,
                                   (j - (GRID - 1) / 2) * SPACING])
                position = centre + rng.uniform(-JITTER, JITTER, 3)
                axis = np.zeros(3)
                while np.linalg.norm(axis[None], axis=-1)[0] != 1.0:
                    axis = rng.normal(size=3)
                    axis /= np.linalg.norm(axis[None], axis=-1)[0]
                out.append((str(kinds[k]), position, axis, float(rng.uniform(0, np.pi))))
                k += 1
    return out


def pile_x3d(sensor: bool) -> str:
    bodies, shapes = [], []
    for k, (kind, position, axis, angle) in enumerate(draws()):
        moment = SPHERE_MOMENT if kind == "sphere" else BOX_MOMENT
        geometry = f"<Sphere radius='{RADIUS!r}'/>" if kind == "sphere" else f"<Box size='{_vec([EDGE] * 3)}'/>"
        bodies.append(
            f"<RigidBody DEF='B{k}' mass='{MASS!r}' position='{_vec(position)}' "
            f"orientation='{_vec(axis)} {angle!r}' "
            f"inertia='{_vec(np.diag([moment] * 3).ravel())}'>"
            f"<CollidableShape DEF='S{k}' containerField='geometry'><Shape containerField='shape'>{geometry}"
            "</Shape></CollidableShape></RigidBody>")
        shapes.append(f"<CollidableShape USE='S{k}' containerField='collidables'/>")
    for name, size, centre in STATIC:
        shapes.append(f"<CollidableShape DEF='{name}' containerField='collidables' translation='{_vec(centre)}'>"
                      f"<Shape containerField='shape'>"
                      f"<Box size='{_vec(size)}'/></Shape></CollidableShape>")
    collision = (f"<CollisionCollection DEF='Contacts' frictionCoefficients='{_vec([MU, MU])}' bounce='0'>\n"
                 + "\n".join(shapes) + "\n</CollisionCollection>")
    sensing = ("<CollisionSensor DEF='Sensor'><CollisionCollection USE='Contacts' containerField='collider'/>"
               "</CollisionSensor>\n") if sensor else ""
    return ("<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Full' version='4.0'><Scene>\n"
            f"<RigidBodyCollection DEF='World' gravity='0 {-GRAVITY!r} 0' iterations='{ITERATIONS}' "
            f"errorCorrection='{ERP!r}'>\n" + "\n".join(bodies) + "\n" + collision + "\n</RigidBodyCollection>\n"
            + sensing + "</Scene></X3D>\n")


# -- the same scene written directly in each engine's API -------------------------------
# Each native_* builds the scene from draws(), steps it for `duration`, reads every body's
# pose and velocity at each frame (and with contacts=True the engine's contact points),
# keeps them all, and returns the bodies' positions (n, 3) at every frame, in scene order.

def _quaternion(axis: np.ndarray, angle: float) -> np.ndarray:
    """w x y z."""
    return np.concatenate([[np.cos(angle / 2)], np.sin(angle / 2) * axis])


def _matrix(q: np.ndarray) -> np.ndarray:
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def _frames(duration: float) -> tuple[int, int]:
    return round(duration * FRAME_RATE), round(1 / (FRAME_RATE * DT))


def native_mujoco(duration: float, contacts: bool = False) -> np.ndarray:
    """As backends/mujoco.py builds it (its collision code as of this writing): a free body
    per body with its inertia explicit, a massless geom each, the floor and walls geoms on
    the world body; 200 bodies and 5 static boxes make 20900 possible pairs, past the
    backend's PAIR_CAP of 20000,
    so geoms collide through MuJoCo's default contype/conaffinity broad phase. With fewer
    pairs (engine_speed.py's 100 boxes: 5450) the backend lists every pair explicitly, and
    so does this: the static geoms' pairs with each body in turn, then the bodies' pairs in
    order, each with friction [mu, mu] and softer friction rows (solreffriction damping
    0.15/dt, the backend's FRICTION_BDT), the geoms' own contype/conaffinity off. Friction: condim 3 on
    the elliptic cone with 30 no-slip iterations; contacts without bounce or softness get the
    backend's "hard" direct solref (stiffness min(ERP, 0.25)/dt^2, damping 1/dt) and its hard
    solimp (impedance 0.99 at any depth)."""
    import mujoco
    spec = mujoco.MjSpec()
    spec.compiler.degree = False
    spec.option.timestep = DT
    spec.option.gravity = [0, -GRAVITY, 0]
    spec.option.iterations = ITERATIONS
    spec.option.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
    spec.option.noslip_iterations = 30
    solref = [-min(ERP, 0.25) / DT ** 2, -1.0 / DT]
    solimp = [0.99, 0.99, 0.001, 0.5, 2.0]

    def surface(geom) -> None:
        geom.condim = 3
        geom.friction = [MU, 0.0, 0.0]
        geom.solref = solref
        geom.solimp = solimp

    n = 0
    for k, (kind, position, axis, angle) in enumerate(draws()):
        body = spec.worldbody.add_body(name=f"b{k}", pos=position, quat=_quaternion(axis, angle))
        moment = SPHERE_MOMENT if kind == "sphere" else BOX_MOMENT
        # ipos must be given with an explicit inertia (MjSpec leaves it NaN otherwise)
        body.explicitinertial, body.mass, body.ipos = True, MASS, [0, 0, 0]
        body.fullinertia = [moment] * 3 + [0, 0, 0]
        body.add_freejoint()
        if kind == "sphere":
            geom = body.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[RADIUS, 0, 0])
        else:
            geom = body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[EDGE / 2] * 3)
        geom.density = 0.0  # the body's inertia is the explicit one
        surface(geom)
        n += 1
    for _, size, centre in STATIC:
        surface(spec.worldbody.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=np.array(size) / 2, pos=centre))
    if n * (n - 1) // 2 + n * len(STATIC) <= PAIR_CAP:
        _explicit_pairs(spec, n, solref, solimp)
    m = spec.compile()
    d = mujoco.MjData(m)
    ids = np.array([m.body(f"b{k}").id for k in range(n)])
    frames, steps_per_frame = _frames(duration)
    out, touching = [], []
    for _ in range(frames):
        mujoco.mj_step(m, d, nstep=steps_per_frame)
        mujoco.mj_kinematics(m, d)
        mujoco.mj_comPos(m, d)
        mujoco.mj_comVel(m, d)
        out.append((d.xpos[ids], d.xquat[ids], d.cvel[ids]))  # fancy indexing copies
        if contacts:
            n, c = d.ncon, d.contact
            touching.append((c.pos[:n].copy(), c.frame[:n, :3].copy(), c.dist[:n].copy(), c.geom1[:n].copy(),
                             c.geom2[:n].copy()))
    return np.array([pos for pos, _, _ in out])


def _explicit_pairs(spec, n: int, solref: list[float], solimp: list[float]) -> None:
    """Every pair that may touch as a MuJoCo `pair`, in the backend's order: the static geoms
    (the world body's, created last) with each body, then each body with every later one."""
    geoms = spec.geoms
    for k, geom in enumerate(geoms):
        geom.name, geom.contype, geom.conaffinity = f"g{k}", 0, 0
    static = [g.name for g in geoms[n:]]
    pairs = [(s, f"g{k}") for k in range(n) for s in static]
    pairs += [(f"g{a}", f"g{b}") for a in range(n) for b in range(a + 1, n)]
    for first, second in pairs:
        pair = spec.add_pair(geomname1=first, geomname2=second)
        pair.condim, pair.friction = 3, [MU, MU, 0.0, 0.0, 0.0]
        pair.solref, pair.solimp = solref, solimp
        pair.solreffriction = [-1e-9, -FRICTION_BDT / DT]


def native_bullet(duration: float, contacts: bool = False) -> np.ndarray:
    """As backends/bullet.py builds it: each body a linkless multibody with its collision
    shape as the base's, mass and inertia set explicitly; the floor and each wall a
    massless multibody created after them; the solver's iterations, ERP (contacts too), no
    split impulse, pyramid friction, each object's friction sqrt(mu) (pybullet multiplies
    two objects'), restitution 0, no rolling or spinning friction, contactProcessingThreshold
    1e-4. (Two collision shapes shared by all bodies, where the backend makes one a body.)"""
    import pybullet as p
    c = p.connect(p.DIRECT)
    p.setGravity(0, -GRAVITY, 0, physicsClientId=c)
    p.setPhysicsEngineParameter(fixedTimeStep=DT, numSubSteps=0, numSolverIterations=ITERATIONS, erp=ERP,
                                useSplitImpulse=0, physicsClientId=c)
    sphere = p.createCollisionShape(p.GEOM_SPHERE, radius=RADIUS, physicsClientId=c)
    box = p.createCollisionShape(p.GEOM_BOX, halfExtents=[EDGE / 2] * 3, physicsClientId=c)
    bodies = []
    for kind, position, axis, angle in draws():
        q = _quaternion(axis, angle)
        uid = p.createMultiBody(baseMass=MASS, baseCollisionShapeIndex=sphere if kind == "sphere" else box,
                                basePosition=position, baseOrientation=[q[1], q[2], q[3], q[0]],
                                flags=p.URDF_USE_SELF_COLLISION, physicsClientId=c)
        moment = SPHERE_MOMENT if kind == "sphere" else BOX_MOMENT
        # multibodies are damped by default, and their coordinate speeds (the base's too) clamped at 100
        p.changeDynamics(uid, -1, mass=MASS, localInertiaDiagonal=[moment] * 3, linearDamping=0, angularDamping=0,
                         maxJointVelocity=1e6, physicsClientId=c)
        bodies.append(uid)
    static = []
    for _, size, centre in STATIC:
        shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=(np.array(size) / 2).tolist(), physicsClientId=c)
        static.append(p.createMultiBody(baseMass=0, baseCollisionShapeIndex=shape, basePosition=centre,
                                        physicsClientId=c))
    p.setPhysicsEngineParameter(restitutionVelocityThreshold=MIN_BOUNCE_SPEED, contactSlop=0, enableConeFriction=0,
                                contactERP=ERP, physicsClientId=c)
    for uid in bodies + static:
        p.changeDynamics(uid, -1, lateralFriction=float(np.sqrt(MU)), restitution=0.0, rollingFriction=0.0,
                         spinningFriction=0.0, contactProcessingThreshold=1e-4, physicsClientId=c)
    frames, steps_per_frame = _frames(duration)
    out, touching = [], []
    for _ in range(frames):
        for _ in range(steps_per_frame):
            p.stepSimulation(physicsClientId=c)
        out.append([(p.getBasePositionAndOrientation(b, physicsClientId=c), p.getBaseVelocity(b, physicsClientId=c))
                    for b in bodies])
        if contacts:
            touching.append(p.getContactPoints(physicsClientId=c))
    p.disconnect(c)
    return np.array([[pose[0] for pose, _ in frame] for frame in out])


def native_dart(duration: float, contacts: bool = False) -> np.ndarray:
    """As backends/dart.py builds it: DART's Bullet collision detector, a free-joint
    skeleton per body with its inertia set, sleeping off, the floor and walls shapes on an
    immobile welded skeleton added last, every shape friction mu (DART takes the smaller
    of two) and restitution 0; DART's default solver (Dantzig's LCP)."""
    import dartpy as dart

    import dart_shared  # beside this script
    world = dart_shared.world(DT, GRAVITY)

    def collide(node, shape, name: str, where=None) -> None:
        frame = node.createShapeNode(shape, name)
        if where is not None:
            t = dart.math.Isometry3()
            t.set_translation(np.asarray(where, dtype=np.float64))
            frame.setRelativeTransform(t)
        frame.createCollisionAspect()
        surface = frame.createDynamicsAspect()
        surface.setFrictionCoeff(MU)
        surface.setRestitutionCoeff(0.0)

    nodes = []
    for k, (kind, position, axis, angle) in enumerate(draws()):
        skeleton = dart.dynamics.Skeleton(f"body{k}")
        joint, node = skeleton.createFreeJointAndBodyNodePair(None)
        pose = dart.math.Isometry3()
        pose.set_rotation(_matrix(_quaternion(axis, angle)))
        pose.set_translation(position)
        joint.setPositions(dart.dynamics.FreeJoint.convertToPositions(pose))
        moment = SPHERE_MOMENT if kind == "sphere" else BOX_MOMENT
        node.setInertia(dart.dynamics.Inertia(MASS, np.zeros(3), moment * np.eye(3)))
        shape = dart.dynamics.SphereShape(RADIUS) if kind == "sphere" else dart.dynamics.BoxShape(np.full(3, EDGE))
        collide(node, shape, f"shape{k}")
        world.addSkeleton(skeleton)
        nodes.append(node)
    # the static shapes last, as the backend's come last: DART's Bullet detector orders each
    # contact's two objects by when they were added, and that order turns the friction pyramid
    # (measured with the floor added first: the pile's mean height 1 cm off after 1 s)
    ground = dart.dynamics.Skeleton("ground")
    _, ground_node = ground.createWeldJointAndBodyNodePair(None)
    ground.setMobile(False)
    for name, size, centre in STATIC:
        collide(ground_node, dart.dynamics.BoxShape(np.array(size)), name, centre)
    world.addSkeleton(ground)
    frames, steps_per_frame = _frames(duration)
    out, touching = [], []
    for _ in range(frames):
        for _ in range(steps_per_frame):
            world.step()
        out.append([(n.getWorldTransform().matrix(), n.getCOMLinearVelocity(), n.getAngularVelocity())
                    for n in nodes])
        if contacts:  # copied out at once: DART's contact objects must not outlive the step
            touching.append([(c.point.copy(), c.normal.copy(), c.penetrationDepth,
                              c.collisionObject1.getShapeFrame().getName(),
                              c.collisionObject2.getShapeFrame().getName())
                             for c in world.getLastCollisionResult().getContacts()])
    return np.array([[tf[:3, 3] for tf, _, _ in frame] for frame in out])


def native_ode(duration: float, contacts: bool = False) -> np.ndarray:
    """As backends/ode.py builds it, through its ctypes binding (backends/ode_lib.py) of the
    system's libode: a body per body at its centre of mass with dMassSetParameters' mass and
    inertia, a geom on each; the floor and walls geoms with no body, created after them;
    quick-step with the world's ERP 0.8, CFM 1e-4, 10 iterations, surface layer 0 and no
    correcting-speed cap; every contact one dContact of mode dContactApprox1 | dContactBounce
    (mu 0.5, bounce 0, bounce_vel 0.1), its joint in a group emptied every step; dRandSetSeed(0)
    before the build (quick-step reorders its rows with ODE's one global generator).

    Collision detection is ODE's own, as a user writing against ODE would do it and unlike
    the backend's numpy broad phase: the geoms in a dHashSpace (its default levels;
    dSimpleSpace measured as fast here), dSpaceCollide calling back into Python for each
    pair whose AABBs overlap, and dCollide there (the pairs of two unmoving geoms, floor
    and walls, skipped). The space hands out pairs in its own order, not the backend's
    (index order, lower index as geom 1), so the contact rows differ in order from the
    first contact on and the pile with them (8.6e-5 m at 0.6 s, mean height 2 mm off after
    5 s); with the space's pairs sorted the backend's way the two sides were measured
    equal to the last bit over 5 s. State is read a body at a time with dBodyGet* calls,
    as a user of the plain C API from Python would; the backend's one numpy gather over
    ODE's memory (ode_lib.Window) is x3drbp's own means, so it is not used here (the
    per-body reads measured about 8% of this side's time)."""
    import ctypes

    import ode_shared  # beside this script
    from backends import ode_lib as ode
    lib = ode.lib
    world = ode_shared.world(GRAVITY, ERP, 1e-4, ITERATIONS)  # 1e-4: constantForceMix's default
    space = ode_shared.hash_space(None)
    mass = (ctypes.c_double * ode.MASS_REALS)()
    bodies, body_of = [], {}  # body_of: each geom's body (None for the floor and walls)
    for kind, position, axis, angle in draws():
        body = lib.dBodyCreate(world)
        moment = SPHERE_MOMENT if kind == "sphere" else BOX_MOMENT
        lib.dMassSetParameters(mass, MASS, 0, 0, 0, moment, moment, moment, 0, 0, 0)
        lib.dBodySetMass(body, mass)
        lib.dBodySetPosition(body, *position)
        lib.dBodySetQuaternion(body, ode.array(_quaternion(axis, angle)))
        geom = lib.dCreateSphere(space, RADIUS) if kind == "sphere" else lib.dCreateBox(space, EDGE, EDGE, EDGE)
        lib.dGeomSetBody(geom, body)
        bodies.append(body)
        body_of[geom] = body
    for _, size, centre in STATIC:
        geom = lib.dCreateBox(space, *size)
        lib.dGeomSetPosition(geom, *centre)
        body_of[geom] = None
    surface = np.zeros(1, dtype=ode.CONTACT)
    surface["mode"] = ode.CONTACT_APPROX1 | ode.CONTACT_BOUNCE
    surface["mu"], surface["bounce"], surface["bounce_vel"] = MU, 0.0, MIN_BOUNCE_SPEED
    buffer = np.repeat(surface, 1024)  # every slot carries the surface; dCollide fills in the geometry
    group = lib.dJointGroupCreate(0)
    found = 0  # contacts in the buffer this step

    @ode_shared.NEAR
    def collide(_data, o1: int, o2: int) -> None:
        nonlocal buffer, found
        b1, b2 = body_of[o1], body_of[o2]
        if b1 is None and b2 is None:
            return
        if len(buffer) - found < PER_PAIR:
            buffer = np.concatenate([buffer, buffer])
        at = buffer.ctypes.data + found * ode.CONTACT.itemsize
        for k in range(lib.dCollide(o1, o2, PER_PAIR, at + ode.GEOM_OFFSET, ode.CONTACT.itemsize)):
            lib.dJointAttach(lib.dJointCreateContact(world, group, at + k * ode.CONTACT.itemsize), b1, b2)
            found += 1

    touching = []

    def reset() -> None:
        nonlocal found
        found = 0

    def read_contacts() -> None:
        if contacts:
            c = buffer[:found]
            touching.append((c["pos"][:, :3].copy(), c["normal"][:, :3].copy(), c["depth"].copy(), c["g1"].copy(),
                             c["g2"].copy()))

    out = ode_shared.simulate(world, space, group, collide, bodies, *_frames(duration), DT, before_step=reset,
                              after_frame=read_contacts)
    return np.array([[pose[0] for pose in frame] for frame in out])


NATIVE = {"mujoco": native_mujoco, "bullet": native_bullet, "dart": native_dart, "ode": native_ode}


# -- measuring ------------------------------------------------------------------------
def positions(trace) -> np.ndarray:
    """Every recorded frame's body positions (frames, n, 3), the t = 0 record left out, so
    that row k is the state at the end of frame k + 1 on both sides."""
    frames = [np.asarray(b.values) for b in trace.blocks_of("position")]
    return np.array(frames[1:])


def contact_counts(trace) -> float:
    """The mean number of contacts a frame in a trace with a CollisionSensor."""
    frames = len(trace.blocks_of("isActive"))
    return sum(t.count for t in trace.tables_of("contacts")) / max(frames, 1)


def refusal(name: str, backend, path: str) -> str | None:
    """Why `x3drbp run` would refuse the scene on this backend (exit 3), or None."""
    from backends import base
    from x3d_core.encodings.load import load
    refused = [str(u) for u, d in base.judged(backend, load(path)) if d.support is base.Support.UNSUPPORTED]
    return f"{name} refuses {', '.join(refused)}" if refused else None


def profile(fn, top: int = 15) -> str:
    prof = cProfile.Profile()
    prof.enable()
    fn()
    prof.disable()
    buf = io.StringIO()
    pstats.Stats(prof, stream=buf).sort_stats("tottime").print_stats(top)
    return buf.getvalue()


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=5.0)
    ap.add_argument("--dart-duration", type=float, default=DART_DURATION,
                    help="DART runs min(duration, this): its Dantzig solver takes ~0.2 s a step on the settled pile")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--backends", default=None,
                    help="default: every engine that runs the scene (mujoco,bullet,dart,ode)")
    ap.add_argument("--profile", action="store_true", help=f"cProfile x3drbp's run where it is over {SLOW}x native")
    args = ap.parse_args(argv)
    # x3drbp's own modules here only: benchmarks/native_run.py imports the native builds above
    # into a process that must not pay for them
    from backends import base
    from x3d_core.semantics.engine import Unsupported
    from x3d_core.semantics.evaluator import RunSettings, run
    from x3d_core.encodings.load import load
    from x3d_core.semantics.world import worlds
    if min(args.duration, args.dart_duration) < CHECK_T:
        ap.error(f"--duration and --dart-duration must reach the {CHECK_T} s check")
    folder = tempfile.mkdtemp(prefix="x3drbp-pile-bench-")
    paths = {}
    for sensor in (False, True):
        paths[sensor] = os.path.join(folder, f"pile{'-sensor' if sensor else ''}.x3d")
        with open(paths[sensor], "w") as f:
            f.write(pile_x3d(sensor))
    names = args.backends.split(",") if args.backends else list(NATIVE)
    chosen = []
    for name in names:
        try:
            backend = base.load(name)
        except ImportError as e:
            print(f"{name}: skipped, unavailable ({e})", file=sys.stderr)
            continue
        why = refusal(name, backend, paths[False]) or refusal(name, backend, paths[True])
        if why:
            print(f"{name}: skipped: {why}", file=sys.stderr)
            continue
        chosen.append((name, backend))
    check = round(CHECK_T * FRAME_RATE) - 1  # the frame row ending at CHECK_T
    print(f"{SPHERES} spheres + {BOXES} boxes falling into a pile in a pit, dt 1/240 s, state read at {FRAME_RATE} Hz; "
          f"best of {args.repeat}\n")
    print("| backend | simulated s | contacts read | native s | x3drbp s | ratio | peak MB native | peak MB x3drbp "
          f"| max pos diff at {CHECK_T:g} s | final mean height native / x3drbp m | diff m | final max body diff m |")
    print("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    failed = False
    slow = []
    for name, backend in chosen:
        native = NATIVE[name]
        duration = min(args.duration, args.dart_duration) if name == "dart" else args.duration
        settings = RunSettings(duration=duration, dt=DT, frame_rate=FRAME_RATE)
        runs = {}
        for sensor in (False, True):
            path = paths[sensor]

            def ours(path=path, backend=backend, settings=settings):
                return run(worlds(load(path)), backend, settings)

            def theirs(native=native, duration=duration, sensor=sensor):
                return native(duration, contacts=sensor)
            try:
                t_native, theirs_pos = timed(theirs, args.repeat)
                t_ours, trace = timed(ours, args.repeat)
            except Unsupported as e:
                print(f"| {name} | {'every frame' if sensor else 'never'} | refused: {e} |||||||||", flush=True)
                break
            ours_pos = positions(trace)
            runs[sensor] = ours_pos
            early = float(np.abs(ours_pos[check] - theirs_pos[check]).max())
            h_native, h_ours = float(theirs_pos[-1, :, 1].mean()), float(ours_pos[-1, :, 1].mean())
            same_height = abs(h_ours - h_native) <= HEIGHT_SAME
            failed |= not (early <= AGREE and same_height)
            final = float(np.abs(ours_pos[-1] - theirs_pos[-1]).max())
            label = f"every frame ({contact_counts(trace):.0f}/frame)" if sensor else "never (no sensor)"
            ratio = t_ours / t_native
            print(f"| {name} {backend.version()} | {duration:g} | {label} | {t_native:.3f} | {t_ours:.3f} | "
                  f"{ratio:.2f}x | {peak_mb(theirs):.1f} | {peak_mb(ours):.1f} | "
                  f"{early:.1e}{'' if early <= AGREE else ' (NOT the same)'} | {h_native:.4f} / {h_ours:.4f} | "
                  f"{h_ours - h_native:+.4f}{'' if same_height else ' (NOT the same)'} | {final:.1e} |", flush=True)
            if ratio > SLOW:
                slow.append((name, sensor, ours))
        if len(runs) == 2 and not np.array_equal(runs[False], runs[True]):
            print(f"\nnote: {name}: reading contacts changed x3drbp's physics (max "
                  f"{np.abs(runs[False] - runs[True]).max():.1e} m)", flush=True)
    print(f"\nA pile is chaotic: final positions need not agree body by body; the mean heights must agree within "
          f"{HEIGHT_SAME:g} m. Positions at {CHECK_T:g} s (before any contact) must agree to {AGREE:g} m. "
          "Peak MB: Python allocations (tracemalloc), not the engines' own.")
    if args.profile:
        for name, sensor, fn in slow:
            print(f"\n## cProfile: x3drbp on {name}, contacts {'read every frame' if sensor else 'never read'}\n")
            print(profile(fn))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

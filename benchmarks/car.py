"""The car scene of benchmarks/engine_speed.py, and the same car written in ODE's own API.

A 10 kg box chassis (2 x 0.4 x 1 m, no collider: only the wheels touch anything) on four
1 kg sphere wheels (radius 0.3 m), each joined to the chassis by a DoubleAxisHingeJoint at
its centre (axis1 0 1 0, the steering axis, free; axis2 0 0 1, the axle; every other field
its default: no stops, no suspension, no motors), rolling at 2 m/s along +x on a static
floor box (top face y = 0), friction 0.8, bounce 0. Every body's inertia is explicit (its
shape's solid inertia), so no engine computes its own.
"""

from __future__ import annotations

import numpy as np

DT, FRAME_RATE, GRAVITY = 1 / 240, 60, 9.81
ITERATIONS, ERP, CFM = 10, 0.8, 1e-4  # RigidBodyCollection's iterations (set), errorCorrection and constantForceMix
MU, MIN_BOUNCE_SPEED = 0.8, 0.1
SPEED = 2.0  # m/s along +x
CHASSIS_MASS, CHASSIS_SIZE = 10.0, np.array([2.0, 0.4, 1.0])
CHASSIS_MOMENTS = CHASSIS_MASS * (CHASSIS_SIZE[[1, 0, 0]] ** 2 + CHASSIS_SIZE[[2, 2, 1]] ** 2) / 12
WHEEL_MASS, RADIUS = 1.0, 0.3
WHEEL_MOMENT = 0.4 * WHEEL_MASS * RADIUS ** 2
START = np.array([-3.0, 0.55, 0.0])  # the chassis centre: its bottom face 0.05 m above the axles
WHEELS = np.array([[x, RADIUS, z] for x in (-0.7, 0.7) for z in (-0.6, 0.6)]) + [START[0], 0.0, 0.0]
FLOOR_SIZE, FLOOR_CENTRE = (20.0, 0.2, 20.0), (0.0, -0.1, 0.0)
SPIN = np.array([0.0, 0.0, -SPEED / RADIUS])  # rolling without slip along +x


def _vec(v) -> str:
    return " ".join(repr(float(x)) for x in v)


def car_x3d() -> str:
    """The scene: the chassis first, then the wheels W0-W3, the joints, the floor."""
    velocity = _vec([SPEED, 0.0, 0.0])
    items = [f"<RigidBody DEF='Chassis' mass='{CHASSIS_MASS!r}' position='{_vec(START)}' linearVelocity='{velocity}' "
             f"inertia='{_vec(np.diag(CHASSIS_MOMENTS).ravel())}'/>"]
    shapes = []
    for k, centre in enumerate(WHEELS):
        items.append(f"<RigidBody DEF='W{k}' mass='{WHEEL_MASS!r}' position='{_vec(centre)}' "
                     f"linearVelocity='{velocity}' angularVelocity='{_vec(SPIN)}' "
                     f"inertia='{_vec(np.diag([WHEEL_MOMENT] * 3).ravel())}'>"
                     f"<CollidableShape DEF='S{k}' containerField='geometry'><Shape containerField='shape'>"
                     f"<Sphere radius='{RADIUS!r}'/></Shape></CollidableShape></RigidBody>")
        shapes.append(f"<CollidableShape USE='S{k}' containerField='collidables'/>")
    for k, centre in enumerate(WHEELS):
        items.append(f"<DoubleAxisHingeJoint anchorPoint='{_vec(centre)}' axis1='0 1 0' axis2='0 0 1'>"
                     "<RigidBody USE='Chassis' containerField='body1'/>"
                     f"<RigidBody USE='W{k}' containerField='body2'/></DoubleAxisHingeJoint>")
    shapes.append(f"<CollidableShape DEF='Floor' containerField='collidables' translation='{_vec(FLOOR_CENTRE)}'>"
                  f"<Shape containerField='shape'><Box size='{_vec(FLOOR_SIZE)}'/></Shape></CollidableShape>")
    collision = (f"<CollisionCollection frictionCoefficients='{_vec([MU, MU])}' bounce='0'>\n"
                 + "\n".join(shapes) + "\n</CollisionCollection>")
    return ("<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Full' version='4.0'><Scene>\n"
            f"<RigidBodyCollection gravity='0 {-GRAVITY!r} 0' iterations='{ITERATIONS}'>\n"
            + "\n".join(items) + "\n" + collision + "\n</RigidBodyCollection>\n</Scene></X3D>\n")


def _frames(duration: float) -> tuple[int, int]:
    return round(duration * FRAME_RATE), round(1 / (FRAME_RATE * DT))


def native_ode(duration: float) -> np.ndarray:
    """As backends/ode.py builds it, through its ctypes binding of libode: a body per body with
    dMassSetParameters' mass and inertia, the chassis first; a hinge2 per wheel (chassis as
    body 1) with no stops, suspension ERP 0.8 and CFM 0 (X3D's defaults: rigid), no motors; a
    sphere geom per wheel and a bodiless box for the floor; quick-step, ERP 0.8, CFM 1e-4, 10
    iterations, surface layer 0; every contact dContactApprox1 | dContactBounce (mu 0.8,
    bounce 0, bounce_vel 0.1). Collision is ODE's own, as a user writes it: the geoms in a
    dSimpleSpace, dSpaceCollide calling back into Python per overlapping pair, dCollide
    there, the pair's geoms in the order the backend gives them (wheel first). State is
    read with dBodyGet* calls every frame. Returns every frame's positions (frames, 5, 3)."""
    import ctypes

    import ode_shared  # beside this script
    from backends import ode_lib as ode
    lib = ode.lib
    world = ode_shared.world(GRAVITY, ERP, CFM, ITERATIONS)
    space = ode_shared.simple_space(None)
    mass = (ctypes.c_double * ode.MASS_REALS)()
    chassis = lib.dBodyCreate(world)
    lib.dMassSetParameters(mass, CHASSIS_MASS, 0, 0, 0, *CHASSIS_MOMENTS, 0, 0, 0)
    lib.dBodySetMass(chassis, mass)
    lib.dBodySetPosition(chassis, *START)
    lib.dBodySetLinearVel(chassis, SPEED, 0, 0)
    bodies, body_of = [chassis], {}
    lib.dMassSetParameters(mass, WHEEL_MASS, 0, 0, 0, WHEEL_MOMENT, WHEEL_MOMENT, WHEEL_MOMENT, 0, 0, 0)
    for centre in WHEELS:
        wheel = lib.dBodyCreate(world)
        lib.dBodySetMass(wheel, mass)
        lib.dBodySetPosition(wheel, *centre)
        lib.dBodySetLinearVel(wheel, SPEED, 0, 0)
        lib.dBodySetAngularVel(wheel, *SPIN)
        geom = lib.dCreateSphere(space, RADIUS)
        lib.dGeomSetBody(geom, wheel)
        body_of[geom] = wheel
        bodies.append(wheel)
    for centre, wheel in zip(WHEELS, bodies[1:]):
        hinge = lib.dJointCreateHinge2(world, None)
        lib.dJointAttach(hinge, chassis, wheel)
        lib.dJointSetHinge2Anchor(hinge, *centre)
        lib.dJointSetHinge2Axes(hinge, ode.array([0, 1, 0]), ode.array([0, 0, 1]))
        lib.dJointSetHinge2Param(hinge, ode.SUSPENSION_ERP, 0.8)
        lib.dJointSetHinge2Param(hinge, ode.SUSPENSION_CFM, 0.0)
    floor = lib.dCreateBox(space, *FLOOR_SIZE)
    lib.dGeomSetPosition(floor, *FLOOR_CENTRE)
    surface = np.zeros(1, dtype=ode.CONTACT)
    surface["mode"] = ode.CONTACT_APPROX1 | ode.CONTACT_BOUNCE
    surface["mu"], surface["bounce"], surface["bounce_vel"] = MU, 0.0, MIN_BOUNCE_SPEED
    buffer = np.repeat(surface, 64)
    group = lib.dJointGroupCreate(0)
    found = 0

    @ode_shared.NEAR
    def collide(_data, o1: int, o2: int) -> None:
        nonlocal found
        if o1 == floor:
            o1, o2 = o2, o1  # the wheel as geom 1, as the backend orders its pairs
        at = buffer.ctypes.data + found * ode.CONTACT.itemsize
        for k in range(lib.dCollide(o1, o2, 16, at + ode.GEOM_OFFSET, ode.CONTACT.itemsize)):
            lib.dJointAttach(lib.dJointCreateContact(world, group, at + k * ode.CONTACT.itemsize), body_of[o1], None)
            found += 1

    def reset() -> None:
        nonlocal found
        found = 0

    out = ode_shared.simulate(world, space, group, collide, bodies, *_frames(duration), DT, before_step=reset)
    return np.array([[pose[0] for pose in frame] for frame in out])

def native_mujoco(duration: float) -> np.ndarray:
    """As backends/mujoco.py builds it: the chassis a free body, each wheel its child with a
    hinge about axis 1 then one about axis 2 at the wheel's centre (no suspension slide: its
    force is 0), inertias explicit, massless sphere geoms and the floor box on the world
    body; the wheels' velocities as joint velocities (the spin about axis 2). Every pair
    that may touch listed explicitly, the floor's with each wheel, then the wheels' with
    each other: condim 3, friction [mu, mu] on the elliptic cone with 30 no-slip
    iterations, the backend's hard solref (stiffness min(ERP, 0.25)/dt^2, damping 1/dt) and
    solimp, friction rows damped 0.15/dt. Reads every body's pose and velocities every
    frame. Returns every frame's positions (frames, 5, 3)."""
    import mujoco
    spec = mujoco.MjSpec()
    spec.compiler.degree = False
    spec.option.timestep, spec.option.gravity, spec.option.iterations = DT, [0, -GRAVITY, 0], ITERATIONS
    spec.option.cone, spec.option.noslip_iterations = mujoco.mjtCone.mjCONE_ELLIPTIC, 30

    def inertial(body, mass: float, moments) -> None:
        body.explicitinertial, body.mass, body.ipos = True, mass, [0, 0, 0]
        body.fullinertia = [*moments, 0, 0, 0]

    chassis = spec.worldbody.add_body(name="chassis", pos=START)
    inertial(chassis, CHASSIS_MASS, CHASSIS_MOMENTS)
    chassis.add_freejoint()
    for k, centre in enumerate(WHEELS):
        wheel = chassis.add_body(name=f"w{k}", pos=centre - START)
        inertial(wheel, WHEEL_MASS, [WHEEL_MOMENT] * 3)
        wheel.add_joint(type=mujoco.mjtJoint.mjJNT_HINGE, axis=[0, 1, 0])
        wheel.add_joint(type=mujoco.mjtJoint.mjJNT_HINGE, axis=[0, 0, 1])
        wheel.add_geom(name=f"g{k}", type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[RADIUS, 0, 0], density=0.0,
                       contype=0, conaffinity=0)
    spec.worldbody.add_geom(name="floor", type=mujoco.mjtGeom.mjGEOM_BOX, size=np.array(FLOOR_SIZE) / 2,
                            pos=FLOOR_CENTRE, contype=0, conaffinity=0)
    names = [f"g{k}" for k in range(len(WHEELS))]
    for first, second in [("floor", n) for n in names] + [(a, b) for i, a in enumerate(names) for b in names[i + 1:]]:
        pair = spec.add_pair(geomname1=first, geomname2=second)
        pair.condim, pair.friction = 3, [MU, MU, 0.0, 0.0, 0.0]
        pair.solref, pair.solimp = [-min(ERP, 0.25) / DT ** 2, -1.0 / DT], [0.99, 0.99, 0.001, 0.5, 2.0]
        pair.solreffriction = [-1e-9, -0.15 / DT]
    m = spec.compile()
    d = mujoco.MjData(m)
    d.qvel[0] = SPEED  # the free joint's linear velocity; then each wheel's steering and spin rates
    d.qvel[6:] = np.tile([0.0, SPIN[2]], len(WHEELS))
    ids = [m.body("chassis").id] + [m.body(f"w{k}").id for k in range(len(WHEELS))]
    frames, steps_per_frame = _frames(duration)
    out = []
    for _ in range(frames):
        mujoco.mj_step(m, d, nstep=steps_per_frame)
        mujoco.mj_kinematics(m, d)
        mujoco.mj_comPos(m, d)
        mujoco.mj_comVel(m, d)
        out.append((d.xpos[ids], d.xquat[ids], d.cvel[ids]))
    return np.array([pos for pos, _, _ in out])


def native_dart(duration: float) -> np.ndarray:
    """As backends/dart.py builds it: DART's Bullet collision detector, sleeping off; an
    immobile welded skeleton for the floor, added to the world first; one skeleton for the
    car, the chassis on a FreeJoint and each wheel its child on a UniversalJoint at the
    wheel's centre (axis 1 fixed in the chassis, axis 2 carried by the wheel: a hinge2
    without suspension), inertias explicit, the car's self-collision on with each
    chassis-wheel pair blacklisted; every shape friction mu, restitution 0; DART's default
    solver. The velocities as joint velocities. Returns every frame's positions (frames, 5, 3)."""
    import dartpy as dart

    import dart_shared  # beside this script

    def at(where) -> dart.math.Isometry3:
        t = dart.math.Isometry3()
        t.set_translation(np.asarray(where, dtype=np.float64))
        return t

    def collide(node, shape, name: str, where=(0.0, 0.0, 0.0)) -> None:
        frame = node.createShapeNode(shape, name)
        frame.setRelativeTransform(at(where))
        frame.createCollisionAspect()
        surface = frame.createDynamicsAspect()
        surface.setFrictionCoeff(MU)
        surface.setRestitutionCoeff(0.0)

    world = dart_shared.world(DT, GRAVITY)
    car = dart.dynamics.Skeleton("car")
    joint, chassis = car.createFreeJointAndBodyNodePair(None)
    joint.setPositions(dart.dynamics.FreeJoint.convertToPositions(at(START)))
    chassis.setInertia(dart.dynamics.Inertia(CHASSIS_MASS, np.zeros(3), np.diag(CHASSIS_MOMENTS)))
    nodes = [chassis]
    for centre in WHEELS:
        joint, wheel = car.createUniversalJointAndBodyNodePair(chassis)
        joint.setAxis1([0.0, 1.0, 0.0])
        joint.setAxis2([0.0, 0.0, 1.0])
        joint.setTransformFromParentBodyNode(at(centre - START))
        joint.setTransformFromChildBodyNode(at(np.zeros(3)))
        wheel.setInertia(dart.dynamics.Inertia(WHEEL_MASS, np.zeros(3), WHEEL_MOMENT * np.eye(3)))
        nodes.append(wheel)
    ground = dart.dynamics.Skeleton("ground")
    _, floor = ground.createWeldJointAndBodyNodePair(None)
    ground.setMobile(False)
    world.addSkeleton(ground)
    for k, wheel in enumerate(nodes[1:]):
        collide(wheel, dart.dynamics.SphereShape(RADIUS), f"wheel{k}")
    collide(floor, dart.dynamics.BoxShape(np.array(FLOOR_SIZE)), "floor", FLOOR_CENTRE)
    car.enableSelfCollisionCheck()
    car.enableAdjacentBodyCheck()
    keep_apart = world.getConstraintSolver().getCollisionOption().collisionFilter
    for wheel in nodes[1:]:
        keep_apart.addBodyNodePairToBlackList(chassis, wheel)
    world.addSkeleton(car)
    car.setVelocities(np.concatenate([[0.0, 0.0, 0.0, SPEED, 0.0, 0.0], np.tile([0.0, SPIN[2]], len(WHEELS))]))
    frames, steps_per_frame = _frames(duration)
    out = []
    for _ in range(frames):
        for _ in range(steps_per_frame):
            world.step()
        out.append([(n.getWorldTransform().matrix(), n.getCOMLinearVelocity(), n.getAngularVelocity())
                    for n in nodes])
    return np.array([[tf[:3, 3] for tf, _, _ in frame] for frame in out])


def native_bullet(duration: float) -> np.ndarray:
    """As backends/bullet.py builds it: one multibody, the chassis its base, each wheel two
    revolute links (a massless link about axis 1 at the wheel's centre, then the wheel about
    axis 2: two hinges in series), self-collision on, damping off, joint motors freed; the
    floor a massless multibody created after it; the solver's iterations, ERP (contacts too),
    no split impulse, pyramid friction, each object's friction sqrt(mu) (pybullet multiplies
    two objects'), restitution 0, no rolling or spinning friction, contactProcessingThreshold
    1e-4. The velocities as the base's and the joints'. Returns every frame's positions."""
    import pybullet as p
    c = p.connect(p.DIRECT)
    p.setGravity(0, -GRAVITY, 0, physicsClientId=c)
    p.setPhysicsEngineParameter(fixedTimeStep=DT, numSubSteps=0, numSolverIterations=ITERATIONS, erp=ERP,
                                useSplitImpulse=0, physicsClientId=c)
    wheels = [p.createCollisionShape(p.GEOM_SPHERE, radius=RADIUS, collisionFramePosition=[0, 0, 0],
                                     collisionFrameOrientation=[0, 0, 0, 1], physicsClientId=c) for _ in WHEELS]
    n = 2 * len(WHEELS)
    unturned = [[0, 0, 0, 1]] * n
    car = p.createMultiBody(
        baseMass=CHASSIS_MASS, baseCollisionShapeIndex=-1, baseVisualShapeIndex=-1, basePosition=START,
        baseOrientation=[0, 0, 0, 1], baseInertialFramePosition=[0, 0, 0], baseInertialFrameOrientation=[0, 0, 0, 1],
        linkMasses=[0.0, WHEEL_MASS] * len(WHEELS), linkCollisionShapeIndices=[x for w in wheels for x in (-1, w)],
        linkVisualShapeIndices=[-1] * n,
        linkPositions=[x for centre in WHEELS for x in (centre - START, [0, 0, 0])], linkOrientations=unturned,
        linkInertialFramePositions=[[0, 0, 0]] * n, linkInertialFrameOrientations=unturned,
        linkParentIndices=[x for k in range(len(WHEELS)) for x in (0, 2 * k + 1)],
        linkJointTypes=[p.JOINT_REVOLUTE] * n, linkJointAxis=[[0, 1, 0], [0, 0, 1]] * len(WHEELS),
        flags=p.URDF_USE_SELF_COLLISION, physicsClientId=c)
    # multibodies are damped by default, and their joint speeds clamped
    p.changeDynamics(car, -1, linearDamping=0, angularDamping=0, maxJointVelocity=1e6, physicsClientId=c)
    p.changeDynamics(car, -1, mass=CHASSIS_MASS, localInertiaDiagonal=CHASSIS_MOMENTS, physicsClientId=c)
    for link in range(n):
        wheel = link % 2 == 1
        p.changeDynamics(car, link, mass=WHEEL_MASS if wheel else 0.0,
                         localInertiaDiagonal=[WHEEL_MOMENT if wheel else 0.0] * 3, physicsClientId=c)
        p.changeDynamics(car, link, jointDamping=0.0, physicsClientId=c)
        p.setJointMotorControl2(car, link, p.VELOCITY_CONTROL, targetVelocity=0.0, force=0.0, physicsClientId=c)
    floor = p.createMultiBody(baseMass=0.0, physicsClientId=c, basePosition=FLOOR_CENTRE,
                              baseCollisionShapeIndex=p.createCollisionShape(
                                  p.GEOM_BOX, halfExtents=(np.array(FLOOR_SIZE) / 2).tolist(), physicsClientId=c))
    p.setPhysicsEngineParameter(restitutionVelocityThreshold=MIN_BOUNCE_SPEED, contactSlop=0, enableConeFriction=0,
                                contactERP=ERP, physicsClientId=c)
    for uid, link in [(car, k) for k in range(1, n, 2)] + [(floor, -1)]:
        p.changeDynamics(uid, link, lateralFriction=float(np.sqrt(MU)), restitution=0.0, rollingFriction=0.0,
                         spinningFriction=0.0, contactProcessingThreshold=1e-4, physicsClientId=c)
    p.resetBaseVelocity(car, [SPEED, 0, 0], [0, 0, 0], physicsClientId=c)
    for link in range(1, n, 2):
        p.resetJointState(car, link, 0.0, SPIN[2], physicsClientId=c)
    links = list(range(n))
    frames, steps_per_frame = _frames(duration)
    out = []
    for _ in range(frames):
        for _ in range(steps_per_frame):
            p.stepSimulation(physicsClientId=c)
        out.append((p.getBasePositionAndOrientation(car, physicsClientId=c), p.getBaseVelocity(car, physicsClientId=c),
                    p.getLinkStates(car, links, computeLinkVelocity=1, computeForwardKinematics=1,
                                    physicsClientId=c)))
    p.disconnect(c)
    return np.array([[base[0]] + [state[0] for state in states[1::2]] for base, _, states in out])


NATIVE = {"ode": native_ode, "mujoco": native_mujoco, "dart": native_dart, "bullet": native_bullet}

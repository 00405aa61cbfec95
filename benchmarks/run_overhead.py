"""Benchmark: x3drbp's run against the same scene written directly in each engine's API.

Two scenes, generated here: a 20-link hinge chain hanging from a fixed body, and 100
free boxes (no collider, so no contacts). Each runs for --duration simulated seconds at
dt = 1/240 s with state read at 60 frames per second. x3drbp's side is load + plan +
build + steps + every frame's bulk readback into the trace (kept in memory); the
native side builds the same model with the engine's own calls, with the same step and
solver iterations, steps it, and reads every body's pose and velocity at each frame.
Writing the trace to CSV is timed apart: it is output, not simulation. The native
versions are written as a user of each engine would write them, with no x3drbp code;
the scene files carry every digit of the numbers they use, and the table's last column
is the largest difference between the two sides' final positions, which must be within
SAME for the comparison to be of the same physics (the exit status is 1 where it is not).

    python benchmarks/run_overhead.py [--duration 10] [--repeat 3] [--backends mujoco,bullet,dart,ode]
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from measure import peak_mb, timed  # noqa: E402  (benchmarks/measure.py, beside this script)

DT = 1 / 240
FRAME_RATE = 60
LINKS = 20
BOXES = 100
INERTIA = "0.0104 0 0 0 0.0104 0 0 0 0.0017"  # a 1 kg, 0.1 x 0.1 x 0.35 box, about its centre
SAME = 1e-6  # m: the largest difference in final positions between the two sides that counts as the same run


# The chain hangs 0.3 rad from the vertical and swings: an undamped chain released from
# the horizontal blows up within seconds at this step on every engine (notes/backends.md)
DIRECTION = np.array([np.sin(0.3), -np.cos(0.3), 0.0])


def _vec(v) -> str:
    """Every digit, so that the native builds below get the very numbers x3drbp reads."""
    return " ".join(repr(float(x)) for x in v)


def chain_x3d() -> str:
    bodies = ["<RigidBody DEF='Base' fixed='true'/>"]
    joints = []
    for k in range(LINKS):
        bodies.append(f"<RigidBody DEF='L{k}' position='{_vec(DIRECTION * (0.35 * k + 0.175))}' "
                      f"inertia='{INERTIA}'/>")
        parent = "Base" if k == 0 else f"L{k - 1}"
        joints.append(f"<SingleAxisHingeJoint anchorPoint='{_vec(DIRECTION * 0.35 * k)}' axis='0 0 1'>"
                      f"<RigidBody USE='{parent}' containerField='body1'/>"
                      f"<RigidBody USE='L{k}' containerField='body2'/></SingleAxisHingeJoint>")
    return _wrap(bodies + joints)


def box_draws() -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Each box's position, linear and angular velocity: the scene file and every native build use these."""
    rng = np.random.default_rng(7)
    out = []
    for _ in range(BOXES):
        position = rng.uniform(-5, 5, 3) + [0.0, 10.0, 0.0]
        out.append((position, rng.uniform(-1, 1, 3), rng.uniform(-3, 3, 3)))
    return out


def boxes_x3d() -> str:
    bodies = [f"<RigidBody DEF='B{k}' position='{_vec(x)}' linearVelocity='{_vec(v)}' angularVelocity='{_vec(w)}' "
              f"inertia='{INERTIA}'/>" for k, (x, v, w) in enumerate(box_draws())]
    return _wrap(bodies)


def _wrap(items: list[str]) -> str:
    return ("<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Full' version='4.0'><Scene>"
            "<RigidBodyCollection gravity='0 -9.81 0' iterations='10'>\n" + "\n".join(items) +
            "\n</RigidBodyCollection></Scene></X3D>\n")


# -- the same scenes written directly in each engine's API --------------------------
# Each returns the moving bodies' final positions (body frame origins, here the centres
# of mass), in the scene's order, for the check against x3drbp's trace.
MASS = 1.0
MOMENTS = [0.0104, 0.0104, 0.0017]  # principal moments, body axes: the INERTIA above


def native_mujoco(scene: str, duration: float) -> np.ndarray:
    import mujoco
    from native_mujoco_chain import chain_spec, options  # beside this script
    inertia = MOMENTS + [0, 0, 0]
    velocities = []
    if scene == "chain":
        spec = chain_spec(LINKS)
    else:
        spec = options()
        for position, v, w in box_draws():
            velocities.append(np.concatenate([v, w]))
            body = spec.worldbody.add_body(pos=position, ipos=[0, 0, 0])
            body.explicitinertial, body.mass, body.fullinertia = True, MASS, inertia
            body.add_freejoint()
    m = spec.compile()
    d = mujoco.MjData(m)
    if velocities:  # free joints: linear (world), angular (body frame, here the same)
        d.qvel[:] = np.concatenate(velocities)
    steps_per_frame = round(1 / (FRAME_RATE * DT))
    frames = []
    for _ in range(round(duration * FRAME_RATE)):
        mujoco.mj_step(m, d, nstep=steps_per_frame)
        mujoco.mj_kinematics(m, d)
        mujoco.mj_comPos(m, d)
        mujoco.mj_comVel(m, d)
        frames.append((d.xpos.copy(), d.xquat.copy(), d.cvel.copy()))
    return frames[-1][0][1:]  # row 0 is the world body


def native_bullet(scene: str, duration: float) -> np.ndarray:
    import pybullet as p
    c = p.connect(p.DIRECT)
    p.setGravity(0, -9.81, 0, physicsClientId=c)
    p.setPhysicsEngineParameter(fixedTimeStep=DT, numSolverIterations=10, numSubSteps=0, physicsClientId=c)
    if scene == "chain":
        # one multibody: a massless fixed base at the origin and 20 revolute links, each
        # link's frame at its hinge, its centre of mass 0.175 m further down the chain
        chain = p.createMultiBody(
            baseMass=0, baseCollisionShapeIndex=-1, basePosition=[0, 0, 0],
            linkMasses=[MASS] * LINKS, linkCollisionShapeIndices=[-1] * LINKS, linkVisualShapeIndices=[-1] * LINKS,
            linkPositions=[[0, 0, 0]] + [DIRECTION * 0.35] * (LINKS - 1), linkOrientations=[[0, 0, 0, 1]] * LINKS,
            linkInertialFramePositions=[DIRECTION * 0.175] * LINKS,
            linkInertialFrameOrientations=[[0, 0, 0, 1]] * LINKS,
            linkParentIndices=list(range(LINKS)), linkJointTypes=[p.JOINT_REVOLUTE] * LINKS,
            linkJointAxis=[[0, 0, 1]] * LINKS, physicsClientId=c)
        p.changeDynamics(chain, -1, linearDamping=0, angularDamping=0, physicsClientId=c)
        for k in range(LINKS):
            # a link without a collision shape gets no inertia unless told
            p.changeDynamics(chain, k, mass=MASS, localInertiaDiagonal=MOMENTS, jointDamping=0, physicsClientId=c)
            p.setJointMotorControl2(chain, k, p.VELOCITY_CONTROL, force=0, physicsClientId=c)  # free the joint
        links = list(range(LINKS))

        def read():
            return p.getLinkStates(chain, links, computeLinkVelocity=1, computeForwardKinematics=1,
                                   physicsClientId=c)

        def final(frame):
            return np.array([s[0] for s in frame])
    else:
        boxes = []
        for position, v, w in box_draws():
            box = p.createMultiBody(baseMass=MASS, baseCollisionShapeIndex=-1, basePosition=position,
                                    physicsClientId=c)
            p.changeDynamics(box, -1, mass=MASS, localInertiaDiagonal=MOMENTS, linearDamping=0, angularDamping=0,
                             physicsClientId=c)
            p.resetBaseVelocity(box, v, w, physicsClientId=c)
            boxes.append(box)

        def read():
            return [(p.getBasePositionAndOrientation(b, physicsClientId=c), p.getBaseVelocity(b, physicsClientId=c))
                    for b in boxes]

        def final(frame):
            return np.array([pose[0] for pose, _ in frame])
    steps_per_frame = round(1 / (FRAME_RATE * DT))
    frames = []
    for _ in range(round(duration * FRAME_RATE)):
        for _ in range(steps_per_frame):
            p.stepSimulation(physicsClientId=c)
        frames.append(read())
    p.disconnect(c)
    return final(frames[-1])


def native_dart(scene: str, duration: float) -> np.ndarray:
    import dartpy as dart
    world = dart.simulation.World()
    world.setTimeStep(DT)
    world.setGravity([0, -9.81, 0])
    sleep = world.getDeactivationOptions()
    sleep.mEnabled = False  # DART puts slow bodies to sleep by default
    world.setDeactivationOptions(sleep)
    inertia = dart.dynamics.Inertia(MASS, np.zeros(3), np.diag(MOMENTS))

    def shift(v) -> dart.math.Isometry3:
        t = dart.math.Isometry3()
        t.set_translation(np.asarray(v, dtype=np.float64))
        return t

    nodes = []
    if scene == "chain":
        chain = dart.dynamics.Skeleton("chain")
        parent = None
        for k in range(LINKS):
            joint, node = chain.createRevoluteJointAndBodyNodePair(parent)
            joint.setAxis([0, 0, 1])
            # the hinge: at the origin for the first link, else 0.175 m beyond the parent's centre
            joint.setTransformFromParentBodyNode(shift(DIRECTION * (0.175 if k else 0.0)))
            joint.setTransformFromChildBodyNode(shift(-0.175 * DIRECTION))
            node.setInertia(inertia)
            nodes.append(node)
            parent = node
        world.addSkeleton(chain)
    else:
        for k, (position, v, w) in enumerate(box_draws()):
            box = dart.dynamics.Skeleton(f"box{k}")
            joint, node = box.createFreeJointAndBodyNodePair(None)
            node.setInertia(inertia)
            joint.setPositions(dart.dynamics.FreeJoint.convertToPositions(shift(position)))
            joint.setVelocities(np.concatenate([w, v]))  # [angular; linear]: unturned, centre at the origin
            world.addSkeleton(box)
            nodes.append(node)
    steps_per_frame = round(1 / (FRAME_RATE * DT))
    frames = []
    for _ in range(round(duration * FRAME_RATE)):
        for _ in range(steps_per_frame):
            world.step()
        frames.append([(n.getWorldTransform().matrix(), n.getCOMLinearVelocity(), n.getAngularVelocity())
                       for n in nodes])
    return np.array([tf[:3, 3] for tf, _, _ in frames[-1]])


def native_ode(scene: str, duration: float) -> np.ndarray:
    import ctypes

    from backends.ode_lib import MASS_REALS, lib  # the ctypes binding of the system's libode
    lib.dAllocateODEDataForThread(0xFFFFFFFF)
    lib.dRandSetSeed(0)
    world = lib.dWorldCreate()
    lib.dWorldSetGravity(world, 0, -9.81, 0)
    lib.dWorldSetERP(world, 0.8)  # X3D's defaults for errorCorrection and constantForceMix
    lib.dWorldSetCFM(world, 1e-4)
    lib.dWorldSetQuickStepNumIterations(world, 10)
    mass = (ctypes.c_double * MASS_REALS)()
    lib.dMassSetParameters(mass, MASS, 0, 0, 0, *MOMENTS, 0, 0, 0)
    bodies = []
    if scene == "chain":
        for k in range(LINKS):
            body = lib.dBodyCreate(world)
            lib.dBodySetMass(body, mass)
            lib.dBodySetPosition(body, *(DIRECTION * (0.35 * k + 0.175)))
            hinge = lib.dJointCreateHinge(world, None)
            lib.dJointAttach(hinge, body, bodies[-1] if bodies else None)  # the first link on the world
            lib.dJointSetHingeAnchor(hinge, *(DIRECTION * 0.35 * k))
            lib.dJointSetHingeAxis(hinge, 0, 0, -1)  # the child turns about +z relative to its parent
            bodies.append(body)
    else:
        for position, v, w in box_draws():
            body = lib.dBodyCreate(world)
            lib.dBodySetMass(body, mass)
            lib.dBodySetPosition(body, *position)
            lib.dBodySetLinearVel(body, *v)
            lib.dBodySetAngularVel(body, *w)
            bodies.append(body)
    steps_per_frame = round(1 / (FRAME_RATE * DT))
    frames = []
    for _ in range(round(duration * FRAME_RATE)):
        for _ in range(steps_per_frame):
            lib.dWorldQuickStep(world, DT)
        frames.append([(lib.dBodyGetPosition(b)[:3], lib.dBodyGetQuaternion(b)[:4], lib.dBodyGetLinearVel(b)[:3],
                        lib.dBodyGetAngularVel(b)[:3]) for b in bodies])
    lib.dWorldDestroy(world)
    return np.array([f[0] for f in frames[-1]])


NATIVE = {"mujoco": native_mujoco, "bullet": native_bullet, "dart": native_dart, "ode": native_ode}


def final_positions(trace) -> np.ndarray:
    """The moving bodies' positions at the trace's last frame, in the scene's order (the
    chain's fixed base left out)."""
    last = trace.blocks_of("position")[-1]
    keep = [k for k, name in enumerate(last.nodes) if name != "Base"]
    return np.asarray(last.values)[keep]






def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=10.0)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--backends", default=",".join(NATIVE))
    args = ap.parse_args(argv)
    # x3drbp's own modules here only: benchmarks/native_run.py imports the native builds above
    # into a process that must not pay for them
    from backends import base
    from x3d_core.semantics.evaluator import RunSettings, run
    from x3d_core.encodings.load import load
    from x3d_core.semantics.world import worlds
    folder = tempfile.mkdtemp(prefix="x3drbp-run-bench-")
    paths = {}
    for name, text in (("chain", chain_x3d()), ("boxes", boxes_x3d())):
        paths[name] = os.path.join(folder, f"{name}.x3d")
        with open(paths[name], "w") as f:
            f.write(text)
    settings = RunSettings(duration=args.duration, dt=DT, frame_rate=FRAME_RATE)
    print(f"{args.duration:g} s simulated, dt 1/240 s, state read at {FRAME_RATE} Hz; best of {args.repeat}\n")
    print("| scene | backend | native s | x3drbp run s | ratio | trace write s | peak MB native | peak MB x3drbp "
          "| max pos diff m |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|")
    differ = False
    for name in args.backends.split(","):
        backend = base.load(name)
        native = NATIVE[name]
        for scene, path in paths.items():
            def ours():
                return run(worlds(load(path)), backend, settings)

            def theirs():
                return native(scene, args.duration)
            t_native, native_positions = timed(theirs, args.repeat)
            t_ours, trace = timed(ours, args.repeat)
            # the same physics on both sides: the final positions agree
            diff = float(np.abs(final_positions(trace) - native_positions).max())
            differ |= not diff <= SAME
            out = os.path.join(folder, f"{scene}-{name}.csv")
            t_write = timed(lambda: trace.write(out), 1)[0]
            print(f"| {scene} | {name} {backend.version()} | {t_native:.3f} | {t_ours:.3f} | "
                  f"{t_ours / t_native:.2f}x | {t_write:.3f} | {peak_mb(theirs):.1f} | {peak_mb(ours):.1f} | "
                  f"{diff:.1e}{'' if diff <= SAME else ' (NOT the same)'} |", flush=True)
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())

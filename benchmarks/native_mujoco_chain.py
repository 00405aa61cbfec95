"""The hand-written MuJoCo script that benchmarks/run_process.py times against `x3drbp run`:
run_overhead.py's hinge chain built with MjSpec, stepped with mj_step, and every frame's
position, orientation (axis-angle), linear and angular velocity of each link written as the
CSV rows x3drbp writes. It imports numpy and mujoco only, as a MuJoCo user's script would
(run_overhead.py builds its chain with `chain_spec` too).

    python benchmarks/native_mujoco_chain.py OUT.csv DURATION [LINKS]
"""

import sys

import mujoco
import numpy as np

DT, FRAME_RATE = 1 / 240, 60
DIRECTION = np.array([np.sin(0.3), -np.cos(0.3), 0.0])  # the chain hangs 0.3 rad from the vertical
MASS, INERTIA = 1.0, [0.0104, 0.0104, 0.0017, 0, 0, 0]  # a 1 kg, 0.1 x 0.1 x 0.35 box about its centre


def options() -> mujoco.MjSpec:
    """A spec with run_overhead.py's settings: radians, the step, gravity along -y, 10 iterations, no contacts."""
    spec = mujoco.MjSpec()
    spec.compiler.degree = False
    spec.option.timestep = DT
    spec.option.gravity = [0, -9.81, 0]
    spec.option.iterations = 10
    spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT
    return spec


def chain_spec(links: int) -> mujoco.MjSpec:
    # ipos must be given with an explicit inertia: MjSpec leaves it undefined (NaN), and
    # mujoco 4.0 then compiles the centre of mass to the body's own pos (measured)
    spec = options()
    parent = spec.worldbody
    for k in range(links):
        body = parent.add_body(pos=DIRECTION * (0.35 if k else 0.175), ipos=[0, 0, 0])
        body.explicitinertial, body.mass, body.fullinertia = True, MASS, INERTIA
        body.add_joint(type=mujoco.mjtJoint.mjJNT_HINGE, pos=-0.175 * DIRECTION, axis=[0, 0, 1])
        parent = body
    return spec


def axis_angle(q: np.ndarray) -> np.ndarray:
    w, v = q[:, :1], q[:, 1:]
    v = np.where(w < 0, -v, v)
    s = np.linalg.norm(v, axis=1)
    angle = 2 * np.arctan2(s, np.abs(w[:, 0]))
    axis = np.divide(v, s[:, None], out=np.tile([0.0, 0.0, 1.0], (len(q), 1)), where=s[:, None] > 0)
    return np.hstack([axis, angle[:, None]])


def text(row: list[float]) -> str:
    return " ".join(repr(x)[:-2] if repr(x).endswith(".0") else repr(x) for x in row)


def main() -> None:
    out, duration = sys.argv[1], float(sys.argv[2])
    links = int(sys.argv[3]) if len(sys.argv) > 3 else 10
    m = chain_spec(links).compile()
    d = mujoco.MjData(m)
    names = [f"L{k}" for k in range(links)]
    lines = ["time,node,field,value"]
    velocity = np.zeros(6)
    steps = round(1 / (FRAME_RATE * DT))
    for frame in range(round(duration * FRAME_RATE) + 1):
        if frame:
            mujoco.mj_step(m, d, nstep=steps)
        mujoco.mj_kinematics(m, d)  # mj_step leaves the poses and velocities of its step's start
        mujoco.mj_comPos(m, d)
        mujoco.mj_comVel(m, d)
        t = text([frame / FRAME_RATE])
        linear, angular = [], []
        for body in range(1, links + 1):
            mujoco.mj_objectVelocity(m, d, mujoco.mjtObj.mjOBJ_BODY, body, velocity, 0)
            angular.append(velocity[:3].copy())
            linear.append(velocity[3:].copy())
        for field, rows in (("position", d.xpos[1:]), ("orientation", axis_angle(d.xquat[1:])),
                            ("linearVelocity", linear), ("angularVelocity", angular)):
            lines += [f"{t},{n},{field},{text(r)}" for n, r in zip(names, np.asarray(rows).tolist())]
    with open(out, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()

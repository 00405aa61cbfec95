"""One native run for benchmarks/engine_speed.py, as a process of its own: a scene built,
stepped and read every frame in one engine's own API, with no x3drbp code imported (the
native builds live in run_overhead.py, pile.py and car.py, whose x3drbp imports are in their
main only, and PhysX's and Drake's in native_physx.py and native_drake.py). It saves what
the build returns, the bodies' positions, to OUT.npy, and the CPU time of the build, steps
and reads (what `x3drbp run --timing` calls the simulation's, simulation_cpu_s) to OUT.json.

    python benchmarks/native_run.py ENGINE chain|car|pile DURATION OUT.npy OUT.json
"""

import importlib
import json
import sys
import time

import numpy as np

# the module each engine's run imports before its clock starts: the engine's own (or its native module's)
ENGINES = {"mujoco": "mujoco", "bullet": "pybullet", "dart": "dartpy", "ode": "backends.ode_lib",
           "physx": "native_physx", "drake": "native_drake"}
OWN_MODULE = ("physx", "drake")  # engines whose builds of all three scenes are in native_ENGINE.py
# the scenes each engine has a native build of
SCENES = {engine: ("chain", "car", "pile") for engine in ENGINES}
CHAIN_LINKS = 10
PILE_BOXES, PILE_LAYERS = 100, 4  # pile.py's 5 x 5 grid, 4 layers of boxes and no spheres


def sized() -> None:
    """run_overhead.py's chain and pile.py's pile set to engine_speed.py's sizes."""
    import pile
    import run_overhead
    run_overhead.LINKS = CHAIN_LINKS
    pile.SPHERES, pile.BOXES, pile.LAYERS = 0, PILE_BOXES, PILE_LAYERS


def build(engine: str, scene: str, duration: float) -> np.ndarray:
    """The bodies' positions: (n, 3) at the end for the chain, (frames, n, 3) for the others."""
    sized()
    if engine in OWN_MODULE:
        return importlib.import_module(f"native_{engine}").NATIVE[scene](duration)
    if scene == "chain":
        import run_overhead
        return run_overhead.NATIVE[engine]("chain", duration)
    if scene == "pile":
        import pile
        return pile.NATIVE[engine](duration)
    import car
    return car.NATIVE[engine](duration)


def main() -> None:
    engine, scene, duration, out, timing = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4], sys.argv[5]
    importlib.import_module(ENGINES[engine])  # the engine's import is no part of the simulation's time
    cpu = time.process_time()
    positions = build(engine, scene, duration)
    cpu = time.process_time() - cpu
    np.save(out, positions)
    with open(timing, "w", encoding="utf-8") as f:
        json.dump({"simulation_cpu_s": cpu}, f)


if __name__ == "__main__":
    main()

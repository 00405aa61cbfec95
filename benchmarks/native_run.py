"""One native run for benchmarks/engine_speed.py, as a process of its own: a scene built,
stepped and read every frame in one engine's own API, with no x3drbp code imported (the
native builds live in run_overhead.py, pile.py and car.py, whose x3drbp imports are in their
main only, and PhysX's, Drake's and pymunk's in native_physx.py, native_drake.py and
native_pymunk.py). It saves what the build returns, the bodies' positions, to OUT.npy, and the
CPU time of the build, steps and reads (what `x3drbp run --timing` calls the simulation's,
simulation_cpu_s) to OUT.json. SIZE, where given, is the chain's links or the pile's boxes
(default engine_speed.py's: 10 and 100).

    python benchmarks/native_run.py ENGINE chain|car|pile DURATION OUT.npy OUT.json [SIZE]
"""

import importlib
import json
import math
import sys
import time

import numpy as np

# the module each engine's run imports before its clock starts: the engine's own (or its native module's)
ENGINES = {"mujoco": "mujoco", "bullet": "pybullet", "dart": "dartpy", "ode": "backends.ode_lib",
           "physx": "native_physx", "drake": "native_drake", "pymunk": "native_pymunk"}
OWN_MODULE = ("physx", "drake", "pymunk")  # engines whose native builds are in native_ENGINE.py
# the scenes each engine has a native build of (pymunk is planar: the chain, in the xy plane, only)
SCENES = {**{engine: ("chain", "car", "pile") for engine in ENGINES}, "pymunk": ("chain",)}
CHAIN_LINKS = 10
PILE_BOXES = 100  # boxes and no spheres, on pile.py's 5 x 5 grid: 4 full layers


def sized(links: int = CHAIN_LINKS, boxes: int = PILE_BOXES) -> None:
    """run_overhead.py's chain and pile.py's pile set to these sizes (default engine_speed.py's):
    the pile's boxes fill its grid's layers from the bottom, the top one part full where need be."""
    import pile
    import run_overhead
    run_overhead.LINKS = links
    pile.SPHERES, pile.BOXES, pile.LAYERS = 0, boxes, math.ceil(boxes / pile.GRID ** 2)


def build(engine: str, scene: str, duration: float, size: int | None = None) -> np.ndarray:
    """The bodies' positions: (n, 3) at the end for the chain, (frames, n, 3) for the others;
    size: the chain's links or the pile's boxes."""
    sized(**({} if size is None else {"links" if scene == "chain" else "boxes": size}))
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
    size = int(sys.argv[6]) if len(sys.argv) > 6 else None
    importlib.import_module(ENGINES[engine])  # the engine's import is no part of the simulation's time
    cpu = time.process_time()
    positions = build(engine, scene, duration, size)
    cpu = time.process_time() - cpu
    np.save(out, positions)
    with open(timing, "w", encoding="utf-8") as f:
        json.dump({"simulation_cpu_s": cpu}, f)


if __name__ == "__main__":
    main()

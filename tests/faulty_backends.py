"""A child `x3drbp run` with deliberately faulty backends registered, for the tests that
prove a crashing, hanging, raising or blowing-up engine costs one verdict, not the suite.

Run as `python tests/faulty_backends.py -m x3drbp run ...` (what children.run_child
starts once sys.executable is a fake_child script calling this): backends named
faulty-KIND wrap the first installed real backend and fail as KIND says at t >= 0.1 s;
every other name loads as usual. Nothing of this is registered outside that child.
"""

from __future__ import annotations

import ctypes
import os
import signal
import sys
import time

import numpy as np

FAULTS = ("segv", "hang", "stuck", "gil", "raise", "nan", "huge")
FAULT_AT = 0.1  # seconds: the first frames run clean, so a blow-up has frames to keep


class _FaultySim:
    def __init__(self, sim, fault: str, dt: float):
        self._sim, self._fault, self._dt, self._steps = sim, fault, dt, 0

    def step(self, n: int = 1) -> None:
        self._sim.step(n)
        self._steps += n
        if self._steps * self._dt < FAULT_AT - 1e-9:
            return
        if self._fault == "segv":
            os.kill(os.getpid(), signal.SIGSEGV)
        elif self._fault == "hang":
            time.sleep(3600)
        elif self._fault == "stuck":  # as an engine's C loop: no Python runs, no signal handler either
            signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGALRM, signal.SIGINT})
            time.sleep(3600)
        elif self._fault == "gil":  # as pybullet's step of 100 overlapping boxes: C that holds the interpreter lock
            signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGALRM, signal.SIGINT})
            ctypes.PyDLL(None).sleep(3600)  # PyDLL keeps the lock through the call: no Python thread runs
        elif self._fault == "raise":
            raise RuntimeError("the engine refused to step")

    def state(self):
        s = self._sim.state()
        if self._fault in ("nan", "huge") and self._steps * self._dt >= FAULT_AT - 1e-9:
            s.angular_velocity[-1, 0] = np.nan if self._fault == "nan" else 1e157
        return s

    def __getattr__(self, name: str):
        return getattr(self._sim, name)


class _FaultyBackend:
    def __init__(self, real, fault: str):
        self._real, self._fault = real, fault
        self.name = f"faulty-{fault}"

    def build(self, world, dt: float) -> _FaultySim:
        return _FaultySim(self._real.build(world, dt), self._fault, dt)

    def __getattr__(self, name: str):  # support, table, version
        return getattr(self._real, name)


def _faulty(name: str) -> bool:
    return name.startswith("faulty-") and name[len("faulty-"):] in FAULTS


def register() -> None:
    """Make base.entry and base.load answer faulty-KIND names too."""
    from backends import base
    real_entry, real_load = base.entry, base.load

    def entry(name: str) -> str:
        return f"{__name__}:{name}" if _faulty(name) else real_entry(name)

    def load(name: str):
        if _faulty(name):
            real = next(b for b in base.available().values() if not isinstance(b, str))
            return _FaultyBackend(real, name[len("faulty-"):])
        return real_load(name)

    base.entry, base.load = entry, load


if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    argv = sys.argv[1:]
    if argv[:2] == ["-m", "x3drbp"]:
        argv = argv[2:]
    register()
    from x3drbp import main
    sys.exit(main(argv))

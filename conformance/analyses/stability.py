"""The stability suite: hard cases run per backend and per step size until they blow up or
the clock ends, each with a verdict and its drift figures.

A hard case is a scene of scenes/stability/ (its leading comment says what it stresses and
argues its bounds), how long to run it, and monitors: functions of the trace that measure a
quantity over the run and, where the quantity has a bound, the first frame past it. The
verdict of a (case, backend, dt) run is the earliest bound broken, named after its monitor
(energy grew past bound, joint drifted past bound, ...), else the case's verdict for a run
that held (survived; stopped for the impact). A run that did not finish keeps the child's
verdict from conformance.runner: blew up (with the time the evaluator or engine gave),
unsupported, crashed, timed out, error.

The bounds say what "stable" means physically, never what an engine happens to reach:
- energy of a conservative system released from rest: it may not rise above its start by
  more than 10% of the energy the motion exchanges (the potential energy of the fall the
  scene allows, stated in the scene): a pendulum swinging back a tenth of its fall higher than
  it was let go from shows energy a viewer sees made. Semi-implicit Euler, the scheme of these
  engines, keeps no exact energy for jointed bodies, but for a motion of angular rate w its
  energy error oscillates by about h w / 2 of the exchange (on a linear oscillator the energy
  it keeps exactly differs from E by h w^2 x v / 2), so the bound admits motions up to
  12 rad/s at h = 1/60 (48 rad/s at 1/240) without a trend; past it a run is too coarse for
  its fastest motion or gains energy step by step. Losses (error correction, softness, an
  iterative solver stopped short) are dissipation: reported, not judged;
- energy and world angular momentum of a torque-free body: exact constants, with no exchange
  to oscillate through: 1% of their start. A rotation update that turns L by the body's own
  rotation keeps L and bounds the error in E; one that takes the gyroscopic term w x I w at
  the start of the step amplifies any wobble by sqrt(1 + (W h)^2) a step (W its rate in the
  body) and drifts in both without bound: the instability these cases catch;
- joints: anchors 1 cm apart at most, a gap a viewer sees on links of 0.1-1 m, and ten times
  what error correction leaves in a converged joint at these rates (the conformance ball
  chain's dt^2 |w|^2 r / (2 ERP): under 1 mm for w = 10 rad/s, r = 5 cm, h = 1/60);
- a stack at rest: each watched box within 1 cm of where it started (5% of a 0.2 m box);
- the impact: the sphere's centre never past the wall's far face.
The monitors read masses, inertias and gravity from the scene through x3d_core, the model the
engines were given: a stability figure measures what an engine made of its own input.
"""

from __future__ import annotations

import contextlib
import math
import os
import re
import shutil
import tempfile
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import ClassVar, Protocol

import numpy as np

from x3d_core.files import atomic
from x3d_core.traces.trace import TraceView

from conformance import results
from conformance.runner import cache, children, verdicts
from conformance.cases import ROOT
from conformance.results import Settings
from conformance.analyses import energy
from conformance.analyses.motion import Model, Motion, first_past, model

SCENES = os.path.join(ROOT, "scenes", "stability")
DEFAULT_DTS = (1 / 60, 1 / 240)
DEFAULT_TIMEOUT = children.DEFAULT_TIMEOUT

TRACES = "traces"  # the folder, under the output folder, of the traces the results cite

SURVIVED, STOPPED = "survived", "stopped"
ENERGY, MOMENTUM, JOINT, DRIFT, TUNNELLED = ("energy grew past bound", "momentum drifted past bound",
                                             "joint drifted past bound", "drifted past bound", "tunnelled")
HELD = (SURVIVED, STOPPED)


# -- what a run measures ----------------------------------------------------------------

@dataclass(frozen=True)
class Figure:
    """One quantity over a run: its worst value, the bound it is held to (None: reported
    only), the first frame time past the bound (None: it held), and where the worst was
    (the joint, for a gap over several)."""
    quantity: str
    value: float
    unit: str = ""
    bound: float | None = None
    at: float | None = None
    where: str = ""

    def __post_init__(self) -> None:  # plain floats (numpy scalars do not go to JSON)
        object.__setattr__(self, "value", float(self.value))

    def to_json(self) -> dict:
        return {"quantity": self.quantity, "value": _json_float(self.value), "unit": self.unit,
                "bound": self.bound, "at": self.at, "where": self.where}


def _json_float(x: float) -> float | str:
    return x if math.isfinite(x) else str(x)


def _worst(x: np.ndarray) -> float:
    """The largest value, inf where any is not finite (a run that overflowed)."""
    x = np.asarray(x, dtype=np.float64)
    return float(np.max(x)) if np.all(np.isfinite(x)) else math.inf


class Monitor(Protocol):
    verdict: str  # the verdict of a run that breaks this monitor's bound

    def read(self, view: TraceView, m: Model) -> list[Figure]: ...


@dataclass(frozen=True)
class EnergyGain:
    """Total energy's rise above its start, as a fraction of `scale` J (None: of the start
    itself, for a system whose energy is all kinetic). Its largest fall is reported."""
    scale: float | None = None
    bound: float = 0.10
    bodies: tuple[str, ...] = ()
    verdict: ClassVar[str] = ENERGY

    def read(self, view: TraceView, m: Model) -> list[Figure]:
        motion = Motion.read(view, m, m.rows(self.bodies))
        with np.errstate(over="ignore", invalid="ignore"):
            e = motion.energy(m.gravity)
            scale = self.scale if self.scale is not None else abs(float(e[0]))
            change = (e - e[0]) / scale
        of = f"E0 = {scale:.4g} J" if self.scale is None else f"{scale:.4g} J exchanged"
        return [Figure(f"energy gain over {of}", 100 * _worst(change), "%", 100 * self.bound,
                       first_past(motion.t, change, self.bound)),
                Figure(f"energy loss over {of}", 100 * _worst(-change), "%")]


@dataclass(frozen=True)
class MomentumDrift:
    """|L(t) - L(0)| of the world angular momentum, as a fraction of |L(0)| (torque-free)."""
    bound: float = 0.01
    bodies: tuple[str, ...] = ()
    verdict: ClassVar[str] = MOMENTUM

    def read(self, view: TraceView, m: Model) -> list[Figure]:
        motion = Motion.read(view, m, m.rows(self.bodies))
        with np.errstate(over="ignore", invalid="ignore"):
            big_l = motion.angular_momentum()
            drift = np.linalg.norm(big_l - big_l[0], axis=1) / np.linalg.norm(big_l[0])
        return [Figure(f"angular momentum drift over |L0| = {np.linalg.norm(big_l[0]):.4g} kg m^2/s",
                       100 * _worst(drift), "%", 100 * self.bound,
                       first_past(motion.t, drift, self.bound))]


@dataclass(frozen=True)
class AnchorGap:
    """|body1AnchorPoint - body2AnchorPoint| of each joint (x3d_core's joint outputs, asked
    for by the scene's forceOutput), the worst joint named."""
    joints: tuple[str, ...]
    bound: float = 0.01
    verdict: ClassVar[str] = JOINT

    def read(self, view: TraceView, m: Model) -> list[Figure]:
        with np.errstate(over="ignore", invalid="ignore"):
            gaps = np.stack([np.linalg.norm(view.series(j, "body1AnchorPoint")[1]
                                            - view.series(j, "body2AnchorPoint")[1], axis=1) for j in self.joints],
                            axis=1)
        t = view.series(self.joints[0], "body1AnchorPoint")[0]
        finite = np.where(np.isfinite(gaps), gaps, math.inf)
        worst = self.joints[int(np.argmax(np.max(finite, axis=0)))]
        per_frame = np.max(finite, axis=1)
        return [Figure("anchor gap", _worst(per_frame), "m", self.bound,
                       first_past(t, per_frame, self.bound), worst)]


@dataclass(frozen=True)
class Displacement:
    """A body's distance from where it started; the largest is judged, the last reported."""
    body: str
    bound: float = 0.01
    verdict: ClassVar[str] = DRIFT

    def read(self, view: TraceView, m: Model) -> list[Figure]:
        t, p = view.series(self.body, "position")
        with np.errstate(over="ignore", invalid="ignore"):
            d = np.linalg.norm(p - p[0], axis=1)
        return [Figure(f"{self.body} displacement (max)", _worst(d), "m", self.bound, first_past(t, d, self.bound)),
                Figure(f"{self.body} displacement at the end", float(d[-1]), "m")]


@dataclass(frozen=True)
class Tunnelling:
    """A body's centre along +x against a wall's far face: ever beyond it, the body went through."""
    body: str
    far_face: float
    verdict: ClassVar[str] = TUNNELLED

    def read(self, view: TraceView, m: Model) -> list[Figure]:
        t, p = view.series(self.body, "position")
        return [Figure(f"{self.body} furthest centre x", _worst(p[:, 0]), "m", self.far_face,
                       first_past(t, p[:, 0], self.far_face))]


# -- the cases ----------------------------------------------------------------------------

@dataclass(frozen=True)
class HardCase:
    name: str
    scene: str  # file name under scenes/stability
    stresses: str  # one line: what is hard about it
    duration: float  # simulated seconds
    monitors: tuple[Monitor, ...]
    held: str = SURVIVED  # the verdict of a run that keeps every bound

    @property
    def path(self) -> str:
        return self.scene if os.path.isabs(self.scene) else os.path.join(SCENES, self.scene)


def _chain(n: int) -> tuple[str, ...]:
    return tuple(f"Joint{k}" for k in range(1, n + 1))


# energies the motion exchanges (J), as the scenes' comments derive them: g = 9.8
CHAIN_EXCHANGE = 50 * 0.1 * 9.8 * 5.0 / 2  # M g L / 2: a 5 m, 5 kg chain from horizontal to hanging
PENDULUM_EXCHANGE = 9.8 * (100.0 * 1.1 + 0.1 * 0.5)  # the bob's centre falls 1.1 m, the arm's 0.5 m
FOUR_BAR_EXCHANGE = 2.118  # from the crank upright to the lowest configuration, over the crank angle

CASES: tuple[HardCase, ...] = (
    HardCase("ball_chain_50", "ball_chain_50.x3d",
             "50 ball-joint links (5 m) released from horizontal: the free end whips through the bottom",
             5.0, (EnergyGain(CHAIN_EXCHANGE), AnchorGap(_chain(50)))),
    HardCase("mass_ratio_pendulum", "mass_ratio_pendulum.x3d",
             "a 0.1 kg arm carrying a 100 kg bob (1:1000 across a joint), released from horizontal",
             10.0, (EnergyGain(PENDULUM_EXCHANGE), AnchorGap(("Shoulder", "Wrist")))),
    HardCase("mass_ratio_stack", "mass_ratio_stack.x3d",
             "a 1000 kg box resting on a 1 kg slab on the floor (1:1000 in a stack)",
             10.0, (Displacement("Heavy"), Displacement("Light"))),
    HardCase("box_stack_10", "box_stack_10.x3d", "ten 1 kg boxes stacked at rest on the floor",
             10.0, (Displacement("Box10"),)),
    HardCase("spinning_wheel_finite", "spinning_wheels.x3d",
             "a free wheel at 150 rad/s with a 2 rad/s wobble, useFiniteRotation TRUE",
             5.0, (EnergyGain(None, 0.01, ("FiniteWheel",)), MomentumDrift(0.01, ("FiniteWheel",)))),
    HardCase("spinning_wheel_plain", "spinning_wheels.x3d",
             "the same wheel with useFiniteRotation FALSE (ODE's infinitesimal rotation update)",
             5.0, (EnergyGain(None, 0.01, ("PlainWheel",)), MomentumDrift(0.01, ("PlainWheel",)))),
    HardCase("intermediate_axis_tumble", "intermediate_axis_tumble.x3d",
             "a 0.1 x 0.4 x 0.9 m box spun about its intermediate axis for 30 s: it flips every few seconds",
             30.0, (EnergyGain(None, 0.01), MomentumDrift(0.01))),
    HardCase("thin_wall_impact", "thin_wall_impact.x3d",
             "a 2 cm sphere at 80 m/s against a static wall 4 cm thick (tunnelling)",
             0.25, (Tunnelling("Pellet", 0.02), EnergyGain(None, 0.01)), held=STOPPED),
    HardCase("four_bar_linkage", "four_bar_linkage.x3d",
             "a four-bar linkage (a closed loop of pins) falling under gravity: loop closure",
             10.0, (EnergyGain(FOUR_BAR_EXCHANGE), AnchorGap(("PinA", "PinB", "PinD", "PinC")))),
)
BY_NAME = {c.name: c for c in CASES}


def select(names: Sequence[str]) -> list[HardCase]:
    unknown = [n for n in names if n not in BY_NAME]
    if unknown:
        raise KeyError(f"unknown case(s) {', '.join(unknown)}; known: {', '.join(BY_NAME)}")
    return [BY_NAME[n] for n in names] if names else list(CASES)


# -- verdicts -------------------------------------------------------------------------------

@dataclass
class StabilityResult:
    case: str
    backend: str
    dt: float
    verdict: str
    at: float | None = None  # when the run broke a bound or blew up
    reason: str = ""
    figures: list[Figure] = field(default_factory=list)
    wall_s: float = 0.0
    trace: str | None = None  # the run's trace, kept: its path relative to the output folder (run_one)
    energy: results.EnergyGrowth | None = None  # its energy grew with nothing doing work (energy.growth)

    def to_json(self) -> dict:
        return {"case": self.case, "backend": self.backend, "dt": self.dt, "verdict": self.verdict, "at": self.at,
                "reason": self.reason, "wall_s": round(self.wall_s, 3), "figures": [f.to_json() for f in self.figures],
                "trace": self.trace, "energy_growth": self.energy.to_json() if self.energy else None}


def judge(case: HardCase, view: TraceView, m: Model) -> tuple[str, float | None, str, list[Figure]]:
    """(verdict, when, why, figures) of a finished run: the earliest bound broken wins."""
    figures: list[Figure] = []
    broken: list[tuple[float, str, Figure]] = []
    for mon in case.monitors:
        for f in mon.read(view, m):
            figures.append(f)
            if f.at is not None:
                broken.append((f.at, mon.verdict, f))
    if not broken:
        return case.held, None, "", figures
    at, verdict, f = min(broken, key=lambda b: b[0])
    unit = f" {f.unit}" if f.unit and f.unit != "%" else f.unit
    where = f" at {f.where}" if f.where else ""
    return verdict, at, f"{f.quantity}{where} past {f.bound:g}{unit} at t = {at:.3g} s (worst {f.value:.3g}{unit})", \
        figures


_BLEW_UP_AT = re.compile(r"blew up (?:at|by) t=([-+0-9.eE]+)")


def trace_name(case: str, backend: str, dt: float) -> str:
    """Where run_one keeps a run's trace, relative to the output folder: traces/CASE-BACKEND-DT.csv
    (the step as dt_label writes it, '/' as '_')."""
    return f"{TRACES}/{case}-{backend}-{results.dt_label(dt).replace('/', '_')}.csv"


def _keep(trace: str, out: str, name: str, wanted: bool) -> str | None:
    """The trace copied whole to out/NAME where wanted and the run left one: NAME, else None.
    A trace an earlier run left under NAME is removed, so that the folder holds only the
    traces the results cite."""
    dest = os.path.join(out, name)
    if wanted and os.path.exists(trace):
        os.makedirs(os.path.dirname(dest), exist_ok=True)
        with atomic.replacing(dest) as part:
            shutil.copyfile(trace, part)
        return name
    with contextlib.suppress(FileNotFoundError):
        os.unlink(dest)
    return None


def _judged(case: HardCase, backend: str, dt: float, out: children.Outcome, path: str) -> StabilityResult:
    """The verdict, as the case judges it, of the child's run that ended so (`out`), its trace at path."""
    def result(verdict: str, reason: str = "", at: float | None = None,
               figures: list[Figure] | None = None) -> StabilityResult:
        return StabilityResult(case.name, backend, dt, verdict, at, reason, figures or [])

    if out.verdict == results.BLEW_UP:
        # the reason less the child's "SCENE: BACKEND: " and where it wrote the frames before (a
        # temporary file: the result names the trace where it is kept)
        reason = out.reason.replace(f" (the frames before it written to {path})", "")
        hit = _BLEW_UP_AT.search(reason)
        return result(results.BLEW_UP, reason[hit.start():] if hit else reason, float(hit.group(1)) if hit else None)
    if out.verdict is not None:
        return result(out.verdict, out.reason)
    try:
        view = cache.read_view(path)  # a CSV read again each report: its view kept
    except (OSError, ValueError) as e:
        return result(results.ERROR, f"unreadable trace: {e}")
    try:
        verdict, at, reason, figures = judge(case, view, model(case.path))
        bodies = energy.model_at(case.path)
        grew = energy.growth(view, bodies) if bodies is not None else None
    except (KeyError, ValueError, IndexError) as e:
        msg = e.args[0] if isinstance(e, KeyError) and e.args else str(e)
        return result(results.ERROR, f"the monitors could not read the trace: {msg}")
    judged = result(verdict, reason, at, figures)
    judged.energy = grew
    return judged


def run_one(case: HardCase, backend: str, dt: float, timeout: float = DEFAULT_TIMEOUT,
            out: str | None = None) -> StabilityResult:
    """One (case, backend, dt) in a child process (children.run_child), judged here. With `out`
    (the output folder), the trace of a run that did not hold is kept there (trace_name) and
    the result names it: the table's reasons link the frames they speak of."""
    return run_shared((case,), backend, dt, timeout, out)[0]


def run_shared(group: Sequence[HardCase], backend: str, dt: float, timeout: float = DEFAULT_TIMEOUT,
               out: str | None = None) -> list[StabilityResult]:
    """run_one for cases of one scene and duration (the same run): the scene run once on the
    backend at dt, and judged as each case judges it, each keeping its own trace (`out`)."""
    started = time.perf_counter()
    first = group[0]
    if not os.path.exists(first.path):
        return [StabilityResult(c.name, backend, dt, results.ERROR, reason=f"no scene file {c.path}",
                                wall_s=time.perf_counter() - started) for c in group]
    with tempfile.TemporaryDirectory(prefix="x3drbp-stab-") as tmp:
        path = os.path.join(tmp, "trace.csv")
        ran = children.run_child(first.path, backend, Settings(first.duration, dt), path, timeout)
        judged = [_judged(c, backend, dt, ran, path) for c in group]
        if out is not None:
            for r in judged:
                r.trace = _keep(path, out, trace_name(r.case, backend, dt), r.verdict not in HELD)
    for r in judged:
        r.wall_s = time.perf_counter() - started
    return judged


def run_suite(cases: Sequence[HardCase], backends: Sequence[str], dts: Sequence[float],
              timeout: float = DEFAULT_TIMEOUT, workers: int | None = None, out: str | None = None,
              progress: bool = False) -> list[StabilityResult]:
    """Every case on every backend at every dt, in parallel (`out` and `progress` as run_one
    and verdicts.run_many take them); results case-, then dt-, then backend-major. Cases of one
    scene and duration share its runs (run_shared: the two spinning-wheel cases watch two wheels
    of one scene, and ran it twice, 44 s of Drake's runs); the runs start finest step first, in
    the cases' order (the 50-link chain first): a step's runs do more steps than a coarser one's,
    and a long run started last leaves a core idle at the end (measured: the suite's runs packed
    onto two workers in 131 s where the cases' order took 137 s)."""
    groups: dict[tuple[str, float], list[HardCase]] = {}
    for c in cases:
        groups.setdefault((c.path, c.duration), []).append(c)
    runs = [(g, b, dt) for dt in sorted(dts) for g in groups.values() for b in backends]
    done = verdicts.run_many([lambda g=g, b=b, dt=dt: run_shared(g, b, dt, timeout, out) for g, b, dt in runs],
                             workers, progress)
    found = {(r.case, r.backend, r.dt): r for judged in done for r in judged}
    return [found[(c.name, b, dt)] for c in cases for dt in dts for b in backends]

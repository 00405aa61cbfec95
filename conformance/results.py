"""The results of x3drbp's runs and analyses, as plain data: what reports/ reads.

Verdicts, the run settings and measures of conformance cases, a case's result and its
convergence study, the backends found, comparisons of runs, and validations of another
implementation's traces. Each type turns to JSON (to_json) and, where a report reads it
back from a file, from JSON. Nothing here runs anything.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from x3d_core.model import schema
from x3d_core.traces.trace import TraceView

def dt_label(dt: float) -> str:
    """A step as people write it: 1/240, else its %g."""
    inv = 1.0 / dt
    return f"1/{round(inv)}" if abs(inv - round(inv)) < 1e-6 * inv else f"{dt:g}"



# -- conformance verdicts ----------------------------------------------------------------

# pass: conforms; conventions: conforms to the clause, but differs from x3drbp's reading where
# the spec is silent, or from a description outside the clause (only convention or description
# measures fail); fail: violates the spec (a measure quoting clause 37 fails). Accuracy measures
# never change a verdict: they are graded apart (Result.accuracy).
PASS, CONVENTIONS, FAIL, UNSUPPORTED, CRASHED, TIMED_OUT, BLEW_UP, ERROR = (
    "pass", "conventions", "fail", "unsupported", "crashed", "timed out", "blew up", "error")
VERDICTS = (PASS, CONVENTIONS, FAIL, UNSUPPORTED, CRASHED, TIMED_OUT, BLEW_UP, ERROR)
JUDGED = (PASS, CONVENTIONS, FAIL)  # the verdicts of a run the expectation measured
# what each judged verdict says, in full, where a verdict is shown to people
MEANING = {PASS: "conforms", CONVENTIONS: "conforms, differs in conventions", FAIL: "violates the spec"}
SPEC, CONVENTION, DESCRIPTION, ACCURACY = "spec", "convention", "description", "accuracy"
KINDS = (SPEC, CONVENTION, DESCRIPTION, ACCURACY)
# the edition of ISO/IEC 19775-1 every SPEC basis quotes: the clause 37 text this project judges
# by (../shared/reference/clause37-rigid-body-physics.txt), a V3 edition from before V3.3 (units
# in words, "metres per second", where V3.3 writes "base units"); and the sources of a DESCRIPTION
EDITION = "V3 pre-3.3"
SOURCES = ("X3DUOM 4.0", "X3D tooltips")


@dataclass(frozen=True)
class Basis:
    """Why a measure holds an implementation to its tolerance.

    SPEC: `text` is "37.x.y Name: " (the subclause as the clause's text numbers and names it) and
    then whole sentences of that subclause, verbatim and uncut, of the edition `source` names
    (EDITION); the tolerance is one any consistent integrator and solver meets at the scene's own
    settings, so a failure is a violation.
    CONVENTION: the clause is silent or ambiguous; `text` names the reading checked (ODE's, as
    a rule) and the alternatives real implementations take, none of them wrong.
    DESCRIPTION: `text` quotes a description from outside the clause (`source`: the X3D Unified
    Object Model or the tooltips): a weaker basis, failing it is not a violation.
    ACCURACY: `text` names the closed form or invariant and how the bound follows from the step
    and the integrator's order; the error is graded against the bound, never a violation.

    A SPEC basis's `also` holds further quotes of the same form, from other subclauses (or other
    sentences of its own that do not join its text), which the same measure enforces with the same
    tolerance: a mass in kilograms by the force it turns into an acceleration, say. Each is held
    to the text as `text` is (tests/test_spec_quotes.py), and each counts as checked
    (docs/clause-coverage.md)."""
    kind: str
    text: str
    source: str = ""
    also: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.kind not in KINDS or not self.text.strip():
            raise ValueError(f"a basis is one of {', '.join(KINDS)} with its text, not {self.kind!r}: {self.text!r}")
        if self.kind == SPEC and self.source != EDITION:
            raise ValueError(f"a spec basis names its edition ({EDITION}), not {self.source!r}")
        if self.kind == DESCRIPTION and self.source not in SOURCES:
            raise ValueError(f"a description names its source ({', '.join(SOURCES)}), not {self.source!r}")
        if self.also and self.kind != SPEC:
            raise ValueError(f"only a spec basis quotes the clause further, not a {self.kind}")
        for quote in self.quotes:
            if "..." in quote or "\u2026" in quote:
                raise ValueError(f"a spec basis quotes whole sentences, uncut: {quote!r}")

    @property
    def quotes(self) -> tuple[str, ...]:
        """Every quote of the clause the measure is held to: a SPEC basis's text, then `also`."""
        return (self.text, *self.also) if self.kind == SPEC else ()

    def label(self) -> str:
        """The kind as a reader needs it: 'spec (V3 pre-3.3)', 'description (X3DUOM 4.0)', 'convention'."""
        return f"{self.kind} ({self.source})" if self.source else self.kind


def spec(quote: str, edition: str = EDITION, *, also: tuple[str, ...] = ()) -> Basis:
    return Basis(SPEC, quote, edition, tuple(also))


def also(basis: Basis, *quotes: str) -> Basis:
    """The same spec basis, holding its measure to further sentences the measure enforces too."""
    return replace(basis, also=(*basis.also, *quotes))


def convention(reading: str) -> Basis:
    return Basis(CONVENTION, reading)


def description(quote: str, source: str = "X3DUOM 4.0") -> Basis:
    return Basis(DESCRIPTION, quote, source)


def accuracy(argument: str) -> Basis:
    return Basis(ACCURACY, argument)


def grade(ratio: float) -> str:
    """An accuracy grade in words: 'within the bound', '3.1x the bound'."""
    if ratio <= 1:
        return "within the bound"
    return "no finite error" if not math.isfinite(ratio) else f"{ratio:.2g}x the bound"


@dataclass(frozen=True)
class Settings:
    """One run: simulated seconds, physics step, frames per second (None: a frame after
    every step, for expectations that must see every state)."""
    duration: float
    dt: float
    frame_rate: float | None = 60.0

    @property
    def rate(self) -> float:
        return 1.0 / self.dt if self.frame_rate is None else self.frame_rate

    def with_dt(self, dt: float) -> Settings:
        return Settings(self.duration, dt, self.frame_rate)

    def args(self) -> list[str]:
        """The `x3drbp run` options (repr keeps every digit of the step)."""
        return ["--duration", repr(self.duration), "--dt", repr(self.dt), "--frame-rate", repr(self.rate)]


@dataclass(frozen=True)
class Measure:
    """One measured error and the tolerance it is held to (same unit). `bound`, where given, is
    the accuracy bound the same error is graded against (from the step and the integrator's
    order): tighter than a spec tolerance, which allows any consistent integrator and solver at
    the scene's settings. An ACCURACY measure's tolerance is its bound."""
    quantity: str
    error: float
    tolerance: float
    unit: str = ""
    basis: Basis | None = None  # None: not stated yet, held as the spec
    bound: float | None = None

    def __post_init__(self) -> None:  # plain floats (numpy scalars do not go to JSON)
        object.__setattr__(self, "error", float(self.error))
        object.__setattr__(self, "tolerance", float(self.tolerance))
        if self.bound is not None:
            object.__setattr__(self, "bound", float(self.bound))

    @property
    def ok(self) -> bool:
        return bool(math.isfinite(self.error) and self.error <= self.tolerance)

    @property
    def ratio(self) -> float:
        return _ratio(self.error, self.tolerance)

    @property
    def accuracy(self) -> float | None:
        """The error over its accuracy bound (None: the measure grades no accuracy)."""
        if self.kind == ACCURACY:
            return self.ratio
        return None if self.bound is None else _ratio(self.error, self.bound)

    def figure(self) -> str:
        """'error E > tolerance T' with the unit: how a failing measure is reported."""
        unit = f" {self.unit}" if self.unit else ""
        return f"error {self.error:.3g}{unit} > tolerance {self.tolerance:.3g}{unit}"

    @property
    def kind(self) -> str:
        """SPEC, CONVENTION, DESCRIPTION or ACCURACY (a measure with no basis is held as the spec)."""
        return SPEC if self.basis is None else self.basis.kind

    @property
    def convention(self) -> bool:
        """The measure checks a reading of a point the clause leaves open, or a description
        outside it: failing it leaves the implementation conforming."""
        return self.kind in (CONVENTION, DESCRIPTION)

    @property
    def graded(self) -> bool:
        """The measure only grades accuracy: it never changes a verdict."""
        return self.kind == ACCURACY

    @property
    def fails(self) -> bool:
        """The measure is judged (not only graded) and its error is beyond its tolerance."""
        return not self.graded and not self.ok

    def to_json(self) -> dict:
        return {"quantity": self.quantity, "error": _finite_or_str(self.error),
                "tolerance": _finite_or_str(self.tolerance), "unit": self.unit, "ok": self.ok,
                "basis": None if self.basis is None else self.basis.kind,
                "basis_source": None if self.basis is None else self.basis.source,
                "basis_text": None if self.basis is None else self.basis.text,
                "basis_also": [] if self.basis is None else list(self.basis.also),
                "bound": None if self.bound is None else _finite_or_str(self.bound),
                "accuracy": None if self.accuracy is None else _finite_or_str(self.accuracy)}


@dataclass
class Result:
    case: str
    backend: str
    verdict: str
    reason: str = ""  # why it is not a pass: failing measures, the declared reason, the error
    measures: list[Measure] = field(default_factory=list)
    wall_s: float = 0.0
    dt: float | None = None  # the step of the (first) run

    def measure(self, quantity: str) -> Measure | None:
        return next((m for m in self.measures if m.quantity == quantity), None)

    def to_json(self) -> dict:
        acc = self.accuracy()
        return {"case": self.case, "backend": self.backend, "verdict": self.verdict, "reason": self.reason,
                "dt": self.dt, "wall_s": round(self.wall_s, 3), "meaning": self.meaning(),
                "accuracy": None if acc is None else _finite_or_str(acc),
                "measures": [m.to_json() for m in self.measures]}

    def failing(self, kind: str | None = None) -> list[Measure]:
        """The judged measures beyond tolerance (accuracy measures are graded, not failed); of
        one kind: SPEC, or CONVENTION (conventions and descriptions both)."""
        return [m for m in self.measures if m.fails and (kind is None or m.convention == (kind == CONVENTION))]

    def graded(self) -> list[Measure]:
        """The measures that grade accuracy (accuracy measures, and judged ones with a bound)."""
        return [m for m in self.measures if m.accuracy is not None]

    def _worst_graded(self) -> Measure | None:
        """The graded measure furthest beyond its bound (None: none graded, or not judged)."""
        worst = max(self.graded(), key=lambda m: m.accuracy, default=None)
        return worst if self.verdict in JUDGED else None

    def accuracy(self) -> float | None:
        """The worst graded error over its bound (None: the case grades none, or the run was
        not judged)."""
        worst = self._worst_graded()
        return None if worst is None else worst.accuracy

    def over_bound(self) -> list[Measure]:
        """The graded measures beyond their accuracy bound."""
        return [m for m in self.graded() if not m.accuracy <= 1]

    def accuracy_text(self) -> str:
        """'accuracy within the bound' or 'accuracy 3.1x the bound (QUANTITY)'; '' where none is graded."""
        worst = self._worst_graded()
        if worst is None:
            return ""
        return "accuracy " + grade(worst.accuracy) + ("" if worst.accuracy <= 1 else f" ({worst.quantity})")

    def meaning(self) -> str:
        """The verdict as people read it: conforms / conforms, differs in conventions: the
        readings / violates the spec: measure, quote, figure; then the accuracy grade."""
        if self.verdict not in JUDGED:
            return self.verdict + (f": {self.reason}" if self.reason else "")
        if self.verdict == PASS:
            said = MEANING[PASS]
        elif self.verdict == CONVENTIONS:
            said = f"{MEANING[CONVENTIONS]}: " + "; ".join(
                f"{m.quantity} ({m.basis.label()}: {m.basis.text}): {m.figure()}" for m in self.failing(CONVENTION))
        else:
            said = f"{MEANING[FAIL]}: " + "; ".join(
                f"{m.quantity}" + (f" ({m.basis.source}, \"{m.basis.text}\")" if m.basis else "") + f": {m.figure()}"
                for m in self.failing(SPEC))
        graded = self.accuracy_text()
        return f"{said}; {graded}" if graded else said


def judge(measures: Sequence[Measure]) -> str:
    """PASS when every judged measure holds; CONVENTIONS when only convention or description
    measures fail; else FAIL. Accuracy measures do not count."""
    failing = [m for m in measures if m.fails]
    if not failing:
        return PASS
    return CONVENTIONS if all(m.convention for m in failing) else FAIL


def _ratio(error: float, limit: float) -> float:
    if not math.isfinite(error):
        return math.inf
    return error / limit if limit > 0 else (0.0 if error == 0 else math.inf)


def _finite_or_str(x: float) -> float | str:
    return x if math.isfinite(x) else str(x)


@dataclass
class Convergence:
    case: str
    backend: str
    quantity: str
    dts: list[float]
    results: list[Result]  # one per dt
    expected_order: float | None = None

    def errors(self) -> list[float | None]:
        out = []
        for r in self.results:
            m = r.measure(self.quantity)
            out.append(m.error if m is not None and r.verdict in JUDGED else None)
        return out

    def order(self) -> float | None:
        return fitted_order(self.dts, self.errors())

    def to_json(self) -> dict:
        return {"case": self.case, "backend": self.backend, "quantity": self.quantity,
                "expected_order": self.expected_order,
                "points": [{"dt": dt, "error": (None if e is None else _finite_or_str(e)), "verdict": r.verdict,
                            "reason": r.reason if r.verdict not in JUDGED else ""}
                           for dt, e, r in zip(self.dts, self.errors(), self.results)],
                "order": self.order()}


# errors below this are rounding: they carry no order (a scheme exact for the case)
ORDER_FLOOR = 1e-11


def fitted_order(dts: Sequence[float], errors: Sequence[float | None]) -> float | None:
    """Least-squares slope of log(error) against log(dt) over the finite errors above
    ORDER_FLOOR; None with fewer than two such points (exact to rounding, or no data)."""
    pts = [(math.log(dt), math.log(e)) for dt, e in zip(dts, errors)
           if e is not None and math.isfinite(e) and e > ORDER_FLOOR]
    if len(pts) < 2:
        return None
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    sxx = sum((x - mx) ** 2 for x, _ in pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sxx if sxx > 0 else None


@dataclass
class BackendInfo:
    name: str
    version: str | None = None
    unavailable: str | None = None  # why it cannot be used here
    integration: str | None = None  # backends.base.Backend.integration
    accurate_integration: str | None = None  # ... and where preferAccuracy is TRUE, if it differs
    scope: str | None = None  # backends.base.Backend.scope: the scenes it takes, where not every one

    def integration_for(self, prefer_accuracy: bool) -> str | None:
        """The scheme a run of a scene steps by: the accurate one where a collection prefers accuracy."""
        return self.accurate_integration if prefer_accuracy and self.accurate_integration else self.integration

    @property
    def usable(self) -> bool:
        return self.unavailable is None


@dataclass(frozen=True)
class Expected:
    """A verdict pinned for one (case, backend): conformance/expectations says how."""
    verdict: str
    failing: tuple[str, ...] = ()  # fail: the measures beyond tolerance, sorted
    reason: str = ""  # unsupported: the backend's reason
    why: str = ""  # a person's word on it
    # pass, conventions, fail: the measures graded beyond their accuracy bound, sorted
    over_bound: tuple[str, ...] = ()


# -- comparisons of runs -----------------------------------------------------------------

POSITION, ORIENTATION = "position", "orientation"
# the body outputs compared besides the pose: every RigidBody output a backend's run records
# (x3d_core.semantics.evaluator), so every one a trace can share with it
LINEAR_VELOCITY, ANGULAR_VELOCITY = "linearVelocity", "angularVelocity"
VELOCITIES = (LINEAR_VELOCITY, ANGULAR_VELOCITY)
UNITS = {POSITION: "m", ORIENTATION: "rad", LINEAR_VELOCITY: "m/s", ANGULAR_VELOCITY: "rad/s"}  # of each kind
RAN = "ran"  # a backend's verdict when it wrote its trace (else one of VERDICTS)
_SI = {"length": "m", "speed": "m/s", "angle": "rad", "angular_rate": "rad/s", None: "1"}


def _joint_outputs() -> dict[str, str]:
    """Every joint output field (of any joint type) and its SI unit, from the node definitions."""
    out = {}
    for t in schema.NODE_TYPES.values():
        if not t.abstract and t.is_a("X3DRigidJointNode"):
            out.update({f.name: _SI[f.unit] for f in t.fields.values() if f.access == "outputOnly"})
    return out


JOINT_OUTPUTS = _joint_outputs()


def _floats(a: np.ndarray) -> list[float]:
    return [float(x) for x in np.asarray(a).tolist()]


@dataclass
class Crossing:
    """The first frame at which a body's divergence passed the threshold."""
    time: float
    bodies: list[str]  # every body over the threshold at that frame, the worst first
    values: list[float]  # their divergences

    def to_json(self) -> dict:
        return {"time": self.time, "bodies": [{"body": b, "value": v} for b, v in zip(self.bodies, self.values)]}

    @classmethod
    def from_json(cls, d: dict) -> Crossing:
        return cls(d["time"], [x["body"] for x in d["bodies"]], [x["value"] for x in d["bodies"]])


@dataclass
class Divergence:
    """One quantity of the bodies (a kind of UNITS: position, orientation, a velocity) between
    two runs. The series are per frame (the pair's times) and per body (the pair's bodies);
    the scalars are None when the runs share no body or no frame."""
    quantity: str
    unit: str
    threshold: float
    rms: float | None = None  # over every frame and body
    max: float | None = None
    max_time: float | None = None
    max_body: str | None = None
    first_over: Crossing | None = None
    frame_rms: np.ndarray = field(default_factory=lambda: np.empty(0))  # over bodies
    frame_max: np.ndarray = field(default_factory=lambda: np.empty(0))
    body_rms: np.ndarray = field(default_factory=lambda: np.empty(0))  # over frames
    body_max: np.ndarray = field(default_factory=lambda: np.empty(0))

    def to_json(self) -> dict:
        return {"quantity": self.quantity, "unit": self.unit, "threshold": self.threshold,
                "rms": self.rms, "max": self.max, "max_time": self.max_time, "max_body": self.max_body,
                "first_over": None if self.first_over is None else self.first_over.to_json(),
                "frame_rms": _floats(self.frame_rms), "frame_max": _floats(self.frame_max),
                "body_rms": _floats(self.body_rms), "body_max": _floats(self.body_max)}

    @classmethod
    def from_json(cls, d: dict) -> Divergence:
        first = d["first_over"]
        return cls(d["quantity"], d["unit"], d["threshold"], d["rms"], d["max"], d["max_time"], d["max_body"],
                   None if first is None else Crossing.from_json(first),
                   *(np.asarray(d[k], dtype=np.float64) for k in ("frame_rms", "frame_max", "body_rms", "body_max")))


@dataclass
class JointDifference:
    """One joint output field of one joint, between two runs."""
    node: str
    field: str
    unit: str
    threshold: float  # the threshold its unit is held to
    rms: float
    max: float
    max_time: float

    @property
    def ratio(self) -> float:
        return self.max / self.threshold

    def to_json(self) -> dict:
        return {"node": self.node, "field": self.field, "unit": self.unit, "threshold": self.threshold,
                "rms": self.rms, "max": self.max, "max_time": self.max_time}

    @classmethod
    def from_json(cls, d: dict) -> JointDifference:
        return cls(d["node"], d["field"], d["unit"], d["threshold"], d["rms"], d["max"], d["max_time"])


@dataclass
class PairComparison:
    """Two backends' runs of one scene, compared at the frame times both recorded."""
    a: str
    b: str
    times: np.ndarray
    bodies: list[str]  # in both traces
    only_in_a: list[str]
    only_in_b: list[str]
    position: Divergence
    orientation: Divergence
    joints: list[JointDifference]  # every joint output both traces hold
    joints_only_in_a: list[str]  # NODE.field
    joints_only_in_b: list[str]
    # the VELOCITIES every shared body has in both traces, in that order (at the pair's times)
    velocities: list[Divergence] = field(default_factory=list)

    @property
    def divergences(self) -> list[Divergence]:
        """Every body quantity compared: position, orientation, then the velocities."""
        return [self.position, self.orientation, *self.velocities]

    def diverged(self) -> list[str]:
        """What passed its threshold (or is no number), the body kinds, then the joint outputs
        (NODE.field); a kind no frame measured is not among them."""
        return ([d.quantity for d in self.divergences if d.max is not None and not d.max <= d.threshold]
                + [f"{j.node}.{j.field}" for j in self.joints if not j.ratio <= 1.0])

    def worst_joint(self) -> JointDifference | None:
        """The joint output furthest past (or nearest to) the threshold of its unit."""
        return max(self.joints, key=lambda j: j.ratio, default=None)

    def to_json(self) -> dict:
        return {"a": self.a, "b": self.b, "times": _floats(self.times), "bodies": self.bodies,
                "only_in_a": self.only_in_a, "only_in_b": self.only_in_b,
                "position": self.position.to_json(), "orientation": self.orientation.to_json(),
                "joints": [j.to_json() for j in self.joints],
                "joints_only_in_a": self.joints_only_in_a, "joints_only_in_b": self.joints_only_in_b,
                "velocities": [v.to_json() for v in self.velocities]}

    @classmethod
    def from_json(cls, d: dict) -> PairComparison:
        return cls(d["a"], d["b"], np.asarray(d["times"], dtype=np.float64), d["bodies"], d["only_in_a"],
                   d["only_in_b"], Divergence.from_json(d["position"]), Divergence.from_json(d["orientation"]),
                   [JointDifference.from_json(j) for j in d["joints"]], d["joints_only_in_a"], d["joints_only_in_b"],
                   # absent from comparisons written before velocities were compared
                   [Divergence.from_json(v) for v in d.get("velocities", [])])


@dataclass(frozen=True)
class EnergyGrowth:
    """A run whose mechanical energy (kinetic plus potential, J) rose past its bound with
    nothing doing work on its scene (conformance/analyses/energy.py): the engine made it."""
    start: float  # the first frame's
    peak: float  # the largest
    peak_at: float  # s, when it was the largest
    rose_at: float  # s, the first frame past start + bound
    bound: float  # J, the rise allowed

    def to_json(self) -> dict:
        return {"start": self.start, "peak": self.peak, "peak_at": self.peak_at, "rose_at": self.rose_at,
                "bound": self.bound}

    @classmethod
    def from_json(cls, d: dict | None) -> EnergyGrowth | None:
        return None if d is None else cls(d["start"], d["peak"], d["peak_at"], d["rose_at"], d["bound"])


@dataclass
class BackendRun:
    """One backend's run: its verdict, and how fast it simulated when it ran."""
    backend: str
    verdict: str  # RAN, or the runner's verdict (unsupported, crashed, timed out, blew up, error)
    reason: str = ""
    version: str | None = None
    simulated_s: float | None = None
    simulation_wall_s: float | None = None  # the simulation alone, as the child timed it
    child_wall_s: float | None = None  # the whole child process: start, imports, load, run, trace writing
    integration: str | None = None  # the backend's integration order (backends.base.Backend.integration)
    energy: EnergyGrowth | None = None  # its energy grew with nothing doing work on the scene

    @property
    def realtime_basis(self) -> str | None:
        """Which wall time the real-time factor divides by: 'simulation' or 'child'."""
        if self.simulated_s is None:
            return None
        return "simulation" if self.simulation_wall_s else ("child" if self.child_wall_s else None)

    @property
    def realtime_factor(self) -> float | None:
        basis = self.realtime_basis
        if basis is None:
            return None
        wall = self.simulation_wall_s if basis == "simulation" else self.child_wall_s
        return self.simulated_s / wall

    def to_json(self) -> dict:
        return {"backend": self.backend, "verdict": self.verdict, "reason": self.reason, "version": self.version,
                "simulated_s": self.simulated_s, "simulation_wall_s": self.simulation_wall_s,
                "child_wall_s": self.child_wall_s, "realtime_factor": self.realtime_factor,
                "realtime_basis": self.realtime_basis, "integration": self.integration,
                "energy_growth": self.energy.to_json() if self.energy else None}

    @classmethod
    def from_json(cls, d: dict) -> BackendRun:
        # integration, energy_growth: absent from comparisons written before they were measured
        return cls(d["backend"], d["verdict"], d["reason"], d["version"], d["simulated_s"],
                   d["simulation_wall_s"], d["child_wall_s"], d.get("integration"),
                   EnergyGrowth.from_json(d.get("energy_growth")))


@dataclass
class Comparison:
    """One scene on several backends: every run's verdict and every pair that both ran."""
    scene: str
    duration: float
    dt: float
    frame_rate: float
    thresholds: dict[str, float]
    runs: list[BackendRun]
    pairs: list[PairComparison]

    def to_json(self) -> dict:
        return {"scene": self.scene, "duration": self.duration, "dt": self.dt, "frame_rate": self.frame_rate,
                "thresholds": self.thresholds, "runs": [r.to_json() for r in self.runs],
                "pairs": [p.to_json() for p in self.pairs]}

    @classmethod
    def from_json(cls, d: dict) -> Comparison:
        return cls(d["scene"], d["duration"], d["dt"], d["frame_rate"], dict(d["thresholds"]),
                   [BackendRun.from_json(r) for r in d["runs"]], [PairComparison.from_json(p) for p in d["pairs"]])


# -- validation of another implementation's traces -------------------------------------

AGREES, DIFFERS = "agrees", "differs"
THEIRS = "theirs"  # their trace's name in comparisons


def agrees(pair: PairComparison) -> bool:
    """Every divergence of their trace from the backend's within its threshold: each body
    quantity compared (pose and velocities) and each shared joint output."""
    return bool(pair.times.size and pair.bodies and all(x.max is not None for x in pair.divergences)
                and not pair.diverged())


@dataclass
class TraceComparison:
    """One of their traces against every backend's run with the settings read off it."""
    trace: str
    settings: Settings
    runs: list[BackendRun]
    pairs: dict[str, PairComparison]  # by backend, for those that ran
    views: dict[str, TraceView] = field(default_factory=dict, repr=False)  # their runs, for recordings

    def verdict(self, backend: str) -> str:
        """AGREES, DIFFERS, or the run's verdict where it did not run."""
        pair = self.pairs.get(backend)
        if pair is None:
            return next(r.verdict for r in self.runs if r.backend == backend)
        return AGREES if agrees(pair) else DIFFERS

    def to_json(self) -> dict:
        s = self.settings
        return {"trace": self.trace, "duration": s.duration, "dt": s.dt, "frame_rate": s.frame_rate,
                "runs": [dict(r.to_json(), comparison=self.verdict(r.backend)) for r in self.runs],
                "pairs": [p.to_json() for p in self.pairs.values()]}


@dataclass
class FrameStep:
    """Their frames' period, the step an implementation that steps once per frame takes, offered
    where a trace judged at another step does not conform; and the trace judged at it."""
    dt: float
    conforms: bool | None  # None: not judged at it (a finer step than the one judged: more runs)
    agreeing: list[str] = field(default_factory=list)  # the backends that agree at it

    def to_json(self) -> dict:
        return {"dt": self.dt, "conforms": self.conforms, "agreeing": self.agreeing}


@dataclass
class Validation:
    scene: str
    traces: list[str]
    thresholds: dict[str, float]
    case: Result | None  # the case's expectation on their traces, where the scene is a case
    comparisons: list[TraceComparison] = field(default_factory=list)
    frame_step: FrameStep | None = None

    @property
    def backends(self) -> list[str]:
        return [r.backend for r in self.comparisons[0].runs] if self.comparisons else []

    def agreeing(self) -> list[str]:
        """The backends that agree with their every trace."""
        return [b for b in self.backends if all(c.verdict(b) == AGREES for c in self.comparisons)]

    @property
    def rule(self) -> str:
        return "the case's expectation" if self.case is not None else "agreement with one backend"

    @property
    def judged(self) -> bool:
        """Whether anything judged the trace: the case's expectation, or a backend whose run it could
        be held to; where every backend refused, failed or timed out, nothing did, and saying the
        trace 'does not conform' would accuse an implementation that nothing measured."""
        return self.case is not None or any(c.pairs for c in self.comparisons)

    @property
    def conforms(self) -> bool:
        if self.case is not None:
            return self.case.verdict in (PASS, CONVENTIONS)
        return bool(self.agreeing())

    def to_json(self) -> dict:
        return {"scene": self.scene, "traces": self.traces, "thresholds": self.thresholds, "rule": self.rule,
                "judged": self.judged, "conforms": self.conforms, "case": None if self.case is None else self.case.to_json(),
                "agreeing": self.agreeing(), "comparisons": [c.to_json() for c in self.comparisons],
                "frame_step": None if self.frame_step is None else self.frame_step.to_json()}

"""How far two runs of one scene part: body poses and joint outputs, frame by frame.

The metrics work on traces already parsed (cases.TraceView: one array per (node, field)),
in bulk over (frames, bodies) arrays. Two runs are compared at the frame times both
recorded (the same settings give the same frames) and on the bodies and joint outputs
both traces hold; what only one holds is listed, not an error.

- position divergence: |p1 - p2| per body and frame, in m;
- orientation divergence: the angle of q1^-1 q2 in rad, in [0, pi] whichever sign each
  trace's quaternion takes (q and -q are one rotation);
- per frame the RMS and the max over bodies, over the run the RMS and the max over
  every (frame, body), and the first frame at which some body passes the threshold,
  with the bodies over it then, the worst first;
- joint outputs: every output field the traces share (angle, separation, anchor points,
  axes...), the difference's magnitude (angles wrapped to (-pi, pi]: a hinge at pi and
  one at -pi agree), RMS and max per (joint, field).

Default thresholds, 1 mm and 1 mrad: the engines step the same semi-implicit Euler, so
free motion agrees to rounding (1e-12 m); what separates runs is how each solves its
constraints and contacts. 1 mm is where that becomes visible at the scale the
component's scenes are built (metres: about a pixel at 1000 px/m), and 1 mrad turns the
end of a 1 m body by that same 1 mm. Scenes at other scales should pass their own.
A joint output is held to the threshold of its unit: m and m/s to the position one,
rad, rad/s and unit axes to the orientation one (rates: that much per second).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from x3d_core import schema

from .cases import TraceView, quaternions, rotation_angle_between

POSITION, ORIENTATION = "position", "orientation"
DEFAULT_THRESHOLDS = {POSITION: 1e-3, ORIENTATION: 1e-3}  # m, rad
UNITS = {POSITION: "m", ORIENTATION: "rad"}
RAN = "ran"  # a backend's verdict when it wrote its trace (else one of runner.VERDICTS)

_SI = {"length": "m", "speed": "m/s", "angle": "rad", "angular_rate": "rad/s", None: "1"}
_HELD_TO = {"m": POSITION, "m/s": POSITION, "rad": ORIENTATION, "rad/s": ORIENTATION, "1": ORIENTATION}


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


def _opt(x: float | None) -> float | None:
    return None if x is None else float(x)


# -- results ------------------------------------------------------------------------------

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
    """One quantity (position or orientation) between two runs. The series are per frame
    (the pair's times) and per body (the pair's bodies); the scalars are None when the
    runs share no body or no frame."""
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

    def worst_joint(self) -> JointDifference | None:
        """The joint output furthest past (or nearest to) the threshold of its unit."""
        return max(self.joints, key=lambda j: j.ratio, default=None)

    def to_json(self) -> dict:
        return {"a": self.a, "b": self.b, "times": _floats(self.times), "bodies": self.bodies,
                "only_in_a": self.only_in_a, "only_in_b": self.only_in_b,
                "position": self.position.to_json(), "orientation": self.orientation.to_json(),
                "joints": [j.to_json() for j in self.joints],
                "joints_only_in_a": self.joints_only_in_a, "joints_only_in_b": self.joints_only_in_b}

    @classmethod
    def from_json(cls, d: dict) -> PairComparison:
        return cls(d["a"], d["b"], np.asarray(d["times"], dtype=np.float64), d["bodies"], d["only_in_a"],
                   d["only_in_b"], Divergence.from_json(d["position"]), Divergence.from_json(d["orientation"]),
                   [JointDifference.from_json(j) for j in d["joints"]], d["joints_only_in_a"], d["joints_only_in_b"])


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
                "realtime_basis": self.realtime_basis}

    @classmethod
    def from_json(cls, d: dict) -> BackendRun:
        return cls(d["backend"], d["verdict"], d["reason"], d["version"], d["simulated_s"],
                   d["simulation_wall_s"], d["child_wall_s"])


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


# -- metrics ------------------------------------------------------------------------------

def bodies(trace: TraceView) -> list[str]:
    """The nodes that have both a position and an orientation: the bodies, in trace order."""
    keys = set(trace.keys())
    return [n for n, f in trace.keys() if f == POSITION and (n, ORIENTATION) in keys]


def _common_times(series: Sequence[np.ndarray]) -> np.ndarray:
    return functools.reduce(np.intersect1d, series) if series else np.empty(0)


def _at(times: np.ndarray, values: np.ndarray, when: np.ndarray) -> np.ndarray:
    """values at the frame times `when` (each one of `times`, which are sorted)."""
    return values[np.searchsorted(times, when)]


def divergence(quantity: str, threshold: float, times: np.ndarray, names: Sequence[str],
               d: np.ndarray) -> Divergence:
    """The statistics of d (frames, bodies), a divergence per frame and body."""
    unit = UNITS[quantity]
    if d.size == 0:
        return Divergence(quantity, unit, threshold)
    sq = d * d
    frame_max = d.max(axis=1)
    f, k = np.unravel_index(int(np.argmax(d)), d.shape)
    over = np.flatnonzero(frame_max > threshold)
    first = None
    if over.size:
        row = d[over[0]]
        worst = np.flatnonzero(row > threshold)
        worst = worst[np.argsort(-row[worst], kind="stable")]
        first = Crossing(float(times[over[0]]), [names[i] for i in worst], _floats(row[worst]))
    return Divergence(quantity, unit, threshold, float(np.sqrt(sq.mean())), float(d[f, k]), float(times[f]),
                      names[k], first, np.sqrt(sq.mean(axis=1)), frame_max, np.sqrt(sq.mean(axis=0)), d.max(axis=0))


def _stack(trace: TraceView, names: Sequence[str], fld: str, times: np.ndarray) -> np.ndarray:
    """(frames, bodies, width): one field of every named node at the given times."""
    return np.stack([_at(*trace.series(n, fld), times) for n in names], axis=1)


def joint_differences(ta: TraceView, tb: TraceView, thresholds: Mapping[str, float]) -> list[JointDifference]:
    """Every joint output both traces hold, in the first trace's order."""
    in_b = set(tb.keys())
    out = []
    for node, fld in ta.keys():
        unit = JOINT_OUTPUTS.get(fld)
        if unit is None or (node, fld) not in in_b:
            continue
        (t1, v1), (t2, v2) = ta.series(node, fld), tb.series(node, fld)
        times = np.intersect1d(t1, t2)
        if not times.size:
            continue
        diff = _at(t1, v1, times) - _at(t2, v2, times)
        if unit == "rad":  # an angle: pi and -pi are one position of the joint
            diff = np.remainder(diff + math.pi, 2.0 * math.pi) - math.pi
        mag = np.linalg.norm(diff, axis=1)
        k = int(np.argmax(mag))
        out.append(JointDifference(node, fld, unit, thresholds[_HELD_TO[unit]], float(np.sqrt(np.mean(mag * mag))),
                                   float(mag[k]), float(times[k])))
    return out


def _joint_keys(trace: TraceView) -> list[str]:
    return [f"{n}.{f}" for n, f in trace.keys() if f in JOINT_OUTPUTS]


def compare_pair(a: str, ta: TraceView, b: str, tb: TraceView,
                 thresholds: Mapping[str, float] = DEFAULT_THRESHOLDS) -> PairComparison:
    """Backend a's trace against backend b's."""
    in_a, in_b = bodies(ta), bodies(tb)
    names = [n for n in in_a if n in in_b]
    times = _common_times([t.series(n, f)[0] for t in (ta, tb) for n in names for f in (POSITION, ORIENTATION)])
    if names and times.size:
        dp = np.linalg.norm(_stack(ta, names, POSITION, times) - _stack(tb, names, POSITION, times), axis=-1)
        do = rotation_angle_between(quaternions(_stack(ta, names, ORIENTATION, times)),
                                    quaternions(_stack(tb, names, ORIENTATION, times)))
    else:
        dp = do = np.empty((times.size, 0))
    ja, jb = _joint_keys(ta), _joint_keys(tb)
    return PairComparison(
        a, b, times, names, _missing(in_a, in_b), _missing(in_b, in_a),
        divergence(POSITION, thresholds[POSITION], times, names, dp),
        divergence(ORIENTATION, thresholds[ORIENTATION], times, names, do),
        joint_differences(ta, tb, thresholds), _missing(ja, jb), _missing(jb, ja))


def _missing(names: Sequence[str], other: Sequence[str]) -> list[str]:
    """The names not in other, in their order."""
    there = set(other)
    return [n for n in names if n not in there]


def compare_all(runs: Sequence[tuple[BackendRun, TraceView | None]],
                thresholds: Mapping[str, float] = DEFAULT_THRESHOLDS) -> list[PairComparison]:
    """Every pair of runs that wrote a trace, in the runs' order."""
    ran = [(r.backend, t) for r, t in runs if t is not None]
    return [compare_pair(a, ta, b, tb, thresholds) for i, (a, ta) in enumerate(ran) for b, tb in ran[i + 1:]]

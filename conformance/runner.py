"""Runs conformance cases on backends, each run in its own process, and gives verdicts.

Each (case, backend) runs `python -m conformance.cli run SCENE --backend NAME ... --trace TMP`
in a child process with a time limit, so that an engine's segfault or endless loop is a
verdict, not a lost suite. The expectation is evaluated here, in the parent, on the trace
the child wrote. Verdicts:

- pass: every measured error within its tolerance;
- fail: some error beyond its tolerance (each Measure says which, by how much);
- unsupported: the backend refused a feature the scene needs (exit 3; the reason is the
  backend's own, from the child's stderr);
- crashed: the child died by a signal (negative return code), or raised an uncaught exception;
- timed out: no result within the time limit (the child's process group is killed);
- blew up: a body's state became non-finite (the evaluator says 'blew up');
- error: the run could not start for reasons that are not the engine's: the scene does not
  load, the backend is unknown or not installed, the trace lacks what the expectation reads.

Pairs run in parallel, at most os.cpu_count() at a time. The pool is of threads, each
waiting on its child process: the children are the processes that do the work, and a
thread pool spares a second interpreter per pair and any pickling.
"""

from __future__ import annotations

import math
import os
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import TypeVar

from x3d_core.trace import read_trace

from .cases import Case, Measure, Settings, TraceView

PASS, FAIL, UNSUPPORTED, CRASHED, TIMED_OUT, BLEW_UP, ERROR = (
    "pass", "fail", "unsupported", "crashed", "timed out", "blew up", "error")
VERDICTS = (PASS, FAIL, UNSUPPORTED, CRASHED, TIMED_OUT, BLEW_UP, ERROR)
DEFAULT_TIMEOUT = 60.0
EXIT_UNSUPPORTED = 3  # conformance.run_command
T = TypeVar("T")  # what run_many's jobs return


@dataclass
class Result:
    case: str
    backend: str
    verdict: str
    reason: str = ""  # why it is not a pass: failing measures, the declared reason, the error
    measures: list[Measure] = field(default_factory=list)
    wall_s: float = 0.0
    dt: float | None = None  # the step of the (first) run

    def worst(self) -> Measure | None:
        return max(self.measures, key=lambda m: m.ratio) if self.measures else None

    def measure(self, quantity: str) -> Measure | None:
        return next((m for m in self.measures if m.quantity == quantity), None)

    def to_json(self) -> dict:
        return {"case": self.case, "backend": self.backend, "verdict": self.verdict, "reason": self.reason,
                "dt": self.dt, "wall_s": round(self.wall_s, 3),
                "measures": [{"quantity": m.quantity, "error": _finite_or_str(m.error),
                              "tolerance": _finite_or_str(m.tolerance), "unit": m.unit, "ok": m.ok}
                             for m in self.measures]}


def _finite_or_str(x: float) -> float | str:
    return x if math.isfinite(x) else str(x)


@dataclass
class Outcome:
    """What one child run came to: None verdict when it wrote its trace."""
    verdict: str | None
    reason: str = ""


def _tail(text: str, lines: int = 3) -> str:
    kept = [ln.strip() for ln in text.strip().splitlines() if ln.strip()]
    return " | ".join(kept[-lines:])


def classify(returncode: int | None, stderr: str, timed_out: bool = False, timeout: float = DEFAULT_TIMEOUT,
             backend: str = "") -> Outcome:
    """The verdict of one child `x3drbp run` from how it ended (None: it succeeded)."""
    if timed_out:
        return Outcome(TIMED_OUT, f"no result within {timeout:g} s")
    if returncode is None:
        return Outcome(ERROR, "the run did not start")
    if returncode < 0:
        try:
            name = signal.Signals(-returncode).name
        except ValueError:
            name = f"signal {-returncode}"
        return Outcome(CRASHED, f"killed by {name}" + (f": {_tail(stderr)}" if stderr.strip() else ""))
    if returncode == 0:
        return Outcome(None)
    if returncode == EXIT_UNSUPPORTED:
        marker = f"unsupported by {backend}: " if backend else "unsupported by "
        reasons = []
        for line in stderr.splitlines():
            if marker in line:
                reasons.append(line.split(marker, 1)[1].strip())
        return Outcome(UNSUPPORTED, "; ".join(reasons) or _tail(stderr) or "the backend refused the scene")
    if "blew up" in stderr:
        line = next(ln for ln in stderr.splitlines() if "blew up" in ln)
        return Outcome(BLEW_UP, line.strip())
    if "Traceback (most recent call last)" in stderr:
        return Outcome(CRASHED, f"uncaught exception: {_tail(stderr, 1)}")
    return Outcome(ERROR, _tail(stderr) or f"exit status {returncode}")


def run_child(scene: str, backend: str, settings: Settings, trace: str,
              timeout: float = DEFAULT_TIMEOUT, extra: Sequence[str] = ()) -> Outcome:
    """`x3drbp run` (with the `extra` options) in its own process (and process group),
    killed after `timeout` seconds."""
    cmd = [sys.executable, "-m", "conformance.cli", "run", scene, "--backend", backend, *settings.args(),
           "--trace", trace, *extra]
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    try:
        proc = subprocess.Popen(cmd, cwd=root, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                stderr=subprocess.PIPE, text=True, start_new_session=True)
    except OSError as e:
        return Outcome(ERROR, f"could not start {sys.executable}: {e}")
    try:
        _, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        try:
            os.killpg(proc.pid, signal.SIGKILL)  # the child's own group: it and anything it started
        except ProcessLookupError:
            pass
        proc.communicate()
        return classify(None, "", timed_out=True, timeout=timeout)
    out = classify(proc.returncode, err, backend=backend)
    if out.verdict is None and not os.path.exists(trace):
        return Outcome(ERROR, "the run succeeded but wrote no trace")
    return out


def evaluate(case: Case, backend: str, traces: Sequence[TraceView], settings: Sequence[Settings]) -> Result:
    """Apply the case's expectation to traces already read."""
    dt = settings[0].dt if settings else None
    try:
        measures = case.expect(traces, settings)
    except (KeyError, ValueError, IndexError) as e:
        msg = e.args[0] if isinstance(e, KeyError) and e.args else str(e)
        return Result(case.name, backend, ERROR, f"the expectation could not read the trace: {msg}", dt=dt)
    failing = [m for m in measures if not m.ok]
    if not failing:
        return Result(case.name, backend, PASS, "", measures, dt=dt)
    reason = "; ".join(f"{m.quantity}: error {m.error:.3g}{' ' + m.unit if m.unit else ''} > tolerance "
                       f"{m.tolerance:.3g}" for m in failing)
    return Result(case.name, backend, FAIL, reason, measures, dt=dt)


def run_pair(case: Case, backend: str, timeout: float = DEFAULT_TIMEOUT,
             settings: Sequence[Settings] | None = None, keep: str | None = None) -> Result:
    """Run one case on one backend (every run of the case, one child each) and judge it.
    `settings` overrides the case's runs (convergence studies); `keep`, a folder, keeps the
    traces there as CASE-BACKEND[-k].csv."""
    settings = tuple(settings or case.runs)
    started = time.perf_counter()
    dt = settings[0].dt
    if not os.path.exists(case.path):
        return Result(case.name, backend, ERROR, f"no scene file {case.path}", dt=dt)
    with tempfile.TemporaryDirectory(prefix="x3drbp-conf-") as tmp:
        folder = keep or tmp
        os.makedirs(folder, exist_ok=True)
        traces = []
        for k, s in enumerate(settings):
            suffix = f"-{k}" if len(settings) > 1 else ""
            path = os.path.join(folder, f"{case.name}-{backend}{suffix}.csv")
            if os.path.exists(path):
                os.unlink(path)
            out = run_child(case.path, backend, s, path, timeout)
            if out.verdict is not None:
                return Result(case.name, backend, out.verdict, out.reason, dt=dt,
                              wall_s=time.perf_counter() - started)
            try:
                traces.append(TraceView(read_trace(path)))
            except (OSError, ValueError) as e:
                return Result(case.name, backend, ERROR, f"unreadable trace: {e}", dt=dt,
                              wall_s=time.perf_counter() - started)
        result = evaluate(case, backend, traces, settings)
    result.wall_s = time.perf_counter() - started
    return result


def run_many(jobs: Sequence[Callable[[], T]], workers: int | None = None) -> list[T]:
    """Run independent jobs in parallel (results in the jobs' order)."""
    workers = max(1, min(workers or os.cpu_count() or 1, len(jobs) or 1))
    with ThreadPoolExecutor(max_workers=workers) as pool:
        return list(pool.map(lambda job: job(), jobs))


def run_matrix(cases: Sequence[Case], backends: Sequence[str], timeout: float = DEFAULT_TIMEOUT,
               workers: int | None = None, keep: str | None = None) -> list[Result]:
    """Every case on every backend; results case-major."""
    jobs = [(lambda c=c, b=b: run_pair(c, b, timeout, keep=keep)) for c in cases for b in backends]
    return run_many(jobs, workers)


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
            out.append(m.error if m is not None and r.verdict in (PASS, FAIL) else None)
        return out

    def order(self) -> float | None:
        return fitted_order(self.dts, self.errors())

    def to_json(self) -> dict:
        return {"case": self.case, "backend": self.backend, "quantity": self.quantity,
                "expected_order": self.expected_order,
                "points": [{"dt": dt, "error": (None if e is None else _finite_or_str(e)), "verdict": r.verdict,
                            "reason": r.reason if r.verdict not in (PASS, FAIL) else ""}
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


def run_convergence(cases: Sequence[Case], backends: Sequence[str], dts: Sequence[float],
                    timeout: float = DEFAULT_TIMEOUT, workers: int | None = None) -> list[Convergence]:
    """Each closed-form case (one with a `convergence` quantity) at every dt, per backend."""
    chosen = [c for c in cases if c.convergence]
    keys = [(c, b, dt) for c in chosen for b in backends for dt in dts]
    results = run_many([(lambda c=c, b=b, dt=dt: run_pair(c, b, timeout, settings=c.at_dt(dt)))
                        for c, b, dt in keys], workers)
    out = []
    for i in range(0, len(keys), len(dts)):
        c, b, _ = keys[i]
        out.append(Convergence(c.name, b, c.convergence, list(dts), results[i:i + len(dts)], c.expected_order))
    return out


_PROBE = """
import json, sys
from backends import base
only = sys.argv[1:]
if only:  # one engine alone (after a probe of all of them died)
    found = {}
    for name in only:
        try:
            found[name] = base.load(name)
        except Exception as e:
            found[name] = f"{type(e).__name__}: {e}"
else:
    try:
        found = base.available()
    except Exception:  # base.available() catches ImportError only: go engine by engine
        found = {}
        for name in base.ENGINES:
            try:
                found[name] = base.load(name)
            except Exception as e:
                found[name] = f"{type(e).__name__}: {e}"
out = {}
for name, b in found.items():
    if isinstance(b, str):
        out[name] = {"unavailable": b}
    else:
        try:
            out[name] = {"version": str(b.version())}
        except Exception as e:  # a backend whose engine imports but cannot say its version
            out[name] = {"unavailable": f"version() failed: {type(e).__name__}: {e}"}
print("\\nx3drbp-probe " + json.dumps(out))  # engines may print on import (pybullet does)
"""


def _probe(names: Sequence[str], timeout: float) -> tuple[dict, str]:
    """Run the probe in a child: (what it reported, why it reported nothing)."""
    import json
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    try:
        done = subprocess.run([sys.executable, "-c", _PROBE, *names], cwd=root, capture_output=True, text=True,
                              timeout=timeout, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        return {}, f"the backend probe gave no answer within {timeout:g} s"
    found = [ln for ln in done.stdout.splitlines() if ln.startswith("x3drbp-probe ")]
    if done.returncode == 0 and found:
        try:
            return json.loads(found[-1].split(" ", 1)[1]), ""
        except json.JSONDecodeError:
            pass
    return {}, classify(done.returncode, done.stderr).reason or "the backend probe printed nothing"


@dataclass
class BackendInfo:
    name: str
    version: str | None = None
    unavailable: str | None = None  # why it cannot be used here

    @property
    def usable(self) -> bool:
        return self.unavailable is None


def named_backends(names: Sequence[str], info: dict[str, BackendInfo]) -> list[str]:
    """The backends a command line names, in its order (default: every usable one);
    ValueError naming any the registry does not know."""
    unknown = [n for n in names if n not in info]
    if unknown:
        raise ValueError(f"unknown backend(s) {', '.join(unknown)}; known: {', '.join(info)}")
    return list(names) or [n for n, i in info.items() if i.usable]


def backend_table(timeout: float = DEFAULT_TIMEOUT) -> dict[str, BackendInfo]:
    """backends.base.available(), asked in a child process: importing an engine can crash,
    and the suite must survive that too. Should the probe of all engines die, each engine
    is probed alone, so that one broken engine does not hide the others. Every name in
    base.ENGINES gets an entry."""
    from backends import base  # the registry itself imports no engine
    data, why = _probe([], timeout)
    if not data:
        whys = {}
        for name in base.ENGINES:
            one, whys[name] = _probe([name], timeout)
            data.update(one)
    else:
        whys = {}
    out = {}
    for name in dict.fromkeys([*base.ENGINES, *data]):
        d = data.get(name)
        if d is None:
            out[name] = BackendInfo(name, unavailable=whys.get(name) or why or "not reported by base.available()")
        else:
            why_not = d.get("unavailable")
            if why_not and why_not.startswith("unavailable: "):  # base.available()'s own wording
                why_not = why_not[len("unavailable: "):]
            out[name] = BackendInfo(name, d.get("version"), why_not)
    return out

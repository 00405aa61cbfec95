"""`x3drbp run` and `x3drbp backends`: one scene on one engine, and the engines' tables."""

from __future__ import annotations

import argparse
import os
import resource
import select
import signal
import sys
import time
from collections import Counter
from collections.abc import Iterator
from contextlib import contextmanager

import numpy as np

from backends import base
from x3d_core.files import atomic
from x3d_core.model.scene import Scene
from x3d_core.semantics.analysis import Use
from x3d_core.semantics.engine import Engine, Simulation, Stopped, TimedOut, Unsupported, on_engine_abort, target_accuracy
from x3d_core.semantics.evaluator import MAX_SOLVER_ITERATIONS, RunSettings, run, too_much_solving
from x3d_core.semantics.outcome import EMPTY, NOTHING_TO_SIMULATE, outcome_warnings, simulates
from x3d_core.semantics.validate import diagnostic
from x3d_core.semantics.world import World, worlds
from x3d_core.traces.trace import Trace
from x3d_core.traces.trace_npz import write_npz

from x3drbp import options


EXIT_OK, EXIT_ERROR, EXIT_USAGE, EXIT_UNSUPPORTED = 0, 1, 2, 3
NAMED, LEAD = 4, 120  # a default note's features named, and characters of its note: one short line each
STUCK_GRACE = 5.0  # s an engine call may run past --timeout before the watchdog ends the run without a trace


class _StepClock:
    """An engine whose simulations add the wall time of their steps to `step_s`: the engine's
    own integration cost, apart from its model build and the evaluator's per-frame reads; and
    that keeps each world's target accuracy (x3d_core.semantics.engine.target_accuracy) for --timing."""

    def __init__(self, engine: Engine):
        self.engine, self.name, self.step_s, self.step_cpu_s = engine, engine.name, 0.0, 0.0
        self.target_accuracy: list[float | None] = []

    def build(self, world: World, dt: float) -> Simulation:
        sim = self.engine.build(world, dt)
        self.target_accuracy.append(target_accuracy(sim))
        return _TimedSteps(sim, self)


class _TimedSteps:
    def __init__(self, sim: Simulation, clock: _StepClock):
        self._sim, self._clock = sim, clock
        self.state = sim.state  # read every frame: not through __getattr__'s failed lookup first

    def step(self, n: int = 1) -> None:
        started, cpu = time.perf_counter(), time.process_time()
        self._sim.step(n)
        self._clock.step_s += time.perf_counter() - started
        self._clock.step_cpu_s += time.process_time() - cpu  # the engine's work, whatever else runs beside it

    def __getattr__(self, name: str):  # state, contacts, set_velocities, set_loads
        return getattr(self._sim, name)


def _write_trace(trace: Trace, path: str | None) -> None:
    """The trace to path (atomically; NumPy's .npz where path ends so), else to standard output."""
    if path and path.endswith(".npz"):
        write_npz(trace.view(), path)
    elif path:
        trace.write(path)
    else:
        sys.stdout.write(trace.text())


def scene_to_run(path: str) -> tuple[Scene, list[World]] | None:
    """The scene and its worlds (built once: the warnings, the backend's judgement and the run
    all read them), its warnings printed once on stderr (before any backend, so once however
    many run it); None after one line saying why where it has errors or nothing to simulate
    (the commands that run it exit 1 then, and write no trace)."""
    scene = options.load_scene(path)
    if scene is None:
        return None
    ws = worlds(scene)
    for d in scene.warnings + outcome_warnings(scene, ws):
        if d.message != NOTHING_TO_SIMULATE:  # said below as the reason the run stops
            print(d, file=sys.stderr)
    if not simulates(scene):
        print(f"{path}: nothing to simulate: {EMPTY} (no trace written)", file=sys.stderr)
        return None
    return scene, ws


STARTED, ENDED = b"s", b"e"  # what a run under a watchdog tells it (_watchdog): its time limit began, is over


def _tell(fd: int, word: bytes) -> None:
    """One word to the watchdog (none where fd is -1: no --timeout); a watchdog gone is no error of the run."""
    if fd >= 0:
        try:
            os.write(fd, word)
        except OSError:
            pass


@contextmanager
def time_limit(seconds: float | None, watchdog: int = -1) -> Iterator[None]:
    """TimedOut raised in the main thread once `seconds` of wall time have passed (between two
    steps: the evaluator keeps the frames before); the watchdog process (_watchdog, on fd
    `watchdog`) told when the limit starts and ends, to end the run should an engine call
    keep the interpreter STUCK_GRACE s past it."""
    if seconds is None:
        yield
        return

    def expire(signum: int, frame: object) -> None:
        raise TimedOut(f"passed its time limit of {seconds:g} s")

    previous = signal.signal(signal.SIGALRM, expire)
    _tell(watchdog, STARTED)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        _tell(watchdog, ENDED)
        signal.signal(signal.SIGALRM, previous)


def _watchdog(seconds: float, said: str) -> tuple[int | None, int]:
    """The command forked, before it imports the engine: (None, fd) in the child, which runs
    on and tells fd when its time limit starts and ends (time_limit); (its exit status, -1) in
    the parent, which waits for it. The parent, not a thread of the run, keeps the limit: an
    engine call that holds the interpreter lock (pybullet's 90 s step of 100 overlapping
    boxes) lets no thread of its process run, nor a Python signal handler. Past STUCK_GRACE s
    beyond the limit the parent SIGKILLs the run and says one line `said` + why, exit 1; the
    trace is written only after the limit ends, so none is half written."""
    sys.stdout.flush()
    sys.stderr.flush()
    r, w = os.pipe()
    parent = os.getpid()
    pid = os.fork()
    if pid == 0:
        os.close(r)
        _die_with(parent)
        return None, w
    os.close(w)
    try:
        return _watch(pid, r, seconds, said), -1
    finally:
        os.close(r)


def _die_with(parent: int) -> None:
    """In the run: SIGKILLed should the watchdog end first (a `kill -9` of the command's pid),
    where Linux can say so; the run's group, the command's own, is what the runners end."""
    if sys.platform.startswith("linux"):
        import ctypes  # here: only a watched run pays its import
        ctypes.CDLL(None).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
        if os.getppid() != parent:  # it ended before the call above
            os._exit(EXIT_ERROR)


def _word(fd: int, timeout: float | None) -> bytes | None:
    """The run's next word on fd (b"" once it has closed it: ended), or None past timeout s."""
    if not select.select([fd], [], [], timeout)[0]:
        return None
    return os.read(fd, 1)


def _watch(pid: int, fd: int, seconds: float, said: str) -> int:
    """The watchdog's side: the run's exit status, or EXIT_ERROR after one line where it kept
    an engine call STUCK_GRACE s past its limit (then SIGKILLed). SIGTERM is passed on to the
    run; SIGINT ignored, as a terminal's Ctrl-C reaches the run too (one process group), which
    says how it ended."""
    def pass_on(signum: int, frame: object) -> None:
        try:
            os.kill(pid, signum)
        except ProcessLookupError:  # reaped already
            pass

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, pass_on)
    if _word(fd, None) == STARTED and _word(fd, seconds + STUCK_GRACE) is None:
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
        print(f"{said}: passed its time limit of {seconds:g} s inside one engine call (no trace written)",
              file=sys.stderr, flush=True)
        return EXIT_ERROR
    code = os.waitstatus_to_exitcode(os.waitpid(pid, 0)[1])
    if code < 0:  # killed by a signal (a segfault): the command dies of it too, as an unwatched run would
        resource.setrlimit(resource.RLIMIT_CORE, (0, resource.getrlimit(resource.RLIMIT_CORE)[1]))  # no core of its own
        if -code != signal.SIGKILL:
            signal.signal(-code, signal.SIG_DFL)
        os.kill(os.getpid(), -code)
        return 128 - code  # a signal its caller had it block: the shell's convention
    return code


def refusal(uses: list[Use], note: str) -> str:
    """Uses refused for one reason, as a refusal says them: each use with its value, the reason
    once (a car's four wheel joints, each field of each, share one), with their count."""
    count = f" ({len(uses)} uses)" if len(uses) > 1 else ""
    return f"{', '.join(map(str, uses))}{count}: {note}"


def approximation(uses: list[Use], note: str) -> str:
    """Uses approximated alike, as a note says them by default, bounded whatever the scene: the
    features (each once, with its count), NAMED of them at most, and the note's lead (-v: every
    use with its value, the whole note)."""
    counts = Counter(u.feature for u in uses)
    names = [f + (f" ({n} uses)" if n > 1 else "") for f, n in counts.items()]
    more = f" and {len(names) - NAMED} more features" if len(names) > NAMED else ""
    return f"{', '.join(names[:NAMED])}{more}: {_lead(note)}"


def _lead(note: str) -> str:
    """A note's first clause, cut at a word to LEAD characters (the whole note under -v)."""
    lead = note.split("; ", 1)[0]
    if len(lead) <= LEAD:
        return lead + (" ... (-v: the whole note)" if lead != note else "")
    return lead[:LEAD].rsplit(" ", 1)[0] + " ... (-v: the whole note)"


def cmd_run(args: argparse.Namespace) -> int:
    problem = options.settings_error(args)
    if problem:
        print(f"x3drbp run: {problem}", file=sys.stderr)
        return EXIT_USAGE
    try:
        base.entry(args.backend)
    except KeyError as e:  # a name no backend registers: bad usage
        print(f"x3drbp run: {e.args[0]}", file=sys.stderr)
        return EXIT_USAGE
    loaded = scene_to_run(args.scene)  # before the backend's import: a plug-in that changes directory moves no input
    if loaded is None:
        return EXIT_ERROR
    scene, ws = loaded
    settings = RunSettings(duration=args.duration, dt=args.dt, frame_rate=args.frame_rate)
    over = too_much_solving(ws, settings)
    if over is not None:  # as --dt 1e-12's steps: before any work
        w, iterations = over
        steps = f"{settings.duration / settings.dt:.3g} steps (--duration {args.duration:g} at --dt {args.dt:g})"
        print(diagnostic(scene, w.node, "iterations", f"{w.iterations} iterations a step for {steps} make "
                         f"{iterations:.3g} solver iterations; a run takes at most {MAX_SOLVER_ITERATIONS:.3g}",
                         "error"), file=sys.stderr)
        return EXIT_ERROR
    watchdog = -1
    if args.timeout is not None:
        status, watchdog = _watchdog(args.timeout, f"{args.scene}: {args.backend}")
        if status is not None:
            return status
    try:
        backend = base.load(args.backend)
    except ImportError as e:
        print(f"x3drbp run: backend {args.backend}: {e}", file=sys.stderr)
        return EXIT_ERROR
    refused: dict[str, list[Use]] = {}
    approximated: dict[str, list[Use]] = {}
    for use, d in base.judged(backend, scene, ws):  # each named with its value
        if d.support is not base.Support.NATIVE:
            (refused if d.support is base.Support.UNSUPPORTED else approximated).setdefault(d.note, []).append(use)
    if not args.quiet:
        for note, uses in approximated.items():  # one line per approximation, or per use with -v
            for line in ([f"{u}: {note}" for u in uses] if args.verbose else [approximation(uses, note)]):
                print(f"{args.scene}: note: {args.backend} approximates {line}", file=sys.stderr)
    if refused:
        for note, uses in refused.items():  # a refusal's reason once, whatever number of uses it covers
            print(f"{args.scene}: unsupported by {args.backend}: {refusal(uses, note)}", file=sys.stderr)
        return EXIT_UNSUPPORTED

    def stopped(e: Stopped) -> None:
        """What did run written, and one line: for a Stopped raised, and for an engine that
        ends the process from inside a step (engine.engine_abort, ODE's assertions)."""
        kept = "no trace written"
        _tell(watchdog, ENDED)  # an engine abort writes from inside its step: no watchdog kills it half way
        if e.trace is not None:
            _write_trace(e.trace, args.trace)
            kept = f"the frames before it written to {args.trace or 'standard output'}"
        print(f"{args.scene}: {args.backend}: {e} ({kept})", file=sys.stderr)

    on_engine_abort(stopped)
    try:
        step_s, step_cpu_s, simulation_s, simulation_cpu_s = [], [], [], []
        with time_limit(args.timeout, watchdog):
            for k in range(args.repeat):  # repeats are timed; the trace is the first run's
                started, cpu = time.perf_counter(), time.process_time()
                clock = _StepClock(backend) if args.timing else None
                ran = run(ws, clock or backend, settings)
                simulation_s.append(time.perf_counter() - started)
                simulation_cpu_s.append(time.process_time() - cpu)
                step_s.append(clock.step_s if clock else 0.0)
                step_cpu_s.append(clock.step_cpu_s if clock else 0.0)
                if k == 0:
                    trace, accuracies = ran, clock.target_accuracy if clock else []
    except Unsupported as e:
        print(f"{args.scene}: unsupported by {args.backend}: {e}", file=sys.stderr)
        return EXIT_UNSUPPORTED
    except Stopped as e:  # blew up or timed out
        stopped(e)
        return EXIT_ERROR
    except Exception as e:  # the engine refused its model: still one line, never a traceback
        print(f"{args.scene}: {args.backend} failed: {type(e).__name__}: {e}", file=sys.stderr)
        return EXIT_ERROR
    _write_trace(trace, args.trace)
    if args.rerun:
        from reports.rerun_recording import write_recording  # rerun is imported when a recording is asked for
        write_recording(args.rerun, scene, [(args.backend, trace.view())])
    if args.timing:
        atomic.write_json(args.timing, {"simulation_wall_s": float(np.median(simulation_s)),
                                        "simulation_cpu_s": float(np.median(simulation_cpu_s)),
                                        "step_wall_s": float(np.median(step_s)),
                                        "step_cpu_s": float(np.median(step_cpu_s)),
                                        "target_accuracy": accuracies,
                                        "repeats": {"simulation_wall_s": simulation_s,
                                                    "simulation_cpu_s": simulation_cpu_s, "step_wall_s": step_s,
                                                    "step_cpu_s": step_cpu_s}},
                          indent=None)
    return EXIT_OK


@contextmanager
def _banner_silenced() -> Iterator[None]:
    """Standard output and error, at the file descriptors, sent nowhere while an engine is
    imported for its table: pybullet writes its build time to them from C on import, which is
    no line of the listing. (An error still says itself: as an exception, after.)"""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(1), os.dup(2)]
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, 1)
        os.dup2(devnull, 2)
        yield
    finally:
        for fd, copy in zip((1, 2), saved):
            os.dup2(copy, fd)
            os.close(copy)
        os.close(devnull)


def cmd_backends(args: argparse.Namespace) -> int:
    """Each backend as the probe finds it, in a child with a time limit (conformance/runner/probe.py):
    a plug-in that crashes or hangs on import, or cannot say its version, is listed as unavailable
    with why. The feature tables are read here, of the backends that imported well there."""
    from conformance.runner import children, probe  # not in every `x3drbp run` child
    for note in base.registry_notes():  # two entry points of one name
        print(f"x3drbp backends: note: {note}", file=sys.stderr)
    for name, info in probe.backend_table(args.timeout or children.DEFAULT_TIMEOUT).items():
        if not info.usable:
            print(f"{name}: unavailable: {info.unavailable}")
            continue
        print(f"{name} {info.version}")
        if args.features:
            try:
                with _banner_silenced():
                    table = base.load(name).table()
            except Exception as e:  # the plug-in's own code: one line, never a traceback
                print(f"  (no feature table: {type(e).__name__}: {e})")
                continue
            for feature, d in sorted(table.items()):
                print(f"  {feature}: {d.support.value}{' (' + d.note + ')' if d.note else ''}")
    return EXIT_OK


_REGISTERED = "{registered backends}"  # in --backend's help, their names once help is printed


class _Help(argparse.HelpFormatter):
    """`x3drbp run --help` naming the registered backends, read only when the help is printed:
    reading them (every installed package's entry points and metadata) cost each run 30 ms of
    CPU it does not need (base.entry finds x3drbp's own backends without them)."""

    def _get_help_string(self, action: argparse.Action) -> str | None:
        text = action.help
        return text.replace(_REGISTERED, ", ".join(base.engines())) if text and _REGISTERED in text else text


def add_command(sub) -> None:
    """`x3drbp run` and `x3drbp backends`."""
    r = sub.add_parser("run", help="run a scene on one backend and write its event trace", formatter_class=_Help)
    r.add_argument("scene")
    r.add_argument("--backend", required=True, help=f"one of {_REGISTERED} (the registered backends: "
                   "`x3drbp backends` says which are usable)")
    options.add_run_settings(r)
    r.add_argument("--timeout", type=float, metavar="S", help="stop the simulation after S seconds of wall "
                   "time (engine build and steps), keeping the frames before; exit 1 (default: no limit)")
    r.add_argument("--trace", help="write the trace CSV here (default: standard output); a name ending .npz "
                   "gets the same rows as NumPy arrays (x3d_core/traces/trace_npz.py), for programs to read fast")
    r.add_argument("--rerun", metavar="OUT.rrd", help="write a rerun recording of the run (open it with `rerun OUT.rrd`)")
    r.add_argument("--timing", metavar="FILE", help="write the simulation's wall time (plan, engine build, "
                   "steps, state readback; not the load or the trace writing) to FILE as JSON "
                   "{\"simulation_wall_s\": S, \"simulation_cpu_s\": ..., \"step_wall_s\": T, \"step_cpu_s\": ..., "
                   "\"target_accuracy\": [...], \"repeats\": {...}}, T the engine's steps alone, each also as the "
                   "process's CPU time, the medians of the repeats, each listed under repeats; target_accuracy per "
                   "world: its error-controlled integrator's target (null: stepped at the fixed step)")
    r.add_argument("--repeat", type=options.repeats, default=1, metavar="N",
                   help="run the simulation N times, for --timing's medians and spread (the trace, recording "
                   "and verdict are the first run's: a run is deterministic; default 1)")
    options.add_verbosity(r, "print no notes of what the backend approximates (errors, refusals and the "
                             "scene's warnings still print)",
                          "a note per approximated use (default: one per approximation, naming its uses)")
    r.set_defaults(func=cmd_run)
    b = sub.add_parser("backends", help="list the registered backends (entry point group x3drbp.backends), their "
                      "engine versions and declared features")
    b.add_argument("--features", action="store_true", help="print each backend's feature table")
    b.add_argument("--timeout", type=options.positive, metavar="S",
                   help="time limit in seconds for the probe to import a backend and ask its version (each "
                        "one that crashes or hangs costs one probe, at most S; default 60)")
    b.set_defaults(func=cmd_backends)

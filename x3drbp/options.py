"""What several commands parse the same way: lists of names, thresholds, run settings, a scene.

`x3drbp run` imports this module and uses only its run settings and scene loading, so what
the commands that run many children need (the comparison thresholds, the runner, the probe)
is imported by the functions that use it: a cold `x3drbp run` starts 40 ms sooner.
"""

from __future__ import annotations

import argparse
import math
import os
import re
import sys
from collections.abc import Callable, Sequence
from fractions import Fraction
from typing import TYPE_CHECKING, Any

from x3d_core.encodings.load import load
from x3d_core.files import atomic
from x3d_core.model.scene import LoadError, Scene

if TYPE_CHECKING:
    from conformance.results import BackendInfo


def names(values: list[str] | None) -> list[str]:
    """Comma- or space-separated names, the option possibly given several times."""
    out: list[str] = []
    for v in values or []:
        out.extend(n for n in v.replace(",", " ").split() if n)
    return list(dict.fromkeys(out))


def listed(values: list[str] | None) -> list[str]:
    """Comma-separated file names or case names, the option possibly given several times: a
    comma within a name written \\, (escaped()); blanks around a name dropped, those within kept."""
    out: list[str] = []
    for v in values or []:
        out.extend(n.strip().replace("\\,", ",") for n in re.split(r"(?<!\\),", v) if n.strip())
    return list(dict.fromkeys(out))


def escaped(name: str) -> str:
    """A name as listed() reads it back whole."""
    return name.replace(",", "\\,")


def thresholds_help() -> str:
    """--threshold's help: every kind, its unit and its default."""
    from conformance.analyses.compare import DEFAULT_THRESHOLDS, UNITS
    return ("divergence thresholds, comma-separated KIND=VALUE, of " + ", ".join(
        f"{k} ({UNITS[k]}, default {v:g})" for k, v in DEFAULT_THRESHOLDS.items()) + "; joint outputs are held to "
        "the kind of their unit")


def thresholds(values: list[str] | None) -> dict[str, float]:
    """KIND=VALUE items over the defaults; ValueError naming what is wrong."""
    from conformance.analyses.compare import DEFAULT_THRESHOLDS, UNITS
    out = dict(DEFAULT_THRESHOLDS)
    for item in names(values):
        kind, _, text = item.partition("=")
        if kind not in out:
            raise ValueError(f"unknown threshold {kind!r}; known: {', '.join(out)}")
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"threshold {kind} must be a positive number of {UNITS[kind]}, not {text!r}")
        out[kind] = value
    return out


# A run records at most this many frames and takes at most this many steps: past them a setting
# is a mistake (--frame-rate 1e9 wanted 7.7 GiB; --dt 1e-12 would step for days), said at once.
MAX_FRAMES = 10**6
MAX_STEPS = 10**9
MAX_REPEATS = 100  # timed runs of one point: a median and its spread need a few, 10^9 would run for ever


def settings_error(args: argparse.Namespace) -> str | None:
    """Why --duration, --dt and --frame-rate (and --timeout where the command has one) cannot
    run, in one line; None when they can (and args.dt in seconds: read_step)."""
    problem = read_step(args)
    if problem:
        return problem
    for name in ("duration", "frame_rate", "timeout"):
        value = getattr(args, name, 1.0)
        if value is not None and not (math.isfinite(value) and value > 0):
            return f"--{name.replace('_', '-')} must be a positive number, not {value:g}"
    too = too_long(args.duration, args.dt, args.frame_rate)
    return too and f"--duration {args.duration:g} at --dt {args.dt:g} and --frame-rate {args.frame_rate:g} makes {too}"


def too_long(duration: float, dt: float, frame_rate: float) -> str | None:
    """What a run of `duration` s at step dt, recording frame_rate frames a second, makes past
    MAX_FRAMES or MAX_STEPS ('N frames; a run records at most M'); None within them."""
    frames, steps = duration * frame_rate, duration / dt
    if frames > MAX_FRAMES:
        return f"{frames:.3g} frames; a run records at most {MAX_FRAMES:g}"
    if steps > MAX_STEPS:
        return f"{steps:.3g} steps; a run takes at most {MAX_STEPS:g}"
    return None


def given(values: list[str] | None, option: str, what: str) -> list[str]:
    """A list option's values (names()); ValueError where one giving of it names none:
    `--dts ,` is a mistake, not the default."""
    empty = [v for v in values or [] if not names([v])]
    if empty:
        raise ValueError(f"{option} names no {what}: {empty[0]!r}")
    return names(values)


def step(text: str, option: str = "--dt", what: str = "a positive step") -> float:
    """A physics step in seconds as typed, a fraction (1/240) or a decimal (0.004): the one
    reading of every --dt and --dts; ValueError naming the option and a value that is not a
    positive finite number (Fraction's own words were 'Fraction(1, 0)')."""
    try:
        dt = float(Fraction(text.strip()))
    except (ValueError, ZeroDivisionError, OverflowError):
        dt = math.nan
    if not (math.isfinite(dt) and dt > 0):
        raise ValueError(f"{option} must be {what} in seconds, as 1/240 or 0.004, not {text!r}")
    return dt


def read_step(args: argparse.Namespace) -> str | None:
    """Turns args.dt, kept as typed (argparse does not read it, so that a bad one is refused
    in the command's one line as every setting is, not in argparse's usage), into seconds;
    the one-line reason where it is no step. A default (a number, or None) stays as it is."""
    if isinstance(args.dt, str):
        try:
            args.dt = step(args.dt)
        except ValueError as e:
            return str(e)
    return None


def steps(values: list[str] | None) -> list[float]:
    """--dts: physics steps in seconds (step()), each once in the order given ([] where none
    is); ValueError naming one that is not a step (`--dts ,` ran as the default)."""
    return list(dict.fromkeys(step(v, "--dts", "positive steps") for v in given(values, "--dts", "step")))


def positive(text: str) -> float:
    """An argparse type: a positive finite number (a time limit, say)."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError(f"must be a positive number, not {text!r}")
    return value


def count(text: str) -> int:
    """An argparse type: a whole number of at least 1 (processes in parallel, say)."""
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be a whole number of at least 1, not {text!r}")
    return value


def repeats(text: str) -> int:
    """An argparse type: timed runs of one point, 1 to MAX_REPEATS."""
    value = count(text) if text.strip().isdigit() else 0
    if not 1 <= value <= MAX_REPEATS:
        raise argparse.ArgumentTypeError(f"must be a whole number from 1 to {MAX_REPEATS}, not {text!r}")
    return value


def add_run_settings(p: argparse.ArgumentParser) -> None:
    """--duration, --dt, --frame-rate: how a scene is run (`x3drbp run` and the commands that run it)."""
    p.add_argument("--duration", type=float, default=1.0, help="simulated seconds (default 1)")
    p.add_argument("--dt", default=1.0 / 240.0, metavar="S",
                   help="physics step in seconds, as 1/240 or 0.004 (default 1/240)")
    p.add_argument("--frame-rate", type=float, default=60.0, help="frames per second (default 60)")


def add_verbosity(p: argparse.ArgumentParser, quiet: str, verbose: str) -> None:
    """-q/--quiet and -v/--verbose, one or the other (options.verbosity reads them)."""
    g = p.add_mutually_exclusive_group()
    g.add_argument("-q", "--quiet", action="store_true", help=quiet)
    g.add_argument("-v", "--verbose", action="store_true", help=verbose)


def add_run_verbosity(p: argparse.ArgumentParser) -> None:
    """-q and -v of the commands that run a scene many times (compare, conformance, stability)."""
    add_verbosity(p, "no progress bar and no notes of what the backends approximate (errors and results "
                     "still print)",
                  "every run's notes, one per approximated use (default: each distinct note once, "
                  "after the runs)")


def verbosity(args: argparse.Namespace) -> int:
    """children.QUIET, DEFAULT or VERBOSE, from -q and -v."""
    from conformance.runner import children
    return children.VERBOSE if args.verbose else children.QUIET if args.quiet else children.DEFAULT


def progress(args: argparse.Namespace) -> bool:
    """Whether to draw a bar of runs done on stderr: for a person watching a terminal, never with -q."""
    from conformance.runner import children
    return children.progress_shown(args.quiet)


def load_scene(path: str) -> Scene | None:
    """The scene, or None after printing why it does not load to stderr: one line per
    error, never a traceback (commands that run a scene exit 1 then)."""
    scene, errors = scene_or_errors(path)
    for line in errors:
        print(line, file=sys.stderr)
    return scene


def scene_or_errors(path: str) -> tuple[Scene | None, list[str]]:
    """The scene, or None and why it does not load, a line per error (never a traceback)."""
    try:
        scene = load(path)
    except LoadError as e:
        return None, [str(d) for d in e.diagnostics]
    except Exception as e:  # a bug of ours, never the file's fault: still one line
        return None, [f"{path}:1:1: error: internal error while reading ({type(e).__name__}: {e}); please report it"]
    return (None if scene.errors else scene), [str(d) for d in scene.errors]


def add_matrix_options(p: argparse.ArgumentParser, verb: str, case_names: list[str], timeout: float) -> None:
    """--backends, --cases, --timeout, --jobs: the commands that run cases on backends."""
    p.add_argument("--backends", action="append", metavar="LIST",
                   help=f"backends to {verb}, comma-separated (default: every installed one)")
    p.add_argument("--cases", action="append", metavar="NAMES",
                   help=f"cases to {verb}, comma-separated (default: all: {', '.join(case_names)})")
    p.add_argument("--timeout", type=positive, default=timeout, metavar="S",
                   help=f"time limit per run in seconds (default {timeout:g})")
    p.add_argument("--jobs", type=count, default=None, metavar="N",
                   help="runs in parallel (default: the number of CPUs)")


def chosen(args: argparse.Namespace, select: Callable[[Sequence[str]], list[Any]]
           ) -> tuple[list[Any], dict[str, BackendInfo], list[str]]:
    """The cases --cases names (through `select`), the backends found here, and those
    --backends names (default: every usable one); ValueError with the one-line reason for a
    name either does not know."""
    try:
        cases = select(given(args.cases, "--cases", "case"))  # `--cases ,` a mistake, not every case
    except KeyError as e:
        raise ValueError(e.args[0]) from None
    from conformance.runner import probe
    return cases, *probe.chosen(given(args.backends, "--backends", "backend"), args.timeout)


def publish(out: str, name: str, text: str, data: dict) -> None:
    """DIR/NAME.md and DIR/NAME.json, each written whole; the markdown also to standard output."""
    os.makedirs(out, exist_ok=True)
    atomic.write_text(os.path.join(out, f"{name}.md"), text)
    atomic.write_json(os.path.join(out, f"{name}.json"), data)
    sys.stdout.write(text)
    print(f"\nwrote {os.path.join(out, name + '.md')} and {name}.json")

"""The x3drbp command line: one module per command, each adding its parser to `main`.

Only the module of the command asked for is imported (all of them for `x3drbp --help` or an
unknown command): `x3drbp run` is the child every other command starts hundreds of times,
and importing every command's analyses cost it 0.3 s of its 0.7 s start.
"""

from __future__ import annotations

import argparse
import importlib
import os
import select
import sys

# One BLAS thread unless the user says otherwise, set before numpy loads (and inherited by
# every child run): x3drbp's arrays are a few bodies wide, and numpy's OpenBLAS otherwise
# starts a thread per core that spins at start and exit: measured, 0.1 s of CPU of a 0.3 s
# `x3drbp run` of the pendulum on 2 cores, for no arithmetic that needs it.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from x3d_core.files.atomic import CannotWrite  # noqa: E402  (after the BLAS setting)
from x3d_core.files.paths import printable  # noqa: E402

# command -> the module under x3drbp whose add_command registers it (run's registers
# run and backends), in the order `x3drbp --help` lists them
COMMANDS = {"check": "check", "advise": "advise", "run": "run", "backends": "run", "compare": "compare",
            "conformance": "conformance", "expectations": "expectations", "stability": "stability",
            "sweep": "sweep", "report": "report", "validate": "validate", "x-ite": "x_ite"}

# the commands whose runs go through the run cache (conformance/runner/cache.py): each takes --no-cache
CACHED = ("advise", "compare", "conformance", "expectations", "report", "stability", "sweep", "validate")

EXIT_INTERRUPTED = 130
# standard output closed by its reader (`x3drbp run SCENE | head -1`): what a shell reports for
# a command killed by SIGPIPE, 128 + 13, as `git log | head` or `cat big | head` give; not 1,
# which says "error" (run) or "does not conform" (validate), and the reader went away by choice
EXIT_BROKEN_PIPE = 141
EXIT_CANNOT_WRITE = 1


def _stdout_gone() -> bool:
    """Whether standard output is a pipe whose reader has closed it (poll says POLLERR)."""
    try:
        fd = sys.stdout.fileno()
        p = select.poll()
        p.register(fd, select.POLLOUT)
        return any(ev & select.POLLERR for _, ev in p.poll(0))
    except (AttributeError, ValueError, OSError):
        return False


def _quiet_stdout() -> None:
    """Python's recipe (library/signal.html, note on SIGPIPE): standard output pointed at
    devnull, so that the interpreter's last flush at exit fails no more."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (AttributeError, ValueError, OSError):
        pass


def _say(line: str) -> None:
    """One line on stderr, as text: the path it names may hold a terminal escape or a newline."""
    try:
        print(printable(line), file=sys.stderr)
    except (OSError, ValueError):  # standard error closed too: the status says it
        pass


PYPROJECT = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "pyproject.toml")


def version() -> str:
    """x3drbp's version: the installed distribution's, else (a source tree run without
    installing) pyproject.toml's. (Imported here: `x3drbp run` starts faster without them.)"""
    import importlib.metadata
    import tomllib
    try:
        return importlib.metadata.version("x3drbp")
    except importlib.metadata.PackageNotFoundError:
        pass
    try:
        with open(PYPROJECT, "rb") as f:
            return str(tomllib.load(f)["project"]["version"])
    except (OSError, KeyError, tomllib.TOMLDecodeError) as e:
        return f"unknown (not installed, and {PYPROJECT} gives none: {type(e).__name__})"


class _Version(argparse.Action):
    """--version: `x3drbp VERSION` on stdout, exit 0; looked up only when asked (every `x3drbp
    run` child parses its options)."""

    def __init__(self, option_strings: list[str], dest: str = argparse.SUPPRESS) -> None:
        super().__init__(option_strings, dest, nargs=0, default=argparse.SUPPRESS,
                         help="print x3drbp's version and exit")

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace, values: object,
                 option_string: str | None = None) -> None:
        print(f"x3drbp {version()}")
        parser.exit()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="x3drbp", description="Conformance and comparison suite for the X3D RigidBodyPhysics component.")
    parser.add_argument("--version", action=_Version)
    sub = parser.add_subparsers(dest="command", required=True)
    for module in _modules(sys.argv[1:] if argv is None else argv):
        importlib.import_module(f"x3drbp.{module}").add_command(sub)
    for command in CACHED:
        if command in sub.choices:
            sub.choices[command].add_argument(
                "--no-cache", action="store_true",
                help="run every run afresh and keep none (default: reuse a run made before with the same scene "
                     "bytes, engine version, x3drbp source and settings; docs/commands/report.md)")
    parser.set_defaults(main=main)  # `x3drbp report` runs the other commands through it
    args = _parsed(parser, sub, argv)
    given = _resolve_outputs(args)
    args.given = {**given, **_resolve_scenes(args)}
    try:
        _check_outputs(args)
        status = _uncached(args) if getattr(args, "no_cache", False) else args.func(args)
        if sys.stdout is not None:
            sys.stdout.flush()  # here, where a reader gone is caught, not at exit
        return status
    except KeyboardInterrupt:
        return EXIT_INTERRUPTED
    except CannotWrite as e:  # an output file: its path, as given, and why
        _say(f"x3drbp {args.command}: cannot write {as_typed(e.path, given)}: {e.reason}")
        return EXIT_CANNOT_WRITE
    except BrokenPipeError as e:
        if _stdout_gone():
            _quiet_stdout()
            return EXIT_BROKEN_PIPE
        _say(f"x3drbp {args.command}: {_oserror(e, given)}")
        return EXIT_CANNOT_WRITE
    except OSError as e:  # the last resort: one line, never a traceback
        _say(f"x3drbp {args.command}: {_oserror(e, given)}")
        return EXIT_CANNOT_WRITE


def _uncached(args: argparse.Namespace) -> int:
    """The command with the run cache off (--no-cache), its steps' too where it runs others (report)."""
    from conformance.runner import cache  # here: an `x3drbp run` child never needs it
    with cache.turned_off(True):
        return args.func(args)


def _parsed(parser: argparse.ArgumentParser, sub: argparse._SubParsersAction, argv: list[str] | None
            ) -> argparse.Namespace:
    """The command line parsed; words the command does not know refused by the command's own
    parser (its usage, not x3drbp's), with the option meant where one is close."""
    args, extras = parser.parse_known_args(argv)
    if extras:
        command = sub.choices[args.command]
        command.error(f"unrecognized arguments: {' '.join(extras)}{_meant(command, extras)}")
    return args


def _meant(command: argparse.ArgumentParser, extras: list[str]) -> str:
    """'; did you mean --duration?' for each unknown option close to one the command has."""
    import difflib  # here: only a mistyped option needs it (every `x3drbp run` imported it)
    known = [o for action in command._actions for o in action.option_strings]
    meant = [close[0] for word in extras if word.startswith("-")
             for close in [difflib.get_close_matches(word.split("=", 1)[0], known, n=1)] if close]
    return "".join(f"; did you mean {m}?" for m in dict.fromkeys(meant))


def _modules(argv: list[str]) -> list[str]:
    """The command modules to register: the asked command's alone where argv names one."""
    asked = next((a for a in argv if not a.startswith("-")), None)
    return [COMMANDS[asked]] if asked in COMMANDS else list(dict.fromkeys(COMMANDS.values()))


# the options that name an output, file or folder (and the trace run and x-ite run write;
# validate's are read); expectations' --pins is read and written
OUTPUT_OPTIONS = ("out", "json", "rerun", "timing", "pins")


def _resolve_outputs(args: argparse.Namespace) -> dict[str, str]:
    """Every output path the command was given made absolute against the folder it was run
    in, before anything runs: a plug-in that changes directory (on import, in a build) moves
    no output. {absolute: as given}, for the messages that name one."""
    given = {}
    for name in OUTPUT_OPTIONS + (("trace",) if args.command in ("run", "x-ite") else ()):
        value = getattr(args, name, None)
        if isinstance(value, str) and value:
            setattr(args, name, os.path.abspath(value))
            given[getattr(args, name)] = value
    return given


def _check_outputs(args: argparse.Namespace) -> None:
    """CannotWrite for an output that cannot be written (a missing folder, a folder, a path
    under a file, read-only), before the command runs anything: it was said after every run,
    and where a command had two outputs, the first was left written (compare's --json where
    its --rerun could not be)."""
    from x3d_core.files import atomic
    for name in OUTPUT_OPTIONS + (("trace",) if args.command in ("run", "x-ite") else ()):
        value = getattr(args, name, None)
        if name != "pins" and isinstance(value, str) and value:  # pins: read as well, checked as read
            (atomic.check_folder if name == "out" else atomic.check)(value)


# the scenes a command reads and hands to children, which run in the project root: (command, option)
SCENE_OPTIONS = (("advise", "paths"), ("compare", "scene"), ("report", "scenes"))


def _resolve_scenes(args: argparse.Namespace) -> dict[str, str]:
    """The scene files and folders a command was given made absolute against the folder it
    was run in, before any child (run in the project root) is handed one. {absolute: as given},
    so that what the command prints names them as the user did (as_given)."""
    given = {}
    for command, name in SCENE_OPTIONS:
        value = getattr(args, name, None) if args.command == command else None
        if value is None:
            continue
        resolved = [os.path.abspath(v) for v in ([value] if isinstance(value, str) else value)]
        given.update(zip(resolved, [value] if isinstance(value, str) else value))
        setattr(args, name, resolved[0] if isinstance(value, str) else resolved)
    return given


def as_given(path: str, given: dict[str, str]) -> str | None:
    """An output's absolute path as the command line named it (or a file within a folder it
    named); None where it is none of them."""
    for full, value in given.items():
        if path == full:
            return value
        if path.startswith(os.path.join(full, "")):
            return os.path.join(value, path[len(os.path.join(full, "")):])
    return None


def as_typed(path: str, given: dict[str, str]) -> str:
    """A path as the command line named it (as_given), else as it is: how a message names it."""
    return as_given(path, given) or path


def _oserror(e: OSError, given: dict[str, str]) -> str:
    """One line for an OSError: `cannot write PATH: REASON` where PATH is an output the
    command was given (an --out folder that cannot be made, say), as given, else `PATH: REASON`."""
    reason = e.strerror or str(e) or type(e).__name__
    if not e.filename:
        return reason
    path = os.fsdecode(e.filename) if isinstance(e.filename, (str, bytes)) else str(e.filename)
    shown = as_given(os.path.abspath(path), given)
    return f"{path}: {reason}" if shown is None else f"cannot write {shown}: {reason}"

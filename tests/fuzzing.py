"""Loader fuzzing shared by tests/test_fuzz.py (bounded, in CI) and tests/fuzz_long.py (a
long run): seed files, mutations, and the one property every input must keep: load()
returns a scene or raises LoadError, within a time bound; anything else is a bug."""

from __future__ import annotations

import glob
import os
import random
import re
import signal
import time
from contextlib import contextmanager
from dataclasses import dataclass

from conftest import CASES, CORPUS, SCENES
from x3d_core.encodings.load import load
from x3d_core.model.scene import LoadError

SUFFIXES = (".x3d", ".x3dv", ".x3dj", ".wrl", ".json")
SEED_BYTES = 200_000  # bigger seeds make slow mutants without finding more
NUMBERS = (b"1e308", b"-1e308", b"NaN", b"nan", b"inf", b"-inf", b"-1", b"-0", b"0", b"1e-320",
           b"99999999999999999999999999", b"0x10", b"1e", b".", b"-", b"1" * 400)
_NUMBER = re.compile(rb"-?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?")
_TOKEN = re.compile(rb"[^\s<>{}\[\]\"',=]+|[<>{}\[\]\"',=]")


class Hung(Exception):
    """The input took longer than its time bound."""


@dataclass
class Finding:
    """An input that broke the property, and how."""
    path: str
    problem: str


def seeds() -> list[str]:
    """The corpus files and the bundled scenes, every encoding."""
    found = [p for root in (CORPUS, SCENES, CASES) for p in glob.glob(os.path.join(root, "**", "*"), recursive=True)
             if p.endswith(SUFFIXES) and os.path.getsize(p) <= SEED_BYTES]
    return sorted(found)


def mutate(data: bytes, rng: random.Random) -> bytes:
    """One to three random edits: byte flips, token deletions and duplications, numbers
    replaced by huge, NaN or negative ones, truncation."""
    for _ in range(rng.randint(1, 3)):
        if not data:
            return data
        kind = rng.randrange(6)
        if kind == 0:
            i = rng.randrange(len(data))
            data = data[:i] + bytes([data[i] ^ (1 << rng.randrange(8))]) + data[i + 1:]
        elif kind in (1, 2):
            tokens = list(_TOKEN.finditer(data))
            if tokens:
                m = rng.choice(tokens)
                middle = b"" if kind == 1 else m.group() * rng.choice((2, 3, 50))
                data = data[:m.start()] + middle + data[m.end():]
        elif kind == 3:
            numbers = list(_NUMBER.finditer(data))
            if numbers:
                m = rng.choice(numbers)
                data = data[:m.start()] + rng.choice(NUMBERS) + data[m.end():]
        elif kind == 4:
            data = data[:rng.randrange(len(data))]
        else:
            i, j = sorted(rng.randrange(len(data) + 1) for _ in range(2))
            data = data[:i] + data[i:j] * rng.choice((2, 10)) + data[j:]
    return data


@contextmanager
def time_bound(seconds: float):
    """Raise Hung in the main thread once the process has spent `seconds` of CPU: a loader
    that loops spends CPU, and a busy machine does not move the bound, as wall time would."""
    def alarm(signum, frame):
        raise Hung(f"no answer within {seconds:g} s of CPU")
    previous = signal.signal(signal.SIGPROF, alarm)
    signal.setitimer(signal.ITIMER_PROF, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGPROF, previous)


def check(path: str, seconds: float = 5.0) -> str | None:
    """None if load(path) keeps the property, else what went wrong (seconds: of CPU)."""
    started = time.process_time()
    try:
        with time_bound(seconds):
            load(path)
    except LoadError:
        pass
    except Hung as e:
        return str(e)
    except Exception as e:  # any other exception escaping load() is a loader bug
        return f"{type(e).__name__}: {e}"
    elapsed = time.process_time() - started
    return f"took {elapsed:.1f} s of CPU" if elapsed > seconds else None


def fuzz(folder: str, seed: int, count: int | None = None, until: float | None = None,
         seconds: float = 5.0) -> tuple[int, list[Finding]]:
    """Mutants of the seed files into folder, each checked: (inputs tried, findings), stopping
    after `count` inputs or at time.monotonic() `until`. Failing inputs stay in folder."""
    rng = random.Random(seed)
    originals = [(p, open(p, "rb").read()) for p in seeds()]
    findings, tried = [], 0
    while (count is None or tried < count) and (until is None or time.monotonic() < until):
        source, data = rng.choice(originals)
        path = os.path.join(folder, f"mutant-{seed}-{tried}{os.path.splitext(source)[1]}")
        with open(path, "wb") as f:
            f.write(mutate(data, rng))
        problem = check(path, seconds)
        if problem is None:
            os.unlink(path)
        else:
            findings.append(Finding(path, f"{problem} (a mutant of {source})"))
        tried += 1
    return tried, findings


# -- inputs at the limits: each a whole scene text in one encoding -------------------
def _numbers(n: int) -> str:
    return " ".join(["0.5 -1.25 3"] * (n // 3))


def huge_array(encoding: str, n: int) -> str:
    """A Coordinate whose point field (MFVec3f) holds n numbers."""
    if encoding == "xml":
        return (f"<X3D profile='Full' version='4.0'><Scene><Shape><IndexedFaceSet><Coordinate point='{_numbers(n)}'/>"
                "</IndexedFaceSet></Shape></Scene></X3D>")
    if encoding == "vrml":
        return f"#X3D V4.0 utf8\nPROFILE Full\nShape {{ geometry IndexedFaceSet {{ coord Coordinate {{ point [ {_numbers(n)} ] }} }} }}\n"
    points = ",".join(["0.5,-1.25,3"] * (n // 3))
    return ('{"X3D": {"@profile": "Full", "@version": "4.0", "Scene": {"-children": [{"Shape": {"-geometry": '
            f'{{"IndexedFaceSet": {{"-coord": {{"Coordinate": {{"@point": [{points}]}}}}}}}}}}}}]}}}}}}')


def deep(encoding: str, depth: int) -> str:
    """depth levels of Transform inside Group inside Transform ..."""
    kinds = ["Group", "Transform"]
    if encoding == "xml":
        opened = "".join(f"<{kinds[k % 2]}>" for k in range(depth))
        closed = "".join(f"</{kinds[k % 2]}>" for k in reversed(range(depth)))
        return f"<X3D profile='Full' version='4.0'><Scene>{opened}{closed}</Scene></X3D>"
    if encoding == "vrml":
        return "#X3D V4.0 utf8\nPROFILE Full\n" + "".join(f"{kinds[k % 2]} {{ children [ " for k in range(depth)) \
            + "] } " * depth + "\n"
    opened = "".join(f'{{"{kinds[k % 2]}": {{"-children": [' for k in range(depth))
    return '{"X3D": {"@profile": "Full", "@version": "4.0", "Scene": {"-children": [' + opened + "]}}" * depth + "]}}}"


def long_string(encoding: str, n: int) -> str:
    """A WorldInfo title, and a DEF name, of n characters."""
    title, name = "t" * n, "N" * n
    if encoding == "xml":
        return f"<X3D profile='Full' version='4.0'><Scene><WorldInfo DEF='{name}' title='{title}'/></Scene></X3D>"
    if encoding == "vrml":
        return f'#X3D V4.0 utf8\nPROFILE Full\nDEF {name} WorldInfo {{ title "{title}" }}\n'
    return ('{"X3D": {"@profile": "Full", "@version": "4.0", "Scene": {"-children": '
            f'[{{"WorldInfo": {{"@DEF": "{name}", "@title": "{title}"}}}}]}}}}}}')

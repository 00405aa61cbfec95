"""Which files on disk are scenes, and how a name from a file is shown on a line of output."""

from __future__ import annotations

import os

SCENE_EXTENSIONS = (".x3d", ".x3dv", ".x3dj")


def shown(path: str) -> str:
    """A file name as a line of output names it: as it is, or quoted with its escapes (Python's
    repr) where it holds a character that does not print (a newline would start a line of
    its own, one that could read `x.x3d: ok`; an undecodable byte would not encode)."""
    return path if path.isprintable() else repr(path)


def printable(text: str) -> str:
    """Text from a user's file (a DEF name, a value a message quotes) as text on a terminal:
    each character that does not print as its Python escape. An escape sequence in a DEF name
    (JSON's \\u001b, ClassicVRML's raw byte) recoloured or moved the terminal's cursor, and a
    newline split a diagnostic into two lines."""
    return text if text.isprintable() else "".join(c if c.isprintable() else repr(c)[1:-1] for c in text)


QUOTE_LIMIT = 80  # characters of a value a message quotes: a value of 10^4 numbers once made a 40 KB line


def clipped(shown: str, limit: int = QUOTE_LIMIT) -> str:
    """A value as a message shows it (its repr, its JSON), cut to its first `limit` characters
    where longer, saying how long it was."""
    return shown if len(shown) <= limit else f"{shown[:limit]}... ({len(shown):,} characters)"


def quoted(text: str, limit: int = QUOTE_LIMIT) -> str:
    """Text from a user's file quoted in a message (repr), at most `limit` characters of it."""
    return repr(text) if len(text) <= limit else f"{text[:limit]!r}... ({len(text):,} characters)"


def none_under(folders: list[str]) -> str:
    """What a command says where scene_files found nothing: the folders named, as text."""
    return f"no X3D files (.x3d, .x3dv, .x3dj) under {', '.join(map(shown, folders))}"


def scene_files(paths: list[str]) -> list[str]:
    """Files as given, folders searched (sorted, so every run sees the same order).

    Entries are chosen by name only, never opened: a named pipe or a device named like a
    scene is listed like any file, and load() refuses it in one line without reading (or
    blocking on) it, so `check` reports it as an error and goes on with the rest. Reported,
    not skipped: a folder whose scene-named entry could not be checked is not all ok."""
    out: list[str] = []
    for p in paths:
        if os.path.isdir(p):
            for root, dirs, files in os.walk(p):
                dirs.sort()
                out.extend(os.path.join(root, f) for f in sorted(files) if f.lower().endswith(SCENE_EXTENSIONS))
        else:
            out.append(p)
    return out

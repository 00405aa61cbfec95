"""Which files on disk are scenes."""

from __future__ import annotations

import os

SCENE_EXTENSIONS = (".x3d", ".x3dv", ".x3dj")


def scene_files(paths: list[str]) -> list[str]:
    """Files as given, folders searched (sorted, so every run sees the same order)."""
    out: list[str] = []
    for p in paths:
        if os.path.isdir(p):
            for root, dirs, files in os.walk(p):
                dirs.sort()
                out.extend(os.path.join(root, f) for f in sorted(files) if f.lower().endswith(SCENE_EXTENSIONS))
        else:
            out.append(p)
    return out

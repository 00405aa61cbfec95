"""Shared paths for the tests."""

from __future__ import annotations

import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.normpath(os.path.join(ROOT, "..", "shared"))
CORPUS = os.path.join(SHARED, "corpus")
UOM = os.path.join(SHARED, "reference", "X3dUnifiedObjectModel-4.0.xml")
SCENES = os.path.join(ROOT, "scenes")
CASES = os.path.join(ROOT, "conformance", "cases")  # a folder per conformance case


def case_scene(name: str) -> str:
    """The scene of conformance case NAME: conformance/cases/NAME/NAME.x3d."""
    return os.path.join(CASES, name, f"{name}.x3d")


# An expression for a child's code: its peak RSS in KiB since it started, from VmHWM, which a
# new program starts afresh. Not ru_maxrss: Linux carries that across fork and exec, so a child
# of a pytest process of 400 MB starts at 400 MB (a bound on growth then passes vacuously).
PEAK_KIB = "int(next(ln.split()[1] for ln in open('/proc/self/status') if ln.startswith('VmHWM:')))"

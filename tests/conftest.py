"""Shared paths for the tests."""

from __future__ import annotations

import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.normpath(os.path.join(ROOT, "..", "shared"))
CORPUS = os.path.join(SHARED, "corpus")
UOM = os.path.join(SHARED, "reference", "X3dUnifiedObjectModel-4.0.xml")
SCENES = os.path.join(ROOT, "scenes")

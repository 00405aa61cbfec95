"""The node model: X3D's field types (where a value is parsed and written), node types and their
fields (schema, from node_defs, the UOM and clause 37's own signatures by edition), units, and the
scene (nodes, routes, diagnostics) every encoding loads into."""

import importlib
import os
import warnings
from typing import Any


def __getattr__(name: str) -> Any:
    """x3d_core.model was the scene module before the wings (x3d_core/__init__.py): the names it
    defined still resolve here, with a DeprecationWarning naming x3d_core.model.scene. Any other
    name (a module of this wing not imported yet, say, or a private one) is no attribute, so that
    the import system goes on to import the module."""
    if name.startswith("_") or os.path.exists(os.path.join(os.path.dirname(__file__), f"{name}.py")):
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    scene = importlib.import_module("x3d_core.model.scene")
    found = getattr(scene, name, None)
    if getattr(found, "__module__", None) != scene.__name__:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    warnings.warn(f"x3d_core.model.{name} has moved to x3d_core.model.scene.{name}: import it from there",
                  DeprecationWarning, stacklevel=2)
    return found

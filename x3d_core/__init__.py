"""x3drbp's backend-neutral core, in five wings (docs/layout.md), each importing only those before
it: files (reading and writing files whole), model (fields, node types, the scene), traces,
semantics (worlds, collisions, the frame loop, joint outputs) and encodings (the loaders and
writers, and load()).

Until the wings, its modules sat in one folder, and engines written outside this tree import
them there (x3d_core.world's World, x3d_core.engine's Simulation). Those paths still work: an
old path imports the module now at its new one, under both names, with a DeprecationWarning
naming the new path. x3d_core.model, now the model wing, still gives the old module's names
(model/__init__.py).
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import importlib.util
import sys
import warnings
from types import ModuleType

MOVED = {  # the module's old path -> where it is now
    "x3d_core.analysis": "x3d_core.semantics.analysis",
    "x3d_core.applied": "x3d_core.semantics.applied",
    "x3d_core.atomic": "x3d_core.files.atomic",
    "x3d_core.build": "x3d_core.encodings.build",
    "x3d_core.clause37": "x3d_core.model.clause37",
    "x3d_core.clause37_nodes": "x3d_core.model.clause37_nodes",
    "x3d_core.collision": "x3d_core.semantics.collision",
    "x3d_core.documents": "x3d_core.files.documents",
    "x3d_core.editions": "x3d_core.model.editions",
    "x3d_core.engine": "x3d_core.semantics.engine",
    "x3d_core.evaluator": "x3d_core.semantics.evaluator",
    "x3d_core.fields": "x3d_core.model.fields",
    "x3d_core.inputs": "x3d_core.files.inputs",
    "x3d_core.integration": "x3d_core.semantics.integration",
    "x3d_core.joint_outputs": "x3d_core.semantics.joint_outputs",
    "x3d_core.json_loader": "x3d_core.encodings.json_loader",
    "x3d_core.line_index": "x3d_core.encodings.line_index",
    "x3d_core.load": "x3d_core.encodings.load",
    "x3d_core.model_diff": "x3d_core.encodings.model_diff",
    "x3d_core.node_defs": "x3d_core.model.node_defs",
    "x3d_core.outcome": "x3d_core.semantics.outcome",
    "x3d_core.paths": "x3d_core.files.paths",
    "x3d_core.planar": "x3d_core.semantics.planar",
    "x3d_core.rotation": "x3d_core.semantics.rotation",
    "x3d_core.schema": "x3d_core.model.schema",
    "x3d_core.standard_nodes": "x3d_core.model.standard_nodes",
    "x3d_core.trace": "x3d_core.traces.trace",
    "x3d_core.trace_npz": "x3d_core.traces.trace_npz",
    "x3d_core.trace_view": "x3d_core.traces.trace_view",
    "x3d_core.units": "x3d_core.model.units",
    "x3d_core.uom": "x3d_core.model.uom",
    "x3d_core.validate": "x3d_core.semantics.validate",
    "x3d_core.vrml_loader": "x3d_core.encodings.vrml_loader",
    "x3d_core.vrml_writer": "x3d_core.encodings.vrml_writer",
    "x3d_core.world": "x3d_core.semantics.world",
    "x3d_core.writer_common": "x3d_core.encodings.writer_common",
    "x3d_core.xml_loader": "x3d_core.encodings.xml_loader",
    "x3d_core.xml_writer": "x3d_core.encodings.xml_writer",
}


class _OldPaths(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds an old path (only once no file answers to it) as the module at its new one."""

    def find_spec(self, name: str, path: object = None, target: object = None) -> importlib.machinery.ModuleSpec | None:
        return importlib.util.spec_from_loader(name, self) if name in MOVED else None

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType:
        warnings.warn(f"{spec.name} has moved to {MOVED[spec.name]}: import it from there", DeprecationWarning,
                      stacklevel=2)
        return importlib.import_module(MOVED[spec.name])

    def exec_module(self, module: ModuleType) -> None:
        """Nothing to run: the module ran when it was imported at its new path."""


sys.meta_path.append(_OldPaths())

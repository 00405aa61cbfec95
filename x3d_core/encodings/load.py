"""Load a scene file in any of the three encodings into the model, validated."""

from __future__ import annotations

import gc
import os

from x3d_core.files.inputs import InputRefused, read_regular
from x3d_core.model.scene import Diagnostic, LoadError, Location, Scene
from x3d_core.semantics.validate import by_type, validate
from x3d_core.semantics.world import trace_names

ENCODINGS = {".x3d": "xml", ".xml": "xml", ".x3dv": "vrml", ".wrl": "vrml", ".x3dj": "json", ".json": "json"}
# A load peaks at ~4.2 bytes of memory per byte read (a 200 MB string in any encoding:
# 0.66-0.86 GB), so this bound keeps every load under 1 GiB; the largest real scenes
# (10^7 numbers) are ~100 MB
MAX_BYTES = 200 * 1024 * 1024


def sniff(path: str, head: bytes) -> str | None:
    """The encoding, from the file's first bytes, else from its extension."""
    text = head.lstrip(b"\xef\xbb\xbf \t\r\n")
    if text.startswith(b"#X3D") or text.startswith(b"#VRML"):
        return "vrml"
    if text.startswith(b"<"):
        return "xml"
    if text.startswith(b"{"):
        return "json"
    return ENCODINGS.get(os.path.splitext(path)[1].lower())


def load(path: str, check: bool = True) -> Scene:
    """The scene of a file. Raises LoadError when the file cannot be read at all; every
    other problem is a diagnostic in scene.diagnostics."""
    try:
        # a named pipe, a device or a folder is refused before a byte is read (a pipe would
        # block forever, /dev/zero never ends); a regular file larger than MAX_BYTES too
        source = read_regular(path, MAX_BYTES)
    except InputRefused as e:
        raise LoadError(Diagnostic("error", Location(path, 1, 1), "", str(e))) from None
    if not source.strip():
        raise LoadError(Diagnostic("error", Location(path, 1, 1), "", "empty file"))
    if b"\x00" in source[:1024] and not source.startswith((b"\xff\xfe", b"\xfe\xff")):
        raise LoadError(Diagnostic("error", Location(path, 1, 1), "", "binary data, not an X3D file"))
    encoding = sniff(path, source[:64])
    if encoding is None:
        raise LoadError(Diagnostic("error", Location(path, 1, 1), "",
                                   "not an X3D file: expected '<' (XML), '#X3D' (ClassicVRML) or '{' (JSON) "
                                   "at the start"))
    scene = Scene(path=path, encoding=encoding)
    if encoding == "xml":
        from .xml_loader import load_xml as read
    elif encoding == "vrml":
        from .vrml_loader import load_vrml as read
    else:
        from .json_loader import load_json as read
    gc_was_on = gc.isenabled()
    gc.disable()  # a load allocates many objects and frees none: collection passes only cost time
    try:
        read(path, source, scene)
    except LoadError as e:
        e.earlier = scene.diagnostics
        raise
    except RecursionError:
        raise LoadError(Diagnostic("error", Location(path, 1, 1), "",
                                   "nesting too deep to read (more levels than any scene needs)")) from None
    finally:
        if gc_was_on:
            gc.enable()
    if check:
        validate(scene, by_type(scene))
        _warn_derived_names(scene)
    return scene


def _warn_derived_names(scene: Scene) -> None:
    """Say which physics nodes go by a derived name in traces (a trace reader looks for DEFs)."""
    for node, name in trace_names(scene)[1]:
        if node.spec is not None and node.spec.component.startswith("RigidBodyPhysics"):
            why = (f"its DEF {node.def_name!r} is taken by another node" if node.def_name
                   else f"{name.rsplit('_', 1)[0]}_k names up to it are DEF names")
            scene.diagnostics.append(Diagnostic("warning", node.loc, node.label,
                                                f"goes by {name!r} in traces: {why}"))

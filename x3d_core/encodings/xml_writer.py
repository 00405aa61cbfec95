"""Write a scene in the X3D XML encoding."""

from __future__ import annotations

from lxml import etree

from x3d_core.model import fields as F
from x3d_core.model.scene import Node, Scene

from .writer_common import node_fields, node_names, raw_text, value_fields

_HEADER = b'<?xml version="1.0" encoding="UTF-8"?>\n'


def write_xml(scene: Scene) -> bytes:
    names = node_names(scene)
    root = etree.Element("X3D", profile=scene.profile, version=_version(scene))
    head = etree.SubElement(root, "head")
    for name, level in scene.components:
        etree.SubElement(head, "component", name=name, level=str(level))
    for name, content in scene.meta:
        etree.SubElement(head, "meta", name=name, content=content)
    body = etree.SubElement(root, "Scene")
    written: set[int] = set()
    for n in scene.roots:
        _node(body, n, None, names, written)
    for r in scene.routes:
        etree.SubElement(body, "ROUTE", fromNode=names[id(r.from_node)], fromField=r.from_field,
                         toNode=names[id(r.to_node)], toField=r.to_field)
    if not len(head):
        root.remove(head)
    return _HEADER + etree.tostring(root, pretty_print=True, encoding="UTF-8")


def _version(scene: Scene) -> str:
    return scene.version if scene.version[:1] in ("3", "4") else "3.0"


def _node(parent: etree._Element, node: Node, field: str | None, names: dict[int, str], written: set[int]) -> None:
    el = etree.SubElement(parent, node.type_name)
    name = names.get(id(node))
    default_container = node.spec.container_field if node.spec is not None else "children"
    if id(node) in written:
        el.set("USE", name)
        if field is not None and field != default_container:
            el.set("containerField", field)
        return
    written.add(id(node))
    if name:
        el.set("DEF", name)
    if field is not None and field != default_container:
        el.set("containerField", field)
    for fname, value, ftype in value_fields(node):
        el.set(fname, F.format_xml(ftype, value) if ftype is not None else raw_text(value, "xml"))
    for decl in node.interface:
        f = etree.SubElement(el, "field", name=decl.name, type=decl.type.name, accessType=decl.access)
        if decl.type.kind == "node":
            for child in (decl.value if isinstance(decl.value, list) else [decl.value]):
                if child is not None:
                    _node(f, child, None, names, written)
        elif decl.access in ("initializeOnly", "inputOutput"):
            f.set("value", F.format_xml(decl.type, decl.value))
    for fname, value, _ in node_fields(node):
        for child in (value if isinstance(value, list) else [value]):
            if child is not None:
                _node(el, child, fname, names, written)

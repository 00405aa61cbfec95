"""Write a scene in the ClassicVRML encoding."""

from __future__ import annotations

from x3d_core.model import fields as F
from x3d_core.model.scene import Node, Scene

from .writer_common import node_fields, node_names, raw_text, value_fields

_INDENT = "  "


def write_vrml(scene: Scene) -> bytes:
    names = node_names(scene)
    version = scene.version if scene.version[:1] in ("3", "4") else "3.0"
    out = [f"#X3D V{version} utf8", "", f"PROFILE {scene.profile}"]
    out += [f"COMPONENT {name}:{level}" for name, level in scene.components]
    out += [f"META {F._quote(name)} {F._quote(content)}" for name, content in scene.meta]
    out.append("")
    written: set[int] = set()
    for n in scene.roots:
        _node(out, n, "", "", names, written)
    for r in scene.routes:
        out.append(f"ROUTE {names[id(r.from_node)]}.{r.from_field} TO {names[id(r.to_node)]}.{r.to_field}")
    return ("\n".join(out) + "\n").encode("utf-8")


def _node(out: list[str], node: Node, lead: str, indent: str, names: dict[int, str], written: set[int]) -> None:
    name = names.get(id(node))
    if id(node) in written:
        out.append(f"{indent}{lead}USE {name}")
        return
    written.add(id(node))
    out.append(f"{indent}{lead}{f'DEF {name} ' if name else ''}{node.type_name} {{")
    inner = indent + _INDENT
    for fname, value, ftype in value_fields(node):
        text = F.format_vrml(ftype, value) if ftype is not None else raw_text(value, "vrml")
        out.append(f"{inner}{fname} {text}")
    for decl in node.interface:
        head = f"{inner}{decl.access} {decl.type.name} {decl.name}"
        if decl.access not in ("initializeOnly", "inputOutput"):
            out.append(head)
        elif decl.type.kind == "node":
            _nodes(out, head + " ", decl.value, decl.type.multi, inner, names, written)
        else:
            out.append(f"{head} {F.format_vrml(decl.type, decl.value)}")
    for fname, value, multi in node_fields(node):
        _nodes(out, f"{fname} ", value, multi, inner, names, written)
    out.append(f"{indent}}}")


def _nodes(out: list[str], lead: str, value, multi: bool, indent: str, names: dict[int, str],
           written: set[int]) -> None:
    if value is None or (isinstance(value, list) and not value):
        out.append(f"{indent}{lead}{'[]' if multi else 'NULL'}")
    elif isinstance(value, list):
        out.append(f"{indent}{lead}[")
        for child in value:
            _node(out, child, "", indent + _INDENT, names, written)
        out.append(f"{indent}]")
    else:
        _node(out, value, lead, indent, names, written)

"""What the XML and ClassicVRML writers share: names for shared nodes, and field order.

Writers write the model as it is: SI values (no UNIT statements), PROTO instances
expanded, pre-standard names in their standard spelling, and every other field as the
file spelt it (X3D 3.x's stopBounce1 in a 3.x file, even a 4.0 name it used instead). A node that is used more
than once or routed gets a DEF name, invented where the file had none.
"""

from __future__ import annotations

from typing import Any, Iterator

from x3d_core.model import fields as F
from x3d_core.model.scene import Node, Scene

from .build import RawValue


def node_names(scene: Scene) -> dict[int, str]:
    """A unique DEF name for every node that needs one (shared, routed, or named in the file)."""
    uses: dict[int, int] = {}
    order: list[Node] = []
    stack = list(reversed(scene.roots))
    while stack:
        n = stack.pop()
        uses[id(n)] = uses.get(id(n), 0) + 1
        if uses[id(n)] == 1:
            order.append(n)
            stack.extend(reversed(list(n.children())))
    routed = {id(r.from_node) for r in scene.routes} | {id(r.to_node) for r in scene.routes}
    taken: set[str] = set()
    names: dict[int, str] = {}
    for n in order:
        if n.def_name is None and uses[id(n)] < 2 and id(n) not in routed:
            continue
        base = n.def_name or f"_{n.type_name}"
        name, k = base, 1
        while name in taken:
            k += 1
            name = f"{base}_{k}"
        taken.add(name)
        names[id(n)] = name
    return names


def value_fields(node: Node) -> Iterator[tuple[str, Any, F.FieldType | None]]:
    """Fields that hold values, not nodes, in definition order: (name as the file spells it, value,
    type or None if raw)."""
    if node.spec is not None:
        for name, fd in node.spec.fields.items():
            if name in node.values and fd.type.kind != "node":
                yield node.spelling(name), node.values[name], fd.type
    else:
        for name, v in node.values.items():
            if isinstance(v, RawValue):
                yield name, v, None


def node_fields(node: Node) -> Iterator[tuple[str, list[Node] | Node | None, bool]]:
    """Fields that hold nodes: (name as the file spells it, value, multi)."""
    if node.spec is not None:
        for name, fd in node.spec.fields.items():
            if name in node.values and fd.type.kind == "node":
                yield node.spelling(name), node.values[name], fd.type.multi
    else:
        for name, v in node.values.items():
            if isinstance(v, (list, Node)) or v is None:
                yield name, v, True


def raw_text(v: RawValue, target: str) -> str:
    """A raw field's text in the target encoding; XML and ClassicVRML differ only in
    brackets around lists and the quotes of a single string."""
    if v.encoding == "json":
        data = v.data if isinstance(v.data, list) else [v.data]
        out = []
        for x in data:
            if isinstance(x, bool):
                out.append(("TRUE" if x else "FALSE") if target == "vrml" else ("true" if x else "false"))
            elif isinstance(x, str):
                out.append(F._quote(x) if target == "vrml" or isinstance(v.data, list) else x)
            else:
                out.append(F._num(x) if isinstance(x, float) else str(x))
        text = " ".join(out)
        return f"[ {text} ]" if target == "vrml" and isinstance(v.data, list) else text
    text = str(v.data)
    if v.encoding == target:
        return text
    t = text.strip()
    if target == "xml":
        if t.startswith("[") and t.endswith("]"):
            t = t[1:-1].strip()
        return " ".join(_BOOL_XML.get(tok, tok) for tok in t.split(" ")) if _is_plain(t) else t
    if t.startswith('"'):
        return t
    if _is_plain(t):
        t = " ".join(_BOOL_VRML.get(tok, tok) for tok in t.split(" "))
        return f"[ {t} ]" if " " in t else t
    return F._quote(text)


_BOOL_VRML = {"true": "TRUE", "false": "FALSE"}
_BOOL_XML = {"TRUE": "true", "FALSE": "false"}


def _is_plain(t: str) -> bool:
    """Numbers or booleans only: the same text in both encodings."""
    for tok in t.replace(",", " ").split():
        if tok in ("true", "false", "TRUE", "FALSE"):
            continue
        try:
            float(tok)
        except ValueError:
            return False
    return bool(t)

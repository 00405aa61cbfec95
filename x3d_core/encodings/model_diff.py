"""Where two scenes differ, node by node: the round-trip check of the writers."""

from __future__ import annotations

from x3d_core.model import fields as F
from x3d_core.model.scene import Node, Scene

from .build import RawValue


def differences(a: Scene, b: Scene, limit: int = 20) -> list[str]:
    """Differences in structure (DEF/USE sharing included), field values, routes and header."""
    out: list[str] = []
    pairs: dict[int, int] = {}

    def diff(x: Node | None, y: Node | None, where: str) -> None:
        if len(out) >= limit:
            return
        if x is None or y is None:
            if x is not y:
                out.append(f"{where}: {x!r} != {y!r}")
            return
        if id(x) in pairs:
            if pairs[id(x)] != id(y):
                out.append(f"{where}: shared node {x.label} is not shared the same way")
            return
        pairs[id(x)] = id(y)
        if x.type_name != y.type_name:
            out.append(f"{where}: {x.type_name} != {y.type_name}")
            return
        here = f"{where}/{x.label}"
        if x.spec is not None:
            for name, fd in x.spec.fields.items():
                if not fd.readable:
                    continue
                vx, vy = x.get(name), y.get(name)
                if fd.type.kind == "node":
                    if fd.type.multi:
                        if len(vx) != len(vy):
                            out.append(f"{here}.{name}: {len(vx)} nodes != {len(vy)}")
                            continue
                        for i, (cx, cy) in enumerate(zip(vx, vy)):
                            diff(cx, cy, f"{here}.{name}[{i}]")
                    else:
                        diff(vx, vy, f"{here}.{name}")
                elif not F.values_equal(fd.type, vx, vy):
                    out.append(f"{here}.{name}: {vx!r} != {vy!r}")
        else:
            kx, ky = set(x.values), set(y.values)
            if kx != ky:
                out.append(f"{here}: fields {sorted(kx ^ ky)} differ")
            for name in sorted(kx & ky):
                vx, vy = x.values[name], y.values[name]
                if isinstance(vx, RawValue) and isinstance(vy, RawValue):
                    if vx.data != vy.data:
                        out.append(f"{here}.{name}: {vx.data!r} != {vy.data!r}")
                else:
                    lx = vx if isinstance(vx, list) else [vx]
                    ly = vy if isinstance(vy, list) else [vy]
                    if len(lx) != len(ly):
                        out.append(f"{here}.{name}: {len(lx)} nodes != {len(ly)}")
                        continue
                    for i, (cx, cy) in enumerate(zip(lx, ly)):
                        diff(cx, cy, f"{here}.{name}[{i}]")
        if [(d.name, d.type.name, d.access) for d in x.interface] != \
                [(d.name, d.type.name, d.access) for d in y.interface]:
            out.append(f"{here}: declared interface differs")

    if len(a.roots) != len(b.roots):
        out.append(f"{len(a.roots)} root nodes != {len(b.roots)}")
    for i, (x, y) in enumerate(zip(a.roots, b.roots)):
        diff(x, y, f"[{i}]")
    if len(a.routes) != len(b.routes):
        out.append(f"{len(a.routes)} routes != {len(b.routes)}")
    for ra, rb in zip(a.routes, b.routes):
        if (pairs.get(id(ra.from_node)), ra.from_field, pairs.get(id(ra.to_node)), ra.to_field) != \
                (id(rb.from_node), rb.from_field, id(rb.to_node), rb.to_field):
            out.append(f"ROUTE {ra.from_field} -> {ra.to_field} differs")
    if a.components != b.components:
        out.append(f"components {a.components} != {b.components}")
    return out[:limit]

"""appliedParameters: the two spellings real files use, read as one set of names."""

from __future__ import annotations

# X3D 3.x/4.0 spell these with a hyphen, X3D 4.1 with an underscore; the model reads both.
CANONICAL = ("BOUNCE", "USER_FRICTION", "FRICTION_COEFFICIENT-2", "ERROR_REDUCTION", "CONSTANT_FORCE",
             "SPEED-1", "SPEED-2", "SLIP-1", "SLIP-2")
_SPELLINGS = {name: name for name in CANONICAL} | {
    name.replace("-", "_"): name for name in CANONICAL if "-" in name}


def canonical(value: str) -> str | None:
    """The X3D 4.0 name of an appliedParameters value, None if it is not one."""
    return _SPELLINGS.get(value)


def applied(values: list[str]) -> frozenset[str]:
    return frozenset(c for c in map(canonical, values) if c is not None)

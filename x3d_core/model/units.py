"""UNIT statements: the model holds SI values, whatever units a file declares."""

from __future__ import annotations

import math

BASE_CATEGORIES = ("angle", "force", "length", "mass")

# Each unit a field may carry, as exponents of the base categories (time is always seconds).
DERIVED: dict[str, dict[str, int]] = {
    "angle": {"angle": 1},
    "force": {"force": 1},
    "length": {"length": 1},
    "mass": {"mass": 1},
    "speed": {"length": 1},
    "acceleration": {"length": 1},
    "angular_rate": {"angle": 1},
    "torque": {"force": 1, "length": 1},
    "inertia": {"mass": 1, "length": 2},
}


def factor(unit: str | None, scene_units: dict[str, float]) -> float:
    """The number that turns a value in the file's units into SI."""
    if unit is None or not scene_units:
        return 1.0
    f = 1.0
    for category, power in DERIVED[unit].items():
        try:
            f *= scene_units.get(category, 1.0) ** power
        except OverflowError:  # (1e200 m)^2: the values it scales are refused as not finite
            return math.inf
    return f

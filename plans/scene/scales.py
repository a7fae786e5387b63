"""Reader of ``[scales]``: the drawing scales μl (m/mm), μv (m/s per mm) and μa (m/s² per mm)
the scene fixes; the rest are chosen when drawing.

Imports only plans.errors and modules of plans.scene (and the standard library).
"""

from __future__ import annotations

from typing import Any, Mapping

from ..errors import SceneError
from .checks import number


def read_scales(table: Mapping[str, Any]) -> dict[str, float]:
    """``[scales]``: mu_l, mu_v, mu_a as given (positive); the others are chosen when drawing."""
    allowed = ("mu_l", "mu_v", "mu_a")
    out = {}
    for key, value in table.items():
        if key not in allowed:
            raise SceneError(f"unknown scale {key!r}; use mu_l, mu_v or mu_a", key=f"scales.{key}")
        out[key] = number(value, f"scales.{key}", positive=True)
    return out

"""Reader of ``[scales]``: the drawing scales μl (m/mm), μv (m/s per mm) and μa (m/s² per mm)
the scene fixes; the rest are chosen when drawing. A scene of gears alone takes none.

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


def refuse_scales(table: Mapping[str, Any]) -> None:
    """``[scales]`` of a scene of gears alone: each scale is checked as :func:`read_scales` does, then
    refused, since the gear sheets choose their own (the train's μl, μV and h from the standard
    series, the pair's enlargement k:1) and would ignore it. An empty table passes."""
    read_scales(table)
    if table:
        key = sorted(table)[0]
        raise SceneError(f"a scene of gears alone chooses its own scales (the train's sheet: μl, μV and h from the "
                         f"standard series; the involute pair: its enlargement k:1), so {key} would be ignored; "
                         "remove it ([scales] scales a linkage's scheme and plans)", key=f"scales.{key}")

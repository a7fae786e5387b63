"""The involute pair's report (``gear_pair`` in the JSON) and its sheets (``-meshing``,
``-cutting``) when drawn.

Reads an analysed pair; imports nothing of the pipeline."""

from __future__ import annotations

import math
from typing import Any

from ...drawing import Style
from ...gears.pair import PairAnalysis
from ...scene import Scene

__all__ = ["pair_report", "pair_sheets"]


def pair_report(a: PairAnalysis) -> dict[str, Any]:
    """The JSON ``gear_pair``: lengths in mm, angles in degrees, per wheel [wheel 1, wheel 2]."""
    p = a.pair
    two = lambda t: [float(v) for v in t]          # noqa: E731
    return {"wheels": list(a.names), "z": list(p.z), "module": p.module, "pressure_angle": math.degrees(p.alpha),
            "addendum": p.addendum, "clearance": p.clearance, "tip_radius": a.tip_radius, "shift_rule": a.rule,
            "x1": p.x[0], "x2": p.x[1], "x_min": two(p.x_min), "undercut": list(p.undercut),
            "working_pressure_angle": math.degrees(p.alpha_w), "reference_centre_distance": p.a,
            "centre_distance": p.a_w, "y": p.y, "delta_y": p.delta_y,
            "d": two(p.d), "db": two(p.db), "dw": two(p.dw), "da": two(p.da), "df": two(p.df),
            "p": p.p, "pb": p.pb, "s": two(p.s), "sa": two(p.sa),
            "line_of_action": p.line, "active_length": p.active, "contact_ratio": p.contact_ratio,
            "specific_sliding": {"wheel1_at_B2": _finite(p.sliding[0]), "wheel2_at_B1": _finite(p.sliding[1])}}


def _finite(v: float) -> float | None:
    """None where the active line reaches past N (interference): the sliding is not defined."""
    return float(v) if math.isfinite(v) else None


def pair_sheets(scene: Scene, a: PairAnalysis, stem: str, style: Style) -> dict[str, str]:
    """The meshing and cutting sheets the scene draws (file name → SVG)."""
    return {}

"""Checking the areas of a turning-moment diagram (``<g data-plan="turning">``, written by
:mod:`plans.drawing.turning`): each ``<path data-area data-value>`` is a closed outline whose
area in paper mm² × ``data-mu-t`` (N·m/mm) × ``data-mu-theta`` (rad/mm) must equal its value (J),
signs aside, within what the rounding of its written points allows: each of the n points moved by
at most √2·precision changes the area by at most perimeter × √2·precision (+ 1e-9 relative).

Part of :mod:`plans.checking`; imports only the standard library and its own siblings."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

from .checking_read import _path_points
from .checking_report import Check, SvgReport

__all__ = ["area_checks", "TURNING"]

TURNING = "turning"
_SVG = "{http://www.w3.org/2000/svg}"


def area_checks(report: SvgReport, root: ET.Element, precision: float) -> None:
    """Add a check per area of every turning-moment diagram in ``root``."""
    for g in root.iter(f"{_SVG}g"):
        if g.get("data-plan") != TURNING:
            continue
        gid = g.get("id") or TURNING
        try:
            mu_t, mu_th = float(g.get("data-mu-t")), float(g.get("data-mu-theta"))
        except (TypeError, ValueError):
            report.problems.append(f"plan {gid}: data-mu-t and data-mu-theta must be numbers")
            continue
        for el in g.iter(f"{_SVG}path"):
            if el.get("data-area") is None:
                continue
            pts = _path_points(el.get("d"))
            try:
                value = float(el.get("data-value"))
            except (TypeError, ValueError):
                value = math.nan
            if len(pts) < 3 or not math.isfinite(value):
                report.problems.append(f"plan {gid}: area {el.get('data-area')}: no outline or value to measure")
                continue
            area = 0.5 * abs(sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(pts, pts[1:] + pts[:1])))
            perimeter = sum(math.dist(p, q) for p, q in zip(pts, pts[1:] + pts[:1]))
            scale = mu_t * mu_th
            check = Check(gid, f"area A{el.get('data-area')} drawn × μT·μθ against its energy", abs(area * scale - abs(value)),
                          perimeter * math.sqrt(2.0) * precision * scale + 1e-9 * abs(value), "J")
            report.checks.append(check)
            if not check.ok:
                report.problems.append(f"plan {gid}: {check.what}: {check.deviation:.3g} J (tolerance "
                                       f"{check.tolerance:.2g} J)")
            report.equations[gid] = report.equations.get(gid, 0) + 1

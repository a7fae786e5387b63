"""Koshel's uncertain-scale plan fitted to its sheet.

Koshel draws the first velocity of a class III group to an arbitrary length and finds the
scale afterwards, so the length is the draughtsman's to choose: :func:`fit_segment` chooses
it from the series 1, 1.5, 2, 2.5, 3, 4, 5, 6, 8 × 10^k mm, as long as possible up to
UNCERTAIN_MM, so that the whole plan is at most KOSHEL_MAX_MM wide and high.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from .plans import EXTENSION_MM, UNCERTAIN_MM, ConstructionLine, Plan, PlanPoint

__all__ = ["fit_segment", "KOSHEL_MAX_MM", "NICE_MM"]

#: Largest width or height of Koshel's plan, mm (it shares an A4 sheet with its notes).
KOSHEL_MAX_MM = 150.0
#: Mantissas of the arbitrary segment's length, mm.
NICE_MM = (1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0)


def _extent(plan: Plan) -> float:
    pts = np.array([p.xy for p in plan.points] + [v.tail for v in plan.vectors] + [v.head for v in plan.vectors])
    return float(np.max(pts.max(axis=0) - pts.min(axis=0)))


def _nice_below(x: float) -> float:
    """The largest series length ≤ x (mm)."""
    k = math.floor(math.log10(x))
    return max(float(f"{m:g}e{e}") for e in (k - 1, k) for m in NICE_MM if float(f"{m:g}e{e}") <= x)


def fit_segment(plan: Plan, segment_mm: float = UNCERTAIN_MM, limit: float = KOSHEL_MAX_MM) -> tuple[Plan, float]:
    """Koshel's ``plan`` drawn with its arbitrary first segment ``segment_mm`` long, redrawn
    with the longest series segment ≤ segment_mm that keeps it within ``limit`` mm; returns
    the plan and the segment's length (mm). The scale K_V = μ grows as the plan shrinks, so
    every vector still measures its exact value; construction lines keep their EXTENSION_MM
    overrun past the images."""
    extent = _extent(plan)
    if extent <= limit:
        return plan, segment_mm
    seg = _nice_below(segment_mm * limit / extent)
    f = seg / segment_mm

    def s(p) -> tuple[float, float]:
        return (float(p[0]) * f, float(p[1]) * f)

    lines = []
    for l in plan.lines:
        a, b = np.array(s(l.start)), np.array(s(l.end))
        u = (b - a) / (np.linalg.norm(b - a) or 1.0)
        grow = EXTENSION_MM * (1.0 - f)
        lines.append(ConstructionLine(tuple(map(float, a - grow * u)), tuple(map(float, b + grow * u)), l.quantity,
                                      l.group))
    return replace(plan, mu=plan.mu / f, points=tuple(PlanPoint(p.label, s(p.xy)) for p in plan.points),
                   vectors=tuple(replace(v, tail=s(v.tail), head=s(v.head)) for v in plan.vectors),
                   lines=tuple(lines)), seg

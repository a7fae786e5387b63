"""Measuring drawings: every tagged vector of an SVG, and every construction with shapely.

``check_svg`` reads an SVG back (ElementTree), measures each ``<line data-quantity>`` in
millimetres, multiplies by its plan's ``data-mu`` and compares with ``data-value``. The
tolerance is the drawing's precision: two rounded end points (``data-precision`` mm each
coordinate) plus 1e-9 relative.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

from shapely.geometry import LineString, Point

from .constructions.plans import Plan
from .errors import DrawingError

__all__ = ["Measurement", "check_svg", "check_plan", "GEOMETRY_TOL_MM"]

_SVG = "{http://www.w3.org/2000/svg}"
#: Largest distance (mm) between a plan image and the construction lines it must lie on.
GEOMETRY_TOL_MM = 1e-6


@dataclass(frozen=True)
class Measurement:
    """One measured vector: drawn length (mm) × μ against the exact value (SI)."""

    quantity: str
    plan: str
    length_mm: float
    mu: float
    value: float
    tolerance: float

    @property
    def measured(self) -> float:
        return self.length_mm * self.mu

    @property
    def error(self) -> float:
        return abs(self.measured - self.value)

    @property
    def ok(self) -> bool:
        return self.error <= self.tolerance


def check_svg(path: str | Path) -> list[Measurement]:
    """Measure every tagged vector of the SVG at ``path``."""
    path = Path(path)
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as exc:
        raise DrawingError(f"{path}: cannot read the SVG ({exc})") from None
    try:
        precision = float(root.get("data-precision", "0.0005"))
    except ValueError:
        raise DrawingError(f"{path}: data-precision is not a number") from None
    out = []
    for g in root.iter(f"{_SVG}g"):
        if g.get("data-mu") is None:
            continue
        try:
            mu = float(g.get("data-mu"))
        except ValueError:
            raise DrawingError(f"{path}: group {g.get('id')} has a non-numeric data-mu") from None
        for line in g.iter(f"{_SVG}line"):
            q = line.get("data-quantity")
            if q is None:
                continue
            try:
                x1, y1, x2, y2 = (float(line.get(k)) for k in ("x1", "y1", "x2", "y2"))
                value = float(line.get("data-value"))
            except (TypeError, ValueError):
                raise DrawingError(f"{path}: line {line.get('id')} ({q}) lacks coordinates or data-value") from None
            if line.get("transform") or g.get("transform"):
                raise DrawingError(f"{path}: line {q} is transformed; plan elements must not be")
            length = math.hypot(x2 - x1, y2 - y1)
            tol = mu * 2.0 * math.sqrt(2.0) * precision + 1e-9 * abs(value)
            out.append(Measurement(q, g.get("data-plan", ""), length, mu, value, tol))
    return out


def check_plan(plan: Plan, tol: float = GEOMETRY_TOL_MM) -> list[str]:
    """Geometric checks of a constructed plan with shapely; returns the failures (empty = good).

    - every vector lies on the construction line of its direction (⊥ link, ∥ guide);
    - the two construction lines of each group meet at an image of the plan;
    - the images of every link with three or more points form a figure similar to it.
    """
    failures = []
    vectors = {v.quantity: v for v in plan.vectors}
    for line in plan.lines:
        geom = LineString([line.start, line.end])
        v = vectors.get(line.quantity)
        if v is not None:
            for end in (v.tail, v.head):
                if geom.distance(Point(end)) > tol:
                    failures.append(f"{line.quantity}: end {end} is {geom.distance(Point(end)):.3g} mm off its line")
    by_group: dict[str, list[LineString]] = {}
    for line in plan.lines:
        by_group.setdefault(line.group, []).append(LineString([line.start, line.end]))
    images = [Point(p.xy) for p in plan.points]
    for group, lines in by_group.items():
        if len(lines) != 2 or group == "I":
            continue
        meet = lines[0].intersection(lines[1])
        if meet.is_empty or meet.geom_type != "Point":
            failures.append(f"group {group}: construction lines do not meet in one point")
        elif min(meet.distance(p) for p in images) > tol:
            failures.append(f"group {group}: construction lines meet {min(meet.distance(p) for p in images):.3g} mm "
                            "from every image")
    return failures


def similarity_ratio(figure: list[tuple[float, float]], image: list[tuple[float, float]]) -> float:
    """Largest relative deviation of the side ratios image/figure from their mean (0 = similar)."""
    sides = []
    for poly in (figure, image):
        sides.append([math.dist(poly[i], poly[j]) for i in range(len(poly)) for j in range(i + 1, len(poly))])
    ratios = [b / a for a, b in zip(*sides) if a > 0]
    mean = sum(ratios) / len(ratios)
    return max(abs(r - mean) for r in ratios) / mean if mean > 0 else 0.0

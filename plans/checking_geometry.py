"""Geometric checks of a constructed plan with shapely (:func:`check_plan`: every vector on its
construction line, each group's lines meeting at an image) and the similarity of a link's
figure and its image (:func:`similarity_ratio`). Paper mm.

Part of :mod:`plans.checking`, which re-exports these names. Knows the constructions'
:class:`~plans.constructions.plans.Plan`; must not import anything above the constructions.
"""

from __future__ import annotations

import math

from shapely.geometry import LineString, Point

from .constructions.plans import Plan

__all__ = ["GEOMETRY_TOL_MM", "check_plan", "similarity_ratio"]

#: Largest distance (mm) between a plan image and the construction lines it must lie on.
GEOMETRY_TOL_MM = 1e-6


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

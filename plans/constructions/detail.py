"""The enlarged detail of a plan's pole region, when images crowd the pole.

A plan is scaled by its largest vector, so images of slow points (or small components) may
gather within a few millimetres of the pole, their letters crowding. :func:`pole_detail`
finds such a crowd (:func:`pole_crowd`: two or more images, not at the pole itself, within
:data:`NEAR_MM` of it), enlarges the region round the pole × k (k from :data:`FACTORS`, the
largest that keeps the enlarged crowd within :data:`DETAIL_MM` of its pole; none when even
that leaves it under :data:`DETAIL_MIN_MM`) and redraws the vectors that lie wholly inside the
region at μ/k (none there: no detail): the detail is a :class:`Plan` of its own (same kind,
μ/k), so every vector measures its value there too and its vector equations close.

Where the detail goes: beside the plan, at the free spot (no vector, construction line or
image within :data:`CLEAR_MM`) that keeps the plan and the detail in the smallest box that
still fits one of the sizes the caller allows (a sheet's drawing area). Everything here is
geometry in plan millimetres (y up, the main plan's pole at the origin); it draws nothing.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, replace
from typing import Callable

import numpy as np
import shapely

from .plan_values import ConstructionLine, Plan, PlanPoint
from .. import linalg as la
from ..spatial import PointGrid, PointRaster, pieces, samples

__all__ = ["PoleRegion", "PlanDetail", "pole_crowd", "enlargeable", "pole_detail", "NEAR_MM", "DETAIL_MM",
           "DETAIL_MIN_MM", "FACTORS", "CLEAR_MM"]

#: Images closer to the pole than this crowd it, mm.
NEAR_MM = 5.0
#: An image closer to the pole than this is at the pole (a fixed point's image, one label with it), mm.
AT_POLE_MM = 1e-6
#: The enlarged crowd's largest distance from the detail's pole, mm (at most).
DETAIL_MM = 60.0
#: … and at least this, else the crowd stays as it is (images within a hundredth of a millimetre
#: share one letter on the plan, as coinciding), mm.
DETAIL_MIN_MM = 10.0
#: Round enlargement factors, tried largest first.
FACTORS = (1000, 500, 200, 100, 50, 20, 10, 5, 2)
#: The detail's frame (a circle) runs this far beyond its farthest image, as a part of that distance.
FRAME_GROW = 0.2
#: … and at least this far, mm (room for the images' letters inside the frame).
FRAME_ROOM_MM = 6.0
#: The circle marking the region on the plan: radius at least, mm.
REGION_MIN_MM = 1.5
#: Free space between the detail (frame, caption) and the plan's lines and images, mm.
CLEAR_MM = 8.0
#: Gap between the frame and its caption, mm.
CAPTION_GAP_MM = 1.5
#: Step of the grid of places tried for the detail, mm.
STEP_MM = 2.5
#: Places tried at once (in order of preference) for the detail's spot.
_CHUNK = 256
#: Longest piece of a segment in the index of the ink, mm.
_PIECE_MM = 10.0
#: Spacing of the ink's sample points, mm; cell of their raster, mm; and how far a box is
#: grown to be taken at once when it holds one (5 · √2 = 7.07 mm < CLEAR_MM · cos(π/16) = 7.85 mm).
_SAMPLE_MM = 2.0
_CELL_MM = 1.25
_SURE_MM = 5.0


@dataclass(frozen=True)
class PoleRegion:
    """Where a detail ×``k`` of a pole region lies: the crowd's largest distance from the
    pole ``radius`` (mm); the region, the circle ``region`` (radius, mm) round ``middle`` (the
    middle of the pole and the crowding images, mm), drawn × k as the detail's frame, the
    circle ``frame`` round ``centre`` (mm, in the main drawing's frame; ``middle`` enlarged
    goes there); ``caption``: the lower left corner of the caption's box and ``box`` (x0, y0,
    x1, y1) all the detail takes on the sheet, caption and the letters' room included."""

    k: int
    radius: float
    middle: tuple[float, float]
    region: float
    centre: tuple[float, float]
    frame: float
    caption: tuple[float, float]
    box: tuple[float, float, float, float]

    def fields(self) -> dict:
        """The region's own fields, to make a detail of it (``PlanDetail(**r.fields(), plan=…)``)."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(PoleRegion)}


@dataclass(frozen=True)
class PlanDetail(PoleRegion):
    """The detail ×``k`` of a plan's pole region (:class:`PoleRegion`): ``plan`` holds the
    images within ``radius`` mm of the pole and the vectors between them, at μ/k."""

    plan: Plan | None = None

    @property
    def mu(self) -> float:
        """The detail's scale, μ/k (unit of the plan per mm)."""
        return self.plan.mu


def pole_crowd(plan: Plan, near: float = NEAR_MM) -> tuple[tuple[str, ...], float] | None:
    """The labels of the images that crowd the pole (within ``near`` mm of it, not at it; two
    or more distinct places) and their largest distance from it (mm); None when there is no
    crowd, or when the plan as a whole is no larger than four times ``near`` (nothing to
    enlarge it against)."""
    pole = plan.point(plan.pole)
    dist = {p.label: math.dist(p.xy, pole) for p in plan.points}
    crowd = [p for p in plan.points if AT_POLE_MM < dist[p.label] < near]
    places: list[tuple[float, float]] = []
    near_places = PointGrid(AT_POLE_MM)
    for p in crowd:
        if not any(math.dist(p.xy, places[k]) < AT_POLE_MM for k in near_places.near(p.xy)):
            places.append(p.xy)
            near_places.add(p.xy)
    if len(places) < 2 or max(dist.values()) < 4.0 * near:
        return None
    return tuple(p.label for p in crowd), max(dist[p.label] for p in crowd)


def _factor(radius: float) -> int | None:
    return next((k for k in FACTORS if k * radius <= DETAIL_MM), None)


def enlargeable(plan: Plan, near: float = NEAR_MM) -> tuple[tuple[str, ...], float, int] | None:
    """The crowd of ``plan``'s pole (:func:`pole_crowd`: labels, radius mm) and the largest factor
    k that keeps it within DETAIL_MM, when a detail is worth drawing: k × radius at least
    DETAIL_MIN_MM and a vector wholly inside the region; else None."""
    crowd = pole_crowd(plan, near)
    if crowd is None:
        return None
    labels, radius = crowd
    k = _factor(radius)
    pole = plan.point(plan.pole)
    inside = [v for v in plan.vectors
              if math.dist(v.tail, pole) <= _reach(radius) and math.dist(v.head, pole) <= _reach(radius)]
    if k is None or k * radius < DETAIL_MIN_MM or not inside:
        return None
    return labels, radius, k


def pole_detail(plan: Plan, *, sizes: tuple[tuple[float, float], ...], room: float,
                caption: Callable[[int], tuple[float, float]], near: float = NEAR_MM) -> PlanDetail | None:
    """The detail of ``plan``'s pole region (see the module docstring), or None when no image
    crowds the pole or no place is found. ``sizes``: the boxes (width, height, mm) the plan
    and its detail together may fill, each part's geometry grown by ``room`` mm for its
    letters; ``caption(k)``: the caption's width and height, mm, of the detail ×k."""
    crowd = enlargeable(plan, near)
    if crowd is None:
        return None
    _, radius, k = crowd
    found = _region(plan, k, radius, sizes=sizes, room=room, caption=caption)
    if found is None:
        return None
    return PlanDetail(**found.fields(), plan=_enlarged(plan, found.k, radius, found.middle, found.centre))


def _region(plan: Plan, k: int | None, radius: float, *, sizes, room: float,
            caption: Callable[[int], tuple[float, float]], reach: float = FRAME_ROOM_MM) -> PoleRegion | None:
    """The region of the largest factor from ``k`` down (:data:`FACTORS`) whose detail finds a
    free place (:func:`_place`), while the crowd × k stays at least DETAIL_MIN_MM; else None."""
    while k is not None and k * radius >= DETAIL_MIN_MM:
        found = _place(plan, k, radius, sizes=sizes, room=room, caption=caption(k), reach=reach)
        if found is not None:
            return found
        k = next((f for f in FACTORS if f < k), None)
    return None


def _place(plan: Plan, k: int, radius: float, *, sizes, room: float, caption,
           reach: float = FRAME_ROOM_MM) -> PoleRegion | None:
    """The detail ×k at the best free place, or None when none fits ``sizes``; the frame runs
    at least ``reach`` mm beyond the farthest enlarged image (room for its letters, or for the
    arrows a lever's detail draws there)."""
    pole = np.array(plan.point(plan.pole), dtype=float)
    inner = np.array([p.xy for p in plan.points if math.dist(p.xy, pole) <= _reach(radius)], dtype=float)
    middle = (inner.min(axis=0) + inner.max(axis=0)) / 2.0
    spread = float(np.max(la.norm(inner - middle, axis=1)))
    frame = max((1.0 + FRAME_GROW) * k * spread, k * spread + reach)
    region = max(frame / k, REGION_MIN_MM)
    cw, ch = caption
    # the detail's content about its pole: the frame, the caption above it
    fx0, fy0 = -frame, -frame
    fx1 = max(frame, -frame + cw)
    fy1 = frame + CAPTION_GAP_MM + ch
    ink = _Ink.of(plan, middle, region)
    gx0, gy0, gx1, gy1 = ink.bounds
    xs = np.arange(math.floor((gx0 - fx1 - CLEAR_MM) / STEP_MM), math.ceil((gx1 - fx0 + CLEAR_MM) / STEP_MM) + 1)
    ys = np.arange(math.floor((gy0 - fy1 - CLEAR_MM) / STEP_MM), math.ceil((gy1 - fy0 + CLEAR_MM) / STEP_MM) + 1)
    cx, cy = np.meshgrid(xs * STEP_MM, ys * STEP_MM, indexing="xy")
    cx, cy = cx.ravel(), cy.ravel()
    detail_box = (fx0, fy0, fx1, fy1)
    fx0, fy0, fx1, fy1 = fx0 - room, fy0 - room, fx1 + room, fy1 + room
    bx0 = np.minimum(gx0 - room, cx + fx0)
    by0 = np.minimum(gy0 - room, cy + fy0)
    bx1 = np.maximum(gx1 + room, cx + fx1)
    by1 = np.maximum(gy1 + room, cy + fy1)
    w, h = bx1 - bx0, by1 - by0
    fits = np.zeros(len(cx), dtype=bool)
    for sw, sh in sizes:
        fits |= (w <= sw) & (h <= sh)
    ok = np.flatnonzero(fits)
    score = np.round(w * h, 6)[ok]
    far = np.round(np.hypot(cx - middle[0], cy - middle[1]), 6)[ok]
    best = ink.first_free(ok[np.lexsort((cy[ok], cx[ok], far, score))], cx, cy, detail_box)
    if best is None:
        return None
    centre = (float(cx[best]), float(cy[best]))
    mid = (float(middle[0]), float(middle[1]))
    return PoleRegion(k, radius, mid, region, centre, frame, (centre[0] - frame, centre[1] + frame + CAPTION_GAP_MM),
                      (float(centre[0] + fx0), float(centre[1] + fy0), float(centre[0] + fx1), float(centre[1] + fy1)))


@dataclass(frozen=True)
class _Ink:
    """What a detail keeps CLEAR_MM from (mm, plan frame): the segments of the vectors and
    construction lines, the images and the region's circle ``disc`` (a polygon)."""

    segments: np.ndarray      # (m, 2, 2)
    points: np.ndarray        # (q, 2)
    disc: shapely.Polygon

    @classmethod
    def of(cls, plan: Plan, middle: np.ndarray, region: float) -> "_Ink":
        """The ink of ``plan``, its region a circle of radius ``region`` round ``middle`` (mm)."""
        segs = [(v.tail, v.head) for v in plan.vectors if v.length > 0] + [(l.start, l.end) for l in plan.lines]
        points = np.array([p.xy for p in plan.points], dtype=float).reshape(-1, 2)
        disc = shapely.Point(middle).buffer(region, quad_segs=8)
        return cls(np.array(segs, dtype=float).reshape(-1, 2, 2), points, disc)

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        """x0, y0, x1, y1 of all the ink, mm."""
        xy = np.concatenate([self.segments.reshape(-1, 2), self.points, shapely.get_coordinates(self.disc)])
        return (float(xy[:, 0].min()), float(xy[:, 1].min()), float(xy[:, 0].max()), float(xy[:, 1].max()))

    def first_free(self, order: np.ndarray, cx: np.ndarray, cy: np.ndarray,
                   box: tuple[float, float, float, float]) -> int | None:
        """The first place in ``order`` where the detail's ``box`` (x0, y0, x1, y1 about the
        place ``cx``, ``cy``; mm) meets no ink grown by CLEAR_MM, or None.

        The ink grown as a whole is the union of its pieces grown one by one (segments cut
        into pieces of at most _PIECE_MM, so that an index of them is queried locally; a piece
        is grown when a tested box first comes near it). A place whose box, grown by
        _SURE_MM, holds a point of the ink is ruled out without a test (that point lies within
        CLEAR_MM · cos(π/16), the inner radius of a grown point, of the box); the others are
        tested exactly, in order, a chunk at a time. Time: linear in the ink and the places."""
        if not len(order):
            return None
        x0, y0, x1, y1 = box
        g = _SURE_MM
        ox, oy = cx[order], cy[order]
        pts = np.concatenate([samples(self.segments, _SAMPLE_MM), self.points,
                              shapely.get_coordinates(self.disc), shapely.get_coordinates(self.disc.centroid)])
        span = (float(min(ox.min() + x0, pts[:, 0].min())) - g, float(min(oy.min() + y0, pts[:, 1].min())) - g,
                float(max(ox.max() + x1, pts[:, 0].max())) + g, float(max(oy.max() + y1, pts[:, 1].max())) + g)
        raster = PointRaster.of(pts, span, _CELL_MM)
        open_ = raster.count_inside(ox + x0 - g, oy + y0 - g, ox + x1 + g, oy + y1 + g) == 0
        order = order[open_]
        cut, _ = pieces(self.segments, _PIECE_MM)
        ink = np.concatenate([shapely.linestrings(cut), shapely.points(self.points), [self.disc]])
        tree = shapely.STRtree(ink)
        grown, made = np.empty(len(ink), dtype=object), np.zeros(len(ink), dtype=bool)
        r = CLEAR_MM
        for start in range(0, len(order), _CHUNK):
            part = order[start:start + _CHUNK]
            px, py = cx[part], cy[part]
            # a piece grown by CLEAR_MM lies within its bounding box grown by as much: grow (once)
            # and test only the pieces whose bounding box comes that near
            bi, gi = tree.query(shapely.box(px + x0 - r, py + y0 - r, px + x1 + r, py + y1 + r))
            new = np.unique(gi[~made[gi]])
            grown[new], made[new] = shapely.buffer(ink[new], r, quad_segs=4), True
            hit = np.zeros(len(part), dtype=bool)
            boxes = shapely.box(px[bi] + x0, py[bi] + y0, px[bi] + x1, py[bi] + y1)
            hit[bi[shapely.intersects(boxes, grown[gi])]] = True
            free = np.flatnonzero(~hit)
            if len(free):
                return int(part[free[0]])
        return None


def _reach(radius: float) -> float:
    """How far from the pole an image is inside the region of crowd ``radius``, mm."""
    return radius * (1.0 + 1e-9) + AT_POLE_MM


def _enlarged(plan: Plan, k: int, radius: float, middle: tuple[float, float], centre: tuple[float, float]) -> Plan:
    """The images within ``radius`` of the pole and the vectors between them, × k about
    ``middle``, which goes to ``centre``; at μ/k."""
    pole = plan.point(plan.pole)

    def inside(xy) -> bool:
        return math.dist(xy, pole) <= _reach(radius)

    def s(xy) -> tuple[float, float]:
        return (centre[0] + k * (float(xy[0]) - middle[0]), centre[1] + k * (float(xy[1]) - middle[1]))

    points = tuple(PlanPoint(p.label, s(p.xy)) for p in plan.points if inside(p.xy))
    vectors = tuple(replace(v, tail=s(v.tail), head=s(v.head)) for v in plan.vectors
                    if inside(v.tail) and inside(v.head))
    labels = {p.label for p in points}
    similar = tuple((link, labs) for link, labs in plan.similar if set(labs) <= labels)
    lines: tuple[ConstructionLine, ...] = ()
    return replace(plan, mu=plan.mu / k, points=points, vectors=vectors, lines=lines, similar=similar)

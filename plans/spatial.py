"""Spatial helpers that keep the layout searches linear in the number of drawn things.

A shapely STRtree answers "what does this box touch" by the bounding boxes of what it holds,
so one long diagonal line is a candidate for every query anywhere in its bounding box and a
plan of n long vectors makes every query O(n). :func:`pieces` cuts straight segments into
short pieces for such an index (what a box touches is unchanged: a segment is the union of
its pieces). :class:`PointRaster` counts sample points in axis-parallel boxes in O(1) each
(a summed-area table). :class:`BoxGrid` holds boxes that arrive one by one (labels placed so
far) in buckets of a uniform grid, so a query reads only the buckets it overlaps;
:class:`PointGrid` does so for points, to find those near a place.
All lengths are millimetres of a drawing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import shapely

__all__ = ["pieces", "samples", "segments_meet_boxes", "PointRaster", "BoxGrid", "PointGrid"]


def pieces(segments: np.ndarray, longest: float) -> tuple[np.ndarray, np.ndarray]:
    """Segments ``(m, 2, 2)`` (mm) cut into equal pieces no longer than ``longest`` (mm): the
    pieces ``(p, 2, 2)`` and, for each, the index of its segment. A segment of zero length is
    one piece, itself."""
    segments = np.asarray(segments, dtype=float).reshape(-1, 2, 2)
    a, b = segments[:, 0], segments[:, 1]
    length = np.hypot(b[:, 0] - a[:, 0], b[:, 1] - a[:, 1])
    count = np.maximum(1, np.ceil(length / longest)).astype(int)
    owner = np.repeat(np.arange(len(segments)), count)
    first = np.cumsum(count) - count
    k = np.arange(len(owner)) - first[owner]
    n = count[owner][:, None]
    start = np.where(k[:, None] == 0, a[owner], a[owner] + (b[owner] - a[owner]) * (k[:, None] / n))
    end = np.where(k[:, None] == n - 1, b[owner], a[owner] + (b[owner] - a[owner]) * ((k[:, None] + 1) / n))
    return np.stack([start, end], axis=1), owner


def samples(segments: np.ndarray, spacing: float) -> np.ndarray:
    """Points ``(q, 2)`` on segments ``(m, 2, 2)`` (mm): both ends of each and points between
    them no farther apart than ``spacing`` (mm)."""
    seg = np.asarray(segments, dtype=float).reshape(-1, 2, 2)
    a, d = seg[:, 0], seg[:, 1] - seg[:, 0]
    count = np.maximum(1, np.ceil(np.hypot(d[:, 0], d[:, 1]) / spacing)).astype(np.int64)
    owner = np.repeat(np.arange(len(seg)), count)
    t = (np.arange(len(owner)) - (np.cumsum(count) - count)[owner]) / count[owner]
    return np.concatenate([a[owner] + d[owner] * t[:, None], seg[:, 1]])


def segments_meet_boxes(ends: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """Whether segment k, ``ends[k]`` = (ax, ay, bx, by), meets the closed box k, ``boxes[k]``
    = (x0, y0, x1, y1), as shapely's ``intersects`` says: decided in numpy where rounding
    cannot change the answer (bounding boxes apart; the box's corners all strictly on one
    side of the segment's line, or strictly on both), by shapely for the rest."""
    ends, boxes = np.asarray(ends, dtype=float).reshape(-1, 4), np.asarray(boxes, dtype=float).reshape(-1, 4)
    ax, ay, bx, by = ends.T
    x0, y0, x1, y1 = boxes.T
    apart = ((np.minimum(ax, bx) > x1) | (x0 > np.maximum(ax, bx))
             | (np.minimum(ay, by) > y1) | (y0 > np.maximum(ay, by)))
    dx, dy = bx - ax, by - ay
    cross = np.stack([dx * (cy - ay) - dy * (cx - ax) for cx in (x0, x1) for cy in (y0, y1)])
    # |computed − exact| of each cross product is below 16·ε·M² (M the largest |coordinate|)
    big = np.max(np.abs(np.concatenate([ends, boxes], axis=1)), axis=1) + 1.0
    tol = 1e-12 * big * big
    above, below = (cross > tol).any(axis=0), (cross < -tol).any(axis=0)
    unsure = ~apart & ~(above & below) & (np.abs(cross) <= tol).any(axis=0)
    out = ~apart & above & below
    if unsure.any():
        k = np.flatnonzero(unsure)
        out[k] = shapely.intersects(shapely.linestrings(ends[k].reshape(-1, 2, 2)),
                                    shapely.box(x0[k], y0[k], x1[k], y1[k]))
    return out


@dataclass(frozen=True)
class PointRaster:
    """How many of a fixed set of points lie in a box, from a summed-area table of cells of
    ``cell`` mm: :meth:`count_inside` counts the points of the cells that lie wholly inside
    each box (a lower bound of the points in the box, exact up to one cell at each edge)."""

    origin: tuple[float, float]
    cell: float
    table: np.ndarray          # (rows + 1, cols + 1) cumulative counts; row = y, column = x

    @classmethod
    def of(cls, points: np.ndarray, bounds: tuple[float, float, float, float], cell: float) -> "PointRaster":
        """The raster of ``points`` (q, 2) over ``bounds`` (x0, y0, x1, y1, mm); points outside
        the bounds are left out."""
        x0, y0, x1, y1 = bounds
        cols = max(1, int(math.ceil((x1 - x0) / cell)))
        rows = max(1, int(math.ceil((y1 - y0) / cell)))
        pts = np.asarray(points, dtype=float).reshape(-1, 2)
        i = np.floor((pts[:, 0] - x0) / cell).astype(np.int64)
        j = np.floor((pts[:, 1] - y0) / cell).astype(np.int64)
        keep = (i >= 0) & (i < cols) & (j >= 0) & (j < rows)
        grid = np.bincount(j[keep] * cols + i[keep], minlength=rows * cols).reshape(rows, cols)
        table = np.zeros((rows + 1, cols + 1), dtype=np.int32)
        table[1:, 1:] = grid.cumsum(axis=0, dtype=np.int32).cumsum(axis=1, dtype=np.int32)
        return cls((x0, y0), cell, table)

    def count_inside(self, x0: np.ndarray, y0: np.ndarray, x1: np.ndarray, y1: np.ndarray) -> np.ndarray:
        """Points in the cells wholly inside each box [x0, x1] × [y0, y1] (arrays, mm)."""
        rows, cols = self.table.shape[0] - 1, self.table.shape[1] - 1
        ox, oy = self.origin
        low = np.ceil((np.stack([x0, y0]) - np.array([[ox], [oy]])) / self.cell)
        high = np.floor((np.stack([x1, y1]) - np.array([[ox], [oy]])) / self.cell)
        top = np.array([[cols], [rows]])
        low = np.minimum(np.maximum(low, 0), top).astype(np.int64)
        high = np.maximum(np.minimum(np.maximum(high, 0), top).astype(np.int64), low)
        (i0, j0), (i1, j1), w = low, high, cols + 1
        c = self.table.ravel()[np.stack([j1 * w + i1, j0 * w + i0, j0 * w + i1, j1 * w + i0])]
        return c[0] + c[1] - c[2] - c[3]


@dataclass(frozen=True)
class BoxGrid:
    """Axis-parallel boxes (x0, y0, x1, y1, mm) added one at a time, bucketed in square cells
    of ``cell`` mm; :meth:`near` gives the indices of the boxes that may overlap a region
    (all of them while they are few: :data:`FEW`)."""

    cell: float
    _rows: list = field(default_factory=lambda: [np.empty((0, 4)), 0])   # [array grown by doubling, rows used]
    _buckets: dict[tuple[int, int], list[int]] = field(default_factory=dict)

    #: Up to this many boxes, :meth:`near` gives all of them (cheaper than reading buckets).
    FEW = 64

    def __len__(self) -> int:
        return self._rows[1]

    def _span(self, x0: float, y0: float, x1: float, y1: float) -> tuple[range, range]:
        c = self.cell
        return (range(math.floor(x0 / c), math.floor(x1 / c) + 1), range(math.floor(y0 / c), math.floor(y1 / c) + 1))

    def add(self, box: tuple[float, float, float, float]) -> int:
        """Add ``box``; returns its index."""
        rows, index = self._rows
        if index == len(rows):
            rows = self._rows[0] = np.concatenate([rows, np.empty((max(16, index), 4))])
        rows[index] = box
        self._rows[1] = index + 1
        xs, ys = self._span(*box)
        for i in xs:
            for j in ys:
                self._buckets.setdefault((i, j), []).append(index)
        return index

    def near(self, x0: float, y0: float, x1: float, y1: float) -> np.ndarray:
        """Indices (ascending) of every box that overlaps or touches [x0, x1] × [y0, y1], and
        perhaps a few more."""
        n = self._rows[1]
        xs, ys = self._span(x0, y0, x1, y1)
        if n <= self.FEW or len(xs) * len(ys) > 4 * len(self._buckets):
            return np.arange(n)
        return np.array(sorted({k for i in xs for j in ys for k in self._buckets.get((i, j), ())}), dtype=np.int64)

    def array(self, indices: np.ndarray) -> np.ndarray:
        """The boxes at ``indices`` as an (k, 4) array."""
        return self._rows[0][indices]


@dataclass(frozen=True)
class PointGrid:
    """Points added one at a time, bucketed in square cells of ``2 · reach``: :meth:`near`
    gives, in the order they were added, every point within ``reach`` of a place (and perhaps
    a few more: the caller applies its own test, so the first that passes it is the first
    of all the points that would)."""

    reach: float
    _buckets: dict[tuple[int, int], list[int]] = field(default_factory=dict)
    _added: list[tuple[int, int]] = field(default_factory=list)

    def _cell(self, xy) -> tuple[int, int]:
        c = 2.0 * self.reach
        return math.floor(float(xy[0]) / c), math.floor(float(xy[1]) / c)

    def add(self, xy) -> int:
        """Add the point ``xy``; returns its index (0, 1, …)."""
        index, cell = len(self._added), self._cell(xy)
        self._added.append(cell)
        self._buckets.setdefault(cell, []).append(index)
        return index

    def near(self, xy) -> list[int]:
        """Indices, ascending, of the points that may lie within ``reach`` of ``xy``."""
        i, j = self._cell(xy)
        found = [k for di in (-1, 0, 1) for dj in (-1, 0, 1) for k in self._buckets.get((i + di, j + dj), ())]
        return sorted(found)

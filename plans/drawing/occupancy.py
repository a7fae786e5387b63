"""How much of a place on a sheet the labels and leaders placed so far cover.

A label with no free place goes where it covers least (:meth:`~plans.drawing.canvas.Canvas.
place_labels`); that measure must cost the same however full the sheet is, or the labels of a
crowded sheet would cost more the more crowded it gets. :class:`Occupancy` keeps, on a grid of
:data:`CELL_MM` cells over the drawing area, how many labels cover each cell (a label covers
every cell its box overlaps) and how many leaders pass through it; the sums over the boxes
near one label come from a summed-area table of the window they span. It is made on first
use (a sheet with no crowded label never builds it). Paper millimetres.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..spatial import samples

__all__ = ["Occupancy", "CELL_MM"]

#: The grid's cell, mm.
CELL_MM = 1.0


@dataclass(frozen=True)
class Occupancy:
    """The labels (boxes x0, y0, x1, y1) and leaders (segments ax, ay, bx, by) placed on the
    drawing ``area`` (x0, y0, x1, y1), mm: :meth:`add_label`, :meth:`add_leader`; then
    :meth:`covered` (of boxes) and :meth:`over_labels` (of segments)."""

    area: tuple[float, float, float, float]
    _labels: list = field(default_factory=list)
    _leaders: list = field(default_factory=list)
    _layers: list = field(default_factory=list)       # [labels + leaders grid, labels grid, labels, leaders applied]

    def add_label(self, box: tuple[float, float, float, float]) -> None:
        """A label placed in ``box`` (mm)."""
        self._labels.append(box)
        if self._layers:
            self._apply()

    def add_leader(self, segment: tuple[float, float, float, float]) -> None:
        """A leader drawn along ``segment`` (mm)."""
        self._leaders.append(segment)
        if self._layers:
            self._apply()

    def _shape(self) -> tuple[int, int]:
        x0, y0, x1, y1 = self.area
        return max(1, math.ceil((y1 - y0) / CELL_MM)), max(1, math.ceil((x1 - x0) / CELL_MM))

    def _cells(self, x0, y0, x1, y1) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Cell ranges [i0, i1) × [j0, j1) of the cells each box overlaps, clipped to the grid."""
        rows, cols = self._shape()
        origin, top = np.array([[self.area[0]], [self.area[1]]]), np.array([[cols], [rows]])
        low = np.floor((np.stack([x0, y0]) - origin) / CELL_MM)
        high = np.floor((np.stack([x1, y1]) - origin) / CELL_MM) + 1
        low = np.minimum(np.maximum(low, 0), top).astype(np.int64)
        high = np.maximum(np.minimum(np.maximum(high, 0), top).astype(np.int64), low)
        return low[0], high[0], low[1], high[1]

    def _apply(self) -> tuple[np.ndarray, np.ndarray]:
        """The grids of labels and leaders (cells covered by labels + leaders passing) and of
        labels alone, with everything added so far on them."""
        if not self._layers:
            shape = self._shape()
            self._layers.extend([np.zeros(shape, dtype=np.int32), np.zeros(shape, dtype=np.int32), 0, 0])
        both, labels, done_labels, done_leaders = self._layers
        ox, oy = self.area[0], self.area[1]
        rows, cols = both.shape
        for x0, y0, x1, y1 in self._labels[done_labels:]:
            i0 = min(max(math.floor((x0 - ox) / CELL_MM), 0), cols)
            j0 = min(max(math.floor((y0 - oy) / CELL_MM), 0), rows)
            i1 = min(max(math.floor((x1 - ox) / CELL_MM) + 1, 0), cols)
            j1 = min(max(math.floor((y1 - oy) / CELL_MM) + 1, 0), rows)
            both[j0:j1, i0:i1] += 1
            labels[j0:j1, i0:i1] += 1
        for s in self._leaders[done_leaders:]:
            pts = samples(np.array(s, dtype=float), 0.5 * CELL_MM)
            i = np.floor((pts[:, 0] - self.area[0]) / CELL_MM).astype(np.int64)
            j = np.floor((pts[:, 1] - self.area[1]) / CELL_MM).astype(np.int64)
            keep = (i >= 0) & (i < cols) & (j >= 0) & (j < rows)
            both.ravel()[np.unique(j[keep] * cols + i[keep])] += 1
        self._layers[2], self._layers[3] = len(self._labels), len(self._leaders)
        return both, labels

    def covered(self, x0: np.ndarray, y0: np.ndarray, x1: np.ndarray, y1: np.ndarray) -> np.ndarray:
        """For each box: over the cells it overlaps, the labels covering them plus the leaders
        passing through them (a label counts once per cell: mm² at 1 mm cells). Read from the
        summed-area table of the window the boxes span, not of the whole sheet."""
        i0, i1, j0, j1 = self._cells(x0, y0, x1, y1)
        if not len(i0):
            return np.zeros(0, dtype=np.int64)
        a, b, c, d = int(i0.min()), int(i1.max()), int(j0.min()), int(j1.max())
        t = np.zeros((d - c + 1, b - a + 1), dtype=np.int64)
        t[1:, 1:] = self._apply()[0][c:d, a:b].cumsum(axis=0).cumsum(axis=1)
        i0, i1, j0, j1 = i0 - a, i1 - a, j0 - c, j1 - c
        return t[j1, i1] - t[j0, i1] - t[j1, i0] + t[j0, i0]

    def over_labels(self, segments: np.ndarray) -> np.ndarray:
        """For each segment (ax, ay, bx, by): how many of its sample points (every cell's
        width, from its start) lie in cells a label covers."""
        segments = np.asarray(segments, dtype=float).reshape(-1, 4)
        if not len(segments):
            return np.zeros(0, dtype=np.int64)
        grid = self._apply()[1]
        rows, cols = grid.shape
        d = segments[:, 2:] - segments[:, :2]
        count = np.maximum(1, np.ceil(np.hypot(d[:, 0], d[:, 1]) / CELL_MM)).astype(np.int64)
        owner = np.repeat(np.arange(len(segments)), count)
        t = (np.arange(len(owner)) - (np.cumsum(count) - count)[owner]) / count[owner]
        pts = segments[owner, :2] + d[owner] * t[:, None]
        i = np.floor((pts[:, 0] - self.area[0]) / CELL_MM).astype(np.int64)
        j = np.floor((pts[:, 1] - self.area[1]) / CELL_MM).astype(np.int64)
        keep = (i >= 0) & (i < cols) & (j >= 0) & (j < rows)
        on = np.zeros(len(owner), dtype=np.int64)
        on[keep] = grid[j[keep], i[keep]] > 0
        return np.bincount(owner, weights=on, minlength=len(segments)).astype(np.int64)

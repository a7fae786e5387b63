"""What a label's box touches of a sheet's ink, in time that does not grow with the sheet.

:class:`InkIndex` answers, for many boxes at once, whether each touches any inked geometry
(exactly: shapely's ``intersects``, :meth:`InkIndex.touches`) and how much ink it holds
(:meth:`InkIndex.ink_mm`, the measure of a crowded label's place). The geometries sit in an
STRtree. Where the ink proves dense (the boxes tested meet many geometries each: long lines,
whose bounding boxes cover much of the sheet, or bundles of lines), the long straight lines
are cut into short pieces (:func:`~plans.spatial.pieces`) in a second STRtree, so a query
reads only what lies near its box, and a summed-area table of sample points along every
line and outline (:class:`~plans.spatial.PointRaster`) is built once: a box that holds one
of them touches ink without a further test. Which way a box is decided never changes the
answer. Paper millimetres (SVG frame, y down).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping, Sequence

import numpy as np
import shapely

from ..spatial import PointRaster, pieces, samples

__all__ = ["InkIndex", "PIECE_MM", "SAMPLE_MM"]

#: Longest piece of a straight line in the STRtree, mm.
PIECE_MM = 5.0
#: Spacing of the sample points along the ink, and cell of their raster, mm (a label's box,
#: its clearance included, is at least some 2.5 mm wide and high).
SAMPLE_MM = 0.5
#: A box is shrunk by this before its raster cells are counted (mm): a sample point counted
#: lies this far inside the box, far beyond the rounding of an interpolated point.
INSET_MM = 1e-6
#: The pieces and the raster are made once the boxes tested so far (at least DENSE_AFTER of
#: them) met more than DENSE_GEOMETRIES geometries each on average.
DENSE_AFTER = 128
DENSE_GEOMETRIES = 8.0


@dataclass(frozen=True)
class InkIndex:
    """The ink of a sheet, indexed: its geometries ``ink`` (``straight``: see :meth:`of`) in
    an STRtree; when the queries show the ink dense, the long lines cut into pieces in a
    second STRtree and the raster of sample points (made once, :meth:`_dense`)."""

    ink: Sequence
    straight: Mapping[int, tuple[tuple, float]]
    tree: shapely.STRtree
    _dense: list = field(default_factory=list)                 # [(STRtree of pieces, PointRaster | None)]
    _work: list[int] = field(default_factory=lambda: [0, 0])   # boxes tested, geometries met

    @classmethod
    def of(cls, ink: Sequence, straight: Mapping[int, tuple[tuple, float]]) -> "InkIndex":
        """The index of geometries ``ink``; ``straight``: for the ones that are a straight line
        (index → ((start, end), half width; 0 for a bare line)), so that the long ones can be
        cut into pieces (a stroke of width into the flat-ended strokes of its pieces, which
        together are that stroke)."""
        return cls(ink, straight, shapely.STRtree(ink))

    def _dense_index(self) -> tuple[shapely.STRtree, PointRaster | None]:
        """The pieces' STRtree and the sample points' raster (made once)."""
        if not self._dense:
            long_ = {i for i, ((a, b), _) in self.straight.items()
                     if abs(b[0] - a[0]) + abs(b[1] - a[1]) > 2.0 * PIECE_MM}
            order = sorted(long_)
            geoms = [np.array([g for i, g in enumerate(self.ink) if i not in long_], dtype=object)]
            if order:
                cut, owner = pieces(np.array([self.straight[i][0] for i in order]), PIECE_MM)
                half = np.array([self.straight[i][1] for i in order])[owner]
                lines = shapely.linestrings(cut)
                wide = half > 0.0
                lines[wide] = shapely.buffer(lines[wide], half[wide], cap_style="flat", quad_segs=1)
                geoms.append(lines)
            every = np.concatenate(geoms)
            pts = _samples(every)
            raster = None
            if len(pts):
                lo, hi = pts.min(axis=0), pts.max(axis=0)
                raster = PointRaster.of(pts, (float(lo[0]), float(lo[1]), float(hi[0]) + SAMPLE_MM,
                                              float(hi[1]) + SAMPLE_MM), SAMPLE_MM)
            self._dense.append((shapely.STRtree(every), raster))
        return self._dense[0]

    def _held(self, x0, y0, x1, y1) -> np.ndarray:
        d = INSET_MM
        raster = self._dense_index()[1]
        return np.zeros(len(x0), dtype=np.int64) if raster is None else \
            raster.count_inside(x0 + d, y0 + d, x1 - d, y1 - d).astype(np.int64)

    def touches(self, x0: np.ndarray, y0: np.ndarray, x1: np.ndarray, y1: np.ndarray) -> np.ndarray:
        """Whether each box [x0, x1] × [y0, y1] (arrays, mm) touches any ink."""
        boxes, work = self._work
        if not self._dense and (boxes < DENSE_AFTER or work <= DENSE_GEOMETRIES * boxes):
            hit = self.tree.query(shapely.box(x0, y0, x1, y1), predicate="intersects")[0]
            self._work[0] += len(x0)
            self._work[1] += len(hit)
            out = np.zeros(len(x0), dtype=bool)
            out[hit] = True
            return out
        out = self._held(x0, y0, x1, y1) > 0
        open_ = np.flatnonzero(~out)
        if len(open_):
            out[open_[self._dense_index()[0].query(shapely.box(x0[open_], y0[open_], x1[open_], y1[open_]),
                                                   predicate="intersects")[0]]] = True
        return out

    def ink_mm(self, x0: np.ndarray, y0: np.ndarray, x1: np.ndarray, y1: np.ndarray) -> np.ndarray:
        """About how many millimetres of ink each box holds: the sample points in the cells
        wholly inside it × their spacing, rounded up."""
        return np.ceil(self._held(x0, y0, x1, y1) * SAMPLE_MM).astype(np.int64)


def _samples(geoms: np.ndarray) -> np.ndarray:
    """Points (q, 2) on ``geoms`` no farther apart than SAMPLE_MM along each line and each
    polygon's boundary: their vertices and points between (every one of them is ink)."""
    lines = geoms.copy()
    polygon = shapely.get_type_id(geoms) == 3
    lines[polygon] = shapely.boundary(geoms[polygon])
    coords, part = shapely.get_coordinates(shapely.get_parts(lines), return_index=True)
    joined = part[1:] == part[:-1]
    edges = np.stack([coords[:-1][joined], coords[1:][joined]], axis=1)
    return np.concatenate([coords, samples(edges, SAMPLE_MM)]) if len(edges) else coords

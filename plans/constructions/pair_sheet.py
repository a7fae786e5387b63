"""The paper geometry of the involute pair's sheets (:mod:`.gear_pair`): :class:`PairSheet` and its
measured segments (:class:`Tag`), the scales of the detail and the general view, and the small
plane helpers they share (angles clockwise from +y, as in :mod:`.gear_cutting`).

Imports numpy only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

__all__ = ["PairSheet", "Tag", "ENLARGEMENTS", "REDUCTIONS", "MODULE_MM", "OVERVIEW_MM", "CUT_TOLERANCE",
           "cut_tolerance", "DETAIL_MM", "MESHING_MM", "SLIDING_MM", "SLIDING_SERIES", "RIM", "scale_for", "arc",
           "turned", "outlines"]

#: Enlargement scales k:1 of the detail, and reductions k0:1 (k0 < 1) of the general view.
ENLARGEMENTS = (1.0, 2.0, 2.5, 4.0, 5.0, 10.0, 20.0, 25.0, 40.0, 50.0, 100.0)
REDUCTIONS = (1.0, 0.5, 0.4, 0.25, 0.2, 0.1, 0.05, 0.04, 0.025, 0.02, 0.01, 0.005, 0.004, 0.0025, 0.002, 0.001,
              5e-4, 4e-4, 2.5e-4, 2e-4, 1e-4)       # down to 1:10 000: wheels of 500 teeth of m = 1000 mm fit
#: The module on paper is at least this, mm.
MODULE_MM = 8.0
#: The general view's largest height, mm.
OVERVIEW_MM = 110.0
#: The cut is within this of the exact profile, mm of the wheel (far below the paper's 0.0005 mm/k),
#: up to a module of ``CUT_MODULE`` mm; beyond it in proportion to the module (:func:`cut_tolerance`).
CUT_TOLERANCE, CUT_MODULE = 1e-4, 20.0


def cut_tolerance(module: float) -> float:
    """The cut's tolerance (mm of the wheel) for ``module`` (mm): ``CUT_TOLERANCE``, times m/20 beyond
    m = 20 mm — the rolling steps then stay those of m = 20 (a module of 1000 mm was cut in 65 s,
    in 2 s now), 5 µm for m = 1000, drawn at 1:100 or smaller (0.05 µm on paper)."""
    return CUT_TOLERANCE * max(1.0, module / CUT_MODULE)


@dataclass(frozen=True)
class Tag:
    """A measured segment: ``group`` ("detail", "overview" or "sliding"), ``quantity``, ``value``
    (mm of the wheel; a specific sliding's |λ| in the ``sliding`` group), paper ends ``a``,
    ``b``, and the names of its ends."""

    group: str
    quantity: str
    value: float
    a: tuple[float, float]
    b: tuple[float, float]
    ends: tuple[str, str]


@dataclass
class PairSheet:
    """Paper geometry: ``k`` (detail) and ``k0`` (general view, 0 when none); ``outlines``
    (name, closed polylines), ``curves`` (name, kind "thin" | "dash" | "thick" | "thickdash" |
    "arc" | "axis", polyline), ``tags``, ``points`` (name, xy) marked with a dot and labelled, ``labels`` (text,
    anchor, preferred direction) and the ``notes``' values."""

    k: float
    k0: float = 0.0
    mu_sliding: float = 0.0                 # μλ of the specific-sliding diagram, 1/mm (0: none)
    dimensions: bool = False                # the tags drawn as dimension lines (arrows both ends, values)
    outlines: list[tuple[str, np.ndarray]] = field(default_factory=list)
    curves: list[tuple[str, str, np.ndarray]] = field(default_factory=list)
    tags: list[Tag] = field(default_factory=list)
    points: list[tuple[str, tuple[float, float]]] = field(default_factory=list)
    labels: list[tuple[str, tuple[float, float], tuple[float, float]]] = field(default_factory=list)

    def bounds(self) -> tuple[float, float, float, float]:
        pts = [p for _, o in self.outlines for p in o] + [p for _, _, c in self.curves for p in c] + \
            [t.a for t in self.tags] + [t.b for t in self.tags] + [p for _, p in self.points]
        a = np.array(pts, float)
        return float(a[:, 0].min()), float(a[:, 1].min()), float(a[:, 0].max()), float(a[:, 1].max())


#: The detail's largest width and height on the sheet, mm (the general view and notes beside it;
#: the meshing detail leaves room below it for the specific-sliding diagram).
DETAIL_MM = (250.0, 185.0)
MESHING_MM = (250.0, 135.0)
#: The largest ordinate of the specific-sliding diagram, mm, and the mantissas of μλ.
SLIDING_MM = 30.0
SLIDING_SERIES = (1.0, 2.0, 2.5, 4.0, 5.0)


def scale_for(m: float, size: tuple[float, float] | None = None, room: tuple[float, float] = DETAIL_MM) -> float:
    """The detail's enlargement: the largest of the series that keeps the detail (``size`` at
    1:1, mm) within :data:`DETAIL_MM`, and at least the smallest that draws the module ≥
    :data:`MODULE_MM` long; where even 1:1 does not fit (a module of tens of mm and more), the
    largest of :data:`REDUCTIONS` that does (1:100 for m = 1000 mm), else the smallest."""
    least = next((k for k in ENLARGEMENTS if m * k >= MODULE_MM - 1e-9), ENLARGEMENTS[-1])
    if size is None:
        return least
    fits = [k for k in ENLARGEMENTS if k >= least and size[0] * k <= room[0] and size[1] * k <= room[1]]
    if fits or least > 1.0:
        return max(fits) if fits else least
    return next((k for k in REDUCTIONS if size[0] * k <= room[0] and size[1] * k <= room[1]), REDUCTIONS[-1])


def arc(centre: np.ndarray, radius: float, a0: float, a1: float, n: int = 181) -> np.ndarray:
    """Points of a circle's arc, the angles clockwise from +y (rad)."""
    a = np.linspace(a0, a1, n)
    return np.column_stack([centre[0] + radius * np.sin(a), centre[1] + radius * np.cos(a)])


def turned(pts: np.ndarray, clockwise: float, scale: float, centre: np.ndarray) -> np.ndarray:
    c, s = math.cos(clockwise), math.sin(clockwise)
    x, y = pts[:, 0], pts[:, 1]
    return np.column_stack([x * c + y * s, -x * s + y * c]) * scale + centre


def outlines(poly) -> list[np.ndarray]:
    geoms = getattr(poly, "geoms", [poly])
    return [np.array(g.exterior.coords) for g in geoms if not g.is_empty and g.geom_type == "Polygon"]


#: The rim drawn below the root circle, modules.
RIM = 1.2



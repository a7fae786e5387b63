"""Wheel 2 of the meshing sheet when it is not an external wheel: a ring gear (internal pair) or a
rack, in mm of the wheel, placed so that one of its flanks passes through the pitch point P.

Angles are clockwise from +y about the wheel's own centre, as in :mod:`.gear_cutting`.

**Ring gear** (z teeth, shift x, tip circle d_a inside its pitch circle, root circle d_f outside
it). Its tooth space is the tooth of an external wheel of z teeth and shift x: the space is
m(π/2 + 2x·tan α) wide on the reference circle, the ring's tooth m(π/2 − 2x·tan α). The space
centred at the angle θ is bounded by the involutes θ ± ψ(R), ψ(R) = e/(2r) + inv α − inv α_R
(e that width, r = m·z/2, α_R = arccos(r_b/R)), from the tip circle out to the root circle, which
closes it. The ring's flanks are pure involutes (its tip lies outside its base circle: an internal
pair whose ring's tip is inside its base circle is refused before it is drawn). The fillet the
pinion cutter leaves at the ring's root is not drawn: the root is a sharp corner on the root circle.

**Rack** (its teeth pointing down to the pinion, its reference line x1·m above P, the pitch line
through P): a tooth's half thickness at the height y is p/4 + (y − x1·m)·tan α; tip line
(x1 − ha2*)·m, root line x1·m + (ha* + c*)·m (the basic rack's dedendum). The tooth whose left
flank passes through P is centred at u0 = p/4 − x1·m·tan α; that flank is x = −y·tan α.

Imports numpy and shapely only.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from shapely.geometry import Polygon

__all__ = ["ring_space_half", "ring_outline", "rack_outline", "rack_centre"]

#: Samples along each flank.
FLANK_SAMPLES = 60


def _inv(a: np.ndarray | float) -> np.ndarray | float:
    return np.tan(a) - a


def ring_space_half(radius: np.ndarray | float, m: float, z: int, alpha: float, x: float) -> np.ndarray:
    """ψ(R): half the angle (rad) of the ring's tooth space at ``radius`` (mm, ≥ r_b), see the module."""
    r = m * z / 2.0
    rb = r * math.cos(alpha)
    e = m * (math.pi / 2.0 + 2.0 * x * math.tan(alpha))
    a_r = np.arccos(np.clip(rb / np.asarray(radius, float), -1.0, 1.0))
    return e / (2.0 * r) + _inv(alpha) - _inv(a_r)


def _polar(radius: np.ndarray, angle: np.ndarray) -> np.ndarray:
    return np.column_stack([radius * np.sin(angle), radius * np.cos(angle)])


def ring_outline(m: float, z: int, alpha: float, x: float, tip_diameter: float, root_diameter: float,
                 rim: float, first_space: float, spaces: int = 5, through: float | None = None) -> Polygon:
    """The ring gear near its +y axis, its centre at the origin: the annulus from the tip circle
    out to the root circle + ``rim`` (mm), over the sector of ``spaces`` tooth spaces centred at
    ``first_space`` + j·2π/z (j = 0 … spaces − 1) and half a pitch beyond, less those spaces; the
    flanks are sampled at the radius ``through`` too (P's, which then lies on the outline)."""
    tau = 2.0 * math.pi / z
    ra, rf = tip_diameter / 2.0, root_diameter / 2.0
    rb = m * z / 2.0 * math.cos(alpha)
    a0, a1 = first_space - 0.5 * tau, first_space + (spaces - 0.5) * tau
    angles = np.linspace(a0, a1, 721)
    sector = np.vstack([_polar(np.full(angles.size, ra), angles), _polar(np.full(angles.size, rf + rim), angles[::-1])])
    ring = Polygon(sector)
    low = max(ra, rb)
    radii = np.linspace(low, rf, FLANK_SAMPLES)
    if through is not None and low < through < rf:
        radii = np.unique(np.append(radii, through))
    half = ring_space_half(radii, m, z, alpha, x)
    inner = max(ra - m, 0.0)                         # carried radially in past the tip, to cut it clean
    cuts = []
    for j in range(-1, spaces + 1):
        theta = first_space + j * tau
        left = _polar(radii, theta - half)                        # out along the left flank
        root = np.linspace(theta - half[-1], theta + half[-1], 12)[1:-1]
        right = _polar(radii[::-1], theta + half[::-1])           # back in along the right flank
        cuts.append(Polygon(np.vstack([_polar(np.array([inner]), np.array([theta - half[0]])), left,
                                       _polar(np.full(root.size, rf), root), right,
                                       _polar(np.array([inner]), np.array([theta + half[0]]))])))
    return ring.difference(shapely.union_all(cuts))


def rack_centre(m: float, alpha: float, x1: float) -> float:
    """u0 (mm): the centre of the rack tooth whose left flank passes through P (see the module)."""
    return math.pi * m / 4.0 - x1 * m * math.tan(alpha)


def rack_outline(m: float, alpha: float, x1: float, tip: float, addendum: float, clearance: float,
                 rim: float, teeth: range = range(-2, 3)) -> np.ndarray:
    """The rack's outline (mm, P at the origin, y up): its ``teeth`` (indices from the tooth right of
    P) down to the tip line (x1 − ``tip``)·m, the roots at x1·m + (``addendum`` + ``clearance``)·m,
    and its body ``rim`` mm above the roots, half a pitch beyond the first and last tooth."""
    p = math.pi * m
    t = math.tan(alpha)
    y_ref = x1 * m
    y_tip, y_root = y_ref - tip * m, y_ref + (addendum + clearance) * m
    half = lambda y: p / 4.0 + (y - y_ref) * t
    u0 = rack_centre(m, alpha, x1)
    left_end, right_end = u0 + (teeth.start - 0.5) * p, u0 + (teeth.stop - 0.5) * p
    pts = [(left_end, y_root + rim), (left_end, y_root)]
    for j in teeth:
        c = u0 + j * p
        pts += [(c - half(y_root), y_root), (c - half(y_tip), y_tip), (c + half(y_tip), y_tip),
                (c + half(y_root), y_root)]
    pts += [(right_end, y_root), (right_end, y_root + rim)]
    return np.array(pts)

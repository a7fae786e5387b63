"""A wheel's teeth cut the way the machine cuts them: the rack cutter (its flanks at the pressure
angle, its tip rounded with radius ρ) rolls over the blank, and the blank less the union of the
cutter's positions is the wheel. Undercut, where it exists, appears by itself.

Geometry in mm, y up, the wheel's centre at the origin; the tooth space being cut at φ = 0 is
centred on the +y axis. At the rolling parameter φ (rad) the cutter's point (u, v) — u along its
rolling line, v above it (away from the centre) — is at Rot(φ)·(u − r·φ, r + v): the rolling line
rolls on the reference circle r = m·z/2 without slipping. The cutter's reference line is at
v = x·m (the shift), its teeth (thickness p/2 on that line) reach down to v = x·m − (ha* + c*)·m.

Accuracy: between two positions Δφ apart, the cut flank is the intersection of two tangents of
the involute, at most ρ_inv·Δφ²/8 outside it (ρ_inv the involute's radius of curvature, under
the tip radius); :func:`step_for` picks Δφ for a stated tolerance.

Exact involute, for the test and the drawing: the flank to the right of the space (clockwise
from +y) is at the clockwise angle β(R) = e/(2r) + inv α_R − inv α, α_R = arccos(r_b/R), e = p − s
the space width on the reference circle; a point at (R, β_P) is r_b·|β_P − inv α_P − (e/(2r) − inv α)|
from it along the normal (the normals of an involute are tangent to its base circle).
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from shapely.geometry import Polygon

__all__ = ["cutter_tooth", "cut_wheel", "step_for", "involute_distance", "flank_angle", "ARC_SEGMENTS"]

#: Segments of the cutter's tip rounding (a quarter circle at most).
ARC_SEGMENTS = 24


def cutter_tooth(m: float, alpha: float, x: float, addendum: float, clearance: float, rho: float,
                 v_top: float) -> np.ndarray:
    """The outline (u, v) of one cutter tooth centred at u = 0 (see the module), from its left
    flank at ``v_top`` round its tip to its right flank at ``v_top``."""
    p = math.pi * m
    v_ref = x * m
    v_tip = v_ref - (addendum + clearance) * m
    t = math.tan(alpha)

    def half(v: float) -> float:
        return p / 4.0 + (v - v_ref) * t

    right = []
    if rho > 0.0:
        vc = v_tip + rho
        uc = half(vc) - rho / math.cos(alpha)
        for a in np.linspace(-math.pi / 2.0, -alpha, ARC_SEGMENTS + 1):
            right.append((uc + rho * math.cos(a), vc + rho * math.sin(a)))
    else:
        right.append((half(v_tip), v_tip))
    right.append((half(v_top), v_top))
    right = np.array(right)
    left = right[::-1] * np.array([-1.0, 1.0])
    if right[0, 0] > 1e-12:
        return np.vstack([left, right])
    return np.vstack([left[:-1], right])         # a pointed tip: one vertex


def step_for(tolerance: float, tip_radius: float, base_radius: float) -> float:
    """The rolling step Δφ (rad) whose scallops on the involute stay within ``tolerance`` (mm):
    ρ_inv·Δφ²/8 ≤ tolerance with ρ_inv ≤ √(r_a² − r_b²)."""
    rho = math.sqrt(max(tip_radius ** 2 - base_radius ** 2, 1e-12))
    return min(math.sqrt(8.0 * tolerance / rho), math.radians(1.0))


def cut_wheel(z: int, m: float, alpha: float, x: float, addendum: float, clearance: float, rho: float,
              tip_diameter: float, *, tolerance: float = 1e-4, spaces: int = 2, first: int = 0) -> Polygon:
    """The wheel's outline near the +y axis: the blank (tip circle ``tip_diameter``) within the
    sector of the spaces ``first`` … ``first + spaces − 1`` (centred at the clockwise angles k·2π/z)
    and half a pitch beyond, less the cutter's positions rolled in steps for ``tolerance`` (mm);
    the teeth between those spaces are whole."""
    r = m * z / 2.0
    ra = tip_diameter / 2.0
    rb = r * math.cos(alpha)
    tau = 2.0 * math.pi / z
    v_top = ra - r + 2.0 * m
    tooth = cutter_tooth(m, alpha, x, addendum, clearance, rho, v_top)
    p = math.pi * m
    dphi = step_for(tolerance, ra, rb)
    # the sector: from half a pitch anticlockwise of space 0 to half a pitch past the last space
    a0, a1 = (first - 0.5) * tau, (first + spaces - 0.5) * tau           # clockwise angles from +y
    angles = np.linspace(a0, a1, 721)
    fan = [(0.0, 0.0)] + [(ra * 1.01 * math.sin(a), ra * 1.01 * math.cos(a)) for a in angles]
    blank = Polygon(fan).intersection(shapely.Point(0.0, 0.0).buffer(ra, quad_segs=720))
    # the cutter's tooth at u = k·p cuts the space at the clockwise angle k·τ while φ runs through
    # the cutting (the flank's contact runs along the line of action, ≤ 3m high: 3m/(sin α cos α) of roll)
    reach = 3.0 * m / (math.sin(alpha) * math.cos(alpha)) / r + 0.5 * tau
    phis = np.arange(-reach, reach + dphi, dphi)
    cuts = []
    for k in range(first - 1, first + spaces + 1):
        uv = tooth + np.array([k * p, 0.0])
        for phi in phis:
            c, s = math.cos(phi), math.sin(phi)
            u = uv[:, 0] - r * phi
            v = r + uv[:, 1]
            cuts.append(np.column_stack([c * u + s * v, -s * u + c * v]))
    swept = shapely.union_all(shapely.polygons(cuts))
    return blank.difference(swept)


def flank_angle(radius: np.ndarray, m: float, z: int, alpha: float, x: float) -> np.ndarray:
    """The clockwise angle from +y (rad) of the involute flank right of space 0 at ``radius`` (mm)."""
    rb = m * z / 2.0 * math.cos(alpha)
    a_r = np.arccos(np.clip(rb / np.asarray(radius, float), -1.0, 1.0))
    return _flank_offset(m, z, alpha, x) + np.tan(a_r) - a_r


def involute_distance(points: np.ndarray, m: float, z: int, alpha: float, x: float) -> np.ndarray:
    """The distance (mm) of ``points`` (N, 2; outside the base circle) from the involute flank right
    of space 0, along its normal (see the module)."""
    rb = m * z / 2.0 * math.cos(alpha)
    pts = np.asarray(points, float)
    radius = np.hypot(pts[:, 0], pts[:, 1])
    beta = np.arctan2(pts[:, 0], pts[:, 1])            # clockwise from +y
    a_p = np.arccos(np.clip(rb / radius, -1.0, 1.0))
    return rb * np.abs(beta - (np.tan(a_p) - a_p) - _flank_offset(m, z, alpha, x))


def _flank_offset(m: float, z: int, alpha: float, x: float) -> float:
    """The clockwise angle of the flank right of space 0 at the base circle: e/(2r) − inv α, with
    e = p − s the space width on the reference circle r."""
    e = math.pi * m - m * (math.pi / 2.0 + 2.0 * x * math.tan(alpha))
    return e / (m * z) - (math.tan(alpha) - alpha)

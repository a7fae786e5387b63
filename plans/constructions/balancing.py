"""The balancing sheet's polygons (paper mm, y up): the couple polygon of the masses' m·r·l
about the reference plane, closed by the other balancing plane's m·r·l, and the force polygon
of the masses' m·r and that plane's, closed by the reference plane's m·r (textbook method of
the reference plane), each to a scale of its own; and the shaft seen from the side with its
planes (:class:`ShaftPlanes`).

Each polygon lays its sides head to tail from its start point ``a`` in the order of
:class:`~plans.dynamics.balancing.RotorBalance` (a zero side — a mass in the reference plane has
no m·r·l — is not drawn, it stays in the table), the vertices lettered a, b, c, …; the closing
vector runs from the last vertex back to ``a``. Reads a solved RotorBalance; computes nothing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..dynamics.balancing import RotorBalance
from .scales import standard_scale

__all__ = ["BalanceSide", "BalancePolygon", "ShaftPlanes", "balance_polygons", "shaft_planes", "POLYGON_MM"]

#: Wanted drawn length of a polygon's largest side (never longer), and its largest extent, mm.
POLYGON_MM = (60.0, 90.0)
POLYGON_MAX_MM = 110.0
#: A side shorter than this fraction of the polygon's largest is zero: not drawn.
ZERO_REL = 1e-12


@dataclass(frozen=True)
class BalanceSide:
    """One drawn vector: ``quantity`` (``mrl:2`` the second mass's m·r·l, ``mrl:B`` a balancing
    plane's …), ``value`` its magnitude (kg·m or kg·m²), ``tail``/``head`` (mm) and the letters of
    the vertices it joins."""

    quantity: str
    value: float
    tail: tuple[float, float]
    head: tuple[float, float]
    start: str
    end: str


@dataclass(frozen=True)
class BalancePolygon:
    """``kind`` "couple" or "force", ``mu`` (kg·m²/mm or kg·m/mm), ``unit``, the drawn ``sides``
    and the ``closing`` vector (None: the polygon closes by itself — a rotor already balanced —
    or, for the couple polygon of one balancing plane, nothing closes it), ``points`` the lettered
    vertices (mm)."""

    kind: str
    mu: float
    unit: str
    sides: tuple[BalanceSide, ...]
    closing: BalanceSide | None
    points: tuple[tuple[str, tuple[float, float]], ...]


@dataclass(frozen=True)
class ShaftPlanes:
    """The shaft from the side: ``mu`` (m/mm), each plane (label, x mm) — the masses' numbered 1 …
    and the balancing planes' L (the reference plane) and M — and the shaft's ends (mm)."""

    mu: float
    planes: tuple[tuple[str, float], ...]
    ends: tuple[float, float]


def _letters(n: int) -> list[str]:
    """a, b, …, z, then a′, b′, …, z′, then a″ (a′′), …: a letter for each of up to 102 vertices."""
    return [chr(ord("a") + k % 26) + "′" * (k // 26) for k in range(n)]


def _polygon(kind: str, unit: str, sides: list[tuple[str, complex]], closing: tuple[str, complex] | None
             ) -> BalancePolygon:
    vecs = [v for _, v in sides] + ([closing[1]] if closing is not None else [])
    top = max((abs(v) for v in vecs), default=0.0)
    drawn = [(q, v) for q, v in sides if abs(v) > ZERO_REL * top]
    at, corners = 0j, [0j]
    for _, v in drawn:
        at += v
        corners.append(at)
    extent = max(max(c.real for c in corners) - min(c.real for c in corners),
                 max(c.imag for c in corners) - min(c.imag for c in corners), top) if top > 0 else 1.0
    mu = standard_scale(top if top > 0 else 1.0, window=POLYGON_MM, limit=POLYGON_MAX_MM, extent=extent)
    letters = _letters(len(corners))
    pts = [(c.real / mu + 0.0, c.imag / mu + 0.0) for c in corners]
    out = [BalanceSide(q, abs(v), pts[k], pts[k + 1], letters[k], letters[k + 1]) for k, (q, v) in enumerate(drawn)]
    close = None
    if closing is not None and abs(closing[1]) > ZERO_REL * top:
        close = BalanceSide(closing[0], abs(closing[1]), pts[-1], pts[0], letters[len(pts) - 1], letters[0])
    return BalancePolygon(kind, mu, unit, tuple(out), close, tuple(zip(letters, pts)))


def balance_polygons(b: RotorBalance) -> tuple[BalancePolygon, ...]:
    """The couple polygon (two balancing planes only) and the force polygon of ``b``."""
    out = []
    if b.dynamic:
        other = b.balancing[1]
        out.append(_polygon("couple", "kg·m²", [(f"mrl:{k + 1}", m.mrl) for k, m in enumerate(b.masses)],
                            ("mrl:M", other.mrl)))
    sides = [(f"mr:{k + 1}", m.mr) for k, m in enumerate(b.masses)]
    if b.dynamic:
        sides.append(("mr:M", b.balancing[1].mr))
    out.append(_polygon("force", "kg·m", sides, ("mr:L", b.balancing[0].mr)))
    return tuple(out)


def shaft_planes(b: RotorBalance, length_mm: float = 100.0) -> ShaftPlanes | None:
    """The planes along the shaft at a series scale fitting ``length_mm``; None when no mass has a
    plane (one balancing plane, the masses in it)."""
    marks = [(str(k + 1), m.plane) for k, m in enumerate(b.masses) if m.plane is not None]
    marks += [(name, p.plane) for name, p in zip(("L", "M"), b.balancing)]
    if len(marks) < 2:
        return None
    lo, hi = min(v for _, v in marks), max(v for _, v in marks)
    span = hi - lo if hi > lo else 1.0
    mu = standard_scale(span, window=(0.6 * length_mm, length_mm), limit=length_mm, extent=span)
    return ShaftPlanes(mu, tuple((name, (v - lo) / mu) for name, v in marks), (-8.0, span / mu + 8.0))


def angle_deg(z: complex) -> float:
    """The direction of ``z``, degrees in [0, 360)."""
    return math.degrees(math.atan2(z.imag, z.real)) % 360.0

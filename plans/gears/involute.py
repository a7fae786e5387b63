"""The geometry of one external involute spur pair with profile shift (ISO 21771, textbook
§3.1), exactly: no table look-up, every value from its formula.

Lengths in mm, angles in radians unless a name says degrees; wheel 1 is the pinion. The pair
is cut by the standard basic rack (pressure angle α, addendum ha*·m, clearance c*·m) shifted by
x·m (positive away from the wheel's centre).

- d = m·z, d_b = d·cos α, p = π·m, p_b = p·cos α;
- the working pressure angle from inv α_w = inv α + 2·tan α·(x1 + x2)/(z1 + z2) (inv a = tan a − a),
  solved by Newton's method to the last bit (:func:`inv_inverse`);
- a = m(z1 + z2)/2, a_w = a·cos α / cos α_w, y = (a_w − a)/m, Δy = x1 + x2 − y;
- d_w = d_b / cos α_w; d_a = d + 2(ha* + x − Δy)·m (the tips shortened so that the radial
  clearance stays c*·m), d_f = d − 2(ha* + c* − x)·m;
- s = m(π/2 + 2x·tan α) on the reference circle, s_a = d_a(s/d + inv α − inv α_a) on the tip;
- the line of action N1N2 = a_w·sin α_w, its active part B1B2 between the tip circles,
  ε_α = B1B2 / p_b;
- the specific sliding at B1, B2 (the ends of the active line): ϑ = (v_t1 − v_t2)/v_t of the
  wheel's own sliding speed, ϑ1 = 1 − ρ2/(u·ρ1), ϑ2 = 1 − u·ρ1/ρ2 with u = z2/z1 and ρ the
  distances from N1, N2;
- undercut by the rack: x < x_min = ha* − z·sin²α/2;
- the paths of approach (from B2 to the pitch point P) and recess (from P to B1), the pinion
  driving: g2 − r_w2·sin α_w and g1 − r_w1·sin α_w with g = √(r_a² − r_b²); the arc of contact
  B1B2/cos α_w on the working pitch circles, and the angles the wheels turn through while one pair
  is in contact, B1B2/r_b (Khurmi & Gupta, Theory of Machines, ch. Toothed Wheels).

Unequal addenda ``addenda`` = (ha1*, ha2*): each tip is d + 2(ha_i* + x_i − Δy)·m; both wheels are
cut by one basic rack of the larger addendum (``addendum``, the roots and x_min). The internal pair
and the pinion with a rack are in :mod:`.contact` (the same :class:`GearPair`, ``kind`` says which).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["GearPair", "gear_pair", "inv", "inv_inverse", "min_shift"]


def inv(a: float) -> float:
    """The involute function tan a − a."""
    return math.tan(a) - a


def inv_inverse(value: float) -> float:
    """The angle a in [0, π/2) whose involute is ``value`` (≥ 0): Newton's method on
    tan a − a = value (derivative tan² a) from Cheng's cube-root start, to the last bit."""
    if not value >= 0.0 or not math.isfinite(value):
        raise ValueError(f"inv α is 0 or more, got {value!r}")
    if value == 0.0:
        return 0.0
    a = min((3.0 * value) ** (1.0 / 3.0), 1.5)      # tan a − a ≈ a³/3 for small a
    for _ in range(100):
        t = math.tan(a)
        step = (t - a - value) / (t * t)
        a_new = a - step
        if a_new <= 0.0:
            a_new = a / 2.0
        elif a_new >= math.pi / 2:
            a_new = (a + math.pi / 2) / 2.0
        if abs(a_new - a) <= 4e-16 * a_new:
            return a_new
        a = a_new
    return a


def min_shift(z: int | float, alpha: float = math.radians(20.0), addendum: float = 1.0) -> float:
    """The smallest shift coefficient x that a rack of addendum ha* and pressure angle α cuts
    without undercut: x_min = ha* − z·sin²α/2."""
    return addendum - z * math.sin(alpha) ** 2 / 2.0


@dataclass(frozen=True)
class GearPair:
    """One pair (see the module; ``kind`` "external", "internal" or "rack"): ``z``, ``x`` (wheel 1,
    wheel 2), ``module`` m (mm),
    ``alpha`` α and ``alpha_w`` α_w (rad), ``a``, ``a_w`` (mm), ``y``, ``delta_y``; per wheel
    (tuples of two, mm): ``d``, ``db``, ``dw``, ``da``, ``df``, ``s`` (reference), ``sa`` (tip);
    ``p``, ``pb`` (mm), ``line`` N1N2, ``active`` B1B2 (mm), ``contact_ratio`` ε_α,
    ``sliding`` (ϑ1 at B2, ϑ2 at B1), ``x_min`` per wheel, ``undercut`` per wheel; ``addenda``
    (ha1*, ha2*) of the tips, ``approach`` and ``recess`` (mm, the pinion driving). A rack (wheel 2)
    has z = None and infinite diameters; its x_min is −inf (not cut by a rack), its line N1N2 inf;
    a ring gear's x_min is −inf too (it is cut by a pinion cutter, the rack's limit is not its)."""

    z: tuple[int, int | None]
    x: tuple[float, float]
    module: float
    alpha: float
    addendum: float
    clearance: float
    alpha_w: float
    a: float
    a_w: float
    y: float
    delta_y: float
    d: tuple[float, float]
    db: tuple[float, float]
    dw: tuple[float, float]
    da: tuple[float, float]
    df: tuple[float, float]
    s: tuple[float, float]
    sa: tuple[float, float]
    p: float
    pb: float
    line: float
    active: float
    contact_ratio: float
    sliding: tuple[float, float]
    x_min: tuple[float, float]
    undercut: tuple[bool, bool]
    kind: str = "external"
    addenda: tuple[float, float] | None = None
    approach: float = math.nan
    recess: float = math.nan

    @property
    def working_pressure_angle_deg(self) -> float:
        return math.degrees(self.alpha_w)

    @property
    def tip_addenda(self) -> tuple[float, float]:
        """(ha1*, ha2*): ``addenda``, or the one ``addendum`` of both wheels."""
        return self.addenda if self.addenda is not None else (self.addendum, self.addendum)

    @property
    def arc(self) -> float:
        """The arc of contact on the working pitch circles, B1B2 / cos α_w, mm."""
        return self.active / math.cos(self.alpha_w)

    @property
    def angles_turned(self) -> tuple[float, float | None]:
        """The angles (rad) the pinion and wheel 2 turn through from engagement to disengagement,
        B1B2 / r_b; None for a rack (it travels :attr:`arc` mm)."""
        return (2.0 * self.active / self.db[0],
                None if self.kind == "rack" else 2.0 * self.active / self.db[1])


def gear_pair(z1: int, z2: int, module: float, *, x1: float = 0.0, x2: float = 0.0,
              pressure_angle_deg: float = 20.0, addendum: float = 1.0, clearance: float = 0.25,
              addenda: tuple[float, float] | None = None) -> GearPair:
    """The geometry of the external pair z1/z2 of ``module`` (mm) with shifts x1, x2; ``addenda``
    (ha1*, ha2*) the tips' addenda when unequal (the cutter's ``addendum`` then their larger)."""
    alpha = math.radians(pressure_angle_deg)
    m = module
    z = (z1, z2)
    x = (x1, x2)
    alpha_w = inv_inverse(inv(alpha) + 2.0 * math.tan(alpha) * (x1 + x2) / (z1 + z2))
    a = m * (z1 + z2) / 2.0
    a_w = a * math.cos(alpha) / math.cos(alpha_w)
    y = (a_w - a) / m
    dy = x1 + x2 - y
    d = tuple(m * k for k in z)
    db = tuple(v * math.cos(alpha) for v in d)
    dw = tuple(v / math.cos(alpha_w) for v in db)
    tips = addenda if addenda is not None else (addendum, addendum)
    da = tuple(dv + 2.0 * (hv + xv - dy) * m for dv, xv, hv in zip(d, x, tips))
    df = tuple(dv - 2.0 * (addendum + clearance - xv) * m for dv, xv in zip(d, x))
    s = tuple(m * (math.pi / 2.0 + 2.0 * xv * math.tan(alpha)) for xv in x)
    sa = tuple(dav * (sv / dv + inv(alpha) - inv(math.acos(min(dbv / dav, 1.0))))
               for dav, sv, dv, dbv in zip(da, s, d, db))
    p = math.pi * m
    pb = p * math.cos(alpha)
    line = a_w * math.sin(alpha_w)
    g1, g2 = (math.sqrt(max((dav / 2) ** 2 - (dbv / 2) ** 2, 0.0)) for dav, dbv in zip(da, db))
    active = g1 + g2 - line
    u = z2 / z1
    rho1_b2 = line - g2          # B2: where wheel 2's tip circle cuts the line, measured from N1
    rho2_b1 = line - g1          # B1: wheel 1's tip circle, measured from N2
    sliding = (1.0 - (line - rho1_b2) / (u * rho1_b2) if rho1_b2 > 0 else -math.inf,
               1.0 - u * (line - rho2_b1) / rho2_b1 if rho2_b1 > 0 else -math.inf)
    x_min = tuple(min_shift(k, alpha, addendum) for k in z)
    undercut = tuple(xv < xm - 1e-12 for xv, xm in zip(x, x_min))
    return GearPair(z=z, x=x, module=m, alpha=alpha, addendum=addendum, clearance=clearance, alpha_w=alpha_w, a=a,
                    a_w=a_w, y=y, delta_y=dy, d=d, db=db, dw=dw, da=da, df=df, s=s, sa=sa, p=p, pb=pb, line=line,
                    active=active, contact_ratio=active / pb, sliding=sliding, x_min=x_min, undercut=undercut,
                    addenda=addenda, approach=g2 - dw[1] / 2 * math.sin(alpha_w),
                    recess=g1 - dw[0] / 2 * math.sin(alpha_w))

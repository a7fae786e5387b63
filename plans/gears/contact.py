"""The internal pair (wheel 2 a ring gear) and the pinion with a rack, as :class:`GearPair`s, with
the internal pair's interference conditions and the sliding velocities of any pair.

Lengths in mm, angles in radians; wheel 1 is the pinion and drives. Both wheels are cut by the
basic rack (pressure angle α, addendum ``addendum``·m, clearance c*·m), the ring by a pinion
cutter of that rack's profile; shifts x·m are positive away from the pinion's centre and, for the
ring, away from its centre (its teeth then thinner, its tip circle larger: KHK Gear Technical
Reference, "internal gears"; SDP/SI, Elements of Metric Gear Technology, §4.4 and Table 4-4).

**Internal pair** (z2 > z1):

- inv α_w = 2·tan α·(x2 − x1)/(z2 − z1) + inv α; a = m(z2 − z1)/2, a_w = a·cos α/cos α_w,
  y = (a_w − a)/m, Δy = (x2 − x1) − y (the tips are not shortened: the clearances are (c* + Δy)·m,
  and Δy ≥ 0);
- d_a1 = d1 + 2(ha1* + x1)·m, d_a2 = d2 − 2(ha2* − x2)·m (inside the pitch circle);
  d_f1 = d1 − 2(ha* + c* − x1)·m, d_f2 = d2 + 2(ha* + c* + x2)·m (outside it);
- s2 = m(π/2 − 2·x2·tan α), s_a2 = d_a2(s2/d2 − inv α + inv α_a2) (the ring's tooth is thinnest
  at its tip, the inner circle);
- N1 lies between N2 and P on the line of action, N1N2 = a_w·sin α_w; the ring's tip circle cuts it
  g2 = √(r_a2² − r_b2²) from N2, the pinion's g1 from N1: approach r_w2·sin α_w − g2, recess
  g1 − r_w1·sin α_w, B1B2 = N1N2 + g1 − g2;
- specific sliding ϑ1 = 1 − ρ2/(u·ρ1), ϑ2 = 1 − u·ρ1/ρ2 with ρ2 = ρ1 + N1N2 (both wheels turn
  one way, u = z2/z1).

**Interference of the internal pair** (SDP/SI, Elements of Metric Gear Technology, §5.2,
Eq. (5-4) … (5-8); the same in KHK's Gear Technical Reference, "internal gears"):

- *involute interference*: the ring's tip must meet the line of action no nearer N2 than N1,
  g2 ≥ N1N2 — the same as z1/z2 ≥ 1 − tan α_a2/tan α_w (Eq. 5-4). Refused: the ring's tip would
  cut the pinion's flank below its base circle;
- *tip (trochoid) interference*: the pinion's tip, leaving the mesh, must clear the ring's tooth
  it leaves: θ1·z1/z2 + inv α_w − inv α_a2 ≥ θ2 (Eq. 5-6) with
  θ1 = acos((r_a2² − r_a1² − a_w²)/(2·a_w·r_a1)) + inv α_a1 − inv α_w,
  θ2 = acos((a_w² + r_a2² − r_a1²)/(2·a_w·r_a2)) (Eq. 5-7). This is the condition behind the
  textbooks' smallest difference of teeth: for standard wheels (α = 20°, ha* = 1, x = 0) it needs
  z2 − z1 ≥ 9 for pinions of 17 … 69 teeth, 10 for 11 … 16, 8 from 70 on (SDP/SI: "larger than 9").
  :func:`tip_interference` returns the left side less the right (rad; below 0: interference).

Trimming interference (pulling the ring off radially) is not checked: the wheels are assembled
axially.

**Pinion and rack**: the rack's reference line at a_w = r1 + x1·m from O1 (α_w = α, the pinion's
working circle its reference circle), its tip line (ha2* − x1)·m inside the pitch line: approach
(ha2* − x1)·m/sin α, recess g1 − r1·sin α; interference where the approach passes N1
(PN1 = r1·sin α). ϑ1 = 1 − PN1/ρ1, ϑ2 = 1 − ρ1/PN1 (the rack's flank moves at ω1·PN1 along itself).

Sliding velocities (Khurmi & Gupta, Theory of Machines, ch. Toothed Wheels): (ω1 + ω2) times the
distance from P (external), (ω1 − ω2) times it (internal: both turn one way; ω1 > ω2), ω1 times it
(a rack) — magnitudes, at engagement (the path of approach) and disengagement (recess).

Imports only the standard library and plans.gears.involute.
"""

from __future__ import annotations

import math

from .involute import GearPair, inv, inv_inverse, min_shift

__all__ = ["internal_pair", "rack_pair", "tip_interference", "pair_tip_interference", "standard_tip_interference",
           "involute_interference", "sliding_velocities"]


def _tip_thickness(da: float, db: float, s: float, d: float, internal: bool) -> float:
    """The tooth thickness on the tip circle d_a (mm): d_a(s/d + inv α − inv α_a) for an external
    tooth, d_a(s/d − inv α + inv α_a) for a ring's (its tooth thins toward its tip, the inner circle)."""
    alpha = math.acos(db / d)
    alpha_a = math.acos(min(db / da, 1.0))
    if internal:
        return da * (s / d - inv(alpha) + inv(alpha_a))
    return da * (s / d + inv(alpha) - inv(alpha_a))


def internal_pair(z1: int, z2: int, module: float, *, x1: float = 0.0, x2: float = 0.0,
                  pressure_angle_deg: float = 20.0, addendum: float = 1.0, clearance: float = 0.25,
                  addenda: tuple[float, float] | None = None) -> GearPair:
    """The internal pair: pinion z1 inside ring gear z2 (> z1), ``module`` mm, shifts x1, x2
    (see the module); ``addenda`` (ha1*, ha2*) when unequal, the cutter's ``addendum`` then their larger."""
    alpha = math.radians(pressure_angle_deg)
    m = module
    tips = addenda if addenda is not None else (addendum, addendum)
    alpha_w = inv_inverse(inv(alpha) + 2.0 * math.tan(alpha) * (x2 - x1) / (z2 - z1))
    a = m * (z2 - z1) / 2.0
    a_w = a * math.cos(alpha) / math.cos(alpha_w)
    y = (a_w - a) / m
    dy = x2 - x1 - y
    d = (m * z1, m * z2)
    db = tuple(v * math.cos(alpha) for v in d)
    dw = tuple(v / math.cos(alpha_w) for v in db)
    da = (d[0] + 2.0 * (tips[0] + x1) * m, d[1] - 2.0 * (tips[1] - x2) * m)
    df = (d[0] - 2.0 * (addendum + clearance - x1) * m, d[1] + 2.0 * (addendum + clearance + x2) * m)
    s = (m * (math.pi / 2.0 + 2.0 * x1 * math.tan(alpha)), m * (math.pi / 2.0 - 2.0 * x2 * math.tan(alpha)))
    sa = (_tip_thickness(da[0], db[0], s[0], d[0], False), _tip_thickness(da[1], db[1], s[1], d[1], True))
    p = math.pi * m
    pb = p * math.cos(alpha)
    line = a_w * math.sin(alpha_w)                      # N1N2, N1 between N2 and P
    g1, g2 = (math.sqrt(max((dav / 2) ** 2 - (dbv / 2) ** 2, 0.0)) for dav, dbv in zip(da, db))
    active = line + g1 - g2
    u = z2 / z1
    rho1_b2 = g2 - line                                 # B2 (the ring's tip), measured from N1
    sliding = (1.0 - g2 / (u * rho1_b2) if rho1_b2 > 0 else -math.inf,
               1.0 - u * g1 / (g1 + line) if g1 > 0 else -math.inf)
    x_min = (min_shift(z1, alpha, addendum), -math.inf)
    undercut = (x1 < x_min[0] - 1e-12, False)
    return GearPair(z=(z1, z2), x=(x1, x2), module=m, alpha=alpha, addendum=addendum, clearance=clearance,
                    alpha_w=alpha_w, a=a, a_w=a_w, y=y, delta_y=dy, d=d, db=db, dw=dw, da=da, df=df, s=s, sa=sa,
                    p=p, pb=pb, line=line, active=active, contact_ratio=active / pb, sliding=sliding, x_min=x_min,
                    undercut=undercut, kind="internal", addenda=addenda,
                    approach=dw[1] / 2 * math.sin(alpha_w) - g2, recess=g1 - dw[0] / 2 * math.sin(alpha_w))


def rack_pair(z1: int, module: float, *, x1: float = 0.0, pressure_angle_deg: float = 20.0,
              addendum: float = 1.0, clearance: float = 0.25,
              addenda: tuple[float, float] | None = None) -> GearPair:
    """The pinion z1 (shift x1) with a rack of the basic profile (see the module): wheel 2's
    diameters are infinite, its z None; ``a`` is r1, ``a_w`` the distance r1 + x1·m from O1 to
    the rack's reference line."""
    alpha = math.radians(pressure_angle_deg)
    m = module
    tips = addenda if addenda is not None else (addendum, addendum)
    inf = math.inf
    r1 = m * z1 / 2.0
    d = (2.0 * r1, inf)
    db = (d[0] * math.cos(alpha), inf)
    da = (d[0] + 2.0 * (tips[0] + x1) * m, inf)
    df = (d[0] - 2.0 * (addendum + clearance - x1) * m, inf)
    s = (m * (math.pi / 2.0 + 2.0 * x1 * math.tan(alpha)), m * math.pi / 2.0)
    sa = (_tip_thickness(da[0], db[0], s[0], d[0], False), m * (math.pi / 2.0 - 2.0 * tips[1] * math.tan(alpha)))
    p = math.pi * m
    pb = p * math.cos(alpha)
    pn1 = r1 * math.sin(alpha)
    g1 = math.sqrt(max((da[0] / 2) ** 2 - (db[0] / 2) ** 2, 0.0))
    approach = (tips[1] - x1) * m / math.sin(alpha)
    recess = g1 - pn1
    active = approach + recess
    rho1_b2 = pn1 - approach
    sliding = (1.0 - pn1 / rho1_b2 if rho1_b2 > 0 else -math.inf, 1.0 - g1 / pn1)
    x_min = (min_shift(z1, alpha, addendum), -inf)
    return GearPair(z=(z1, None), x=(x1, 0.0), module=m, alpha=alpha, addendum=addendum, clearance=clearance,
                    alpha_w=alpha, a=r1, a_w=r1 + x1 * m, y=x1, delta_y=0.0, d=d, db=db, dw=d, da=da, df=df, s=s,
                    sa=sa, p=p, pb=pb, line=inf, active=active, contact_ratio=active / pb, sliding=sliding,
                    x_min=x_min, undercut=(x1 < x_min[0] - 1e-12, False), kind="rack", addenda=addenda,
                    approach=approach, recess=recess)


def involute_interference(p: GearPair) -> float:
    """The internal pair's involute margin g2 − N1N2 (mm): where the ring's tip circle meets the
    line of action, less the distance N2N1; below 0 the ring's tip reaches inside N1 and cuts the
    pinion's flank below its base circle (SDP/SI Eq. 5-4: z1/z2 ≥ 1 − tan α_a2/tan α_w)."""
    g2 = math.sqrt(max((p.da[1] / 2) ** 2 - (p.db[1] / 2) ** 2, 0.0))
    return g2 - p.line


def tip_interference(z1: int, z2: int, alpha: float, a_w: float, alpha_w: float, ra1: float, ra2: float,
                     rb1: float, rb2: float) -> float:
    """The tip (trochoid) interference margin of an internal pair (rad; below 0 the pinion's tip
    strikes the ring's tooth as it leaves the mesh): θ1·z1/z2 + inv α_w − inv α_a2 − θ2, SDP/SI,
    Elements of Metric Gear Technology, §5.2 (b), Eq. (5-6) … (5-8). Lengths in mm, angles in rad.
    −inf where the tip circles do not cross (no room for the pinion's tip: the pair cannot run)."""
    c1 = (ra2 * ra2 - ra1 * ra1 - a_w * a_w) / (2.0 * a_w * ra1)
    c2 = (a_w * a_w + ra2 * ra2 - ra1 * ra1) / (2.0 * a_w * ra2)
    if not (-1.0 <= c1 <= 1.0 and -1.0 <= c2 <= 1.0):
        return -math.inf
    alpha_a1 = math.acos(min(rb1 / ra1, 1.0))
    alpha_a2 = math.acos(min(rb2 / ra2, 1.0))
    theta1 = math.acos(c1) + inv(alpha_a1) - inv(alpha_w)
    theta2 = math.acos(c2)
    return theta1 * z1 / z2 + inv(alpha_w) - inv(alpha_a2) - theta2


def pair_tip_interference(p: GearPair) -> float:
    """:func:`tip_interference` of the internal pair ``p`` (rad)."""
    return tip_interference(p.z[0], p.z[1], p.alpha, p.a_w, p.alpha_w, p.da[0] / 2, p.da[1] / 2, p.db[0] / 2,
                            p.db[1] / 2)


def standard_tip_interference(z1: int, z2: int) -> float:
    """:func:`tip_interference` of standard wheels z1 inside ring z2 (α = 20°, ha* = 1, x = 0),
    rad, of any module: what a gear train of standard wheels is checked by."""
    alpha = math.radians(20.0)
    m = 1.0
    r1, r2 = m * z1 / 2.0, m * z2 / 2.0
    return tip_interference(z1, z2, alpha, r2 - r1, alpha, r1 + m, r2 - m, r1 * math.cos(alpha),
                            r2 * math.cos(alpha))


def sliding_velocities(p: GearPair, n1: float) -> tuple[float, float]:
    """The sliding velocities (m/s, magnitudes) at engagement and disengagement with the pinion
    at ``n1`` rpm: (ω1 ± ω2) or ω1 (a rack) times the paths of approach and recess."""
    w1 = 2.0 * math.pi * n1 / 60.0
    if p.kind == "rack":
        w = w1
    else:
        w2 = w1 * p.z[0] / p.z[1]
        w = w1 - w2 if p.kind == "internal" else w1 + w2
    return w * p.approach / 1000.0, w * p.recess / 1000.0

"""One involute pair of a scene (``[gear_pair]``): its shifts by the scene's rule, its geometry
(:mod:`.involute`) and the checks a designer makes — refused in one line where the pair cannot
work, warned where it works poorly:

- a pointed tip (s_a ≤ 0) is refused; s_a < 0.25·m warns;
- ε_α < 1 is refused; ε_α < 1.2 warns;
- interference (a tip circle reaching past the other wheel's tangency point N) is refused
  (a warning when only the cutting is drawn: the wheels are not put in mesh);
- undercut (x < x_min) warns;
- an internal pair (``internal``): the involute interference (the ring's tip inside N1) and the
  tip (trochoid) interference of :mod:`.contact` are refused like the external interference;
- a pinion with a rack (``rack``): the rack's tip line past N1 is interference, refused alike.

Shift rules: "none" (x = 0); "no_undercut": x_i = max(x_min,i, 0), the smallest shifts that are
not negative and avoid undercut (a rack is not shifted by it; an internal pair takes no rule);
"balanced": x1 = −x2 (the centre distance stays m(z1 + z2)/2),
chosen so that the specific sliding at the two ends of the active line is equal (ϑ1 at B2 =
ϑ2 at B1), within the bounds that keep both wheels free of undercut.

Imports only plans.errors, plans.scene and plans.gears (and the standard library).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import SceneError
from ..scene.gear_pair import MAX_PAIR_TEETH, MIN_PAIR_TEETH, GearPairSpec
from ..scene.gears import GearTrain
from .contact import involute_interference, internal_pair, pair_tip_interference, rack_pair, sliding_velocities
from .involute import GearPair, gear_pair, inv, min_shift

__all__ = ["PairAnalysis", "analyse_pair", "THIN_TIP", "LOW_CONTACT_RATIO"]

#: A tip thinner than this many modules warns.
THIN_TIP = 0.25
#: A contact ratio under this warns (under 1 the pair cannot mesh continuously: refused).
LOW_CONTACT_RATIO = 1.2


@dataclass(frozen=True)
class PairAnalysis:
    """The pair (:class:`~plans.gears.involute.GearPair`), the rule that gave its shifts
    ("given", "none", "no_undercut", "balanced"), the cutter's tip radius ρ (mm), the wheels'
    names (from a train's mesh, else "1", "2"), one-line ``warnings``, the pinion's speed ``n1``
    (rpm, None when not given) and the ``sliding_velocity`` at engagement and disengagement (m/s)."""

    pair: GearPair
    rule: str
    tip_radius: float
    names: tuple[str, str]
    warnings: tuple[str, ...]
    n1: float | None = None
    sliding_velocity: tuple[float, float] | None = None


def _build(spec: GearPairSpec, z1: int, z2: int | None, m: float, x1: float, x2: float,
           internal: bool = False) -> GearPair:
    common = dict(pressure_angle_deg=spec.pressure_angle, addendum=spec.addendum, clearance=spec.clearance,
                  addenda=spec.addenda)
    if spec.rack:
        return rack_pair(z1, m, x1=x1, **common)
    if internal:
        return internal_pair(z1, z2, m, x1=x1, x2=x2, **common)
    return gear_pair(z1, z2, m, x1=x1, x2=x2, **common)


def _balanced(spec: GearPairSpec, z1: int, z2: int, m: float) -> tuple[float, float]:
    """x1 = −x2 with equal specific sliding at the ends of the active line (bisection; the
    difference ϑ1 − ϑ2 grows with x1), kept where neither wheel is undercut."""
    alpha = math.radians(spec.pressure_angle)
    lo, hi = min_shift(z1, alpha, spec.addendum), -min_shift(z2, alpha, spec.addendum)
    if lo > hi:
        return lo, -lo
    lo, hi = max(lo, -1.0), min(hi, 1.0)

    def f(x: float) -> float:
        s = _build(spec, z1, z2, m, x, -x).sliding
        return s[0] - s[1]

    f_lo, f_hi = f(lo), f(hi)
    if f_lo >= 0.0 or f_hi <= 0.0:           # balance lies beyond the undercut bounds: the nearer bound
        x = lo if abs(f_lo) <= abs(f_hi) else hi
        return x, -x
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(mid) < 0.0:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-15:
            break
    x = 0.5 * (lo + hi)
    return x, -x


def analyse_pair(spec: GearPairSpec, gears: GearTrain | None = None, *, meshing: bool = True) -> PairAnalysis:
    """The pair of ``spec`` (its wheels from ``gears`` when it names a mesh), checked; with
    ``meshing`` False (only the cutting of wheel 1 is drawn) interference and a contact ratio
    under 1 are warnings, not refusals: the wheels are not put in mesh."""
    names = ("1", "2")
    if spec.mesh is not None:
        if gears is None:
            raise SceneError("mesh names two wheels of [gears], and the scene has no [gears]", key="gear_pair.mesh")
        wheels = []
        for name in spec.mesh:
            try:
                wheels.append(gears.wheel(name))
            except KeyError:
                raise SceneError(f"mesh names wheel {name!r}, which is not in [gears.wheels]",
                                 key="gear_pair.mesh") from None
        a, b = wheels
        if tuple(spec.mesh) not in gears.meshes and tuple(reversed(spec.mesh)) not in gears.meshes:
            raise SceneError(f"wheels {a.name} and {b.name} are not in mesh in [gears] meshes", key="gear_pair.mesh")
        internal = a.internal or b.internal
        if a.module is None or b.module is None:
            raise SceneError(f"wheels {a.name} and {b.name} need a module in [gears.wheels] to be drawn in mesh",
                             key="gear_pair.mesh")
        for w in (a, b):                     # the bounds z1, z2 of a pair written out have
            if not MIN_PAIR_TEETH <= w.teeth <= MAX_PAIR_TEETH:
                raise SceneError(f"wheel {w.name} has {w.teeth} teeth; a wheel of the pair drawn in mesh has "
                                 f"{MIN_PAIR_TEETH} … {MAX_PAIR_TEETH} teeth (its generation is drawn tooth by "
                                 "tooth): mesh another pair of [gears]", key="gear_pair.mesh")
        if a.internal or (a.teeth > b.teeth and not b.internal):
            a, b = b, a                      # the pinion first, a ring gear second
        if internal and b.teeth <= a.teeth:
            raise SceneError(f"ring gear {b.name} ({b.teeth} teeth) must have more teeth than {a.name} ({a.teeth}) "
                             "inside it", key="gear_pair.mesh")
        z1, z2, m, names = a.teeth, b.teeth, a.module, (a.name, b.name)
    else:
        z1, z2, m, internal = spec.z1, spec.z2, spec.module, spec.internal
    alpha = math.radians(spec.pressure_angle)
    if spec.x1 is not None:
        rule, (x1, x2) = "given", (spec.x1, spec.x2)
    elif internal and spec.shift != "none":
        raise SceneError(f"shift = {spec.shift!r} is a rule for an external pair, and ring gear {names[1]} makes this "
                         "one internal; give x1, x2", key="gear_pair.shift")
    elif spec.shift == "no_undercut" and spec.rack:
        rule, (x1, x2) = spec.shift, (max(min_shift(z1, alpha, spec.addendum), 0.0), 0.0)
    elif spec.shift == "no_undercut":
        rule, (x1, x2) = spec.shift, (max(min_shift(z1, alpha, spec.addendum), 0.0),
                                      max(min_shift(z2, alpha, spec.addendum), 0.0))
    elif spec.shift == "balanced":
        rule, (x1, x2) = spec.shift, _balanced(spec, z1, z2, m)
    else:
        rule, (x1, x2) = "none", (0.0, 0.0)
    if internal:
        if inv(alpha) + 2.0 * math.tan(alpha) * (x2 - x1) / (z2 - z1) <= 0.0:
            raise SceneError(f"x2 − x1 = {x2 - x1:g} is too negative for the internal pair {z1}/{z2}: the working "
                             "pressure angle would be 0 or less", key="gear_pair.x1")
    elif not spec.rack and x1 + x2 <= -(z1 + z2) / (2.0 * math.tan(alpha)) * (math.tan(alpha) - alpha):
        raise SceneError(f"x1 + x2 = {x1 + x2:g} is too negative for {z1} + {z2} teeth: the working pressure angle "
                         "would be 0 or less", key="gear_pair.x1")
    p = _build(spec, z1, z2, m, x1, x2, internal)
    warnings: list[str] = []
    for k in range(2):
        w = names[k]
        teeth = "a rack" if p.z[k] is None else f"{p.z[k]} teeth"
        if p.sa[k] <= 0.0:
            by_addendum = p.z[k] is None or p.addenda is not None or p.x[k] == 0.0   # no shift: the addendum's
            fix = "give a smaller addendum" + ("" if p.z[k] is None else " or shift") if p.addenda is not None else \
                "give a smaller addendum or pressure angle" if by_addendum else \
                "give a smaller shift" if p.x[k] > 0.0 else "give a shift nearer 0"
            raise SceneError(f"the tip of wheel {w} ({teeth}, x = {p.x[k]:.4g}) is pointed: s_a = "
                             f"{p.sa[k]:.4g} mm ≤ 0; {fix}",
                             key="gear_pair.addendum" if by_addendum else f"gear_pair.x{k + 1}")
        if p.sa[k] < THIN_TIP * m:
            warnings.append(f"the tip of wheel {w} is thin: s_a = {p.sa[k]:.4g} mm < {THIN_TIP:g}·m = "
                            f"{THIN_TIP * m:.4g} mm")
    if p.kind == "internal":
        _ring_root(p, names[1])
    for text in _interference(p, names):
        if meshing:
            raise SceneError(text, key="gear_pair")
        warnings.append(text)
    if p.contact_ratio < 1.0:
        text = (f"the contact ratio ε_α = {p.contact_ratio:.4g} is under 1: the pair does not mesh continuously; "
                "give more teeth or smaller shifts")
        if meshing:
            raise SceneError(text, key="gear_pair")
        warnings.append(text)
    if p.contact_ratio < LOW_CONTACT_RATIO:
        warnings.append(f"the contact ratio ε_α = {p.contact_ratio:.4g} is under {LOW_CONTACT_RATIO:g}")
    for k in range(2):
        if p.undercut[k]:
            warnings.append(f"wheel {names[k]} ({p.z[k]} teeth, x = {p.x[k]:.4g}) is undercut: x < x_min = "
                            f"{p.x_min[k]:.4g}")
    sliding = sliding_velocities(p, spec.n1) if spec.n1 is not None else None
    return PairAnalysis(pair=p, rule=rule, tip_radius=spec.tip_radius * m, names=names, warnings=tuple(warnings),
                        n1=spec.n1, sliding_velocity=sliding)


def _ring_root(p: GearPair, name: str) -> None:
    """Refuse a ring gear whose tooth space closes before its root circle: the space is the tooth of
    an external wheel of its teeth and shift, e(R) = 2R(e/d + inv α − inv α_R), e = p − s2 on the
    reference circle; e(R_f) ≤ 0 is a pinion cutter with a pointed tooth (large x2 or α)."""
    e = p.p - p.s[1]
    rf = p.df[1] / 2.0
    ef = 2.0 * rf * (e / p.d[1] + inv(p.alpha) - inv(math.acos(p.db[1] / p.df[1])))
    if ef <= 0.0:
        key, fix = ("gear_pair.x2", "give a smaller shift x2") if p.x[1] > 0.0 else \
            ("gear_pair.pressure_angle", "give a smaller pressure angle or clearance")
        raise SceneError(f"the tooth space of ring gear {name} closes before its root circle (d_f = {p.df[1]:.4g} "
                         f"mm, x2 = {p.x[1]:.4g}): its width there is {ef:.4g} mm ≤ 0, the pinion cutter's tooth "
                         f"would be pointed; {fix}", key=key)


def _interference(p: GearPair, names: tuple[str, str]) -> list[str]:
    """One line per interference of the pair ``p`` (see the module)."""
    out = []
    g = [math.sqrt(max((da / 2) ** 2 - (db / 2) ** 2, 0.0)) if math.isfinite(da) else math.inf
         for da, db in zip(p.da, p.db)]
    if p.kind == "external":
        for k in range(2):
            if g[k] > p.line * (1 + 1e-12):
                other = names[1 - k]
                out.append(f"interference: the tip circle of wheel {names[k]} (d_a = {p.da[k]:.4g} mm) reaches past "
                           f"the tangency point N of wheel {other} on the line of action ({g[k]:.4g} mm from its "
                           f"own N, the line N1N2 is {p.line:.4g} mm): wheel {other} needs a larger shift")
    elif p.kind == "rack":
        pn1 = p.d[0] / 2 * math.sin(p.alpha)
        if p.approach > pn1 * (1 + 1e-12):
            out.append(f"interference: the tip line of the rack reaches past the tangency point N1 of wheel "
                       f"{names[0]} (the path of approach is {p.approach:.4g} mm, PN1 = {pn1:.4g} mm): give wheel "
                       f"{names[0]} a larger shift x1, more teeth or the rack a smaller addendum")
    else:
        margin = involute_interference(p)
        if p.da[1] < p.db[1]:
            out.append(f"interference: the tip circle of ring gear {names[1]} (d_a = {p.da[1]:.4g} mm) lies inside its "
                       f"base circle (d_b = {p.db[1]:.4g} mm): its teeth end in no involute there and cut the pinion's "
                       "flank (involute interference); give the ring more teeth, a smaller addendum or a positive "
                       "shift x2")
        elif margin < -1e-12 * p.line:
            out.append(f"interference: the tip circle of ring gear {names[1]} (d_a = {p.da[1]:.4g} mm) meets the line "
                       f"of action {g[1]:.4g} mm from its N2, inside the tangency point N1 of wheel {names[0]} "
                       f"(N1N2 = {p.line:.4g} mm): the ring's tip would cut the pinion's flank below its base circle "
                       "(involute interference); give the ring a smaller addendum or a positive shift x2, or the "
                       "pinion more teeth")
        tip = pair_tip_interference(p)
        if tip < -1e-12:
            why = f"θ1·z1/z2 + inv α_w − inv α_a2 − θ2 = {tip:.4g} rad < 0" if math.isfinite(tip) else \
                f"its tip circle, d_a1 = {p.da[0]:.4g} mm, does not cross the ring's, d_a2 = {p.da[1]:.4g} mm"
            out.append(f"tip interference: the tip of wheel {names[0]} strikes the teeth of ring gear {names[1]} as it "
                       f"leaves the mesh ({why}, SDP/SI Eq. 5-6); "
                       f"z2 − z1 = {p.z[1] - p.z[0]} is too few: give the ring more teeth")
    return out

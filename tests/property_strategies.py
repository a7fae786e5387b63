"""Hypothesis strategies for the property tests (``test_properties*.py``): the parameters of the
builders of ``property_cases.py``, drawn.

Random dimensions that assemble, random drive angles, and drive angles within 10⁻³…1° of the
form's singular positions (found analytically, then offset by a drawn amount). Dead centres
that are not singular (crank and coupler collinear: the output's extreme positions) are drawn
too, exactly and 10⁻³…1° away. ``cases(form, ...)`` filters out the draws that cannot assemble.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import strategies as st

from property_cases import (_J, _ang, _cross, _u, build_prp, build_rpp_turning, build_rpp_yoke, build_rpr, build_rrp,
                            build_rrp_slot, build_rrr)


# --- strategies ---------------------------------------------------------------------------------

def _f(lo: float, hi: float):
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False)


ANGLE = _f(-math.pi, math.pi)
SIGN = st.sampled_from([1.0, -1.0])
#: distance from a singular position, degrees: log-uniform in 10⁻³ … 1
NEAR_DEG = _f(-3.0, 0.0).map(lambda k: 10.0 ** k)
#: the same, or exactly there (for positions that are hard but not singular)
AT_OR_NEAR_DEG = st.one_of(st.just(0.0), NEAR_DEG)
OMEGA = st.one_of(_f(0.5, 30.0), _f(-30.0, -0.5))
EPSILON = _f(-100.0, 100.0)
UNIT = _f(0.05, 5.0)
COUPLER = st.tuples(_f(-0.5, 1.5), st.one_of(_f(0.1, 1.0), _f(-1.0, -0.1)))
MODES = st.sampled_from(["regular", "near"])
#: forms with a crank-coupler dead centre that is not singular (the output's extreme position)
MODES_DC = st.sampled_from(["regular", "near", "extreme"])


def _margin_ok(values, unit, margin=0.02) -> bool:
    return all(abs(a - b) > margin * unit for i, a in enumerate(values) for b in values[i + 1:])


@st.composite
def rrr_cases(draw, mode=None, delta_deg=None):
    mode = mode or draw(MODES_DC)
    unit, g = draw(UNIT), draw(ANGLE)
    r, d = unit * draw(_f(0.2, 1.0)), unit * draw(_f(0.3, 1.5))
    if mode == "near":
        # a fold at cos(φ − g) = c_f: |AC| there is lm + ln (outer) or |lm − ln| (inner)
        c_f = draw(_f(-0.95, 0.95))
        s_f = math.sqrt(r * r + d * d - 2 * r * d * c_f)
        outer = draw(st.booleans())
        if outer:
            lam = draw(_f(0.2, 0.8))
            lm, ln = lam * s_f, (1 - lam) * s_f
        else:
            short = unit * draw(_f(0.2, 1.0))
            lm, ln = (short + s_f, short) if draw(st.booleans()) else (short, short + s_f)
    elif mode == "extreme":
        # the rocker's extreme position exists: |OB| = |r ± lm| lies between |d − ln| and d + ln
        lm, stretched = unit * draw(_f(0.3, 1.5)), draw(st.booleans())
        R = abs(r + lm if stretched else r - lm)
        a, b = abs(R - d), R + d              # ln must lie strictly between these
        ln = a + (b - a) * draw(_f(0.05, 0.95))
    else:
        lm, ln = unit * draw(_f(0.3, 1.5)), unit * draw(_f(0.3, 1.5))
    lo, hi = max(abs(lm - ln), abs(d - r)), min(lm + ln, d + r)
    # assemblable somewhere, never |AC| = 0, no two limits at once (no change-point linkages)
    limits = [abs(lm - ln), lm + ln, abs(d - r), d + r]
    if not (hi - lo > 0.05 * unit and lo > 0.02 * unit and _margin_ok(limits, unit)):
        return None
    cos_of = [(r * r + d * d - s * s) / (2 * r * d) for s in (lm + ln, abs(lm - ln))]
    if any(0.98 < abs(c) < 1.02 for c in cos_of):
        return None          # a fold next to the crank's line through C: two singular laws at once
    a_lo = math.acos(min(1.0, (r * r + d * d - lo * lo) / (2 * r * d)))
    a_hi = math.acos(max(-1.0, (r * r + d * d - hi * hi) / (2 * r * d)))
    side = draw(SIGN)
    if mode == "extreme":
        # crank and coupler collinear (the rocker's extreme position, a dead centre of the
        # crank-rocker that is not singular): |OB| = |r ± lm| and |CB| = ln
        signed = r + lm if stretched else r - lm
        if not (abs(d - ln) + 0.02 * unit < R < d + ln - 0.02 * unit):
            return None
        x = (R * R - ln * ln + d * d) / (2 * d)
        B = x * _u(g) + side * math.sqrt(R * R - x * x) * _J(_u(g))
        phi_dc = _ang(B * math.copysign(1.0, signed))
        A, C = r * _u(phi_dc), d * _u(g)
        branch = math.copysign(1.0, _cross(C - A, B - A))
        dlt = math.radians(delta_deg if delta_deg is not None else draw(AT_OR_NEAR_DEG)) * draw(SIGN)
        case = build_rrr(r=r, d=d, g=g, lm=lm, ln=ln, phi=phi_dc + dlt, branch=branch, coupler=draw(COUPLER),
                         omega=draw(OMEGA), epsilon=draw(EPSILON),
                         note=f"{'stretched' if signed > 0 else 'folded'} crank-coupler dead centre")
        return case if case.delta > math.radians(2.0) else None
    if mode == "near":
        dlt = math.radians(delta_deg if delta_deg is not None else draw(NEAR_DEG))
        psi = math.acos(c_f) + (-dlt if outer else dlt)      # into the assembling side
        note = f"{'outer' if outer else 'inner'} fold"
    else:
        psi = a_lo + draw(_f(0.02, 0.98)) * (a_hi - a_lo)
        note = "regular"
    case = build_rrr(r=r, d=d, g=g, lm=lm, ln=ln, phi=g + side * psi, branch=draw(SIGN), coupler=draw(COUPLER),
                     omega=draw(OMEGA), epsilon=draw(EPSILON), note=note)
    return case


@st.composite
def rrp_cases(draw, mode=None, delta_deg=None, variant=None):
    mode = mode or draw(MODES if variant == "crank slot" else MODES_DC)
    # the crank-rod dead centres: with the guide on the frame
    variant = variant or ("frame guide" if mode == "extreme" else draw(st.sampled_from(["frame guide", "crank slot"])))
    assert not (mode == "extreme" and variant != "frame guide")
    unit = draw(UNIT)
    r = unit * draw(_f(0.2, 1.0))
    # the law: scale·sin(x) − b = ±l, with x = φ − α for the frame guide (scale = r, b = e:
    # g = r sin(φ − α) − e) and x = c_dir − ψ for the crank slot (scale = |C|, b = h:
    # q = h − |C| sin x); folds where it reaches ±l
    scale = r if variant == "frame guide" else unit * draw(_f(0.2, 1.5))
    if mode == "near":
        # the fold first: sin x_f = s_f on the +l or −l side, then the offset that puts it there
        s_f, plus = draw(_f(-0.95, 0.95)), draw(st.booleans())
        length = unit * draw(_f(0.3, 2.0))
        b = scale * s_f - (length if plus else -length)
    else:
        b = unit * draw(_f(-0.6, 0.6))
        length = unit * draw(_f(0.3, 2.0))
    if variant == "frame guide":
        alpha, e = draw(ANGLE), b
    else:
        kappa, h, c_dist, c_dir = draw(ANGLE), b, scale, draw(ANGLE)
    folds = [(b + length) / scale, (b - length) / scale]
    if any(0.98 < abs(s) < 1.02 for s in folds):
        return None
    lo, hi = max(-1.0, folds[1]), min(1.0, folds[0])
    if hi - lo < 0.05:
        return None
    if mode == "extreme":
        # crank and rod collinear (the slider's dead centres): |OB| = |r ± l|, B on the guide
        signed = r + length if draw(st.booleans()) else r - length
        R = abs(signed)
        if R < abs(e) + 0.02 * unit:
            return None
        u = _u(alpha)
        B = e * _J(u) + draw(SIGN) * math.sqrt(R * R - e * e) * u
        phi_dc = _ang(B * math.copysign(1.0, signed))
        branch = math.copysign(1.0, float((B - r * _u(phi_dc)) @ u))
        dlt = math.radians(delta_deg if delta_deg is not None else draw(AT_OR_NEAR_DEG)) * draw(SIGN)
        case = build_rrp(r=r, alpha=alpha, e=e, rod=length, phi=phi_dc + dlt, branch=branch, coupler=draw(COUPLER),
                         omega=draw(OMEGA), epsilon=draw(EPSILON),
                         note=f"{'outer' if signed > 0 else 'inner'} crank-rod dead centre")
        return case if case.delta > math.radians(2.0) else None
    if mode == "near":
        x_f = math.asin(s_f) if draw(st.booleans()) else math.pi - math.asin(s_f)
        dlt = math.radians(delta_deg if delta_deg is not None else draw(NEAR_DEG))
        # a·sin x − b moves away from ±l (into the assembling side) as x moves by ∓sign(cos x_f)
        x = x_f - (1 if plus else -1) * math.copysign(dlt, math.cos(x_f))
        note = f"{variant}, fold {'+' if plus else '-'}l"
    else:
        s = lo + draw(_f(0.02, 0.98)) * (hi - lo)
        x = math.asin(s) if draw(st.booleans()) else math.pi - math.asin(s)
        note = f"{variant}, regular"
    omega, epsilon, branch = draw(OMEGA), draw(EPSILON), draw(SIGN)
    if variant == "frame guide":
        return build_rrp(r=r, alpha=alpha, e=e, rod=length, phi=alpha + x, branch=branch, coupler=draw(COUPLER),
                         omega=omega, epsilon=epsilon, note=note)
    return build_rrp_slot(r=r, kappa=kappa, h=h, c_dist=c_dist, c_dir=c_dir, lm=length, phi=c_dir - x - kappa,
                          branch=branch, omega=omega, epsilon=epsilon, note=note)


@st.composite
def rpr_cases(draw, mode=None, delta_deg=None):
    mode = mode or draw(MODES)
    unit, gamma = draw(UNIT), draw(ANGLE)
    # a rotating (d < r) or an oscillating (d > r) lever, never passing through C
    r = unit * draw(_f(0.2, 1.0))
    d = r * draw(st.one_of(_f(0.2, 0.85), _f(1.15, 3.0)))
    if mode == "near":
        c_s = draw(_f(-0.95, 0.95))
        h = draw(SIGN) * math.sqrt(r * r + d * d - 2 * r * d * c_s)
    else:
        h = draw(st.one_of(st.just(0.0), _f(-0.5, 0.5))) * unit
    # |AC| runs over [|d − r|, d + r] and must stay ≥ |h|; keep every limit apart
    if not _margin_ok([abs(d - r), d + r, abs(h)], unit):
        return None
    c = (r * r + d * d - h * h) / (2 * r * d)
    if c < -0.98 or 0.98 < abs(c) < 1.02:
        return None
    side = draw(SIGN)
    if mode == "near":
        dlt = math.radians(delta_deg if delta_deg is not None else draw(NEAR_DEG))
        psi = math.acos(c) + dlt
        note = "fold |AC| = |h|"
    else:
        a0 = math.acos(min(1.0, c))
        psi = a0 + draw(_f(0.02, 0.98)) * (math.pi - a0)
        note = "regular" + (", slot through C" if h == 0 else "")
    lever = (unit * draw(_f(0.2, 1.0)), draw(ANGLE))
    return build_rpr(r=r, d=d, gamma=gamma, h=h, phi=gamma + side * psi, branch=draw(SIGN), lever=lever,
                     omega=draw(OMEGA), epsilon=draw(EPSILON), note=note)


@st.composite
def prp_cases(draw, mode=None, delta_deg=None):
    mode = mode or draw(MODES)
    unit = draw(UNIT)
    beta, kappa = draw(ANGLE), draw(ANGLE)
    if mode == "near":
        dlt = math.radians(delta_deg if delta_deg is not None else draw(NEAR_DEG))
        gam = draw(st.sampled_from([0.0, math.pi])) + draw(SIGN) * dlt
        note = "near parallel guides"
    else:
        gam = draw(SIGN) * draw(_f(math.radians(2.0), math.radians(178.0)))
        note = "regular"
    psi = beta + gam
    return build_prp(r=unit * draw(_f(0.2, 1.0)), kappa=kappa, c=unit * draw(_f(-0.5, 0.5)), beta=beta,
                     e=unit * draw(_f(-1.0, 1.0)), phi=psi - kappa, omega=draw(OMEGA), epsilon=draw(EPSILON),
                     note=note)


@st.composite
def rpp_cases(draw, mode=None, delta_deg=None, variant=None, gamma=None):
    mode = mode or draw(MODES)
    variant = variant or draw(st.sampled_from(["yoke", "turning"]))
    unit = draw(UNIT)
    if gamma is not None:      # the angle between the guides, drawn by the caller's strategy
        gam = draw(gamma)
        note = f"{variant}, guides at {math.degrees(gam):.3g}°"
    elif mode == "near":
        dlt = math.radians(delta_deg if delta_deg is not None else draw(NEAR_DEG))
        gam = draw(st.sampled_from([0.0, math.pi])) + draw(SIGN) * dlt
        note = f"{variant}, near parallel guides"
    else:
        gam = draw(SIGN) * draw(_f(math.radians(5.0), math.radians(175.0)))
        note = f"{variant}, regular"
    r, phi = unit * draw(_f(0.2, 1.0)), draw(ANGLE)
    omega, epsilon = draw(OMEGA), draw(EPSILON)
    if variant == "yoke":
        w = unit * np.array([draw(_f(-1.0, 1.0)), draw(_f(-1.0, 1.0))])
        return build_rpp_yoke(r=r, beta=draw(ANGLE), gamma=gam, e=unit * draw(_f(-1.0, 1.0)), w=w, phi=phi,
                              omega=omega, epsilon=epsilon, note=note)
    c = unit * draw(_f(0.1, 1.0)) * _u(draw(ANGLE))
    q = unit * np.array([draw(_f(-1.0, 1.0)), draw(_f(-1.0, 1.0))])
    return build_rpp_turning(r=r, kappa=draw(ANGLE), gamma=gam, c=c, q=q, phi=phi, omega=omega, epsilon=epsilon,
                             note=note)


STRATEGIES = {"RRR": rrr_cases, "RRP": rrp_cases, "RPR": rpr_cases, "PRP": prp_cases, "RPP": rpp_cases}


def cases(form: str, **kw):
    """Valid cases of ``form`` (draws that cannot assemble are filtered out)."""
    return STRATEGIES[form](**kw).filter(lambda c: c is not None)

"""Property tests over random class II mechanisms (issue 4, "hard cases stay stable").

Hypothesis draws mechanisms of each of the five class II forms — RRR (four-bar), RRP
(crank-slider with offset and inclined guide, and a rod sliding on the crank's own slot),
RPR (slotted lever, oscillating or rotating), PRP (tangent mechanism with an offset slot
and an arbitrary frame guide), RPP (Scotch yoke with an inclined slot, and a yoke sliding
on the crank's slot) — with random dimensions that assemble, random drive angles, and
drive angles within 10⁻³…1° of the form's singular positions (found analytically below,
then offset by a drawn amount). Each scene is a dict taken through
``parse_scene → build_mechanism → analyse_structure → analyse``, and checked for

* loop closure: every revolute pair's two carriers give the same world point, every slider
  stays on its guide line and keeps the guide's angle (1e-12 of the mechanism's extent);
* derivatives: v and a of every point, ω and ε of every link, against 8th-order finite
  differences of plans' own positions along the drive (relative 1e-7, see ``fd_tolerance``);
* rigidity of every link's velocity and acceleration fields, and the pair identities at
  velocity and acceleration level (a slider's acceleration relative to its guide's
  coincident point has the normal component 2·ω_guide·σ: the Coriolis term) — 1e-12;
* drawings: every SVG of ``render_scene`` passes ``check_svg`` and its ``v:X``/``a:X``
  values are the finite-difference-checked magnitudes;
* exactly at a singular position analyse raises (SingularPositionError or AssemblyError),
  and closer than 10⁻³° it either raises or returns finite numbers;
* after a walk of up to 179° from the sketch (never across a singular angle) every point is
  where the builder's closed form puts it on the sketch's branch;
* four-bars near their folds against the four-bar solved in 50 digits (1e-7, no floor).

Dead centres that are not singular (crank and coupler collinear: the output's extreme
positions) are drawn too, exactly and 10⁻³…1° away. Two bugs found here, once strict xfails,
are fixed and kept as tests: an RPP group turning with a known guide (``RPP_TURNING``), and a
walk longer than half a turn that depended on the other requested angles (``WALK_CASE``).

A mutation test (``test_mutation.py``) shows that these checks catch a wrong Coriolis term.
The worst errors seen are printed at the end of the module (``pytest -s``).
"""

from __future__ import annotations

import dataclasses
import functools
import json
import math
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pytest
from hypothesis import event as _event, example, given, settings, strategies as st
from hypothesis.control import currently_in_test_context

from conftest import toml_text
from plans.checking import check_svg
from plans.errors import AssemblyError, SingularPositionError
from plans.kinematics import analyse
from plans.model import build_mechanism
from plans.pipeline import render_scene
from plans.scene import FRAME, parse_scene
from plans.structure import analyse_structure

#: with filterwarnings = error, hypothesis' report of a failing example (its patch writer
#: imports libcst → mypy_extensions, deprecated) would turn into an INTERNALERROR hiding it
pytestmark = pytest.mark.filterwarnings("ignore:mypy_extensions.TypedDict is deprecated:DeprecationWarning")

EPS = float(np.finfo(float).eps)

#: loop closure, relative to the mechanism's extent (and absolute for angles, rad)
TOL_CLOSURE = 1e-12
#: derivatives against finite differences of positions, relative to the largest magnitude
TOL_FD = 1e-7
#: rigid-field and pair identities, relative to the magnitudes of their terms
TOL_RIGID = 1e-12
#: finite differences: offsets -4..4 (8th order) on the drive angle, step h = min(H_MAX, δ/H_DIV)
#: rad, δ the distance from the nearest singular drive angle. Near a singular position a
#: position varies like √δ (fold) or 1/δ (parallel guides of PRP): its Taylor series converges
#: within δ, and the relative truncation error of the 8th-order formulas is ~ c·(h/δ)⁸ with
#: c ≈ 6 for √δ and 9!/630 ≈ 600 for 1/δ, so h = δ/20 keeps it below 3e-10 and 3e-8. Far from
#: singular positions (and for RPP, whose singularity does not depend on φ) the positions are
#: smooth on the scale of a radian and h = 1e-2 rad makes truncation negligible. Rounding grows
#: like eps/h (velocities) and eps/h² (accelerations): ``fd_tolerance``.
H_MAX = 1e-2
H_DIV = 20.0
OFFSETS = np.arange(-4, 5)

WORST: dict[str, tuple[float, str]] = {}


def event(label: str) -> None:
    """hypothesis.event, also callable from plain tests (where it does nothing)."""
    if currently_in_test_context():
        _event(label)


def record(kind: str, err: float, where: str) -> float:
    if err >= WORST.get(kind, (-1.0, ""))[0]:
        WORST[kind] = (float(err), where)
    return err


@pytest.fixture(scope="module", autouse=True)
def _report():
    yield
    print("\nworst errors seen in the property tests (kind: error / tolerance used, at)")
    for kind in sorted(WORST):
        err, where = WORST[kind]
        print(f"  {kind:48s} {err:9.2e}  {where}")


# --- geometry helpers -------------------------------------------------------------------------

def _u(a: float) -> np.ndarray:
    return np.array([math.cos(a), math.sin(a)])


def _J(v) -> np.ndarray:
    return np.array([-v[1], v[0]])


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _ang(v) -> float:
    return math.atan2(v[1], v[0])


def _pt(x) -> list[float]:
    return [float(x[0]), float(x[1])]


def _dist(a: float, angles, period: float = 2 * math.pi) -> float:
    """Angular distance (rad) of ``a`` from the nearest of ``angles`` (mod ``period``)."""
    return min((abs(math.remainder(a - s, period)) for s in angles), default=math.inf)


@dataclass(frozen=True)
class Case:
    """A generated mechanism: its scene dict, the drive angle φ (degrees, also the sketch's),
    the group form it must contain, the singular drive angles (rad) and ``delta``: the distance
    (rad) of φ from the nearest of them. RPP groups are singular for every φ or for none (their
    guides keep their angle): ``parallel`` is the distance (rad) of that angle from 0 or π."""

    form: str
    scene: dict
    phi: float
    singular: tuple[float, ...] = ()
    delta: float = math.inf
    note: str = ""
    parallel: float = math.inf
    rebuild: object = field(default=None, compare=False)

    def __repr__(self) -> str:   # hypothesis prints this for a falsifying example: paste it in @example
        def num(x: float) -> str:
            return "math.inf" if x == math.inf else repr(x)
        return (f"Case({self.form!r}, {self.scene!r}, {self.phi!r}, singular={self.singular!r}, "
                f"delta={num(self.delta)}, note={self.note!r}, parallel={num(self.parallel)})")

    @property
    def label(self) -> str:
        far = (f"{math.degrees(self.delta):.3g}° from singular" if self.singular else "") + \
              (f"guides {math.degrees(self.parallel):.3g}° from parallel" if self.parallel < math.inf else "")
        return f"{self.form} {self.note} φ={self.phi:.6g}° {far}".strip()


def _drive(phi: float, omega: float, epsilon: float) -> dict:
    return {"link": "1", "angle": math.degrees(phi), "omega": omega, "epsilon": epsilon}


# --- builders: one per form, from explicit parameters (the strategies draw them) ---------------

def build_rrr(*, r, d, g, lm, ln, phi, branch, coupler, omega, epsilon, note="") -> Case:
    """Four-bar O-A-B-C: crank OA = r about O = 0, frame pivot C at distance d in direction g,
    coupler AB = lm (with a coupler point M at (α, β) in the frame A→B, J(A→B)), rocker
    BC = ln. Singular (coupler and rocker collinear) where |AC| = lm + ln or |lm − ln|:
    cos(φ − g) = (r² + d² − s²)/(2rd)."""
    A, C = r * _u(phi), d * _u(g)
    v = C - A
    L = float(np.linalg.norm(v))
    x = (lm * lm - ln * ln + L * L) / (2 * L)
    h = math.sqrt(max(lm * lm - x * x, 0.0))
    ex = v / L
    B = A + x * ex + branch * h * _J(ex)
    M = A + coupler[0] * (B - A) + coupler[1] * _J(B - A)
    singular = []
    for s in (lm + ln, abs(lm - ln)):
        c = (r * r + d * d - s * s) / (2 * r * d)
        if abs(c) < 1:
            singular += [g + math.acos(c), g - math.acos(c)]
    scene = {"title": "random four-bar",
             "points": {"O": [0.0, 0.0], "C": _pt(C), "A": _pt(A), "B": _pt(B), "M": _pt(M)},
             "links": {"0": ["O", "C"], "1": ["O", "A"], "2": ["A", "B", "M"], "3": ["C", "B"]},
             "drive": _drive(phi, omega, epsilon),
             "lengths": {"OA": r, "OC": d, "AB": lm, "BC": ln}}
    return Case("RRR", scene, math.degrees(phi), tuple(singular), _dist(phi, singular), note)


def build_rrp(*, r, alpha, e, rod, phi, branch, coupler, omega, epsilon, note="") -> Case:
    """Crank-slider: crank OA = r, rod AB = l = ``rod`` (coupler point M), slider B on the frame line
    J(u)·x = e, u = (cos α, sin α) (offset e). With g = J(u)·A − e: B = A − g·J(u) ± √(l² − g²)·u;
    singular (rod ⟂ guide) where g = ±l, sin(φ − α) = (e ± l)/r."""
    u, n = _u(alpha), _J(_u(alpha))
    A = r * _u(phi)
    gap = float(n @ A) - e
    B = A - gap * n + branch * math.sqrt(max(rod * rod - gap * gap, 0.0)) * u
    M = A + coupler[0] * (B - A) + coupler[1] * _J(B - A)
    singular = []
    for s in ((e + rod) / r, (e - rod) / r):
        if abs(s) < 1:
            singular += [alpha + math.asin(s), alpha + math.pi - math.asin(s)]
    scene = {"title": "random crank-slider",
             "points": {"O": [0.0, 0.0], "A": _pt(A), "B": _pt(B), "M": _pt(M)},
             "links": {"0": ["O"], "1": ["O", "A"], "2": ["A", "B", "M"], "3": ["B"]},
             "sliders": [{"link": "3", "on": "0", "through": "B", "angle": math.degrees(alpha)}],
             "drive": _drive(phi, omega, epsilon),
             "lengths": {"OA": r, "AB": rod}}
    return Case("RRP", scene, math.degrees(phi), tuple(singular), _dist(phi, singular), note)


def build_rrp_slot(*, r, kappa, h, c_dist, c_dir, lm, phi, branch, omega, epsilon, note="") -> Case:
    """RRP with a turning guide: block 3 slides along a slot of the crank (the line through O
    at angle ψ = φ + κ), its pin E lies h off the slot line; rod 2 (CE = lm) joins E to the
    frame pivot C = c_dist·u(c_dir). q = h − J(u)·C = h − |C| sin(c_dir − ψ) is E's line's
    signed distance from C; singular (rod ⟂ slot) where q = ±lm."""
    psi = phi + kappa
    u, n = _u(psi), _J(_u(psi))
    C = c_dist * _u(c_dir)
    w = h * n - C
    q = float(n @ w)
    E = h * n + (-float(w @ u) + branch * math.sqrt(max(lm * lm - q * q, 0.0))) * u
    singular = []
    for s in ((h - lm) / c_dist, (h + lm) / c_dist):
        if abs(s) < 1:
            for beta in (math.asin(s), math.pi - math.asin(s)):
                singular.append(c_dir - beta - kappa)
    scene = {"title": "random rod on a crank slot",
             "points": {"O": [0.0, 0.0], "K": _pt(r * _u(phi)), "C": _pt(C), "E": _pt(E)},
             "links": {"0": ["O", "C"], "1": ["O", "K"], "2": ["C", "E"], "3": ["E"]},
             "sliders": [{"link": "3", "on": "1", "through": "O", "angle": math.degrees(psi)}],
             "drive": _drive(phi, omega, epsilon)}
    return Case("RRP", scene, math.degrees(phi), tuple(singular), _dist(phi, singular), note)


def build_rpr(*, r, d, gamma, h, phi, branch, lever, omega, epsilon, note="") -> Case:
    """Slotted lever: crank OA = r, block 2 on A slides in a slot of lever 3 (pivot C at
    distance d in direction γ); the slot is the line through A at signed distance h from C,
    one of the two tangents from A (``branch``). Singular (slot ⟂ AC... D, E, F a right angle
    at D) where |AC| = |h|: cos(φ − γ) = (r² + d² − h²)/(2rd)."""
    A, C = r * _u(phi), d * _u(gamma)
    v = A - C
    L = float(np.linalg.norm(v))
    tau = math.asin(max(-1.0, min(1.0, h / L)))
    alpha = _ang(v) + (tau if branch > 0 else math.pi - tau)
    T = C + lever[0] * _u(alpha + lever[1])     # fixed in the lever: at an angle to its slot
    singular = []
    c = (r * r + d * d - h * h) / (2 * r * d)
    if abs(c) < 1:
        singular = [gamma + math.acos(c), gamma - math.acos(c)]
    scene = {"title": "random slotted lever",
             "points": {"O": [0.0, 0.0], "C": _pt(C), "A": _pt(A), "T": _pt(T)},
             "links": {"0": ["O", "C"], "1": ["O", "A"], "2": ["A"], "3": ["C", "T"]},
             "sliders": [{"link": "2", "on": "3", "through": "A", "angle": math.degrees(alpha)}],
             "drive": _drive(phi, omega, epsilon)}
    return Case("RPR", scene, math.degrees(phi), tuple(singular), _dist(phi, singular), note)


def build_prp(*, r, kappa, c, beta, e, phi, omega, epsilon, note="") -> Case:
    """Tangent mechanism: the crank's slot is the line at distance c from O with direction
    ψ = φ + κ; block 2 slides in it and is pinned at B to slider 3 on the frame line through
    e·J(u(β)) with direction β. Singular (guides parallel) where ψ ≡ β (mod π)."""
    psi = phi + kappa
    u1, u2 = _u(psi), _u(beta)
    p1, p2 = c * _J(u1), e * _J(u2)
    t = _cross(p2 - p1, u2) / _cross(u1, u2)
    B = p1 + t * u1
    singular = [beta - kappa, beta - kappa + math.pi]
    scene = {"title": "random tangent mechanism",
             "points": {"O": [0.0, 0.0], "K": _pt(r * _u(phi)), "B": _pt(B)},
             "links": {"0": ["O"], "1": ["O", "K"], "2": ["B"], "3": ["B"]},
             "sliders": [{"link": "2", "on": "1", "through": "B", "angle": math.degrees(psi)},
                         {"link": "3", "on": "0", "through": "B", "angle": math.degrees(beta)}],
             "drive": _drive(phi, omega, epsilon)}
    return Case("PRP", scene, math.degrees(phi), tuple(singular), _dist(phi, singular), note)


def build_rpp_yoke(*, r, beta, gamma, e, w, phi, omega, epsilon, note="") -> Case:
    """Scotch yoke: crank OA = r, block 2 on A slides in the yoke's slot (direction β + γ),
    the yoke 3 slides on the frame guide J(u(β))·x = e, with its point Y on that guide and its
    slot through Y + w (w fixed in the yoke, which only translates). Singular for every φ when
    γ ≡ 0 (mod π): ``parallel`` is γ's distance from that."""
    A = r * _u(phi)
    ub, us = _u(beta), _u(beta + gamma)
    P = e * _J(ub)
    det = _cross(ub, us)
    Y = P + (_cross(A - w - P, us) / det if det != 0.0 else 0.0) * ub
    scene = {"title": "random Scotch yoke",
             "points": {"O": [0.0, 0.0], "A": _pt(A), "Y": _pt(Y)},
             "links": {"0": ["O"], "1": ["O", "A"], "2": ["A"], "3": ["Y"]},
             "sliders": [{"link": "2", "on": "3", "through": "A", "angle": math.degrees(beta + gamma)},
                         {"link": "3", "on": "0", "through": "Y", "angle": math.degrees(beta)}],
             "drive": _drive(phi, omega, epsilon)}
    return Case("RPP", scene, math.degrees(phi), note=note, parallel=_dist(gamma, [0.0], math.pi))


def build_rpp_turning(*, r, kappa, gamma, c, q, phi, omega, epsilon, note="") -> Case:
    """RPP turning with the crank: link 3 slides along the crank's slot through O (direction
    ψ = φ + κ); link 2, pinned to the frame at C, slides in a slot of link 3 (direction ψ + γ)
    through C. Link 3's point Q is q = (along, across) from the slots' vertex V in link 3's
    axes. Singular for every φ when γ ≡ 0 (mod π)."""
    psi = phi + kappa
    u0, u1 = _u(psi), _u(psi + gamma)
    det = _cross(u0, u1)
    V = (_cross(c, u1) / det if det != 0.0 else 0.0) * u0
    Q = V + q[0] * u0 + q[1] * _J(u0)
    scene = {"title": "random turning RPP",
             "points": {"O": [0.0, 0.0], "K": _pt(r * _u(phi)), "Q": _pt(Q), "C": _pt(c)},
             "links": {"0": ["O", "C"], "1": ["O", "K"], "2": ["C"], "3": ["Q"]},
             "sliders": [{"link": "3", "on": "1", "through": "O", "angle": math.degrees(psi)},
                         {"link": "2", "on": "3", "through": "C", "angle": math.degrees(psi + gamma)}],
             "drive": _drive(phi, omega, epsilon)}
    return Case("RPP", scene, math.degrees(phi), note=note, parallel=_dist(gamma, [0.0], math.pi))


def _rebuildable(builder):
    """The builder, with ``Case.rebuild(phi)``: the same mechanism assembled at another angle
    on the same branch (every builder's parameters other than φ fix the links' shapes)."""
    @functools.wraps(builder)
    def wrapped(**kw):
        params = {k: v for k, v in kw.items() if k != "phi"}
        return dataclasses.replace(builder(**kw), rebuild=lambda phi: wrapped(phi=phi, **params))
    return wrapped


build_rrr, build_rrp, build_rrp_slot, build_rpr, build_prp, build_rpp_yoke, build_rpp_turning = map(
    _rebuildable, (build_rrr, build_rrp, build_rrp_slot, build_rpr, build_prp, build_rpp_yoke, build_rpp_turning))


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


# --- the checks ---------------------------------------------------------------------------------

def load(scene: dict):
    mech = build_mechanism(parse_scene(scene))
    return mech, analyse_structure(mech)


def fd_weights(x: np.ndarray, m: int = 2) -> np.ndarray:
    """Finite-difference weights for derivatives 0..m at 0 on the nodes ``x`` (Fornberg's
    algorithm, exact for polynomials of degree len(x) − 1): column k holds d^k/dx^k."""
    n = len(x)
    c = np.zeros((n, m + 1))
    c[0, 0] = 1.0
    c1, c4 = 1.0, x[0]
    for i in range(1, n):
        mn = min(i, m)
        c2, c5, c4 = 1.0, c4, x[i]
        for j in range(i):
            c3 = x[i] - x[j]
            c2 *= c3
            if j == i - 1:
                for k in range(mn, 0, -1):
                    c[i, k] = c1 * (k * c[i - 1, k - 1] - c5 * c[i - 1, k]) / c2
                c[i, 0] = -c1 * c5 * c[i - 1, 0] / c2
            for k in range(mn, 0, -1):
                c[j, k] = (c4 * c[j, k] - k * c[j, k - 1]) / c3
            c[j, 0] = c4 * c[j, 0] / c3
        c1 = c2
    return c


def test_fd_weights_are_the_textbook_ones():
    """The helper reproduces the classical 8th-order central coefficients on uniform nodes."""
    w = fd_weights(OFFSETS.astype(float))
    d1 = np.array([1 / 280, -4 / 105, 1 / 5, -4 / 5, 0.0, 4 / 5, -1 / 5, 4 / 105, -1 / 280])
    d2 = np.array([-1 / 560, 8 / 315, -1 / 5, 8 / 5, -205 / 72, 8 / 5, -1 / 5, 8 / 315, -1 / 560])
    assert np.max(np.abs(w[:, 1] - d1)) < 1e-14 and np.max(np.abs(w[:, 2] - d2)) < 1e-13
    assert np.max(np.abs(w[:, 0] - (OFFSETS == 0))) < 1e-15


def _pairs(mech):
    return [(name, p) for name, link in mech.links.items() for p in link.points]


@dataclass
class Errors:
    """Worst errors of one case, each as (error, tolerance)."""

    values: dict = field(default_factory=dict)

    def add(self, kind: str, err: float, tol: float) -> None:
        old = self.values.get(kind)
        if old is None or err / tol > old[0] / old[1]:
            self.values[kind] = (float(err), float(tol))

    def failures(self) -> list[str]:
        return [f"{k}: {e:.3g} > {t:.3g}" for k, (e, t) in self.values.items() if not e <= t]


def measure(case: Case, h: float | None = None) -> tuple[Errors, object]:
    """Every property of ``case``, measured (not asserted): loop closure, pair and rigidity
    identities, finite differences. Returns the errors and the solved Motion."""
    mech, structure = load(case.scene)
    forms = [g.form for g in structure.groups]
    assert forms == [case.form], f"generator bug: expected one {case.form} group, got {forms}"
    m = analyse(mech, structure, np.array([case.phi]))
    pts = _pairs(mech)
    errs = Errors()
    for name, st_ in m.links.items():
        for arr in (st_.theta, st_.origin, st_.omega, st_.v, st_.epsilon, st_.a):
            assert np.all(np.isfinite(arr)), f"non-finite state of link {name}"
    P = {k: m.position(k[1], k[0])[0] for k in pts}
    V = {k: m.velocity(k[1], k[0])[0] for k in pts}
    A = {k: m.acceleration(k[1], k[0])[0] for k in pts}
    allp = np.array(list(P.values()))
    size = max(float(np.hypot(*(allp.max(axis=0) - allp.min(axis=0)))), mech.size)
    # probes: every point of every link and the link's own origin, a further material point
    probes = {}
    for name, link in mech.links.items():
        s = m.links[name]
        probes[name] = [(P[(name, p)], V[(name, p)], A[(name, p)]) for p in link.points]
        probes[name].append((s.origin[0], s.velocity(s.origin)[0], s.acceleration(s.origin)[0]))
    vmax = max(np.linalg.norm(v) for pr in probes.values() for _, v, _ in pr)
    amax = max(np.linalg.norm(a) for pr in probes.values() for _, _, a in pr)

    # pair identities hold to rounding amplified by the groups' conditioning: Cramer's rule
    # divides the velocity terms by sin (error ~ eps/|sin|), and the acceleration terms, which
    # carry those velocities, by sin again (~ eps/sin²); 0.001° from a PRP group's parallel
    # guides |sin| ~ 2e-5 and eps/|sin| ~ 1e-11 > TOL_RIGID
    sins = [geometric_sin(g, m) for g in structure.groups]
    cond = min([1.0] + [abs(float(m.sines[g.name][0])) for g in structure.groups])
    tol_v = max(TOL_RIGID, 16 * EPS / cond)
    tol_a = max(TOL_RIGID, 16 * EPS / cond ** 2)

    # loop closure: revolute pairs, prismatic pairs
    for r in mech.revolutes:
        errs.add("closure: revolute", np.linalg.norm(P[(r.a, r.point)] - P[(r.b, r.point)]) / size, TOL_CLOSURE)
        errs.add("pair: revolute velocity", np.linalg.norm(V[(r.a, r.point)] - V[(r.b, r.point)]) / vmax, tol_v)
        errs.add("pair: revolute acceleration", np.linalg.norm(A[(r.a, r.point)] - A[(r.b, r.point)]) / amax,
                 tol_a)
    for p in mech.prismatics:
        s, g = m.links[p.slider], m.links[p.guide]
        X = s.point(p.anchor[p.slider])
        u, n = g.direction(p.direction)[0], g.direction(p.normal)[0]
        errs.add("closure: slider on its line", abs(float((X - g.point(p.anchor[p.guide]))[0] @ n)) / size,
                 TOL_CLOSURE)
        errs.add("closure: slider keeps the guide's angle",
                 abs(math.remainder(float(s.theta[0] - g.theta[0]), 2 * math.pi)), TOL_CLOSURE)
        dv = (s.velocity(X) - g.velocity(X))[0]
        da = (s.acceleration(X) - g.acceleration(X))[0]
        sigma, w = float(dv @ u), float(g.omega[0])
        errs.add("pair: slider velocity along its guide", abs(float(dv @ n)) / vmax, tol_v)
        errs.add("pair: slider omega = guide omega", abs(float(s.omega[0] - g.omega[0])) * size / vmax, tol_v)
        errs.add("pair: Coriolis (a_s - a_g).n = 2 w sigma", abs(float(da @ n) - 2 * w * sigma) / amax, tol_a)
        errs.add("pair: slider epsilon = guide epsilon", abs(float(s.epsilon[0] - g.epsilon[0])) * size / amax,
                 tol_a)

    # rigidity of every link's velocity and acceleration fields
    for name, pr in probes.items():
        for i, (Pa, va, aa) in enumerate(pr):
            for Pb, vb, ab in pr[i + 1:]:
                d, dv, da = Pb - Pa, vb - va, ab - aa
                ld = float(np.linalg.norm(d))
                if ld == 0.0:
                    continue
                errs.add("rigid: (vB-vA).(B-A)", abs(float(dv @ d)) / (vmax * ld), TOL_RIGID)
                errs.add("rigid: (aB-aA).(B-A) + |vB-vA|^2", abs(float(da @ d + dv @ dv)) / (amax * ld + vmax ** 2),
                         TOL_RIGID)

    # the conditioning plans reports is the geometric one
    for g, sg in zip(structure.groups, sins):
        errs.add("conditioning: |sin| reported - geometric", abs(abs(float(m.sines[g.name][0])) - sg), TOL_RIGID)

    # finite differences of positions along the drive (all points on one stencil: the group
    # cannot be assembled beyond the singular position, so h shrinks near it)
    w1, e1 = mech.drive.speed, mech.drive.rate
    h = min(H_MAX, case.delta / H_DIV) if h is None else h
    near = analyse(mech, structure, case.phi + math.degrees(h) * OFFSETS, order=0)
    theta = near.links[mech.drive.link].theta      # the nodes as plans turns them into radians
    wts = fd_weights(theta - theta[4])
    fd_v, fd_a, fd_w, fd_e = {}, {}, {}, {}
    for k in pts:
        diff = near.position(k[1], k[0]) - near.position(k[1], k[0])[4]
        d1, d2 = wts[:, 1] @ diff, wts[:, 2] @ diff
        fd_v[k], fd_a[k] = w1 * d1, w1 * w1 * d2 + e1 * d1
    moving = [n for n in mech.links if n != FRAME]
    for n in moving:
        t = np.unwrap(near.links[n].theta)
        d1, d2 = wts[:, 1] @ (t - t[4]), wts[:, 2] @ (t - t[4])
        fd_w[n], fd_e[n] = w1 * d1, w1 * w1 * d2 + e1 * d1
    vref, aref = fd_scales(fd_v, fd_a, w1)
    wref = max(max(abs(v) for v in fd_w.values()), vref / size)
    eref = max(max(abs(v) for v in fd_e.values()), aref / size)
    noise = rounding_noise(mech, structure, m, near, min(sins))
    for k in pts:
        fv, fa = fd_floor(wts, w1, e1, noise[k[0]])
        errs.add("FD: velocity", np.linalg.norm(V[k] - fd_v[k]) / vref, max(TOL_FD, fv / vref))
        errs.add("FD: acceleration", np.linalg.norm(A[k] - fd_a[k]) / aref, max(TOL_FD, fa / aref))
    for n in moving:
        # θ of a link is fixed by two of its points (or copied from its guide): its noise is the
        # points' over the link's extent, at most the mechanism's
        pts_n = [P[(n, p)] for p in mech.links[n].points]
        extent = max([float(np.linalg.norm(a - b)) for a in pts_n for b in pts_n if a is not b] or [size])
        fv, fa = fd_floor(wts, w1, e1, noise[n] / extent)
        errs.add("FD: omega", abs(m.links[n].omega[0] - fd_w[n]) / wref, max(TOL_FD, fv / wref))
        errs.add("FD: epsilon", abs(m.links[n].epsilon[0] - fd_e[n]) / eref, max(TOL_FD, fa / eref))
    return errs, m


def fd_scales(fd_v, fd_a, w1) -> tuple[float, float]:
    """The magnitudes errors are relative to: the largest |v| of any point, and the largest
    |a| or |ω|·(largest |v|), whichever is larger — the acceleration scale the velocities
    imply (a point moving at v on a path turning at ω has a ~ ω·v); without it a position
    where every acceleration happens to be small (the tangent mechanism's slider at its foot
    point) would be judged against a near-zero scale."""
    vref = max(np.linalg.norm(v) for v in fd_v.values())
    aref = max(max(np.linalg.norm(a) for a in fd_a.values()), abs(w1) * vref)
    return vref, aref


def rounding_noise(mech, structure, m, near, sin: float) -> dict[str, float]:
    """Rounding error (m) of the positions of each link's points, per link.

    The frame and the driving link: a few ulps of their largest coordinate. A group's links:
    a few ulps of the largest quantity their positions are computed from — their points'
    coordinates over the stencil, the world anchors of the group's guides and, for two guides,
    their vertex (RPP: a virtual point ~ size/sin away) — amplified by 1/|sin|: a circle or line
    intersection at angle ~sin amplifies the rounding of its data by 1/sin. ``ROUNDING_ULPS`` is
    the safety factor on the constant."""
    out = {}
    for name in mech.links:
        coords = [np.abs(near.position(p, name)).max() for p in mech.links[name].points]
        out[name] = ROUNDING_ULPS * EPS * max(coords + [0.0])
    for g in structure.groups:
        big = [np.abs(near.position(p, n)).max() for n in g.links for p in mech.links[n].points]
        for j in (g.d, g.e, g.f):
            if j.kind == "P":
                pr = j.prismatic
                big += [np.abs(m.links[x].point(pr.anchor[x])).max() for x in (pr.slider, pr.guide)]
        if [j.kind for j in (g.d, g.e, g.f)].count("P") == 2:
            big.append(np.abs(vertex(g, m)).max())
        for n in g.links:
            out[n] = ROUNDING_ULPS * EPS * max(big) / sin
    return out


def fd_floor(wts, w1, e1, noise: float) -> tuple[float, float]:
    """The largest error the difference quotients make of a position noise ``noise``: at most
    Σ|w1|·noise in dr/dθ and Σ|w2|·noise in d²r/dθ², times ω and ω² (+ |ε|·dr/dθ)."""
    s1, s2 = np.sum(np.abs(wts[:, 1])), np.sum(np.abs(wts[:, 2]))
    return abs(w1) * s1 * noise, (w1 * w1 * s2 + abs(e1) * s1) * noise


#: safety factor on the rounding floor of the positions (see rounding_noise)
ROUNDING_ULPS = 16.0


def vertex(g, m) -> np.ndarray:
    """World intersection of the two guide lines of a group with two prismatic pairs."""
    lines = []
    for j in (g.d, g.e, g.f):
        if j.kind == "P":
            pr = j.prismatic
            s = m.links[pr.guide]
            lines.append((s.point(pr.anchor[pr.guide])[0], s.direction(pr.direction)[0]))
    (p1, u1), (p2, u2) = lines
    return p1 + _cross(p2 - p1, u2) / _cross(u1, u2) * u1


def geometric_sin(g, m) -> float:
    """|sin| of the angle between the two unknown directions of group ``g``'s velocity
    equations, from the solved positions (theory: RRR ω_m k×DE, ω_n k×FE; RRP ω_m k×DE, σ u_F;
    RPR ω k×FD, σ u_E; PRP σ_D u_D, σ_F u_F; RPP σ_E u_E, σ_F u_F)."""
    def pt(point, link):
        return m.position(point, link)[0]

    def guide(joint):
        pr = joint.prismatic
        return m.links[pr.guide].direction(pr.direction)[0]

    if g.form == "RRR":
        a, b = pt(g.e.point, g.m) - pt(g.d.point, g.m), pt(g.e.point, g.n) - pt(g.f.point, g.n)
        return abs(_cross(a, b)) / (np.linalg.norm(a) * np.linalg.norm(b))
    if g.form == "RRP":
        a = pt(g.e.point, g.m) - pt(g.d.point, g.m)
        return abs(float(a @ guide(g.f))) / np.linalg.norm(a)
    if g.form == "RPR":
        a = pt(g.d.point, g.m) - pt(g.f.point, g.n)
        return abs(float(a @ guide(g.e))) / np.linalg.norm(a)
    if g.form == "PRP":
        return abs(_cross(guide(g.d), guide(g.f)))
    return abs(_cross(guide(g.e), guide(g.f)))


def check(case: Case, h: float | None = None) -> object:
    """Assert every property of ``case``; record the worst errors."""
    event(case.note)
    errs, motion = measure(case, h)
    for kind, (err, tol) in errs.values.items():
        record(f"{case.form}: {kind}", err, case.label)
        if tol != TOL_FD and kind.startswith("FD"):
            record(f"{case.form}: {kind} (error/tolerance, floor used)", err / tol, case.label)
    bad = errs.failures()
    assert not bad, f"{case.label}: " + "; ".join(bad)
    return motion


COMMON = dict(derandomize=True, deadline=None, database=None)


# --- the property tests: every form, each kind of position -------------------------------------

N_EXAMPLES = 150


def _property_test(form: str, mode: str, doc: str, examples=()):
    @settings(max_examples=N_EXAMPLES, **COMMON)
    @given(case=cases(form, mode=mode))
    def test(case):
        check(case)
    for case in examples:
        test = example(case=case)(test)
    test.__doc__ = doc
    return test


# Cases that failed while this file was written (each a mistake of the test, not of plans; kept
# so that the fix of the test stays in place):
EXAMPLES = {
    # FD step taken from the guides' angle (0.01° from parallel) instead of the drive's: h = 4e-6
    # rad made the rounding of the positions dominate (2e-5); RPP's positions are smooth in φ
    "RPP": [build_rpp_yoke(r=1.0, beta=0.0, gamma=math.radians(0.01), e=0.0, w=np.array([0.5403023058681398,
                           0.8414709848078965]), phi=1.0, omega=1.0, epsilon=0.0),
            # its positions pass through the guides' vertex ~ |OC|/sin γ = 5500 m away: the rounding
            # floor must count it (``vertex``), and h = 1e-3 rad left FD errors of 8e-7
            Case("RPP", {"title": "random turning RPP",
                         "points": {"O": [0.0, 0.0], "K": [1.0, 0.0], "Q": [0.0, 0.0], "C": [0.0, 1.0]},
                         "links": {"0": ["O", "C"], "1": ["O", "K"], "2": ["C"], "3": ["Q"]},
                         "sliders": [{"link": "3", "on": "1", "through": "O", "angle": 57.29577951308232},
                                     {"link": "2", "on": "3", "through": "C", "angle": 57.301402926334234}],
                         "drive": {"link": "1", "angle": 0.0, "omega": 1.0, "epsilon": 0.0}},
                 0.0, note="turning, near parallel guides", parallel=9.81470764459972e-05)],
    # slot and frame guide almost the same line: every acceleration ~6e-4 m/s² while |v| ~ 0.75 m/s,
    # so "relative to max|a|" judged FD noise against a near-zero scale (now max(|a|, ω·|v|))
    "PRP": [Case("PRP", {"title": "random tangent mechanism",
                         "points": {"O": [0.0, 0.0], "K": [2.999995430739863, 0.005235985097694926],
                                    "B": [-0.0013089972712766827, 1.5]},
                         "links": {"0": ["O"], "1": ["O", "K"], "2": ["B"], "3": ["B"]},
                         "sliders": [{"link": "2", "on": "1", "through": "B", "angle": 0.1},
                                     {"link": "3", "on": "0", "through": "B", "angle": 0.0}],
                         "drive": {"link": "1", "angle": 0.1, "omega": 1.0, "epsilon": 0.0}},
                 0.1, singular=(0.0, math.pi), delta=0.0017453292519943296, note="near parallel guides")],
    # 0.0032° from a fold with h = δ/40: FD acceleration error 1.3e-7 from rounding (plans agrees with
    # a 50-digit four-bar to 4e-12): the rounding floor of ``fd_tolerance`` and h = δ/20
    "RRR": [Case("RRR", {"title": "random four-bar",
                         "points": {"O": [0.0, 0.0], "C": [0.3125, 0.0], "A": [0.8750267184554136, 0.4840746244011871],
                                    "B": [0.5950960979441492, 0.2404885816972208],
                                    "M": [1.11861276115938, 0.2041440038899227]},
                         "links": {"0": ["O", "C"], "1": ["O", "A"], "2": ["A", "B", "M"], "3": ["C", "B"]},
                         "drive": {"link": "1", "angle": 28.95186209419968, "omega": 1.0, "epsilon": 0.0},
                         "lengths": {"OA": 1.0, "OC": 0.3125, "AB": 0.3710731902199349, "BC": 0.3710731902199349}},
                 28.95186209419968, singular=(0.5053605102841573, -0.5053605102841573),
                 delta=5.519215703220226e-05, note="outer fold")],
}


test_rrr_regular = _property_test("RRR", "regular", "Four-bars (crank-rockers, double rockers, ...) at random angles.")
test_rrr_near_fold = _property_test("RRR", "near", "Four-bars 1e-3..1° from coupler-rocker collinear (a fold).",
                                    EXAMPLES["RRR"])
test_rrr_near_dead_centre = _property_test("RRR", "extreme", "Four-bars at and 1e-3..1° from crank-coupler collinear.")
test_rrp_regular = _property_test("RRP", "regular", "Crank-sliders (offset, inclined guide) and rods on a crank slot.")
test_rrp_near_fold = _property_test("RRP", "near", "RRP 1e-3..1° from rod ⟂ guide (a fold).")
test_rrp_near_dead_centre = _property_test("RRP", "extreme", "Crank-sliders at and 1e-3..1° from crank-rod collinear.")
test_rpr_regular = _property_test("RPR", "regular", "Slotted levers, oscillating and rotating, slot off C or not.")
test_rpr_near_fold = _property_test("RPR", "near", "Slotted levers 1e-3..1° from |AC| = slot offset (a fold).")
test_prp_regular = _property_test("PRP", "regular", "Tangent mechanisms with offset slots and inclined guides.")
test_prp_near_parallel = _property_test("PRP", "near", "Tangent mechanisms 1e-3..1° from parallel guides.",
                                        EXAMPLES["PRP"])
test_rpp_regular = _property_test("RPP", "regular", "Scotch yokes with inclined slots, yokes on a crank slot.")
test_rpp_near_parallel = _property_test("RPP", "near", "RPP with guides 1e-3..1° from parallel (every φ).",
                                        EXAMPLES["RPP"])


# --- at and closer than 10⁻³° to the singular position: an error, never inf or NaN ------------------

def _raises_or_finite(mech, structure, values) -> str:
    try:
        m = analyse(mech, structure, np.asarray(values, float))
    except (SingularPositionError, AssemblyError):
        return "raised"
    for name, s in m.links.items():
        for arr in (s.theta, s.origin, s.omega, s.v, s.epsilon, s.a):
            assert np.all(np.isfinite(arr)), f"link {name}: non-finite state at {values}"
    return "finite"


def _singular_test(form: str, doc: str):
    @settings(max_examples=N_SINGULAR, **COMMON)
    @given(case=cases(form, mode="near", delta_deg=1.0), closer=st.lists(_f(-13.0, -3.0), min_size=3, max_size=3))
    def test(case, closer):
        mech, structure = load(case.scene)
        # the nearest singular drive angle, continued to the sketch's turn
        target = case.phi + math.degrees(min((math.remainder(s_ - math.radians(case.phi), 2 * math.pi)
                                              for s_ in case.singular), key=abs))
        assert abs(abs(target - case.phi) - 1.0) < 1e-9
        side = math.copysign(1.0, case.phi - target)
        for values in ([target], [case.phi, target], [target, case.phi + side * 0.5]):
            with pytest.raises((SingularPositionError, AssemblyError)):
                analyse(mech, structure, np.array(values))
        # closer than the accuracy range: an error or finite numbers
        for k in sorted(closer):
            event(_raises_or_finite(mech, structure, [target + side * 10.0 ** k]))
    test.__doc__ = doc
    return test


N_SINGULAR = 25
test_rrr_at_fold = _singular_test("RRR", "Four-bars exactly at coupler-rocker collinear (sketch 1° away).")
test_rrp_at_fold = _singular_test("RRP", "RRP exactly at rod ⟂ guide (frame guide and crank slot).")
test_rpr_at_fold = _singular_test("RPR", "Slotted levers exactly at |AC| = slot offset.")
test_prp_at_parallel = _singular_test("PRP", "Tangent mechanisms exactly at parallel guides.")


@settings(max_examples=N_SINGULAR, **COMMON)
@given(case=rpp_cases(mode="regular", gamma=st.one_of(
    st.sampled_from([0.0, math.pi]),
    st.tuples(SIGN, _f(-13.0, -3.0)).map(lambda t: t[0] * math.radians(10.0 ** t[1])))).filter(lambda c: c is not None))
def test_rpp_at_parallel(case):
    """RPP with exactly parallel guides (γ = 0 or π) raises at every φ; 1e-13..1e-3° from
    parallel it raises or returns finite numbers."""
    mech, structure = load(case.scene)
    values = case.phi + np.array([0.0, 1.0, 90.0])
    if case.parallel == 0.0:
        with pytest.raises((SingularPositionError, AssemblyError)):
            analyse(mech, structure, values)
    else:
        event(_raises_or_finite(mech, structure, values))


# --- drawings: every plan of a random mechanism passes `plans check` --------------------------------

def test_toml_writer_round_trips():
    import tomllib

    case = build_rrp(r=0.1, alpha=0.2, e=-0.01, rod=0.3, phi=1.0, branch=1.0, coupler=(0.5, 0.2), omega=-7.0,
                     epsilon=1e-05)
    assert tomllib.loads(toml_text(case.scene)) == case.scene


def check_drawings(case: Case) -> None:
    """render_scene on the scene written as TOML: every SVG's tagged vectors, measured and
    multiplied by μ, equal their data-value (check_svg), and the data-value of every absolute
    vector v:X, a:X is |v_X|, |a_X| of the motion checked by ``check`` against finite
    differences."""
    motion = check(case)
    scene = dict(case.scene, plans={"draw": ["scheme", "velocity", "acceleration"]})
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "random.toml"
        path.write_text(toml_text(scene), encoding="utf-8")
        rendered = render_scene(path)
        svgs = {name: text for name, text in rendered.files.items() if name.endswith(".svg")}
        assert {n.split("-")[1].split(".")[0] for n in svgs} == {"scheme", "velocity", "acceleration"}
        points = set(case.scene["points"])
        n_absolute = 0
        for name, text in svgs.items():
            svg = Path(tmp) / name
            svg.write_text(text, encoding="utf-8")
            for meas in check_svg(svg):
                assert meas.ok, f"{name}: {meas.quantity} measures {meas.measured:.6g}, value {meas.value:.6g}"
                kind, _, point = meas.quantity.partition(":")
                if point in points and kind in ("v", "a"):
                    exact = (motion.velocity if kind == "v" else motion.acceleration)(point)[0]
                    assert meas.value == pytest.approx(float(np.linalg.norm(exact)), rel=1e-12)
                    n_absolute += 1
        assert n_absolute >= 2       # at least the crank pin's v and a
    data = json.loads(rendered.files["random.json"])
    assert len(data["positions"]) == 1


#: every form; RPP only as Scotch yokes (see test_drawings_rpp_turning_with_a_known_guide)
DRAWABLE = {"RRR": cases("RRR"), "RRP frame guide": cases("RRP", variant="frame guide"),
            "RRP crank slot": cases("RRP", variant="crank slot"), "RPR": cases("RPR"), "PRP": cases("PRP"),
            "RPP yoke": cases("RPP", variant="yoke")}


@pytest.mark.parametrize("kind", list(DRAWABLE))
@settings(max_examples=12, **COMMON)
@given(data=st.data())
def test_drawings_pass_plans_check(kind, data):
    """Four-bars, crank-sliders, rods on a crank slot, slotted levers, tangent mechanisms and
    Scotch yokes, at random, near-singular and dead-centre positions: the rendered plans pass
    `plans check` with the exact values."""
    check_drawings(data.draw(DRAWABLE[kind], label="case"))


#: Regression (fixed in 6fe062e): a slider of the group on a known turning guide (slot in the
#: crank). The acceleration plan's line parallel to the guide must pass through the tip of the
#: Coriolis vector drawn from the guide point's known image, e1 + 2ω×(v_E3 − v_E1); plans drew
#: it from the slider's (unknown) image, so the line passed through e1 itself, |a^k|/μa off the
#: right one, and render_scene's own geometric check refused the plan.
SLIDER_ON_TURNING_GUIDE = {
    # the falsifying example of test_drawings_pass_plans_check
    "RRP rod on a crank slot, E off the slot": Case(
        "RRP", {"title": "random rod on a crank slot",
                "points": {"O": [0.0, 0.0], "K": [-0.9682458365518543, 0.25000000000000006], "C": [1.0, 0.0],
                           "E": [0.5182372542187895, -0.13380828366490877]},
                "links": {"0": ["O", "C"], "1": ["O", "K"], "2": ["C", "E"], "3": ["E"]},
                "sliders": [{"link": "3", "on": "1", "through": "O", "angle": -194.47751218592992}],
                "drive": {"link": "1", "angle": -194.47751218592992, "omega": 1.0, "epsilon": 0.0}},
        -194.47751218592992, note="found by hypothesis"),
    "PRP tangent mechanism, offset slot": build_prp(r=0.3, kappa=0.2, c=0.05, beta=math.pi / 2, e=-0.15, phi=0.5,
                                                   omega=5.0, epsilon=0.0),
    # the slot through O: a_B1 = −ω²·OB lies on the slot, the wrong line passed through the pole
    # and met the frame guide's line there — drawn "right" by accident unless ε ≠ 0
    "PRP tangent mechanism, slot through O, epsilon != 0": build_prp(r=0.3, kappa=0.0, c=0.0, beta=math.pi / 2,
                                                                    e=-0.15, phi=0.5, omega=5.0, epsilon=30.0),
}


@pytest.mark.parametrize("name", list(SLIDER_ON_TURNING_GUIDE))
def test_drawings_slider_on_a_known_turning_guide(name):
    check_drawings(SLIDER_ON_TURNING_GUIDE[name])


#: An RPP group turning with a known guide: link 3 slides on the crank's slot, link 2 (pinned to
#: the frame at C) slides in a slot of link 3. The plans once drew the group's two sliding
#: relations for two different points of link 3 — C3 (pair 2/3) and Q3 (pair 3/1, labelled by
#: link 3's own point Q) — whose images differ because link 3 turns, so the two construction
#: lines met at neither image. (The Scotch yoke's link 3 only translates, so its points share
#: one image and the plan worked.)
RPP_TURNING = {
    "RPP on a crank slot": build_rpp_turning(r=0.3, kappa=0.3, gamma=1.6, c=np.array([0.1, 0.2]),
                                             q=np.array([0.15, 0.05]), phi=0.3, omega=9.0, epsilon=30.0),
    "RPP on a crank slot, Q on the crank's slot": build_rpp_turning(
        r=0.3, kappa=0.0, gamma=math.radians(100.0), c=np.array([0.1, 0.2]), q=np.array([0.1, 0.0]), phi=0.4,
        omega=9.0, epsilon=0.0),
}


@pytest.mark.parametrize("name", list(RPP_TURNING))
def test_drawings_rpp_turning_with_a_known_guide(name):
    """Once a strict xfail: both sliding relations are now written for the outer pin D of the
    group, so their construction lines meet at its image d3."""
    check_drawings(RPP_TURNING[name])


def test_rpp_turning_with_a_known_guide_kinematics_are_right():
    """The same mechanisms pass every kinematic check."""
    for case in RPP_TURNING.values():
        check(case)


# --- continuation: a drive angle far from the sketch's ---------------------------------------------

#: positions after a walk against the builders' closed forms at the same angle, relative to the
#: mechanism's extent (two different formulas for the same point: a few ulps, amplified by the
#: group's conditioning 1/|sin|, which the regular cases keep below ~30)
TOL_WALK = 1e-12


def _free_arc(case: Case) -> tuple[float, float]:
    """How far (rad) the drive may turn down and up from the sketch before a singular angle."""
    phi = math.radians(case.phi)
    ups = [(s - phi) % (2 * math.pi) for s in case.singular]
    return (min((2 * math.pi - u for u in ups), default=math.inf), min(ups, default=math.inf))


@settings(max_examples=100, **COMMON)
@given(case=st.one_of([cases(form, mode="regular") for form in STRATEGIES]), t=_f(0.0, 1.0))
def test_walk_from_the_sketch_keeps_the_branch(case, t):
    """Requested 0..179° away from the sketch (never across a singular angle, which plans
    refuses), alone or together with the sketch's angle: every point is where the builder's
    closed form puts it on the sketch's branch at the requested angle, and the velocities and
    accelerations are those of the same mechanism sketched at that angle, which pass every
    check of ``check``."""
    down, up = _free_arc(case)
    margin = math.radians(0.5)
    # at most half a turn, so that the angle alone and with the sketch's are walked to along the
    # same steps (compared bit for bit below); longer walks: test_walk_longer_than_half_a_turn
    lo, hi = -min(down - margin, math.radians(179.0)), min(up - margin, math.radians(179.0))
    turn = lo + t * (hi - lo)
    target = case.rebuild(math.radians(case.phi) + turn)
    event("full turn" if not case.singular else "limited turn")
    mech, structure = load(case.scene)
    m = analyse(mech, structure, np.array([target.phi]))
    both = analyse(mech, structure, np.array([case.phi, target.phi]), order=0)
    assert all(np.array_equal(both.links[n].origin[1], m.links[n].origin[0]) for n in m.links)
    size = max(mech.size, load(target.scene)[0].size)
    err = max(np.linalg.norm(m.position(p)[0] - np.asarray(xy)) for p, xy in target.scene["points"].items()) / size
    record(f"{case.form}: walk: |r - r_closed form| / size", err, f"{case.label} → {target.phi:.6g}°")
    # two formulas for one pose differ by a few ulps amplified by 1/|sin| (the group's
    # conditioning there; the walk may end 0.5° from a singular angle, |sin| ~ 0.009);
    # velocities from the two poses differ by that times 1/|sin| again, accelerations twice
    cond = min([1.0] + [abs(float(s[0])) for s in m.sines.values()])
    tol = {k: max(TOL_WALK, 16 * EPS / cond ** (k + 1)) for k in range(3)}
    assert err < tol[0], f"{case.label}: walked to {target.phi:g}°, a point is {err:.3g}·size off"
    there = check(target)
    for k, qty in ((1, "velocity"), (2, "acceleration")):
        got = {p: getattr(m, qty)(p)[0] for p in target.scene["points"]}
        want = {p: getattr(there, qty)(p)[0] for p in target.scene["points"]}
        scale = max(np.linalg.norm(v) for v in want.values())
        err = max(np.linalg.norm(got[p] - want[p]) for p in got) / scale
        record(f"{case.form}: walk: {qty} vs sketched there", err, f"{case.label} → {target.phi:.6g}°")
        assert err < tol[k], f"{case.label}: walked to {target.phi:g}°, {qty} off by {err:.3g} (tol {tol[k]:.1e})"


#: A slotted lever whose crank cannot turn fully (limit positions at ±36.3°), sketched at
#: −108.17°: −308.17° is reached by turning the crank 200° down, without passing a limit.
WALK_CASE = Case("RPR", {"title": "random slotted lever",
                         "points": {"O": [0.0, 0.0], "C": [0.1875, 0.0],
                                    "A": [-0.11692679333668564, -0.35630482034348065],
                                    "T": [0.043634633589446636, -0.989597269775719]},
                         "links": {"0": ["O", "C"], "1": ["O", "A"], "2": ["A"], "3": ["C", "T"]},
                         "sliders": [{"link": "2", "on": "3", "through": "A", "angle": -98.27158059498339}],
                         "drive": {"link": "1", "angle": -108.16802875730697, "omega": 1.0, "epsilon": 0.0}},
                 -108.16802875730697, singular=(0.6341838408240408, -0.6341838408240408),
                 delta=1.2537044063828762, note="regular")


def test_walk_longer_than_half_a_turn():
    """Found by test_walk_from_the_sketch_keeps_the_branch (turn −200°) before it was limited to
    half a turn; once a strict xfail (alone, −308.17° was walked to from −468.17°, up across the
    limit position at −396.17°, and refused). The same angle, requested alone and with the
    sketch's, gives the same pose: alone it is now walked the long way round when the short
    way passes a limit position."""
    mech, structure = load(WALK_CASE.scene)
    target = WALK_CASE.phi - 200.0
    together = analyse(mech, structure, np.array([target, WALK_CASE.phi]), order=0)
    r = math.hypot(*WALK_CASE.scene["points"]["A"])
    assert np.linalg.norm(together.position("A", "2")[0] - r * _u(math.radians(target))) < 1e-12
    alone = analyse(mech, structure, np.array([target]), order=0)
    for link in ("2", "3"):
        assert np.array_equal(alone.links[link].theta[0], together.links[link].theta[0])
        assert np.array_equal(alone.links[link].origin[0], together.links[link].origin[0])


# --- an exact oracle where one is cheap: the four-bar near its folds in 50 digits ----------------

@settings(max_examples=40, **COMMON)
@given(case=cases("RRR", mode="near"))
def test_rrr_near_fold_against_50_digit_closed_form(case):
    """1e-3..1° from a fold, v_B, a_B, ω and ε of coupler and rocker against the four-bar solved
    in 50-digit arithmetic from the model's own float data (test_kinematics'
    ``_four_bar_in_50_digits``): relative 1e-7, no floor — double precision has enough digits
    here (plans' error grows like eps/sin³, sin ≥ ~2e-3 at 1e-3° from a fold)."""
    from test_kinematics import _four_bar_in_50_digits

    mech, structure = load(case.scene)
    m = analyse(mech, structure, np.array([case.phi]))
    exact = _four_bar_in_50_digits(mech, case.phi, m.position("B", "3")[0])
    size = mech.size
    errs = {"position": np.linalg.norm(m.position("B", "3")[0] - exact["B"]) / size,
            "velocity": np.linalg.norm(m.velocity("B", "3")[0] - exact["v_B"]) / np.linalg.norm(exact["v_B"]),
            "acceleration": np.linalg.norm(m.acceleration("B", "3")[0] - exact["a_B"]) / max(
                np.linalg.norm(exact["a_B"]), abs(mech.drive.speed) * np.linalg.norm(exact["v_B"])),
            "omega": np.max(np.abs([m.links["2"].omega[0] - exact["w"][0], m.links["3"].omega[0] - exact["w"][1]]))
            / np.max(np.abs(exact["w"])),
            "epsilon": np.max(np.abs([m.links["2"].epsilon[0] - exact["e"][0],
                                      m.links["3"].epsilon[0] - exact["e"][1]]))
            / max(np.max(np.abs(exact["e"])), np.linalg.norm(exact["a_B"]) / size)}
    for qty, err in errs.items():
        record(f"RRR: 50-digit near fold: {qty}", float(err), case.label)
        assert err < (TOL_CLOSURE if qty == "position" else TOL_FD), f"{case.label}: {qty} {err:.3g}"

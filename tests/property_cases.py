"""Random class II mechanisms for the property tests (``test_properties*.py``): ``Case`` and one
builder per form, from explicit parameters (``property_strategies.py`` draws them).

The five class II forms — RRR (four-bar), RRP (crank-slider with offset and inclined guide, and
a rod sliding on the crank's own slot), RPR (slotted lever, oscillating or rotating), PRP
(tangent mechanism with an offset slot and an arbitrary frame guide), RPP (Scotch yoke with an
inclined slot, and a yoke sliding on the crank's slot). Each builder assembles the mechanism in
closed form at the drive angle φ, on the branch it is given, and finds the form's singular
drive angles analytically (RPP: singular for every φ or for none, ``Case.parallel``). The
result is a scene dict; ``Case.rebuild(phi)`` is the same mechanism at another angle on the
same branch (the walks of ``test_properties_walk.py`` compare plans' continuation with it).
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass, field

import numpy as np


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

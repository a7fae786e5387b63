"""The counterweights of ``[counterweights]``: their masses and angles, for a four-bar (full force
balance) or a crank-slider (the rotating masses and a fraction of the reciprocating ones).

Every vector of a link is a complex number in the link's own frame: origin its first point
(its pivot on the frame), x along the line to its second point, y 90° counter-clockwise; so a
point X of link k is at P_k + e^{iφ_k}·z_k(X) in the world, φ_k the link's angle
(``motion.angles``). A coupler's centre of mass S = A + λ·(B − A) with the complex ratio
λ = (S − A)/(B − A), the same in every frame; so m·r_S = m(1 − λ)·r_A + m·λ·r_B exactly: the
coupler's mass distributed to its two pins (complex masses when S is off the line AB).

**Four-bar** (crank 1 pivoted at O, coupler 2 with pins A and B, rocker 3 pivoted at C; any
names): by the method of linearly independent vectors (Lowen and Berkof) the moving links'
total m·r_G = const + e^{iφ1}(m1·z1(S1) + m2(1 − λ)·z1(A)) + e^{iφ3}(m3·z3(S3) + m2·λ·z3(B)),
and e^{iφ1}, e^{iφ3} are linearly independent functions of the motion, so r_G stands still if
and only if both brackets vanish: the crank's counterweight is m_c·ρ·e^{iα} = −(first bracket),
the rocker's −(second). It needs both.

**Crank-slider** (crank pivoted at O, rod A–B, slider on a frame guide): the textbook's lumping,
the rod's mass to its pins by the projection t = Re λ of its centre on AB (m2(1 − t) at A,
rotating, m2·t at B, reciprocating with the slider: m_rec = m3 + m2·t); the crank's counterweight
balances the crank's own m1·z1(S1), the rod's part at A and a fraction c of m_rec at A:
m_c·ρ·e^{iα} = −(m1·z1(S1) + (m2(1 − t) + c·m_rec)·z1(A)). Along the line of stroke u (from O
toward the slider) the reciprocating inertia force is, to O((r/l)³) for an in-line engine at
constant ω (x = r cos θ + l√(1 − (r/l)² sin²θ), θ the crank's angle from u):
F_p = m_rec·r·ω²·cos θ (primary), F_s = m_rec·r·ω²·cos 2θ / n (secondary), n = l/r; after
balancing (1 − c)·F_p stays along u and −c·m_rec·r·ω²·sin θ comes in across it (along k × u).

Numeric; reads a solved Motion and the scene; refusals are SceneError naming ``counterweights``.
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..errors import SceneError
from ..kinematics import Motion
from ..kinematics.state import cross
from ..model import Mechanism, Prismatic
from ..scene import FRAME, Scene
from ..scene.counterweights import DEFAULT_RECIPROCATING, CounterweightSpec

__all__ = ["Counterweight", "Reciprocating", "find_counterweights", "SNAP"]

#: A counterweight's m·ρ within this fraction of the sum of the terms it balances is rounding:
#: no counterweight is needed there (0 kg at 0°), as for a rotor's balancing masses.
SNAP = 1e-13


@dataclass(frozen=True)
class Counterweight:
    """A counterweight found: ``mass`` (kg) at ``radius`` (m) from ``pivot`` (the first point of
    ``link``), at ``angle`` (degrees in [0, 360), counter-clockwise from the link's line first
    point → second point); ``mr`` = mass·radius (kg·m)."""

    link: str
    pivot: str
    radius: float
    mass: float
    angle: float

    @property
    def mr(self) -> float:
        return self.mass * self.radius


@dataclass(frozen=True, eq=False)
class Reciprocating:
    """A crank-slider's forces along its line of stroke at N positions (N, SI).

    ``fraction`` c balanced by the counterweight; ``rod_at_pin``, ``rod_at_slider`` the rod's
    mass lumped at the crank pin and at the slider (kg); ``mass`` m_rec (kg, slider + rod's part);
    ``crank`` r, ``rod`` l (m), ``n`` = l/r; ``stroke`` u (2,) the line of stroke's unit direction
    from the crank's pivot toward the slider, ``offset`` e = u × (B − O) (m; the closed forms are
    for e = 0); ``theta`` the crank's angle from u (deg, CCW), ``omega`` ω (rad/s); ``primary``
    m_rec·r·ω²·cos θ and ``secondary`` m_rec·r·ω²·cos 2θ/n (before balancing), ``primary_after``
    (1 − c)·F_p along u and ``transverse_after`` −c·m_rec·r·ω²·sin θ along k × u (after);
    ``exact`` −m_rec·a_B·u, the reciprocating masses' inertia force from the kinematics."""

    fraction: float
    rod_at_pin: float
    rod_at_slider: float
    mass: float
    crank: float
    rod: float
    n: float
    stroke: np.ndarray
    offset: float
    theta: np.ndarray
    omega: np.ndarray
    primary: np.ndarray
    secondary: np.ndarray
    primary_after: np.ndarray
    transverse_after: np.ndarray
    exact: np.ndarray


def _frame_of(motion: Motion, link: str) -> Callable[[str], complex]:
    """z(X): a point of ``link`` as a complex number in the link's frame (first point, x toward
    the second)."""
    local = motion.mechanism.links[link].local
    pts = motion.mechanism.links[link].points
    p0 = complex(*local[pts[0]])
    axis = complex(*local[pts[1]]) - p0
    e = axis / abs(axis)
    return lambda name: (complex(*local[name]) - p0) / e


def _mass(scene: Scene, link: str) -> tuple[float, str | None]:
    m = scene.masses.get(link)
    return (0.0, None) if m is None else (m.mass, m.centre)


def _ratio(motion: Motion, link: str, a: str, b: str, s: str | None) -> complex:
    """λ = (S − A)/(B − A) of a link's centre S between its pins A and B (0 without a centre)."""
    if s is None:
        return 0j
    local = motion.mechanism.links[link].local
    za, zb, zs = (complex(*local[p]) for p in (a, b, s))
    return (zs - za) / (zb - za)


def _weight(spec: CounterweightSpec, needed: complex, scale: float) -> Counterweight:
    """The counterweight of ``spec`` whose m·ρ·e^{iα} is ``needed`` (kg·m, in its link's frame)."""
    if abs(needed) <= SNAP * scale or needed == 0:
        return Counterweight(spec.link, spec.pivot, spec.radius, 0.0, 0.0)
    angle = math.degrees(cmath.phase(needed)) % 360.0
    return Counterweight(spec.link, spec.pivot, spec.radius, abs(needed) / spec.radius,
                         0.0 if angle >= 360.0 else angle)


def _pin(mech: Mechanism, x: str, y: str) -> str | None:
    """The point of the revolute pair joining links x and y (None when they are not joined)."""
    return next((r.point for r in mech.revolutes if {r.a, r.b} == {x, y}), None)


def find_counterweights(motion: Motion, scene: Scene) -> tuple[tuple[Counterweight, ...], Reciprocating | None]:
    """The counterweights of ``scene.counterweights`` for the mechanism of ``motion``: a four-bar
    of revolute pairs (full force balance, both links pivoted on the frame) or a crank-slider
    (the crank's, with its reciprocating fraction; then also its :class:`Reciprocating`).
    Anything else is refused in one line naming ``counterweights``."""
    mech = motion.mechanism
    moving = mech.moving
    pivoted = [k for k in moving if _pin(mech, FRAME, k) is not None]
    what = ("counterweights are found for a four-bar of revolute pairs (crank, coupler, rocker pivoted on the frame) "
            "or a crank-slider (crank, rod, slider on a frame guide)")
    if len(moving) != 3:
        raise SceneError(f"{what}; this mechanism has {len(moving)} moving links", key="counterweights")
    if not mech.prismatics and len(mech.revolutes) == 4 and len(pivoted) == 2:
        c1, c3 = pivoted
        coupler = next(k for k in moving if k not in pivoted)
        a, b = _pin(mech, c1, coupler), _pin(mech, coupler, c3)
        if a is not None and b is not None:
            return _four_bar(motion, scene, c1, coupler, c3, a, b), None
    if len(mech.prismatics) == 1 and len(mech.revolutes) == 3 and len(pivoted) == 1:
        p = mech.prismatics[0]
        crank = pivoted[0]
        slider = p.slider if p.guide == FRAME else p.guide if p.slider == FRAME else None
        rod = next((k for k in moving if k not in (crank, slider)), None)
        if slider is not None and slider != crank and rod is not None:
            a, b = _pin(mech, crank, rod), _pin(mech, rod, slider)
            if a is not None and b is not None:
                return _crank_slider(motion, scene, crank, rod, slider, a, b, p)
    raise SceneError(f"{what}; this one has {len(mech.revolutes)} revolute and {len(mech.prismatics)} prismatic "
                     "pairs", key="counterweights")


def _four_bar(motion: Motion, scene: Scene, c1: str, coupler: str, c3: str, a: str, b: str
              ) -> tuple[Counterweight, ...]:
    """Full force balance of a four-bar (crank ``c1``, ``coupler`` with pins ``a`` on c1 and ``b``
    on ``c3``): one counterweight on each link pivoted on the frame."""
    specs = scene.counterweights
    for link, spec in specs.items():
        if spec.reciprocating is not None:
            raise SceneError("reciprocating is the fraction of a crank-slider's reciprocating masses; a four-bar has "
                             "none: remove it", key=f"counterweights.{link}.reciprocating")
    missing = [k for k in (c1, c3) if k not in specs]
    if missing:
        raise SceneError(f"full force balance of a four-bar needs a counterweight on each link pivoted on the frame, "
                         f"{c1} and {c3}: one alone cannot hold the centre of mass still (Lowen–Berkof); add "
                         f"\"{missing[0]}\" = {{ radius = … }}", key="counterweights")
    m2, s2 = _mass(scene, coupler)
    lam = _ratio(motion, coupler, a, b, s2)
    out = []
    for link, pin, share in ((c1, a, m2 * (1.0 - lam)), (c3, b, m2 * lam)):
        z = _frame_of(motion, link)
        m, s = _mass(scene, link)
        own = m * z(s) if s is not None else 0j
        rest = share * z(pin)
        out.append(_weight(specs[link], -(own + rest), abs(own) + abs(rest)))
    return tuple(out)


def _crank_slider(motion: Motion, scene: Scene, crank: str, rod: str, slider: str, a: str, b: str,
                  pair: Prismatic) -> tuple[tuple[Counterweight, ...], Reciprocating]:
    """The crank's counterweight of a crank-slider and its primary and secondary forces."""
    spec = scene.counterweights.get(crank)
    if spec is None:          # the reader lets through only links pivoted on the frame: the crank
        raise SceneError(f"a crank-slider's counterweight goes on its crank {crank}", key="counterweights")
    c = DEFAULT_RECIPROCATING if spec.reciprocating is None else spec.reciprocating
    m1, s1 = _mass(scene, crank)
    m2, s2 = _mass(scene, rod)
    m3, _ = _mass(scene, slider)
    t = _ratio(motion, rod, a, b, s2).real
    at_pin, at_slider = m2 * (1.0 - t), m2 * t
    m_rec = m3 + at_slider
    z = _frame_of(motion, crank)
    own = m1 * z(s1) if s1 is not None else 0j
    rest = (at_pin + c * m_rec) * z(a)
    weight = _weight(spec, -(own + rest), abs(own) + abs(rest))
    local = motion.mechanism.links[rod].local
    r, l = abs(z(a)), float(math.hypot(*(local[b] - local[a])))
    pivot = motion.position(spec.pivot, crank)
    pin, block = motion.position(a, crank), motion.position(b, slider)
    u = np.asarray(pair.direction, float) / math.hypot(*pair.direction)   # the frame's local frame is the world's
    if float(np.sum((block[0] - pivot[0]) * u)) < 0.0:
        u = -u
    arm = pin - pivot
    theta = np.arctan2(cross(np.broadcast_to(u, arm.shape), arm), np.sum(arm * u, axis=1))
    omega = motion.links[crank].omega
    w2 = omega * omega
    base = m_rec * r * w2
    acc = motion.acceleration(b, slider)
    return (weight,), Reciprocating(
        fraction=c, rod_at_pin=at_pin, rod_at_slider=at_slider, mass=m_rec, crank=r, rod=l, n=l / r, stroke=u,
        offset=float(cross(u, block[0] - pivot[0])), theta=np.degrees(theta), omega=np.asarray(omega, float),
        primary=base * np.cos(theta), secondary=base * np.cos(2.0 * theta) / (l / r),
        primary_after=(1.0 - c) * base * np.cos(theta), transverse_after=-c * base * np.sin(theta),
        exact=-m_rec * np.sum(acc * u, axis=1))

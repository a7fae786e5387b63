"""Every real assembly of a class III or IV group with a sliding (prismatic) pair, the other
links held at ``known`` (seed 002's method, :mod:`plans.kinematics.assemblies` for revolute pairs).

A prismatic pair fixes the relative angle of its two links (their local frames are the sketch's,
so the angles are equal) and puts a point of one on a line of the other. For a rod r sliding on a
link U (the pair's anchors a_r on r, a_U on U, its local normal n), every point Y of r (local y)
lies on the line of U at a fixed offset (the pair's equation (X_s − Y_g)·n_g = 0 moved along r):

    (Y − Q_U)·R(θ_U)n = d,   Q_U = U's anchor in the world,   d = (y − a_r)·n.

* Class III: the base link's pose (φ; C, the world position of its local point ``ref``) is the
  unknown. A rod joined by two revolute pairs gives a circle, a rod with one sliding pair a line,
  each a condition g = α|C|² + β(φ)·C + γ(φ) = 0 (lengths ÷ size; :class:`Condition`); a rod
  with two sliding pairs fixes φ to its outer link's angle. Subtracting a circle (α = 1) from
  the other two leaves two conditions linear in C: C = N/Δ by Cramer's rule (Δ, N of degree 2
  in cos φ, sin φ), and the circle, × Δ², gives F(φ) = |N|² + Δ β·N + Δ² γ, a trigonometric
  polynomial of degree ≤ 5; with three lines, F = det[β_k γ_k] (degree ≤ 3). F vanishes at
  every assembly's φ (where Δ = 0, N = adj·L·C = Δ·C = 0 as well), so no assembly is missed.
  At each root C is where two of the conditions meet (circles and lines) and meets the third;
  a travel never appears as an unknown: it follows from C.
* Class IV: the links x, y with the outer pairs are placed by one parameter each: a pinned link
  by its angle, a sliding one by its travel s = size·tan(φ/2) (the seed's half-angle substitution
  maps the unbounded travel onto the circle, s = ∞ at φ = π). Each rod's condition between x and
  y is affine in (cos ψ, sin ψ) for a pinned y and a quadratic in its travel for a sliding one,
  which × cos²(ψ/2) is affine in (cos ψ, sin ψ) too: A cos ψ + B sin ψ = D, with A, B, D read off
  three values of ψ (0, ±π/2). They are of degree 1 in cos φ, sin φ for a pinned x; for a sliding
  x a quadratic in s, × cos²(φ/2) degree 1 as well: the residual of
  :func:`.trig_roots.cramer_residual` is of degree ≤ 4, as for revolute pairs, and ψ follows
  from the quadratics (7). Roots at s = ∞ are dropped.

The roots are bracketed by :func:`.trig_roots.trig_roots` (certified: Fourier coefficients
from 64 samples bound |F′|); each is completed here and polished by the caller.
Lengths in metres, angles in radians, counter-clockwise positive.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np

from ..errors import SceneError
from ..structure import ComplexGroup, Pair
from .state import LinkState
from .trig_roots import cramer_residual, group_roots, half_angle_roots
from .. import linalg as la

__all__ = ["Condition", "sliding_poses", "base_conditions", "base_residual"]

States = Mapping[str, LinkState]
#: A completed C must meet every condition within this (lengths ÷ size) before polishing.
MEET_TOL = 1e-6


def _rot(v: np.ndarray, c: np.ndarray, s: np.ndarray) -> np.ndarray:
    """R(φ)·v (n, 2) for one vector v (2,) and cos φ, sin φ (n,)."""
    return np.column_stack([c * v[0] - s * v[1], s * v[0] + c * v[1]])


@dataclass(frozen=True)
class Condition:
    """One rod's condition on the base pose (φ, C) of a class III group, lengths ÷ size:

    * ``RR`` |C + R(φ)p − a|² = c²  (p: the inner pin from ``ref``, a: the outer pin, c: the rod's length)
    * ``PR`` (C + R(φ)p − a)·n = c  (the inner pin on the outer link's line: a its anchor, n its world normal)
    * ``RP`` (a − C − R(φ)p)·R(φ)n = c  (the outer pin a on the base's line: p its anchor from ``ref``,
      n the pair's local normal)."""

    kind: str
    p: np.ndarray
    a: np.ndarray
    n: np.ndarray
    c: float

    @property
    def alpha(self) -> float:
        return 1.0 if self.kind == "RR" else 0.0

    def terms(self, cp: np.ndarray, sp: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """β (n, 2) and γ (n,) of α|C|² + β·C + γ = 0 at cos φ, sin φ (n,)."""
        rp = _rot(self.p, cp, sp)
        if self.kind == "RR":
            w = rp - self.a
            return 2.0 * w, w[:, 0] ** 2 + w[:, 1] ** 2 - self.c ** 2
        if self.kind == "PR":
            return np.broadcast_to(self.n, rp.shape), la.dot(rp - self.a, self.n) - self.c
        rn = _rot(self.n, cp, sp)
        return -rn, la.dot(rn, self.a) - la.dot(self.p, self.n) - self.c


def sliding_poses(mech, g: ComplexGroup, known: States) -> list[dict[str, LinkState]]:
    """Every real assembly of ``g`` (with a sliding pair), before polishing: the states of the
    group's links (and the other links of ``known``)."""
    known = {n: s for n, s in known.items() if n not in g.links}
    return _class_iii(mech, g, known) if g.base is not None else _class_iv(mech, g, known)


# --- class III: the base link's pose ---------------------------------------------------------

def base_conditions(mech, g: ComplexGroup, known: States) -> tuple[np.ndarray, list[Condition], list[float]]:
    """``ref`` (the base's local point C stands for), the conditions of the rods with at most one
    sliding pair, and the base angles fixed by the rods with two (rad)."""
    size, base = mech.size, g.base
    loc = {n: mech.links[n].local for n in g.links}
    ref = np.mean(list(loc[base].values()), axis=0)
    conds, fixed = [], []
    for r in g.rods:
        o, i, lr = r.outer, r.inner, loc[r.link]
        if o.kind == "R" and i.kind == "R":
            conds.append(Condition("RR", (loc[base][i.point] - ref) / size, _world(mech, known, o) / size,
                                   np.zeros(2), la.norm(lr[i.point] - lr[o.point]) / size))
        elif o.kind == "P" and i.kind == "R":
            pr, k = o.prismatic, o.b
            conds.append(Condition("PR", (loc[base][i.point] - ref) / size, known[k].point(pr.anchor[k])[0] / size,
                                   known[k].direction(pr.normal)[0], la.dot(lr[i.point] - pr.anchor[r.link], pr.normal) / size))
        elif o.kind == "R" and i.kind == "P":
            pr = i.prismatic
            conds.append(Condition("RP", (pr.anchor[base] - ref) / size, _world(mech, known, o) / size, pr.normal,
                                   la.dot(lr[o.point] - pr.anchor[r.link], pr.normal) / size))
        else:
            fixed.append(float(known[o.b].theta[0]))
    return ref, conds, fixed


def base_residual(conds: list[Condition]):
    """F(φ) of three conditions (see the module): zero at every base angle of an assembly."""
    j = next((k for k, c in enumerate(conds) if c.alpha), None)

    def f(phi):
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        cp, sp = np.cos(phi), np.sin(phi)
        t = [c.terms(cp, sp) for c in conds]
        if j is None:       # three lines: (C, 1) is a null vector of the rows [β γ]
            (b0, g0), (b1, g1), (b2, g2) = t
            return (b0[:, 0] * (b1[:, 1] * g2 - g1 * b2[:, 1]) - b0[:, 1] * (b1[:, 0] * g2 - g1 * b2[:, 0])
                    + g0 * (b1[:, 0] * b2[:, 1] - b1[:, 1] * b2[:, 0]))
        bj, gj = t[j]
        rows = [(t[k][0] - conds[k].alpha * bj, gj * conds[k].alpha - t[k][1]) for k in range(3) if k != j]
        (l0, r0), (l1, r1) = rows
        det = l0[:, 0] * l1[:, 1] - l0[:, 1] * l1[:, 0]
        nx = r0 * l1[:, 1] - r1 * l0[:, 1]
        ny = l0[:, 0] * r1 - l1[:, 0] * r0
        return nx * nx + ny * ny + det * (bj[:, 0] * nx + bj[:, 1] * ny) + det * det * gj
    return f


def _class_iii(mech, g: ComplexGroup, known: States) -> list[dict[str, LinkState]]:
    ref, conds, fixed = base_conditions(mech, g, known)
    if len(fixed) > 1:
        raise SceneError(f"group {g.name} (form {g.form}): two rods slide on both their pairs, so the base link can "
                         "still slide: its assemblies are a continuum; leave \"assemblies\" out of draw", key="plans.draw")
    roots = fixed or group_roots(g, base_residual(conds), "angle of the base link")
    out = []
    for phi in roots:
        for c in _meet_all(conds, phi):
            states = dict(known)
            cs, sn = math.cos(phi), math.sin(phi)
            world = c * mech.size
            states[g.base] = _state(phi, world - np.array([cs * ref[0] - sn * ref[1], sn * ref[0] + cs * ref[1]]))
            out.append(_rods(mech, g, states))
    return out


def _meet_all(conds: list[Condition], phi: float) -> list[np.ndarray]:
    """Every C (÷ size) where the conditions meet at base angle φ: the meeting points of each two
    (circle or line), kept where every condition holds within MEET_TOL."""
    cp, sp = np.array([math.cos(phi)]), np.array([math.sin(phi)])
    t = [(c.alpha, *(x[0] for x in c.terms(cp, sp))) for c in conds]
    found: list[np.ndarray] = []
    for i in range(len(t)):
        for k in range(i + 1, len(t)):
            for c in _meet(t[i], t[k]):
                ok = all(abs(al * la.dot(c, c) + la.dot(b, c) + gm) <= MEET_TOL for al, b, gm in t)
                if ok and not any(la.norm(c - f) <= 1e-9 for f in found):
                    found.append(c)
    return found


def _meet(one, two) -> list[np.ndarray]:
    """The points of α|C|² + β·C + γ = 0 for two conditions (α 1: a circle, 0: a line)."""
    (a1, b1, g1), (a2, b2, g2) = sorted((one, two), key=lambda t: -t[0])
    if a1 and a2:       # two circles: the first with their radical line
        b2, g2 = b1 - b2, g1 - g2
    if not a1:          # two lines
        det = b1[0] * b2[1] - b1[1] * b2[0]
        if abs(det) <= 1e-12 * la.norm(b1) * la.norm(b2):
            return []
        return [np.array([(-g1 * b2[1] + g2 * b1[1]) / det, (-b1[0] * g2 + b2[0] * g1) / det])]
    nn = la.dot(b2, b2)
    if nn == 0.0:
        return []
    m = -0.5 * b1
    foot = m - (la.dot(b2, m) + g2) / nn * b2
    r2 = la.dot(m, m) - g1
    h2 = r2 - la.dot(foot - m, foot - m)       # r² − (distance of the line)²
    if h2 < -1e-9 * max(r2, 1e-300):
        return []
    along = np.array([-b2[1], b2[0]]) / math.sqrt(nn)
    h = math.sqrt(max(h2, 0.0))
    return [foot + h * along, foot - h * along]


# --- class IV: the two links with outer pairs --------------------------------------------------

def _class_iv(mech, g: ComplexGroup, known: States) -> list[dict[str, LinkState]]:
    ox, oy = g.outer
    x, y = ox.a, oy.a
    rods = [n for n in g.links if n not in (x, y)]
    joints = []
    for rod in rods:
        pairs = {p.other(rod): p for p in g.inner if rod in (p.a, p.b)}
        if set(pairs) != {x, y}:
            raise SceneError(f"group {g.name}: its assemblies are not yet enumerated for this form (the links with "
                             "outer pairs are not opposite in the contour); leave \"assemblies\" out of draw",
                             key="plans.draw")
        joints.append((rod, pairs[x], pairs[y]))
    slides = ox.kind == "P"
    place_x, place_y = _placer(mech, known, ox), _placer(mech, known, oy)
    if any(px.kind == py.kind == "P" for _, px, py in joints):
        return _locked(mech, g, known, joints, place_x, place_y)
    quarter = np.array([0.0, 0.5 * math.pi, -0.5 * math.pi])
    weight = np.array([1.0, 0.5, 0.5]) if oy.kind == "P" else np.ones(3)      # cos²(ψ/2) when y slides

    def coefficients(phi: np.ndarray):
        sx = place_x(np.repeat(phi, 3))
        sy = place_y(np.tile(quarter, len(phi)))
        e = np.array([_rod_condition(mech, rod, px, py, x, y, sx, sy).reshape(-1, 3) * weight for rod, px, py in joints])
        b = 0.5 * (e[:, :, 1] - e[:, :, 2])
        d = -0.5 * (e[:, :, 1] + e[:, :, 2])
        a = e[:, :, 0] + d
        w = np.cos(0.5 * phi) ** 2 if slides else 1.0     # s = size·tan(φ/2): a quadratic in s × cos²(φ/2)
        return a * w, b * w, d * w

    out = []
    for phi in group_roots(g, cramer_residual(coefficients, 1.0), f"{'travel' if slides else 'angle'} of link {x}"):
        if slides and abs(math.cos(0.5 * phi)) < 1e-9:      # s = ∞
            continue
        a, b, d = (v[:, 0] for v in coefficients(np.array([phi])))
        for psi in half_angle_roots(a, b, d):
            if oy.kind == "P" and abs(math.cos(0.5 * psi)) < 1e-9:
                continue
            states = {**known, x: place_x(np.array([phi])), y: place_y(np.array([psi]))}
            out.append(_rods(mech, g, states))
    return out


def _locked(mech, g: ComplexGroup, known: States, joints, place_x, place_y) -> list[dict[str, LinkState]]:
    """A class IV group whose rod slides on both x and y: a sliding pair keeps two links at one
    angle (their local frames are the sketch's), so x and y turn together, θ_y = θ_x. Pinned
    both, one angle t places both; one sliding, the other's angle is its guide's and t gives the
    slide (s = size·tan(t/2), the condition × cos²(t/2)). The other rod's condition is then a
    trigonometric polynomial of degree ≤ 2 in t: its roots are the assemblies. Both sliding, or
    both rods sliding on both pairs, leaves a continuum (or nothing): refused, or none."""
    (ox, oy), (x, y) = g.outer, (g.outer[0].a, g.outer[1].a)
    others = [(rod, px, py) for rod, px, py in joints if not px.kind == py.kind == "P"]
    if not others or (ox.kind == oy.kind == "P"):
        zero = np.zeros(1)
        if abs(math.remainder(float(place_x(zero).theta[0]) - float(place_y(zero).theta[0]), 2 * math.pi)) > 1e-12:
            return []           # two guides at different angles: the rod cannot slide on both
        raise SceneError(f"group {g.name} (form {g.form}): a rod slides on both its pairs and nothing else fixes "
                         "how far x and y slide or turn together: its assemblies are a continuum; leave "
                         "\"assemblies\" out of draw", key="plans.draw")
    rod, px, py = others[0]

    def states(t: np.ndarray) -> tuple[LinkState, LinkState, np.ndarray]:
        if ox.kind == oy.kind == "R":
            return place_x(t), place_y(t), np.ones(len(t))
        weight = np.cos(0.5 * t) ** 2
        if ox.kind == "P":
            sx = place_x(t)
            return sx, place_y(np.full(len(t), float(sx.theta[0]))), weight
        sy = place_y(t)
        return place_x(np.full(len(t), float(sy.theta[0]))), sy, weight

    def f(t):
        sx, sy, w = states(np.atleast_1d(np.asarray(t, dtype=float)))
        return _rod_condition(mech, rod, px, py, x, y, sx, sy) * w

    out = []
    for t in group_roots(g, f, f"angle of links {x} and {y}"):
        if (ox.kind == "P" or oy.kind == "P") and abs(math.cos(0.5 * t)) < 1e-9:      # s = ∞
            continue
        sx, sy, _ = states(np.array([t]))
        out.append(_rods(mech, g, {**known, x: sx, y: sy}))
    return out


def _placer(mech, known: States, outer: Pair):
    """The link of an outer pair placed by one parameter φ (n,): a pinned link turned by φ; a
    sliding one (at its outer link's angle) moved s = size·tan(φ/2) along the guide from where
    its anchor is on the outer link's anchor."""
    link, other, loc = outer.a, outer.b, mech.links[outer.a].local
    if outer.kind == "R":
        w, x0 = _world(mech, known, outer), loc[outer.point]

        def place(phi):
            c, s = np.cos(phi), np.sin(phi)
            return LinkState(phi, np.column_stack([w[0] - (c * x0[0] - s * x0[1]), w[1] - (s * x0[0] + c * x0[1])]))
        return place
    pr = outer.prismatic
    k = known[other]
    u = k.direction(pr.direction)[0]
    o0 = k.point(pr.anchor[other])[0] - k.direction(pr.anchor[link])[0]

    def place(phi):
        s = mech.size * np.tan(0.5 * phi)
        return LinkState(np.full(len(phi), float(k.theta[0])), o0 + s[:, None] * u)
    return place


def _rod_condition(mech, rod: str, px: Pair, py: Pair, x: str, y: str, sx: LinkState, sy: LinkState) -> np.ndarray:
    """The condition (n,) that ``rod`` puts between x and y at their states: |X − Y|² − l²
    (÷ size²) for two revolute pairs; (Y − Q)·R(θ)n − d (÷ size) for a sliding pair on one side."""
    size, lr = mech.size, mech.links[rod].local
    if px.kind == "R" and py.kind == "R":
        dx = sx.point(mech.links[x].local[px.point]) - sy.point(mech.links[y].local[py.point])
        l2 = float(la.norm(lr[px.point] - lr[py.point])) ** 2
        return (dx[:, 0] ** 2 + dx[:, 1] ** 2 - l2) / size ** 2
    (sl, ls, p), (pin, lp, q) = ((sx, x, px), (sy, y, py)) if px.kind == "P" else ((sy, y, py), (sx, x, px))
    pr = p.prismatic
    yw = pin.point(mech.links[lp].local[q.point])
    qw = sl.point(pr.anchor[ls])
    n = sl.direction(pr.normal)
    d = la.dot(lr[q.point] - pr.anchor[rod], pr.normal)
    return (la.dot(yw - qw, n) - d) / size


# --- completion ----------------------------------------------------------------------------

def _rods(mech, g: ComplexGroup, states: dict[str, LinkState]) -> dict[str, LinkState]:
    """``states`` with every link of ``g`` not yet in it placed from the links it joins: its angle
    from a sliding pair (the other link's) or from its two pins, its origin by least squares on
    its pair equations (linear in it: exact at an assembly)."""
    for name in g.links:
        if name in states:
            continue
        loc = mech.links[name].local
        mine = [p for p in g.pairs if name in (p.a, p.b)]
        slide = next((p for p in mine if p.kind == "P"), None)
        if slide is not None:
            theta = float(states[slide.other(name)].theta[0])
        else:
            (pa, pb) = mine[:2]
            wa, wb = (states[p.other(name)].point(mech.links[p.other(name)].local[p.point])[0] for p in (pa, pb))
            d, dl = wb - wa, loc[pb.point] - loc[pa.point]
            theta = math.atan2(d[1], d[0]) - math.atan2(dl[1], dl[0])
        cs, sn = math.cos(theta), math.sin(theta)
        rot = np.array([[cs, -sn], [sn, cs]])
        rows, rhs = [], []
        for p in mine:
            other = states[p.other(name)]
            if p.kind == "R":
                w = other.point(mech.links[p.other(name)].local[p.point])[0] - la.matmul(rot, loc[p.point])
                rows += [[1.0, 0.0], [0.0, 1.0]]
                rhs += [w[0], w[1]]
            else:
                pr = p.prismatic
                n = other.direction(pr.normal)[0]
                w = other.point(pr.anchor[p.other(name)])[0] - la.matmul(rot, pr.anchor[name])
                rows.append([n[0], n[1]])
                rhs.append(la.dot(w, n))
        m, v = np.array(rows), np.array(rhs)
        origin = la.solve(la.matmul(m.T, m), la.matmul(m.T, v))
        states[name] = _state(theta, origin)
    return states


def _state(theta: float, origin: np.ndarray) -> LinkState:
    return LinkState(np.array([theta]), np.asarray(origin, dtype=float).reshape(1, 2))


def _world(mech, known: States, pair: Pair) -> np.ndarray:
    """World position (2,) of an outer pin, from its known link."""
    return known[pair.b].point(mech.links[pair.b].local[pair.point])[0]

"""Closed-form solutions of the five forms of class II Assur groups.

Notation (after Artobolevsky): links m and n; outer pair D joins m to a known link k,
inner pair E joins m and n, outer pair F joins n to a known link p. R = revolute (a pin),
P = prismatic (a line common to both links, which therefore share ω and ε).

Positions: circle–circle (RRR), circle–line (RRP), line-at-a-distance (RPR) — two
assembly branches each — and line–line (PRP, RPP) — one solution.

Velocities and accelerations: the vector loop through E, differentiated once and twice,
is a plane vector equation ``rhs = x1·U1 + x2·U2`` in two scalar unknowns (ω, ε, or a
sliding speed σ and its rate σ̇). It is solved in closed form by Cramer's rule with the
cross product, x1 = (rhs × U2)/(U1 × U2), x2 = (U1 × rhs)/(U1 × U2); the velocity and
acceleration equations share U1, U2, so sin(U1, U2) measures how well the position is
conditioned, and sin = 0 is the form's singular position. A sliding speed σ is the
velocity of the group's link relative to the other link of its prismatic pair, along the
pair's line; its Coriolis term is 2·ω × σu.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Mapping

import numpy as np

from ..model import Mechanism
from ..scene import FRAME
from ..structure import Group, Joint
from .tolerances import PARALLEL_DET
from .state import J, LinkState, _pair, _rotated, cos_sin, cross
from .. import linalg as la

__all__ = ["Candidate", "candidates", "conditioning", "velocities", "accelerations", "SINGULAR_REASON"]


@dataclass(frozen=True)
class Candidate:
    """One assembly branch of a group at every position: poses of m and n, where it is real
    (``valid``), and ``why(i)``, the reason it is not at position i."""

    m: LinkState
    n: LinkState
    valid: np.ndarray
    why: Callable[[int], str]


SINGULAR_REASON = {
    "RRR": "links {m} and {n} are collinear (dead centre): the velocity equations have no unique solution",
    "RRP": "link {m} is perpendicular to the guide of link {n}: the velocity equations have no unique solution",
    "RPR": "the guide of links {m}/{n} is perpendicular to the line of their pivots: no unique solution",
    "PRP": "the two guides are parallel: the position of the pin between links {m} and {n} is undetermined",
    "RPP": "the two guides are parallel: link {n}'s position along them is undetermined",
}

States = Mapping[str, LinkState]


def _local(mech: Mechanism, link: str, point: str) -> np.ndarray:
    return mech.links[link].local[point]


def _pin(mech: Mechanism, states: States, joint: Joint) -> np.ndarray:
    """World position of an outer revolute pair, from the known link."""
    return states[joint.other].point(_local(mech, joint.other, joint.point))


def _place(la: np.ndarray, lb: np.ndarray, a: np.ndarray, b: np.ndarray) -> LinkState:
    """The pose putting local points la, lb at world points a, b (|ab| = |la lb|); cos θ and
    sin θ follow from the unit vectors of ab and of la lb, without trigonometry."""
    d = b - a
    dx, dy = d[:, 0], d[:, 1]
    ex, ey = float(lb[0] - la[0]), float(lb[1] - la[1])
    theta = np.arctan2(dy, dx)
    theta -= np.arctan2(ey, ex)
    el = float(np.hypot(ex, ey))
    ex, ey = ex / el, ey / el
    r = np.sqrt(dx * dx + dy * dy)
    r = 1.0 / np.where(r > 0.0, r, 1.0)
    c = (dx * ex + dy * ey) * r
    sn = (dy * ex - dx * ey) * r
    return LinkState(theta, _rotated(la, c, sn, base=a, sign=-1.0)).seeded(c, sn)


def _fixed_angle(theta: np.ndarray, local: np.ndarray, x: np.ndarray, cs: tuple | None = None) -> LinkState:
    """The pose with rotation θ putting local point ``local`` at world point x (``cs``: cos θ,
    sin θ when known)."""
    c, sn = cos_sin(theta) if cs is None else cs
    return LinkState(theta, _rotated(local, c, sn, base=x, sign=-1.0)).seeded(c, sn)


def _scaled(k: np.ndarray, u: np.ndarray, base: np.ndarray | None = None, sign: float = 1.0) -> np.ndarray:
    """base + sign·k·u for scalars k (N,) and vectors u (N, 2), in columns."""
    out = _pair(len(u))
    for i in (0, 1):
        if base is None:
            np.multiply(k, u[:, i], out=out[:, i])
        elif sign < 0.0:
            np.subtract(base[:, i], k * u[:, i], out=out[:, i])
        else:
            np.add(base[:, i], k * u[:, i], out=out[:, i])
    return out


def _line(mech_state: LinkState, anchor: np.ndarray, direction: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return mech_state.point(anchor), mech_state.direction(direction)


def _intersect(p1: np.ndarray, u1: np.ndarray, p2: np.ndarray, u2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Intersection of lines p1 + t·u1 and p2 + s·u2; second value: u1 × u2. Where
    |u1 × u2| ≤ PARALLEL_DET the lines are parallel: the point there is a finite placeholder
    (the caller marks it invalid), never the overflow of dividing by a subnormal cross product."""
    det = cross(u1, u2)
    safe = np.where(np.abs(det) > PARALLEL_DET, det, 1.0)
    t = cross(p2 - p1, u2) / safe
    return p1 + t[..., None] * u1, det


# --- positions -----------------------------------------------------------------------------

def candidates(group: Group, mech: Mechanism, states: States, tol: float, branch: int | None = None
               ) -> list[Candidate]:
    """Every assembly branch of ``group``, given the states of the links it is attached to.
    ``tol`` is the length tolerance (m) for assembly at a limit position. With ``branch``,
    only that branch (its index in the full list) is solved, and the list holds it alone."""
    return _POSITIONS[group.form](group, mech, states, tol, branch)


def _signs(branch: int | None) -> tuple[float, ...]:
    """The signs of a two-branch form's solutions: both, or the one of ``branch``."""
    return (1.0, -1.0) if branch is None else ((1.0, -1.0)[branch],)


def _rrr(g: Group, mech: Mechanism, states: States, tol: float, branch: int | None = None
         ) -> list[Candidate]:
    D, F = _pin(mech, states, g.d), _pin(mech, states, g.f)
    Lm = mech.links[g.m].local
    Ln = mech.links[g.n].local
    lm = float(la.norm(Lm[g.e.point] - Lm[g.d.point]))
    ln = float(la.norm(Ln[g.e.point] - Ln[g.f.point]))
    d = F - D
    L2 = d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1]
    L = np.sqrt(L2)
    Ls = np.where(L == 0.0, 1.0, L)
    x = (lm * lm - ln * ln + L2) / (2.0 * Ls)
    h2 = lm * lm - x * x
    valid = (L > 0.0) & (h2 >= -2.0 * tol * (lm + ln))
    h = np.sqrt(np.clip(h2, 0.0, None))
    ex = _scaled(1.0 / Ls, d)

    def why(i: int) -> str:
        low = abs(lm - ln) if abs(lm - ln) > 1e-12 * (lm + ln) else 0.0     # equal links: 0, not rounding noise
        return (f"|{g.d.point}{g.f.point}| = {L[i]:.6g} m, but links {g.m} ({lm:.6g} m) and {g.n} ({ln:.6g} m) "
                f"join only between {low:.6g} and {lm + ln:.6g} m")

    out = []
    for sign in _signs(branch):
        E = _scaled(x, ex, D) + _scaled(sign * h, J(ex))
        out.append(Candidate(_place(Lm[g.d.point], Lm[g.e.point], D, E),
                             _place(Ln[g.f.point], Ln[g.e.point], F, E), valid, why))
    return out


def _rrp(g: Group, mech: Mechanism, states: States, tol: float, branch: int | None = None
         ) -> list[Candidate]:
    D = _pin(mech, states, g.d)
    pr, p = g.f.prismatic, g.f.other
    Lm, Ln = mech.links[g.m].local, mech.links[g.n].local
    lm = float(la.norm(Lm[g.e.point] - Lm[g.d.point]))
    theta = states[p].theta
    Q, u = _line(states[p], pr.anchor[p], pr.direction)
    h = float(la.dot(Ln[g.e.point] - pr.anchor[g.n], pr.normal))   # E's offset from the line, fixed in n
    Qh = Q + h * J(u) if h != 0.0 else Q
    w = Qh - D
    wx, wy, ux, uy = w[:, 0], w[:, 1], u[:, 0], u[:, 1]
    b = wx * ux + wy * uy
    disc = b * b - (wx * wx + wy * wy - lm * lm)
    valid = disc >= -2.0 * tol * lm
    root = np.sqrt(np.clip(disc, 0.0, None))

    def why(i: int) -> str:
        dist = abs(float(cross(u[i], w[i])))
        return (f"link {g.m} ({g.d.point}{g.e.point} = {lm:.6g} m) cannot reach the line of pin {g.e.point} "
                f"({dist:.6g} m away from {g.d.point})")

    out = []
    for sign in _signs(branch):
        E = _scaled(sign * root - b, u, Qh)
        out.append(Candidate(_place(Lm[g.d.point], Lm[g.e.point], D, E),
                             _fixed_angle(theta, Ln[g.e.point], E, states[p]._cos_sin), valid, why))
    return out


def _rpr(g: Group, mech: Mechanism, states: States, tol: float, branch: int | None = None
         ) -> list[Candidate]:
    D, F = _pin(mech, states, g.d), _pin(mech, states, g.f)
    pr = g.e.prismatic
    Lm, Ln = mech.links[g.m].local, mech.links[g.n].local
    h = float(la.dot(Lm[g.d.point] - pr.anchor[g.m], pr.normal) - la.dot(Ln[g.f.point] - pr.anchor[g.n], pr.normal))
    d = D - F
    L = np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1])
    beta = np.arctan2(d[:, 1], d[:, 0])
    gamma = float(np.arctan2(pr.normal[1], pr.normal[0]))
    valid = (L > 0.0) & (np.abs(h) <= L + tol)
    c = np.arccos(np.clip(h / np.where(L == 0.0, 1.0, L), -1.0, 1.0))

    def why(i: int) -> str:
        return (f"pivots {g.d.point} and {g.f.point} are {L[i]:.6g} m apart, less than the guide's offset "
                f"{abs(h):.6g} m")

    out = []
    for sign in _signs(branch):
        theta = beta - gamma - sign * c
        out.append(Candidate(_fixed_angle(theta, Lm[g.d.point], D), _fixed_angle(theta, Ln[g.f.point], F), valid, why))
    return out


def _prp(g: Group, mech: Mechanism, states: States, tol: float, branch: int | None = None
         ) -> list[Candidate]:
    k, p = g.d.other, g.f.other
    E = g.e.point
    Lm, Ln = mech.links[g.m].local, mech.links[g.n].local
    lines = []
    for joint, link, L in ((g.d, g.m, Lm), (g.f, g.n, Ln)):
        pr = joint.prismatic
        Q, u = _line(states[joint.other], pr.anchor[joint.other], pr.direction)
        h = float(la.dot(L[E] - pr.anchor[link], pr.normal))
        lines.append((Q + h * J(u), u))
    Ew, det = _intersect(*lines[0], *lines[1])
    valid = np.abs(det) > PARALLEL_DET

    def why(i: int) -> str:
        return f"the guides of links {g.m} and {g.n} are parallel, so pin {E} has no position"

    return [Candidate(_fixed_angle(states[k].theta, Lm[E], Ew, states[k]._cos_sin),
                      _fixed_angle(states[p].theta, Ln[E], Ew, states[p]._cos_sin), valid, why)]


def _rpp(g: Group, mech: Mechanism, states: States, tol: float, branch: int | None = None
         ) -> list[Candidate]:
    D = _pin(mech, states, g.d)
    pe, pf, p = g.e.prismatic, g.f.prismatic, g.f.other
    Lm = mech.links[g.m].local
    theta = states[p].theta
    m_state = _fixed_angle(theta, Lm[g.d.point], D, states[p]._cos_sin)
    Q, det = _intersect(*_line(m_state, pe.anchor[g.m], pe.direction), *_line(states[p], pf.anchor[p], pf.direction))
    Q_local, _ = _intersect(pe.anchor[g.n][None], pe.direction[None], pf.anchor[g.n][None], pf.direction[None])
    valid = np.abs(det) > PARALLEL_DET

    def why(i: int) -> str:
        return f"the two guides of link {g.n} are parallel, so its position along them is undetermined"

    return [Candidate(m_state, _fixed_angle(theta, Q_local[0], Q, states[p]._cos_sin), valid, why)]


_POSITIONS = {"RRR": _rrr, "RRP": _rrp, "RPR": _rpr, "PRP": _prp, "RPP": _rpp}


# --- velocities and accelerations ----------------------------------------------------------

def _cramer(U1: np.ndarray, U2: np.ndarray, rhs: np.ndarray, det: np.ndarray | None = None
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """Solve rhs = x1·U1 + x2·U2; also return sin of the angle between U1 and U2 (None when
    ``det``, U1 × U2, is given: the sin is known already)."""
    if det is not None:
        safe = det if det.all() else np.where(det == 0.0, 1.0, det)
        return cross(rhs, U2) / safe, cross(U1, rhs) / safe, None
    det = cross(U1, U2)
    scale = np.sqrt((U1[:, 0] * U1[:, 0] + U1[:, 1] * U1[:, 1]) * (U2[:, 0] * U2[:, 0] + U2[:, 1] * U2[:, 1]))
    # np.where only where a zero needs it (it costs several products)
    sin = det / scale if scale.all() else np.where(scale > 0.0, det / np.where(scale > 0.0, scale, 1.0), 0.0)
    safe = det if det.all() else np.where(det == 0.0, 1.0, det)
    return cross(rhs, U2) / safe, cross(U1, rhs) / safe, sin


def _sin(U1: np.ndarray, U2: np.ndarray) -> np.ndarray:
    """sin of the angle between U1 and U2 (0 where either is zero), as :func:`_cramer` gives it."""
    det = cross(U1, U2)
    scale = np.sqrt((U1[:, 0] * U1[:, 0] + U1[:, 1] * U1[:, 1]) * (U2[:, 0] * U2[:, 0] + U2[:, 1] * U2[:, 1]))
    return det / scale if scale.all() else np.where(scale > 0.0, det / np.where(scale > 0.0, scale, 1.0), 0.0)


def _cramer_known(sin: np.ndarray):
    """:func:`_cramer` returning the ``sin`` already known instead of computing it again."""
    def solve(U1: np.ndarray, U2: np.ndarray, rhs: np.ndarray):
        x1, x2, _ = _cramer(U1, U2, rhs, cross(U1, U2))
        return x1, x2, sin
    return solve


def _geometry(g: Group, mech: Mechanism, states: States) -> dict[str, np.ndarray]:
    """World positions of the group's pair points and guide directions."""
    geo: dict[str, np.ndarray] = {}
    m, n = states[g.m], states[g.n]
    Lm, Ln = mech.links[g.m].local, mech.links[g.n].local
    if g.d.kind == "R":
        geo["D"] = m.point(Lm[g.d.point])
    if g.f.kind == "R":
        geo["F"] = n.point(Ln[g.f.point])
    if g.e.kind == "R":
        geo["E"] = m.point(Lm[g.e.point])
    for key, joint, state in (("ud", g.d, m), ("ue", g.e, m), ("uf", g.f, n)):
        if joint.kind == "P":
            geo[key] = state.direction(joint.prismatic.direction)
    return geo


def _directions(g: Group, geo: dict[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """U1, U2: the directions of the two unknowns in the group's velocity equation."""
    form = g.form
    if form == "RRR":
        return -J(geo["E"] - geo["D"]), J(geo["E"] - geo["F"])
    if form == "RRP":
        return -J(geo["E"] - geo["D"]), geo["uf"]
    if form == "RPR":
        return J(geo["D"] - geo["F"]), geo["ue"]
    if form == "PRP":
        return -geo["ud"], geo["uf"]
    return geo["ue"], geo["uf"]


def conditioning(g: Group, mech: Mechanism, states: States, keep: dict | None = None) -> np.ndarray:
    """sin of the angle between U1 and U2 (positions only): 0 at the form's singular position.
    ``keep``, when given, receives the geometry, U1, U2 and sin (for :func:`velocities` at
    the same poses: see ``pre`` there)."""
    geo = _geometry(g, mech, states)
    U1, U2 = _directions(g, geo)
    sin = _sin(U1, U2)
    if keep is not None:
        keep.update(geo=geo, U1=U1, U2=U2, sin=sin)
    return sin


def _velocity(name: str, state: LinkState, x: np.ndarray) -> np.ndarray | None:
    """v of link ``name``'s point at ``x``; None (zero) on the frame."""
    return None if name == FRAME else state.velocity(x)


def _acceleration(name: str, state: LinkState, x: np.ndarray) -> np.ndarray | None:
    """a of link ``name``'s point at ``x``; None (zero) on the frame."""
    return None if name == FRAME else state.acceleration(x)


def _difference(a: np.ndarray | None, b: np.ndarray | None, n: int) -> np.ndarray:
    """a − b, None being zero."""
    if b is None:
        return np.zeros((n, 2)) if a is None else a
    return -b if a is None else a - b


def velocities(g: Group, mech: Mechanism, states: dict[str, LinkState], pre: dict | None = None
               ) -> tuple[dict, np.ndarray]:
    """Set ω and v of the group's links in ``states``; return the sliding speeds σ and sin.
    ``pre``: what :func:`conditioning` kept at these very poses (it is not computed again)."""
    if pre is None:
        geo = _geometry(g, mech, states)
        U1, U2 = _directions(g, geo)
        solve = _cramer
    else:
        geo, U1, U2 = pre["geo"], pre["U1"], pre["U2"]
        solve = _cramer_known(pre["sin"])
    k, p = states[g.d.other], states[g.f.other]
    m, n = states[g.m], states[g.n]
    form = g.form
    if form == "RRR":
        D, E, F = geo["D"], geo["E"], geo["F"]
        vD, vF = _velocity(g.d.other, k, D), _velocity(g.f.other, p, F)
        wm, wn, sin = solve(U1, U2, _difference(vD, vF, len(D)))
        states[g.m] = m.with_velocity(wm, D, vD, own=True)
        states[g.n] = n.with_velocity(wn, F, vF, own=True)
        return {"_geo": (geo, U1, U2)}, sin
    if form == "RRP":
        D, E, u = geo["D"], geo["E"], geo["uf"]
        vD, vEp = _velocity(g.d.other, k, D), _velocity(g.f.other, p, E)
        wm, s, sin = solve(U1, U2, _difference(vD, vEp, len(D)))
        states[g.m] = m.with_velocity(wm, D, vD, own=True)
        states[g.n] = n.with_velocity(p.omega, E, _scaled(s, u, vEp))
        return {"f": s, "_geo": (geo, U1, U2)}, sin
    if form == "RPR":
        D, F, u = geo["D"], geo["F"], geo["ue"]
        w, s, sin = solve(U1, U2, k.velocity(D) - p.velocity(F))
        states[g.m] = m.with_velocity(w, D, k.velocity(D))
        states[g.n] = n.with_velocity(w, F, p.velocity(F))
        return {"e": s}, sin
    if form == "PRP":
        E, u1, u2 = geo["E"], geo["ud"], geo["uf"]
        vEk, vEp = k.velocity(E), p.velocity(E)
        s1, s2, sin = solve(U1, U2, vEk - vEp)
        states[g.m] = m.with_velocity(k.omega, E, _scaled(s1, u1, vEk))
        states[g.n] = n.with_velocity(p.omega, E, _scaled(s2, u2, vEp))
        return {"d": s1, "f": s2}, sin
    # RPP
    D, uf = geo["D"], geo["uf"]
    vDp = p.velocity(D)
    se, sf, sin = solve(U1, U2, k.velocity(D) - vDp)
    states[g.m] = m.with_velocity(p.omega, D, k.velocity(D))
    states[g.n] = n.with_velocity(p.omega, D, _scaled(sf, uf, vDp))
    return {"e": se, "f": sf}, sin


def accelerations(g: Group, mech: Mechanism, states: dict[str, LinkState], sliding: dict) -> None:
    """Set ε and a of the group's links in ``states`` (velocities must be set)."""
    geo, U1, U2 = sliding["_geo"] if "_geo" in sliding else (None, None, None)
    if geo is None:
        geo = _geometry(g, mech, states)
        U1, U2 = _directions(g, geo)
    k, p = states[g.d.other], states[g.f.other]
    m, n = states[g.m], states[g.n]
    form = g.form

    def sq(w: np.ndarray) -> np.ndarray:
        return w * w

    def cor(w: np.ndarray, s: np.ndarray, u: np.ndarray) -> np.ndarray:
        """Coriolis acceleration 2·ω × (σ u)."""
        return _scaled(2.0 * (w * s), J(u))

    if form == "RRR":
        D, E, F = geo["D"], geo["E"], geo["F"]
        aD, aF = _acceleration(g.d.other, k, D), _acceleration(g.f.other, p, F)
        rhs = _scaled(sq(n.omega), E - F, _scaled(sq(m.omega), E - D, _difference(aD, aF, len(D)), -1.0))
        em, en, _ = _cramer(U1, U2, rhs, cross(U1, U2))
        states[g.m] = m.with_acceleration(em, D, aD, own=True)
        states[g.n] = n.with_acceleration(en, F, aF, own=True)
    elif form == "RRP":
        D, E, u = geo["D"], geo["E"], geo["uf"]
        s = sliding["f"]
        if g.f.other == FRAME:      # a fixed guide: no acceleration of its points, no Coriolis term
            aD = _acceleration(g.d.other, k, D)
            rhs = _scaled(sq(m.omega), E - D, _difference(aD, None, len(D)), -1.0)
            em, ds, _ = _cramer(U1, U2, rhs, cross(U1, U2))
            states[g.m] = m.with_acceleration(em, D, aD, own=True)
            states[g.n] = n.with_acceleration(p.epsilon, E, _scaled(ds, u))
            return
        aD, aEp = k.acceleration(D), p.acceleration(E)
        rhs = _scaled(sq(m.omega), E - D, aD - aEp, -1.0) - cor(p.omega, s, u)
        em, ds, _ = _cramer(U1, U2, rhs, cross(U1, U2))
        states[g.m] = m.with_acceleration(em, D, aD, own=True)
        states[g.n] = n.with_acceleration(p.epsilon, E, _scaled(ds, u, aEp) + cor(p.omega, s, u))
    elif form == "RPR":
        D, F, u = geo["D"], geo["F"], geo["ue"]
        s, w = sliding["e"], m.omega
        aD, aF = k.acceleration(D), p.acceleration(F)
        rhs = _scaled(sq(w), D - F, aD - aF) - cor(w, s, u)
        e, _, _ = _cramer(U1, U2, rhs)
        states[g.m] = m.with_acceleration(e, D, aD)
        states[g.n] = n.with_acceleration(e, F, aF)
    elif form == "PRP":
        E, u1, u2 = geo["E"], geo["ud"], geo["uf"]
        s1, s2 = sliding["d"], sliding["f"]
        aEk = k.acceleration(E) + cor(k.omega, s1, u1)
        aEp = p.acceleration(E) + cor(p.omega, s2, u2)
        ds1, ds2, _ = _cramer(U1, U2, aEk - aEp)
        states[g.m] = m.with_acceleration(k.epsilon, E, _scaled(ds1, u1, aEk))
        states[g.n] = n.with_acceleration(p.epsilon, E, _scaled(ds2, u2, aEp))
    else:  # RPP
        D, ue, uf = geo["D"], geo["ue"], geo["uf"]
        se, sf, w = sliding["e"], sliding["f"], p.omega
        aD = k.acceleration(D)
        aDp = p.acceleration(D)
        rhs = aD - aDp - cor(w, se, ue) - cor(w, sf, uf)
        dse, dsf, _ = _cramer(U1, U2, rhs)
        states[g.m] = m.with_acceleration(p.epsilon, D, aD)
        states[g.n] = n.with_acceleration(p.epsilon, D, _scaled(dsf, uf, aDp) + cor(w, sf, uf))

"""Class III groups through Assur's special points: the graphic-analytical solution.

A class III (order III) group is a base link b with three rods; each rod i joins b to a
known link k_i. The rod's *axis* is the line along which it transmits the base link's
velocity component:

* rod R–R (outer pin A, inner pin B): the line AB;
* rod P–R (slides on a guide of k_i, pinned to b at B): through B, normal to the guide;
* rod R–P (pinned to k_i at A, slides along a line of b): through A, normal to that line.

The special point S_ij is the intersection of axes i and j, taken as a point of b. Its
velocity differs from that of k_i's point at S_ij only along e_i ⊥ axis i (and likewise for
j), so it follows from two known directions (Cramer's rule):

    v_S = v_S(k_i) + x_i·e_i = v_S(k_j) + x_j·e_j

Two special points fix the base link (ω_b, and every point's velocity), then each rod.
Accelerations follow in the same way, the normal and Coriolis terms being known from the
velocities:

    a_S = a_K(k_i) + c_i + y_i·e_i,   c_i = −ω_r²·(B − A) − ω_b²·(S − B)          (R–R)
                                      c_i = 2ω_k·k×(v_B − v_B(k)) − ω_b²·(S − B)   (P–R)
                                      c_i = −2ω_b·k×(v_A − v_A(b)) − ω_b²·(S − A)  (R–P)

This solution shares no equations with :mod:`plans.kinematics.generic` (the Jacobian
solve); the two are cross-checked in the tests. The three axes meeting in one point is the
group's singular position (every special point coincides; the construction lines through
the known images are parallel).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Mapping

import numpy as np

from ..model import Mechanism
from ..structure import ComplexGroup, Rod
from .state import J, LinkState, cross
from .tolerances import CROSS_CHECK_RTOL
from .. import linalg as la

__all__ = ["Axis", "SpecialPoint", "TriadSolution", "GroupPoints", "axes", "special_points", "solve_triad", "condition",
           "supports", "triad_groups", "triads", "disagreement", "disagreements", "group_points", "CROSS_CHECK_RTOL",
           "pick", "known_acceleration"]



States = Mapping[str, LinkState]


@dataclass(frozen=True)
class Axis:
    """A rod's axis at N positions: ``point`` X (N, 2) where the rod meets its known link
    ``known`` (whose point there has a known velocity), unit ``direction`` d, and the inner
    pin's world position ``pin`` (B for pinned rods, A's base point for R–P rods)."""

    rod: Rod
    known: str
    point: np.ndarray
    direction: np.ndarray
    pin: np.ndarray

    @property
    def normal(self) -> np.ndarray:
        """e = k × d: the direction of the special point's unknown velocity term."""
        return J(self.direction)


@dataclass(frozen=True)
class SpecialPoint:
    """S_ij, the meeting point of axes i and j, as a point of the base link: position (m),
    sin of the angle between the axes, and (when solved) velocity and acceleration."""

    name: str
    rods: tuple[int, int]
    position: np.ndarray
    sin: np.ndarray
    v: np.ndarray | None = None
    a: np.ndarray | None = None


@dataclass(frozen=True)
class TriadSolution:
    """The group's link states and its special points, solved through the special points."""

    links: dict[str, LinkState]
    points: tuple[SpecialPoint, ...]


@dataclass(frozen=True)
class GroupPoints:
    """A class III group's rod axes and special points at every position, read off the solved
    motion (its Jacobian solution, not :func:`solve_triad`'s): each point's ``v`` (m/s) and
    ``a`` (m/s²) are those of S as a point of the base link (None below the motion's order);
    ``known[(k, r)]`` (N, 2) m/s² is a_K(k_r) + c_r, the known part of special point k's
    acceleration along its rod r (:func:`known_acceleration`; only at order 2)."""

    group: ComplexGroup
    axes: tuple[Axis, ...]
    points: tuple[SpecialPoint, ...]
    known: Mapping[tuple[int, int], np.ndarray]


def supports(g: ComplexGroup) -> bool:
    """True for class III groups whose rods all have a defined axis (no P–P rod)."""
    return g.base is not None and all(r.form != "PP" for r in g.rods)


def triad_groups(structure) -> tuple[ComplexGroup, ...]:
    """The groups of ``structure`` that have special points (see :func:`supports`), in order;
    callers ask this instead of which class a group is."""
    return tuple(g for g in structure.groups if isinstance(g, ComplexGroup) and supports(g))


def triads(motion) -> dict[ComplexGroup, TriadSolution]:
    """Every class III group of a solved motion solved a second, independent way, through its
    special points (only the special points when the motion has positions only)."""
    out = {}
    for g in triad_groups(motion.structure):
        out[g] = solve_triad(g, motion.mechanism, motion.links, order=motion.order) if motion.order >= 1 \
            else TriadSolution({}, special_points(g, motion.mechanism, motion.links))
    return out


def group_points(motion) -> dict[str, GroupPoints]:
    """Every class III group's axes and special points (group name → :class:`GroupPoints`),
    with the velocities and accelerations of the motion at them (see :class:`GroupPoints`)."""
    mech, links, out = motion.mechanism, motion.links, {}
    for g in triad_groups(motion.structure):
        ax = axes(g, mech, links)
        base = links[g.base]
        points, known = [], {}
        with np.errstate(over="ignore", invalid="ignore"):    # S far away where two axes are near parallel
            for k, p in enumerate(_special_points(ax)):
                v = base.velocity(p.position) if motion.order >= 1 else None
                a = base.acceleration(p.position) if motion.order >= 2 else None
                points.append(replace(p, v=v, a=a))
                if motion.order >= 2:
                    for r in p.rods:
                        known[(k, r)] = known_acceleration(ax[r], g, mech, links, links, p.position)
        out[g.name] = GroupPoints(g, ax, tuple(points), known)
    return out


def disagreements(motion) -> dict[str, float]:
    """Per class III group (name → value), the :func:`disagreement` of its special-point
    solution (:func:`triads`) with the motion's; empty below order 1."""
    if motion.order < 1:
        return {}
    return {name: disagreement(motion, t) for name, t in motion.triads.items()}


def disagreement(motion, triad: TriadSolution) -> float:
    """Largest difference between the special-point solution ``triad`` and the Jacobian
    solution in ``motion`` of a group's links (ω·size and v of every point; ε·size and a),
    relative to the speed (acceleration) of the mechanism's fastest point at that position
    (:meth:`~plans.kinematics.state.Solution.rate_scale`): a link at rest up to rounding (a
    stationary instant) is compared with the mechanism's motion, not with its own noise."""
    worst = 0.0
    mech = motion.mechanism
    scales = [motion.rate_scale(k) for k in range(1, motion.order + 1)]
    scales = [np.where(sc > 0.0, sc, 1.0)[:, None] for sc in scales]
    for link, s in triad.links.items():
        ref = motion.links[link]
        pts = [ref.point(x) for x in mech.links[link].local.values()]
        kinds = [[(ref.omega[:, None] * mech.size, s.omega[:, None] * mech.size)]
                 + [(ref.velocity(x), s.velocity(x)) for x in pts]]
        if motion.order >= 2:
            kinds.append([(ref.epsilon[:, None] * mech.size, s.epsilon[:, None] * mech.size)]
                         + [(ref.acceleration(x), s.acceleration(x)) for x in pts])
        for pairs, scale in zip(kinds, scales):
            worst = max(worst, max(float(np.max(np.abs(a - b) / scale)) for a, b in pairs))
    return worst


def _unit(v: np.ndarray) -> np.ndarray:
    return v / la.norm(v, axis=-1, keepdims=True)


def axes(g: ComplexGroup, mech: Mechanism, states: States) -> tuple[Axis, ...]:
    """The three rods' axes."""
    out = []
    for rod in g.rods:
        known = rod.outer.b
        if rod.form == "RR":
            a = states[known].point(mech.links[known].local[rod.outer.point])
            b = states[g.base].point(mech.links[g.base].local[rod.inner.point])
            out.append(Axis(rod, known, a, _unit(b - a), b))
        elif rod.form == "PR":
            pr = rod.outer.prismatic
            b = states[g.base].point(mech.links[g.base].local[rod.inner.point])
            out.append(Axis(rod, known, b, J(states[known].direction(pr.direction)), b))
        else:  # RP: pinned to the known link at A, sliding along a line of the base link
            pr = rod.inner.prismatic
            a = states[known].point(mech.links[known].local[rod.outer.point])
            out.append(Axis(rod, known, a, J(states[pr.guide].direction(pr.direction)), a))
    return tuple(out)


def condition(g: ComplexGroup, mech: Mechanism, states: States) -> np.ndarray:
    """The group's condition figure: det of the axes' normalised line coordinates
    (d, (X − c) × d / size) over the product of the rows' norms — ±1 for well-spread axes,
    0 when they meet in one point (c: the base link's first pin). Its sign changes across a
    singular position."""
    ax = axes(g, mech, states)
    c = ax[0].pin
    size = mech.size
    rows = np.stack([np.column_stack([x.direction, cross(x.point - c, x.direction) / size]) for x in ax], axis=1)
    return la.det(rows) / np.prod(la.norm(rows, axis=2), axis=1)


def special_points(g: ComplexGroup, mech: Mechanism, states: States) -> tuple[SpecialPoint, ...]:
    """S1 = axes 1∩2, S2 = axes 1∩3, S3 = axes 2∩3 (positions only; parallel axes give a
    point far away and sin = 0 — such a point is never used)."""
    return _special_points(axes(g, mech, states))


def _special_points(ax: tuple[Axis, ...]) -> tuple[SpecialPoint, ...]:
    """The special points where the axes ``ax`` meet (see :func:`special_points`)."""
    out = []
    for k, (i, j) in enumerate(((0, 1), (0, 2), (1, 2))):
        x, s = _meet(ax[i].point, ax[i].direction, ax[j].point, ax[j].direction)
        out.append(SpecialPoint(f"S{k + 1}", (i, j), x, s))
    return tuple(out)


def _meet(p1, u1, p2, u2) -> tuple[np.ndarray, np.ndarray]:
    det = cross(u1, u2)
    t = cross(p2 - p1, u2) / np.where(det == 0.0, 1.0, det)
    return p1 + t[:, None] * u1, det


def pick(points: tuple[SpecialPoint, ...]) -> np.ndarray:
    """Per position, the index (0–2) of the special point left out: the one whose axes are
    nearest parallel."""
    return np.argmin(np.stack([np.abs(p.sin) for p in points], axis=1), axis=1)


def _two_directions(base_i: np.ndarray, e_i: np.ndarray, base_j: np.ndarray, e_j: np.ndarray) -> np.ndarray:
    """The vector w = base_i + x·e_i = base_j + y·e_j (two known directions)."""
    x = cross(base_j - base_i, e_j) / cross(e_i, e_j)
    return base_i + x[:, None] * e_i


def solve_triad(g: ComplexGroup, mech: Mechanism, states: States, order: int = 2) -> TriadSolution:
    """Velocities (order 1) and accelerations (order 2) of the group's links through the
    special points. ``states`` must hold the group's poses and the known links' motion."""
    ax = axes(g, mech, states)
    pts = special_points(g, mech, states)
    skip = pick(pts)
    n = len(skip)
    base = states[g.base]

    def known_v(i: int, x: np.ndarray) -> np.ndarray:
        return states[ax[i].known].velocity(x)

    # velocities of the special points
    sv = [_two_directions(known_v(i, p.position), ax[i].normal, known_v(j, p.position), ax[j].normal)
          for p, (i, j) in ((p, p.rods) for p in pts)]
    first = np.where(skip == 0, 1, 0)
    second = np.where(skip == 2, 1, 2)
    pos = np.stack([p.position for p in pts])          # (3, N, 2)
    vel = np.stack(sv)
    idx = np.arange(n)
    p1, p2 = pos[first, idx], pos[second, idx]
    v1, v2 = vel[first, idx], vel[second, idx]
    d = p2 - p1
    omega_b = cross(d, v2 - v1) / np.einsum("ij,ij->i", d, d)
    b_state = base.with_velocity(omega_b, p1, v1)
    links = {g.base: b_state}
    for ax_i in ax:
        links[ax_i.rod.link] = _rod_velocity(ax_i, g, mech, states, b_state)
    points = [SpecialPoint(p.name, p.rods, p.position, p.sin, v=vv) for p, vv in zip(pts, sv)]
    if order < 2:
        return TriadSolution(links, tuple(points))
    # accelerations of the special points
    w_b = omega_b
    sa = []
    for p in pts:
        i, j = p.rods
        terms = [known_acceleration(ax[r], g, mech, states, links, p.position) for r in (i, j)]
        sa.append(_two_directions(terms[0], ax[i].normal, terms[1], ax[j].normal))
    acc = np.stack(sa)
    a1, a2 = acc[first, idx], acc[second, idx]
    # a2 − a1 = ε k×d − ω² d
    eps_b = cross(d, a2 - a1 + (w_b ** 2)[:, None] * d) / np.einsum("ij,ij->i", d, d)
    b_state = links[g.base].with_acceleration(eps_b, p1, a1)
    links[g.base] = b_state
    for ax_i in ax:
        links[ax_i.rod.link] = _rod_acceleration(ax_i, g, mech, states, links)
    points = [SpecialPoint(p.name, p.rods, p.position, p.sin, v=p.v, a=aa) for p, aa in zip(points, sa)]
    return TriadSolution(links, tuple(points))


def _rod_velocity(ax: Axis, g: ComplexGroup, mech: Mechanism, states: States, b: LinkState) -> LinkState:
    rod, k = ax.rod, states[ax.known]
    r = states[rod.link]
    if rod.form == "RR":
        a, pin = ax.point, ax.pin
        va, vb = k.velocity(a), b.velocity(pin)
        d = pin - a
        w = cross(d, vb - va) / np.einsum("ij,ij->i", d, d)
        return r.with_velocity(w, a, va)
    if rod.form == "PR":                      # turns with the guide link, pinned to b at B
        return r.with_velocity(k.omega, ax.pin, b.velocity(ax.pin))
    return r.with_velocity(b.omega, ax.point, k.velocity(ax.point))   # RP: turns with b, pinned at A


def known_acceleration(ax: Axis, g: ComplexGroup, mech: Mechanism, states: States,
                        links: Mapping[str, LinkState], s: np.ndarray) -> np.ndarray:
    """a_K(k_i) + c_i: the known part of the special point's acceleration along rod i."""
    rod, k, b = ax.rod, states[ax.known], links[g.base]
    w_b2 = (b.omega ** 2)[:, None]
    if rod.form == "RR":
        w_r2 = (links[rod.link].omega ** 2)[:, None]
        return k.acceleration(ax.point) - w_r2 * (ax.pin - ax.point) - w_b2 * (s - ax.pin)
    if rod.form == "PR":
        v_rel = b.velocity(ax.pin) - k.velocity(ax.pin)
        return k.acceleration(ax.pin) + 2.0 * k.omega[:, None] * J(v_rel) - w_b2 * (s - ax.pin)
    v_rel = k.velocity(ax.point) - b.velocity(ax.point)
    return k.acceleration(ax.point) - 2.0 * b.omega[:, None] * J(v_rel) - w_b2 * (s - ax.point)


def _rod_acceleration(ax: Axis, g: ComplexGroup, mech: Mechanism, states: States,
                      links: Mapping[str, LinkState]) -> LinkState:
    rod, k, b = ax.rod, states[ax.known], links[g.base]
    r = links[rod.link]
    if rod.form == "RR":
        a, pin = ax.point, ax.pin
        aa, ab = k.acceleration(a), b.acceleration(pin)
        d = pin - a
        e = cross(d, ab - aa + (r.omega ** 2)[:, None] * d) / np.einsum("ij,ij->i", d, d)
        return r.with_acceleration(e, a, aa)
    if rod.form == "PR":
        return r.with_acceleration(k.epsilon, ax.pin, b.acceleration(ax.pin))
    return r.with_acceleration(b.epsilon, ax.point, k.acceleration(ax.point))

"""Every real assembly of each Assur group at one position, the earlier groups of the structural
formula held in the poses the motion gives them (seed 002's analytical method).

* Class II groups: the closed forms of :mod:`plans.kinematics.groups` give both branches of
  the two-branch forms (RRR, RRP, RPR) and the one pose of the line–line forms (PRP, RPP).
* Class III and IV groups of revolute pairs: all angles but one, φ, are eliminated (the seed's
  system (6)); the remaining angle ψ follows from quadratics in u = tan(ψ/2) (its (7)), whose
  discriminants decide reality. The residual f(φ) left by the elimination is a trigonometric
  polynomial of degree ≤ 4; its real roots are all bracketed by a certified search
  (:func:`.trig_roots.trig_roots`), refined by Brent's method, completed by the quadratics and
  polished by a Newton step on the group's pair equations (:class:`~plans.kinematics.generic.GroupEquations`).
* Class III and IV groups with a sliding pair: the same, on the base link's pose (class III) or
  with a sliding link's travel mapped onto the circle by the half-angle substitution (class IV),
  in :mod:`.assemblies_prismatic`.

Lengths in metres, angles in radians, counter-clockwise positive; a link's pose maps a local
(sketch) point x to o + R(θ)·x, as everywhere in plans.kinematics.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np

from ..errors import SceneError
from ..structure import ComplexGroup, Group, Pair
from .generic import GroupEquations
from .groups import candidates
from .special import condition
from .state import LinkState
from .tolerances import ASSEMBLY_RTOL
from .trig_roots import GRID, cramer_residual, group_roots, half_angle_roots
from .assemblies_prismatic import sliding_poses
from .. import linalg as la

__all__ = ["Assembly", "GroupAssemblies", "assemblies", "group_assemblies", "dyad_pairs", "SAME_RTOL", "MERGE_RTOL",
           "GRID", "residual_function"]

#: Two poses are one assembly when no point of the group differs by more than this × size.
SAME_RTOL = 1e-9
#: ... and the enumeration lists two poses as one when they are closer than this × size: near a
#: double root (two assemblies about to merge, a distance d apart) a pose is resolved in double
#: precision only to ~1e-16·size²/d, so copies of one root scatter by more than SAME_RTOL once
#: d < 1e-7·size; √(1e-16) is where that scatter and d meet: closer assemblies are one here.
MERGE_RTOL = 1e-8
#: An assembly's pair equations must hold to this × size after polishing (m; angles × size).
POLISH_RTOL = 1e-12


@dataclass(frozen=True)
class Assembly:
    """One real assembly of a group: world ``points`` of the group's links (m) and the links'
    ``poses`` (x_o, y_o in m, θ in rad); ``chosen`` when it is the motion's own pose;
    ``condition`` the class III group's condition figure at that pose (±1 well spread, 0 at a
    singular position; :func:`plans.kinematics.special.condition`), None for other groups."""

    points: Mapping[str, tuple[float, float]]
    poses: Mapping[str, tuple[float, float, float]]
    chosen: bool
    condition: float | None = None      # a class III group's condition figure there (special.condition)


@dataclass(frozen=True)
class GroupAssemblies:
    """Every real assembly of group ``group`` at one position (the motion's pose among them)."""

    group: str
    assemblies: tuple[Assembly, ...]

    @property
    def count(self) -> int:
        return len(self.assemblies)

    def as_dict(self) -> dict:
        """The JSON report's entry: ``{"count": n, "poses": [{"points": {P: [x, y]}, "chosen": b}]}`` (m)."""
        return {"count": self.count,
                "poses": [{"points": {p: [float(x), float(y)] for p, (x, y) in a.points.items()},
                           "chosen": a.chosen, **({} if a.condition is None else {"condition": a.condition})}
                          for a in self.assemblies]}


def assemblies(motion, i: int) -> dict[str, GroupAssemblies]:
    """Every Assur group's real assemblies at position i (group name → :class:`GroupAssemblies`),
    each with the earlier groups in the motion's poses."""
    return {g.name: group_assemblies(motion, g, i) for g in motion.structure.groups}


def _at(motion, i: int) -> dict[str, LinkState]:
    """Every link's state at position i alone (N = 1)."""
    return {n: LinkState(s.theta[i:i + 1], s.origin[i:i + 1]) for n, s in motion.links.items()}


def dyad_pairs(g: Group) -> tuple[Pair, ...]:
    """A class II group's pairs in the form of :class:`~plans.kinematics.generic.GroupEquations`."""
    return tuple(Pair(j.kind, a, b, j.point, j.prismatic)
                 for j, a, b in ((g.d, g.m, g.d.other), (g.e, g.m, g.n), (g.f, g.n, g.f.other)))


def group_assemblies(motion, g: Group | ComplexGroup, i: int) -> GroupAssemblies:
    """The real assemblies of group ``g`` at position i; the one the motion has is ``chosen``
    (the nearest pose, matched within MERGE_RTOL × size of every point; poses closer than that
    are listed once)."""
    mech = motion.mechanism
    size = mech.size
    known = _at(motion, i)
    if isinstance(g, Group):
        poses = [{g.m: c.m, g.n: c.n} for c in candidates(g, mech, known, ASSEMBLY_RTOL * size) if bool(c.valid[0])]
    else:
        poses = _complex(mech, g, known)
    found: list[dict[str, tuple[float, float]]] = []
    kept: list[dict[str, LinkState]] = []
    for pose in poses:
        pts = _points(mech, pose)
        if not any(_gap(pts, f) <= MERGE_RTOL * size for f in found):
            found.append(pts)
            kept.append(pose)
    own = {n: known[n] for n in g.links}
    mine = _points(mech, own)
    near = sorted((_gap(mine, f), k) for k, f in enumerate(found))
    chosen = near[0][1] if near and near[0][0] <= MERGE_RTOL * size else None
    if chosen is None:          # not met by the enumeration (it never is, in the tests): listed as is
        found.append(mine)
        kept.append(own)
        chosen = len(found) - 1
    out = [Assembly(pts, {n: (float(s.origin[0, 0]), float(s.origin[0, 1]), float(s.theta[0]))
                          for n, s in pose.items()}, k == chosen, _condition(mech, g, known, pose))
           for k, (pts, pose) in enumerate(zip(found, kept))]
    # order by geometry: the points the group moves (its outer pins are the same in every pose, up
    # to rounding, which must not decide), each coordinate to 1e-9 of the size
    held = {p.point for p in g.outer if p.kind == "R"} if isinstance(g, ComplexGroup) \
        else {j.point for j in (g.d, g.f) if j.kind == "R"}
    out.sort(key=lambda a: tuple(round(c / size, 9) for p in sorted(a.points) if p not in held for c in a.points[p]))
    return GroupAssemblies(g.name, tuple(out))


def _condition(mech, g, known: Mapping[str, LinkState], pose: Mapping[str, LinkState]) -> float | None:
    """A class III group's condition figure at ``pose`` (the other links at ``known``); None for
    other groups."""
    if not isinstance(g, ComplexGroup) or g.base is None or any(r.form == "PP" for r in g.rods):
        return None         # (a rod sliding on both its pairs has no axis)
    return float(condition(g, mech, {**known, **pose})[0])


def _points(mech, pose: Mapping[str, LinkState]) -> dict[str, tuple[float, float]]:
    """World position of every point of the links in ``pose`` (m)."""
    out: dict[str, tuple[float, float]] = {}
    for name, s in pose.items():
        for p, x in mech.links[name].local.items():
            if p not in out:
                w = s.point(x)[0]
                out[p] = (float(w[0]), float(w[1]))
    return out


def _gap(a: Mapping[str, tuple[float, float]], b: Mapping[str, tuple[float, float]]) -> float:
    """The largest distance (m) between a point of pose ``a`` and the same point of pose ``b``."""
    return max(math.hypot(a[p][0] - b[p][0], a[p][1] - b[p][1]) for p in a)


# --- class III and IV: the elimination ------------------------------------------------------

@dataclass(frozen=True)
class _Elimination:
    """An all-revolute group reduced to two angles: φ (the pose angle of link ``x``) and ψ (of
    link ``y``, pinned at the known world point ``pivot``, its local point ``y0``). Two
    conditions are left, k = 0, 1: |pivot + R(ψ)·v_k − (c_k + R(φ)·s_k)| = l_k (m)."""

    x: str
    y: str
    pivot: np.ndarray
    y0: np.ndarray
    v: np.ndarray        # (2, 2) local vectors on y
    c: np.ndarray        # (2, 2) world points
    s: np.ndarray        # (2, 2) local vectors on x
    l: np.ndarray        # (2,) lengths
    x_at: tuple          # how x is placed: ("pin", world point, local point) or ("on_y", local on y, local on x)

    def coefficients(self, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """A, B, D (2, n) of A cos ψ + B sin ψ = D, the two conditions at angles ``phi`` (n,):
        with w = c + R(φ)s − pivot, A = 2 v·w, B = 2 v×w, D = |v|² + |w|² − l² (m²)."""
        cp, sp = np.cos(phi), np.sin(phi)
        out = []
        for k in (0, 1):
            sx, sy = self.s[k]
            wx = self.c[k, 0] - self.pivot[0] + cp * sx - sp * sy
            wy = self.c[k, 1] - self.pivot[1] + sp * sx + cp * sy
            vx, vy = self.v[k]
            out.append((2.0 * (vx * wx + vy * wy), 2.0 * (vx * wy - vy * wx),
                        vx * vx + vy * vy + wx * wx + wy * wy - self.l[k] ** 2))
        return tuple(np.array([o[j] for o in out]) for j in range(3))


def residual_function(e: _Elimination, size: float):
    """f(φ) = (N_c² + N_s² − Δ²)/size⁸ of the two conditions on ψ (:func:`.trig_roots.cramer_residual`):
    zero exactly where they have a solution on the unit circle. A, B, D are of degree 1 in
    cos φ, sin φ, so f is a trigonometric polynomial of degree ≤ 4: at most 8 roots on the circle."""
    return cramer_residual(e.coefficients, size ** -8)


def _complex(mech, g: ComplexGroup, known: dict[str, LinkState]) -> list[dict[str, LinkState]]:
    """Every real assembly of a class III/IV group (the other links at ``known``): its revolute
    pairs' elimination here, a sliding pair's in :mod:`.assemblies_prismatic`; each completed
    pose polished by one Newton step on the group's own pair equations (generic.py)."""
    if any(p.kind != "R" for p in g.pairs):
        rough = sliding_poses(mech, g, known)
    else:
        e = _eliminate(mech, g, known)
        f = residual_function(e, mech.size)
        rough = [_pose(mech, g, e, known, phi, psi) for phi in group_roots(g, f, f"angle of link {e.x}")
                 for psi in _psi(e, phi)]
    eq = GroupEquations(mech, g.links, g.pairs)
    out = []
    for pose in rough:
        res = eq.newton(eq.pose(pose), known)
        if res.converged and res.residual <= POLISH_RTOL * mech.size:
            out.append({n: s for n, s in eq.states(res.q, known).items() if n in eq.col})
    return out


def _world(mech, known: Mapping[str, LinkState], pair: Pair) -> np.ndarray:
    """World position (2,) of an outer pin, from its known link."""
    return known[pair.b].point(mech.links[pair.b].local[pair.point])[0]


def _eliminate(mech, g: ComplexGroup, known: Mapping[str, LinkState]) -> _Elimination:
    """The two-angle reduction of ``g``: a class III group's φ is its base link's angle and ψ its
    first rod's; a class IV group's φ and ψ are the angles of its two links with outer pairs."""
    loc = {n: mech.links[n].local for n in g.links}
    if g.base is not None:
        r0, *others = g.rods
        y, y0 = r0.link, loc[r0.link][r0.outer.point]
        b0 = loc[g.base][r0.inner.point]
        v = loc[y][r0.inner.point] - y0
        c = np.array([_world(mech, known, r.outer) for r in others])
        s = np.array([b0 - loc[g.base][r.inner.point] for r in others])
        l = np.array([float(la.norm(loc[r.link][r.inner.point] - loc[r.link][r.outer.point])) for r in others])
        return _Elimination(g.base, y, _world(mech, known, r0.outer), y0, np.array([v, v]), c, s, l,
                            ("on_y", loc[y][r0.inner.point], b0))
    ox, oy = g.outer
    x, y = ox.a, oy.a
    rods = [n for n in g.links if n not in (x, y)]
    v, s, l = [], [], []
    for rod in rods:
        pins = {p.other(rod): p.point for p in g.inner if rod in (p.a, p.b)}
        if set(pins) != {x, y}:
            raise SceneError(f"group {g.name}: its assemblies are not yet enumerated for this form (the links with "
                             "outer pairs are not opposite in the contour); leave \"assemblies\" out of draw",
                             key="plans.draw")
        v.append(loc[y][pins[y]] - loc[y][oy.point])
        s.append(loc[x][pins[x]] - loc[x][ox.point])
        l.append(float(la.norm(loc[rod][pins[x]] - loc[rod][pins[y]])))
    px = _world(mech, known, ox)
    return _Elimination(x, y, _world(mech, known, oy), loc[y][oy.point], np.array(v), np.array([px, px]),
                        np.array(s), np.array(l), ("pin", px, loc[x][ox.point]))


def _psi(e: _Elimination, phi: float) -> list[float]:
    """ψ at a root φ: the roots of the first condition's quadratic (7) in u = tan(ψ/2) that
    satisfy the second one (:func:`.trig_roots.half_angle_roots`)."""
    return half_angle_roots(*(x[:, 0] for x in e.coefficients(np.array([phi]))))


def _placed(theta: float, world: np.ndarray, local: np.ndarray) -> LinkState:
    """The pose with angle θ putting local point ``local`` at world point ``world``."""
    cs, sn = math.cos(theta), math.sin(theta)
    o = np.array([world[0] - (cs * local[0] - sn * local[1]), world[1] - (sn * local[0] + cs * local[1])])
    return LinkState(np.array([theta]), o[None, :])


def _pose(mech, g: ComplexGroup, e: _Elimination, known: Mapping[str, LinkState], phi: float, psi: float
          ) -> dict[str, LinkState]:
    """Every link of ``g`` (and the known ones) placed from φ, ψ: y on its pivot, x on its pin
    (or on y's point, for a class III base), each other link on two of its pins."""
    states = dict(known)
    states[e.y] = _placed(psi, e.pivot, e.y0)
    how, p1, p2 = e.x_at
    world = p1 if how == "pin" else states[e.y].point(p1)[0]
    states[e.x] = _placed(phi, world, p2)
    for name in g.links:
        if name in (e.x, e.y):
            continue
        pins = [(p.point, p.other(name)) for p in g.pairs if name in (p.a, p.b) and p.other(name) in states]
        (pa, la_), (pb, lb) = pins[:2]
        loc = mech.links[name].local
        wa = states[la_].point(mech.links[la_].local[pa])[0]
        wb = states[lb].point(mech.links[lb].local[pb])[0]
        d, dl = wb - wa, loc[pb] - loc[pa]
        states[name] = _placed(math.atan2(d[1], d[0]) - math.atan2(dl[1], dl[0]), wa, loc[pa])
    return states

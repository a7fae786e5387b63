"""Kinetostatics: the reactions of every pair and the balancing element, group by group.

The groups are solved from the farthest (the last attached) back to the original mechanism,
each with the loads of its links and the reactions the groups after it already put on them
(d'Alembert: every link is in equilibrium under its loads, its inertia included):

* a class II group in closed form, as the textbook builds its force plan:

  - RRR: R^τ of each outer pair from its link's moments about the inner pin E
    (R^τ_D = ΣM_E(link m)/l_DE, along k × (E − D)/l_DE), then R^n_D, R^n_F (along the links,
    D → E and F → E) from the group's force polygon (two known directions);
  - RRP: R^τ_D likewise, then R^n_D and the guide's normal reaction from the polygon;
  - RPR: the outer reactions' components along the slide from each link's forces along it,
    the rest from the group's moments about D and its polygon;
  - PRP: both normal reactions from the polygon; RPP: the two normal reactions on the middle
    link from its polygon, then R_D from the first link's.

  The inner reaction follows from one link's polygon, and each prismatic reaction's moment
  (where it acts along the guide) from its link's moments;
* a class III or IV group, and the original mechanism of a drive inside the chain, as one
  linear system: three equations a link (ΣFx, ΣFy, ΣM), two unknowns a pair (and the
  balancing element for the original mechanism), solved at every position at once;
* the driving link: its pairs with the frame and the balancing moment (or force) the same way.

A revolute pair's reaction acts at the pin. A prismatic pair's is normal to the guide, its
point of application unknown: it is held as the force N·ν (ν = k × u, u the guide's direction)
at the pair's reference point r0 plus a couple T (the reaction's moment about r0); it acts at
r0 + (T/N)·u along the guide.

Signs: ``R:i-j`` is the force of link i on link j (that of j on i is its opposite); moments
CCW positive; the balancing element is what the drive applies to the driving link, in
equilibrium with every load, inertia included.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

import numpy as np

from ..errors import PlansError, SceneError
from ..kinematics import Motion
from ..kinematics.state import J, cross
from ..model import Prismatic
from ..scene import FRAME, Scene
from ..structure import ComplexGroup, DrivenGroup, Group, Pair
from .loads import Couple, Load, applied_loads, force_sum, moment_about

__all__ = ["ForceTerm", "GroupForces", "Reaction", "Balancing", "Forces", "solve_forces", "SINGULAR_COND",
           "POINT_RTOL"]

#: A group's linear system (scaled to O(1) coefficients) whose condition number exceeds this
#: has no unique solution: the balancing force's line passes through the pivot, or the group
#: sits at a singular position (the kinematics refuses those below |sin| = 1e-6, where the
#: condition is ~1e6; rounding then still leaves 1e-10 of precision).
SINGULAR_COND = 1e12
#: A prismatic reaction smaller than this × the largest force at its position has no defined
#: point of application (T/N would be rounding noise): it is reported as null.
POINT_RTOL = 1e-12


@dataclass(frozen=True, eq=False)
class ForceTerm:
    """One side of a force polygon: ``vector`` (N, 2) in N. ``quantity``: ``G:3``, ``F:in:2``,
    ``F:ext:B``, ``F:bal``, ``R:0-3`` (the force of link 0 on link 3; ``:n``/``:t`` for the
    normal and tangential components of a class II group's outer revolute pair); ``kind``:
    ``gravity``, ``inertia``, ``external``, ``balance`` or ``reaction``."""

    quantity: str
    vector: np.ndarray
    kind: str


@dataclass(frozen=True, eq=False)
class GroupForces:
    """The force polygon of one group (or of the original mechanism, ``I(0-1)``): ``terms`` in
    the order they are drawn, summing to zero at every position; ``inner``: the reactions of
    its inner pairs (``R:i-j``, the force of i on j), found from one link's polygon."""

    group: str
    links: tuple[str, ...]
    terms: tuple[ForceTerm, ...]
    inner: tuple[ForceTerm, ...]


@dataclass(frozen=True, eq=False)
class Reaction:
    """The reaction of one pair: ``force`` (N, 2) N, of link ``first`` on link ``second``.

    A revolute pair (``kind`` ``"R"``): ``point`` is the pin (N, 2) m. A prismatic pair
    (``"P"``): ``u`` the guide's unit direction (N, 2); ``origin`` (N, 2) the reference point,
    the pair's point ``at`` projected on the guide; ``moment`` (N,) N·m the reaction's moment
    about ``origin``; ``offset`` (N,) m = moment / (force · ν), where along u from ``origin``
    the reaction acts, and ``point`` = origin + offset·u — both NaN where the reaction is
    (nearly) zero and acts nowhere in particular."""

    key: str
    first: str
    second: str
    kind: str
    force: np.ndarray
    point: np.ndarray
    at: str | None = None
    u: np.ndarray | None = None
    origin: np.ndarray | None = None
    moment: np.ndarray | None = None
    offset: np.ndarray | None = None


@dataclass(frozen=True, eq=False)
class Balancing:
    """The balancing element on the driving link ``link``: ``kind`` ``"moment"`` (``value``
    (N,) N·m, CCW positive), ``"force"`` (``value`` (N,) N along ``direction`` (N, 2) at
    ``point`` (N, 2), the link's point ``at``) or ``"actuator"`` (a cylinder's force
    ``value`` along the guide ``direction`` on the rod ``link`` at ``point``, and its opposite
    on the cylinder ``reacts_on``). ``vector`` = value·direction (N, 2) for a force."""

    link: str
    kind: str
    value: np.ndarray
    at: str | None = None
    direction: np.ndarray | None = None
    point: np.ndarray | None = None
    reacts_on: str | None = None

    @property
    def vector(self) -> np.ndarray | None:
        return None if self.direction is None else self.value[:, None] * self.direction


@dataclass(frozen=True, eq=False)
class Forces:
    """The force analysis at N positions.

    ``loads``/``couples``: every load the lever takes (gravity, inertia, external and the
    balancing element, ``F:bal``/``M:bal``), each with its link and point of application;
    ``reactions``: key ``"i-j"`` → :class:`Reaction` for every pair (the frame's too);
    ``groups``: the force polygons in the order solved (farthest group first, the original
    mechanism last); ``balance``: the balancing element from the group-by-group solution;
    ``power``: the same element's value from the power balance alone,
    −(Σ F·v + Σ M·ω)/(its velocity factor) over every other load, None when the drive stands;
    ``power_residual``: |Σ F·v + Σ M·ω| over every load and the group-by-group balance, over
    the largest single |term| (0 when all are 0; None when the drive stands)."""

    loads: tuple[Load, ...]
    couples: tuple[Couple, ...]
    reactions: Mapping[str, Reaction]
    groups: tuple[GroupForces, ...]
    balance: Balancing
    power: np.ndarray | None
    power_residual: np.ndarray | None

    def on_link(self, link: str) -> tuple[list[Load], list[Couple]]:
        """Every force and couple acting on ``link``: its loads, the balancing element, and
        each pair's reaction (a prismatic one as its force at the reference point plus its
        moment about it)."""
        loads = [l for l in self.loads if l.link == link]
        couples = [c for c in self.couples if c.link == link]
        for r in self.reactions.values():
            for who, sign, tag in ((r.second, 1.0, f"R:{r.first}-{r.second}"), (r.first, -1.0, f"R:{r.second}-{r.first}")):
                if who != link:
                    continue
                at = r.point if r.kind == "R" else r.origin
                loads.append(Load(tag, link, at, sign * r.force, "reaction"))
                if r.kind == "P":
                    couples.append(Couple(tag, link, sign * r.moment, "reaction"))
        return loads, couples


# --- the pairs as the solver sees them ---------------------------------------------------------

@dataclass(frozen=True, eq=False)
class _Pair:
    """A pair to solve: the force of ``first`` on ``second``; a pin at ``point`` or a
    prismatic pair ``prismatic``."""

    first: str
    second: str
    kind: str
    point: str | None = None
    prismatic: Prismatic | None = None


class _Geometry:
    """Pins, guides and reference points of the pairs, computed once per pair."""

    def __init__(self, motion: Motion):
        self.motion = motion
        self._cache: dict = {}

    def pin(self, point: str) -> np.ndarray:
        key = ("pin", point)
        if key not in self._cache:
            self._cache[key] = self.motion.position(point)
        return self._cache[key]

    def guide(self, p: Prismatic) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """u (the guide's unit direction), ν = k × u and the reference point r0 (the pair's
        label point projected on the common line), each (N, 2)."""
        key = ("guide", id(p))
        if key not in self._cache:
            m = self.motion
            u = m.links[p.guide].direction(p.direction)
            on_line = m.links[p.slider].point(p.anchor[p.slider])
            label = m.position(p.label)
            r0 = on_line + np.sum((label - on_line) * u, axis=1)[:, None] * u
            self._cache[key] = (u, J(u), r0)
        return self._cache[key]

    def anchor(self, pair: _Pair) -> np.ndarray:
        """Where the pair's unknown force is applied in the equations: the pin, or r0."""
        return self.pin(pair.point) if pair.kind == "R" else self.guide(pair.prismatic)[2]


def _split(f: np.ndarray, a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """x, y (N,) with f = x·a + y·b (Cramer's rule; a, b (N, 2) not parallel)."""
    det = cross(a, b)
    return cross(f, b) / det, cross(a, f) / det


def _unit(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    length = np.hypot(v[:, 0], v[:, 1])
    return v / length[:, None], length


class _Solver:
    """Accumulates loads and solved reactions link by link while the groups are solved."""

    def __init__(self, motion: Motion, scene: Scene):
        self.motion = motion
        self.mech = motion.mechanism
        self.geo = _Geometry(motion)
        self.loads, self.couples = applied_loads(motion, scene)
        self.acting: dict[str, list[Load]] = {name: [l for l in self.loads if l.link == name] for name in self.mech.links}
        self.turning: dict[str, list[Couple]] = {name: [c for c in self.couples if c.link == name]
                                                 for name in self.mech.links}
        self.reactions: dict[str, Reaction] = {}
        self.groups: list[GroupForces] = []
        self.size = self.mech.size
        self.n = len(motion)

    # --- bookkeeping ---
    def key(self, first: str, second: str) -> str:
        base = f"{first}-{second}"
        k, key = 1, base
        while key in self.reactions:
            k += 1
            key = f"{base}#{k}"
        return key

    def record(self, pair: _Pair, force: np.ndarray, moment: np.ndarray | None = None) -> Reaction:
        """Store a solved reaction (force of first on second; a prismatic pair's moment about
        r0) and put its opposite on ``first`` for the groups still to solve."""
        key = self.key(pair.first, pair.second)
        if pair.kind == "R":
            r = Reaction(key, pair.first, pair.second, "R", force, self.geo.pin(pair.point), at=pair.point)
            self.acting[pair.first].append(Load(f"R:{pair.second}-{pair.first}", pair.first, r.point, -force, "reaction"))
        else:
            u, nu, r0 = self.geo.guide(pair.prismatic)
            normal = np.sum(force * nu, axis=1)
            scale = np.maximum(np.hypot(force[:, 0], force[:, 1]), self._force_scale())
            defined = np.abs(normal) > POINT_RTOL * scale
            offset = np.where(defined, moment / np.where(defined, normal, 1.0), np.nan)
            point = r0 + offset[:, None] * u
            r = Reaction(key, pair.first, pair.second, "P", force, point, at=pair.prismatic.label, u=u, origin=r0,
                         moment=moment, offset=offset)
            tag = f"R:{pair.second}-{pair.first}"
            self.acting[pair.first].append(Load(tag, pair.first, r0, -force, "reaction"))
            self.turning[pair.first].append(Couple(tag, pair.first, -moment, "reaction"))
        self.reactions[key] = r
        return r

    def _force_scale(self) -> np.ndarray:
        """The largest load (N) at each position: what 'nearly zero' is measured against."""
        scale = np.zeros(self.n)
        for l in self.loads:
            scale = np.maximum(scale, np.hypot(l.force[:, 0], l.force[:, 1]))
        for c in self.couples:
            scale = np.maximum(scale, np.abs(c.moment) / self.size)
        return scale

    def terms_of(self, link: str) -> list[ForceTerm]:
        """The forces on ``link`` known so far (loads, then reactions of later groups), as
        force-polygon terms."""
        return [ForceTerm(l.quantity, l.force, l.kind) for l in self.acting[link]]

    def fsum(self, link: str) -> np.ndarray:
        return force_sum(self.acting[link]) if self.acting[link] else np.zeros((self.n, 2))

    def msum(self, link: str, x: np.ndarray) -> np.ndarray:
        return moment_about(self.acting[link], self.turning[link], x)

    # --- class II groups, closed form ---
    def class2(self, g: Group) -> None:
        m, n = g.m, g.n
        d = _Pair(g.d.other, m, g.d.kind, g.d.point, g.d.prismatic)
        e = _Pair(m, n, g.e.kind, g.e.point, g.e.prismatic)
        f = _Pair(g.f.other, n, g.f.kind, g.f.point, g.f.prismatic)
        fm, fn = self.fsum(m), self.fsum(n)
        known = self.terms_of(m) + self.terms_of(n)
        geo = self.geo
        form = g.form
        tau_d = tau_f = None
        if form in ("RRR", "RRP"):
            pd, pe = geo.pin(d.point), geo.pin(e.point)
            nu_d, l_d = _unit(pe - pd)
            t_d = self.msum(m, pe) / l_d                # ΣM_E(m) = −l_DE·R^τ_D + M_E(loads) = 0
            tau_d = t_d[:, None] * J(nu_d)
            if form == "RRR":
                pf = geo.pin(f.point)
                nu_f, l_f = _unit(pe - pf)
                t_f = self.msum(n, pe) / l_f
                tau_f = t_f[:, None] * J(nu_f)
                other = nu_f
                rest = -(fm + fn + tau_d + tau_f)
            else:
                other = geo.guide(f.prismatic)[1]
                rest = -(fm + fn + tau_d)
            n_d, n_f = _split(rest, nu_d, other)
            norm_d = n_d[:, None] * nu_d
            r_d = tau_d + norm_d
            r_f = (tau_f if tau_f is not None else 0.0) + n_f[:, None] * other
            r_e = -(fn + r_f)
            self.record(d, r_d)
            if form == "RRR":
                self.record(f, r_f)
            else:   # the slider's moments about E: the guide's reaction acts where it balances them
                _, _, r0 = geo.guide(f.prismatic)
                self.record(f, r_f, -self.msum(n, pe) - cross(r0 - pe, r_f))
            self.record(e, r_e)
            terms = [ForceTerm(f"R:{d.first}-{m}:t", tau_d, "reaction"), *known]
            if form == "RRR":
                terms += [ForceTerm(f"R:{f.first}-{n}:t", tau_f, "reaction"),
                          ForceTerm(f"R:{f.first}-{n}:n", n_f[:, None] * other, "reaction")]
            else:
                terms.append(ForceTerm(f"R:{f.first}-{n}", r_f, "reaction"))
            terms.append(ForceTerm(f"R:{d.first}-{m}:n", norm_d, "reaction"))
        elif form == "RPR":
            pd, pf = geo.pin(d.point), geo.pin(f.point)
            u, nu, r0 = geo.guide(e.prismatic)
            a_f = -np.sum(fn * u, axis=1)                # link n along the slide: the inner reaction is ⊥ u
            arm = pf - pd
            b_f = -(self.msum(m, pd) + self.msum(n, pd) + a_f * cross(arm, u)) / np.sum(arm * u, axis=1)
            r_f = a_f[:, None] * u + b_f[:, None] * nu
            r_d = -(fm + fn + r_f)
            r_e = -(fn + r_f)
            self.record(d, r_d)
            self.record(f, r_f)
            self.record(e, r_e, -self.msum(n, pf) - cross(r0 - pf, r_e))
            terms = [ForceTerm(f"R:{d.first}-{m}", r_d, "reaction"), *known,
                     ForceTerm(f"R:{f.first}-{n}", r_f, "reaction")]
        elif form == "PRP":
            pe = geo.pin(e.point)
            _, nu_d, r0_d = geo.guide(d.prismatic)
            _, nu_f, r0_f = geo.guide(f.prismatic)
            rest = -(fm + fn)
            a_d, a_f = _split(rest, nu_d, nu_f)
            r_d, r_f = a_d[:, None] * nu_d, a_f[:, None] * nu_f
            r_e = -(fn + r_f)
            self.record(d, r_d, -self.msum(m, pe) - cross(r0_d - pe, r_d))
            self.record(f, r_f, -self.msum(n, pe) - cross(r0_f - pe, r_f))
            self.record(e, r_e)
            terms = [ForceTerm(f"R:{d.first}-{m}", r_d, "reaction"), *known,
                     ForceTerm(f"R:{f.first}-{n}", r_f, "reaction")]
        elif form == "RPP":
            pd = geo.pin(d.point)
            _, nu_e, r0_e = geo.guide(e.prismatic)
            _, nu_f, r0_f = geo.guide(f.prismatic)
            a_e, a_f = _split(-fn, nu_e, nu_f)          # link n: N_E ν_E + N_F ν_F + ΣF_n = 0
            r_e, r_f = a_e[:, None] * nu_e, a_f[:, None] * nu_f
            r_d = r_e - fm
            mm, mn = self.msum(m, pd), self.msum(n, pd)
            t_e = mm - cross(r0_e - pd, r_e)
            t_f = -mn - mm - cross(r0_f - pd, r_f)
            self.record(d, r_d)
            self.record(f, r_f, t_f)
            self.record(e, r_e, t_e)
            terms = [ForceTerm(f"R:{d.first}-{m}", r_d, "reaction"), *known,
                     ForceTerm(f"R:{f.first}-{n}", r_f, "reaction")]
        else:   # pragma: no cover - the structure knows only the five forms
            raise PlansError(f"group {g.name}: unknown form {form}")
        inner = (ForceTerm(f"R:{m}-{n}", self.reactions[self._last_key(m, n)].force, "reaction"),)
        self.groups.append(GroupForces(g.name, (m, n), tuple(terms), inner))

    def _last_key(self, first: str, second: str) -> str:
        return next(k for k in reversed(list(self.reactions)) if self.reactions[k].first == first
                    and self.reactions[k].second == second)

    # --- any group as one linear system ---
    def system(self, name: str, links: tuple[str, ...], pairs: list[_Pair], balance: "_BalanceSpec | None" = None
               ) -> np.ndarray | None:
        """Solve the equilibrium of ``links`` (3 equations each) for the reactions of ``pairs``
        (2 unknowns each) and the balancing element's value (1 unknown); records the
        reactions and returns the balance's value (None without one)."""
        n, size = self.n, self.size
        row = {link: 3 * i for i, link in enumerate(links)}
        cols = 2 * len(pairs) + (balance is not None)
        if cols != 3 * len(links):   # pragma: no cover - the structure guarantees a determinate group
            raise PlansError(f"group {name}: {cols} unknowns for {3 * len(links)} equations")
        anchors = [self.geo.anchor(p) for p in pairs]
        x = np.mean(anchors, axis=0) if anchors else self.motion.position(self.mech.links[links[0]].points[0])
        a = np.zeros((n, cols, cols))
        b = np.zeros((n, cols))
        for link in links:
            r = row[link]
            b[:, r:r + 2] = -self.fsum(link)
            b[:, r + 2] = -self.msum(link, x) / size
        for j, (p, at) in enumerate(zip(pairs, anchors)):
            c = 2 * j
            arm = (at - x) / size
            for link, sign in ((p.second, 1.0), (p.first, -1.0)):
                if link not in row:
                    continue
                r = row[link]
                if p.kind == "R":         # unknowns Rx, Ry at the pin
                    a[:, r, c] += sign
                    a[:, r + 1, c + 1] += sign
                    a[:, r + 2, c] += -sign * arm[:, 1]
                    a[:, r + 2, c + 1] += sign * arm[:, 0]
                else:                     # unknowns N (along ν at r0) and T/size (its moment about r0)
                    nu = self.geo.guide(p.prismatic)[1]
                    a[:, r, c] += sign * nu[:, 0]
                    a[:, r + 1, c] += sign * nu[:, 1]
                    a[:, r + 2, c] += sign * cross(arm, nu)
                    a[:, r + 2, c + 1] += sign
        if balance is not None:
            c = cols - 1
            for link, sign in balance.acts_on:
                r = row[link]
                if balance.kind == "moment":      # unknown M/size
                    a[:, r + 2, c] += sign
                else:                             # unknown F along w at the point
                    w = balance.direction
                    a[:, r, c] += sign * w[:, 0]
                    a[:, r + 1, c] += sign * w[:, 1]
                    a[:, r + 2, c] += sign * cross((balance.point - x) / size, w)
        cond = np.linalg.cond(a)
        bad = ~(cond < SINGULAR_COND)
        if np.any(bad):
            i = int(np.argmax(bad))
            value = self.motion.values[i]
            if balance is not None and balance.kind == "force" and balance.given:
                raise SceneError(f"the balancing force's line cannot balance the mechanism at {value:g} (it has no "
                                 "arm about the driving link's motion there); choose another angle or point",
                                 key="balance.angle")
            raise PlansError(f"group {name}: its equilibrium equations are singular at {value:g} (condition "
                             f"{cond[i]:.2e}); the reactions have no unique solution there")
        sol = np.linalg.solve(a, b[..., None])[..., 0]
        # one step of iterative refinement: an ill-conditioned group (a cylinder's, cond ~1e5)
        # leaves its equations unbalanced by cond × eps after the plain solve, eps after this
        sol += np.linalg.solve(a, (b - np.einsum("nij,nj->ni", a, sol))[..., None])[..., 0]
        for j, p in enumerate(pairs):
            c = 2 * j
            if p.kind == "R":
                self.record(p, np.ascontiguousarray(sol[:, c:c + 2]))
            else:
                nu = self.geo.guide(p.prismatic)[1]
                self.record(p, sol[:, c, None] * nu, sol[:, c + 1] * size)
        if balance is None:
            return None
        return sol[:, cols - 1] * (size if balance.kind == "moment" else 1.0)


@dataclass(frozen=True, eq=False)
class _BalanceSpec:
    """The balancing element as the linear system takes it: ``kind`` ``"moment"`` or a force
    (``"force"``, ``"actuator"``) along ``direction`` at ``point``; ``acts_on``: (link, sign)."""

    kind: str
    acts_on: tuple[tuple[str, float], ...]
    direction: np.ndarray | None = None
    point: np.ndarray | None = None
    given: bool = True
    at: str | None = None


def _balance_spec(motion: Motion, scene: Scene, geo: _Geometry) -> _BalanceSpec:
    mech = motion.mechanism
    spec = scene.balance
    d = mech.drive
    if spec is None or spec.kind == "moment":
        if not d.kind.angular:
            raise SceneError(f"link {d.link} slides and cannot turn, so a moment on it balances nothing",
                             key="balance.moment_on")
        return _BalanceSpec("moment", ((d.link, 1.0),), given=spec is not None and spec.given)
    if spec.kind == "force" and spec.at is not None:
        rad = np.radians(spec.angle)
        w = motion.links[spec.link].direction(np.array([np.cos(rad), np.sin(rad)]))
        return _BalanceSpec("force", ((spec.link, 1.0),), w, motion.position(spec.at, spec.link), given=True,
                            at=spec.at)
    p = d.guide                       # along the drive's guide, at the pair's point
    u, _, r0 = geo.guide(p)
    if spec.kind == "actuator":
        return _BalanceSpec("actuator", ((d.link, 1.0), (p.other(d.link), -1.0)), u, r0, given=spec.given,
                            at=p.label)
    return _BalanceSpec("force", ((d.link, 1.0),), u, r0, given=spec.given, at=p.label)


def solve_forces(motion: Motion, scene: Scene, *, closed_forms: bool = True) -> Forces:
    """The force analysis of ``scene`` on its solved ``motion`` (order 2 when a link has a
    mass or an inertia, order ≥ 1 for the power balance; order 0 gives no power check).

    ``closed_forms=False`` solves the class II groups as linear systems too (the tests compare
    the two); their polygons then carry whole reactions, without the ``:n``/``:t`` split."""
    s = _Solver(motion, scene)
    mech, structure = s.mech, motion.structure
    for g in reversed(structure.groups):
        if isinstance(g, Group) and closed_forms:
            s.class2(g)
        else:
            if isinstance(g, Group):      # the dyad's pairs as a class III/IV group's
                g = ComplexGroup(links=(g.m, g.n), klass=2, inner=(
                    Pair(g.e.kind, g.m, g.n, g.e.point, g.e.prismatic),), outer=tuple(
                    Pair(j.kind, link, j.other, j.point, j.prismatic) for link, j in ((g.m, g.d), (g.n, g.f))))
            inner = [_Pair(p.a, p.b, p.kind, p.point, p.prismatic) for p in g.inner]
            outer = [_Pair(p.b, p.a, p.kind, p.point, p.prismatic) for p in g.outer]
            known = [t for link in g.links for t in s.terms_of(link)]
            s.system(g.name, g.links, inner + outer)
            terms = known + [ForceTerm(f"R:{p.first}-{p.second}", s.reactions[s._last_key(p.first, p.second)].force,
                                       "reaction") for p in outer]
            inner_terms = tuple(ForceTerm(f"R:{p.first}-{p.second}",
                                          s.reactions[s._last_key(p.first, p.second)].force, "reaction") for p in inner)
            s.groups.append(GroupForces(g.name, g.links, tuple(terms), inner_terms))
    bal = _balance_spec(motion, scene, s.geo)
    driven: DrivenGroup | None = structure.driven
    if driven is not None:
        links = driven.links
        inner = [_Pair(p.a, p.b, p.kind, p.point, p.prismatic) for p in driven.inner]
        outer = [_Pair(p.b, p.a, p.kind, p.point, p.prismatic) for p in driven.outer]
        name = driven.name
    else:
        links = (mech.drive.link,)
        inner = []
        outer = [_Pair(FRAME, mech.drive.link, "R", point=r.point) for r in mech.revolutes
                 if {r.a, r.b} == {FRAME, mech.drive.link}]
        outer += [_Pair(FRAME, mech.drive.link, "P", prismatic=p) for p in mech.prismatics
                  if {p.slider, p.guide} == {FRAME, mech.drive.link}]
        name = structure.original
    known = [t for link in links for t in s.terms_of(link)]
    value = s.system(name, links, inner + outer, bal)
    if bal.kind == "moment":
        balancing = Balancing(mech.drive.link, "moment", value)
        bal_couples = (Couple("M:bal", mech.drive.link, value, "balance"),)
        bal_loads: tuple[Load, ...] = ()
        bal_terms: list[ForceTerm] = []
    else:
        other = bal.acts_on[1][0] if len(bal.acts_on) > 1 else None
        balancing = Balancing(mech.drive.link, bal.kind, value, at=bal.at, direction=bal.direction, point=bal.point,
                              reacts_on=other)
        vec = balancing.vector
        bal_loads = (Load("F:bal", mech.drive.link, bal.point, vec, "balance"),)
        if other is not None:
            bal_loads += (Load(f"F:bal:{other}", other, bal.point, -vec, "balance"),)
        bal_couples = ()
        bal_terms = [ForceTerm(l.quantity, l.force, "balance") for l in bal_loads]
    terms = known + bal_terms + [ForceTerm(f"R:{p.first}-{p.second}",
                                           s.reactions[s._last_key(p.first, p.second)].force, "reaction")
                                 for p in outer]
    inner_terms = tuple(ForceTerm(f"R:{p.first}-{p.second}", s.reactions[s._last_key(p.first, p.second)].force,
                                  "reaction") for p in inner)
    s.groups.append(GroupForces(name, links, tuple(terms), inner_terms))
    loads = s.loads + bal_loads
    couples = s.couples + bal_couples
    power, residual = _power(motion, s.loads, s.couples, balancing)
    return Forces(loads=loads, couples=couples, reactions=dict(s.reactions), groups=tuple(s.groups),
                  balance=balancing, power=power, power_residual=residual)


def _power(motion: Motion, loads: tuple[Load, ...], couples: tuple[Couple, ...], bal: Balancing
           ) -> tuple[np.ndarray | None, np.ndarray | None]:
    """The balancing element from the power balance (d'Alembert, virtual work): Σ F·v + Σ M·ω
    over every load is zero, so value = −P/(its velocity factor): ω of the driving link for
    a moment, w·v of its point for a force, the sliding speed for a cylinder's actuator. And
    the residual of that balance with the group-by-group value. None when the drive stands."""
    if motion.order < 1 or motion.mechanism.drive.speed == 0.0:
        return None, None
    terms = [np.sum(l.force * motion.links[l.link].velocity(l.point), axis=1) for l in loads]
    terms += [c.moment * motion.links[c.link].omega for c in couples]
    total = np.sum(terms, axis=0) if terms else np.zeros(len(motion))
    if bal.kind == "moment":
        factor = motion.links[bal.link].omega
    else:
        v = motion.links[bal.link].velocity(bal.point)
        if bal.reacts_on is not None:
            v = v - motion.links[bal.reacts_on].velocity(bal.point)
        factor = np.sum(bal.direction * v, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        power = np.where(factor != 0.0, -total / np.where(factor != 0.0, factor, 1.0), np.nan)
    bal_term = bal.value * factor
    scale = np.max(np.abs(np.array(terms + [bal_term])), axis=0)
    residual = np.where(scale > 0.0, np.abs(total + bal_term) / np.where(scale > 0.0, scale, 1.0), 0.0)
    return power, residual

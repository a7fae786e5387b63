"""The reactions group by group: :class:`_Solver` keeps every link's loads and the reactions
solved so far, solves a class II group in closed form (:meth:`_Solver.class2`) and any other
group, or the original mechanism with its balancing element, as one linear system
(:meth:`_Solver.system`). Conventions: :mod:`plans.kinetostatics.solve`.

Must not import :mod:`.solve` or anything above the kinetostatics.
"""

from __future__ import annotations

from typing import Mapping

import numpy as np

from ..errors import PlansError, SceneError
from ..kinematics import Motion
from ..kinematics.state import J, cross
from ..kinematics.walk import fmt
from ..scene import Scene
from ..structure import Group
from .balance import _BalanceSpec
from .loads import Couple, Load, Travel, applied_loads, force_sum, moment_about
from .pairs import _Geometry, _Pair, _split, _unit
from .results import ForceTerm, GroupForces, Reaction
from .. import linalg as la

#: A group's linear system (scaled to O(1) coefficients) whose condition number exceeds this
#: has no unique solution: the balancing force's line passes through the pivot, or the group
#: sits at a singular position (the kinematics refuses those below |sin| = 1e-6, where the
#: condition is ~1e6; rounding then still leaves 1e-10 of precision).
SINGULAR_COND = 1e12
#: A prismatic reaction smaller than this × the largest force at its position has no defined
#: point of application (T/N would be rounding noise): it is reported as null.
POINT_RTOL = 1e-12


class _Solver:
    """Accumulates loads and solved reactions link by link while the groups are solved."""

    def __init__(self, motion: Motion, scene: Scene, travel: Travel | None = None,
                 laws: Mapping[int, np.ndarray] | None = None):
        self.motion = motion
        self.mech = motion.mechanism
        self.geo = _Geometry(motion)
        self.loads, self.couples = applied_loads(motion, scene, travel, laws=laws)
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
            value = fmt(self.motion.mechanism, float(self.motion.values[i]))     # 30° or 0.02 m
            if balance is not None and balance.kind == "force" and balance.given:
                raise SceneError(f"the balancing force's line cannot balance the mechanism at {value} (it has no "
                                 "arm about the driving link's motion there); choose another angle or point",
                                 key="balance.angle")
            raise PlansError(f"group {name}: its equilibrium equations are singular at {value} (condition "
                             f"{cond[i]:.2e}); the reactions have no unique solution there")
        sol = la.solve(a, b[..., None])[..., 0]
        # one step of iterative refinement: an ill-conditioned group (a cylinder's, cond ~1e5)
        # leaves its equations unbalanced by cond × eps after the plain solve, eps after this
        sol += la.solve(a, (b - np.einsum("nij,nj->ni", a, sol))[..., None])[..., 0]
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

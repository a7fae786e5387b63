"""The generic Assur-group solver: Newton on the pair equations, linear solves for the rates.

Used for class III and IV groups (and usable for any group): the unknowns are the poses
(x_o, y_o, θ) of the group's links, q ∈ R^{3k}; every pair gives two equations Φ(q) = 0:

* revolute pair at P between links a and b:   X_a(P) − X_b(P) = 0
* prismatic pair, slider s on guide g:         θ_s − θ_g = 0,  (X_s − Y_g)·n_g = 0

(X_s, Y_g: the pair's anchor points on each link; n_g: the line's normal turned with g).
Positions: Newton's method, continued along the drive's walk from the sketch (where every
pose is the identity) with a linear predictor. Velocities and accelerations: the same
Jacobian A = ∂Φ/∂q multiplies the unknown rates (v_o, ω) and (a_o, ε); the known links' and
the quadratic (normal, Coriolis) terms form the right-hand side:

    A·q̇ = −Φ̇|q̇=0        A·q̈ = −Φ̈|q̈=0

solved for all positions at once with ``numpy.linalg.solve``. The condition figure of a
position is sign(det A) times the polar sine of the equations reduced to the group's turning
and sliding rates (:mod:`plans.kinematics.figure`): a class II group's sin(U1, U2) generalised
(1 = well conditioned, 0 = singular; the sign changes across a singular position).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

import numpy as np

from ..model import Mechanism
from .figure import reduced_figure
from .state import J, LinkState
from .tolerances import MAX_ITER, NEWTON_RTOL
from .. import linalg as la

__all__ = ["GroupEquations", "NewtonResult", "TOLERANCE", "MAX_ITER"]

TOLERANCE = NEWTON_RTOL      # Newton stops below TOLERANCE·size (m); see tolerances.py

States = Mapping[str, LinkState]


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.einsum("...i,...i->...", a, b)


@dataclass(frozen=True)
class NewtonResult:
    """q at the solution, the iterations taken, the final residual (m) and convergence."""

    q: np.ndarray
    iterations: int
    residual: float
    converged: bool


class GroupEquations:
    """The pair equations of one group: residual, Jacobian and rate terms, vectorised over
    positions. ``links`` are the group's (unknown) links in column order."""

    def __init__(self, mech: Mechanism, links: tuple[str, ...], pairs: tuple):
        self.mech = mech
        self.links = tuple(links)
        self.pairs = tuple(pairs)
        self.col = {name: 3 * i for i, name in enumerate(self.links)}
        self.size = mech.size
        if 2 * len(self.pairs) != 3 * len(self.links):
            raise ValueError("an Assur group has 3 equations per link: 2 per pair")

    def at(self, i: int) -> "GroupEquations":
        """The equations at position ``i`` of the walk's grid alone (the same for a group; a
        driven group's hold the drive's value there)."""
        return self

    # -- poses -------------------------------------------------------------------------
    def states(self, q: np.ndarray, known: States) -> dict[str, LinkState]:
        """All link states with the group's links put at poses ``q`` (N, 3k)."""
        out = dict(known)
        for name, c in self.col.items():
            out[name] = LinkState(q[:, c + 2], q[:, c:c + 2])
        return out

    def pose(self, states: States) -> np.ndarray:
        """q (N, 3k) of the group's links in ``states``."""
        return np.concatenate([np.column_stack([states[n].origin, states[n].theta]) for n in self.links], axis=1)

    # -- equations -----------------------------------------------------------------------
    def _point_a(self, pair, states: States) -> np.ndarray:
        """A revolute pair's point on its link a (equal to the one on b, at a solution)."""
        return states[pair.a].point(self.mech.links[pair.a].local[pair.point])

    def _geometry(self, pair, states: States):
        if pair.kind == "R":
            loc = self.mech.links
            xa = states[pair.a].point(loc[pair.a].local[pair.point])
            xb = states[pair.b].point(loc[pair.b].local[pair.point])
            return xa, xb
        p = pair.prismatic
        s, g = states[p.slider], states[p.guide]
        return s.point(p.anchor[p.slider]), g.point(p.anchor[p.guide]), g.direction(p.normal)

    def residual(self, states: States) -> np.ndarray:
        """Φ (N, 2·pairs): metres for point equations, radians for angle equations."""
        rows = []
        for pair in self.pairs:
            if pair.kind == "R":
                xa, xb = self._geometry(pair, states)
                rows += [xa - xb]
            else:
                xs, yg, n = self._geometry(pair, states)
                p = pair.prismatic
                d = states[p.slider].theta - states[p.guide].theta
                rows += [np.column_stack([np.arctan2(np.sin(d), np.cos(d)), _dot(xs - yg, n)])]
        return np.concatenate(rows, axis=1)

    def jacobian(self, states: States) -> np.ndarray:
        """A = ∂Φ/∂q (N, 2·pairs, 3k) with respect to the group's poses."""
        n_pos = len(next(iter(states.values())).theta)
        a = np.zeros((n_pos, 2 * len(self.pairs), 3 * len(self.links)))
        for k, pair in enumerate(self.pairs):
            r = 2 * k
            if pair.kind == "R":
                xa = self._point_a(pair, states)
                for link, sign in ((pair.a, 1.0), (pair.b, -1.0)):
                    if link in self.col:
                        c = self.col[link]
                        a[:, r, c] += sign
                        a[:, r + 1, c + 1] += sign
                        a[:, r:r + 2, c + 2] += sign * J(xa - states[link].origin)
                continue
            p = pair.prismatic
            xs, yg, n = self._geometry(pair, states)
            if p.slider in self.col:
                a[:, r, self.col[p.slider] + 2] += 1.0
            if p.guide in self.col:
                a[:, r, self.col[p.guide] + 2] -= 1.0
            self._offset_jacobian(a[:, r + 1], p, states, xs, yg, n)
        return a

    # -- the offset of a slider's point along a direction turning with its guide ---------
    # Φ = (X_s − Y_g)·d_g: a prismatic pair's second equation (d = its normal n) and a
    # cylinder's stroke (d = the guide's direction u, kinematics/drives.py); one set of terms.
    def _offset_jacobian(self, row: np.ndarray, p, states: States, xs: np.ndarray, yg: np.ndarray,
                         d: np.ndarray) -> None:
        """Add ∂Φ/∂q of Φ = (X_s − Y_g)·d into ``row`` (N, 3k), in place."""
        if p.slider in self.col:
            c = self.col[p.slider]
            row[:, c:c + 2] += d
            row[:, c + 2] += _dot(J(xs - states[p.slider].origin), d)
        if p.guide in self.col:
            c = self.col[p.guide]
            row[:, c:c + 2] -= d
            row[:, c + 2] += -_dot(J(yg - states[p.guide].origin), d) + _dot(xs - yg, J(d))

    @staticmethod
    def _offset_rate(p, states: States, xs: np.ndarray, yg: np.ndarray, d: np.ndarray, order: int) -> np.ndarray:
        """Φ̇ (``order`` 1) or Φ̈ (2) of Φ = (X_s − Y_g)·d with the unknown rates of that order
        at zero (N,): Φ̇ = (V_s − V_g)·d + ω_g (X_s − Y_g)·k×d, Φ̈ = (A_s − A_g)·d
        + 2ω_g (V_s − V_g)·k×d + (X_s − Y_g)·(ε_g k×d − ω_g² d)."""
        s, g = states[p.slider], states[p.guide]
        dv = s.velocity(xs) - g.velocity(yg)
        w = g.omega
        if order == 1:
            return _dot(dv, d) + w * _dot(xs - yg, J(d))
        da = s.acceleration(xs) - g.acceleration(yg)
        return _dot(da, d) + 2.0 * w * _dot(dv, J(d)) + _dot(xs - yg, g.epsilon[:, None] * J(d) - (w * w)[:, None] * d)

    def velocity_terms(self, states: States) -> np.ndarray:
        """Φ̇ with the group's rates (v_o, ω) set to zero (N, 2·pairs)."""
        rows = []
        for pair in self.pairs:
            if pair.kind == "R":
                xa = self._point_a(pair, states)
                rows.append(states[pair.a].velocity(xa) - states[pair.b].velocity(xa))
                continue
            p = pair.prismatic
            xs, yg, n = self._geometry(pair, states)
            rows.append(np.column_stack([states[p.slider].omega - states[p.guide].omega,
                                         self._offset_rate(p, states, xs, yg, n, 1)]))
        return np.concatenate(rows, axis=1)

    def acceleration_terms(self, states: States) -> np.ndarray:
        """Φ̈ with the group's (a_o, ε) set to zero, its ω known (N, 2·pairs)."""
        rows = []
        for pair in self.pairs:
            if pair.kind == "R":
                xa = self._point_a(pair, states)
                rows.append(states[pair.a].acceleration(xa) - states[pair.b].acceleration(xa))
                continue
            p = pair.prismatic
            xs, yg, n = self._geometry(pair, states)
            rows.append(np.column_stack([states[p.slider].epsilon - states[p.guide].epsilon,
                                         self._offset_rate(p, states, xs, yg, n, 2)]))
        return np.concatenate(rows, axis=1)

    # -- conditioning --------------------------------------------------------------------
    def _scaled(self, a: np.ndarray) -> np.ndarray:
        """A with angular columns ÷size and angle rows ×size (every entry dimensionless)."""
        a = a.copy()
        a[:, :, 2::3] /= self.size
        return self._scale_rows(a)

    def _scale_rows(self, m: np.ndarray) -> np.ndarray:
        """``m`` with the rows of angle equations (prismatic pairs) ×size, in place."""
        for k, pair in enumerate(self.pairs):
            if pair.kind == "P":
                m[:, 2 * k] *= self.size
        return m

    def scaled_jacobian(self, states: States) -> np.ndarray:
        """A made dimensionless (see :meth:`_scaled`) at every position (N, 2·pairs, 3k): the
        matrix of both rate solves and of the condition figure, which may share it."""
        return self._scaled(self.jacobian(states))

    def condition(self, states: States, a: np.ndarray | None = None) -> np.ndarray:
        """The condition figure at every position (N,): sign(det A) × the polar sine of the
        reduced velocity equations (:func:`~plans.kinematics.figure.reduced_figure`), or, should
        those not be square, σ_min/σ_max of A; ``a``: the scaled Jacobian, when already at hand."""
        if a is None:
            a = self._scaled(self.jacobian(states))
        rows, ties, sliding = self._figure_rows(states, a)
        figure = reduced_figure(np.stack(rows, axis=1), self._turning_sets(ties), [r for r, _ in sliding])
        if figure is None:
            sv = np.linalg.svd(a, compute_uv=False)
            figure = sv[:, -1] / sv[:, 0]
        return np.sign(la.det(a)) * figure

    def _figure_rows(self, states: States, a: np.ndarray) -> tuple[list[np.ndarray], list[tuple[str, str | None]], list]:
        """The rows of the reduced figure (scaled as ``a``'s), the links each angle row turns
        together (None: a known link), and (row, pair) of each prismatic pair's sliding: its
        normal row, then its offset along the guide (whose rate is the sliding)."""
        rows: list[np.ndarray] = []
        ties: list[tuple[str, str | None]] = []
        sliding: list = []
        for k, pair in enumerate(self.pairs):
            if pair.kind == "R":
                rows += [a[:, 2 * k], a[:, 2 * k + 1]]
                continue
            p = pair.prismatic
            ties.append((p.slider, p.guide))
            xs, yg, _ = self._geometry(pair, states)
            along = np.zeros_like(a[:, 0])
            self._offset_jacobian(along, p, states, xs, yg, states[p.guide].direction(p.direction))
            along[:, 2::3] /= self.size
            rows += [a[:, 2 * k + 1], along]
            sliding.append((len(rows) - 1, p))
        return rows, ties, sliding

    def _turning_sets(self, ties: list[tuple[str, str | None]]) -> np.ndarray:
        """(3k, c): a column per set of the group's links that turn together by ``ties`` and
        with no known link, 1 in its links' turning columns."""
        root = {name: name for name in self.links}

        def find(x: str) -> str:
            while root[x] != x:
                x = root[x]
            return x
        held = []
        for pair in ties:
            inside = [x for x in pair if x in self.col]
            if len(inside) == 2:
                root[find(inside[0])] = find(inside[1])
            elif inside:        # turned with a known link (or by the drive)
                held.append(inside[0])
        held_roots = {find(x) for x in held}
        free = list(dict.fromkeys(find(x) for x in self.links if find(x) not in held_roots))
        sets = np.zeros((3 * len(self.links), len(free)))
        for name in self.links:
            if find(name) in free:
                sets[self.col[name] + 2, free.index(find(name))] = 1.0
        return sets

    # -- solves --------------------------------------------------------------------------
    def _solve(self, states: States, rhs: np.ndarray, a: np.ndarray | None = None) -> np.ndarray:
        if a is None:
            a = self._scaled(self.jacobian(states))
        rhs = self._scale_rows(rhs.copy())
        x = la.solve(a, -rhs[..., None])[..., 0]
        x[:, 2::3] /= self.size
        return x

    def velocities(self, states: dict[str, LinkState], a: np.ndarray | None = None) -> None:
        """Solve the group's ω and v_o at every position (in place in ``states``); ``a``: the
        scaled Jacobian at these poses (:meth:`scaled_jacobian`), when already at hand."""
        self._rates(states, 1, a)

    def accelerations(self, states: dict[str, LinkState], a: np.ndarray | None = None) -> None:
        """Solve the group's ε and a_o at every position (in place in ``states``); ``a`` as
        for :meth:`velocities`."""
        self._rates(states, 2, a)

    def _rates(self, states: dict[str, LinkState], order: int, a: np.ndarray | None = None) -> None:
        zero = {**states, **{n: _with_rates(states[n], order) for n in self.links}}
        terms = self.velocity_terms(zero) if order == 1 else self.acceleration_terms(zero)
        x = self._solve(zero, terms, a)
        for name, c in self.col.items():
            s = states[name]
            put = s.with_velocity if order == 1 else s.with_acceleration
            states[name] = put(x[:, c + 2], s.origin, x[:, c:c + 2])

    def newton(self, q: np.ndarray, known: States, *, tol: float = TOLERANCE, maxiter: int = MAX_ITER,
               polish: bool = True) -> NewtonResult:
        """Newton's method from ``q`` (N, 3k) at every position at once, until the largest
        residual is below ``tol``·size; with ``polish``, one more step then takes the
        quadratically converging iteration down to rounding level."""
        q = q.copy()
        limit = tol * self.size
        res = np.inf
        polishing = False
        before: tuple[np.ndarray, float] | None = None
        for it in range(maxiter + 2):
            st = self.states(q, known)
            phi = self._scale_rows(self.residual(st))
            res = float(np.max(np.abs(phi))) if phi.size else 0.0
            if polishing and before is not None and not res <= before[1]:
                # the polish step made things worse (a singular Jacobian: the step is noise);
                # keep the converged position it started from
                return NewtonResult(before[0], it, before[1], True)
            if not np.isfinite(res):
                return NewtonResult(q, it, res, False)
            if polishing or (res <= limit and not polish):
                return NewtonResult(q, it, res, res <= limit)
            if res <= limit:
                polishing = True
                before = (q.copy(), res)
            elif it >= maxiter:
                break
            a = self._scaled(self.jacobian(st))
            try:
                dx = la.solve(a, -phi[..., None])[..., 0]
            except np.linalg.LinAlgError:   # a singular position: converged if the residual says so
                return NewtonResult(q, it, res, res <= limit)
            dx[:, 2::3] /= self.size   # the scaled unknown is size·Δθ
            q = q + dx
        return NewtonResult(q, maxiter, res, False)


def _with_rates(state: LinkState, order: int) -> LinkState:
    """The state with its unknown rates of ``order`` (1: ω, v; 2: ε, a) set to zero."""
    n = len(state.theta)
    if order == 1:
        out = LinkState(state.theta, state.origin, np.zeros(n), np.zeros((n, 2)))
    else:
        out = LinkState(state.theta, state.origin, state.omega, state.v, np.zeros(n), np.zeros((n, 2)))
    if "_cos_sin" in state.__dict__:     # the same θ: its cos θ, sin θ as already computed
        out.seeded(*state._cos_sin)
    return out


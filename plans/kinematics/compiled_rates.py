"""A class III/IV group's rates: :class:`GroupRates` solves its velocities and accelerations at
the requested positions with the compiled Jacobian (and the condition figure from its reduced blocks).
"""

from __future__ import annotations

import numpy as np

from ..model import Mechanism
from .compiled import CompiledGroup, States, _cos_sin
from .generic import GroupEquations, _with_rates
from .state import LinkState, _spin
from .. import linalg as la

__all__ = ["GroupRates"]


class GroupRates:
    """A class III/IV group's velocity and acceleration solves at its solved poses, sharing
    one scaled Jacobian A (the compiled group's, :meth:`CompiledGroup.evaluate`), and its
    condition figure (:meth:`CompiledGroup.condition`); for a group of revolute pairs only, right-hand sides assembled
    from the known links' pin motions without the generic per-pair terms (a group with a
    prismatic pair takes them from :class:`~plans.kinematics.generic.GroupEquations`).

    The same equations as ``GroupEquations.velocities``/``accelerations``, solved as they
    are (``numpy.linalg.solve``, LU with pivoting): the results agree to rounding (the tests
    compare both), and a link at rest comes out at rest exactly, as there. (The block
    solver of the walk, :meth:`CompiledGroup._block_solver`, leaves ~1e-17 of rounding on
    such a link, which the cross-check against the special points, relative to each link's
    own largest value, would report.)"""

    def __init__(self, mech: Mechanism, links: tuple[str, ...], pairs: tuple, states: States):
        self.mech = mech
        self.links = tuple(links)
        self.pairs = tuple(pairs)
        self.states = states
        known = {name: s for name, s in states.items() if name not in self.links}
        self.group = group = CompiledGroup(mech, self.links, self.pairs, known)
        self.size = group.size
        self.col = {name: 3 * L for name, L in group.index.items()}
        n_pos = group.n_pos
        self.q = np.empty((n_pos, group.n))
        for name, c in self.col.items():
            s = states[name]
            self.q[:, c:c + 2] = s.origin
            self.q[:, c + 2] = s.theta
        self.idx = np.arange(n_pos)
        self._a: np.ndarray | None = None
        self.revolute_only = not group.prismatic

    def jacobian(self) -> np.ndarray:
        """The scaled Jacobian A (N, n, n) at the poses (computed once)."""
        if self._a is None:
            self._a = self.group.evaluate(self.q, self.idx)[1]
        return self._a

    def condition(self) -> np.ndarray:
        """The condition figure at the poses (as GroupEquations.condition): from the compiled
        k×k blocks for a group of revolute pairs only, else from the pair equations."""
        figure = self.group.condition(self.q, self.idx)
        if figure is None:
            figure = GroupEquations(self.mech, self.links, self.pairs).condition(self.states)
        return figure

    def _solve(self, rhs: np.ndarray) -> np.ndarray:
        """The group's rates x (N, n) from A·x = −rhs (rhs scaled as A's rows; x unscaled)."""
        x = la.solve(self.jacobian(), -rhs[..., None])[..., 0]
        x[:, 2::3] /= self.size
        return x

    def _known_rows(self, states: States, order: int) -> np.ndarray:
        """Σ ±(velocity, order 1, or acceleration, order 2) of the known links' points at the
        revolute pairs, in the pairs' rows (N, n); prismatic rows 0."""
        out = np.zeros((len(self.idx), self.group.n))
        for r, link, local, sign in self.group.known_pins:
            st = states[link]
            m = _spin_known(st, st.direction(local), order)
            if sign > 0:
                out[:, r:r + 2] += m
            else:
                out[:, r:r + 2] -= m
        return out

    def velocities(self, states: dict[str, LinkState]) -> None:
        """Solve the group's ω and v_o at every position (in place in ``states``)."""
        if self.revolute_only:
            rhs = self._known_rows(states, 1)
        else:
            rhs = self._generic_terms(states, 1)
        x = self._solve(rhs)
        for name, c in self.col.items():
            s = states[name]
            states[name] = s._keep_cos_sin(LinkState(s.theta, s.origin, x[:, c + 2].copy(), _columns(x, c)))

    def accelerations(self, states: dict[str, LinkState]) -> None:
        """Solve the group's ε and a_o at every position (in place in ``states``; the group's
        velocities solved)."""
        if self.revolute_only:
            rhs = self._known_rows(states, 2)
            g = self.group
            w = np.column_stack([states[name].omega for name in self.links])
            w2 = w * w
            th = self.q[:, 2::3]
            c, s = _cos_sin(th)
            # the group's links' centripetal terms: −ω²·R(θ)·local at every pin, with signs
            rhs -= la.matmul(w2 * c, g._mc) + la.matmul(w2 * s, g._ms)
        else:
            rhs = self._generic_terms(states, 2)
        x = self._solve(rhs)
        for name, c in self.col.items():
            s = states[name]
            states[name] = s._keep_cos_sin(LinkState(s.theta, s.origin, s.omega, s.v, x[:, c + 2].copy(),
                                                     _columns(x, c)))

    def _generic_terms(self, states: States, order: int) -> np.ndarray:
        eq = GroupEquations(self.mech, self.links, self.pairs)
        zero = {**states, **{n: _with_rates(states[n], order) for n in self.links}}
        terms = eq.velocity_terms(zero) if order == 1 else eq.acceleration_terms(zero)
        return eq._scale_rows(terms)


def _spin_known(st: LinkState, rel: np.ndarray, order: int) -> np.ndarray:
    """Velocity (order 1) or acceleration (2) of the point of known link ``st`` at ``rel``
    from its origin (N, 2)."""
    if order == 1:
        return _spin(st.v, st.omega, rel)
    w = st.omega
    return _spin(st.a, w, rel, w * w, st.epsilon)


def _columns(x: np.ndarray, c: int) -> np.ndarray:
    """x[:, c:c+2] as a fresh (N, 2) array stored by columns (as the rigid-body relations make them)."""
    out = np.empty((2, len(x))).T
    out[:] = x[:, c:c + 2]
    return out

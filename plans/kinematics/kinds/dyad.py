"""Class II groups (dyads): the five forms in closed form (:mod:`plans.kinematics.groups`).

Positions: every assembly branch at every position at once; the walk keeps the branch the
group has at the sketch (the sign of the assembly determinant cannot change along a walk
that passes no singular position, which :func:`~plans.kinematics.walk.check_crossing`
refuses). Rates: Cramer's rule on the differentiated vector loop; its sin(U1, U2) is the
condition figure.
"""

from __future__ import annotations

import math

import numpy as np

from ...model import Mechanism
from ..groups import SINGULAR_REASON, Candidate, accelerations, candidates, conditioning, velocities
from ..state import LinkState
from ..tolerances import ASSEMBLY_RTOL
from ..walk import Walk, check_crossing, failure
from .base import Rates, Seed, States

__all__ = ["Dyad", "branch_at_sketch"]


class Dyad:
    """The solver of a class II group (:class:`~plans.structure.Group`)."""

    closed_form = True

    def __init__(self, mech: Mechanism, group):
        self.mech = mech
        self.group = group

    def reason(self) -> str:
        g = self.group
        return SINGULAR_REASON[g.form].format(m=g.m, n=g.n)

    def branches(self, states: States, tol: float, branch: int | None = None) -> list[Candidate]:
        """Every assembly branch at every position of ``states`` (only ``branch``, when given)."""
        return candidates(self.group, self.mech, states, tol, branch)

    def sketch_branch(self, options: list[Candidate], sweeps: list[np.ndarray]) -> int:
        """The index of the branch among ``options`` that the walk keeps: the one nearest the sketch."""
        return int(branch_at_sketch(self.mech, self.group.links, options, sweeps)[0])

    def positions(self, states: dict[str, LinkState], walk: Walk) -> None:
        g, mech = self.group, self.mech
        options = self.branches(states, ASSEMBLY_RTOL * mech.size)
        choice = branch_at_sketch(mech, g.links, options, walk.sweeps)
        m_state = _select([o.m for o in options], choice)
        n_state = _select([o.n for o in options], choice)
        valid = np.choose(choice, [o.valid for o in options])
        for sweep in walk.sweeps:
            bad = np.flatnonzero(~valid[sweep])
            if bad.size:
                i = sweep[bad[0]]
                raise failure(mech, g, walk, i, "cannot assemble", options[int(choice[i])].why(i))
        states[g.m], states[g.n] = m_state, n_state
        sin = conditioning(g, mech, states)
        check_crossing(mech, g, self.reason(), sin, walk)

    def condition(self, states: States, values: np.ndarray | None = None, keep: dict | None = None) -> np.ndarray:
        """sin(U1, U2) at every position; ``keep`` receives the geometry it used (the velocity
        step's ``pre``)."""
        return conditioning(self.group, self.mech, states, keep)

    def rates(self, states: dict[str, LinkState], values: np.ndarray, pre: dict | None = None) -> Rates:
        """Solves the velocities with the condition figure (Cramer's rule gives both at once)."""
        sliding, sin = velocities(self.group, self.mech, states, pre)
        return Rates(sin, sliding)

    def velocities(self, states: dict[str, LinkState], rates: Rates) -> None:
        """Nothing left to do: :meth:`rates` solved them."""

    def accelerations(self, states: dict[str, LinkState], rates: Rates) -> None:
        accelerations(self.group, self.mech, states, rates.solve)

    def local_start(self, states: dict[str, LinkState], here: States, x: float) -> Seed:
        """The branch nearest the solved poses ``here`` (origins and turns, as lengths)."""
        g, mech = self.group, self.mech
        options = self.branches(states, ASSEMBLY_RTOL * mech.size)
        cost = [float(np.sum((o.m.origin - here[g.m].origin) ** 2) + np.sum((o.n.origin - here[g.n].origin) ** 2)
                      + mech.size ** 2 * (_turn(o.m.theta - here[g.m].theta) ** 2
                                          + _turn(o.n.theta - here[g.n].theta) ** 2))
                for o in options]
        k = int(np.argmin(cost))
        states[g.m], states[g.n] = options[k].m, options[k].n
        return Seed(np.empty(0), k)

    def local_pose(self, states: dict[str, LinkState], x: float, seed: Seed) -> Seed | None:
        g = self.group
        o = self.branches(states, ASSEMBLY_RTOL * self.mech.size)[seed.branch]
        if not bool(o.valid[0]):
            return None
        states[g.m], states[g.n] = o.m, o.n
        return seed

    def special_points(self, states: States) -> None:
        """A dyad has none."""
        return None


def _turn(d: np.ndarray) -> float:
    return float(np.arctan2(np.sin(d), np.cos(d))[0])


def _select(options: list[LinkState], choice: np.ndarray) -> LinkState:
    """The state that takes, at position i, option ``choice[i]``."""
    theta = np.choose(choice, [o.theta for o in options])
    origin = np.choose(choice[:, None], [o.origin for o in options])
    out = LinkState(theta, origin)
    if all("_cos_sin" in o.__dict__ for o in options):   # as solved (a pose placed from points seeds them)
        out.seeded(*(np.choose(choice, [o._cos_sin[i] for o in options]) for i in (0, 1)))
    return out


def branch_at_sketch(mech: Mechanism, links: tuple[str, str], options: list, sweeps: list[np.ndarray]) -> np.ndarray:
    """Index of the chosen option at every grid position: the one nearest the sketch, kept
    everywhere. A class II group's options are its assembly branches in a fixed order (the
    sign of the assembly determinant: E left or right of D→F, and the like), and that sign
    cannot change along a walk that passes no singular position — which
    :func:`~plans.kinematics.walk.check_crossing` refuses — so no step of the walk needs to
    choose again."""
    n = len(options[0].valid)
    if len(options) == 1:
        return np.zeros(n, dtype=int)
    locals_ = [(name, mech.links[name].local[p], p) for name in links for p in mech.links[name].points]
    size = mech.size
    i = int(sweeps[0][0])
    sketch = [float(v) for _, _, p in locals_ for v in mech.sketch[p]] + [size, 0.0, size, 0.0]

    def signature(o) -> list[float]:
        # the links' points and orientations at the sketch: branches differ in one or the other
        # (in floats: one position, where numpy's per-call cost would dominate)
        out, turn = [], []
        for name, state in zip(links, (o.m, o.n)):
            c, s = state._cos_sin
            c, s = float(c[i]), float(s[i])
            ox, oy = float(state.origin[i, 0]), float(state.origin[i, 1])
            for link, x, _ in locals_:
                if link == name:
                    x0, y0 = float(x[0]), float(x[1])
                    out += [ox + (c * x0 - s * y0), oy + (s * x0 + c * y0)]
            theta = float(state.theta[i])
            turn += [size * math.cos(theta), size * math.sin(theta)]
        return out + turn

    # an invalid option is never preferred over a valid one
    cost = [sum((a - b) ** 2 for a, b in zip(signature(o), sketch)) + (0.0 if o.valid[i] else math.inf)
            for o in options]
    return np.full(n, int(np.argmin(cost)), dtype=int)

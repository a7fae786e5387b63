"""The original mechanism of a drive inside the chain (a coupler's angle, a hydraulic
cylinder's stroke): its links and the drive's equation solved together by Newton's method
(:mod:`plans.kinematics.drives`), step by step along the walk."""

from __future__ import annotations

import numpy as np

from ...model import Mechanism
from ..continuation import newton_walk
from ..drives import DrivenEquations
from ..state import LinkState
from ..walk import Walk, check_crossing
from .base import Rates, Seed, States

__all__ = ["Driven"]


class Driven:
    """The solver of a :class:`~plans.structure.DrivenGroup`; its equations hold the drive's
    value, so each call takes the drive ``values`` it is solved at."""

    closed_form = False

    def __init__(self, mech: Mechanism, group):
        self.mech = mech
        self.group = group

    def reason(self) -> str:
        return ("the original mechanism's equations (its pairs and the drive's) are singular: the drive "
                "cannot move its links uniquely here (a dead position of the drive)")

    def _equations(self, values: np.ndarray) -> DrivenEquations:
        return DrivenEquations(self.mech, self.group, values)

    def positions(self, states: dict[str, LinkState], walk: Walk) -> None:
        eq = self._equations(walk.grid)
        states.update(newton_walk(self.mech, self.group, eq, states, walk))
        check_crossing(self.mech, self.group, self.reason(), eq.condition(states), walk)

    def condition(self, states: States, values: np.ndarray) -> np.ndarray:
        """sign(det A)·σ_min/σ_max of the scaled Jacobian of the pairs' and the drive's equations."""
        return self._equations(values).condition(states)

    def rates(self, states: dict[str, LinkState], values: np.ndarray, pre: dict | None = None) -> Rates:
        eq = self._equations(values)
        a = eq.scaled_jacobian(states)
        return Rates(eq.condition(states, a), (eq, a))

    def velocities(self, states: dict[str, LinkState], rates: Rates) -> None:
        eq, a = rates.solve
        eq.velocities(states, a)

    def accelerations(self, states: dict[str, LinkState], rates: Rates) -> None:
        eq, a = rates.solve
        eq.accelerations(states, a)

    def local_start(self, states: dict[str, LinkState], here: States, x: float) -> Seed:
        for name in self.group.links:
            states[name] = LinkState(here[name].theta, here[name].origin)
        return Seed(self._equations(np.array([x])).pose(here)[0])

    def local_pose(self, states: dict[str, LinkState], x: float, seed: Seed) -> Seed | None:
        eq = self._equations(np.array([x]))      # the drive's value x enters its equations
        result = eq.newton(seed.pose[None, :], states)
        if not result.converged:
            return None
        states.update(eq.states(result.q, {}))
        return Seed(result.q[0])

    def special_points(self, states: States) -> None:
        """The original mechanism has none."""
        return None

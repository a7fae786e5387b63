"""Class III and IV groups: four links and six pairs solved together by Newton's method
(:mod:`plans.kinematics.compiled`), continued along the walk; rates from one compiled Jacobian.

A class III group whose rods all have an axis also has special points (Assur's points, where
two rods' axes meet): its condition figure is then the determinant of the axes' line
coordinates (:func:`plans.kinematics.special.condition`), which vanishes exactly when the
three axes meet in one point. Any other group's is the sine of its velocity equations reduced
to its turning and sliding rates (:mod:`plans.kinematics.figure`), as a class II group's is.
"""

from __future__ import annotations

from functools import cached_property

import numpy as np

from ...model import Mechanism
from .. import special
from ..compiled import CompiledGroup
from ..compiled_rates import GroupRates
from ..continuation import continue_group
from ..generic import GroupEquations
from ..state import LinkState
from ..walk import Walk, check_crossing
from .base import Rates, Seed, States

__all__ = ["Complex"]


class Complex:
    """The solver of a class III/IV group (:class:`~plans.structure.ComplexGroup`)."""

    closed_form = False

    def __init__(self, mech: Mechanism, group):
        self.mech = mech
        self.group = group
        self.axes = special.supports(group)      # a class III group with special points

    @cached_property
    def eq(self) -> GroupEquations:
        """The group's pair equations."""
        return GroupEquations(self.mech, self.group.links, self.group.pairs)

    def reason(self) -> str:
        g = self.group
        if g.base is not None:
            rods = ", ".join(r.link for r in g.rods)
            return (f"the axes of rods {rods} meet in one point (the special points coincide, their construction "
                    "lines are parallel): the group's velocity equations have no unique solution")
        return "the group's velocity equations (its Jacobian) are singular: the closed contour is at a dead position"

    def positions(self, states: dict[str, LinkState], walk: Walk) -> None:
        poses, compiled = continue_group(self.mech, self.group, self.eq, states, walk)
        states.update(poses)
        check_crossing(self.mech, self.group, self.reason(), self._walk_condition(states, compiled), walk)

    def _walk_condition(self, states: States, group: CompiledGroup | None) -> np.ndarray:
        """The condition figure along the walk, for the crossing check: the special points'
        (cheap), else the compiled group's (the walk's own, when at hand)."""
        if self.axes:
            return special.condition(self.group, self.mech, states)
        if group is None:     # the walk's own compiled group (the same known links), when at hand
            eq = self.eq
            known = {name: s for name, s in states.items() if name not in eq.col}
            group = CompiledGroup(self.mech, eq.links, eq.pairs, known)
        return self._figure(states, group)

    def _figure(self, states: States, group: CompiledGroup) -> np.ndarray:
        """The figure of :mod:`plans.kinematics.figure`: from the compiled blocks for a group of
        revolute pairs only, else from the pair equations."""
        figure = group.condition(self.eq.pose(states), np.arange(group.n_pos))
        return self.eq.condition(states) if figure is None else figure

    def condition(self, states: States, values: np.ndarray | None = None) -> np.ndarray:
        """The rods' axes for a class III group, else the generalised sine of the group's
        velocity equations (:mod:`plans.kinematics.figure`; ±, 0 at a singular position)."""
        if self.axes:
            return special.condition(self.group, self.mech, states)
        eq = self.eq
        known = {name: s for name, s in states.items() if name not in eq.col}
        return self._figure(states, CompiledGroup(self.mech, eq.links, eq.pairs, known))

    def rates(self, states: dict[str, LinkState], values: np.ndarray, pre: dict | None = None) -> Rates:
        g = self.group
        rates = GroupRates(self.mech, g.links, g.pairs, states)
        return Rates(special.condition(g, self.mech, states) if self.axes else rates.condition(), rates)

    def velocities(self, states: dict[str, LinkState], rates: Rates) -> None:
        rates.solve.velocities(states)

    def accelerations(self, states: dict[str, LinkState], rates: Rates) -> None:
        rates.solve.accelerations(states)

    def local_start(self, states: dict[str, LinkState], here: States, x: float) -> Seed:
        for name in self.group.links:
            states[name] = LinkState(here[name].theta, here[name].origin)
        return Seed(self.eq.pose(here)[0])

    def local_pose(self, states: dict[str, LinkState], x: float, seed: Seed) -> Seed | None:
        eq = self.eq
        known = {n: s for n, s in states.items() if n not in eq.col}
        q, _, conv, _ = CompiledGroup(self.mech, eq.links, eq.pairs, known).newton(seed.pose[None, :], np.array([0]))
        if not conv[0]:
            return None
        for name, c in eq.col.items():
            states[name] = LinkState(q[:, c + 2], q[:, c:c + 2])
        return Seed(q[0])

    def special_points(self, states: States) -> tuple[special.SpecialPoint, ...] | None:
        return special.special_points(self.group, self.mech, states) if self.axes else None

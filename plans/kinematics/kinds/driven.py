"""The original mechanism of a drive inside the chain (a coupler's angle, a hydraulic
cylinder's stroke): its links and the drive's equation solved together by Newton's method
(:mod:`plans.kinematics.drives`), step by step along the walk."""

from __future__ import annotations

import numpy as np

from ...model import Mechanism
from ...scene import DriveKind
from ..continuation import newton_walk
from ..drives import DrivenEquations
from ..state import LinkState
from ..walk import Walk, check_crossing, limit_reached
from .base import Rates, Seed, States
from ... import linalg as la

__all__ = ["Driven", "LIMIT_HALVINGS", "LIMIT_MOVE", "LIMIT_CONDITION"]

#: Most halvings of the step in which a walk failed, to find the drive's limit position: a
#: step (1° or 1/200 of the size) halved 60 times is below rounding of the drive's value.
LIMIT_HALVINGS = 60
#: A halving whose pose moves more than this × size from the last one has left the walk's
#: branch (Newton found another assembly): it counts as beyond the limit.
LIMIT_MOVE = 0.25
#: At the limit so found the original mechanism's condition figure must be at most this for
#: the failure to be the drive's limit position (at a fold it falls like the square root of
#: the distance: ~1e-6 at a rounding-level distance); otherwise the general message stands.
LIMIT_CONDITION = 1e-3


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
        known = {name: s for name, s in states.items() if name not in eq.col}

        def stop(i: int, prev: int, q: np.ndarray):
            return self._limit(walk, i, prev, q, {name: s.take(np.array([prev])) for name, s in known.items()})

        states.update(newton_walk(self.mech, self.group, eq, states, walk, stop))
        check_crossing(self.mech, self.group, self.reason(), eq.condition(states), walk)

    def _limit(self, walk: Walk, i: int, prev: int, q: np.ndarray, known: States):
        """The error of a walk that fails at step i, after step ``prev`` (pose ``q``), because
        the drive has reached a limit position between the two (or None, when it has not):
        the limit bisected to rounding level (Newton converges on the sketch's side of it, from
        the pose last found, and finds no position beyond), and there the original mechanism's
        equations are singular (|condition| ≤ LIMIT_CONDITION)."""
        lo, hi = float(walk.grid[prev]), float(walk.grid[i])
        size = self.mech.size
        for _ in range(LIMIT_HALVINGS):
            mid = 0.5 * (lo + hi)
            if mid in (lo, hi):
                break
            result = self._equations(np.array([mid])).newton(q[None, :], known)
            moved = np.max(np.abs(result.q[0] - q) * np.tile([1.0, 1.0, size], len(q) // 3))
            if result.converged and moved <= LIMIT_MOVE * size:
                lo, q = mid, result.q[0]
            else:
                hi = mid
        eq = self._equations(np.array([lo]))
        at = eq.states(q[None, :], known)
        if not abs(float(eq.condition(at)[0])) <= LIMIT_CONDITION:
            return None
        return limit_reached(self.mech, self.group, walk, i, lo, self._stroke_length(at))

    def _stroke_length(self, states: States) -> str:
        """A cylinder's length there, as the distance between its pins (the cylinder's pin and the
        rod's, the points each shares with another link), when each has one; else nothing."""
        d = self.mech.drive
        if d.kind != DriveKind.CYLINDER:
            return ""
        pins = []
        for link, other in ((d.guide.guide, d.link), (d.link, d.guide.guide)):
            own = [p for p in self.mech.links[link].points
                   if any(p in l.points for name, l in self.mech.links.items() if name not in (link, other))]
            if len(own) != 1:
                return ""
            pins.append((link, own[0]))
        (ga, pa), (gb, pb) = pins
        length = la.norm(states[ga].point(self.mech.links[ga].local[pa])[0]
                                - states[gb].point(self.mech.links[gb].local[pb])[0])
        return f"; the cylinder's length {pa}{pb} = {float(length):g} m"

    def condition(self, states: States, values: np.ndarray) -> np.ndarray:
        """The generalised sine of the pairs' and the drive's velocity equations reduced to the
        links' turning and sliding rates (:mod:`plans.kinematics.figure`), with det A's sign."""
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

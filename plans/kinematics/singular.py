"""How far a solved position is from its group's singular position: a local search.

:func:`distance` answers the near-singular warning's question — how many degrees (metres)
of drive lie between position i of a solved :class:`~plans.kinematics.motion.Motion` and the
nearest singular (limit or crossing) position of one group — without analysing the whole
mechanism again for every trial value. Only the groups up to the one asked about are
posed, and only at the trial drive values, continued from the pose at position i:

* class II groups take the closed-form assembly branch the motion took at i;
* class III/IV groups are continued from their pose at i by Newton's method in steps of at
  most the walk's step (1° or 1/200 of the mechanism's size), each trial continuing from
  the nearest value already posed.

The search is the secant method on the squared condition figure c² (c ~ √δ at a limit
position, c ~ δ where branches cross); a trial past a limit position (the group no longer
assembles) or past a sign change of c is first retried just short of itself (SHORT_OF_ROOT),
then stepped back towards the last good value.
"""

from __future__ import annotations

import numpy as np

from .kinds import GroupSolver, Seed, chain
from .state import LinkState, Solution
from .walk import drive_states, step

__all__ = ["distance", "LocalPoser", "FIRST_SHORTENINGS", "SHORT_OF_ROOT"]

#: How often the search's first step (0.05° or 1e-4 × size) is quartered when neither side can
#: be posed: a few hundredths of a degree from a limit position (where the near-singular warning
#: begins) a step of 0.05° either passes the limit or lands on the other branch (the pose moves
#: like the square root of the distance there); 8 quarterings reach 1e-6°.
FIRST_SHORTENINGS = 9
#: A secant root that lands past a limit position (c² ≈ k·(L − x) + O((L − x)²): the root lies
#: past L by O(d²) when the secant's points are d away) is retried this fraction of its step short
#: of it: posable while that excess is under 1e-3·d, and then 1e-3·d from L, so each such step
#: takes ~three digits off the distance (halving back, the fallback, takes one bit).
SHORT_OF_ROOT = 1e-3


class LocalPoser:
    """Poses of the links of the groups up to ``group`` at drive values near position i."""

    def __init__(self, motion: Solution, group: str, i: int):
        self.mech = mech = motion.mechanism
        solvers = chain(mech, motion.structure)
        last = next(k for k, s in enumerate(solvers) if s.group.name == group)
        self.solvers: list[GroupSolver] = solvers[:last + 1]
        self.target = self.solvers[-1]
        self.step = step(mech)
        x0 = float(motion.values[i])
        here = {name: s.take(np.array([i])) for name, s in motion.links.items()}
        # each group's seed at i: a class II group's branch taken there, the others' poses
        states = self._drive(x0)
        seeds = {s.group.name: s.local_start(states, here, x0) for s in self.solvers}
        self.cache: list[tuple[float, dict[str, Seed], dict[str, LinkState]]] = [(x0, seeds, states)]
        self.sign = np.sign(self._condition(states, x0))

    def _drive(self, x: float) -> dict[str, LinkState]:
        return drive_states(self.mech, np.array([x]))

    def _condition(self, states, x: float) -> float:
        return float(self.target.condition(states, np.array([x]))[0])

    def _pose_at(self, x: float, start: dict[str, Seed]):
        """All states at x, each group continued from its seed in ``start`` (None when a group
        does not assemble)."""
        states = self._drive(x)
        seeds = {}
        for s in self.solvers:
            seed = s.local_pose(states, x, start[s.group.name])
            if seed is None:
                return None
            seeds[s.group.name] = seed
        return seeds, states

    def _unit(self, n: int) -> np.ndarray:
        """Metres per unit of each of a pose vector's n entries (x_o, y_o, θ per link): 1 for
        coordinates, the mechanism's size for angles, so that moves compare as lengths."""
        return np.tile([1.0, 1.0, self.mech.size], n // 3)

    def condition(self, x: float) -> float | None:
        """The target group's condition figure at drive value x, or None when x cannot be
        reached from position i without the group falling apart or passing a singular
        position."""
        x_near, pose, states = min(self.cache, key=lambda c: abs(c[0] - x))
        n_steps = max(1, int(np.ceil(abs(x - x_near) / self.step - 1e-9)))
        prev = pose
        prev_x = x_near
        for k in range(1, n_steps + 1):
            xk = x_near + (x - x_near) * k / n_steps
            got = self._pose_at(xk, prev)
            if got is None:
                return None
            moved = max((np.max(np.abs(got[0][n].pose - p.pose) * self._unit(len(p.pose)))
                         for n, p in prev.items() if p.pose.size), default=0.0)
            if moved > 0.05 * self.mech.size and moved > 0.05 * self.mech.size * abs(xk - prev_x) / self.step:
                return None              # the branch jumped
            prev, prev_x, states = got[0], xk, got[1]
            c = self._condition(states, xk)
            if np.sign(c) != self.sign or not np.isfinite(c):
                return None
            self.cache.append((xk, prev, states))
        return self._condition(states, prev_x)


def distance(motion: Solution, group: str, i: int) -> float | None:
    """How far the drive is from the singular position of ``group`` nearest position ``i``
    of ``motion`` (degrees for a crank, metres for a slider), or None when none is found
    nearby. Secant steps on the squared condition figure c², which falls to zero linearly
    at a limit position and quadratically where branches cross; a step that lands past a
    limit position (or past c's sign change) is halved back towards the last good value; the
    first step is shortened (FIRST_SHORTENINGS) while neither side of position i can be posed."""
    mech = motion.mechanism
    h = 0.05 if mech.drive.kind.angular else 1e-4 * mech.size
    poser = LocalPoser(motion, group, i)

    def f(x: float) -> float | None:
        c = poser.condition(x)
        return None if c is None else c * c

    start = float(motion.values[i])
    x0, f0 = start, float(motion.sines[group][i]) ** 2
    x1, f1 = start, None
    for _ in range(FIRST_SHORTENINGS):
        for x1 in (start + h, start - h):
            f1 = f(x1)
            if f1 is not None:
                break
        if f1 is not None:
            break
        h /= 4.0
    for _ in range(16):
        if f1 is None or f1 == f0:
            return None
        x2 = x1 - f1 * (x1 - x0) / (f1 - f0)
        if abs(x2 - start) > 20.0 * h + 10.0 * abs(x1 - start):
            return None
        f2 = f(x2)
        if f2 is None:      # past a limit position, where c² is nearly linear: the root is just short
            x2 = x1 + (1.0 - SHORT_OF_ROOT) * (x2 - x1)
            f2 = f(x2)
        tries = 0
        while f2 is None and tries < 30:      # past a limit position: step back towards x1
            x2 = 0.5 * (x1 + x2)
            f2, tries = f(x2), tries + 1
        if f2 is None:
            return None
        if abs(x2 - x1) < 1e-6 * h:
            return abs(x2 - start)
        x0, f0, x1, f1 = x1, f1, x2, f2
    return abs(x1 - start)

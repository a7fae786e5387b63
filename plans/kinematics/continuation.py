"""Poses of a group solved by Newton's method (class III/IV groups, a drive inside the chain),
continued along the walk from the sketch, where every pose is the identity.

Two ways: the fast continuation of :mod:`plans.kinematics.compiled` (coarse adaptive steps,
then batched Newton at every grid position, then the walk's acceptance tests), and the
step-by-step walk (:func:`newton_walk`: Newton at every step from the previous one, with a
linear predictor), which is also the one that reports a failure. A pose vector holds
(x_o, y_o, θ) per link, in the order of the group's equations.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from ..errors import AssemblyError
from ..model import Mechanism
from .compiled import CompiledGroup
from .compiled_walk import walk as compiled_walk
from .generic import GroupEquations
from .state import LinkState
from .tolerances import JUMP_RATIO
from .walk import Walk, failure, step
from .. import linalg as la

__all__ = ["continue_group", "fast_walk", "newton_walk", "Stop"]

#: What a walk that fails at step i after step ``prev`` (its pose q) reports instead of the
#: general message, or None: ``stop(i, prev, q)``.
Stop = Callable[[int, int, np.ndarray], "AssemblyError | None"]


def continue_group(mech: Mechanism, g, eq: GroupEquations, states: dict[str, LinkState], walk: Walk
                   ) -> tuple[dict[str, LinkState], CompiledGroup]:
    """Poses of a class III/IV group along the walk (and its compiled equations): the fast
    continuation, or, when that is not sure of every position, the step-by-step walk, which
    also reports any failure."""
    q, group = fast_walk(mech, eq, states, walk)
    if q is None:
        return newton_walk(mech, g, eq, states, walk), group
    return {name: LinkState(q[:, c + 2], q[:, c:c + 2]) for name, c in eq.col.items()}, group


def fast_walk(mech: Mechanism, eq: GroupEquations, states: dict[str, LinkState], walk: Walk
              ) -> tuple[np.ndarray | None, CompiledGroup]:
    """The group's poses (len(grid), 3k) by :func:`plans.kinematics.compiled_walk.walk`, or None,
    and its compiled equations."""
    grid, sweeps = walk.grid, walk.sweeps
    known = {name: s for name, s in states.items() if name not in eq.col}
    group = CompiledGroup(mech, eq.links, eq.pairs, known)
    first = np.array([sweeps[0][0]])
    q0, _, conv, _ = group.newton(np.zeros((1, group.n)), first)
    if not conv[0]:
        return None, group
    q = np.empty((len(grid), group.n))
    q[first[0]] = q0[0]
    h = step(mech)
    for sweep in sweeps:
        part = compiled_walk(group, sweep, grid[sweep], q[sweep[0]], h, JUMP_RATIO)
        if part is None:
            return None, group
        q[sweep] = part
    return q, group


def newton_walk(mech: Mechanism, g, eq: GroupEquations, states: dict[str, LinkState], walk: Walk,
                stop: Stop | None = None) -> dict[str, LinkState]:
    """Poses of group ``g`` (its equations ``eq``) along the walk: Newton at every step from the
    previous step (linear predictor), starting at the sketch, where every pose is the identity.
    Where a step fails, ``stop`` (when given) may say why instead of the general message: it
    is called with the failing step's index, the step before and its pose."""
    grid = walk.grid
    q = np.zeros((len(grid), 3 * len(eq.links)))
    done = np.zeros(len(grid), dtype=bool)
    cols = [c for c in range(q.shape[1]) if c % 3 != 2]

    def known(i: int) -> dict[str, LinkState]:
        return {name: s.take(np.array([i])) for name, s in states.items() if name not in eq.col}

    for sweep in walk.sweeps:
        prev = prev2 = None
        for i in sweep:
            if done[i]:
                prev2, prev = prev, i
                continue
            guesses = [q[prev]] if prev is not None else [q[i]]
            if prev2 is not None:
                guesses.insert(0, 2.0 * q[prev] - q[prev2])
            result = None
            for guess in guesses:
                result = eq.at(i).newton(guess[None, :], known(i))
                if result.converged:
                    break
            if not result.converged:
                raise _why(stop, i, prev, q) or failure(
                    mech, g, walk, i, "cannot assemble: Newton's method finds no position of the group's "
                    f"links (residual {result.residual:.1e} m), the group falls apart there")
            q[i] = result.q[0]
            if prev is not None:
                moved = np.max(np.abs(q[i, cols] - q[prev, cols]))
                # the step before, for a step as long as this one (a requested value makes a
                # short step in the grid), or for the first step its linear prediction
                before = np.max(np.abs(q[prev, cols] - q[prev2, cols])) \
                    * abs(grid[i] - grid[prev]) / abs(grid[prev] - grid[prev2]) if prev2 is not None else \
                    _predicted_move(eq.at(i), q[prev], known(i), cols)
                if moved > 0.01 * mech.size and moved > JUMP_RATIO * before:
                    raise _why(stop, i, prev, q) or failure(
                        mech, g, walk, i, "the assembly branch would jump between neighbouring steps (a limit "
                        "position or a singular position lies there)")
            done[i] = True
            prev2, prev = prev, i
    return {name: LinkState(q[:, c + 2], q[:, c:c + 2]) for name, c in eq.col.items()}


def _why(stop: Stop | None, i: int, prev: int | None, q: np.ndarray) -> AssemblyError | None:
    """``stop``'s error for a walk failing at step i after step ``prev`` (None: the general one)."""
    return None if stop is None or prev is None else stop(i, prev, q[prev].copy())


def _predicted_move(eq: GroupEquations, q: np.ndarray, known: dict[str, LinkState], cols: list[int]) -> float:
    """How far (largest coordinate, m) a step from pose ``q`` to the position of ``known``
    moves the group's origins by the linear prediction (one Newton step): the yardstick of a
    walk's first step, which has no step before it."""
    st = eq.states(q[None, :], known)
    try:
        dx = la.solve(eq.scaled_jacobian(st), -eq._scale_rows(eq.residual(st))[..., None])[0, :, 0]
    except np.linalg.LinAlgError:
        return 0.0
    return float(np.max(np.abs(dx[cols])))

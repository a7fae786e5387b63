"""The walk from the sketch: the drive's grid of steps, the poses of the frame and the driving
link along it, and the checks every kind of group makes on the way.

Positions are continued from the sketch: the drive is walked from its sketch value to every
requested value in steps of at most 1° (a crank, ``STEP_DEG``) or 1/200 of the mechanism's
size (a slider), and each group keeps the assembly branch it has at the sketch. A group that
falls apart, or whose condition figure changes sign (a singular position) before a requested
value, stops the walk with an :class:`~plans.errors.AssemblyError` naming the group and the
value. This module knows the drive, the grid and the error messages; it knows no kind of group
(each kind's solver, :mod:`plans.kinematics.kinds`, calls it).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import AssemblyError
from ..model import Mechanism
from ..scene import FRAME, LINEAR_STEPS_PER_SIZE, STEP_DEG, DriveKind   # the walk's steps, bounded by the scene
from .state import LinkState, rotate
from .tolerances import SINGULAR_SIN
from .. import linalg as la

__all__ = ["Walk", "walk_to", "step", "start", "drive_states", "set_drive_rates", "check_crossing", "failure",
           "limit_reached", "group_label", "fmt", "requested_beyond"]


@dataclass(frozen=True)
class Walk:
    """The continuation grid: its drive ``values`` (degrees or metres), its ``sweeps`` (index
    paths from the start, ``grid[0]``: up, then down), the ``requested`` values and the index
    of each in the grid (``index``)."""

    grid: np.ndarray
    sweeps: list[np.ndarray]
    requested: np.ndarray
    index: np.ndarray


def step(mech: Mechanism) -> float:
    """The walk's step: 1° for an angular drive, 1/200 of the mechanism's size (m) for a linear one."""
    return STEP_DEG if mech.drive.kind.angular else mech.size / LINEAR_STEPS_PER_SIZE


def start(mech: Mechanism, values: np.ndarray) -> float:
    """The walk's first value: a crank's sketch angle moved by whole turns towards the values'
    median, a slider's sketch position."""
    first = mech.drive.sketch_value
    if mech.drive.kind.angular:
        # round() is monotonic: when the extremes round alike, so does the median (no sort needed)
        low, high = np.round((np.array([values.min(), values.max()]) - first) / 360.0)
        turns = low if low == high else np.round((np.median(values) - first) / 360.0)
        first += 360.0 * turns
    return first


def walk_to(mech: Mechanism, values: np.ndarray, first: float | None = None) -> Walk:
    """The walk to ``values``. A crank's walk starts at its sketch angle moved by whole turns
    towards the values' median, unless ``first`` (such an angle) is given."""
    if mech.drive.kind.angular:
        if first is None:
            first = start(mech, values)
        h = STEP_DEG
    else:
        first = mech.drive.sketch_value
        h = mech.size / LINEAR_STEPS_PER_SIZE
    up = np.unique(np.concatenate([np.arange(first, values.max(), h), values[values >= first]]))
    down = np.unique(np.concatenate([np.arange(first, values.min(), -h), values[values <= first]]))[::-1]
    up = up[up > first]
    down = down[down < first]
    grid = np.concatenate([[first], up, down])
    sweeps = [np.arange(0, 1 + len(up)), np.concatenate([[0], np.arange(1 + len(up), len(grid))])]
    order = np.argsort(grid, kind="stable")          # the grid's values are distinct
    index = order[np.searchsorted(grid[order], values)]
    return Walk(grid, sweeps, values, index)


def drive_states(mech: Mechanism, values: np.ndarray) -> dict[str, LinkState]:
    """Poses of the frame and the driving link at drive ``values`` (the frame alone for a drive
    inside the chain: its link is solved with the original mechanism's)."""
    n = len(values)
    zero = np.zeros(n)
    states = {FRAME: LinkState(zero, np.zeros((n, 2)), zero, np.zeros((n, 2)), zero, np.zeros((n, 2))
                               ).seeded(np.ones(n), zero)}
    d = mech.drive
    local = mech.links[d.link].local
    if d.kind == DriveKind.ROTARY:
        pivot = mech.links[FRAME].local[d.pivot]
        arm = local[d.tip] - local[d.pivot]
        theta = np.radians(values) - np.arctan2(arm[1], arm[0])
        states[d.link] = LinkState(theta, pivot - rotate(local[d.pivot], theta))
    elif d.kind == DriveKind.LINEAR:
        g = d.guide
        across = g.normal * float(la.dot(g.anchor[FRAME] - g.anchor[d.link], g.normal))
        states[d.link] = LinkState(zero.copy(), across + values[:, None] * g.direction)
    return states


def set_drive_rates(mech: Mechanism, states: dict[str, LinkState], values: np.ndarray) -> None:
    """The driving link's ω, ε (a crank) or v, a (a slider) at every position, in ``states``."""
    d = mech.drive
    n = len(values)
    if d.link not in states:
        return      # a drive inside the chain: its rates enter the original mechanism's equations
    s = states[d.link]
    if d.kind == DriveKind.ROTARY:
        pivot = np.broadcast_to(mech.links[FRAME].local[d.pivot], (n, 2))
        s = s.with_velocity(np.full(n, d.speed), pivot, None, own=True)       # the pivot is still
        s = s.with_acceleration(np.full(n, d.rate), pivot, None, own=True)
    elif d.kind == DriveKind.LINEAR:
        u = d.guide.direction
        s = s.with_velocity(np.zeros(n), s.origin, np.broadcast_to(d.speed * u, (n, 2)).copy())
        s = s.with_acceleration(np.zeros(n), s.origin, np.broadcast_to(d.rate * u, (n, 2)).copy())
    states[d.link] = s


def check_crossing(mech: Mechanism, g, reason: str, sin: np.ndarray, walk: Walk) -> None:
    """Refuse to continue through a singular position of group ``g`` (``reason``: why it has
    no unique solution there): where its condition figure ``sin`` changes sign between two
    steps of a sweep (and a requested value lies beyond), the branch beyond is ambiguous."""
    grid = walk.grid
    for sweep in walk.sweeps:
        s = sin[sweep]
        flips = np.flatnonzero((np.sign(s[:-1]) * np.sign(s[1:]) < 0) | (np.abs(s[:-1]) < SINGULAR_SIN))
        if not flips.size:
            continue
        a, b = grid[sweep[flips[0]]], grid[sweep[flips[0] + 1]]
        target = requested_beyond(walk.requested, b, b - a)
        if target is not None:
            turns = _turns(mech, walk)
            raise AssemblyError(
                f"the walk from the sketch passes a singular position between {fmt(mech, a - turns)} and "
                f"{fmt(mech, b - turns)} ({reason}); positions beyond it cannot be reached without "
                "ambiguity — request positions on the sketch's side or redraw the sketch there",
                group=group_label(g), angle=fmt(mech, target), at=float(b))


def failure(mech: Mechanism, g, walk: Walk, i: int, why: str, detail: str = "") -> AssemblyError:
    """The error of group ``g`` failing at grid position ``i`` for reason ``why``, reported at
    the requested value nearest beyond it (and where the walk failed, when that differs).
    ``detail`` is what was measured at position ``i`` (``|AC| = 0.4 m, but …``): it is said
    of the value where the walk failed, never of the requested one when they differ
    (``at 170°: cannot assemble (the walk from the sketch at 90° fails at 145°): at 145°,
    |AC| = …``)."""
    grid = walk.grid
    sweep = next(sw for sw in walk.sweeps if i in sw)
    target = requested_beyond(walk.requested, grid[i], grid[sweep[-1]] - grid[0])
    target = grid[i] if target is None else target
    turns = _turns(mech, walk)
    failed = fmt(mech, grid[i] - turns)
    where = "" if grid[i] == target else \
        f" (the walk from the sketch at {fmt(mech, grid[0] - turns)} fails at {failed})"
    told = "" if not detail else f": {detail}" if grid[i] == target else f": at {failed}, {detail}"
    return AssemblyError(f"{why}{where}{told}; check the lengths or the requested positions",
                         group=group_label(g), angle=fmt(mech, target), at=float(grid[i]))


def _turns(mech: Mechanism, walk: Walk) -> float:
    """The whole turns (degrees) a crank's walk starts away from the sketch (0 for a linear
    drive): messages print the walk's angles in the sketch's own turn, as the user drew it
    (the walk from 90°, not from 450°, fails at 7°)."""
    if not mech.drive.kind.angular:
        return 0.0
    return 360.0 * round((float(walk.grid[0]) - mech.drive.sketch_value) / 360.0)


def limit_reached(mech: Mechanism, g, walk: Walk, i: int, limit: float, detail: str = "") -> AssemblyError:
    """The error of a drive inside the chain (group ``g``, its original mechanism) whose walk
    fails at grid position i because the drive has reached a limit position at drive value
    ``limit`` (a dead position of the drive: the coupler's angle or the cylinder's stroke is
    extreme there); ``detail`` adds what else the user measures there (the cylinder's length)."""
    grid = walk.grid
    sweep = next(sw for sw in walk.sweeps if i in sw)
    target = requested_beyond(walk.requested, grid[i], grid[sweep[-1]] - grid[0])
    target = grid[i] if target is None else target
    turns = _turns(mech, walk)
    what = f"link {mech.drive.link}'s angle" if mech.drive.kind.angular else "the stroke from the sketch"
    return AssemblyError(
        f"the drive has reached a limit position at {fmt(mech, limit - turns)} ({what}{detail}): the original "
        "mechanism is at a dead position there and its links cannot follow the drive further from the sketch "
        f"({fmt(mech, grid[0] - turns)}); request positions on the sketch's side of the limit",
        group=group_label(g), angle=fmt(mech, target), at=float(grid[i]))


def group_label(g) -> str:
    """How messages name a group: ``group II(2-3) (RRR)``."""
    return f"group {g.name} ({g.form})"


def fmt(mech: Mechanism, value: float) -> str:
    """A drive value as messages print it: ``30°`` or ``0.02 m``."""
    return f"{value:g}°" if mech.drive.kind.angular else f"{value:g} m"


def requested_beyond(values: np.ndarray, at: float, direction: float) -> float | None:
    """The requested value nearest ``at`` on or past it in the walk's ``direction`` (None if none)."""
    beyond = values[(values - at) * direction >= 0]
    return float(beyond[np.argmin(np.abs(beyond - at))]) if beyond.size else None

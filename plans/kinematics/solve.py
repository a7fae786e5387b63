"""Solving a mechanism group by group, over many drive positions at once.

Positions are continued from the sketch: the drive is walked from its sketch value to
every requested value in steps of at most ``STEP`` (1° or 1/200 of the mechanism's size),
and at each step every group takes the assembly branch nearest the previous step (the
sketch, at the start). The branch therefore never jumps, and a position that cannot be
reached without the mechanism falling apart is reported, with the group and the reason.
Velocities and accelerations are then solved at the requested positions only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from ..errors import AssemblyError, SingularPositionError
from ..model import Mechanism
from ..structure import Structure
from ..scene import FRAME, LINEAR_STEPS_PER_SIZE, STEP_DEG, DriveKind   # the walk's steps, bounded by the scene
from ..structure import ComplexGroup, DrivenGroup
from . import special
from .compiled import CompiledGroup, GroupRates, walk as compiled_walk
from .drives import DrivenEquations
from .generic import GroupEquations
from .groups import SINGULAR_REASON, accelerations, candidates, conditioning, velocities
from .tolerances import ASSEMBLY_RTOL, JUMP_RATIO, SINGULAR_SIN, WARN_SIN
from .state import LinkState, Motion, rotate

__all__ = ["analyse", "drive_states", "singular_reason", "group_condition", "SINGULAR_SIN", "WARN_SIN", "STEP_DEG", "JUMP_RATIO"]

#: A class II mechanism's request of more drive values than this is solved in blocks of this
#: many (:func:`_direct_motion`): a block's temporaries (32–64 KiB each) stay in the cache and
#: are reused from the heap, where arrays of 100 000 positions are mapped and faulted in afresh
#: (about 12 500 page faults a call, as costly as the arithmetic). Smaller blocks pay the
#: per-call overhead of every numpy operation more often (512: twice as slow).
DIRECT_BLOCK = 4096



def singular_reason(g) -> str:
    """Why group ``g`` has no unique solution at a singular position."""
    if isinstance(g, DrivenGroup):
        return ("the original mechanism's equations (its pairs and the drive's) are singular: the drive "
                "cannot move its links uniquely here (a dead position of the drive)")
    if not isinstance(g, ComplexGroup):
        return SINGULAR_REASON[g.form].format(m=g.m, n=g.n)
    if g.base is not None:
        rods = ", ".join(r.link for r in g.rods)
        return (f"the axes of rods {rods} meet in one point (the special points coincide, their construction "
                "lines are parallel): the group's velocity equations have no unique solution")
    return "the group's velocity equations (its Jacobian) are singular: the closed contour is at a dead position"


def analyse(mech: Mechanism, structure: Structure, values: np.ndarray | None = None, *, order: int = 2) -> Motion:
    """Positions (order 0), velocities (1) and accelerations (2) at the drive ``values``
    (degrees for a crank, metres for a slider; the scene's values by default)."""
    values = np.asarray(mech.drive.values if values is None else values, dtype=float)
    if values.size > DIRECT_BLOCK:      # a large request of a class II mechanism: solved in blocks
        motion = _direct_motion(mech, structure, values, order)
        if motion is not None:
            return motion
    pre: dict[str, dict] = {}      # per class II group, its geometry at the values when already solved
    states = _reach(mech, structure, values, pre)
    sines: dict[str, np.ndarray] = {}
    if order >= 1:
        _set_drive_rates(mech, states, values)
        sliding = {}
        complex_ = {}     # per class III/IV group: its rate solves (one Jacobian for both)
        driven = None     # a drive inside the chain: its equations and scaled Jacobian
        if structure.driven is not None:
            g = structure.driven
            eq = DrivenEquations(mech, g, values)
            a = eq.scaled_jacobian(states)
            driven = eq, a
            sines[g.name] = eq.condition(states, a)
            _refuse_singular(mech, g, sines[g.name], values)
            eq.velocities(states, a)
        for g in structure.groups:
            if isinstance(g, ComplexGroup):
                rates = GroupRates(mech, g.links, g.pairs, states)
                complex_[g.name] = rates
                sines[g.name] = special.condition(g, mech, states) if special.supports(g) else rates.condition()
                _refuse_singular(mech, g, sines[g.name], values)
                rates.velocities(states)
                continue
            sliding[g.name], sines[g.name] = velocities(g, mech, states, pre.get(g.name))
            _refuse_singular(mech, g, sines[g.name], values)
        if order >= 2:
            if driven is not None:
                eq, a = driven
                eq.accelerations(states, a)
            for g in structure.groups:
                if isinstance(g, ComplexGroup):
                    complex_[g.name].accelerations(states)
                else:
                    accelerations(g, mech, states, sliding[g.name])
    return Motion(mechanism=mech, structure=structure, values=values, order=order, links=states, sines=sines)


def _reach(mech: Mechanism, structure: Structure, values: np.ndarray, pre: dict | None = None
           ) -> dict[str, LinkState]:
    """Poses at ``values``: all in one walk from the sketch (moved by whole turns towards the
    values' median); when that walk fails, each angle alone, walked the short way round and
    then, if that passes a limit or singular position, the long way (a crank that cannot turn
    fully reaches an angle only from one side). An angle reachable neither way is reported
    as the short way's failure."""
    fast = _direct(mech, structure, values, pre)
    if fast is not None:
        return fast
    try:
        states, targets = _positions(mech, structure, values)
        return {name: s.take(targets) for name, s in states.items()}
    except AssemblyError:
        if not mech.drive.kind.angular:
            raise
    parts = []
    for value in values:
        one = np.array([value])
        near = mech.drive.sketch_value + 360.0 * np.round((value - mech.drive.sketch_value) / 360.0)
        try:
            states, targets = _positions(mech, structure, one, start=near)
        except AssemblyError as short_way:
            try:
                states, targets = _positions(mech, structure, one, start=near + (360.0 if near < value else -360.0))
            except AssemblyError:
                raise short_way from None
        parts.append({name: s.take(targets) for name, s in states.items()})
    out = {name: LinkState(*(None if getattr(parts[0][name], f.name) is None
                             else np.concatenate([getattr(p[name], f.name) for p in parts])
                             for f in fields(LinkState))) for name in parts[0]}
    for name, state in out.items():   # cos θ, sin θ as solved, where every part knows them
        if all("_cos_sin" in p[name].__dict__ for p in parts):
            state.seeded(*(np.concatenate([p[name]._cos_sin[i] for p in parts]) for i in (0, 1)))
    return out


def group_condition(mech: Mechanism, g: ComplexGroup, states: dict[str, LinkState]) -> np.ndarray:
    """A class III/IV group's condition figure (±1 well conditioned, 0 singular): the rods'
    axes for a class III group, else the scaled Jacobian's σ_min/σ_max."""
    if special.supports(g):
        return special.condition(g, mech, states)
    eq = GroupEquations(mech, g.links, g.pairs)
    known = {name: s for name, s in states.items() if name not in eq.col}
    return CompiledGroup(mech, eq.links, eq.pairs, known).condition(eq.pose(states),
                                                                    np.arange(len(states[g.links[0]].theta)))


def _grid_condition(mech: Mechanism, g: ComplexGroup, eq: GroupEquations, states: dict[str, LinkState],
                    group: CompiledGroup | None = None) -> np.ndarray:
    """The condition figure along the walk, for :func:`_check_crossing`: a class III group's
    special points (cheap), else the compiled group's stand-in with the same sign and the
    same value wherever it is small."""
    if special.supports(g):
        return special.condition(g, mech, states)
    if group is None:     # the walk's own compiled group (the same known links), when at hand
        known = {name: s for name, s in states.items() if name not in eq.col}
        group = CompiledGroup(mech, eq.links, eq.pairs, known)
    return group.crossing_figure(eq.pose(states), np.arange(group.n_pos))


def _refuse_singular(mech: Mechanism, g, sin: np.ndarray, values: np.ndarray) -> None:
    bad = np.flatnonzero(np.abs(sin) < SINGULAR_SIN)
    if bad.size:
        raise SingularPositionError(singular_reason(g), group=_group_label(g), angle=_fmt(mech, values[bad[0]]))


def _fmt(mech: Mechanism, value: float) -> str:
    return f"{value:g}°" if mech.drive.kind.angular else f"{value:g} m"


def _grid(mech: Mechanism, values: np.ndarray, start: float | None = None
          ) -> tuple[np.ndarray, list[np.ndarray], np.ndarray]:
    """The continuation grid: its values, its sweeps (index paths from the start), and the
    index of every requested value in it. A crank's walk starts at its sketch angle moved by
    whole turns towards the values' median, unless ``start`` (such an angle) is given."""
    if mech.drive.kind.angular:
        if start is None:
            start = _start(mech, values)
        step = STEP_DEG
    else:
        start = mech.drive.sketch_value
        step = mech.size / LINEAR_STEPS_PER_SIZE
    up = np.unique(np.concatenate([np.arange(start, values.max(), step), values[values >= start]]))
    down = np.unique(np.concatenate([np.arange(start, values.min(), -step), values[values <= start]]))[::-1]
    up = up[up > start]
    down = down[down < start]
    grid = np.concatenate([[start], up, down])
    sweeps = [np.arange(0, 1 + len(up)), np.concatenate([[0], np.arange(1 + len(up), len(grid))])]
    order = np.argsort(grid, kind="stable")          # the grid's values are distinct
    index = order[np.searchsorted(grid[order], values)]
    return grid, sweeps, index


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
        across = g.normal * float(np.dot(g.anchor[FRAME] - g.anchor[d.link], g.normal))
        states[d.link] = LinkState(zero.copy(), across + values[:, None] * g.direction)
    return states


def _set_drive_rates(mech: Mechanism, states: dict[str, LinkState], values: np.ndarray) -> None:
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


def _start(mech: Mechanism, values: np.ndarray) -> float:
    """The walk's first value: a crank's sketch angle moved by whole turns towards the values'
    median, a slider's sketch position."""
    start = mech.drive.sketch_value
    if mech.drive.kind.angular:
        # round() is monotonic: when the extremes round alike, so does the median (no sort needed)
        low, high = np.round((np.array([values.min(), values.max()]) - start) / 360.0)
        turns = low if low == high else np.round((np.median(values) - start) / 360.0)
        start += 360.0 * turns
    return start


def _direct(mech: Mechanism, structure: Structure, values: np.ndarray, pre: dict | None = None
            ) -> dict[str, LinkState] | None:
    """Poses at ``values`` of a mechanism of class II groups only, without walking through
    every value: each group's assembly branch is the one the walk takes at its start (constant
    along a walk that crosses no singular position), and only that branch is solved, at the
    walk's own steps (from the start to the extreme values, where assembly and singular
    crossings are checked as the walk checks them) and at the values, in one pass. Each value must assemble, be well away from a singular
    position (|sin| ≥ SINGULAR_SIN) and have the sign of sin of the walk's step before it (on
    the sketch's side), so that no singular position lies between that step and the value:
    then the walk through every value (:func:`_positions`) would choose the same branch and
    refuse nothing, and its poses at the values are these, to the last bit. None (the full
    walk decides, and reports any failure) when a check fails or a group is of class III/IV."""
    if not _direct_applies(structure, values):
        return None
    start = _start(mech, values)
    ends = np.array([values.min(), values.max()])
    grid, sweeps, _ = _grid(mech, ends, start)
    k = len(grid)
    # the walk's steps and the values, solved together: each group on the branch the walk
    # would take at its start (the sketch's), then checked along the steps as the walk checks
    states = drive_states(mech, np.concatenate([grid, values]))
    tol = ASSEMBLY_RTOL * mech.size
    first = np.array([0])            # the grid's start
    before = _steps_before(grid, sweeps, start, values)
    kept: dict[str, dict] = {}
    sin_at: dict[str, np.ndarray] = {}
    for g in structure.groups:
        # every branch over all positions at once (one call: cheaper than solving the start
        # alone first), the one the walk takes at its start kept
        options = candidates(g, mech, states, tol)
        option = options[int(_branch(mech, g.links, options, [first])[0])]
        if not option.valid.all():
            return None
        states[g.m], states[g.n] = option.m, option.n
        keep: dict = {}
        sin = conditioning(g, mech, states, keep)
        walk_sin, sin = sin[:k], sin[k:]
        try:
            _check_crossing(mech, g, walk_sin, grid, sweeps, ends)
        except AssemblyError:
            return None
        if not _clear_of_singular(sin, walk_sin[before]):
            return None
        kept[g.name] = keep
        sin_at[g.name] = sin
    at = slice(k, None)
    if pre is not None:    # the geometry at the values, for the velocity step (``pre`` of groups.velocities)
        for name, keep in kept.items():
            pre[name] = {"geo": {key: v[at] for key, v in keep["geo"].items()},
                         "U1": keep["U1"][at], "U2": keep["U2"][at], "sin": sin_at[name]}
    return {name: s.take(at) for name, s in states.items()}


def _direct_applies(structure: Structure, values: np.ndarray) -> bool:
    """Whether the direct path may answer: finite values (a 1-D, non-empty array) of a
    mechanism of class II groups only (no class III/IV group, no drive inside the chain)."""
    return bool(values.ndim == 1 and values.size and np.all(np.isfinite(values))) \
        and structure.driven is None and not any(isinstance(g, ComplexGroup) for g in structure.groups)


def _clear_of_singular(sin: np.ndarray, walk_sin: np.ndarray) -> bool:
    """Every value well away from a singular position (|sin| ≥ SINGULAR_SIN) and on the side
    of the walk's step before it (the same sign of sin): no singular position between them."""
    return bool(np.all((np.abs(sin) >= SINGULAR_SIN) & (np.sign(sin) == np.sign(walk_sin))))


def _steps_before(grid: np.ndarray, sweeps: list[np.ndarray], start: float, values: np.ndarray) -> np.ndarray:
    """The index in ``grid`` of the walk's step before every value, on the sketch's side."""
    up, down = grid[sweeps[0]], grid[sweeps[1]][::-1]
    high = values >= start
    if high.all():     # every value on the way up (a turn from the sketch): no masks needed
        return sweeps[0][np.searchsorted(up, values, side="right") - 1]
    before = np.empty(len(values), dtype=int)
    before[high] = sweeps[0][np.searchsorted(up, values[high], side="right") - 1]
    before[~high] = sweeps[1][::-1][np.searchsorted(down, values[~high], side="left")]
    return before


@dataclass(frozen=True)
class _Plan:
    """What the direct path decides once for all the values of a blocked request
    (:func:`_direct_motion`): the walk's steps from the start
    to the extreme values (``grid``, its ``sweeps``, the ``start``), each class II group's
    assembly branch there and its sin along those steps, and the assembly tolerance (m)."""

    grid: np.ndarray
    sweeps: list[np.ndarray]
    start: float
    tol: float
    branch: dict[str, int]
    walk_sin: dict[str, np.ndarray]


def _direct_plan(mech: Mechanism, structure: Structure, values: np.ndarray) -> _Plan | None:
    """The direct path's walk from the start to the extreme ``values``: every branch of each
    group solved at the walk's steps, the one the walk takes at its start kept, and assembly
    and singular crossings checked along the steps as the walk checks them. None when a check
    fails or a group is of class III/IV (then the full walk decides)."""
    if not _direct_applies(structure, values):
        return None
    start = _start(mech, values)
    ends = np.array([values.min(), values.max()])
    grid, sweeps, _ = _grid(mech, ends, start)
    states = drive_states(mech, grid)
    tol = ASSEMBLY_RTOL * mech.size
    first = np.array([0])            # the grid's start
    branch: dict[str, int] = {}
    walk_sin: dict[str, np.ndarray] = {}
    for g in structure.groups:
        # every branch (one call: cheaper than solving the start alone first), the one the
        # walk takes at its start kept
        options = candidates(g, mech, states, tol)
        b = int(_branch(mech, g.links, options, [first])[0])
        option = options[b]
        if not option.valid.all():
            return None
        states[g.m], states[g.n] = option.m, option.n
        sin = conditioning(g, mech, states)
        try:
            _check_crossing(mech, g, sin, grid, sweeps, ends)
        except AssemblyError:
            return None
        branch[g.name], walk_sin[g.name] = b, sin
    return _Plan(grid, sweeps, start, tol, branch, walk_sin)


def _direct_block(mech: Mechanism, structure: Structure, plan: _Plan, values: np.ndarray
                  ) -> tuple[dict[str, LinkState], dict[str, dict]] | None:
    """Poses at ``values`` (all of them, or a block of them) on the branches of ``plan``, and
    per group what :func:`groups.conditioning` kept there (``pre`` of groups.velocities); None
    when a value does not assemble, is near a singular position or has not the sign of sin of
    the walk's step before it. Element by element the same arithmetic as at all values at
    once: a block's poses are those of the whole request."""
    before = _steps_before(plan.grid, plan.sweeps, plan.start, values)
    states = drive_states(mech, values)
    kept: dict[str, dict] = {}
    for g in structure.groups:
        (option,) = candidates(g, mech, states, plan.tol, plan.branch[g.name])
        if not option.valid.all():
            return None
        states[g.m], states[g.n] = option.m, option.n
        keep: dict = {}
        sin = conditioning(g, mech, states, keep)
        if not _clear_of_singular(sin, plan.walk_sin[g.name][before]):
            return None
        kept[g.name] = {"geo": keep["geo"], "U1": keep["U1"], "U2": keep["U2"], "sin": sin}
    return states, kept


def _direct_motion(mech: Mechanism, structure: Structure, values: np.ndarray, order: int) -> Motion | None:
    """:func:`analyse` of a class II mechanism at more than DIRECT_BLOCK values: the direct
    path's walk checked once (:func:`_direct_plan`), then positions, velocities and
    accelerations solved block by block into arrays of the full size (rows of one buffer,
    :func:`_allocate`), so that every temporary is a block's (see DIRECT_BLOCK). The same
    results as at all values at once, to the last bit; None where :func:`_direct` would
    give None (the full walk then decides and reports)."""
    plan = _direct_plan(mech, structure, values)
    if plan is None:
        return None
    n = len(values)
    out: dict[str, dict[str, np.ndarray | None]] = {}
    sines: dict[str, np.ndarray] = {g.name: np.empty(n) for g in structure.groups} if order >= 1 else {}
    for lo in range(0, n, DIRECT_BLOCK):
        part = values[lo:lo + DIRECT_BLOCK]
        solved = _direct_block(mech, structure, plan, part)
        if solved is None:
            return None
        states, kept = solved
        if order >= 1:
            _set_drive_rates(mech, states, part)
            sliding = {}
            for g in structure.groups:
                sliding[g.name], sin = velocities(g, mech, states, kept[g.name])
                sines[g.name][lo:lo + len(part)] = sin    # |sin| ≥ SINGULAR_SIN: checked in _direct_block
            if order >= 2:
                for g in structure.groups:
                    accelerations(g, mech, states, sliding[g.name])
        _store(out, states, lo, n)
    links = {}
    for name, arrays in out.items():
        cs = arrays.pop("_cos_sin")
        links[name] = LinkState(**arrays)
        if cs is not None:
            links[name].seeded(*cs)
    return Motion(mechanism=mech, structure=structure, values=values, order=order, links=links, sines=sines)


def _store(out: dict[str, dict], states: dict[str, LinkState], lo: int, n: int) -> None:
    """Copy a block's states (positions lo, lo + 1, …) into ``out``'s full-size arrays (made
    at the first block, as rows of one buffer), cos θ and sin θ too when known."""
    if not out:
        _allocate(out, states, n)
    for name, s in states.items():
        dst = out[name]
        for key in _FIELDS:
            v = getattr(s, key)
            if v is not None:
                dst[key][lo:lo + len(v)] = v
        cs = s.__dict__.get("_cos_sin")
        if cs is not None and dst["_cos_sin"] is not None:
            for d, src in zip(dst["_cos_sin"], cs):
                d[lo:lo + len(src)] = src


_FIELDS = tuple(f.name for f in fields(LinkState))


def _allocate(out: dict[str, dict], states: dict[str, LinkState], n: int) -> None:
    """Full-size arrays for every field of the block's ``states`` (None stays None): rows of
    one (rows, n) buffer, a vector field two rows (stored by columns, as a block's are). One
    large allocation instead of some forty of 0.8 MB: numpy backs it with huge pages, and
    the page faults of a call fall from ~8 600 to ~900."""
    layout = []
    for name, s in states.items():
        for key in _FIELDS:
            v = getattr(s, key)
            if v is not None:
                layout.append((name, key, v.shape[1] if v.ndim == 2 else 0))
        if "_cos_sin" in s.__dict__:
            layout += [(name, "_cos", 0), (name, "_sin", 0)]
    buf = np.empty((sum(max(w, 1) for *_, w in layout), n))
    row = 0
    for name, s in states.items():
        out[name] = dict.fromkeys(_FIELDS)
    for name, key, w in layout:
        out[name][key] = buf[row:row + w].T if w else buf[row]
        row += max(w, 1)
    for name, d in out.items():
        d["_cos_sin"] = (d.pop("_cos"), d.pop("_sin")) if "_cos" in d else None


def _positions(mech: Mechanism, structure: Structure, values: np.ndarray, start: float | None = None,
               record: dict | None = None) -> tuple[dict[str, LinkState], np.ndarray]:
    """Poses along the walk to ``values`` (see the module); ``record``, when given, receives
    the grid and its sweeps (key None) and, per class II group, its branch and sin along the walk."""
    grid, sweeps, index = _grid(mech, values, start)
    if record is not None:
        record[None] = grid, sweeps
    states = drive_states(mech, grid)
    tol = ASSEMBLY_RTOL * mech.size
    if structure.driven is not None:   # the original mechanism, step by step with the drive's values
        eq = DrivenEquations(mech, structure.driven, grid)
        states.update(_walk(mech, structure.driven, eq, states, grid, sweeps, values))
        _check_crossing(mech, structure.driven, eq.condition(states), grid, sweeps, values)
    for g in structure.groups:
        if isinstance(g, ComplexGroup):
            eq = GroupEquations(mech, g.links, g.pairs)
            poses, compiled = _continue(mech, g, eq, states, grid, sweeps, values)
            states.update(poses)
            _check_crossing(mech, g, _grid_condition(mech, g, eq, states, compiled), grid, sweeps, values)
            continue
        options = candidates(g, mech, states, tol)
        choice = _branch(mech, g.links, options, sweeps)
        m_state = _select([o.m for o in options], choice)
        n_state = _select([o.n for o in options], choice)
        valid = np.choose(choice, [o.valid for o in options])
        for sweep in sweeps:
            bad = np.flatnonzero(~valid[sweep])
            if bad.size:
                i = sweep[bad[0]]
                target = _requested_beyond(values, grid[i], grid[sweep[-1]] - grid[0])
                target = grid[i] if target is None else target
                where = "" if grid[i] == target else (f" (the walk from the sketch at {_fmt(mech, grid[0])} "
                                                      f"fails at {_fmt(mech, grid[i])})")
                raise AssemblyError(f"cannot assemble: {options[int(choice[i])].why(i)}{where}; check the "
                                    "lengths or the requested positions", group=_group_label(g),
                                    angle=_fmt(mech, target))
        states[g.m], states[g.n] = m_state, n_state
        sin = conditioning(g, mech, states)
        _check_crossing(mech, g, sin, grid, sweeps, values)
        if record is not None:
            record[g.name] = int(choice[0]), sin
    return states, index


def _check_crossing(mech: Mechanism, g, sin: np.ndarray, grid: np.ndarray, sweeps: list[np.ndarray],
                    values: np.ndarray) -> None:
    """Refuse to continue through a singular position: where sin changes sign between two
    steps of a sweep (and a requested value lies beyond), the branch beyond is ambiguous."""
    for sweep in sweeps:
        s = sin[sweep]
        flips = np.flatnonzero((np.sign(s[:-1]) * np.sign(s[1:]) < 0) | (np.abs(s[:-1]) < SINGULAR_SIN))
        if not flips.size:
            continue
        a, b = grid[sweep[flips[0]]], grid[sweep[flips[0] + 1]]
        target = _requested_beyond(values, b, b - a)
        if target is not None:
            raise AssemblyError(
                f"the walk from the sketch passes a singular position between {_fmt(mech, a)} and {_fmt(mech, b)} "
                f"({singular_reason(g)}); positions beyond it cannot be reached without "
                "ambiguity — request positions on the sketch's side or redraw the sketch there",
                group=_group_label(g), angle=_fmt(mech, target))


def _continue(mech: Mechanism, g: ComplexGroup, eq: GroupEquations, states: dict[str, LinkState],
              grid: np.ndarray, sweeps: list[np.ndarray], values: np.ndarray
              ) -> tuple[dict[str, LinkState], CompiledGroup]:
    """Poses of a class III/IV group along the walk (and its compiled equations): the fast continuation of
    :mod:`plans.kinematics.compiled` (coarse adaptive steps, then batched Newton at every
    grid position, then the walk's acceptance tests), or, when that is not sure of every
    position, the step-by-step walk (:func:`_walk`), which also reports any failure."""
    q, group = _fast_walk(mech, eq, states, grid, sweeps)
    if q is None:
        return _walk(mech, g, eq, states, grid, sweeps, values), group
    return {name: LinkState(q[:, c + 2], q[:, c:c + 2]) for name, c in eq.col.items()}, group


def _fast_walk(mech: Mechanism, eq: GroupEquations, states: dict[str, LinkState], grid: np.ndarray,
               sweeps: list[np.ndarray]) -> tuple[np.ndarray | None, CompiledGroup]:
    """The group's poses (len(grid), 3k) by :func:`plans.kinematics.compiled.walk`, or None,
    and its compiled equations."""
    known = {name: s for name, s in states.items() if name not in eq.col}
    group = CompiledGroup(mech, eq.links, eq.pairs, known)
    start = np.array([sweeps[0][0]])
    q0, _, conv, _ = group.newton(np.zeros((1, group.n)), start)
    if not conv[0]:
        return None, group
    q = np.empty((len(grid), group.n))
    q[start[0]] = q0[0]
    step = STEP_DEG if mech.drive.kind.angular else mech.size / LINEAR_STEPS_PER_SIZE
    for sweep in sweeps:
        part = compiled_walk(group, sweep, grid[sweep], q[sweep[0]], step, JUMP_RATIO)
        if part is None:
            return None, group
        q[sweep] = part
    return q, group


def _walk(mech: Mechanism, g: ComplexGroup, eq: GroupEquations, states: dict[str, LinkState],
          grid: np.ndarray, sweeps: list[np.ndarray], values: np.ndarray) -> dict[str, LinkState]:
    """Poses of a class III/IV group along the walk: Newton at every step from the previous
    step (linear predictor), starting at the sketch, where every pose is the identity."""
    q = np.zeros((len(grid), 3 * len(eq.links)))
    done = np.zeros(len(grid), dtype=bool)
    cols = [c for c in range(q.shape[1]) if c % 3 != 2]

    def known(i: int) -> dict[str, LinkState]:
        return {name: s.take(np.array([i])) for name, s in states.items() if name not in eq.col}

    def fail(i: int, why: str) -> AssemblyError:
        sweep = next(sw for sw in sweeps if i in sw)
        target = _requested_beyond(values, grid[i], grid[sweep[-1]] - grid[0])
        target = grid[i] if target is None else target
        where = "" if grid[i] == target else f" (the walk from the sketch at {_fmt(mech, grid[0])} fails at " \
                                             f"{_fmt(mech, grid[i])})"
        return AssemblyError(f"{why}{where}; check the lengths or the requested positions",
                             group=_group_label(g), angle=_fmt(mech, target))

    for sweep in sweeps:
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
                raise fail(i, "cannot assemble: Newton's method finds no position of the group's links "
                              f"(residual {result.residual:.1e} m), the group falls apart there")
            q[i] = result.q[0]
            if prev is not None:
                moved = np.max(np.abs(q[i, cols] - q[prev, cols]))
                # the step before, for a step as long as this one (a requested value makes a
                # short step in the grid), or for the first step its linear prediction
                before = np.max(np.abs(q[prev, cols] - q[prev2, cols])) \
                    * abs(grid[i] - grid[prev]) / abs(grid[prev] - grid[prev2]) if prev2 is not None else \
                    _predicted_move(eq.at(i), q[prev], known(i), cols)
                if moved > 0.01 * mech.size and moved > JUMP_RATIO * before:
                    raise fail(i, "the assembly branch would jump between neighbouring steps (a limit "
                                  "position or a singular position lies there)")
            done[i] = True
            prev2, prev = prev, i
    return {name: LinkState(q[:, c + 2], q[:, c:c + 2]) for name, c in eq.col.items()}


def _predicted_move(eq: GroupEquations, q: np.ndarray, known: dict[str, LinkState], cols: list[int]) -> float:
    """How far (largest coordinate, m) a step from pose ``q`` to the position of ``known``
    moves the group's origins by the linear prediction (one Newton step): the yardstick of a
    walk's first step, which has no step before it."""
    st = eq.states(q[None, :], known)
    try:
        dx = np.linalg.solve(eq.scaled_jacobian(st), -eq._scale_rows(eq.residual(st))[..., None])[0, :, 0]
    except np.linalg.LinAlgError:
        return 0.0
    return float(np.max(np.abs(dx[cols])))


def _group_label(g) -> str:
    return f"group {g.name} ({g.form})"


def _requested_beyond(values: np.ndarray, at: float, direction: float) -> float | None:
    """The requested value nearest ``at`` on or past it in the walk's ``direction`` (None if none)."""
    beyond = values[(values - at) * direction >= 0]
    return float(beyond[np.argmin(np.abs(beyond - at))]) if beyond.size else None


def _select(options: list[LinkState], choice: np.ndarray) -> LinkState:
    """The state that takes, at position i, option ``choice[i]``."""
    theta = np.choose(choice, [o.theta for o in options])
    origin = np.choose(choice[:, None], [o.origin for o in options])
    out = LinkState(theta, origin)
    if all("_cos_sin" in o.__dict__ for o in options):   # as solved (a pose placed from points seeds them)
        out.seeded(*(np.choose(choice, [o._cos_sin[i] for o in options]) for i in (0, 1)))
    return out


def _branch(mech: Mechanism, links: tuple[str, str], options: list, sweeps: list[np.ndarray]) -> np.ndarray:
    """Index of the chosen option at every grid position: the one nearest the sketch, kept
    everywhere. A class II group's options are its assembly branches in a fixed order (the
    sign of the assembly determinant: E left or right of D→F, and the like), and that sign
    cannot change along a walk that passes no singular position — which
    :func:`_check_crossing` refuses — so no step of the walk needs to choose again."""
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

"""Solving a mechanism group by group, over many drive positions at once.

Positions are continued from the sketch (:mod:`plans.kinematics.walk`): the drive is walked
from its sketch value to every requested value in steps of at most 1° (or 1/200 of the
mechanism's size), and every group keeps the assembly branch it has at the sketch. The branch
therefore never jumps, and a position that cannot be reached without the mechanism falling
apart is reported, with the group and the reason. Velocities and accelerations are then
solved at the requested positions only.

Each group is solved by the solver of its kind (:mod:`plans.kinematics.kinds`), through one
protocol: this module never asks what kind a group is. A chain of groups in closed form
(class II) is also solved directly at the requested values when that gives the walk's result
to the last bit (:func:`_direct`).
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from ..errors import AssemblyError, SingularPositionError
from ..model import Mechanism
from ..structure import Structure
from .kinds import GroupSolver, chain
from .motion import Motion
from .state import LinkState
from .tolerances import ASSEMBLY_RTOL, SINGULAR_SIN
from .walk import check_crossing, drive_states, fmt, group_label, set_drive_rates, start, walk_to

__all__ = ["analyse", "DIRECT_BLOCK"]

#: A class II mechanism's request of more drive values than this is solved in blocks of this
#: many (:func:`_direct_motion`): a block's temporaries (32–64 KiB each) stay in the cache and
#: are reused from the heap, where arrays of 100 000 positions are mapped and faulted in afresh
#: (about 12 500 page faults a call, as costly as the arithmetic). Smaller blocks pay the
#: per-call overhead of every numpy operation more often (512: twice as slow).
DIRECT_BLOCK = 4096


def analyse(mech: Mechanism, structure: Structure, values: np.ndarray | None = None, *, order: int = 2) -> Motion:
    """Positions (order 0), velocities (1) and accelerations (2) at the drive ``values``
    (degrees for a crank, metres for a slider; the scene's values by default)."""
    values = np.asarray(mech.drive.values if values is None else values, dtype=float)
    solvers = chain(mech, structure)
    if values.size > DIRECT_BLOCK:      # a large request of a class II mechanism: solved in blocks
        motion = _direct_motion(mech, structure, values, order, solvers)
        if motion is not None:
            return motion
    pre: dict[str, dict] = {}      # per class II group, its geometry at the values when already solved
    states = _reach(mech, structure, values, pre, solvers)
    sines: dict[str, np.ndarray] = {}
    if order >= 1:
        set_drive_rates(mech, states, values)
        rates = {}
        for s in solvers:
            name = s.group.name
            rates[name] = r = s.rates(states, values, pre.get(name))
            sines[name] = r.condition
            _refuse_singular(mech, s, r.condition, values)
            s.velocities(states, r)
        if order >= 2:
            for s in solvers:
                s.accelerations(states, rates[s.group.name])
    return Motion(mechanism=mech, structure=structure, values=values, order=order, links=states, sines=sines)


def _reach(mech: Mechanism, structure: Structure, values: np.ndarray, pre: dict | None = None,
           solvers: list[GroupSolver] | None = None) -> dict[str, LinkState]:
    """Poses at ``values``: all in one walk from the sketch (moved by whole turns towards the
    values' median); when that walk fails, each angle as if walked alone (:func:`_each_way`):
    the short way round and then, if that passes a limit or singular position, the long way
    (a crank that cannot turn fully reaches an angle only from one side). An angle reachable
    neither way is reported as the short way's failure."""
    fast = _direct(mech, structure, values, pre, solvers)
    if fast is not None:
        return fast
    try:
        states, targets = _positions(mech, structure, values)
        return {name: s.take(targets) for name, s in states.items()}
    except AssemblyError as e:
        if not mech.drive.kind.angular:
            raise
        joint = e
    return _each_way(mech, structure, values, (start(mech, values), joint))


def _each_way(mech: Mechanism, structure: Structure, values: np.ndarray,
              tried: tuple[float, AssemblyError]) -> dict[str, LinkState]:
    """Poses at the crank angles ``values``, each reached as if walked alone: from the sketch
    moved by whole turns to within ±180° of it (the short way round), else from one turn
    further (the long way). The angles that start alike are walked together, in one walk
    per start (:func:`_walk_from`); a walk that stops passes the angles beyond where it
    stopped on to the long way. An angle the long way does not reach either is reported
    with the short way's error, walked alone (the first such angle in the order given).
    ``tried``: the start of the walk to all the values that failed, and its error."""
    sketch = mech.drive.sketch_value
    near = sketch + 360.0 * np.round((values - sketch) / 360.0)
    parts: list[tuple[np.ndarray, dict[str, LinkState]]] = []
    short, short_errors = _walk_from(mech, structure, values, near, np.arange(len(values)), parts, tried)
    far = near[short] + np.where(near[short] < values[short], 360.0, -360.0)
    neither, long_errors = _walk_from(mech, structure, values[short], far, short, parts)
    for i in np.sort(neither):
        if i in short_errors and i in long_errors:    # each way walked to this angle alone
            raise short_errors[i]
        one = values[i:i + 1]
        try:
            states, targets = _positions(mech, structure, one, start=near[i])
        except AssemblyError as short_way:
            try:
                states, targets = _positions(mech, structure, one, start=near[i] + (360.0 if near[i] < one[0]
                                                                                    else -360.0))
            except AssemblyError:
                raise short_way from None
        parts.append((np.array([i]), {name: s.take(targets) for name, s in states.items()}))
    return _gather(parts)


def _walk_from(mech: Mechanism, structure: Structure, values: np.ndarray, starts: np.ndarray, index: np.ndarray,
               parts: list, tried: tuple[float, AssemblyError] | None = None
               ) -> tuple[np.ndarray, dict[int, AssemblyError]]:
    """Walk to ``values`` from their ``starts`` (crank angles, whole turns from the sketch),
    one walk per start, appending (the values' ``index``, their states) to ``parts``. A walk
    that stops (its error's ``at``) is walked again without the values at or beyond where it
    stopped on that side of its start. Returns the ``index`` of the values left behind, and
    the error of each that a walk to it alone left behind. ``tried``: a walk to all the values
    from one start that has failed already, and its error (not walked again)."""
    left: list[np.ndarray] = []
    alone: dict[int, AssemblyError] = {}
    for first in np.unique(starts):
        mine = np.flatnonzero(starts == first)
        while mine.size:
            try:
                if tried is not None and first == tried[0] and mine.size == len(values):
                    raise tried[1]
                states, targets = _positions(mech, structure, values[mine], start=float(first))
            except AssemblyError as e:
                beyond = np.ones(mine.size, dtype=bool) if e.at is None or e.at == first else \
                    (values[mine] - e.at) * np.sign(e.at - first) >= 0
                if mine.size == 1:
                    alone[int(index[mine[0]])] = e
                if not beyond.any():
                    beyond[:] = True
                left.append(mine[beyond])
                mine = mine[~beyond]
                continue
            parts.append((index[mine], {name: s.take(targets) for name, s in states.items()}))
            break
    return (index[np.concatenate(left)] if left else np.empty(0, dtype=int)), alone


def _gather(parts: list[tuple[np.ndarray, dict[str, LinkState]]]) -> dict[str, LinkState]:
    """The states of ``parts`` (each the positions it holds, by index, and its states there)
    put together in the order of the values (cos θ, sin θ too where every part knows them)."""
    order = np.argsort(np.concatenate([index for index, _ in parts]), kind="stable")
    names = parts[0][1]
    out = {name: LinkState(*(None if getattr(parts[0][1][name], f.name) is None
                             else np.concatenate([getattr(p[name], f.name) for _, p in parts])[order]
                             for f in fields(LinkState))) for name in names}
    for name, state in out.items():
        if all("_cos_sin" in p[name].__dict__ for _, p in parts):
            state.seeded(*(np.concatenate([p[name]._cos_sin[k] for _, p in parts])[order] for k in (0, 1)))
    return out


def _positions(mech: Mechanism, structure: Structure, values: np.ndarray, start: float | None = None
               ) -> tuple[dict[str, LinkState], np.ndarray]:
    """Poses along the walk to ``values`` (see :mod:`plans.kinematics.walk`), group by group,
    and the index of every value in the walk's grid."""
    walk = walk_to(mech, values, start)
    states = drive_states(mech, walk.grid)
    for s in chain(mech, structure):
        s.positions(states, walk)
    return states, walk.index


def _refuse_singular(mech: Mechanism, s: GroupSolver, sin: np.ndarray, values: np.ndarray) -> None:
    bad = np.flatnonzero(np.abs(sin) < SINGULAR_SIN)
    if bad.size:
        raise SingularPositionError(s.reason(), group=group_label(s.group), angle=fmt(mech, values[bad[0]]))


def _direct(mech: Mechanism, structure: Structure, values: np.ndarray, pre: dict | None = None,
            solvers: list[GroupSolver] | None = None) -> dict[str, LinkState] | None:
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
    solvers = chain(mech, structure) if solvers is None else solvers
    if not _direct_applies(solvers, values):
        return None
    first_value = start(mech, values)
    ends = np.array([values.min(), values.max()])
    walk = walk_to(mech, ends, first_value)
    grid, sweeps = walk.grid, walk.sweeps
    k = len(grid)
    # the walk's steps and the values, solved together: each group on the branch the walk
    # would take at its start (the sketch's), then checked along the steps as the walk checks
    states = drive_states(mech, np.concatenate([grid, values]))
    tol = ASSEMBLY_RTOL * mech.size
    first = np.array([0])            # the grid's start
    before = _steps_before(grid, sweeps, first_value, values)
    kept: dict[str, dict] = {}
    sin_at: dict[str, np.ndarray] = {}
    for s in solvers:
        g = s.group
        # every branch over all positions at once (one call: cheaper than solving the start
        # alone first), the one the walk takes at its start kept
        options = s.branches(states, tol)
        option = options[s.sketch_branch(options, [first])]
        if not option.valid.all():
            return None
        states[g.m], states[g.n] = option.m, option.n
        keep: dict = {}
        sin = s.condition(states, None, keep)
        walk_sin, sin = sin[:k], sin[k:]
        try:
            check_crossing(mech, g, s.reason(), walk_sin, walk)
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


def _direct_applies(solvers: list[GroupSolver], values: np.ndarray) -> bool:
    """Whether the direct path may answer: finite values (a 1-D, non-empty array) of a chain
    of groups in closed form only (class II: no class III/IV group, no drive inside the chain)."""
    return bool(values.ndim == 1 and values.size and np.all(np.isfinite(values))) \
        and all(s.closed_form for s in solvers)


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


def _direct_plan(mech: Mechanism, solvers: list[GroupSolver], values: np.ndarray) -> _Plan | None:
    """The direct path's walk from the start to the extreme ``values``: every branch of each
    group solved at the walk's steps, the one the walk takes at its start kept, and assembly
    and singular crossings checked along the steps as the walk checks them. None when a check
    fails or a group is of class III/IV (then the full walk decides)."""
    if not _direct_applies(solvers, values):
        return None
    first_value = start(mech, values)
    ends = np.array([values.min(), values.max()])
    walk = walk_to(mech, ends, first_value)
    grid, sweeps = walk.grid, walk.sweeps
    states = drive_states(mech, grid)
    tol = ASSEMBLY_RTOL * mech.size
    first = np.array([0])            # the grid's start
    branch: dict[str, int] = {}
    walk_sin: dict[str, np.ndarray] = {}
    for s in solvers:
        g = s.group
        # every branch (one call: cheaper than solving the start alone first), the one the
        # walk takes at its start kept
        options = s.branches(states, tol)
        b = s.sketch_branch(options, [first])
        option = options[b]
        if not option.valid.all():
            return None
        states[g.m], states[g.n] = option.m, option.n
        sin = s.condition(states)
        try:
            check_crossing(mech, g, s.reason(), sin, walk)
        except AssemblyError:
            return None
        branch[g.name], walk_sin[g.name] = b, sin
    return _Plan(grid, sweeps, first_value, tol, branch, walk_sin)


def _direct_block(mech: Mechanism, structure: Structure, plan: _Plan, values: np.ndarray,
                  solvers: list[GroupSolver]) -> tuple[dict[str, LinkState], dict[str, dict]] | None:
    """Poses at ``values`` (all of them, or a block of them) on the branches of ``plan``, and
    per group what :func:`groups.conditioning` kept there (``pre`` of groups.velocities); None
    when a value does not assemble, is near a singular position or has not the sign of sin of
    the walk's step before it. Element by element the same arithmetic as at all values at
    once: a block's poses are those of the whole request."""
    before = _steps_before(plan.grid, plan.sweeps, plan.start, values)
    states = drive_states(mech, values)
    kept: dict[str, dict] = {}
    for s in solvers:
        g = s.group
        (option,) = s.branches(states, plan.tol, plan.branch[g.name])
        if not option.valid.all():
            return None
        states[g.m], states[g.n] = option.m, option.n
        keep: dict = {}
        sin = s.condition(states, None, keep)
        if not _clear_of_singular(sin, plan.walk_sin[g.name][before]):
            return None
        kept[g.name] = {"geo": keep["geo"], "U1": keep["U1"], "U2": keep["U2"], "sin": sin}
    return states, kept


def _direct_motion(mech: Mechanism, structure: Structure, values: np.ndarray, order: int,
                   solvers: list[GroupSolver]) -> Motion | None:
    """:func:`analyse` of a class II mechanism at more than DIRECT_BLOCK values: the direct
    path's walk checked once (:func:`_direct_plan`), then positions, velocities and
    accelerations solved block by block into arrays of the full size (rows of one buffer,
    :func:`_allocate`), so that every temporary is a block's (see DIRECT_BLOCK). The same
    results as at all values at once, to the last bit; None where :func:`_direct` would
    give None (the full walk then decides and reports)."""
    plan = _direct_plan(mech, solvers, values)
    if plan is None:
        return None
    n = len(values)
    out: dict[str, dict[str, np.ndarray | None]] = {}
    sines: dict[str, np.ndarray] = {s.group.name: np.empty(n) for s in solvers} if order >= 1 else {}
    for lo in range(0, n, DIRECT_BLOCK):
        part = values[lo:lo + DIRECT_BLOCK]
        solved = _direct_block(mech, structure, plan, part, solvers)
        if solved is None:
            return None
        states, kept = solved
        if order >= 1:
            set_drive_rates(mech, states, part)
            rates = {}
            for s in solvers:
                name = s.group.name
                rates[name] = r = s.rates(states, part, kept[name])
                sines[name][lo:lo + len(part)] = r.condition    # |sin| ≥ SINGULAR_SIN: checked in _direct_block
            if order >= 2:
                for s in solvers:
                    s.accelerations(states, rates[s.group.name])
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

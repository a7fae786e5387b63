"""Readers of ``[plans]`` (``draw``, ``senses``) and of the cycle: ``[drive] positions`` and
``start`` with ``[plans] output``, ``trace`` and ``at`` (one revolution of a crank in N equal
steps; positions numbered 0 … N−1).

Imports only plans.errors and modules of plans.scene (and the standard library).
"""

from __future__ import annotations

from typing import Any, Mapping, Sequence

from ..errors import SceneError
from .checks import SHOW, whole
from .values import (CYCLE_SHEETS, CYCLE_STARTS, DEFAULT_DRAW, DRAWABLE, FRAME, MAX_POSITIONS, MAX_VELOCITY_PLANS,
                     MIN_CYCLE_POSITIONS, Cycle, Drive, Slider)


def read_draw(table: Mapping[str, Any]) -> tuple[tuple[str, ...], bool]:
    """What to draw, and whether the scheme shows the senses of ω and ε (``senses``)."""
    extra = sorted(str(k) for k in set(table) - {"draw", "senses"})
    if extra:
        raise SceneError(f"unknown key {extra[0]!r}; [plans] has draw and senses", key=f"plans.{extra[0]}")
    draw = table.get("draw", list(DEFAULT_DRAW))
    if not isinstance(draw, list) or not draw:
        raise SceneError(f"draw is a non-empty list of {', '.join(DRAWABLE)}", key="plans.draw")
    for item in draw:
        if not isinstance(item, str) or item not in DRAWABLE:
            raise SceneError(f"cannot draw {SHOW.repr(item)}; choose from {', '.join(DRAWABLE)}", key="plans.draw")
    senses = table.get("senses", False)
    if not isinstance(senses, bool):
        raise SceneError(f"senses is true or false, not {SHOW.repr(senses)}", key="plans.senses")
    if senses and "scheme" not in draw:
        raise SceneError("senses = true marks ω and ε on the scheme, which is not drawn; add \"scheme\" to draw",
                         key="plans.senses")
    return tuple(d for d in DRAWABLE if d in draw), senses


def cycle_positions(cycle: Mapping[str, Any]) -> int:
    """The number of positions of ``[drive] positions`` (and a valid ``start``)."""
    if "positions" not in cycle:
        raise SceneError('start chooses the first of positions = N; add positions (e.g. 12) or remove start',
                         key="drive.start")
    n = whole(cycle["positions"])
    if n is None:
        raise SceneError(f"positions is a whole number of equal steps per revolution (e.g. 12), got "
                         f"{SHOW.repr(cycle['positions'])}", key="drive.positions")
    if not MIN_CYCLE_POSITIONS <= n <= MAX_POSITIONS:
        raise SceneError(f"positions = {n} is out of range: {MIN_CYCLE_POSITIONS} to {MAX_POSITIONS} equal steps per "
                         "revolution (the graphical differentiation needs three chords; one a degree is the most)",
                         key="drive.positions")
    start = cycle.get("start", "angle")
    if start not in CYCLE_STARTS:
        raise SceneError(f"start is \"angle\" (the first position is angle) or \"extreme\" (the output link's "
                         f"extreme position), got {SHOW.repr(start)}", key="drive.start")
    return n


def _default_output(drive: Drive, links: Mapping[str, tuple[str, ...]], sliders: Sequence[Slider]) -> str:
    """The cycle's output when ``[plans] output`` is not given: the last moving link; when that
    is the driving link, the last other one that turns about a frame pivot or slides on a frame
    guide (the driving link when there is none)."""
    moving = [name for name in links if name != FRAME]
    if moving[-1] != drive.link:
        return moving[-1]
    frame = set(links[FRAME]) if FRAME in links else set()
    able = [n for n in moving if n != drive.link and (set(links[n]) & frame or any(
        s.link == n and s.on == FRAME for s in sliders))]
    return able[-1] if able else drive.link


def read_cycle(keys: Mapping[str, Any], drive: Drive, plans: Mapping[str, Any], draw: tuple[str, ...],
               points: Mapping[str, Any], links: Mapping[str, tuple[str, ...]],
               sliders: Sequence[Slider] = ()) -> Cycle | None:
    """The cycle of ``[drive] positions`` with ``[plans] output`` and ``trace``; None without
    positions (then the cycle sheets and keys are refused)."""
    if not keys:
        wanted = [d for d in draw if d in CYCLE_SHEETS]
        if wanted:
            raise SceneError(f"draw {wanted[0]!r} shows the whole revolution; add [drive] positions = N (e.g. 12)",
                             key="plans.draw")
        for key in ("output", "trace", "at"):
            if key in plans:
                raise SceneError(f"{key} belongs to the cycle sheets; add [drive] positions = N (e.g. 12)",
                                 key=f"plans.{key}")
        return None
    n = cycle_positions(keys)
    if "velocities" in draw and n > MAX_VELOCITY_PLANS:
        raise SceneError(f"the velocities sheet holds at most {MAX_VELOCITY_PLANS} plans, positions = {n}; "
                         "lower positions or leave \"velocities\" out of draw", key="plans.draw")
    if "diagrams" in draw and drive.speed == 0.0:
        raise SceneError("the kinematic diagrams plot against time t = φ/ω1, which needs the crank to turn: give "
                         "omega ≠ 0 or leave \"diagrams\" out of draw", key="drive.omega")
    if "diagrams" in draw and drive.rate != 0.0:
        raise SceneError("the kinematic diagrams take ω1 constant (t = φ/ω1): give epsilon = 0 or leave "
                         "\"diagrams\" out of draw", key="drive.epsilon")
    moving = [name for name in links if name != FRAME]
    driven = [name for name in moving if name != drive.link]
    output = plans.get("output", _default_output(drive, links, sliders) if moving else "")
    if output not in moving:
        raise SceneError(f"output names the output link of the cycle, one of the moving links "
                         f"{', '.join(moving)} (a string, e.g. \"{moving[-1]}\"); got {SHOW.repr(output)}",
                         key="plans.output")
    if output == drive.link and "output" in plans:
        fix = f'name the driven link whose motion the cycle shows, e.g. "{driven[-1]}"' if driven else \
            "the mechanism has no other moving link: remove output"
        raise SceneError(f"output {output!r} is the driving link itself, whose angle is the cycle's time axis (its "
                         f"diagrams would be a straight line and its stroke the whole turn); {fix}", key="plans.output")
    if output == drive.link and "diagrams" in draw:
        raise SceneError(f"the kinematic diagrams show a driven link's motion against the crank's angle, and no "
                         f"moving link but the driving link {output} turns about a frame pivot or slides on a frame "
                         "guide; leave \"diagrams\" out of draw", key="plans.draw")
    trace = plans.get("trace", [])
    if not isinstance(trace, list) or not all(isinstance(p, str) for p in trace):
        raise SceneError(f'trace is a list of point names, e.g. ["C"]; got {SHOW.repr(trace)}', key="plans.trace")
    for p in trace:
        if p not in points:
            raise SceneError(f"unknown point {p!r} to trace; use a name from [points]", key="plans.trace")
    if len(set(trace)) != len(trace):
        raise SceneError("trace lists a point twice", key="plans.trace")
    raw = plans.get("at", list(range(n)))
    at = [whole(k) for k in raw] if isinstance(raw, list) else None
    if at is None or None in at or not all(0 <= k < n for k in at) or len(set(at)) != len(at):
        raise SceneError(f"at lists the position numbers (0 to {n - 1}, each once) drawn on sheets of their own, "
                         f"e.g. [0, 3]; got {SHOW.repr(raw)}", key="plans.at")
    if not at and not set(CYCLE_SHEETS) & set(draw):
        raise SceneError("at = [] draws no position on sheets of its own, and draw holds no sheet of the whole "
                         f"cycle ({', '.join(CYCLE_SHEETS)}): nothing would be drawn; list positions in at, or add "
                         "a cycle sheet to draw", key="plans.at")
    return Cycle(positions=n, start=keys.get("start", "angle"), output=output, trace=tuple(trace),
                 at=tuple(sorted(at)))

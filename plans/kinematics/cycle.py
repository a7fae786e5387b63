"""One revolution of a crank: the cycle's positions, the output link's motion over them and
its exact extreme positions.

The output link is a slider on a frame guide (its displacement s along the guide's direction
u, m; v = ds/dt, a = d²s/dt²) or a link pivoted on the frame (its angle ψ, rad, of the line
first point → second point; ω = dψ/dt, ε = dω/dt): a rocker when it swings, a crank when it
turns fully over the crank's revolution (the output of a drag-link four-bar, whose frame is its
shortest link), which has no extreme position. Its extreme positions are where
its velocity changes sign: bracketed on a dense grid of crank angles, then refined by Newton's
method on ds/dφ (a slider) or dψ/dφ (a rocker), solved with ω1 = 1 rad/s, ε1 = 0 so that
ds/dφ = v and d²s/dφ² = a, with bisection whenever a Newton step leaves its bracket.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..errors import AssemblyError, SceneError
from ..model import Mechanism
from ..scene import FRAME
from ..structure import Structure
from .solve import analyse
from .motion import Motion
from .. import linalg as la

__all__ = ["Output", "Cycle", "output_motion", "solve_cycle", "DENSE_MIN", "EXTREME_TOL_DEG"]

#: Fewest samples of the dense revolution (trajectories, exact curves, extreme brackets).
DENSE_MIN = 360
#: Newton on ds/dφ stops when its step is below this, degrees.
EXTREME_TOL_DEG = 1e-11
#: Most Newton (or bisection) steps of the extreme search.
EXTREME_STEPS = 80


@dataclass(frozen=True)
class Output:
    """The output link's motion at N positions. ``kind`` is "slider" (``s`` m along the guide's
    direction from the guide's anchor, ``v`` m/s, ``a`` m/s²), or "rocker" or "crank" for a link
    pivoted on the frame that swings or turns fully (``s`` the angle ψ in rad, continuous over
    the positions, ``v`` = ω rad/s, ``a`` = ε rad/s²; :func:`output_motion` says "rocker",
    :func:`solve_cycle` tells a crank from the whole revolution); ``point`` is the slider's pair
    point, or the point farthest from the pivot; ``v``, ``a`` are None when not computed."""

    link: str
    kind: str
    point: str
    s: np.ndarray
    v: np.ndarray | None
    a: np.ndarray | None


@dataclass(frozen=True)
class Cycle:
    """A solved revolution: ``motion`` at the N positions (``values``, degrees in [0, 360),
    equal steps ``step`` (degrees, negative for a crank turning clockwise) from ``start``), ``dense`` at 2·m·N + 1 crank angles from ``start`` to
    ``start`` + 360° (every position is ``dense.values[2·m·i]``, every mid-interval
    ``dense.values[2·m·i + m]``), the output link's motion on both, and ``extremes``: the
    motion at the output's two extreme positions (smallest s first), or None when it has none
    (a link that turns fully)."""

    start: float
    step: float
    every: int
    motion: Motion
    dense: Motion
    output: Output
    dense_output: Output
    extremes: Motion | None
    extreme_output: Output | None


def _kind(mech: Mechanism, link: str) -> tuple[str, str, str]:
    """("slider", the pair's key, its point) or ("rocker", its pivot, its far point)."""
    pairs = [p for p in mech.prismatics if p.slider == link and p.guide == FRAME]
    if pairs:
        same = [p for p in mech.prismatics if (p.slider, p.guide) == (link, FRAME)]
        key = f"{link}/{FRAME}" + (f"#{pairs[0].index}" if len(same) > 1 else "")
        return "slider", key, pairs[0].label
    pivots = [p for p in mech.links[link].points if p in mech.links[FRAME].local]
    if not pivots:
        raise SceneError(f"the output link {link} neither slides on a frame guide nor turns about a frame pivot, so "
                         "it has no displacement or angle to draw over the cycle; name one that does in "
                         "[plans] output", key="plans.output")
    pivot = pivots[0]
    far = max(mech.links[link].points, key=lambda q: float(la.norm(mech.sketch[q] - mech.sketch[pivot])))
    return "rocker", pivot, far


def output_motion(motion: Motion, link: str) -> Output:
    """The output link's displacement, velocity and acceleration at the motion's positions
    (read off the solved states: the slider's sliding, or the rocker's rotation θ from the
    sketch plus the sketch's direction of its first two points, unwrapped along the positions)."""
    kind, key, point = _kind(motion.mechanism, link)
    if kind == "slider":
        sl = motion.sliding[key]
        return Output(link, kind, point, sl.s, sl.v, sl.a)
    state = motion.links[link]
    local = motion.mechanism.links[link]
    base = 0.0
    if len(local.points) >= 2:
        d = local.local[local.points[1]] - local.local[local.points[0]]
        base = math.atan2(float(d[1]), float(d[0]))
    psi = np.unwrap(base + state.theta)
    return Output(link, kind, point, psi, state.omega, state.epsilon)


def _values(start: float, n: int, every: int, sense: float) -> tuple[np.ndarray, np.ndarray]:
    """The N positions (mod 360°) and the dense grid (2·every steps per position, closed), in
    the crank's sense of rotation ``sense`` (+1 CCW, −1 CW)."""
    step = sense * 360.0 / n
    dense = start + step / (2 * every) * np.arange(2 * every * n + 1)
    values = np.mod(dense[:-1:2 * every], 360.0)
    return np.where(values >= 360.0, 0.0, values), dense


def solve_cycle(mech: Mechanism, structure: Structure, *, positions: int, start: float | None, output: str,
                order: int, dense_order: int) -> Cycle:
    """The revolution of the crank in ``positions`` equal steps from ``start`` (degrees), or,
    with ``start`` None, from the output link's extreme position where its displacement (angle)
    is smallest. ``order`` is the order of the N-position motion, ``dense_order`` that of the
    dense one (each ≥ 1 when extremes are needed). Unreachable or singular positions raise the
    solver's errors, naming the angle."""
    try:
        return _solve_cycle(mech, structure, positions=positions, start=start, output=output, order=order,
                            dense_order=dense_order)
    except AssemblyError as e:
        raise type(e)(f"{e.message} — a cycle turns link {mech.drive.link} through one revolution, so it needs a "
                      f"crank that turns fully: list the angles it reaches instead of positions = {positions}",
                      group=e.group, angle=e.angle, at=e.at) from None


def _solve_cycle(mech: Mechanism, structure: Structure, *, positions: int, start: float | None, output: str,
                 order: int, dense_order: int) -> Cycle:
    """:func:`solve_cycle`, whose errors it words for a cycle."""
    every = max(1, math.ceil(DENSE_MIN / (2 * positions)))
    extremes = _extremes(mech, structure, output, mech.drive.sketch_value if start is None else start)
    if start is None:
        if extremes is None:
            raise SceneError(f"the output link {output} turns fully (a crank, not a rocker): it has no extreme "
                             "position to start from; give the first position as angle instead of "
                             "start = \"extreme\"", key="drive.start")
        start = float(extremes[0])
    sense = -1.0 if mech.drive.speed < 0 else 1.0
    values, dense_values = _values(start, positions, every, sense)
    motion = analyse(mech, structure, values, order=order)
    dense = analyse(mech, structure, dense_values, order=max(dense_order, order))
    ext = ext_out = None
    if extremes is not None:
        ext = analyse(mech, structure, np.asarray(extremes), order=max(order, 1))
        ext_out = output_motion(ext, output)
    outputs = (output_motion(motion, output), output_motion(dense, output), ext_out)
    full = outputs[1]
    if full.kind == "rocker" and abs(float(full.s[-1] - full.s[0])) > math.pi:   # a turn: 2π, a swing: 0
        outputs = tuple(None if o is None else replace(o, kind="crank") for o in outputs)
    return Cycle(start=start, step=sense * 360.0 / positions, every=every, motion=motion, dense=dense,
                 output=outputs[0], dense_output=outputs[1], extremes=ext, extreme_output=outputs[2])


def _extremes(mech: Mechanism, structure: Structure, output: str, around: float) -> np.ndarray | None:
    """The crank angles (degrees) of the output's smallest and largest displacement over one
    revolution from ``around``, refined where ds/dφ changes sign; None when it never does."""
    _kind(mech, output)
    unit = replace(mech, drive=replace(mech.drive, speed=1.0, rate=0.0))   # ω1 = 1: v = ds/dφ, a = d²s/dφ²
    grid = around + np.arange(DENSE_MIN + 1) * (360.0 / DENSE_MIN)
    out = output_motion(analyse(unit, structure, grid, order=1), output)
    v = out.v
    scale = float(np.max(np.abs(v)))
    if scale == 0.0:
        return None
    change = np.flatnonzero((np.sign(v[:-1]) != np.sign(v[1:])) | (v[:-1] == 0.0))
    if not change.size:
        return None
    lo, hi = grid[change].copy(), grid[change + 1].copy()
    v_lo = v[change]
    phi = 0.5 * (lo + hi)
    for _ in range(EXTREME_STEPS):
        o = output_motion(analyse(unit, structure, phi, order=2), output)
        d1, d2 = o.v, o.a          # ds/dφ per radian, d²s/dφ²
        same = np.sign(d1) == np.sign(v_lo)
        lo, v_lo = np.where(same, phi, lo), np.where(same, d1, v_lo)
        hi = np.where(same, hi, phi)
        with np.errstate(divide="ignore", invalid="ignore"):
            newton = phi - np.degrees(d1 / d2)
        inside = np.isfinite(newton) & (newton > np.minimum(lo, hi)) & (newton < np.maximum(lo, hi))
        nxt = np.where(inside, newton, 0.5 * (lo + hi))
        done = np.all((np.abs(nxt - phi) < EXTREME_TOL_DEG) | (d1 == 0.0))
        phi = np.where(d1 == 0.0, phi, nxt)
        if done:
            break
    s = output_motion(analyse(unit, structure, phi, order=0), output).s
    if out.kind == "rocker":        # the angles of the refined points, on the grid's branch
        s = s + 2 * np.pi * np.round((np.interp(phi, grid, out.s) - s) / (2 * np.pi))
    return np.array([phi[int(np.argmin(s))], phi[int(np.argmax(s))]], dtype=float)

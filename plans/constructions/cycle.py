"""The cycle sheets as geometry in paper mm (y up): the mechanism at every position of one
revolution with its extreme positions and the trajectories of chosen points, and the
velocity plans of every position side by side with a table of their values.

Nothing here solves anything: the positions, extreme positions and dense samples are solved
motions (:class:`plans.kinematics.cycle.Cycle`), read point by point.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..kinematics import Motion
from ..scene import FRAME
from .plans import Plan, PlanPoint, PlanVector, velocity_plan
from .scales import SERIES, extent_of, fitting_scale
from .scheme import Scheme, scheme
from .. import linalg as la

__all__ = ["PositionsSheet", "Trace", "Tick", "Cell", "VelocitiesSheet", "positions_sheet", "velocities_sheet",
           "value_table", "shifted", "GRID_MM", "TABLE_ROW_MM"]

#: The drawing area of an A3 landscape sheet that the velocity plans and their table share, mm.
GRID_MM = (392.0, 249.0)
#: Largest drawing of the positions sheet (width, height), mm: an A3 landscape sheet's drawing
#: area less room for the labels and the notes.
POSITIONS_MM = (330.0, 200.0)
#: Height of one row of the table of values, mm.
TABLE_ROW_MM = 5.5
#: Room kept round each small plan for its labels, and for its caption above it, mm.
CELL_ROOM_MM = 7.0
CAPTION_MM = 6.0


@dataclass(frozen=True)
class Trace:
    """The trajectory of ``point``: its positions over one revolution (mm), a closed curve."""

    point: str
    path: tuple[tuple[float, float], ...]


@dataclass(frozen=True)
class Tick:
    """Position ``index`` of a slider's point on its frame guide: ``at`` (mm) on the guide,
    ``axis`` the guide's unit direction as drawn (its hatching on the right of it), ``side``
    +1 (labelled on the left of the axis) when the point moves along the axis there, −1 when
    it moves back: each stroke's positions are numbered on a side of their own."""

    index: int
    at: tuple[float, float]
    axis: tuple[float, float]
    side: float


@dataclass(frozen=True)
class PositionsSheet:
    """The mechanism at N positions (``poses``: one scheme each, position i = poses[i]), the
    output link's two extreme positions (``extremes``, smallest displacement first, each with
    its crank angle in ``extreme_angles``), trajectories, the crank's pivot and tip, the output
    link and its point, and ``stroke``: the output's travel between the extremes (m, or rad).
    A slider on the frame has ``ticks``: its positions marked on the guide (its block is drawn
    at the extremes only, as a textbook draws the positions of a ram)."""

    mu_l: float
    poses: tuple[Scheme, ...]
    angles: tuple[float, ...]
    extremes: tuple[Scheme, ...]
    extreme_angles: tuple[float, ...]
    traces: tuple[Trace, ...]
    pivot: str
    tip: str
    output: str
    point: str
    kind: str
    stroke: float | None
    ticks: tuple[Tick, ...] = ()


def positions_scale(dense: Motion) -> float:
    """μl (m/mm) of the positions sheet: the smallest series scale that draws every point at
    every dense sample within POSITIONS_MM."""
    pts = np.stack([dense.position(p) for p in dense.mechanism.sketch], axis=1)
    w, h = extent_of(pts)
    return max(fitting_scale(w, POSITIONS_MM[0]), fitting_scale(h, POSITIONS_MM[1]))


def positions_sheet(motion: Motion, extremes: Motion | None, dense: Motion, *, output: str, point: str,
                    kind: str, extreme_s: np.ndarray | None, trace: tuple[str, ...]) -> PositionsSheet:
    """The positions sheet from the N-position motion, the motion at the two extreme positions
    (None when the output has none) and the dense motion (trajectories of ``trace``; it sets
    the scale, :func:`positions_scale`)."""
    mech = motion.mechanism
    mu_l = positions_scale(dense)
    poses = tuple(scheme(motion, i, mu_l) for i in range(len(motion)))
    ext = () if extremes is None else tuple(scheme(extremes, j, mu_l) for j in range(len(extremes)))
    traces = tuple(Trace(p, tuple((float(x), float(y)) for x, y in dense.position(p) / mu_l)) for p in trace)
    stroke = None if extreme_s is None else float(extreme_s[1] - extreme_s[0])
    angles = tuple(float(v) for v in motion.values)
    ext_angles = () if extremes is None else tuple(float(v) % 360.0 for v in extremes.values)
    return PositionsSheet(mu_l=mu_l, poses=poses, angles=angles, extremes=ext, extreme_angles=ext_angles,
                          traces=traces, pivot=mech.drive.pivot, tip=mech.drive.tip, output=output, point=point,
                          kind=kind, stroke=stroke, ticks=_ticks(motion, output, poses))


def _ticks(motion: Motion, output: str, poses: tuple[Scheme, ...]) -> tuple[Tick, ...]:
    """The positions of slider ``output`` on its frame guide (none for another output): each
    position's pin, and its side by the sense of its velocity along the guide (the sense of
    its next step when the velocities are not known, or the point stands)."""
    mech = motion.mechanism
    pr = next((pr for pr in mech.prismatics if pr.slider == output and pr.guide == FRAME
               and len(mech.links[output].points) == 1), None)
    if pr is None:
        return ()
    u = np.asarray(pr.direction, dtype=float)
    u = u / float(la.norm(u))
    at = motion.position(pr.label)
    s = np.array([float(la.dot(p, u)) for p in at])
    v = np.array([float(la.dot(w, u)) for w in motion.velocity(pr.label)]) if motion.order >= 1 else np.zeros(len(s))
    n = len(s)
    step = np.array([s[(i + 1) % n] - s[i] for i in range(n)])
    sense = np.where(v != 0.0, v, step)
    axis = (float(u[0]), float(u[1]))
    return tuple(Tick(i, poses[i].points[pr.label], axis, 1.0 if sense[i] >= 0.0 else -1.0) for i in range(n))


# --- the velocity plans of every position --------------------------------------------------

@dataclass(frozen=True)
class Cell:
    """The velocity plan of position ``index`` (crank angle ``angle``, deg) moved into its cell;
    ``caption`` is where its caption's baseline starts (mm)."""

    index: int
    angle: float
    plan: Plan
    caption: tuple[float, float]


@dataclass(frozen=True)
class VelocitiesSheet:
    """Every position's velocity plan in one scale ``mu_v`` on a grid of ``columns`` cells
    (``size``: cell width, height, mm) in the box (0, 0)–``GRID_MM``, with the table of values
    below them (its top-left corner ``table_at``, mm)."""

    mu_v: float
    cells: tuple[Cell, ...]
    columns: int
    size: tuple[float, float]
    table: "ValueTable"
    table_at: tuple[float, float]


@dataclass(frozen=True)
class ValueTable:
    """The values at every position: ``columns`` (header in label markup, unit), ``rows`` of
    numbers (position number, crank angle in degrees, |v| of each point m/s, ω of each link
    rad/s), and the ``points`` and ``links`` the columns name."""

    columns: tuple[tuple[str, str], ...]
    rows: tuple[tuple[float, ...], ...]
    points: tuple[str, ...]
    links: tuple[str, ...]


def value_table(motion: Motion) -> ValueTable:
    """|v| of every point of a moving link that is not on the frame, and ω of every moving
    link with two points or more but the crank, at every position (read off the motion)."""
    mech = motion.mechanism
    points = tuple(p for p in mech.sketch if motion.carrier(p) != FRAME and p not in mech.links[FRAME].local)
    links = tuple(n for n in mech.moving if n != mech.drive.link and len(mech.links[n].points) >= 2)
    speed = [la.norm(motion.velocity(p), axis=1) for p in points]
    omega = [motion.links[n].omega for n in links]
    rows = tuple((float(i), float(motion.values[i]), *(float(v[i]) for v in speed), *(float(w[i]) for w in omega))
                 for i in range(len(motion)))
    columns = (("№", ""), (f"φ_{{{mech.drive.link}}}", "°")) + tuple((f"v_{{{p}}}", "m/s") for p in points) + \
        tuple((f"ω_{{{n}}}", "rad/s") for n in links)
    return ValueTable(columns, rows, points, links)


def shifted(plan: Plan, dx: float, dy: float) -> Plan:
    """The plan moved by (dx, dy) mm, without its construction lines (a small plan among many
    shows its vectors only)."""
    def mv(p: tuple[float, float]) -> tuple[float, float]:
        return (p[0] + dx, p[1] + dy)

    return replace(plan, points=tuple(PlanPoint(p.label, mv(p.xy)) for p in plan.points),
                   vectors=tuple(PlanVector(v.quantity, mv(v.tail), mv(v.head), v.value, v.kind) for v in plan.vectors),
                   lines=())


def _box(plan: Plan) -> tuple[float, float, float, float]:
    xy = np.array([p.xy for p in plan.points])
    (x0, y0), (x1, y1) = xy.min(axis=0), xy.max(axis=0)
    return float(x0), float(y0), float(x1), float(y1)


def _grid(n: int) -> tuple[int, int]:
    """Columns and rows of a grid of n cells on a landscape sheet (about 4:3 cells)."""
    cols = max(1, math.ceil(math.sqrt(n * 4.0 / 3.0)))
    return cols, math.ceil(n / cols)


def velocities_sheet(motion: Motion) -> VelocitiesSheet:
    """Every position's velocity plan, one series scale μV for all (the smallest whose largest
    plan fits its cell), on a grid above the table of values."""
    table = value_table(motion)
    n = len(motion)
    cols, rows = _grid(n)
    table_h = TABLE_ROW_MM * (n + 2)
    cw, ch = GRID_MM[0] / cols, (GRID_MM[1] - table_h - 4.0) / rows
    room_w, room_h = cw - 2 * CELL_ROOM_MM, ch - 2 * CELL_ROOM_MM - CAPTION_MM
    unit = [velocity_plan(motion, i, 1.0) for i in range(n)]            # m/s as mm: the extents at μ = 1
    boxes = [_box(p) for p in unit]
    w = max(b[2] - b[0] for b in boxes)
    h = max(b[3] - b[1] for b in boxes)
    extent = max(w / room_w, h / room_h)
    if not extent > 0.0:          # at rest: every image at the pole, any scale draws it
        extent = 1.0
    k = math.floor(math.log10(extent)) - 1
    mu = min(m * 10.0 ** e for e in range(k, k + 3) for m in SERIES if m * 10.0 ** e >= extent)
    mu = float(f"{mu:.6g}")
    cells = []
    for i in range(n):
        r, c = divmod(i, cols)
        plan = velocity_plan(motion, i, mu)
        x0, y0, x1, y1 = _box(plan)
        cx, cy = c * cw + cw / 2, GRID_MM[1] - r * ch - CAPTION_MM - ch / 2 + CAPTION_MM / 2
        moved = shifted(plan, cx - (x0 + x1) / 2, cy - (y0 + y1) / 2)
        cells.append(Cell(i, float(motion.values[i]), moved, (c * cw + 3.0, GRID_MM[1] - r * ch - 4.5)))
    return VelocitiesSheet(mu_v=mu, cells=tuple(cells), columns=cols, size=(cw, ch), table=table,
                           table_at=(0.0, table_h))

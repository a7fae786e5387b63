"""The assignment sheet of a handout variant: the scheme to scale, the data table and empty
framed areas where the student draws the plans, on an A3 landscape sheet with the standard
frame and title block (:mod:`.sheet`).

Layout (paper mm, y down; the drawing area of A3 landscape is x 21…414, y 6…256): the data
table and the task at the foot of the left column, the scheme in the room above them, one framed area per plan
the scene asks (velocity, acceleration) stacked in the right column. The scheme's μl is the
finest value of the standard series at which the scheme fits its slot.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Mapping, Sequence

from ..constructions.scales import SERIES
from ..constructions.scheme import Scheme
from ..scene import Scene
from .canvas import Canvas, fmt
from .marks import bounds
from .scheme import scheme_layers
from .sheet import FORMATS, TitleBlock, new_sheet
from .style import Style
from .text import Box, runs, width, wrap

__all__ = ["draw_assignment", "given_cells", "Layout", "LAYOUT"]


@dataclass(frozen=True)
class Layout:
    """Where things go on the A3 landscape sheet (paper mm, y down)."""

    left: Box = Box(21.0, 6.0, 216.0, 256.0)      # the scheme above, the data table and task below
    inset: float = 2.0        # the table's and the task's margin inside the left column
    answers: Box = Box(220.0, 8.0, 412.0, 254.0)
    gap: float = 4.0          # between the answer areas
    row: float = 7.0          # a data table row
    columns: int = 4          # data table cells per row

    def __post_init__(self) -> None:
        if not (self.row > 0 and self.columns >= 1):
            raise ValueError("Layout.row must be positive and Layout.columns at least 1")


LAYOUT = Layout()
#: What each plan's framed area is called, with the scale the student writes in.
_AREAS = {"velocity": ("Velocity plan (pole p)", "μ_V = ________ (m/s)/mm"),
          "acceleration": ("Acceleration plan (pole π)", "μ_a = ________ (m/s²)/mm")}


def _fit_mu(scheme_at: Callable[[float], Scheme], slot: Box) -> float:
    """The finest series μl (m/mm) at which the scheme, with room for its labels, fits ``slot``."""
    for mu in sorted({float(f"{m:g}e{k}") for k in range(-12, 22) for m in SERIES}):
        b = bounds(_coords(scheme_at(mu)))
        if b[2] - b[0] <= slot.x1 - slot.x0 and b[3] - b[1] <= slot.y1 - slot.y0:
            return mu
    raise ValueError("the scheme fits no series scale")   # a sketch is at most 1e20 m (scene.MAX_COORD_M)


def _coords(sch) -> list:
    return list(sch.points.values()) + [g.start for g in sch.guides] + [g.end for g in sch.guides] + \
        [p for c in sch.cylinders for p in c.barrel] + [p for a in sch.inputs for p in (a.start, a.end)]


def _values(v: tuple[float, ...], unit: str) -> str:
    """The drive's values as a list; angles in 0 … 360° (a turn past 360° is written as its
    angle, 370° as 10°)."""
    if unit == "°":
        return ", ".join(f"{(x % 360.0) + 0.0:g}{unit}" for x in v)
    return ", ".join(f"{x:g}{unit}" for x in v)


def given_cells(scene: Scene, lengths: Mapping[str, float] | None, drive: bool = True) -> list[str]:
    """The data table's cells: every length (named as ``lengths`` names them, else by the
    scene's point order), then (``drive``) the drive's position, speed and rate."""
    if lengths is None:
        lengths = {"".join(sorted(pair, key=list(scene.points).index)): value for pair, value in scene.lengths.items()}
    cells = [f"l_{{{name.replace('-', '')}}} = {value:g} m" for name, value in lengths.items()]
    d = scene.drive
    j = d.link
    if not drive:
        return cells
    if d.kind.angular:
        cells += [f"φ_{{{j}}} = {_values(d.values, '°')}", f"ω_{{{j}}} = {d.speed:g} rad/s",
                  f"ε_{{{j}}} = {d.rate:g} rad/s²"]
    else:
        cells += [f"s = {_values(d.values, ' m')}", f"v = {d.speed:g} m/s", f"a = {d.rate:g} m/s²"]
    return cells


def _flow(widths: Sequence[float], cell: float, columns: int) -> list[tuple[int, int, int]]:
    """(row, column, span) of each data cell in turn: as many columns as its text needs (all of
    a row at most), on the next row when the rest of this one is too short."""
    out, r, c = [], 0, 0
    for w in widths:
        span = min(max(1, math.ceil(w / cell - 1e-9)), columns)
        if c + span > columns:
            r, c = r + 1, 0
        out.append((r, c, span))
        c += span
    return out


def _task(scene: Scene, points: Sequence[str], links: Sequence[str]) -> str:
    """One sentence saying what to draw and find (the velocities and accelerations of ``points``,
    the angular ones of ``links``)."""
    kinds = [k for k in ("velocity", "acceleration") if k in scene.draw]
    plans = " and the ".join(f"{k} plan" for k in kinds) or "scheme"
    what = {("velocity",): "velocities", ("acceleration",): "accelerations"}.get(tuple(kinds),
                                                                                 "velocities and accelerations")
    where = "each given position" if len(scene.drive.values) > 1 else "the given position"
    sentence = f"Task: draw the {plans} at {where}"
    if kinds:
        angular = "angular " + what.replace(" and accelerations", " and angular accelerations")
        sentence += (f" to scale; find the {what} of points {', '.join(points)}"
                     + (f" and the {angular} of links {', '.join(links)}" if links else ""))
    return sentence + "."


def draw_assignment(scheme_at: Callable[[float], Scheme], scene: Scene, *, variant: str, points: Sequence[str],
                    links: Sequence[str], lengths: Mapping[str, float] | None = None, style: Style = Style(),
                    layout: Layout = LAYOUT, extra: Sequence[str] = (), task: str | None = None,
                    areas: Sequence[tuple[str, str, str]] | None = None, position: str | None = None,
                    drawn_at: float | None = None) -> str:
    """SVG text of a variant's assignment sheet (A3 landscape): the scheme at the first asked
    position (``scheme_at(μl)`` constructs it; drawn in the finest series μl that fits its slot),
    the given lengths and drive values, the task (find the velocities and accelerations of
    ``points``, the angular ones of ``links``), and an empty framed area per plan, labelled.
    ``lengths`` names the given lengths as the scene file does (``OA``). Other kinds of
    assignment add ``extra`` data cells (masses, loads), say their own ``task``, frame their own
    ``areas`` ((id, name, the scale to write in) each) and give their own ``position`` (the title
    block's row; the drive's cells are then left out of the table)."""
    fmt_ = FORMATS[2]
    d = scene.drive
    j = d.link
    L = layout.left
    t = Box(L.x0 + layout.inset, L.y0, L.x1 - layout.inset, L.y1 - 1.0)
    cells = given_cells(scene, lengths, drive=position is None) + list(extra)
    cw = (t.x1 - t.x0) / layout.columns
    places = _flow([width(runs(c), style.text, False) + 4.0 for c in cells], cw, layout.columns)
    rows = max((r for r, _, _ in places), default=-1) + 1
    task = wrap(task or _task(scene, points, links), t.x1 - t.x0 - 6.0, style.text)
    top = t.y1 - 5.0 * len(task) - 1.5 - rows * layout.row        # the table's first line
    slot = Box(L.x0, L.y0, L.x1, top - 6.5 - 3.0)
    mu = _fit_mu(scheme_at, slot)
    position = position or (
        f"φ_{{{j}}} = {_values(d.values, '°')}, ω_{{{j}}} = {d.speed:g} rad/s, ε_{{{j}}} = {d.rate:g} rad/s²"
        if d.kind.angular else f"s = {_values(d.values, ' m')}, v = {d.speed:g} m/s, a = {d.rate:g} m/s²")
    block = TitleBlock(scene.title, f"Assignment, {variant}", position,
                       f"μ_l = {mu:g} m/mm (scheme); plan scales: the student's")
    ident = "assignment"
    dwg, canvas = new_sheet(fmt_, (0.0, 0.0, 1.0, 1.0), ident=ident, style=style, block=block)
    dwg.attribs["data-sheet"] = "assignment"

    sch = scheme_at(mu)
    b = bounds(_coords(sch))
    offset = ((slot.x0 + slot.x1) / 2 - (b[0] + b[2]) / 2, (slot.y0 + slot.y1) / 2 + (b[1] + b[3]) / 2)
    sc = Canvas(dwg, style, offset, slot)
    scheme_layers(dwg, sc, sch, ident, style)
    sc.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))

    g = dwg.add(dwg.g(id=f"{ident}-data", stroke=style.colour, fill="none", stroke_width=fmt(style.thin, 3)))
    texts = dwg.add(dwg.g(id=f"{ident}-data-text"))
    at = d.values[0] if drawn_at is None else drawn_at
    caption = "Given" + (f" (the scheme is drawn at φ_{{{j}}} = {at % 360.0 + 0.0:.4g}°)"
                         if d.kind.angular and (len(d.values) > 1 or drawn_at is not None) else "")
    canvas.text(texts, (t.x0, top - 2.5), caption, size=style.text)
    for k, (cell, (r, c, span)) in enumerate(zip(cells, places)):
        x, y = t.x0 + c * cw, top + r * layout.row
        g.add(dwg.rect(insert=(fmt(x, 3), fmt(y, 3)), size=(fmt(span * cw, 3), fmt(layout.row, 3))))
        canvas.text(texts, (x + 2.0, y + layout.row / 2 + 1.2), cell, size=style.text, ident=f"{ident}-given{k}")
    y = top + rows * layout.row + 5.5
    for k, line in enumerate(task):
        canvas.text(texts, (t.x0, y + 5.0 * k), line, size=style.text, ident=f"{ident}-task{k}")

    if areas is None:
        kinds = [k for k in ("velocity", "acceleration") if k in scene.draw] or ["velocity"]
        areas = [(k, *_AREAS[k]) for k in kinds]
        many = len(d.values) > 1
    else:
        many = False
    a = layout.answers
    h = (a.y1 - a.y0 - layout.gap * (len(areas) - 1)) / len(areas)
    frames = dwg.add(dwg.g(id=f"{ident}-answers", stroke=style.colour, fill="none", stroke_width=fmt(style.vector, 3)))
    for k, (kind, name, scale) in enumerate(areas):
        y0 = a.y0 + k * (h + layout.gap)
        el = dwg.rect(insert=(fmt(a.x0, 3), fmt(y0, 3)), size=(fmt(a.x1 - a.x0, 3), fmt(h, 3)),
                      id=f"{ident}-area-{kind}")
        el.attribs["data-area"] = kind
        frames.add(el)
        plural = name.replace(" plan", " plans") if many else name
        canvas.text(texts, (a.x0 + 3.0, y0 + 6.0), plural, size=style.text, ident=f"{ident}-area-{kind}-name")
        canvas.text(texts, (a.x1 - 3.0 - width(runs(scale), style.text, False), y0 + 6.0), scale, size=style.text,
                    ident=f"{ident}-area-{kind}-scale")
    return dwg.tostring()

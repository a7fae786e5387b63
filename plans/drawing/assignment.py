"""The assignment sheet of a handout variant: the scheme to scale, the data table and empty
framed areas where the student draws the plans, on an A3 landscape sheet with the standard
frame and title block (:mod:`.sheet`); the areas it has no room for go on A3 answer sheets.

Layout (paper mm, y down; the drawing area of A3 landscape is x 21…414, y 6…256): the data
table and the task at the foot of the left column, the scheme in the room above them, the
framed areas in columns on the right. Each area is as large as the drawings it must hold (the
answer key's, :class:`Area`) plus its caption row and a margin; the areas take the sheet's
room in order, a column at a time, while the left column keeps at least ``Layout.min_left``
(an area past that, and every one after it, goes on the next answer sheet); the room left over
widens the left column up to its usual width, then the areas. The scheme's μl is the finest
value of the standard series at which the scheme fits its slot.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Callable, Mapping, Sequence
from xml.etree import ElementTree as ET

import svgwrite

from ..constructions.scales import SERIES
from ..constructions.scheme import Scheme
from ..scene import Scene
from .canvas import Canvas, fmt
from .marks import bounds
from .scheme import scheme_layers
from .sheet import FORMATS, TitleBlock, new_sheet
from .style import Style
from .text import Box, Run, box, runs, width, wrap

__all__ = ["draw_assignment", "given_cells", "Layout", "LAYOUT", "Area", "area_size", "frame_areas", "answer_sheets", "drawings",
           "gear_frames", "add_frames"]


@dataclass(frozen=True)
class Layout:
    """Where things go on the A3 landscape sheet (paper mm, y down)."""

    left: Box = Box(21.0, 6.0, 216.0, 256.0)      # the scheme above, the data table and task below (widest)
    inset: float = 2.0        # the table's and the task's margin inside the left column
    answers: Box = Box(220.0, 8.0, 412.0, 254.0)  # the areas' room (x0: the answer sheets' is `sheet_x0`)
    gap: float = 4.0          # between the answer areas
    row: float = 7.0          # a data table row
    columns: int = 4          # data table cells per row
    min_left: float = 170.0   # the left column's least width, mm
    sheet_x0: float = 23.0    # an answer sheet's areas start here, mm

    def __post_init__(self) -> None:
        if not (self.row > 0 and self.columns >= 1):
            raise ValueError("Layout.row must be positive and Layout.columns at least 1")
        if not 0 < self.min_left <= self.left.x1 - self.left.x0:
            raise ValueError("Layout.min_left must be positive and at most the left column's width")


LAYOUT = Layout()
#: What each plan's framed area is called, with the scale the student writes in.
_AREAS = {"velocity": ("Velocity plan (pole p)", "μ_V = ________ (m/s)/mm"),
          "acceleration": ("Acceleration plan (pole π)", "μ_a = ________ (m/s²)/mm")}
#: An area's caption row (its name and scale, baseline at 6 mm) above the room, and the margin
#: around the room on the other sides, mm.
CAPTION_MM = 8.0
PAD_MM = 3.0
#: Between the drawings of one area (each group's force plan), mm; they go in rows at most
#: SHELF_MM wide (one drawing wider than that has a row of its own).
PIECE_GAP_MM = 6.0
SHELF_MM = 200.0
#: The room of an area whose drawings are not known, mm.
DEFAULT_ROOM_MM = (120.0, 90.0)


@dataclass(frozen=True)
class Area:
    """A framed area where the student draws: ``kind`` (its ``data-area``: velocity,
    acceleration, forces, lever, diagrams, wittenbauer, pictures), its caption ``name`` and the
    ``scale`` the student writes in (markup), the drawings it must hold (``holds``: width,
    height of each, mm: the answer key's at the key's scales) and the position it is for
    (``position``: a sheet-name suffix such as ``-60``, when several are drawn)."""

    kind: str
    name: str
    scale: str
    holds: tuple[tuple[float, float], ...] = ()
    position: str = ""


def _room(holds: Sequence[tuple[float, float]]) -> tuple[float, float]:
    """Width and height (mm) of the room holding every drawing of ``holds``, side by side in
    rows at most SHELF_MM wide, PIECE_GAP_MM apart."""
    if not holds:
        return DEFAULT_ROOM_MM
    rows: list[list[tuple[float, float]]] = [[]]
    for w, h in holds:
        row = rows[-1]
        if row and sum(x for x, _ in row) + PIECE_GAP_MM * len(row) + w > SHELF_MM:
            rows.append(row := [])
        row.append((w, h))
    return (max(sum(x for x, _ in r) + PIECE_GAP_MM * (len(r) - 1) for r in rows),
            sum(max(y for _, y in r) for r in rows) + PIECE_GAP_MM * (len(rows) - 1))


def area_size(area: Area, style: Style = Style()) -> tuple[float, float]:
    """The least width and height of ``area``'s frame, mm: its room with the margin and the
    caption row, and wide enough for its name and scale side by side."""
    w, h = _room(area.holds)
    caption = width(runs(area.name), style.text, False) + width(runs(area.scale), style.text, False) + 10.0
    return max(w + 2.0 * PAD_MM, caption), h + CAPTION_MM + PAD_MM


def _columns(sizes: Sequence[tuple[float, float]], room: float, height: float, gap: float, *,
             first: bool = False) -> list[list[int]]:
    """The first areas of ``sizes`` (in order) that fit a region ``room`` wide and ``height``
    high, in columns left to right, each column's areas one above the other: the indices of
    each column's areas (an area higher than the region counts as ``height`` high; ``first``:
    the first area is placed even when wider than the region, an empty answer sheet's)."""
    cols: list[list[int]] = []
    used, col_w, col_h = 0.0, 0.0, 0.0
    for k, (w, h) in enumerate(sizes):
        h = min(h, height)
        if cols and col_h + gap + h <= height and used - col_w + max(col_w, w) <= room:
            cols[-1].append(k)
            used, col_w, col_h = used - col_w + max(col_w, w), max(col_w, w), col_h + gap + h
        elif used + (gap if cols else 0.0) + w <= room or first and not k:
            used += (gap if cols else 0.0) + w
            cols.append([k])
            col_w, col_h = w, h
        else:
            break
    return cols


def _frames(cols: list[list[int]], sizes: Sequence[tuple[float, float]], region: Box, gap: float) -> list[Box]:
    """The frame of each area placed by :func:`_columns` in ``region``: the room left over
    shared out, the columns widened alike, each column's areas heightened alike."""
    widths = [max(sizes[k][0] for k in col) for col in cols]
    extra = max(0.0, (region.x1 - region.x0 - gap * (len(cols) - 1) - sum(widths)) / max(len(cols), 1))
    out, x = [], region.x0
    for col, w in zip(cols, widths):
        hs = [min(sizes[k][1], region.y1 - region.y0) for k in col]
        more = max(0.0, (region.y1 - region.y0 - gap * (len(col) - 1) - sum(hs)) / len(col))
        y = region.y0
        for h in hs:
            out.append(Box(x, y, min(x + w + extra, region.x1), y + h + more))
            y += h + more + gap
        x += w + extra + gap
    return out


def frame_areas(dwg, canvas: Canvas, placed: Sequence[tuple[Area, Box]], ident: str, style: Style) -> None:
    """Draw each area's frame (``<rect data-area>``) and its caption: the name at the top left,
    the scale to write in at the top right."""
    frames = dwg.add(dwg.g(id=f"{ident}-answers", stroke=style.colour, fill="none",
                           stroke_width=fmt(style.vector, 3)))
    texts = dwg.add(dwg.g(id=f"{ident}-answers-text"))
    for area, b in placed:
        key = f"{area.kind}{area.position}"
        el = dwg.rect(insert=(fmt(b.x0, 3), fmt(b.y0, 3)), size=(fmt(b.x1 - b.x0, 3), fmt(b.y1 - b.y0, 3)),
                      id=f"{ident}-area-{key}")
        el.attribs["data-area"] = area.kind
        if area.position:
            el.attribs["data-position"] = area.position
        frames.add(el)
        canvas.text(texts, (b.x0 + 3.0, b.y0 + 6.0), area.name, size=style.text, ident=f"{ident}-area-{key}-name")
        canvas.text(texts, (b.x1 - 3.0 - width(runs(area.scale), style.text, False), b.y0 + 6.0), area.scale,
                    size=style.text, ident=f"{ident}-area-{key}-scale")


_SVG = "{http://www.w3.org/2000/svg}"
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def drawings(svg: str) -> list[tuple[str, Box]]:
    """The drawings of a sheet as its SVG text marks them (a ``<g>`` with ``data-plan`` or
    ``data-diagram``; a detail, an enlarged piece of another, left out), each as what it is
    (``velocity``, ``force``, ``lever``, ``M``, ``wittenbauer``…) and its box on the paper
    (mm, y down): the ink's coordinates and the texts' boxes (the sheets draw with absolute
    coordinates, paths of M, L and Z only)."""
    out: list[tuple[str, Box]] = []

    def visit(el) -> None:
        for child in el:
            if child.tag != f"{_SVG}g":
                continue
            what = child.get("data-plan") or child.get("data-diagram")
            if what is None:
                visit(child)
            elif child.get("data-detail") is None and "-detail-" not in child.get("id", ""):
                b = _extent(child)
                if b is not None:
                    out.append((what, b))

    visit(ET.fromstring(svg))
    return out


def _extent(group) -> Box | None:
    """The box of every shape and text inside ``group`` (mm), or None when it holds none."""
    xs: list[float] = []
    ys: list[float] = []
    for el in group.iter():
        tag = el.tag.removeprefix(_SVG)
        num = lambda name: float(el.get(name, "0"))  # noqa: E731
        if tag == "line":
            xs += [num("x1"), num("x2")]
            ys += [num("y1"), num("y2")]
        elif tag in ("path", "polygon", "polyline"):
            v = [float(t) for t in _NUMBER.findall(el.get("d" if tag == "path" else "points", ""))]
            xs += v[0::2]
            ys += v[1::2]
        elif tag == "rect":
            xs += [num("x"), num("x") + num("width")]
            ys += [num("y"), num("y") + num("height")]
        elif tag == "circle":
            xs += [num("cx") - num("r"), num("cx") + num("r")]
            ys += [num("cy") - num("r"), num("cy") + num("r")]
        elif tag == "text":
            size = float(el.get("font-size", "3.5"))
            parts = tuple(Run(t.text or "", float(t.get("font-size", size)) < size) for t in el.iter(f"{_SVG}tspan"))
            b = box(parts or (Run(el.text or ""),), size, el.get("font-style") == "italic", num("x"), num("y"),
                    el.get("text-anchor", "start"))
            xs += [b.x0, b.x1]
            ys += [b.y0, b.y1]
    return Box(min(xs), min(ys), max(xs), max(ys)) if xs else None


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
                    areas: Sequence[Area] | None = None, position: str | None = None,
                    drawn_at: float | None = None) -> tuple[str, ...]:
    """SVG texts of a variant's assignment (A3 landscape sheets): first the assignment sheet,
    with the scheme at the first asked position (``scheme_at(μl)`` constructs it; drawn in the
    finest series μl that fits its slot), the given lengths and drive values, the task (find
    the velocities and accelerations of ``points``, the angular ones of ``links``) and the
    framed areas it has room for; then an answer sheet for each further batch of areas (see the
    module docstring). ``lengths`` names the given lengths as the scene file does (``OA``).
    Other kinds of assignment add ``extra`` data cells (masses, loads), say their own ``task``,
    frame their own ``areas`` (default: a plan of each kind the scene draws, of no known size)
    and give their own ``position`` (the title block's row; the drive's cells are then left out
    of the table)."""
    fmt_ = FORMATS[2]
    d = scene.drive
    j = d.link
    if areas is None:
        areas = [Area(k, *_AREAS[k]) for k in [k for k in ("velocity", "acceleration") if k in scene.draw]
                 or ["velocity"]]
    sizes = [area_size(a, style) for a in areas]
    a = layout.answers
    cols = _columns(sizes, a.x1 - layout.left.x0 - layout.min_left - layout.gap, a.y1 - a.y0, layout.gap)
    first = sum(len(c) for c in cols)
    used = sum(max(sizes[k][0] for k in c) for c in cols) + layout.gap * max(len(cols) - 1, 0)
    left_w = min(layout.left.x1 - layout.left.x0, a.x1 - layout.left.x0 - layout.gap - used) if cols else \
        layout.left.x1 - layout.left.x0
    L = Box(layout.left.x0, layout.left.y0, layout.left.x0 + left_w, layout.left.y1)
    region = Box(L.x1 + layout.gap, a.y0, a.x1, a.y1)
    sheets = _answer_sheets(areas[first:], sizes[first:], layout)
    t = Box(L.x0 + layout.inset, L.y0, L.x1 - layout.inset, L.y1 - 1.0)
    cells = [row for c in given_cells(scene, lengths, drive=position is None) + list(extra)   # a long one: rows
             for row in wrap(c, t.x1 - t.x0 - 4.0, style.text)]
    cw = (t.x1 - t.x0) / layout.columns
    places = _flow([width(runs(c), style.text, False) + 4.0 for c in cells], cw, layout.columns)
    rows = max((r for r, _, _ in places), default=-1) + 1
    told = task or _task(scene, points, links)
    if sheets:
        told += "".join(f" Answer sheet {k + 2}: " + "; ".join(_plain_name(x) for x in batch) + "."
                        for k, batch in enumerate(sheets))
    task = wrap(told, t.x1 - t.x0 - 6.0, style.text)
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
    frame_areas(dwg, canvas, list(zip(areas[:first], _frames(cols, sizes, region, layout.gap))), ident, style)
    placed = [_batch_frames(batch, layout, style) for batch in sheets]
    return (dwg.tostring(), *answer_sheets(scene.title, variant, position, "plan scales: the student's", placed,
                                           fmt_, style))


def answer_sheets(title: str, variant: str, position: str, scales: str,
                  batches: Sequence[Sequence[tuple[Area, Box]]], fmt_, style: Style) -> list[str]:
    """SVG texts of an assignment's answer sheets 2, 3, …: each batch's framed areas (placed) on a
    sheet of format ``fmt_`` with its title block (``variant``: "variant 01")."""
    out = []
    for k, batch in enumerate(batches):
        block = TitleBlock(title, f"Assignment, {variant}: answer sheet {k + 2}", position, scales)
        ident = f"assignment-{k + 2}"
        dwg, canvas = new_sheet(fmt_, (0.0, 0.0, 1.0, 1.0), ident=ident, style=style, block=block)
        dwg.attribs["data-sheet"] = "assignment"
        frame_areas(dwg, canvas, batch, ident, style)
        out.append(dwg.tostring())
    return out


def _plain_name(area: Area) -> str:
    """An area's name as the task's note on the answer sheets says it (its pole left out)."""
    return re.sub(r" \(pole .\)", "", area.name)


def _answer_sheets(areas: Sequence[Area], sizes: Sequence[tuple[float, float]], layout: Layout) -> list[list[Area]]:
    """The areas the assignment sheet has no room for, in batches of an answer sheet each."""
    a, out, k = layout.answers, [], 0
    while k < len(areas):
        n = sum(len(c) for c in _columns(sizes[k:], a.x1 - layout.sheet_x0, a.y1 - a.y0, layout.gap, first=True))
        out.append(list(areas[k:k + n]))
        k += n
    return out


def _batch_frames(batch: Sequence[Area], layout: Layout, style: Style) -> list[tuple[Area, Box]]:
    """The frames of an answer sheet's areas: the whole width of its drawing area."""
    a = layout.answers
    sizes = [area_size(x, style) for x in batch]
    region = Box(layout.sheet_x0, a.y0, a.x1, a.y1)
    cols = _columns(sizes, region.x1 - region.x0, a.y1 - a.y0, layout.gap, first=True)
    return list(zip(batch, _frames(cols, sizes, region, layout.gap)))


#: Around a gear train's picture in its frame: room for its labels, mm.
GEAR_MARGIN_MM = 8.0
_PICTURES = {"gear-velocity": ("Linear-velocity picture", "μ_V = ________ (m/s)/mm"),
             "gear-omega": ("Angular-velocity picture", "μ_ω = ________ (rad/s)/mm")}


def gear_frames(key: str, sheet: str, gap: float = LAYOUT.gap) -> list[tuple[Area, Box]]:
    """The frames of a gear train's assignment ``sheet`` (SVG text), each where its ``key``
    (the gear sheet, laid out alike) draws the picture (the linear-velocity picture beside the
    side view it is projected from): the picture's box, GEAR_MARGIN_MM around it and the caption
    row above, within the drawing area and clear of what the sheet draws; both pictures in one
    frame when theirs would meet."""
    root = ET.fromstring(sheet)
    area = next((f for f in FORMATS if f"{f.width:g}mm" == root.get("width") and f"{f.height:g}mm" ==
                 root.get("height")), FORMATS[2]).area
    m = GEAR_MARGIN_MM
    found = [(Area("pictures", *_PICTURES[what], ((b.x1 - b.x0, b.y1 - b.y0),), "-" + what[5:]), b)
             for what, b in drawings(key) if what in _PICTURES]
    frames = [Box(b.x0 - m, b.y0 - m - CAPTION_MM, b.x1 + m, b.y1 + m) for _, b in found]
    if len(found) == 2 and frames[0].overlaps(frames[1], gap):
        (a, p), (c, q) = found
        found = [(Area("pictures", "Velocity pictures", f"{a.scale}; {c.scale}", a.holds + c.holds),
                  Box(min(p.x0, q.x0), min(p.y0, q.y0), max(p.x1, q.x1), max(p.y1, q.y1)))]
        frames = [Box(min(f.x0 for f in frames), min(f.y0 for f in frames), max(f.x1 for f in frames),
                      max(f.y1 for f in frames))]
    taken = _obstacles(root)
    out = []
    for (a, p), f in zip(found, frames):
        f = Box(f.x0, f.y0, max(f.x1, f.x0 + area_size(Area(a.kind, a.name, a.scale, ((0.0, 0.0),)))[0]), f.y1)
        f = Box(max(f.x0, area.x0), max(f.y0, area.y0), min(f.x1, area.x1), min(f.y1, area.y1))
        for o in taken:
            if o.overlaps(f) and not o.overlaps(p):
                f = _clear(f, p, o)
        out.append((a, f))
    return out


def _clear(f: Box, p: Box, o: Box, gap: float = 1.0) -> Box:
    """Frame ``f`` of a picture ``p`` cut back on one side, the one that loses least, so that it
    keeps ``gap`` mm from ``o`` (a box beside ``p``)."""
    cuts = []
    if o.y0 >= p.y1:
        cuts.append(Box(f.x0, f.y0, f.x1, min(f.y1, o.y0 - gap)))
    if o.y1 <= p.y0:
        cuts.append(Box(f.x0, max(f.y0, o.y1 + gap), f.x1, f.y1))
    if o.x0 >= p.x1:
        cuts.append(Box(f.x0, f.y0, min(f.x1, o.x0 - gap), f.y1))
    if o.x1 <= p.x0:
        cuts.append(Box(max(f.x0, o.x1 + gap), f.y0, f.x1, f.y1))
    return max(cuts, key=lambda b: (b.x1 - b.x0) * (b.y1 - b.y0), default=f)


def _obstacles(root) -> list[Box]:
    """The box of every shape and text a sheet draws but its frame and title block."""
    out = []
    for g in root:
        if g.tag == f"{_SVG}g" and not g.get("id", "").endswith(("-frame", "-title", "-title-text")):
            for el in g.iter():
                if el.tag.removeprefix(_SVG) in ("line", "path", "polygon", "polyline", "rect", "circle", "text"):
                    b = _extent(el)
                    if b is not None:
                        out.append(b)
    return out


def add_frames(svg: str, placed: Sequence[tuple[Area, Box]], ident: str, style: Style = Style()) -> str:
    """``svg`` (a sheet's text) with the frames and captions of ``placed`` drawn on top."""
    dwg = svgwrite.Drawing(debug=False, profile="full")
    frame_areas(dwg, Canvas(dwg, style, (0.0, 0.0), Box(0.0, 0.0, 1e9, 1e9)), placed, ident, style)
    head, end, tail = svg.rpartition("</svg>")
    return head + "".join(el.tostring() for el in dwg.elements if el.elementname == "g") + end + tail

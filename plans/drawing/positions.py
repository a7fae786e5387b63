"""The cycle's sheets of positions and of velocity plans.

``draw_positions``: the frame's supports and guides once, the mechanism at every position in
thin lines (the crank's tip numbered A₀ … A_{N−1} and the output point likewise, as a
textbook numbers the positions), the output link's two extreme positions in thick red lines
labelled with primes (E′ where its displacement is smallest, E″ largest), and the
trajectories of the traced points as smooth closed curves.

``draw_velocities``: every position's velocity plan from its pole in one scale (the vectors
tagged as on a velocity plan sheet, so ``plans check`` measures them), each captioned with its
position, and the table of |v| of the points and ω of the links at every position.
"""

from __future__ import annotations


import numpy as np

from ..constructions.cycle import GRID_MM, TABLE_ROW_MM, PositionsSheet, VelocitiesSheet
from ..constructions.scheme import Scheme
from .canvas import Canvas, fmt
from .marks import bounds, markup
from .scheme import block_corners, frame_guide, support
from .sheet import FORMATS, TitleBlock, choose_format, new_sheet, note_lines
from .style import Style
from .svg import Heading, plan_layers
from .text import runs, width
from .. import linalg as la

__all__ = ["draw_positions", "draw_velocities", "PIN_MM", "NOTE_ROOM_MM"]

#: Radius of a pin on the thin positions, mm.
PIN_MM = 0.6
#: Room kept below the drawing for the notes, mm.
NOTE_ROOM_MM = 12.0


def _frame_parts(canvas: Canvas, g, sch: Scheme, ident: str, style: Style) -> None:
    """The frame's guides (hatched) and supports, once."""
    for k, gd in enumerate(sch.guides):
        if not gd.fixed:
            continue
        canvas.line(g, gd.start, gd.end, width=style.vector, stroke_width=fmt(style.vector, 3), id=f"{ident}-guide{k}")
        frame_guide(canvas, g, gd, k, ident, style)
    for k, p in enumerate(sch.supports):
        support(canvas, g, sch.points[p], k, ident, style)


def _pose(canvas: Canvas, g, sch: Scheme, ident: str, w: float, style: Style, pins: bool = True) -> None:
    """One position of the moving links: bars, plates (outlines), blocks, slots, pins."""
    sw = fmt(w, 3)
    for gd in sch.guides:
        if not gd.fixed:
            canvas.line(g, gd.start, gd.end, width=w, stroke_width=sw, id=f"{ident}-slot{gd.link}")
    for name, pts in sch.links:
        if len(pts) >= 3:
            canvas.polygon(g, [sch.points[p] for p in pts], width=w, stroke_width=sw, fill="none",
                           stroke_linejoin="round", id=f"{ident}-link{name}")
        elif len(pts) == 2:
            canvas.line(g, sch.points[pts[0]], sch.points[pts[1]], width=w, stroke_width=sw, id=f"{ident}-link{name}")
    for b in sch.blocks:
        if b.pin is not None:
            canvas.line(g, b.pin, b.center, width=w, stroke_width=sw, id=f"{ident}-rod{b.link}")
        canvas.polygon(g, block_corners(b), width=w, fill="none", stroke_width=sw, id=f"{ident}-block{b.link}")
    if pins:
        for k, p in enumerate(sch.joints):
            if p in sch.supports:
                continue
            canvas.circle(g, sch.points[p], PIN_MM, filled=True, fill="#fff", stroke_width=fmt(style.thin, 3),
                          id=f"{ident}-j{k}")


def draw_positions(sheet: PositionsSheet, heading: Heading, *, ident: str, style: Style = Style(),
                   notes: tuple[str, ...] = ()) -> str:
    """SVG text of the positions sheet (see the module)."""
    coords = [xy for s in sheet.poses + sheet.extremes for xy in s.points.values()]
    coords += [p for s in sheet.poses[:1] for gd in s.guides for p in (gd.start, gd.end)]
    coords += [p for t in sheet.traces for p in t.path]
    x0, y0, x1, y1 = bounds(coords)
    box = (x0, y0 - NOTE_ROOM_MM, x1, y1)
    f = choose_format(box[2] - box[0], box[3] - box[1]) or FORMATS[2]
    scales = f"μ_l = {sheet.mu_l:g} m/mm; positions 0 … {len(sheet.poses) - 1} every {abs(360.0 / len(sheet.poses)):g}°"
    dwg, canvas = new_sheet(f, box, ident=ident, style=style,
                            block=TitleBlock(heading.mechanism, heading.sheet, heading.position, scales))
    g = dwg.g(id=f"{ident}-scheme", stroke=style.colour, fill="none", stroke_linecap="round")
    g.attribs["data-mu"] = repr(sheet.mu_l)
    g.attribs["data-plan"] = "scheme"
    traces = dwg.g(id=f"{ident}-traces", stroke=style.vector_colour, fill="none")
    for k, t in enumerate(sheet.traces):
        el = canvas.polyline(traces, t.path, closed=True, width=style.vector, stroke_width=fmt(style.vector, 3),
                             id=f"{ident}-trace{k}")
        el.attribs["data-point"] = t.point
    pivot_xy = np.asarray(sheet.poses[0].points[sheet.pivot])
    radius = float(la.norm(np.subtract(sheet.poses[0].points[sheet.tip], pivot_xy)))
    el = canvas.circle(traces, pivot_xy, radius, stroke=style.construction_colour, stroke_width=fmt(style.thin, 3),
                       stroke_dasharray=style.dash, id=f"{ident}-crank-circle")
    el.attribs["data-point"] = sheet.tip
    g.add(traces)
    poses = dwg.g(id=f"{ident}-poses", stroke=style.colour)
    for i, sch in enumerate(sheet.poses):
        pg = dwg.g(id=f"{ident}-pos{i}")
        pg.attribs["data-position"] = str(i)
        pg.attribs["data-angle"] = repr(sheet.angles[i])
        _pose(canvas, pg, sch, f"{ident}-pos{i}", style.thin, style)
        poses.add(pg)
    g.add(poses)
    ext = dwg.g(id=f"{ident}-extremes", stroke=style.component_colour)
    for j, sch in enumerate(sheet.extremes):
        eg = dwg.g(id=f"{ident}-ext{j}")
        eg.attribs["data-angle"] = repr(sheet.extreme_angles[j])
        _pose(canvas, eg, sch, f"{ident}-ext{j}", style.link, style, pins=False)
        ext.add(eg)
    g.add(ext)
    frame = dwg.g(id=f"{ident}-frame-parts", stroke=style.colour, fill="none")
    _frame_parts(canvas, frame, sheet.poses[0], ident, style)
    g.add(frame)
    dwg.add(g)
    labels = dwg.g(id=f"{ident}-labels", fill=style.colour)
    first = sheet.poses[0]
    centre = np.mean([xy for s in sheet.poses for xy in s.points.values()], axis=0)
    for j, sch in enumerate(sheet.extremes):
        xy = sch.points[sheet.point]
        canvas.circle(labels, xy, 0.9, filled=True, fill=style.component_colour, stroke="none", id=f"{ident}-ed{j}")
        canvas.label(labels, xy, markup(sheet.point) + ("′" if j == 0 else "″"), size=style.text,
                     prefer=np.subtract(xy, centre), ident=f"{ident}-el{j}", digits=False, near=0.8,
                     fill=style.component_colour)
    for p in first.supports:
        xy = first.points[p]
        canvas.label(labels, xy, markup(p), size=style.text, prefer=(-1.0, 0.4), ident=f"{ident}-s{p}",
                     digits=False, near=1.0)
    pivot = np.asarray(first.points[sheet.pivot])
    for i, sch in enumerate(sheet.poses):
        tip = sch.points[sheet.tip]
        canvas.label(labels, tip, f"{markup(sheet.tip)}_{{{i}}}", size=style.small_text,
                     prefer=np.subtract(tip, pivot), ident=f"{ident}-a{i}", digits=False, near=0.6)
    for i, sch in enumerate(sheet.poses):
        if sheet.point == sheet.tip:
            break
        xy = sch.points[sheet.point]
        canvas.label(labels, xy, f"{markup(sheet.point)}_{{{i}}}", size=style.small_text,
                     prefer=np.subtract(xy, centre), ident=f"{ident}-o{i}", digits=False, near=0.6)
    for k, t in enumerate(sheet.traces):
        path = np.array(t.path)
        top = path[int(np.argmax(path[:, 1]))]
        canvas.label(labels, top, f"path of {markup(t.point)}", size=style.small_text, italic=False, prefer=(0.0, 1.0),
                     ident=f"{ident}-tl{k}", digits=False, near=0.6, fill=style.vector_colour)
    dwg.add(labels)
    if notes:
        note_lines(canvas, dwg.add(dwg.g(id=f"{ident}-notes")), notes, style)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))
    return dwg.tostring()


def _number(x: float, digits: int = 4) -> str:
    """A table entry: ``digits`` significant digits, no exponent for ordinary values."""
    if x == 0.0:
        return "0"
    s = f"{x:.{digits}g}"
    return s.replace("-", "−")


def draw_velocities(sheet: VelocitiesSheet, heading: Heading, *, ident: str, style: Style = Style()) -> str:
    """SVG text of every position's velocity plan and the table of values (see the module)."""
    f = FORMATS[2]
    scale = f"μ_V = {sheet.mu_v:g} (m/s)/mm on every plan; vector = drawn length × μ_V"
    dwg, canvas = new_sheet(f, (0.0, 0.0, GRID_MM[0], GRID_MM[1]), ident=ident, style=style,
                            block=TitleBlock(heading.mechanism, heading.sheet, heading.position, scale))
    captions = dwg.g(id=f"{ident}-captions", fill=style.colour)
    for c in sheet.cells:
        plan_layers(dwg, canvas, c.plan, f"{ident}-{c.index}", style)
        canvas.text(captions, canvas.paper(c.caption), f"{c.index}: φ_1 = {c.angle:.4g}°", size=style.small_text,
                    ident=f"{ident}-cap{c.index}")
    dwg.add(captions)
    _table(dwg, canvas, sheet, ident, style)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))
    return dwg.tostring()


def _table(dwg, canvas: Canvas, sheet: VelocitiesSheet, ident: str, style: Style) -> None:
    """The table of values: a header of symbols and units, one row per position."""
    t = sheet.table
    size = style.small_text
    header = [f"{sym}, {unit}" if unit else sym for sym, unit in t.columns]
    cells = [[f"{int(r[0])}", f"{r[1]:.4g}"] + [_number(v) for v in r[2:]] for r in t.rows]
    widths = [max(width_of(h, size) for h in [header[k]] + [row[k] for row in cells]) + 4.0
              for k in range(len(header))]
    total = sum(widths)
    x0 = (GRID_MM[0] - total) / 2
    top = sheet.table_at[1]
    g = dwg.g(id=f"{ident}-table", stroke=style.colour, fill="none")
    g.attribs["class"] = "value-table"
    texts = dwg.g(id=f"{ident}-table-text", fill=style.colour)
    n_rows = len(cells) + 1
    for k in range(n_rows + 1):
        y = top - k * TABLE_ROW_MM
        w = style.vector if k in (0, 1, n_rows) else style.thin
        canvas.line(g, (x0, y), (x0 + total, y), width=w, stroke_width=fmt(w, 3), id=f"{ident}-tr{k}")
    x = x0
    for k in range(len(widths) + 1):
        w = style.vector if k in (0, len(widths)) else style.thin
        canvas.line(g, (x, top), (x, top - n_rows * TABLE_ROW_MM), width=w, stroke_width=fmt(w, 3),
                    id=f"{ident}-tc{k}")
        if k < len(widths):
            x += widths[k]
    for r, row in enumerate([header] + cells):
        x = x0
        base = top - r * TABLE_ROW_MM - TABLE_ROW_MM / 2 - 0.26 * size * 1.0
        for k, text in enumerate(row):
            el_id = f"{ident}-t{r}-{k}"
            at = canvas.paper((x + widths[k] / 2 - width_of(text, size) / 2, base))
            canvas.text(texts, at, text, size=size, ident=el_id)
            x += widths[k]
    dwg.add(g)
    dwg.add(texts)


def width_of(text: str, size: float, italic: bool = False) -> float:
    """Width of ``text`` in label markup at ``size`` mm (texts are written start-anchored at
    a measured offset: a centred text with subscripts is not drawn alike by every renderer)."""
    return width(runs(text), size, italic)

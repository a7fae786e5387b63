"""The cycle's sheets of positions and of velocity plans.

``draw_positions``: the frame's supports and guides once, the mechanism at every position in
thin lines (the crank's tip numbered A₀ … A_{N−1} and the output point likewise, as a
textbook numbers the positions), the output link's two extreme positions in thick red lines
labelled with primes (E′ where its displacement is smallest, E″ largest), and the
trajectories of the traced points as smooth closed curves. A slider on the frame is drawn as
a textbook draws a ram's positions: its block at the two extremes only, each position a tick
across the guide, numbered in a column beside the guide (one side for each stroke), each
number spread clear of the others along the guide and joined to its tick by a leader.

``draw_velocities``: every position's velocity plan from its pole in one scale (the vectors
tagged as on a velocity plan sheet, so ``plans check`` measures them), each captioned with its
position, and the table of |v| of the points and ω of the links at every position.
"""

from __future__ import annotations

import math

import numpy as np
import shapely

from ..constructions.cycle import GRID_MM, TABLE_ROW_MM, PositionsSheet, Tick, VelocitiesSheet
from ..constructions.scheme import Scheme
from .canvas import CLEARANCE, Canvas, fmt
from .marks import bounds, markup
from .scheme import block_corners, frame_guide, support
from .sheet import FORMATS, TitleBlock, choose_format, new_sheet, note_lines
from .style import Style
from .svg import Heading, plan_layers
from .text import box as text_box, runs, significant, width
from .. import linalg as la

__all__ = ["draw_positions", "draw_velocities", "PIN_MM", "NOTE_ROOM_MM", "TICK_MM", "LABEL_NEAR_MM"]

#: Radius of a pin on the thin positions, mm.
PIN_MM = 0.6
#: Room kept below the drawing for the notes, mm.
NOTE_ROOM_MM = 12.0
#: A slider's position on its guide: the tick across the guide, mm; the least gap between two
#: of its numbers along the guide, mm; a number farther than LABEL_NEAR_MM (mm) from its
#: tick's end is joined to it by a leader; the column of numbers is tried up to COLUMN_MM
#: (mm) from the guide, in steps of COLUMN_STEP_MM.
TICK_MM = 4.0
LABEL_GAP_MM = 0.6
LABEL_NEAR_MM = 1.0
COLUMN_MM = 40.0
COLUMN_STEP_MM = 0.5


def _frame_parts(canvas: Canvas, g, sch: Scheme, ident: str, style: Style) -> None:
    """The frame's guides (hatched) and supports, once."""
    for k, gd in enumerate(sch.guides):
        if not gd.fixed:
            continue
        canvas.line(g, gd.start, gd.end, width=style.vector, stroke_width=fmt(style.vector, 3), id=f"{ident}-guide{k}")
        frame_guide(canvas, g, gd, k, ident, style)
    for k, p in enumerate(sch.supports):
        support(canvas, g, sch.points[p], k, ident, style)


def _pose(canvas: Canvas, g, sch: Scheme, ident: str, w: float, style: Style, pins: bool = True,
          hide: tuple[str, str] | None = None) -> None:
    """One position of the moving links: bars, plates (outlines), blocks, slots, pins; ``hide``
    (a link, its point): that block and pin left out (a slider's position drawn as a tick)."""
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
        if hide is not None and b.link == hide[0]:
            continue
        if b.pin is not None:
            canvas.line(g, b.pin, b.center, width=w, stroke_width=sw, id=f"{ident}-rod{b.link}")
        canvas.polygon(g, block_corners(b), width=w, fill="none", stroke_width=sw, id=f"{ident}-block{b.link}")
    if pins:
        for k, p in enumerate(sch.joints):
            if p in sch.supports or (hide is not None and p == hide[1]):
                continue
            canvas.circle(g, sch.points[p], PIN_MM, filled=True, fill="#fff", stroke_width=fmt(style.thin, 3),
                          id=f"{ident}-j{k}")


def draw_positions(sheet: PositionsSheet, heading: Heading, *, ident: str, style: Style = Style(),
                   notes: tuple[str, ...] = (), branches: tuple[tuple[int, int], ...] = ()) -> str:
    """SVG text of the positions sheet (see the module). ``branches``: pairs of neighbouring
    positions (k, k + 1) between which a group's count of real assemblies changes; each is marked
    on the crank's circle between the two crank positions, a bar outwards, lettered "branch"."""
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
    _branches(canvas, dwg, traces, sheet, branches, pivot_xy, radius, ident, style)
    poses = dwg.g(id=f"{ident}-poses", stroke=style.colour)
    for i, sch in enumerate(sheet.poses):
        pg = dwg.g(id=f"{ident}-pos{i}")
        pg.attribs["data-position"] = str(i)
        pg.attribs["data-angle"] = repr(sheet.angles[i])
        _pose(canvas, pg, sch, f"{ident}-pos{i}", style.thin, style,
              hide=(sheet.output, sheet.point) if sheet.ticks else None)
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
    for t in sheet.ticks:   # each position of the slider: a tick across its guide
        n = np.array([-t.axis[1], t.axis[0]]) * TICK_MM / 2
        el = canvas.line(frame, np.add(t.at, -n), np.add(t.at, n), width=style.thin,
                         stroke_width=fmt(style.thin, 3), id=f"{ident}-tick{t.index}")
        el.attribs["data-position"] = str(t.index)
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
    if sheet.ticks:
        _tick_labels(canvas, labels, sheet, ident, style)
    for i, sch in enumerate(sheet.poses):
        if sheet.point == sheet.tip or sheet.ticks:
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


#: Length of a branch mark outwards from the crank's circle, mm.
BRANCH_MM = 6.0


def _branches(canvas: Canvas, dwg, parent, sheet: PositionsSheet, branches: tuple[tuple[int, int], ...],
              pivot: np.ndarray, radius: float, ident: str, style: Style) -> None:
    """A bar on the crank's circle halfway (the short way round) between the crank's tips at
    positions k and j, for each branch (k, j); ``data-branch`` = "k-j"."""
    for k, j in branches:
        a = [math.atan2(*np.subtract(sheet.poses[i].points[sheet.tip], pivot)[::-1]) for i in (k, j)]
        mid = a[0] + 0.5 * ((a[1] - a[0] + math.pi) % (2.0 * math.pi) - math.pi)
        u = np.array([math.cos(mid), math.sin(mid)])
        inner, outer = pivot + u * radius, pivot + u * (radius + BRANCH_MM)
        el = canvas.line(parent, inner, outer, width=style.link, stroke=style.component_colour,
                         stroke_width=fmt(style.link, 3), id=f"{ident}-branch{k}-{j}")
        el.attribs["data-branch"] = f"{k}-{j}"
        canvas.label(parent, outer, "branch", size=style.small_text, italic=False, prefer=tuple(u),
                     ident=f"{ident}-branch{k}-{j}-l", digits=False, near=0.6, fill=style.component_colour)


def _tick_labels(canvas: Canvas, parent, sheet: PositionsSheet, ident: str, style: Style) -> None:
    """The numbers of a slider's positions (``sheet.ticks``): each stroke's in a column on its
    side of the guide, spread along the guide just enough to keep LABEL_GAP_MM apart (the
    least squares shift from their ticks, in their order), the column as near the guide as
    keeps every number clear of the ink, other labels and the drawing area's edge; a number
    away from its tick is joined to the tick's end by a leader. A stroke whose column finds
    no room anywhere has its numbers placed as other labels are."""
    size = style.small_text
    tree = shapely.STRtree(canvas.ink)
    for side in (1.0, -1.0):
        ticks = sorted((t for t in sheet.ticks if t.side == side), key=lambda t: float(la.dot(t.at, t.axis)))
        if not ticks:
            continue
        texts = [f"{markup(sheet.point)}_{{{t.index}}}" for t in ticks]
        placed = _column(canvas, tree, ticks, texts, size, side, canvas.placed)
        for t, text, spot in zip(ticks, texts, placed or [None] * len(ticks)):
            end = np.add(t.at, side * np.array([-t.axis[1], t.axis[0]]) * TICK_MM / 2)
            if spot is None:
                canvas.label(parent, end, text, size=size, prefer=side * np.array([-t.axis[1], t.axis[0]]),
                             ident=f"{ident}-o{t.index}", digits=False, near=0.6)
                continue
            b = canvas.text(parent, spot, text, size=size, italic=True, ident=f"{ident}-o{t.index}")
            tip = canvas.paper(end)
            near = (min(max(tip[0], b.x0), b.x1), min(max(tip[1], b.y0), b.y1))
            if math.dist(tip, near) > LABEL_NEAR_MM:
                el = canvas.line(parent, end, (near[0] - canvas.dx, canvas.dy - near[1]), width=0.6 * style.thin,
                                 stroke=style.construction_colour, stroke_width=fmt(0.6 * style.thin, 3),
                                 id=f"{ident}-ol{t.index}")
                el.attribs["class"] = "leader"
                el.attribs["data-position"] = str(t.index)


def _column(canvas: Canvas, tree, ticks: list[Tick], texts: list[str], size: float, side: float,
            others) -> list[tuple[float, float]] | None:
    """Baseline starts (paper mm) of ``texts``, the numbers of ``ticks`` (in order along the
    guide) in a column on ``side`` of it (see :func:`_tick_labels`), or None."""
    u = np.array(ticks[0].axis, dtype=float)
    n = side * np.array([-u[1], u[0]])
    boxes = [text_box(runs(t, digits=False), size, True, 0.0, 0.0) for t in texts]
    w = np.array([b.x1 - b.x0 for b in boxes])
    h = np.array([b.y1 - b.y0 for b in boxes])
    along = np.abs(u[0]) * w + np.abs(u[1]) * h
    across = np.abs(n[0]) * w + np.abs(n[1]) * h
    t = np.array([float(la.dot(k.at, u)) for k in ticks])
    gaps = np.concatenate([[0.0], np.cumsum((along[:-1] + along[1:]) / 2 + LABEL_GAP_MM)])
    spread = _increasing(t - gaps) + gaps          # the least squares shift keeping the gaps
    base = np.array(ticks[0].at) + (spread - t[0])[:, None] * u
    a = canvas.area
    taken = [shapely.box(o.x0, o.y0, o.x1, o.y1) for o in others]
    for d in np.arange(TICK_MM / 2 + LABEL_NEAR_MM / 2, COLUMN_MM, COLUMN_STEP_MM):
        centres = [canvas.paper(c) for c in base + (d + across / 2)[:, None] * n]
        rects = [(cx - wi / 2, cy - hi / 2, cx + wi / 2, cy + hi / 2) for (cx, cy), wi, hi in zip(centres, w, h)]
        if any(r[0] < a.x0 or r[1] < a.y0 or r[2] > a.x1 or r[3] > a.y1 for r in rects):
            continue
        grown = [shapely.box(r[0] - CLEARANCE, r[1] - CLEARANCE, r[2] + CLEARANCE, r[3] + CLEARANCE) for r in rects]
        if len(tree.query(grown, predicate="intersects")[0]) or any(g.intersects(o) for g in grown for o in taken):
            continue
        return [(r[0] - b.x0, r[1] - b.y0) for r, b in zip(rects, boxes)]
    return None


def _increasing(y: np.ndarray) -> np.ndarray:
    """The non-decreasing sequence nearest ``y`` in least squares (pooled adjacent violators)."""
    blocks: list[list[float]] = []              # [mean, count]
    for v in y:
        blocks.append([float(v), 1.0])
        while len(blocks) > 1 and blocks[-2][0] > blocks[-1][0]:
            (m1, c1), (m2, c2) = blocks.pop(-2), blocks.pop()
            blocks.append([(m1 * c1 + m2 * c2) / (c1 + c2), c1 + c2])
    return np.concatenate([np.full(int(c), m) for m, c in blocks])


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
    cells = [[f"{int(r[0])}", f"{r[1]:.4g}"] + [significant(v, 4) for v in r[2:]] for r in t.rows]
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

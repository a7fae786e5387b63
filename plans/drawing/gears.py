"""The gear sheet (``-gears``): the train's side view, its linear-velocity picture on the same
radius axis and its angular-velocity picture (see :mod:`plans.constructions.gears`).

The pitch-point velocities (``vp:a-b``) are tagged vectors of the group ``data-plan="gear-velocity"``
(μ = μV), the ω segments (``omega:L``) of ``data-plan="gear-omega"`` (μ = μω), so ``plans check``
measures them; each link's velocity line carries ``data-link-line`` and each ray of the angular
picture ``data-ray`` with the link's name, so the checker also finds every ray parallel to its
link's line.
"""

from __future__ import annotations

import math
from typing import Callable

from ..constructions.gears import GearSheet
from .canvas import Canvas, fmt
from .marks import bounds, markup, vector
from .scheme import _hatch, support
from .sheet import FORMATS, TitleBlock, choose_format, new_sheet, note_lines
from .style import Style
from .svg import Heading
from .text import runs, significant, width

__all__ = ["draw_gears", "fits", "to_fit"]

#: Length of the ticks at a wheel's pitch diameter, mm (each side of the wheel's line).
TICK_MM = 2.0
#: How far a ring gear's rim stands out beyond its pitch circle, mm.
RIM_MM = 5.0
#: Where a turning ring gear's disc runs down to its shaft, mm beyond the ring's plane.
DISC_MM = 16.0
#: Radius of a turning ring gear's hollow shaft in the side view, mm.
HUB_MM = 3.0
#: The speed table's column widths and row height, mm.
TABLE_COLUMNS_MM = (16.0, 12.0, 26.0, 26.0)
ROW_MM = 6.0
#: Room kept below the drawing for the notes, mm.
NOTE_ROOM_MM = 10.0


def _direction(canvas: Canvas, tail, head) -> str:
    (x0, y0), (x1, y1) = canvas.paper(tail), canvas.paper(head)
    return repr(math.degrees(math.atan2(y1 - y0, x1 - x0)) + 0.0)


def _coords(sheet: GearSheet) -> list[tuple[float, float]]:
    pts: list[tuple[float, float]] = []
    for w in sheet.wheels:
        extra = RIM_MM + 3.0 if w.internal else TICK_MM
        for sign in ((1, -1) if w.mirror else (1,)):
            pts += [(w.x - TICK_MM, sign * w.y - w.r - extra), (w.x + TICK_MM, sign * w.y + w.r + extra)]
    for s in sheet.shafts:
        pts += [(s.x0 - 6.0, s.y - 8.0), (s.x1, s.y)]
    for ln in sheet.lines:
        pts += [ln.start, ln.end]
    pts += [sheet.pole, (sheet.pole[0], sheet.pole[1] - 6.0)]
    pts += [seg.head for seg in sheet.omega]
    for short, k, (ox, oy) in ((*_short(sheet), _detail_origin(sheet)), (*_short_v(sheet), _v_detail_origin(sheet))):
        if short:                                      # the ω and v details under the pole
            pts += [(ox - 4.0, oy + 6.0), (ox + max(k * abs(s.head[0] - s.tail[0]) for s in short) + 14.0,
                                           oy - 4.0 * len(short) - 3.0)]
    x, y = _table_at(sheet)
    pts += [(x, y), (x + sum(TABLE_COLUMNS_MM), y - ROW_MM * (len(sheet.table) + 1))]
    if sheet.end is not None:
        for _, (cx, cy), r, _ in sheet.end.circles:
            pts += [(cx - r - 2.0, cy - r - 2.0), (cx + r + 2.0, cy + r + 6.0)]
    return pts


def _table_at(sheet: GearSheet) -> tuple[float, float]:
    """The table's top left corner: under the side view, or under the end view, mm."""
    x0 = min([s.x0 for s in sheet.shafts] + [w.x for w in sheet.wheels]) - 8.0
    bottom = min(min(w.y for w in sheet.wheels if not w.mirror) - max(w.r for w in sheet.wheels) - 6.0,
                 min((-w.y - w.r - 6.0 for w in sheet.wheels if w.mirror), default=0.0))
    if sheet.end is not None:
        (cx, cy), reach = sheet.end.centre, max(r + math.dist(c, sheet.end.centre)
                                                for _, c, r, _ in sheet.end.circles)
        return min(x0, cx - reach), cy - reach - 12.0
    return x0, bottom - 12.0


def _end_view(dwg, canvas: Canvas, sheet: GearSheet, ident: str, style: Style, labels) -> None:
    """The planets seen along the axis: pitch circles, the carrier's arms, a caption with its scale."""
    end = sheet.end
    if end is None:
        return
    g = dwg.g(id=f"{ident}-end", stroke=style.colour, fill="none")
    g.attribs["data-mu"] = repr(end.mu)
    g.attribs["data-plan"] = "scheme"
    for k, (a, b) in enumerate(end.arms):
        canvas.line(g, a, b, width=style.link, stroke_width=fmt(style.link, 3), id=f"{ident}-earm{k}")
    seen = set()
    for k, (name, c, r, ring) in enumerate(end.circles):
        w = style.link if ring else style.vector
        canvas.circle(g, c, r, stroke_width=fmt(w, 3), id=f"{ident}-ec{k}")
        if name not in seen:        # each wheel named once: a central one at its top, a planet outside it
            seen.add(name)
            out = (c[0] - end.centre[0], c[1] - end.centre[1])
            at, prefer = ((c[0], c[1] + r), (0.3, 1.0)) if out == (0.0, 0.0) else \
                ((c[0] + r * 0.7071, c[1] + r * 0.7071), (1.0, 1.0))
            canvas.label(labels, at, markup(name), size=style.small_text, prefer=prefer, ident=f"{ident}-el{k}",
                         near=0.6)
    canvas.circle(g, end.centre, 0.9, filled=True, fill=style.colour, stroke="none", id=f"{ident}-eo")
    dwg.add(g)
    reach = max(r + math.dist(c, end.centre) for _, c, r, _ in end.circles)
    canvas.text(labels, canvas.paper((end.centre[0] - reach, end.centre[1] - reach - 6.0)),
                f"along the axis (μ_l = {end.mu:g} m/mm)", size=style.small_text, ident=f"{ident}-ecap")


def _table(dwg, canvas: Canvas, sheet: GearSheet, at: tuple[float, float], ident: str, style: Style,
           given: frozenset[str] | None = None) -> None:
    """The speeds of every wheel and carrier: name, teeth, n (rpm), ω (rad/s); with ``given``
    (an assignment) only those links' speeds are filled in, the rest left for the student."""
    header = ["link", "z", "n, rpm", "ω, rad/s"]
    rows = [header] + [[markup(r.name), "—" if r.teeth is None else str(r.teeth)]
                       + ([significant(r.rpm, 6), significant(r.omega, 5)] if given is None or r.name in given else ["", ""])
                       for r in sheet.table]
    g = dwg.g(id=f"{ident}-table", stroke=style.colour, fill="none")
    g.attribs["class"] = "value-table"
    texts = dwg.g(id=f"{ident}-table-text", fill=style.colour)
    x0, top = at
    total = sum(TABLE_COLUMNS_MM)
    for k in range(len(rows) + 1):
        w = style.vector if k in (0, 1, len(rows)) else style.thin
        canvas.line(g, (x0, top - k * ROW_MM), (x0 + total, top - k * ROW_MM), width=w, stroke_width=fmt(w, 3),
                    id=f"{ident}-tr{k}")
    x = x0
    for k in range(len(TABLE_COLUMNS_MM) + 1):
        w = style.vector if k in (0, len(TABLE_COLUMNS_MM)) else style.thin
        canvas.line(g, (x, top), (x, top - len(rows) * ROW_MM), width=w, stroke_width=fmt(w, 3), id=f"{ident}-tc{k}")
        if k < len(TABLE_COLUMNS_MM):
            x += TABLE_COLUMNS_MM[k]
    size = style.small_text
    for r, row in enumerate(rows):
        x = x0
        base = top - r * ROW_MM - ROW_MM / 2 - 0.26 * size
        for k, text in enumerate(row):
            w = width(runs(text), size, False)
            canvas.text(texts, canvas.paper((x + TABLE_COLUMNS_MM[k] / 2 - w / 2, base)), text, size=size,
                        ident=f"{ident}-t{r}-{k}")
            x += TABLE_COLUMNS_MM[k]
    dwg.add(g)
    dwg.add(texts)


def fits(sheet: GearSheet) -> bool:
    """Whether the sheet's content (the side view, pictures, table, end view and the notes' room)
    fits an A3 sheet's drawing area."""
    x0, y0, x1, y1 = bounds(_coords(sheet))
    return choose_format(x1 - x0, y1 - y0 + NOTE_ROOM_MM) is not None


def to_fit(build: Callable[[float], GearSheet], side_max: float) -> GearSheet:
    """``build(side)`` for the largest side-view height from ``side_max`` down (steps of 0.8×) whose
    sheet fits A3 (:func:`fits`); the smallest tried when none does."""
    side = side_max
    sheet = build(side)
    while not fits(sheet) and side > 0.2 * side_max:
        side *= 0.8
        sheet = build(side)
    return sheet


def draw_gears(sheet: GearSheet, heading: Heading, *, ident: str, style: Style = Style(),
               notes: tuple[str, ...] = (), given: frozenset[str] | None = None) -> str:
    """SVG text of the gear sheet (see the module). ``given`` makes it an assignment: the
    pictures' room left empty, the table's speeds filled in only for those links, the scales of
    the pictures left to the student."""
    x0, y0, x1, y1 = bounds(_coords(sheet))
    box = (x0, y0 - NOTE_ROOM_MM, x1, y1)
    f = choose_format(box[2] - box[0], box[3] - box[1]) or FORMATS[2]
    scales = (f"μ_l = {sheet.mu_l:g} m/mm, μ_V = {sheet.mu_v:g} (m/s)/mm, h = {sheet.h:g} mm, "
              f"μ_ω = {sheet.mu_omega:.4g} (rad/s)/mm") if given is None else \
        f"μ_l = {sheet.mu_l:g} m/mm (scheme); the pictures' scales: the student's"
    dwg, canvas = new_sheet(f, box, ident=ident, style=style,
                            block=TitleBlock(heading.mechanism, heading.sheet, heading.position, scales))
    if given is not None:
        dwg.attribs["data-sheet"] = "assignment"
    labels = dwg.g(id=f"{ident}-labels", fill=style.colour)
    _side_view(dwg, canvas, sheet, ident, style, labels)
    if given is None:
        _velocity_picture(dwg, canvas, sheet, ident, style, labels)
        _omega_picture(dwg, canvas, sheet, ident, style, labels)
        _v_detail(dwg, canvas, sheet, ident, style, labels)
    _end_view(dwg, canvas, sheet, ident, style, labels)
    _table(dwg, canvas, sheet, _table_at(sheet), ident, style, given)
    dwg.add(labels)
    notes = tuple(notes) + sheet.notes                 # the passive planets written out
    if notes:
        note_lines(canvas, dwg.add(dwg.g(id=f"{ident}-notes")), notes, style)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))
    return dwg.tostring()


def _side_view(dwg, canvas: Canvas, sheet: GearSheet, ident: str, style: Style, labels) -> None:
    g = dwg.g(id=f"{ident}-scheme", stroke=style.colour, fill="none", stroke_linecap="round")
    g.attribs["data-mu"] = repr(sheet.mu_l)
    g.attribs["data-plan"] = "scheme"
    thick, sw = style.link, fmt(style.link, 3)
    xs = [s.x0 for s in sheet.shafts] + [s.x1 for s in sheet.shafts]
    canvas.line(g, (min(xs) - 8.0, 0.0), (max(xs) + 8.0, 0.0), width=style.thin, stroke=style.construction_colour,
                stroke_width=fmt(style.thin, 3), stroke_dasharray="8 1.5 1 1.5", id=f"{ident}-axis")
    for k, s in enumerate(sheet.shafts):
        if s.fixed:
            continue                                   # a link held still is part of the frame
        if s.sleeve > 0.0:                             # a hollow shaft round the central one
            for j, y in enumerate((s.sleeve, -s.sleeve)):
                canvas.line(g, (s.x0, y), (s.x1, y), width=thick, stroke_width=sw, id=f"{ident}-shaft{k}-{j}")
            end = s.x1 if s.x1 >= max(xs) - 1e-9 else s.x0
            support(canvas, g, (end, s.sleeve), k, f"{ident}-b", style)
            continue
        for j, sign in enumerate((1, -1) if s.mirror else (1,)):
            y = sign * s.y
            canvas.line(g, (s.x0, y), (s.x1, y), width=thick, stroke_width=sw, id=f"{ident}-shaft{k}-{j}")
        if s.frame:
            end = s.x0 if s.x0 <= min(xs) + 1e-9 or s.y != 0.0 else s.x1
            support(canvas, g, (end, s.y), k, f"{ident}-b", style)
    for k, c in enumerate(sheet.carriers):
        for j, sign in enumerate((1, -1)):
            canvas.polyline(g, [(x, sign * y) for x, y in c.path], width=thick, stroke_width=sw,
                            id=f"{ident}-carrier{k}-{j}")
        end = c.path[1]
        canvas.label(labels, end, markup(c.name), size=style.text, prefer=(-1.0, 0.3), ident=f"{ident}-cl{k}",
                     near=1.0)
    for k, w in enumerate(sheet.wheels):
        for j, sign in enumerate((1, -1) if w.mirror else (1,)):
            y = sign * w.y
            top, bottom = y + w.r, y - w.r
            wid = f"{ident}-wheel{k}-{j}"
            if w.internal:
                for side, (pitch, rim) in enumerate(((top, top + RIM_MM), (bottom, bottom - RIM_MM))):
                    canvas.line(g, (w.x, pitch), (w.x, rim), width=thick, stroke_width=sw, id=f"{wid}-{side}")
                    canvas.line(g, (w.x - TICK_MM, pitch), (w.x + TICK_MM, pitch), width=thick, stroke_width=sw,
                                id=f"{wid}-t{side}")
                    if not w.fixed:                # the ring's disc down to its hollow shaft, outboard
                        out = DISC_MM if w.x >= max(v.x for v in sheet.wheels) else -DISC_MM
                        hub = HUB_MM if side == 0 else -HUB_MM
                        canvas.polyline(g, [(w.x, rim), (w.x + out, rim), (w.x + out, hub),
                                            (w.x + out + 0.6 * out, hub)], width=thick, stroke_width=sw,
                                        id=f"{wid}-d{side}")
                    if w.fixed:
                        a, b = (w.x - 4.0, rim), (w.x + 4.0, rim)
                        canvas.line(g, a, b, width=style.vector, stroke_width=fmt(style.vector, 3),
                                    id=f"{wid}-g{side}")
                        canvas.strokes(g, _hatch(a, b, 1.0 if side == 0 else -1.0, style),
                                       stroke_width=fmt(style.thin, 3), id=f"{wid}-h{side}")
            elif w.sleeve > 0.0:                       # on a hollow shaft: from it outwards, not across the axis
                canvas.line(g, (w.x, w.sleeve), (w.x, top), width=thick, stroke_width=sw, id=wid)
                canvas.line(g, (w.x, -w.sleeve), (w.x, bottom), width=thick, stroke_width=sw, id=f"{wid}-low")
                for side, yy in enumerate((top, bottom)):
                    canvas.line(g, (w.x - TICK_MM, yy), (w.x + TICK_MM, yy), width=thick, stroke_width=sw,
                                id=f"{wid}-t{side}")
            else:
                canvas.line(g, (w.x, bottom), (w.x, top), width=thick, stroke_width=sw, id=wid)
                for side, yy in enumerate((top, bottom)):
                    canvas.line(g, (w.x - TICK_MM, yy), (w.x + TICK_MM, yy), width=thick, stroke_width=sw,
                                id=f"{wid}-t{side}")
            if j == 0:
                at = (w.x, top + RIM_MM) if w.internal else (w.x, y + 0.55 * w.r)
                canvas.label(labels, at, markup(w.name), size=style.text, prefer=(1.0, 0.6 if w.internal else 0.0),
                             ident=f"{ident}-wl{k}", near=1.0)
    dwg.add(g)


def _velocity_picture(dwg, canvas: Canvas, sheet: GearSheet, ident: str, style: Style, labels) -> None:
    g = dwg.g(id=f"{ident}-velocity", stroke=style.colour, fill="none", stroke_linecap="round")
    g.attribs["data-mu"] = repr(sheet.mu_v)
    g.attribs["data-plan"] = "gear-velocity"
    g.attribs["data-vectors"] = str(len(sheet.pitch))
    ys = [p for ln in sheet.lines for p in (ln.start[1], ln.end[1])]
    el = canvas.line(g, (sheet.axis_x, min(ys + [0.0]) - 4.0), (sheet.axis_x, max(ys) + 6.0), width=style.thin,
                     stroke=style.construction_colour, stroke_width=fmt(style.thin, 3), id=f"{ident}-raxis")
    el.attribs["data-construction"] = "radius axis"
    canvas.label(labels, (sheet.axis_x, max(ys) + 6.0), "r", size=style.text, prefer=(-1.0, 0.0),
                 ident=f"{ident}-raxis-l", near=0.8)
    for k, ln in enumerate(sheet.lines):
        el = canvas.line(g, ln.start, ln.end, width=style.vector, stroke=style.component_colour,
                         stroke_width=fmt(style.vector, 3), id=f"{ident}-line{k}")
        el.attribs["data-construction"] = "velocity line"
        el.attribs["data-link-line"] = ln.link
        at = (0.4 * ln.start[0] + 0.6 * ln.end[0], 0.4 * ln.start[1] + 0.6 * ln.end[1])
        dx, dy = ln.end[0] - ln.start[0], ln.end[1] - ln.start[1]
        canvas.label(labels, at, markup(ln.link), size=style.small_text, prefer=(dy, -dx) if dx or dy else (1.0, 0.0),
                     ident=f"{ident}-ll{k}", near=0.8, fill=style.component_colour)
    for k, p in enumerate(sheet.pitch):
        line = vector(canvas, g, p.tail, p.head, style.vector_colour, f"{ident}-vp{k}", f"{ident}-vph{k}", style)
        line.attribs["data-quantity"] = f"vp:{p.a}-{p.b}"
        line.attribs["data-value"] = repr(abs(p.v))
        line.attribs["data-direction"] = _direction(canvas, p.tail, p.head) if p.v != 0 else "0.0"
        line.attribs["data-from"], line.attribs["data-to"] = f"r{p.a}{p.b}", f"v{p.a}{p.b}"
        canvas.label(labels, p.head, f"v_{{{p.a}{p.b}}}", size=style.small_text, prefer=(1.0, 1.0),
                     ident=f"{ident}-vpl{k}", near=0.8, fill=style.vector_colour)
    dwg.add(g)


def _omega_picture(dwg, canvas: Canvas, sheet: GearSheet, ident: str, style: Style, labels) -> None:
    g = dwg.g(id=f"{ident}-omega", stroke=style.colour, fill="none", stroke_linecap="round")
    g.attribs["data-mu"] = repr(sheet.mu_omega)
    g.attribs["data-plan"] = "gear-omega"
    drawn = [s for s in sheet.omega if s.omega != 0.0]
    g.attribs["data-vectors"] = str(len(drawn))
    g.attribs["data-pole"] = f"{fmt(canvas.paper(sheet.pole)[0], 3)} {fmt(canvas.paper(sheet.pole)[1], 3)}"
    line_y = sheet.pole[1] + sheet.h
    xs = [s.head[0] for s in sheet.omega] + [sheet.axis_x]
    el = canvas.line(g, (min(xs) - 6.0, line_y), (max(xs) + 6.0, line_y), width=style.thin,
                     stroke=style.construction_colour, stroke_width=fmt(style.thin, 3), id=f"{ident}-wline")
    el.attribs["data-construction"] = "ω line"
    el = canvas.line(g, sheet.pole, (sheet.pole[0], line_y), width=style.thin, stroke=style.construction_colour,
                     stroke_width=fmt(style.thin, 3), stroke_dasharray=style.dash, id=f"{ident}-h")
    el.attribs["data-construction"] = "pole distance h"
    canvas.circle(g, sheet.pole, 0.8, filled=True, fill=style.colour, stroke="none", id=f"{ident}-pole")
    canvas.label(labels, sheet.pole, "P", size=style.text, prefer=(-1.0, -1.0), ident=f"{ident}-pl", near=1.0)
    canvas.label(labels, (sheet.pole[0], sheet.pole[1] + sheet.h / 2), f"h = {sheet.h:g} mm", size=style.small_text,
                 italic=False, prefer=(-1.0, 0.0), ident=f"{ident}-hl", near=1.0)
    for k, s in enumerate(sheet.omega):
        ray = canvas.line(g, sheet.pole, s.head, width=style.thin, stroke=style.component_colour,
                          stroke_width=fmt(style.thin, 3), id=f"{ident}-ray{k}")
        ray.attribs["data-construction"] = "ray"
        ray.attribs["data-ray"] = s.link
    for k, s in enumerate(drawn):
        line = vector(canvas, g, s.tail, s.head, style.vector_colour, f"{ident}-w{k}", f"{ident}-wh{k}", style)
        line.attribs["data-quantity"] = f"omega:{s.link}"
        line.attribs["data-value"] = repr(abs(s.omega))
        line.attribs["data-direction"] = _direction(canvas, s.tail, s.head)
        line.attribs["data-from"], line.attribs["data-to"] = "o", f"w{s.link}"
        canvas.label(labels, s.head, f"ω_{{{s.link}}}", size=style.small_text, prefer=(0.3, 1.0),
                     ident=f"{ident}-wl{k}", near=0.8, fill=style.vector_colour)
    dwg.add(g)
    _omega_detail(dwg, canvas, sheet, ident, style, labels)


#: An ω segment drawn shorter than this is drawn again, enlarged, in a detail under the picture, mm.
SHORT_MM = 5.0
#: The enlargements a detail may take.
DETAIL_FACTORS = (2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0)


def _factor(short: list) -> tuple[list, float]:
    """``short`` and the smallest factor drawing each of its segments at least SHORT_MM long (1.0: none)."""
    if not short:
        return [], 1.0
    least = min(abs(s.head[0] - s.tail[0]) for s in short)
    return short, next((f for f in DETAIL_FACTORS if least * f >= SHORT_MM), DETAIL_FACTORS[-1])


#: A speed below this × the sheet's largest is a rounded zero (a fixed wheel's pitch point), not drawn again.
ZERO_REL = 1e-9


def _short(sheet: GearSheet) -> tuple[list, float]:
    """The ω segments drawn under SHORT_MM (not 0) and the factor of their detail."""
    top = max((abs(s.omega) for s in sheet.omega), default=0.0)
    return _factor([s for s in sheet.omega if abs(s.omega) > ZERO_REL * top and abs(s.head[0] - s.tail[0]) < SHORT_MM])


def _short_v(sheet: GearSheet) -> tuple[list, float]:
    """The pitch-point velocities drawn under SHORT_MM (not 0) and the factor of their detail."""
    top = max((abs(p.v) for p in sheet.pitch), default=0.0)
    return _factor([p for p in sheet.pitch if abs(p.v) > ZERO_REL * top and abs(p.head[0] - p.tail[0]) < SHORT_MM])


def _detail_origin(sheet: GearSheet) -> tuple[float, float]:
    return sheet.axis_x, sheet.pole[1] - 12.0


def _v_detail_origin(sheet: GearSheet) -> tuple[float, float]:
    """Under the ω detail (or where it would be)."""
    ox, oy = _detail_origin(sheet)
    return ox, oy - (4.0 * len(_short(sheet)[0]) + 10.0 if _short(sheet)[0] else 0.0)


def _omega_detail(dwg, canvas: Canvas, sheet: GearSheet, ident: str, style: Style, labels) -> None:
    """The short ω segments again, k× longer, from a point under the pole (``data-plan="bound"``,
    μ = μω/k): each measured (``omega:L:detail``, not the picture's own ω_L, its ray's end), each
    named, the factor stated."""
    short, k = _short(sheet)
    rows = [(f"omega:{s.link}:detail", abs(s.omega), s.head[0] - s.tail[0], f"o{j}", f"w{s.link}", f"ω_{{{s.link}}}")
            for j, s in enumerate(short)]
    _detail(dwg, canvas, ident, style, labels, rows, k, _detail_origin(sheet), sheet.mu_omega,
            ("omega-detail", "w", "dcap", "ω segments, μ_ω", "(rad/s)/mm"))


def _v_detail(dwg, canvas: Canvas, sheet: GearSheet, ident: str, style: Style, labels) -> None:
    """The short pitch-point velocities again, k× longer, under the ω detail (``data-plan="bound"``,
    μ = μV/k): each measured (``vp:a-b:detail``), each named, the factor stated."""
    short, k = _short_v(sheet)
    rows = [(f"vp:{p.a}-{p.b}:detail", abs(p.v), p.head[0] - p.tail[0], f"r{j}", f"v{p.a}{p.b}", f"v_{{{p.a}{p.b}}}")
            for j, p in enumerate(short)]
    _detail(dwg, canvas, ident, style, labels, rows, k, _v_detail_origin(sheet), sheet.mu_v,
            ("v-detail", "v", "dvcap", "v segments, μ_V", "(m/s)/mm"))


def _detail(dwg, canvas: Canvas, ident: str, style: Style, labels, rows: list, k: float,
            origin: tuple[float, float], mu: float, names: tuple[str, str, str, str, str]) -> None:
    """Segments ``rows`` (quantity, value, drawn length mm, from, to, label) drawn again k× longer
    from ``origin``, one under the other, in a measured group (μ = ``mu``/k), with a caption;
    ``names``: the group's id, the letter of its elements' ids, the caption's id, its words, the unit."""
    if not rows:
        return
    group, letter, cap, words, unit = names
    ox, oy = origin
    g = dwg.g(id=f"{ident}-{group}", stroke=style.colour, fill="none")
    g.attribs["data-mu"] = repr(mu / k)
    g.attribs["data-plan"] = "bound"
    g.attribs["data-vectors"] = str(len(rows))
    for j, (quantity, value, length, frm, to, text) in enumerate(rows):
        y = oy - 4.0 * j
        head = (ox + k * length, y)
        line = vector(canvas, g, (ox, y), head, style.vector_colour, f"{ident}-d{letter}{j}",
                      f"{ident}-d{letter}h{j}", style)
        line.attribs["data-quantity"] = quantity
        line.attribs["data-value"] = repr(value)
        line.attribs["data-direction"] = _direction(canvas, (ox, y), head)
        line.attribs["data-from"], line.attribs["data-to"] = frm, to
        canvas.label(labels, head, text, size=style.small_text, prefer=(1.0, 0.0),
                     ident=f"{ident}-d{letter}l{j}", near=0.8, fill=style.vector_colour)
    canvas.text(dwg.add(dwg.g(id=f"{ident}-{group}-caption", fill=style.colour)),
                canvas.paper((ox - 2.0, oy + 3.5)), f"detail ×{k:g} of the short {words} = {mu / k:.4g} {unit}",
                size=style.small_text, ident=f"{ident}-{cap}")
    dwg.add(g)

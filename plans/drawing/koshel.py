"""Koshel's sheet: the scheme with the construction of the base link's centre P_j (left), the
velocity plan in an uncertain scale (right) and the method step by step (below), on A3
landscape.

The two panels are drawn on one canvas by moving its offset between them, so the label
placer sees every inked element of both. Tagged groups, each measured by ``plans check``:
the plan (``data-plan="velocity"``, μ = K_V; with its detail ×k, μ = K_V/k, when images
crowd its pole), the segments P_j–X of the proportion
(``data-plan="centres"``, μ = μl, as on the centres sheet) and the vectors V_S drawn from the
special points S on the scheme in the plan's scale (``data-plan="bound"``, μ = K_V).
"""

from __future__ import annotations

import math

import numpy as np

from ..constructions.koshel import KoshelSheet
from .canvas import Canvas, fmt
from .marks import arrow as _arrow, bounds, markup as _markup, union, vector as _vector
from .scheme import scheme_layers
from .sheet import FORMATS, TitleBlock, new_sheet
from .style import Style
from .svg import COINCIDE_MM as _COINCIDE_MM, Heading, _crowd, _tag, centre_rays, detail_layers, detail_of, plan_layers
from .text import wrap

__all__ = ["draw_koshel", "PLAN_PANEL_MM", "STEP_TEXT_MM"]

#: Width of the plan's panel (right), mm; the scheme's panel takes the rest of the width.
PLAN_PANEL_MM = 172.0
#: Height of the steps' text, and its line spacing, mm.
STEP_TEXT_MM = 3.0
STEP_LEAD_MM = 4.4
#: Room for a panel's caption, mm.
CAPTION_MM = 7.0


def _place(canvas: Canvas, content, box) -> None:
    """Move the canvas so that ``content`` (mm, y up) is centred in paper ``box`` (x0, y0, x1, y1)."""
    canvas.dx = (box[0] + box[2]) / 2 - (content[0] + content[2]) / 2
    canvas.dy = (box[1] + box[3]) / 2 + (content[1] + content[3]) / 2


def _scheme_side(dwg, canvas: Canvas, sheet: KoshelSheet, ident: str, style: Style) -> None:
    """The scheme, the construction lines of P_j, P_j, the segments P_j–X and V_S."""
    red = style.component_colour
    cons = dwg.g(id=f"{ident}-pconstruction", stroke=style.construction_colour, stroke_width=fmt(style.thin, 3),
                 stroke_dasharray=style.dash, fill="none")
    for k, l in enumerate(sheet.lines):
        el = canvas.line(cons, l.start, l.end, id=f"{ident}-pl{k}")
        el.attribs["data-through"] = l.through
    dwg.add(cons)
    scheme_layers(dwg, canvas, sheet.scheme, f"{ident}-s", style)
    dwg.add(centre_rays(dwg, canvas, sheet.rays, sheet.mu_l, ident=ident, group=f"{ident}-proportion", style=style))
    vs = dwg.g(id=f"{ident}-special", fill="none")
    vs.attribs["data-mu"] = repr(sheet.k_v)
    vs.attribs["data-plan"] = "bound"
    vs.attribs["data-vectors"] = str(len(sheet.vectors))
    marks = dwg.g(id=f"{ident}-marks", fill=red)
    for k, v in enumerate(sheet.vectors):
        el = _vector(canvas, vs, v.tail, v.head, style.vector_colour, f"{ident}-sv{k}", f"{ident}-sh{k}", style)
        _tag(el, canvas, f"v:{v.name}", v.value, v.tail, v.head, v.name, v.name.lower())
        canvas.label(marks, v.head, f"V_{{{v.name}}}", size=style.text, prefer=np.subtract(v.head, v.tail),
                     ident=f"{ident}-svl{k}", digits=False, near=0.6, fill=style.vector_colour)
    dwg.add(vs)
    c = sheet.centre
    if c.xy is not None:
        canvas.circle(marks, c.xy, 1.0, filled=True, id=f"{ident}-pc")
        canvas.label(marks, c.xy, _markup(c.name), size=style.text, prefer=np.subtract(c.xy, c.anchor),
                     ident=f"{ident}-pct", digits=False, near=0.8, fill=red)
    else:
        tip = tuple(np.add(c.anchor, np.multiply(c.direction, 18.0)))
        canvas.line(marks, c.anchor, tip, stroke=red, stroke_width=fmt(style.thin, 3), id=f"{ident}-pd")
        _arrow(canvas, marks, c.anchor, tip, red, f"{ident}-pdh", style, of=f"{ident}-pd")
        canvas.label(marks, tip, f"{_markup(c.name)} (off the sheet)", size=style.small_text, prefer=c.direction,
                     ident=f"{ident}-pdt", digits=False, fill=red)
    for k, (name, xy) in enumerate(sheet.specials):
        if c.xy is not None and math.dist(xy, c.xy) < _COINCIDE_MM:
            continue                 # the special point at rest is P_j itself (its label says so below)
        canvas.circle(marks, xy, 0.7, fill="#fff", stroke=red, stroke_width=fmt(style.thin, 3), id=f"{ident}-sp{k}")
        canvas.label(marks, xy, _markup(name), size=style.small_text, prefer=(1.0, -1.0), ident=f"{ident}-spt{k}",
                     digits=False, near=0.5, fill=red)
    dwg.add(marks)


def draw_koshel(sheet: KoshelSheet, heading: Heading, *, ident: str, style: Style = Style()) -> str:
    """SVG text of Koshel's sheet (see the module docstring)."""
    fmt_ = FORMATS[2]
    scales = f"μ_l = {sheet.mu_l:g} m/mm;  K_{{V}} = {sheet.k_v:.4g} (m/s)/mm (found in step 4)"
    sch = sheet.scheme
    left_pts = list(sch.points.values()) + [g.start for g in sch.guides] + [g.end for g in sch.guides] \
        + [p for l in sheet.lines for p in (l.start, l.end)] + [v.head for v in sheet.vectors] \
        + [xy for _, xy in sheet.specials] + ([sheet.centre.xy] if sheet.centre.xy is not None else [])
    left = bounds(left_pts)
    plan = sheet.plan
    dwg, canvas = new_sheet(fmt_, left, ident=ident, style=style,
                            block=TitleBlock(heading.mechanism, heading.sheet, heading.position, scales))
    a = canvas.area
    room = a.x1 - a.x0 - 16.0     # the viewer's serif may run wider than DejaVu's metrics
    rows = [r for step in sheet.steps for r in wrap(step, room, STEP_TEXT_MM, indent="   ")]
    text_top = a.y1 - 2.0 - STEP_LEAD_MM * len(rows)
    split = a.x1 - PLAN_PANEL_MM
    top = a.y0 + CAPTION_MM
    right = bounds([p.xy for p in plan.points] + [l.start for l in plan.lines] + [l.end for l in plan.lines])
    detail = detail_of(plan, ((PLAN_PANEL_MM, text_top - 2.0 - top),), style, "K_{V}")
    if detail is not None:      # images crowding the pole: enlarged beside the plan, within the panel
        right = union(right, detail.box)
    notes = dwg.g(id=f"{ident}-notes")
    canvas.text(notes, (a.x0 + 3.0, a.y0 + 5.0), f"Scheme, μ_l = {sheet.mu_l:g} m/mm: the centre "
                f"{_markup(sheet.centre.name)} of link {sheet.base} (Koshel, Fig. 1–2)", size=style.small_text)
    canvas.text(notes, (split + 3.0, a.y0 + 5.0), f"Velocity plan in an uncertain scale, K_{{V}} = {sheet.k_v:.4g} "
                "(m/s)/mm", size=style.small_text)
    _place(canvas, left, (a.x0, top, split, text_top - 2.0))
    _scheme_side(dwg, canvas, sheet, ident, style)
    _place(canvas, right, (split, top, a.x1, text_top - 2.0))
    plan_layers(dwg, canvas, plan, ident, style, unlabelled=_crowd(detail))
    if detail is not None:
        detail_layers(dwg, canvas, plan, detail, ident, style, "K_{V}")
    sep = dwg.g(id=f"{ident}-steps-rule", stroke=style.colour, stroke_width=fmt(style.thin, 3))
    y = canvas.dy - (text_top - 2.0)        # the rule above the steps, in the canvas's content mm
    canvas.line(sep, (a.x0 - canvas.dx, y), (a.x1 - canvas.dx, y), id=f"{ident}-rule")
    dwg.add(sep)
    for k, row in enumerate(rows):
        canvas.text(notes, (a.x0 + 3.0, text_top + 3.2 + STEP_LEAD_MM * k), row, size=STEP_TEXT_MM)
    dwg.add(notes)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))   # outside every plan: not vectors
    return dwg.tostring()

"""Kinetostatics sheets: the groups' force plans and Zhukovsky's lever, in SVG.

**Force plans** (:func:`draw_force_plans`): each group's polygon in a panel of its own, with
its own μF (as a textbook draws them), captioned with the group, μF and the vector equation it
closes, and a table below of every force of the group — zero ones included, which are not
drawn — with its value and drawn length. Panels are set side by side, then in rows, on the
smallest standard sheet that holds them (A4 or A3); plans that do not fit one A3 sheet go on
the next sheet; a panel too tall for A3 with its table below has the table beside the
polygon. Known forces are blue, reaction components red, whole reactions black, reactions
between the group's own links black and dashed; the directions of the normal components are
thin dashed lines. Each run of short sides (:func:`~plans.constructions.forces.force_details`)
is drawn again beside the polygon in an enlarged detail with its own μF ("detail k, μF = …",
its own ``<g data-plan="force" data-detail="run">``); the polygon letters only the run's
ends and labels none of its sides, and the table's note says, for each side under 2 mm,
where it is drawn again or that it is negligible. Vertices nearer than
:data:`VERTEX_SPOT_MM` share one label.

**Lever** (:func:`draw_lever`): the velocity plan turned 90° clockwise (thin), the forces at
the turned images as arrows in μF (a moment's couple dashed, the balancing element red), the
arms h_i from the pole as thin lines to the foot of each perpendicular (the line of action
drawn on, dashed, when the foot is off the arrow), and beside it the written equation
Σ M_p = 0 term by term and the balancing result (an arm of 0 — a line through the pole —
written as such). When loaded images crowd the pole, an enlarged detail ×k of the pole region
(:mod:`plans.constructions.lever_detail`) is drawn beside the lever, captioned "detail ×k,
μV = …, μF = …": a lever of its own, its images, forces at their own μF′ and arms k·h
labelled h_i as on the lever, which leaves off its letters of those images, short forces and
arms. The labels are asked for in the orders of :data:`LABEL_ORDERS` in turn, until one
places them all clear.

What ``plans check`` reads (besides the tags of :mod:`.svg`): a force plan's ``<g>`` has
``data-plan="force"``, ``data-mu`` = μF (N/mm), ``data-group``; each vector ``data-role``
(``side``, ``total``, ``internal``) and ``data-from``/``data-to`` the vertices it joins. The
lever's ``<g>`` has ``data-plan="lever"``, ``data-mu`` = μF, ``data-mu-v`` = μV,
``data-sense`` and ``data-pole`` (the pole's paper x, y as written); each force line
``data-h`` (its exact arm, mm) and ``data-moment`` (N·mm, counter-clockwise positive on the
lever, i.e. clockwise positive in the SVG frame's y-down terms), ``data-from`` the image it
is applied at; each arm ``<line data-construction="arm" data-arm=QUANTITY>`` runs from the
pole to the foot. The pole detail is a second lever ``<g>`` with ``data-detail="pole"``,
``data-mu`` = μF′, ``data-mu-v`` = μV/k, ``data-pole`` the detail's pole, each force's
``data-h`` its arm there (k·h, mm) and ``data-moment`` ± F·k·h; ``plans check`` measures its
forces and arms but asks no Σ M_p = 0 of it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ..errors import DrawingError
from ..constructions.forces import SHORT_SIDE_MM, ForceDetail, ForcePlan, Lever, LeverForce, component_of, force_details
from ..constructions.detail import NEAR_MM
from ..constructions.lever_detail import LeverDetail, lever_detail
from .canvas import Canvas, fmt
from .marks import LABEL_ROOM_MM, NO_HEAD_MM, arrow as _arrow, bounds, markup as _markup, union
from .sheet import FORMATS, TitleBlock, choose_format, new_sheet
from .style import Style
from .svg import Heading, _decimal, _tag, detail_frame, direction_text, plan_group
from .text import ASCENT, DESCENT, runs, width, wrap
from .. import linalg as la

__all__ = ["draw_force_plans", "draw_lever", "symbol", "PANEL_GAP_MM", "TABLE_TEXT_MM", "TABLE_LEAD_MM"]

#: Space between panels, mm.
PANEL_GAP_MM = 8.0
#: Height of the tables' and captions' text, and their line spacing, mm.
TABLE_TEXT_MM = 2.8
TABLE_LEAD_MM = 4.4
#: Columns of a force table: symbol, value (N), drawn length (mm), note; their widths, mm.
TABLE_COLUMNS_MM = (22.0, 20.0, 18.0, 52.0)
#: Vertices nearer than this share one label naming them all, mm: a letter is about 2.5 mm
#: tall, and two vertices nearer than SHORT_SIDE_MM read as one spot (the layout measurer's rule).
VERTEX_SPOT_MM = 3.0
#: Width of the lever's written computation, mm.
LEVER_TEXT_MM = 118.0
#: Arms shorter than this are not drawn (their force's line passes through the pole), mm.
MIN_ARM_MM = 0.5
#: Where else along its arm (a fraction from the pole) an arm's label h_i may go, tried in
#: turn after the arm's middle.
ARM_LABEL_AT = (0.65, 0.35, 0.8, 0.2)
#: Side of the right-angle mark at the foot of an arm, mm.
RIGHT_ANGLE_MM = 1.8
_KIND_COLOUR = {"gravity": "vector", "inertia": "vector", "external": "vector", "balance": "vector",
                "reaction": "component", "reaction_n": "component", "reaction_t": "component"}


def _sub(text: str) -> str:
    return "{" + text + "}"


def symbol(quantity: str) -> str:
    """The printed name of a force tag, in label markup: ``R:1-2`` → R₁₂, ``R:1-2:n`` → R₁₂,ₙ,
    ``R:1-2:t`` → R₁₂,τ, ``G:3`` → G₃, ``F:in:2`` → F_in,2, ``F:ext:B`` → F_B, ``F:bal`` →
    F_bal, ``M:2`` → M₂, ``M:in:2`` → M_in,2, ``M:ext:2`` → M₂, a couple's force ``F:M:2:a``
    (``F:M:ext:2:a``) → F′₂ (at a), ``F:M:in:2:a`` → F′_in,2."""
    parts = quantity.split(":")
    base, comp = component_of(quantity)
    if base.startswith("R:") and "-" in base:
        i, _, j = base[2:].partition("-")
        ij = f"{i}{j}" if len(i) == 1 and len(j) == 1 else f"{i},{j}"
        return f"R_{_sub(ij + ({'n': ',n', 't': ',τ'}[comp] if comp else ''))}"
    if len(parts) == 2 and parts[0] in ("G", "M", "F"):
        return f"{parts[0]}_{_sub(parts[1])}"
    if len(parts) == 3 and parts[:2] == ["F", "in"]:
        return f"F_{_sub('in,' + parts[2])}"
    if len(parts) == 3 and parts[:2] == ["F", "ext"]:
        return f"F_{_sub(parts[2])}"
    if len(parts) == 3 and parts[0] == "M":                 # M:in:2, M:ext:2 (the force analysis' tags)
        return f"M_{_sub(('in,' if parts[1] == 'in' else '') + parts[2])}"
    if len(parts) >= 4 and parts[:2] == ["F", "M"]:          # a couple's force: F:M:2:a, F:M:in:2:a
        which = parts[2:-1]
        return f"F′_{_sub(('in,' if which[0] == 'in' else '') + which[-1])}"
    return quantity.replace("_", " ")


def _number(v: float, digits: int = 4) -> str:
    """``v`` with ``digits`` significant figures, no exponent below 10^7, − for minus."""
    if v == 0 or not math.isfinite(v):
        return "0" if v == 0 else str(v)
    if abs(v) < 1e-3:                          # a rounding zero or a tiny value: in powers of ten
        return f"{v:.{digits - 1}e}".replace("-", "−")
    v = float(f"{v:.{digits}g}")               # rounded first: 9.99996 → 10.00, not 10.000
    places = max(0, digits - 1 - int(math.floor(math.log10(abs(v)))))
    s = f"{v:.{places}f}" if abs(v) < 1e7 else f"{v:.{digits - 1}e}"
    return s.replace("-", "−")


def _signed(v: float, digits: int = 4) -> str:
    return ("+" if v >= 0 else "") + _number(v, digits)


def _colour(style: Style, kind: str) -> str:
    return style.vector_colour if _KIND_COLOUR.get(kind) == "vector" else style.component_colour


def _dashed_vector(canvas: Canvas, parent, tail, head, colour: str, ident: str, head_ident: str, style: Style,
                   width_: float | None = None):
    """A dashed vector: one ``<line>`` tail → head (it measures the whole vector), dashes up to
    under its arrowhead, and the head."""
    L = math.dist(tail, head)
    head_len = min(style.arrow_length, 0.5 * L) if L >= NO_HEAD_MM else 0.0
    shaft = max(L - head_len * 0.8, 0.0)
    on, off = (float(x) for x in style.dash.split())
    pattern, done = [], 0.0
    while done + on < shaft:
        pattern += [on, off]
        done += on + off
    pattern += [max(min(on, shaft - done), 0.0), L + 1.0]
    w = style.vector if width_ is None else width_
    el = canvas.line(parent, tail, head, width=w, id=ident, stroke=colour, stroke_width=fmt(w, 3),
                     stroke_dasharray=" ".join(fmt(x, 3) for x in pattern))
    _arrow(canvas, parent, tail, head, colour, head_ident, style, of=ident)
    return el


def _solid_vector(canvas: Canvas, parent, tail, head, colour: str, ident: str, head_ident: str, style: Style,
                  width_: float | None = None):
    """A vector as one ``<line>`` whose visible shaft stops under its arrowhead (as marks.vector)."""
    L = math.dist(tail, head)
    head_len = min(style.arrow_length, 0.5 * L) if L >= NO_HEAD_MM else 0.0
    shaft = max(L - head_len * 0.8, 0.0)
    w = style.vector if width_ is None else width_
    el = canvas.line(parent, tail, head, width=w, id=ident, stroke=colour, stroke_width=fmt(w, 3),
                     stroke_dasharray=f"{fmt(shaft, 3)} {fmt(L + 1, 3)}")
    _arrow(canvas, parent, tail, head, colour, head_ident, style, of=ident)
    return el


def _side_label_direction(tail, head, centre) -> np.ndarray:
    """Perpendicular to a side, away from the polygon's centre."""
    d = np.subtract(head, tail)
    n = np.array([-d[1], d[0]])
    if la.norm(n) < 1e-12:
        return np.array([0.6, 0.8])
    mid = np.add(tail, head) / 2
    return n if la.dot(n, mid - np.asarray(centre)) >= 0 else -n


# --- force plans ------------------------------------------------------------------------------

@dataclass(frozen=True)
class _Panel:
    plan: ForcePlan
    content: tuple[float, float, float, float]     # the polygon's box, mm y up (labels' room included)
    caption: tuple[str, ...]
    rows: tuple[tuple[str, str, str, str], ...]
    width: float
    height: float
    details: tuple[ForceDetail, ...] = ()
    detail_boxes: tuple[tuple[float, float, float, float], ...] = ()    # each detail's box, mm y up
    poly_width: float = 0.0                        # width of the polygon with its details beside it, mm
    poly_height: float = 0.0
    table_beside: bool = False                     # the table right of the polygon, not below it


def _detail_caption(k: int, d: ForceDetail) -> str:
    return f"detail {k + 1}, μ_F = {d.mu:g} N/mm"


def _table_rows(plan: ForcePlan, details: Sequence[ForceDetail] = ()) -> list[tuple[str, str, str, str]]:
    """A row per force: symbol, value (N), drawn length on the polygon (mm) and a note — where
    a side under SHORT_SIDE_MM is drawn again (its detail and length there) or why it is
    negligible."""
    drawn = {v.quantity: v for v in plan.vectors}
    again = {v.quantity: (k, d, v) for k, d in enumerate(details) for v in d.vectors}
    rows = []
    for t in list(plan.terms) + list(plan.totals) + list(plan.internal):
        v = drawn.get(t.quantity)
        note = ""
        if v is not None and v.length < SHORT_SIDE_MM:
            if t.quantity in again:
                k, d, w = again[t.quantity]
                note = (f"< {SHORT_SIDE_MM:g} mm; in detail {k + 1}: {_number(w.length, 3)} mm"
                        if w.length >= SHORT_SIDE_MM else
                        f"negligible: {_number(w.length, 2)} mm in detail {k + 1}")
            else:
                note = f"negligible: < {SHORT_SIDE_MM:g} mm at μ_F"
        rows.append((symbol(t.quantity), _number(t.value), _number(v.length, 4) if v else "0 (not drawn)", note))
    return rows


def _panel(plan: ForcePlan, style: Style) -> _Panel:
    coords = [p.xy for p in plan.points] + [l.start for l in plan.lines] + [l.end for l in plan.lines]
    content = bounds(coords)
    details = force_details(plan)
    boxes = tuple(bounds([p.xy for p in d.points]) for d in details)
    equation = " + ".join(symbol(t.quantity) for t in plan.terms) + " = 0"
    head = f"Force plan of group {plan.group},  μ_F = {plan.mu:g} N/mm"
    w_poly = content[2] - content[0]
    h_poly = content[3] - content[1]
    if details:
        col = max(max(b[2] - b[0] for b in boxes),
                  max(width(runs(_detail_caption(k, d)), TABLE_TEXT_MM, False) for k, d in enumerate(details)))
        w_poly += PANEL_GAP_MM + col
        h_poly = max(h_poly, sum(TABLE_LEAD_MM + b[3] - b[1] for b in boxes))
    table_w = sum(TABLE_COLUMNS_MM)
    room = max(w_poly, table_w, 90.0)
    caption = tuple(wrap(head, room, TABLE_TEXT_MM) + wrap(equation, room, TABLE_TEXT_MM, indent="   "))
    rows = _table_rows(plan, details)
    w = max(room, max(width(runs(c), TABLE_TEXT_MM, False) for c in caption))
    h_table = TABLE_LEAD_MM * (len(rows) + 1.8)
    h = TABLE_LEAD_MM * (len(caption) + 0.5) + h_poly + h_table
    a3 = FORMATS[2].area
    if h > a3.y1 - a3.y0:
        # too tall for an A3 sheet's height with the table below: the table beside the polygon
        w = max(w_poly + PANEL_GAP_MM + table_w, max(width(runs(c), TABLE_TEXT_MM, False) for c in caption))
        h = TABLE_LEAD_MM * (len(caption) + 0.5) + max(h_poly, h_table)
        return _Panel(plan, content, caption, tuple(rows), w, h, details, boxes, w_poly, h_poly, True)
    return _Panel(plan, content, caption, tuple(rows), w, h, details, boxes, w_poly, h_poly)


def _pack(panels: Sequence[_Panel], room_w: float, room_h: float) -> list[list[tuple[_Panel, float, float]]]:
    """Panels in rows, left to right, sheet after sheet: (panel, x, y) from each sheet's top left."""
    sheets, sheet, x, y, row_h = [], [], 0.0, 0.0, 0.0
    for p in panels:
        if sheet and x + p.width > room_w:
            x, y, row_h = 0.0, y + row_h + PANEL_GAP_MM, 0.0
        if sheet and y + p.height > room_h:
            sheets.append(sheet)
            sheet, x, y, row_h = [], 0.0, 0.0, 0.0
        sheet.append((p, x, y))
        x += p.width + PANEL_GAP_MM
        row_h = max(row_h, p.height)
    if sheet:
        sheets.append(sheet)
    return sheets


def _place(canvas: Canvas, content, box) -> None:
    """Move the canvas so that ``content`` (mm, y up) is centred in paper ``box`` (x0, y0, x1, y1)."""
    canvas.dx = (box[0] + box[2]) / 2 - (content[0] + content[2]) / 2
    canvas.dy = (box[1] + box[3]) / 2 + (content[1] + content[3]) / 2


def draw_force_plans(plans: Sequence[ForcePlan], heading: Heading, *, ident: str,
                     style: Style = Style()) -> tuple[str, ...]:
    """SVG texts of the force plans of one position (see the module docstring): usually one
    sheet; more when the panels do not fit one A3 sheet."""
    if not plans:
        return ()
    panels = [_panel(p, style) for p in plans]
    a3 = FORMATS[2].area
    groups = _pack(panels, a3.x1 - a3.x0, a3.y1 - a3.y0)
    out = []
    for s, placed in enumerate(groups):
        sid = ident if len(groups) == 1 else f"{ident}-{s + 1}"
        out.append(_force_sheet(placed, heading, sid, style))
    return tuple(out)


def _force_sheet(placed, heading: Heading, ident: str, style: Style) -> str:
    W = max(x + p.width for p, x, _ in placed)
    H = max(y + p.height for p, _, y in placed)
    fmt_ = choose_format(W, H) or FORMATS[2]
    scales = ";  ".join(f"{p.plan.group}: μ_F = {p.plan.mu:g} N/mm" for p, _, _ in placed)
    dwg, canvas = new_sheet(fmt_, (0.0, 0.0, W, H), ident=ident, style=style,
                            block=TitleBlock(heading.mechanism, heading.sheet, heading.position, scales))
    ox, oy = canvas.dx, canvas.dy - H          # paper position of the packed content's top left
    texts = dwg.g(id=f"{ident}-texts")
    rules = dwg.g(id=f"{ident}-rules", stroke=style.colour, stroke_width=fmt(style.thin, 3))
    for k, (p, x, y) in enumerate(placed):
        pid = f"{ident}-g{k}"
        left, top = ox + x, oy + y
        for r, line in enumerate(p.caption):
            canvas.text(texts, (left, top + TABLE_LEAD_MM * (r + 0.75)), line, size=TABLE_TEXT_MM,
                        ident=f"{pid}-cap{r}")
        poly_top = top + TABLE_LEAD_MM * (len(p.caption) + 0.5)
        ch, cw = p.content[3] - p.content[1], p.content[2] - p.content[0]
        if p.details:
            # the polygon on the left, its details stacked in a column beside it
            _place(canvas, p.content, (left, poly_top, left + cw, poly_top + p.poly_height))
            _force_layers(dwg, canvas, p.plan, pid, style, details=p.details)
            dx = left + cw + PANEL_GAP_MM
            dy = poly_top
            for j, (d, b) in enumerate(zip(p.details, p.detail_boxes)):
                canvas.text(texts, (dx, dy + TABLE_LEAD_MM * 0.75), _detail_caption(j, d), size=TABLE_TEXT_MM,
                            ident=f"{pid}-dcap{j}")
                dy += TABLE_LEAD_MM
                _place(canvas, b, (dx, dy, dx + b[2] - b[0], dy + b[3] - b[1]))
                _detail_layers(dwg, canvas, p.plan, d, f"{pid}-x{j}", style)
                dy += b[3] - b[1]
        else:
            _place(canvas, p.content, (left, poly_top, left + (cw if p.table_beside else max(cw, p.width)),
                                       poly_top + ch))
            _force_layers(dwg, canvas, p.plan, pid, style)
        ty = poly_top + p.poly_height + TABLE_LEAD_MM * 0.9
        if p.table_beside:
            left, ty = left + p.poly_width + PANEL_GAP_MM, poly_top + TABLE_LEAD_MM * 0.9
        cols = np.cumsum((0.0,) + TABLE_COLUMNS_MM)
        for c, head in enumerate(("force", "F, N", "drawn, mm", "")):
            if not head:
                continue
            canvas.text(texts, (left + cols[c], ty), head, size=TABLE_TEXT_MM, ident=f"{pid}-th{c}")
        rule_y = ty + TABLE_LEAD_MM * 0.45
        canvas.line(rules, (left - canvas.dx, canvas.dy - rule_y), (left + cols[-1] - canvas.dx, canvas.dy - rule_y),
                    id=f"{pid}-rule")
        for r, row in enumerate(p.rows):
            yy = ty + TABLE_LEAD_MM * (r + 1.1)
            for c, cell in enumerate(row):
                canvas.text(texts, (left + cols[c], yy), cell, size=TABLE_TEXT_MM, ident=f"{pid}-t{r}-{c}")
    dwg.add(rules)
    dwg.add(texts)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))
    return dwg.tostring()


def _vertex_labels(points, hidden: set[str] = frozenset()) -> list[tuple[tuple[float, float], str]]:
    """The vertex labels to write: (point, text). Vertices nearer one another than
    VERTEX_SPOT_MM share one label (their letters joined, ``≡`` when they coincide), at the
    first of them; ``hidden`` vertices (drawn in a detail) get none."""
    out: list[tuple[tuple[float, float], list[str]]] = []
    for p in points:
        if p.label in hidden:
            continue
        near = next((o for o in out if math.dist(o[0], p.xy) < VERTEX_SPOT_MM), None)
        if near is None:
            out.append((p.xy, [p.label]))
        elif p.label not in near[1]:
            near[1].append(p.label)
    texts = []
    for xy, names in out:
        same = all(math.dist(xy, q.xy) < 1e-6 for q in points if q.label in names)
        texts.append((xy, (" ≡ " if same else ", ").join(_markup(n) for n in names)))
    return texts


def _force_layers(dwg, canvas: Canvas, plan: ForcePlan, ident: str, style: Style,
                  details: Sequence[ForceDetail] = ()) -> None:
    """One polygon's group: direction lines, tagged vectors with heads, vertices and labels.
    The inner vertices of a run drawn in a detail are not lettered, nor its sides labelled
    here (the detail letters and labels them)."""
    g = plan_group(dwg, canvas, plan, "force", ident, style)
    g.attribs["data-group"] = plan.group
    labels = dwg.g(id=f"{ident}-labels", fill=style.colour)
    centre = np.mean([p.xy for p in plan.points], axis=0)
    hidden = {p.label for d in details for p in d.points[1:-1]}
    in_detail = {v.quantity for d in details for v in d.vectors}

    def vertex(xy) -> str | None:
        return next((p.label for p in plan.points if math.dist(p.xy, xy) <= 1e-9), None)

    # the vertices' labels are asked for first: each must sit by its point, while a side's label
    # may go anywhere beside its side
    _letter_vertices(canvas, labels, plan.points, hidden, centre, ident, style)
    for k, v in enumerate(plan.vectors):
        el, colour = _force_vector(canvas, g, v, f"{ident}-v{k}", f"{ident}-h{k}", style)
        _tag(el, canvas, v.quantity, v.value, v.tail, v.head, vertex(v.tail), vertex(v.head))
        el.attribs["data-role"] = v.role
        el.attribs["data-kind"] = v.kind
        if not (v.role == "side" and (v.length < SHORT_SIDE_MM or v.quantity in in_detail)):
            # (else labelled in its detail, or unreadable and negligible in the table)
            _label_side(canvas, labels, v, colour, centre, f"{ident}-vl{k}", style)
    g.add(labels)
    dwg.add(g)


def _letter_vertices(canvas: Canvas, labels, points, hidden, centre, ident: str, style: Style) -> None:
    """A dot at every vertex and a letter (one per spot, :func:`_vertex_labels`) away from ``centre``."""
    for k, p in enumerate(points):
        canvas.circle(labels, p.xy, 0.45, filled=True, id=f"{ident}-d{k}")
    for k, (xy, text) in enumerate(_vertex_labels(points, hidden)):
        away = np.subtract(xy, centre)
        canvas.label(labels, xy, text, size=style.small_text + 0.5,
                     prefer=away if la.norm(away) > 1e-9 else (0.6, 0.8), ident=f"{ident}-l{k}",
                     digits=False, near=0.5)


def _label_side(canvas: Canvas, labels, v, colour: str, centre, ident: str, style: Style) -> None:
    """The force's symbol beside side ``v``, on the side away from ``centre``."""
    mid = tuple(np.add(v.tail, v.head) / 2)
    canvas.label(labels, mid, symbol(v.quantity), size=style.text, prefer=_side_label_direction(v.tail, v.head, centre),
                 ident=ident, digits=False, fill=colour, near=0.4)


def _force_vector(canvas: Canvas, g, v, ident: str, head_ident: str, style: Style):
    """A force plan's vector drawn as its role asks (an inner reaction dashed): (line, colour)."""
    if v.role == "internal":
        return _dashed_vector(canvas, g, v.tail, v.head, style.colour, ident, head_ident, style), style.colour
    colour = style.colour if v.role == "total" else _colour(style, v.kind)
    return _solid_vector(canvas, g, v.tail, v.head, colour, ident, head_ident, style), colour


def _detail_layers(dwg, canvas: Canvas, plan: ForcePlan, detail: ForceDetail, ident: str, style: Style) -> None:
    """A detail's own plan group (``data-plan="force"``, ``data-mu`` its μF, ``data-detail``
    the group): its sides tagged as on the polygon, its vertices lettered as there."""
    g = dwg.g(id=f"{ident}-plan")
    g.attribs["data-mu"] = repr(detail.mu)
    g.attribs["data-plan"] = "force"
    g.attribs["data-vectors"] = str(len(detail.vectors))
    g.attribs["data-group"] = plan.group
    g.attribs["data-detail"] = "run"
    labels = dwg.g(id=f"{ident}-labels", fill=style.colour)
    centre = np.mean([p.xy for p in detail.points], axis=0)
    _letter_vertices(canvas, labels, detail.points, (), centre, ident, style)
    for k, v in enumerate(detail.vectors):
        el, colour = _force_vector(canvas, g, v, f"{ident}-v{k}", f"{ident}-h{k}", style)
        _tag(el, canvas, v.quantity, v.value, v.tail, v.head, detail.points[k].label, detail.points[k + 1].label)
        el.attribs["data-role"] = "side"
        el.attribs["data-kind"] = v.kind
        if v.length >= SHORT_SIDE_MM:
            _label_side(canvas, labels, v, colour, centre, f"{ident}-vl{k}", style)
    g.add(labels)
    dwg.add(g)


# --- the lever --------------------------------------------------------------------------------

def _arm_numbers(lever: Lever, detail: LeverDetail | None = None) -> dict[int, int]:
    """Index of a force on the lever → the number of its drawn arm (1, 2, … in order): drawn
    on the lever, or in its pole detail."""
    again = {f.quantity: f for f in detail.lever.forces} if detail is not None else {}
    drawn = [k for k, f in enumerate(lever.forces)
             if f.arm >= MIN_ARM_MM or (f.quantity in again and again[f.quantity].arm >= MIN_ARM_MM)]
    return {k: n + 1 for n, k in enumerate(drawn)}


def _arm_text(f: LeverForce, h: str) -> str:
    """A load's row: its value, arm and moment about p; an arm of 0 (its line through p) as such."""
    if f.arm == 0.0:
        return f"  {symbol(f.quantity)} = {_number(f.value)} N, {h} = 0 (its line passes through p):  0"
    return f"  {symbol(f.quantity)} = {_number(f.value)} N, {h} = {_number(f.arm)} mm:  {_signed(f.moment, 5)}"


def _lever_text(lever: Lever, note: str = "", detail: LeverDetail | None = None) -> list[str]:
    """The written computation of the lever (rows of label markup); ``note``: why no load is
    on it (the first row after the plan's, when there is none); ``detail``: its pole detail."""
    rows = [f"Velocity plan turned 90° {lever.sense} about the pole {lever.pole} (μ_V = {lever.mu_v:g} (m/s)/mm);"]
    if lever.forces:
        rows += [f"forces applied at the images of their points, μ_F = {lever.mu:g} N/mm; arms h in mm;",
                 "moments about p, counter-clockwise positive (N·mm):"]
    loads = [f for f in lever.forces if f.kind != "balance"]
    numbers = _arm_numbers(lever, detail)
    couples: dict[str, LeverForce] = {}
    for f in lever.forces:
        if f.kind == "couple":
            couples.setdefault(f.source, f)
    for src, f in couples.items():
        rows.append(f"  {symbol(src)} as the couple {symbol(f.quantity)} = {symbol(src)} / l = {_number(f.value)} N "
                    "⊥ the link at the images of its two points (dashed)")
    for f in loads:
        k = lever.forces.index(f)
        rows.append(_arm_text(f, f"h_{_sub(str(numbers[k]))}" if k in numbers else "h"))
    if not loads:
        rows.append((note or "no load acts at this position") + ";")
    if not any(f.kind == "balance" for f in lever.forces):      # exactly 0: no force, nothing drawn
        unit = "N" if lever.balance == "force" else "N·m"
        rows.append(f"Σ M_p(loads) = 0 N·mm, so {symbol(lever.balance_quantity)} = 0 {unit}: nothing to balance "
                    "(none drawn)")
        return rows
    rows.append(f"Σ M_p(loads) = {_signed(lever.moment_sum, 5)} N·mm;  Σ M_p = 0 gives")
    if lever.balance == "force":
        f = lever.forces[-1]
        k = lever.forces.index(f)
        h = f"h_{_sub(str(numbers[k]))}" if k in numbers else "h"
        rows.append(f"  {symbol(lever.balance_quantity)} = −Σ M_p(loads) / (±{h}) = "
                    f"{_signed(-lever.moment_sum, 5)} / ({_signed(lever.unit_moment, 4)}) = "
                    f"{_number(lever.result, 5)} N")
        rows.append(f"  (along the given direction; |{symbol(lever.balance_quantity)}| = {_number(abs(lever.result), 5)}"
                    " N)")
    else:
        m = symbol(lever.balance_quantity)
        rows.append(f"  {m} as the couple F′ = {m} / l_{{OA}} ⊥ OA at o and a: its moment about p is {m}·k, "
                    f"k = {_signed(lever.unit_moment, 4)} mm/m;")
        sense = "counter-clockwise" if lever.result > 0 else "clockwise" if lever.result < 0 else "no moment"
        rows.append(f"  {m} = −Σ M_p(loads) / k = {_number(lever.result, 5)} N·m ({sense})")
        if lever.omega and lever.result:
            drive = "driving" if lever.result * lever.omega > 0 else "braking"
            rows.append(f"  ω_1 = {_number(lever.omega, 4)} rad/s: {m} is {drive}")
    return rows


#: A lever force drawn shorter than this (mm) records the direction of its line, not of its ends.
SHORT_MM = 1e-6


def lever_caption(lever: Lever, k: int, mu: float) -> str:
    """The statement of the lever's pole detail ×k: its factor and its two scales."""
    return f"detail ×{k}, μ_V = {_decimal(lever.mu_v / k)} (m/s)/mm, μ_F = {mu:g} N/mm"


def _lever_detail(lever: Lever, text_w: float, text_h: float, style: Style) -> LeverDetail | None:
    """The pole detail of ``lever`` placed so that the lever, it and the written computation
    (``text_w`` × ``text_h`` mm, beside or below) fit one sheet's drawing area."""
    sizes = []
    for f in FORMATS:
        aw, ah = f.area.x1 - f.area.x0, f.area.y1 - f.area.y0
        sizes += [(aw - PANEL_GAP_MM - text_w, ah), (aw, ah - PANEL_GAP_MM - text_h)]

    def caption(k: int, mu: float) -> tuple[float, float]:
        return width(runs(lever_caption(lever, k, mu)), style.small_text, False), \
            (ASCENT + DESCENT) * style.small_text + 0.5

    return lever_detail(lever, sizes=tuple((w, h) for w, h in sizes if w > 0 and h > 0), room=LABEL_ROOM_MM,
                        caption=caption)


def _rows(lever: Lever, note: str, detail: LeverDetail | None) -> tuple[list[str], float, float]:
    rows = [r for row in _lever_text(lever, note, detail) for r in wrap(row, LEVER_TEXT_MM, TABLE_TEXT_MM,
                                                                        indent="      ")]
    return rows, max(width(runs(r), TABLE_TEXT_MM, False) for r in rows) + 2.0, TABLE_LEAD_MM * (len(rows) + 1)


def draw_lever(lever: Lever, heading: Heading, *, ident: str, style: Style = Style(), note: str = "") -> str:
    """SVG text of Zhukovsky's lever at one position (see the module docstring); ``note``: why
    no load is on it, written in its computation when none is. Loaded images crowding the pole
    get an enlarged detail beside the lever (:func:`~plans.constructions.lever_detail.lever_detail`)."""
    coords = [p.xy for p in lever.points] + [f.head for f in lever.forces] + [f.foot for f in lever.forces]
    content = bounds(coords)
    rows, text_w, text_h = _rows(lever, note, None)
    detail = _lever_detail(lever, text_w, text_h, style) if lever.forces else None
    if detail is not None:
        rows, text_w, text_h = _rows(lever, note, detail)
        content = union(content, detail.box)
    cw, ch = content[2] - content[0], content[3] - content[1]
    beside = (cw + PANEL_GAP_MM + text_w, max(ch, text_h))
    below = (max(cw, text_w), ch + PANEL_GAP_MM + text_h)
    fmt_b, fmt_u = choose_format(*beside), choose_format(*below)
    order = {f: k for k, f in enumerate(FORMATS)}
    if fmt_b is None and fmt_u is None:
        raise DrawingError(f"Zhukovsky's lever is {cw:.0f} mm × {ch:.0f} mm with its forces and arms, beyond an A3 "
                           "sheet with its computation: turn a velocity plan of a coarser μV")
    use_beside = fmt_b is not None and (fmt_u is None or order[fmt_b] <= order[fmt_u])
    W, H = beside if use_beside else below
    fmt_ = (fmt_b if use_beside else fmt_u) or FORMATS[2]
    scales = f"μ_V = {lever.mu_v:g} (m/s)/mm (turned {lever.sense});  " + \
        (f"μ_F = {lever.mu:g} N/mm" if lever.forces else "μ_F: no force to draw")
    numbers = _arm_numbers(lever, detail)
    best: tuple[int, str] | None = None
    for asked in LABEL_ORDERS:
        crowded, svg = _lever_sheet(lever, heading, ident, style, fmt_, W, H, scales, cw, ch, use_beside, content,
                                    rows, text_h, numbers, detail, asked)
        if crowded == 0:
            return svg
        if best is None or crowded < best[0]:
            best = (crowded, svg)
    return best[1]


#: The orders in which the lever's labels are tried, until one places every label clear:
#: (images' letters first, arms' labels anywhere along their arms, the shortest arms' first).
LABEL_ORDERS = ((False, False, False), (True, True, False), (False, True, False), (True, False, False),
                (True, True, True), (False, True, True))


def _lever_sheet(lever: Lever, heading: Heading, ident: str, style: Style, fmt_, W: float, H: float, scales: str,
                 cw: float, ch: float, use_beside: bool, content, rows, text_h: float, numbers: dict[int, int],
                 detail: LeverDetail | None, order: tuple[bool, bool, bool]) -> tuple[int, str]:
    """The lever's sheet with its labels asked for in ``order`` (see LABEL_ORDERS): how many
    labels found no free place, and the SVG text."""
    dwg, canvas = new_sheet(fmt_, (0.0, 0.0, W, H), ident=ident, style=style,
                            block=TitleBlock(heading.mechanism, heading.sheet, heading.position, scales))
    ox, oy = canvas.dx, canvas.dy - H
    if use_beside:
        lever_box = (ox, oy, ox + cw, oy + H)
        tx, ty = ox + cw + PANEL_GAP_MM, oy + (H - text_h) / 2
    else:
        lever_box = (ox, oy, ox + W, oy + ch)
        tx, ty = ox, oy + ch + PANEL_GAP_MM
    _place(canvas, content, lever_box)
    _lever_layers(dwg, canvas, lever, ident, style, numbers=numbers, detail=detail, order=order)
    if detail is not None:
        _lever_detail_layers(dwg, canvas, lever, detail, ident, style, numbers, order)
    texts = dwg.g(id=f"{ident}-texts")
    for r, row in enumerate(rows):
        canvas.text(texts, (tx, ty + TABLE_LEAD_MM * (r + 0.8)), row, size=TABLE_TEXT_MM, ident=f"{ident}-w{r}")
    dwg.add(texts)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))
    return canvas.crowded, dwg.tostring()


def _lever_detail_layers(dwg, canvas: Canvas, lever: Lever, detail: LeverDetail, ident: str, style: Style,
                         numbers: dict[int, int], order: tuple[bool, bool, bool] = (False, False, False)) -> None:
    """The pole detail: a thin circle round the region on the lever, the detail's own circle,
    its caption and the enlarged lever, a lever group of its own (``data-detail="pole"``)."""
    detail_frame(dwg, canvas, detail, lever_caption(lever, detail.k, detail.lever.mu), ident, style)
    index = {f.quantity: k for k, f in enumerate(lever.forces)}
    mine = {k: numbers[index[f.quantity]] for k, f in enumerate(detail.lever.forces) if index[f.quantity] in numbers}
    _lever_layers(dwg, canvas, detail.lever, f"{ident}-detail", style, numbers=mine, tag_detail=True, order=order)


def _lever_layers(dwg, canvas: Canvas, lever: Lever, ident: str, style: Style, *, numbers: dict[int, int],
                  detail: LeverDetail | None = None, tag_detail: bool = False,
                  order: tuple[bool, bool, bool] = (False, False, False)) -> None:
    """The turned plan, the tagged forces, their arms and the images' letters of ``lever``;
    ``numbers``: force index → its arm's number; ``detail``: the pole detail, whose images,
    arms and short forces are lettered there, not here; ``tag_detail``: this is that detail;
    ``order``: (the images' letters asked for first, an arm's label anywhere along its arm, the
    arms' labels after the forces' names, shortest arm first) — else each force's name and
    its arm's label in turn, the images' letters last, an arm's label by its middle."""
    images_first, anywhere, short_first = order
    hidden: set[str] = set()
    inside: set[str] = set()
    if detail is not None:
        hidden = {p.label for p in detail.lever.points if p.label != lever.pole}
        inside = detail.quantities
    turned = dwg.g(id=f"{ident}-turned", stroke=style.colour, stroke_width=fmt(style.vector, 3), fill="none")
    turned.attribs["data-role"] = "turned velocity plan"
    for k, (a, b) in enumerate(lever.segments):
        canvas.line(turned, a, b, width=style.vector, id=f"{ident}-s{k}")
    dwg.add(turned)
    g = dwg.g(id=f"{ident}-lever")
    g.attribs["data-mu"] = repr(lever.mu)
    g.attribs["data-plan"] = "lever"
    g.attribs["data-mu-v"] = repr(lever.mu_v)
    g.attribs["data-sense"] = lever.sense
    g.attribs["data-vectors"] = str(len(lever.forces))
    g.attribs["data-pole"] = ",".join(canvas.xy(lever.pole_xy))
    if tag_detail:
        g.attribs["data-detail"] = "pole"
    cons = dwg.g(id=f"{ident}-arms", stroke=style.construction_colour, stroke_width=fmt(style.thin, 3), fill="none")
    labels = dwg.g(id=f"{ident}-labels", fill=style.colour)
    pole = np.asarray(lever.pole_xy)
    crowd = (np.asarray(detail.middle), detail.region + NEAR_MM) if detail is not None else None
    # label requests (an arm's length to sort by, canvas.label's arguments, its keywords);
    # else (a force's name, then its arm's label) in turn
    force_labels: list[tuple] = []
    arm_labels: list[tuple] = []
    for k, f in enumerate(lever.forces):
        colour = style.component_colour if f.kind == "balance" else style.vector_colour
        draw = _dashed_vector if f.quantity.startswith("F:M:") else _solid_vector
        el = draw(canvas, g, f.tail, f.head, colour, f"{ident}-v{k}", f"{ident}-h{k}", style)
        _tag(el, canvas, f.quantity, f.value, f.tail, f.head, f.at, f.quantity)
        if f.value / lever.mu < SHORT_MM:
            # far too short for its ends to carry a direction (a zero, or vanishing, balancing
            # element: its head is its tail in floating point): the direction of its line
            el.attribs["data-direction"] = direction_text(f.direction[0], -f.direction[1])
        el.attribs["data-h"] = repr(f.arm)
        el.attribs["data-moment"] = repr(f.moment)
        el.attribs["data-kind"] = f.kind
        in_detail = f.quantity in inside
        if not (in_detail and crowd is not None and math.dist(f.head, crowd[0]) <= crowd[1]):
            # (a short force at the crowd is lettered in the detail)
            ask = (0.0, (labels, f.head, symbol(f.quantity)),
                   dict(size=style.text, prefer=np.subtract(f.head, f.tail), ident=f"{ident}-vl{k}", digits=False,
                        fill=colour, near=0.6))
            (force_labels if images_first or short_first else arm_labels).append(ask)
        if f.arm < MIN_ARM_MM:
            continue
        arm = canvas.line(cons, pole, f.foot, id=f"{ident}-a{k}")
        arm.attribs["data-construction"] = "arm"
        arm.attribs["data-arm"] = f.quantity
        # the line of action on to the foot, when the foot is off the arrow
        t, hd, foot = np.asarray(f.tail), np.asarray(f.head), np.asarray(f.foot)
        d = hd - t
        s = la.dot(foot - t, d) / la.dot(d, d) if la.dot(d, d) > 0 else 0.0
        if s < 0 or s > 1:
            near = t if s < 0 else hd
            ext = canvas.line(cons, near, foot, id=f"{ident}-e{k}", stroke_dasharray=style.dash)
            ext.attribs["data-construction"] = "line of action"
        if f.arm >= 3 * RIGHT_ANGLE_MM and math.dist(f.tail, f.head) > 0:
            e1 = (pole - foot) / f.arm
            e2 = d / math.sqrt(la.dot(d, d))
            if la.dot(t - foot, e2) < 0:
                e2 = -e2
            r = RIGHT_ANGLE_MM
            canvas.polyline(cons, [foot + r * e1, foot + r * (e1 + e2), foot + r * e2], id=f"{ident}-ra{k}")
        if in_detail:
            continue                    # its arm is labelled in the detail
        mid = (pole + foot) / 2
        n = np.array([-(foot - pole)[1], (foot - pole)[0]])
        along = tuple(tuple(pole + t * (foot - pole)) for t in ARM_LABEL_AT) if anywhere else ()
        arm_labels.append((f.arm, (labels, tuple(mid), f"h_{_sub(str(numbers[k]))}"),
                           dict(size=style.small_text + 0.5, prefer=n, ident=f"{ident}-al{k}", digits=False,
                                fill=style.construction_colour, near=0.4, also=along)))
    g.add(cons)
    centre = np.mean([p.xy for p in lever.points], axis=0)
    seen: list[tuple[float, float]] = []
    image_labels: list[tuple] = []
    for k, p in enumerate(lever.points):
        if any(math.dist(p.xy, q) < 0.3 for q in seen):
            continue
        same = [q.label for q in lever.points if math.dist(q.xy, p.xy) < 0.3]
        seen.append(p.xy)
        canvas.circle(labels, p.xy, 0.45, filled=True, id=f"{ident}-d{k}")
        same = [s for s in same if s not in hidden]
        if not same:
            continue
        away = np.subtract(p.xy, centre)
        image_labels.append((0.0, (labels, p.xy, " ≡ ".join(_markup(s) for s in same)),
                             dict(size=style.text, prefer=away if la.norm(away) > 1e-9 else (-0.6, -0.8),
                                  ident=f"{ident}-l{k}", digits=False, near=0.5)))
    if short_first:
        arm_labels.sort(key=lambda ask: ask[0])         # only arms' labels here: the shortest arm first
    asks = image_labels + force_labels + arm_labels if images_first else force_labels + arm_labels + image_labels
    for _, args, kwargs in asks:
        canvas.label(*args, **kwargs)
    g.add(labels)
    dwg.add(g)


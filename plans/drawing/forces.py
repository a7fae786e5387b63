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

Zhukovsky's lever is drawn by :mod:`.lever`, the marks both share (symbols, numbers, vectors) are
in :mod:`.force_marks`.

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

from ..constructions.forces import SHORT_SIDE_MM, ForceDetail, ForcePlan, force_details
from .canvas import Canvas, fmt
from ..constructions.group_diagram import GroupDiagram
from .force_marks import (PANEL_GAP_MM, TABLE_LEAD_MM, TABLE_TEXT_MM, _colour, _dashed_vector, _number, _place,
                          _side_label_direction, _solid_vector, symbol)
from .group_diagram import diagram_box, diagram_rows, draw_group_diagram
from .marks import bounds, markup as _markup
from .sheet import FORMATS, TitleBlock, choose_format, new_sheet
from .style import Style
from .svg import Heading, _tag, plan_group
from .text import runs, width, wrap
from .. import linalg as la

__all__ = ["draw_force_plans", "symbol", "PANEL_GAP_MM", "TABLE_TEXT_MM", "TABLE_LEAD_MM"]

#: Columns of a force table: symbol, value (N), drawn length (mm), note; their widths, mm.
TABLE_COLUMNS_MM = (22.0, 20.0, 18.0, 52.0)
#: Vertices nearer than this share one label naming them all, mm: a letter is about 2.5 mm
#: tall, and two vertices nearer than SHORT_SIDE_MM read as one spot (the layout measurer's rule).
VERTEX_SPOT_MM = 3.0
#: Width the written moment equations under a group's diagram wrap to (at least), mm.
WRITTEN_MM = 70.0


# --- force plans ------------------------------------------------------------------------------

@dataclass(frozen=True)
class _Panel:
    """One group's panel: its caption over columns of blocks (:data:`ARRANGEMENTS`) — ``D`` the
    group drawn alone (its views side by side, or stacked), ``W`` their written equations,
    ``P`` the polygon with its details beside it, ``T`` the table."""

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
    detail_at: tuple[tuple[float, float], ...] = ()    # each detail's top left in the polygon's block, mm
    diagrams: tuple[GroupDiagram, ...] = ()        # the group drawn alone (a triad: twice)
    diagram_contents: tuple[tuple[float, float, float, float], ...] = ()
    written: tuple[str, ...] = ()                  # under the diagrams: their methods, equations and notes
    stacked: bool = False                          # the diagrams one over the other, not side by side
    columns: tuple[tuple[str, ...], ...] = (("P", "T"),)
    sizes: tuple[tuple[str, float, float], ...] = ()   # each block's width and height, mm


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
        if v is None and t.value > 0:          # a whole reaction whose components are not adjacent sides
            note = "its components are drawn"
        rows.append((symbol(t.quantity), _number(t.value), _number(v.length, 4) if v else
                     ("not drawn" if t.value > 0 else "0 (not drawn)"), note))
    return rows


def _panel(plan: ForcePlan, style: Style, diagrams: Sequence[GroupDiagram] = ()) -> list[_Panel]:
    """The panel of one group (its narrowest arrangement that fits an A3 sheet); two (the group
    drawn alone, then its polygon) when no arrangement fits."""
    options = _panel_options(plan, style, diagrams)
    if options:
        return [options[0]]
    if diagrams:
        return _split_panel(plan, style, diagrams)
    return [_panel_options(plan, style, fit=False)[0]]      # too large anyway: the least overflow


def _panel_options(plan: ForcePlan, style: Style, diagrams: Sequence[GroupDiagram] = (), *, fit: bool = True
                   ) -> list[_Panel]:
    """Every arrangement of the group's panel that fits an A3 sheet, the narrowest first (with
    ``fit=False`` every arrangement, the least overflowing first)."""
    coords = [p.xy for p in plan.points] + [l.start for l in plan.lines] + [l.end for l in plan.lines]
    content = bounds(coords)
    details = force_details(plan)
    boxes = tuple(bounds([p.xy for p in d.points]) for d in details)
    equation = " + ".join(symbol(t.quantity) for t in plan.terms) + " = 0"
    head = f"Force plan of group {plan.group},  μ_F = {plan.mu:g} N/mm"
    w_poly = content[2] - content[0]
    h_poly = content[3] - content[1]
    detail_at = []
    if details:
        # the details in columns beside the polygon, a new column where one would outgrow an A3 sheet
        tallest = FORMATS[2].area.y1 - FORMATS[2].area.y0 - 4 * TABLE_LEAD_MM
        x, y, col = w_poly + PANEL_GAP_MM, 0.0, 0.0
        for k, (d, b) in enumerate(zip(details, boxes)):
            bw = max(b[2] - b[0], width(runs(_detail_caption(k, d)), TABLE_TEXT_MM, False))
            bh = TABLE_LEAD_MM + b[3] - b[1]
            if y > 0 and y + bh > max(tallest, h_poly):
                x, y, col = x + col + PANEL_GAP_MM, 0.0, 0.0
            detail_at.append((x, y))
            y += bh
            col = max(col, bw)
            h_poly = max(h_poly, y)
        w_poly = x + col
    boxes_d = tuple(diagram_box(d) for d in diagrams)
    rows = _table_rows(plan, details)
    table = (sum(TABLE_COLUMNS_MM) if any(r[3] for r in rows) else sum(TABLE_COLUMNS_MM[:3]),
             TABLE_LEAD_MM * (len(rows) + 1.8))
    poly = (w_poly, h_poly)
    a3 = FORMATS[2].area
    room_w, room_h = a3.x1 - a3.x0, a3.y1 - a3.y0
    found = []
    for stacked in ((False, True) if len(diagrams) > 1 else (False,)):
        for columns in (ARRANGEMENTS if diagrams else PLAIN):
            size, written = _blocks(diagrams, boxes_d, stacked, poly, table)
            cols = [[(name, *size[name]) for name in col] for col in columns]
            body_w = sum(max(w for _, w, _ in col) for col in cols) + PANEL_GAP_MM * (len(cols) - 1)
            body_w = max(body_w, 0.0 if diagrams else 90.0)
            caption = tuple(wrap(head, body_w, TABLE_TEXT_MM) + wrap(equation, body_w, TABLE_TEXT_MM, indent="   "))
            w = max([body_w] + [width(runs(c), TABLE_TEXT_MM, False) for c in caption])
            h = TABLE_LEAD_MM * (len(caption) + 0.5) + max(sum(h for _, _, h in col) + TABLE_LEAD_MM * 0.9 *
                                                             (len(col) - 1) for col in cols)
            over = max(w - room_w, 0.0) + max(h - room_h, 0.0)
            if fit and over > 0:
                continue
            found.append(((over, w, h), _Panel(plan, content, caption, tuple(rows), w, h, details, boxes, w_poly, h_poly,
                                         tuple(detail_at), tuple(diagrams), boxes_d, written, stacked,
                                         tuple(tuple(c) for c in columns),
                                         tuple((k, float(v[0]), float(v[1])) for k, v in size.items()))))
    found.sort(key=lambda f: f[0])
    return [p for _, p in found]


def _split_panel(plan: ForcePlan, style: Style, diagrams: Sequence[GroupDiagram]) -> list[_Panel]:
    """The group drawn alone and its polygon, each a panel (they do not fit one A3 sheet together)."""
    boxes_d = tuple(diagram_box(d) for d in diagrams)
    alone = f"Group {plan.group} drawn alone, μ_l = {diagrams[0].mu:g} m/mm (its force plan follows)"
    size, written = _blocks(diagrams, boxes_d, False, (0.0, 0.0), (0.0, 0.0))
    cap = tuple(wrap(alone, size["W"][0], TABLE_TEXT_MM))
    first = _Panel(plan, bounds([(0.0, 0.0)]), cap, (), max(size["D"][0], size["W"][0]),
                   TABLE_LEAD_MM * (len(cap) + 0.5) + size["D"][1] + TABLE_LEAD_MM * 0.9 + size["W"][1],
                   diagrams=tuple(diagrams), diagram_contents=boxes_d, written=written, columns=(("D", "W"),),
                   sizes=tuple((k, float(v[0]), float(v[1])) for k, v in size.items()))
    return [first] + _panel(plan, style)


#: How a panel's blocks may be set in columns, tried in turn (the narrowest that fits an A3
#: sheet wins): the diagrams over their equations, the polygon, the table.
ARRANGEMENTS = ((("D", "W", "T"), ("P",)), (("D", "W"), ("P", "T")), (("D", "W"), ("P",), ("T",)),
                (("D", "W", "P", "T"),), (("D", "W", "P"), ("T",)))
PLAIN = ((("P", "T"),), (("P",), ("T",)))


def _blocks(diagrams, boxes, stacked: bool, poly, table) -> tuple[dict[str, tuple[float, float]], tuple[str, ...]]:
    """Each block's size, mm, and the written rows wrapped to the diagrams' width."""
    ws = [b[2] - b[0] for b in boxes]
    hs = [b[3] - b[1] for b in boxes]
    if stacked:
        dw, dh = max(ws, default=0.0), sum(hs) + PANEL_GAP_MM * max(len(hs) - 1, 0)
    else:
        dw, dh = sum(ws) + PANEL_GAP_MM * max(len(ws) - 1, 0), max(hs, default=0.0)
    size = {"P": poly, "T": table}
    written: tuple[str, ...] = ()
    if diagrams:
        room = max(dw, WRITTEN_MM)
        written = tuple(r for d in diagrams for row in diagram_rows(d)
                        for r in wrap(row, room, TABLE_TEXT_MM, indent="      "))
        size["D"] = (dw, dh)
        size["W"] = (max([room] + [width(runs(r), TABLE_TEXT_MM, False) for r in written]),
                     TABLE_LEAD_MM * (len(written) + 0.2))
    return size, written


def _pack(panels: Sequence[_Panel], room_w: float, room_h: float, *, keep: bool = True
          ) -> list[list[tuple[_Panel, float, float]]]:
    """Panels in rows, left to right, sheet after sheet: (panel, x, y) from each sheet's top left.
    The driving link's panel (the last, ``I(…)``) stays on a sheet of the group before it: when
    it would open a sheet of its own, that group's last panel moves on with it, or (when the two
    cannot share a sheet) it joins the nearest sheet of that group with room for it."""
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
    if keep and len(sheets) > 1 and len(sheets[-1]) == 1 and panels[-1].plan.group.startswith("I("):
        crank = panels[-1]
        last = sheets[-2][-1][0]
        together = _pack([last, crank], room_w, room_h, keep=False)
        if len(together) == 1:                         # the last group's panel moves on to the crank's sheet
            sheets[-2].pop()
            sheets[-1:] = together
        else:                                          # else the crank joins the nearest sheet of its group
            group = last.plan.group
            for k in range(len(sheets) - 2, -1, -1):
                if all(q.plan.group != group for q, _, _ in sheets[k]):
                    break
                joined = _pack([q for q, _, _ in sheets[k]] + [crank], room_w, room_h, keep=False)
                if len(joined) == 1:
                    sheets[k] = joined[0]
                    sheets.pop()
                    break
        sheets = [s for s in sheets if s]
    return sheets


def draw_force_plans(plans: Sequence[ForcePlan], heading: Heading, *, ident: str,
                     style: Style = Style(), diagrams: Sequence[GroupDiagram] = ()) -> tuple[str, ...]:
    """SVG texts of the force plans of one position (see the module docstring): usually one
    sheet; more when the panels do not fit one A3 sheet. ``diagrams``: the groups drawn alone
    (:mod:`.group_diagram`), each beside the polygon of its group."""
    if not plans:
        return ()
    alone: dict[str, list[GroupDiagram]] = {}
    for d in diagrams:
        alone.setdefault(d.group, []).append(d)
    panels = [q for p in plans for q in _panel(p, style, alone.get(p.group, ()))]
    a3 = FORMATS[2].area
    room = (a3.x1 - a3.x0, a3.y1 - a3.y0)
    groups = _pack(panels, *room)
    if len(plans) > 1 and plans[-1].group.startswith("I(") and len(groups[-1]) == 1 and len(panels) > 1:
        # the driving link alone on its sheet: another arrangement of it and of the last group's
        # panel may let the two share one
        pair = _pair(plans[-2], plans[-1], style, alone, room)
        if pair is not None:
            head = _pack(panels[:-2], *room) if len(panels) > 2 else []
            groups = head + [pair]
    out = []
    for s, placed in enumerate(groups):
        sid = ident if len(groups) == 1 else f"{ident}-{s + 1}"
        out.append(_force_sheet(placed, heading, sid, style))
    return tuple(out)


def _pair(last: ForcePlan, crank: ForcePlan, style: Style, alone, room) -> list | None:
    """The last group's panel and the driving link's on one sheet, beside or below each other,
    in the first arrangements of the two that fit (the narrowest first); None when none does."""
    for a in _panel_options(last, style, alone.get(last.group, ())):
        for b in _panel_options(crank, style, alone.get(crank.group, ())):
            if a.width + PANEL_GAP_MM + b.width <= room[0] and max(a.height, b.height) <= room[1]:
                return [(a, 0.0, 0.0), (b, a.width + PANEL_GAP_MM, 0.0)]
            if max(a.width, b.width) <= room[0] and a.height + PANEL_GAP_MM + b.height <= room[1]:
                return [(a, 0.0, 0.0), (b, 0.0, a.height + PANEL_GAP_MM)]
    return None


def _force_sheet(placed, heading: Heading, ident: str, style: Style) -> str:
    W = max(x + p.width for p, x, _ in placed)
    H = max(y + p.height for p, _, y in placed)
    fmt_ = choose_format(W, H) or FORMATS[2]
    said: dict[str, list[str]] = {}
    for p, _, _ in placed:
        said.setdefault(p.plan.group, [])
        for what in ([f"μ_F = {p.plan.mu:g} N/mm"] if p.rows else []) + \
                ([f"μ_l = {p.diagrams[0].mu:g} m/mm"] if p.diagrams else []):
            if what not in said[p.plan.group]:
                said[p.plan.group].append(what)
    scales = ";  ".join(f"{g}: {', '.join(v)}" for g, v in said.items())
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
        body = top + TABLE_LEAD_MM * (len(p.caption) + 0.5)
        size = {k: (w, h) for k, w, h in p.sizes}
        x0 = left
        for col in p.columns:
            y0 = body
            for block in col:
                _block(dwg, canvas, texts, rules, p, block, (x0, y0), pid, style)
                y0 += size[block][1] + TABLE_LEAD_MM * 0.9
            x0 += max(size[b][0] for b in col) + PANEL_GAP_MM
    dwg.add(rules)
    dwg.add(texts)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))
    return dwg.tostring()


def _block(dwg, canvas: Canvas, texts, rules, p: _Panel, block: str, at: tuple[float, float], pid: str,
           style: Style) -> None:
    """Draw one block of panel ``p`` with its top left at paper ``at``."""
    left, top = at
    if block == "D":
        x, y = left, top
        for j, (d, b) in enumerate(zip(p.diagrams, p.diagram_contents)):
            w, h = b[2] - b[0], b[3] - b[1]
            _place(canvas, b, (x, y, x + w, y + h))
            draw_group_diagram(dwg, canvas, d, f"{pid}-d{j}", style)
            if p.stacked:
                y += h + PANEL_GAP_MM
            else:
                x += w + PANEL_GAP_MM
    elif block == "W":
        for r, line in enumerate(p.written):
            canvas.text(texts, (left, top + TABLE_LEAD_MM * (r + 0.75)), line, size=TABLE_TEXT_MM, ident=f"{pid}-w{r}")
    elif block == "P":
        cw = p.content[2] - p.content[0]
        if p.details:
            # the polygon on the left, its details stacked in a column beside it
            _place(canvas, p.content, (left, top, left + cw, top + p.poly_height))
            _force_layers(dwg, canvas, p.plan, pid, style, details=p.details)
            for j, (d, b, (ox, oy)) in enumerate(zip(p.details, p.detail_boxes, p.detail_at)):
                dx, dy = left + ox, top + oy
                canvas.text(texts, (dx, dy + TABLE_LEAD_MM * 0.75), _detail_caption(j, d), size=TABLE_TEXT_MM,
                            ident=f"{pid}-dcap{j}")
                dy += TABLE_LEAD_MM
                _place(canvas, b, (dx, dy, dx + b[2] - b[0], dy + b[3] - b[1]))
                _detail_layers(dwg, canvas, p.plan, d, f"{pid}-x{j}", style)
        else:
            room = cw if p.diagrams or len(p.columns) > 1 else max(cw, p.width)
            _place(canvas, p.content, (left, top, left + room, top + p.poly_height))
            _force_layers(dwg, canvas, p.plan, pid, style)
    else:
        ty = top + TABLE_LEAD_MM * 0.75
        w = next(w for k, w, _ in p.sizes if k == "T") if p.sizes else sum(TABLE_COLUMNS_MM)
        cols = np.cumsum((0.0,) + TABLE_COLUMNS_MM)
        cols[-1] = w
        for c, head in enumerate(("force", "F, N", "drawn, mm", "")):
            if head:
                canvas.text(texts, (left + cols[c], ty), head, size=TABLE_TEXT_MM, ident=f"{pid}-th{c}")
        rule_y = ty + TABLE_LEAD_MM * 0.45
        canvas.line(rules, (left - canvas.dx, canvas.dy - rule_y), (left + cols[-1] - canvas.dx, canvas.dy - rule_y),
                    id=f"{pid}-rule")
        for r, row in enumerate(p.rows):
            for c, cell in enumerate(row):
                canvas.text(texts, (left + cols[c], ty + TABLE_LEAD_MM * (r + 1.1)), cell, size=TABLE_TEXT_MM,
                            ident=f"{pid}-t{r}-{c}")


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

"""The ``-balancing`` sheet of a rotor (:mod:`plans.constructions.balancing`): the shaft with its
planes (the reference plane L marked), the table of m, r, θ, l, m·r and m·r·l of every mass and
of the balancing masses found, and the couple and force polygons, each to its own stated scale,
its sides blue and the closing vector (the balancing one) red.

Each polygon is a ``<g data-plan="balance-couple">`` (``"balance-force"``) with ``data-mu`` its
scale; every side and the closing vector a tagged ``<line>`` (``data-quantity`` ``mrl:2``,
``mr:L`` …, ``data-value`` the magnitude, ``data-direction``, ``data-from``/``data-to`` the vertex
letters), so ``plans check`` measures each (length × μ = value, direction) and finds the polygon
closed (the closing vector ends where the first side starts).
"""

from __future__ import annotations

from ..constructions.balancing import BalancePolygon, ShaftPlanes
from ..dynamics.balancing import RotorBalance
from .canvas import Canvas, fmt
from .force_marks import _number, _solid_vector
from .marks import bounds
from .sheet import FORMATS, TitleBlock, choose_format, new_sheet, note_lines
from .style import Style
from .svg import Heading, _tag
from .text import wrap

__all__ = ["draw_balancing"]

TEXT_MM = 2.8
LEAD_MM = 4.6
GAP_MM = 12.0
COLUMNS = ("", "m, kg", "r, m", "θ, °", "l, m", "m·r, kg·m", "m·r·l, kg·m²")
COLUMN_MM = (12.0, 18.0, 16.0, 16.0, 16.0, 22.0, 24.0)


def _symbol(q: str) -> str:
    kind, _, which = q.partition(":")
    return ("(m·r·l)" if kind == "mrl" else "(m·r)") + f"_{{{which}}}"


def _rows(b: RotorBalance) -> list[tuple[str, ...]]:
    out = []
    for k, m in enumerate(b.masses):
        out.append((str(k + 1), _number(m.mass), _number(m.radius), _number(m.angle), _number(m.l),
                    _number(abs(m.mr)), _number(abs(m.mrl))))
    for name, p in zip(("L", "M"), b.balancing):
        out.append((name, _number(p.mass), _number(p.radius), _number(p.angle), _number(p.l), _number(abs(p.mr)),
                    _number(abs(p.mrl))))
    return out


def draw_balancing(b: RotorBalance, polygons: tuple[BalancePolygon, ...], shaft: ShaftPlanes | None,
                   heading: Heading, *, ident: str, style: Style = Style(), notes: tuple[str, ...] = ()) -> str:
    """SVG text of the sheet (see the module)."""
    rows = _rows(b)
    table_w, table_h = sum(COLUMN_MM), LEAD_MM * (len(rows) + 1.5)
    shaft_h = 24.0 if shaft is not None else 0.0
    left_w = max(table_w, (shaft.ends[1] - shaft.ends[0] + 20.0) if shaft is not None else 0.0)
    area = FORMATS[2].area
    room = area.x1 - area.x0 - 2.0
    blocks, x, y, row_h = [], left_w + GAP_MM, 0.0, shaft_h + table_h
    for k, poly in enumerate(polygons):
        box = bounds([p for _, p in poly.points])
        w = max(box[2] - box[0], 70.0)
        caption = tuple(wrap(_caption(b, poly), w, TEXT_MM))
        h = box[3] - box[1] + LEAD_MM * (len(caption) + 0.8)
        if x + w > room:                              # no room beside: a row of their own below
            x, y, row_h = 0.0, y + row_h + GAP_MM, 0.0
        blocks.append((poly, box, caption, x, y))
        x += w + GAP_MM
        row_h = max(row_h, h)
    W = max([left_w] + [bx + max(box[2] - box[0], 70.0) for _, box, _, bx, _ in blocks])
    H = y + row_h + 6.0 * (len(notes) + 1)
    f = choose_format(W, H) or FORMATS[2]
    scales = "; ".join(f"{p.kind} polygon μ = {p.mu:g} {p.unit}/mm" for p in polygons) + \
        (f"; shaft μ_l = {shaft.mu:g} m/mm" if shaft is not None else "")
    dwg, canvas = new_sheet(f, (0.0, -H, W, 0.0), ident=ident, style=style,
                            block=TitleBlock(heading.mechanism, heading.sheet, heading.position, scales))
    texts = dwg.add(dwg.g(id=f"{ident}-texts", fill=style.colour))
    labels = dwg.g(id=f"{ident}-labels", fill=style.colour)
    if shaft is not None:
        _shaft(dwg, canvas, shaft, (10.0 - shaft.ends[0], -12.0), f"{ident}-shaft", style, labels)
    ty = shaft_h + LEAD_MM
    xs = [sum(COLUMN_MM[:k]) for k in range(len(COLUMN_MM))]
    for c, head in enumerate(COLUMNS):
        canvas.text(texts, canvas.paper((xs[c], -ty)), head, size=TEXT_MM, ident=f"{ident}-th{c}")
    rule = dwg.add(dwg.g(id=f"{ident}-rule", stroke=style.colour, stroke_width=fmt(style.thin, 3)))
    canvas.line(rule, (0.0, -ty - 1.5), (table_w, -ty - 1.5), width=style.thin, id=f"{ident}-rule0")
    for r, row in enumerate(rows):
        for c, cell in enumerate(row):
            canvas.text(texts, canvas.paper((xs[c], -ty - LEAD_MM * (r + 1.1))), cell, size=TEXT_MM,
                        ident=f"{ident}-t{r}-{c}")
    for k, (poly, box, caption, x0, y0) in enumerate(blocks):
        for j, line in enumerate(caption):
            canvas.text(texts, canvas.paper((x0, -y0 - LEAD_MM * (j + 1))), line, size=TEXT_MM,
                        ident=f"{ident}-cap{k}-{j}")
        top = y0 + LEAD_MM * (len(caption) + 0.8)
        _polygon(dwg, canvas, poly, (x0 - box[0], -top - box[3]), f"{ident}-p{k}", style, labels)
    dwg.add(labels)
    if notes:
        note_lines(canvas, dwg.add(dwg.g(id=f"{ident}-notes")), notes, style)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))
    return dwg.tostring()


def _caption(b: RotorBalance, poly: BalancePolygon) -> str:
    if poly.kind == "couple":
        return f"Couple polygon about the reference plane L, μ = {poly.mu:g} kg·m²/mm: Σ(m·r·l) + (m·r·l)_{{M}} = 0"
    return (f"Force polygon, μ = {poly.mu:g} kg·m/mm: Σ(m·r) + " + ("(m·r)_{M} + " if b.dynamic else "") +
            "(m·r)_{L} = 0")


def _polygon(dwg, canvas: Canvas, poly: BalancePolygon, shift: tuple[float, float], ident: str, style: Style,
             labels) -> None:
    def p(xy) -> tuple[float, float]:
        return xy[0] + shift[0], xy[1] + shift[1]

    g = dwg.g(id=ident)
    g.attribs["data-plan"] = f"balance-{poly.kind}"
    g.attribs["data-mu"] = repr(poly.mu)
    sides = list(poly.sides) + ([poly.closing] if poly.closing is not None else [])
    g.attribs["data-vectors"] = str(len(sides))
    cx = sum(p(xy)[0] for _, xy in poly.points) / len(poly.points)
    cy = sum(p(xy)[1] for _, xy in poly.points) / len(poly.points)
    for k, s in enumerate(sides):
        closing = s is poly.closing
        colour = style.component_colour if closing else style.vector_colour
        el = _solid_vector(canvas, g, p(s.tail), p(s.head), colour, f"{ident}-v{k}", f"{ident}-h{k}", style)
        _tag(el, canvas, s.quantity, s.value, p(s.tail), p(s.head), s.start, s.end)
        mid = ((p(s.tail)[0] + p(s.head)[0]) / 2, (p(s.tail)[1] + p(s.head)[1]) / 2)
        canvas.label(labels, mid, _symbol(s.quantity), size=style.text, prefer=(mid[0] - cx, mid[1] - cy),
                     ident=f"{ident}-vl{k}", digits=False, fill=colour, near=0.4)
    for k, (name, xy) in enumerate(poly.points):
        canvas.circle(g, p(xy), 0.45, filled=True, id=f"{ident}-d{k}")
        canvas.label(labels, p(xy), name, size=style.small_text + 0.5, prefer=(p(xy)[0] - cx, p(xy)[1] - cy),
                     ident=f"{ident}-l{k}", digits=False, near=0.5)
    dwg.add(g)


def _shaft(dwg, canvas: Canvas, s: ShaftPlanes, at: tuple[float, float], ident: str, style: Style, labels) -> None:
    """The shaft as a line, each plane a short cross line named above it (L: the reference plane)."""
    g = dwg.g(id=ident, stroke=style.colour, fill="none")
    g.attribs["data-plan"] = "scheme"
    g.attribs["data-mu"] = repr(s.mu)
    x0, y0 = at
    canvas.line(g, (x0 + s.ends[0], y0), (x0 + s.ends[1], y0), width=style.link, stroke_width=fmt(style.link, 3),
                id=f"{ident}-axis", stroke_dasharray="8 1.5 1 1.5")
    for k, (name, x) in enumerate(s.planes):
        canvas.line(g, (x0 + x, y0 - 4.0), (x0 + x, y0 + 4.0), width=style.vector,
                    stroke_width=fmt(style.vector, 3), id=f"{ident}-plane{k}",
                    stroke=style.component_colour if name in ("L", "M") else style.colour)
        canvas.label(labels, (x0 + x, y0 + 4.0), name + (" (reference)" if name == "L" else ""),
                     size=style.small_text + 0.5, prefer=(0.0, 1.0), ident=f"{ident}-n{k}", digits=False, near=0.5)
    dwg.add(g)

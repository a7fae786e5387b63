"""The ``-assemblies`` sheet (:mod:`plans.constructions.assembly_sheet`): for each class III/IV
group a caption and its assemblies side by side (rows of as many as the sheet holds), each a
small scheme — links thick, the outer pins as fixed joints (a circle over a short hatched base),
sliding pairs as on the scheme sheet (blocks, hatched frame guides, slots), every point lettered — numbered under it with its condition figure, the chosen (drawn) one in a
frame; a class II group's count written as a line of text.

Every small scheme is a ``<g data-plan="scheme" data-mu="μl">`` (``plans check`` reports the sheet
as a scheme: nothing to measure), with ``data-assembly`` its number and ``data-chosen``.
"""

from __future__ import annotations

from dataclasses import replace

from ..constructions.assembly_sheet import AssemblySheet, SmallScheme
from .canvas import Canvas, fmt
from .marks import markup
from .scheme import block_corners, frame_guide
from .sheet import FORMATS, TitleBlock, choose_format, new_sheet, note_lines
from .style import Style
from .svg import Heading
from .text import runs, width as text_width

__all__ = ["draw_assemblies", "SCHEME_GAP_MM"]

#: Room between two small schemes and around each (labels), mm.
SCHEME_GAP_MM = 12.0
#: Height of a caption line and of the line under each scheme, mm.
LINE_MM = 5.5


def _caption(s: SmallScheme) -> str:
    """The line under a small scheme: its number, "(drawn)" for the chosen one, its condition."""
    return f"{s.number}" + (" (drawn)" if s.chosen else "") + \
        (f", condition {s.condition:+.3f}" if s.condition is not None else "")


def _cell(s: SmallScheme, style: Style) -> tuple[float, float]:
    """A small scheme's cell (width, height), mm: its box with SCHEME_GAP_MM around it, at least as
    wide as its caption (and the frame around the chosen one holds both)."""
    caption = text_width(runs(_caption(s)), style.small_text + 0.5, False) + 4.0
    return (max(s.box[2] - s.box[0] + SCHEME_GAP_MM, caption),
            s.box[3] - s.box[1] + SCHEME_GAP_MM + LINE_MM * 2)


def _layout(sheet: AssemblySheet, width: float, style: Style) -> list[tuple[str, object, float, float]]:
    """What goes where (kind, item, x, y of its top left, mm from the content's top left, y down):
    captions, schemes and texts."""
    out, y = [], 0.0
    for row in sheet.rows:
        if not row.schemes:
            out.append(("text", f"{row.group}: {row.count} assemblies at this position (class II: its two closed "
                                f"forms); the one drawn is number {row.chosen}", 0.0, y))
            y += LINE_MM
            continue
        out.append(("caption", f"{row.group}: {row.count} real assemblies at this position; the one drawn (framed) is "
                               f"number {row.chosen}", 0.0, y))
        y += LINE_MM + 2.0
        x, tallest = 0.0, 0.0
        for s in row.schemes:
            w, h = _cell(s, style)
            if x > 0 and x + w > width:
                x, y, tallest = 0.0, y + tallest, 0.0
            out.append(("scheme", s, x, y))
            x += w
            tallest = max(tallest, h)
        y += tallest + 2.0
    return out


def draw_assemblies(sheet: AssemblySheet, heading: Heading, *, ident: str, style: Style = Style(),
                    notes: tuple[str, ...] = ()) -> str:
    """SVG text of the sheet (see the module)."""
    for f in FORMATS:           # the smallest sheet whose width the rows wrap to and whose height holds them
        area = f.area
        items = _layout(sheet, area.x1 - area.x0 - 4.0, style)
        right = max([x + (_cell(it, style)[0] if kind == "scheme" else 0.0) for kind, it, x, _ in items] + [120.0])
        bottom = max(y + (_cell(it, style)[1] if kind == "scheme" else LINE_MM)
                     for kind, it, x, y in items) + 4.0 * (len(notes) + 1)
        if choose_format(right, bottom) in (f, *FORMATS[:FORMATS.index(f)]):
            break
    f = choose_format(right, bottom) or FORMATS[2]
    dwg, canvas = new_sheet(f, (0.0, -bottom, right, 0.0), ident=ident, style=style,
                            block=TitleBlock(heading.mechanism, heading.sheet, heading.position,
                                             f"μ_l = {sheet.mu:g} m/mm (every scheme)"))
    texts = dwg.add(dwg.g(id=f"{ident}-texts", fill=style.colour))
    for k, (kind, it, x, y) in enumerate(items):
        if kind in ("caption", "text"):
            canvas.text(texts, canvas.paper((x, -y - 4.0)), it, size=style.small_text + 0.5, ident=f"{ident}-t{k}")
        else:
            _scheme(dwg, canvas, it, (x, y), f"{ident}-s{k}", style, mu=sheet.mu)
    if notes:
        note_lines(canvas, dwg.add(dwg.g(id=f"{ident}-notes")), notes, style)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))
    return dwg.tostring()


def _scheme(dwg, canvas: Canvas, s: SmallScheme, at: tuple[float, float], ident: str, style: Style, *,
            mu: float) -> None:
    """One small scheme with its top left at ``at`` (x right, y down from the content's top)."""
    cell = _cell(s, style)[0]
    half = SCHEME_GAP_MM / 2
    dx, dy = at[0] + 0.5 * (cell - (s.box[2] - s.box[0])) - s.box[0], -(at[1] + half) - s.box[3]

    def p(xy) -> tuple[float, float]:
        return xy[0] + dx, xy[1] + dy

    g = dwg.g(id=ident, stroke=style.colour, fill="none", stroke_linecap="round")
    g.attribs["data-plan"] = "scheme"
    g.attribs["data-mu"] = repr(mu)
    g.attribs["data-assembly"] = str(s.number)
    g.attribs["data-chosen"] = "true" if s.chosen else "false"
    labels = dwg.g(id=f"{ident}-labels", fill=style.colour)
    for k, gd in enumerate(s.guides):        # under the links, as on the scheme sheet
        gd = replace(gd, start=p(gd.start), end=p(gd.end), stem=None if gd.stem is None else tuple(map(p, gd.stem)))
        w = style.vector if gd.fixed else style.link
        canvas.line(g, gd.start, gd.end, width=w, stroke_width=fmt(w, 3), id=f"{ident}-guide{k}")
        if gd.stem is not None:
            canvas.line(g, gd.stem[0], gd.stem[1], width=style.link, stroke_width=fmt(style.link, 3),
                        id=f"{ident}-stem{k}")
        if gd.fixed:
            frame_guide(canvas, g, gd, k, ident, style)
    for k, (link, pts) in enumerate(s.bars):
        pts = [p(q) for q in pts]
        if len(pts) > 2:
            pts = pts + pts[:1]
        for j in range(len(pts) - 1):
            canvas.line(g, pts[j], pts[j + 1], width=style.link, stroke_width=fmt(style.link, 3), id=f"{ident}-b{k}-{j}")
    for b in s.blocks:
        canvas.polygon(g, block_corners(replace(b, center=p(b.center))), width=style.link, fill="#fff",
                       stroke_width=fmt(style.link, 3), id=f"{ident}-block{b.link}")
    pins = {n for n, _ in s.pins}
    for k, (name, xy) in enumerate(s.points):
        q = p(xy)
        canvas.circle(g, q, 0.9, fill="#fff", stroke=style.colour, stroke_width=fmt(style.thin, 3), id=f"{ident}-j{k}")
        if name in pins:          # held on an earlier link: a short hatched base under it
            canvas.line(g, (q[0] - 2.2, q[1] - 1.6), (q[0] + 2.2, q[1] - 1.6), width=style.thin,
                        stroke_width=fmt(style.thin, 3), id=f"{ident}-g{k}")
            for t in range(3):
                x0 = q[0] - 2.0 + 1.6 * t
                canvas.line(g, (x0, q[1] - 1.6), (x0 - 0.9, q[1] - 2.5), width=style.thin,
                            stroke_width=fmt(style.thin, 3), id=f"{ident}-h{k}-{t}")
        canvas.label(labels, q, markup(name), size=style.small_text + 0.5, prefer=(-0.7, 0.7), ident=f"{ident}-l{k}",
                     near=0.9)
    base = -(at[1] + s.box[3] - s.box[1] + SCHEME_GAP_MM)
    size = style.small_text + 0.5
    left = at[0] + 0.5 * (cell - text_width(runs(_caption(s)), size, False))
    canvas.text(labels, canvas.paper((left, base - 3.5)), _caption(s), size=size, ident=f"{ident}-n")
    if s.chosen:
        frame = [(at[0] + 1.0, -at[1] - 1.0), (at[0] + cell - 1.0, -at[1] - 1.0), (at[0] + cell - 1.0, base - 5.5),
                 (at[0] + 1.0, base - 5.5)]
        canvas.polyline(g, frame, closed=True, width=style.thin, stroke=style.component_colour,
                        stroke_width=fmt(style.thin, 3), id=f"{ident}-frame")
    g.add(labels)
    dwg.add(g)

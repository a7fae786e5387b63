"""Standard sheets: ISO 216 formats, the frame and the title block.

Every sheet is A4 or A3, portrait or landscape: the smallest of A4 portrait, A4 landscape,
A3 landscape and A3 portrait whose drawing area holds the content. The frame leaves a 20 mm
binding margin on the left and 5 mm elsewhere (ISO 5457 / GOST 2.301); the title block,
185 mm × 35 mm, sits in the frame's lower right corner and names the mechanism, the sheet,
the position and the scales. The drawing area is the frame above the title block.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np
import svgwrite

from .canvas import Canvas, fmt
from .style import Style
from .font_metrics import BOOK
from .text import SUB_SIZE, UNKNOWN_EM, Box, box, minus_signs, plain, runs, width, wrap

__all__ = ["Format", "FORMATS", "choose_format", "TitleBlock", "new_sheet", "FRAME_MM", "TITLE_BLOCK_MM",
           "LARGEST"]

#: Frame margins left, top, right, bottom, mm.
FRAME_MM = (20.0, 5.0, 5.0, 5.0)
#: The drawing area keeps this far inside the frame's centreline and the title block: half the
#: frame's 0.7 mm line and a little air, mm.
AREA_INSET_MM = 1.0
#: Title block width and height, mm.
TITLE_BLOCK_MM = (185.0, 35.0)


@dataclass(frozen=True)
class Format:
    """A sheet format: its name and size (mm)."""

    name: str
    width: float
    height: float

    @property
    def area(self) -> Box:
        """The drawing area: inside the frame, above the title block (paper mm, y down)."""
        left, top, right, bottom = (m + AREA_INSET_MM for m in FRAME_MM)
        return Box(left, top, self.width - right, self.height - bottom - TITLE_BLOCK_MM[1])


#: In the order tried: the first whose drawing area holds the content is used.
FORMATS = (Format("A4", 210.0, 297.0), Format("A4", 297.0, 210.0), Format("A3", 420.0, 297.0),
           Format("A3", 297.0, 420.0))
LARGEST = FORMATS[2:]


def choose_format(width_mm: float, height_mm: float) -> Format | None:
    """The first format whose drawing area holds a ``width_mm`` × ``height_mm`` content box,
    or None when even A3 does not."""
    for f in FORMATS:
        a = f.area
        if width_mm <= a.x1 - a.x0 and height_mm <= a.y1 - a.y0:
            return f
    return None


@dataclass(frozen=True)
class TitleBlock:
    """What the title block says: mechanism, sheet, position and scale rows."""

    mechanism: str
    sheet: str
    position: str
    scales: str


#: Title block rows: caption and height, mm.
_ROWS = (("Mechanism", 11.0), ("Sheet", 8.0), ("Position", 8.0), ("Scales", 8.0))
_CAPTION_MM = 22.0
_FORMAT_MM = 18.0


def new_sheet(fmt_: Format, content: tuple[float, float, float, float], *, ident: str, style: Style,
              block: TitleBlock) -> tuple[svgwrite.Drawing, Canvas]:
    """An empty sheet of format ``fmt_`` with its frame and title block, and a canvas whose
    content box ``content`` (x0, y0, x1, y1; mm, y up) is centred in the drawing area."""
    W, H = fmt_.width, fmt_.height
    w, h = fmt(W, 1), fmt(H, 1)
    dwg = svgwrite.Drawing(size=(f"{w}mm", f"{h}mm"), viewBox=f"0 0 {w} {h}", debug=False, profile="full")
    dwg.attribs["id"] = ident
    dwg.attribs["data-precision"] = fmt(style.precision, 10)
    dwg.attribs["data-format"] = fmt_.name
    dwg.add(dwg.rect(insert=(0, 0), size=(w, h), fill="#fff", id=f"{ident}-paper"))
    dwg.set_desc(title=plain(f"{block.mechanism}: {block.sheet}, {block.position}"))
    area = fmt_.area
    x0, y0, x1, y1 = content
    dx = (area.x0 + area.x1) / 2 - (x0 + x1) / 2
    dy = (area.y0 + area.y1) / 2 + (y0 + y1) / 2
    canvas = Canvas(dwg, style, (dx, dy), area)
    frame = dwg.g(id=f"{ident}-frame", stroke=style.colour, fill="none")
    left, top, right, bottom = FRAME_MM
    el = dwg.rect(insert=(fmt(left, 3), fmt(top, 3)), size=(fmt(W - left - right, 3), fmt(H - top - bottom, 3)),
                  stroke_width=fmt(style.link, 3))
    el.attribs["class"] = "frame"
    frame.add(el)
    _title_block(dwg, canvas, frame, fmt_, block, style)
    dwg.add(frame)
    return dwg, canvas


def _fit(text: str, room: float, size: float, smallest: float) -> tuple[str, float]:
    """``text`` at the largest height ≤ ``size`` (down to ``smallest``) at which it fits
    ``room`` mm; cut short with "…" when it does not fit even at ``smallest``."""
    w = width(runs(text), size, False)
    if w <= room:
        return text, size
    if w * smallest / size <= room:
        return text, size * room / w
    text = text[:_most_chars(text, room, smallest)]
    while text and width(runs(text + "…"), smallest, False) > room:
        text = text[:-1]
    return text.rstrip() + "…", smallest


def _most_chars(text: str, room: float, size: float) -> int:
    """How many leading characters of ``text`` might fit ``room`` mm at height ``size`` with
    "…" after them, so that :func:`_fit` cuts from there, not from the end. Plain text (its
    width grows with every character): the last prefix that fits, from the running sum of the
    advance widths, and two more for rounding. With markup: the first prefix that would fill
    more than the room even were every glyph a subscript (the markup characters _ { } print
    nothing), and every longer one does too."""
    em, _, _, table = BOOK
    default = UNKNOWN_EM * em
    advance = np.array([table.get(c, default) for c in text] or [0.0])
    if "_" not in text:
        ends = (np.cumsum(advance) + table.get("…", default)) / em * size      # ends[k]: text[:k + 1] + "…"
        return min(len(text), int(np.searchsorted(ends, room, side="right")) + 2)
    advance[[i for i, c in enumerate(text) if c in "_{}"]] = 0.0
    least = np.cumsum(advance) / em * SUB_SIZE * size * (1.0 - 1e-9)               # least[k]: text[:k + 1]
    return min(len(text), int(np.searchsorted(least, room, side="right")) + 1)


#: A title-block value is shrunk down to this height on one line (mm), then wrapped on two.
ONE_LINE_MM = 2.8
#: Baseline to baseline of a wrapped value, in text heights (more than a line's box, 1.23).
LINE_SPACING = 1.3
#: The part of a cell's width a value's measured width may fill.
METRIC_MARGIN = 0.93


def _fit_rows(text: str, room: float, size: float, row_h: float) -> tuple[list[str], float]:
    """``text`` as the rows of a title-block cell ``room`` mm wide and ``row_h`` high: one line
    at the largest height ≤ ``size`` down to :data:`ONE_LINE_MM`; else two lines, as large as
    the cell's height allows and both fit; else one line cut short at 2 mm (:func:`_fit`).
    The room is taken :data:`METRIC_MARGIN` short: renderers' fonts run a few per cent wider
    than the metrics (cairosvg's did, past the frame)."""
    room *= METRIC_MARGIN
    w = width(runs(text), size, False)
    if w <= room:
        return [text], size
    if w * ONE_LINE_MM / size <= room:
        return [text], size * room / w
    line = box(runs(text), 1.0, False, 0.0, 0.0)
    s = min(size, (row_h - 1.0) / (LINE_SPACING + line.y1 - line.y0))
    while s >= 2.0:
        rows = wrap(text, room, s)
        if len(rows) <= 2 and all(width(runs(r), s, False) <= room for r in rows):
            return rows, s
        s = round(s - 0.1, 6)
    value, size = _fit(text, room, size, 2.0)
    return [value], size


def _title_block(dwg: svgwrite.Drawing, canvas: Canvas, frame, fmt_: Format, block: TitleBlock, style: Style) -> None:
    W, H = fmt_.width, fmt_.height
    bw, bh = TITLE_BLOCK_MM
    x0, y_bottom = W - FRAME_MM[2] - bw, H - FRAME_MM[3]
    y = y_bottom - bh
    g = dwg.g(id=f"{dwg.attribs['id']}-title", stroke=style.colour, fill="none", stroke_width=fmt(style.vector, 3))
    g.attribs["class"] = "title-block"
    g.add(dwg.rect(insert=(fmt(x0, 3), fmt(y, 3)), size=(fmt(bw, 3), fmt(bh, 3)), stroke_width=fmt(style.link, 3)))
    texts = dwg.g(id=f"{dwg.attribs['id']}-title-text", stroke="none")
    values = (block.mechanism, block.sheet, block.position, block.scales)
    room = bw - _CAPTION_MM - 3.0
    for k, ((caption, row_h), value) in enumerate(zip(_ROWS, values)):
        if k:
            g.add(dwg.line(start=(fmt(x0, 3), fmt(y, 3)), end=(fmt(x0 + bw, 3), fmt(y, 3)),
                           stroke_width=fmt(style.thin, 3)))
        base = y + row_h / 2 + 1.2
        canvas.text(texts, (x0 + 2.0, base), caption, size=style.small_text)
        this_room = room - (_FORMAT_MM if k == 1 else 0.0)
        rows, size = _fit_rows(value, this_room, style.title_text if k == 0 else style.text, row_h)
        if len(rows) == 1:
            first = y + row_h / 2 + 0.35 * size
        else:       # the two lines' boxes (ascent of the first to descent of the second) centred in the row
            b = box(runs(rows[0]), size, False, 0.0, 0.0)
            first = y + (row_h - (LINE_SPACING * size + b.y1 - b.y0)) / 2 - b.y0
        for j, row in enumerate(rows):
            canvas.text(texts, (x0 + _CAPTION_MM + 1.5, first + j * LINE_SPACING * size), row, size=size)
        y += row_h
    g.add(dwg.line(start=(fmt(x0 + _CAPTION_MM, 3), fmt(y_bottom - bh, 3)), end=(fmt(x0 + _CAPTION_MM, 3),
                   fmt(y_bottom, 3)), stroke_width=fmt(style.thin, 3)))
    fy = y_bottom - bh + _ROWS[0][1]
    fx = x0 + bw - _FORMAT_MM
    g.add(dwg.line(start=(fmt(fx, 3), fmt(fy, 3)), end=(fmt(fx, 3), fmt(fy + _ROWS[1][1], 3)),
                   stroke_width=fmt(style.thin, 3)))
    canvas.text(texts, (fx + _FORMAT_MM / 2, fy + _ROWS[1][1] / 2 + 1.2), fmt_.name, size=style.text,
                anchor="middle")
    frame.add(g)
    frame.add(texts)


def note_lines(canvas: Canvas, parent, lines: Sequence[str], style: Style) -> None:
    """Lines of small text at the bottom left of the drawing area (why a plan is empty, which
    rule gave way), each wrapped at word boundaries to the area's width; a negative number with
    the minus sign."""
    a = canvas.area
    room = a.x1 - a.x0 - 6.0
    rows = [row for line in lines for row in wrap(minus_signs(line), room, style.small_text)]
    y = a.y1 - 2.0 - 4.0 * (len(rows) - 1)
    for k, row in enumerate(rows):
        canvas.text(parent, (a.x0 + 3.0, y + 4.0 * k), row, size=style.small_text)

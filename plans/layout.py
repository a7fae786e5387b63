"""The layout of a sheet measured from its SVG text alone.

:func:`measure_layout` reads an SVG sheet the way a reader of the paper would see it, without
the bookkeeping of the code that drew it: it parses every ``<text>`` (position, anchor, font
size and style, ``<tspan>`` runs with their ``dx``/``dy`` shifts), sizes each with the metrics
of the sheet's font (:mod:`plans.drawing.text`: advance widths, ascent and descent), and every
inked shape (``<line>``, ``<path>``, ``<polygon>``, ``<polyline>``, ``<rect>``, ``<circle>``,
``<ellipse>``: a stroke is its centreline buffered by half its stroke width, a dark fill is its
area; a pale fill, white or the plates' tint, is paper). It counts five faults:

- ``overlapping_labels`` — two text boxes whose interiors meet (touching edges is fine);
- ``labels_crossing_lines`` — a text box meeting inked geometry; a leader
  (``<line class="leader">``) never crosses the label its end point touches, and the texts of
  the title block are not measured against the title block's own cells or the frame (they
  must stay inside the frame instead);
- ``labels_off_sheet`` — a text box not inside the frame's inner area (``<rect class="frame">``
  less half its stroke; the paper when there is no frame), or, for any text but the title
  block's, not inside the drawing area (the frame's inner area less the title block's rect);
- ``long_heads`` — an arrowhead (``<path class="head" data-for=ID>``) longer, tip to the middle
  of its base, than the vector ``<line id=ID>`` it ends (or, for a drawn arc ``<path id=ID>``,
  the arc and on to the tip); or a tagged vector (``<line data-quantity>`` in a plan group)
  shorter than :data:`NO_HEAD_MM` that has a head;
- ``beyond_a3`` — a sheet larger than A3 (297 mm × 420 mm, either way round).

A label crossing one element counts once, however many strokes of it (hatching) it meets.
White space is read as SVG 1.1 renders it: a run of spaces is one space. A head whose
``data-for`` names no ``<line>`` or ``<path>`` (and no line ends at its tip) cannot be
measured: it is listed in :attr:`LayoutReport.unmatched_heads`, not counted.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

import numpy as np
import shapely

from .drawing.text import ASCENT, DESCENT, _em

__all__ = ["LayoutReport", "measure_layout", "A3_MM", "NO_HEAD_MM", "SHOWN"]

#: The largest sheet allowed, mm (either orientation), and the tolerance on it.
A3_MM = (297.0, 420.0)
SIZE_TOLERANCE_MM = 0.05
#: Standard formats recognised by size (either orientation).
FORMATS = {"A4": (210.0, 297.0), "A3": (297.0, 420.0)}
#: A tagged vector shorter than this must have no arrowhead, mm (the writer's promise,
#: plans.drawing.marks.NO_HEAD_MM, restated here so the measurer does not read the writer).
NO_HEAD_MM = 2.0
#: Rounding allowance of written coordinates when comparing lengths, mm.
ROUNDING_MM = 2e-3
#: How close a leader's end must be to a label's box to be that label's leader, mm.
LEADER_TOUCH_MM = 0.01
#: Offenders listed per fault (the counts are complete).
SHOWN = 12
#: A paint lighter than this (relative luminance, 0 … 1) is paper, not ink.
PALE = 0.9

#: A circle as a 48-gon (unit radius).
_CIRCLE = [(math.cos(2 * math.pi * k / 48), math.sin(2 * math.pi * k / 48)) for k in range(48)]
_SKIP = {"defs", "clipPath", "mask", "symbol", "marker", "pattern", "metadata", "title", "desc", "style", "script"}
_INHERITED = ("fill", "stroke", "stroke-width", "stroke-linecap", "stroke-linejoin", "font-size", "font-style",
              "text-anchor", "fill-opacity", "stroke-opacity", "opacity", "visibility", "xml:space")
_NUM = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_UNITS = {"mm": 1.0, "cm": 10.0, "in": 25.4, "pt": 25.4 / 72.0, "pc": 25.4 / 6.0, "px": 25.4 / 96.0, "": None}
_NAMED = {"none": None, "transparent": None, "white": (1.0, 1.0, 1.0), "black": (0.0, 0.0, 0.0)}


@dataclass(frozen=True)
class LayoutReport:
    """What :func:`measure_layout` found on one sheet: the five counts and, for each, up to
    :data:`SHOWN` offenders in words (label ids or texts, the ink they meet)."""

    width: float                 #: sheet width, mm
    height: float                #: sheet height, mm
    format: str                  #: "A4", "A3" or "W×H mm"
    overlapping_labels: int
    labels_crossing_lines: int
    labels_off_sheet: int
    long_heads: int
    beyond_a3: int
    overlaps: tuple[str, ...] = ()
    crossings: tuple[str, ...] = ()
    off_sheet: tuple[str, ...] = ()
    heads: tuple[str, ...] = ()
    oversize: tuple[str, ...] = ()
    labels: int = 0              #: texts measured
    unmatched_heads: tuple[str, ...] = field(default=())

    COUNTS = ("overlapping_labels", "labels_crossing_lines", "labels_off_sheet", "long_heads", "beyond_a3")
    DETAILS = {"overlapping_labels": "overlaps", "labels_crossing_lines": "crossings",
               "labels_off_sheet": "off_sheet", "long_heads": "heads", "beyond_a3": "oversize"}

    @property
    def counts(self) -> dict[str, int]:
        return {name: getattr(self, name) for name in self.COUNTS}

    @property
    def clean(self) -> bool:
        return not any(self.counts.values())

    def offenders(self, name: str) -> tuple[str, ...]:
        """The listed offenders of count ``name``."""
        return getattr(self, self.DETAILS[name])


# --- small parsers ------------------------------------------------------------------------------

def _local(tag) -> str:
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


_XML_SPACE = "{http://www.w3.org/XML/1998/namespace}space"


def _attr(el, name: str):
    return el.attrib.get(_XML_SPACE if name == "xml:space" else name)


_STYLED = frozenset(_INHERITED + ("display", "stroke-dasharray", "transform", "x", "y", "dx", "dy"))


def _style(el) -> dict[str, str]:
    """Presentation attributes of ``el``: its attributes, overridden by its ``style``."""
    out = {}
    for key, v in el.attrib.items():
        name = "xml:space" if key == _XML_SPACE else key
        if name in _STYLED:
            out[name] = v.strip()
    for decl in (el.attrib.get("style") or "").split(";"):
        if ":" in decl:
            k, v = decl.split(":", 1)
            out[k.strip()] = v.strip()
    return out


def _number(text: str | None, default: float = 0.0) -> float:
    if text is None:
        return default
    m = _NUM.search(text)
    return float(m.group()) if m else default


def _numbers(text: str | None) -> list[float]:
    return [float(v) for v in _NUM.findall(text or "")]


def _length_mm(text: str | None) -> float | None:
    """A root width or height in mm (user units are taken as mm)."""
    if not text:
        return None
    m = re.fullmatch(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([a-z%]*)\s*", text)
    if not m:
        return None
    unit = _UNITS.get(m.group(2), None)
    value = float(m.group(1))
    return value if m.group(2) == "" else value * unit if unit else None


def _paint(value: str | None, default):
    """The RGB (0 … 1) of a paint, None for none; an unknown paint counts as black."""
    if value is None:
        return default
    v = value.strip().lower()
    if v in _NAMED:
        return _NAMED[v]
    m = re.fullmatch(r"#([0-9a-f]{3}|[0-9a-f]{6})", v)
    if m:
        h = m.group(1)
        if len(h) == 3:
            h = "".join(c * 2 for c in h)
        return tuple(int(h[i:i + 2], 16) / 255.0 for i in (0, 2, 4))
    m = re.fullmatch(r"rgb\(\s*([^,]+),\s*([^,]+),\s*([^)]+)\)", v)
    if m:
        parts = [p.strip() for p in m.groups()]
        return tuple(float(p[:-1]) / 100.0 if p.endswith("%") else float(p) / 255.0 for p in parts)
    return (0.0, 0.0, 0.0)


def _inked(rgb, *opacities: str | None) -> bool:
    """A paint that marks the paper: not none, not transparent, not paper-pale."""
    if rgb is None or any(o is not None and _number(o, 1.0) <= 0.0 for o in opacities):
        return False
    r, g, b = rgb
    return 0.2126 * r + 0.7152 * g + 0.0722 * b < PALE


def _transform(text: str | None) -> np.ndarray:
    """The 3×3 matrix of an SVG ``transform`` list."""
    m = np.eye(3)
    for name, args in re.findall(r"(matrix|translate|scale|rotate|skewX|skewY)\s*\(([^)]*)\)", text or ""):
        a = _numbers(args)
        if name == "matrix" and len(a) == 6:
            t = np.array([[a[0], a[2], a[4]], [a[1], a[3], a[5]], [0, 0, 1]])
        elif name == "translate":
            t = np.array([[1, 0, a[0]], [0, 1, a[1] if len(a) > 1 else 0.0], [0, 0, 1]])
        elif name == "scale":
            t = np.diag([a[0], a[1] if len(a) > 1 else a[0], 1.0])
        elif name == "rotate":
            c, s = math.cos(math.radians(a[0])), math.sin(math.radians(a[0]))
            t = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
            if len(a) == 3:
                t = np.array([[1, 0, a[1]], [0, 1, a[2]], [0, 0, 1]]) @ t @ np.array([[1, 0, -a[1]], [0, 1, -a[2]],
                                                                                      [0, 0, 1]])
        elif name == "skewX":
            t = np.array([[1, math.tan(math.radians(a[0])), 0], [0, 1, 0], [0, 0, 1]])
        elif name == "skewY":
            t = np.array([[1, 0, 0], [math.tan(math.radians(a[0])), 1, 0], [0, 0, 1]])
        else:
            raise ValueError(f"cannot read transform {name}({args})")
        m = m @ t
    return m


def _path_subpaths(d: str) -> list[tuple[list[tuple[float, float]], bool]]:
    """The subpaths of a path of straight segments (M, L, H, V, Z, either case): points and
    whether each is closed. Curves are refused (ValueError): the sheets draw none."""
    tokens = re.findall(r"[A-Za-z]|[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?", d)
    out: list[tuple[list[tuple[float, float]], bool]] = []
    cur: list[tuple[float, float]] = []
    x = y = 0.0
    start = (0.0, 0.0)
    cmd = None
    i = 0

    def flush(closed: bool = False):
        nonlocal cur
        if cur:
            out.append((cur, closed))
        cur = []

    while i < len(tokens):
        t = tokens[i]
        if t.isalpha():
            cmd = t
            i += 1
            if cmd in "Zz":
                if cur:
                    flush(True)
                x, y = start
                continue
            if cmd not in "MmLlHhVv":
                raise ValueError(f"path command {cmd!r}: only straight segments are measured")
            continue
        if cmd is None:
            raise ValueError(f"path data starts without a command: {d[:40]!r}")
        if cmd in "Mm":
            nx, ny = float(tokens[i]), float(tokens[i + 1])
            i += 2
            if cmd == "m" and (out or cur):
                nx, ny = x + nx, y + ny
            flush()
            x, y = nx, ny
            start = (x, y)
            cur = [(x, y)]
            cmd = "L" if cmd == "M" else "l"
            continue
        if cmd in "Ll":
            nx, ny = float(tokens[i]), float(tokens[i + 1])
            i += 2
            x, y = (x + nx, y + ny) if cmd == "l" else (nx, ny)
        elif cmd in "Hh":
            v = float(tokens[i])
            i += 1
            x = x + v if cmd == "h" else v
        else:
            v = float(tokens[i])
            i += 1
            y = y + v if cmd == "v" else v
        if not cur:
            cur = [start] if start == (x, y) else [(x, y)]
        cur.append((x, y))
    flush()
    return out


# --- what a sheet holds ----------------------------------------------------------------------------

@dataclass
class _Text:
    box: tuple[float, float, float, float]
    name: str
    title: bool               # a text of the title block


@dataclass
class _Ink:
    centre: object            # shapely geometry: centreline (stroke) or area (fill)
    half: float               # half the stroke width (0 for a fill area)
    cap: str
    join: str
    name: str
    layer: str                # "frame", "title", "leader" or "" (the drawing)
    end: tuple[float, float] | None = None      # a leader's end point
    element: int = 0                            # which SVG element (a path's subpaths share it)

    def geometry(self):
        if self.half <= 0:
            return self.centre
        cap = {"butt": "flat", "round": "round", "square": "square"}.get(self.cap, "flat")
        join = {"miter": "mitre", "round": "round", "bevel": "bevel"}.get(self.join, "mitre")
        return shapely.buffer(self.centre, self.half, cap_style=cap, join_style=join, quad_segs=4, mitre_limit=4.0)


class _Reader:
    def __init__(self, root):
        self.texts: list[_Text] = []
        self.ink: list[_Ink] = []
        self.lines: dict[str, tuple[tuple[float, float], tuple[float, float], bool]] = {}   # id -> ends, tagged
        self.heads: list[tuple[str, str, list[tuple[float, float]]]] = []                   # id, data-for, points
        self.frame: tuple[float, float, float, float] | None = None
        self.block = None
        self.root = root
        self.elements = 0
        self.paths: dict[str, list[tuple[float, float]]] = {}    # id -> points of its first subpath

    # context: dict of inherited style + flags
    def walk(self, el, ctx: dict, m: np.ndarray) -> None:
        tag = _local(el.tag)
        if tag in _SKIP:
            return
        st = _style(el)
        if st.get("display") == "none":
            return
        ctx = dict(ctx)
        for k in _INHERITED:
            if k in st:
                ctx[k] = st[k]
        if "transform" in st:
            m = m @ _transform(st["transform"])
        classes = (_attr(el, "class") or "").split()
        ident = _attr(el, "id") or ""
        if "title-block" in classes or ident.endswith("-title-text"):
            ctx["title"] = True
        if _attr(el, "data-plan") is not None:
            ctx["plan"] = True
        if ident:
            ctx["where"] = ident
        if tag == "text":
            self.text(el, ctx, m)
            return
        if tag in ("g", "svg", "a", "switch"):
            for child in el:
                self.walk(child, ctx, m)
            return
        if ctx.get("visibility") in ("hidden", "collapse"):
            return
        self.shape(el, tag, st, ctx, m, classes, ident)

    # -- shapes ----------------------------------------------------------------------------------
    def shape(self, el, tag, st, ctx, m, classes, ident) -> None:
        self.elements += 1
        element = self.elements
        (ma, mc, me), (mb, md, mf) = m[0].tolist(), m[1].tolist()

        def pt(x, y):
            return ma * x + mc * y + me, mb * x + md * y + mf

        num = lambda name: _number(_attr(el, name))  # noqa: E731
        scale = math.sqrt(abs(ma * md - mb * mc)) or 1.0
        closed_parts: list[list[tuple[float, float]]] = []
        open_parts: list[list[tuple[float, float]]] = []
        area = None
        if tag == "line":
            a, b = pt(num("x1"), num("y1")), pt(num("x2"), num("y2"))
            open_parts.append([a, b])
            if ident:
                self.lines[ident] = (a, b, _attr(el, "data-quantity") is not None and bool(ctx.get("plan")))
        elif tag == "path":
            for pts, closed in _path_subpaths(_attr(el, "d") or ""):
                (closed_parts if closed else open_parts).append([pt(*p) for p in pts])
            if ident and (open_parts or closed_parts):
                self.paths[ident] = (open_parts or closed_parts)[0]
            if "head" in classes:
                pts = [q for part in closed_parts + open_parts for q in part]
                self.heads.append((ident or "?", _attr(el, "data-for") or "", pts))
        elif tag in ("polygon", "polyline"):
            v = _numbers(_attr(el, "points"))
            pts = [pt(v[i], v[i + 1]) for i in range(0, len(v) - 1, 2)]
            (closed_parts if tag == "polygon" else open_parts).append(pts)
        elif tag == "rect":
            x, y, w, h = num("x"), num("y"), num("width"), num("height")
            if w <= 0 or h <= 0:
                return
            pts = [pt(x, y), pt(x + w, y), pt(x + w, y + h), pt(x, y + h)]
            closed_parts.append(pts)
            if ("frame" in classes and self.frame is None) or (ctx.get("title") and self.block is None):
                stroked = _inked(_paint(ctx.get("stroke"), None))
                half = 0.5 * scale * _number(ctx.get("stroke-width"), 1.0) if stroked else 0.0
                xs, ys = [p[0] for p in pts], [p[1] for p in pts]
                if "frame" in classes:      # its inner area
                    self.frame = (min(xs) + half, min(ys) + half, max(xs) - half, max(ys) - half)
                else:                       # the title block with its outline
                    self.block = (min(xs) - half, min(ys) - half, max(xs) + half, max(ys) + half)
            if ident.endswith("-paper"):
                return
        elif tag in ("circle", "ellipse"):
            cx, cy = num("cx"), num("cy")
            rx = num("r") if tag == "circle" else num("rx")
            ry = num("r") if tag == "circle" else num("ry")
            if rx <= 0 or ry <= 0:
                return
            closed_parts.append([pt(cx + rx * cos, cy + ry * sin) for cos, sin in _CIRCLE])
        else:
            return
        name = f"{tag}{'.' + '.'.join(classes) if classes else ''} {ident or 'in ' + ctx.get('where', '?')}"
        layer = "frame" if "frame" in classes else "title" if ctx.get("title") else \
            "leader" if "leader" in classes else ""
        fill = _inked(_paint(ctx.get("fill"), (0.0, 0.0, 0.0)), ctx.get("fill-opacity"), ctx.get("opacity"))
        stroke = _inked(_paint(ctx.get("stroke"), None), ctx.get("stroke-opacity"), ctx.get("opacity"))
        width = _number(ctx.get("stroke-width"), 1.0) * scale
        if fill and tag not in ("line",):
            polys = [shapely.Polygon(p) for p in closed_parts + open_parts if len(p) >= 3]
            polys = [p if p.is_valid else p.buffer(0) for p in polys]
            if polys:
                area = shapely.union_all(polys)
                if not area.is_empty:
                    self.ink.append(_Ink(area, 0.0, "butt", "miter", name, layer, element=element))
        if stroke and width > 0:
            cap, join = ctx.get("stroke-linecap", "butt"), ctx.get("stroke-linejoin", "miter")
            lines = [shapely.LinearRing(p) for p in closed_parts if len(p) >= 3] + \
                [shapely.LineString(p) for p in open_parts if len(p) >= 2]
            for p in open_parts + closed_parts:
                if len(p) == 1 or (len(set(p)) == 1 and cap != "butt"):      # a dot: a round or square cap
                    lines.append(shapely.Point(p[0]))
            for g in lines:
                if g.length == 0 and not isinstance(g, shapely.Point):
                    g = shapely.Point(g.coords[0]) if cap != "butt" else None
                if g is None or (isinstance(g, shapely.Point) and cap == "butt"):
                    continue
                end = tuple(open_parts[0][-1]) if layer == "leader" and open_parts else None
                self.ink.append(_Ink(g, 0.5 * width, "round" if isinstance(g, shapely.Point) else cap, join, name,
                                     layer, end, element))

    # -- texts -----------------------------------------------------------------------------------
    def text(self, el, ctx, m) -> None:
        if ctx.get("visibility") in ("hidden", "collapse"):
            return
        if abs(m[0, 1]) > 1e-12 or abs(m[1, 0]) > 1e-12 or m[0, 0] <= 0 or m[1, 1] <= 0:
            raise ValueError("a rotated, skewed or mirrored text cannot be measured")
        glyphs: list[list] = []   # [char, size, italic, abs_x, abs_y, dx, dy, anchor]; char "" only positions
        self._glyphs(el, ctx, glyphs)
        kept = _collapse(glyphs, preserve=ctx.get("xml:space") == "preserve")
        if not any(g[0] for g in kept):
            return
        x = y = 0.0
        chunks: list[list] = []
        for g in kept:
            c, size, italic, ax, ay, dx, dy, anchor = g
            if ax is not None or not chunks:
                x = ax if ax is not None else x
                chunks.append([anchor, x, x, []])
            if ay is not None:
                y = ay
            x += dx
            y += dy
            if not c:
                continue
            adv = _em(c, italic) * size
            chunks[-1][3].append((x, x + adv, y - ASCENT * size, y + DESCENT * size))
            x += adv
            chunks[-1][2] = x
        boxes = []
        for anchor, start, end, items in chunks:
            if not items:
                continue
            shift = {"middle": -0.5 * (end - start), "end": -(end - start)}.get(anchor, 0.0)
            boxes.append((min(i[0] for i in items) + shift, min(i[2] for i in items),
                          max(i[1] for i in items) + shift, max(i[3] for i in items)))
        x0, y0 = min(b[0] for b in boxes), min(b[1] for b in boxes)
        x1, y1 = max(b[2] for b in boxes), max(b[3] for b in boxes)
        (X0, Y0, _), (X1, Y1, _) = m @ (x0, y0, 1.0), m @ (x1, y1, 1.0)
        words = "".join(g[0] for g in kept)
        ident = _attr(el, "id")
        name = f"{words!r}" + (f" ({ident})" if ident else f" in {ctx.get('where', '?')}")
        self.texts.append(_Text((float(X0), float(Y0), float(X1), float(Y1)), name, bool(ctx.get("title"))))

    def _glyphs(self, el, ctx, out: list) -> None:
        """The characters of a text or tspan, each with its size, style, anchor and position
        attributes (``x``, ``y``, ``dx``, ``dy``: one value per character, in order)."""
        st = _style(el)
        ctx = dict(ctx)
        for k in ("font-size", "font-style", "text-anchor"):
            if k in st:
                ctx[k] = st[k]
        size = _number(ctx.get("font-size"), 16.0)
        italic = ctx.get("font-style", "normal") in ("italic", "oblique")
        anchor = ctx.get("text-anchor", "start")
        pos = [_numbers(st.get(k)) for k in ("x", "y", "dx", "dy")]
        count = 0

        def glyph(c: str) -> list:
            nonlocal count
            k = count
            count += 1
            (xs, ys, dxs, dys) = pos
            return [c, size, italic, xs[k] if k < len(xs) else None, ys[k] if k < len(ys) else None,
                    dxs[k] if k < len(dxs) else 0.0, dys[k] if k < len(dys) else 0.0, anchor]

        def first_of_child():
            # positions of this element given before its first character, which a child writes
            if count == 0 and any(pos):
                out.append(glyph(""))

        out.extend(glyph(c) for c in el.text or "")
        for child in el:
            if _local(child.tag) in ("tspan", "a") and _style(child).get("display") != "none":
                first_of_child()
                self._glyphs(child, ctx, out)
            out.extend(glyph(c) for c in child.tail or "")
        first_of_child()


def _collapse(glyphs: list[list], preserve: bool) -> list[list]:
    """SVG 1.1 white space: line breaks dropped, tabs as spaces, runs of spaces as one, no
    leading or trailing space (``xml:space="preserve"``: every white character a space). A
    dropped character keeps its positions as an empty glyph."""
    out: list[list] = []

    def drop(g):
        if g[3] is not None or g[4] is not None or g[5] or g[6]:
            out.append([""] + g[1:])

    for g in glyphs:
        c = g[0]
        if preserve:
            out.append([" " if c in "\n\r\t" else c] + g[1:])
            continue
        if c in "\n\r":
            drop(g)
            continue
        if c == "\t":
            c = " "
        last = next((h[0] for h in reversed(out) if h[0]), None)
        if c == " " and (last is None or last == " "):
            drop(g)
            continue
        out.append([c] + g[1:])
    if not preserve:
        while out and out[-1][0] in (" ", ""):    # trailing positions move nothing drawn
            out.pop()
    return out


def _sheet_size(root) -> tuple[float, float, np.ndarray]:
    """Width and height in mm and the matrix from user units to mm."""
    vb = _numbers(_attr(root, "viewBox"))
    w, h = _length_mm(_attr(root, "width")), _length_mm(_attr(root, "height"))
    if len(vb) == 4 and vb[2] > 0 and vb[3] > 0:
        w = vb[2] if w is None else w
        h = vb[3] if h is None else h
        sx, sy = w / vb[2], h / vb[3]
        return w, h, np.array([[sx, 0, -vb[0] * sx], [0, sy, -vb[1] * sy], [0, 0, 1.0]])
    if w is None or h is None:
        raise ValueError("the sheet has neither a size in mm nor a viewBox")
    return w, h, np.eye(3)


def _format(w: float, h: float) -> str:
    for name, (a, b) in FORMATS.items():
        if (abs(w - a) <= SIZE_TOLERANCE_MM and abs(h - b) <= SIZE_TOLERANCE_MM) or \
                (abs(w - b) <= SIZE_TOLERANCE_MM and abs(h - a) <= SIZE_TOLERANCE_MM):
            return name
    return f"{w:g}×{h:g} mm"


def _fmt_box(b) -> str:
    return f"[{b[0]:.2f}, {b[1]:.2f} – {b[2]:.2f}, {b[3]:.2f}]"


def _touches(box, point) -> bool:
    """Whether ``point`` lies in ``box`` or within LEADER_TOUCH_MM of it."""
    dx = max(box[0] - point[0], 0.0, point[0] - box[2])
    dy = max(box[1] - point[1], 0.0, point[1] - box[3])
    return math.hypot(dx, dy) <= LEADER_TOUCH_MM


def measure_layout(svg_text: str | bytes) -> LayoutReport:
    """The layout faults of one SVG sheet (see the module docstring)."""
    root = ET.fromstring(svg_text)
    if _local(root.tag) != "svg":
        raise ValueError("not an SVG document")
    W, H, m = _sheet_size(root)
    reader = _Reader(root)
    reader.walk(root, {}, m)
    texts, ink = reader.texts, reader.ink

    # -- beyond A3 --------------------------------------------------------------------------------
    small, large = sorted((W, H))
    oversize = [] if small <= A3_MM[0] + SIZE_TOLERANCE_MM and large <= A3_MM[1] + SIZE_TOLERANCE_MM else \
        [f"sheet {W:g} mm × {H:g} mm is larger than A3 ({A3_MM[0]:g} × {A3_MM[1]:g})"]

    boxes = np.array([t.box for t in texts], dtype=float).reshape(-1, 4)
    polys = shapely.box(boxes[:, 0], boxes[:, 1], boxes[:, 2], boxes[:, 3])

    # -- overlapping labels -----------------------------------------------------------------------
    overlaps: list[str] = []
    n_overlaps = 0
    if len(texts) > 1:
        x0, y0, x1, y1 = boxes.T
        hit = (x0[:, None] < x1[None, :]) & (x0[None, :] < x1[:, None]) & \
              (y0[:, None] < y1[None, :]) & (y0[None, :] < y1[:, None])
        i, j = np.nonzero(np.triu(hit, 1))
        n_overlaps = len(i)
        for a, b in list(zip(i, j))[:SHOWN]:
            overlaps.append(f"{texts[a].name} {_fmt_box(texts[a].box)} overlaps "
                            f"{texts[b].name} {_fmt_box(texts[b].box)}")

    # -- labels crossing lines --------------------------------------------------------------------
    crossings: list[str] = []
    n_cross = 0
    if texts and ink:
        tree = shapely.STRtree([k.centre for k in ink])
        reach = max(k.half for k in ink)
        grown = shapely.box(boxes[:, 0] - reach, boxes[:, 1] - reach, boxes[:, 2] + reach, boxes[:, 3] + reach)
        t_idx, k_idx = tree.query(grown, predicate="intersects")
        buffered: dict[int, object] = {}
        seen: set[tuple[int, int]] = set()     # (text, element): one crossing per pair
        for a, b in zip(t_idx.tolist(), k_idx.tolist()):
            t, k = texts[a], ink[b]
            if t.title and k.layer in ("title", "frame"):
                continue
            if k.layer == "leader" and k.end is not None and _touches(t.box, k.end):
                continue
            if (a, k.element) in seen:
                continue
            if b not in buffered:
                buffered[b] = k.geometry()
            g = buffered[b]
            if shapely.intersects(polys[a], g) and not shapely.touches(polys[a], g):
                seen.add((a, k.element))
                n_cross += 1
                if len(crossings) < SHOWN:
                    whose = [u.name for u in texts if k.end is not None and _touches(u.box, k.end)]
                    to = f" (the leader of {', '.join(whose)})" if whose else ""
                    crossings.append(f"{t.name} {_fmt_box(t.box)} crosses {k.name}{to}")

    # -- labels off the sheet ---------------------------------------------------------------------
    off: list[str] = []
    n_off = 0
    inner = shapely.box(*(reader.frame or (0.0, 0.0, W, H)))
    area = inner.difference(shapely.box(*reader.block)) if reader.block else inner
    for t, p in zip(texts, polys):
        where = inner if t.title else area
        if not where.covers(p):
            n_off += 1
            if len(off) < SHOWN:
                what = "the frame" if t.title or not inner.covers(p) else "the drawing area (it meets the title block)"
                off.append(f"{t.name} {_fmt_box(t.box)} is not inside {what}")

    # -- arrowheads -------------------------------------------------------------------------------
    heads: list[str] = []
    unmatched: list[str] = []
    n_heads = 0
    with_head: set[str] = set()
    for ident, target, pts in reader.heads:
        corners = list(dict.fromkeys(pts))
        if len(corners) != 3:
            unmatched.append(f"head {ident}: not a triangle")
            continue
        vec = reader.lines.get(target)
        if vec is not None:
            a, b, _ = vec
            tip = min(corners, key=lambda p: math.dist(p, b))
            vec_len = math.dist(a, b)
        elif target in reader.paths:
            # a drawn arc (the drive's ω, ε): the path, then on to the head's tip
            line = reader.paths[target]
            # its tip: the corner opposite the shortest side (the base)
            tip = min(corners, key=lambda p: math.dist(*[q for q in corners if q is not p]))
            vec_len = sum(math.dist(p, q) for p, q in zip(line, line[1:])) + math.dist(line[-1], tip)
        else:
            unmatched.append(f"head {ident} (data-for={target!r}): no vector line")
            continue
        with_head.add(target)
        rest = [p for p in corners if p is not tip]
        base = ((rest[0][0] + rest[1][0]) / 2, (rest[0][1] + rest[1][1]) / 2)
        head_len = math.dist(tip, base)
        if head_len > vec_len + ROUNDING_MM:
            n_heads += 1
            if len(heads) < SHOWN:
                heads.append(f"head {ident} is {head_len:.3f} mm long, its vector {target} {vec_len:.3f} mm")
    for ident, (a, b, tagged) in reader.lines.items():
        L = math.dist(a, b)
        if tagged and ident in with_head and L < NO_HEAD_MM - ROUNDING_MM:
            n_heads += 1
            if len(heads) < SHOWN:
                heads.append(f"vector {ident} is {L:.3f} mm < {NO_HEAD_MM:g} mm and has a head")

    return LayoutReport(
        width=W, height=H, format=_format(W, H),
        overlapping_labels=n_overlaps, labels_crossing_lines=n_cross, labels_off_sheet=n_off,
        long_heads=n_heads, beyond_a3=len(oversize),
        overlaps=tuple(overlaps), crossings=tuple(crossings), off_sheet=tuple(off), heads=tuple(heads),
        oversize=tuple(oversize), labels=len(texts), unmatched_heads=tuple(unmatched))

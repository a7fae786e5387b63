"""What an SVG sheet holds, as a reader of the paper sees it: every text's box (sized with the
metrics of the sheet's font, :mod:`plans.drawing.text`), every inked shape (a stroke as its
centreline and half width, a dark fill as its area), the vectors' lines, the arrowheads, the
frame and the title block; and the sheet's size in mm.

Knows :mod:`.parsing` and the font metrics of :mod:`plans.drawing.text`; must not import
:mod:`.measure` or anything that draws a sheet.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import linalg as la
import shapely

from ..drawing.text import ASCENT, DESCENT, _em
from .parsing import (_INHERITED, _attr, _inked, _length_mm, _local, _number, _numbers, _paint, _path_subpaths,
                      _style, _transform)

#: A circle as a 48-gon (unit radius).
_CIRCLE = [(math.cos(2 * math.pi * k / 48), math.sin(2 * math.pi * k / 48)) for k in range(48)]
_SKIP = {"defs", "clipPath", "mask", "symbol", "marker", "pattern", "metadata", "title", "desc", "style", "script"}


@dataclass
class _Text:
    box: tuple[float, float, float, float]
    name: str
    title: bool               # a text of the title block
    words: str = ""           # what it reads
    force: str = ""           # the id of the force plan group (data-plan="force") it is in, if any


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
        # force plan group id -> vertex name -> paper points where a tagged vector names it
        # (data-from at its tail, data-to at its head)
        self.vertices: dict[str, dict[str, list[tuple[float, float]]]] = {}
        self.groups = 0

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
            m = la.matmul(m, _transform(st["transform"]))
        classes = (_attr(el, "class") or "").split()
        ident = _attr(el, "id") or ""
        if "title-block" in classes or ident.endswith("-title-text"):
            ctx["title"] = True
        if _attr(el, "data-plan") is not None:
            ctx["plan"] = True
            if _attr(el, "data-plan") == "force":
                self.groups += 1
                ctx["force"] = ident or f"force plan {self.groups}"
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
            if ctx.get("force") and _attr(el, "data-quantity") is not None:
                named = self.vertices.setdefault(ctx["force"], {})
                for key, p in (("data-from", a), ("data-to", b)):
                    if _attr(el, key):
                        named.setdefault(_attr(el, key), []).append(p)
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
        (X0, Y0, _), (X1, Y1, _) = la.matmul(m, (x0, y0, 1.0)), la.matmul(m, (x1, y1, 1.0))
        words = "".join(g[0] for g in kept)
        ident = _attr(el, "id")
        name = f"{words!r}" + (f" ({ident})" if ident else f" in {ctx.get('where', '?')}")
        self.texts.append(_Text((float(X0), float(Y0), float(X1), float(Y1)), name, bool(ctx.get("title")), words,
                                ctx.get("force", "")))

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

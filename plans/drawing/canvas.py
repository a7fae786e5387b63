"""A sheet being drawn: content millimetres (y up) mapped onto the paper, every inked line
and arrowhead remembered, and labels placed last, clear of all of them.

The drawing modules add elements through :class:`Canvas`; each line, outline, dot and
arrowhead is also kept as a shapely geometry in paper millimetres (SVG frame, y down). Labels
are only requested while drawing (:meth:`Canvas.label`); :meth:`Canvas.place_labels` then
puts each one, in request order, at the first free spot around its anchor: at growing gaps
(:data:`GAPS`, mm), in sixteen directions starting from the preferred one, a spot being free
when the label's box, grown by :data:`CLEARANCE`, touches no inked geometry, no label placed
before it, and stays inside the drawing area. Far spots (:data:`LEADER_GAPS`) get a thin
leader from the anchor. A label may name a line rather than a point (``also``: further anchors
along it, tried in turn at each stage of gaps). A label that finds no free spot at all is put at its least crowded
candidate and counted in :attr:`Canvas.crowded` (the layout test requires none).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Sequence

import numpy as np
import shapely
import svgwrite

from .style import Style
from .text import FONT, SUB_SHIFT, SUB_SIZE, Box, Run, box, runs

__all__ = ["Canvas", "fmt", "GAPS", "LEADER_GAPS", "CLEARANCE"]

#: Gaps tried between an anchor and its label's box, mm (the last ones with a leader).
GAPS = (0.7, 1.4, 2.3, 3.4, 4.8, 6.5)
LEADER_GAPS = (9.0, 12.0, 16.0, 22.0, 30.0, 40.0)
#: Free space kept between a label's box and any inked geometry or other label, mm.
CLEARANCE = 0.25
#: Directions tried around an anchor.
DIRECTIONS = 16
#: The gaps tried in turn (nearest first; the last stage with leaders).
_STAGES = ((GAPS[:2], False), (GAPS[2:], False), (LEADER_GAPS, True))


def fmt(x: float, decimals: int) -> str:
    """A coordinate rounded to ``decimals`` with trailing zeros stripped (never "-0")."""
    s = f"{round(x, decimals):.{decimals}f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


@dataclass(frozen=True)
class _Request:
    parent: object
    anchor: tuple[float, float]          # paper mm
    parts: tuple[Run, ...]
    size: float
    italic: bool
    prefer: float                        # preferred direction, radians, paper frame (y down)
    ident: str
    fill: str | None
    near: float                          # smallest gap, mm (clear of a symbol drawn at the anchor)
    others: tuple[tuple[float, float], ...] = ()    # further anchors tried in turn, paper mm


class Canvas:
    """One SVG sheet: ``offset`` maps content (x, y up) to paper (x + dx, dy − y)."""

    def __init__(self, dwg: svgwrite.Drawing, style: Style, offset: tuple[float, float], area: Box):
        self.dwg, self.style = dwg, style
        self.dx, self.dy = offset
        self.area = area
        self.ink: list = []
        self._requests: list[_Request] = []
        self.crowded = 0
        self.placed: list[Box] = []
        self._leaders: list = []

    # -- coordinates -------------------------------------------------------------------
    def paper(self, p: Sequence[float]) -> tuple[float, float]:
        return (float(p[0]) + self.dx, self.dy - float(p[1]))

    def f(self, x: float) -> str:
        return fmt(x, self.style.decimals)

    def xy(self, p: Sequence[float]) -> tuple[str, str]:
        q = self.paper(p)
        return self.f(q[0]), self.f(q[1])

    def _rounded(self, p: Sequence[float]) -> tuple[float, float]:
        q = self.paper(p)
        d = self.style.decimals
        return round(q[0], d), round(q[1], d)

    # -- inked elements (content coordinates) --------------------------------------------
    def line(self, parent, a, b, *, ink: bool = True, width: float | None = None, **attrs):
        el = self.dwg.line(start=self.xy(a), end=self.xy(b), **attrs)
        parent.add(el)
        if ink:
            self._ink_line([self._rounded(a), self._rounded(b)], width)
        return el

    def polyline(self, parent, pts, *, closed: bool = False, width: float | None = None, **attrs):
        d = "M" + " L".join(",".join(self.xy(p)) for p in pts) + (" Z" if closed else "")
        el = self.dwg.path(d=d, **attrs)
        parent.add(el)
        paper = [self._rounded(p) for p in pts]
        self._ink_line(paper + paper[:1] if closed else paper, width)
        return el

    def strokes(self, parent, segments, *, width: float | None = None, **attrs):
        """Many separate strokes (hatching) as one path."""
        d = " ".join(f"M{','.join(self.xy(a))} L{','.join(self.xy(b))}" for a, b in segments)
        el = self.dwg.path(d=d, **attrs)
        parent.add(el)
        for a, b in segments:
            self._ink_line([self._rounded(a), self._rounded(b)], width)
        return el

    def polygon(self, parent, pts, *, filled: bool = False, width: float | None = None, **attrs):
        el = self.dwg.polygon([self.xy(p) for p in pts], **attrs)
        parent.add(el)
        paper = [self._rounded(p) for p in pts]
        if filled:
            self.ink.append(shapely.Polygon(paper))
        else:
            self._ink_line(paper + paper[:1], width)
        return el

    def keep_out(self, pts) -> None:
        """Keep labels out of the inside of content polygon ``pts`` (nothing is drawn)."""
        self.ink.append(shapely.Polygon([self._rounded(p) for p in pts]))

    def circle(self, parent, c, r: float, *, filled: bool = False, **attrs):
        el = self.dwg.circle(center=self.xy(c), r=fmt(r, 3), **attrs)
        parent.add(el)
        q = self._rounded(c)
        disc = shapely.Point(q).buffer(r, quad_segs=4)
        self.ink.append(disc if filled else disc.exterior)
        return el

    def head(self, parent, tail, tip, length: float, **attrs):
        """A filled arrowhead of ``length`` (mm) at ``tip``, pointing from ``tail``."""
        (x0, y0), (x1, y1) = self.paper(tail), self.paper(tip)
        L = math.hypot(x1 - x0, y1 - y0)
        ux, uy = (x1 - x0) / L, (y1 - y0) / L
        aw = self.style.arrow_width * length / self.style.arrow_length
        bx, by = x1 - length * ux, y1 - length * uy
        pts = [(x1, y1), (bx - aw * uy, by + aw * ux), (bx + aw * uy, by - aw * ux)]
        el = self.dwg.path(d="M" + " L".join(f"{self.f(a)},{self.f(b)}" for a, b in pts) + " Z", **attrs)
        parent.add(el)
        d = self.style.decimals
        self.ink.append(shapely.Polygon([(round(a, d), round(b, d)) for a, b in pts]))
        return el

    def _ink_line(self, pts, width: float | None) -> None:
        half = 0.5 * (width if width is not None else self.style.thin)
        geom = shapely.LineString(pts)
        self.ink.append(geom.buffer(half, cap_style="flat", quad_segs=1) if half > 0.2 else geom)

    # -- text ------------------------------------------------------------------------------
    def text(self, parent, at_paper: tuple[float, float], label: str, *, size: float, italic: bool = False,
             anchor: str = "start", ident: str | None = None, digits: bool = False, fill: str | None = None):
        """Text at a fixed paper point (baseline); returns its box."""
        parts = runs(label, digits=digits)
        parent.add(self._text_el(parts, at_paper, size, italic, anchor, ident, fill))
        b = box(parts, size, italic, at_paper[0], at_paper[1], anchor)
        self.placed.append(b)
        return b

    def _text_el(self, parts, at, size, italic, anchor, ident, fill):
        t = self.dwg.text("", insert=(self.f(at[0]), self.f(at[1])), font_size=fmt(size, 2), text_anchor=anchor,
                          font_family=FONT, font_style="italic" if italic else "normal", stroke="none",
                          fill=fill or self.style.colour)
        t.attribs["class"] = "label"
        if ident:
            t.attribs["id"] = ident
        shift = 0.0
        for r in parts:
            want = SUB_SHIFT * size if r.sub else 0.0
            kw = {"font_size": fmt(size * SUB_SIZE, 2)} if r.sub else {}
            if want != shift:
                kw["dy"] = [fmt(want - shift, 2)]
            t.add(self.dwg.tspan(r.text, **kw))
            shift = want
        return t

    def label(self, parent, at, label: str, *, size: float, italic: bool = True, prefer=(1.0, 1.0),
              ident: str = "", digits: bool = True, fill: str | None = None, near: float = 0.0,
              also: Sequence[Sequence[float]] = ()) -> None:
        """Ask for a label of content point ``at``, preferably in content direction ``prefer``;
        it is placed by :meth:`place_labels`. ``also``: further content points it may label
        instead (a line's label anywhere along it), each tried in turn at every stage of gaps."""
        ang = math.atan2(-float(prefer[1]), float(prefer[0])) if any(prefer) else -math.pi / 4
        self._requests.append(_Request(parent, self.paper(at), runs(label, digits=digits), size, italic, ang,
                                       ident, fill, near, tuple(self.paper(a) for a in also)))

    def place_labels(self, leader_parent) -> None:
        """Place every requested label (see the module docstring)."""
        tree = shapely.STRtree(self.ink) if self.ink else None
        angles = np.arange(DIRECTIONS) * (2 * math.pi / DIRECTIONS)
        for req in self._requests:
            b0 = box(req.parts, req.size, req.italic, 0.0, 0.0)
            w, h_up, h_down = b0.x1, -b0.y0, b0.y1
            order = np.argsort(np.abs((angles - req.prefer + math.pi) % (2 * math.pi) - math.pi), kind="stable")
            dirs = angles[order]
            best = None
            anchor, chosen = req.anchor, None
            for gaps, leader in _STAGES:
                for at in (req.anchor,) + req.others:
                    x0, y0, hits, free = self._candidates(req, dirs, gaps, w, h_up + h_down, tree, leader, at)
                    ok = np.flatnonzero(free & (hits == 0))
                    if len(ok):
                        k = int(ok[0])
                        chosen, anchor = (x0[k], y0[k]), at
                        break
                    score = hits + (~free) * 1000
                    k = int(np.argmin(score))
                    if best is None or score[k] < best[0]:
                        best = (score[k], (x0[k], y0[k]), leader, at)
                if chosen is not None:
                    break
            else:
                self.crowded += 1
                chosen, leader, anchor = best[1], best[2], best[3]
            bx = Box(chosen[0], chosen[1], chosen[0] + w, chosen[1] + h_up + h_down)
            self.placed.append(bx)
            req.parent.add(self._text_el(req.parts, (bx.x0, bx.y0 + h_up), req.size, req.italic, "start",
                                         req.ident or None, req.fill))
            if leader:
                self._leader(leader_parent, anchor, bx)
        self._requests.clear()

    def _candidates(self, req: _Request, dirs, gaps, w: float, h: float, tree, leader: bool, anchor=None):
        """Candidate boxes (left, top) at ``gaps`` × ``dirs`` around ``anchor`` (the request's
        by default), how many things each touches, and whether each lies in the drawing area."""
        if anchor is not None:
            req = replace(req, anchor=anchor)
        g = np.array([max(gap, req.near) for gap in gaps])[:, None]
        ux, uy = np.cos(dirs)[None, :], np.sin(dirs)[None, :]
        hw, hh = w / 2, h / 2
        reach = np.abs(ux) * hw + np.abs(uy) * hh   # the box's edge nearest the anchor is ``gap`` away
        x0 = (req.anchor[0] + ux * (g + reach) - hw).ravel()
        y0 = (req.anchor[1] + uy * (g + reach) - hh).ravel()
        x1, y1 = x0 + w, y0 + h
        a = self.area
        free = (x0 >= a.x0) & (x1 <= a.x1) & (y0 >= a.y0) & (y1 <= a.y1)
        c = CLEARANCE
        hits = np.zeros(len(x0), dtype=int)
        if self.placed:
            p = np.array([(q.x0, q.y0, q.x1, q.y1) for q in self.placed])
            hits += ((x0[:, None] < p[None, :, 2] + c) & (p[None, :, 0] < x1[:, None] + c)
                     & (y0[:, None] < p[None, :, 3] + c) & (p[None, :, 1] < y1[:, None] + c)).sum(axis=1)
        boxes = shapely.box(x0 - c, y0 - c, x1 + c, y1 + c)
        if tree is not None:
            np.add.at(hits, tree.query(boxes, predicate="intersects")[0], 1)
        for seg in self._leaders:
            hits += shapely.intersects(boxes, seg)
        if leader and self.placed:   # a leader may cross lines, never another label
            ends = np.stack([np.clip(req.anchor[0], x0, x1), np.clip(req.anchor[1], y0, y1)], axis=1)
            starts = np.broadcast_to(np.array(req.anchor, dtype=float), ends.shape)
            legs = shapely.linestrings(np.stack([starts, ends], axis=1))
            others = shapely.union_all([shapely.box(q.x0 - c, q.y0 - c, q.x1 + c, q.y1 + c) for q in self.placed])
            hits += shapely.intersects(legs, others)
        return x0, y0, hits, free

    def _leader(self, parent, anchor, bx: Box) -> None:
        """A thin line from the anchor to the nearest point of the label's box."""
        nx = min(max(anchor[0], bx.x0), bx.x1)
        ny = min(max(anchor[1], bx.y0), bx.y1)
        el = self.dwg.line(start=(self.f(anchor[0]), self.f(anchor[1])), end=(self.f(nx), self.f(ny)),
                           stroke=self.style.construction_colour, stroke_width=fmt(self.style.thin * 0.6, 3))
        el.attribs["class"] = "leader"
        parent.add(el)
        self._leaders.append(shapely.LineString([anchor, (nx, ny)]))

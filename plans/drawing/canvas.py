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
candidate (the least ink, label and leader under it: :meth:`Canvas._least_crowded`) and
counted in :attr:`Canvas.crowded` (the layout test requires none). Every search reads only
what lies near its anchor (:class:`~plans.drawing.ink_index.InkIndex`,
:class:`~plans.spatial.BoxGrid`, :class:`~plans.drawing.occupancy.Occupancy`), so placing n
labels takes time linear in n.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np
import shapely
import svgwrite

from ..spatial import BoxGrid, segments_meet_boxes
from .ink_index import InkIndex
from .occupancy import Occupancy
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
#: Placed labels and leaders are bucketed in square cells this wide, mm (see :mod:`plans.spatial`).
_CELL_MM = 10.0
#: The largest gap tried, mm.
_FARTHEST = max(GAPS + LEADER_GAPS)
#: A candidate outside the drawing area scores this much worse than any inside it.
_OUTSIDE = 10 ** 9


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
        self._straight: dict[int, tuple[tuple[tuple[float, float], tuple[float, float]], float]] = {}
        self._requests: list[_Request] = []
        self.crowded = 0
        self.placed: list[Box] = []
        self._placed_grid = BoxGrid(_CELL_MM)
        # (ax, ay, bx, by) of each leader drawn, mm: as many rows in use as the leaders' grid holds
        self._leader_ends = np.empty((0, 4))
        self._leader_grid = BoxGrid(_CELL_MM)
        self._occupancy = Occupancy((area.x0, area.y0, area.x1, area.y1))

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
        if len(pts) == 2 and pts[0] != pts[1]:
            self._straight[len(self.ink)] = ((pts[0], pts[1]), half if half > 0.2 else 0.0)
        self.ink.append(geom.buffer(half, cap_style="flat", quad_segs=1) if half > 0.2 else geom)

    def _place(self, b: Box) -> None:
        """Remember ``b`` as taken by a label."""
        self.placed.append(b)
        self._placed_grid.add((b.x0, b.y0, b.x1, b.y1))
        self._occupancy.add_label((b.x0, b.y0, b.x1, b.y1))

    # -- text ------------------------------------------------------------------------------
    def text(self, parent, at_paper: tuple[float, float], label: str, *, size: float, italic: bool = False,
             anchor: str = "start", ident: str | None = None, digits: bool = False, fill: str | None = None):
        """Text at a fixed paper point (baseline); returns its box."""
        parts = runs(label, digits=digits)
        parent.add(self._text_el(parts, at_paper, size, italic, anchor, ident, fill))
        b = box(parts, size, italic, at_paper[0], at_paper[1], anchor)
        self._place(b)
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
        ink = InkIndex.of(self.ink, self._straight) if self.ink else None
        angles = np.arange(DIRECTIONS) * (2 * math.pi / DIRECTIONS)
        for req in self._requests:
            b0 = box(req.parts, req.size, req.italic, 0.0, 0.0)
            w, h_up, h_down = b0.x1, -b0.y0, b0.y1
            order = np.argsort(np.abs((angles - req.prefer + math.pi) % (2 * math.pi) - math.pi), kind="stable")
            dirs = angles[order]
            anchor, chosen, failed = req.anchor, None, []
            tries = [(gaps, leader, at) for gaps, leader in _STAGES for at in (req.anchor,) + req.others]
            # the nearest gaps round the anchor first (where most labels go), then all the others at once
            for batch in (tries[:1], tries[1:]):
                x0, y0, ok, free, ends = self._candidates(req, dirs, batch, w, h_up + h_down, ink)
                for (gaps, leader, at), lo, hi in zip(batch, ends[:-1], ends[1:]):
                    first = np.flatnonzero(ok[lo:hi])
                    if len(first):
                        k = lo + int(first[0])
                        chosen, anchor = (x0[k], y0[k]), at
                        break
                    failed.append((leader, at, x0[lo:hi], y0[lo:hi], free[lo:hi]))
                if chosen is not None:
                    break
            else:
                self.crowded += 1
                chosen, leader, anchor = self._least_crowded(failed, w, h_up + h_down, ink)
            bx = Box(chosen[0], chosen[1], chosen[0] + w, chosen[1] + h_up + h_down)
            self._place(bx)
            req.parent.add(self._text_el(req.parts, (bx.x0, bx.y0 + h_up), req.size, req.italic, "start",
                                         req.ident or None, req.fill))
            if leader:
                self._leader(leader_parent, anchor, bx)
        self._requests.clear()

    def _least_crowded(self, failed, w: float, h: float, ink: InkIndex | None):
        """The place, leader and anchor of the least crowded of the ``failed`` tries' candidates
        (the first of the lowest score in the first try that has it). The score costs the same
        wherever the candidate is: each millimetre of ink under the box counts 1, each cell
        (1 mm²) of a label or leader it overlaps 1 (:class:`~plans.drawing.occupancy.Occupancy`),
        each millimetre of its leader over a label 1, and a place outside the drawing area
        more than any inside it."""
        x0 = np.concatenate([f[2] for f in failed])
        y0 = np.concatenate([f[3] for f in failed])
        c = CLEARANCE
        x1, y1 = x0 + w + c, y0 + h + c
        score = self._occupancy.covered(x0 - c, y0 - c, x1, y1)
        if ink is not None:
            score += ink.ink_mm(x0 - c, y0 - c, x1, y1)
        score += np.concatenate([~f[4] for f in failed]) * _OUTSIDE
        legs = [np.stack([np.full(len(xs), at[0]), np.full(len(xs), at[1]), np.clip(at[0], xs, xs + w),
                          np.clip(at[1], ys, ys + h)], axis=1) for leader, at, xs, ys, _ in failed if leader]
        if legs:
            over = iter(np.split(self._occupancy.over_labels(np.concatenate(legs)),
                                 np.cumsum([len(g) for g in legs])[:-1]))
        best, lo = None, 0
        for leader, at, xs, ys, free in failed:
            hi = lo + len(xs)
            mine = score[lo:hi] + next(over) if leader else score[lo:hi]
            lo = hi
            k = int(np.argmin(mine))
            if best is None or mine[k] < best[0]:
                best = (mine[k], (xs[k], ys[k]), leader, at)
        return best[1], best[2], best[3]

    def _candidates(self, req: _Request, dirs, tries, w: float, h: float, ink: InkIndex | None):
        """Candidate boxes (left, top) for each of ``tries`` (gaps, with a leader, anchor): at
        the gaps × ``dirs`` round the anchor; whether each is free (in the drawing area,
        touching no ink, label or leader, its leader crossing no label), whether it lies in the
        drawing area, and where each try's candidates start (and the last ends). Labels and
        leaders are looked at only for the candidates in the area and clear of ink."""
        xs, ys, ends = [], [], [0]
        hw, hh = w / 2, h / 2
        ux, uy = np.cos(dirs)[None, :], np.sin(dirs)[None, :]
        reach = np.abs(ux) * hw + np.abs(uy) * hh   # the box's edge nearest the anchor is ``gap`` away
        for gaps, leader, at in tries:
            g = np.array([max(gap, req.near) for gap in gaps])[:, None]
            xs.append((at[0] + ux * (g + reach) - hw).ravel())
            ys.append((at[1] + uy * (g + reach) - hh).ravel())
            ends.append(ends[-1] + len(xs[-1]))
        x0, y0 = (np.concatenate(v) if len(v) > 1 else v[0] for v in (xs, ys))
        x1, y1 = x0 + w, y0 + h
        a = self.area
        free = (x0 >= a.x0) & (x1 <= a.x1) & (y0 >= a.y0) & (y1 <= a.y1)
        c = CLEARANCE
        ok = free.copy()
        if ink is not None and ok.any():
            k = np.flatnonzero(ok)
            ok[k[ink.touches(x0[k] - c, y0[k] - c, x1[k] + c, y1[k] + c)]] = False
        k = np.flatnonzero(ok)
        if not len(k):
            return x0, y0, ok, free, ends
        bx0, by0, bx1, by1 = x0[k], y0[k], x1[k], y1[k]
        hit = np.zeros(len(k), dtype=bool)
        span = _FARTHEST + req.near + w + h + c     # no candidate reaches farther from its anchor
        at = [t[2] for t in tries]
        near = (min(p[0] for p in at) - span, min(p[1] for p in at) - span,
                max(p[0] for p in at) + span, max(p[1] for p in at) + span)
        if self.placed:
            p = self._placed_grid.array(self._placed_grid.near(*near))
            hit |= ((bx0[:, None] < p[None, :, 2] + c) & (p[None, :, 0] < bx1[:, None] + c)
                    & (by0[:, None] < p[None, :, 3] + c) & (p[None, :, 1] < by1[:, None] + c)).any(axis=1)
        leaders = self._leader_grid.near(*near)
        if len(leaders):   # only the pairs whose bounding boxes meet are tested
            grown = np.stack([bx0 - c, by0 - c, bx1 + c, by1 + c], axis=1)
            bi, li = np.nonzero(_meet(grown, self._leader_grid.array(leaders)))
            if len(bi):
                hit[bi[segments_meet_boxes(self._leader_ends[leaders[li]], grown[bi])]] = True
        lead = np.zeros(len(x0), dtype=bool)
        for t, (_, leader, _) in enumerate(tries):
            lead[ends[t]:ends[t + 1]] = leader
        m = np.flatnonzero(lead[k] & ~hit)
        if len(m) and self.placed:   # a leader may cross lines, never another label
            anchors = np.zeros((len(x0), 2))
            for t, (_, _, at_t) in enumerate(tries):
                anchors[ends[t]:ends[t + 1]] = at_t
            ax, ay = anchors[k[m], 0], anchors[k[m], 1]
            legs = np.stack([ax, ay, np.clip(ax, bx0[m], bx1[m]), np.clip(ay, by0[m], by1[m])], axis=1)
            reach = (min(near[0], float(ax.min())), min(near[1], float(ay.min())),
                     max(near[2], float(ax.max())), max(near[3], float(ay.max())))
            q = self._placed_grid.array(self._placed_grid.near(*reach)) + np.array([-c, -c, c, c])
            li, qi = np.nonzero(_meet(np.concatenate([np.minimum(legs[:, :2], legs[:, 2:]),
                                                      np.maximum(legs[:, :2], legs[:, 2:])], axis=1), q))
            hit[m[li[segments_meet_boxes(legs[li], q[qi])]]] = True
        ok[k[hit]] = False
        return x0, y0, ok, free, ends

    def _leader(self, parent, anchor, bx: Box) -> None:
        """A thin line from the anchor to the nearest point of the label's box."""
        nx = min(max(anchor[0], bx.x0), bx.x1)
        ny = min(max(anchor[1], bx.y0), bx.y1)
        el = self.dwg.line(start=(self.f(anchor[0]), self.f(anchor[1])), end=(self.f(nx), self.f(ny)),
                           stroke=self.style.construction_colour, stroke_width=fmt(self.style.thin * 0.6, 3))
        el.attribs["class"] = "leader"
        parent.add(el)
        n = len(self._leader_grid)
        if n == len(self._leader_ends):
            self._leader_ends = np.concatenate([self._leader_ends, np.empty((max(16, n), 4))])
        self._leader_ends[n] = (anchor[0], anchor[1], nx, ny)
        self._leader_grid.add((min(anchor[0], nx), min(anchor[1], ny), max(anchor[0], nx), max(anchor[1], ny)))
        self._occupancy.add_leader((anchor[0], anchor[1], nx, ny))


def _meet(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(k, m): whether closed boxes a[i] and b[j] (x0, y0, x1, y1) meet."""
    return ((a[:, None, 0] <= b[None, :, 2]) & (b[None, :, 0] <= a[:, None, 2])
            & (a[:, None, 1] <= b[None, :, 3]) & (b[None, :, 1] <= a[:, None, 3]))

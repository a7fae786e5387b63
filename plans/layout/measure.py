"""The seven layout faults of one sheet (:func:`measure_layout`, :class:`LayoutReport`):
overlapping labels, labels crossing lines, labels off the sheet, long arrowheads, beyond A3,
overlapping vertex letters of force plans, and drawn elements outside the drawing area (any
inked line, outline or fill of the drawing — not the frame's, the title block's — that leaves
the frame or runs into the title block).

Knows :mod:`.sheet` (what the sheet holds) and :mod:`.parsing`; must not import anything that
draws a sheet.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

import numpy as np
import shapely

from .parsing import _local
from .sheet import _Reader, _sheet_size

__all__ = ["LayoutReport", "measure_layout", "A3_MM", "SIZE_TOLERANCE_MM", "FORMATS", "NO_HEAD_MM", "ROUNDING_MM",
           "LEADER_TOUCH_MM", "SHOWN", "VERTEX_SPOT_MM"]

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
#: Two vertices of a force plan nearer than this are one spot to the eye: their letters, each
#: by its vertex, cannot say which is which, mm (a side this short is unreadable on the plan).
VERTEX_SPOT_MM = 2.0


@dataclass(frozen=True)
class LayoutReport:
    """What :func:`measure_layout` found on one sheet: the six counts and, for each, up to
    :data:`SHOWN` offenders in words (label ids or texts, the ink they meet)."""

    width: float                 #: sheet width, mm
    height: float                #: sheet height, mm
    format: str                  #: "A4", "A3" or "W×H mm"
    overlapping_labels: int
    labels_crossing_lines: int
    labels_off_sheet: int
    long_heads: int
    beyond_a3: int
    overlapping_vertex_letters: int = 0
    ink_off_area: int = 0        #: drawn elements leaving the frame or entering the title block
    overlaps: tuple[str, ...] = ()
    crossings: tuple[str, ...] = ()
    off_sheet: tuple[str, ...] = ()
    heads: tuple[str, ...] = ()
    oversize: tuple[str, ...] = ()
    labels: int = 0              #: texts measured
    unmatched_heads: tuple[str, ...] = field(default=())
    vertex_letters: tuple[str, ...] = ()
    outside: tuple[str, ...] = ()

    COUNTS = ("overlapping_labels", "labels_crossing_lines", "labels_off_sheet", "long_heads", "beyond_a3",
              "overlapping_vertex_letters", "ink_off_area")
    DETAILS = {"overlapping_labels": "overlaps", "labels_crossing_lines": "crossings",
               "labels_off_sheet": "off_sheet", "long_heads": "heads", "beyond_a3": "oversize",
               "overlapping_vertex_letters": "vertex_letters", "ink_off_area": "outside"}

    @property
    def counts(self) -> dict[str, int]:
        return {name: getattr(self, name) for name in self.COUNTS}

    @property
    def clean(self) -> bool:
        return not any(self.counts.values())

    def offenders(self, name: str) -> tuple[str, ...]:
        """The listed offenders of count ``name``."""
        return getattr(self, self.DETAILS[name])


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
    """The layout faults of one SVG sheet (see :mod:`plans.layout`)."""
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

    # -- drawn elements outside the drawing area ---------------------------------------------------
    outside: list[str] = []
    n_outside = 0
    room = area.buffer(ROUNDING_MM, join_style="mitre")
    for k in ink:
        if k.layer in ("frame", "title"):
            continue
        g = k.geometry()
        if not room.covers(g):
            n_outside += 1
            if len(outside) < SHOWN:
                b = g.bounds
                where = "leaves the frame" if not inner.buffer(ROUNDING_MM, join_style="mitre").covers(g) else \
                    "runs into the title block"
                outside.append(f"{k.name} {_fmt_box(b)} {where}")

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

    n_letters, letters = _vertex_letters(texts, reader.vertices)

    return LayoutReport(
        width=W, height=H, format=_format(W, H),
        overlapping_labels=n_overlaps, labels_crossing_lines=n_cross, labels_off_sheet=n_off,
        long_heads=n_heads, beyond_a3=len(oversize), overlapping_vertex_letters=n_letters, ink_off_area=n_outside,
        overlaps=tuple(overlaps), crossings=tuple(crossings), off_sheet=tuple(off), heads=tuple(heads),
        oversize=tuple(oversize), labels=len(texts), unmatched_heads=tuple(unmatched),
        vertex_letters=tuple(letters), outside=tuple(outside))


def _vertex_letters(texts, vertices: dict[str, dict[str, list[tuple[float, float]]]]) -> tuple[int, list[str]]:
    """Pairs of vertex letters of one force plan that overlap or sit on one spot: a vertex
    letter is a text of the plan's group reading exactly the name of a vertex its tagged vectors
    join (data-from/data-to); a pair counts when the two boxes' interiors meet, or when the
    vertices they name lie nearer than VERTEX_SPOT_MM (the first place each name is drawn)."""
    n, shown = 0, []
    for gid, named in vertices.items():
        letters = [t for t in texts if t.force == gid and t.words in named]
        for a in range(len(letters)):
            for b in range(a + 1, len(letters)):
                s, t = letters[a], letters[b]
                (p0, q0, p1, q1), (r0, u0, r1, u1) = s.box, t.box
                overlap = p0 < r1 and r0 < p1 and q0 < u1 and u0 < q1
                gap = math.dist(named[s.words][0], named[t.words][0])
                if overlap or gap < VERTEX_SPOT_MM:
                    n += 1
                    if len(shown) < SHOWN:
                        why = "overlaps" if overlap else f"names a vertex {gap:.2f} mm from that of"
                        shown.append(f"{gid}: {s.name} {_fmt_box(s.box)} {why} {t.name} {_fmt_box(t.box)}")
    return n, shown

"""Where a scheme's drive arcs go, in paper millimetres (y up): the φ1 arc's radius and the
arc arrows ω1, ε1 about the crank's pivot, each the first of a textbook's preferred places that
keeps clear of the other links, the pins, the support, the other arrows and the labels' room
(:func:`place_arrow`). Pure geometry on numpy arrays; :mod:`.scheme` builds the arcs from it.
"""

from __future__ import annotations

import math

import numpy as np

from .scheme_drive import clearance
from .. import linalg as la

__all__ = ["HEAD_MM", "ARC_CLEAR_MM", "ARC_MAX_MM", "ARC_MIN_MM", "ARC_STEP_MM", "ARROW_FIRST", "ARROW_SEP_MM",
           "LABEL_CLEAR_MM", "NEAR_SLACK_MM", "PHI_MAX_MM", "PIN_CLEAR_MM", "PIN_ROOM_MM", "REFERENCE_OVERRUN_MM",
           "ROOM_CLEAR_MM", "arc_samples", "clear", "phi_radius", "place_arrow", "polyline", "support_segments"]


def arc_samples(centre: np.ndarray, r: float, start: float, sweep: float, step: float = 4.0) -> np.ndarray:
    """Points (n + 1, 2) along the arc of radius ``r`` about ``centre`` from ``start`` through
    ``sweep`` (degrees, counter-clockwise positive), at most ``step`` degrees apart."""
    n = max(int(math.ceil(abs(sweep) / step)), 1)
    t = np.radians(start + sweep * np.arange(n + 1) / n)
    return centre + r * np.column_stack([np.cos(t), np.sin(t)])


def polyline(pts: np.ndarray) -> np.ndarray:
    """The segments (n − 1, 2, 2) joining consecutive points (n, 2)."""
    return np.stack([pts[:-1], pts[1:]], axis=1)


#: Arrowhead length of the drive's arc arrows ω1, ε1, and of the links' ω_j, ε_j, mm.
HEAD_MM = 3.0
#: Radii of the drive's arc arrows ω1, ε1 about the pivot: least, largest (a short arc near the
#: pivot, as textbooks draw it, whatever the crank's length), and the step between tries, mm.
ARC_MIN_MM = 5.0
ARC_MAX_MM = 15.0
ARC_STEP_MM = 1.5
#: Largest radius of the φ1 arc, mm, and how far its reference line runs beyond it, mm.
PHI_MAX_MM = 9.0
REFERENCE_OVERRUN_MM = 4.0
#: Clearances of a drive arc arrow, mm: from lines, from pins (centres), from a label's room.
ARC_CLEAR_MM = 1.2
PIN_CLEAR_MM = 2.6
ROOM_CLEAR_MM = 2.5
#: Room kept free beside an arc arrow's head for its label (3 mm out from the head), mm.
LABEL_CLEAR_MM = 1.5
#: Least distance between two arc arrows (their heads are 2 mm wide), mm.
ARROW_SEP_MM = 3.5
#: How far beyond the farthest arc and label room (ARC_MAX_MM + 3 mm from the pivot) a line, pin
#: or room can still matter to an arc's placement: more than every clearance above.
NEAR_SLACK_MM = 10.0
#: Drive arc candidates tried first, before all the others at once (most schemes find room
#: among the first few).
ARROW_FIRST = 8
#: How far from the pivot a crank's pin keeps its arcs, mm.
PIN_ROOM_MM = 2.5


def phi_radius(c: np.ndarray, r_phi: float, reference: float, sweep: float, others: np.ndarray,
                pins: np.ndarray) -> float:
    """The φ1 arc's radius: ``r_phi`` (mm), or, when the arc or its reference line up to it
    would meet another link's line or a pin there, the largest of 1 mm steps down to
    ARC_MIN_MM that keeps clear of them (ARC_CLEAR_MM, PIN_CLEAR_MM); ``r_phi`` when none does."""
    ref = np.array([math.cos(math.radians(reference)), math.sin(math.radians(reference))])
    for r in np.arange(r_phi, ARC_MIN_MM - 1e-9, -1.0):
        pts = arc_samples(c, float(r), reference, sweep)
        line = c + np.linspace(PIN_CLEAR_MM, r, 8)[:, None] * ref
        near = float(np.min(la.norm(pts[:, None] - pins[None], axis=-1))) if len(pins) else math.inf
        if clear(np.concatenate([pts, line]), [others]) >= ARC_CLEAR_MM and near >= PIN_CLEAR_MM:
            return float(r)
    return r_phi


def support_segments(c: np.ndarray) -> np.ndarray:
    """The frame support's symbol under pivot ``c`` (triangle, ground line, hatching), mm: the
    drawing's default 5 mm support and 2.2 mm hatch strokes, as segments."""
    s, h = 5.0, 2.2
    pts = [((0, 0), (-s / 2, -s)), ((0, 0), (s / 2, -s)), ((-s, -s), (s, -s)), ((-s - h, -s - h), (s - h, -s - h))]
    return np.array([[c + a, c + b] for a, b in pts], dtype=float)


def clear(pts: np.ndarray, segments: list[np.ndarray]) -> float:
    """The least distance (mm) from ``pts`` to the segments of ``segments`` (each (m, 2, 2))."""
    segs = [x for x in segments if len(x)]
    return clearance(pts, np.concatenate(segs)) if segs else math.inf


def _segments_near(segments: np.ndarray, c: np.ndarray, reach: float) -> np.ndarray:
    """The segments (m, 2, 2) of ``segments`` that come within ``reach`` mm of point ``c``."""
    if len(segments) == 0:
        return segments
    a, b = segments[:, 0], segments[:, 1]
    ab = b - a
    t = np.clip(la.dot(c - a, ab) / np.maximum(la.dot(ab, ab), 1e-12), 0.0, 1.0)
    return segments[la.norm(a + t[:, None] * ab - c, axis=-1) <= reach]


def _arrow_candidates(length: float, r_phi: float) -> list[tuple[float, float, float]]:
    """(span deg, offset from the crank deg, radius mm) of the drive's arc arrows, in the order
    a textbook prefers: across the crank beyond φ1 and inside the crank's pin (or, on a short
    crank, outside its pin), then beside the crank, then behind the pivot and across from it;
    every radius within ARC_MIN_MM … ARC_MAX_MM (nearest φ1's first) and every arc long enough
    for its head."""
    radii = [ARC_MIN_MM + ARC_STEP_MM * k for k in range(int((ARC_MAX_MM - ARC_MIN_MM) / ARC_STEP_MM + 1e-9) + 1)]
    across = [r for r in radii if r_phi + 3.5 <= r <= length - PIN_CLEAR_MM] + \
        [r for r in radii if r >= length + PIN_CLEAR_MM + 1.5]
    radii.sort(key=lambda r: (abs(r - min(r_phi + 3.5, ARC_MAX_MM)), r))     # nearest just beyond φ1 first
    order = [(span, 0.0, r) for span in (70.0, 55.0, 40.0) for r in across]
    order += [(span, off, r) for span in (60.0, 45.0) for off in (50.0, -50.0) for r in radii]
    order += [(span, off, r) for span in (70.0, 50.0) for off in (180.0, 115.0, -115.0, 150.0, -150.0)
              for r in radii]
    order += [(span, off, r) for span in (50.0, 35.0) for off in (90.0, -90.0, 30.0, -30.0) for r in radii]
    return [o for o in order if math.radians(o[0]) * o[2] >= HEAD_MM + 2.5]


def place_arrow(c: np.ndarray, length: float, r_phi: float, crank: float, sense: float, segments: np.ndarray,
                 others: np.ndarray, pins: np.ndarray, taken: list[np.ndarray],
                 rooms: list[np.ndarray], arrows: list[np.ndarray]) -> tuple[float, float, float]:
    """(radius mm, middle direction deg, span deg) of a drive arc arrow about pivot ``c``.

    The first of :func:`_arrow_candidates` that keeps clear: ARC_CLEAR_MM of the other links'
    lines (``others``), the support and φ1 (``taken``), ARROW_SEP_MM of the arc arrows already
    placed (``arrows``), PIN_CLEAR_MM of the pins, ROOM_CLEAR_MM of the labels' rooms
    (``rooms``), and leaves LABEL_CLEAR_MM for its own label by its head (``sense`` +1: the head
    at the counter-clockwise end) from every line (``segments``). Failing all: the one that
    misses least."""
    # only what lies within NEAR_MM of the pivot can decide: every candidate's arc and label room
    # lie within ARC_MAX_MM + 3 mm of it, so anything farther is more than NEAR_SLACK_MM from them,
    # beyond every clearance asked (the same choice, in time linear in the mechanism)
    reach = ARC_MAX_MM + 3.0 + NEAR_SLACK_MM
    segments, others = _segments_near(segments, c, reach), _segments_near(others, c, reach)
    pins = pins[la.norm(pins - c, axis=-1) <= reach] if len(pins) else pins
    rooms = [r for r in rooms if len(r) and float(np.min(la.norm(np.reshape(r, (-1, 2)) - c, axis=-1))) <= reach]
    # the first few candidates, then all the others at once (each arc's samples padded with its
    # last one; a crowded pivot rejects many, the time stays one pass over its lines): the first
    # that keeps clear, else the one that misses least (the first of those within 1e-9 mm)
    cands = _arrow_candidates(length, r_phi)
    margins: list[float] = []
    for lo, hi in ((0, ARROW_FIRST), (ARROW_FIRST, len(cands))):
        block = cands[lo:hi]
        if not block:
            continue
        mids = [crank + off for _, off, _ in block]
        arcs = [arc_samples(c, r, mid - span / 2, span) for (span, _, r), mid in zip(block, mids)]
        most = max(len(a) for a in arcs)
        pts = np.stack([np.concatenate([a, np.repeat(a[-1:], most - len(a), axis=0)]) for a in arcs])
        heads = [math.radians(mid + sense * span / 2) for (span, _, _), mid in zip(block, mids)]
        room = np.array([c + (r + 3.0) * np.array([math.cos(h), math.sin(h)]) for (_, _, r), h in zip(block, heads)])
        lines = np.minimum(_clear_each(pts, [others] + taken), _clear_each(pts, arrows) + ARC_CLEAR_MM - ARROW_SEP_MM)
        label = np.minimum(_clear_each(room[:, None], [segments] + taken + arrows), _nearest_each(room[:, None], pins))
        got = np.minimum.reduce([lines - ARC_CLEAR_MM, _nearest_each(pts, pins) - PIN_CLEAR_MM,
                                 _nearest_each(pts, np.array(rooms).reshape(-1, 2)) - ROOM_CLEAR_MM,
                                 label - LABEL_CLEAR_MM])
        fits = np.flatnonzero(got >= 0.0)
        if len(fits):
            span, _, r = block[int(fits[0])]
            return float(r), mids[int(fits[0])], span
        margins += got.tolist()
    k = 0
    for j, m in enumerate(margins):
        if m > margins[k] + 1e-9:
            k = j
    span, off, r = cands[k]
    return float(r), crank + off, span


def _clear_each(pts: np.ndarray, segments: list[np.ndarray]) -> np.ndarray:
    """The least distance (mm) from each candidate's samples ``pts`` (K, S, 2) to the segments
    of ``segments`` (each (m, 2, 2)); infinite without segments."""
    segs = [x for x in segments if len(x)]
    if not segs:
        return np.full(len(pts), math.inf)
    segs = np.concatenate(segs)
    a, ab = segs[:, 0], segs[:, 1] - segs[:, 0]
    p = pts[:, :, None, :]
    t = np.clip(np.einsum("...k,...k->...", p - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-12), 0.0, 1.0)
    return np.min(la.norm(p - (a + t[..., None] * ab), axis=-1), axis=(1, 2))


def _nearest_each(pts: np.ndarray, to: np.ndarray) -> np.ndarray:
    """The least distance (mm) from each candidate's samples ``pts`` (K, S, 2) to points ``to``."""
    if not len(to):
        return np.full(len(pts), math.inf)
    return np.min(la.norm(pts[:, :, None, :] - to[None, None], axis=-1), axis=(1, 2))

"""The kinematic scheme at one position, as geometry in paper millimetres (y up): world
coordinates divided by μl. Symbols (joints, blocks, supports, arc arrows) keep paper sizes.

Besides the links, pairs and guides, the scheme holds what a textbook scheme marks: the
driving crank's angle φ1 (an arc from the reference direction through the pivot to the
crank), the arc arrows ω1 and, when it is not zero, ε1 (their senses from their signs; each
placed where it keeps clear of φ1, the pins, the other links and the other arrow), and
on request (``senses=True``) the arc arrows ω_j, ε_j of every other moving link. A slotted
link's slot is joined to the rest of its link (a stem, as the yoke of a Scotch yoke), and two
blocks on one pin are drawn apart: the one on the frame guide is moved along its guide and
carried from the pin by a short rod, as textbooks draw a block on a rod. Hydraulic cylinders
(barrel, piston, rod) and a linear drive's input arrows v, a come from :mod:`.scheme_drive`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..kinematics import Motion
from ..scene import FRAME, DriveKind
from .scheme_drive import Cylinder, DriveArrow, clearance, cylinders, drive_arrows
from .. import linalg as la

__all__ = ["Scheme", "Block", "Guide", "Arc", "scheme", "BLOCK_MM", "HEAD_MM", "SENSE_HEAD_MM", "ARC_MAX_MM",
           "REFERENCE_OVERRUN_MM"]

#: Slider block size along and across its guide, mm.
BLOCK_MM = (12.0, 7.0)
#: How far a guide runs beyond the positions its slider takes, mm.
GUIDE_MARGIN_MM = 10.0
#: How far a slot (a moving guide) runs beyond its block's end, mm.
SLOT_MARGIN_MM = 3.0
#: Free length of the rod that carries a block moved off its pin, mm.
ROD_GAP_MM = 3.0
#: Arrowhead length of the drive's arc arrows ω1, ε1, and of the links' ω_j, ε_j, mm.
HEAD_MM = 3.0
SENSE_HEAD_MM = 2.5
#: Sweep of the drive's arc arrows and of the links' ones, degrees.
ARROW_SWEEP = 70.0
SENSE_SWEEP = 90.0
#: A point this close to a line (mm) lies on it.
ON_LINE_MM = 1e-6


@dataclass(frozen=True)
class Block:
    """A slider block centred at ``center``, turned to the guide's direction (deg). ``pin`` is
    the pair's point when the block was moved off it along its guide (another block sits on
    the pin): the block is then carried from the pin by a rod along the guide."""

    link: str
    center: tuple[float, float]
    angle: float
    pin: tuple[float, float] | None = None


@dataclass(frozen=True)
class Guide:
    """A guide segment; ``fixed`` guides (on the frame) are hatched. A moving guide (a slot)
    whose link has no point on the slot's line carries a ``stem``: the segment from the foot
    on the slot to the nearest point of its link, perpendicular to the slot (rigid)."""

    link: str
    start: tuple[float, float]
    end: tuple[float, float]
    fixed: bool
    stem: tuple[tuple[float, float], tuple[float, float]] | None = None


@dataclass(frozen=True)
class Arc:
    """An arc about ``centre`` of ``radius`` (mm) from ``start`` (deg, from +x, CCW) through
    ``sweep`` degrees (CCW positive). ``kind`` is "phi" (the drive's angle, no head; its
    reference line is drawn along ``start``), "omega" or "epsilon" (an arc arrow of ``head``
    mm at the end). ``label`` is in label markup."""

    kind: str
    link: str
    centre: tuple[float, float]
    radius: float
    start: float
    sweep: float
    label: str
    head: float = 0.0

    @property
    def end(self) -> float:
        return self.start + self.sweep

    def at(self, angle: float) -> tuple[float, float]:
        t = math.radians(angle)
        return (self.centre[0] + self.radius * math.cos(t), self.centre[1] + self.radius * math.sin(t))


@dataclass(frozen=True)
class Scheme:
    """Everything the scheme drawing needs at one position."""

    mu_l: float
    points: dict[str, tuple[float, float]]
    links: tuple[tuple[str, tuple[str, ...]], ...]   # moving link → its points (drawn as bars / plates)
    joints: tuple[str, ...]                          # revolute pins
    supports: tuple[str, ...]                        # frame pivots
    blocks: tuple[Block, ...]
    guides: tuple[Guide, ...]
    drive_pivot: str | None
    omega: float                                     # ω1, rad/s (a linear drive: its speed, m/s)
    epsilon: float = 0.0                             # ε1, rad/s² (a linear drive: m/s²)
    phi: float | None = None                         # φ1, deg, from ``reference`` (a rotary drive)
    reference: float = 0.0                           # direction φ1 is measured from, deg
    dots: tuple[str, ...] = ()                       # points on a link that are no pair (coupler points)
    arcs: tuple[Arc, ...] = ()                       # φ1, ω1, ε1 and, on request, ω_j, ε_j
    cylinders: tuple[Cylinder, ...] = ()             # hydraulic cylinders: barrel, piston, rod
    inputs: tuple[DriveArrow, ...] = ()              # a linear drive's input arrows v (and a)


def _xy(v: np.ndarray) -> tuple[float, float]:
    return (float(v[0]), float(v[1]))


def _sub(name: str) -> str:
    return f"_{{{name}}}"


def _half_extent(angle: float, along: float) -> float:
    """Half the extent of a block turned to ``angle`` (deg), measured along direction ``along``."""
    d = math.radians(along - angle)
    return BLOCK_MM[0] / 2 * abs(math.cos(d)) + BLOCK_MM[1] / 2 * abs(math.sin(d))


def scheme(motion: Motion, i: int, mu_l: float, *, senses: bool = False) -> Scheme:
    """The scheme at position ``i``; ``mu_l`` in m/mm. With ``senses``, arc arrows ω_j (and
    ε_j when accelerations are known) of every moving link but the driving one."""
    mech = motion.mechanism
    points = {p: _xy(motion.position(p)[i] / mu_l) for p in mech.sketch}
    shared = [p for p in mech.sketch if sum(p in l.local for l in mech.links.values()) > 1]
    joints = tuple(p for p in shared if any(p in mech.links[l].local for l in mech.moving))
    supports = tuple(p for p in mech.links[FRAME].points if p in joints)
    blocks, offsets = _blocks(motion, i, mu_l, points)
    guides = [_guide(motion, i, mu_l, pr, offsets.get(id(pr), 0.0), points) for pr in mech.prismatics]
    links = tuple((name, mech.links[name].points) for name in mech.moving)
    centres = {b.center for b in blocks}
    dots = tuple(p for p in mech.sketch if p not in joints and points[p] not in centres)
    d = mech.drive
    phi = reference = None
    arcs: list[Arc] = []
    if d.kind == DriveKind.ROTARY:
        phi = float(motion.values[i])
        c, tip = np.asarray(points[d.pivot]), np.asarray(points[d.tip])
        crank = float(np.degrees(np.arctan2(*(tip - c)[::-1])))
        reference = (crank - phi + 180.0) % 360.0 - 180.0
        if abs(reference) < 1e-9:
            reference = 0.0
        every = _segments(points, links, blocks, guides)
        others = _segments(points, [(n, p) for n, p in links if n != d.link], blocks,
                           [gd for gd in guides if gd.link != d.link])   # the crank's slot is the crank's
        pins = np.array([points[p] for p in joints if p != d.pivot], dtype=float).reshape(-1, 2)
        arcs = _drive_arcs(d, motion.drive_rates(i), c, float(la.norm(tip - c)), crank, phi, reference,
                           every, others, pins)
    if d.kind == DriveKind.COUPLER:    # the given ω, ε of the driving coupler, on it
        arcs += _sense_arcs(motion, i, points, blocks, (d.link,))
    if senses:
        arcs += _sense_arcs(motion, i, points, blocks, tuple(n for n in mech.moving if n != d.link))
    cyls = cylinders(motion, i, mu_l)
    block = next(((b.center, BLOCK_MM[1] / 2) for b in blocks if b.link == d.link), None)
    in_cyl = {c.barrel_link for c in cyls} | {c.rod_link for c in cyls}
    segments = _segments(points, [(n, p) for n, p in links if n not in in_cyl], blocks, guides)
    return Scheme(mu_l=mu_l, points=points, links=links, joints=joints, supports=supports,
                  blocks=tuple(blocks), guides=tuple(guides), cylinders=cyls,
                  inputs=drive_arrows(motion, i, mu_l, block, cyls, segments),
                  drive_pivot=d.pivot if d.kind == DriveKind.ROTARY else None, omega=motion.drive_rates(i)[0],
                  epsilon=motion.drive_rates(i)[1],
                  phi=phi, reference=reference if reference is not None else 0.0, dots=dots, arcs=tuple(arcs))


def _segments(points, links, blocks, guides) -> np.ndarray:
    """The scheme's lines as segments (m, 2, 2), mm: bars, plates' edges, blocks' sides, guides."""
    segs = []
    for _, pts in links:
        xy = [points[p] for p in pts]
        if len(xy) == 2:
            segs.append((xy[0], xy[1]))
        elif len(xy) > 2:
            segs += [(xy[k], xy[(k + 1) % len(xy)]) for k in range(len(xy))]
    for b in blocks:
        u = np.array([math.cos(math.radians(b.angle)), math.sin(math.radians(b.angle))])
        n = np.array([-u[1], u[0]])
        c = [np.add(b.center, sx * BLOCK_MM[0] / 2 * u + sy * BLOCK_MM[1] / 2 * n)
             for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        segs += [(c[k], c[(k + 1) % 4]) for k in range(4)]
        if b.pin is not None:
            segs.append((b.pin, b.center))
    for gd in guides:
        segs.append((gd.start, gd.end))
        if gd.stem is not None:
            segs.append(gd.stem)
    return np.array(segs, dtype=float).reshape(-1, 2, 2)


def _blocks(motion: Motion, i: int, mu_l: float, points) -> tuple[list[Block], dict[int, float]]:
    """The blocks of single-point sliders; of two or more blocks on one pin the first whose
    guide moves (a block in a slot) stays on the pin, the others are moved along their guides
    clear of it. Returns the blocks and the offsets (mm along the guide) by pair."""
    mech = motion.mechanism
    found = []
    for pr in mech.prismatics:
        if len(mech.links[pr.slider].points) != 1:
            continue
        u = motion.links[pr.guide].direction(pr.direction)[i]
        angle = float(np.degrees(np.arctan2(u[1], u[0])))
        found.append((pr, _xy(motion.position(pr.label)[i] / mu_l), angle))
    groups: list[list] = []
    for f in found:
        grp = next((g for g in groups if math.dist(g[0][1], f[1]) < 1e-6), None)
        (grp.append(f) if grp is not None else groups.append([f]))
    blocks, offsets = [], {}
    others = [np.asarray(xy) for xy in points.values()]
    for grp in groups:
        grp.sort(key=lambda f: f[0].guide == FRAME)        # a block in a slot stays on its pin
        pin = grp[0][1]
        blocks.append(Block(grp[0][0].slider, pin, grp[0][2]))
        placed = [grp[0][2]]
        for pr, _, angle in grp[1:]:
            u = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
            reach = max(_half_extent(a, angle) for a in placed)
            s = reach + ROD_GAP_MM + BLOCK_MM[0] / 2 + (len(placed) - 1) * (BLOCK_MM[0] + ROD_GAP_MM)
            far = [p for p in others if math.dist(p, pin) > 1e-6]

            def room(sign: float) -> float:
                c = np.asarray(pin) + sign * s * u
                return min((float(la.norm(p - c)) for p in far), default=math.inf)

            sign = 1.0 if room(1.0) >= room(-1.0) else -1.0
            centre = np.asarray(pin) + sign * s * u
            blocks.append(Block(pr.slider, _xy(centre), angle, pin))
            offsets[id(pr)] = sign * s
            placed.append(angle)
    return blocks, offsets


def _guide(motion: Motion, i: int, mu_l: float, pr, offset: float, points) -> Guide:
    """The guide of pair ``pr``: over the slider's travel at every analysed position (and its
    block, when moved ``offset`` mm along the guide). A frame guide runs past the travel; a
    slot runs a little past its block and reaches its own link: to a point of the link on its
    line, or, when none is, past the foot of a stem from the link's nearest point (a yoke)."""
    mech = motion.mechanism
    state = motion.links[pr.guide]
    u = state.direction(pr.direction)
    anchor = state.point(pr.anchor[pr.guide])[i] / mu_l
    travel = motion.position(pr.label) / mu_l
    anchors = state.point(pr.anchor[pr.guide]) / mu_l
    rel = [float(la.dot(travel[j] - anchors[j], u[j])) for j in range(len(travel))]
    rel += [r + offset for r in rel] if offset else []
    fixed = pr.guide == FRAME
    margin = BLOCK_MM[0] / 2 + (GUIDE_MARGIN_MM if fixed else SLOT_MARGIN_MM)
    t0 = min(rel + [0.0]) - margin
    t1 = max(rel + [0.0]) + margin
    ui = u[i]
    stem = None
    if not fixed:
        own = [np.asarray(points[p]) for p in mech.links[pr.guide].points]
        along = [float(la.dot(p - anchor, ui)) for p in own]
        across = [abs(float(ui[0] * (p - anchor)[1] - ui[1] * (p - anchor)[0])) for p in own]
        on = [t for t, d in zip(along, across) if d < ON_LINE_MM]
        if on:
            t0, t1 = min([t0] + on), max([t1] + on)
        elif own:
            k = int(np.argmin(across))
            t = along[k]
            t0, t1 = min(t0, t - margin), max(t1, t + margin)
            stem = (_xy(anchor + t * ui), _xy(own[k]))
    return Guide(pr.guide, _xy(anchor + t0 * ui), _xy(anchor + t1 * ui), fixed, stem)


def _arc_samples(centre: np.ndarray, r: float, start: float, sweep: float, step: float = 4.0) -> np.ndarray:
    n = max(int(math.ceil(abs(sweep) / step)), 1)
    t = np.radians(start + sweep * np.arange(n + 1) / n)
    return centre + r * np.column_stack([np.cos(t), np.sin(t)])


def _polyline(pts: np.ndarray) -> np.ndarray:
    return np.stack([pts[:-1], pts[1:]], axis=1)


def _drive_arcs(d, rates: tuple[float, float], c: np.ndarray, length: float, crank: float, phi: float,
                reference: float, segments: np.ndarray, others: np.ndarray, pins: np.ndarray) -> list[Arc]:
    """φ1 from the reference direction to the crank; ω1 and ε1 (``rates``, when not zero) as
    short arc arrows about the pivot (radius at most ARC_MAX_MM), each placed where it keeps
    clear of the other links' lines (``others``, mm; ``segments``: every line, the driving
    link's too, for the labels), its pins (``pins``), the support, the φ1 arc with its
    reference line and label, and each other (see :func:`_place_arrow`)."""
    centre = _xy(c)
    r_phi = min(max(0.4 * length, 5.0), PHI_MAX_MM)
    if length - r_phi < PIN_ROOM_MM:                  # a very short crank: φ1 inside it still
        r_phi = max(length - PIN_ROOM_MM, 3.5)
    arcs = []
    sweep = math.copysign(abs(phi) % 360.0, phi)
    r_phi = _phi_radius(c, r_phi, reference, sweep, others, pins)
    taken: list[np.ndarray] = [_support_segments(c)]
    rooms: list[np.ndarray] = []                      # points kept for labels: the φ1 label's
    arrows: list[np.ndarray] = []                     # the arc arrows placed (as segments)
    if abs(sweep) > 1e-9:
        arcs.append(Arc("phi", d.link, centre, r_phi, reference, sweep, "φ" + _sub(d.link)))
        taken.append(_polyline(_arc_samples(c, r_phi, reference, sweep)))
        ref = math.radians(reference)
        taken.append(np.array([[c, c + (r_phi + REFERENCE_OVERRUN_MM) * np.array([math.cos(ref), math.sin(ref)])]]))
        mid = math.radians(reference + sweep / 2)
        rooms.append(c + (r_phi + 3.0) * np.array([math.cos(mid), math.sin(mid)]))
    for kind, value, sym in (("omega", rates[0], "ω"), ("epsilon", rates[1], "ε")):
        if value == 0.0:
            continue
        s = math.copysign(1.0, value)
        r, mid, span = _place_arrow(c, length, r_phi, crank, s, segments, others, pins, taken, rooms, arrows)
        arcs.append(Arc(kind, d.link, centre, r, mid - s * span / 2, s * span, sym + _sub(d.link), HEAD_MM))
        arrows.append(_polyline(_arc_samples(c, r, mid - span / 2, span)))
        end = math.radians(mid + s * span / 2)
        rooms.append(c + (r + 3.0) * np.array([math.cos(end), math.sin(end)]))
    return arcs


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


def _phi_radius(c: np.ndarray, r_phi: float, reference: float, sweep: float, others: np.ndarray,
                pins: np.ndarray) -> float:
    """The φ1 arc's radius: ``r_phi`` (mm), or, when the arc or its reference line up to it
    would meet another link's line or a pin there, the largest of 1 mm steps down to
    ARC_MIN_MM that keeps clear of them (ARC_CLEAR_MM, PIN_CLEAR_MM); ``r_phi`` when none does."""
    ref = np.array([math.cos(math.radians(reference)), math.sin(math.radians(reference))])
    for r in np.arange(r_phi, ARC_MIN_MM - 1e-9, -1.0):
        pts = _arc_samples(c, float(r), reference, sweep)
        line = c + np.linspace(PIN_CLEAR_MM, r, 8)[:, None] * ref
        near = float(np.min(la.norm(pts[:, None] - pins[None], axis=-1))) if len(pins) else math.inf
        if _clear(np.concatenate([pts, line]), [others]) >= ARC_CLEAR_MM and near >= PIN_CLEAR_MM:
            return float(r)
    return r_phi


def _support_segments(c: np.ndarray) -> np.ndarray:
    """The frame support's symbol under pivot ``c`` (triangle, ground line, hatching), mm: the
    drawing's default 5 mm support and 2.2 mm hatch strokes, as segments."""
    s, h = 5.0, 2.2
    pts = [((0, 0), (-s / 2, -s)), ((0, 0), (s / 2, -s)), ((-s, -s), (s, -s)), ((-s - h, -s - h), (s - h, -s - h))]
    return np.array([[c + a, c + b] for a, b in pts], dtype=float)


def _clear(pts: np.ndarray, segments: list[np.ndarray]) -> float:
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


def _place_arrow(c: np.ndarray, length: float, r_phi: float, crank: float, sense: float, segments: np.ndarray,
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
        arcs = [_arc_samples(c, r, mid - span / 2, span) for (span, _, r), mid in zip(block, mids)]
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


def _sense_arcs(motion: Motion, i: int, points, blocks: list[Block], links: tuple[str, ...]) -> list[Arc]:
    """ω_j, ε_j arc arrows at the middle of each of ``links``."""
    mech = motion.mechanism
    if motion.order < 1:
        return []
    arcs = []
    kinds = ("omega", "epsilon") if motion.order >= 2 else ("omega",)
    scale = {k: max([1.0] + [abs(float(getattr(motion.links[n], k)[i])) for n in mech.moving]) for k in kinds}
    for name in links:
        state = motion.links[name]
        pts = mech.links[name].points
        xy = np.array([points[p] for p in pts])
        block = next((b for b in blocks if b.link == name), None)
        if len(pts) >= 2:
            mid = xy.mean(axis=0)
            e = xy[1] - xy[0]
            across = float(np.degrees(np.arctan2(e[1], e[0])))
            r = 7.0
        else:
            mid = np.asarray(block.center if block else xy[0])
            across = (block.angle if block else 0.0) + 90.0
            r = 0.5 * math.hypot(*BLOCK_MM) + 2.0
        for kind in kinds:
            value, sym = float(getattr(state, kind)[i]), "ω" if kind == "omega" else "ε"
            if abs(value) <= 1e-9 * scale[kind]:
                continue   # the link translates (or its ω is momentarily constant)
            s = math.copysign(1.0, value)
            arcs.append(Arc(kind, name, _xy(mid), r, across - s * SENSE_SWEEP / 2, s * SENSE_SWEEP,
                            sym + _sub(name), SENSE_HEAD_MM))
            r += 4.0
    return arcs

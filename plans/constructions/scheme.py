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
from .drive_arcs import (ARC_MAX_MM, HEAD_MM, PHI_MAX_MM, PIN_ROOM_MM, REFERENCE_OVERRUN_MM, arc_samples, phi_radius,
                         place_arrow, polyline, support_segments)
from .scheme_drive import Cylinder, DriveArrow, cylinders, drive_arrows
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
    r_phi = phi_radius(c, r_phi, reference, sweep, others, pins)
    taken: list[np.ndarray] = [support_segments(c)]
    rooms: list[np.ndarray] = []                      # points kept for labels: the φ1 label's
    arrows: list[np.ndarray] = []                     # the arc arrows placed (as segments)
    if abs(sweep) > 1e-9:
        arcs.append(Arc("phi", d.link, centre, r_phi, reference, sweep, "φ" + _sub(d.link)))
        taken.append(polyline(arc_samples(c, r_phi, reference, sweep)))
        ref = math.radians(reference)
        taken.append(np.array([[c, c + (r_phi + REFERENCE_OVERRUN_MM) * np.array([math.cos(ref), math.sin(ref)])]]))
        mid = math.radians(reference + sweep / 2)
        rooms.append(c + (r_phi + 3.0) * np.array([math.cos(mid), math.sin(mid)]))
    for kind, value, sym in (("omega", rates[0], "ω"), ("epsilon", rates[1], "ε")):
        if value == 0.0:
            continue
        s = math.copysign(1.0, value)
        r, mid, span = place_arrow(c, length, r_phi, crank, s, segments, others, pins, taken, rooms, arrows)
        arcs.append(Arc(kind, d.link, centre, r, mid - s * span / 2, s * span, sym + _sub(d.link), HEAD_MM))
        arrows.append(polyline(arc_samples(c, r, mid - span / 2, span)))
        end = math.radians(mid + s * span / 2)
        rooms.append(c + (r + 3.0) * np.array([math.cos(end), math.sin(end)]))
    return arcs


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

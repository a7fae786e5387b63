"""The mechanism model: rigid links with local geometry, revolute and prismatic pairs, the drive.

Each link gets *local coordinates* of its points: the sketch, corrected by ``[lengths]``.
The local frame is aligned with the sketch (first point at its sketch position, the
direction to the second point as sketched), so the sketch itself is the pose θ = 0,
origin = (0, 0) of every link, and a pose (θ, o) maps a local point x to o + R(θ)·x.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np

from .errors import SceneError
from .scene import FRAME, Scene, Slider, DriveKind
from . import linalg as la

__all__ = ["Link", "Revolute", "Prismatic", "DriveSpec", "Mechanism", "build_mechanism", "LENGTH_RTOL"]

#: Relative tolerance for lengths that must agree (over-determined link shapes), and for
#: deciding that three points of a link are collinear.
LENGTH_RTOL = 1e-9
#: Sides that add up to within this (relative) are collinear: decimal lengths such as 0.6 =
#: 0.4 + 0.2 miss exactly by a rounding, which would otherwise lift the point sqrt(eps) ~ 1e-8
#: off the line; data given to 16 digits cannot tell a triangle that flat from a line.
COLLINEAR_RTOL = 16 * np.finfo(float).eps


@dataclass(frozen=True, eq=False)
class Link:
    """A rigid link: its point names and their local coordinates (metres); compared and
    hashed by identity (it holds arrays)."""

    name: str
    points: tuple[str, ...]
    local: Mapping[str, np.ndarray]

    @property
    def is_frame(self) -> bool:
        return self.name == FRAME


@dataclass(frozen=True)
class Revolute:
    """A revolute pair at ``point`` joining two links."""

    point: str
    a: str
    b: str

    def other(self, link: str) -> str:
        return self.b if link == self.a else self.a


@dataclass(frozen=True, eq=False)
class Prismatic:
    """A prismatic pair: ``slider`` translates along a line fixed in ``guide``.

    Compared and hashed by identity (it holds arrays): one object per ``[[sliders]]`` entry,
    so groups and pairs that hold it can be dictionary keys.

    ``anchor`` holds, for each of the two links, a local point on the common line;
    ``direction`` is the line's local unit direction (the same in both links, whose
    relative rotation is zero). Sliding velocity is measured along ``direction``.
    """

    slider: str
    guide: str
    anchor: Mapping[str, np.ndarray]
    direction: np.ndarray
    label: str           # the point that names the pair on plans, e.g. "B" in v:B3/B2
    index: int

    @property
    def a(self) -> str:
        return self.slider

    @property
    def b(self) -> str:
        return self.guide

    def other(self, link: str) -> str:
        return self.guide if link == self.slider else self.slider

    @property
    def normal(self) -> np.ndarray:
        return np.array([-self.direction[1], self.direction[0]])


@dataclass(frozen=True)
class DriveSpec:
    """The driving link: ``pivot`` and ``tip`` for a crank (angle of pivot → tip) or a coupler
    (its absolute angle, of the line from its first point ``pivot`` to its second ``tip``; the
    pivot is then not on the frame), or ``guide`` for a slider driven along a guide on the frame
    or, for a hydraulic cylinder, on a moving link (``guide.guide``)."""

    link: str
    kind: DriveKind
    values: tuple[float, ...]
    speed: float
    rate: float
    pivot: str | None = None
    tip: str | None = None
    guide: Prismatic | None = None
    sketch_value: float = 0.0   # the drive's value in the sketch: degrees for a crank or coupler, 0 m for a slider


@dataclass(frozen=True)
class Mechanism:
    """A mechanism ready for structural and kinematic analysis."""

    title: str
    links: Mapping[str, Link]
    revolutes: tuple[Revolute, ...]
    prismatics: tuple[Prismatic, ...]
    drive: DriveSpec
    sketch: Mapping[str, np.ndarray]

    @property
    def moving(self) -> tuple[str, ...]:
        return tuple(name for name in self.links if name != FRAME)

    @property
    def size(self) -> float:
        """A length scale of the mechanism (m): the sketch's bounding-box diagonal."""
        pts = np.array(list(self.sketch.values()))
        return float(np.hypot(*(pts.max(axis=0) - pts.min(axis=0)))) or 1.0



def build_mechanism(scene: Scene) -> Mechanism:
    """Turn a validated scene into a :class:`Mechanism` (link shapes, pairs, drive)."""
    sketch = {name: np.array(xy, dtype=float) for name, xy in scene.points.items()}
    links = {name: Link(name, pts, _shape(name, pts, sketch, scene.lengths)) for name, pts in scene.links.items()}
    revolutes = []
    for point in scene.points:
        carriers = scene.links_of(point)
        # a point shared by k links is k - 1 revolute pairs: chain them to the first carrier
        revolutes += [Revolute(point, carriers[0], other) for other in carriers[1:]]
    prismatics = tuple(_prismatic(s, links, sketch) for s in scene.sliders)
    drive = _drive(scene, links, prismatics, sketch)
    return Mechanism(title=scene.title, links=links, revolutes=tuple(revolutes), prismatics=prismatics,
                     drive=drive, sketch=sketch)


def _shape(name: str, pts: tuple[str, ...], sketch: Mapping[str, np.ndarray],
           lengths: Mapping[frozenset[str], float]) -> dict[str, np.ndarray]:
    """Local coordinates of a link's points (m).

    With no ``[lengths]`` on the link the sketch itself is the shape, to the bit. Otherwise p1
    is put at the length p0p1 along the sketched direction, and each further point keeps its
    sketched offset from p0 (no length of it given), lies at its given length in its sketched
    direction (one given), or is trilaterated from p0 and p1 on the sketch's side (both given):
    its height above p0p1 comes from the triangle's area by Kahan's cancellation-free Heron
    formula, so a point on the line (a rod's midpoint) stays on it instead of sqrt(rounding
    residue) ~ 1e-8 off it."""
    key = f"links.{name}"
    if len(pts) >= 2 and sketch[pts[0]].tolist() == sketch[pts[1]].tolist():
        raise SceneError(f"points {pts[0]} and {pts[1]} coincide in the sketch; a link's points must be distinct",
                         key=key)
    if not any(a in pts and b in pts for a, b in map(tuple, lengths)):
        return {p: sketch[p].copy() for p in pts}

    def dist(a: str, b: str) -> float:
        return lengths.get(frozenset((a, b)), float(la.norm(sketch[a] - sketch[b])))

    local = {pts[0]: sketch[pts[0]].copy()}
    p0, p1 = pts[0], pts[1]
    axis = sketch[p1] - sketch[p0]
    ex = axis / la.norm(axis)
    ey = np.array([-ex[1], ex[0]])
    d01 = dist(p0, p1)
    local[p1] = local[p0] + d01 * ex
    for pk in pts[2:]:
        rel = sketch[pk] - sketch[p0]
        given0, given1 = frozenset((p0, pk)) in lengths, frozenset((p1, pk)) in lengths
        if not (given0 or given1):        # nothing given: where the sketch puts it, from p0
            local[pk] = local[p0] + rel       # (the local frame is the sketch's)
            continue
        if given0 != given1:              # one distance given: at that distance, as sketched
            near = p0 if given0 else p1
            arm = sketch[pk] - sketch[near]
            local[pk] = local[near] + dist(near, pk) * arm / la.norm(arm)
            continue
        d0, d1 = dist(p0, pk), dist(p1, pk)
        h = _height(d01, d0, d1)
        if h is None:
            raise SceneError(f"lengths {p0}{pk} = {d0:g}, {p1}{pk} = {d1:g} and {p0}{p1} = {d01:g} cannot form a "
                             "triangle; correct [lengths] or the sketch", key=key)
        x = (d0 * d0 - d1 * d1 + d01 * d01) / (2.0 * d01)
        side = float(axis[0] * rel[1] - axis[1] * rel[0])
        local[pk] = local[p0] + x * ex + math.copysign(h, side) * ey
    for pair, value in lengths.items():
        a, b = tuple(pair)
        if a in local and b in local:
            got = float(la.norm(local[a] - local[b]))
            if abs(got - value) > 1e-7 * max(value, 1e-12):
                raise SceneError(f"length {a}{b} = {value:g} m contradicts the link's other lengths "
                                 f"(they give {got:.6g} m); a link's shape must be consistently determined", key=key)
    return local


def _height(base: float, d0: float, d1: float) -> float | None:
    """Height (m) over side ``base`` of the triangle with sides base, d0, d1, from its area by
    Kahan's formula; 0 when the sides add up to rounding (collinear points); None when they
    violate the triangle inequality by more than LENGTH_RTOL."""
    a, b, c = sorted((base, d0, d1), reverse=True)
    slack = c - (a - b)            # ≥ 0 for a triangle; exact when the sides are
    if slack < -LENGTH_RTOL * a:
        return None
    if slack <= COLLINEAR_RTOL * a:
        return 0.0
    product = (a + (b + c)) * slack * (c + (a - b)) * (a + (b - c))
    return 0.5 * math.sqrt(max(product, 0.0)) / base


def _prismatic(s: Slider, links: Mapping[str, Link], sketch: Mapping[str, np.ndarray]) -> Prismatic:
    p = s.through[0]
    if s.angle is not None:
        direction = np.array([math.cos(math.radians(s.angle)), math.sin(math.radians(s.angle))])
    else:
        q = s.through[1]
        direction = None
        for name in (s.on, s.link):  # prefer the local shape of a link that carries both points
            if p in links[name].local and q in links[name].local:
                direction = links[name].local[q] - links[name].local[p]
                break
        if direction is None:
            direction = sketch[q] - sketch[p]
        direction = direction / la.norm(direction)
    anchor = {}
    for name in (s.link, s.on):
        local = links[name].local
        anchor[name] = next((local[t] for t in s.through if t in local), sketch[p]).copy()
    return Prismatic(slider=s.link, guide=s.on, anchor=anchor, direction=direction,
                     label=_pair_label(s, links, sketch, anchor[s.on], direction), index=s.index)


def _pair_label(s: Slider, links: Mapping[str, Link], sketch: Mapping[str, np.ndarray], on_line: np.ndarray,
                direction: np.ndarray) -> str:
    """The point that names a prismatic pair on plans and where its block is drawn: the
    slider's point on the line (else its first point) — unless the guide is the block (a
    moving link with fewer points than the slider: a lever sliding in a block pinned to a
    crank), then the block's point on the line where a third moving link is pinned to it."""
    slider, guide = links[s.link], links[s.on]
    default = next((t for t in s.through if t in slider.local), slider.points[0])
    if s.on == FRAME or len(guide.points) >= len(slider.points):
        return default
    span = max(float(la.norm(x - on_line)) for x in sketch.values()) or 1.0
    for p in guide.points:
        d = sketch[p] - on_line
        on = abs(float(d[0] * direction[1] - d[1] * direction[0])) <= 1e-9 * span
        if on and any(p in link.points for name, link in links.items() if name not in (s.link, s.on, FRAME)):
            return p
    return default


def _drive(scene: Scene, links: Mapping[str, Link], prismatics: tuple[Prismatic, ...],
           sketch: Mapping[str, np.ndarray]) -> DriveSpec:
    d = scene.drive
    link = links[d.link]
    if not d.kind.angular:
        guide = next(p for p in prismatics if p.slider == d.link and p.guide == d.along)
        return DriveSpec(link=d.link, kind=d.kind, values=d.values, speed=d.speed, rate=d.rate, guide=guide)
    frame_points = set(links[FRAME].points)
    pivots = [p for p in link.points if p in frame_points]
    if len(pivots) > 1:
        raise SceneError(f"the driving link {d.link} is pinned to the frame at {len(pivots)} points "
                         f"({', '.join(pivots)}) and cannot turn; drive a crank (one point listed in both "
                         f"links 0 and {d.link}) or a coupler (none)", key="drive.link")
    kind = DriveKind.ROTARY if pivots else DriveKind.COUPLER
    pivot = pivots[0] if pivots else link.points[0]
    others = [p for p in link.points if p != pivot]
    if not others:
        what = (f"only its pivot {pivot}; add the crank pin (its angle is measured pivot → that point)"
                if pivots else f"one point, {pivot}; a coupler's angle is that of the line from its first "
                "point to its second: list two")
        raise SceneError(f"the driving link {d.link} has {what}", key=f"links.{d.link}")
    tip = others[0]
    arm = sketch[tip] - sketch[pivot]
    return DriveSpec(link=d.link, kind=kind, values=d.values, speed=d.speed, rate=d.rate, pivot=pivot, tip=tip,
                     sketch_value=math.degrees(math.atan2(arm[1], arm[0])))

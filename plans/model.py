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
from .scene import FRAME, Scene, Slider

__all__ = ["Link", "Revolute", "Prismatic", "DriveSpec", "Mechanism", "build_mechanism", "LENGTH_RTOL"]

#: Relative tolerance for lengths that must agree (over-determined link shapes), and for
#: deciding that three points of a link are collinear.
LENGTH_RTOL = 1e-9


@dataclass(frozen=True)
class Link:
    """A rigid link: its point names and their local coordinates (metres)."""

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


@dataclass(frozen=True)
class Prismatic:
    """A prismatic pair: ``slider`` translates along a line fixed in ``guide``.

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
    """The driving link: ``pivot`` and ``tip`` for a crank (angle of pivot → tip), or ``guide``
    for a slider driven along a frame guide."""

    link: str
    kind: str
    values: tuple[float, ...]
    speed: float
    rate: float
    pivot: str | None = None
    tip: str | None = None
    guide: Prismatic | None = None
    sketch_value: float = 0.0   # the drive's value in the sketch: degrees for a crank, 0 m for a slider


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
    """Local coordinates of a link's points: trilaterate from the first two points with the
    given lengths (else the sketch distances), keeping the sketch's side of each point."""
    key = f"links.{name}"

    def dist(a: str, b: str) -> float:
        return lengths.get(frozenset((a, b)), float(np.linalg.norm(sketch[a] - sketch[b])))

    local = {pts[0]: sketch[pts[0]].copy()}
    if len(pts) == 1:
        return local
    p0, p1 = pts[0], pts[1]
    axis = sketch[p1] - sketch[p0]
    if np.linalg.norm(axis) == 0.0:
        raise SceneError(f"points {p0} and {p1} coincide in the sketch; a link's points must be distinct", key=key)
    ex = axis / np.linalg.norm(axis)
    ey = np.array([-ex[1], ex[0]])
    d01 = dist(p0, p1)
    local[p1] = local[p0] + d01 * ex
    for pk in pts[2:]:
        d0, d1 = dist(p0, pk), dist(p1, pk)
        x = (d0 * d0 - d1 * d1 + d01 * d01) / (2.0 * d01)
        h2 = d0 * d0 - x * x
        if h2 < -LENGTH_RTOL * d0 * d0 * 10:
            raise SceneError(f"lengths {p0}{pk} = {d0:g}, {p1}{pk} = {d1:g} and {p0}{p1} = {d01:g} cannot form a "
                             "triangle; correct [lengths] or the sketch", key=key)
        side = float(axis[0] * (sketch[pk] - sketch[p0])[1] - axis[1] * (sketch[pk] - sketch[p0])[0])
        h = math.sqrt(max(h2, 0.0))
        local[pk] = local[p0] + x * ex + math.copysign(h, side) * ey
    for pair, value in lengths.items():
        a, b = tuple(pair)
        if a in local and b in local:
            got = float(np.linalg.norm(local[a] - local[b]))
            if abs(got - value) > 1e-7 * max(value, 1e-12):
                raise SceneError(f"length {a}{b} = {value:g} m contradicts the link's other lengths "
                                 f"(they give {got:.6g} m); a link's shape must be consistently determined", key=key)
    return local


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
        direction = direction / np.linalg.norm(direction)
    anchor = {}
    for name in (s.link, s.on):
        local = links[name].local
        anchor[name] = next((local[t] for t in s.through if t in local), sketch[p]).copy()
    # the pair is named on plans by the slider's point on the line (else the slider's first point)
    label = next((t for t in s.through if t in links[s.link].local), links[s.link].points[0])
    return Prismatic(slider=s.link, guide=s.on, anchor=anchor, direction=direction, label=label, index=s.index)


def _drive(scene: Scene, links: Mapping[str, Link], prismatics: tuple[Prismatic, ...],
           sketch: Mapping[str, np.ndarray]) -> DriveSpec:
    d = scene.drive
    link = links[d.link]
    if d.kind == "linear":
        guide = next(p for p in prismatics if p.slider == d.link and p.guide == FRAME)
        return DriveSpec(link=d.link, kind="linear", values=d.values, speed=d.speed, rate=d.rate, guide=guide)
    frame_points = set(links[FRAME].points)
    pivots = [p for p in link.points if p in frame_points]
    if len(pivots) != 1:
        raise SceneError(f"the driving link {d.link} must be pivoted on the frame at exactly one point "
                         f"(a point listed in both links 0 and {d.link}); found {len(pivots)}", key="drive.link")
    pivot = pivots[0]
    others = [p for p in link.points if p != pivot]
    if not others:
        raise SceneError(f"the driving link {d.link} has only its pivot {pivot}; add the crank pin "
                         "(its angle is measured pivot → that point)", key=f"links.{d.link}")
    tip = others[0]
    arm = sketch[tip] - sketch[pivot]
    return DriveSpec(link=d.link, kind="rotary", values=d.values, speed=d.speed, rate=d.rate, pivot=pivot, tip=tip,
                     sketch_value=math.degrees(math.atan2(arm[1], arm[0])))

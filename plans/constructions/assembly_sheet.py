"""The ``-assemblies`` sheet's geometry (paper mm, y up): every real assembly of each class III
and IV group at one position, side by side at one μl, as small schemes numbered 1 … n — the
group's links (a plate as its outline through its points), its outer pins on the links it
joins (held where the earlier groups put them), each sliding pair as in the scheme (a block on
its pin turned to the guide, a frame guide hatched, a slot on its link), the chosen (drawn)
assembly marked and the condition figure of each written under it; a class II group is a line
of text.

Reads the assemblies found (:func:`plans.kinematics.assemblies.assemblies`) and the mechanism's
links; computes nothing of the kinematics.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np

from ..kinematics.assemblies import Assembly, GroupAssemblies
from ..model import Mechanism
from ..scene import FRAME
from .scales import fitting_scale
from .scheme import BLOCK_MM, Block, Guide
from .. import linalg as la

__all__ = ["SmallScheme", "GroupRow", "AssemblySheet", "assembly_sheet", "SCHEME_MM"]

#: The largest width or height of one small scheme, mm.
SCHEME_MM = 62.0
#: How far a frame guide runs past its block (a slot: past its block or its link's points), mm.
GUIDE_RUN_MM = (6.0, 3.0)
#: Room kept around a guide for its hatching, mm.
HATCH_ROOM_MM = 3.0


@dataclass(frozen=True)
class SmallScheme:
    """One assembly drawn small: ``number`` (1 …), ``chosen``, ``condition`` (None for a group
    without one), ``bars`` (link, its points' mm positions in order), ``pins`` the outer pins (name,
    mm), ``points`` every named point of the group (name, mm), ``blocks`` and ``guides`` of its
    sliding pairs (as the scheme's), relative to the scheme's own box ``box`` (x0, y0, x1, y1)."""

    number: int
    chosen: bool
    condition: float | None
    bars: tuple[tuple[str, tuple[tuple[float, float], ...]], ...]
    pins: tuple[tuple[str, tuple[float, float]], ...]
    points: tuple[tuple[str, tuple[float, float]], ...]
    box: tuple[float, float, float, float]
    blocks: tuple[Block, ...] = ()
    guides: tuple[Guide, ...] = ()


@dataclass(frozen=True)
class GroupRow:
    """A group's assemblies: ``group``, ``count`` and its ``schemes`` (none for a class II group,
    which the sheet writes as text)."""

    group: str
    count: int
    chosen: int
    schemes: tuple[SmallScheme, ...]


@dataclass(frozen=True)
class AssemblySheet:
    """Every group's row at one position, at one ``mu`` (m/mm)."""

    mu: float
    rows: tuple[GroupRow, ...]


def assembly_sheet(mech: Mechanism, structure, found: Mapping[str, GroupAssemblies]) -> AssemblySheet:
    """The sheet of the assemblies ``found`` at one position (group name → its assemblies)."""
    groups = {g.name: g for g in structure.groups}
    spans = []
    for name, ga in found.items():
        if groups[name].klass < 3:
            continue
        for a in ga.assemblies:
            xy = np.array(list(a.points.values()))          # the outer pins are points of its links too
            spans.append(float(np.max(np.ptp(xy, axis=0))))
    mu = fitting_scale(max(spans), SCHEME_MM) if spans else fitting_scale(mech.size, SCHEME_MM)
    rows = []
    for name, ga in found.items():
        g = groups[name]
        chosen = next(k for k, a in enumerate(ga.assemblies) if a.chosen) + 1
        if g.klass < 3:
            rows.append(GroupRow(name, ga.count, chosen, ()))
            continue
        schemes = []
        for k, a in enumerate(ga.assemblies):
            names = [p.point for p in g.outer if p.kind == "R" and p.point in a.points]
            pts = {p: np.asarray(xy, float) / mu for p, xy in a.points.items()}
            pin_mm = [pts[n] for n in names]
            blocks, guides, extent = _sliders(mech, g, a, pts, mu)
            allxy = np.array(list(pts.values()) + extent)
            lo, hi = allxy.min(axis=0), allxy.max(axis=0)
            bars = tuple((link, tuple((float(pts[p][0]), float(pts[p][1])) for p in mech.links[link].points if p in pts))
                         for link in g.links)
            schemes.append(SmallScheme(k + 1, a.chosen, a.condition, bars,
                                       tuple((n, (float(x[0]), float(x[1]))) for n, x in zip(names, pin_mm)),
                                       tuple((p, (float(x[0]), float(x[1]))) for p, x in pts.items()),
                                       (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])), blocks, guides))
        rows.append(GroupRow(name, ga.count, chosen, tuple(schemes)))
    return AssemblySheet(mu, tuple(rows))


def _sliders(mech: Mechanism, g, a: Assembly, pts: Mapping[str, np.ndarray], mu: float
             ) -> tuple[tuple[Block, ...], tuple[Guide, ...], list[np.ndarray]]:
    """The blocks and guides of ``g``'s sliding pairs in assembly ``a`` (mm) and the points (mm)
    that bound them: a single-point slider is a block on its pin turned to the guide (slider and
    guide turn together, so either link's angle gives the direction); a frame guide runs
    GUIDE_RUN_MM[0] past the block, a slot GUIDE_RUN_MM[1] past it and on to its link's points on
    its line, or, when none is, to the foot of a stem from the link's nearest point."""
    blocks, guides, extent = [], [], []
    for p in g.pairs:
        if p.kind != "P":
            continue
        pr, link = p.prismatic, p.a
        x, y, theta = a.poses[link]
        c, s = math.cos(theta), math.sin(theta)
        u = np.array([c * pr.direction[0] - s * pr.direction[1], s * pr.direction[0] + c * pr.direction[1]])
        anchor = np.array([x + c * pr.anchor[link][0] - s * pr.anchor[link][1],
                           y + s * pr.anchor[link][0] + c * pr.anchor[link][1]]) / mu
        centre = pts.get(pr.label, anchor)
        fixed = pr.guide == FRAME
        half = BLOCK_MM[0] / 2 if len(mech.links[pr.slider].points) == 1 else 0.0
        run = half + GUIDE_RUN_MM[0 if fixed else 1]
        t0, t1 = -run, run
        stem = None
        if not fixed and pr.guide in g.links:
            own = [pts[q] for q in mech.links[pr.guide].points if q in pts]
            along = [la.dot(q - centre, u) for q in own]
            across = [abs(u[0] * (q - centre)[1] - u[1] * (q - centre)[0]) for q in own]
            on = [t for t, d in zip(along, across) if d < 1e-6]
            if on:
                t0, t1 = min([t0] + on), max([t1] + on)
            elif own:
                k = int(np.argmin(across))
                t0, t1 = min(t0, along[k] - GUIDE_RUN_MM[1]), max(t1, along[k] + GUIDE_RUN_MM[1])
                foot = centre + along[k] * u
                stem = ((float(foot[0]), float(foot[1])), (float(own[k][0]), float(own[k][1])))
        ends = [centre + t0 * u, centre + t1 * u]
        guides.append(Guide(pr.guide, (float(ends[0][0]), float(ends[0][1])), (float(ends[1][0]), float(ends[1][1])),
                            fixed, stem))
        n = np.array([-u[1], u[0]])
        room = BLOCK_MM[1] / 2 + (HATCH_ROOM_MM if fixed else 0.0)
        extent += [e + k * room * n for e in ends for k in (-1.0, 1.0)]
        if half:
            blocks.append(Block(pr.slider, (float(centre[0]), float(centre[1])), math.degrees(math.atan2(u[1], u[0]))))
    return tuple(blocks), tuple(guides), extent

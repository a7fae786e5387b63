"""The ``-assemblies`` sheet's geometry (paper mm, y up): every real assembly of each class III
and IV group at one position, side by side at one μl, as small schemes numbered 1 … n — the
group's links (a plate as its outline through its points), its outer pins on the links it
joins (held where the earlier groups put them), the chosen (drawn) assembly marked and the
condition figure of each written under it; a class II group is a line of text.

Reads the assemblies found (:func:`plans.kinematics.assemblies.assemblies`) and the mechanism's
links; computes nothing of the kinematics.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

import numpy as np

from ..kinematics.assemblies import GroupAssemblies
from ..model import Mechanism
from .scales import fitting_scale

__all__ = ["SmallScheme", "GroupRow", "AssemblySheet", "assembly_sheet", "SCHEME_MM"]

#: The largest width or height of one small scheme, mm.
SCHEME_MM = 62.0


@dataclass(frozen=True)
class SmallScheme:
    """One assembly drawn small: ``number`` (1 …), ``chosen``, ``condition`` (None for a group
    without one), ``bars`` (link, its points' mm positions in order), ``pins`` the outer pins (name,
    mm) and ``points`` every named point of the group (name, mm), relative to the scheme's own
    box ``box`` (x0, y0, x1, y1)."""

    number: int
    chosen: bool
    condition: float | None
    bars: tuple[tuple[str, tuple[tuple[float, float], ...]], ...]
    pins: tuple[tuple[str, tuple[float, float]], ...]
    points: tuple[tuple[str, tuple[float, float]], ...]
    box: tuple[float, float, float, float]


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
            allxy = np.array(list(pts.values()))
            lo, hi = allxy.min(axis=0), allxy.max(axis=0)
            bars = tuple((link, tuple((float(pts[p][0]), float(pts[p][1])) for p in mech.links[link].points if p in pts))
                         for link in g.links)
            schemes.append(SmallScheme(k + 1, a.chosen, a.condition, bars,
                                       tuple((n, (float(x[0]), float(x[1]))) for n, x in zip(names, pin_mm)),
                                       tuple((p, (float(x[0]), float(x[1]))) for p, x in pts.items()),
                                       (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))))
        rows.append(GroupRow(name, ga.count, chosen, tuple(schemes)))
    return AssemblySheet(mu, tuple(rows))

"""The speeds of a gear train, exactly: one linear equation per mesh (Willis' formula in the
mesh's reference frame), one per input, solved in fractions; the ratios, the Willis equation of
each carrier and the tabular method (carrier held, then everything turned with the carrier).

Speeds are in rpm, counter-clockwise positive; ω = n·π/30 rad/s. A transmission ratio
i_jk = n_j/n_k keeps its sign (+ when both turn one way).

Imports only plans.errors, plans.scene and plans.gears.train (and the standard library).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Mapping

from ..errors import StructureError
from ..scene.gears import GearTrain
from .train import GearLink, TrainStructure, train_structure


@dataclass(frozen=True)
class Willis:
    """Willis' equation of carrier ``carrier`` between links ``a`` and ``b`` (two central links;
    a central link and a planet when the carrier has one central link):
    (n_a − n_H)/(n_b − n_H) = ``ratio`` (= i_ab^H, from the teeth); ``residual`` = (n_a − n_H) −
    i_ab^H·(n_b − n_H) in rpm, evaluated in floating point from the solved speeds."""

    carrier: str
    a: str
    b: str
    ratio: Fraction
    residual: float


@dataclass(frozen=True)
class TrainSpeeds:
    """The solved train: ``rpm`` maps every wheel and carrier to its exact speed (rpm, Fraction),
    links held still included (0)."""

    structure: TrainStructure
    rpm: Mapping[str, Fraction]
    willis: tuple[Willis, ...]

    @property
    def train(self) -> GearTrain:
        return self.structure.train

    def omega(self, name: str) -> float:
        """ω of wheel or carrier ``name``, rad/s (counter-clockwise positive)."""
        return float(self.rpm[name]) * math.pi / 30.0

    def ratio(self, j: str, k: str) -> Fraction | None:
        """i_jk = n_j/n_k, exact; None when ``k`` is at rest."""
        nk = self.rpm[k]
        return None if nk == 0 else self.rpm[j] / nk


def exact(value: float) -> Fraction:
    """A float the user wrote (1450.0, 0.1) as the decimal fraction it reads as."""
    return Fraction(repr(float(value)))


def solve_train(train: GearTrain, *, inputs: Mapping[str, float] | None = None) -> TrainSpeeds:
    """Solve ``train`` for the speeds of every link from its inputs (``inputs`` overrides the
    scene's ``[gears.input]``, name → rpm). Refused with a :class:`StructureError`: a locked train
    (W = 0), inputs that do not match W, an input on a link held still, or inputs that do not
    determine the train."""
    structure = train_structure(train)
    given = dict(train.inputs) if inputs is None else dict(inputs)
    w = structure.mobility
    moving = structure.moving
    index = {link.name: k for k, link in enumerate(moving)}
    rows = [_mesh_row(m, index, len(moving)) for m in structure.meshes]
    rank = _rank([r[:] for r in rows]) if rows else 0
    free = len(moving) - rank
    if free == 0 or w <= 0:
        raise StructureError(f"the train is locked: {structure.formula}"
                             f"{'' if free == 0 else f', and its meshes leave {free} motion(s)'}; free a fixed "
                             "link or remove a mesh", key="gears")
    if free != w:
        raise StructureError(f"{structure.formula}, but the meshes leave "
                             f"{free} independent motion(s): a closed loop of meshes constrains twice; remove a mesh",
                             key="gears.meshes")
    if len(given) != w:
        hint = "a planetary train (W = 1) takes one input" if w == 1 else \
            f"a differential (W = {w}) takes {w} inputs; or hold a central wheel still with [gears] fixed"
        raise StructureError(f"the train has W = {w} but [gears.input] gives {len(given)} speed(s); {hint}",
                             key="gears.input")
    seen: dict[str, str] = {}
    for name in given:
        link = structure.link_of(name)
        if link.fixed:
            raise StructureError(f"{name!r} is held still ([gears] fixed) and cannot be an input; drive a moving "
                                 "link", key=f"gears.input.{name}")
        if link.name in seen:
            raise StructureError(f"{seen[link.name]!r} and {name!r} are on one shaft: one input each; drive "
                                 "another link", key=f"gears.input.{name}")
        seen[link.name] = name
        row = [Fraction(0)] * (len(moving) + 1)
        row[index[link.name]] = Fraction(1)
        row[-1] = exact(given[name])
        rows.append(row)
    solution = _solve(rows, len(moving))
    if solution is None:
        raise StructureError(f"the inputs {', '.join(given)} do not determine the train (their links are tied "
                             "by the meshes); drive another link", key="gears.input")
    by_link = {link.name: (Fraction(0) if link.fixed else solution[index[link.name]]) for link in structure.links}
    rpm = {m: by_link[link.name] for link in structure.links for m in link.members}
    rpm = {n: rpm[n] for n in train.names}
    return TrainSpeeds(structure=structure, rpm=rpm, willis=_willis(structure, rpm))


def _mesh_row(mesh, index: Mapping[str, int], size: int) -> list[Fraction]:
    """z_a·(n_a − n_R) ∓ z_b·(n_b − n_R) = 0 written as n_a − n_R − ratio·(n_b − n_R) = 0."""
    row = [Fraction(0)] * (size + 1)
    for link, coef in ((mesh.link_a, Fraction(1)), (mesh.link_b, -mesh.ratio),
                       (mesh.reference, mesh.ratio - 1)):
        if link is not None and link in index:
            row[index[link]] += coef
    return row


def _rank(rows: list[list[Fraction]]) -> int:
    """Rank of the coefficient part (all but the last column), by exact elimination."""
    rank, cols = 0, len(rows[0]) - 1
    for c in range(cols):
        pivot = next((r for r in range(rank, len(rows)) if rows[r][c] != 0), None)
        if pivot is None:
            continue
        rows[rank], rows[pivot] = rows[pivot], rows[rank]
        for r in range(rank + 1, len(rows)):
            f = rows[r][c] / rows[rank][c]
            if f:
                rows[r] = [x - f * y for x, y in zip(rows[r], rows[rank])]
        rank += 1
    return rank


def _solve(rows: list[list[Fraction]], size: int) -> list[Fraction] | None:
    """The unique solution of the (consistent, full-rank) system, or None."""
    rows = [r[:] for r in rows]
    if _rank([r[:] for r in rows]) < size:
        return None
    for c in range(size):
        pivot = next(r for r in range(c, len(rows)) if rows[r][c] != 0)
        rows[c], rows[pivot] = rows[pivot], rows[c]
        p = rows[c][c]
        rows[c] = [x / p for x in rows[c]]
        for r in range(len(rows)):
            if r != c and rows[r][c] != 0:
                f = rows[r][c]
                rows[r] = [x - f * y for x, y in zip(rows[r], rows[c])]
    if any(rows[r][-1] != 0 for r in range(size, len(rows))):
        return None
    return [rows[c][-1] for c in range(size)]


def carrier_ratio(structure: TrainStructure, carrier: str, a: str, b: str) -> Fraction | None:
    """i_ab^H of links ``a`` and ``b`` with carrier link ``carrier`` held: the product of the mesh
    ratios along the meshes seen from that carrier (and the frame-fixed meshes when the carrier
    is held too), or None when no such path joins them."""
    frontier, seen = [(a, Fraction(1))], {a: Fraction(1)}
    while frontier:
        link, ratio = frontier.pop(0)
        for m in structure.meshes:
            if m.reference != carrier:
                continue
            for here, there, r in ((m.link_a, m.link_b, m.ratio), (m.link_b, m.link_a, 1 / m.ratio)):
                if here == link and there not in seen:
                    seen[there] = ratio * r         # (n_a − n_H)/(n_there − n_H)
                    frontier.append((there, seen[there]))
    return seen.get(b)


def central_links(structure: TrainStructure, carrier: str) -> tuple[GearLink, ...]:
    """The links on the central axis that mesh with the planets of carrier link ``carrier`` (scene
    order): suns and rings, also one on another carrier's shaft (a later stage's sun)."""
    names = {n for m in structure.meshes if m.reference == carrier for n in (m.link_a, m.link_b)}
    return tuple(link for link in structure.links
                 if link.name in names and link.axis_on is None and link.name != carrier)


def _willis(structure: TrainStructure, rpm: Mapping[str, Fraction]) -> tuple[Willis, ...]:
    """Each carrier's Willis equations: its first central link with every other one; with a single
    central link, that link with each of its planets (both seen from the carrier)."""
    out = []
    for c in structure.train.carriers:
        h = structure.link_of(c).name
        central = [link.name for link in central_links(structure, h)]
        planets = [link.name for link in structure.planets_of(c)]
        pairs = [(central[0], b) for b in central[1:]] if len(central) > 1 else \
            [(central[0], p) for p in planets] if central else \
            [(planets[0], b) for b in planets[1:2]]
        for a, b in pairs:
            ratio = carrier_ratio(structure, h, a, b)
            if ratio is None:
                continue
            na, nb, nh = float(rpm[a]), float(rpm[b]), float(rpm[c])
            out.append(Willis(carrier=c, a=a, b=b, ratio=ratio, residual=(na - nh) - float(ratio) * (nb - nh)))
    return tuple(out)


def tabular(speeds: TrainSpeeds, carrier: str) -> tuple[tuple[str, Fraction, Fraction, Fraction], ...]:
    """The tabular method for ``carrier``: for each link of its train (carrier, central links,
    planets), (name, n − n_H with the carrier held, n_H when all turn with the carrier, n)."""
    s = speeds.structure
    h = s.link_of(carrier).name
    names = [h] + [link.name for link in central_links(s, h)] + [link.name for link in s.planets_of(carrier)]
    nh = speeds.rpm[carrier]
    return tuple((n, speeds.rpm[n] - nh, nh, speeds.rpm[n]) for n in dict.fromkeys(names))

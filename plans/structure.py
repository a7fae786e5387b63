"""Structural analysis: Chebyshev's W, Assur groups, their forms, the structural formula.

The decomposition is built up from the original mechanism (frame + driving link): at each
step the first pair of unknown links that forms a class II group on the known links is
attached; when no pair does, the first four links that form a class III group (a base link
with three inner pairs and three rods) or a class IV group (a closed four-sided contour with
two outer pairs). Read backwards, this is the textbook's removal of the farthest group
first, simplest groups first; each attached group has W = 0, so W of the remaining chain is
unchanged by every removal.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

from .errors import StructureError
from .model import Mechanism, Prismatic
from .scene import FRAME

__all__ = ["Joint", "Group", "Pair", "Rod", "ComplexGroup", "Structure", "analyse_structure", "FORMS"]

#: The five forms of class II groups (outer pair D of link m, inner pair E, outer pair F of n).
FORMS = ("RRR", "RRP", "RPR", "PRP", "RPP")
_ROMAN = {1: "I", 2: "II", 3: "III", 4: "IV"}


@dataclass(frozen=True)
class Joint:
    """One pair of a group as the solver sees it.

    ``kind`` is ``"R"`` (``point`` is the pin; for an outer pair its position is known from
    link ``other``) or ``"P"`` (``prismatic`` is the pair; ``other`` the link on the far side).
    """

    kind: str
    other: str
    point: str | None = None
    prismatic: Prismatic | None = None

    def describe(self) -> str:
        if self.kind == "R":
            return f"R {self.point}"
        p = self.prismatic
        return f"P {p.slider}/{p.guide}"


@dataclass(frozen=True)
class Group:
    """A class II Assur group: links ``m`` and ``n``, outer pair ``d`` (m–k), inner pair ``e``
    (m–n), outer pair ``f`` (n–p)."""

    m: str
    n: str
    d: Joint
    e: Joint
    f: Joint

    klass: int = 2
    order: int = 2

    @property
    def form(self) -> str:
        return self.d.kind + self.e.kind + self.f.kind

    @property
    def links(self) -> tuple[str, str]:
        return (self.m, self.n)

    @property
    def name(self) -> str:
        return f"{_ROMAN[self.klass]}({self.m}-{self.n})"

    def as_dict(self) -> dict:
        return {"name": self.name, "links": [self.m, self.n], "class": self.klass, "order": self.order,
                "form": self.form, "pairs": [j.describe() for j in (self.d, self.e, self.f)]}


@dataclass(frozen=True)
class Structure:
    """W, the original mechanism and the groups in the order they are attached (and solved)."""

    dof: int
    moving: int
    p5: int
    p4: int
    drive: str
    groups: tuple["Group | ComplexGroup", ...]

    @property
    def klass(self) -> int:
        return max((g.klass for g in self.groups), default=1)

    @property
    def formula(self) -> str:
        return " ← ".join([f"I({FRAME}-{self.drive})", *(g.name for g in self.groups)])

    def as_dict(self) -> dict:
        return {"dof": self.dof, "class": self.klass, "formula": self.formula,
                "moving_links": self.moving, "p5": self.p5, "p4": self.p4,
                "groups": [g.as_dict() for g in self.groups]}


def analyse_structure(mech: Mechanism) -> Structure:
    """Count W = 3n − 2·P5 − P4 and split the mechanism into Assur groups.

    Raises :class:`StructureError` when W differs from the number of drives (one), or when
    some links do not split into class II groups.
    """
    n = len(mech.moving)
    p5 = len(mech.revolutes) + len(mech.prismatics)
    p4 = 0
    dof = 3 * n - 2 * p5 - p4
    if dof != 1:
        hint = ("the chain is locked (a structure, not a mechanism); remove a pair or add a link"
                if dof < 1 else f"it needs {dof} drives; this version takes one — add pairs or links to fix it")
        raise StructureError(f"W = 3·{n} − 2·{p5} − {p4} = {dof}, but the scene has 1 drive: {hint}", key="links")
    drive = mech.drive.link
    _check_original_mechanism(mech)
    known = {FRAME, drive}
    remaining = [name for name in mech.moving if name != drive]
    groups: list[Group] = []
    while remaining:
        group = next((g for a, b in combinations(remaining, 2) if (g := _dyad(mech, known, a, b))), None)
        if group is None:
            group = next((g for four in combinations(remaining, 4) if (g := _complex(mech, known, four))), None)
        if group is None:
            raise StructureError(
                f"links {', '.join(remaining)} do not split into Assur groups of class II, III or IV attached to "
                f"links {', '.join(sorted(known))}: they are not connected to them, or form a group of a higher "
                "class, which this version does not solve", key="links")
        groups.append(group)
        known |= set(group.links)
        remaining = [r for r in remaining if r not in group.links]
    return Structure(dof=dof, moving=n, p5=p5, p4=p4, drive=drive, groups=tuple(groups))


def _check_original_mechanism(mech: Mechanism) -> None:
    d = mech.drive
    if d.kind == "rotary":
        return  # the pivot on the frame is checked when the model is built
    if not any(p.slider == d.link and p.guide == FRAME for p in mech.prismatics):
        raise StructureError(f"the driving slider {d.link} has no guide on the frame", key="drive.link")


def _joints(mech: Mechanism, link: str, others: set[str]) -> list[Joint]:
    """The pairs joining ``link`` to any link of ``others`` (one joint per pin or slider)."""
    joints = []
    for point in mech.links[link].points:
        carriers = [name for name, l in mech.links.items() if point in l.local and name in others]
        if carriers:
            joints.append(Joint("R", carriers[0], point=point))
    for p in mech.prismatics:
        if link in (p.slider, p.guide) and p.other(link) in others:
            joints.append(Joint("P", p.other(link), prismatic=p))
    return joints


def _dyad(mech: Mechanism, known: set[str], a: str, b: str) -> Group | None:
    outer_a, outer_b = _joints(mech, a, known), _joints(mech, b, known)
    # a pin shared by a, b and a known link fixes both a and b there: two outer pairs, no inner one
    inner = [j for j in _joints(mech, a, {b}) if not (j.kind == "R" and any(o.point == j.point for o in outer_a))]
    if len(outer_a) != 1 or len(outer_b) != 1 or len(inner) != 1:
        return None
    m, n, d, f = a, b, outer_a[0], outer_b[0]
    e = inner[0]
    if d.kind == "P" and f.kind == "R":       # PRR → RRP, PPR → RPP: put the revolute outer pair first
        m, n, d, f = n, m, f, d
    e = Joint(e.kind, n, point=e.point, prismatic=e.prismatic)
    if d.kind + e.kind + f.kind not in FORMS:
        raise StructureError(f"links {m} and {n} are joined only by prismatic pairs (PPP): such a group "
                             "does not fix its position; replace one slider by a pin", key="sliders")
    return Group(m=m, n=n, d=d, e=e, f=f)


@dataclass(frozen=True)
class Pair:
    """A kinematic pair of a class III/IV group: ``a`` is a link of the group, ``b`` the
    other link (of the group for an inner pair, known for an outer one); ``point`` names a
    revolute pair's pin, ``prismatic`` a sliding pair."""

    kind: str
    a: str
    b: str
    point: str | None = None
    prismatic: Prismatic | None = None

    def describe(self) -> str:
        return f"R {self.point}" if self.kind == "R" else f"P {self.prismatic.slider}/{self.prismatic.guide}"

    def other(self, link: str) -> str:
        return self.b if link == self.a else self.a

    @property
    def label(self) -> str:
        """The point that names the pair (the pin, or the slider's label point)."""
        return self.point if self.kind == "R" else self.prismatic.label


@dataclass(frozen=True)
class Rod:
    """A rod of a class III group: link ``link`` joined to the base link by ``inner`` and to
    a known link by ``outer``."""

    link: str
    inner: Pair
    outer: Pair

    @property
    def form(self) -> str:
        return self.outer.kind + self.inner.kind


@dataclass(frozen=True)
class ComplexGroup:
    """A class III (order III: base link + three rods) or class IV (order II: closed
    four-sided contour) Assur group of four links and six pairs."""

    links: tuple[str, ...]
    inner: tuple[Pair, ...]
    outer: tuple[Pair, ...]
    klass: int
    base: str | None = None      # class III: the base link (three inner pairs)

    @property
    def order(self) -> int:
        return len(self.outer)

    @property
    def rods(self) -> tuple[Rod, ...]:
        """Class III: the three rods, in the order of the base link's pairs."""
        if self.base is None:
            return ()
        out = []
        for p in self.inner:
            rod = p.other(self.base)
            out.append(Rod(rod, p, next(o for o in self.outer if o.a == rod)))
        return tuple(out)

    @property
    def form(self) -> str:
        """The kinds of the pairs: class III rod by rod (outer+inner), e.g. ``RR-RR-RR``;
        class IV the contour then the outer pairs, e.g. ``RRRR-RR``."""
        if self.base is not None:
            return "-".join(r.form for r in self.rods)
        return "".join(p.kind for p in self.inner) + "-" + "".join(p.kind for p in self.outer)

    @property
    def name(self) -> str:
        return f"{_ROMAN[self.klass]}({'-'.join(self.links)})"

    @property
    def pairs(self) -> tuple[Pair, ...]:
        return self.inner + self.outer

    def as_dict(self) -> dict:
        out = {"name": self.name, "links": list(self.links), "class": self.klass, "order": self.order,
               "form": self.form, "pairs": [p.describe() for p in self.pairs],
               "inner_pairs": [p.describe() for p in self.inner], "outer_pairs": [p.describe() for p in self.outer]}
        if self.base is not None:
            out["base_link"] = self.base
            out["rods"] = [r.link for r in self.rods]
        return out


def _pairs_of(mech: Mechanism, links: set[str], others: set[str]) -> list[Pair]:
    """Pairs joining a link of ``links`` to a link of ``others`` (a pin shared by several
    links is one pair per extra link, as in W)."""
    out = []
    for r in mech.revolutes:
        for a, b in ((r.a, r.b), (r.b, r.a)):
            if a in links and b in others and not (b in links and a > b):
                out.append(Pair("R", a, b, point=r.point))
    for p in mech.prismatics:
        for a, b in ((p.slider, p.guide), (p.guide, p.slider)):
            if a in links and b in others and not (b in links and a > b):
                out.append(Pair("P", a, b, prismatic=p))
    return out


def _complex(mech: Mechanism, known: set[str], four: tuple[str, ...]) -> ComplexGroup | None:
    """The class III or IV group formed by links ``four`` on the ``known`` links, if any."""
    links = set(four)
    inner = _pairs_of(mech, links, links)
    outer = _pairs_of(mech, links, known)
    if len(inner) + len(outer) != 6:
        return None
    degree = {name: sum(name in (p.a, p.b) for p in inner) for name in four}
    if any(sum(p.a == name for p in outer) + degree[name] < 2 for name in four):
        return None
    base = [name for name in four if degree[name] == 3]
    if len(inner) == 3 and len(base) == 1:       # a star: base link + three rods
        b = base[0]
        if any(sum(p.a == r for p in outer) != 1 for r in four if r != b):
            return None
        inner = [Pair(p.kind, b, p.other(b), p.point, p.prismatic) for p in inner]
        return ComplexGroup(links=four, inner=tuple(inner), outer=tuple(outer), klass=3, base=b)
    if len(inner) == 4 and all(d == 2 for d in degree.values()) and len(outer) == 2:
        return ComplexGroup(links=four, inner=tuple(_contour(inner)), outer=tuple(outer), klass=4)
    return None


def _contour(inner: list[Pair]) -> list[Pair]:
    """The four inner pairs of a class IV group in order around the contour."""
    ordered = [inner[0]]
    rest = inner[1:]
    link = inner[0].b
    while rest:
        nxt = next(p for p in rest if link in (p.a, p.b))
        rest.remove(nxt)
        ordered.append(Pair(nxt.kind, link, nxt.other(link), nxt.point, nxt.prismatic))
        link = nxt.other(link)
    return ordered

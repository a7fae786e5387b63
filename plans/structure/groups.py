"""The value types of structural analysis: pairs and joints, the Assur groups (class II
:class:`Group`, class III/IV :class:`ComplexGroup`), the original mechanism of a drive inside
the chain (:class:`DrivenGroup`) and the :class:`Structure` that lists them.

Knows nothing of how the groups are found (:mod:`plans.structure.search`). Imports only
plans.model and plans.scene; must not import the search, kinematics or anything above.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from ..model import Prismatic
from ..scene import FRAME

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

    #: The kind of group, the key of its solver in :data:`plans.kinematics.kinds.SOLVERS`.
    kind: ClassVar[str] = "dyad"

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
    """W, the original mechanism and the groups in the order they are attached (and solved).

    ``driven``: for a drive inside the chain (a coupler's angle, a hydraulic cylinder), the
    original mechanism's links solved together with the drive (:class:`DrivenGroup`); None for
    a crank or a slider on the frame (the original mechanism is the frame and that link)."""

    dof: int
    moving: int
    p5: int
    p4: int
    drive: str
    groups: tuple["Group | ComplexGroup", ...]
    driven: "DrivenGroup | None" = None

    @property
    def klass(self) -> int:
        return max((g.klass for g in self.groups), default=1)

    @property
    def original(self) -> str:
        """The original mechanism, as the structural formula writes it: I(0-1), I(0-1-2-3)."""
        return self.driven.name if self.driven is not None else f"I({FRAME}-{self.drive})"

    @property
    def formula(self) -> str:
        return " ← ".join([self.original, *(g.name for g in self.groups)])

    def as_dict(self) -> dict:
        out = {"dof": self.dof, "class": self.klass, "formula": self.formula,
               "moving_links": self.moving, "p5": self.p5, "p4": self.p4,
               "groups": [g.as_dict() for g in self.groups]}
        if self.driven is not None:
            out["original_mechanism"] = self.driven.as_dict()
        return out



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

    kind: ClassVar[str] = "complex"

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


@dataclass(frozen=True)
class DrivenGroup:
    """The original mechanism of a drive inside the chain: links (not the frame) that the
    frame and the drive's one given coordinate fix — a coupler's absolute angle, or a
    hydraulic cylinder's stroke (link ``drive`` sliding in its guide link). Its pairs give
    2p = 3n − 1 equations and the drive the last one; the links are solved together
    (:mod:`plans.kinematics.drives`). ``inner``: pairs among its links; ``outer``: with the
    frame (``a`` is the group's link)."""

    kind: ClassVar[str] = "driven"

    links: tuple[str, ...]
    inner: tuple[Pair, ...]
    outer: tuple[Pair, ...]
    drive: str
    klass: int = 1
    base: None = None          # no base link: its relations are drawn as a class IV group's

    @property
    def pairs(self) -> tuple[Pair, ...]:
        return self.inner + self.outer

    @property
    def order(self) -> int:
        return len(self.outer)

    @property
    def form(self) -> str:
        return "".join(p.kind for p in self.inner) + "-" + "".join(p.kind for p in self.outer)

    @property
    def name(self) -> str:
        return f"I({FRAME}-{'-'.join(self.links)})"

    def as_dict(self) -> dict:
        return {"name": self.name, "links": list(self.links), "class": self.klass, "drive": self.drive,
                "form": self.form, "pairs": [p.describe() for p in self.pairs]}


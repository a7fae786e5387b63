"""Structural analysis: Chebyshev's W, Assur groups, their forms, the structural formula.

The decomposition is built up from the original mechanism (frame + driving link): at each
step the first pair of unknown links (in [links] order) that forms a class II group on the
known links is attached; when no pair does, the first four links that form a class III group
(a base link with three inner pairs and three rods) or a class IV group (a closed four-sided
contour with two outer pairs). Read backwards, this is the textbook's removal of the farthest
group first, simplest groups first; each attached group has W = 0, so W of the remaining chain
is unchanged by every removal.

"The first" is the first in the order of ``itertools.combinations`` over the remaining links,
but the search does not walk those combinations (n²/2 pairs and n⁴/24 fours at every step):
a group's outer pairs join it to known links, so only links next to the known ones (the
frontier) can take part — a dyad is two adjacent frontier links, a class III group a base
with three frontier rods, a class IV group a four-link contour through a frontier link. Those
few candidates are checked and the first in combination order is attached: the same groups as
a walk over every combination, in the same order and orientation, but the work is about the
frontier's size per step (O(n²) in all) however the links are listed, instead of growing as n⁴
(n⁵ counting each check's look-ups) with the unknown links. The listing only breaks ties and
orients the groups' names, as before.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar
from itertools import combinations

from .errors import StructureError
from .model import Mechanism, Prismatic
from .scene import FRAME, DriveKind

__all__ = ["Joint", "Group", "Pair", "Rod", "ComplexGroup", "DrivenGroup", "Structure", "analyse_structure", "FORMS",
           "MAX_DRIVEN_LINKS"]

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


def analyse_structure(mech: Mechanism) -> Structure:
    """Count W = 3n − 2·P5 − P4 and split the mechanism into Assur groups.

    Raises :class:`StructureError` when W differs from the number of drives (one), or when
    some links do not split into Assur groups of class II, III or IV.
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
    ix = _Index(mech)
    driven = _driven_group(ix, mech) if mech.drive.kind in (DriveKind.COUPLER, DriveKind.CYLINDER) else None
    groups = _decompose(ix, mech, {FRAME, *(driven.links if driven else (drive,))})
    return Structure(dof=dof, moving=n, p5=p5, p4=p4, drive=drive, groups=tuple(groups), driven=driven)


def _decompose(ix: "_Index", mech: Mechanism, known: set[str] | None = None) -> list["Group | ComplexGroup"]:
    """The Assur groups in the order they attach to the ``known`` links: the frame and the
    original mechanism (by default the driving link)."""
    known = {FRAME, mech.drive.link} if known is None else set(known)
    remaining = {name for name in mech.moving if name not in known}
    frontier = {x for k in known for x in ix.neighbours[k] if x in remaining}   # remaining links next to known ones
    groups: list[Group | ComplexGroup] = []
    while remaining:
        group = _first_dyad(ix, known, remaining, frontier)
        if group is None:
            group = _first_complex(ix, known, remaining, frontier)
        if group is None:
            raise StructureError(_no_split(ix, known, remaining), key="links")
        groups.append(group)
        known |= set(group.links)
        remaining -= set(group.links)
        frontier -= set(group.links)
        frontier |= {x for k in group.links for x in ix.neighbours[k] if x in remaining}
    return groups


def _no_split(ix: "_Index", known: set[str], remaining: set[str]) -> str:
    """Why ``remaining`` does not split: the links (abbreviated when many); the links held by
    two pairs on known links (locked); the parts of them, joined by pairs, that move on their
    own (W > 0 relative to the known links) or are locked (W < 0)."""
    def names(links, order=ix.rank.__getitem__) -> str:
        ordered = sorted(links, key=order)
        return ", ".join(ordered) if len(ordered) <= 12 else \
            f"{', '.join(ordered[:6])}, …, {', '.join(ordered[-3:])} ({len(ordered)} links)"

    parts = []
    for x in sorted(remaining, key=ix.rank.__getitem__):
        held = ix.joints(x, known)
        if len(held) >= 2 and len(parts) < 3:
            on = sorted({j.other for j in held}, key=ix.rank.__getitem__)
            parts.append(f"link {x} is held by {len(held)} pairs on link{'s' if len(on) > 1 else ''} "
                         f"{', '.join(on)} and cannot move (W = −{2 * len(held) - 3} of its own)")
    for part in ix.components(remaining):
        pairs = len(ix.pairs_of(part, part | known))
        w = 3 * len(part) - 2 * pairs
        if w > 0:
            parts.append(f"links {names(part)} can move without the drive (W = {w} of their own)")
        elif w < 0:
            parts.append(f"links {names(part)} are locked (W = −{-w} of their own)")
    why = ("; ".join(parts) + " — a pair is misplaced") if parts else \
        "they are not connected to them, or form a group of a higher class, which this version does not solve"
    return (f"links {names(remaining)} do not split into Assur groups of class II, III or IV attached to "
            f"links {names(known, order=None)}: {why}")


def _check_original_mechanism(mech: Mechanism) -> None:
    d = mech.drive
    if d.kind == DriveKind.ROTARY:
        return  # the pivot on the frame is checked when the model is built
    if d.kind == DriveKind.COUPLER:
        if any(FRAME in (p.slider, p.guide) and d.link in (p.slider, p.guide) for p in mech.prismatics):
            raise StructureError(f"the driving link {d.link} slides on the frame, so its angle cannot change: "
                                 "drive it by a displacement, or drive another link", key="drive.link")
        return
    along = d.guide.guide if d.guide is not None else FRAME
    if not any(p.slider == d.link and p.guide == along for p in mech.prismatics):
        where = "on the frame" if along == FRAME else f"in link {along}"
        raise StructureError(f"the driving slider {d.link} has no guide {where}", key="drive.link")


#: Most links solved together with a drive inside the chain (:class:`DrivenGroup`): the
#: original mechanism of a coupler drive on a six-bar has 3 to 5; the search over connected
#: link sets stops beyond this.
MAX_DRIVEN_LINKS = 6


def _driven_group(ix: "_Index", mech: Mechanism) -> "DrivenGroup":
    """The original mechanism of a drive inside the chain: the fewest links, connected, holding
    the driven link (and a cylinder's guide link), that are fixed by their pairs (among
    themselves and with the frame) together with the drive's one given coordinate:
    3·n − 2·p = 1. Ties go to the first in [links] order."""
    d = mech.drive
    core = frozenset({d.link} | ({d.guide.guide} if d.kind == DriveKind.CYLINDER else set()))
    level = {core}
    while level:
        fits = []
        for links in level:
            pairs = ix.pairs_of(set(links), set(links) | {FRAME})
            if 3 * len(links) - 2 * len(pairs) == 1 and len(ix.components(set(links))) == 1 \
                    and any(FRAME in (p.a, p.b) for p in pairs):
                fits.append(tuple(sorted(links, key=ix.rank.__getitem__)))
        if fits:
            links = min(fits, key=lambda t: [ix.rank[x] for x in t])
            inner = ix.pairs_of(set(links), set(links))
            outer = ix.pairs_of(set(links), {FRAME})
            return DrivenGroup(links=links, inner=tuple(inner), outer=tuple(outer), drive=d.link)
        if len(next(iter(level))) >= MAX_DRIVEN_LINKS:
            break
        level = {links | {x} for links in level for k in links for x in ix.adjacent[k] if x != FRAME and x not in links}
    what = f"link {d.link}" if d.kind == DriveKind.COUPLER else f"links {d.guide.guide} and {d.link}"
    raise StructureError(f"no set of up to {MAX_DRIVEN_LINKS} links with {what} is fixed by its pairs and the "
                         "drive's one coordinate (3n − 2p = 1): the drive does not move the chain; check its "
                         "pairs, or drive a crank on the frame", key="drive.link")


class _Index:
    """Who is joined to whom in a mechanism, built once per analysis.

    ``rank``: a link's place in [links] (the search's order); ``carriers``: the links carrying
    a point, in [links] order; ``sliding``: a link's prismatic pairs; ``neighbours``: the links
    sharing a point or a prismatic pair with a link; ``incident``: a link's pairs as the pair
    count of W has them (a pin of k links is k − 1 revolutes, see ``build_mechanism``), with
    their place in ``revolutes + prismatics``; ``adjacent``: the links those pairs join it to.
    """

    def __init__(self, mech: Mechanism):
        self.mech = mech
        self.rank = {name: i for i, name in enumerate(mech.links)}
        self.carriers: dict[str, list[str]] = {}
        for name, link in mech.links.items():
            for point in link.local:
                self.carriers.setdefault(point, []).append(name)
        self.sliding: dict[str, list[Prismatic]] = {name: [] for name in mech.links}
        for p in mech.prismatics:
            self.sliding[p.slider].append(p)
            if p.guide != p.slider:
                self.sliding[p.guide].append(p)
        self.neighbours: dict[str, set[str]] = {name: set() for name in mech.links}
        for name, link in mech.links.items():
            for point in link.points:
                self.neighbours[name].update(c for c in self.carriers[point] if c != name)
            self.neighbours[name].update(p.other(name) for p in self.sliding[name])
        # (place, link, other link, pin, prismatic) for each end of each pair
        self.incident: dict[str, list[tuple[int, str, str, str | None, Prismatic | None]]] = \
            {name: [] for name in mech.links}
        for i, r in enumerate(mech.revolutes):
            self.incident[r.a].append((i, r.a, r.b, r.point, None))
            self.incident[r.b].append((i, r.b, r.a, r.point, None))
        for i, p in enumerate(mech.prismatics, start=len(mech.revolutes)):
            self.incident[p.slider].append((i, p.slider, p.guide, None, p))
            self.incident[p.guide].append((i, p.guide, p.slider, None, p))
        self.adjacent: dict[str, set[str]] = {name: {e[2] for e in self.incident[name]} for name in mech.links}

    def joints(self, link: str, others: set[str]) -> list[Joint]:
        """The pairs joining ``link`` to any link of ``others`` (one joint per pin or slider)."""
        joints = []
        for point in self.mech.links[link].points:
            carrier = next((c for c in self.carriers[point] if c in others), None)
            if carrier is not None:
                joints.append(Joint("R", carrier, point=point))
        for p in self.sliding[link]:
            if p.other(link) in others:
                joints.append(Joint("P", p.other(link), prismatic=p))
        return joints

    def pairs_of(self, links: set[str], others: set[str]) -> list[Pair]:
        """Pairs joining a link of ``links`` to a link of ``others``, in the order of the
        mechanism's revolutes then prismatics (a pair inside ``links`` once, from its
        alphabetically first link)."""
        found = {}
        for link in links:
            for i, a, b, point, prismatic in self.incident[link]:
                if b in others and not (b in links and a > b):
                    found[i] = Pair("P" if prismatic is not None else "R", a, b, point=point, prismatic=prismatic)
        return [found[i] for i in sorted(found)]

    def count(self, link: str, others: set[str]) -> int:
        """How many pairs join ``link`` to links of ``others``."""
        return sum(e[2] in others for e in self.incident[link])

    def components(self, links: set[str]) -> list[set[str]]:
        """``links`` split into parts joined by pairs, in [links] order of their first links."""
        left, parts = set(links), []
        for start in sorted(links, key=self.rank.__getitem__):
            if start not in left:
                continue
            part, todo = {start}, [start]
            left.discard(start)
            while todo:
                for x in self.adjacent[todo.pop()]:
                    if x in left:
                        left.discard(x)
                        part.add(x)
                        todo.append(x)
            parts.append(part)
        return parts


def _first_dyad(ix: _Index, known: set[str], remaining: set[str], frontier: set[str]) -> Group | None:
    """The first pair of remaining links (in [links] order) that forms a class II group on
    the known links: two adjacent frontier links, each with one outer pair."""
    single = {x for x in frontier if len(ix.joints(x, known)) == 1}
    best = None
    for a in single:
        for b in ix.neighbours[a]:
            if b in single and ix.rank[a] < ix.rank[b] and (best is None or (ix.rank[a], ix.rank[b]) < best[0]) \
                    and _dyad_fit(ix, known, a, b):
                best = ((ix.rank[a], ix.rank[b]), a, b)
    return None if best is None else _dyad(ix, known, best[1], best[2])


def _dyad_fit(ix: _Index, known: set[str], a: str, b: str) -> tuple[Joint, Joint, Joint] | None:
    """The outer pairs of ``a`` and ``b`` and their inner pair, if they form a class II group
    on the known links (a listed before b)."""
    outer_a, outer_b = ix.joints(a, known), ix.joints(b, known)
    # a pin shared by a, b and a known link fixes both a and b there: two outer pairs, no inner one
    inner = [j for j in ix.joints(a, {b}) if not (j.kind == "R" and any(o.point == j.point for o in outer_a))]
    if len(outer_a) != 1 or len(outer_b) != 1 or len(inner) != 1:
        return None
    return outer_a[0], inner[0], outer_b[0]


def _dyad(ix: _Index, known: set[str], a: str, b: str) -> Group | None:
    fit = _dyad_fit(ix, known, a, b)
    if fit is None:
        return None
    (d, e, f), m, n = fit, a, b
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


def _first_complex(ix: _Index, known: set[str], remaining: set[str],
                   frontier: set[str]) -> ComplexGroup | None:
    """The first four remaining links (in [links] order) that form a class III or IV group on
    the known links. Candidates: a base link with no outer pair and three rods, each joined to
    it and to the known links by one pair (class III); a contour of four links through a link
    with an outer pair (class IV); :func:`_complex` decides."""
    outer = {x: ix.count(x, known) for x in frontier}
    candidates: set[frozenset[str]] = set()
    rods = {x for x, k in outer.items() if k == 1}
    for base in {b for r in rods for b in ix.adjacent[r] if b in remaining and not outer.get(b)}:
        arms = sorted((r for r in ix.adjacent[base] if r in rods and ix.count(r, {base}) == 1), key=ix.rank.__getitem__)
        candidates.update(frozenset((base, *three)) for three in combinations(arms, 3))
    for a in (x for x, k in outer.items() if 1 <= k <= 2):
        for b in ix.adjacent[a] & remaining:
            for c in ix.adjacent[b] & remaining - {a}:
                for d in ix.adjacent[c] & remaining - {a, b}:
                    if a in ix.adjacent[d]:
                        candidates.add(frozenset((a, b, c, d)))
    ordered = sorted((tuple(sorted(c, key=ix.rank.__getitem__)) for c in candidates),
                     key=lambda four: [ix.rank[x] for x in four])      # the order of combinations()
    return next((g for four in ordered if (g := _complex(ix, known, four))), None)


def _complex(ix: _Index, known: set[str], four: tuple[str, ...]) -> ComplexGroup | None:
    """The class III or IV group formed by links ``four`` on the ``known`` links, if any."""
    links = set(four)
    inner = ix.pairs_of(links, links)
    outer = ix.pairs_of(links, known)
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
        contour = _contour(inner)
        return None if contour is None else ComplexGroup(links=four, inner=tuple(contour), outer=tuple(outer),
                                                         klass=4)
    return None


def _contour(inner: list[Pair]) -> list[Pair] | None:
    """The four inner pairs of a class IV group in order around the contour; None when they
    do not close one contour (two links joined twice, and two others)."""
    ordered = [inner[0]]
    rest = inner[1:]
    link = inner[0].b
    while rest:
        nxt = next((p for p in rest if link in (p.a, p.b)), None)
        if nxt is None:
            return None
        rest.remove(nxt)
        ordered.append(Pair(nxt.kind, link, nxt.other(link), nxt.point, nxt.prismatic))
        link = nxt.other(link)
    return ordered

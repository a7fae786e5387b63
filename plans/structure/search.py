"""The decomposition search: Chebyshev's W, the original mechanism, the Assur groups in order.

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

Imports only plans.errors, plans.model, plans.scene and the structure package's value types
and index; must not import kinematics or anything above the structure layer.
"""

from __future__ import annotations

from bisect import bisect_left, insort
from itertools import combinations
from typing import Iterator

from ..errors import StructureError
from ..model import Mechanism
from ..scene import FRAME, DriveKind
from .groups import FORMS, ComplexGroup, DrivenGroup, Group, Joint, Pair, Structure
from .index import _Index


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
    held = _Held(ix, known, remaining)
    groups: list[Group | ComplexGroup] = []
    while remaining:
        group = _first_dyad(ix, known, remaining, held.frontier, held)
        if group is None:
            group = _first_complex(ix, known, remaining, set(held.frontier))
        if group is None:
            raise StructureError(_no_split(ix, known, remaining), key="links")
        groups.append(group)
        known |= set(group.links)
        remaining -= set(group.links)
        for k in group.links:
            held.learn(k)
    return groups


class _Held:
    """How many joints each remaining link has on the known links (``len(ix.joints(x, known))``),
    kept up to date as links become known (:meth:`learn`): a pin counts for its carriers when
    its first carrier becomes known, a slider when one of its two links does, so the search
    reads each pin and slider a bounded number of times, however many links share a pin.
    ``frontier``: the remaining links with a joint on the known ones (link → how many)."""

    def __init__(self, ix: _Index, known: set[str], remaining: set[str]):
        self.ix, self.remaining = ix, remaining
        self.frontier: dict[str, int] = {}
        self._carried: set[str] = set()
        self._names = list(ix.rank)
        self._single: list[int] = []          # ranks of the frontier links with one joint, ascending
        for k in known:
            self.learn(k)

    def single(self) -> Iterator[str]:
        """The frontier links with exactly one joint on the known ones, in [links] order."""
        return (self._names[r] for r in self._single)

    def learn(self, link: str) -> None:
        """``link`` is known now (and no longer remaining)."""
        if self.frontier.pop(link, 0) == 1:
            del self._single[bisect_left(self._single, self.ix.rank[link])]
        for point in self.ix.mech.links[link].points:
            if point not in self._carried:
                self._carried.add(point)
                for x in self.ix.carriers[point]:
                    self._bump(x)
        for p in self.ix.sliding[link]:
            self._bump(p.other(link))

    def _bump(self, x: str) -> None:
        if x not in self.remaining:
            return
        count = self.frontier[x] = self.frontier.get(x, 0) + 1
        rank = self.ix.rank[x]
        if count == 1:
            insort(self._single, rank)
        elif count == 2:
            del self._single[bisect_left(self._single, rank)]


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


def _first_dyad(ix: _Index, known: set[str], remaining: set[str], frontier,
                held: "_Held | None" = None) -> Group | None:
    """The first pair of remaining links (in [links] order) that forms a class II group on
    the known links: two adjacent frontier links, each with one outer pair. The links are
    tried in that order and the first fit ends the search (a pin shared by many links makes
    every pair of them adjacent: trying them all would cost their number squared).
    ``held``: the joint counts kept by :func:`_decompose` (else counted here)."""
    if held is None:
        order = sorted((x for x in frontier if len(ix.joints(x, known)) == 1), key=ix.rank.__getitem__)
        is_single = set(order).__contains__
    else:
        order, counts = held.single(), held.frontier
        is_single = lambda x: counts.get(x) == 1    # noqa: E731
    for a in order:
        for b in ix.later_neighbours(a):
            if is_single(b) and _dyad_fit(ix, known, a, b):
                return _dyad(ix, known, a, b)
    return None


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

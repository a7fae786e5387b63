"""Velocity and acceleration plans as geometry in plan millimetres (pole at the origin, y up).

The image of a point X is v_X/μV (a_X/μa). Each vector of the plan is a
:class:`PlanVector` tagged with its quantity:

- ``v:X``, ``a:X`` — absolute velocity / acceleration of scene point X (from the pole);
- ``v:X/Y`` — velocity of X relative to Y, both on one link (⊥ XY);
- ``a:X/Y:n`` — normal component ω²·XY, from y towards n, directed X → Y;
- ``a:X/Y:t`` — tangential component ε·XY, from n to x, ⊥ XY;
- ``a:X/Y`` — the whole relative acceleration |a_X − a_Y|, from y to x: drawn for every
  rigid relation of the plan beside its components (as the textbook draws a→b beside
  a→n_BA→b), for the similarity images of extra points, and for the sides of similar
  figures; left out where the absolute ``a:X`` draws that very segment (y at the pole: Y
  fixed, or its acceleration zero now), where one component is zero (the other one is the
  whole), and relative to a special point S (no side of the link);
- ``v:P3/P2`` — velocity of the point P of guide link 3 relative to the coincident point
  of slider link 2 (∥ guide); ``a:P3/P2:cor`` the Coriolis component 2·ω × v_rel (to
  point k), ``a:P3/P2:r`` the relative sliding acceleration (∥ guide, from k).

A point name followed by a link name (``A3``) is the point of that link now at X.

How the plans are built (:func:`_plan`, one :class:`_Builder` per plan): the relations of
:func:`relations`, group by group, each drawn as its vector(s) and the construction line of
the direction that defines an image (a group's two lines meet at the image they find);
then the class III groups' special-point route (:func:`_special`); the absolute vectors;
then the sides still missing of every link's similar figure (:func:`_close_figures`),
so the images of a link with three or more points always form a closed polygon of vectors
on both plans; last, each segment is kept once (:meth:`_Builder.finish`): no quantity is
drawn twice, and no relative vector retraces an absolute one, either way (a point
momentarily at rest has its image at the pole; the vector into it is the absolute one
reversed). No vector ends at the image of a fixed point.

- **Class II** groups: their pairs' relations (rigid, sliding with Coriolis).
- **Class III** groups, *one* route through one special point S (the meeting point of the
  axes of rods i and j; the best conditioned of the three): s from the two directions ⊥
  those axes through the rods' known images; the third rod's pin k from s (⊥ S–k) and its
  rod's own line; the pins of rods i and j from k (⊥ k–pin) and their rods' own lines; each
  pin's two lines form the group ``III(…):B``. The other routes (the other special points)
  are not drawn: the whole group is solved a second way, numerically, as a cross-check
  (:attr:`plans.kinematics.Motion.triad_disagreement`).
- **Class IV** groups: each link with an outer pair O gives its other pins relative to O, and
  each link without one gives its pin on the far side relative to the pin nearer the frame;
  every relation gets its construction line (group ``IV(…):X`` per image x) and, on the
  acceleration plan, n and τ components and the total, like a class II rigid relation. No
  relation ends at a fixed point (one from the frame pivot starts at the pole, along the
  absolute vector, like the four-bar's ``v:B/C``), and no quantity is drawn twice.

**Labels.** Images of scene points are their lower-case names (``b``, ``a3``); the pole is
``p`` or ``π``; special points ``s1``. Ends of components are ``n_XY`` (normal) and
``k_XY`` (Coriolis), printed as the letter n or k with the subscript XY. Images of scene
points win: when any image of the plan is printed with the letter n (a point N, or a point
named ``n_…``), every normal component's end is written ``n′_XY`` instead (``n″`` if ``n′``
is taken too, and so on), and likewise ``k′_XY`` for the Coriolis ends in a scene with a
point K, so a printed letter never means both a point's image and a component's end. Images
are keyed by identity (:meth:`_Builder.put`), and a label repeating another gets a prime.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import count

import numpy as np

from ..errors import ConstructionError
from ..kinematics import Motion, special
from ..kinematics.sliders import Sliding
from ..kinematics.state import J
from ..scene import FRAME, DriveKind
from ..structure import ComplexGroup, DrivenGroup

__all__ = ["PlanPoint", "PlanVector", "ConstructionLine", "Plan", "Relation", "relations",
           "velocity_plan", "acceleration_plan", "uncertain_plan", "EXTENSION_MM", "UNCERTAIN_MM"]

#: How far a construction line runs beyond the points it passes through, mm.
EXTENSION_MM = 12.0
#: Vectors shorter than this are not drawn (their value is zero to drawing precision), mm.
MIN_DRAWN_MM = 1e-6


@dataclass(frozen=True)
class PlanPoint:
    """An image on a plan: label (``b``, ``a3``, ``n_BA``, ``k_A3A2``) and position (mm)."""

    label: str
    xy: tuple[float, float]


@dataclass(frozen=True)
class PlanVector:
    """A drawn vector: ``quantity`` tag, tail and head (mm), exact magnitude ``value`` (SI)."""

    quantity: str
    tail: tuple[float, float]
    head: tuple[float, float]
    value: float
    kind: str  # absolute, relative, normal, tangential, coriolis, sliding

    @property
    def length(self) -> float:
        return float(np.hypot(self.head[0] - self.tail[0], self.head[1] - self.tail[1]))


@dataclass(frozen=True)
class ConstructionLine:
    """A line of known direction through a known image: its two end points (mm), and the
    tag of the vector that must lie on it."""

    start: tuple[float, float]
    end: tuple[float, float]
    quantity: str
    group: str


@dataclass(frozen=True)
class Plan:
    """One plan at one position: ``kind`` is ``velocity`` or ``acceleration``."""

    kind: str
    mu: float
    pole: str
    points: tuple[PlanPoint, ...]
    vectors: tuple[PlanVector, ...]
    lines: tuple[ConstructionLine, ...]
    similar: tuple[tuple[str, tuple[str, ...]], ...]  # link → labels of its images (similarity)

    def point(self, label: str) -> tuple[float, float]:
        return next(p.xy for p in self.points if p.label == label)


@dataclass(frozen=True)
class Relation:
    """A relative motion drawn on the plans.

    ``rigid``: point ``x`` relative to point ``y`` on ``link`` (``pair`` True when it is one
    of the group's equations, False for a similarity image). ``slide``: the guide's point
    relative to the slider's point at ``x`` (``frame``: the guide or slider is the frame, so
    only a construction line through the pole is drawn). ``lines``: the group of its
    construction line, when it is not ``group`` (the image it helps find, ``III(…):B``).
    """

    kind: str
    link: str
    x: str
    y: str
    group: str
    other: str = ""
    pair: bool = True
    lines: str = ""     # group of its construction line when not ``group`` (class III/IV: per image)

    @property
    def line_group(self) -> str:
        return self.lines or self.group


def relations(motion: Motion) -> tuple[Relation, ...]:
    """The relative motions that build the plans, group by group in solving order."""
    mech, structure = motion.mechanism, motion.structure
    out: list[Relation] = []
    d = mech.drive
    constructed: set[tuple[str, str]] = set()
    if d.kind == DriveKind.ROTARY:
        out.append(Relation("rigid", d.link, d.tip, d.pivot, group="I"))
    elif d.kind == DriveKind.LINEAR:
        out.append(Relation("slide", d.link, d.guide.label, "", group="I", other=FRAME))
    else:   # a drive inside the chain: the original mechanism's relations, drawn as a class IV group's
        g = structure.driven
        out += _driven_relations(g)
        constructed |= {(link, p.point) for p in g.pairs if p.kind == "R" for link in (p.a, p.b) if link in g.links}
    for g in structure.groups:
        name = g.name
        if g.klass > 2:            # class III and IV: the group's own relations
            out += _complex_relations(g)
            if special.supports(g):
                constructed |= {(g.base, p.point) for p in g.inner if p.kind == "R"}
            if g.base is None:   # class IV: every pin's image comes from the group's relations
                constructed |= {(link, p.point) for p in g.pairs if p.kind == "R" for link in (p.a, p.b)
                                if link in g.links}
            continue
        # every sliding relation of a group is written for the one point whose image the
        # group's construction finds: the pin E (RRP, PRP) or the outer pin D (RPR, RPP);
        # two relations for different points of a turning link would meet at no image
        at = g.e.point if g.e.kind == "R" else g.d.point
        for joint in (g.d, g.e, g.f):
            if joint.kind == "P":
                pr = joint.prismatic
                out.append(Relation("slide", pr.slider, at, "", group=name, other=pr.guide))
        if g.d.kind == "R" and g.e.kind == "R":
            out.append(Relation("rigid", g.m, g.e.point, g.d.point, group=name))
        if g.f.kind == "R" and g.e.kind == "R":
            out.append(Relation("rigid", g.n, g.e.point, g.f.point, group=name))
        if g.form == "RPR":
            out.append(Relation("rigid", g.n, g.d.point, g.f.point, group=name))
    fixed = set(mech.links[FRAME].points)
    for link in mech.moving:
        pts = mech.links[link].points
        joints = [p for p in pts if len([l for l in mech.links.values() if p in l.local]) > 1]
        bases = joints[:2] if joints else list(pts[:1])
        for p in pts:
            if p not in bases and (link, p) not in constructed:  # similarity images, relative to the link's moving base points
                out += [Relation("rigid", link, p, b, group=link, pair=False) for b in bases if b not in fixed]
    return tuple(out)


def _complex_relations(g: ComplexGroup) -> list[Relation]:
    """Class III: each rod's relative motion (its pin relative to its outer pair); the base
    link's pins are built from one special point at each position (:func:`_special`).
    Class IV: a link with an outer pair O gives each of its other pins X relative to O; a link
    without one, its two pins, the one farther from the frame relative to the nearer one (so no
    relation ends at a fixed point). Every relation is drawn like a group's pair (construction
    line, n and τ components): the lines of the relations ending at one pin x form the group
    ``IV(…):X`` (two lines through the known images, meeting at x)."""
    out = []
    lines = {}
    if g.base is not None:
        for rod in g.rods:       # a rod's sliding line is one of the two that find its base point
            if rod.form == "PR":
                lines[rod.outer.prismatic] = f"{g.name}:{rod.inner.point}"
            elif rod.form == "RP":   # the base link's point under the rod's outer pin
                lines[rod.inner.prismatic] = f"{g.name}:{rod.outer.point}{g.base}"
    for pair in g.pairs:
        if pair.kind == "P":
            pr = pair.prismatic
            out.append(Relation("slide", pr.slider, pr.label, "", group=g.name, other=pr.guide,
                                lines=lines.get(pr, "")))
    if g.base is not None:
        for rod in g.rods:
            if rod.form == "RR":
                out.append(Relation("rigid", rod.link, rod.inner.point, rod.outer.point, group=g.name,
                                    lines=f"{g.name}:{rod.inner.point}"))
        return out
    outer = {p.a if p.a in g.links else p.b: p for p in g.outer}
    pins = {link: [p.point for p in g.pairs if p.kind == "R" and link in (p.a, p.b)] for link in g.links}
    # distance (in links) of a pin from the frame through the group's outer pairs: pins of a
    # link pinned to the frame first, then those of the other outer links, then the rest
    rank: dict[str, int] = {}
    for link, o in sorted(outer.items(), key=lambda lo: FRAME not in (lo[1].a, lo[1].b)):
        for x in pins[link]:
            rank.setdefault(x, 0 if FRAME in (o.a, o.b) else 1)
    for link in g.links:
        o = outer.get(link)
        if o is not None and o.kind == "R":
            out += [Relation("rigid", link, x, o.point, group=g.name, lines=f"{g.name}:{x}")
                    for x in pins[link] if x != o.point]
        else:
            inner = [x for x in pins[link] if o is None or x != o.point]
            if len(inner) < 2:
                continue
            y = min(inner, key=lambda x: rank.get(x, 2))
            out += [Relation("rigid", link, x, y, group=g.name, lines=f"{g.name}:{x}") for x in inner if x != y]
    return out


def _driven_relations(g: DrivenGroup) -> list[Relation]:
    """The original mechanism of a drive inside the chain: its pairs' relations as for a
    class IV group (:func:`_complex_relations`), and for each sliding pair whose guide link
    turns about an outer pin O, the guide's point at the pair relative to O (v_B2 ⊥ AB of a
    cylinder swinging about A), from which the slider's image follows along the guide."""
    out = _complex_relations(g)
    outer = {p.a: p for p in g.outer if p.kind == "R"}
    for pair in g.pairs:
        if pair.kind == "P" and pair.prismatic.guide in outer:
            pr, o = pair.prismatic, outer[pair.prismatic.guide]
            out.append(Relation("rigid", pr.guide, pr.label, o.point, group=g.name,
                                lines=f"{g.name}:{pr.label}{pr.guide}"))
    return out


def _label(motion: Motion, point: str, link: str) -> str:
    """``B`` when ``link`` carries B, else ``B3`` (the point of link 3 now at B)."""
    return point if point in motion.mechanism.links[link].local else f"{point}{link}"


#: Marks a plan label that would otherwise repeat another (a point named P beside the pole p).
PRIME = "′"
#: Kinds of component ends (image keys) and their letters: normal ``n``, Coriolis ``k``.
COMPONENT_ENDS = ("n", "k")


class _Builder:
    """Collects a plan's images, vectors and lines. Images are keyed by what they are (the
    pole, the image of point X of link L, an n or k end), never by their printed label, so a
    point named ``P`` or ``n_BA`` cannot land on the pole or on a component's end; labels are
    made unique only when the plan is finished (:meth:`plan_points`)."""

    def __init__(self, motion: Motion, i: int, mu: float, kind: str):
        self.motion, self.i, self.mu, self.kind = motion, i, mu, kind
        self.points: dict[tuple, tuple[float, float]] = {}
        self.names: dict[tuple, str] = {}
        self.vectors: list[PlanVector] = []
        self.lines: list[ConstructionLine] = []
        self.extra: dict[str, np.ndarray] = {}   # constructed points (special points S1…): world position
        self.optional: set[str] = set()          # relative vectors left out where an absolute one draws them

    def put(self, key: tuple, label: str, xy) -> tuple[float, float]:
        """Record an image (first one wins) under ``key``, printed as ``label``."""
        if key not in self.points:
            self.points[key] = tuple(float(c) for c in xy)
            self.names[key] = label
        return self.points[key]

    def image_key(self, point: str, link: str) -> tuple:
        if point in self.extra:
            return ("img", point, "")
        return ("img", point, "" if point in self.motion.mechanism.links[link].local else link)

    def plan_points(self) -> tuple[tuple[PlanPoint, ...], dict[tuple, str]]:
        """The images with unique labels (a repeat gets primes, in the order drawn) and the
        label each key got. The pole and the images of points are labelled first; the ends of
        components (keys ``n``, ``k``) then take a letter no image is printed with (n, else
        n′, n″ …; k likewise), so a printed letter never names two things."""
        taken: set[str] = set()
        final: dict[tuple, str] = {}
        ends = [k for k in self.points if k[0] in COMPONENT_ENDS]
        for key in self.points:
            if key[0] not in COMPONENT_ENDS:
                final[key] = self._unique(self.names[key], taken)
        printed = {label.partition("_")[0] for label in final.values()}   # as drawn: letter, subscript
        letters = {}
        for kind in COMPONENT_ENDS:
            letters[kind] = kind
            while letters[kind] in printed:
                letters[kind] += PRIME
        for key in ends:
            label = self.names[key]
            final[key] = self._unique(letters[key[0]] + label[len(key[0]):], taken)
        return tuple(PlanPoint(final[k], xy) for k, xy in self.points.items()), final

    @staticmethod
    def _unique(label: str, taken: set[str]) -> str:
        while label in taken:
            label += PRIME
        taken.add(label)
        return label

    def fixed(self, point: str, link: str) -> bool:
        """True when ``link``'s point at ``point`` is a pair with the frame (its image is the pole)."""
        links = self.motion.mechanism.links
        return point not in self.extra and link != FRAME and point in links[FRAME].local and point in links[link].local

    def world(self, point: str) -> np.ndarray:
        if point in self.extra:
            return self.extra[point]
        return self.motion.position(point)[self.i]

    def label(self, point: str, link: str) -> str:
        return point if point in self.extra else _label(self.motion, point, link)

    def quantity(self, point: str, link: str) -> np.ndarray:
        """v (m/s) or a (m/s²) of the point of ``link`` now at ``point``, as the motion gives it."""
        at = self.motion.velocity_at if self.kind == "velocity" else self.motion.acceleration_at
        return at(link, self.world(point), self.i)

    def slide(self, slider: str, guide: str) -> Sliding:
        """The kinematics' sliding of ``slider`` along ``guide`` (the first such pair, as
        the plans take it)."""
        return next(s for s in self.motion.sliding.values() if s.slider == slider and s.guide == guide)

    def image(self, point: str, link: str) -> tuple[float, float]:
        key = self.image_key(point, link)
        if key in self.points:
            return self.points[key]
        return self.put(key, self.label(point, link).lower(), self.quantity(point, link) / self.mu)

    def vector(self, quantity: str, tail, head, value: float, kind: str, optional: bool = False) -> bool:
        """Draw a vector (not when shorter than MIN_DRAWN_MM: returns whether it is drawn);
        ``optional``: a relative vector left out if an absolute vector draws the same segment
        (:meth:`finish`)."""
        if np.hypot(head[0] - tail[0], head[1] - tail[1]) <= MIN_DRAWN_MM:
            return False
        self.vectors.append(PlanVector(quantity, tuple(tail), tuple(head), float(value), kind))
        if optional:
            self.optional.add(quantity)
        return True

    def finish(self) -> None:
        """Each segment drawn once: an optional relative vector that an absolute vector draws
        (y at the pole) is left out, and so is a relative vector into the pole (its point
        momentarily at rest) that an absolute vector draws the other way."""
        absolute = [v for v in self.vectors if v.kind == "absolute"]

        def redundant(v: PlanVector) -> bool:
            if v.kind != "relative":
                return False
            if v.quantity in self.optional and _at_pole(v.tail):
                return any(_same(w.head, v.head) for w in absolute)
            return _at_pole(v.head) and any(_same(w.head, v.tail) for w in absolute)

        self.vectors = [v for v in self.vectors if not redundant(v)]

    def line(self, through, direction: np.ndarray, reach, quantity: str, group: str) -> None:
        """A construction line through ``through`` with ``direction``, covering points ``reach``."""
        u = direction / np.linalg.norm(direction)
        t = [float(np.dot(np.subtract(r, through), u)) for r in reach] + [0.0]
        a = np.add(through, (min(t) - EXTENSION_MM) * u)
        b = np.add(through, (max(t) + EXTENSION_MM) * u)
        self.lines.append(ConstructionLine(tuple(map(float, a)), tuple(map(float, b)), quantity, group))


def velocity_plan(motion: Motion, i: int, mu_v: float) -> Plan:
    """The velocity plan at position ``i`` in scale ``mu_v`` ((m/s)/mm)."""
    return _plan(motion, i, mu_v, "velocity")


def acceleration_plan(motion: Motion, i: int, mu_a: float) -> Plan:
    """The acceleration plan at position ``i`` in scale ``mu_a`` ((m/s²)/mm)."""
    return _plan(motion, i, mu_a, "acceleration")


def _plan(motion: Motion, i: int, mu: float, kind: str) -> Plan:
    b = _Builder(motion, i, mu, kind)
    mech = motion.mechanism
    sym = "v" if kind == "velocity" else "a"
    pole = b.put(("pole",), "p" if kind == "velocity" else "π", (0.0, 0.0))
    for rel in relations(motion):
        if rel.kind == "rigid":
            _rigid(b, rel, sym)
        else:
            _slide(b, rel, sym, pole)
    for g in special.triad_groups(motion.structure):
        _special(b, g, sym)
    for name in mech.sketch:  # absolute vectors of every moving scene point
        link = motion.carrier(name)
        if link == FRAME:
            continue
        head = b.image(name, link)
        b.vector(f"{sym}:{name}", pole, head, float(np.linalg.norm(b.quantity(name, link))), "absolute")
    _close_figures(b, sym)
    b.finish()
    points, final = b.plan_points()
    similar = tuple((link, tuple(final[b.image_key(p, link)] for p in mech.links[link].points))
                    for link in mech.moving if len(mech.links[link].points) >= 3)
    return Plan(kind=kind, mu=mu, pole=final[("pole",)], points=points,
                vectors=tuple(b.vectors), lines=tuple(b.lines), similar=similar)


def _rigid(b: _Builder, rel: Relation, sym: str) -> None:
    motion, link = b.motion, rel.link
    xl, yl = b.label(rel.x, link), b.label(rel.y, link)
    tail, head = b.image(rel.y, link), b.image(rel.x, link)
    r = b.world(rel.x) - b.world(rel.y)   # the link's segment Y → X, m
    state = motion.links[link]
    q = f"{sym}:{xl}/{yl}"
    if sym == "v" or not rel.pair:
        if rel.group == "I" and sym == "v":
            return  # the crank tip's velocity relative to the fixed pivot is its absolute velocity
        value = float(np.linalg.norm(b.quantity(rel.x, link) - b.quantity(rel.y, link)))
        b.vector(q, tail, head, value, "relative", optional=not rel.pair)
        if rel.pair:
            b.line(tail, J(r), [head], q, rel.line_group)
        return
    w, e = float(state.omega[b.i]), float(state.epsilon[b.i])
    normal = -w * w * r
    if rel.group == "I" and e == 0.0:
        return  # a crank turning uniformly: πa is the normal component itself
    n_xy = b.put(("n", xl, yl), f"n_{xl}{yl}", np.add(tail, normal / b.mu))
    both = b.vector(f"{q}:n", tail, n_xy, float(np.linalg.norm(normal)), "normal")
    both &= b.vector(f"{q}:t", n_xy, head, abs(e) * float(np.linalg.norm(r)), "tangential")
    b.line(n_xy, J(r), [head], f"{q}:t", rel.line_group)
    # the whole relative acceleration a→b beside its components (the textbook's a_BA); left
    # out where the absolute a:X draws that very segment (y at the pole), where one component
    # is zero (the other is the whole), and never from a special point (no side of the link)
    if both and rel.y not in b.extra:
        b.vector(q, tail, head, float(np.linalg.norm(b.quantity(rel.x, link) - b.quantity(rel.y, link))), "relative",
                 optional=True)


def _at_pole(xy) -> bool:
    return float(np.hypot(xy[0], xy[1])) <= MIN_DRAWN_MM


def _same(p, q) -> bool:
    return float(np.hypot(p[0] - q[0], p[1] - q[1])) <= MIN_DRAWN_MM


def _close_figures(b: _Builder, sym: str) -> None:
    """The sides still missing of every link's similar figure (three or more points): the
    polygon of its images in the link's order, each side a relative vector ``v:Q/P`` (from
    the earlier point, or from a fixed point: no side ends at the pole) unless a vector of
    the plan already joins the two images."""
    motion = b.motion
    drawn = {v.quantity for v in b.vectors}

    def joined(p, q) -> bool:
        return any((_same(v.tail, p) and _same(v.head, q)) or (_same(v.tail, q) and _same(v.head, p))
                   for v in b.vectors)

    for link in motion.mechanism.moving:
        pts = motion.mechanism.links[link].points
        if len(pts) < 3:
            continue
        for k, y in enumerate(pts):
            x = pts[(k + 1) % len(pts)]
            if b.fixed(x, link) or (_at_pole(b.image(x, link)) and not _at_pole(b.image(y, link))):
                x, y = y, x       # never a side into the pole
            tail, head = b.image(y, link), b.image(x, link)
            q = f"{sym}:{b.label(x, link)}/{b.label(y, link)}"
            if q in drawn or joined(tail, head):
                continue
            b.vector(q, tail, head, float(np.linalg.norm(b.quantity(x, link) - b.quantity(y, link))), "relative")
            drawn.add(q)


def _solved_before(motion: Motion, link: str, group: str) -> bool:
    """True when ``link`` is known before group ``group`` is solved (driver, frame, or a
    link of an earlier group)."""
    for g in motion.structure.groups:
        if g.name == group:
            return link not in g.links
    return True


def _slide(b: _Builder, rel: Relation, sym: str, pole) -> None:
    motion, slider, guide = b.motion, rel.link, rel.other
    pr = next(p for p in motion.mechanism.prismatics if p.slider == slider and p.guide == guide)
    u = motion.links[guide].direction(pr.direction)[b.i]
    if FRAME in (slider, guide):
        moving = slider if guide == FRAME else guide
        b.line(pole, u, [b.image(rel.x, moving)], f"{sym}:{_label(motion, rel.x, moving)}", rel.line_group)
        return
    # the construction starts from the image already known: the guide's when it was solved
    # before the group (a slider of the group on a known turning guide), the slider's when it
    # was; within the group, that of the link carrying the pair's point (the block pinned there)
    if _solved_before(motion, guide, rel.group):
        known, moving = guide, slider
    elif _solved_before(motion, slider, rel.group) or rel.x in motion.mechanism.links[slider].local:
        known, moving = slider, guide
    else:
        known, moving = guide, slider
    kl, ml = f"{rel.x}{known}", f"{rel.x}{moving}"
    tail, head = b.image(rel.x, known), b.image(rel.x, moving)
    q = f"{sym}:{ml}/{kl}"
    if sym == "v":
        value = float(np.linalg.norm(b.quantity(rel.x, moving) - b.quantity(rel.x, known)))
        b.vector(q, tail, head, value, "relative")
        b.line(tail, u, [head], q, rel.line_group)
        return
    # a_moving = a_known + a^k + a^r: the kinematics gives the slider's Coriolis term relative
    # to the guide, 2 ω_guide × σu, and σ̇ along the guide; the guide relative to the slider
    # has both with the opposite sign
    slide = b.slide(slider, guide)
    sense = 1.0 if moving == slider else -1.0
    coriolis = sense * slide.coriolis[b.i]
    k_xy = b.put(("k", ml, kl), f"k_{ml}{kl}", np.add(tail, coriolis / b.mu))
    b.vector(f"{q}:cor", tail, k_xy, float(np.linalg.norm(coriolis)), "coriolis")
    b.vector(f"{q}:r", k_xy, head, abs(float(slide.a[b.i])), "sliding")
    b.line(k_xy, u, [head], f"{q}:r", rel.line_group)


def _special(b: _Builder, g: ComplexGroup, sym: str) -> None:
    """A class III group along one route, as with ruler and set square: the special point S
    (meeting point of the axes of rods i and j, a point of the base link) from the known
    images of the two rods' outer pairs along the two directions ⊥ the axes; the third rod's
    pin k from s (⊥ S–k) and its rod's own line (drawn with the group's relations); then the
    pins of rods i and j from k (⊥ k–pin), each with its rod's own line (its axis passes
    through S, so s gives it no second direction). The route is the one whose line pairs are
    the farthest from parallel (:func:`_route`); the base triangle is closed by
    :func:`_close_figures`. The axes, special points and known acceleration terms are the
    motion's (:attr:`~plans.kinematics.Motion.special_points`)."""
    motion, i = b.motion, b.i
    mech = motion.mechanism
    found = motion.special_points[g.name]
    ax = found.axes
    route = _route(ax, found.points, i)
    p = found.points[route]
    # S1, S2, S3 — primed if the scene has points of those names
    s_name = p.name + PRIME * next(k for k in count() if p.name + PRIME * k not in mech.sketch)
    b.extra[s_name] = p.position[i]
    s_img = b.image(s_name, g.base)
    for r in p.rods:
        rod = ax[r].rod
        pin = rod.inner.point if rod.form == "PR" else rod.outer.point
        k_lab = b.label(pin, ax[r].known)
        k_img = b.image(pin, ax[r].known)
        e = ax[r].normal[i]
        q = f"{sym}:{s_name}/{k_lab}"
        total = b.quantity(s_name, g.base) - b.quantity(pin, ax[r].known)
        if sym == "v":
            b.vector(q, k_img, s_img, float(np.linalg.norm(total)), "relative")
            b.line(k_img, e, [s_img], q, f"{g.name}:{s_name}")
            continue
        c = found.known[(route, r)][i] - b.quantity(pin, ax[r].known)      # normal (and Coriolis) components, known
        n_xy = b.put(("n", s_name, k_lab), f"n_{s_name}{k_lab}", np.add(k_img, c / b.mu))
        b.vector(f"{q}:n", k_img, n_xy, float(np.linalg.norm(c)), "normal")
        b.vector(f"{q}:t", n_xy, s_img, float(np.linalg.norm(total - c)), "tangential")
        b.line(n_xy, e, [s_img], f"{q}:t", f"{g.name}:{s_name}")
    third = next(r for r in range(3) if r not in p.rods)
    pins = [_base_point(x) for x in ax]
    _rigid(b, Relation("rigid", g.base, pins[third], s_name, group=g.name,
                       lines=f"{g.name}:{b.label(pins[third], g.base)}"), sym)
    for r in p.rods:
        _rigid(b, Relation("rigid", g.base, pins[r], pins[third], group=g.name,
                           lines=f"{g.name}:{b.label(pins[r], g.base)}"), sym)


def _base_point(ax: special.Axis) -> str:
    """The base link's point on a rod's axis whose image the rod's own line finds: the inner
    pin (R–R, P–R), or the point of the base under the outer pin (R–P)."""
    rod = ax.rod
    return rod.inner.point if rod.inner.kind == "R" else rod.outer.point


def _route(ax: tuple[special.Axis, ...], pts: tuple[special.SpecialPoint, ...], i: int) -> int:
    """Index of the special point to draw from at position i: each route meets four pairs of
    lines (s; the third pin from s; the two other pins from it), the route whose worst pair is
    the farthest from parallel (largest smallest |sin|) is drawn."""
    def sin(u: np.ndarray, d: np.ndarray) -> float:   # |sin| between a segment u and a unit direction d
        n = float(np.linalg.norm(u))
        return abs(float(u[0] * d[1] - u[1] * d[0])) / n if n > 0.0 else 0.0

    n = i
    scores = []
    for p in pts:
        i, j = p.rods
        k = next(r for r in range(3) if r not in p.rods)
        s, pk = p.position[n], ax[k].pin[n]
        scores.append(min(abs(float(p.sin[n])), sin(pk - s, ax[k].direction[n]),
                          sin(ax[i].pin[n] - pk, ax[i].direction[n]), sin(ax[j].pin[n] - pk, ax[j].direction[n])))
    return int(np.argmax(scores))


#: Length of the arbitrary first vector of Koshel's uncertain-scale plan, mm.
UNCERTAIN_MM = 60.0
#: A group whose base pin moves slower than this fraction of its driving pin's speed is at rest
#: for Koshel's construction (its velocities are then rounding noise, ~1e-16 of the driver's),
#: and a base link with |ω|·size below this fraction of its pin's speed translates.
AT_REST = 1e-9


def uncertain_plan(motion: Motion, i: int, g: ComplexGroup) -> Plan | None:
    """Koshel's velocity plan of a class III group in an "uncertain scale", at position i.

    The base link's centre P being known (found on the scheme), the velocity of the pin X of
    the rod driven from a known moving link is drawn first, of arbitrary length UNCERTAIN_MM,
    ⊥ PX. The rod's outer pin Y follows from two directions (⊥ XY through x, the known
    direction of v_Y through p), which fixes the scale K_V = V_Y / py; the base link's other
    pins follow by the similarity proportion |pc| = |px|·PC/PX, ⊥ PC. Returns None when the
    construction does not apply to the group (no rod pinned to a moving known link); raises
    :class:`~plans.errors.ConstructionError` at a position where it degenerates: the group
    momentarily at rest (every image at the pole: no segment to draw, no scale to find), or
    the base link translating (its centre P at infinity)."""
    mech = motion.mechanism
    rods = [r for r in g.rods if r.form == "RR" and r.outer.b != FRAME]
    if not rods:
        return None
    rod = rods[0]
    x_name, y_name, known = rod.inner.point, rod.outer.point, rod.outer.b
    v_x = motion.velocity(x_name, g.base)[i]
    v_y = motion.velocity(y_name, known)[i]
    omega = float(motion.links[g.base].omega[i])
    if np.linalg.norm(v_x) <= AT_REST * np.linalg.norm(v_y):
        raise ConstructionError(f"group {g.name} is momentarily at rest (|v_{x_name}| = {np.linalg.norm(v_x):.1e} m/s "
                                f"while |v_{y_name}| = {np.linalg.norm(v_y):.3g} m/s): every image of the group is "
                                "at the pole, so Koshel's arbitrary segment has nothing to scale")
    if abs(omega) * mech.size <= AT_REST * float(np.linalg.norm(v_x)):
        raise ConstructionError(f"base link {g.base} of group {g.name} translates at this position (ω{g.base} = "
                                f"{omega:.1e} rad/s): its instantaneous centre is at infinity, so Koshel's "
                                "construction from it does not apply")
    centre = motion.centre_from(g.base, x_name, i)     # P of the base link (ω ≠ 0 here)
    b = _Builder(motion, i, float(np.linalg.norm(v_x)) / UNCERTAIN_MM, "velocity")
    pole = b.put(("pole",), "p", (0.0, 0.0))
    x_img = b.image(x_name, g.base)
    b.line(pole, J(motion.position(x_name)[i] - centre), [x_img], f"v:{x_name}", f"{g.name}:P")
    b.vector(f"v:{x_name}", pole, x_img, float(np.linalg.norm(v_x)), "absolute")
    y_img = b.image(y_name, known)
    r = motion.position(y_name)[i] - motion.position(x_name)[i]
    b.line(x_img, J(r), [y_img], f"v:{y_name}/{x_name}", f"{g.name}:{y_name}")
    b.line(pole, v_y, [y_img], f"v:{y_name}", f"{g.name}:{y_name}")
    b.vector(f"v:{y_name}/{x_name}", x_img, y_img, float(np.linalg.norm(v_y - v_x)), "relative")
    b.vector(f"v:{y_name}", pole, y_img, float(np.linalg.norm(v_y)), "absolute")
    for pair in g.inner:
        if pair.kind == "R" and pair.point != x_name:
            img = b.image(pair.point, g.base)
            v = motion.velocity(pair.point, g.base)[i]
            b.line(pole, J(motion.position(pair.point)[i] - centre), [img], f"v:{pair.point}", f"{g.name}:P")
            b.vector(f"v:{pair.point}", pole, img, float(np.linalg.norm(v)), "absolute")
    points, final = b.plan_points()
    pins = {p.point for p in g.inner if p.kind == "R"}
    similar = ((g.base, tuple(final[b.image_key(p, g.base)] for p in mech.links[g.base].points)),) \
        if set(mech.links[g.base].points) <= pins else ()
    return Plan(kind="velocity", mu=b.mu, pole=final[("pole",)], points=points, vectors=tuple(b.vectors), lines=tuple(b.lines),
                similar=similar)

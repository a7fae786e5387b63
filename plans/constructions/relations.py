"""The relative motions that build the plans, group by group in solving order: class II
pairs (rigid, sliding), class III rods and class IV contours, the original mechanism of a
drive inside the chain, and the similarity images of extra points.

Reads the motion's mechanism and structure; must not import the builder or the drawing of
vectors.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..kinematics import Motion, special
from ..scene import FRAME, DriveKind
from ..structure import ComplexGroup, DrivenGroup

__all__ = ["Relation", "relations"]


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

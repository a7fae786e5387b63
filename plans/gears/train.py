"""The structure of a gear train: its links (wheels joined on one shaft, carriers), the frame each
mesh is seen from, and the mobility W = 3n − 2p5 − p4 with the passive planets.

A planet is passive when it repeats another: the equally spaced copies of ``planets = k``, and a
planet link written out that has the same carrier, the same teeth and meshes the same links as
an earlier one (Khurmi & Gupta draw pinions B and C both between sun A and ring D). The count
n, p5, p4 leaves them out; counted with them, W = 3n' − 2p5' − p4' + q, where q is the number of
redundant constraints they add (a passive link with m meshes adds m − 1).

Every mesh is a higher pair (p4); every moving link turns in one revolute pair (p5), on the frame
or on the carrier that carries its axis. A mesh is seen from its *reference*: the frame when both
axes are fixed, else the carrier that carries the planet's axis (the other wheel is then a
central wheel, coaxial with that carrier). In that frame the mesh is an ordinary pair:
(ω_a − ω_R)/(ω_b − ω_R) = −z_b/z_a (external) or +z_b/z_a (one wheel a ring gear).

Imports only plans.errors and plans.scene (and the standard library).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from ..errors import StructureError
from ..scene.gears import GearTrain


@dataclass(frozen=True)
class GearLink:
    """One link of the train: ``members`` (wheels and carriers joined on one shaft, scene order;
    the first is its ``name``), ``axis_on`` the carrier carrying its axis (None: the frame),
    ``carrier`` whether it holds a carrier, ``fixed`` whether it is held still."""

    name: str
    members: tuple[str, ...]
    axis_on: str | None
    carrier: bool
    fixed: bool


@dataclass(frozen=True)
class Mesh:
    """A mesh of wheels ``a`` and ``b`` (on links ``link_a``, ``link_b``), seen from the link
    ``reference`` (None: the frame). ``ratio`` = (ω_a − ω_R)/(ω_b − ω_R) = ∓ z_b/z_a, exact."""

    a: str
    b: str
    link_a: str
    link_b: str
    external: bool
    reference: str | None
    ratio: Fraction


@dataclass(frozen=True)
class PassivePlanet:
    """Planet link ``name`` written out as a repeat of ``copy_of`` on carrier ``carrier``: the same
    teeth, meshing the same links in its ``meshes`` meshes; it turns as ``copy_of`` does."""

    name: str
    copy_of: str
    carrier: str
    meshes: int


@dataclass(frozen=True)
class TrainStructure:
    """Links, meshes and the count of the train. ``mobility`` is W = 3n − 2p5 − p4 of the train
    without its passive planets (one of each on its carrier); ``passive_planets`` the passive
    planet links (the extra equally spaced copies and those written out, ``passive``), with
    ``passive_meshes`` meshes, and ``redundant`` q, the constraints they add: counted with them,
    W = 3(n + passive_planets) − 2(p5 + passive_planets) − (p4 + passive_meshes) + q."""

    train: GearTrain
    links: tuple[GearLink, ...]
    meshes: tuple[Mesh, ...]
    n: int
    p5: int
    p4: int
    passive_planets: int
    redundant: int
    passive: tuple[PassivePlanet, ...] = ()
    passive_meshes: int = 0

    @property
    def mobility(self) -> int:
        return 3 * self.n - 2 * self.p5 - self.p4

    @property
    def formula(self) -> str:
        """W as counted without the passive planets: "W = 3·n − 2·p5 − p4 = W"."""
        return f"W = 3·{self.n} − 2·{self.p5} − {self.p4} = {self.mobility}"

    @property
    def formula_with_passive(self) -> str:
        """W counted with every passive planet: "W = 3·n' − 2·p5' − p4' + q = W"."""
        n = self.n + self.passive_planets
        return (f"W = 3·{n} − 2·{self.p5 + self.passive_planets} − {self.p4 + self.passive_meshes} + "
                f"{self.redundant} = {self.mobility}")

    def copy_of(self, link: str) -> str | None:
        """The planet link that passive link ``link`` repeats, or None (not a written-out copy)."""
        return next((p.copy_of for p in self.passive if p.name == link), None)

    def link_of(self, member: str) -> GearLink:
        """The link that holds wheel or carrier ``member``."""
        for link in self.links:
            if member in link.members:
                return link
        raise KeyError(member)

    @property
    def moving(self) -> tuple[GearLink, ...]:
        return tuple(link for link in self.links if not link.fixed)

    def planets_of(self, carrier: str, *, passive: bool = False) -> tuple[GearLink, ...]:
        """The links whose axes ``carrier`` carries (with ``passive``, the written-out copies too)."""
        copies = set() if passive else {p.name for p in self.passive}
        return tuple(link for link in self.links if link.axis_on == carrier and link.name not in copies)

    def copies(self, link: str) -> tuple[str, ...]:
        """The written-out passive copies of planet link ``link`` (scene order)."""
        return tuple(p.name for p in self.passive if p.copy_of == link)


def train_structure(train: GearTrain) -> TrainStructure:
    """The links, meshes and count of ``train``; a train that no wheel set can form (a carrier
    without a planet, two ring gears in mesh, a shaft joining a planet to a central link, …) is
    refused with a :class:`StructureError` naming the wheels."""
    links = _links(train)
    link_of = {m: link for link in links for m in link.members}
    for c in train.carriers:
        if not any(link.axis_on == c for link in links):
            raise StructureError(f"carrier {c!r} carries no planet; give a wheel on = {c!r} or remove the carrier",
                                 key="gears.carriers")
    meshes = tuple(_mesh(train, a, b, link_of) for a, b in train.meshes)
    passive = _written_copies(train, links, meshes)
    copies = {p.name for p in passive}
    counted = [m for m in meshes if m.link_a not in copies and m.link_b not in copies]
    moving = [link for link in links if not link.fixed and link.name not in copies]
    k = train.planets
    extra = redundant = extra_meshes = 0
    for c in train.carriers:                       # k − 1 more sets of each carrier's planets
        planets = {link.name for link in moving if link.axis_on == c}
        touching = sum(1 for m in counted if m.link_a in planets or m.link_b in planets)
        extra += (k - 1) * len(planets)
        extra_meshes += (k - 1) * touching
        redundant += (k - 1) * max(touching - len(planets), 0)
    for p in passive:                              # each written-out copy, k times
        extra += k
        extra_meshes += k * p.meshes
        redundant += k * (p.meshes - 1)
    return TrainStructure(train=train, links=links, meshes=meshes, n=len(moving), p5=len(moving), p4=len(counted),
                          passive_planets=extra, redundant=redundant, passive=passive, passive_meshes=extra_meshes)


def _written_copies(train: GearTrain, links: tuple[GearLink, ...], meshes: tuple[Mesh, ...]
                    ) -> tuple[PassivePlanet, ...]:
    """The planet links that repeat an earlier one (scene order): the same carrier, held still or
    not alike, wheels of the same teeth, module and kind, each meshing the same links."""
    partners: dict[str, set[str]] = {}
    for m in meshes:
        partners.setdefault(m.a, set()).add(m.link_b)
        partners.setdefault(m.b, set()).add(m.link_a)
    first: dict[tuple, str] = {}
    out = []
    for link in links:
        if link.axis_on is None or link.carrier:
            continue
        wheels = [train.wheel(n) for n in link.members]
        if any(not partners.get(w.name) for w in wheels):
            continue                               # a wheel meshing nothing repeats nothing
        key = (link.axis_on, link.fixed, tuple(sorted((w.teeth, w.internal, w.module or 0.0,
                                                       tuple(sorted(partners[w.name]))) for w in wheels)))
        if key in first:
            count = sum(1 for m in meshes if link.name in (m.link_a, m.link_b))
            out.append(PassivePlanet(name=link.name, copy_of=first[key], carrier=link.axis_on, meshes=count))
        else:
            first[key] = link.name
    return tuple(out)


def _links(train: GearTrain) -> tuple[GearLink, ...]:
    """Union of wheels and carriers by ``shaft``, each link named by its first member in scene order."""
    order = list(train.names)
    parent = {n: n for n in order}

    def root(n: str) -> str:
        while parent[n] != n:
            parent[n] = parent[parent[n]]
            n = parent[n]
        return n

    for w in train.wheels:
        if w.shaft is not None:
            ra, rb = root(w.name), root(w.shaft)
            if ra != rb:
                first, second = sorted((ra, rb), key=order.index)
                parent[second] = first
    groups: dict[str, list[str]] = {}
    for n in order:
        groups.setdefault(root(n), []).append(n)
    out = []
    for members in sorted(groups.values(), key=lambda ms: order.index(ms[0])):
        carriers = [m for m in members if m in train.carriers]
        axes = {train.wheel(m).on for m in members if m not in train.carriers}
        if carriers:
            axes.add(None)
        if len(axes) > 1:
            shown = ", ".join(f"{m} on {train.wheel(m).on or 'the frame'}" for m in members if m not in carriers)
            raise StructureError(f"wheels joined on one shaft turn about one axis, but {shown}"
                                 + (f" (joined to carrier {carriers[0]!r}, whose axis is fixed)" if carriers else "")
                                 + "; give them the same on", key="gears.wheels")
        if len(carriers) > 1:
            raise StructureError(f"carriers {carriers[0]!r} and {carriers[1]!r} are joined on one shaft; "
                                 "list one carrier", key="gears.carriers")
        out.append(GearLink(name=members[0], members=tuple(members), axis_on=axes.pop(), carrier=bool(carriers),
                            fixed=any(m in train.fixed for m in members)))
    return tuple(out)


def _mesh(train: GearTrain, a: str, b: str, link_of: dict[str, GearLink]) -> Mesh:
    wa, wb = train.wheel(a), train.wheel(b)
    key = "gears.meshes"
    if wa.internal and wb.internal:
        raise StructureError(f"{a!r} and {b!r} are both ring gears, which cannot mesh; make one external "
                             "(internal = false)", key=key)
    la, lb = link_of[a], link_of[b]
    if la is lb:
        raise StructureError(f"{a!r} and {b!r} are on one shaft and cannot mesh", key=key)
    ca, cb = la.axis_on, lb.axis_on
    if ca is not None and cb is not None and ca != cb:
        raise StructureError(f"{a!r} (on {ca!r}) and {b!r} (on {cb!r}) are carried by two carriers and cannot "
                             "stay in mesh; carry both on one carrier", key=key)
    if wa.module is not None and wb.module is not None and wa.module != wb.module:
        raise StructureError(f"{a!r} (module {wa.module:g} mm) and {b!r} (module {wb.module:g} mm) mesh but "
                             "have different modules; give them one module", key=key)
    reference = ca if ca is not None else cb
    ref_link = None if reference is None else link_of[reference].name
    external = not (wa.internal or wb.internal)
    ratio = Fraction(wb.teeth, wa.teeth) * (-1 if external else 1)
    return Mesh(a=a, b=b, link_a=la.name, link_b=lb.name, external=external, reference=ref_link, ratio=ratio)

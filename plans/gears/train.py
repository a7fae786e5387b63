"""The structure of a gear train: its links (wheels joined on one shaft, carriers), the frame each
mesh is seen from, and the mobility W = 3n − 2p5 − p4 with the passive planets.

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
class TrainStructure:
    """Links, meshes and the count of the train. ``mobility`` is W = 3n − 2p5 − p4 of the train as
    described (one planet per carrier); ``passive_planets`` the extra equally spaced copies, and
    ``redundant`` the constraints they add (W counted with them is mobility − redundant)."""

    train: GearTrain
    links: tuple[GearLink, ...]
    meshes: tuple[Mesh, ...]
    n: int
    p5: int
    p4: int
    passive_planets: int
    redundant: int

    @property
    def mobility(self) -> int:
        return 3 * self.n - 2 * self.p5 - self.p4

    def link_of(self, member: str) -> GearLink:
        """The link that holds wheel or carrier ``member``."""
        for link in self.links:
            if member in link.members:
                return link
        raise KeyError(member)

    @property
    def moving(self) -> tuple[GearLink, ...]:
        return tuple(link for link in self.links if not link.fixed)

    def planets_of(self, carrier: str) -> tuple[GearLink, ...]:
        """The links whose axes ``carrier`` carries."""
        return tuple(link for link in self.links if link.axis_on == carrier)


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
    moving = [link for link in links if not link.fixed]
    planet_links = [link for link in moving if link.axis_on is not None]
    extra = (train.planets - 1) * len(planet_links)
    planet_meshes = sum(1 for m in meshes for link in planet_links if link.name in (m.link_a, m.link_b))
    redundant = (train.planets - 1) * (planet_meshes - len(planet_links)) if planet_links else 0
    return TrainStructure(train=train, links=links, meshes=meshes, n=len(moving), p5=len(moving), p4=len(meshes),
                          passive_planets=extra, redundant=max(redundant, 0))


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

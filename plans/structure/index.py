"""Who is joined to whom in a mechanism: the look-up tables the structural search reads.

Imports only plans.model and the group value types; must not import the search or anything
above the structure layer.
"""

from __future__ import annotations

from ..model import Mechanism, Prismatic
from .groups import Joint, Pair


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
        self._later: dict[str, list[str]] = {}

    def later_neighbours(self, link: str) -> list[str]:
        """The neighbours of ``link`` listed after it in [links], in that order (kept once made)."""
        later = self._later.get(link)
        if later is None:
            later = self._later[link] = sorted((x for x in self.neighbours[link] if self.rank[x] > self.rank[link]),
                                               key=self.rank.__getitem__)
        return later

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

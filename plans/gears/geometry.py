"""The geometry of a gear train where modules are given: pitch radii r = m·z/2, where each
carrier holds its planets' axes, and the conditions of a planetary train (coaxial, assembly for
equally spaced planets, neighbourhood) and of each wheel (undercut).

Where a carrier holds its planets: a planet meshing a central wheel has its axis at
r_c + r_p (a sun) or r_c − r_p (a ring) from the central axis, the same for each central wheel it
meshes (the coaxial condition); two planets of one carrier in mesh have their axes r_p + r_q
apart, which closes the triangle with the central axis when |a_p − a_q| ≤ r_p + r_q ≤ a_p + a_q
(a double-planet train: the planets need not stand on one radius).

Standard wheels are assumed (no profile shift, ha* = 1, α = 20°): the tip diameter is
d_a = m·(z + 2) (external), the fewest teeth without undercut 17. A wheel inside a ring gear is
checked for the internal pair's tip (trochoid) interference, SDP/SI, Elements of Metric Gear
Technology, §5.2 (b), Eq. (5-6) (:func:`plans.gears.contact.standard_tip_interference`): the
smallest difference of teeth is 9 for wheels of 17 … 69 teeth, 10 for 11 … 16, 8 from 70 on. It
does not depend on the module, so a train without modules is checked too, with a warning instead
of a refusal. (The
involute interference of a standard ring, its tip circle m(z − 2) inside the pinion's N1, is left
to ``[gear_pair]``: it would refuse every planet under 18 teeth, and 18 in a ring of 90.)

Imports only plans.errors, plans.scene and plans.gears (and the standard library).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction

from ..errors import StructureError
from .contact import standard_tip_interference
from .speeds import carrier_ratio, central_links
from .train import GearLink, TrainStructure

#: The fewest teeth of a standard external wheel (α = 20°, ha* = 1) that is not undercut.
MIN_TEETH = 17
#: Relative tolerance of the coaxial condition (arms compared in mm).
COAXIAL_TOL = 1e-9


@dataclass(frozen=True)
class TrainGeometry:
    """``radius`` maps each wheel to its pitch radius, mm; ``arm`` each carrier to the distance
    of its farthest planet axis from the central axis, mm; ``planet_arm`` each planet link (its
    written-out copies too) to the distance of its axis, mm, and ``planet_angle`` to the angle of
    its axis about the central axis, rad, counter-clockwise from its carrier's first planet;
    ``sets`` each carrier's equally spaced planet sets (planets = k times the planets written
    out as copies); ``warnings`` one line each (undercut); ``unchecked`` why some condition
    could not be checked (no modules, a planet chain the assembly formula does not cover)."""

    radius: dict[str, float]
    arm: dict[str, float]
    warnings: tuple[str, ...]
    unchecked: tuple[str, ...]
    planet_arm: dict[str, float] = field(default_factory=dict)
    planet_angle: dict[str, float] = field(default_factory=dict)
    sets: dict[str, int] = field(default_factory=dict)


def train_geometry(structure: TrainStructure) -> TrainGeometry | None:
    """The geometry of the train, or None when no wheel has a module (the train is solved from
    its teeth alone). A failed condition raises a :class:`StructureError` naming the wheels."""
    train = structure.train
    if all(w.module is None for w in train.wheels):
        return None
    missing = [w.name for w in train.wheels if w.module is None]
    if missing:
        raise StructureError(f"wheel(s) {', '.join(missing)} have no module while others do; give every wheel "
                             "its module, or none", key="gears.wheels")
    radius = {w.name: w.module * w.teeth / 2.0 for w in train.wheels}
    warnings = [f"wheel {w.name!r} has {w.teeth} teeth, fewer than {MIN_TEETH}: a standard wheel is undercut "
                "(shift its profile or give it more teeth)" for w in train.wheels
                if not w.internal and w.teeth < MIN_TEETH]
    for m in structure.meshes:
        ring, inner = (m.a, m.b) if train.wheel(m.a).internal else (m.b, m.a) if train.wheel(m.b).internal else (None, None)
        if ring is not None and train.wheel(ring).teeth <= train.wheel(inner).teeth:
            raise StructureError(f"ring gear {ring!r} ({train.wheel(ring).teeth} teeth) must have more teeth than "
                                 f"{inner!r} ({train.wheel(inner).teeth}) inside it", key="gears.meshes")
    problems = internal_interference(structure)
    if problems:
        raise StructureError(problems[0], key="gears.meshes")
    arm: dict[str, float] = {}
    planet_arm: dict[str, float] = {}
    planet_angle: dict[str, float] = {}
    sets: dict[str, int] = {}
    unchecked: list[str] = []
    for c in train.carriers:
        placed, missing_note = _place(structure, c, radius)
        unchecked += missing_note
        if not placed:
            continue
        arm[c] = max(d for d, _ in placed.values())
        for p, (d, t) in placed.items():
            planet_arm[p], planet_angle[p] = d, t
        _clearance(structure, c, placed)
        k = planet_sets(structure, c)
        if k is None:
            unchecked.append(f"carrier {c!r}: its planets are written out a different number of times each, so "
                             "their assembly and neighbourhood went unchecked; write each planet once and give "
                             "planets = k")
            continue
        sets[c] = k
        for p in structure.planets_of(c):            # the copies written out: the next sets
            for i, copy in enumerate(structure.copies(p.name), start=1):
                if p.name in placed:
                    planet_arm[copy] = placed[p.name][0]
                    planet_angle[copy] = placed[p.name][1] + 2.0 * math.pi * i / k
        if k > 1:
            unchecked += _assembly(structure, c, k)
            _neighbours(structure, c, placed, k)
    return TrainGeometry(radius=radius, arm=arm, warnings=tuple(warnings), unchecked=tuple(unchecked),
                         planet_arm=planet_arm, planet_angle=planet_angle, sets=sets)


def internal_interference(structure: TrainStructure) -> list[str]:
    """One line per internal mesh of standard wheels whose inner wheel's tip strikes the ring's
    teeth as it leaves the mesh (tip interference, see the module), scene order; a ring with no
    more teeth than its inner wheel is said so (the module-given check refuses it first)."""
    train = structure.train
    out = []
    for m in structure.meshes:
        if m.external:
            continue
        ring, inner = (m.a, m.b) if train.wheel(m.a).internal else (m.b, m.a)
        z2, z1 = train.wheel(ring).teeth, train.wheel(inner).teeth
        if z2 <= z1:
            out.append(f"ring gear {ring!r} ({z2} teeth) must have more teeth than {inner!r} ({z1}) inside it")
        elif standard_tip_interference(z1, z2) < -1e-12:
            need = next((z for z in range(z2 + 1, z1 + 100) if standard_tip_interference(z1, z) >= -1e-12), None)
            more = f"give the ring at least {need} teeth" if need is not None else "give the ring more teeth"
            out.append(f"ring gear {ring!r} ({z2} teeth) and {inner!r} ({z1}) inside it interfere: the tip of "
                       f"{inner!r} strikes the ring's teeth as it leaves the mesh (tip interference of standard "
                       f"wheels, z2 − z1 = {z2 - z1}); {more}")
    return out


def planet_sets(structure: TrainStructure, carrier: str) -> int | None:
    """The equally spaced planet sets of ``carrier``: planets = k times (1 + the copies written out
    of each of its planets); None when its planets are written out a different number of times."""
    counts = {len(structure.copies(p.name)) for p in structure.planets_of(carrier)}
    return structure.train.planets * (1 + counts.pop()) if len(counts) == 1 else None


def _central_arms(structure: TrainStructure, link: GearLink, radius: dict[str, float]) -> list[tuple[str, float]]:
    """(the mesh as text, the distance of the axis it sets, mm) for each mesh of planet link
    ``link`` with a central wheel."""
    train = structure.train
    out = []
    for m in structure.meshes:
        for planet, central in ((m.a, m.b), (m.b, m.a)):
            other = structure.link_of(central)
            if planet in link.members and other.axis_on is None:
                ring = train.wheel(central).internal
                value = radius[central] - radius[planet] if ring else radius[central] + radius[planet]
                out.append((f"r_{central} {'−' if ring else '+'} r_{planet}", value))
    return out


def _planet_meshes(structure: TrainStructure, carrier: str, radius: dict[str, float]
                   ) -> list[tuple[str, str, str, str, float]]:
    """(link p, wheel of p, link q, wheel of q, the distance of their axes, mm) for each mesh of
    two planet links of ``carrier`` (passive copies left out)."""
    planets = {p.name for p in structure.planets_of(carrier)}
    return [(m.link_a, m.a, m.link_b, m.b, radius[m.a] + radius[m.b] if m.external else abs(radius[m.a] - radius[m.b]))
            for m in structure.meshes if m.link_a in planets and m.link_b in planets]


def _place(structure: TrainStructure, carrier: str, radius: dict[str, float]
           ) -> tuple[dict[str, tuple[float, float]], list[str]]:
    """Each planet link of ``carrier`` → (distance of its axis from the central axis mm, angle
    rad), and what could not be placed. The coaxial condition (one distance per planet link)
    and the meshing of two planets (the triangle closes) are refused when they fail."""
    placed: dict[str, tuple[float, float]] = {}
    distance: dict[str, float] = {}
    for p in structure.planets_of(carrier):
        arms = _central_arms(structure, p, radius)
        if not arms:
            continue
        (first, value), *rest = arms
        for other, v in rest:
            if abs(v - value) > COAXIAL_TOL * max(value, v):
                raise StructureError(f"carrier {carrier!r}: the coaxial condition does not close: {first} gives an "
                                     f"arm of {value:g} mm, {other} {v:g} mm; change the teeth so both are equal",
                                     key="gears.wheels")
        distance[p.name] = value
    if not distance:
        return {}, [f"carrier {carrier!r}: its planets mesh no central wheel, so its arm is not set"]
    pairs = _planet_meshes(structure, carrier, radius)
    for p, wp, q, wq, gap in pairs:
        if p in distance and q in distance:
            dp, dq = distance[p], distance[q]
            lo, hi = abs(dp - dq), dp + dq
            tol = COAXIAL_TOL * max(hi, gap)
            if not lo - tol <= gap <= hi + tol:
                sign = "+" if gap == radius[wp] + radius[wq] else "−"
                raise StructureError(f"carrier {carrier!r}: planets {wp!r} and {wq!r} cannot mesh: their axes are "
                                     f"{dp:g} mm and {dq:g} mm from the central axis, so {lo:g} … {hi:g} mm apart, "
                                     f"but r_{wp} {sign} r_{wq} = {gap:g} mm; change the teeth", key="gears.wheels")
    for name, d in distance.items():               # each group of planets in mesh: its first at angle 0
        if name in placed:
            continue
        placed[name] = (d, 0.0)
        frontier = [name]
        while frontier:
            here = frontier.pop(0)
            for p, _, q, _, gap in pairs:
                for a, b in ((p, q), (q, p)):
                    if a == here and b not in placed and b in distance:
                        da, db = distance[a], distance[b]
                        cos = (da * da + db * db - gap * gap) / (2.0 * da * db) if da > 0 and db > 0 else 1.0
                        placed[b] = (db, placed[a][1] + math.acos(max(-1.0, min(1.0, cos))))
                        frontier.append(b)
    loose = [p.name for p in structure.planets_of(carrier) if p.name not in placed]
    note = [f"carrier {carrier!r}: planet {p!r} meshes no central wheel, so its place and its clearances went "
            "unchecked" for p in loose]
    return placed, note


def _tip(structure: TrainStructure, wheel: str) -> float:
    """The tip diameter d_a = m·(z + 2) of ``wheel``, mm (a ring's inner tip circle m·(z − 2))."""
    w = structure.train.wheel(wheel)
    return w.module * (w.teeth - 2 if w.internal else w.teeth + 2)


def _planes(structure: TrainStructure) -> dict[str, int]:
    """Each wheel's plane: wheels joined by meshes (directly or through others) share one."""
    plane = {w.name: k for k, w in enumerate(structure.train.wheels)}
    for _ in structure.meshes:
        for m in structure.meshes:
            plane[m.a] = plane[m.b] = min(plane[m.a], plane[m.b])
    return plane


def _clearance(structure: TrainStructure, carrier: str, placed: dict[str, tuple[float, float]]) -> None:
    """Refuse a planet wheel that runs into a central wheel of its plane it does not mesh (the
    outer planet of a double-planet train into the sun, the inner one into the ring)."""
    plane = _planes(structure)
    meshing = {frozenset(pair) for pair in structure.train.meshes}
    central = [n for link in central_links(structure, structure.link_of(carrier).name) for n in link.members
               if n not in structure.train.carriers]
    for p in structure.planets_of(carrier):
        if p.name not in placed:
            continue
        d = placed[p.name][0]
        for w in p.members:
            for c in central:
                if plane[c] != plane[w] or frozenset((c, w)) in meshing:
                    continue
                ring = structure.train.wheel(c).internal
                room = _tip(structure, c) / 2.0 - d if ring else d - _tip(structure, c) / 2.0
                if room <= _tip(structure, w) / 2.0:
                    raise StructureError(f"carrier {carrier!r}: planet {w!r} (its axis {d:g} mm from the centre, tip "
                                         f"diameter {_tip(structure, w):.4g} mm) runs into {c!r} (tip diameter "
                                         f"{_tip(structure, c):.4g} mm), which it does not mesh; change the teeth",
                                         key="gears.wheels")


def _chain(structure: TrainStructure, carrier: str) -> tuple[str, tuple[str, ...], str] | None:
    """(central wheel a, the planet wheels from a to b, central wheel b) when the carrier's train
    runs between two central wheels through one planet link (one wheel, or two on one shaft), or
    through a chain of planet links of one wheel each in mesh (a double-planet train); else None."""
    h = structure.link_of(carrier).name
    central = central_links(structure, h)
    planets = structure.planets_of(carrier)
    if len(central) != 2 or not planets:
        return None
    names = {p.name for p in planets}
    wheel_of = {n: p.name for p in planets for n in p.members}
    meshes = [(m.a, m.b) for m in structure.meshes if m.link_a in names or m.link_b in names]
    ends = []
    for c in central:
        touching = [(x, y) for a, b in meshes for x, y in ((a, b), (b, a)) if x in c.members and y in wheel_of]
        if len(touching) != 1:
            return None
        ends.append(touching[0])
    (sun, first), (other, last) = ends
    if len(planets) == 1:
        return sun, (first,) if first == last else (first, last), other
    if any(len(p.members) != 1 for p in planets):
        return None
    inner = [(a, b) for a, b in meshes if a in wheel_of and b in wheel_of]
    if len(inner) != len(planets) - 1 or len(meshes) != len(planets) + 1:
        return None
    path, seen = [first], {first}
    while path[-1] != last:
        step = [y for a, b in inner for x, y in ((a, b), (b, a)) if x == path[-1] and y not in seen]
        if len(step) != 1:
            return None
        path.append(step[0])
        seen.add(step[0])
    return (sun, tuple(path), other) if len(path) == len(planets) else None


def assembly_number(structure: TrainStructure, carrier: str, k: int | None = None) -> Fraction | None:
    """The number that must be whole for ``k`` equally spaced planet sets (default: the carrier's
    sets, :func:`planet_sets`), from central wheels a and b and the planet wheels between them:
    z_a·(1 − i_ab^H)·z_g'/(k·gcd(z_g, z_g')) for one planet link, g meshing a and g' meshing b
    ((z_a + z_b)/k for a single planet wheel between a sun and a ring); z_a·(1 − i_ab^H)/k for a
    chain of single planet wheels in mesh ((z_a − z_b)/k for a double planet between a sun and a
    ring). None when the train is not of those forms."""
    chain = _chain(structure, carrier)
    k = planet_sets(structure, carrier) if k is None else k
    if chain is None or k is None:
        return None
    train = structure.train
    sun, planets, other = chain
    h = structure.link_of(carrier).name
    i_ab = carrier_ratio(structure, h, structure.link_of(sun).name, structure.link_of(other).name)
    if i_ab is None:
        return None
    za = train.wheel(sun).teeth
    if structure.link_of(planets[0]) is structure.link_of(planets[-1]):
        zg, zg2 = train.wheel(planets[0]).teeth, train.wheel(planets[-1]).teeth
        return za * (1 - i_ab) * zg2 / (k * math.gcd(zg, zg2))
    return za * (1 - i_ab) / k


def _assembly(structure: TrainStructure, carrier: str, k: int) -> list[str]:
    n = assembly_number(structure, carrier, k)
    if n is None:
        return [(f"carrier {carrier!r}: the assembly condition of {k} planets went unchecked: it is checked "
                 "for one planet link, or a chain of single planets, between two central wheels")]
    if n.denominator != 1:
        raise StructureError(f"carrier {carrier!r}: {k} equally spaced planets cannot be assembled: the assembly "
                             f"number is {abs(float(n)):.6g}, not a whole number; change planets or the teeth",
                             key="gears.planets")
    return []


def _neighbours(structure: TrainStructure, carrier: str, placed: dict[str, tuple[float, float]], k: int) -> None:
    """Refuse ``k`` planet sets whose tip circles overlap: a planet link and its copy in the next
    set (2·a·sin(π/k) > its largest tip diameter), and wheels in one plane of two planet links in
    mesh (a double planet: their axes farther apart than the mean of their tip diameters), across
    sets and within one."""
    plane = _planes(structure)
    meshing = {frozenset(pair) for pair in structure.train.meshes}
    planets = [p for p in structure.planets_of(carrier) if p.name in placed]
    group = {p.name: p.name for p in planets}      # planets in mesh, whose angles apart are known
    for _ in planets:
        for m in structure.meshes:
            if m.link_a in group and m.link_b in group:
                group[m.link_a] = group[m.link_b] = min(group[m.link_a], group[m.link_b])
    for p in planets:
        tip, name = max((_tip(structure, n), n) for n in p.members)
        gap = 2.0 * placed[p.name][0] * math.sin(math.pi / k)
        if gap <= tip:
            raise StructureError(f"carrier {carrier!r}: {k} planets do not fit: adjacent axes are {gap:.4g} mm "
                                 f"apart, less than the tip diameter {tip:.4g} mm of {name!r}; use fewer planets "
                                 "or a smaller planet", key="gears.planets")
    for i, p in enumerate(planets):
        for q in planets[i + 1:]:
            if group[p.name] != group[q.name]:
                continue                           # not in mesh: where they stand is the designer's
            (dp, tp), (dq, tq) = placed[p.name], placed[q.name]
            for w in p.members:
                for u in q.members:
                    if plane[w] != plane[u]:
                        continue
                    need = (_tip(structure, w) + _tip(structure, u)) / 2.0
                    for j in range(k):
                        if j == 0 and frozenset((w, u)) in meshing:
                            continue
                        t = tq + 2.0 * math.pi * j / k - tp
                        apart = math.sqrt(max(dp * dp + dq * dq - 2.0 * dp * dq * math.cos(t), 0.0))
                        if apart <= need:
                            where = "in one set" if j == 0 else "of neighbouring sets"
                            raise StructureError(f"carrier {carrier!r}: {k} planet sets do not fit: {w!r} and {u!r} "
                                                 f"{where} are {apart:.4g} mm apart, within {need:.4g} mm of their "
                                                 "tips; use fewer planets or smaller planets", key="gears.planets")

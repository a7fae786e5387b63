"""The geometry of a gear train where modules are given: pitch radii r = m·z/2, the carriers'
arms from the coaxial condition, and the conditions of a planetary train (coaxial, assembly for
equally spaced planets, neighbourhood) and of each wheel (undercut).

Standard wheels are assumed (no profile shift, ha* = 1, α = 20°): the tip diameter is
d_a = m·(z + 2) (external), the fewest teeth without undercut 17.

Imports only plans.errors, plans.scene and plans.gears (and the standard library).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from ..errors import StructureError
from .speeds import carrier_ratio, central_links
from .train import TrainStructure

#: The fewest teeth of a standard external wheel (α = 20°, ha* = 1) that is not undercut.
MIN_TEETH = 17
#: Relative tolerance of the coaxial condition (arms compared in mm).
COAXIAL_TOL = 1e-9


@dataclass(frozen=True)
class TrainGeometry:
    """``radius`` maps each wheel to its pitch radius, mm; ``arm`` each carrier to the distance
    of its planets' axes from the central axis, mm; ``warnings`` one line each (undercut);
    ``unchecked`` why some condition could not be checked (no modules, a planet chain the
    assembly formula does not cover)."""

    radius: dict[str, float]
    arm: dict[str, float]
    warnings: tuple[str, ...]
    unchecked: tuple[str, ...]


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
    arm: dict[str, float] = {}
    unchecked: list[str] = []
    for c in train.carriers:
        arms = _arms(structure, c, radius)
        if not arms:
            unchecked.append(f"carrier {c!r}: its planets mesh no central wheel, so its arm is not set")
            continue
        (first, value), *rest = arms
        for other, v in rest:
            if abs(v - value) > COAXIAL_TOL * max(value, v):
                raise StructureError(f"carrier {c!r}: the coaxial condition does not close: {first} gives an arm "
                                     f"of {value:g} mm, {other} {v:g} mm; change the teeth so both are equal",
                                     key="gears.wheels")
        arm[c] = value
        if train.planets > 1:
            unchecked += _assembly(structure, c)
            _neighbours(structure, c, value)
    return TrainGeometry(radius=radius, arm=arm, warnings=tuple(warnings), unchecked=tuple(unchecked))


def _arms(structure: TrainStructure, carrier: str, radius: dict[str, float]) -> list[tuple[str, float]]:
    """(the mesh as text, the arm it sets) for each mesh of a planet of ``carrier`` with a central wheel."""
    train = structure.train
    out = []
    for m in structure.meshes:
        for planet, central in ((m.a, m.b), (m.b, m.a)):
            if train.wheel(planet).on == carrier and structure.link_of(central).axis_on is None:
                ring = train.wheel(central).internal
                value = radius[central] - radius[planet] if ring else radius[central] + radius[planet]
                sign = "−" if ring else "+"
                out.append((f"r_{central} {sign} r_{planet}", value))
    return out


def _planet_pair(structure: TrainStructure, carrier: str) -> tuple[str, str, str, str] | None:
    """(central a, planet wheel on a, planet wheel on b, central b) when the carrier's train is one
    planet link between two central wheels, else None."""
    h = structure.link_of(carrier).name
    central = central_links(structure, h)
    planets = structure.planets_of(carrier)
    if len(central) != 2 or len(planets) != 1:
        return None
    a, b = central[0].name, central[1].name
    wa = [x for m in structure.meshes for x, y in ((m.a, m.b), (m.b, m.a))
          if structure.link_of(y).name == a and x in planets[0].members]
    wb = [x for m in structure.meshes for x, y in ((m.a, m.b), (m.b, m.a))
          if structure.link_of(y).name == b and x in planets[0].members]
    if len(wa) != 1 or len(wb) != 1:
        return None
    sun = next(y for m in structure.meshes for x, y in ((m.a, m.b), (m.b, m.a))
               if x == wa[0] and structure.link_of(y).name == a)
    other = next(y for m in structure.meshes for x, y in ((m.a, m.b), (m.b, m.a))
                 if x == wb[0] and structure.link_of(y).name == b)
    return sun, wa[0], wb[0], other


def assembly_number(structure: TrainStructure, carrier: str) -> Fraction | None:
    """z_a·(1 − i_ab^H)·z_g'/(k·gcd(z_g, z_g')) for central wheels a, b and the planet's wheels g
    (on a) and g' (on b); it must be a whole number for k equally spaced planets ((z_a + z_b)/k for
    a single planet wheel between a sun and a ring). None when the train is not of that form."""
    pair = _planet_pair(structure, carrier)
    if pair is None:
        return None
    train = structure.train
    sun, g, g2, other = pair
    h = structure.link_of(carrier).name
    i_ab = carrier_ratio(structure, h, structure.link_of(sun).name, structure.link_of(other).name)
    if i_ab is None:
        return None
    za, zg, zg2 = (train.wheel(n).teeth for n in (sun, g, g2))
    return za * (1 - i_ab) * zg2 / (train.planets * math.gcd(zg, zg2))


def _assembly(structure: TrainStructure, carrier: str) -> list[str]:
    n = assembly_number(structure, carrier)
    k = structure.train.planets
    if n is None:
        return [f"carrier {carrier!r}: the assembly condition of {k} planets is checked only for one planet "
                "between two central wheels"]
    if n.denominator != 1:
        raise StructureError(f"carrier {carrier!r}: {k} equally spaced planets cannot be assembled: the assembly "
                             f"number is {float(n):.6g}, not a whole number; change planets or the teeth",
                             key="gears.planets")
    return []


def _neighbours(structure: TrainStructure, carrier: str, arm: float) -> None:
    train = structure.train
    k = train.planets
    tips = [(train.wheel(n).module * (train.wheel(n).teeth + 2), n)
            for link in structure.planets_of(carrier) for n in link.members]
    tip, name = max(tips)
    gap = 2.0 * arm * math.sin(math.pi / k)
    if gap <= tip:
        raise StructureError(f"carrier {carrier!r}: {k} planets do not fit: adjacent axes are {gap:.4g} mm apart, "
                             f"less than the tip diameter {tip:.4g} mm of {name!r}; use fewer planets or a smaller "
                             "planet", key="gears.planets")

"""A rotor's random variants (``plans handout ROTOR.toml --random N``): the masses, their radii,
angles and planes drawn around the base's, and the check that keeps a drawn rotor's balancing
masses of the base's size.

The draws, in a fixed order: for each mass, its mass × U(1 − MASS_SPREAD, 1 + MASS_SPREAD) and
its radius × U(1 − LENGTH_SPREAD, 1 + LENGTH_SPREAD), both to three significant digits (a mass of
0 stays 0), and its angle a multiple of ANGLE_STEP_DEG over the turn; then each place along the
shaft, in the shaft's order, a shift × U(−PLANE_SHIFT, PLANE_SHIFT) of its distance to the
nearer neighbouring place (away from 0 where it would cross it: a shaft measured from its end
keeps every plane at or past it). A place holding a balancing plane keeps it (the shift is drawn
and left unused), as does a place nearer its neighbour than 10 grains (a grain: 10^(e − 2) m, e
the decade of the rotor's span, so a 0.7 m rotor's planes are whole millimetres); the others
move, rounded to the grain, so the planes keep the base's order, the masses that share a plane
keep sharing it, and no mass comes into a balancing plane it was not in. A drawn rotor is kept
when every balancing mass lies within BALANCING_RANGE × the base's (:func:`balancing_gap`).

Knows :mod:`.variants`; must not import the solving, the random draws' driver, the writing or
the command line.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

import numpy as np

from ..errors import SceneError
from .variants import LENGTH_SPREAD, Drawn, Handout, Variant

__all__ = ["MASS_SPREAD", "ANGLE_STEP_DEG", "PLANE_SHIFT", "BALANCING_RANGE", "draw_rotor", "balancing_gap",
           "check_rotor_base", "plane_grain"]

#: Random masses: the base's × U(1 − spread, 1 + spread).
MASS_SPREAD = 0.5
#: Random angles of the masses: multiples of this over the turn, degrees.
ANGLE_STEP_DEG = 15.0
#: A place along the shaft moves by at most this fraction of its distance to the nearer neighbour
#: (two neighbours moving toward each other keep a fifth of their distance).
PLANE_SHIFT = 0.4
#: A drawn rotor's balancing mass in each plane, as a multiple of the base's: kept within these.
BALANCING_RANGE = (0.05, 20.0)
#: A place nearer its neighbour than this many grains keeps its base position.
_STILL_GRAINS = 10


def _round3(x: float) -> float:
    return float(f"{x:.3g}")


def plane_grain(places: list[float]) -> float:
    """The rounding of a drawn plane (m): 10^(e − 2), e the decade of the span of ``places``
    (1 mm for a span of 0.1 to 1 m); 0 when they span nothing."""
    span = max(places) - min(places) if places else 0.0
    return 10.0 ** (math.floor(math.log10(span)) - 2) if span > 0.0 else 0.0


def draw_rotor(h: Handout, rng: np.random.Generator, number: int) -> Variant:
    """One random rotor (see the module), as the masses' full tables."""
    rotor = h.base_data["rotor"]
    masses = [dict(m) for m in rotor["masses"]]
    steps = round(360.0 / ANGLE_STEP_DEG)
    for m in masses:
        m["mass"] = _round3(float(m["mass"]) * rng.uniform(1 - MASS_SPREAD, 1 + MASS_SPREAD)) + 0.0
        m["radius"] = _round3(float(m["radius"]) * rng.uniform(1 - LENGTH_SPREAD, 1 + LENGTH_SPREAD))
        m["angle"] = float(rng.integers(0, steps)) * ANGLE_STEP_DEG
    balancing = {float(p) for p in rotor["balance"]["planes"]}
    places = sorted({float(m["plane"]) for m in masses if "plane" in m} | balancing)
    grain = plane_grain(places)
    moved = {}
    for k, x in enumerate(places):
        shift = rng.uniform(-PLANE_SHIFT, PLANE_SHIFT)
        gaps = [abs(x - places[j]) for j in (k - 1, k + 1) if 0 <= j < len(places)]
        if x in balancing or not gaps or min(gaps) < _STILL_GRAINS * grain:
            continue
        digits = -round(math.log10(grain))
        if x >= 0.0 > x + shift * min(gaps):      # a shaft measured from its end keeps its planes at or past it
            shift = abs(shift)
        moved[x] = round(x + shift * min(gaps), digits) + 0.0
    for m in masses:
        if "plane" in m:
            m["plane"] = moved.get(float(m["plane"]), m["plane"])
    return Variant(number=number, masses=tuple(masses))


def _masses(report: Mapping[str, Any]) -> list[float]:
    return [float(b["mass"]) for b in report["rotor"]["balancing"]]


def check_rotor_base(h: Handout, report: Mapping[str, Any]) -> None:
    """Refuse a base whose balancing mass is 0 in a plane: its variants' masses there would have
    no size to be kept near."""
    for name, m in zip(("L", "M"), _masses(report)):
        if not m > 0.0:
            raise SceneError(f"--random keeps each balancing mass within {BALANCING_RANGE[0]:g}…"
                             f"{BALANCING_RANGE[1]:g} × the base's, and the base needs none in plane {name} (its "
                             "polygon closes by itself): give a base that needs balancing in every plane, or write a "
                             "variants file", file=str(h.base), key="rotor.masses")


def balancing_gap(h: Handout, base: Mapping[str, Any], d: Drawn) -> str:
    """Why drawn rotor ``d``'s balancing masses are refused ("" when kept): one outside
    BALANCING_RANGE × the base's (``base``: the base scene's report)."""
    if not h.rotor:
        return ""
    lo, hi = BALANCING_RANGE
    for name, m0, m in zip(("L", "M"), _masses(base), _masses(d.sheets.report)):
        if not lo * m0 <= m <= hi * m0:
            return (f"{d.name}: the balancing mass in plane {name} is {m:.4g} kg, {m / m0:.3g} × the base's "
                    f"{m0:.4g} kg (kept within {lo:g}…{hi:g} ×)")
    return ""

"""Random variants around a base scene (``plans handout --random N --seed S``): lengths,
crank angle and ω1 drawn from ``numpy.random.default_rng(seed)`` in a fixed order, a draw that
does not assemble or misses the margin drawn again.

Knows :mod:`.variants` and :mod:`.solving`; must not import the writing, the index page, the
drawing or the command line.
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path
from typing import Callable

import numpy as np

from ..errors import SceneError
from ..gears.geometry import MIN_TEETH
from ..pipeline import render
from ..scene import parse_scene
from .solving import VariantError, group_margins, short_of, solve_variant, turns_fully
from .variants import (ANGLE_STEP_DEG, LENGTH_SPREAD, MARGIN_SIN, MAX_TRIES, SPEED_RANGE, SPEED_SERIES, Drawn,
                       Handout, Variant, read_base)

__all__ = ["random_variants"]

def _round3(x: float) -> float:
    """``x`` to three significant digits (as its shortest decimal)."""
    return float(f"{x:.3g}")


def _speeds(base: float) -> tuple[float, ...]:
    """The series values within SPEED_RANGE × |base| (|base| itself when none), with its sign."""
    if base == 0.0:
        return (0.0,)
    lo, hi = abs(base) * SPEED_RANGE[0], abs(base) * SPEED_RANGE[1]
    k0 = math.floor(math.log10(lo)) - 1
    found = sorted({float(f"{m:g}e{k}") for k in range(k0, k0 + 4) for m in SPEED_SERIES
                    if lo * (1 - 1e-12) <= float(f"{m:g}e{k}") <= hi * (1 + 1e-12)})
    return tuple(math.copysign(s, base) for s in (found or [abs(base)]))


def _draw(h: Handout, rng: np.random.Generator, number: int) -> Variant:
    """One random variant (see :mod:`plans.handout`); the draws are made in a fixed order."""
    if h.train:
        return _draw_train(h, rng, number)
    base_lengths = h.base_data.get("lengths", {})
    lengths = {n: _round3(float(x) * rng.uniform(1 - LENGTH_SPREAD, 1 + LENGTH_SPREAD))
               for n, x in base_lengths.items()}
    drive = h.base_data["drive"]
    pos, speed_key, _ = h.keys
    steps = int(round(360.0 / ANGLE_STEP_DEG))
    angle = float(rng.integers(0, steps)) * ANGLE_STEP_DEG
    rotary = h.angular and not _is_coupler(h)
    values = (angle,) if rotary and h.kind != "dynamics" else None   # a machine's cycle has its own positions
    speeds = _speeds(float(drive.get(speed_key, 0.0)))
    speed = speeds[int(rng.integers(0, len(speeds)))]
    return Variant(number=number, lengths=lengths, values=values, speed=speed)


def _planet_wheels(wheels: dict, carrier: str) -> set[str]:
    """The wheels of ``carrier``'s planets: those on it, and those on their shafts."""
    on = {n for n, w in wheels.items() if w.get("on") == carrier}
    return on | {n for n, w in wheels.items() if w.get("shaft") in on}


def _draw_train(h: Handout, rng: np.random.Generator, number: int) -> Variant:
    """A gear train's random variant: every wheel's teeth × U(1 − spread, 1 + spread), rounded,
    an external wheel at least MIN_TEETH (no undercut); then, carrier by carrier, each central
    wheel of a later mesh with the carrier's planets takes the teeth that close the coaxial
    condition on the first mesh's arm (a draw where no whole number does is refused by the
    train and drawn again); the input speeds from the series within SPEED_RANGE × the base's.
    The assembly and neighbourhood conditions are the train's own refusals."""
    gears = h.base_data["gears"]
    wheels = gears["wheels"]
    teeth = {}
    for name, w in wheels.items():
        z = int(round(int(w["teeth"]) * rng.uniform(1 - LENGTH_SPREAD, 1 + LENGTH_SPREAD)))
        teeth[name] = max(z, MIN_TEETH) if not w.get("internal") else z
    for carrier in gears.get("carriers", []):
        planets = _planet_wheels(wheels, carrier)
        arm = None
        for a, b in gears.get("meshes", []):
            for planet, central in ((a, b), (b, a)):
                if planet not in planets or central in planets:
                    continue
                mp, mc = float(wheels[planet].get("module", 1.0)), float(wheels[central].get("module", 1.0))
                ring = bool(wheels[central].get("internal"))
                if arm is None:
                    arm = (mc * teeth[central] + (-1 if ring else 1) * mp * teeth[planet]) / 2.0
                else:
                    z = (2.0 * arm + (1 if ring else -1) * mp * teeth[planet]) / mc
                    teeth[central] = int(round(z)) if abs(z - round(z)) < 1e-9 else max(int(z), 1)
    inputs = {str(n): speed for n, base in gears.get("input", {}).items()
              for speeds in [_speeds(float(base))] for speed in [speeds[int(rng.integers(0, len(speeds)))]]}
    return Variant(number=number, teeth=teeth, inputs=inputs)


#: What each cause of a refused draw says (see :func:`_none_works`).
_CAUSES = {"build": "had lengths that form no link", "assembly": "did not assemble, or were singular, at the "
           "drawn position", "margin": "came closer to a singular position than the margin, or their crank did not turn fully"}


def _none_works(h: Handout, causes: dict[str, list]) -> SceneError:
    """The error when MAX_TRIES draws give no variant: how many draws each cause refused, the
    most frequent first with an example, and what to change for it."""
    ranked = sorted(causes.items(), key=lambda item: -item[1][0])
    top, (_, example) = ranked[0]
    counts = ", ".join(f"{k} {_CAUSES.get(c, f'set {c[6:]}, which the base scene refuses')}" for c, (k, _) in ranked)
    drive = h.base_data.get("drive", {})
    if top == "value:angle" and drive.get("start") == "extreme":
        return SceneError(f"none of {MAX_TRIES} draws gives a variant: {counts}; --random draws each variant's "
                          'crank angle over the turn, but start = "extreme" finds the first position itself, so every '
                          'drawn angle is refused: give the base [drive] angle (the first position) instead of '
                          'start = "extreme", or write a variants file that leaves angle out', file=str(h.base),
                          key="drive.start")
    fix = f"the base's lengths ±{LENGTH_SPREAD:.0%} give too few mechanisms that work: check the base scene" \
        if top in _CAUSES else f"the draws set {top[6:]}, which the base scene refuses: check the base scene's " \
        "[drive] and [lengths]"
    return SceneError(f"none of {MAX_TRIES} draws gives a variant: {counts} (e.g. {example}); {fix}",
                      file=str(h.base), key="--random")


def _is_coupler(h: Handout) -> bool:
    """Whether the angle drive turns a link with no pivot on the frame (its angle cannot go round)."""
    links = h.base_data["links"]
    return not set(links[str(h.base_data["drive"]["link"])]) & set(links["0"])


def random_variants(path: str | Path, count: int, seed: int, *, margin: float = MARGIN_SIN,
                    progress: Callable[[int, str], None] | None = None) -> tuple[Handout, list[Drawn]]:
    """``count`` variants around the base scene at ``path``, drawn from ``default_rng(seed)``,
    each solved and kept only when it assembles with |condition| ≥ ``margin`` everywhere; a
    failed draw is drawn again (up to MAX_TRIES times a variant). Returns the handout and the
    solved variants."""
    h = read_base(path)
    base = render(parse_scene(h.base_data, file=str(h.base)))
    margins = group_margins(base, margin)
    turning = not turns_fully(base)      # a base whose crank turns fully keeps variants that do
    h = replace(h, variants=tuple(Variant(k + 1) for k in range(count)), seed=seed, margin=margin, margins=margins)
    rng = np.random.default_rng(seed)
    drawn: list[Drawn] = []
    redraws = 0
    for number in range(1, count + 1):
        causes: dict[str, list] = {}        # why draws were refused: cause → [count, the first message]
        for _ in range(MAX_TRIES):
            v = _draw(h, rng, number)
            try:
                d = solve_variant(h, v)
            except VariantError as exc:
                why = f"value:{exc.sub}" if exc.cause == "value" else exc.cause
                causes.setdefault(why, [0, exc.message])[0] += 1
                redraws += 1
                continue
            short = short_of(d.sheets, margins) or (turns_fully(d.sheets) if turning else "")
            if not short:
                drawn.append(d)
                break
            causes.setdefault("margin", [0, f"{d.name}: {short}"])[0] += 1
            redraws += 1
        else:
            raise _none_works(h, causes)
        if progress:
            progress(number, drawn[-1].name)
    variants = tuple(d.variant for d in drawn)
    return replace(h, variants=variants, redraws=redraws), drawn

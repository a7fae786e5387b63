"""Random variants around a base scene (``plans handout --random N --seed S``): lengths,
crank angle and ω1 drawn from ``numpy.random.default_rng(seed)`` in a fixed order, a draw that
does not assemble or misses the margin drawn again.

Lengths are drawn link by link (:func:`length_plan`): the points of a link that lie on one line
in the base (a centre of mass on its rod, a pin on a bar) stay on it — of the lengths between
them only the longest (the bar) is drawn, the others keep their ratio to it — and every other
length of the link is drawn on its own, so a plate keeps its shape within ±LENGTH_SPREAD. A
gear train's teeth and a rotor's masses (:mod:`.rotor`) are drawn their own ways.

Knows :mod:`.variants`, :mod:`.solving` and :mod:`.rotor`; must not import the writing, the index page, the
drawing or the command line.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import replace
from fractions import Fraction
from pathlib import Path
from typing import Callable, Mapping

import numpy as np

from ..errors import SceneError
from ..gears.geometry import MIN_TEETH
from ..pipeline import render
from ..scene import parse_scene
from ..scene.sketch import length_points
from ..scene.values import MIN_RATE
from .solving import (LINE_RTOL, VariantError, base_mechanism, group_margins, short_of, solve_variant, turns_fully,
                      variant_gap)
from .rotor import balancing_gap, check_rotor_base, draw_rotor
from .variants import (ANGLE_STEP_DEG, LENGTH_SPREAD, MARGIN_SIN, MAX_TRIES, SPEED_RANGE, SPEED_SERIES, Drawn,
                       Handout, Variant, read_base)

__all__ = ["random_variants", "length_plan"]

def _round3(x: float) -> float:
    """``x`` to three significant digits (as its shortest decimal)."""
    return float(f"{x:.3g}")


def _speeds(base: float, file: str, key: str, unit: str) -> tuple[float, ...]:
    """The series values within SPEED_RANGE × |base| (|base| itself when none), with its sign; a
    base below MIN_RATE in magnitude (but not 0) is refused, naming ``file`` and ``key``."""
    if base == 0.0:
        return (0.0,)
    if abs(base) < MIN_RATE:
        raise SceneError(f"--random draws speeds within {SPEED_RANGE[0]:g}…{SPEED_RANGE[1]:g} × the base's, and "
                         f"{base:g} {unit} is too small to draw around: give the base's speed at least {MIN_RATE:g} "
                         f"{unit} in magnitude", file=file, key=key)
    lo, hi = abs(base) * SPEED_RANGE[0], abs(base) * SPEED_RANGE[1]
    k0 = math.floor(math.log10(lo)) - 1
    found = sorted({float(f"{m:g}e{k}") for k in range(k0, k0 + 4) for m in SPEED_SERIES
                    if lo * (1 - 1e-12) <= float(f"{m:g}e{k}") <= hi * (1 + 1e-12)})
    return tuple(math.copysign(s, base) for s in (found or [abs(base)]))


def _pair(key: str, points: Mapping[str, object]) -> tuple[str, str]:
    """The two points a [lengths] key names (``AB`` or ``A-B``; the scene reader has checked it
    names exactly two)."""
    return length_points(key, points)[0]


def _decimal(x: float) -> Fraction:
    """``x`` as the decimal it is written as (its shortest repr), exactly."""
    return Fraction(repr(float(x)))


def length_plan(h: Handout) -> dict[str, tuple[str, Fraction]]:
    """How each of the base's [lengths] is drawn: key → (the key drawn, the ratio to it, exact
    in the decimals written). The lengths between points of one link that lie on one line in
    the base (within LINE_RTOL of the link's size) share the longest of them, the bar, with
    their base ratio to it; any other length is drawn on its own (itself, 1)."""
    lengths = h.base_data.get("lengths", {})
    plan = {k: (k, Fraction(1)) for k in lengths}
    mech = base_mechanism(h)
    if mech is None or not lengths:
        return plan
    pairs = {k: _pair(k, mech.sketch) for k in lengths}
    for link in mech.links.values():
        xy, pts = link.local, link.points
        size = max((math.dist(xy[a], xy[b]) for a, b in itertools.combinations(pts, 2)), default=0.0)
        mine = [k for k, (a, b) in pairs.items() if a in pts and b in pts and plan[k] == (k, 1)]
        for k in mine:
            a, b = pairs[k]
            (ax, ay), (bx, by) = xy[a], xy[b]
            line = {p for p in pts if abs((bx - ax) * (xy[p][1] - ay) - (by - ay) * (xy[p][0] - ax))
                    <= LINE_RTOL * size * math.dist(xy[a], xy[b])}
            family = [j for j in mine if set(pairs[j]) <= line]
            if len(line) < 3 or len(family) < 2:
                continue
            bar = max(family, key=lambda j: float(lengths[j]))
            for j in family:
                plan[j] = (bar, _decimal(lengths[j]) / _decimal(lengths[bar]))
    return plan


def _draw(h: Handout, rng: np.random.Generator, number: int, plan: Mapping[str, tuple[str, Fraction]]) -> Variant:
    """One random variant (see :mod:`plans.handout`); the draws are made in a fixed order: a
    factor for each length drawn (a bar at its first length), the angle, the speed (none for a
    crank the gear train turns: its ω is the train's). A length on a bar is the drawn bar × its
    ratio, exact in decimals, then rounded once to a float: the lengths of a point on the bar add
    up to the bar's within an ulp, so the scene puts the point on it."""
    if h.train:
        return _draw_train(h, rng, number)
    if h.rotor:
        return draw_rotor(h, rng, number)
    base_lengths = h.base_data.get("lengths", {})
    factors: dict[str, float] = {}
    for name in base_lengths:
        bar = plan[name][0]
        if bar not in factors:
            factors[bar] = rng.uniform(1 - LENGTH_SPREAD, 1 + LENGTH_SPREAD)
    lengths = {}
    for name in base_lengths:
        bar, ratio = plan[name]
        drawn = _round3(float(base_lengths[bar]) * factors[bar])
        lengths[name] = drawn if bar == name else float(_decimal(drawn) * ratio)
    drive = h.base_data["drive"]
    pos, speed_key, _ = h.keys
    steps = int(round(360.0 / ANGLE_STEP_DEG))
    angle = float(rng.integers(0, steps)) * ANGLE_STEP_DEG
    rotary = h.angular and not _is_coupler(h)
    values = (angle,) if rotary and h.kind != "dynamics" else None   # a machine's cycle has its own positions
    if "gears" in h.base_data:           # a crank the train turns: [drive] has no ω to vary
        return Variant(number=number, lengths=lengths, values=values)
    speeds = _speeds(float(drive.get(speed_key, 0.0)), str(h.base), f"drive.{speed_key}",
                     "rad/s" if h.angular else "m/s")
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
              for speeds in [_speeds(float(base), str(h.base), f"gears.input.{n}", "rpm")]
              for speed in [speeds[int(rng.integers(0, len(speeds)))]]}
    return Variant(number=number, teeth=teeth, inputs=inputs)


#: What each cause of a refused draw says (see :func:`_none_works`).
_CAUSES = {"build": "had lengths that form no link", "assembly": "did not assemble, or were singular, at the "
           "drawn position", "margin": "came closer to a singular position than the margin, or their crank did not turn fully",
           "shape": "changed a link's shape", "empty": "left their task nothing to find (at rest, or the balancing "
           "element 0 at the drawn position)", "stroke": "put the output off the stroke its working force acts on",
           "ratio": "needed a balancing mass outside 0.05…20 × the base's"}


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
    fixes = {"empty": "the drawn variants leave the task nothing to find: check the base scene's loads and drive",
             "stroke": "its working force acts on too little of the turn: check the force's stroke and from",
             "ratio": "the drawn masses rarely balance with masses of the base's size: check its balancing radii",
             "shape": "the base's links cannot keep their shapes with their lengths drawn: give a centre of mass on a "
                      "bar by its distances to both ends"}
    if top in _CAUSES:
        fix = fixes.get(top, f"the base's lengths ±{LENGTH_SPREAD:.0%} give too few mechanisms that work: check the "
                        "base scene")
    else:
        fix = f"the draws set {top[6:]}, which the base scene refuses: check the base scene's [drive] and [lengths]"
    return SceneError(f"none of {MAX_TRIES} draws gives a variant: {counts} (e.g. {example}); {fix}",
                      file=str(h.base), key="--random")


def _is_coupler(h: Handout) -> bool:
    """Whether the angle drive turns a link with no pivot on the frame (its angle cannot go round)."""
    links = h.base_data["links"]
    return not set(links[str(h.base_data["drive"]["link"])]) & set(links["0"])


def _off_stroke(h: Handout, d: Drawn) -> str:
    """Why a forces assignment's drawn position misses a force that acts on one stroke only (the
    working force of a press or a slider): "" when every such force acts there."""
    if h.kind != "forces" or d.sheets.forces is None:
        return ""
    external = [load for load in d.sheets.forces.loads if load.kind == "external"]
    for f, load in zip(d.scene.forces, external):
        if f.stroke != "both" and not np.any(load.force[0]):
            return f"{d.name}: the force at {f.at} acts on the {f.stroke} stroke only, and the drawn position is off it"
    return ""


def _at_rest(h: Handout, base: Drawn) -> None:
    """Refuse a base whose variants would all have nothing to find: at rest (a zero speed is
    drawn as zero) and asking nothing (:func:`~.solving.variant_gap`); a rotor whose base needs
    no balancing mass in a plane (:func:`~.rotor.check_rotor_base`)."""
    if h.rotor:
        return check_rotor_base(h, base.sheets.report)
    if h.train:
        inputs = h.base_data["gears"].get("input", {})
        still, key = all(float(n) == 0.0 for n in inputs.values()), f"gears.input.{next(iter(inputs), '')}"
    elif "gears" in h.base_data:
        still, key = False, ""
    else:
        speed_key = h.keys[1]
        still, key = float(h.base_data["drive"].get(speed_key, 0.0)) == 0.0, f"drive.{speed_key}"
    gap = variant_gap(base) if still else ""
    if gap.startswith("nothing to find"):
        raise SceneError(f"--random keeps a zero speed zero, so every variant would have {gap}", file=str(h.base),
                         key=key)


def random_variants(path: str | Path, count: int, seed: int, *, margin: float = MARGIN_SIN,
                    progress: Callable[[int, str], None] | None = None) -> tuple[Handout, list[Drawn]]:
    """``count`` variants around the base scene at ``path``, drawn from ``default_rng(seed)``,
    each solved and kept only when it assembles with |condition| ≥ ``margin`` everywhere, keeps
    its links' shapes, has something to find and (a forces assignment) has its working force
    acting at the drawn position; a failed draw is drawn again (up to MAX_TRIES times a variant),
    its cause counted for the error when none works. A base whose variants would all be at rest
    with nothing to find is refused at once. Returns the handout and the solved variants."""
    h = read_base(path)
    scene = parse_scene(h.base_data, file=str(h.base))
    base = render(scene)
    _at_rest(h, Drawn(Variant(0), "the base", scene, base))
    plan = length_plan(h)
    margins = group_margins(base, margin)
    turning = not turns_fully(base)      # a base whose crank turns fully keeps variants that do
    h = replace(h, variants=tuple(Variant(k + 1) for k in range(count)), seed=seed, margin=margin, margins=margins)
    rng = np.random.default_rng(seed)
    drawn: list[Drawn] = []
    redraws = 0
    for number in range(1, count + 1):
        causes: dict[str, list] = {}        # why draws were refused: cause → [count, the first message]
        for _ in range(MAX_TRIES):
            v = _draw(h, rng, number, plan)
            try:
                d = solve_variant(h, v)
            except VariantError as exc:
                why = f"value:{exc.sub}" if exc.cause == "value" else exc.cause
                causes.setdefault(why, [0, exc.message])[0] += 1
                redraws += 1
                continue
            short = short_of(d.sheets, margins) or (turns_fully(d.sheets) if turning else "")
            off = "" if short else _off_stroke(h, d) or balancing_gap(h, base.report, d)
            if not short and not off:
                drawn.append(d)
                break
            cause = "margin" if short else "ratio" if h.rotor else "stroke"
            causes.setdefault(cause, [0, off or f"{d.name}: {short}"])[0] += 1
            redraws += 1
        else:
            raise _none_works(h, causes)
        if progress:
            progress(number, drawn[-1].name)
    variants = tuple(d.variant for d in drawn)
    return replace(h, variants=variants, redraws=redraws), drawn

"""What a student doing a handout's graphical task finds, and how closely a drawing gives it.

**A machine's dynamics** (kind ``dynamics``): the task asks for the works by graphical
integration over the cycle's N positions, then Wittenbauer's diagram. Its answers are the
chord method's at those positions, as the key's dynamics sheet draws it
(:func:`plans.constructions.dynamics.dynamics_diagrams`: over each interval M_r is taken at
the interval's middle and the chord rises by that ordinate × Δφ), not the exact values: the
chords differ from the exact works by the quadrature's error, a few % and up to some 10 % where
a load jumps between two positions (the compressor at 12 positions: J 9 % above the exact).
Refining the positions instead would take 36 to 72 of them for the examples whose loads jump
(a force analysis each), and the cycle's positions are equally spaced (plans.dynamics): the task
keeps its positions and is marked against the method at them.

- M_d: the constant moment whose work over the cycle equals the chords' work, −A_g(Φ)/Φ over
  the cycle Φ (2π a turn; counter-clockwise +, as the JSON's ``constant_moment``); not asked when
  ``[dynamics] driving`` is a law (it is then given);
- J_fw: Wittenbauer's tangents, tan ψ = ω_m²(1 ± δ)/2, to the N points (I_r, ΔT_g) joined by
  straight lines (so the tangents touch at points): J = (max_k(ΔT_k − k₊·I_k) −
  min_k(ΔT_k − k₋·I_k))/(ω_m²·δ), I_r with the rotor's;
- δ reached with a given flywheel J: the δ whose tangents give that J (bisection: the J of the
  tangents falls as δ grows).

Each has its drawing precision, a length read to :data:`READ_MM` (the dynamics sheet's ±0.5 mm)
at the key's scales: M_d from A_g(Φ) on the work graph, μ_A·READ_MM/Φ; J and δ from the
segment kl the tangents cut on Wittenbauer's ΔT axis, μ_T·READ_MM/(ω_m²·δ) and
μ_T·READ_MM/(ω_m²·J).

**A rotor's balancing** (kind ``balancing``): the polygons sum exactly what they draw, so the
masses and angles are marked against the exact ones; their precision: the closing vector read to
READ_MM at the key's polygon scale (m_L = |m·r|_L/r_L from the force polygon, m_M =
|m·r·l|_M/(r_M·|l_M|) from the couple polygon), its direction to :data:`ANGLE_READ_DEG` plus the
turn READ_MM at its head gives it, READ_MM/length.

Knows the pipeline's stages, the constructions and plans.dynamics' balancing; must not import
any other module of :mod:`plans.handout`.
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass

import numpy as np

from ..constructions.balancing import balance_polygons
from ..constructions.dynamics import dynamics_diagrams
from ..dynamics.balancing import balance_rotor
from ..pipeline.sheets.dynamics import READ_MM
from ..pipeline.stages import machine_motion, solve_motion
from ..scene import Scene

__all__ = ["READ_MM", "ANGLE_READ_DEG", "Chords", "chord_answers", "tangent_inertia", "tangent_delta",
           "balancing_precision"]

#: How closely a direction is read with a protractor, degrees (its least division).
ANGLE_READ_DEG = 1.0
#: Bisection steps for δ with a given flywheel (2⁻⁶⁰ of the bracket: below a double's rounding).
_STEPS = 60


@dataclass(frozen=True)
class Chords:
    """A dynamics task's answers by the chord method at its ``positions`` N: ``moment`` M_d
    (N·m, counter-clockwise +), ``inertia`` J_fw (kg·m²; None with a given flywheel), ``delta``
    δ reached (None when δ is given), and the drawing precision of each (same units)."""

    positions: int
    moment: float
    moment_precision: float
    inertia: float | None
    inertia_precision: float
    delta: float | None
    delta_precision: float


def tangent_inertia(energy: np.ndarray, inertia: np.ndarray, omega_m: float, delta: float) -> float:
    """J (kg·m²) by Wittenbauer's tangents (tan ψ = ω_m²(1 ± δ)/2) to the points (I_k, ΔT_k)
    joined by straight lines: (max(ΔT − k₊·I) − min(ΔT − k₋·I))/(ω_m²·δ)."""
    w2 = omega_m * omega_m
    hi, lo = 0.5 * w2 * (1.0 + delta), 0.5 * w2 * (1.0 - delta)
    return float((np.max(energy - hi * inertia) - np.min(energy - lo * inertia)) / (w2 * delta))


def tangent_delta(energy: np.ndarray, inertia: np.ndarray, omega_m: float, flywheel: float) -> float:
    """δ whose Wittenbauer tangents to the points give the flywheel ``flywheel`` (kg·m²), by
    bisection on (0, 1): :func:`tangent_inertia` falls as δ grows."""
    lo, hi = 0.0, 1.0
    for _ in range(_STEPS):
        mid = 0.5 * (lo + hi)
        if mid == 0.0 or tangent_inertia(energy, inertia, omega_m, mid) > flywheel:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


_CACHE: dict[int, tuple[weakref.ref, Chords]] = {}


def chord_answers(scene: Scene) -> Chords:
    """The chord method's answers of a scene with ``[dynamics]`` (see the module), solved once a
    scene object (a variant's scene asked again gives the same answers at once)."""
    hit = _CACHE.get(id(scene))
    if hit is not None and hit[0]() is scene:
        return hit[1]
    _, cycle = solve_motion(scene)
    machine = machine_motion(scene, cycle)
    assert machine is not None, "chord_answers needs a scene with [dynamics] and a cycle"
    d = dynamics_diagrams(machine)
    _, a, t, _ = d.graphs
    n = d.positions
    work = a.graphical[-1][2]                  # the graph's work over the cycle: ± the loads' (A_d of an engine)
    loads = work if d.loads_drive else -work
    cycle = math.radians(machine.period)
    moment = machine.sense * (-loads / cycle) + 0.0
    energy = np.array([v for _, _, v in t.graphical[:n]])
    inertia = np.asarray(machine.inertia(machine.theta), dtype=float)
    wheel, w2 = machine.flywheel, machine.omega_m ** 2
    j = dj = None
    if wheel.given:
        j_given = wheel.inertia_exact
        delta = tangent_delta(energy, inertia, machine.omega_m, j_given)
        ddelta = t.mu * READ_MM / (w2 * j_given) if j_given > 0.0 else math.inf
    else:
        delta, ddelta = None, 0.0
        j = tangent_inertia(energy, inertia, machine.omega_m, wheel.delta)
        dj = t.mu * READ_MM / (w2 * wheel.delta)
    out = Chords(positions=n, moment=moment, moment_precision=a.mu * READ_MM / cycle, inertia=j,
                 inertia_precision=dj or 0.0, delta=delta, delta_precision=ddelta)
    key = id(scene)
    _CACHE[key] = (weakref.ref(scene, lambda _, k=key: _CACHE.pop(k, None)), out)
    return out


def balancing_precision(scene: Scene) -> tuple[tuple[float, float], ...]:
    """For each balancing plane of the scene's ``[rotor]`` (L, then M): how closely its mass (kg)
    and its angle (degrees) are read off the key's polygons (see the module); an angle of a
    closing vector shorter than READ_MM is not readable (180°)."""
    b = balance_rotor(scene.rotor)
    polygons = {p.kind: p for p in balance_polygons(b)}
    out = []
    for k, plane in enumerate(b.balancing):
        poly = polygons["force" if k == 0 else "couple"]
        per_mm = poly.mu / plane.radius if k == 0 else poly.mu / (plane.radius * abs(plane.l))
        length = poly.closing.value / poly.mu if poly.closing is not None else 0.0
        turn = math.degrees(math.asin(READ_MM / length)) if length > READ_MM else 180.0
        out.append((READ_MM * per_mm, min(ANGLE_READ_DEG + turn, 180.0)))
    return tuple(out)

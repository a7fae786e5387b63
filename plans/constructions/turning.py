"""The ``-turning`` sheet's geometry (paper mm, y up): the turning-moment diagram T(θ) of a
machine given by its crank torque, to scale, with the resisting torque's line T_res(θ), each
area between them (from 0°, the crossings and the end of the period) as a closed outline with
its signed energy, the ordinates of T at the table's vertices and at the crossings (measured
segments), and the angles of the greatest and least speed.

An area's outline runs along T from one crossing to the next and back along T_res on the dense
grid of :class:`~plans.dynamics.turning.TurningAnalysis` (every break and crossing in it): its
area in mm² × μT × μθ (rad/mm) is its energy in J, within the chords' error on the grid (exact for
tables and triangles). Reads a solved analysis; computes nothing of the dynamics.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..dynamics.turning import TurningAnalysis
from .diagrams import ticks_for
from .scales import fitting_scale

__all__ = ["TurningArea", "TurningDiagram", "turning_diagram", "THETA_MM", "TORQUE_MM"]

#: Largest length of the θ axis (one period) and height of the diagram, mm.
THETA_MM = 250.0
TORQUE_MM = 110.0


@dataclass(frozen=True)
class TurningArea:
    """Area ``number`` (1 …) between θ ``start`` and ``end`` (deg): ``energy`` (J, + where T
    exceeds T_res), its ``outline`` (mm, closed) and where its label goes (mm)."""

    number: int
    start: float
    end: float
    energy: float
    outline: tuple[tuple[float, float], ...]
    label_at: tuple[float, float]


@dataclass(frozen=True)
class TurningDiagram:
    """``mu_theta`` (rad/mm) and ``mu_t`` (N·m/mm); the ``torque`` and ``resisting`` curves (mm);
    ``areas``; ``ordinates`` (θ deg, x mm, y mm, T N·m) at the vertices and crossings; the axes'
    ``theta_ticks`` (deg, x mm) and ``t_ticks`` (N·m, y mm); ``low``/``high`` (mm, the drawn range)
    and ``length`` (mm); ``extremes`` (which, θ deg, x mm) of the speed."""

    mu_theta: float
    mu_t: float
    torque: tuple[tuple[float, float], ...]
    resisting: tuple[tuple[float, float], ...]
    areas: tuple[TurningArea, ...]
    ordinates: tuple[tuple[float, float, float, float], ...]
    theta_ticks: tuple[tuple[float, float], ...]
    t_ticks: tuple[tuple[float, float], ...]
    low: float
    high: float
    length: float
    extremes: tuple[tuple[str, float, float], ...]


def turning_diagram(a: TurningAnalysis) -> TurningDiagram:
    """The diagram of a solved cycle (see the module)."""
    period_rad = a.period * math.pi / 180.0
    mu_theta = fitting_scale(period_rad, THETA_MM)
    lo = min(0.0, float(np.min(a.torque)), float(np.min(a.resisting)))
    hi = max(0.0, float(np.max(a.torque)), float(np.max(a.resisting)))
    mu_t = fitting_scale(hi - lo if hi > lo else 1.0, TORQUE_MM)
    theta = np.asarray(a.theta, float)

    def x(deg) -> np.ndarray:
        return np.asarray(deg, float) * (math.pi / 180.0) / mu_theta

    xs = x(theta)
    torque = tuple(zip(xs.tolist(), (np.asarray(a.torque) / mu_t).tolist()))
    resisting = tuple(zip(xs.tolist(), (np.asarray(a.resisting) / mu_t).tolist()))
    bounds = [0.0] + [float(c) for c in a.crossings if c > 0.0] + [float(a.period)]
    areas = []
    for k, (t0, t1) in enumerate(zip(bounds[:-1], bounds[1:])):
        inside = (theta >= t0 - 1e-12) & (theta <= t1 + 1e-12)
        tx, tt, tr = xs[inside], np.asarray(a.torque)[inside] / mu_t, np.asarray(a.resisting)[inside] / mu_t
        outline = list(zip(tx.tolist(), tt.tolist())) + list(zip(tx[::-1].tolist(), tr[::-1].tolist()))
        j = int(np.argmax(np.abs(tt - tr)))
        areas.append(TurningArea(k + 1, t0, t1, float(a.areas[k]), tuple(outline),
                                 (float(tx[j]), float(0.5 * (tt[j] + tr[j])))))
    at = sorted(set([float(v) for v in a.breaks] + [float(c) for c in a.crossings]) | {0.0, float(a.period)})
    ords = []
    for deg in at:
        k = int(np.argmin(np.abs(theta - deg)))
        ords.append((deg, float(xs[k]), float(a.torque[k] / mu_t), float(a.torque[k])))
    step = 30.0 if a.period <= 360.0 else 60.0
    theta_ticks = tuple((d, float(x(d))) for d in np.arange(0.0, a.period + 1e-9, step))
    t_ticks = tuple((v, v / mu_t) for v in ticks_for(lo, hi, 8)) if hi > lo else ((0.0, 0.0),)
    extremes = (("max", float(a.energy_max_at), float(x(a.energy_max_at))),
                ("min", float(a.energy_min_at), float(x(a.energy_min_at))))
    return TurningDiagram(mu_theta, mu_t, torque, resisting, tuple(areas), tuple(ords), theta_ticks, t_ticks,
                          lo / mu_t, hi / mu_t, float(x(a.period)), extremes)

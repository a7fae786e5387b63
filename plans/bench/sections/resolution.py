"""Section 3 of ``plans bench``: positions per revolution → error of graphical differentiation
of the slider's s(φ) against the exact velocity and acceleration.

Knows the kinematics; must not import another section module, :mod:`plans.bench` itself or
the command line.
"""

from __future__ import annotations

import math

import numpy as np

from ...kinematics import analyse
from ..chart import Chart, Series
from ..timing import best_time
from .common import Column, Config, Section, cycle_angles, load_example

__all__ = ["CYCLE_SCENE", "cycle_resolution"]

CYCLE_SCENE = "crank_slider_central"


def cycle_resolution(cfg: Config) -> Section:
    """Positions per revolution → error of the slider's velocity and acceleration found by
    graphical differentiation (periodic central differences of s(φ)) against the exact ones."""
    mech, structure = load_example(CYCLE_SCENE)
    prism = next(p for p in mech.prismatics if p.guide == "0")
    u = np.asarray(prism.direction, float)            # the guide is fixed in the frame: a world direction
    point = prism.label
    omega, eps = mech.drive.speed, mech.drive.rate

    def numeric(angles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        s = analyse(mech, structure, angles, order=0).position(point) @ u
        h = math.radians(360.0 / len(angles))
        nxt, prv = np.roll(s, -1), np.roll(s, 1)
        d1 = (nxt - prv) / (2 * h)
        d2 = (nxt - 2 * s + prv) / (h * h)
        return d1 * omega, d2 * omega ** 2 + d1 * eps   # v = s'·ω, a = s''·ω² + s'·ε

    rows = []
    prev = None
    for n in cfg.resolutions:
        angles = cycle_angles(mech, n)
        exact = analyse(mech, structure, angles, order=2)
        v_ex, a_ex = exact.velocity(point) @ u, exact.acceleration(point) @ u
        v_num, a_num = numeric(angles)
        ev = float(np.max(np.abs(v_num - v_ex)) / np.max(np.abs(v_ex)))
        ea = float(np.max(np.abs(a_num - a_ex)) / np.max(np.abs(a_ex)))
        order = None if prev is None else math.log(prev[1] / ev) / math.log(n / prev[0])
        t_num = best_time(lambda: numeric(angles), repeat=cfg.repeat)
        t_ex = best_time(lambda: analyse(mech, structure, angles, order=2), repeat=cfg.repeat)
        rows.append((n, 360.0 / n, ev, ea, order, t_num * 1e3, t_ex * 1e3))
        prev = (n, ev)
    cols = (Column("positions", "positions/turn", "d"), Column("step_deg", "step (°)", "g"),
            Column("v_rel_error", "v rel. error", ".1e"), Column("a_rel_error", "a rel. error", ".1e"),
            Column("observed_order_v", "order (v)", ".2f"), Column("ms_numeric", "ms differentiated", ".2f"),
            Column("ms_exact", "ms exact", ".2f"))
    xs = tuple(float(r[0]) for r in rows)
    notes = [f"slider {point} of {CYCLE_SCENE}: s(φ) along its guide at n evenly spaced crank angles; "
             "v = ω·(s[k+1] − s[k−1])/2h, a = ω²·(s[k+1] − 2s[k] + s[k−1])/h² (periodic), against "
             "plans.kinematics.analyse(order=2); errors relative to the largest |v|, |a| over the turn.",
             "ms differentiated: positions (order 0) + differences; ms exact: the analytic velocities and "
             f"accelerations at the same positions; best of {cfg.repeat}. Both walk the drive in 1° steps from "
             "the sketch, so below 360 positions the time hardly changes."]
    charts = [Chart("cycle-resolution", "Cycle resolution: graphical differentiation of s(φ)",
                    "positions per revolution", "relative error",
                    (Series("velocity", xs, tuple(r[2] for r in rows)),
                     Series("acceleration", xs, tuple(r[3] for r in rows))), log_x=True, log_y=True,
                    note="central differences: error ∝ h² (slope −2)")]
    return Section("cycle_resolution", "3. Cycle resolution (graphical differentiation vs exact)", cols, rows,
                   notes, {"scene": CYCLE_SCENE, "point": point}, charts)

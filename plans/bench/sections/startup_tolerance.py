"""Section 11 of ``plans bench``: the motor start-up's integrator tolerance → its error and its
time (what accuracy costs).

Knows the dynamics; must not import another section module, :mod:`plans.bench` itself or the
command line.
"""

from __future__ import annotations

import numpy as np

from ...dynamics import machine_dynamics, startup
from ...pipeline.stages import solve_motion
from ...scene import read_scene
from ..chart import Chart, Series
from .common import Column, Config, Section, best_of, example_path

__all__ = ["STARTUP_SCENE", "startup_tolerance"]

STARTUP_SCENE = "six_link_press_startup"
#: The reference run's relative tolerance in the full run (DOP853 near double precision);
#: each configuration names its own (Config.startup_reference_rtol).
REFERENCE_RTOL = 1e-13


def startup_tolerance(cfg: Config) -> Section:
    """DOP853's rtol → the largest error of ω(t) over the start-up against a run at
    cfg.startup_reference_rtol, the error of δ over the last revolution, the right side's evaluations and the time."""
    scene = read_scene(example_path(STARTUP_SCENE))
    _, cycle = solve_motion(scene)
    machine = machine_dynamics(scene, cycle)
    motor, t_end = scene.dynamics.motor, cfg.startup_t_end
    ref_rtol = cfg.startup_reference_rtol
    ref = startup(machine, motor, t_end, rtol=ref_rtol, atol=ref_rtol * 0.1)
    rows = []
    for rtol in cfg.startup_tolerances:
        seconds, run = best_of(lambda: startup(machine, motor, t_end, rtol=rtol, atol=rtol * 1e-2), cfg.repeat)
        err = float(np.max(np.abs(run.omega - ref.omega)) / machine.omega_m)
        d_err = abs(run.last[2] - ref.last[2]) / ref.last[2] if run.last and ref.last else None
        rows.append((rtol, err, d_err, run.evaluations, seconds))
    cols = (Column("rtol", "rtol", ".0e"), Column("omega_rel_error", "ω error / ω_m", ".1e"),
            Column("delta_rel_error", "δ rel. error", ".1e"), Column("evaluations", "evaluations", "d"),
            Column("seconds", "time (s)", ".3f"))
    xs = tuple(r[0] for r in rows)
    notes = [f"{STARTUP_SCENE}: the start-up from rest for {t_end:g} s by solve_ivp's DOP853 at rtol (atol = rtol/100 "
             f"rad, rad/s); ω(t) at {len(ref.t)} instants against a run at rtol = {ref_rtol:g}; δ over the last "
             "whole revolution before the end (— before two whole turns, 4.5 s; the steady δ once the start-up, "
             "about 8 s, is over; before that its error still measures the integrator). Time: the integration alone (the steady cycle's shooting "
             "included), best of "
             f"{cfg.repeat}. plans uses rtol = 1e-10."]
    charts = [Chart("startup-tolerance", "Start-up: integrator tolerance against error", "rtol", "ω error / ω_m",
                    (Series("ω(t)", xs, tuple(max(r[1], 1e-16) for r in rows)),), log_x=True, log_y=True,
                    note="DOP853: the error follows rtol down to a floor near 1e-9")]
    return Section("startup_tolerance", "11. Start-up: integrator tolerance (error vs time)", cols, rows, notes,
                   {"scene": STARTUP_SCENE, "t_end": t_end}, charts)

"""Section 5 of ``plans bench``: the crank-slider and the four-bar over one turn solved by
pylinkage and by plans in the same run (skipped when pylinkage is not installed).

Knows the kinematics and :mod:`.pylinkage_model`; must not import another section module,
:mod:`plans.bench` itself or the command line.
"""

from __future__ import annotations

import math

import numpy as np

from ...kinematics import analyse
from ..chart import Chart, Series
from ..timing import best_time, once
from .common import Column, Config, Section, cycle_angles, load_example, max_norm
from .pylinkage_model import INSTALL_HINT, pylinkage_model

__all__ = ["PEER_SCENES", "peer_comparison"]

PEER_SCENES = ("crank_slider_central", "four_bar")


def peer_comparison(cfg: Config) -> Section:
    """The crank-slider and the four-bar over one turn, solved by pylinkage and by plans in the
    same run: time ratio and largest differences of positions, velocities, accelerations."""
    title = "5. Peer comparison (pylinkage, same cycles)"
    try:
        import pylinkage as pl
    except ImportError:
        return Section("peer_comparison", title, skipped="pylinkage is not installed: section skipped; install "
                       f"the bench extra: {INSTALL_HINT}")
    try:
        from pylinkage._numba_compat import HAS_NUMBA   # pylinkage's own flag; absent in other versions
    except ImportError:   # pragma: no cover
        HAS_NUMBA = None
    version = getattr(pl, "__version__", "?")
    n = cfg.peer_positions
    rows = []
    curves = []
    for stem in PEER_SCENES:
        mech, structure = load_example(stem)
        angles = cycle_angles(mech, n)
        step = 360.0 / n

        def fresh():
            return pylinkage_model(pl, mech, stem, float(angles[0]), step)

        def best_pyl(method: str) -> tuple[float, list]:
            warm, _ = fresh()   # numba compiles (or loads) its kernels on their first call: not timed
            list(getattr(warm, method)(2))
            best, out = math.inf, None
            for _ in range(max(cfg.repeat, 1)):
                linkage, _ = fresh()
                t, out = once(lambda: list(getattr(linkage, method)(n)))
                best = min(best, t)
            return best, out

        t_pyl_pos, steps = best_pyl("step")
        t_pyl_all, derived = best_pyl("step_with_derivatives")
        t_plans_pos = best_time(lambda: analyse(mech, structure, angles, order=0), repeat=cfg.repeat)
        t_plans_all = best_time(lambda: analyse(mech, structure, angles, order=2), repeat=cfg.repeat)
        motion = analyse(mech, structure, angles, order=2)
        _, index = fresh()
        dr = dr_all = dv = da = 0.0
        worst_curve = np.zeros(n)
        for p, k in index.items():
            pos = np.array([s[k] for s in steps], dtype=float)
            pos2 = np.array([s[0][k] for s in derived], dtype=float)
            vel = np.array([s[1][k] for s in derived], dtype=float)
            acc = np.array([s[2][k] for s in derived], dtype=float)
            gap = np.linalg.norm(pos - motion.position(p), axis=1)
            worst_curve = np.maximum(worst_curve, gap)
            dr = max(dr, float(np.max(gap)))
            dr_all = max(dr_all, max_norm(pos2, motion.position(p)))
            dv = max(dv, max_norm(vel, motion.velocity(p)))
            da = max(da, max_norm(acc, motion.acceleration(p)))
        compared = ", ".join(index)
        rows.append((stem, "positions", n, t_plans_pos * 1e3, t_pyl_pos * 1e3, t_pyl_pos / t_plans_pos, dr,
                     None, None, compared))
        rows.append((stem, "pos + vel + acc", n, t_plans_all * 1e3, t_pyl_all * 1e3, t_pyl_all / t_plans_all,
                     dr_all, dv, da, compared))
        curves.append(Series(f"{stem} (points {compared})", tuple(float(a - angles[0]) for a in angles),
                             tuple(worst_curve)))
    cols = (Column("scene", "scene", "s"), Column("what", "what", "s"), Column("positions", "N", "d"),
            Column("plans_ms", "plans ms", ".2f"), Column("pylinkage_ms", "pylinkage ms", ".2f"),
            Column("speed_ratio", "pylinkage/plans time", ".2f"), Column("max_dr_m", "max |Δr| (m)", ".1e"),
            Column("max_dv", "max |Δv| (m/s)", ".1e"), Column("max_da", "max |Δa| (m/s²)", ".1e"),
            Column("points", "points", "s"))
    notes = [f"pylinkage {version} (numba {'installed' if HAS_NUMBA else 'not installed: its pure-Python path'}): "
             "Linkage.step() for positions, step_with_derivatives() with set_input_velocity(ω, ε) for velocities "
             "and accelerations; plans: analyse(order=0) and analyse(order=2).",
             f"Same dimensions (read from the plans model), same {n} crank angles from the sketch's "
             f"({360 / n:g}° steps), same assembly branch (pylinkage's dyad starts at the sketch's joint); model "
             f"construction not timed; best of {cfg.repeat}.",
             "pylinkage/plans time > 1: plans is faster. plans walks the drive from the sketch in 1° steps "
             "(branch continuation) whatever N, which is most of its time at small N.",
             "|Δr| grows along the turn because pylinkage turns its crank step by step (atan2 of the current "
             "position + Δφ), so its crank pin A itself drifts by rounding; plans places every angle directly."]
    summary = {"pylinkage": version, "numba": HAS_NUMBA,
               "max_position_difference_m": max(r[6] for r in rows),
               "plans_faster": {f"{r[0]} {r[1]}": r[5] > 1 for r in rows}}
    charts = [Chart("peer-difference", "pylinkage vs plans: position difference over the turn",
                    "crank turned from the sketch (°)", "largest |Δr| of the compared points (m)", tuple(curves),
                    log_y=True)]
    return Section("peer_comparison", title, cols, rows, notes, summary, charts)

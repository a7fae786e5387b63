"""Section 7 of ``plans bench``: full analysis (order 2) time per position of a class III and a
class IV example against the crank-slider.

Knows the kinematics; must not import another section module, :mod:`plans.bench` itself or
the command line.
"""

from __future__ import annotations

from typing import Any, Callable

from ...kinematics import analyse
from ..chart import Chart, Series
from ..timing import best_time, once
from .common import TIMING_BUDGET, Column, Config, Section, best_of, cycle_angles, load_example

__all__ = ["CLASS_COST_TARGET", "CLASS_SCENES", "class_cost"]

#: A class III or IV example may cost at most this many times the crank-slider per position.
CLASS_COST_TARGET = 10.0

CLASS_SCENES = ("crank_slider_central", "class3_six_link", "class4_six_link")


def _timed(fn: Callable[[], Any], repeat: int) -> float:
    """Seconds per call after a warm-up call: short calls looped (best_time), slow ones repeated
    within TIMING_BUDGET."""
    first, _ = once(fn)
    if first < 0.05:
        return best_time(fn, repeat=repeat)
    return best_of(fn, repeat)[0]


def class_cost(cfg: Config) -> Section:
    """Full analysis (order 2) time per position of a class III and a class IV example against
    the crank-slider, at cfg.class_positions (72) and cfg.class_large_positions a turn."""
    small, large = cfg.class_positions, cfg.class_large_positions
    measured = []
    for stem in CLASS_SCENES:
        mech, structure = load_example(stem)
        per = []
        for n in (small, large):
            angles = cycle_angles(mech, n)
            per.append(_timed(lambda: analyse(mech, structure, angles, order=2), cfg.repeat) / n)
        groups = " ".join(str(g.name) for g in structure.groups)
        measured.append((stem, structure.klass, groups, per))
    ref = measured[0][3]
    rows = []
    for stem, klass, groups, per in measured:
        ratio = per[0] / ref[0]
        verdict = "reference" if stem == CLASS_SCENES[0] else \
            ("met" if ratio <= CLASS_COST_TARGET else f"over ×{ratio / CLASS_COST_TARGET:.1f}")
        rows.append((stem, klass, groups, small, per[0] * 1e6, ratio, verdict, large, per[1] * 1e6, per[1] / ref[1]))
    cols = (Column("scene", "scene", "s"), Column("class", "class", "d"), Column("groups", "groups", "s"),
            Column("positions", "N", "d"), Column("us_per_position", "µs/pos", ".1f"),
            Column("ratio", "× crank-slider", ".1f"), Column("target", f"≤{CLASS_COST_TARGET:g}×", "s"),
            Column("large_positions", "N'", "d"), Column("large_us_per_position", "µs/pos at N'", ".2f"),
            Column("large_ratio", "× crank-slider at N'", ".1f"))
    notes = ["plans.kinematics.analyse(mech, structure, angles, order=2): positions, velocities and accelerations "
             f"of every point at N = {small} crank angles evenly over one turn from the sketch (one call), per "
             f"position; × crank-slider: against {CLASS_SCENES[0]} at the same N "
             f"(target ≤ {CLASS_COST_TARGET:g}×).",
             f"N' = {large}: the same at more positions a turn, to show what is fixed cost per call. Warm-up call "
             f"first; best of {cfg.repeat} (calls over {TIMING_BUDGET:g} s: fewer, within that budget)."]
    summary = {"target": CLASS_COST_TARGET, "positions": small,
               "ratios": {row[0]: row[5] for row in rows[1:]},
               "met": all(row[5] <= CLASS_COST_TARGET for row in rows[1:])}
    xs = (float(small), float(large))
    charts = [Chart("class-cost", "Full analysis (order 2): time per position by group class",
                    "positions per turn", "µs per position",
                    tuple(Series(f"{row[0]} (class {row[1]})", xs, (row[4], row[8])) for row in rows),
                    log_x=True, log_y=True)]
    return Section("class_cost", f"7. Class III / IV cost per position (vs crank-slider, target ≤ "
                   f"{CLASS_COST_TARGET:g}× at {small} a turn)", cols, rows, notes, summary, charts)

"""Section 4 of ``plans bench``: throughput of the vectorised analysis against a per-angle
loop (:func:`throughput`) and plans rendered per second (:func:`render_rate`, 4b).

Knows the kinematics and the pipeline; must not import another section module,
:mod:`plans.bench` itself or the command line.
"""

from __future__ import annotations

import math

import numpy as np

from ...kinematics import analyse
from ...pipeline import render_scene
from ..chart import Chart, Series
from ..timing import best_time, once
from .common import Column, Config, Section, cycle_angles, example_path, load_example, max_norm

__all__ = ["THROUGHPUT_TARGET", "THROUGHPUT_SCENES", "LOOP_PASSES", "throughput", "render_rate"]

#: The vectorised analysis should beat a per-angle Python loop by at least this factor.
THROUGHPUT_TARGET = 20.0

THROUGHPUT_SCENES = ("crank_slider_central", "six_link_press")
#: Passes of the per-angle loop (each some 0.2–1 s in the full bench); the best is kept.
LOOP_PASSES = 3


def throughput(cfg: Config) -> Section:
    """Positions per second of the full analysis (order 2) vectorised over N angles against
    a Python loop calling analyse with one angle at a time."""
    rows = []
    series = []
    loop_series = []
    batch: dict[str, dict[int, float]] = {}
    n = cfg.throughput_positions
    for stem in THROUGHPUT_SCENES:
        mech, structure = load_example(stem)
        angles = cycle_angles(mech, n)
        t_vec = best_time(lambda: analyse(mech, structure, angles, order=2), repeat=cfg.repeat)
        vec = analyse(mech, structure, angles, order=2)
        pick = np.linspace(0, n, cfg.loop_positions, endpoint=False).astype(int)
        t_loop = math.inf
        for _ in range(min(cfg.repeat, LOOP_PASSES)):   # whole passes over the picked angles: the best one
            t, singles = once(lambda: [analyse(mech, structure, angles[i:i + 1], order=2) for i in pick])
            t_loop = min(t_loop, t)
        r_vec = {p: vec.position(p) for p in mech.sketch}
        a_vec = {p: vec.acceleration(p) for p in mech.sketch}
        a_max = max(float(np.max(np.linalg.norm(a, axis=1))) for a in a_vec.values())
        diff = max(max(max_norm(m.position(p), r_vec[p][i:i + 1]),
                       max_norm(m.acceleration(p), a_vec[p][i:i + 1]) / a_max)
                   for m, i in zip(singles, pick) for p in mech.sketch)
        per_vec, per_loop = t_vec / n, t_loop / len(pick)
        ratio = per_loop / per_vec
        rows.append((stem, n, 1 / per_vec, len(pick), 1 / per_loop, ratio,
                     "met" if ratio >= THROUGHPUT_TARGET else f"short ×{THROUGHPUT_TARGET / ratio:.2f}", diff))
        sizes = tuple(b for b in cfg.batch_sizes if b <= n)
        rates = []
        for b in sizes:
            sub = cycle_angles(mech, b)
            rates.append(b / best_time(lambda: analyse(mech, structure, sub, order=2), repeat=cfg.repeat))
        batch[stem] = dict(zip(sizes, rates))
        series.append(Series(f"{stem}: vectorised", tuple(float(b) for b in sizes), tuple(rates)))
        loop_series.append(Series(f"{stem}: per-angle loop", tuple(float(b) for b in sizes),
                                  tuple(1 / per_loop for _ in sizes)))
    cols = (Column("scene", "scene", "s"), Column("positions", "N", "d"),
            Column("vectorised_per_s", "vectorised pos/s", ",.0f"), Column("loop_timed_on", "loop timed on", "d"),
            Column("loop_per_s", "loop pos/s", ",.0f"), Column("ratio", "ratio", ".1f"),
            Column("target", f"≥{THROUGHPUT_TARGET:g}×", "s"), Column("max_rel_difference", "loop vs vec. Δ", ".0e"))
    notes = [f"full analysis (positions + velocities + accelerations, plans.kinematics.analyse order=2) over N "
             f"crank angles evenly over a turn in one call (best of {cfg.repeat}), against a Python loop calling "
             "analyse with one angle at a time.",
             f"The loop is timed on {cfg.loop_positions} of the N angles, evenly spread over the turn (best of "
             f"{min(cfg.repeat, LOOP_PASSES)} passes), and extrapolated per position; each call walks the drive "
             "from the sketch to its angle in 1° steps, as a single-angle render does.",
             "loop vs vec. Δ: largest difference between the two results (positions in m, accelerations "
             "relative to the largest), a check that both computed the same thing."]
    short = [r for r in rows if r[5] < THROUGHPUT_TARGET]
    summary = {"target": THROUGHPUT_TARGET, "met": not short, "ratios": {r[0]: r[5] for r in rows},
               "vectorised_per_s_by_batch": batch}
    if short:
        notes.append("below target: " + "; ".join(f"{r[0]} reaches {r[5]:.1f}×, short by a factor "
                                                  f"{THROUGHPUT_TARGET / r[5]:.2f}" for r in short))
    charts = [Chart("throughput", "Throughput of the full analysis (order 2)", "positions per call (N)",
                    "positions per second", tuple(series + loop_series), log_x=True, log_y=True)]
    return Section("throughput", f"4. Throughput (vectorised vs per-angle loop, target ≥ {THROUGHPUT_TARGET:g}×)",
                   cols, rows, notes, summary, charts)


def render_rate(cfg: Config) -> Section:
    """Plans rendered per second by plans.pipeline.render_scene (everything but writing files)."""
    rows = []
    for stem in cfg.render_scenes:
        path = example_path(stem)
        r = render_scene(path)
        sheets = sum(name.endswith(".svg") for name in r.files)
        t = best_time(lambda: render_scene(path), repeat=cfg.repeat)
        rows.append((stem, len(r.motion), sheets, t * 1e3, sheets / t, 1 / t))
    cols = (Column("scene", "scene", "s"), Column("positions", "positions", "d"), Column("sheets", "sheets", "d"),
            Column("ms_per_scene", "ms per scene", ".1f"), Column("sheets_per_s", "sheets/s", ".0f"),
            Column("scenes_per_s", "scenes/s", ".1f"))
    notes = ["render_scene: read, solve, scales, constructions, shapely and similarity checks, SVG and JSON text "
             f"(files not written); sheets = scheme + velocity + acceleration plans per position; best of "
             f"{cfg.repeat}."]
    return Section("render_rate", "4b. Plans rendered per second", cols, rows, notes)

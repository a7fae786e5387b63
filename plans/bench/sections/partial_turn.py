"""Section 8 of ``plans bench``: a class III crank that cannot turn fully, asked for angles on
both sides of its sketch — the joint walk fails, so the solver walks once per side of the sketch
(bisecting on the distance the walk reaches) instead of once per angle. Times both ways in one
run and their largest difference of any point's position.

Knows the kinematics; must not import another section module, :mod:`plans.bench` itself or
the command line.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ...kinematics import analyse
from ...kinematics import solve as _solve
from ...model import build_mechanism
from ...scene import read_scene
from ...structure import analyse_structure
from ..timing import once
from .common import Column, Config, Section, example_path

__all__ = ["partial_turn", "PARTIAL_SCENE", "PARTIAL_RANGES"]

#: koshel_variant1 with its crank 2.5 times longer: the crank reaches -87° … 170° only.
PARTIAL_SCENE, CRANK_SCALE = "koshel_variant1", 2.5
#: The crank angles asked for, degrees: every degree of the reachable arc, both sides of the sketch (45°).
PARTIAL_RANGES = ((0.0, 170.0), (273.0, 359.0))


def _mechanism():
    scene = read_scene(example_path(PARTIAL_SCENE))
    o, a = np.array(scene.points["O"]), np.array(scene.points["A"])
    points = dict(scene.points, A=tuple(float(c) for c in o + CRANK_SCALE * (a - o)))
    mech = build_mechanism(dataclasses.replace(scene, points=points, lengths={}))
    return mech, analyse_structure(mech)


def partial_turn(cfg: Config) -> Section:
    mech, structure = _mechanism()
    angles = np.concatenate([np.arange(lo, hi + 1.0) for lo, hi in PARTIAL_RANGES])
    walks = {"n": 0}
    original = _solve._positions

    def counted(*args, **kwargs):
        walks["n"] += 1
        return original(*args, **kwargs)

    _solve._positions = counted
    try:
        t_new, motion = once(lambda: analyse(mech, structure, angles, order=0))
        new_walks, walks["n"] = walks["n"], 0
        t_old, parts = once(lambda: [_solve._one_way(mech, structure, v) for v in angles])
        old_walks = walks["n"]
    finally:
        _solve._positions = original
    worst = 0.0
    for k, part in enumerate(parts):
        for name, state in part.items():
            worst = max(worst, float(np.max(np.abs(state.origin[0] - motion.links[name].origin[k]))))
    rows = [("each angle alone", len(angles), old_walks, t_old, 1.0, 0.0),
            ("per side of the sketch", len(angles), new_walks, t_new, t_old / t_new, worst)]
    cols = (Column("path", "path", "s"), Column("angles", "angles", "d"), Column("walks", "walks", "d"),
            Column("seconds", "s", ".3f"), Column("speedup", "× faster", ".1f"),
            Column("max_difference_m", "max |Δ origin|, m", ".1e"))
    notes = [f"{PARTIAL_SCENE} with its crank {CRANK_SCALE:g}× longer (reaches -87° … 170°), asked for every degree of "
             f"{', '.join(f'{lo:g}–{hi:g}°' for lo, hi in PARTIAL_RANGES)}: the joint walk fails (a crank that cannot "
             "turn), then the solver walks once per side of the sketch instead of once per angle (old path: "
             "kinematics.solve._one_way for each angle), positions only; one run each. max |Δ origin|: the largest "
             "difference of any link's origin between the two (Newton's root to rounding)."]
    summary = {"angles": len(angles), "walks": new_walks, "walks_each_alone": old_walks,
               "speedup": t_old / t_new, "max_difference_m": worst}
    return Section("partial_turn", "8. A crank that cannot turn fully: walks per side vs per angle", cols, rows, notes,
                   summary)

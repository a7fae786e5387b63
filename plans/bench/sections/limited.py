"""Section 8 of ``plans bench``: a crank that cannot turn fully, asked for angles on both sides
of its sketch — the request one walk from the sketch cannot serve, so each angle is reached as
if walked alone (the short way round, else the long way), the angles that start alike walked
together. Timed in one call against each angle walked alone (what every angle once cost).

Knows the scene reader and the kinematics; must not import another section module,
:mod:`plans.bench` itself or the command line.
"""

from __future__ import annotations

import tomllib

import numpy as np

from ...kinematics import Motion, analyse
from ...model import Mechanism, build_mechanism
from ...scene import parse_scene
from ...structure import Structure, analyse_structure
from ..timing import once
from .common import Column, Config, Section, best_of, example_path

__all__ = ["LIMITED_SCENE", "LIMITED_POINTS", "LIMITED_RANGE", "limited_crank", "limited_angles", "walk_difference",
           "limited_walk"]

#: The class III six-link (examples/class3_six_link.toml) with a crank OA of 0.102 m instead
#: of 0.05 m, sketched at 120°: the crank rocks between about −138° and 205° (where the
#: group falls apart), so the angles below −60° (300°) are reached only the long way round.
LIMITED_SCENE = "class3_six_link"
LIMITED_POINTS = {"A": [-0.051, 0.088334591], "B": [0.160150308, 0.077983751], "F": [0.271061617, 0.145775207],
                  "C": [0.267303867, -0.11499841]}
#: The requested angles run evenly over this range (degrees), written in [0°, 360°).
LIMITED_RANGE = (-135.0, 200.0)


def limited_crank() -> tuple[Mechanism, Structure]:
    """The limited crank's mechanism and structure."""
    data = tomllib.loads(example_path(LIMITED_SCENE).read_text(encoding="utf-8"))
    data["points"].update(LIMITED_POINTS)
    mech = build_mechanism(parse_scene(data))
    return mech, analyse_structure(mech)


def limited_angles(n: int) -> np.ndarray:
    """``n`` crank angles evenly over LIMITED_RANGE, each written in [0°, 360°) (degrees)."""
    return np.mod(np.linspace(*LIMITED_RANGE, n), 360.0)


def walk_difference(together: Motion, alone: list[Motion], index: np.ndarray) -> float:
    """The largest difference between ``together``'s positions, velocities and accelerations at
    ``index`` and those of each angle solved ``alone``: positions relative to the mechanism's
    size, velocities and accelerations to the largest of ``together``'s."""
    mech = together.mechanism
    worst = 0.0
    for f in ("position", "velocity", "acceleration"):
        whole = {p: getattr(together, f)(p) for p in mech.sketch}
        scale = mech.size if f == "position" else max(float(np.max(np.abs(v))) for v in whole.values())
        for m, i in zip(alone, index):
            for p in mech.sketch:
                worst = max(worst, float(np.max(np.abs(getattr(m, f)(p)[0] - whole[p][i]))) / scale)
    return worst


def limited_walk(cfg: Config) -> Section:
    """Positions per second of the full analysis (order 2) of the limited crank at
    cfg.limited_positions angles in one call, against each angle walked alone."""
    mech, structure = limited_crank()
    n = cfg.limited_positions
    angles = limited_angles(n)
    t_call, motion = best_of(lambda: analyse(mech, structure, angles, order=2), cfg.repeat)
    pick = np.linspace(0, n, cfg.limited_alone, endpoint=False).astype(int)
    t_alone, alone = once(lambda: [analyse(mech, structure, angles[i:i + 1], order=2) for i in pick])
    per_call, per_alone = t_call / n, t_alone / len(pick)
    diff = walk_difference(motion, alone, pick)
    rows = [(f"{LIMITED_SCENE}, OA 0.102 m", n, t_call, 1 / per_call, len(pick), 1 / per_alone,
             per_alone / per_call, diff)]
    cols = (Column("scene", "scene", "s"), Column("positions", "N", "d"), Column("call_s", "one call s", ".3f"),
            Column("per_s", "pos/s", ",.0f"), Column("alone_timed_on", "alone timed on", "d"),
            Column("alone_per_s", "alone pos/s", ",.0f"), Column("ratio", "ratio", ".1f"),
            Column("max_rel_difference", "alone vs call Δ", ".0e"))
    low, high = LIMITED_RANGE
    span = f"from {low:g}° to {high:g}°".replace("-", "−")
    notes = [f"{LIMITED_SCENE} with its crank OA 0.102 m, sketched at 120°: the crank rocks between about −138° "
             f"and 205°; N angles evenly {span}, written in [0°, 360°) (the angles below −60° only the long way "
             "round). analyse(order=2) in one call (best of "
             f"{cfg.repeat}, within the timing budget) against each angle walked alone, timed on "
             f"{cfg.limited_alone} of them (one pass), which is what every angle cost before the angles that "
             "start alike were walked together (N = 360 then took 5.8 s).",
             "alone vs call Δ: largest difference between the two (positions relative to the size, velocities "
             "and accelerations to the largest): rounding, amplified near the limit positions."]
    summary = {"positions": n, "per_s": 1 / per_call, "ratio": per_alone / per_call, "max_rel_difference": diff}
    return Section("limited_walk", "8. A crank that cannot turn fully (angles on both sides of the sketch)", cols,
                   rows, notes, summary)

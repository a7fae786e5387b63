"""Per-position cost of the full kinematics (positions, velocities, accelerations) of a
class III and a class IV example against the crank-slider, at 72 positions a turn.

    python benchmarks/complex_groups.py [repeats]
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from plans.kinematics import analyse
from plans.model import build_mechanism
from plans.scene import read_scene
from plans.structure import analyse_structure

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
CASES = {"crank-slider": "crank_slider_central", "class III": "class3_six_link", "class IV": "class4_six_link"}
VALUES = np.linspace(0.0, 360.0, 72, endpoint=False)


def cost(name: str, repeats: int) -> float:
    """Best-of-``repeats`` seconds per position of analyse(..., order=2) at 72 positions."""
    mech = build_mechanism(read_scene(EXAMPLES / f"{name}.toml"))
    structure = analyse_structure(mech)
    analyse(mech, structure, VALUES, order=2)          # warm-up
    best = np.inf
    for _ in range(repeats):
        t = time.perf_counter()
        analyse(mech, structure, VALUES, order=2)
        best = min(best, time.perf_counter() - t)
    return best / len(VALUES)


def main(repeats: int = 20) -> None:
    per = {label: cost(name, repeats) for label, name in CASES.items()}
    base = per["crank-slider"]
    for label, c in per.items():
        print(f"{label:13s} {c * 1e6:8.1f} µs/position  {c * 72e3:7.2f} ms/turn  ratio {c / base:5.1f}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 20)

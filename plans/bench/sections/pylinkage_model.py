"""A bundled scene as a pylinkage Linkage, shared by the peer comparison (section 5) and the
numba comparison (section 6). pylinkage is passed in, never imported here.

Knows the model; must not import a section module, :mod:`plans.bench` itself or the command
line.
"""

from __future__ import annotations

import math

import numpy as np

from ...model import Mechanism
from .common import local_distance

__all__ = ["INSTALL_HINT", "pylinkage_model"]

INSTALL_HINT = 'pip install ".[bench]"'


def pylinkage_model(pl, mech: Mechanism, stem: str, first_deg: float, step_deg: float):
    """The scene as a pylinkage Linkage: same dimensions, crank angles first_deg, first_deg +
    step_deg, … on its successive steps, the assembly branch of the sketch (given as the
    initial position of the dyad's joint). Returns the linkage, its crank, and the index in
    ``linkage.components`` of every compared point."""
    d = mech.drive
    o = mech.sketch[d.pivot]
    step = math.radians(step_deg)
    ground = pl.Ground(float(o[0]), float(o[1]), name=d.pivot)
    crank = pl.Crank(ground, local_distance(mech, d.link, d.pivot, d.tip), angular_velocity=step,
                     initial_angle=math.radians(first_deg) - step, name=d.tip)   # step() turns before it yields
    if stem == "crank_slider_central":
        prism = next(p for p in mech.prismatics if p.guide == "0")
        b = mech.sketch[prism.label]
        anchor = np.asarray(prism.anchor["0"], float)
        ahead = anchor + np.asarray(prism.direction, float)
        line0 = pl.Ground(float(anchor[0]), float(anchor[1]), name="guide-0")
        line1 = pl.Ground(float(ahead[0]), float(ahead[1]), name="guide-1")
        slider = pl.RRPDyad(crank.output, line0, line1, local_distance(mech, "2", d.tip, prism.label),
                            x=float(b[0]), y=float(b[1]), name=prism.label)
        components = [ground, line0, line1, crank, slider]
        points = {d.tip: 3, prism.label: 4}
    elif stem == "four_bar":
        c, b = mech.sketch["C"], mech.sketch["B"]
        pivot = pl.Ground(float(c[0]), float(c[1]), name="C")
        rocker = pl.RRRDyad(crank.output, pivot, local_distance(mech, "2", "A", "B"),
                            local_distance(mech, "3", "C", "B"), x=float(b[0]), y=float(b[1]), name="B")
        components = [ground, pivot, crank, rocker]
        points = {d.tip: 2, "B": 3}
    else:   # pragma: no cover - only the two scenes above are modelled
        raise ValueError(f"no pylinkage model of {stem}")
    linkage = pl.Linkage(components, name=stem)
    linkage.set_input_velocity(crank, d.speed, d.rate)
    return linkage, points

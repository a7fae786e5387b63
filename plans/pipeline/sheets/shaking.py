"""The ``-shaking`` sheet of a linkage over its cycle (``draw = [..., "shaking"]``): the hodograph
of the shaking force, the trajectory of the total centre of mass and the shaking moment against
φ (:mod:`plans.constructions.shaking`, :mod:`plans.drawing.shaking`), with the counterweights of
``[counterweights]`` and, dashed, without them.

Reads a solved :class:`~plans.dynamics.shaking.ShakingAnalysis`; imports nothing of the pipeline."""

from __future__ import annotations

import numpy as np

from ...constructions.shaking import shaking_sheet
from ...drawing import Style
from ...drawing.shaking import draw_shaking
from ...drawing.svg import Heading
from ...drawing.text import significant
from ...dynamics.shaking import ShakingAnalysis
from ...scene import Scene

__all__ = ["shaking_sheets"]


def shaking_sheets(scene: Scene, a: ShakingAnalysis, stem: str, style: Style) -> dict[str, str]:
    """The sheet (file name → SVG)."""
    now = a.shaking
    largest = float(np.max(np.hypot(now.force[:, 0], now.force[:, 1])))
    notes = [f"The shaking force Σ(−m·a_S) = −M·a of the total centre of mass (M = {significant(now.mass, 5)} kg), its moment "
             f"about {a.about} (CCW +) Σ(r_S − O) × (−m·a_S) − Σ I_S·ε; the largest |F| = {significant(largest, 5)} N, |M| = "
             f"{significant(float(np.max(np.abs(now.moment))), 5)} N·m over the cycle's {len(a.angles)} positions."]
    if a.balanced is not None:
        before = float(np.max(np.hypot(a.without.force[:, 0], a.without.force[:, 1])))
        weights = "; ".join(f"link {c.link}: {significant(c.mass, 5)} kg at r = {significant(c.radius, 5)} m, {significant(c.angle, 4)}°"
                            for c in a.counterweights)
        notes.append(f"With the counterweights ({weights}); without them (dashed; black on the moment graph) the "
                     f"largest |F| is {significant(before, 5)} N.")
    heading = Heading(scene.title, "Shaking force, centre of mass and shaking moment",
                      f"{len(a.angles)} positions from φ = {float(a.angles[0]) % 360.0:.6g}°")
    return {f"{stem}-shaking.svg": draw_shaking(shaking_sheet(a), heading, ident="shaking", style=style,
                                                notes=tuple(notes))}

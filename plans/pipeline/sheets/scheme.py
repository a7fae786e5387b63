"""The kinematic scheme of one position (``-scheme``), drawn at μl with the senses of ω and ε
when the scene asks for them.

Reads a solved Motion; imports nothing of the pipeline but :mod:`.page`."""

from __future__ import annotations

from ...constructions import Scales, scheme
from ...drawing import Heading, draw_scheme
from .page import Page

__all__ = ["scheme_sheets"]


def scheme_sheets(page: Page, scales: Scales) -> dict[str, str]:
    """The scheme at ``page`` when the scene draws it (file name → SVG)."""
    scene, motion = page.scene, page.motion
    if "scheme" not in scene.draw:
        return {}
    sch = scheme(motion, page.i, scales.mu_l, senses=scene.senses)
    return {page.file("scheme"): draw_scheme(sch, Heading(scene.title, "Kinematic scheme", page.label),
                                             formula=motion.structure.formula, ident=page.ident("scheme"),
                                             style=page.style)}

"""The ``-assemblies`` sheet of each position drawn on its own, when the scene asks for the
assemblies (``draw = [..., "assemblies"]``): every real assembly of each group there
(:mod:`plans.constructions.assembly_sheet`, :mod:`plans.drawing.assemblies`).

Reads the assemblies found by :func:`plans.pipeline.stages.assembly_analysis`; imports nothing of
the pipeline but :mod:`.page`."""

from __future__ import annotations

from typing import Mapping

from ...constructions.assembly_sheet import assembly_sheet
from ...drawing.assemblies import draw_assemblies
from ...drawing.svg import Heading
from ...kinematics.assemblies import GroupAssemblies
from .page import Page

__all__ = ["assembly_sheets"]

#: What the sheet says of its numbers and figures.
NOTE = ("Each real assembly of a group with the earlier groups held where the drawn mechanism has them, numbered "
        "1 … n in the order of its points' coordinates (the JSON's positions[i].assemblies[group].poses, in the same "
        "order). The condition figure of a class III group is det of its three axes' normalised line coordinates: "
        "±1 well spread, 0 where its axes meet in one point (a singular position); its sign tells the two sides of "
        "a singular position apart.")


def assembly_sheets(page: Page, found: Mapping[str, GroupAssemblies]) -> dict[str, str]:
    """The sheet of ``page``'s position (file name → SVG)."""
    motion = page.motion
    sheet = assembly_sheet(motion.mechanism, motion.structure, found)
    heading = Heading(page.scene.title, "Every assembly of each group", page.label)
    return {page.file("assemblies"): draw_assemblies(sheet, heading, ident=page.ident("assemblies"), style=page.style,
                                                     notes=(NOTE,))}

"""Koshel's sheets of one position (``-koshel``): for each class III group, the centre P of its
base link and the velocity plan in an uncertain scale, checked as the plans are. A construction
that degenerates or fails its check gives a sheet saying why, and a warning; the other sheets
are unaffected.

Reads a solved Motion; imports nothing of the pipeline but plans.pipeline.rest, :mod:`.page`
and the plans' similarity check (:mod:`.plans`)."""

from __future__ import annotations

from ...checking import check_plan
from ...constructions import uncertain_plan
from ...constructions.koshel import fit_segment, koshel_sheet
from ...drawing import Heading, Style
from ...drawing.koshel import draw_koshel
from ...errors import ConstructionError
from ...kinematics import Motion
from ...structure import ComplexGroup
from ..rest import empty_sheet, rest_note
from .page import Page
from .plans import similarity_failures

__all__ = ["koshel_sheets"]


def koshel_sheets(page: Page, still: bool) -> tuple[dict[str, str], list[str]]:
    """Koshel's sheet at ``page`` when the scene draws velocity plans (file name → SVG: one
    sheet, the last group's, when several groups apply) and the warnings of the sheets that
    are not drawn; ``still``: the velocities are all zero (:func:`~plans.pipeline.rest.at_rest`)."""
    scene, motion, i = page.scene, page.motion, page.i
    files: dict[str, str] = {}
    warnings: list[str] = []
    if "velocity" not in scene.draw:
        return files, warnings
    unit = "°" if motion.mechanism.drive.kind.angular else " m"
    for g in (found.group for found in motion.special_points.values()):
        koshel = _koshel(motion, i, g, still, title=scene.title, label=page.label, ident=page.ident("koshel"),
                         style=page.style)
        if koshel is None:
            continue
        files[page.file("koshel")], why = koshel
        if why:
            warnings.append(f"{page.stem}: Koshel's plan at {motion.values[i]:g}{unit} is not drawn: {why}")
    return files, warnings


def _koshel(motion: Motion, i: int, g: ComplexGroup, still: bool, *, title: str, label: str, ident: str,
            style: Style) -> tuple[str, str] | None:
    """Koshel's sheet of class III group ``g`` at position i and why it is empty ("" when it
    is drawn); None when the construction does not apply to the group. A construction that
    degenerates here, or fails its check, gives a sheet that states why (the other sheets are
    unaffected); a mechanism at rest, a sheet saying so."""
    heading = Heading(title, "Velocity plan in an uncertain scale (Koshel)", label)
    try:
        plan = uncertain_plan(motion, i, g)
    except ConstructionError as exc:
        plan, why = None, str(exc)
    else:
        if plan is None:
            return None
        plan, segment = fit_segment(plan)
        failures = [] if still else check_plan(plan) + similarity_failures(motion, plan, i)
        why = f"the construction failed its geometric check: {failures[0]} (please report this scene)" \
            if failures else ""
    if still:       # the mechanism at rest: said once for the whole scene
        return empty_sheet("velocity", heading, why=rest_note(motion, "velocity"), ident=ident, style=style), ""
    if not why:
        try:
            sheet = koshel_sheet(motion, i, g, plan, segment)
        except ConstructionError as exc:
            why = str(exc)
    if why:
        return empty_sheet("velocity", heading, why=f"not drawn at this position: {why}", ident=ident,
                           style=style), why
    heading = Heading(title, f"Koshel's method: centre P{g.base} and velocity plan in an uncertain scale", label)
    return draw_koshel(sheet, heading, ident=ident, style=style), ""

"""A variant solved: its scene data (the base's with the variant's lengths and drive), its
scene, its rendered sheets, and the margin from singular positions each group must keep.

Knows :mod:`.variants`, the scene reader and the pipeline; must not
import the random draws, the writing, the index page, the drawing or the command line.
"""

from __future__ import annotations

import copy
from typing import Mapping

import numpy as np

from ..errors import PlansError, SceneError
from ..kinematics import WARN_SIN, analyse
from ..scene.values import DriveKind
from ..pipeline import Sheets, render
from ..scene import Scene, parse_scene
from .variants import MARGIN_SIN, Drawn, Handout, Variant

__all__ = ["VariantError", "variant_data", "variant_scene", "solve_variant", "worst_sine", "group_margins",
           "short_of", "TURN_STEP_DEG", "turns_fully"]

#: A crank's variant must assemble at every multiple of this over the turn (degrees) when its
#: base's crank turns fully (Grashof's condition, for any chain), each position at least
#: WARN_SIN from a singular one.
TURN_STEP_DEG = 5.0


class VariantError(SceneError):
    """A variant that cannot be made, and why: ``cause`` "value" (the scene refuses a value the
    variant sets, at its key ``sub``: ``angle``, ``lengths.AB``), "build" (its lengths form no
    link) or "assembly" (it does not assemble, or is singular, at an asked position)."""

    def __init__(self, message: str, *, file: str | None = None, key: str | None = None, cause: str = "value",
                 sub: str = ""):
        super().__init__(message, file=file, key=key)
        self.cause, self.sub = cause, sub


def variant_data(h: Handout, v: Variant) -> dict:
    """The base scene's TOML data with the variant's lengths and drive values."""
    data = copy.deepcopy(dict(h.base_data))
    if h.train:
        wheels = data["gears"]["wheels"]
        for name, z in v.teeth.items():
            wheels[name] = {**wheels[name], "teeth": z}
        if v.inputs:
            data["gears"]["input"] = {**data["gears"].get("input", {}), **v.inputs}
        return data
    if v.lengths:
        data["lengths"] = {**data.get("lengths", {}), **v.lengths}
    drive = data["drive"]
    for key, value in zip(h.keys, (list(v.values) if v.values is not None else None, v.speed, v.rate)):
        if value is not None:
            drive[key] = value[0] if isinstance(value, list) and len(value) == 1 else value
    return data


def _where(h: Handout, v: Variant) -> tuple[str, str]:
    """The file and key that name variant ``v`` in error messages."""
    return (str(h.source), f"variant[{v.number - 1}]") if h.source else (str(h.base), f"--random ({h.name(v)})")


def variant_scene(h: Handout, v: Variant) -> Scene:
    """The scene of variant ``v``; a value the scene refuses is reported at the variant's key."""
    file, key = _where(h, v)
    try:
        return parse_scene(variant_data(h, v), file=str(h.base))
    except SceneError as exc:
        sub = exc.key or ""
        for table, alias in (("drive.", ""), ("lengths.", "lengths."), ("gears.wheels.", "teeth."),
                         ("gears.input.", "input.")):
            if sub.startswith(table):
                sub = alias + sub[len(table):]
        raise VariantError(f"{exc.message} ({h.name(v)})", file=file, key=f"{key}.{sub}" if sub else key,
                           sub=sub) from None


def solve_variant(h: Handout, v: Variant) -> Drawn:
    """Variant ``v`` rendered (every sheet the scene draws); a variant that cannot be assembled
    or is singular is one error naming the variant and why."""
    scene = variant_scene(h, v)
    name = h.name(v)
    file, key = _where(h, v)
    try:
        sheets = render(scene, stem=name)
    except SceneError as exc:      # a link's lengths that cannot form its shape
        where = f" (link {exc.key[len('links.'):]})" if exc.key and exc.key.startswith("links.") else ""
        raise VariantError(f"{name} cannot be built: {exc.message}{where}", file=file, key=key,
                           cause="build") from None
    except PlansError as exc:      # does not assemble, or singular, at an asked position
        why = str(exc).removeprefix(f"{h.base}, ").removeprefix(f"{h.base}: ")
        raise VariantError(f"{name} cannot be drawn: {why}", file=file, key=key, cause="assembly") from None
    return Drawn(v, name, scene, sheets)


def worst_sine(sheets: Sheets) -> float:
    """The smallest |condition figure| over every group and position (1 with no group)."""
    if sheets.motion is None:
        return 1.0
    return min((float(np.min(np.abs(s))) for s in sheets.motion.sines.values()), default=1.0)


def group_margins(base: Sheets, margin: float = MARGIN_SIN) -> dict[str, float]:
    """The margin each group of the base scene must keep: ``margin`` for every group, whose
    figures all mean the same closeness to a singular position (plans.kinematics.figure); none
    for a gear train (its conditions are kept exactly, see :func:`short_of`)."""
    return {} if base.motion is None else {g: margin for g in base.motion.sines}


def turns_fully(sheets: Sheets) -> str:
    """Why the crank of ``sheets`` does not turn a full revolution ("" when it does, and for
    any other drive): the mechanism solved at every TURN_STEP_DEG from the first position must
    assemble and keep |condition| ≥ WARN_SIN."""
    m = sheets.motion
    if m is None or m.mechanism.drive.kind != DriveKind.ROTARY:
        return ""
    angles = float(m.values[0]) + np.arange(0.0, 360.0, TURN_STEP_DEG)
    try:
        turn = analyse(m.mechanism, m.structure, angles, order=1)
    except PlansError as exc:
        return f"the crank does not turn fully: {exc}"
    for g, s in turn.sines.items():
        k = int(np.argmin(np.abs(s)))
        if abs(s[k]) < WARN_SIN:
            return f"the crank does not turn fully: group {g} comes to a dead position near {angles[k] % 360:g}°"
    return ""


def short_of(sheets: Sheets, margins: Mapping[str, float]) -> str:
    """Why ``sheets`` misses the margins ("" when it keeps them all); a gear train misses them
    when one of its wheels is undercut (the coaxial, assembly and neighbourhood conditions are
    refused by the train itself)."""
    if sheets.motion is None:
        return "; ".join(sheets.train.geometry.warnings) if sheets.train and sheets.train.geometry else ""
    for g, s in sheets.motion.sines.items():
        worst = float(np.min(np.abs(s)))
        if worst < margins.get(g, MARGIN_SIN):
            return f"group {g}: condition {worst:.3g} below the margin {margins.get(g, MARGIN_SIN):g}"
    return ""

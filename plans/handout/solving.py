"""A variant solved: its scene data (the base's with the variant's lengths and drive), its
scene, its rendered sheets, and the margin from singular positions each group must keep; a
variant is refused when it changes a link's shape (:func:`shape_change`) or leaves its task
nothing to find (:func:`variant_gap`).

Knows :mod:`.asked`, :mod:`.variants`, the scene reader, the model and the pipeline; must not
import the random draws, the writing, the index page, the drawing or the command line.
"""

from __future__ import annotations

import copy
import itertools
import math
from typing import Mapping

import numpy as np

from ..errors import PlansError, SceneError
from ..kinematics import WARN_SIN, analyse
from ..model import Link, Mechanism, build_mechanism
from ..scene.values import DriveKind
from ..pipeline import Sheets, render
from ..scene import Scene, parse_scene
from .asked import asked, task_gap
from .variants import MARGIN_SIN, Drawn, Handout, Variant

__all__ = ["VariantError", "variant_data", "variant_scene", "solve_variant", "worst_sine", "group_margins",
           "short_of", "TURN_STEP_DEG", "turns_fully", "LINE_RTOL", "shape_change", "variant_gap",
           "base_mechanism"]

#: A crank's variant must assemble at every multiple of this over the turn (degrees) when its
#: base's crank turns fully (Grashof's condition, for any chain), each position at least
#: WARN_SIN from a singular one.
TURN_STEP_DEG = 5.0
#: Three points of a link are on one line when the height of their triangle over its longest
#: side is at most this × the link's size (its two farthest points' distance): a rod's centre
#: of mass on its bar. A variant keeps such a point on its line, and every other three points
#: of a link turning the same way (a plate keeps its shape, not turned inside out).
LINE_RTOL = 1e-9


class VariantError(SceneError):
    """A variant that cannot be made, and why: ``cause`` "value" (the scene refuses a value the
    variant sets, at its key ``sub``: ``angle``, ``lengths.AB``), "build" (its lengths form no
    link) or "assembly" (it does not assemble, or is singular, at an asked position)."""

    def __init__(self, message: str, *, file: str | None = None, key: str | None = None, cause: str = "value",
                 sub: str = ""):
        super().__init__(message, file=file, key=key)
        self.cause, self.sub = cause, sub


def variant_data(h: Handout, v: Variant) -> dict:
    """The base scene's TOML data with the variant's lengths and drive values (a gear train's
    teeth and input speeds, a rotor's masses)."""
    data = copy.deepcopy(dict(h.base_data))
    if h.train:
        wheels = data["gears"]["wheels"]
        for name, z in v.teeth.items():
            wheels[name] = {**wheels[name], "teeth": z}
        if v.inputs:
            data["gears"]["input"] = {**data["gears"].get("input", {}), **v.inputs}
        return data
    if h.rotor:
        masses = [{**m, **(v.masses[k] if k < len(v.masses) else {})} for k, m in enumerate(data["rotor"]["masses"])]
        data["rotor"] = {**data["rotor"], "masses": masses}
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
                         ("gears.input.", "input."), ("rotor.masses", "masses")):
            if sub.startswith(table):
                sub = alias + sub[len(table):]
        raise VariantError(f"{exc.message} ({h.name(v)})", file=file, key=f"{key}.{sub}" if sub else key,
                           sub=sub) from None


def solve_variant(h: Handout, v: Variant) -> Drawn:
    """Variant ``v`` rendered (every sheet the scene draws); a variant that cannot be assembled
    or is singular, that changes a link's shape (:func:`shape_change`) or whose task has nothing
    to find (:func:`variant_gap`) is one error naming the variant and why."""
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
    if sheets.motion is not None:
        changed = shape_change(base_mechanism(h), sheets.motion.mechanism)
        if changed:
            raise VariantError(f"{name} changes a link's shape: {changed}; give the lengths of one link in the base's "
                               "proportions (a point on a bar: its distances in the ratio of the base's)", file=file,
                               key=f"{key}.lengths" if h.source else key, cause="shape")
    d = Drawn(v, name, scene, sheets)
    gap = variant_gap(d)
    if gap:
        raise VariantError(f"{name} cannot be set as a task: {gap}", file=file, key=key, cause="empty")
    return d


def base_mechanism(h: Handout) -> Mechanism | None:
    """The base scene's mechanism (None for a gear train alone)."""
    scene = parse_scene(h.base_data, file=str(h.base))
    return None if scene.drive is None else build_mechanism(scene)


def _sides(link: Link) -> dict[tuple[str, str, str], tuple[int, float]]:
    """Every three points of ``link`` (in its order): 0 when they lie on one line (within
    LINE_RTOL of the link's size), else the sense they turn (±1); and the height of their
    triangle over its longest side (m)."""
    xy = link.local
    pts = link.points
    size = max((math.dist(xy[a], xy[b]) for a, b in itertools.combinations(pts, 2)), default=0.0)
    out = {}
    for a, b, c in itertools.combinations(pts, 3):
        (ax, ay), (bx, by), (cx, cy) = xy[a], xy[b], xy[c]
        cross = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
        longest = max(math.dist(xy[a], xy[b]), math.dist(xy[b], xy[c]), math.dist(xy[a], xy[c]))
        height = abs(cross) / longest if longest > 0.0 else 0.0
        out[(a, b, c)] = (0 if height <= LINE_RTOL * size else (1 if cross > 0 else -1), height)
    return out


def shape_change(base: Mechanism | None, variant: Mechanism) -> str:
    """How ``variant``'s links leave the shapes of ``base``'s ("" when none does): three points
    on one line in the base off it (a centre of mass off its rod), or three that turned the other
    way or came onto one line (a plate turned inside out or flattened)."""
    if base is None:
        return ""
    for name, link in base.links.items():
        after = _sides(variant.links[name])
        for (a, b, c), (sense, _) in _sides(link).items():
            now, height = after[(a, b, c)]
            if now == sense:
                continue
            if sense == 0:
                return (f"{a}, {b} and {c} of link {name} lie on one line in the base, and the variant's lengths put "
                        f"them {height:.3g} m off it")
            return (f"{a}, {b} and {c} of link {name} " + ("come onto one line" if now == 0 else "turn the other way")
                    + " (the link's shape turned over)")
    return ""


def variant_gap(d: Drawn) -> str:
    """Why variant ``d``'s assignment cannot be set (:func:`plans.handout.asked.task_gap` on what
    it asks: a linkage's moving points and its moving links but the driving one, as its
    assignment names them); "" when it can."""
    motion = d.sheets.motion
    if d.scene.drive is None or motion is None:
        return task_gap(d.scene, asked(d.scene, d.sheets.report))
    mech = motion.mechanism
    points = [p for p in mech.sketch if motion.carrier(p) != "0"]
    links = [n for n in mech.moving if n != d.scene.drive.link]
    return task_gap(d.scene, asked(d.scene, d.sheets.report, points=points, links=links))


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

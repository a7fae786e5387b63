"""The force sheets of the positions drawn on their own: the force plans, group by group
(``-forces``; ``-forces-2`` … when one A3 sheet does not hold them), and Zhukovsky's lever
(``-lever``), built at every position and checked against the group-by-group balancing
element.

Reads a solved Motion and Forces; imports nothing of the pipeline but :mod:`.page`."""

from __future__ import annotations

from typing import Iterable

from ...constructions import Scales, velocity_plan
from ...constructions.forces import Lever
from ...constructions.group_diagram import group_diagrams
from ...constructions.kinetostatics import BESIDE_DIAGRAM_MM, group_force_plans, lever, lever_plan_scale, lever_scale
from ...drawing import Heading, Style
from ...drawing.svg import draw_empty
from ...drawing.forces import draw_force_plans
from ...drawing.lever import draw_lever
from ...errors import PlansError
from ...kinematics import Motion
from ...kinetostatics import MIN_LOAD, Forces
from ...scene import Scene
from .page import Page

__all__ = ["LEVER_RTOL", "force_sheets", "force_warnings", "unloaded", "NO_LOAD", "AT_REST"]

#: Why a force sheet asked for has nothing to draw: the same words on the force plans and the
#: lever, on the sheet and in the warning.
NO_LOAD = (f"no load in effect at this position (none given, every mass zero, or each below {MIN_LOAD:g} N or "
           "N·m): every reaction and the balancing element are zero")
AT_REST = ("the mechanism is at rest (the drive stands): there is no velocity plan to turn into the lever; "
           "the balancing element is the group-by-group one, in the report")

#: The lever's balancing element must equal the group-by-group one to this fraction of the
#: scale of the loads' moments (:func:`~plans.constructions.kinetostatics.lever_scale`,
#: Σ|F|·v_max/ω1 for a moment): both are exact, the difference is rounding.
LEVER_RTOL = 1e-9


def force_sheets(scene: Scene, motion: Motion, forces: Forces, scales: Scales, own: Iterable[int], *, stem: str,
                 path: str, style: Style) -> tuple[dict[str, str], dict[int, Lever]]:
    """The force-plan and lever sheets the scene draws at the positions ``own`` (file name →
    SVG) and Zhukovsky's lever at every position (position → lever; none without ``lever`` in
    the scene's drawings or without μV), built once for both the sheets and the report. A
    lever that disagrees with the group-by-group analysis raises a PlansError prefixed ``path``."""
    levers = {i: _lever_at(motion, forces, i, scales.mu_v, path) for i in range(len(motion))} \
        if "lever" in scene.draw and scales.mu_v is not None else {}
    files: dict[str, str] = {}
    if not {"forces", "lever"} & set(scene.draw):
        return files, levers
    for i in own:
        page = Page.at(scene, motion, i, stem, style)
        if "forces" in scene.draw:
            heading = Heading(scene.title, "Force plans", page.label)
            alone = () if unloaded(forces, i) else group_diagrams(motion, forces, i)
            plans = () if unloaded(forces, i) else group_force_plans(
                forces, i, limit=BESIDE_DIAGRAM_MM, first_normal={d.group: f"R:{e.unknown[3:]}:n" for d in alone
                                                                  for e in d.equations if e.unknown.startswith("Rn:")})
            sheets = draw_force_plans(plans, heading, ident=page.ident("forces"), style=style, diagrams=alone) \
                if plans else \
                (draw_empty("force", heading, ident=page.ident("forces"), style=style, notes=(NO_LOAD,)),)
            for k, svg in enumerate(sheets):
                files[f"{stem}-forces{page.suffix}{'' if k == 0 else f'-{k + 1}'}.svg"] = svg
        if "lever" in scene.draw:
            heading = Heading(scene.title, "Zhukovsky's lever", page.label)
            files[page.file("lever")] = draw_lever(levers[i], heading, ident=page.ident("lever"), style=style,
                                                   note=NO_LOAD if unloaded(forces, i) else "") \
                if i in levers else draw_empty("lever", heading, ident=page.ident("lever"), style=style,
                                               notes=(AT_REST,))
    return files, levers


def force_warnings(scene: Scene, motion: Motion, forces: Forces, levers: dict[int, Lever], own: Iterable[int],
                   path: str) -> list[str]:
    """A warning for the force sheets drawn without a load (no load in effect: the force plans
    hold no polygon, the lever no force; one line for both when they are at the same positions)
    and one for levers of a mechanism at rest (no velocity plan to turn)."""
    out = []
    own = list(own)
    bare = [i for i in own if unloaded(forces, i)]
    plans = bare if "forces" in scene.draw else []
    still = [i for i in own if i not in levers] if "lever" in scene.draw else []
    drawn = [i for i in bare if i in levers] if "lever" in scene.draw else []
    if plans and plans == drawn:
        out.append(f"{path}: force plans and Zhukovsky's lever at {_values(motion, bare)}: {NO_LOAD}; the sheets say "
                   "so (the lever is the turned plan with no force on it)")
    else:
        if plans:
            out.append(f"{path}: force plans at {_values(motion, plans)}: {NO_LOAD}; the sheet says so")
        if drawn:
            out.append(f"{path}: Zhukovsky's lever at {_values(motion, drawn)}: {NO_LOAD}; the sheet says so (the "
                       "turned plan with no force on it)")
    if still:
        out.append(f"{path}: Zhukovsky's lever at {_values(motion, still)}: {AT_REST}; the sheet says so")
    return out


def unloaded(forces: Forces, i: int) -> bool:
    """Whether no load is in effect at position ``i``: every given force and couple (inertia and
    weights included) is 0 there (:data:`~plans.kinetostatics.MIN_LOAD`)."""
    return not any(l.force[i].any() for l in forces.loads if l.kind != "balance") and \
        not any(c.moment[i] for c in forces.couples if c.kind != "balance")


def _values(motion: Motion, positions: list[int]) -> str:
    unit = "°" if motion.mechanism.drive.kind.angular else " m"
    return ", ".join(f"{motion.values[i]:g}{unit}" for i in positions)


def _lever_at(motion: Motion, forces: Forces, i: int, mu_v: float, path: str) -> Lever:
    """The lever at position i, checked against the group-by-group balancing element."""
    plan = velocity_plan(motion, i, mu_v)
    mu = lever_plan_scale(plan)
    result = lever(motion, forces, i, plan if mu == mu_v else velocity_plan(motion, i, mu))
    # against the scale of the loads' moments, not the element's own size: near an extreme
    # position (the loaded point at rest) the element is itself rounding of that scale
    if abs(result.result - float(forces.balance.value[i])) > LEVER_RTOL * max(lever_scale(result),
                                                                              abs(result.result)):
        unit = "°" if motion.mechanism.drive.kind.angular else " m"
        raise PlansError(f"{path}: Zhukovsky's lever gives {result.result:.12g} at {motion.values[i]:g}{unit}, the "
                         f"group-by-group analysis {float(forces.balance.value[i]):.12g} (please report this scene)")
    return result

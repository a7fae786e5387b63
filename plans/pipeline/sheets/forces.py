"""The force sheets of the positions drawn on their own: the force plans, group by group
(``-forces``; ``-forces-2`` … when one A3 sheet does not hold them), and Zhukovsky's lever
(``-lever``), built at every position and checked against the group-by-group balancing
element.

Reads a solved Motion and Forces; imports nothing of the pipeline but :mod:`.page`."""

from __future__ import annotations

from typing import Iterable

from ...constructions import Scales, velocity_plan
from ...constructions.forces import Lever
from ...constructions.kinetostatics import group_force_plans, lever, lever_plan_scale
from ...drawing import Heading, Style
from ...drawing.forces import draw_force_plans, draw_lever
from ...errors import PlansError
from ...kinematics import Motion
from ...kinetostatics import Forces
from ...scene import Scene
from .page import Page

__all__ = ["LEVER_RTOL", "force_sheets"]

#: The lever's balancing element must equal the group-by-group one to this fraction of the
#: lever's largest load moment (both are exact; the difference is rounding).
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
            sheets = draw_force_plans(group_force_plans(forces, i), Heading(scene.title, "Force plans", page.label),
                                      ident=page.ident("forces"), style=style)
            for k, svg in enumerate(sheets):
                files[f"{stem}-forces{page.suffix}{'' if k == 0 else f'-{k + 1}'}.svg"] = svg
        if i in levers:
            files[page.file("lever")] = draw_lever(levers[i], Heading(scene.title, "Zhukovsky's lever", page.label),
                                                   ident=page.ident("lever"), style=style)
    return files, levers


def _lever_at(motion: Motion, forces: Forces, i: int, mu_v: float, path: str) -> Lever:
    """The lever at position i, checked against the group-by-group balancing element."""
    plan = velocity_plan(motion, i, mu_v)
    mu = lever_plan_scale(plan)
    result = lever(motion, forces, i, plan if mu == mu_v else velocity_plan(motion, i, mu))
    scale = max([abs(f.moment) for f in result.forces] + [0.0]) / abs(result.unit_moment) \
        if result.unit_moment else 0.0
    if abs(result.result - float(forces.balance.value[i])) > LEVER_RTOL * max(scale, abs(result.result)):
        raise PlansError(f"{path}: Zhukovsky's lever gives {result.result:.12g} at {motion.values[i]:g}, the "
                         f"group-by-group analysis {float(forces.balance.value[i]):.12g} (please report this scene)")
    return result

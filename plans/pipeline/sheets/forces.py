"""The force sheets of the positions drawn on their own: the force plans, group by group
(``-forces``; ``-forces-2`` … when one A3 sheet does not hold them), and Zhukovsky's lever
(``-lever``), built at every position and checked against the group-by-group balancing
element.

Reads a solved Motion and Forces; imports nothing of the pipeline but :mod:`.page`."""

from __future__ import annotations

import math
from typing import Iterable

from ...constructions import Scales, velocity_plan
from ...constructions.forces import Lever
from ...constructions.kinetostatics import group_force_plans, lever, lever_plan_scale
from ...drawing import Heading, Style
from ...drawing.svg import draw_empty
from ...drawing.forces import draw_force_plans, draw_lever
from ...errors import PlansError
from ...kinematics import Motion
from ...kinetostatics import Forces
from ...scene import Scene
from .page import Page

__all__ = ["LEVER_RTOL", "force_sheets", "force_warnings", "NO_LOAD", "AT_REST"]

#: Why a force sheet asked for has nothing to draw.
NO_LOAD = ("no load in effect at this position (none given, every mass zero, or each too small to count): "
           "every reaction and the balancing element are zero")
AT_REST = ("the mechanism is at rest (the drive stands): there is no velocity plan to turn into the lever; "
           "the balancing element is in the force plans and the report")

#: The lever's balancing element must equal the group-by-group one to this fraction of the
#: loads times the plan's size, Σ|F|·max|px| (both are exact; the difference is rounding).
LEVER_RTOL = 1e-9
#: ... and to this absolute amount (N or N·m): loads at the edge of the double range (1e-300 N)
#: round away in one of the two computations; nothing a machine feels is this small.
LEVER_ATOL = 1e-200


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
            plans = group_force_plans(forces, i)
            sheets = draw_force_plans(plans, heading, ident=page.ident("forces"), style=style) if plans else \
                (draw_empty("force", heading, ident=page.ident("forces"), style=style, notes=(NO_LOAD,)),)
            for k, svg in enumerate(sheets):
                files[f"{stem}-forces{page.suffix}{'' if k == 0 else f'-{k + 1}'}.svg"] = svg
        if "lever" in scene.draw:
            heading = Heading(scene.title, "Zhukovsky's lever", page.label)
            files[page.file("lever")] = draw_lever(levers[i], heading, ident=page.ident("lever"), style=style) \
                if i in levers else draw_empty("lever", heading, ident=page.ident("lever"), style=style,
                                               notes=(AT_REST,))
    return files, levers


def force_warnings(scene: Scene, motion: Motion, forces: Forces, levers: dict[int, Lever], own: Iterable[int],
                   path: str) -> list[str]:
    """One warning per force sheet drawn empty: no load in effect (force plans), the mechanism at
    rest (the lever has no velocity plan to turn), a lever with no load on it."""
    out = []
    own = list(own)
    if "forces" in scene.draw:
        empty = [i for i in own if not group_force_plans(forces, i)]
        if empty:
            out.append(f"{path}: force plans at {_values(motion, empty)}: {NO_LOAD}; the sheet says so")
    if "lever" in scene.draw:
        still = [i for i in own if i not in levers]
        if still:
            out.append(f"{path}: Zhukovsky's lever at {_values(motion, still)}: {AT_REST}; the sheet says so")
        bare = [i for i in own if i in levers and not any(f.kind != "balance" for f in levers[i].forces)]
        if bare:
            out.append(f"{path}: Zhukovsky's lever at {_values(motion, bare)}: no load in effect, the balancing "
                       "element is 0 (the lever is drawn with it)")
    return out


def _values(motion: Motion, positions: list[int]) -> str:
    unit = "°" if motion.mechanism.drive.kind.angular else " m"
    return ", ".join(f"{motion.values[i]:g}{unit}" for i in positions)


def _lever_at(motion: Motion, forces: Forces, i: int, mu_v: float, path: str) -> Lever:
    """The lever at position i, checked against the group-by-group balancing element."""
    plan = velocity_plan(motion, i, mu_v)
    mu = lever_plan_scale(plan)
    result = lever(motion, forces, i, plan if mu == mu_v else velocity_plan(motion, i, mu))
    # the scale of the figures: the loads times the plan's size, Σ|F|·max|p x| (≈ Σ|F|·max|v|/ω1: the
    # rounding of every velocity is relative to the largest), over the lever moment of a unit
    # balancing element; so a balancing element near zero (an extreme position, where the loaded
    # point is at rest) is compared with what the loads could give, not with its own rounding
    pole = result.pole_xy
    size = max([math.dist(p.xy, pole) for p in result.points] + [0.0])
    reach = sum(f.value for f in result.forces if f.kind != "balance") * size
    scale = reach / abs(result.unit_moment) if result.unit_moment else 0.0
    if abs(result.result - float(forces.balance.value[i])) > LEVER_RTOL * max(scale, abs(result.result)) \
            + LEVER_ATOL:
        unit = "°" if motion.mechanism.drive.kind.angular else " m"
        raise PlansError(f"{path}: Zhukovsky's lever gives {result.result:.12g} at {motion.values[i]:g}{unit}, the "
                         f"group-by-group analysis {float(forces.balance.value[i]):.12g} (please report this scene)")
    return result

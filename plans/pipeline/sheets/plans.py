"""The velocity and acceleration plans of one position (``-velocity``, ``-acceleration``), at μV
and μa, each checked (closure, construction lines, similarity) before it is drawn; a plan at
rest is a sheet with the pole alone saying so.

Reads a solved Motion; imports nothing of the pipeline but plans.pipeline.rest and :mod:`.page`."""

from __future__ import annotations

import math

from ...checking import check_plan, similarity_ratio
from ...constructions import Scales, acceleration_plan, velocity_plan
from ...constructions.plans import Plan
from ...drawing import Heading, draw_plan
from ...errors import PlansError
from ...kinematics import Motion
from ..rest import empty_sheet, rest_note
from .page import Page

__all__ = ["plan_sheets", "similarity_failures"]


def plan_sheets(page: Page, scales: Scales, rest: tuple[bool, bool], path: str) -> dict[str, str]:
    """The velocity and acceleration plans at ``page`` the scene draws (file name → SVG);
    ``rest`` from :func:`~plans.pipeline.rest.at_rest`. A plan that fails its check raises a
    PlansError prefixed ``path``."""
    scene, motion, i = page.scene, page.motion, page.i
    files: dict[str, str] = {}
    for kind, builder, mu, still in (("velocity", velocity_plan, scales.mu_v, rest[0]),
                                     ("acceleration", acceleration_plan, scales.mu_a, rest[1])):
        if kind not in scene.draw:
            continue
        heading = Heading(scene.title, f"{kind.capitalize()} plan", page.label)
        if still:
            files[page.file(kind)] = empty_sheet(kind, heading, ident=page.ident(kind), why=rest_note(motion, kind),
                                                 style=page.style)
            continue
        plan = builder(motion, i, mu)
        failures = check_plan(plan) + similarity_failures(motion, plan, i)
        if failures:
            unit = "°" if motion.mechanism.drive.kind.angular else " m"
            raise PlansError(f"{path}: {kind} plan at {motion.values[i]:g}{unit} failed its geometric check: "
                             f"{failures[0]} (please report this scene)")
        sym = "μ_V" if kind == "velocity" else "μ_a"
        files[page.file(kind)] = draw_plan(plan, heading, ident=page.ident(kind), style=page.style,
                                           notes=tuple(n for n in scales.notes if n.startswith(sym)))
    return files


def similarity_failures(motion: Motion, plan: Plan, i: int, tol: float = 1e-9) -> list[str]:
    """Images of a link's points form a figure similar to the link (similarity theorem)."""
    out = []
    for link, labels in plan.similar:
        names = motion.mechanism.links[link].points
        figure = [tuple(motion.position(p)[i]) for p in names]
        image = [plan.point(l) for l in labels]
        if max(math.dist(image[0], q) for q in image) < 1e-9:
            continue  # the link is at rest on this plan: its image is one point
        dev = similarity_ratio(figure, image)
        if dev > 1e-6:
            out.append(f"images of link {link} are not similar to it (side ratios differ by {dev:.2e})")
    return out

"""A mechanism at rest: whether its velocities and accelerations are all zero, why (the note
written on its sheets and in the warning), and the plan sheet with the pole alone that stands
for a plan with nothing to draw (at rest, or a construction that cannot be drawn).

Reads a solved Motion and draws with plans.drawing; imports nothing of the pipeline's stages,
sheets, report or API."""

from __future__ import annotations

import numpy as np

from ..constructions.plans import Plan, PlanPoint
from ..drawing import Heading, Style, draw_plan
from ..kinematics import Motion

__all__ = ["at_rest", "rest_note", "empty_sheet"]


def at_rest(motion: Motion) -> tuple[bool, bool]:
    """Whether every velocity, and every acceleration, is zero at every position: the drive
    stands (ω1 = 0 or v = 0; with ε1 = 0 or a = 0 too for the accelerations), or every
    computed vector is exactly zero."""
    mech = motion.mechanism
    still_v = still_a = False
    if motion.order >= 1:
        still_v = mech.drive.speed == 0.0 or all(not np.any(motion.velocity(p)) for p in mech.sketch)
    if motion.order >= 2:
        still_a = (still_v and mech.drive.rate == 0.0) or all(not np.any(motion.acceleration(p)) for p in mech.sketch)
    return still_v, still_a


def empty_sheet(kind: str, heading: Heading, *, why: str, ident: str, style: Style) -> str:
    """A plan sheet with the pole alone: the plan of a mechanism at rest (every image at the
    pole), or a construction that cannot be drawn at this position; ``why`` is written below
    it, wrapped to the sheet. Any scale draws it the same; μ = 1 is written."""
    pole = "p" if kind == "velocity" else "π"
    plan = Plan(kind=kind, mu=1.0, pole=pole, points=(PlanPoint(pole, (0.0, 0.0)),), vectors=(), lines=(),
                similar=())
    return draw_plan(plan, heading, ident=ident, style=style, notes=(why,))


def rest_note(motion: Motion, kind: str) -> str:
    """Why a plan of ``kind`` is the pole alone: the drive stands (ω1 = 0, and ε1 = 0 for the
    accelerations), or every computed vector is zero."""
    d = motion.mechanism.drive
    what = "velocities are" if kind == "velocity" else "accelerations are"
    if d.speed != 0.0 or (kind == "acceleration" and d.rate != 0.0):
        return f"all {what} zero at every position, every image is at the pole"
    drive = (f"ω{d.link} = 0" if d.kind.angular else "v = 0") if kind == "velocity" else \
        (f"ω{d.link} = 0, ε{d.link} = 0" if d.kind.angular else "v = 0, a = 0")
    what = "velocities are" if kind == "velocity" else "velocities and accelerations are"
    return f"the mechanism is at rest ({drive}): all {what} zero, every image is at the pole"

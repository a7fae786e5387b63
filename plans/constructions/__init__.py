"""Constructions: the plans and the scheme as pure geometry, in millimetres of paper (y up).

Nothing here computes kinematics: it reads a solved :class:`~plans.kinematics.Motion` — the
points' positions, velocities and accelerations (``motion.velocity_at`` for any point of a
link), the sliding, the centres, the class III groups' special points — and nothing here draws
(the drawing package turns these objects into SVG). ``tests/test_motion_flow.py`` holds both.
"""

from .scales import SERIES, Scales, choose_scales, standard_scale
from .plans import Plan, PlanPoint, PlanVector, ConstructionLine, velocity_plan, acceleration_plan, uncertain_plan
from .scheme import Scheme, scheme

__all__ = ["SERIES", "Scales", "choose_scales", "standard_scale", "Plan", "PlanPoint", "PlanVector",
           "ConstructionLine", "velocity_plan", "acceleration_plan", "uncertain_plan", "Scheme", "scheme"]

"""Constructions: the plans and the scheme as pure geometry, in millimetres of paper (y up).

Nothing here solves kinematics (it reads a solved :class:`~plans.kinematics.Motion`) and
nothing here draws (the drawing package turns these objects into SVG).
"""

from .scales import SERIES, Scales, choose_scales, standard_scale
from .plans import Plan, PlanPoint, PlanVector, ConstructionLine, velocity_plan, acceleration_plan, uncertain_plan
from .scheme import Scheme, scheme

__all__ = ["SERIES", "Scales", "choose_scales", "standard_scale", "Plan", "PlanPoint", "PlanVector",
           "ConstructionLine", "velocity_plan", "acceleration_plan", "uncertain_plan", "Scheme", "scheme"]

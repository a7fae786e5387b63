"""Kinetostatics: inertia loads, the reactions of every pair group by group, the balancing
element, and the power balance that checks it. Numeric, vectorised over positions; reads a
solved :class:`~plans.kinematics.Motion` and never draws."""

from .loads import MIN_LOAD, Couple, Load, Travel, applied_loads, external_force, forces_following
from .solve import Balancing, Forces, ForceTerm, GroupForces, Reaction, solve_forces

__all__ = ["Couple", "Load", "Travel", "applied_loads", "external_force", "forces_following", "MIN_LOAD", "Balancing", "Forces", "ForceTerm", "GroupForces", "Reaction",
           "solve_forces"]

"""The machine's motion under its loads (the second problem of dynamics): the loads and masses
reduced to the crank, the work and energy over a steady cycle, the flywheel for an allowed
coefficient of speed fluctuation, and the true speed of the crank. Numeric; reads a solved
:class:`~plans.kinematics.cycle.Cycle` (and solves the kinematics at the points its exact
integrals need); never draws."""

from .machine import Flywheel, MachineDynamics, flywheel_for, machine_dynamics
from .piecewise import Piecewise
from .reduced import Reduced, reduce

__all__ = ["Flywheel", "MachineDynamics", "machine_dynamics", "flywheel_for", "Piecewise", "Reduced", "reduce"]

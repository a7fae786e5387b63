"""The machine's motion under its loads (the second problem of dynamics): the loads and masses
reduced to the crank, the work and energy over a steady cycle, the flywheel for an allowed
coefficient of speed fluctuation, the true speed of the crank, and the start-up by a motor
(integrated in time by SciPy). Numeric; reads a solved
:class:`~plans.kinematics.cycle.Cycle` (and solves the kinematics at the points its exact
integrals need); never draws. Flywheel problems without a linkage (a crank torque
over a cycle, punching and riveting): :mod:`.turning`."""

from .machine import Flywheel, MachineDynamics, flywheel_for, machine_dynamics
from .motor import motor_moment, no_load_speed
from .piecewise import Piecewise
from .reduced import Reduced, reduce
from .startup import Startup, Steady, startup, steady_cycle
from .true_speed import at_true_speed
from .turning import OperationAnalysis, TurningAnalysis, analyse_operation, analyse_turning

__all__ = ["Flywheel", "MachineDynamics", "machine_dynamics", "flywheel_for", "Piecewise", "Reduced", "reduce",
           "Startup", "Steady", "startup", "steady_cycle", "motor_moment", "no_load_speed", "at_true_speed",
           "TurningAnalysis", "OperationAnalysis", "analyse_turning", "analyse_operation"]

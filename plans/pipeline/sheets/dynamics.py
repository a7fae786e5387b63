"""The machine's steady cycle under its loads (``[dynamics]``): the report's ``cycle.dynamics``
(reduced moment and inertia, work, energy, the flywheel, the true speed) and its warnings.

Reads a solved MachineDynamics (and the force analysis, to show the balancing moment against
the reduced quantities); imports nothing of the pipeline."""

from __future__ import annotations

from typing import Mapping

import numpy as np

from ...constructions.forces import Lever
from ...drawing import Style
from ...dynamics import MachineDynamics
from ...kinetostatics import Forces
from ...scene import Scene

__all__ = ["dynamics_sheets", "dynamics_warnings", "balance_from_dynamics"]


def balance_from_dynamics(machine: MachineDynamics, omega1: float) -> np.ndarray:
    """The balancing moment (N·m, CCW) the reduced quantities give at the cycle's positions at a
    constant ω1 (ε1 = 0): M_b = −M_r + I_r·ε1 + ½·(dI_r/dφ)·ω1²."""
    at = machine.at
    return -at.moment + 0.5 * at.slope * omega1 ** 2


def dynamics_sheets(scene: Scene, machine: MachineDynamics, forces: Forces | None, levers: Mapping[int, Lever],
                    stem: str, style: Style) -> tuple[dict[str, str], dict]:
    """The dynamics sheet (when drawn) and the report's ``cycle.dynamics``."""
    th = machine.theta
    s = machine.sense
    wheel = machine.flywheel
    hi, lo, reached = machine.delta_reached()
    data: dict = {
        "reduced_moment": [float(x) for x in machine.at.moment],
        "reduced_inertia": [float(x) for x in machine.at.inertia],
        "reduced_inertia_slope": [float(x) for x in machine.at.slope],
        "rotor_inertia": machine.rotor,
        "constant_moment": s * machine.constant,
        "work_resisting": [float(x) for x in machine.resisting_work(th)],
        "work_driving": [float(x) for x in machine.driving_work(th)],
        "kinetic_energy_change": [float(x) for x in machine.energy(th)],
        "flywheel": {"inertia_exact": wheel.inertia_exact, "inertia_wittenbauer": wheel.inertia_wittenbauer,
                     "difference": None if wheel.inertia_wittenbauer is None or wheel.inertia_exact == 0.0 else
                     abs(wheel.inertia_wittenbauer - wheel.inertia_exact) / wheel.inertia_exact,
                     "required": wheel.required, "delta": wheel.delta, "given": wheel.given},
        "omega_mean": machine.omega_m, "omega_max": hi, "omega_min": lo, "delta_reached": reached,
        "omega": [float(x) for x in s * machine.omega(th)],
        "epsilon": [float(x) for x in s * machine.epsilon(th)],
    }
    w1 = s * machine.omega_m
    if forces is not None and forces.balance.kind == "moment":
        mb = balance_from_dynamics(machine, w1)
        groups = forces.balance.value
        ref = np.maximum(np.abs(groups), 1e-300)
        data["balance_check"] = {
            "from_reduced": [float(x) for x in mb], "groups": [float(x) for x in groups],
            "lever": {str(i): float(lv.result) for i, lv in sorted(levers.items())},
            "max_relative_difference": float(np.max(np.abs(mb - groups) / np.maximum(ref, np.max(np.abs(groups)))))}
    return {}, data


def dynamics_warnings(machine: MachineDynamics) -> list[str]:
    """A flywheel that is not needed (the machine's own inertia keeps δ)."""
    w = machine.flywheel
    if w.required is not None and w.required < 0.0:
        return [f"no flywheel is needed: the machine's own inertia keeps the speed's fluctuation within "
                f"δ = {w.delta:.4g} (it would take J = {w.required:.4g} kg·m² to reach it exactly)"]
    return []

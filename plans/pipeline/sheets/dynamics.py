"""The machine's steady cycle under its loads (``[dynamics]``): the report's ``cycle.dynamics``
(reduced moment and inertia, work, energy, the flywheel, the true speed) and its warnings.

Reads a solved MachineDynamics (and the force analysis, to show the balancing moment against
the reduced quantities); imports nothing of the pipeline."""

from __future__ import annotations

from typing import Mapping

import numpy as np

from ...constructions.dynamics import DynamicsDiagrams, dynamics_diagrams
from ...constructions.forces import Lever
from ...drawing import Heading, Style
from ...drawing.dynamics import draw_dynamics
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
    files: dict[str, str] = {}
    if "dynamics" in scene.draw:
        d = dynamics_diagrams(machine)
        link = scene.drive.link
        position = f"{len(th)} positions from φ_{link} = {machine.start % 360.0:.6g}°, ω_m = {machine.omega_m:g} rad/s, " \
                   + (f"δ = {wheel.delta:.4g}" if not wheel.given else f"J = {wheel.inertia_exact:g} kg·m² given")
        files[f"{stem}-dynamics.svg"] = draw_dynamics(
            d, Heading(scene.title, "Dynamics: reduced moment and inertia, work, energy, flywheel", position),
            ident="dynamics", style=style, notes=_notes(machine, d), scales=_scales(d))
        w = d.wittenbauer
        data["sheet"] = {"mu_phi": d.mu_phi, "pole": d.pole, "works": list(d.works), "mu": {g.quantity: g.mu for g in d.graphs},
                         "graphical_error": {g.quantity: g.error for g in d.graphs if g.graphical},
                         "wittenbauer": {"mu_i": w.mu_i, "mu_t": w.mu_t, "i0": w.i0, "segment": w.segment,
                                         "inertia": w.inertia,
                                         "psi": {t.which: t.psi for t in w.tangents}}}
    return files, data


def _scales(d: DynamicsDiagrams) -> str:
    m, a, t, i = d.graphs
    w = d.wittenbauer
    return (f"μ_φ = {d.mu_phi:g} rad/mm; μ_M = {m.mu:g} N·m/mm; μ_A = {a.mu:.4g} J/mm (H = {d.pole:g} mm); "
            f"μ_ΔT = {t.mu:g} J/mm; μ_I = {i.mu:g} kg·m²/mm; Wittenbauer: μ_I = {w.mu_i:g} kg·m²/mm, "
            f"μ_T = {w.mu_t:g} J/mm")


def _notes(machine: MachineDynamics, d: DynamicsDiagrams) -> tuple[str, ...]:
    m, a, t, i = d.graphs
    w = d.wittenbauer
    wheel = machine.flywheel
    loads, line = ("A_d", "A_r") if d.loads_drive else ("A_r", "A_d")
    what = "consumer's" if d.loads_drive else "driving"
    out = [f"M_r: the loads' reduced moment, positive where it drives the crank. {loads} = "
           f"{'' if d.loads_drive else '−'}∫M_r dφ by graphical integration by chords (dashed): over each of the "
           f"{d.positions} intervals M_r is taken at the interval's middle and the chord rises by that ordinate × Δφ "
           f"(the pole at H = {d.pole:g} mm: μ_A = μ_M·μ_φ·H); {line}: the constant {what} moment "
           f"{abs(machine.constant):.6g} N·m, the straight line to the end of {loads}. ΔT = A_d − A_r. Solid: exact.",
           f"Graphical {loads} differs from the exact by at most {100 * a.error:.2g} % of its largest value, "
           f"graphical ΔT by at most {100 * t.error:.2g} %."]
    if w.segment is not None:
        tmax, tmin = w.tangents
        jw = wheel.inertia_wittenbauer
        diff = abs(jw - wheel.inertia_exact) / wheel.inertia_exact if wheel.inertia_exact > 0.0 else 0.0
        out.append(f"Wittenbauer: tan ψ = (μ_I/μ_T)·ω_m²(1 ± δ)/2 with ω_m = {machine.omega_m:g} rad/s, δ = "
                   f"{wheel.delta:.4g}: ψ_max = {tmax.psi:.3f}°, ψ_min = {tmin.psi:.3f}°; the tangents cut kl = "
                   f"{abs(w.segment) / w.mu_t:.2f} mm on the ΔT axis (at I_r = {w.i0:g} kg·m²): "
                   f"J_fw = kl·μ_T/(ω_m²·δ) − {w.i0:g} = {w.inertia:.5g} kg·m². Exactly (ω_max, ω_min = "
                   f"ω_m(1 ± δ/2)): J_fw = {wheel.inertia_exact:.6g} kg·m²; Wittenbauer's differs by "
                   f"{100 * diff:.2g} % (its tangents take ω²/2 to first order in δ).")
        if wheel.required is not None and wheel.required < 0.0:
            out.append("No flywheel is needed: the machine's own inertia keeps δ.")
    else:
        hi, lo, reached = machine.delta_reached()
        out.append(f"With the given flywheel J = {wheel.inertia_exact:g} kg·m²: ω_max = {hi:.6g}, ω_min = {lo:.6g} "
                   f"rad/s, δ = {reached:.4g}.")
    return tuple(out)


def dynamics_warnings(machine: MachineDynamics) -> list[str]:
    """A flywheel that is not needed (the machine's own inertia keeps δ)."""
    w = machine.flywheel
    if w.required is not None and w.required < 0.0:
        return [f"no flywheel is needed: the machine's own inertia keeps the speed's fluctuation within "
                f"δ = {w.delta:.4g} (it would take J = {w.required:.4g} kg·m² to reach it exactly)"]
    return []

"""The machine's steady cycle under its loads (``[dynamics]``): the report's ``cycle.dynamics``
(reduced moment and inertia, work, energy, the flywheel, the true speed) and its warnings.

Reads a solved MachineDynamics (and the force analysis, to show the balancing moment against
the reduced quantities); imports nothing of the pipeline."""

from __future__ import annotations

from typing import Mapping

import numpy as np

from ...constructions.dynamics import DynamicsDiagrams, dynamics_diagrams, startup_diagrams
from ...constructions.forces import Lever
from ...drawing import Heading, Style
from ...drawing.dynamics import draw_dynamics, draw_startup
from ...dynamics import MachineDynamics, Startup
from ...dynamics.startup import STEADY_BAND
from ...kinetostatics import Forces
from ...scene import Scene

__all__ = ["dynamics_sheets", "dynamics_warnings", "balance_from_dynamics"]


def balance_from_dynamics(machine: MachineDynamics, omega1: np.ndarray | float,
                          epsilon1: np.ndarray | float = 0.0) -> np.ndarray:
    """The balancing moment (N·m, CCW) the reduced quantities give at the cycle's positions with
    the crank's ω1, ε1 there (CCW): M_b = −M_r + I_r·ε1 + ½·(dI_r/dφ)·ω1² (I_r of the links
    alone: the rotor and flywheel are not in the force analysis)."""
    at = machine.at
    return -at.moment + at.inertia * epsilon1 + 0.5 * at.slope * np.asarray(omega1) ** 2


def dynamics_sheets(scene: Scene, machine: MachineDynamics, forces: Forces | None, levers: Mapping[int, Lever],
                    stem: str, style: Style, started: Startup | None = None) -> tuple[dict[str, str], dict]:
    """The dynamics and start-up sheets (when drawn) and the report's ``cycle.dynamics``
    (with ``startup`` when simulated)."""
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
        "period": machine.period, "driving": "constant" if machine.driving is None else "law",
        "theta": [k * machine.period / len(th) for k in range(len(th))],
        "driving_moment": [float(x) for x in s * machine.driving_moment(th)],
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
    if scene.dynamics.true_speed:
        w1, e1 = s * machine.omega(th), s * machine.epsilon(th)
    else:
        w1, e1 = s * machine.omega_m, 0.0
    if forces is not None and forces.balance.kind == "moment":
        groups = forces.balance.value      # one turn's positions: M_b repeats every turn (no moment's law here)
        mb = balance_from_dynamics(machine, w1, e1)[:len(groups)]
        ref = np.maximum(np.abs(groups), 1e-300)
        data["balance_check"] = {
            "from_reduced": [float(x) for x in mb], "groups": [float(x) for x in groups],
            "lever": {str(i): float(lv.result) for i, lv in sorted(levers.items())},
            "max_relative_difference": float(np.max(np.abs(mb - groups) / np.maximum(ref, np.max(np.abs(groups)))))}
        if scene.dynamics.true_speed:   # the crank's moment less the flywheel's and rotor's inertia: M_d − (J + I_rotor)·ε1
            data["balance_check"]["driving_moment"] = [
                float(x) for x in groups + (machine.J + machine.rotor) * np.asarray(e1) * np.ones(len(groups))]
    files: dict[str, str] = {}
    if "dynamics" in scene.draw:
        d = dynamics_diagrams(machine)
        link = scene.drive.link
        cycle = f"{len(th)} positions" if d.turns == 1 else \
            f"{len(th)} positions over {machine.period:g}° ({d.turns} turns)"
        position = f"{cycle} from φ_{link} = {machine.start % 360.0:.6g}°, ω_m = {machine.omega_m:g} rad/s, " \
                   + (f"δ = {wheel.delta:.4g}" if not wheel.given else f"J = {wheel.inertia_exact:g} kg·m² given")
        files[f"{stem}-dynamics.svg"] = draw_dynamics(
            d, Heading(scene.title, "Dynamics: reduced moment and inertia, work, energy, flywheel", position),
            ident="dynamics", style=style, notes=_notes(machine, d), scales=_scales(d))
        w = d.wittenbauer
        data["sheet"] = {"mu_phi": d.mu_phi, "pole": d.pole, "works": list(d.works), "mu": {g.quantity: g.mu for g in d.graphs},
                         "graphical_error": {g.quantity: g.error for g in d.graphs if g.graphical},
                         "wittenbauer": {"mu_i": w.mu_i, "mu_t": w.mu_t, "i0": w.i0, "segment": w.segment,
                                         "inertia": w.inertia,
                                         "reading_error": None if w.segment is None else _reading(machine, d),
                                         "psi": {t.which: t.psi for t in w.tangents}}}
        if d.seconds:       # a driving law: A_r by chords too
            data["sheet"]["graphical_error"]["A_r"] = next(c.error for c in d.seconds if c.chords)
        if d.turns > 1:
            data["sheet"]["turned_inertia"] = "one turn"
    if started is not None:
        data["startup"] = _startup_data(machine, started)
        if "startup" in scene.draw:
            files[f"{stem}-startup.svg"] = _startup_sheet(scene, machine, started, style)
    return files, data


def _startup_data(machine: MachineDynamics, st: Startup) -> dict:
    s = machine.sense
    out: dict = {"t_end": st.t_end, "solver": "DOP853", "rtol": st.rtol, "atol": st.atol,
                 "evaluations": st.evaluations, "time_to_steady": st.time_to_steady,
                 "t": [float(x) for x in st.t],
                 "phi": [float(x) for x in (machine.start + s * np.degrees(st.theta))],
                 "omega": [float(x) for x in s * st.omega],
                 "motor_moment": [float(x) for x in s * st.motor],
                 "load_moment": [float(x) for x in s * st.load],
                 "steady": None, "last_revolution": None}
    if st.steady is not None:
        q = st.steady
        out["steady"] = {"omega_mean": q.omega_mean, "omega_max": q.omega_max, "omega_min": q.omega_min,
                         "delta": q.delta, "flywheel_delta": machine.flywheel.delta,
                         "difference": abs(q.delta - machine.flywheel.delta) / machine.flywheel.delta}
    if st.last is not None:
        out["last_revolution"] = {"omega_max": st.last[0], "omega_min": st.last[1], "delta": st.last[2]}
    return out


def _startup_sheet(scene: Scene, machine: MachineDynamics, st: Startup, style: Style) -> str:
    d = startup_diagrams(st)
    w, m = d.graphs
    motor = scene.dynamics.motor
    what = (f"motor {motor.power:g} W, {motor.rated_rpm:g}/{motor.synchronous_rpm:g} rpm, λ = "
            f"{motor.breakdown:g}") if not motor.torque else "motor by its torque table"
    position = f"from rest at φ_{scene.drive.link} = {machine.start % 360.0:.6g}°, {what}, i = {motor.ratio:g}"
    law = "Kloss' formula" if not motor.torque else "its torque–speed table"
    notes = [f"(I_r + J)·dω/dt + ½·(dI_r/dφ)·ω² = M_motor(ω) + M_r(φ), moments at the crank in its sense of rotation "
             f"(M_r < 0 where the loads resist), M_motor by {law} through the ratio i; J = {machine.J:.6g} kg·m² "
             f"(the flywheel) and the rotor's {machine.rotor:g} kg·m² in I_r. Integrated by SciPy's DOP853 (explicit "
             f"Runge–Kutta of order 8 with error control), rtol = {st.rtol:g}, atol = {st.atol:g}, "
             f"{st.evaluations} evaluations."]
    if st.steady is not None:
        q = st.steady
        reached = f"steady from t = {st.time_to_steady:.4g} s" if st.time_to_steady is not None else \
            f"not steady by t = {st.t_end:g} s"
        notes.append(f"Steady cycle (dashed: ω_max = {q.omega_max:.6g}, ω_min = {q.omega_min:.6g} rad/s): ω_m = "
                     f"{q.omega_mean:.6g} rad/s, δ = {q.delta:.5g} ({reached}, ω within ±{100 * STEADY_BAND:g} % of "
                     f"ω_m of the band); the flywheel was found for δ = {machine.flywheel.delta:.4g} with a constant "
                     f"driving moment: the motor's falling characteristic gives {q.delta:.4g}.")
    scales = f"μ_t = {d.mu_t:g} s/mm; μ_ω = {w.mu:g} rad/s/mm; μ_M = {m.mu:g} N·m/mm"
    return draw_startup(d, Heading(scene.title, "Start-up by the motor", position), ident="startup", style=style,
                        notes=tuple(notes), scales=scales)


#: How closely a drawn segment is read off the sheet with a ruler, mm: the graphical error the
#: dynamics sheet states for J from Wittenbauer's kl.
READ_MM = 0.5


def _reading(machine: MachineDynamics, d: DynamicsDiagrams) -> float:
    """The error of J_fw (kg·m²) from kl read to ±READ_MM: μT·READ_MM/(ω_m²·δ)."""
    return d.wittenbauer.mu_t * READ_MM / (machine.omega_m ** 2 * machine.flywheel.delta)


def _scales(d: DynamicsDiagrams) -> str:
    m, a, t, i = d.graphs
    return (f"μ_φ = {d.mu_phi:g} rad/mm; μ_M = {m.mu:g} N·m/mm; μ_A = {a.mu:.4g} J/mm (H = {d.pole:g} mm); "
            f"μ_ΔT = {t.mu:g} J/mm and μ_I = {i.mu:g} kg·m²/mm, Wittenbauer's too (by projection; I_r(φ) turned, "
            f"μ_φ = {d.mu_phi_turned:g} rad/mm)")


def _notes(machine: MachineDynamics, d: DynamicsDiagrams) -> tuple[str, ...]:
    m, a, t, i = d.graphs
    w = d.wittenbauer
    wheel = machine.flywheel
    loads, line = ("A_d", "A_r") if d.loads_drive else ("A_r", "A_d")
    what = "consumer's" if d.loads_drive else "driving"
    if d.seconds:
        r_error = next(c.error for c in d.seconds if c.chords)
        out = [f"M_r: the loads' reduced moment, positive where it drives the crank; M_d: the driving moment, the law "
               f"given against the crank angle (its mean {machine.constant:.6g} N·m). A_d = ∫M_d dφ and A_r = −∫M_r dφ "
               f"by graphical integration by chords (dashed): over each of the {d.positions} intervals the moment is "
               f"taken at the interval's middle and the chord rises by that ordinate × Δφ (the pole at H = {d.pole:g} "
               f"mm: μ_A = μ_M·μ_φ·H). ΔT = A_d − A_r. Solid: exact.",
               f"Graphical A_d differs from the exact by at most {100 * a.error:.2g} % of its largest value, A_r by "
               f"{100 * r_error:.2g} %, graphical ΔT by at most {100 * t.error:.2g} %."]
    else:
        out = [f"M_r: the loads' reduced moment, positive where it drives the crank. {loads} = "
               f"{'' if d.loads_drive else '−'}∫M_r dφ by graphical integration by chords (dashed): over each of the "
               f"{d.positions} intervals M_r is taken at the interval's middle and the chord rises by that ordinate × Δφ "
               f"(the pole at H = {d.pole:g} mm: μ_A = μ_M·μ_φ·H); {line}: the constant {what} moment "
               f"{abs(machine.constant):.6g} N·m, the straight line to the end of {loads}. ΔT = A_d − A_r. Solid: exact.",
               f"Graphical {loads} differs from the exact by at most {100 * a.error:.2g} % of its largest value, "
               f"graphical ΔT by at most {100 * t.error:.2g} %."]
    if d.turns > 1:
        n = d.per_turn
        out.append(f"The cycle is {machine.period:g}°, {d.turns} turns of the crank: M_r, the works and ΔT run over it "
                   f"(positions 0 … {d.positions}, every {360.0 / n:g}°), and so does Wittenbauer's curve. I_r repeats "
                   f"every turn, as the linkage does: it is drawn turned over one turn, positions k, k + {n}, … on one "
                   f"row.")
    if w.segment is not None:
        tmax, tmin = w.tangents
        jw = wheel.inertia_wittenbauer
        diff = abs(jw - wheel.inertia_exact) / wheel.inertia_exact if wheel.inertia_exact > 0.0 else 0.0
        out.append(f"Wittenbauer: tan ψ = (μ_I/μ_T)·ω_m²(1 ± δ)/2 with ω_m = {machine.omega_m:g} rad/s, δ = "
                   f"{wheel.delta:.4g}: ψ_max = {tmax.psi:.3f}°, ψ_min = {tmin.psi:.3f}°; the tangents cut kl = "
                   f"{abs(w.segment) / w.mu_t:.2f} mm on the ΔT axis (at I_r = {w.i0:g} kg·m²): "
                   f"J_fw = kl·μ_T/(ω_m²·δ) − {w.i0:g} = {w.inertia:.5g} kg·m². Exactly (ω_max, ω_min = "
                   f"ω_m(1 ± δ/2)): J_fw = {wheel.inertia_exact:.6g} kg·m²; Wittenbauer's differs by "
                   f"{100 * diff:.2g} % (its tangents take ω²/2 to first order in δ). Read to ±{READ_MM:g} mm, kl "
                   f"gives J_fw within ±{_reading(machine, d):.2g} kg·m² ({100 * _reading(machine, d) / w.inertia:.2g} %).")
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

"""The start-up by a motor (issue 18, item 5): Kloss' formula against its defining points, the
energy balance of the simulated start-up against the links' kinetic energy summed here, the
steady cycle it settles into against the periodic solution, and the refusals."""

from __future__ import annotations

import math

import numpy as np
import pytest

from conftest import EXAMPLES as _ALL, refused_line
from plans import render
from plans.checking import check_svg
from plans.dynamics import machine_dynamics, motor_moment, no_load_speed, startup
from plans.kinematics import analyse
from plans.pipeline import record_stages
from plans.pipeline.stages import solve_motion
from plans.scene import read_scene
from plans.scene.dynamics import Motor

EXAMPLES = _ALL[0].parent
NAME = "six_link_press_startup"
RPM = 2 * math.pi / 60


@pytest.fixture(scope="module")
def solved():
    scene = read_scene(EXAMPLES / f"{NAME}.toml")
    motion, cycle = solve_motion(scene)
    machine = machine_dynamics(scene, cycle)
    return scene, motion, machine, startup(machine, scene.dynamics.motor, scene.dynamics.simulate.t_end)


def test_kloss_through_its_rated_and_breakdown_points():
    m = Motor(ratio=3.0, power=4000.0, rated_rpm=1440.0, synchronous_rpm=1500.0, breakdown=2.5)
    rated = 4000.0 / (1440.0 * RPM)
    at = lambda rpm: float(motor_moment(m, rpm * RPM / 3.0))        # noqa: E731  (crank speed = motor/3)
    assert at(1440.0) == pytest.approx(3.0 * rated, rel=1e-12)
    s_r = 1 - 1440 / 1500
    s_k = s_r * (2.5 + math.sqrt(2.5 ** 2 - 1))
    assert at(1500.0 * (1 - s_k)) == pytest.approx(3.0 * 2.5 * rated, rel=1e-12)
    rpm = np.linspace(0.0, 1499.0, 3000)
    assert max(at(r) for r in rpm) <= 3.0 * 2.5 * rated * (1 + 1e-12)
    assert at(1500.0) == 0.0 and at(1520.0) < 0.0
    assert no_load_speed(m) == pytest.approx(1500.0 * RPM / 3.0, rel=1e-15)


def test_torque_table_is_linear_between_and_beyond_its_rows():
    m = Motor(ratio=2.0, torque=((0.0, 10.0), (1000.0, 8.0), (1500.0, 0.0)))
    assert float(motor_moment(m, 500.0 * RPM / 2.0)) == pytest.approx(2.0 * 9.0, rel=1e-12)
    assert float(motor_moment(m, 1600.0 * RPM / 2.0)) == pytest.approx(2.0 * -1.6, rel=1e-12)
    assert no_load_speed(m) == pytest.approx(1500.0 * RPM / 2.0, rel=1e-15)


def test_startup_conserves_energy(solved):
    """No losses: at three of the integrator's step ends, T(t) − T(0) equals the motor's work
    plus the loads' — T summed here from the links' velocities (a drive at 1 rad/s, scaled by
    ω²) and the flywheel, the motor's work ∫M·ω dt by Simpson's rule on the dense solution with
    Kloss' formula written here — to the bound the integrator's error control gives (below).

    The bound. E = T(θ, ω) − W_loads(θ) − W_motor(t) is constant on the exact solution. DOP853
    accepts a step when the RMS over (θ, ω) of its error estimate, each component scaled by
    s = atol + rtol·|y|, is below 1: each component errs by at most √2·s. A step's errors δθ,
    δω change E by ∂E/∂θ·δθ + ∂E/∂ω·δω = (½·I′·ω² − M_r)·δθ + (I + J)·ω·δω; summed over the
    steps with no cancellation. That holds on every step because the start-up stops at each
    kink of the loads: no step has one inside (a step over a kink errs by up to ~0.08·ΔM′·(ω·h)²,
    beyond what its estimate sees: stepping over them, the start-up once missed this sum by 3×).
    The motor's work is integrated over the dense output (of order 7; its error, measured against
    rtol 1e-13, is under 5× the step's, taken as 10×): h·|d(M·ω)/dω|·10·√2·s_ω a step. Simpson's
    rule errs by (t/180)·dt⁴·max|p⁗| = t/180·max|Δ⁴p| (Δ⁴ the fourth difference of the samples).
    The kinematics and the piecewise fits of the loads agree to ~1e-15 of T and W (< 1e-11 J),
    below all of these. Measured: under 0.006 of the bound, at rtol 3e-11 … 1e-9 too."""
    scene, motion, machine, st = solved
    mech, structure = motion.mechanism, motion.structure
    motor = scene.dynamics.motor
    rated = motor.power / (motor.rated_rpm * RPM)
    s_r = 1 - motor.rated_rpm / motor.synchronous_rpm
    s_k = s_r * (motor.breakdown + math.sqrt(motor.breakdown ** 2 - 1))
    two_pi = 2 * math.pi

    def kloss(w):
        s = 1 - w * motor.ratio / (motor.synchronous_rpm * RPM)
        return motor.ratio * 2 * motor.breakdown * rated / (s / s_k + s_k / s) if s != 0 else 0.0

    def power(w):
        return kloss(w) * w

    def kinetic(theta, omega):
        phi = machine.start + machine.sense * np.degrees(np.atleast_1d(theta))
        m = analyse(mech, structure, phi, order=1)
        w1 = mech.drive.speed
        total = np.zeros(len(phi))
        for link, mass in scene.masses.items():
            v = m.velocity(mass.centre, link)
            total += mass.mass * np.sum(v * v, axis=1) + mass.inertia * m.links[link].omega ** 2
        i_r = total / w1 ** 2 + scene.dynamics.rotor_inertia + machine.J
        return 0.5 * i_r * np.atleast_1d(omega) ** 2

    sol = st.solution
    steps = sol.t                                       # the integrator's step ends, 0 … t_end
    th_s, w_s = sol.sol(steps)
    s_th, s_w = st.atol + st.rtol * np.abs(th_s), st.atol + st.rtol * np.abs(w_s)
    dp = np.array([abs(power(w * (1 + 1e-7)) - power(w * (1 - 1e-7))) / (2e-7 * w) if w > 0 else abs(kloss(0.0))
                   for w in w_s])                       # |d(M·ω)/dω|, by a central difference
    de_dth = np.abs(0.5 * machine.slope(th_s % two_pi) * w_s ** 2 - machine.moment(th_s % two_pi))
    de_dw = (machine.inertia(th_s % two_pi) + machine.J) * np.abs(w_s)
    h = np.diff(steps, prepend=0.0)
    per_step = math.sqrt(2) * (de_dth * s_th + de_dw * s_w + 10 * h * dp * s_w)
    for k in (len(steps) // 4, len(steps) // 2, len(steps) - 1):
        t_k = steps[k]
        tt = np.linspace(0.0, t_k, 200001)
        y = sol.sol(tt)
        p = np.array([power(w) for w in y[1]])
        dt = tt[1] - tt[0]
        w_motor = dt / 3 * (p[0] + p[-1] + 4 * p[1:-1:2].sum() + 2 * p[2:-1:2].sum())
        th = th_s[k]
        turns = math.floor(th / two_pi)
        w_loads = turns * float(machine.work(two_pi)) + float(machine.work(th - turns * two_pi))
        gained = float(kinetic(th, w_s[k])[0])
        bound = float(per_step[1:k + 1].sum()) + t_k / 180 * float(np.max(np.abs(np.diff(p, 4))))
        assert abs(gained - (w_motor + w_loads)) <= bound, (t_k, gained, w_motor, w_loads, bound)


def test_steady_state_agrees_with_the_periodic_cycle_and_the_flywheel(solved):
    """The last simulated revolution's ω_max, ω_min and δ are the periodic solution's (shot over
    one revolution in φ, independently of the time integration) to what the start-up has not yet
    lost of its transient, plus the sampling of both maxima; its δ is the flywheel's δ = 1/20 less
    what the motor's falling characteristic damps (a few per cent: a physical statement, not a
    numerical tolerance), and the mean speed is the drive's ω within the motor's slip change (1 %,
    likewise).

    The transient: a deviation δω from the periodic solution changes T by δT = (I + J)·ω·δω, and
    d(δT)/dφ = (dM_motor/dω)·δω < 0 on the motor's falling branch: δT only decays, so over the
    last revolution |δω| ≤ |δω at its start|·max((I + J)·ω)/min((I + J)·ω) (to first order in δω;
    it decays by ~0.36 a revolution, so this bound is sharp within that factor: the deviation is
    physical, the start-up ends before it is gone, and the bound follows it, not a rounding).
    Sampling: each maximum is taken over samples Δ apart, within ½·max|ω″|·(Δ/2)² of the true one —
    max|Δ²ω|/8 on the start-up's 4001 instants, and on the periodic solution's ≥ 3990 points a
    revolution in φ with d²ω/dφ² ≤ max|ω̈|/ω² + max|ω̇|²/ω³. The integrations (rtol 1e-10 of ω,
    the shooting to 1e-12 of ω0) add less than 1e-8 rad/s, far below either."""
    from scipy.optimize import brentq

    scene, motion, machine, st = solved
    hi, lo, d = st.last
    q = st.steady
    sol = st.solution
    two_pi = 2 * math.pi
    turns = int(st.theta[-1] // two_pi)
    t_a, t_b = (brentq(lambda t, n=n: sol.sol(t)[0] - n * two_pi, 0.0, st.t_end, xtol=1e-14)
                for n in (turns - 1, turns))
    transient = abs(float(sol.sol(t_a)[1]) - q.omega0)
    th = np.linspace(0.0, two_pi, 4001)
    i_w = (machine.inertia(th) + machine.J) * machine.omega(th)
    transient *= float(i_w.max() / i_w.min())
    tt = np.linspace(t_a, t_b, 4001)
    ws = sol.sol(tt)[1]
    dt = tt[1] - tt[0]
    wd, wdd = np.abs(np.gradient(ws, dt)).max(), np.abs(np.diff(ws, 2)).max() / dt ** 2
    w_min = float(ws.min())
    sampled = wdd * (dt / 2) ** 2 / 2 + (wdd / w_min ** 2 + wd ** 2 / w_min ** 3) * (two_pi / 3990 / 2) ** 2 / 2
    bound = transient + sampled + 1e-8
    assert abs(hi - q.omega_max) <= bound and abs(lo - q.omega_min) <= bound, (hi, lo, q, transient, sampled)
    # δ = (hi − lo)/mean: each of hi, lo within ``bound``
    mean = 0.5 * (hi + lo)
    assert abs(d - q.delta) <= 2 * bound / mean + q.delta * bound / mean, (d, q.delta, bound)
    assert q.delta == pytest.approx(machine.flywheel.delta, rel=0.05) and q.delta < machine.flywheel.delta
    assert q.omega_mean == pytest.approx(abs(scene.drive.speed), rel=0.01)
    assert 0.0 < st.time_to_steady < st.t_end


@pytest.fixture(scope="module")
def rendered_startup():
    """The start-up example rendered once for this module, with the stages that ran."""
    with record_stages() as stages:
        out = render(EXAMPLES / f"{NAME}.toml")
    return out, list(stages)


def test_startup_sheet_checks_and_report(rendered_startup):
    out = rendered_startup[0]
    assert f"{NAME}-startup.svg" in out.files and f"{NAME}-dynamics.svg" in out.files
    data = out.report["cycle"]["dynamics"]["startup"]
    assert data["solver"] == "DOP853" and data["rtol"] == 1e-10
    assert len(data["t"]) == len(data["omega"]) == len(data["motor_moment"]) == len(data["load_moment"])
    assert data["omega"][0] == 0.0 and data["t"][-1] == data["t_end"]
    assert data["steady"]["difference"] < 0.05


def test_startup_sheet_passes_plans_check(tmp_path, rendered_startup):
    out = rendered_startup[0]
    path = tmp_path / "startup.svg"
    path.write_text(out.files[f"{NAME}-startup.svg"], encoding="utf-8")
    found = check_svg(path)
    assert len(found) == 26 and all(m.ok for m in found)
    data = out.report["cycle"]["dynamics"]["startup"]
    by = {m.quantity: m.value for m in found}
    assert by["w@12"] == pytest.approx(abs(data["omega"][-1]), rel=1e-12)


@pytest.mark.parametrize("stage", ["startup", "true_speed"])
def test_stage_runs_only_when_asked(stage, rendered_startup):
    """The flywheel example asks for neither the start-up nor the true speed; the start-up example for both."""
    with record_stages() as stages:
        render(EXAMPLES / "six_link_press_flywheel.toml")
    assert stage not in stages
    assert rendered_startup[1].count(stage) == 1


@pytest.mark.parametrize("old, new, words", [
    ("power = 370.0", "power = 20.0", "cannot start the load"),
    ("power = 370.0", "power = -1.0", "power"),
    ("rated_rpm = 1370.0", "rated_rpm = 1600.0", "rated_rpm"),
    ("breakdown = 2.2", "breakdown = 0.8", "breakdown"),
    ("ratio = 18.4", "ratio = 0", "ratio"),
    ("breakdown = 2.2  # M_max / M_rated\n", "", "breakdown is missing"),
    ("power = 370.0", "torque = [[0, 5.0], [1500, 0.0]]\npower = 370.0", "one of the two"),
    ('simulate = { t_end = 15.0, from = "rest" }', 'simulate = { t_end = 0.0 }', "t_end"),
    ('simulate = { t_end = 15.0, from = "rest" }', 'simulate = { t_end = 5.0, from = "speed" }', "from"),
    ("[motor]", "[motor_x]", "unknown"),
    ('simulate = { t_end = 15.0, from = "rest" }', "", "add simulate"),
])
def test_bad_startup_input_is_one_line_and_exit_2(tmp_path, old, new, words):
    text = (EXAMPLES / f"{NAME}.toml").read_text()
    assert old in text
    assert words in refused_line(tmp_path, text.replace(old, new))


# --- the positions at the true speed ([dynamics] true_speed) ----------------------------------------------

def test_true_speed_forces_balance_the_constant_driving_moment(rendered_startup):
    """At the true ω1(φ), ε1(φ) the crank's balancing moment found group by group (and on the
    lever) is the constant driving moment less the flywheel's and rotor's inertia torque:
    M_b + (J + I_rotor)·ε1 = M_d at every position, to 1e-9 — the force analysis and the
    dynamics meet without sharing a formula."""
    data = rendered_startup[0].report
    dyn = data["cycle"]["dynamics"]
    md = dyn["constant_moment"]
    j = dyn["flywheel"]["inertia_exact"] + dyn["rotor_inertia"]
    eps = [p["links"]["1"]["epsilon"] for p in data["positions"]]
    assert max(abs(e) for e in eps) > 0.1          # the true speed does vary
    for p, e, w, w_true in zip(data["positions"], eps, [p["links"]["1"]["omega"] for p in data["positions"]],
                               dyn["omega"]):
        assert w == pytest.approx(w_true, rel=1e-12)
        assert p["forces"]["balance"]["moment"] + j * e == pytest.approx(md, rel=1e-9)
        if p["forces"]["lever"]:
            assert p["forces"]["lever"]["moment"] + j * e == pytest.approx(md, rel=1e-9)


def test_true_speed_motion_is_the_kinematics_solved_at_that_speed(solved):
    """The rescaled motion (velocities ∝ ω1, accelerations ∝ (ε1, ω1²)) against the mechanism
    solved afresh with its drive at each position's ω1, ε1: 1e-12 of the largest value."""
    from dataclasses import replace

    from plans.dynamics import at_true_speed
    from plans.model import build_mechanism
    from plans.structure import analyse_structure

    scene, motion, machine, _ = solved
    w = machine.sense * machine.omega(machine.theta)
    e = machine.sense * machine.epsilon(machine.theta)
    true = at_true_speed(motion, w, e)
    mech = build_mechanism(scene)
    structure = analyse_structure(mech)
    for i in (0, 3, 7, 10):
        fresh = analyse(replace(mech, drive=replace(mech.drive, speed=float(w[i]), rate=float(e[i]))), structure,
                        np.array([motion.values[i]]), order=2)
        for point in ("A", "B", "C", "E", "S4"):
            v, a = true.velocity(point)[i], true.acceleration(point)[i]
            assert np.allclose(v, fresh.velocity(point)[0], rtol=0, atol=1e-12 * np.max(np.abs(true.velocity(point))))
            assert np.allclose(a, fresh.acceleration(point)[0], rtol=0,
                               atol=1e-12 * np.max(np.abs(true.acceleration(point))))


@pytest.mark.parametrize("old, new, words", [
    ("true_speed = true", "true_speed = 1", "true or false"),
    ('"positions", "dynamics"', '"positions", "diagrams", "dynamics"', "diagrams"),
])
def test_bad_true_speed_is_one_line(tmp_path, old, new, words):
    text = (EXAMPLES / f"{NAME}.toml").read_text()
    assert old in text
    assert words in refused_line(tmp_path, text.replace(old, new))

"""The machine's dynamics at its edges (issue 32, items 7 and 11–15): the flywheel at a tiny δ
against mpmath, a crank turned by a gear train at 0 rpm, a machine without masses, δ and the
start-up's length against their stated bounds, and refusals that name the file and the key."""

from __future__ import annotations

import dataclasses
import json
import math
import re
import sys
import warnings

import mpmath
import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from conftest import CRANK_SLIDER_MACHINE, EXAMPLES as _ALL, plans_cli, refused_line
from plans.checking import check_svg
from plans.dynamics import flywheel_for, machine_dynamics, startup
from plans.dynamics.piecewise import fit, nodes_of
from plans.errors import SceneError
from plans.pipeline.stages import solve_motion
from plans.scene import read_scene
from plans.scene.dynamics import MIN_DELTA, read_dynamics

EXAMPLES = _ALL[0].parent
STARTUP = sys.modules["plans.dynamics.startup"]       # the module (plans.dynamics.startup is the function)


def _text(name: str) -> str:
    return (EXAMPLES / f"{name}.toml").read_text(encoding="utf-8")


@pytest.fixture(scope="module")
def press():
    """The press of six_link_press_startup: its scene, cycle and steady machine."""
    scene = read_scene(EXAMPLES / "six_link_press_startup.toml")
    _, cycle = solve_motion(scene)
    return scene, cycle, machine_dynamics(scene, cycle)


# --- 7: the exact flywheel at a small δ ------------------------------------------------------------

def test_flywheel_at_a_tiny_delta_against_mpmath():
    """ΔT = A·sin θ, I = I0 + B·cos θ: max(ΔT − k·I) = √(A² + k²B²) − k·I0 and
    min(ΔT − k·I) = −√(A² + k²B²) − k·I0, so with k = ½ω_m²(1 ± δ/2)² the tangents give
    J = (√(A² + k_max²B²) + √(A² + k_min²B²))/(k_max − k_min) − I0, here in 50 digits. At δ = 1e-9
    k_max − k_min in doubles keeps 8 digits (it was 8e-8 off); the flywheel is right to 1e-12,
    and given that J back, the δ it keeps is 1e-9 to 1e-12."""
    a, b, i0, w, d = 150.0, 0.04, 0.1, 8.0, 1e-9
    edges = np.linspace(0.0, 2.0 * math.pi, 361)
    x = nodes_of(edges)
    energy, inertia = fit(edges, a * np.sin(x)), fit(edges, i0 + b * np.cos(x))
    with mpmath.workdps(50):
        big_a, big_b, big_w, big_d = (mpmath.mpf(v) for v in (a, b, w, d))
        k_hi, k_lo = big_w ** 2 * (1 + big_d / 2) ** 2 / 2, big_w ** 2 * (1 - big_d / 2) ** 2 / 2
        exact = float((mpmath.sqrt(big_a ** 2 + k_hi ** 2 * big_b ** 2) + mpmath.sqrt(big_a ** 2 + k_lo ** 2 * big_b ** 2))
                      / (k_hi - k_lo) - i0)
    wheel, _ = flywheel_for(energy, inertia, w, delta=d)
    assert exact == pytest.approx(2 * a / (w * w * d), rel=1e-3)           # ~4.7e9 kg·m²
    assert abs(wheel.inertia_exact - exact) <= 1e-12 * exact
    given, _ = flywheel_for(energy, inertia, w, flywheel=exact)
    assert abs(given.delta - d) <= 1e-12 * d


def _extreme(f, sign: float) -> float:
    """The largest (sign +1) or smallest (−1) value of f over [0, 2π]: a grid of 2¹⁶ points, then
    Brent's search between the best point's neighbours (scipy, not plans' golden section)."""
    th = np.linspace(0.0, 2.0 * math.pi, 2 ** 16 + 1)
    y = sign * f(th)
    k = int(np.argmax(y))
    lo, hi = th[max(k - 1, 0)], th[min(k + 1, len(th) - 1)]
    r = minimize_scalar(lambda t: -sign * float(f(t)), bounds=(lo, hi), method="bounded",
                        options={"xatol": 1e-14})
    return max(float(y[k]), -float(r.fun)) * sign


def test_press_flywheel_at_a_tiny_delta(press):
    """The press at δ = 1e-9 (the API; a scene is held to δ ≥ 1e-6): J against the tangents'
    extremes found here by another search, the factor k_max − k_min = ω_m²·δ in 50 digits; the δ
    it reaches (ω_max − ω_min over their mean) is 1e-9 to 1e-12 (it was 1.00000026e-9)."""
    scene, cycle, _ = press
    d = 1e-9
    tiny = dataclasses.replace(scene, dynamics=dataclasses.replace(scene.dynamics, delta=d))
    m = machine_dynamics(tiny, cycle)
    w = m.omega_m
    with mpmath.workdps(50):
        k_hi = mpmath.mpf(w) ** 2 * (1 + mpmath.mpf(d) / 2) ** 2 / 2
        k_lo = mpmath.mpf(w) ** 2 * (1 - mpmath.mpf(d) / 2) ** 2 / 2
        c_hi = _extreme(lambda t: m.energy(t) - float(k_hi) * m.inertia(t), 1.0)
        c_lo = _extreme(lambda t: m.energy(t) - float(k_lo) * m.inertia(t), -1.0)
        exact = float((mpmath.mpf(c_hi) - mpmath.mpf(c_lo)) / (k_hi - k_lo))
    assert abs(m.J - exact) <= 1e-12 * exact
    hi, lo, reached = m.delta_reached()
    assert abs(reached - d) <= 1e-12 * d
    assert hi == pytest.approx(w * (1 + d / 2), rel=1e-15) and lo == pytest.approx(w * (1 - d / 2), rel=1e-15)
    omega = m.omega(np.linspace(0.0, 2 * math.pi, 4001))
    assert np.all(omega <= hi * (1 + 1e-15)) and np.all(omega >= lo * (1 - 1e-15))


# --- 11: a crank turned by a gear train at 0 rpm ---------------------------------------------------------

def _train_driven(rpm: str) -> str:
    """six_link_press_flywheel with its crank turned by press_drive's train, the motor at ``rpm``."""
    press = _text("six_link_press_flywheel")
    train = (EXAMPLES / "gears" / "press_drive.toml").read_text(encoding="utf-8")
    train = train[train.index("[gears.wheels]"):].replace("a = 1450.0", f"a = {rpm}")
    press = press.replace("omega = 8.0  # rad/s, the mean speed\n", "")
    return press.replace("[dynamics]", train + "\n[dynamics]").replace('"dynamics"]', '"dynamics", "gears"]')


@pytest.mark.parametrize("rpm", ["0.0", "1e-300"])
def test_train_at_rest_is_refused_at_its_input(tmp_path, rpm):
    line = refused_line(tmp_path, _train_driven(rpm))
    assert f"{tmp_path / 'bad.toml'}: [gears.input" in line
    assert "1e-09 rad/s" in line


# --- 12: a machine without masses ---------------------------------------------------------------------------

#: A central crank-slider, crank 0.1 m, rod 0.4 m, ω = 10 rad/s, no masses; F = 1000 N on the
#: slider along −x, the whole cycle.
CRANK_SLIDER = """title = "crank-slider, no masses"
""" + CRANK_SLIDER_MACHINE + """[[forces]]
link = "3"
at = "B"
vector = [-1000.0, 0.0]
[dynamics]
delta = 0.05
[plans]
output = "3"
draw = ["dynamics"]
"""


def _rendered(tmp_path, text: str) -> dict:
    scene = tmp_path / "machine.toml"
    scene.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    r = plans_cli(["render", scene, "-o", out, "-q"])
    assert r.returncode == 0, r.stderr
    sheet = out / "machine-dynamics.svg"
    assert all(m.ok for m in check_svg(sheet))
    return json.loads((out / "machine.json").read_text(encoding="utf-8"))["cycle"]["dynamics"]


def test_crank_slider_without_masses_flywheel_by_hand(tmp_path):
    """By hand: the force is constant and along the guide, so its work is −F·(x − x0) whatever
    the path — it has no mean, the constant driving moment is 0, and ΔT = F·(x0 − x). x runs over
    the stroke 2r = 0.2 m, so ΔT swings by 2F·r = 200 J. With I_r ≡ 0 the tangents of the energy–
    mass curve touch at its top and bottom: J = (ΔT_max − ΔT_min)/(δ·ω_m²) = 200/(0.05·100) =
    40 kg·m². The sheet draws I_r ≡ 0 on its axis and Wittenbauer's kl = 200 J."""
    data = _rendered(tmp_path, CRANK_SLIDER)
    assert data["flywheel"]["inertia_exact"] == pytest.approx(40.0, rel=1e-12)
    assert data["flywheel"]["inertia_wittenbauer"] == pytest.approx(40.0, rel=1e-12)   # exact when I_r ≡ 0
    assert data["delta_reached"] == pytest.approx(0.05, rel=1e-12)
    assert data["constant_moment"] == pytest.approx(0.0, abs=1e-9)
    assert max(abs(v) for v in data["reduced_inertia"]) == 0.0
    assert abs(data["sheet"]["wittenbauer"]["segment"]) == pytest.approx(200.0, rel=1e-12)
    assert max(data["kinetic_energy_change"]) - min(data["kinetic_energy_change"]) <= 200.0 * (1 + 1e-12)


def test_crank_slider_given_its_flywheel_keeps_delta(tmp_path):
    """The same machine given J = 40 kg·m²: ω² = ω_m² + 2(e0 + ΔT)/J swings by 2·200/40 = 10 rad²/s²
    about a mean that keeps (ω_max + ω_min)/2 = 10 rad/s: δ = 0.05."""
    data = _rendered(tmp_path, CRANK_SLIDER.replace("delta = 0.05", "flywheel = 40.0"))
    assert data["delta_reached"] == pytest.approx(0.05, rel=1e-12)
    assert data["omega_max"] ** 2 - data["omega_min"] ** 2 == pytest.approx(10.0, rel=1e-12)
    assert 0.5 * (data["omega_max"] + data["omega_min"]) == pytest.approx(10.0, rel=1e-15)


def test_machine_without_loads_draws_its_flat_moment(tmp_path):
    """Masses and no loads: M_r ≡ 0, ΔT ≡ 0, T constant; the speed varies with I_r alone and the
    flywheel keeps it within δ."""
    text = CRANK_SLIDER.replace('[[forces]]\nlink = "3"\nat = "B"\nvector = [-1000.0, 0.0]\n',
                                '[masses.3]\nmass = 2.0\ncentre = "B"\n')
    data = _rendered(tmp_path, text)
    assert max(abs(v) for v in data["reduced_moment"]) == 0.0
    assert data["delta_reached"] == pytest.approx(0.05, rel=1e-12)
    assert data["flywheel"]["inertia_exact"] > 0.0


# --- 13: δ against its bound -----------------------------------------------------------------------------

def test_delta_far_below_any_machine_is_refused(tmp_path):
    line = refused_line(tmp_path, _text("six_link_press_flywheel").replace("delta = 0.05", "delta = 1e-300"))
    assert f"{tmp_path / 'bad.toml'}: [dynamics.delta]" in line and "1e-06" in line and "1/1000" in line
    assert read_dynamics({"delta": MIN_DELTA}).delta == MIN_DELTA
    with pytest.raises(SceneError, match="1e-06"):
        read_dynamics({"delta": 0.99 * MIN_DELTA})


# --- 14: start-ups that would not end ----------------------------------------------------------------------

def _startup_text(old: str, new: str) -> str:
    text = _text("six_link_press_startup")
    assert old in text
    return text.replace(old, new)


def test_start_up_of_thousands_of_turns_is_refused(tmp_path, press):
    """t_end = 3600 s (the reader's largest) at the motor's no-load speed 1500/18.4 rpm = 8.537
    rad/s: 4891 turns, beyond MAX_TURNS = 200; the line gives the t_end that passes, 200 turns:
    200·2π/8.537 = 147.2 s."""
    line = refused_line(tmp_path, _startup_text("t_end = 15.0", "t_end = 3600.0"))
    assert f"{tmp_path / 'bad.toml'}: [dynamics.simulate.t_end]" in line
    assert "4891 times" in line and f"beyond {STARTUP.MAX_TURNS} turns" in line
    assert "give t_end ≤ 147 s" in line
    scene, _, machine = press
    STARTUP._check_length(machine, scene.dynamics.motor, 147.0)        # what it gives passes


def test_motor_whose_torque_grows_with_speed_is_refused(tmp_path):
    """No no-load speed: the crank would speed up without end (ω grows exponentially)."""
    text = _startup_text("power = 370.0  # W, rated\n", "torque = [[0.0, 5.0], [1500.0, 10.0]]\n")
    for key in ("rated_rpm = 1370.0\n", "synchronous_rpm = 1500.0\n", "breakdown = 2.2  # M_max / M_rated\n"):
        text = text.replace(key, "")
    line = refused_line(tmp_path, text.replace("t_end = 15.0", "t_end = 3600.0"))
    assert f"{tmp_path / 'bad.toml'}: [motor.torque]" in line and "no-load speed" in line


@pytest.mark.parametrize("old, new, tau", [
    ("power = 370.0", "power = 1e9", 2.582e-7),           # a 1 GW motor
    ("ratio = 18.4", "ratio = 1e6", 2.362e-10),           # the slope at the crank grows as i²
])
def test_motor_far_stiffer_than_the_machine_is_refused(tmp_path, press, old, new, tau):
    """τ = min(I_r + J)/max|dM/dω|, Kloss' slope at synchronous speed 2·M_k/(s_k·ω_sync) times
    i²: with the press's 47.34 kg·m² the start-up's 15 s are ~1e7 τ and more, beyond 2e4 τ."""
    line = refused_line(tmp_path, _startup_text(old, new))
    assert f"{tmp_path / 'bad.toml'}: [dynamics.simulate.t_end]" in line
    assert f"τ = {tau:.4g} s" in line and f"beyond {STARTUP.MAX_STIFFNESS:g} τ" in line
    assert f"give t_end ≤ {STARTUP.MAX_STIFFNESS * tau:.3g} s" in line


def test_stiff_start_up_takes_evaluations_in_proportion_to_its_bound(press):
    """A 370 kW motor on the press (τ = 0.70 ms): 2000 τ of start-up take no more than their
    share of MAX_EVALUATIONS at MAX_STIFFNESS (15 evaluations a τ; DOP853 takes ~4.4)."""
    scene, _, machine = press
    motor = dataclasses.replace(scene.dynamics.motor, power=370e3)
    i_min = float(np.min(machine.inertia(np.linspace(0.0, 2 * math.pi, 721)))) + machine.J
    tau = i_min / STARTUP.motor_stiffness(motor)
    assert tau == pytest.approx(6.977e-4, rel=1e-3)
    st = startup(machine, motor, 2000 * tau)
    assert st.evaluations <= STARTUP.MAX_EVALUATIONS * 2000 / STARTUP.MAX_STIFFNESS


def test_start_up_takes_evaluations_in_proportion_to_its_turns(press):
    """The example's 15 s are 20.4 turns at the no-load speed: within their share of
    MAX_EVALUATIONS at MAX_TURNS (1500 a turn; the press takes ~620)."""
    scene, _, machine = press
    motor = scene.dynamics.motor
    turns = 15.0 * (motor.synchronous_rpm * 2 * math.pi / 60 / motor.ratio) / (2 * math.pi)
    st = startup(machine, motor, 15.0)
    assert st.evaluations <= STARTUP.MAX_EVALUATIONS * turns / STARTUP.MAX_TURNS


def test_start_up_past_its_evaluations_is_refused(press, monkeypatch):
    """The guard behind both bounds: past MAX_EVALUATIONS (here 3000) the start-up stops and the
    line names the instant reached, and a t_end below it."""
    scene, _, machine = press
    monkeypatch.setattr(STARTUP, "MAX_EVALUATIONS", 3000)
    with pytest.raises(SceneError) as err:
        startup(machine, scene.dynamics.motor, 15.0)
    assert err.value.key == "dynamics.simulate.t_end"
    reached = float(re.search(r"reached only t = (\S+) s", err.value.message).group(1))
    given = float(re.search(r"give t_end ≤ (\S+) s", err.value.message).group(1))
    assert 0.0 < given <= reached < 15.0


# --- 15: refusals that name the file and the key -----------------------------------------------------------------

@pytest.mark.parametrize("old, new, key, words", [
    ("power = 370.0", "power = 20.0", "motor", "the crank stops at t = 5.621 s"),          # later, in the cycle
    ("power = 370.0  # W, rated\nrated_rpm = 1370.0\nsynchronous_rpm = 1500.0\nbreakdown = 2.2  # M_max / M_rated\n",
     "torque = [[0.0, -1.0], [1000.0, 5.0], [1500.0, 0.0]]\n", "motor", "starting moment at the crank is -18.4 N·m"),
])
def test_motor_that_cannot_start_names_file_and_key(tmp_path, old, new, key, words):
    line = refused_line(tmp_path, _startup_text(old, new))
    assert line.startswith(f"plans: error: {tmp_path / 'bad.toml'}: [{key}]: the motor cannot start the load")
    assert words in line and "give a stronger motor" in line


def test_flywheel_too_small_names_file_and_key(tmp_path):
    line = refused_line(tmp_path, _text("six_link_press_flywheel").replace("delta = 0.05", "flywheel = 0.0"))
    assert f"{tmp_path / 'bad.toml'}: [dynamics.flywheel]: with a flywheel of 0 kg·m² the crank stops" in line
    assert "give a larger flywheel" in line


def test_machine_without_inertia_names_file_and_key_and_warns_nothing(tmp_path):
    """No masses, no rotor, flywheel = 0: refused before any division by its zero inertia (no
    numpy RuntimeWarning on the way)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        line = refused_line(tmp_path, CRANK_SLIDER.replace("delta = 0.05", "flywheel = 0.0"))
    assert f"{tmp_path / 'bad.toml'}: [dynamics.flywheel]: the machine has no inertia at all" in line
    assert "rotor_inertia" in line and "flywheel > 0" in line
    assert not [w for w in caught if issubclass(w.category, RuntimeWarning)]

"""A linkage's dynamics under laws in the crank angle (issue 35, item 3): ``[dynamics] driving`` as a
torque against the crank angle, ``[[moments]] law``, and a cycle of several turns (``period``).
Each against a value found here another way: a closed form integrated by hand (a rotor under a
harmonic or a semicircular torque, a load on the second turn only), today's constant driving, the
same cycle over one turn, and the flywheel problem without a linkage ([turning], its own exact
analysis by crossings)."""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from conftest import CRANK_SLIDER_MACHINE, EXAMPLES as _ALL, refused_line
from plans import render
from plans.checking import check_svg
from plans.dynamics import analyse_turning, machine_dynamics
from plans.errors import SceneError
from plans.pipeline.stages import solve_motion
from plans.scene import parse_scene
from plans.scene.turning import read_turning

EXAMPLES = _ALL[0].parent
ENGINE = EXAMPLES / "flywheel" / "engine_crank_slider.toml"

#: A central crank-slider without masses (I_r ≡ 0) and a rotor of 2 kg·m² on the crank (so the
#: reduced inertia is 2 kg·m², constant), ω_m = 10 rad/s CCW, δ = 0.05; a constant load of 500 N·m
#: against the crank, and a harmonic driving law of mean 500 N·m: T = 500 + 150·sin(3θ + 20°).
ROTOR = """title = "crank-slider, rotor only"
""" + CRANK_SLIDER_MACHINE + """[[moments]]
link = "1"
value = -500.0
[dynamics]
delta = 0.05
rotor_inertia = 2.0
driving = { mean = 500.0, harmonics = [[150.0, 3, 20.0]] }
[plans]
output = "3"
draw = ["scheme"]
"""
W2, DELTA, ROTOR_I = 100.0, 0.05, 2.0          # ω_m², δ, I_r of ROTOR
HARMONIC = 'driving = { mean = 500.0, harmonics = [[150.0, 3, 20.0]] }'
#: ROTOR over two turns: the load only on the second, R = 400 N·m against the crank, driven by a
#: constant moment.
TWO_TURNS = ROTOR.replace('value = -500.0', 'law = { shapes = [{ kind = "rectangle", from = 360, to = 720, '
                          'peak = -400.0 }] }').replace(HARMONIC, "period = 720")


def _machine(text: str):
    scene = parse_scene(tomllib.loads(text))
    _, cycle = solve_motion(scene)
    return machine_dynamics(scene, cycle)


def _report(tmp_path, text: str) -> dict:
    path = tmp_path / "machine.toml"
    path.write_text(text, encoding="utf-8")
    return render(path).report["cycle"]["dynamics"]


def _press(**dynamics) -> str:
    """The six-link press of the examples with its dynamics alone (no force analysis, no sheet),
    ``dynamics`` added to its [dynamics] (TOML values as text)."""
    text = (EXAMPLES / "six_link_press_flywheel.toml").read_text(encoding="utf-8")
    data = tomllib.loads(text)
    data["plans"]["draw"] = ["scheme"]
    data["plans"]["at"] = [0]
    data.pop("balance", None)
    data["dynamics"].update(dynamics)
    return data


def _machine_of(data: dict):
    scene = parse_scene(data)
    _, cycle = solve_motion(scene)
    return machine_dynamics(scene, cycle)


# --- the driving law ----------------------------------------------------------------------------------------

def test_driving_table_equal_to_the_loads_mean_is_the_constant_driving():
    """A table [[0, M], [360, M]] with M the constant driving moment today's press finds gives the
    same machine: J, δ reached, ΔT and ε along the cycle, to rounding (1e-15 measured; 1e-12 asked,
    the quadrature's own error)."""
    const = _machine_of(_press())
    m = const.constant
    law = _machine_of(_press(driving=[[0.0, m], [360.0, m]]))
    assert law.driving is not None and const.driving is None
    assert law.J == pytest.approx(const.J, rel=1e-12)
    assert law.delta_reached()[2] == pytest.approx(const.delta_reached()[2], rel=1e-12)
    th = np.linspace(0.0, 2 * np.pi, 1001)
    swing = float(np.ptp(const.energy(th)))
    assert np.max(np.abs(law.energy(th) - const.energy(th))) <= 1e-12 * swing
    assert np.max(np.abs(law.epsilon(th) - const.epsilon(th))) <= 1e-12 * np.max(np.abs(const.epsilon(th)))
    assert np.max(np.abs(law.driving_work(th) - const.driving_work(th))) <= 1e-12 * swing


def test_harmonic_driving_on_a_rotor_in_closed_form(tmp_path):
    """M_r = −500 N·m, I_r = 2 kg·m², M_d = 500 + A·sin(kθ + φ) (A = 150, k = 3, φ = 20°):
    ΔT(θ) = (A/k)(cos φ − cos(kθ + φ)), ΔE = 2A/k = 100 J. With I constant the tangents give
    J = ΔE/(ω_m²δ) − I = 100/5 − 2 = 18 kg·m²; ε = A·sin(kθ + φ)/(I + J); ω = ω_m(1 ± δ/2) at the
    extremes of ΔT. The report says so at the 12 positions."""
    a, k, phi = 150.0, 3.0, math.radians(20.0)
    data = _report(tmp_path, ROTOR)
    assert data["driving"] == "law" and data["period"] == 360.0
    assert data["flywheel"]["inertia_exact"] == pytest.approx(2 * a / k / (W2 * DELTA) - ROTOR_I, rel=1e-12)
    assert data["delta_reached"] == pytest.approx(DELTA, rel=1e-12)
    assert (data["omega_max"], data["omega_min"]) == pytest.approx((10.25, 9.75), rel=1e-13)
    assert data["theta"] == [30.0 * i for i in range(12)]
    th = np.radians(data["theta"])
    assert data["driving_moment"] == pytest.approx(500.0 + a * np.sin(k * th + phi), rel=1e-12)
    assert data["constant_moment"] == pytest.approx(500.0, rel=1e-14)       # the law's mean
    energy = a / k * (math.cos(phi) - np.cos(k * th + phi))
    assert np.max(np.abs(np.array(data["kinetic_energy_change"]) - energy)) <= 1e-12 * 2 * a / k
    assert data["work_driving"] == pytest.approx(500.0 * th + energy, rel=1e-12, abs=1e-12)
    assert data["work_resisting"] == pytest.approx(500.0 * th, rel=1e-12, abs=1e-12)
    eps = a * np.sin(k * th + phi) / (ROTOR_I + 18.0)
    assert np.max(np.abs(np.array(data["epsilon"]) - eps)) <= 1e-12 * a / 20.0


@pytest.mark.parametrize("order", [3, 37, 100])
def test_harmonic_driving_of_high_order(order):
    """J = (2A/k)/(ω_m²δ) − I with a rotor of 0.01 kg·m², up to the highest order a law takes: the
    panels shrink to 20°/k, and ΔT is ∫(M_r + M_d) at once, so the fluctuation (3 J at k = 100)
    is not the difference of the two works (3142 J each): 1.3e-13 measured at k = 100."""
    text = ROTOR.replace("[[150.0, 3, 20.0]]", f"[[150.0, {order}, 20.0]]").replace("rotor_inertia = 2.0",
                                                                                   "rotor_inertia = 0.01")
    assert _machine(text).J == pytest.approx(2 * 150.0 / order / (W2 * DELTA) - 0.01, rel=1e-12)


def test_semicircle_driving_in_closed_form():
    """A semicircle p·√(1 − u²) over 0 … 180° (p = 1000 N·m) against its mean pπ/8: ΔT is
    p·(π/2)(½(u√(1 − u²) + asin u) + π/4) − pπ/8·θ, greatest and least where the semicircle is
    pπ/8, u = ±c with c = √(1 − π²/64): ΔE = p(π/2)·asin c − pπ²c/16 and J = ΔE/(ω_m²δ) − I.
    The panels halve towards the semicircle's ends (without that the works differ by 4e-7 and the
    cycle is refused as unbalanced)."""
    p = 1000.0
    m0 = p * math.pi / 8
    text = ROTOR.replace("value = -500.0", f"value = {-m0!r}").replace(
        HARMONIC, f'driving = {{ shapes = [{{ kind = "semicircle", from = 0, to = 180, peak = {p!r} }}] }}')
    machine = _machine(text)
    c = math.sqrt(1.0 - math.pi ** 2 / 64)
    swing = p * math.pi / 2 * math.asin(c) - p * math.pi ** 2 * c / 16
    assert machine.J == pytest.approx(swing / (W2 * DELTA) - ROTOR_I, rel=1e-12)
    th = np.linspace(0.0, 2 * np.pi, 2001)
    u = np.clip((np.degrees(th) - 90.0) / 90.0, -1.0, 1.0)
    energy = p * math.pi / 2 * (0.5 * (u * np.sqrt(1 - u * u) + np.arcsin(u)) + math.pi / 4) - m0 * th
    assert np.max(np.abs(machine.energy(th) - energy)) <= 1e-11 * swing


def test_moment_law_equal_to_a_value_is_that_value():
    """A moment on the press's rocker 3 written as a law [[0, M], [360, M]] reduces as the value M
    does (M·ω3/ω1 at every node): the same reduced moment and J."""
    base = _press()
    base["moments"] = [{"link": "3", "value": -150.0}]
    law = _press()
    law["moments"] = [{"link": "3", "law": [[0.0, -150.0], [360.0, -150.0]]}]
    a, b = _machine_of(base), _machine_of(law)
    size = np.max(np.abs(a.at.moment))
    assert np.max(np.abs(a.at.moment - b.at.moment)) <= 1e-13 * size
    assert b.J == pytest.approx(a.J, rel=1e-12)


def test_moment_law_on_the_crank_draws_the_dynamics_sheet(tmp_path):
    """A triangular resisting moment on the crank (0 → 800 N·m at 90° → 0 at 180°, against it) and
    a constant driving moment, its mean 200 N·m. By hand: ΔT = 200θ − W(θ) is greatest where the
    load rises through 200 (θ = π/8: 25π − 12.5π) and least where it falls through it (θ = 7π/8:
    175π − 387.5π), ΔE = 225π J, J = 225π/5 − 2. The sheet is drawn and passes `plans check`."""
    text = ROTOR.replace("value = -500.0", "law = [[0, 0], [90, -800], [180, 0], [360, 0]]").replace(
        HARMONIC, "").replace('draw = ["scheme"]', 'draw = ["dynamics"]')
    path = tmp_path / "machine.toml"
    path.write_text(text, encoding="utf-8")
    rendered = render(path)
    data = rendered.report["cycle"]["dynamics"]
    assert data["constant_moment"] == pytest.approx(200.0, rel=1e-13)
    assert data["flywheel"]["inertia_exact"] == pytest.approx(225 * math.pi / (W2 * DELTA) - ROTOR_I, rel=1e-12)
    sheet = tmp_path / "machine-dynamics.svg"
    sheet.write_text(rendered.files["machine-dynamics.svg"], encoding="utf-8")
    assert all(m.ok for m in check_svg(sheet))


# --- several turns ------------------------------------------------------------------------------------------

def test_two_turns_with_the_load_on_the_second_by_hand(tmp_path):
    """Over 720° the load R = 400 N·m acts on the second turn only; the constant driving moment is
    the mean R/2. By hand: ΔT = Rθ/2 on the first turn (to πR at 360°), then πR − (R/2)(θ − 2π),
    back to 0 at 720°: ΔE = πR, J = πR/(ω_m²δ) − I; the speed is greatest at 360° and least at 0°.
    The cycle's arrays have 24 positions, 0 … 690°."""
    r = 400.0
    data = _report(tmp_path, TWO_TURNS)
    assert data["period"] == 720.0 and data["driving"] == "constant"
    assert data["theta"] == [30.0 * i for i in range(24)]
    assert all(len(data[k]) == 24 for k in ("reduced_moment", "reduced_inertia", "kinetic_energy_change", "omega",
                                            "epsilon", "work_driving", "work_resisting", "driving_moment"))
    assert data["constant_moment"] == pytest.approx(r / 2, rel=1e-13)
    assert data["flywheel"]["inertia_exact"] == pytest.approx(math.pi * r / (W2 * DELTA) - ROTOR_I, rel=1e-12)
    th = np.radians(data["theta"])
    energy = np.where(th <= 2 * np.pi, r * th / 2, math.pi * r - r / 2 * (th - 2 * np.pi))
    assert np.max(np.abs(np.array(data["kinetic_energy_change"]) - energy)) <= 1e-12 * math.pi * r
    assert data["reduced_moment"] == pytest.approx(np.where(th < 2 * np.pi, 0.0, -r), abs=1e-12 * r)
    omega = np.array(data["omega"])
    assert int(np.argmax(omega)) == 12 and int(np.argmin(omega)) == 0
    assert (data["omega_max"], data["omega_min"]) == pytest.approx((10.25, 9.75), rel=1e-13)


def test_press_over_two_turns_repeats_its_turn():
    """The press over 720° with its loads alone repeats its one-turn cycle: the same J (ΔT and I_r
    repeat), the positions of the second turn the same as the first's (the linkage is solved at
    θ mod 360°: the first turn's bit for bit, the second's to the rounding of θ − 2π). With a moment on the crank over the second turn only (a rectangle of
    −100 N·m), the loads' work is the one-turn work, then its total plus −100·(θ − 2π)."""
    one = _machine_of(_press())
    two = _machine_of(_press(period=720))
    n = len(one.theta)
    assert two.J == pytest.approx(one.J, rel=1e-12)
    assert two.at.inertia[n:] == pytest.approx(two.at.inertia[:n], rel=1e-13)
    assert np.array_equal(two.at.moment[:n], one.at.moment)
    assert np.max(np.abs(two.at.moment[n:] - one.at.moment)) <= 1e-13 * np.max(np.abs(one.at.moment))
    data = _press(period=720)
    data["moments"] = [{"link": "1", "law": {"shapes": [{"kind": "rectangle", "from": 360, "to": 720,
                                                           "peak": -100.0 * one.sense}]}}]
    loaded = _machine_of(data)
    th = np.linspace(0.0, 2 * np.pi, 361)
    total = one.work(2 * np.pi)
    size = float(np.max(np.abs(one.work(th))))
    assert np.max(np.abs(loaded.work(th) - one.work(th))) <= 1e-12 * size
    assert np.max(np.abs(loaded.work(th + 2 * np.pi) - (total + one.work(th) - 100.0 * th))) <= 1e-12 * size
    assert loaded.constant == pytest.approx(one.constant + 100.0 / 2, rel=1e-12)


def test_force_analysis_over_two_turns_checks_one_turn(tmp_path):
    """The press over 720° with its force plans and lever: the balancing moment from the reduced
    quantities is checked at the one turn the force analysis solves (the linkage's loads repeat),
    against the groups to the press's own 1e-9."""
    text = (EXAMPLES / "six_link_press_flywheel.toml").read_text(encoding="utf-8")
    text = text.replace("[dynamics]\n", "[dynamics]\nperiod = 720\n").replace('"positions", "dynamics"]', '"positions"]')
    data = _report(tmp_path, text)
    check = data["balance_check"]
    assert len(data["reduced_moment"]) == 2 * len(check["groups"]) == 24
    assert check["max_relative_difference"] <= 1e-9


def test_engine_example_against_the_flywheel_problem_without_a_linkage():
    """The example's torque over two turns, analysed as [turning] (crossings, closed-form areas):
    ΔE, and J = ΔE/(ω_m²δ) for a constant inertia. The example without its masses and with a rotor
    of 1 kg·m² needs J − 1 (2e-15 measured); with its masses, whose I_r varies with the crank angle,
    the machine is solved over 720° (24 positions) and its J is its own (17.4775 kg·m²)."""
    data = tomllib.loads(ENGINE.read_text(encoding="utf-8"))
    spec = read_turning({"period": 720, "omega": 150.0, "delta": 0.01, "torque": data["dynamics"]["driving"]}, None)
    ref = analyse_turning(spec)
    assert ref.mean_torque == pytest.approx(256.25, rel=1e-14)      # 1025π J over 4π
    engine = _machine_of(tomllib.loads(ENGINE.read_text(encoding="utf-8")))
    assert len(engine.theta) == 24 and engine.period == 720.0
    assert engine.delta_reached()[2] == pytest.approx(0.01, rel=1e-12)
    assert engine.J == pytest.approx(17.4774996, rel=1e-7)
    data.pop("masses")
    data["dynamics"]["rotor_inertia"] = 1.0
    assert _machine_of(data).J == pytest.approx(ref.inertia - 1.0, rel=1e-12)


# --- refused ------------------------------------------------------------------------------------------------

BAD = {
    "period": (TWO_TURNS.replace("period = 720", "period = 500"), "dynamics.period", "whole number of turns"),
    "beyond": (ROTOR.replace(HARMONIC, "driving = [[0, 500], [400, 500]]"), "dynamics.driving", "its last the period 360°"),
    "shape beyond": (TWO_TURNS.replace("period = 720", ""), "moments[0].law.shapes[0].to", "outside the cycle"),
    "unbalanced": (ROTOR.replace("mean = 500.0", "mean = 510.0"), "dynamics.driving",
                   "does 3204.42451 J over the cycle and the loads take 3141.59265 J"),
    "no work": (ROTOR.replace("mean = 500.0", "mean = -10.0"), "dynamics.driving", "it must drive"),
    "constant": (ROTOR.replace(HARMONIC, "driving = { mean = 500.0 }"), "dynamics.driving", "constant over the cycle"),
    "number": (ROTOR.replace(HARMONIC, "driving = 500.0"), "dynamics.driving", 'driving is "constant"'),
    "order": (ROTOR.replace("[[150.0, 3, 20.0]]", "[[150.0, 300, 20.0]]"), "dynamics.driving", "order k = 300"),
    "both": (ROTOR.replace("value = -500.0", "value = -500.0\nlaw = [[0, 1], [360, 2]]"), "moments[0]", "one of the two"),
    "no dynamics": (TWO_TURNS.split("[dynamics]")[0] + '[plans]\noutput = "3"\ndraw = ["scheme"]\n', "moments[0].law",
                    "add [dynamics]"),
    "narrow shape": (ROTOR.replace(HARMONIC, 'driving = { shapes = [{ kind = "semicircle", from = 10, '
                                             'to = 10.0000000001, peak = 1e12 }] }'),
                     "dynamics.driving.shapes[0]", "resolves"),
    "loads drive": (ROTOR.replace("value = -500.0", "value = 500.0"), "dynamics.driving", "nothing takes their work"),
    "forces": (TWO_TURNS.replace('draw = ["scheme"]', 'draw = ["scheme", "forces"]'), "moments[0].law",
               "take a law over one turn"),
    "true speed": (TWO_TURNS.replace("period = 720", "period = 720\ntrue_speed = true"), "dynamics.true_speed",
                   "not done yet over a cycle of 720°"),
    "simulate": (TWO_TURNS.replace("period = 720", "period = 720\nsimulate = { t_end = 1.0 }")
                 + "[motor]\ntorque = [[0, 1000], [100, 0]]\n", "dynamics.simulate", "not done yet over a cycle"),
    "simulate law": (ROTOR.replace("rotor_inertia = 2.0", "rotor_inertia = 2.0\nsimulate = { t_end = 1.0 }")
                     + "[motor]\ntorque = [[0, 1000], [100, 0]]\n", "dynamics.simulate", "driven by [motor]"),
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_refused_in_one_line(tmp_path, name):
    text, key, words = BAD[name]
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(SceneError) as err:
        render(path)
    line = str(err.value)
    assert "\n" not in line and f"[{key}]" in line and words in line, line


def test_unbalanced_law_names_the_factor_on_the_command_line(tmp_path):
    """The factor that balances the works, 500/510, in the one line the command prints."""
    line = refused_line(tmp_path, BAD["unbalanced"][0])
    assert "bad.toml: [dynamics.driving]" in line and f"{500 / 510:.12g}" in line

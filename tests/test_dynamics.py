"""The machine in motion (issue 18): loads that follow the cycle, the reduced moment and inertia,
the flywheel exactly and by Wittenbauer, the true speed — each against an independent computation
(the force analysis group by group and on the lever, a sum written here from the solved motion,
a direct integration of the energy equation, published turning-moment problems)."""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from conftest import EXAMPLES as _ALL, refused_line

EXAMPLES = _ALL[0].parent
from plans import render
from plans.checking import check_svg
from plans.dynamics import flywheel_for, machine_dynamics
from plans.dynamics.piecewise import Piecewise
from plans.kinematics import analyse
from plans.pipeline import record_stages
from plans.pipeline.stages import solve_motion
from plans.scene import parse_scene, read_scene
from plans.scene.file import parse_toml

DYNAMICS_EXAMPLES = ("six_link_press_flywheel", "compressor_flywheel", "shaper_flywheel")


_REPORTS: dict[str, dict] = {}


def _report(name: str) -> dict:
    """The example's report, rendered once for this module (several tests read each)."""
    if name not in _REPORTS:
        _REPORTS[name] = render(EXAMPLES / f"{name}.toml").report
    return _REPORTS[name]


@pytest.mark.parametrize("name", DYNAMICS_EXAMPLES + ("six_link_press_startup",))
def test_balancing_moment_from_reduced_quantities(name):
    """M_b = −M_r + I_r·ε1 + ½·(dI_r/dφ)·ω1² at every position, against the group-by-group
    balancing moment and Zhukovsky's lever, to 1e-9 of the largest: at a constant ω1 (ε1 = 0),
    and in the start-up example at the true ω1(φ), ε1(φ) (true_speed)."""
    data = _report(name)
    dyn = data["cycle"]["dynamics"]
    w1 = np.array([p["links"]["1"]["omega"] for p in data["positions"]])
    e1 = np.array([p["links"]["1"]["epsilon"] for p in data["positions"]])
    assert (np.any(e1 != 0.0)) == (name == "six_link_press_startup")
    mb = -np.array(dyn["reduced_moment"]) + np.array(dyn["reduced_inertia"]) * e1 \
        + 0.5 * np.array(dyn["reduced_inertia_slope"]) * w1 ** 2
    groups = np.array([p["forces"]["balance"]["moment"] for p in data["positions"]])
    size = np.max(np.abs(groups))
    assert np.max(np.abs(mb - groups)) <= 1e-9 * size
    levers = {i: p["forces"]["lever"]["moment"] for i, p in enumerate(data["positions"]) if p["forces"]["lever"]}
    assert levers
    for i, value in levers.items():
        assert abs(mb[i] - value) <= 1e-9 * size


@pytest.mark.parametrize("name", DYNAMICS_EXAMPLES + ("six_link_press_startup",))
def test_reduced_inertia_is_the_sum_of_the_links_energies(name):
    """I_r = Σ(m·v_S² + I_S·ω²)/ω1², summed here from the report's velocities, to 1e-12."""
    scene = read_scene(EXAMPLES / f"{name}.toml")
    data = _report(name)
    dyn = data["cycle"]["dynamics"]
    for i, p in enumerate(data["positions"]):
        w1 = p["links"][scene.drive.link]["omega"]
        total = 0.0
        for link, m in scene.masses.items():
            v = np.array(p["points"][m.centre]["v"])
            total += m.mass * float(v @ v) + m.inertia * p["links"][link]["omega"] ** 2
        assert dyn["reduced_inertia"][i] == pytest.approx(total / w1 ** 2, rel=1e-12, abs=1e-300)


def test_reduced_inertia_slope_against_finite_differences():
    scene = read_scene(EXAMPLES / "six_link_press_flywheel.toml")
    motion, cycle = solve_motion(scene)
    machine = machine_dynamics(scene, cycle)
    mech, structure = motion.mechanism, motion.structure
    h = 1e-4     # degrees

    def inertia(phi):
        m = analyse(mech, structure, np.array(phi), order=1)
        w1 = mech.drive.speed
        total = 0.0
        for link, mass in scene.masses.items():
            v = m.velocity(mass.centre, link)
            total = total + mass.mass * np.sum(v * v, axis=1) + mass.inertia * m.links[link].omega ** 2
        return total / w1 ** 2
    phi = motion.values
    fd = (inertia(phi + h) - inertia(phi - h)) / math.radians(2 * h)
    assert np.max(np.abs(fd - machine.at.slope)) <= 1e-6 * np.max(np.abs(machine.at.slope))


@pytest.mark.parametrize("name", DYNAMICS_EXAMPLES)
def test_exact_flywheel_meets_delta(name):
    dyn = _report(name)["cycle"]["dynamics"]
    wheel = dyn["flywheel"]
    assert wheel["inertia_exact"] > 0.0
    assert abs(dyn["delta_reached"] - wheel["delta"]) <= 1e-9 * wheel["delta"]
    assert abs(0.5 * (dyn["omega_max"] + dyn["omega_min"]) - dyn["omega_mean"]) <= 1e-9 * dyn["omega_mean"]
    # Wittenbauer's tangents with ω_m²(1 ± δ)/2 differ from the exact ones by O(δ²)
    assert abs(wheel["inertia_wittenbauer"] - wheel["inertia_exact"]) <= wheel["delta"] ** 2 * wheel["inertia_exact"]


def _direct_speed(scene, cycle, machine, theta_end: float):
    """ω(θ) from Lagrange's equation of the whole machine written here from its kinetic energy
    T = ½·(Σ m·v_S² + I_S·ω²)(φ, ω1) + ½·(J + rotor)·ω1² and the power of its loads computed from
    the forces themselves — dI/dφ by central differences, not from the reduced form — integrated
    with an adaptive Runge–Kutta to 1e-12."""
    mech, structure = cycle.motion.mechanism, cycle.motion.structure
    w1 = mech.drive.speed
    sense = 1.0 if w1 > 0 else -1.0
    law = scene.forces
    ends = analyse(mech, structure, cycle.extremes.values, order=0)
    y_ends = [float(y) for y in ends.position("E", "5")[:, 1]]
    low, high = min(y_ends), max(y_ends)        # the ram's guide is vertical (+y): s is y up to a constant
    h = 1e-3

    def unit_inertia(phi):
        m = analyse(mech, structure, np.atleast_1d(phi), order=1)
        total = 0.0
        for link, mass in scene.masses.items():
            v = m.velocity(mass.centre, link) / w1
            total = total + mass.mass * np.sum(v * v, axis=1) + mass.inertia * (m.links[link].omega / w1) ** 2
        return float(total[0]) + scene.dynamics.rotor_inertia + machine.J

    def load_power_per_omega(phi):
        """Σ F·v/ω1 of every load, the press's working force evaluated here from its table."""
        m = analyse(mech, structure, np.atleast_1d(phi), order=1)
        p = 0.0
        for link, mass in scene.masses.items():
            v = m.velocity(mass.centre, link)[0]
            p += -mass.mass * scene.gravity * v[1]
        for f in law:
            v = m.velocity(f.at, f.link)[0]
            s = float(m.position(f.at, f.link)[0][1])
            x = high - s if f.origin == "max" else s - low
            working = (v[1] < 0) if f.origin == "max" else (v[1] > 0)
            on = working if f.stroke == "working" else (not working if f.stroke == "return" else True)
            mag = np.interp(x, [q[0] for q in f.law], [q[1] for q in f.law]) if on else 0.0
            p += mag * float(np.array(f.vector) @ v)
        return p / w1

    def rhs(theta, y):
        phi = machine.start + sense * math.degrees(theta)
        w = y[0]
        i0 = unit_inertia(phi)
        di = (unit_inertia(phi + sense * h) - unit_inertia(phi - sense * h)) / math.radians(2 * h)
        m = sense * load_power_per_omega(phi) + machine.constant
        return [(m - 0.5 * w * w * di) / (i0 * w)]

    w0 = float(machine.omega(0.0))
    breaks = sorted(set([0.0, *[float(b) for b in machine.breaks if 0.0 < b < theta_end], theta_end]))
    ts, ws = [], []
    y = [w0]
    for a, b in zip(breaks[:-1], breaks[1:]):
        sol = solve_ivp(rhs, (a, b), y, method="DOP853", rtol=1e-12, atol=1e-12, dense_output=True)
        grid = np.linspace(a, b, 5)[1:]
        ts += list(grid)
        ws += list(sol.sol(grid)[0])
        y = [sol.y[0, -1]]
    return np.array(ts), np.array(ws)


def test_true_speed_agrees_with_a_direct_integration_of_the_equation_of_motion():
    scene = read_scene(EXAMPLES / "six_link_press_flywheel.toml")
    motion, cycle = solve_motion(scene)
    machine = machine_dynamics(scene, cycle)
    ts, ws = _direct_speed(scene, cycle, machine, 2 * math.pi)
    assert np.max(np.abs(ws - machine.omega(ts))) <= 1e-6 * machine.omega_m
    assert ws[-1] == pytest.approx(float(machine.omega(0.0)), rel=1e-8)     # a steady, periodic cycle


# --- published turning-moment problems: the flywheel with the reduced inertia constant --------------

def _steps(areas_mm2: list[float], mu_moment: float, mu_angle_deg: float, base: float = 0.0):
    """A moment diagram of rectangles whose areas (mm², in order, above + or below − the mean line)
    are the book's, drawn 1 mm of angle wide each: ΔT as a Piecewise of θ (rad)."""
    widths = np.full(len(areas_mm2), 1.0) * math.radians(mu_angle_deg)
    edges = np.concatenate([[0.0], np.cumsum(widths)])
    heights = np.array(areas_mm2) * mu_moment          # N·m over 1 mm of angle
    moment = Piecewise(edges, heights[:, None] * np.ones((1, 1)))
    return moment.integral(0.0)


def test_khurmi_multicylinder_engine_flywheel_mass():
    """Khurmi & Gupta, Theory of Machines, Example 16.4: areas +52, −124, +92, −140, +85, −72, +107 mm²
    at 1 mm = 600 N·m and 1 mm = 3°; 600 rpm, total fluctuation ±1.5 %; flywheel of radius 0.5 m:
    m = 182.5 kg (ΔE = 5403 N·m)."""
    energy = _steps([52, -124, 92, -140, 85, -72, 107], 600.0, 3.0)
    assert float(energy(energy.edges[-1])) == pytest.approx(0.0, abs=1e-9)
    edges = energy.edges
    inertia = Piecewise(edges, np.zeros((len(edges) - 1, 1)))
    omega = 2 * math.pi * 600 / 60
    wheel, _ = flywheel_for(energy, inertia, omega, delta=0.03)
    mass = wheel.inertia_exact / 0.5 ** 2
    assert round(mass, 1) == 182.5
    assert wheel.inertia_wittenbauer == pytest.approx(wheel.inertia_exact, rel=1e-12)


def test_khurmi_petrol_engine_fluctuation_of_speed():
    """Khurmi & Gupta, Example 16.2: areas +295, −685, +40, −340, +960, −270 mm² at 1 mm = 5 N·m and
    1 mm = 1°; rotating parts 36 kg at k = 150 mm; 1800 rpm: the coefficient of fluctuation of speed
    is 0.003 (ΔE = 86 N·m). Here the flywheel is given and δ found."""
    energy = _steps([295, -685, 40, -340, 960, -270], 5.0, 1.0)
    edges = energy.edges
    inertia = Piecewise(edges, np.zeros((len(edges) - 1, 1)))
    omega = 2 * math.pi * 1800 / 60
    wheel, _ = flywheel_for(energy, inertia, omega, flywheel=36 * 0.15 ** 2)
    assert round(wheel.delta, 3) == 0.003
    energy_swing = 985 * 5 * math.pi / 180
    assert wheel.delta == pytest.approx(energy_swing / (36 * 0.15 ** 2 * omega ** 2), rel=1e-4)


def test_machine_torque_over_three_turns():
    """Khurmi & Gupta, Example 16.5: the machine's torque rises from 750 to 3000 N·m over ½ turn, holds
    for 1 turn, falls to 750 over ½ turn and holds for 1 turn; constant driving torque; flywheel 500 kg
    at k = 0.6 m; 250 rpm: power 49.1 kW and total fluctuation of speed 7.16 % (±3.58 %)."""
    pi = math.pi
    edges = np.array([0.0, pi, 3 * pi, 4 * pi, 6 * pi])
    # the machine's moment (resisting, negative) as Legendre series on each panel: linear ramps
    mid = np.array([(750 + 3000) / 2, 3000.0, (750 + 3000) / 2, 750.0])
    half = np.array([1125.0, 0.0, -1125.0, 0.0])
    load = Piecewise(edges, -np.column_stack([mid, half]))
    work = load.integral(0.0)
    mean = -load.total() / (6 * pi)
    assert round(mean * 2 * pi * 250 / 60 / 1000, 1) == 49.1
    line = Piecewise(edges, np.column_stack([mean * (edges[:-1] + edges[1:]) / 2, mean * np.diff(edges) / 2]))
    from plans.dynamics.piecewise import combine
    energy = combine((1.0, work), (1.0, line))
    inertia = Piecewise(edges, np.zeros((4, 1)))
    wheel, _ = flywheel_for(energy, inertia, 2 * pi * 250 / 60, flywheel=500 * 0.6 ** 2)
    assert round(100 * wheel.delta, 2) == 7.16


# --- what is computed only when asked ---------------------------------------------------------------

def test_dynamics_runs_only_when_asked():
    with record_stages() as stages:
        render(EXAMPLES / "six_link_press_forces.toml")
    assert "dynamics" not in stages
    with record_stages() as stages:
        render(EXAMPLES / "six_link_press_flywheel.toml")
    assert stages.count("dynamics") == 1


def test_dynamics_report_is_deterministic():
    a = render(EXAMPLES / "shaper_flywheel.toml").json
    b = render(EXAMPLES / "shaper_flywheel.toml").json
    assert a == b


# --- loads that follow the cycle ---------------------------------------------------------------------

def test_law_force_follows_the_ram_on_its_working_stroke_only():
    scene = read_scene(EXAMPLES / "six_link_press_flywheel.toml")
    data = render(scene).report
    top = max(e["s"] for e in data["cycle"]["extremes"])
    f = scene.forces[0]
    for p in data["positions"]:
        moving_down = p["points"]["E"]["v"][1] < -1e-9
        slider = p["sliders"]
        key = next(iter(slider))
        travel = top - slider[key]["s"]
        expected = np.interp(travel, [q[0] for q in f.law], [q[1] for q in f.law]) if moving_down else 0.0
        # the reactions balance the force: the power balance holds with it (the report's residual)
        assert p["forces"]["power_residual"] <= 1e-9
        r = np.array(p["forces"]["reactions"]["4-5"]) + np.array(p["forces"]["reactions"]["0-5"])
        weight = -10.0 * 9.81
        inertia = np.array(p["forces"]["inertia"]["5"]["force"])
        # ram: R45 + R05 + G + F_in + F = 0 → F_y
        fy = -(r[1] + weight + inertia[1])
        assert fy == pytest.approx(expected, abs=1e-9 * 4000)


def test_opposing_force_on_a_slider_marghitu():
    """Marghitu's crank-slider with a force −sign(v)·500 N on the slider: its sense follows the slider's
    velocity at every position, and the balancing moment equals −F·v/ω1 (no masses)."""
    text = (EXAMPLES / "crank_slider_forces.toml").read_text()
    data = parse_toml(text, "marghitu.toml")
    for k in ("masses", "gravity", "moments"):
        data.pop(k, None)
    data["forces"] = [{"link": "3", "at": "B", "magnitude": 500.0, "oppose": True}]
    data["drive"] = {"link": "1", "angle": 10.0, "omega": 10.0, "positions": 8}
    data["plans"] = {"draw": ["forces"], "output": "3"}
    data.pop("balance", None)
    scene = parse_scene(data)
    rep = render(scene, stem="marghitu").report
    for p in rep["positions"]:
        v = np.array(p["points"]["B"]["v"])
        f = -np.array(p["forces"]["reactions"]["2-3"]) - np.array(p["forces"]["reactions"]["0-3"])
        if np.linalg.norm(v) < 1e-9:
            assert np.linalg.norm(f) <= 1e-9
            continue
        assert f == pytest.approx(-500.0 * v / np.linalg.norm(v), abs=1e-9)
        assert p["forces"]["balance"]["moment"] == pytest.approx(-float(f @ v) / 10.0, rel=1e-9, abs=1e-9)


# --- bad input ------------------------------------------------------------------------------------

@pytest.mark.parametrize("old, new, words", [
    ("[0.03, 1000.0], [0.04, 4000.0]", "[0.04, 1000.0], [0.03, 4000.0]", "not monotone"),
    ("delta = 0.05", "delta = 0.0", "delta"),
    ("delta = 0.05", "delta = -0.1", "delta"),
    ("delta = 0.05", "delta = 0.9", "delta"),
    ("delta = 0.05", "delta = 0.05\nflywheel = 3.0", "one of"),
    ("delta = 0.05", "flywheel = -1.0", "flywheel"),
    ("delta = 0.05", "delta = 0.05\nmotor = 1", "unknown key"),
    ("positions = 12\nstart = \"extreme\"  # the first position: the ram at its lowest",
     "angle = [30.0]", "positions"),
    ('stroke = "working"', 'stroke = "sometimes"', "stroke"),
    ('from = "max"', 'from = "top"', "from"),
    ("law = [[0.0, 0.0]", "law = [[-0.01, 0.0]", "0 or more"),
])
def test_bad_dynamics_input_is_one_line_and_exit_2(tmp_path, old, new, words):
    text = (EXAMPLES / "six_link_press_flywheel.toml").read_text()
    assert old in text
    assert words in refused_line(tmp_path, text.replace(old, new))


# --- the dynamics sheet ---------------------------------------------------------------------------------

def _sheet(name: str, tmp_path):
    out = render(EXAMPLES / f"{name}.toml")
    path = tmp_path / f"{name}-dynamics.svg"
    path.write_text(out.files[f"{name}-dynamics.svg"], encoding="utf-8")
    return out.report, path


@pytest.mark.parametrize("name", DYNAMICS_EXAMPLES)
def test_dynamics_sheet_passes_plans_check_and_draws_the_reported_values(name, tmp_path):
    """Every tagged ordinate (M_r, A, ΔT, I_r at the positions) and the segment kl measures
    within drawing precision, and the ordinates are the report's exact values."""
    data, path = _sheet(name, tmp_path)
    dyn = data["cycle"]["dynamics"]
    found = check_svg(path)
    assert found and all(m.ok for m in found), [m for m in found if not m.ok][:3]
    by = {m.quantity: m for m in found}
    n = len(dyn["reduced_moment"])
    work = dyn["work_resisting"] if dyn["sheet"]["works"][0] == "A_r" else dyn["work_driving"]
    for k in range(n):
        assert by[f"M@{k}"].value == pytest.approx(abs(dyn["reduced_moment"][k] * _sense(data)), rel=1e-12, abs=1e-9)
        assert by[f"I@{k}"].value == pytest.approx(dyn["reduced_inertia"][k] + dyn["rotor_inertia"], rel=1e-12)
        assert by[f"T@{k}"].value == pytest.approx(abs(dyn["kinetic_energy_change"][k]), rel=1e-9, abs=1e-9)
        assert by[f"A@{k}"].value == pytest.approx(abs(work[k]), rel=1e-9, abs=1e-9)
    assert f"M@{n}" in by and "kl" in by


def _sense(data) -> float:
    return 1.0 if data["positions"][0]["links"]["1"]["omega"] > 0 else -1.0


@pytest.mark.parametrize("name", DYNAMICS_EXAMPLES)
def test_wittenbauer_figure_within_the_error_the_sheet_states(name, tmp_path):
    """J read off the drawing (kl measured in the SVG, J = kl·μT/(ω_m²δ) − I0) is within the
    difference the sheet states between Wittenbauer's J and the exact one, plus what the drawn
    coordinates' rounding allows."""
    data, path = _sheet(name, tmp_path)
    dyn = data["cycle"]["dynamics"]
    w = dyn["sheet"]["wittenbauer"]
    kl = next(m for m in check_svg(path) if m.quantity == "kl")
    energy = w["mu_t"] * (dyn["omega_mean"] ** 2 * dyn["flywheel"]["delta"])
    j_drawn = kl.length_mm * w["mu_t"] / (dyn["omega_mean"] ** 2 * dyn["flywheel"]["delta"]) - w["i0"]
    exact = dyn["flywheel"]["inertia_exact"]
    stated = dyn["flywheel"]["difference"]
    text = path.read_text(encoding="utf-8")
    assert f"differs by {100 * stated:.2g} %" in text
    assert abs(j_drawn - exact) <= stated * exact + kl.tolerance / kl.mu * w["mu_t"] / energy * w["mu_t"] + 1e-12
    assert abs(j_drawn - exact) <= 1e-3 * exact          # and the drawing is good to the thousandth
    # the tangents' angles: tan ψ = (μI/μT)·ω_m²(1 ± δ)/2
    d = dyn["flywheel"]["delta"]
    for which, sign in (("max", 1), ("min", -1)):
        tan = w["mu_i"] / w["mu_t"] * dyn["omega_mean"] ** 2 * (1 + sign * d) / 2
        assert w["psi"][which] == pytest.approx(math.degrees(math.atan(tan)), rel=1e-12)


@pytest.mark.parametrize("name", DYNAMICS_EXAMPLES)
def test_graphical_work_is_the_sum_of_middle_ordinates(name, tmp_path):
    """The dashed work on the sheet at position k is ∓Σ M_r(middle of interval j)·Δφ over j < k:
    the middles' M_r read from a second render of the scene with twice the positions (its odd
    positions), so the chords are checked against values this sheet did not compute."""
    out = render(EXAMPLES / f"{name}.toml")
    n = len(out.report["cycle"]["dynamics"]["reduced_moment"])
    text = (EXAMPLES / f"{name}.toml").read_text(encoding="utf-8")
    assert f"positions = {n}" in text
    path = tmp_path / f"{name}_twice.toml"
    path.write_text(text.replace(f"positions = {n}", f"positions = {2 * n}"), encoding="utf-8")
    twice = render(path).report["cycle"]["dynamics"]
    middles = np.array(twice["reduced_moment"][1::2]) * _sense(out.report)
    sheet = out.files[f"{name}-dynamics.svg"]
    group = sheet[sheet.index('id="dynamics-A-gdots"'):]
    group = group[:group.index("</g>")]
    drawn = np.array([float(v) for v in re.findall(r'data-value="([^"]+)"', group)])
    chords = np.concatenate([[0.0], np.cumsum(middles * 2 * np.pi / n)])
    loads_resist = out.report["cycle"]["dynamics"]["sheet"]["works"][0] == "A_r"
    expect = -chords if loads_resist else chords
    assert len(drawn) == n + 1
    assert np.max(np.abs(drawn - expect)) <= 1e-9 * np.max(np.abs(expect))


@pytest.mark.parametrize("stem", ["six_link_press_flywheel", "compressor_flywheel", "shaper_flywheel"])
def test_wittenbauer_read_off_the_sheet_gives_j_within_its_stated_error(demo_rendered, stem):
    """kl measured on the drawn sheet × its μT (the sheet's own attributes) gives J_fw = kl·μT/(ω_m²·δ)
    − I0 equal to the exact J within the graphical error the sheet states (kl read to ±0.5 mm) and
    the method's own difference; and ΔT(φ) and Wittenbauer's diagram share μT, I_r(φ) and it μI
    (the projection)."""
    import xml.etree.ElementTree as ET
    svg = ET.parse(demo_rendered / f"{stem}-dynamics.svg").getroot()
    ns = "{http://www.w3.org/2000/svg}"
    dyn = json.loads((demo_rendered / f"{stem}.json").read_text(encoding="utf-8"))["cycle"]["dynamics"]
    fly, sheet = dyn["flywheel"], dyn["sheet"]
    seg = next(l for l in svg.iter(f"{ns}line") if l.get("data-quantity") == "kl")
    group = next(g for g in svg.iter(f"{ns}g") if g.get("id") == "dynamics-wittenbauer-kl")
    kl = math.dist((float(seg.get("x1")), float(seg.get("y1"))), (float(seg.get("x2")), float(seg.get("y2"))))
    mu_t = float(group.get("data-mu"))
    w = next(g for g in svg.iter(f"{ns}g") if g.get("data-diagram") == "wittenbauer")
    i0 = float(w.get("data-i0"))
    j = kl * mu_t / (dyn["omega_mean"] ** 2 * fly["delta"]) - i0
    drawn = 2 * math.sqrt(2) * 0.0005 * mu_t / (dyn["omega_mean"] ** 2 * fly["delta"])
    assert abs(j - fly["inertia_wittenbauer"]) <= drawn * 1.001
    stated = sheet["wittenbauer"]["reading_error"]
    assert abs(j - fly["inertia_exact"]) <= stated + abs(fly["inertia_wittenbauer"] - fly["inertia_exact"]) + drawn
    graphs = {g.get("data-diagram"): g for g in svg.iter(f"{ns}g") if g.get("data-diagram")}
    assert float(graphs["T"].get("data-scale")) == float(w.get("data-mu-t"))
    assert float(graphs["I"].get("data-scale")) == float(w.get("data-mu-i")) and graphs["I"].get("data-turned") == "90"
    # the projection: the ΔT graph's zero level is Wittenbauer's
    assert float(graphs["T"].get("data-origin").split(",")[1]) == pytest.approx(float(w.get("data-origin").split(",")[1]),
                                                                               abs=1e-3)

"""Published flywheel problems against [turning] and [flywheel] that tests/test_turning.py does not
have (it has Khurmi & Gupta's Examples 16.5, 16.6, 16.9–16.14, 16.16 and 16.19–16.22).

Source: R. S. Khurmi & J. K. Gupta, *Theory of Machines* (S. Chand), ch. 16 "Turning Moment Diagrams
and Flywheel", the examples numbered and paged as in FOSSEE/Python-Textbook-Companions,
Theory_Of_Machines/ch16.ipynb (id 1909037012 in the public code index), which gives each example's data
and the output its code printed; the FOSSEE Scilab companion's scripts of the same examples agree
(16.7: id 16275765447, 16.15: id 16811730124). Each printed answer is written as the literal printed and
asserted within its format's rounding: %.1f ±0.05, %.2f ±0.005, %.3f ±0.0005, %d truncates,
%.f and round() round to the nearest (no ties arise). Where the book rounds on the way
(a torque to 1 N·m, an angle to 0.1 rad, ω to 0.1 rad/s), plans's exact values are taken through the
same roundings and give the printed answer, and the exact value is also asserted. Where the diagram is
given by its areas or its extremes only, the torque here is a diagram of that kind (triangles with the
stated areas, lobes with the stated energy), and the test says why the answer does not depend on the
part the book leaves out. Units: N·m, J, rad/s, kg, m."""

from __future__ import annotations

import math

import pytest

from plans.dynamics.turning import analyse_turning
from plans.scene import parse_scene

RPM = math.pi / 30.0
REL = 1e-12


def _analysis(tables: dict):
    s = parse_scene(tables)
    return analyse_turning(s.turning, s.flywheel)


def _lobes(energies: list[float], mean: float, period: float = 360.0) -> list[list[float]]:
    """A torque table: one triangle on the mean line for each energy (J, in order), each 1/n of the
    period wide; with energies +ΔE, −ΔE the fluctuation is ΔE exactly."""
    w = period / len(energies)
    rows = [[0.0, mean]]
    for k, e in enumerate(energies):
        rows += [[(k + 0.5) * w, mean + 2.0 * e / math.radians(w)], [(k + 1) * w, mean]]
    rows[-1][0] = period
    return rows


# --- diagrams of triangles -----------------------------------------------------------------------------

def _double_acting(apex2: float) -> dict:
    """Ex. 16.7's engine: a triangle of 2000 N·m at 80° over the outstroke, one of 1500 N·m over the
    return stroke (its apex at ``apex2``°, which the data do not give)."""
    shapes = [{"kind": "triangle", "from": 0, "to": 180, "peak": 2000, "at": 80},
              {"kind": "triangle", "from": 180, "to": 360, "peak": 1500, "at": apex2}]
    return {"turning": {"rpm": 100, "delta": 0.015, "torque": {"shapes": shapes}}, "flywheel": {"radius": 1.75}}


@pytest.mark.parametrize("apex2", [200.0, 260.0, 320.0])
def test_khurmi_16_7_two_triangles_speed_extremes(apex2):
    """Ex. 16.7 (p. 578; Fig. 16.9): a double-acting engine's diagram, two triangles on bases of π, of
    2000 N·m at 80° (4π/9) from the inner dead centre and 1500 N·m, at 100 rpm, ±0.75 %, k = 1.75 m.
    Printed: "CE = 18 %" (%d), "m = 197.3 kg" (%.1f), the speed least at "35 degrees" and greatest at
    "136 degrees" (%d). In closed form: T_m = (2000 + 1500)/4 = 875, the outstroke's triangle crosses it
    at 80·875/2000 = 35° and 80 + 100·1125/2000 = 136.25°, ΔE = ½·π(1125/2000)·1125.

    The return stroke's apex is not in the data, and the answers do not depend on it while E stays
    between its values at 35° and 136.25° (−267.26 and 726.76 J) over the return stroke: E(180°) =
    392.69 J, the area below the mean before the second triangle crosses it is 875²·a/(2·1500) for an
    apex a rad after 180°, and its area above is 409.06 J, so a ∈ [0.294, 2.586] rad, 196.8° … 328.2°
    (checked at 190°: outside, ΔE grows)."""
    a = _analysis(_double_acting(apex2))
    de = 0.5 * math.pi * 1125 / 2000 * 1125
    assert a.mean_torque == pytest.approx(875.0, rel=REL)
    assert a.energy_fluctuation == pytest.approx(de, rel=REL)
    assert a.energy_coefficient == pytest.approx(de / (875 * 2 * math.pi), rel=REL)
    assert int(100 * a.energy_coefficient) == 18
    assert a.mass == pytest.approx(de / (1.75 ** 2 * (100 * RPM) ** 2 * 0.015), rel=REL) and abs(a.mass - 197.3) <= 0.05
    assert (a.energy_min_at, a.energy_max_at) == pytest.approx((35.0, 136.25), rel=REL)
    assert (int(a.energy_min_at), int(a.energy_max_at)) == (35, 136)
    assert _analysis(_double_acting(190.0)).energy_fluctuation > de + 1.0


def test_khurmi_16_8_three_cylinders_overlapping_triangles():
    """Ex. 16.8 (p. 580; Fig. 16.10): three single-acting cylinders, cranks 120° apart, each a triangle of
    90 N·m at 60° from its dead centre over its power stroke (180°), nothing on the return; 600 rpm,
    12 kg at k = 80 mm. The third crank's triangle runs over 240° … 420° and is written as three
    triangles within the turn (rising to 90 at 300°, falling 90 → 45 over 300°–360°, 45 → 0 over
    0°–60°). Printed: "Power developed = 4.24 kW" (%.2f), "CS = 4 %" (round, then %d), "CE = 2.78 %"
    (%.2f), the greatest acceleration "292 rad/s**2" (%d). The book's ΔE, E + 5.89 to E − 5.89: the
    sum repeats every 120°, 45 + 0.75θ up to 90 at 60° and back, T_m = 67.5, so ΔE = ½·(π/3)·22.5."""
    shapes = [{"kind": "triangle", "from": 0, "to": 180, "peak": 90, "at": 60},
              {"kind": "triangle", "from": 120, "to": 300, "peak": 90, "at": 180},
              {"kind": "triangle", "from": 240, "to": 360, "peak": 90, "at": 300},
              {"kind": "triangle", "from": 300, "to": 360, "peak": 45, "at": 360},
              {"kind": "triangle", "from": 0, "to": 60, "peak": 45, "at": 0}]
    a = _analysis({"turning": {"rpm": 600, "torque": {"shapes": shapes}, "at": [60.0, 180.0, 300.0]},
                   "flywheel": {"mass": 12.0, "radius": 0.08}})
    de, j = 0.5 * math.pi / 3 * 22.5, 12.0 * 0.08 ** 2
    assert a.mean_torque == pytest.approx(67.5, rel=REL) and abs(a.power / 1e3 - 4.24) <= 0.005
    assert a.energy_fluctuation == pytest.approx(de, rel=REL) and abs(a.energy_fluctuation - 11.78) <= 0.005
    assert a.delta == pytest.approx(de / (j * (600 * RPM) ** 2), rel=REL) and round(100 * a.delta) == 4
    assert abs(100 * a.energy_coefficient - 2.78) <= 0.005
    for _, _, alpha in a.acceleration:
        assert alpha == pytest.approx(22.5 / j, rel=REL) and int(alpha) == 292


def test_khurmi_16_17_four_stroke_triangles_and_the_rim():
    """Ex. 16.17 (p. 596; Fig. 16.20): a four-stroke engine's diagram of four triangles, 5, 21, 85, 8 ×
    10⁻⁵ m² (suction, compression below the zero line; expansion above; exhaust below), 1 m² = 14 MN·m,
    the speed between 98 and 102 rpm, the rim σ = 7.5 MPa, ρ = 8150 kg/m³, b = 4t. Printed: "I = 2316
    kg-m**2" (%.f), "t = 21.6 mm", "b = 86.3 mm" (%.1f). The book's way: T_m = 568 (rounded), the
    expansion's peak AG = int(11900/(π/2)) = 7575, DE = (AG − T_m)/AG·π = 2.9 rad (to 0.1 rad),
    ΔE = ½·DE·(AG − T_m). Exactly, ΔE = ½π(AG − T_m)²/AG (the excess of the expansion triangle over
    the mean: everything else is below it, wherever the apexes are): I = 2321.2 kg·m², and the rim's
    t and b scale as √ΔE."""
    c, areas = 14e6, [-5e-5, -21e-5, 85e-5, -8e-5]
    shapes = [{"kind": "triangle", "from": 180 * k, "to": 180 * (k + 1), "peak": 2 * s * c / math.pi}
              for k, s in enumerate(areas)]
    rim = {"density": 8150, "stress": 7.5e6, "width_to_thickness": 4.0}
    a = _analysis({"turning": {"period": 720, "rpm": 100, "delta": 0.04, "torque": {"shapes": shapes}},
                   "flywheel": {"rim": rim}})
    peak, tm = 2 * 85e-5 * c / math.pi, 51e-5 * c / (4 * math.pi)
    assert a.mean_torque == pytest.approx(tm, rel=REL)
    assert a.energy_fluctuation == pytest.approx(0.5 * math.pi * (peak - tm) ** 2 / peak, rel=REL)
    k2 = (100 * RPM) ** 2 * 0.04
    assert a.inertia == pytest.approx(a.energy_fluctuation / k2, rel=REL) and round(a.inertia, 1) == 2321.2
    fg = round(a.mean_torque)
    ag = int(int(85e-5 * c) / (0.5 * math.pi))
    de_book = 0.5 * round((ag - fg) / ag * math.pi, 1) * (ag - fg)
    assert (fg, ag) == (568, 7575) and round(de_book / k2) == 2316
    scale = math.sqrt(de_book / a.energy_fluctuation)
    assert abs(1e3 * a.rim.thickness * scale - 21.6) <= 0.05 and abs(1e3 * a.rim.width * scale - 86.3) <= 0.05
    assert a.rim.width == pytest.approx(4 * a.rim.thickness, rel=REL)


@pytest.mark.parametrize("negative", ["rectangle", "triangle"])
def test_khurmi_16_18_power_stroke_triangle_and_a_rim_of_fifteen_sixteenths(negative):
    """Ex. 16.18 (p. 599; Fig. 16.21): a four-stroke engine, 50 kW at 150 rpm (75 explosions a minute);
    the work of the power stroke 1.4 times the net work of the cycle, its diagram a triangle; ±0.5 %;
    the rim σ = 4 MPa, ρ = 7200 kg/m³, b = 4t, carrying 15/16 of the flywheel's energy (``share``).
    Printed: "D = 3 m" (%d), "t = 170 mm" (rounded), "b = 680 mm" (4 × the rounded t). ΔE is the
    triangle's excess over the mean, ½π(T_max − T_m)²/T_max, whatever the other strokes' −0.4 of the
    work looks like while it stays below the mean: here as a rectangle over the other three strokes or
    as a triangle over the exhaust stroke, the same answers."""
    omega = 150 * RPM
    tm = 50e3 / omega
    work = 4 * math.pi * tm
    t_max = 1.4 * work / (0.5 * math.pi)
    if negative == "rectangle":
        rest = {"kind": "rectangle", "from": 180, "to": 720, "peak": -0.4 * work / (3 * math.pi)}
    else:
        rest = {"kind": "triangle", "from": 540, "to": 720, "peak": -2 * 0.4 * work / math.pi}
    shapes = [{"kind": "triangle", "from": 0, "to": 180, "peak": t_max}, rest]
    rim = {"density": 7200, "stress": 4e6, "width_to_thickness": 4.0, "share": 15 / 16}
    a = _analysis({"turning": {"period": 720, "rpm": 150, "delta": 0.01, "torque": {"shapes": shapes}},
                   "flywheel": {"rim": rim}})
    de = 0.5 * math.pi * (t_max - tm) ** 2 / t_max
    assert a.power == pytest.approx(50e3, rel=REL) and a.energy_fluctuation == pytest.approx(de, rel=REL)
    v = math.sqrt(4e6 / 7200)
    assert a.rim.diameter == pytest.approx(60 * v / (math.pi * 150), rel=REL) and int(a.rim.diameter) == 3
    assert a.rim.mass == pytest.approx(15 / 16 * de / (v * v * 0.01), rel=REL)
    t = round(1e3 * a.rim.thickness)
    assert (t, 4 * t) == (170, 680) and round(1e3 * a.rim.width) == 680


# --- the fluctuation of energy given -------------------------------------------------------------------

def test_khurmi_16_15_rim_of_a_given_diameter():
    """Ex. 16.15 (p. 594; Scilab id 16811730124): 150 kW at 80 rpm, the fluctuation of energy 0.1 of the
    work per turn, ±2 %, the rim's mean diameter 2 m, ρ = 7200 kg/m³, the rim 95 % of the flywheel's
    inertia. Printed: "m = 3787 kg" (%.f), "A = 0.084 m**2" (%.3f). The companion rounds ω = 8.3776 to
    8.4 rad/s (so did the book): exactly, m = 0.95·ΔE/(ω²·δ·1 m²) = 3807.0 kg, and the rim's section
    m/(ρ·π·D) rounds to 0.084 m² either way. The diagram: lobes of ±ΔE about the mean (the book gives
    only ΔE)."""
    work = 150e3 * 60 / 80
    mean = work / (2 * math.pi)
    rim = {"density": 7200, "diameter": 2.0, "width_to_thickness": 1.0, "share": 0.95}
    a = _analysis({"turning": {"rpm": 80, "delta": 0.04, "torque": _lobes([0.1 * work, -0.1 * work], mean)},
                   "flywheel": {"rim": rim}})
    assert a.energy_fluctuation == pytest.approx(0.1 * work, rel=REL)
    assert a.energy_coefficient == pytest.approx(0.1, rel=REL)
    assert a.rim.mass == pytest.approx(0.95 * a.inertia, rel=REL) and round(a.rim.mass, 1) == 3807.0
    assert round(0.95 * a.energy_fluctuation / (8.4 ** 2 * 0.04)) == 3787
    assert a.rim.area == pytest.approx(a.rim.mass / (7200 * math.pi * 2.0), rel=REL) and round(a.rim.area, 3) == 0.084
    assert a.rim.width * a.rim.thickness == pytest.approx(a.rim.area, rel=REL)


def test_khurmi_16_1_speeds_from_the_fluctuation_of_energy():
    """Ex. 16.1 (p. 573): a flywheel of 6.5 t, k = 1.8 m, 120 rpm, the fluctuation of energy 56 kN·m:
    printed "N1 = 121 rpm", "N2 = 119 rpm" (rounded). With the mass given plans finds δ = ΔE/(Jω²) and
    the speeds ω(1 ± δ/2)."""
    a = _analysis({"turning": {"rpm": 120, "torque": _lobes([56e3, -56e3], 80e3)},
                   "flywheel": {"mass": 6500.0, "radius": 1.8}})
    j = 6500 * 1.8 ** 2
    assert a.delta == pytest.approx(56e3 / (j * (120 * RPM) ** 2), rel=REL)
    n1, n2 = a.omega_max / RPM, a.omega_min / RPM
    assert (n1 + n2) / 2 == pytest.approx(120.0, rel=REL) and (round(n1), round(n2)) == (121, 119)


def test_khurmi_16_3_mass_from_the_energy_coefficient():
    """Ex. 16.3 (p. 574): 300 kW at 90 rpm, the fluctuation of energy 0.1 of the work per turn, ±0.5 %,
    k = 2 m: printed "m = 5628 kg" (%d; 5628.7)."""
    work = 300e3 * 60 / 90
    torque = _lobes([0.1 * work, -0.1 * work], work / (2 * math.pi))
    a = _analysis({"turning": {"rpm": 90, "delta": 0.01, "torque": torque}, "flywheel": {"radius": 2.0}})
    assert a.mass == pytest.approx(0.1 * work / (4.0 * (90 * RPM) ** 2 * 0.01), rel=REL) and int(a.mass) == 5628

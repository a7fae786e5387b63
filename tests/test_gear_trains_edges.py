"""Gear trains at their edges (issue 32, items 1–4): passive planets written out (Khurmi & Gupta
Ex. 13.7), a double-planet train whose planets do not stand on one radius, every carrier's Willis
equation and assembly check in a two-stage train, and an unassemblable stage whose sun sits on
another carrier's shaft.

Every expected value is worked here by hand from the teeth (Willis' formula in fractions, the
assembly number (z_a + z_b)/k, the law of cosines), not read from plans.gears."""

from __future__ import annotations

import json
import math
from fractions import Fraction

import plans
from plans.gears import analyse_train
from plans.scene.gears import read_gears

from conftest import plans_cli, refused_line

# --- 1. Khurmi & Gupta Ex. 13.7: pinions B and C on arm H, both meshing sun A and ring D -----------
# The book's answers fix z_A : z_D: with D fixed the arm turns z_A/(z_A + z_D) = 4/13 of A's turn,
# so z_D/z_A = 9/4; the book's wheels are A = 40, D = 90, and the pinions (90 − 40)/2 = 25.
Z_A, Z_D = 40, 90
Z_P = (Z_D - Z_A) // 2


def _kg(inputs: str, *, fixed: bool, module: bool = True, planets: int = 1) -> str:
    m = ", module = 2.0" if module else ""
    return f"""title = "Khurmi & Gupta Ex. 13.7"
[gears.wheels]
A = {{ teeth = {Z_A}{m} }}
B = {{ teeth = {Z_P}{m}, on = "H" }}
C = {{ teeth = {Z_P}{m}, on = "H" }}
D = {{ teeth = {Z_D}{m}, internal = true }}
[gears]
carriers = ["H"]
meshes = [["A", "B"], ["B", "D"], ["A", "C"], ["C", "D"]]
{'fixed = ["D"]' if fixed else ''}
planets = {planets}
[gears.input]
{inputs}
"""


def _train(text: str):
    import tomllib
    return read_gears(tomllib.loads(text)["gears"])


def _arm_by_willis(n_a: Fraction, n_d: Fraction) -> Fraction:
    """n_H from (n_A − n_H)/(n_D − n_H) = −z_D/z_A (external sun–pinion, internal pinion–ring)."""
    i = Fraction(-Z_D, Z_A)
    return (n_a - i * n_d) / (1 - i)


def test_kg_13_7_d_fixed_the_arm_turns_4_13_of_a_turn_with_a():
    a = Fraction(-1)                                   # one turn of A clockwise (clockwise is −)
    assert _arm_by_willis(a, Fraction(0)) == Fraction(-4, 13)      # the book: 4/13 clockwise
    for module in (True, False):
        analysis = analyse_train(_train(_kg("A = -1.0", fixed=True, module=module)))
        rpm = analysis.speeds.rpm
        assert rpm["H"] == Fraction(-4, 13)
        # each pinion turns as the other: (n_B − n_H)/(n_A − n_H) = −z_A/z_B
        assert rpm["B"] == rpm["C"] == rpm["H"] + (a - rpm["H"]) * Fraction(-Z_A, Z_P) == Fraction(4, 5)
        s = analysis.speeds.structure
        assert [(p.name, p.copy_of, p.carrier) for p in s.passive] == [("C", "B", "H")]
        # without C: n = 3 (A, B, H), p5 = 3, p4 = 2; with it n = 4, p5 = 4, p4 = 4 and q = 1
        assert (s.n, s.p5, s.p4, s.mobility) == (3, 3, 2, 1)
        assert s.redundant == 1 and 3 * 4 - 2 * 4 - 4 + s.redundant == 1
        assert s.formula_with_passive == "W = 3·4 − 2·4 − 4 + 1 = 1"


def test_kg_13_7_d_turning_half_a_turn_back_the_arm_turns_1_26_anticlockwise():
    expected = _arm_by_willis(Fraction(-1), Fraction(1, 2))
    assert expected == Fraction(1, 26)                 # the book: 1/26 of a turn anticlockwise
    analysis = analyse_train(_train(_kg("A = -1.0\nD = 0.5", fixed=False)))
    assert analysis.speeds.rpm["H"] == Fraction(1, 26)
    s = analysis.speeds.structure
    assert s.mobility == 2 and s.formula_with_passive == "W = 3·5 − 2·5 − 4 + 1 = 2"
    (w,) = analysis.speeds.willis
    assert (w.carrier, w.a, w.b, w.ratio) == ("H", "A", "D", Fraction(-9, 4))


def test_kg_13_7_renders_and_names_its_passive_planet(tmp_path):
    scene = tmp_path / "kg.toml"
    scene.write_text(_kg("A = -1.0", fixed=True), encoding="utf-8")
    r = plans_cli(["render", scene, "-o", tmp_path / "out", "-q"])
    assert r.returncode == 0, r.stderr
    g = json.loads((tmp_path / "out" / "kg.json").read_text(encoding="utf-8"))["gears"]
    assert g["speeds"]["H"]["rpm_exact"] == "-4/13"
    assert g["passive"]["written"] == [{"planet": "C", "copy_of": "B", "carrier": "H", "meshes": 2}]
    assert g["passive"]["count"] == {"n": 4, "p5": 4, "p4": 4, "q": 1, "formula": "W = 3·4 − 2·4 − 4 + 1 = 1"}
    # B and C are two equally spaced planets: (z_A + z_D)/2 = 65 whole; arm r_A + r_B = 40 + 25 = 65 mm
    assert g["geometry"]["planet_sets"] == {"H": 2}
    assert g["geometry"]["planet_arm_mm"] == {"B": 65.0, "C": 65.0}
    assert g["geometry"]["planet_angle_deg"] == {"B": 0.0, "C": 180.0}
    assert g["warnings"] == []
    svg = (tmp_path / "out" / "kg-gears.svg").read_text(encoding="utf-8")
    assert "C repeats B on H" in svg and "W = 3·4 − 2·4 − 4 + 1 = 1" in svg


def test_written_copies_with_planets_k_are_k_times_as_many_planets(tmp_path):
    # planets = 2 of each of B and C: 4 equally spaced planets, (40 + 90)/4 = 32.5 not whole
    line = refused_line(tmp_path, _kg("A = -1.0", fixed=True, planets=2))
    assert "[gears.planets]" in line and "carrier 'H'" in line and "4 equally spaced planets" in line
    assert "32.5" in line and "bad.toml" in line


# --- 2. a double-planet train: sun a, planets g1–g2 in mesh on H, ring b ----------------------------
# module 2: r = z mm. a = 30, g1 = 18 → g1's axis at 30 + 18 = 48 mm; b = 90, g2 = 18 → 90 − 18 = 72 mm;
# their axes r_g1 + r_g2 = 36 mm apart: |48 − 72| = 24 ≤ 36 ≤ 120, the triangle closes.
DOUBLE = """title = "double planet"
[gears.wheels]
a  = {{ teeth = {a}, module = 2.0 }}
g1 = {{ teeth = {g1}, module = 2.0, on = "H" }}
g2 = {{ teeth = {g2}, module = 2.0, on = "H" }}
b  = {{ teeth = {b}, module = 2.0, internal = true }}
[gears]
carriers = ["H"]
meshes = [["a", "g1"], ["g1", "g2"], ["g2", "b"]]
fixed = ["b"]
planets = 3
[gears.input]
a = 1000.0
"""


def test_a_double_planet_train_whose_planets_are_not_on_one_radius_is_solved(tmp_path):
    scene = tmp_path / "dp.toml"
    scene.write_text(DOUBLE.format(a=30, g1=18, g2=18, b=90), encoding="utf-8")
    r = plans_cli(["render", scene, "-o", tmp_path / "out", "-q"])
    assert r.returncode == 0, r.stderr
    g = json.loads((tmp_path / "out" / "dp.json").read_text(encoding="utf-8"))["gears"]
    # Willis with H held: a → g1 → g2 → b: (−18/30)·(−18/18)·(+90/18), i_ab^H = +z_b/z_a = 3
    i_ab = Fraction(-18, 30) * Fraction(-18, 18) * Fraction(90, 18)
    assert i_ab == Fraction(3)
    n_h = Fraction(1000) / (1 - i_ab)                 # n_b = 0: (n_a − n_H) = i·(0 − n_H)
    assert g["speeds"]["H"]["rpm_exact"] == str(n_h) == "-500"
    assert g["willis"][0]["ratio"]["exact"] == "3"
    assert g["geometry"]["planet_arm_mm"] == {"g1": 48.0, "g2": 72.0}
    angle = math.degrees(math.acos((48 ** 2 + 72 ** 2 - 36 ** 2) / (2 * 48 * 72)))
    assert abs(g["geometry"]["planet_angle_deg"]["g2"] - angle) < 1e-9 and 26 < angle < 27
    # assembly: (z_a − z_b)/k = −60/3 whole; one set more than W counts: q = 3 meshes − 2 links
    assert g["passive"]["redundant_constraints"] == 2 * (3 - 2)
    assert g["geometry"]["unchecked"] == [] and g["warnings"] == []


def test_a_double_planet_train_is_refused_only_when_it_truly_does_not_close(tmp_path):
    # g1 = g2 = 10: axes 38 + 10 = 48 and 82 − 10 = 72 mm, but only 20 mm apart: 20 < |48 − 72| = 24
    line = refused_line(tmp_path, DOUBLE.format(a=38, g1=10, g2=10, b=82))
    assert "[gears.wheels]" in line and "'g1' and 'g2' cannot mesh" in line
    assert "48 mm and 72 mm" in line and "24 … 120 mm" in line and "20 mm" in line
    # sun 40, g1 17 (axis 57), g2 20 (axis 82 − 20 = 62): closes (5 ≤ 37 ≤ 119), but g2's tip circle
    # (radius 22) comes within 62 − 22 = 40 mm of the centre, inside the sun's tip circle (42 mm)
    line = refused_line(tmp_path, DOUBLE.format(a=40, g1=17, g2=20, b=82))
    assert "[gears.wheels]" in line and "planet 'g2'" in line and "runs into 'a'" in line
    # a 91-tooth ring puts g2 at 91 − 18 = 73 mm (closes: 25 ≤ 36 ≤ 121), but 3 sets need
    # (z_a − z_b)/3 whole, and (30 − 91)/3 = −20.33… is not
    assert Fraction(30 - 91, 3).denominator != 1
    line = refused_line(tmp_path, DOUBLE.format(a=30, g1=18, g2=18, b=91))
    assert "[gears.planets]" in line and "cannot be assembled" in line and "20.3333" in line


# --- 3. and 4. two stages: the second stage's sun a2 on the first carrier's shaft --------------------
TWO = """title = "two stages"
[gears.wheels]
a1 = {{ teeth = 18, module = 3.0 }}
g1 = {{ teeth = 27, module = 3.0, on = "H1" }}
b1 = {{ teeth = 72, module = 3.0, internal = true }}
a2 = {{ teeth = {a2}, module = 2.0, shaft = "H1" }}
g2 = {{ teeth = {g2}, module = 2.0, on = "H2" }}
b2 = {{ teeth = {b2}, module = 2.0, internal = true }}
[gears]
carriers = ["H1", "H2"]
meshes = [["a1", "g1"], ["g1", "b1"], ["a2", "g2"], ["g2", "b2"]]
fixed = ["b1", "b2"]
planets = 3
[gears.input]
a1 = 1450.0
"""


def test_every_carrier_gets_its_willis_equation_and_its_assembly_check(tmp_path):
    scene = tmp_path / "two.toml"
    scene.write_text(TWO.format(a2=21, g2=24, b2=69), encoding="utf-8")
    r = plans_cli(["render", scene, "-o", tmp_path / "out", "-q"])
    assert r.returncode == 0, r.stderr
    assert "warning" not in r.stderr
    g = json.loads((tmp_path / "out" / "two.json").read_text(encoding="utf-8"))["gears"]
    n_h1 = Fraction(1450) / (1 + Fraction(72, 18))    # 290: the sun a2 turns with H1
    n_h2 = n_h1 / (1 + Fraction(69, 21))              # 203/3
    assert g["speeds"]["H2"]["rpm_exact"] == str(n_h2) == "203/3"
    by_carrier = {w["carrier"]: w for w in g["willis"]}
    assert set(by_carrier) == {"H1", "H2"}
    h2 = by_carrier["H2"]
    assert h2["central"] == ["a2", "b2"] and h2["ratio"]["exact"] == str(Fraction(-69, 21)) == "-23/7"
    assert h2["equation"] == "(n_a2 − n_H2)/(n_b2 − n_H2) = −23/7"
    assert abs(h2["residual_rpm"]) < 1e-9
    assert (n_h1 - n_h2) / (0 - n_h2) == Fraction(-23, 7)          # the equation holds exactly
    # assembly of both stages checked: (18 + 72)/3 = 30, (21 + 69)/3 = 30; nothing left unchecked
    assert g["geometry"]["unchecked"] == [] and g["warnings"] == []
    assert g["geometry"]["arm_mm"] == {"H1": 67.5, "H2": 45.0}
    assert {row["link"] for row in g["tabular"]["H2"]} == {"H2", "a2", "b2", "g2"}


def test_a_stage_whose_sun_is_on_another_carriers_shaft_is_checked_for_assembly(tmp_path):
    # (20 + 80)/3 = 33.33…: 3 equally spaced planets cannot be assembled, on H1's shaft or alone
    assert Fraction(20 + 80, 3).denominator != 1
    line = refused_line(tmp_path, TWO.format(a2=20, g2=30, b2=80))
    assert "[gears.planets]" in line and "carrier 'H2'" in line and "33.3333" in line
    alone = """title = "stage alone"
[gears.wheels]
a2 = { teeth = 20, module = 2.0 }
g2 = { teeth = 30, module = 2.0, on = "H2" }
b2 = { teeth = 80, module = 2.0, internal = true }
[gears]
carriers = ["H2"]
meshes = [["a2", "g2"], ["g2", "b2"]]
fixed = ["b2"]
planets = 3
[gears.input]
a2 = 1450.0
"""
    assert refused_line(tmp_path, alone).split(": ", 1)[1] == line.split(": ", 1)[1]


def test_an_assembly_that_cannot_be_checked_is_a_warning(tmp_path):
    # a 3K train: block g–g2 on H between sun a, ring b (held) and ring e; the assembly formula
    # covers two central wheels only, so stderr and the report say it went unchecked
    scene = tmp_path / "threek.toml"
    scene.write_text("""title = "3K"
[gears.wheels]
a  = { teeth = 20, module = 2.0 }
g  = { teeth = 20, module = 2.0, on = "H" }
b  = { teeth = 60, module = 2.0, internal = true }
g2 = { teeth = 18, module = 2.0, on = "H", shaft = "g" }
e  = { teeth = 58, module = 2.0, internal = true }
[gears]
carriers = ["H"]
meshes = [["a", "g"], ["g", "b"], ["g2", "e"]]
fixed = ["b"]
planets = 3
[gears.input]
a = 1000.0
""", encoding="utf-8")
    r = plans_cli(["render", scene, "-o", tmp_path / "out"])
    assert r.returncode == 0, r.stderr
    warned = [w for w in r.stderr.splitlines() if w.startswith("warning:") and "assembly" in w]
    assert len(warned) == 1 and "carrier 'H'" in warned[0] and "unchecked" in warned[0]
    g = json.loads((tmp_path / "out" / "threek.json").read_text(encoding="utf-8"))["gears"]
    assert any("assembly" in w and "carrier 'H'" in w for w in g["warnings"])
    # Willis with H held, a → g (external) → b (internal) and a → g = g2 → e: exact from the teeth
    i_ab = Fraction(-20, 20) * Fraction(60, 20)
    i_ae = Fraction(-20, 20) * Fraction(58, 18)
    n_h = Fraction(1000) / (1 - i_ab)
    assert g["speeds"]["H"]["rpm_exact"] == str(n_h)
    n_e = n_h + (1000 - n_h) / i_ae
    assert g["speeds"]["e"]["rpm_exact"] == str(n_e)
    assert {tuple(w["central"]) for w in g["willis"]} == {("a", "b"), ("a", "e")}


def test_plans_api_counts_a_written_copy_like_planets_k():
    # K&G with planets = 1 and C written out, against planets = 2 with B alone: one planet set more
    # either way, q = 1, and the same speeds
    written = analyse_train(_train(_kg("A = -1.0", fixed=True)))
    text = _kg("A = -1.0", fixed=True, planets=2).replace('C = { teeth = 25, module = 2.0, on = "H" }\n', "")
    text = text.replace(', ["A", "C"], ["C", "D"]', "")
    spaced = analyse_train(_train(text))
    for a in (written, spaced):
        assert a.speeds.structure.redundant == 1 and a.speeds.structure.passive_planets == 1
        assert a.speeds.rpm["H"] == Fraction(-4, 13)
    assert plans.gears.planet_sets(written.speeds.structure, "H") == 2 == \
        plans.gears.planet_sets(spaced.speeds.structure, "H")

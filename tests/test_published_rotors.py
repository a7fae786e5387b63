"""Published rotor-balancing problems against [rotor] (issue 37), beyond Khurmi & Gupta's
Examples 21.1 and 21.2 and GATE 2019's problem, which tests/test_rotor.py already has.

Source: two worked examples of a FOSSEE Scilab Textbook Companion whose book the scripts do not
name (a companion of the Scilab 6.0.2 template: each script starts "//OS-version - Windows 10",
"//Scilab-version - 6.0.2"; its wording, "Resolving all the assumed forces horizontally",
"Since, H and V are both positive, therefore the resultant ... lies in the first quadrant", is
Khurmi's). They are cited by their ids in the public code index (``find_string`` /
``read_file``). Both are masses in one plane balanced by one mass (static balance): ΣH = Σ m r cos θ,
ΣV = Σ m r sin θ, the balancing m = √(ΣH² + ΣV²)/r at 180° + atan(ΣV/ΣH). Each printed answer
(printf %.2f: what the format prints of the script's own arithmetic, redone in Python, for the
scripts are stored without their output) is asserted within ±0.005, and plans is compared with the
script's closed form to 1e-13 relative (radii in mm are given to plans in m: the masses do not
change).

Khurmi & Gupta's ch. 21 examples with two balancing planes other than 21.2 (21.3–21.5: a mass, a
plane's place or the angles unknown) are not of the form [rotor] takes (known masses balanced in
two given planes); no companion script of them is in the index.

Two planes (and one more plane): the FOSSEE Python Textbook Companions (repository
FOSSEE/Python-Textbook-Companions; each notebook stores its code and the output it printed),
T. Bevan, *The Theory of Machines*, 3rd ed. (CBS, 2005), ch. 14 "Balancing",
The_Theory_of_Machines_by_T._Bevan/ch14.ipynb (blob 7b422dce, commit 2510d8e7), and B. K. Sarkar,
*Theory of Machines* (Tata McGraw-Hill, 2002), ch. 8 "Balancing of Rotating Masses",
Theory_Of_Machines_by__B._K._Sarkar/Chapter8_1.ipynb (blob 00deb110, commit 02f16477; shown at
https://tbc-python.fossee.in/convert-notebook/Theory_Of_Machines_by__B._K._Sarkar/Chapter8_1.ipynb)."""

from __future__ import annotations

import cmath
import json
import math

import pytest

from plans import render
from plans.dynamics.balancing import balance_rotor
from plans.scene import parse_scene


def _scene(masses: list[tuple[float, float, float]], radius: float, rpm: float | None = None) -> dict:
    """One plane: (mass kg, radius m, angle °) each, balanced at ``radius`` m."""
    rotor = {"masses": [{"mass": m, "radius": r, "angle": a} for m, r, a in masses],
             "balance": {"planes": [0.0], "radius": radius}}
    if rpm is not None:
        rotor["rpm"] = rpm
    return {"title": "Rotor", "rotor": rotor}


def _closed_form(masses: list[tuple[float, float, float]], radius: float) -> tuple[float, float]:
    """The scripts' way: ΣH, ΣV, m = R/r, θ = 180° + atan(ΣV/ΣH) (ΣH, ΣV > 0 in both problems)."""
    h = sum(m * r * math.cos(math.radians(a)) for m, r, a in masses)
    v = sum(m * r * math.sin(math.radians(a)) for m, r, a in masses)
    assert h > 0 and v > 0
    return math.hypot(h, v) / radius, 180.0 + math.degrees(math.atan(v / h))


@pytest.mark.parametrize("ident, masses, radius, printed", [
    # id 19276169926: masses 2, 4, 6, 8 kg at 1.2, 0.8, 0.4, 0.2 m, at 0°, 60°, 120°, 135°, the
    # balancing mass at 0.8 m (the shaft at 500 rpm, which the answer does not use). Printed:
    # "Magnitude of the balancing mass = 7.76 kg", "Angle, which the balancing mass makes with A
    # = 254.41 degrees".
    ("19276169926", [(2.0, 1.2, 0.0), (4.0, 0.8, 60.0), (6.0, 0.4, 120.0), (8.0, 0.2, 135.0)], 0.8, (7.76, 254.41)),
    # id 19203598764: bodies A, B, C of 10, 9, 16 kg at 100, 125, 50 mm, at 0°, 60°, 135°, the
    # balancing body D at 150 mm (100 rpm, not used). Printed: "Mass of the balancing body D =
    # 12.23 kg", "Angle, which the balancing body makes with A = 237.09 degres" (the script's own
    # note: the book's answers differ by its rounding).
    ("19203598764", [(10.0, 0.100, 0.0), (9.0, 0.125, 60.0), (16.0, 0.050, 135.0)], 0.150, (12.23, 237.09)),
])
def test_masses_in_one_plane(ident, masses, radius, printed):
    a = balance_rotor(parse_scene(_scene(masses, radius)).rotor)
    (b,) = a.balancing
    mass, angle = _closed_form(masses, radius)
    assert not a.dynamic
    assert b.mass == pytest.approx(mass, rel=1e-13) and b.angle == pytest.approx(angle, rel=1e-13)
    assert abs(b.mass - printed[0]) <= 0.005 and abs(b.angle - printed[1]) <= 0.005


def test_one_plane_report_with_the_scripts_speed():
    """id 19276169926 gives the shaft's speed, 500 rpm, which the problem does not use: with it the
    JSON reports the unbalanced force before balancing, ω²·|Σ m r| = ω²·(7.76 kg × 0.8 m) — the
    centrifugal force the balancing mass cancels — and no residual force after it."""
    masses = [(2.0, 1.2, 0.0), (4.0, 0.8, 60.0), (6.0, 0.4, 120.0), (8.0, 0.2, 135.0)]
    out = render(parse_scene(_scene(masses, 0.8, rpm=500.0)), stem="rotor")
    rep = json.loads(out.files["rotor.json"])["rotor"]
    omega = 500.0 * math.pi / 30.0
    mass, angle = _closed_form(masses, 0.8)
    assert rep["kind"] == "static" and rep["omega"] == pytest.approx(omega, rel=1e-15)
    assert rep["unbalanced"]["force"] == pytest.approx(omega ** 2 * mass * 0.8, rel=1e-13)
    (b,) = rep["balancing"]
    assert b["mass"] == pytest.approx(mass, rel=1e-13) and b["angle"] == pytest.approx(angle, rel=1e-13)
    assert rep["residual"]["force"] <= 1e-12 * rep["unbalanced"]["force"]


# --- two balancing planes ----------------------------------------------------------------------

IN = 0.0254   # m an inch: Bevan's data are in inches and pounds (the masses come out in pounds)


def _two_planes(masses: list[tuple[float, float, float, float]], planes: tuple[float, float],
                radii: tuple[float, float]) -> tuple[tuple[float, float], tuple[float, float]]:
    """The test's own two-plane balance of (mass, radius m, angle °, plane m) each: the couple
    about the first plane C = Σ m·r·e^{iθ}·(z − z₁) is closed by U₂ = −C/(z₂ − z₁) in the second, the
    force by U₁ = −(Σ m·r·e^{iθ} + U₂) in the first; (mass, angle ° in [0, 360)) of each."""
    vec = [cmath.rect(m * r, math.radians(a)) for m, r, a, _ in masses]
    couple = sum((v * (z - planes[0]) for v, (_, _, _, z) in zip(vec, masses)), 0j)
    u2 = -couple / (planes[1] - planes[0])
    u1 = -(sum(vec, 0j) + u2)
    return tuple((abs(u) / r, math.degrees(cmath.phase(u)) % 360.0) for u, r in ((u1, radii[0]), (u2, radii[1])))


def _rotor(masses: list[tuple[float, float, float, float]], planes: tuple[float, float],
           radii: tuple[float, float]) -> dict:
    rotor = {"masses": [{"mass": m, "radius": r, "angle": a, "plane": z} for m, r, a, z in masses],
             "balance": {"planes": list(planes), "radius": list(radii)}}
    return {"title": "Rotor", "rotor": rotor}


@pytest.mark.parametrize("case, side, printed", [("a", -10.0, (24, 144)), ("b", 10.0, (24, 96))])
def test_bevan_one_mass_balanced_in_two_planes(case, side, printed):
    """Bevan, ch. 14, Example 1 (p. 491): a 200 lb mass at 9 in, balanced by masses at 15 in in two
    planes 1 and M, d = 50 in apart, the mass l = 10 in from plane 1, (a) outside the two planes,
    (b) between them. The script (eqs. 14.2, 14.3): B_M = W·r·l/(d·b), B₁ = W·r·(d ± l)/(d·b) (its
    "ma = d+l", "mb = d-l": the mass's distance from plane M). Printed (%.f): "a) Bm= 24 lb ; B1=
    144 lb", "b) Bm= 24 lb ; B1= 96 lb" — exactly 24, 144, 96, so within ±0.5. Not printed, from the
    moments: (a) B_M on the mass's side (0°), B₁ opposite it (180°); (b) both opposite (180°).
    Lengths are given in m (× 0.0254): the masses, ratios of lengths, do not change."""
    masses = [(200.0, 9 * IN, 0.0, side * IN)]
    planes, radii = (0.0, 50 * IN), (15 * IN, 15 * IN)
    one, m_plane = balance_rotor(parse_scene(_rotor(masses, planes, radii)).rotor).balancing
    assert (one.plane, m_plane.plane) == planes
    assert abs(m_plane.mass - printed[0]) <= 0.5 and abs(one.mass - printed[1]) <= 0.5
    (b1, t1), (bm, tm) = _two_planes(masses, planes, radii)
    w_r, l, d, b = 200.0 * 9, 10.0, 50.0, 15.0            # Bevan's closed form, in his units
    assert bm == pytest.approx(w_r * l / (d * b), rel=1e-12)
    assert b1 == pytest.approx(w_r * (d + l if case == "a" else d - l) / (d * b), rel=1e-12)
    assert m_plane.mass == pytest.approx(bm, rel=1e-12) and one.mass == pytest.approx(b1, rel=1e-12)
    assert (round(m_plane.angle, 9), round(one.angle, 9)) == ((0.0 if case == "a" else 180.0), 180.0)
    assert (round(tm, 9), round(t1, 9)) == ((0.0 if case == "a" else 180.0), 180.0)


SARKAR_3 = [(200.0, 0.080, 0.0, 0.0), (300.0, 0.070, 45.0, 0.3), (400.0, 0.060, 115.0, 0.4),
            (200.0, 0.080, 235.0, 0.7)]


def test_sarkar_four_masses_two_planes_measured():
    """Sarkar, ch. 8, Illustration 3 (p. 223): masses A, B, C, D of 200, 300, 400, 200 kg at 80, 70,
    60, 80 mm, balanced in planes X and Y at 100 mm. The script gives only these and what it
    measured off the drawn polygons: "mY=7.3/.04" (the couple polygon's closing side 7.3 kg·m² over
    rY·lY = 0.1 × 0.4 m², so Y is 0.4 m from X, the reference plane), "mX=35./.1" (the force
    polygon's 35 kg·m), "thetaX=146" by measurement; printed: "mass of X= 350.0 kg", "mass of Y=
    182.5 kg", "angle with mA= 146.0 degrees". Masses, radii and 0.4 m are those of Khurmi & Gupta's
    Ex. 21.2 (tests/test_rotor.py), the same problem; the angles and planes, which the script does
    not state, are taken from there: A, B, C, D at 0°, 45°, 115°, 235° in planes 0, 0.3, 0.4, 0.7 m,
    X at 0.1 m, Y at 0.5 m. Exactly, the couple is 7.362 kg·m², the force 35.297 kg·m, X at 213.37°
    counter-clockwise from A, i.e. 146.63° from A the other way.

    Bounds, a drawing's: lengths measured off polygons drawn to scale, about 2 % (7.3 is 0.85 %
    and 35 0.84 % off); an angle read with a protractor to 1° off a drawing good to 1 % of its size
    (its direction within atan 0.01 = 0.57°), 1.5°."""
    planes, radii = (0.1, 0.5), (0.1, 0.1)
    a = balance_rotor(parse_scene(_rotor(SARKAR_3, planes, radii)).rotor)
    x, y = a.balancing
    assert a.dynamic and (x.plane, y.plane) == planes and a.reference_plane == 0.1
    assert abs(a.couple_closing) == pytest.approx(7.3, rel=0.02) and y.mass == pytest.approx(182.5, rel=0.02)
    assert abs(a.force_closing) == pytest.approx(35.0, rel=0.02) and x.mass == pytest.approx(350.0, rel=0.02)
    assert 360.0 - x.angle == pytest.approx(146.0, abs=1.5)
    (mx, tx), (my, ty) = _two_planes(SARKAR_3, planes, radii)
    assert (x.mass, x.angle) == pytest.approx((mx, tx), rel=1e-12)
    assert (y.mass, y.angle) == pytest.approx((my, ty), rel=1e-12)
    assert abs(a.couple_closing) == pytest.approx(my * 0.1 * 0.4, rel=1e-12)
    assert abs(a.force_closing) == pytest.approx(mx * 0.1, rel=1e-12)
    assert (round(mx, 2), round(tx, 2), round(my, 2), round(ty, 2)) == (352.97, 213.37, 184.06, 347.2)


def test_bevan_four_weights_in_one_plane():
    """Bevan, ch. 14, Example 2 (p. 491): weights of 200, 300, 240, 260 lb at 9, 7, 10, 12 in, the
    script resolving them at α = 45°, γ − β = 60° behind 180° and β = 75° past 180° (i.e. at 0°,
    45°, 120°, 255°), balanced at 24 in. Printed: "Balance weight required = 57.9 lb" (%.1f),
    "theta = 23.28 degrees" (%.2f: atan(V/H), the resultant's angle; the balance weight is opposite
    it, at 203.28°). Lengths in m as above."""
    masses = [(200.0, 9 * IN, 0.0), (300.0, 7 * IN, 45.0), (240.0, 10 * IN, 120.0), (260.0, 12 * IN, 255.0)]
    (b,) = balance_rotor(parse_scene(_scene(masses, 24 * IN)).rotor).balancing
    assert abs(b.mass - 57.9) <= 0.05 and abs((b.angle - 180.0) - 23.28) <= 0.005
    al, be, ga = math.radians(45.0), math.radians(75.0), math.radians(135.0)   # the script's own sums
    h = 200 * 9 + 300 * 7 * math.cos(al) - 240 * 10 * math.cos(ga - be) - 260 * 12 * math.cos(be)
    v = 300 * 7 * math.sin(al) + 240 * 10 * math.sin(ga - be) - 260 * 12 * math.sin(be)
    assert b.mass == pytest.approx(math.hypot(h, v) / 24, rel=1e-12)
    assert b.angle == pytest.approx(180.0 + math.degrees(math.atan(v / h)), rel=1e-12)

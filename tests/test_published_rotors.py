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
two given planes); no companion script of them is in the index."""

from __future__ import annotations

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

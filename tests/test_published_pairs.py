"""Published involute-pair problems against [gear_pair] (issue 34), beyond those in
tests/test_gear_pair_contract.py (the pinion and rack, the internal gear 18/72, the 20/40 pair at
2000 rpm are there and not repeated here).

Source: R. S. Khurmi & J. K. Gupta, *Theory of Machines* (S. Chand), ch. 12 "Toothed Wheels", as
the FOSSEE Scilab Textbook Companion of the book reproduces its worked examples (one script per
example: the given data, the book's formulas — KP, PL, the path of approach and recess; rA, RA,
the tip radii — and printf formats that print the book's answers). Each script is cited by its id
in the public code index (``find_string`` / ``read_file``). The example numbers are inferred from
the problem statements (the scripts do not carry them), so they are given as "ch. 12".

Each printed answer is written as the literal its format prints (the scripts are stored without
their output: the literal is what the format prints of the script's own arithmetic, redone in Python
in IEEE doubles as Scilab does it) and asserted within that format's rounding: %.1f ±0.05, %.2f
±0.005, %.3f ±0.0005, %d truncates (n ≤ x < n + 1). Each is also worked here in closed form the
book's way (KP = √(R_A² − R²cos²φ) − R sin φ, PL likewise with r, the arc KL/cos φ, the angle
arc/r) and plans' general formulas (from the line of action, with shifts) are compared with it to
1e-12 relative.

Examples of the chapter plans does not take, each refused in one line (asserted below, with the
reason worked independently): the pair 16/28 at 16° whose addenda put each tip on the other
wheel's interference point (the pinion's tip, 1.79 modules, is pointed), and the pair 30/50 with
the same rule (the pinion's addendum is 4.64 modules, beyond 2.5). the closing note of this stop lists them
with the companion's printed values."""

from __future__ import annotations

import json
import math

import pytest

from plans import render
from plans.errors import SceneError
from plans.scene import parse_scene

REL = 1e-12


def _report(table: dict) -> tuple[dict, tuple[str, ...]]:
    out = render(parse_scene({"gear_pair": table, "plans": {"draw": []}}), stem="pair")
    return json.loads(out.files["pair.json"])["gear_pair"], out.warnings


def _refusal(table: dict) -> str:
    with pytest.raises(SceneError) as info:
        render(parse_scene({"gear_pair": table, "plans": {"draw": []}}), stem="pair")
    return str(info.value)


def _paths(z1: int, z2: int, m: float, tip1: float, tip2: float, phi_deg: float) -> tuple[float, float]:
    """The book's path of approach KP (the wheel's tip) and of recess PL (the pinion's tip), mm:
    KP = √(R_A² − R²cos²φ) − R sin φ, PL = √(r_A² − r²cos²φ) − r sin φ, external pair."""
    phi = math.radians(phi_deg)
    r, big = m * z1 / 2, m * z2 / 2
    kp = math.sqrt((big + tip2) ** 2 - (big * math.cos(phi)) ** 2) - big * math.sin(phi)
    pl = math.sqrt((r + tip1) ** 2 - (r * math.cos(phi)) ** 2) - r * math.sin(phi)
    return kp, pl


def _inv(a: float) -> float:
    return math.tan(a) - a


def _tip_thickness(z: int, m: float, addendum_mm: float, phi_deg: float) -> float:
    """The tooth thickness on the tip circle of an unshifted wheel, mm: s_a = d_a(s/d + inv α − inv α_a),
    s = πm/2, cos α_a = d cos α / d_a."""
    alpha = math.radians(phi_deg)
    d = m * z
    da = d + 2 * addendum_mm
    return da * (math.pi * m / 2 / d + _inv(alpha) - _inv(math.acos(d * math.cos(alpha) / da)))


def test_khurmi_angle_turned_and_sliding_at_a_pitch_line_speed():
    """Ch. 12 (companion id 16234825959), the script's data: two gears of 20° pressure angle, the
    pinion of 20 teeth, gear ratio 2, module 5 mm, addendum one module, pitch line speed 1.2 m/s;
    find the angle turned through by the pinion while one pair of teeth is in mesh and the greatest
    velocity of sliding. Printed: "Angle turned through by pinion ... = 29.43 degrees"
    (%.2f), "Maximum velocity of sliding, vS = 455.3 mm/s" (%.1f). The pitch line speed fixes
    ω1 = v/r = 24 rad/s, n1 = 720/π rpm; the book's vS = (ω1 + ω2)·KP, the larger of the two paths."""
    n1 = 1.2 / 0.05 * 60 / (2 * math.pi)
    rep, warnings = _report({"z1": 20, "z2": 40, "module": 5.0, "n1": n1})
    kp, pl = _paths(20, 40, 5.0, 5.0, 5.0, 20.0)
    arc = (kp + pl) / math.cos(math.radians(20.0))
    assert rep["path_of_approach"] == pytest.approx(kp, rel=REL) and rep["path_of_recess"] == pytest.approx(pl, rel=REL)
    assert rep["angle_turned"][0] == pytest.approx(math.degrees(arc / 50.0), rel=REL)
    assert abs(rep["angle_turned"][0] - 29.43) <= 0.005
    w1 = 1.2e3 / 50.0
    v = rep["sliding_velocity"]
    assert v["engagement"] == pytest.approx((w1 + w1 / 2) * kp / 1e3, rel=REL)
    assert max(v.values()) == v["engagement"] and abs(1e3 * v["engagement"] - 455.3) <= 0.05
    assert warnings == ()


def test_khurmi_path_arc_and_contact_ratio_with_an_addendum_in_mm():
    """Ch. 12 (companion id 16043684919; Fig. 12.11), the script's data: a pinion of 30 teeth
    drives a gear of 80, involute, 20°, module 12 mm, addendum 10 mm; find the path of contact, the
    arc of contact and the contact ratio. Printed: "KL = 52.3
    mm" (%.1f), "Length of arc of contact = 55.61 mm" (%.2f). The addendum of 10 mm is 10/12 of a
    module: ``addendum = 10/12``. The contact ratio, arc/p = 1.475 (the book: "1.5, say 2"), is not
    compared with the script's line: it divides by ``pc`` where the script defined ``Pc`` (Scilab
    names are case-sensitive), so that line prints nothing reliable."""
    rep, warnings = _report({"z1": 30, "z2": 80, "module": 12.0, "addendum": 10.0 / 12.0})
    kp, pl = _paths(30, 80, 12.0, 10.0, 10.0, 20.0)
    arc = (kp + pl) / math.cos(math.radians(20.0))
    assert rep["path_of_contact"] == pytest.approx(kp + pl, rel=REL) and abs(rep["path_of_contact"] - 52.3) <= 0.05
    assert rep["arc_of_contact"] == pytest.approx(arc, rel=REL) and abs(rep["arc_of_contact"] - 55.61) <= 0.005
    assert rep["contact_ratio"] == pytest.approx(arc / (math.pi * 12.0), rel=REL)
    assert rep["da"] == pytest.approx([360.0 + 20.0, 960.0 + 20.0], rel=REL) and warnings == ()


def test_khurmi_pairs_in_contact_angles_and_sliding_to_rolling():
    """Ch. 12 (companion id 16482490161; Fig. 12.11), the script's data: 17 and 49 involute
    teeth, module 6 mm, 20°, addendum one module; find the number of pairs of teeth in contact, the
    angles turned through by the pinion and the wheel while one pair is in contact, and the ratio
    of sliding to rolling as the tip of the larger wheel's tooth begins and ends contact. Printed:
    "Number of pairs of teeth in contact = 2" (%d of n + 1, n = arc/p), "Angle turned through by the
    pinion = 34.6 degrees" (%.1f), "... by the gear wheel = 11 degrees" (%d: 11.997 truncated; the
    book rounds it to 12), the ratios "0.41" (%.2f) and "0.354" (%.3f) — (1 + t/T)·KP/r and
    (1 + t/T)·PL/r, i.e. the sliding velocity over the pitch line velocity ω1·r, here from the
    JSON's sliding velocities at any n1. The pinion of 17 teeth is undercut by a hair (x_min =
    0.0057): plans warns, as the book does not."""
    n1 = 100.0
    rep, warnings = _report({"z1": 17, "z2": 49, "module": 6.0, "n1": n1})
    kp, pl = _paths(17, 49, 6.0, 6.0, 6.0, 20.0)
    arc = (kp + pl) / math.cos(math.radians(20.0))
    assert rep["arc_of_contact"] == pytest.approx(arc, rel=REL)
    assert 1.0 <= rep["contact_ratio"] < 2.0 and int(rep["contact_ratio"] + 1) == 2
    pinion, wheel = rep["angle_turned"]
    assert pinion == pytest.approx(math.degrees(arc / 51.0), rel=REL) and abs(pinion - 34.6) <= 0.05
    assert wheel == pytest.approx(math.degrees(arc / 147.0), rel=REL) and 11 <= wheel < 12
    pitch_line = 2 * math.pi * n1 / 60 * 51.0 / 1e3
    approach, recess = (rep["sliding_velocity"][k] / pitch_line for k in ("engagement", "disengagement"))
    assert approach == pytest.approx((1 + 17 / 49) * kp / 51.0, rel=REL) and abs(approach - 0.41) <= 0.005
    assert recess == pytest.approx((1 + 17 / 49) * pl / 51.0, rel=REL) and abs(recess - 0.354) <= 0.0005
    assert len(warnings) == 1 and "undercut" in warnings[0]


def test_khurmi_addendum_for_an_arc_of_contact_of_one_and_three_quarter_pitches():
    """Ch. 12 (companion id 16237618266), the script's data: two equal wheels of 40 teeth, 20°,
    module 6 mm; find the addendum of each so that the arc of contact is 1.75 circular pitches. The
    book: path = 1.75·πm·cos φ, each half of it
    from one tip, R_A = √(R²cos²φ + (path/2 + R sin φ)²). Printed: "Addendum of the wheel = 6.14 mm"
    (%.2f). plans, given that addendum (in modules), finds the contact ratio 1.75 and the arc 1.75p
    (to 1e-12: the inverse problem closes exactly)."""
    m, phi = 6.0, math.radians(20.0)
    big = 120.0
    path = 1.75 * math.pi * m * math.cos(phi)
    addendum = math.hypot(big * math.cos(phi), path / 2 + big * math.sin(phi)) - big
    assert abs(addendum - 6.14) <= 0.005
    rep, warnings = _report({"z1": 40, "z2": 40, "module": m, "addendum": addendum / m})
    assert rep["contact_ratio"] == pytest.approx(1.75, rel=REL)
    assert rep["arc_of_contact"] == pytest.approx(1.75 * math.pi * m, rel=REL)
    assert rep["path_of_approach"] == pytest.approx(path / 2, rel=REL)
    assert rep["path_of_recess"] == pytest.approx(path / 2, rel=REL)
    assert warnings == ()


def test_khurmi_addenda_to_the_interference_points_are_refused():
    """Two examples of ch. 12 set each wheel's addendum so that its tip reaches the other wheel's
    interference point, A_P = (mt/2)[√(1 + (T/t)(T/t + 2) sin²φ) − 1] and A_W the same with t and T
    exchanged (the path of contact is then all of N1N2, (r + R) sin φ). plans takes addenda per
    wheel but refuses both pairs, for their pinions' tips:

    * companion id 16598198291: φ = 16°, m = 6, t = 16, T = 28 (G = 1.75), 240 rpm: A_P = 10.76 mm
      (1.79 modules), A_W = 4.56 mm; printed "Addendum on pinion = 10.76 mm", "Addendum on wheel =
      4.56 mm", "KL = 38.39 mm", "1044" and "471 mm/s". The script adds A_P to the *wheel's* radius
      (RA = R + addendump), so its path and sliding velocities are not the book's; with the addenda
      on their own wheels the path is (r + R) sin φ = 36.38 mm. The pinion's tip is pointed
      (s_a = −1.78 mm worked below): refused at [gear_pair.addendum].
    * companion id 16565033126: φ = 20°, m = 4, t = 30, T = 50, 1000 rpm: A_P = 18.572 mm, 4.64
      modules; printed "3.438 m/s", "5.731 m/s", "Contact ratio = 5". Refused: beyond the 2.5
      modules an addendum may have (and pointed as well)."""
    s2 = math.sin(math.radians(16.0)) ** 2
    a_p = 6.0 * 16 / 2 * (math.sqrt(1 + 1.75 * 3.75 * s2) - 1)
    a_w = 6.0 * 28 / 2 * (math.sqrt(1 + (1 / 1.75) * (1 / 1.75 + 2) * s2) - 1)
    assert (round(a_p, 2), round(a_w, 2)) == (10.76, 4.56)
    assert _tip_thickness(16, 6.0, a_p, 16.0) == pytest.approx(-1.782, abs=5e-4)
    e = _refusal({"z1": 16, "z2": 28, "module": 6.0, "pressure_angle": 16.0, "addendum": [a_p / 6.0, a_w / 6.0],
                  "n1": 240.0})
    assert e.startswith("[gear_pair.addendum]: the tip of wheel 1") and "pointed" in e and "-1.782" in e
    s2 = math.sin(math.radians(20.0)) ** 2
    a_p = 4.0 * 30 / 2 * (math.sqrt(1 + (5 / 3) * (5 / 3 + 2) * s2) - 1)
    a_w = 4.0 * 50 / 2 * (math.sqrt(1 + 0.6 * 2.6 * s2) - 1)
    assert (round(a_p, 3), round(a_w, 3)) == (18.572, 8.742)
    assert _tip_thickness(30, 4.0, a_p, 20.0) < 0.0
    e = _refusal({"z1": 30, "z2": 50, "module": 4.0, "addendum": [a_p / 4.0, a_w / 4.0], "n1": 1000.0})
    assert e.startswith("[gear_pair.addendum]") and "2.5" in e

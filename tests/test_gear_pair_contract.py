"""[gear_pair] grows (issue 34): an internal pair (``internal``), addenda per wheel (``addendum =
[ha1, ha2]``), a pinion with a rack (``rack``) and the pinion's speed (``n1``); the paths of
approach and recess, the arc of contact, the angles turned and the sliding velocities in the JSON;
the internal pair's interference in [gear_pair] and in gear trains; every refusal one line naming
its key; the old report's keys and values unchanged.

Published problems: R.S. Khurmi & J.K. Gupta, Theory of Machines (S. Chand), ch. 12 "Toothed
Wheels", as the FOSSEE Scilab Textbook Companion of the book reproduces them (FOSSEE/Scilab-TBC-
Uploads: one script per example, its given data and the book's formulas, each answer printed with
a format: %.2f, %.3f, %d). The data here are the companion's; each printed answer is written as the
literal the companion's format prints, and asserted within that format's rounding (%.2f: ±0.005;
%d truncates: [n, n + 1)). Each is also worked in this file in closed form, the book's way, and
compared with plans' general formulas (with shifts, from the line of action) to 1e-12 relative.
Uicker, Pennock & Shigley's problem states its own contact ratio of 1.6, and the handbooks' shifted
internal pair is checked against SDP/SI's equations."""

from __future__ import annotations

import json
import math
from pathlib import Path

import mpmath
import pytest

from conftest import refused_line
from plans import render
from plans.errors import SceneError, StructureError
from plans.gears import analyse_train
from plans.gears.contact import (internal_pair, involute_interference, pair_tip_interference,
                                 standard_tip_interference)
from plans.gears.involute import gear_pair, inv
from plans.scene import parse_scene, read_scene

ROOT = Path(__file__).resolve().parent.parent
REL = 1e-12


def _report(table: dict, draw: list[str] | None = None) -> tuple[dict, tuple[str, ...], list[str]]:
    data = {"gear_pair": table}
    if draw is not None:
        data["plans"] = {"draw": draw}
    out = render(parse_scene(data), stem="pair")
    return json.loads(out.files["pair.json"])["gear_pair"], out.warnings, sorted(out.files)


def _refusal(table: dict) -> SceneError:
    with pytest.raises(SceneError) as info:
        render(parse_scene({"gear_pair": table}), stem="pair")
    return info.value


# --- a pinion with a rack ----------------------------------------------------------------------

def test_khurmi_pinion_and_rack():
    """R.S. Khurmi & J.K. Gupta, Theory of Machines (S. Chand), ch. 12 "Toothed Wheels", worked
    example on the rack: "A pinion of 20 involute teeth and 125 mm pitch circle diameter drives a
    rack. The addendum of both pinion and rack is 6.25 mm. What is the least pressure angle which
    can be used to avoid interference? With this pressure angle, find the length of the arc of
    contact and the minimum number of teeth in contact at a time." Worked the book's way:
    the rack's tip line through N1, addendum = r·sin²φ; approach = addendum/sin φ; recess =
    √(r_A² − r²cos²φ) − r·sin φ; arc = (approach + recess)/cos φ; pairs in contact = arc/p."""
    r, add, m = 62.5, 6.25, 125.0 / 20
    phi = math.asin(math.sqrt(add / r))
    assert round(math.degrees(phi), 2) == 18.43
    assert abs(math.degrees(phi) - 18.435) <= 0.0005          # printed: "phi = 18.435 degrees" (%.3f)
    approach = add / math.sin(phi)
    recess = math.sqrt((r + add) ** 2 - (r * math.cos(phi)) ** 2) - r * math.sin(phi)
    arc = (approach + recess) / math.cos(phi)
    pairs = arc / (math.pi * m)
    n1 = 100.0
    rep, warnings, files = _report({"z1": 20, "module": m, "rack": True, "pressure_angle": math.degrees(phi),
                                    "n1": n1})
    assert rep["kind"] == "rack" and rep["z"] == [20, None]
    for key, value in (("path_of_approach", approach), ("path_of_recess", recess),
                       ("path_of_contact", approach + recess), ("arc_of_contact", arc), ("contact_ratio", pairs)):
        assert rep[key] == pytest.approx(value, rel=REL)
        assert round(rep[key], 2) == round(value, 2)            # the book prints 0.01 mm
    assert 1.0 < rep["contact_ratio"] < 2.0                     # one pair always, two at times
    assert abs(rep["arc_of_contact"] - 36.68) <= 0.005          # printed: "Length of arc of contact = 36.68 mm"
    assert rep["angle_turned"][0] == pytest.approx(math.degrees(arc / r), rel=REL)
    assert rep["angle_turned"][1] is None and rep["rack_travel"] == pytest.approx(arc, rel=REL)
    w1 = 2 * math.pi * n1 / 60
    assert rep["sliding_velocity"]["engagement"] == pytest.approx(w1 * approach / 1000, rel=REL)
    assert rep["sliding_velocity"]["disengagement"] == pytest.approx(w1 * recess / 1000, rel=REL)
    # what a rack has not is null: its teeth, diameters, the line N1N2 ending at infinity
    assert rep["da"][1] is None and rep["line_of_action"] is None and rep["x_min"][1] is None
    assert rep["centre_distance"] == pytest.approx(r, rel=REL) and rep["working_pressure_angle"] == pytest.approx(
        math.degrees(phi), rel=REL)
    assert files == ["pair-cutting.svg", "pair-meshing.svg", "pair.json"]
    assert not any("not drawn" in w for w in warnings)
    # the book's angle rounded down to 18.43° puts the rack's tip line just past N1: refused
    e = _refusal({"z1": 20, "module": m, "rack": True, "pressure_angle": 18.43})
    assert str(e).startswith("[gear_pair]: interference: the tip line of the rack") and "\n" not in str(e)


# --- addenda per wheel ---------------------------------------------------------------------------

def test_uicker_long_and_short_addenda():
    """J.J. Uicker, G.R. Pennock & J.E. Shigley, Theory of Machines and Mechanisms (Oxford), ch.
    "Spur Gears", end-of-chapter problem (long-and-short addenda; its number differs by edition):
    "A 12-tooth pinion with a diametral pitch of 2 teeth/in and φ = 20° is to mesh with a 60-tooth
    gear at a center distance of 18 in. Calculate the maximum addendum of the gear teeth if there
    is to be no interference. Then calculate the addendum of the pinion which will give a contact
    ratio of 1.6 if the maximum addendum of the gear is used." The gear's tip circle through N1:
    R_A = √((R cos φ)² + ((r + R) sin φ)²); the path 1.6·p·cos φ, of which the approach is r·sin φ;
    the pinion's tip r_A = √((r cos φ)² + (r sin φ + recess)²). The contact ratio 1.6 is the
    problem's own number."""
    phi, m = math.radians(20.0), 25.4 / 2                        # P = 2 teeth/in: m = 12.7 mm
    r, big = 12 * m / 2, 60 * m / 2
    assert r + big == pytest.approx(18 * 25.4, rel=REL)          # the problem's 18 in
    tip2 = math.hypot(big * math.cos(phi), (r + big) * math.sin(phi))
    path = 1.6 * math.pi * m * math.cos(phi)
    recess = path - r * math.sin(phi)
    tip1 = math.hypot(r * math.cos(phi), r * math.sin(phi) + recess)
    ha = [(tip1 - r) / m, (tip2 - big) / m]
    assert [round((t - c) / 25.4, 3) for t, c in ((tip1, r), (tip2, big))] == [0.678, 0.381]   # in inches
    rep, warnings, files = _report({"z1": 12, "z2": 60, "module": m, "addendum": ha})
    assert files == ["pair-cutting.svg", "pair-meshing.svg", "pair.json"]
    assert rep["addendum"] == pytest.approx(ha, rel=REL)
    assert rep["contact_ratio"] == pytest.approx(1.6, rel=REL)
    assert rep["path_of_approach"] == pytest.approx(r * math.sin(phi), rel=REL)   # the gear's tip reaches N1
    assert rep["path_of_recess"] == pytest.approx(recess, rel=REL)
    assert rep["da"] == pytest.approx([2 * tip1, 2 * tip2], rel=REL)
    assert any("thin" in w for w in warnings) and any("undercut" in w for w in warnings)


def test_unequal_addenda_whose_sum_is_not_two_are_drawn():
    """ha = [1.0, 0.8] (sum 1.8): the tips d + 2·ha_i·m, the roots cut by one rack of the larger
    addendum (d − 2(1 + 0.25)m), the paths from each tip, and both sheets drawn."""
    m, alpha = 4.0, math.radians(20.0)
    rep, _, files = _report({"z1": 20, "z2": 40, "module": m, "addendum": [1.0, 0.8]})
    assert rep["da"] == pytest.approx([80.0 + 8.0, 160.0 + 6.4], rel=REL)
    assert rep["df"] == pytest.approx([80.0 - 10.0, 160.0 - 10.0], rel=REL)
    r, big = 40.0, 80.0
    approach = math.sqrt(83.2 ** 2 - (big * math.cos(alpha)) ** 2) - big * math.sin(alpha)
    recess = math.sqrt(44.0 ** 2 - (r * math.cos(alpha)) ** 2) - r * math.sin(alpha)
    assert rep["path_of_approach"] == pytest.approx(approach, rel=REL)
    assert rep["path_of_recess"] == pytest.approx(recess, rel=REL)
    assert files == ["pair-cutting.svg", "pair-meshing.svg", "pair.json"]


# --- the internal pair -----------------------------------------------------------------------------

def _khurmi_internal_path(r: float, big: float, tip1: float, tip2: float, phi: float) -> float:
    """The textbook's path of contact of an internal pair: √(r_A² − r²cos²φ) − √(R_A² − R²cos²φ)
    + (R − r)·sin φ (Khurmi & Gupta, ch. 12, "internal gears")."""
    return (math.sqrt(tip1 ** 2 - (r * math.cos(phi)) ** 2) - math.sqrt(tip2 ** 2 - (big * math.cos(phi)) ** 2)
            + (big - r) * math.sin(phi))


def test_khurmi_internal_gear_with_addenda_in_mm():
    """Khurmi & Gupta, Theory of Machines, ch. 12 "Toothed Wheels", worked example (the companion's
    data): "A pinion having 18 teeth engages with an internal gear having 72 teeth. If the gear teeth
    have involute profile with 20° pressure angle, module of 4 mm and the addenda on pinion and gear
    are 8.5 mm and 3.5 mm respectively, find the length of path of contact." Printed: "KL = 28.04 mm"
    (%.2f). Unequal addenda given per wheel (2.125·m and 0.875·m, their sum 3m: no shift gives
    them). Worked the book's way (:func:`_khurmi_internal_path`). plans computes the same path — and
    refuses the pair in a scene: the pinion's tip of 8.5 mm on a 4 mm module is pointed (s_a < 0),
    which the book does not look at."""
    phi, m = math.radians(20.0), 4.0
    path = _khurmi_internal_path(36.0, 144.0, 36.0 + 8.5, 144.0 - 3.5, phi)
    p = internal_pair(18, 72, m, addenda=(8.5 / m, 3.5 / m))
    assert p.active == pytest.approx(path, rel=REL) and abs(p.active - 28.04) <= 0.005
    assert p.approach + p.recess == pytest.approx(path, rel=REL)
    assert p.approach == pytest.approx(144.0 * math.sin(phi) - math.sqrt(140.5 ** 2 - (144.0 * math.cos(phi)) ** 2),
                                       rel=REL)                       # the companion's KP
    assert p.a_w == pytest.approx(m * (72 - 18) / 2, rel=REL)
    assert p.sa[0] < 0.0
    e = _refusal({"z1": 18, "z2": 72, "module": m, "internal": True, "addendum": [8.5 / m, 3.5 / m]})
    assert str(e).startswith("[gear_pair.addendum]: the tip of wheel 1") and "pointed" in str(e)


def test_standard_internal_pair_report():
    """A standard internal pair 20/80, m = 5, n1 = 1000 rpm, against the closed forms: the ring's
    tip inside its pitch circle, its root outside, a = m(z2 − z1)/2, the paths, the contact ratio
    by KHK's form [z1(tan α_a1 − tan α_w) − z2(tan α_a2 − tan α_w)]/2π, the angles turned, the
    specific sliding and the sliding velocities (ω1 − ω2)·path (both wheels turn one way)."""
    m, alpha, n1 = 5.0, math.radians(20.0), 1000.0
    rep, warnings, files = _report({"z1": 20, "z2": 80, "module": m, "internal": True, "n1": n1})
    r, big = 50.0, 200.0
    assert rep["kind"] == "internal" and rep["centre_distance"] == pytest.approx(150.0, rel=REL)
    assert rep["da"] == pytest.approx([110.0, 390.0], rel=REL) and rep["df"] == pytest.approx([87.5, 412.5], rel=REL)
    path = _khurmi_internal_path(r, big, r + m, big - m, alpha)
    approach = big * math.sin(alpha) - math.sqrt((big - m) ** 2 - (big * math.cos(alpha)) ** 2)
    recess = math.sqrt((r + m) ** 2 - (r * math.cos(alpha)) ** 2) - r * math.sin(alpha)
    assert rep["path_of_contact"] == pytest.approx(path, rel=REL) == rep["active_length"]
    assert rep["path_of_approach"] == pytest.approx(approach, rel=REL)
    assert rep["path_of_recess"] == pytest.approx(recess, rel=REL)
    ta = [math.tan(math.acos(db / da)) for db, da in zip(rep["db"], rep["da"])]
    khk = (20 * (ta[0] - math.tan(alpha)) - 80 * (ta[1] - math.tan(alpha))) / (2 * math.pi)
    assert rep["contact_ratio"] == pytest.approx(khk, rel=1e-11)
    assert rep["arc_of_contact"] == pytest.approx(path / math.cos(alpha), rel=REL)
    assert rep["angle_turned"] == pytest.approx([math.degrees(path / (r * math.cos(alpha))),
                                                 math.degrees(path / (big * math.cos(alpha)))], rel=REL)
    w1 = 2 * math.pi * n1 / 60
    w2 = w1 * 20 / 80
    assert rep["sliding_velocity"]["engagement"] == pytest.approx((w1 - w2) * approach / 1000, rel=REL)
    assert rep["sliding_velocity"]["disengagement"] == pytest.approx((w1 - w2) * recess / 1000, rel=REL)
    # specific sliding from the profiles' speeds ω·ρ along the line (ρ from N1 and N2, one side)
    n1n2 = 150.0 * math.sin(alpha)
    g2 = math.sqrt((big - m) ** 2 - (big * math.cos(alpha)) ** 2)
    g1 = math.sqrt((r + m) ** 2 - (r * math.cos(alpha)) ** 2)
    s = rep["specific_sliding"]
    assert s["wheel1_at_B2"] == pytest.approx((w1 * (g2 - n1n2) - w2 * g2) / (w1 * (g2 - n1n2)), rel=1e-11)
    assert s["wheel2_at_B1"] == pytest.approx((w2 * (g1 + n1n2) - w1 * g1) / (w2 * (g1 + n1n2)), rel=1e-11)
    assert rep["x_min"][1] is None and rep["undercut"] == [False, False]
    assert files == ["pair-cutting.svg", "pair-meshing.svg", "pair.json"]
    assert not any("not drawn" in w for w in warnings)


def test_shifted_internal_pair_of_the_gear_handbooks():
    """SDP/SI, Elements of Metric Gear Technology, §5.1, Table 5-1, and KHK, Gear Technical
    Reference, "internal gears": the profile-shifted internal pair m = 3, α = 20°, z = 16/24,
    x = 0/+0.516. Worked here from the tables' own formulas, not their printed numbers:
    d_a1 = d1 + 2(1 + x1)m, d_a2 = d2 − 2(1 − x2)m, d_f = d_a ∓ 2·2.25·m; inv α_w = 2 tan α
    (x2 − x1)/(z2 − z1) + inv α solved by mpmath; a_w from SDP Eq. (5-1), cos α_w = (d_b2 − d_b1)/2a_w.
    Its 8 teeth of difference pass both interference conditions thanks to x2 (the standard 16/24
    fails both)."""
    m, alpha = 3.0, math.radians(20.0)
    rep, _, _ = _report({"z1": 16, "z2": 24, "module": m, "internal": True, "x1": 0.0, "x2": 0.516})
    assert [round(v, 3) for v in rep["da"]] == [54.000, 69.096]
    assert [54.000, 69.096] == [16 * m + 2 * m, round(24 * m - 2 * (1 - 0.516) * m, 3)]
    assert [round(v, 3) for v in rep["df"]] == [40.500, 82.596]
    mpmath.mp.dps = 40
    target = inv(alpha) + 2 * math.tan(alpha) * 0.516 / 8
    alpha_w = float(mpmath.findroot(lambda a: mpmath.tan(a) - a - mpmath.mpf(target), mpmath.mpf(0.5)))
    assert math.radians(rep["working_pressure_angle"]) == pytest.approx(alpha_w, abs=1e-14)
    db = rep["db"]
    assert math.cos(alpha_w) == pytest.approx((db[1] - db[0]) / (2 * rep["centre_distance"]), rel=REL)
    assert rep["y"] == pytest.approx((rep["centre_distance"] - 12.0) / m, rel=REL)
    p = internal_pair(16, 24, m, x2=0.516)
    assert involute_interference(p) > 0 and pair_tip_interference(p) > 0
    q = internal_pair(16, 24, m)
    assert involute_interference(q) < 0 and pair_tip_interference(q) < 0


def _tip_penetration(z1: int, z2: int, steps: int = 1500) -> float:
    """How far (rad, about the ring's centre) the tip land of a standard pinion (α = 20°, ha* = 1,
    x = 0) enters the ring's teeth over three pinion pitches of rolling, simulated: the pinion's
    pitch circle rolls inside the ring's (ring held, carrier angle ψ, the pinion turning
    −(z2 − z1)/z1·ψ), and each tip point between the ring's tip and root circles is compared with
    the half-width of the ring's tooth space there, π/2z2 + inv α − inv α_r. 0: never inside."""
    alpha, m = math.radians(20.0), 1.0
    r1, r2 = z1 * m / 2, z2 * m / 2
    a, ra1, ra2, rf2 = r2 - r1, r1 + m, r2 - m, r2 + 1.25 * m
    rb2 = r2 * math.cos(alpha)
    beta = math.pi / (2 * z1) + inv(alpha) - inv(math.acos(r1 * math.cos(alpha) / ra1))
    pitch2 = 2 * math.pi / z2
    worst = 0.0
    for i in range(-steps, steps + 1):
        psi = 3 * i / steps * 2 * math.pi / z1
        turn = -(z2 - z1) / z1 * psi
        for k in range(-2, 3):
            for f in (-1.0, -0.5, 0.0, 0.5, 1.0):
                t = turn + 2 * math.pi * k / z1 + f * beta
                x, y = a * math.cos(psi) + ra1 * math.cos(t), a * math.sin(psi) + ra1 * math.sin(t)
                rho = math.hypot(x, y)
                if ra2 < rho < rf2:
                    ang = (math.atan2(y, x) + pitch2 / 2) % pitch2 - pitch2 / 2
                    half = math.pi / (2 * z2) + inv(alpha) - inv(math.acos(min(rb2 / rho, 1.0)))
                    worst = max(worst, abs(ang) - half)
    return worst


@pytest.mark.parametrize("z1, z2", [(30, 37), (30, 38), (30, 39), (25, 33), (25, 34)])
def test_tip_interference_agrees_with_a_simulation(z1, z2):
    """SDP/SI Eq. (5-6) says interference exactly where the simulated tip enters the ring's teeth,
    and by about as much (the formula's margin is an angle about the ring's centre too, taken at
    the tip circles' crossing: within half of it of the deepest entry simulated)."""
    margin = standard_tip_interference(z1, z2)
    inside = _tip_penetration(z1, z2)
    if margin < 0:
        assert 0.5 * -margin < inside < 1.5 * -margin
    else:
        assert inside == 0.0


def test_involute_interference_is_the_handbooks_condition():
    """g2 ≥ N1N2 is SDP/SI Eq. (5-4), z1/z2 ≥ 1 − tan α_a2/tan α_w, over shifted and standard pairs;
    for standard teeth the smallest ring for an 18- and a 20-tooth pinion is 161 and 64 teeth."""
    for z1, z2, x1, x2 in [(18, 72, 0, 0), (20, 63, 0, 0), (20, 62, 0, 0), (16, 24, 0, 0.516), (30, 40, 0.2, 0.5),
                           (25, 100, -0.2, 0.1), (12, 50, 0.4, 0.9)]:
        p = internal_pair(z1, z2, 2.0, x1=x1, x2=x2)
        eq54 = z1 / z2 - (1 - math.tan(math.acos(p.db[1] / p.da[1])) / math.tan(p.alpha_w))
        assert (involute_interference(p) >= 0) == (eq54 >= 0)
    # standard teeth (m = 1): (z2 − 2)² ≥ (z2·cos α)² + ((z2 − z1)·sin α)²,
    # i.e. z2 ≥ (z1²s − 4)/(2·z1·s − 4)
    # with s = sin²α, where 2·z1·s > 4 (z1 ≥ 18); below, no ring is free of it
    s = math.sin(math.radians(20.0)) ** 2
    for z1 in (18, 20, 27, 40):
        first = next(z2 for z2 in range(z1 + 1, 400) if involute_interference(internal_pair(z1, z2, 1.0)) >= 0)
        assert first == max(z1 + 1, math.ceil((z1 * z1 * s - 4) / (2 * z1 * s - 4)))
    assert [first for z1 in (18, 20) for first in [math.ceil((z1 * z1 * s - 4) / (2 * z1 * s - 4))]] == [161, 64]
    assert all(involute_interference(internal_pair(17, z2, 1.0)) < 0 for z2 in range(26, 400))


# --- the pinion's speed on an external pair ---------------------------------------------------------

def test_khurmi_sliding_velocities_of_an_external_pair():
    """Khurmi & Gupta, Theory of Machines, ch. 12, worked example: "A pair of gears, having 40 and
    20 teeth respectively, are rotating in mesh, the speed of the smaller being 2000 r.p.m.
    Determine the velocity of sliding between the gear teeth faces at the point of engagement, at
    the pitch point, and at the point of disengagement if the smaller gear is the driver. Assume
    that the gear teeth are 20° involute form, addendum length is 5 mm and the module is 5 mm.
    Also find the angle through which the pinion turns while any pair of teeth are in contact."
    The book's way: v = (ω1 + ω2)·path (0 at the pitch point), the angle = arc/r."""
    phi = math.radians(20.0)
    r, big = 50.0, 100.0
    approach = math.sqrt(105.0 ** 2 - (big * math.cos(phi)) ** 2) - big * math.sin(phi)
    recess = math.sqrt(55.0 ** 2 - (r * math.cos(phi)) ** 2) - r * math.sin(phi)
    w1 = 2000 * 2 * math.pi / 60
    w = w1 + w1 / 2
    rep, _, _ = _report({"z1": 20, "z2": 40, "module": 5.0, "n1": 2000.0}, draw=[])
    v = rep["sliding_velocity"]
    assert v["engagement"] == pytest.approx(w * approach / 1000, rel=REL) and round(v["engagement"], 2) == 3.97
    assert v["disengagement"] == pytest.approx(w * recess / 1000, rel=REL) and round(v["disengagement"], 2) == 3.61
    angle = math.degrees((approach + recess) / math.cos(phi) / r)
    assert rep["angle_turned"][0] == pytest.approx(angle, rel=REL)
    assert round(rep["angle_turned"][0], 2) == round(angle, 2)
    # printed (the companion's %d of mm/s truncates, %.2f rounds): "vSK = 3972 mm/s", "vsL = 3609 mm/s",
    # "Angle through which the pinion turns = 29.43 degrees"
    assert 3972 <= 1000 * v["engagement"] < 3973 and 3609 <= 1000 * v["disengagement"] < 3610
    assert abs(rep["angle_turned"][0] - 29.43) <= 0.005
    assert rep["n1"] == 2000.0 and rep["kind"] == "external" and "rack_travel" not in rep
    # without n1, no sliding velocity
    rep, _, _ = _report({"z1": 20, "z2": 40, "module": 5.0}, draw=[])
    assert "sliding_velocity" not in rep and "n1" not in rep


# --- refusals --------------------------------------------------------------------------------------

BASE = {"z1": 20, "z2": 40, "module": 2.0}
RING = {"z1": 20, "z2": 80, "module": 2.0, "internal": True}
RACK = {"z1": 20, "module": 2.0, "rack": True}


@pytest.mark.parametrize("table, key, words", [
    ({**BASE, "internal": "yes"}, "internal", "internal is true"),
    ({**BASE, "internal": 1}, "internal", "internal is true"),
    ({**RACK, "rack": "true"}, "rack", "rack is true"),
    ({**RING, "rack": True}, "rack", "ring gear or a rack, not both"),
    ({"z1": 20, "rack": True, "mesh": ["a", "b"]}, "rack", "remove rack or mesh"),
    ({"internal": True, "mesh": ["a", "b"]}, "internal", "remove internal"),
    ({**RACK, "z2": 40}, "z2", "a rack has no teeth count z2"),
    ({**RACK, "x1": 0.1, "x2": 0.1}, "x2", "a rack is not shifted"),
    ({"module": 2.0, "rack": True}, "z1", "z1 is missing"),
    ({"z1": 20, "rack": True}, "module", "module is missing"),
    ({**RING, "z2": 20}, "z2", "more teeth than the pinion"),
    ({**RING, "z2": 12}, "z2", "more teeth than the pinion"),
    ({**RING, "shift": "no_undercut"}, "shift", "give x1, x2 for an internal pair"),
    ({**RING, "shift": "balanced"}, "shift", "give x1, x2 for an internal pair"),
    ({**RACK, "shift": "balanced"}, "shift", "give x1 for a rack"),
    ({**BASE, "n1": 0.0}, "n1", "above 0 rpm"),
    ({**BASE, "n1": -100.0}, "n1", "above 0 rpm"),
    ({**BASE, "n1": float("nan")}, "n1", "not a finite number"),
    ({**BASE, "n1": float("inf")}, "n1", "not a finite number"),
    ({**BASE, "n1": 2e6}, "n1", "rpm"),
    ({**BASE, "n1": "fast"}, "n1", "expected a number"),
    ({**BASE, "n1": True}, "n1", "expected a number"),
    ({**BASE, "addendum": [1.0]}, "addendum", "[ha1, ha2]; got 1 numbers"),
    ({**BASE, "addendum": [1.0, 1.0, 1.0]}, "addendum", "got 3 numbers"),
    ({**BASE, "addendum": []}, "addendum", "got 0 numbers"),
    ({**BASE, "addendum": [-0.1, 1.0]}, "addendum", "the addendum of wheel 1"),
    ({**BASE, "addendum": [1.0, 3.0]}, "addendum", "the addendum of wheel 2"),
    ({**BASE, "addendum": [0.0, 0.0]}, "addendum", "both addenda are 0"),
    ({**BASE, "addendum": ["1", 1.0]}, "addendum", "expected a number"),
    ({**BASE, "addendum": [1.0, float("nan")]}, "addendum", "not a finite number"),
    ({**BASE, "addendum": 2.0}, "addendum", "0.5 … 1.5"),
    ({**RING, "x1": 1.0, "x2": -1.0}, "x1", "too negative for the internal pair"),
    ({"z1": 30, "z2": 38, "module": 2.0, "internal": True}, None, "tip interference"),
    ({"z1": 18, "z2": 72, "module": 2.0, "internal": True}, None, "(involute interference)"),
    ({"z1": 20, "z2": 28, "module": 2.0, "internal": True}, None, "inside its base circle"),
    ({"z1": 12, "module": 2.0, "rack": True}, None, "tip line of the rack"),
    ({**RACK, "addendum": [1.0, 2.5], "pressure_angle": 35.0}, "addendum", "pointed"),
])
def test_refusals_are_one_line_naming_the_key(table, key, words):
    e = _refusal(table)
    line = str(e)
    assert "\n" not in line and words in line, line
    assert line.startswith(f"[gear_pair.{key}]: " if key else "[gear_pair]: "), line


def test_a_refused_internal_pair_is_one_line_from_the_command_line(tmp_path):
    line = refused_line(tmp_path, "[gear_pair]\nz1 = 30\nz2 = 38\nmodule = 2.0\ninternal = true\n")
    assert "bad.toml" in line and "[gear_pair]" in line and "tip interference" in line and "z2 − z1 = 8" in line


# --- the internal pair of a train ------------------------------------------------------------------

_TRAIN = """[gears.wheels]
a = {{ teeth = {z1}{m} }}
b = {{ teeth = {z2}{m}, internal = true }}
[gears]
meshes = [["a", "b"]]
[gears.input]
a = 100.0
"""


def _train(z1: int, z2: int, module: bool) -> str:
    return _TRAIN.format(z1=z1, z2=z2, m=", module = 2.0" if module else "")


def test_a_train_refuses_an_internal_mesh_with_tip_interference_when_it_has_modules(tmp_path):
    import tomllib

    from plans.scene.gears import read_gears
    train = read_gears(tomllib.loads(_train(30, 38, True))["gears"])
    with pytest.raises(StructureError) as info:
        analyse_train(train)
    assert info.value.key == "gears.meshes"
    assert str(info.value) == ("[gears.meshes]: ring gear 'b' (38 teeth) and 'a' (30) inside it interfere: the tip of "
                               "'a' strikes the ring's teeth as it leaves the mesh (tip interference of standard "
                               "wheels, z2 − z1 = 8); give the ring at least 39 teeth")
    line = refused_line(tmp_path, _train(30, 38, True))
    assert "bad.toml" in line and "[gears.meshes]" in line and "at least 39 teeth" in line
    # 39 teeth are enough: no refusal, no warning of it
    enough = analyse_train(read_gears(tomllib.loads(_train(30, 39, True))["gears"]))
    assert not any("interfere" in w for w in enough.warnings)


def test_a_train_without_modules_warns_of_the_tip_interference():
    scene = parse_scene(__import__("tomllib").loads(_train(30, 38, False)))
    out = render(scene, stem="t")
    warned = [w for w in out.warnings if "interfere" in w]
    assert len(warned) == 1 and "ring gear 'b' (38 teeth)" in warned[0] and "at least 39 teeth" in warned[0]
    report = json.loads(out.files["t.json"])["gears"]
    assert any("tip interference" in w for w in report["warnings"])


def test_the_bundled_planetary_trains_pass_the_internal_check():
    for stem in ("planetary_1_21", "planetary_type_b", "differential_1_21", "press_drive"):
        scene = read_scene(ROOT / "examples" / "gears" / f"{stem}.toml")
        assert not any("interfere" in w for w in analyse_train(scene.gears).warnings)


def test_a_mesh_of_a_planet_and_its_ring_is_an_internal_pair():
    """mesh = ["2", "3"] of the train of Fig. 1.21 (planet 27, ring 72, m = 3): the ring second."""
    data = __import__("tomllib").loads((ROOT / "examples" / "gears" / "planetary_1_21.toml").read_text())
    data["gear_pair"] = {"mesh": ["3", "2"]}
    data["plans"] = {"draw": ["gears"]}
    rep = json.loads(render(parse_scene(data), stem="m").files["m.json"])["gear_pair"]
    assert rep["kind"] == "internal" and rep["wheels"] == ["2", "3"] and rep["z"] == [27, 72]
    assert rep["centre_distance"] == pytest.approx(3.0 * (72 - 27) / 2, rel=REL)
    data["gear_pair"] = {"mesh": ["2", "3"], "shift": "balanced"}
    with pytest.raises(SceneError, match=r"^\[gear_pair.shift\]: .*ring gear 3 makes this one internal"):
        render(parse_scene(data), stem="m")


# --- the old report ----------------------------------------------------------------------------------

def _same(a, b) -> bool:
    """JSON values equal, numbers to 1e-12 relative."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, float) or isinstance(b, float):
        return a == pytest.approx(b, rel=1e-12, abs=1e-12)
    return a == b


def test_the_old_report_keys_and_values_are_unchanged():
    """The example pair_12_no_undercut rendered now holds every key of the report as it was
    rendered into output/ (their values equal), and the new keys besides."""
    scene = ROOT / "examples" / "gears" / "pair_12_no_undercut.toml"
    now = json.loads(render(scene).files["pair_12_no_undercut.json"])["gear_pair"]
    old_keys = {"wheels", "z", "module", "pressure_angle", "addendum", "clearance", "tip_radius", "shift_rule", "x1",
                "x2", "x_min", "undercut", "working_pressure_angle", "reference_centre_distance", "centre_distance",
                "y", "delta_y", "d", "db", "dw", "da", "df", "p", "pb", "s", "sa", "line_of_action", "active_length",
                "contact_ratio", "specific_sliding"}
    assert old_keys <= set(now)
    assert {"kind", "path_of_approach", "path_of_recess", "path_of_contact", "arc_of_contact",
            "angle_turned"} <= set(now)
    assert isinstance(now["addendum"], float) and now["kind"] == "external"
    saved = ROOT / "output" / "pair_12_no_undercut.json"
    if not saved.exists():
        pytest.skip("output/ is not rendered")
    before = json.loads(saved.read_text(encoding="utf-8"))["gear_pair"]
    assert old_keys <= set(before)
    for key in old_keys:
        assert _same(now[key], before[key]), key
    g = gear_pair(12, 30, now["module"], x1=now["x1"], x2=now["x2"])
    assert now["path_of_contact"] == pytest.approx(g.active, rel=REL)

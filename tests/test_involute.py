"""The involute pair's geometry (issue 19, the core): a published profile-shifted pair to its
printed rounding, inv α_w against mpmath, the contact ratio by a second formula, and the
undercut limit."""

from __future__ import annotations

import math
import random

import mpmath
import pytest

from plans.gears.involute import gear_pair, inv, inv_inverse, min_shift


def test_khk_profile_shifted_pair():
    """KHK Gear Technical Reference, the profile-shifted external pair (m = 3, α = 20°, z = 12/24,
    x = 0.6/0.36): α_w = 26.0886°, y = 0.83329, a_w = 56.4999 mm, d_b = 33.8289/67.6579,
    d_w = 37.667/75.333, d_a = 44.840/79.400, d_f = 32.100/66.660 mm, as printed."""
    g = gear_pair(12, 24, 3.0, x1=0.6, x2=0.36)
    assert round(g.working_pressure_angle_deg, 4) == 26.0886
    assert round(g.y, 5) == 0.83329
    assert round(g.a_w, 4) == 56.4999
    assert [round(v, 4) for v in g.db] == [33.8289, 67.6579]
    assert [round(v, 3) for v in g.dw] == [37.667, 75.333]
    assert [round(v, 3) for v in g.da] == [44.840, 79.400]
    assert [round(v, 3) for v in g.df] == [32.100, 66.660]


def test_khk_standard_pair():
    """KHK Gear Technical Reference, the standard external pair (m = 3, α = 20°, z = 12/24):
    a = 54.000, d = 36/72, d_a = 42/78, d_b = 33.829/67.658, d_f = 28.5/64.5 mm, as printed."""
    g = gear_pair(12, 24, 3.0)
    assert round(g.a_w, 3) == 54.000 and [round(v, 3) for v in g.d] == [36.0, 72.0]
    assert [round(v, 3) for v in g.da] == [42.0, 78.0]
    assert [round(v, 3) for v in g.db] == [33.829, 67.658]
    assert [round(v, 3) for v in g.df] == [28.5, 64.5]


def test_khurmi_arc_of_contact():
    """Khurmi & Gupta, Theory of Machines, toothed wheels (from my knowledge of the worked example;
    its number may differ by edition): 20° involute pair, pinion 20 teeth, ratio 2, module 5 mm,
    addendum one module, pitch-line speed 1.2 m/s — path of approach 12.65 mm, path of recess
    11.49 mm, arc of contact 25.69 mm, the pinion turns through 29.43° while one pair is in mesh,
    the largest sliding velocity (ω1 + ω2)·approach = 455.4 mm/s."""
    g = gear_pair(20, 40, 5.0)
    g1, g2 = (math.sqrt((da / 2) ** 2 - (db / 2) ** 2) for da, db in zip(g.da, g.db))
    approach = g2 - g.dw[1] / 2 * math.sin(g.alpha_w)         # from B2 to P
    recess = g1 - g.dw[0] / 2 * math.sin(g.alpha_w)           # from P to B1
    assert round(approach, 2) == 12.65 and round(recess, 2) == 11.49
    assert approach + recess == pytest.approx(g.active, rel=1e-14)
    arc = g.active / math.cos(g.alpha)
    assert round(arc, 2) == 25.69
    assert round(math.degrees(arc / (g.d[0] / 2)), 2) == 29.43
    w1 = 1.2e3 / (g.d[0] / 2)                                  # rad/s from the pitch-line speed, mm/s
    assert round((w1 + w1 / 2) * round(approach, 2), 1) == 455.4


def test_unshifted_pair_is_the_standard_one():
    g = gear_pair(20, 45, 2.5)
    assert g.alpha_w == pytest.approx(math.radians(20.0), abs=1e-15)
    assert g.a_w == pytest.approx(81.25, rel=1e-15) and g.y == pytest.approx(0.0, abs=1e-12)
    assert g.da == pytest.approx((55.0, 117.5), rel=1e-15) and g.df == pytest.approx((43.75, 106.25), rel=1e-15)
    assert g.s == pytest.approx((2.5 * math.pi / 2,) * 2, rel=1e-15)


def test_working_pressure_angle_against_mpmath():
    """inv α_w = inv α + 2 tan α (x1 + x2)/(z1 + z2) solved in double precision, against mpmath's
    root at 50 digits: within 1e-14 rad over random pairs (negative sums included)."""
    mpmath.mp.dps = 50
    rng = random.Random(7)
    for _ in range(200):
        z1, z2 = rng.randint(8, 60), rng.randint(8, 150)
        xs = rng.uniform(-0.5, 1.2)
        alpha = math.radians(rng.choice((14.5, 20.0, 25.0)))
        target = inv(alpha) + 2 * math.tan(alpha) * xs / (z1 + z2)
        if target <= 0:
            continue
        mine = inv_inverse(target)
        exact = mpmath.findroot(lambda a: mpmath.tan(a) - a - mpmath.mpf(target), mpmath.mpf(alpha))
        assert abs(mine - float(exact)) <= 1e-14
    assert inv_inverse(0.0) == 0.0
    with pytest.raises(ValueError):
        inv_inverse(-1e-3)


@pytest.mark.parametrize("z1, z2, x1, x2", [(12, 24, 0.6, 0.36), (18, 37, 0.0, 0.0), (10, 30, 0.5, -0.2),
                                            (25, 25, 0.3, 0.3)])
def test_contact_ratio_by_the_pressure_angles(z1, z2, x1, x2):
    """ε_α from the active length B1B2/p_b equals the textbook's second form
    [z1(tan α_a1 − tan α_w) + z2(tan α_a2 − tan α_w)]/2π, α_a = arccos(d_b/d_a)."""
    g = gear_pair(z1, z2, 4.0, x1=x1, x2=x2)
    tip = [math.acos(db / da) for db, da in zip(g.db, g.da)]
    other = (z1 * (math.tan(tip[0]) - math.tan(g.alpha_w)) + z2 * (math.tan(tip[1]) - math.tan(g.alpha_w))) / (2 * math.pi)
    assert g.contact_ratio == pytest.approx(other, rel=1e-12)


def test_undercut_limit_of_the_rack():
    """x_min = ha* − z·sin²α/2: without shift, undercut below 17 teeth and not from 18 on."""
    for z in range(6, 17):
        assert gear_pair(z, 40, 1.0).undercut[0]
        assert not gear_pair(z, 40, 1.0, x1=min_shift(z)).undercut[0]
    for z in range(18, 60):
        assert not gear_pair(z, 40, 1.0).undercut[0]


def test_specific_sliding_by_velocities():
    """ϑ at the ends of the active line, against the sliding written from the profiles' tangential
    speeds ω·ρ at the contact point."""
    g = gear_pair(14, 35, 2.0, x1=0.3, x2=0.0)
    w1 = 1.0
    w2 = w1 * 14 / 35
    g2 = math.sqrt((g.da[1] / 2) ** 2 - (g.db[1] / 2) ** 2)
    rho1 = g.line - g2
    assert g.sliding[0] == pytest.approx((w1 * rho1 - w2 * g2) / (w1 * rho1), rel=1e-12)
    g1 = math.sqrt((g.da[0] / 2) ** 2 - (g.db[0] / 2) ** 2)
    rho2 = g.line - g1
    assert g.sliding[1] == pytest.approx((w2 * rho2 - w1 * g1) / (w2 * rho2), rel=1e-12)

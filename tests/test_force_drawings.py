"""Force plans and Zhukovsky's lever, drawn from plain inputs (plans.constructions.forces,
plans.drawing.forces) and read back by ``plans check`` and the layout measurer.

The lever's balancing force and moment are checked against the power balance
Σ F·v + Σ M·ω = 0 on random forces at random images (v = image × μV), independently of the
turned-plan geometry; the sheets are checked by measuring them (every vector, each polygon's
closure, the arms, Σ M_p = 0), and ``plans check`` must fail on doctored copies.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from conftest import CRANK_SLIDER, sheet_words
from plans.checking import inspect_svg
from plans.cli import main
from plans.constructions import velocity_plan
from plans.constructions.forces import (BalanceForce, BalanceMoment, ForceTerm, LeverCouple, LeverLoad, force_plan,
                                        zhukovsky_lever)
from plans.constructions.plans import Plan, PlanPoint, PlanVector
from plans.constructions.force_polygon import FORCE_SERIES
from plans.drawing.forces import draw_force_plans, symbol
from plans.drawing.lever import draw_lever
from plans.drawing.svg import Heading
from plans.errors import ConstructionError
from plans.layout import measure_layout
from plans.pipeline import render_scene

HEADING = Heading("Test mechanism", "Force plans", "φ1 = 30°")


def in_series(mu: float) -> bool:
    k = math.floor(math.log10(mu) + 1e-12)
    return any(math.isclose(mu, m * 10.0 ** k, rel_tol=1e-12) for m in FORCE_SERIES)


def random_group(rng: np.random.Generator) -> tuple[list[ForceTerm], ForceTerm]:
    """Known forces of two links, the reaction R_12 in components (n along a random link
    direction, t ⊥ it) and R_03 closing the polygon; and R_32, the internal reaction that closes
    the forces on link 2 alone."""
    u = rng.normal(size=2)
    u /= np.linalg.norm(u)
    n_, t_ = rng.uniform(-300, 300) * u, rng.uniform(-300, 300) * np.array([-u[1], u[0]])
    g2, f2 = (0.0, -rng.uniform(10, 100)), tuple(rng.uniform(-400, 400, size=2))
    g3, f3 = (0.0, -rng.uniform(10, 100)), tuple(rng.uniform(-400, 400, size=2))
    link2 = [ForceTerm("R:1-2:n", tuple(n_), "reaction_n"), ForceTerm("R:1-2:t", tuple(t_), "reaction_t"),
             ForceTerm("G:2", g2, "gravity"), ForceTerm("F:in:2", f2, "inertia")]
    s2 = np.sum([t.vector for t in link2], axis=0)
    link3 = [ForceTerm("G:3", g3, "gravity"), ForceTerm("F:ext:C", f3, "external")]
    r03 = -(s2 + np.sum([t.vector for t in link3], axis=0))
    return link2 + link3 + [ForceTerm("R:0-3", tuple(r03), "reaction")], ForceTerm("R:3-2", tuple(-s2), "reaction")


def write(tmp_path: Path, name: str, text: str) -> Path:
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


def assert_checked(path: Path) -> None:
    r = inspect_svg(path)
    assert r.kind == "plan" and r.ok, (r.problems, [m for m in r.measurements if not m.ok],
                                       [c for c in r.closures if not c.ok], [c for c in r.checks if not c.ok])


def assert_clean(text: str) -> None:
    rep = measure_layout(text)
    assert rep.clean, {k: rep.offenders(k) for k, v in rep.counts.items() if v}


# --- force plans --------------------------------------------------------------------------------

@pytest.mark.parametrize("seed", range(6))
def test_a_random_closed_polygon_is_drawn_to_scale_and_passes_check(tmp_path, seed):
    rng = np.random.default_rng(seed)
    terms, r32 = random_group(rng)
    fp = force_plan("II(2-3)", terms, internal=[r32])
    assert in_series(fp.mu)
    fmax = max(t.value for t in terms)
    assert fmax / fp.mu <= 150.0 + 1e-9       # the largest side: 100–150 mm, never longer
    # every drawn side: length × μF = |F|, tail → head = F / μF
    for v, t in zip(fp.sides, terms):
        assert v.quantity == t.quantity
        np.testing.assert_allclose(np.subtract(v.head, v.tail) * fp.mu, t.vector, rtol=0, atol=1e-9 * fmax)
    # the whole reaction R_12 = Rn + Rt, the internal R_32 a diagonal, the polygon closed on a
    drawn = {v.quantity: v for v in fp.vectors}
    assert drawn["R:1-2"].role == "total" and drawn["R:3-2"].role == "internal"
    np.testing.assert_allclose(np.subtract(drawn["R:3-2"].head, drawn["R:3-2"].tail) * fp.mu, r32.vector,
                               atol=1e-9 * fmax)
    assert fp.sides[-1].head == fp.point(fp.start)
    svgs = draw_force_plans([fp], HEADING, ident="forces")
    assert len(svgs) == 1
    path = write(tmp_path, "forces.svg", svgs[0])
    assert_checked(path)
    r = inspect_svg(path)
    assert {c.what for c in r.checks} >= {"Σ of the 7 drawn sides", "Σ of the recorded forces"}
    assert_clean(svgs[0])
    lines = re.findall(r'<line[^>]*data-quantity="([^"]+)"[^>]*data-value="([^"]+)"', svgs[0])
    assert {q for q, _ in lines} == {t.quantity for t in terms} | {"R:1-2", "R:3-2"}


def test_forces_that_do_not_close_are_refused():
    terms, _ = random_group(np.random.default_rng(1))
    terms[2] = ForceTerm("G:2", (0.0, terms[2].vector[1] - 1e-3), "gravity")
    with pytest.raises(ConstructionError, match="do not close"):
        force_plan("II(2-3)", terms)


def test_an_internal_reaction_that_joins_no_vertices_is_refused():
    terms, r32 = random_group(np.random.default_rng(2))
    with pytest.raises(ConstructionError, match="joins no two vertices"):
        force_plan("II(2-3)", terms, internal=[ForceTerm("R:3-2", (r32.vector[0] + 50.0, r32.vector[1]), "reaction")])


def test_bad_terms_are_refused():
    with pytest.raises(ConstructionError, match="kind"):
        force_plan("II(2-3)", [ForceTerm("G:2", (0.0, -1.0), "weight"), ForceTerm("R:1-2", (0.0, 1.0), "reaction")])
    with pytest.raises(ConstructionError, match="repeated"):
        force_plan("II(2-3)", [ForceTerm("G:2", (0.0, -1.0), "gravity"), ForceTerm("G:2", (0.0, 1.0), "gravity")])
    with pytest.raises(ConstructionError, match="finite"):
        force_plan("II(2-3)", [ForceTerm("G:2", (math.nan, -1.0), "gravity")])


def test_zero_forces_are_not_drawn_but_listed(tmp_path):
    terms, _ = random_group(np.random.default_rng(3))
    terms.insert(3, ForceTerm("F:in:3", (0.0, 0.0), "inertia"))
    fp = force_plan("II(2-3)", terms)
    assert "F:in:3" not in {v.quantity for v in fp.vectors}
    assert "F:in:3" in {t.quantity for t in fp.terms}
    svg = draw_force_plans([fp], HEADING, ident="forces")[0]
    words = sheet_words(svg)
    assert "Fin,3" in words and "0 (not drawn)" in words
    assert_checked(write(tmp_path, "f.svg", svg))


def test_several_groups_share_a_sheet_each_with_its_own_scale(tmp_path):
    a, ra = random_group(np.random.default_rng(4))
    b, _ = random_group(np.random.default_rng(5))
    b = [ForceTerm(t.quantity, tuple(np.multiply(t.vector, 20.0)), t.kind) for t in b]
    plans_ = [force_plan("II(2-3)", a, internal=[ra]), force_plan("II(4-5)", b)]
    assert plans_[0].mu != plans_[1].mu
    svgs = draw_force_plans(plans_, HEADING, ident="forces")
    assert len(svgs) == 1
    path = write(tmp_path, "two.svg", svgs[0])
    assert_checked(path)
    r = inspect_svg(path)
    assert len(r.equations) == 2
    mus = sorted(float(m) for m in re.findall(r'data-plan="force"[^>]*|data-mu="([^"]+)"', svgs[0]) if m)
    assert mus == sorted(p.mu for p in plans_)
    assert_clean(svgs[0])


def test_many_groups_spill_onto_further_sheets(tmp_path):
    plans_ = [force_plan(f"II({2 * k}-{2 * k + 1})", random_group(np.random.default_rng(10 + k))[0])
              for k in range(1, 7)]
    svgs = draw_force_plans(plans_, HEADING, ident="forces")
    assert len(svgs) >= 2
    for k, svg in enumerate(svgs):
        assert_checked(write(tmp_path, f"s{k}.svg", svg))
        assert_clean(svg)
    groups = re.findall(r'data-group="([^"]+)"', "".join(svgs))
    assert groups == [p.group for p in plans_]


@pytest.mark.parametrize("doctor, why", [
    (lambda s: _retag(s, "G:2", "data-value", 1.01), "value"),
    (lambda s: _retag(s, "F:in:2", "x2", 1.01), "moved end"),
])
def test_check_fails_on_a_doctored_force_plan(tmp_path, capsys, doctor, why):
    terms, r32 = random_group(np.random.default_rng(7))
    svg = draw_force_plans([force_plan("II(2-3)", terms, internal=[r32])], HEADING, ident="forces")[0]
    good = write(tmp_path, "good.svg", svg)
    assert main(["check", str(good)]) == 0
    doctored = doctor(svg)
    assert doctored != svg, why
    bad = write(tmp_path, "bad.svg", doctored)
    capsys.readouterr()
    assert main(["check", str(bad)]) == 1
    assert "FAIL" in capsys.readouterr().out


def test_a_polygon_that_does_not_close_fails_the_sum_of_sides(tmp_path):
    """Shift a side *and* its vertex label so no two ends are named alike: only the sum of
    the sides can tell."""
    terms, _ = random_group(np.random.default_rng(8))
    svg = draw_force_plans([force_plan("II(2-3)", terms)], HEADING, ident="forces")[0]
    m = re.search(r'<line[^>]*data-quantity="R:0-3"[^>]*>', svg)
    line = m.group()
    x1 = re.search(r'x1="([^"]+)"', line).group(1)
    moved = line.replace(f'x1="{x1}"', f'x1="{float(x1) + 2:g}"')
    moved = re.sub(r'data-from="[^"]+"', 'data-from="zz"', moved)
    r = inspect_svg(write(tmp_path, "open.svg", svg.replace(line, moved)))
    assert not r.ok
    assert any(not c.ok and c.what.startswith("Σ of the") for c in r.checks)


# --- the lever ----------------------------------------------------------------------------------

def random_plan(rng: np.random.Generator, n: int = 6) -> Plan:
    """A velocity plan of random images (mm) around the pole, μV from the series."""
    pts = [PlanPoint("p", (0.0, 0.0))] + [PlanPoint(chr(ord("a") + k), tuple(rng.uniform(-60, 60, size=2)))
                                          for k in range(n)]
    vecs = tuple(PlanVector(f"v:{p.label.upper()}", (0.0, 0.0), p.xy, math.hypot(*p.xy) * 0.01, "absolute")
                 for p in pts[1:])
    return Plan("velocity", 0.01, "p", tuple(pts), vecs, (), ())


def power_case(rng: np.random.Generator):
    """Random loads at random images, a random couple on a link consistent with its images, and
    the power of all of it: Σ F·v + M·ω (v = image × μV)."""
    plan = random_plan(rng)
    mu_v = plan.mu
    loads, power = [], 0.0
    for k in range(5):
        img = plan.points[1 + k].xy if k < 3 else tuple(rng.uniform(-60, 60, size=2))
        f = tuple(rng.uniform(-500, 500, size=2))
        loads.append(LeverLoad(f"F:ext:{k}", img, f, label="" if k < 3 else f"s{k}"))
        power += float(np.dot(f, np.multiply(img, mu_v)))
    # a link AB of length l turning at ω: its images differ by ω l J û / μV
    u = rng.normal(size=2)
    u /= np.linalg.norm(u)
    length, moment = rng.uniform(0.1, 0.8), rng.uniform(-50, 50)
    omega = rng.uniform(-60.0, 60.0) * mu_v / length       # the images at most 60 mm apart
    e1 = np.asarray(plan.points[1].xy)
    e2 = e1 + omega * length * np.array([-u[1], u[0]]) / mu_v
    couple = LeverCouple("M:2", moment, (tuple(e1), tuple(e2)), length, tuple(u * 3.0))
    power += moment * omega
    return plan, loads, couple, power


@pytest.mark.parametrize("seed", range(20))
def test_the_balancing_force_is_the_power_balance(seed):
    rng = np.random.default_rng(seed)
    plan, loads, couple, power = power_case(rng)
    img = np.asarray(plan.points[2].xy)
    d = rng.normal(size=2)
    lever = zhukovsky_lever(plan, loads, BalanceForce(tuple(img), tuple(d)), couples=[couple])
    u = d / np.linalg.norm(d)
    expected = -power / float(u @ (img * plan.mu))
    assert lever.result == pytest.approx(expected, rel=1e-9)
    np.testing.assert_allclose(lever.balance_vector, expected * u, rtol=1e-9, atol=1e-12 * abs(expected))
    assert abs(lever.residual) <= 1e-9 * sum(abs(f.moment) for f in lever.forces)


@pytest.mark.parametrize("seed", range(20))
def test_the_balancing_moment_is_the_power_balance(seed):
    rng = np.random.default_rng(100 + seed)
    plan, loads, couple, power = power_case(rng)
    u = rng.normal(size=2)
    u /= np.linalg.norm(u)
    omega1, l_oa = rng.choice([-1, 1]) * rng.uniform(1, 30), rng.uniform(0.05, 0.3)
    a = omega1 * l_oa * np.array([-u[1], u[0]]) / plan.mu          # the crank tip's image, O at the pole
    lever = zhukovsky_lever(plan, loads, BalanceMoment(((0.0, 0.0), tuple(a)), l_oa, tuple(u)), couples=[couple])
    assert lever.omega == pytest.approx(omega1, rel=1e-12)
    assert lever.result == pytest.approx(-power / omega1, rel=1e-9)


def test_the_arms_are_distances_from_the_pole_to_the_lines_of_action():
    plan, loads, couple, _ = power_case(np.random.default_rng(5))
    lever = zhukovsky_lever(plan, loads, BalanceForce(plan.points[3].xy, (1.0, 0.3)), couples=[couple])
    pole = np.asarray(lever.pole_xy)
    for f in lever.forces:
        r, F = np.asarray(f.point) - pole, np.asarray(f.force)
        assert f.moment == pytest.approx(r[0] * F[1] - r[1] * F[0], rel=1e-12, abs=1e-9)
        assert f.arm * f.value == pytest.approx(abs(f.moment), rel=1e-12, abs=1e-9)
        foot = np.asarray(f.foot) - pole
        assert np.hypot(*foot) == pytest.approx(f.arm, rel=1e-12, abs=1e-9)
        assert abs(float(foot @ F)) <= 1e-9 * max(f.arm, 1.0) * f.value           # ⊥ the force
    # turned clockwise: each turned image is (y, −x) of the unturned one
    unturned = {p.label: p.xy for p in plan.points}
    for p in lever.points:
        if p.label in unturned:
            x, y = unturned[p.label]
            assert p.xy == pytest.approx((y, -x), abs=1e-12)


def test_couples_must_match_their_images_and_the_balance_must_move():
    plan, loads, couple, _ = power_case(np.random.default_rng(6))
    skew = LeverCouple("M:2", 1.0, couple.ends, couple.length_m, (couple.direction[1], -couple.direction[0]))
    with pytest.raises(ConstructionError, match="⊥"):
        zhukovsky_lever(plan, loads, BalanceForce(plan.points[2].xy, (1.0, 0.0)), couples=[skew])
    img = np.asarray(plan.points[2].xy)
    through_pole = (-img[1], img[0])        # turned clockwise, the image lies on this line's normal… through p
    with pytest.raises(ConstructionError, match="pole"):
        zhukovsky_lever(plan, loads, BalanceForce(tuple(img), through_pole))


def lever_sheet(seed: int, moment: bool):
    rng = np.random.default_rng(seed)
    plan, loads, couple, _ = power_case(rng)
    if moment:
        a = np.asarray(plan.points[1].xy)
        u = np.array([a[1], -a[0]]) / np.hypot(*a)       # O → A with J û ∥ a (ω1 > 0)
        bal = BalanceMoment(((0.0, 0.0), tuple(a)), 0.1, tuple(u))
    else:
        bal = BalanceForce(plan.points[2].xy, tuple(rng.normal(size=2)))
    lever = zhukovsky_lever(plan, loads, bal, couples=[couple])
    return lever, draw_lever(lever, Heading("Test", "Zhukovsky's lever", "φ1 = 30°"), ident="lever")


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("moment", [False, True])
def test_lever_sheets_pass_check_and_layout(tmp_path, seed, moment):
    lever, svg = lever_sheet(seed, moment)
    path = write(tmp_path, "lever.svg", svg)
    assert_checked(path)
    r = inspect_svg(path)
    assert any(c.what == "Σ M_p with the drawn arms" for c in r.checks)
    assert sum(c.what.startswith("arm of") for c in r.checks) >= len(lever.forces)
    assert_clean(svg)
    assert symbol(lever.balance_quantity).split("_")[0] in sheet_words(svg)


def _retag(svg: str, quantity: str, attr: str, factor: float) -> str:
    line = re.search(rf'<line[^>]*data-quantity="{re.escape(quantity)}"[^>]*>', svg).group()
    new = re.sub(rf'({attr}=")([^"]+)"', lambda m: m.group(1) + repr(float(m.group(2)) * factor) + '"', line)
    return svg.replace(line, new)


def _move_arm_end(svg: str) -> str:
    m = re.search(r'<line[^>]*data-construction="arm"[^>]*>', svg)
    line = m.group()
    x2 = re.search(r'x2="([^"]+)"', line).group(1)
    return svg.replace(line, line.replace(f'x2="{x2}"', f'x2="{float(x2) + 0.8:g}"'))


@pytest.mark.parametrize("doctor", [
    lambda s: _retag(s, "F:bal", "data-value", 1.02),           # the balancing force's value
    lambda s: _retag(s, "F:bal", "data-h", 1.05),               # its arm as recorded
    _move_arm_end,                                             # an arm drawn off its line
    lambda s: s.replace('data-pole="', 'data-pole="1', 1),      # the pole moved
], ids=["value", "arm", "arm-line", "pole"])
def test_check_fails_on_a_doctored_lever(tmp_path, capsys, doctor):
    _, svg = lever_sheet(3, False)
    assert main(["check", str(write(tmp_path, "good.svg", svg))]) == 0
    doctored = doctor(svg)
    assert doctored != svg
    capsys.readouterr()
    assert main(["check", str(write(tmp_path, "bad.svg", doctored))]) == 1
    assert "FAIL" in capsys.readouterr().out


def test_a_lever_whose_moments_do_not_balance_fails(tmp_path):
    """A balancing force of the wrong size, consistently drawn and recorded (the arrow shortened
    with its value): every vector measures right, only Σ M_p = 0 tells."""
    plan, loads, couple, _ = power_case(np.random.default_rng(9))
    good = zhukovsky_lever(plan, loads, BalanceForce(plan.points[2].xy, (0.3, 1.0)), couples=[couple])
    wrong = zhukovsky_lever(plan, loads[:-1], BalanceForce(plan.points[2].xy, (0.3, 1.0)), couples=[couple],
                            mu=good.mu)
    forces = good.forces[:-1] + wrong.forces[-1:]
    from dataclasses import replace
    bad = replace(good, forces=forces)
    r = inspect_svg(write(tmp_path, "unbalanced.svg", draw_lever(bad, HEADING, ident="lever")))
    assert all(m.ok for m in r.measurements)
    assert [c.what for c in r.checks if not c.ok] == ["Σ M_p with the drawn arms"]


# --- a solved mechanism -------------------------------------------------------------------------

def test_the_crank_slider_lever_and_force_plans(tmp_path):
    """The central crank-slider at its sketch: a resisting force at B, weights, an inertia force
    and a moment on the rod; the balancing moment on the crank from the lever equals the power
    balance with the motion's own velocities, and the sheets pass check and layout."""
    result = render_scene(CRANK_SLIDER)
    motion = result.motion
    plan = velocity_plan(motion, 0, result.scales.mu_v)
    r = {p: motion.position(p)[0] for p in "OABC"}
    v = {p: motion.velocity(p)[0] for p in "ABC"}
    w1, w2 = motion.links["1"].omega[0], motion.links["2"].omega[0]
    f_b, g2, f_in, m2 = (-800.0, 0.0), (0.0, -40.0), (150.0, 60.0), 4.0
    loads = [LeverLoad("F:ext:B", plan.point("b"), f_b), LeverLoad("G:2", plan.point("c"), g2),
             LeverLoad("F:in:2", plan.point("c"), f_in)]
    couple = LeverCouple("M:2", m2, (plan.point("a"), plan.point("b")), 0.4, tuple(r["B"] - r["A"]))
    bal = BalanceMoment((plan.point("o"), plan.point("a")), 0.1, tuple(r["A"] - r["O"]))
    lever = zhukovsky_lever(plan, loads, bal, couples=[couple])
    power = np.dot(f_b, v["B"]) + np.dot(g2, v["C"]) + np.dot(f_in, v["C"]) + m2 * w2
    assert lever.omega == pytest.approx(w1, rel=1e-12)
    assert lever.result == pytest.approx(-power / w1, rel=1e-9)
    heading = Heading("Central crank-slider mechanism", "Zhukovsky's lever", "φ1 = 45°")
    svg = draw_lever(lever, heading, ident="lever")
    assert_checked(write(tmp_path, "cs-lever.svg", svg))
    assert_clean(svg)
    # the group II(2-3): Rn along AB, Rt ⊥ AB (from Σ M_B of link 2), R_03 ⊥ the guide, closing
    u = (r["B"] - r["A"]) / np.linalg.norm(r["B"] - r["A"])
    known = np.add(np.add(g2, f_in), f_b)
    rt = -0.5 * known[1] * np.array([-u[1], u[0]])          # any value: the polygon closes by Rn and R03
    rest = -(known + rt)
    rn, r03 = np.linalg.solve(np.array([[u[0], 0.0], [u[1], 1.0]]), rest)
    terms = [ForceTerm("R:1-2:n", tuple(rn * u), "reaction_n"), ForceTerm("R:1-2:t", tuple(rt), "reaction_t"),
             ForceTerm("G:2", g2, "gravity"), ForceTerm("F:in:2", f_in, "inertia"),
             ForceTerm("F:ext:B", f_b, "external"), ForceTerm("R:0-3", (0.0, r03), "reaction")]
    fp = force_plan("II(2-3)", terms)
    svgs = draw_force_plans([fp], Heading("Crank-slider", "Force plans", "φ1 = 45°"), ident="forces")
    for k, s in enumerate(svgs):
        assert_checked(write(tmp_path, f"cs-forces{k}.svg", s))
        assert_clean(s)

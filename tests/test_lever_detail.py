"""Zhukovsky's lever with loaded images crowding its pole: an enlarged detail of the pole region
(its own μV/k and μF′, arms k·h, checked but for Σ M_p), labels clear; an arm of a line
through the pole written h = 0; a well-spread gallery lever gets no detail."""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from plans.checking import inspect_svg
from plans.constructions.detail import NEAR_MM
from plans.constructions.lever_detail import lever_crowd
from plans.constructions.plan_values import Plan, PlanPoint, PlanVector
from plans.constructions.zhukovsky import BalanceForce, LeverLoad, zhukovsky_lever
from plans.drawing.lever import _lever_text
from plans.layout import measure_layout
from plans.pipeline import render_scene

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
SVG = "{http://www.w3.org/2000/svg}"
#: Two ends each rounded to the writer's 0.0005 mm: a drawn length is good to this, mm.
ROUND_MM = 2.0 * math.sqrt(2.0) * 0.0005
#: The handout variants whose levers piled labels at the pole (scene, seed, variant, lever sheet:
#: the press's variants are cycles, a lever at positions 0 and 6, its working force on the
#: working stroke only).
CROWDED = (("class3_forces", 11, 3, "lever"), ("class3_forces", 11, 5, "lever"),
           ("six_link_press_forces", 12, 1, "lever-120"), ("six_link_press_forces", 12, 4, "lever-20"),
           ("six_link_press_forces", 7, 2, "lever-25"))


@pytest.fixture(scope="module")
def handouts(tmp_path_factory) -> dict[tuple[str, int], Path]:
    """The answer keys' SVG sheets of ``plans handout SCENE --random 6 --seed S``, each variant in
    its folder as the handout writes it (drawn by the handout's own random_variants; the PDFs
    and the assignment sheets, which these tests do not read, are not made)."""
    from plans.handout import random_variants

    out = {}
    for scene, seed in sorted({(s, d) for s, d, *_ in CROWDED}):
        dest = tmp_path_factory.mktemp(scene)
        _, drawn = random_variants(EXAMPLES / f"{scene}.toml", 6, seed)
        for d in drawn:
            (dest / d.name).mkdir()
            for name, text in d.sheets.files.items():
                if name.endswith(".svg"):
                    (dest / d.name / name).write_text(text, encoding="utf-8")
        out[(scene, seed)] = dest
    return out


def _lever_svg(handouts, scene: str, seed: int, variant: int, sheet: str = "lever") -> Path:
    return handouts[(scene, seed)] / f"variant-{variant:02d}" / f"variant-{variant:02d}-{sheet}.svg"


def _levers(svg: str) -> dict[str, ET.Element]:
    """The lever groups by their data-detail ("" for the lever itself)."""
    root = ET.fromstring(svg)
    return {g.get("data-detail") or "": g for g in root.iter(f"{SVG}g") if g.get("data-plan") == "lever"}


@pytest.mark.parametrize("scene,seed,variant,sheet", CROWDED)
def test_crowded_levers_are_legible_and_pass_check(handouts, scene, seed, variant, sheet):
    path = _lever_svg(handouts, scene, seed, variant, sheet)
    svg = path.read_text(encoding="utf-8")
    m = measure_layout(svg)
    assert m.clean, m.counts
    r = inspect_svg(path)
    assert r.problems == []
    lever = _levers(svg)[""]
    # the lever itself still holds every force and its Σ M_p = 0 check
    assert any(c.what.startswith("Σ M_p") and c.plan == lever.get("id") for c in r.checks)


def test_the_detail_enlarges_the_pole_region(handouts):
    path = _lever_svg(handouts, "class3_forces", 11, 3)
    svg = path.read_text(encoding="utf-8")
    groups = _levers(svg)
    assert set(groups) == {"", "pole"}
    main_g, detail = groups[""], groups["pole"]
    caption = "".join(ET.fromstring(svg).find(".//*[@id='lever-detail-caption']").itertext())
    k = int(re.search(r"detail ×(\d+)", caption).group(1))
    mu_v, mu_f = float(main_g.get("data-mu-v")), float(detail.get("data-mu"))
    assert float(detail.get("data-mu-v")) == pytest.approx(mu_v / k, rel=1e-12)
    assert caption == f"detail ×{k}, μV = {mu_v / k:g} (m/s)/mm, μF = {mu_f:g} N/mm"
    main_h = {l.get("data-quantity"): float(l.get("data-h")) for l in main_g.iter(f"{SVG}line")
              if l.get("data-quantity")}
    px, py = (float(c) for c in detail.get("data-pole").split(","))
    arms = {a.get("data-arm"): a for a in detail.iter(f"{SVG}line") if a.get("data-construction") == "arm"}
    forces = [l for l in detail.iter(f"{SVG}line") if l.get("data-quantity")]
    assert 2 <= len(forces) < len(main_h)
    measured = 0
    for line in forces:
        q = line.get("data-quantity")
        h = main_h[q]
        assert float(line.get("data-h")) == pytest.approx(k * h, rel=1e-9, abs=1e-9)
        # the force drawn at the detail's scale
        x1, y1, x2, y2 = (float(line.get(c)) for c in ("x1", "y1", "x2", "y2"))
        assert math.hypot(x2 - x1, y2 - y1) * mu_f == pytest.approx(float(line.get("data-value")),
                                                                   abs=mu_f * ROUND_MM + 1e-9)
        if k * h >= 0.5:
            a = arms[q]
            ax1, ay1, ax2, ay2 = (float(a.get(c)) for c in ("x1", "y1", "x2", "y2"))
            assert math.hypot(ax1 - px, ay1 - py) <= ROUND_MM
            assert math.hypot(ax2 - ax1, ay2 - ay1) == pytest.approx(k * h, abs=2 * ROUND_MM)
            measured += 1
    assert measured >= 3
    # the detail's largest force is legible (10–16 mm) where the lever drew it under 5 mm
    longest = max(float(l.get("data-value")) for l in forces) / mu_f
    assert 10.0 <= longest <= 16.0
    # the lever's checker measured the detail's arms but asked no Σ M_p of it
    r = inspect_svg(path)
    did = detail.get("id")
    assert sum(c.what.startswith("arm of") for c in r.checks if c.plan == did) >= 2 * measured
    assert not any(c.what.startswith("Σ M_p") for c in r.checks if c.plan == did)
    # the crowded images are lettered in the detail, not on the lever
    letters = {t.get("id"): "".join(t.itertext()) for t in ET.fromstring(svg).iter(f"{SVG}text")}
    main_letters = [v for i, v in letters.items() if re.fullmatch(r"lever-l\d+", i or "")]
    detail_letters = [v for i, v in letters.items() if re.fullmatch(r"lever-detail-l\d+", i or "")]
    assert any("s4" in v.replace(" ", "") for v in detail_letters)
    assert not any("s4" in v.replace(" ", "") for v in main_letters)


def test_a_well_spread_gallery_lever_gets_no_detail(tmp_path):
    files = render_scene(EXAMPLES / "crank_slider_forces.toml").files
    levers = {n: s for n, s in files.items() if "lever" in n}
    assert levers
    for name, svg in levers.items():
        assert set(_levers(svg)) == {""}, name
        assert measure_layout(svg).clean, name
        path = tmp_path / Path(name).name
        path.write_text(svg, encoding="utf-8")
        assert inspect_svg(path).problems == []


def _plan(points: dict[str, tuple[float, float]]) -> Plan:
    pts = tuple(PlanPoint(k, v) for k, v in points.items())
    vectors = tuple(PlanVector(f"v:{k.upper()}", points["p"], v, math.hypot(*v), "absolute")
                    for k, v in points.items() if k != "p")
    return Plan("velocity", 0.01, "p", pts, vectors, (), ())


def test_an_arm_through_the_pole_is_written_zero():
    # b's turned image is (30.7, −40.1) mm; a force along it, computed in floating point,
    # has a rounding arm of ~1e-14 mm: its line passes through the pole
    b = (40.1, 30.7)
    turned = np.array([b[1], -b[0]])
    force = turned * (1 / 3) * 7.1
    assert turned[0] * force[1] - turned[1] * force[0] != 0.0          # the rounding is there
    plan = _plan({"p": (0.0, 0.0), "a": (80.0, 0.0), "b": b})
    loads = [LeverLoad("G:2", b, tuple(force)), LeverLoad("G:3", (80.0, 0.0), (-50.0, 0.0))]
    lever = zhukovsky_lever(plan, loads, BalanceForce((80.0, 0.0), (1.0, 0.0)))
    through = next(f for f in lever.forces if f.quantity == "G:2")
    assert through.arm == 0.0 and through.moment == 0.0
    other = next(f for f in lever.forces if f.quantity == "G:3")
    assert other.arm == pytest.approx(80.0, rel=1e-12)       # turned a at (0, −80), the force along x
    rows = _lever_text(lever)
    row = next(r for r in rows if r.strip().startswith("G_{2}"))
    assert row.endswith("h = 0 (its line passes through p):  0")
    assert "e−" not in row and "e-" not in row


def test_lever_crowd_needs_two_loaded_places_near_the_pole():
    plan = _plan({"p": (0.0, 0.0), "a": (80.0, 0.0), "b": (1.0, 2.0), "c": (2.0, -1.0)})
    one = zhukovsky_lever(plan, [LeverLoad("G:2", (1.0, 2.0), (0.0, -10.0))], BalanceForce((80.0, 0.0), (1.0, 0.0)))
    assert lever_crowd(one) is None
    two = zhukovsky_lever(plan, [LeverLoad("G:2", (1.0, 2.0), (0.0, -10.0)), LeverLoad("G:3", (2.0, -1.0), (0.0, -5.0))],
                          BalanceForce((80.0, 0.0), (1.0, 0.0)))
    assert lever_crowd(two) == pytest.approx(math.hypot(1.0, 2.0), rel=1e-12)
    assert lever_crowd(two) < NEAR_MM
    # one loaded image near the pole and a force applied at the pole itself: a crowd too
    at_pole = zhukovsky_lever(plan, [LeverLoad("G:2", (1.0, 2.0), (0.0, -10.0)),
                                     LeverLoad("F:ext:P", (0.0, 0.0), (3.0, 0.0), label="p")],
                              BalanceForce((80.0, 0.0), (1.0, 0.0)))
    assert lever_crowd(at_pole) == pytest.approx(math.hypot(1.0, 2.0), rel=1e-12)


def test_a_force_legible_on_the_lever_is_not_drawn_again(handouts):
    # six-link press, seed 7, variant 2 at 25°: e (3.1 mm from p) carries F_E = 4000 N, drawn 32 mm
    # on the lever, and G5, F_in,5 (under 1 mm); the detail redraws these, not F_E
    svg = _lever_svg(handouts, "six_link_press_forces", 7, 2, "lever-25").read_text(encoding="utf-8")
    groups = _levers(svg)
    mu = float(groups[""].get("data-mu"))
    drawn = {}
    for l in groups[""].iter(f"{SVG}line"):
        if l.get("data-quantity"):
            x1, y1, x2, y2 = (float(l.get(c)) for c in ("x1", "y1", "x2", "y2"))
            drawn[l.get("data-quantity")] = (math.hypot(x2 - x1, y2 - y1), l.get("data-from"))
    again = {l.get("data-quantity") for l in groups["pole"].iter(f"{SVG}line") if l.get("data-quantity")}
    assert drawn["F:ext:E"][0] == pytest.approx(4000.0 / mu, abs=ROUND_MM) and drawn["F:ext:E"][1] == "e"
    assert "F:ext:E" not in again
    assert {"G:5", "F:in:5"} <= again
    assert all(drawn[q][0] < 10.0 for q in again)

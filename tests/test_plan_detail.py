"""The detail ×k of a plan's pole region: drawn where images crowd the pole, measured like the
plan at μ/k, absent from a well-spread plan; Koshel's plans legible (largest vector tens of mm,
the crowd of variant 1 at 0° enlarged)."""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from plans.checking import inspect_svg
from plans.constructions.detail import CLEAR_MM, DETAIL_MIN_MM, DETAIL_MM, FACTORS, pole_crowd, pole_detail
from plans.constructions.plans import Plan, PlanPoint, PlanVector
from plans.layout import measure_layout
from plans.pipeline import read_scene, render_scene, solve_scene

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
SVG = "{http://www.w3.org/2000/svg}"
#: Two ends each rounded to the writer's 0.0005 mm: a drawn length is good to this, mm.
ROUND_MM = 2.0 * math.sqrt(2.0) * 0.0005
#: The examples whose scenes draw Koshel's sheets.
KOSHEL_SCENES = ("class3_forces", "class3_six_link", "koshel_variant1", "koshel_variant2", "triad_at_rest",
                 "triad_sliding_rod")


@pytest.fixture(scope="module")
def files() -> dict[str, str]:
    out: dict[str, str] = {}
    for name in ("class3_six_link", "four_bar", "koshel_variant1"):
        out.update(render_scene(EXAMPLES / f"{name}.toml").files)
    return out


def _groups(svg: str) -> dict[str, ET.Element]:
    root = ET.fromstring(svg)
    return {g.get("id"): g for g in root.iter(f"{SVG}g") if g.get("data-mu") is not None}


def _vectors(group: ET.Element) -> dict[str, tuple[float, float]]:
    """quantity → (drawn length mm, exact value) of a plan group's tagged lines."""
    out = {}
    for line in group.iter(f"{SVG}line"):
        q = line.get("data-quantity")
        if q:
            x1, y1, x2, y2 = (float(line.get(k)) for k in ("x1", "y1", "x2", "y2"))
            out[q] = (math.hypot(x2 - x1, y2 - y1), float(line.get("data-value")))
    return out


def _check(tmp_path: Path, name: str, svg: str):
    path = tmp_path / name
    path.write_text(svg, encoding="utf-8")
    return inspect_svg(path)


def _extent(group: ET.Element) -> float:
    """The largest width or height of a plan group's tagged lines, mm."""
    pts = np.array([[float(l.get(k)) for k in (a, b)] for l in group.iter(f"{SVG}line") if l.get("data-quantity")
                    for a, b in (("x1", "y1"), ("x2", "y2"))])
    return float(np.max(pts.max(axis=0) - pts.min(axis=0)))


# -- geometry -----------------------------------------------------------------------------------------

def _plan(points: dict[str, tuple[float, float]], vectors: list[tuple[str, str, str]], mu: float = 0.01) -> Plan:
    pts = tuple(PlanPoint(k, v) for k, v in points.items())
    vecs = tuple(PlanVector(q, points[t], points[h], mu * math.dist(points[t], points[h]), "relative")
                 for q, t, h in vectors)
    return Plan("velocity", mu, "p", pts, vecs, (), ())


def test_a_crowd_of_two_images_is_enlarged_by_the_largest_round_factor():
    plan = _plan({"p": (0.0, 0.0), "b": (1.0, 0.0), "c": (0.0, 2.0), "a": (0.0, 100.0)},
                 [("v:B", "p", "b"), ("v:C", "p", "c"), ("v:C/B", "b", "c"), ("v:A", "p", "a")])
    assert pole_crowd(plan) == (("b", "c"), 2.0)
    # the crowd reaches 2 mm from the pole: the largest factor keeping it within DETAIL_MM
    k = max(f for f in FACTORS if 2.0 * f <= DETAIL_MM)
    assert k == 20
    d = pole_detail(plan, sizes=((400.0, 400.0),), room=10.0, caption=lambda k: (40.0, 3.0))
    assert d is not None and d.k == k and d.mu == pytest.approx(plan.mu / k)
    drawn = {v.quantity: v for v in d.plan.vectors}
    assert set(drawn) == {"v:B", "v:C", "v:C/B"}            # pa leaves the region: not in the detail
    for q, length in (("v:B", 1.0), ("v:C", 2.0), ("v:C/B", math.sqrt(5.0))):
        assert drawn[q].length == pytest.approx(k * length)
        assert drawn[q].value / d.mu == pytest.approx(drawn[q].length)
    # the detail's frame keeps CLEAR_MM off the plan's vectors (pa runs along x = 0, y 0…100) and images
    cx, cy = d.centre
    to_pa = math.hypot(cx, cy - min(max(cy, 0.0), 100.0))
    assert to_pa >= d.frame + CLEAR_MM - 1e-9
    assert math.dist(d.centre, d.middle) >= d.frame + d.region + CLEAR_MM - 1e-9


def test_a_crowd_too_close_to_enlarge_or_without_a_vector_gets_no_detail():
    def detail(plan):
        return pole_detail(plan, sizes=((400.0, 400.0),), room=10.0, caption=lambda k: (40.0, 3.0))

    # 0.005 mm from the pole: × 1000 leaves 5 mm, under DETAIL_MIN_MM
    tiny = _plan({"p": (0.0, 0.0), "b": (0.005, 0.0), "c": (0.0, 0.004), "a": (0.0, 100.0)},
                 [("v:B", "p", "b"), ("v:C", "p", "c"), ("v:A", "p", "a")])
    assert pole_crowd(tiny) is not None and 1000 * 0.005 < DETAIL_MIN_MM and detail(tiny) is None
    # two images near the pole, each reached from far only: nothing to redraw
    far = _plan({"p": (0.0, 0.0), "b": (1.0, 0.0), "c": (0.0, 2.0), "a": (0.0, 100.0)},
                [("v:B/A", "a", "b"), ("v:C/A", "a", "c"), ("v:A", "p", "a")])
    assert pole_crowd(far) is not None and detail(far) is None


def test_one_image_near_the_pole_is_no_crowd():
    plan = _plan({"p": (0.0, 0.0), "b": (1.0, 0.0), "a": (0.0, 100.0)}, [("v:B", "p", "b"), ("v:A", "p", "a")])
    assert pole_crowd(plan) is None


# -- the sheets ---------------------------------------------------------------------------------------

def test_class3_velocity_at_30_has_a_detail_x10_measured_at_mu_over_k(files, tmp_path):
    svg = files["class3_six_link-velocity-30.svg"]
    groups = _groups(svg)
    plan, detail = groups["velocity-30-plan"], groups["velocity-30-detail-plan"]
    mu = float(plan.get("data-mu"))
    assert mu == 0.005
    # the images of B, C, F, S1 crowd the pole: |v_B| is the farthest, v_A is the plan's reference
    motion = solve_scene(read_scene(EXAMPLES / "class3_six_link.toml"))
    i = list(motion.values).index(30.0)
    far = max(float(np.linalg.norm(motion.velocity(p)[i])) for p in ("B", "C", "F")) / mu
    assert 3.0 < far < 5.0 < float(np.linalg.norm(motion.velocity("A")[i])) / mu
    k = max(f for f in FACTORS if far * f <= DETAIL_MM)
    assert k == 10
    assert detail.get("data-plan") == "velocity"
    assert float(detail.get("data-mu")) == pytest.approx(mu / k, rel=1e-12)
    assert f"detail ×{k}, μ" in re.sub(r"<[^>]+>", "", svg) and f"= {mu / k:g} (m/s)/mm" in svg
    drawn = _vectors(detail)
    assert {"v:B", "v:C", "v:F"} <= set(drawn) and "v:A" not in drawn and "v:S1/A" not in drawn
    for q, (length, value) in drawn.items():
        assert length == pytest.approx(value / (mu / k), abs=ROUND_MM), q
    # the detail's v:B is k times the plan's
    assert drawn["v:B"][0] == pytest.approx(k * _vectors(plan)["v:B"][0], abs=k * ROUND_MM + ROUND_MM)
    report = _check(tmp_path, "c3.svg", svg)
    assert report.ok, report.problems
    assert report.equations["velocity-30-detail-plan"] > 0    # the detail closes too
    assert measure_layout(svg).clean


def test_a_well_spread_plan_has_no_detail(files):
    for name in ("four_bar-velocity-30.svg", "four_bar-acceleration-30.svg"):
        assert "detail" not in files[name]
        assert len(_groups(files[name])) == 1


def test_koshel_variant1_at_0_is_legible(files, tmp_path):
    svg = files["koshel_variant1-koshel-0.svg"]
    groups = _groups(svg)
    plan = groups["koshel-0-plan"]
    assert _extent(plan) >= 50.0
    assert max(length for length, _ in _vectors(plan).values()) >= 50.0
    # b, c, d lie 0.2 mm from the pole on the plan: enlarged in the detail, each tens of mm there
    detail = groups["koshel-0-detail-plan"]
    k_v = float(plan.get("data-mu"))
    k = round(k_v / float(detail.get("data-mu")))
    assert k == 200 and f"detail ×{k}, K" in re.sub(r"<[^>]+>", "", svg)
    drawn = _vectors(detail)
    assert set(drawn) == {"v:B", "v:C", "v:D"}
    for q, (length, value) in drawn.items():
        assert length == pytest.approx(value / (k_v / k), abs=ROUND_MM) and length >= 20.0, q
    report = _check(tmp_path, "k.svg", svg)
    assert report.ok, report.problems
    assert measure_layout(svg).clean


@pytest.mark.parametrize("name", KOSHEL_SCENES)
def test_every_gallery_koshel_sheet_is_legible(name, tmp_path):
    sheets = {f: s for f, s in render_scene(EXAMPLES / f"{name}.toml").files.items() if "-koshel-" in f}
    assert sheets
    drawn = 0
    for f, svg in sheets.items():
        groups = _groups(svg)
        plan = next((g for i, g in groups.items() if i.endswith("koshel-" + f.split("-koshel-")[1][:-4] + "-plan")),
                    None)
        if plan is None or plan.get("data-vectors") == "0":
            continue                          # not drawn at this position (a group at rest): its sheet says why
        drawn += 1
        vectors = _vectors(plan)
        assert max(length for length, _ in vectors.values()) >= 50.0, f
        # images within 5 mm of the pole, but not at it: two or more get a detail where each is ≥ 5 mm
        crowd = [q for q, (length, _) in vectors.items() if re.fullmatch(r"v:\w+", q) and 1e-3 < length < 5.0]
        if len(crowd) >= 2:
            detail = _vectors(next(g for i, g in groups.items() if i.endswith("-detail-plan")))
            assert all(detail[q][0] >= 5.0 for q in crowd), f
        assert _check(tmp_path, f, svg).ok, f
        assert measure_layout(svg).clean, f
    assert drawn

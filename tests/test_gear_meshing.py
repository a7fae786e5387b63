"""The meshing sheet as the course draws it: one pair of profiles touching at the pitch point P,
the other teeth at the pitch, the arc of action and the specific-sliding diagram
(:func:`plans.constructions.gear_pair.meshing`), and ``plans check`` finding P on both drawn
working profiles (:func:`plans.checking_gears.contact_problems`).

The contact is checked against the wheels' outlines cut by the simulated rack cutter (shapely),
not against the involute formula that placed them; the sliding ordinates against the JSON."""

from __future__ import annotations

import json
import math
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import shapely

from plans.checking import inspect_svg
from plans.constructions.gear_pair import CUT_TOLERANCE, meshing, specific_sliding
from plans.gears.pair import analyse_pair
from plans.scene import read_scene

SVG = "{http://www.w3.org/2000/svg}"
#: The pair examples drawing a meshing sheet.
MESHING = ("pair_12_no_undercut", "pair_balanced", "pair_from_train", "pair_internal", "pair_rack")


def _analysis(stem: str):
    from plans.examples import __path__ as where
    scene = read_scene(f"{where[0]}/gears/{stem}.toml")
    return analyse_pair(scene.gear_pair, scene.gears)


@pytest.mark.parametrize("stem", MESHING)
def test_one_pair_of_cut_profiles_touches_at_p(stem):
    """P lies on the boundary of both wheels as cut (within the cut's tolerance, scaled to paper),
    the two wheels do not overlap, and the pair drawn thick passes through P."""
    a = _analysis(stem)
    s = meshing(a)
    wheels = {}
    for name, pts in s.outlines:
        key = name.split("-")[0]
        wheels.setdefault(key, []).append(shapely.Polygon(pts))
    w1, w2 = (shapely.union_all(wheels[k]) for k in ("wheel1", "wheel2"))
    p = shapely.Point(0.0, 0.0)
    tol = 10 * CUT_TOLERANCE * s.k + 1e-6             # the cut's steps, on paper
    assert w1.boundary.distance(p) <= tol and w2.boundary.distance(p) <= tol
    # touching, not cutting into each other: at most a sliver of the cut's tolerance along a tooth
    assert w1.intersection(w2).area <= tol * 2.5 * a.pair.module * s.k
    for name, kind, pts in s.curves:
        if name.startswith("working-profile"):
            assert shapely.LineString(pts).distance(p) <= 1e-9


@pytest.mark.parametrize("stem", MESHING)
def test_the_sliding_ordinates_are_the_reports(demo_rendered, stem):
    """λ1 at B2 and λ2 at B1 drawn (measured by plans check as length × μλ) equal the JSON's specific
    sliding, their sense up for a positive value; λ1 at B1 and λ2 at B2 equal the closed form."""
    report = json.loads((demo_rendered / f"{stem}.json").read_text(encoding="utf-8"))["gear_pair"]
    root = ET.parse(demo_rendered / f"{stem}-meshing.svg").getroot()
    g = next(g for g in root.iter(f"{SVG}g") if g.get("id") == "meshing-sliding")
    tags = {l.get("data-quantity"): l for l in g.iter(f"{SVG}line")}
    exact = {"λ1:B2": report["specific_sliding"]["wheel1_at_B2"], "λ2:B1": report["specific_sliding"]["wheel2_at_B1"]}
    a = _analysis(stem)
    p = a.pair
    pn1 = p.dw[0] / 2 * math.sin(p.alpha_w)
    l1, l2 = specific_sliding(a, np.array([pn1 + p.recess]))     # at B1
    m1, m2 = specific_sliding(a, np.array([pn1 - p.approach]))   # at B2
    exact.update({"λ1:B1": float(l1[0]), "λ2:B2": float(m2[0])})
    assert float(m1[0]) == pytest.approx(exact["λ1:B2"], rel=1e-12)
    for q, value in exact.items():
        line = tags[q]
        assert float(line.get("data-value")) == pytest.approx(abs(value), rel=1e-12)
        dy = float(line.get("y2")) - float(line.get("y1"))              # paper y down: up is negative
        assert dy * value <= 0
    r = inspect_svg(demo_rendered / f"{stem}-meshing.svg")
    assert r.ok, r.problems
    measured = {m.quantity: m for m in r.measurements if m.quantity.startswith("λ")}
    assert set(measured) == set(exact) and all(m.ok for m in measured.values())


def test_check_fails_a_pair_that_does_not_touch_at_p(demo_rendered, tmp_path):
    """A working profile moved 0.05 mm on the paper: P is off it, named."""
    text = (demo_rendered / "pair_12_no_undercut-meshing.svg").read_text(encoding="utf-8")
    root = ET.fromstring(text)
    path = next(e for e in root.iter(f"{SVG}path") if e.get("data-working-profile") == "2")
    path.set("d", re.sub(r"([ML])([-0-9.]+),", lambda m: f"{m.group(1)}{float(m.group(2)) + 0.05:.3f},", path.get("d")))
    bad = tmp_path / "moved.svg"
    bad.write_text(ET.tostring(root, encoding="unicode"), encoding="utf-8")
    problems = inspect_svg(bad).problems
    assert any("working profile of wheel 2" in q for q in problems), problems


@pytest.mark.parametrize("stem", ("pair_balanced", "pair_internal", "pair_rack"))
def test_the_mate_fills_the_pinions_spaces_on_the_rolling_circles(stem):
    """Without backlash, wheel 2's teeth fill wheel 1's spaces where the two roll: measured on the
    drawn outlines (wheel 1 cut by the simulated rack, wheel 2 an external wheel so cut, a ring or
    a rack), the arc each tooth of wheel 2 covers on its working circle (a rack's: its pitch line)
    equals the arc of wheel 1's space on its working circle, and the two pitches agree."""
    a = _analysis(stem)
    p = a.pair
    s = meshing(a)
    k = s.k
    polys = {}
    for name, pts in s.outlines:
        polys.setdefault(name.split("-")[0], []).append(shapely.Polygon(pts))
    w1, w2 = (shapely.union_all(polys[n]) for n in ("wheel1", "wheel2"))

    def chords(poly, circle):
        inside = poly.intersection(circle)
        parts = getattr(inside, "geoms", [inside])
        return sorted(g.length for g in parts if g.length > 0.2 * p.module * k)

    def arc(centre, radius, span, mid=0.0):
        t = np.linspace(mid - span, mid + span, 20001)
        return shapely.LineString(np.column_stack([centre[0] + radius * np.sin(t), centre[1] + radius * np.cos(t)]))

    rw1 = p.dw[0] / 2 * k
    teeth1 = chords(w1, arc((0.0, -rw1), rw1, 1.6 * 2 * math.pi / p.z[0]))
    pitch1 = math.pi * p.dw[0] / p.z[0] * k
    if p.kind == "rack":
        teeth2 = chords(w2, shapely.LineString([(-2.2 * p.p * k, 0.0), (2.2 * p.p * k, 0.0)]))
        pitch2 = p.p * k
    else:
        rw2 = p.dw[1] / 2 * k
        centre, mid = ((0.0, rw2), math.pi) if p.kind == "external" else ((0.0, -rw2), 0.0)
        teeth2 = chords(w2, arc(centre, rw2, 1.6 * 2 * math.pi / p.z[1], mid))
        pitch2 = math.pi * p.dw[1] / p.z[1] * k
    assert pitch1 == pytest.approx(pitch2, rel=1e-12)
    # chords along a polyline of 20001 points: arcs within (span/20000)²·r/8, far below the cut's tolerance
    tol = 10 * CUT_TOLERANCE * k + 1e-6
    space1 = pitch1 - teeth1[len(teeth1) // 2]
    tooth2 = teeth2[len(teeth2) // 2]
    assert tooth2 == pytest.approx(space1, abs=2 * tol)

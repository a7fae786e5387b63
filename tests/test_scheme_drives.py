"""The scheme's drives as a textbook draws them: a hydraulic cylinder as a barrel with a piston
and a piston rod, the input arrows v, a of a linear drive along its guide, and the crank's φ1,
ω1, ε1 arcs clear of each other on short cranks. Measured on the drawn SVG against the exact
positions (× 1/μl)."""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest
import shapely

from plans.constructions import scheme
from plans.drawing.text import box, runs
from plans.pipeline import solve_scene
from plans.pipeline.scales import scene_scales
from plans.scene import read_scene

from conftest import EXAMPLES, toml_text
from test_scheme import _path_points, _shape, _svg

EX = {p.stem: p for p in EXAMPLES}
#: Written coordinates carry three decimals (mm), each rounded by at most 0.0005: a written
#: point is off by at most √2·0.0005 mm, two of them (a segment's ends, or a point and the
#: paper map taken from the first pin's rounded circle) by at most 2·√2·0.0005 mm in all, and
#: by at most 2·0.0005 in either coordinate. The checks below hold to these worst cases (exact
#: by construction; the largest seen is 0.6 of them).
ROUND_MM = 2.0 * math.sqrt(2.0) * 0.0005


def _solve(path):
    scene = read_scene(path)
    motion = solve_scene(scene)
    return motion, scene_scales(scene, motion).mu_l


def _variant(tmp_path, stem: str, **drive) -> object:
    """A copy of example ``stem`` with ``drive`` keys replaced, drawing the scheme and plans."""
    data = tomllib.loads(EX[stem].read_text(encoding="utf-8"))
    data["drive"] = dict(data["drive"], **drive)
    data["plans"] = dict(data.get("plans", {}), draw=["scheme", "velocity", "acceleration"])
    path = tmp_path / f"{stem}.toml"
    path.write_text(toml_text(data), encoding="utf-8")
    return path


def _drawn(motion, mu, i):
    sch = scheme(motion, i, mu)
    els, root = _svg(sch)
    return sch, els


def _to_paper(els, sch):
    """The content → paper map, from the first pin's drawn circle (exact point ÷ μl there)."""
    p = sch.joints[0]
    c = els["s-j0"]
    dx = float(c.get("cx")) - sch.points[p][0]
    dy = float(c.get("cy")) + sch.points[p][1]
    return lambda q: np.array([q[0] + dx, dy - q[1]])


def _by_part(els, part):
    return [el for el in els.values() if el.get("data-part") == part]


def _line_ends(el):
    return (np.array([float(el.get("x1")), float(el.get("y1"))]),
            np.array([float(el.get("x2")), float(el.get("y2"))]))


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


# -- 1. the hydraulic cylinder -------------------------------------------------------------------

def test_the_boom_is_driven_by_a_barrel_with_a_piston_and_a_rod():
    motion, mu = _solve(EX["hydraulic_boom"])
    lengths = []
    for i in range(len(motion)):
        sch, els = _drawn(motion, mu, i)
        paper = _to_paper(els, sch)
        exact = {p: paper(motion.position(p)[i] / mu) for p in ("A", "B", "P")}
        (barrel,), (piston,), (rod,) = _by_part(els, "barrel"), _by_part(els, "piston"), _by_part(els, "rod")
        assert barrel.tag.endswith("polygon") and barrel.get("data-link") == "2" and rod.get("data-link") == "3"
        outline = _shape(barrel)
        corners = np.array(outline.exterior.coords[:-1])
        assert len(corners) == 4
        sides = [corners[(k + 1) % 4] - corners[k] for k in range(4)]
        unit = [v / np.linalg.norm(v) for v in sides]
        assert all(abs(float(np.dot(unit[k], unit[(k + 1) % 4]))) < 1e-3 for k in range(4))   # a rectangle
        axis = exact["B"] - exact["A"]
        axis /= np.linalg.norm(axis)
        long_side = sides[0] if np.linalg.norm(sides[0]) > np.linalg.norm(sides[1]) else sides[1]
        assert abs(_cross(long_side / np.linalg.norm(long_side), axis)) < 1e-3     # along the cylinder's axis
        assert abs(_cross(np.mean(corners, axis=0) - exact["A"], axis)) < ROUND_MM   # centred on it
        lengths.append(float(np.linalg.norm(long_side)))
        # the piston: across the barrel, inside it, at the piston head P while P is inside; the
        # barrel stops short of the rod's pin B at every position (the rod shows), so where this
        # example's rod (BP = 0.3 m, its whole stroke) has P beyond the barrel's mouth, the piston
        # is drawn at the mouth
        a, b = _line_ends(piston)
        assert not outline.buffer(ROUND_MM).contains(shapely.Point(exact["B"]))
        if outline.buffer(-0.1).contains(shapely.Point(exact["P"])):
            assert np.allclose((a + b) / 2, exact["P"], rtol=0.0, atol=ROUND_MM)
        else:
            assert float(np.dot((a + b) / 2 - exact["A"], axis)) < float(np.dot(exact["P"] - exact["A"], axis))
        assert abs(float(np.dot(b - a, axis))) < ROUND_MM
        assert outline.buffer(-0.1).contains(shapely.LineString([a, b]))
        # the rod: from the piston along the axis to the rod's pin B (exact positions ÷ μl)
        s, e = _line_ends(rod)
        assert np.allclose(s, (a + b) / 2, rtol=0.0, atol=ROUND_MM)
        assert np.allclose(e, exact["B"], rtol=0.0, atol=ROUND_MM)
        assert abs(_cross((e - s) / np.linalg.norm(e - s), axis)) < 1e-4
    assert max(lengths) - min(lengths) <= 2 * ROUND_MM   # one barrel at every position (two lengths, each ROUND_MM)


def test_with_a_short_stroke_the_pin_stays_outside_the_barrel(tmp_path):
    """Strokes 0 … 0.12 m leave room: the barrel holds the piston and stops short of pin B."""
    motion, mu = _solve(_variant(tmp_path, "hydraulic_boom", displacement=[0.0, 0.06, 0.12]))
    for i in range(len(motion)):
        sch, els = _drawn(motion, mu, i)
        paper = _to_paper(els, sch)
        outline = _shape(_by_part(els, "barrel")[0])
        b = shapely.Point(paper(motion.position("B")[i] / mu))
        assert not outline.contains(b) and outline.distance(b) > 2.0
        assert outline.contains(shapely.Point(paper(motion.position("P")[i] / mu)))


def test_the_oscillating_cylinder_is_drawn_as_a_cylinder_too():
    motion, mu = _solve(EX["oscillating_cylinder"])
    sch, els = _drawn(motion, mu, 0)
    (barrel,) = _by_part(els, "barrel")
    assert barrel.get("data-link") == "3" and _by_part(els, "rod")[0].get("data-link") == "2"
    assert "s-link2" not in els and "s-link3" not in els    # no bare bars under the cylinder
    outline = _shape(barrel)
    for p in ("C",):
        assert outline.exterior.distance(shapely.Point(_to_paper(els, sch)(sch.points[p]))) < 2.6


def test_a_slider_crank_keeps_its_block():
    motion, mu = _solve(EX["crank_slider_central"])
    sch, els = _drawn(motion, mu, 0)
    assert sch.cylinders == () and not _by_part(els, "barrel") and sch.inputs == ()


# -- 2. the input arrows of a linear drive ------------------------------------------------------

def _arrow(els, kind: str, link: str):
    el = els[f"s-input{kind}{link}"]
    s, e = _line_ends(el)
    head = els[f"s-input{kind}{link}h"]
    assert head.get("data-for") == f"s-input{kind}{link}"
    tip = max(_path_points(head.get("d")), key=lambda p: float(np.linalg.norm(np.subtract(p, s))))
    label = "".join(els[f"s-input{kind}{link}l"].itertext())
    return s, np.array(tip), label


def test_a_slider_drive_has_its_speed_arrow_along_the_guide():
    motion, mu = _solve(EX["elliptic_trammel"])       # slider 1 on the horizontal guide, v = 1 m/s, a = 0
    sch, els = _drawn(motion, mu, 0)
    s, tip, label = _arrow(els, "v", "1")
    assert label == "v1" and "s-inputa1" not in els
    d = tip - s
    assert abs(d[1]) < ROUND_MM and d[0] > 10.0       # along +x (paper y down): the sense of v > 0
    # beside the block, on the side away from the hatching (above it: smaller paper y)
    block = _shape(els["s-block1"])
    assert block.distance(shapely.LineString([s, tip])) > 2.0 and s[1] < block.bounds[1]


def test_a_slider_drive_backwards_points_back_and_shows_a(tmp_path):
    motion, mu = _solve(_variant(tmp_path, "elliptic_trammel", velocity=-1.0, acceleration=3.0))
    sch, els = _drawn(motion, mu, 0)
    s, tip, label = _arrow(els, "v", "1")
    assert label == "v1" and tip[0] < s[0] - 10.0
    s, tip, label = _arrow(els, "a", "1")
    assert label == "a1" and tip[0] > s[0] + 10.0


def test_the_cylinder_drive_has_v32_and_a32_along_its_axis():
    motion, mu = _solve(EX["hydraulic_boom"])         # v = 0.05 m/s, a = 0.02 m/s²: the rod extends
    sch, els = _drawn(motion, mu, 2)
    paper = _to_paper(els, sch)
    axis = paper(sch.points["B"]) - paper(sch.points["A"])
    axis /= np.linalg.norm(axis)
    for kind in ("v", "a"):
        s, tip, label = _arrow(els, kind, "3")
        assert label == f"{kind}32"
        d = (tip - s) / np.linalg.norm(tip - s)
        assert abs(_cross(d, axis)) < 1e-3 and float(np.dot(d, axis)) > 0.99
        for part in ("barrel", "rod"):
            assert _shape(_by_part(els, part)[0]).distance(shapely.LineString([s, tip])) > 1.5


# -- 3. the crank's arcs on short cranks -----------------------------------------------------

def _label_box(el):
    text = "".join(el.itertext())
    return box(runs(text, digits=False), float(el.get("font-size")), el.get("font-style") == "italic",
               float(el.get("x")), float(el.get("y")))


def _overlap(a, b) -> bool:
    return not (a.x1 <= b.x0 or b.x1 <= a.x0 or a.y1 <= b.y0 or b.y1 <= a.y0)


@pytest.mark.parametrize("stem,angle,epsilon", [("six_link_press", 60.0, 0.0), ("six_link_press", 60.0, 40.0),
                                                ("quick_return", 30.0, 0.0), ("quick_return", 30.0, -25.0)])
def test_the_crank_arcs_keep_clear_of_each_other(tmp_path, stem, angle, epsilon):
    motion, mu = _solve(_variant(tmp_path, stem, epsilon=epsilon))
    i = [round(float(v), 6) for v in motion.values].index(angle)
    sch, els = _drawn(motion, mu, i)
    kinds = ["phi", "omega"] + (["epsilon"] if epsilon else [])
    assert sorted(a.kind for a in sch.arcs) == sorted(kinds)
    labels = {k: _label_box(els[f"s-{k}1l"]) for k in kinds}
    crank = [_label_box(els[f"s-p{k}"]) for k, p in enumerate(sch.points) if p in ("O", "A")]
    crank.append(_label_box(els["s-n1"]))
    for a in kinds:
        for b in kinds:
            if a < b:
                assert not _overlap(labels[a], labels[b]), (a, b)
        assert not any(_overlap(labels[a], c) for c in crank), a
    # the arcs (φ1 with its reference line) do not cross each other, nor any pin but the pivot's
    shapes = {k: _shape(els[f"s-{k}1"]) for k in kinds}
    shapes["phi"] = shapes["phi"].union(_shape(els["s-phi1ref"]))
    for a in kinds:
        for b in kinds:
            if a < b:
                assert shapes[a].distance(shapes[b]) > 1.0, (a, b)
    pivot = sch.joints.index(sch.drive_pivot)
    for k in range(len(sch.joints)):
        if k != pivot:
            pin = _shape(els[f"s-j{k}"])
            assert all(shapes[a].distance(pin) > 0.8 for a in kinds if a != "phi")
    # the arc arrows keep clear of every other link's line
    for name, pts in sch.links:
        if name != "1" and f"s-link{name}" in els:
            assert all(shapes[a].distance(_shape(els[f"s-link{name}"]).boundary
                       if els[f"s-link{name}"].tag.endswith("polygon") else _shape(els[f"s-link{name}"])) > 0.8
                       for a in ("omega", "epsilon") if a in kinds), name


@pytest.mark.parametrize("stem", ["hydraulic_boom", "oscillating_cylinder"])
def test_no_label_sits_in_a_barrel(stem):
    """Labels keep out of the barrel (the rod shows inside it): no text box meets its inside."""
    motion, mu = _solve(EX[stem])
    for i in range(len(motion)):
        sch, els = _drawn(motion, mu, i)
        inside = _shape(_by_part(els, "barrel")[0]).buffer(-0.35)      # within the outline's stroke
        for el in els.values():
            if el.get("class") == "label" and el.tag.endswith("text") and el.get("x"):
                b = _label_box(el)
                assert not inside.intersects(shapely.box(b.x0, b.y0, b.x1, b.y1)), (i, "".join(el.itertext()))


def test_the_scheme_with_a_cylinder_is_byte_identical_when_drawn_again():
    from plans.drawing import Heading
    from plans.drawing.svg import draw_scheme
    motion, mu = _solve(EX["hydraulic_boom"])
    texts = [draw_scheme(scheme(motion, 1, mu), Heading("m", "Kinematic scheme", "p"), formula="f", ident="s")
             for _ in range(2)]
    assert texts[0] == texts[1] and "data-part=\"barrel\"" in texts[0]

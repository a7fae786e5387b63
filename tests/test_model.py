"""The model's link shapes: exact where the sketch is exact, exact to rounding on a link's line."""

from __future__ import annotations

import math

import numpy as np
import pytest

from plans.errors import SceneError
from plans.kinematics import analyse
from plans.model import build_mechanism
from plans.scene import parse_scene
from plans.structure import analyse_structure

EPS = np.finfo(float).eps


def _crank_slider(lengths: dict, extra: dict | None = None, frame: list | None = None) -> dict:
    """Crank OA 0.1 at 30°, rod AB 0.4 with M its midpoint (a centre of mass on the rod's line)."""
    a = [0.1 * math.cos(math.radians(30.0)), 0.1 * math.sin(math.radians(30.0))]
    bx = a[0] + math.sqrt(0.4 ** 2 - a[1] ** 2)
    pts = {"O": [0.0, 0.0], "A": a, "B": [bx, 0.0], "M": [(a[0] + bx) / 2, a[1] / 2]} | (extra or {})
    return {"points": pts,
            "links": {"0": frame or ["O"], "1": ["O", "A"], "2": ["A", "B", "M"], "3": ["B"]},
            "sliders": [{"link": "3", "on": "0", "through": "B", "angle": 0.0}],
            "drive": {"link": "1", "angle": [30.0, 75.0, 200.0], "omega": 10.0},
            "lengths": lengths}


def _off_line(p, a, b) -> float:
    """Distance (m) of p from the line ab."""
    u = (b - a) / np.linalg.norm(b - a)
    return abs(float(u[0] * (p - a)[1] - u[1] * (p - a)[0]))


@pytest.mark.parametrize("lengths", [{"OA": 0.1, "AB": 0.4, "AM": 0.2, "BM": 0.2}, {"AB": 0.4, "AM": 0.2}])
def test_point_on_a_rods_line_stays_on_it_to_rounding(lengths):
    mech = build_mechanism(parse_scene(_crank_slider(lengths)))
    local = mech.links["2"].local
    size = mech.size
    assert _off_line(local["M"], local["A"], local["B"]) <= 4 * EPS * size
    am = lengths["AM"]
    assert abs(np.linalg.norm(local["M"] - local["A"]) - am) <= 4 * EPS * am
    motion = analyse(mech, analyse_structure(mech), order=2)
    for i in range(len(motion)):
        r = {p: motion.position(p)[i] for p in "ABM"}
        assert _off_line(r["M"], r["A"], r["B"]) <= 8 * EPS * size
        # M's velocity and acceleration follow A and B linearly (it divides AB in a fixed ratio)
        t = am / lengths["AB"]
        for f in (motion.velocity, motion.acceleration):
            want = (1 - t) * f("A")[i] + t * f("B")[i]
            assert np.linalg.norm(f("M")[i] - want) <= 64 * EPS * max(np.linalg.norm(f("A")[i]),
                                                                       np.linalg.norm(f("B")[i]))


def test_frame_points_are_exactly_where_the_sketch_puts_them():
    """Collinear frame points (a guide's line) and every point of a link without [lengths]."""
    extra = {"C": [0.7, 0.0], "D": [1.0 / 3.0, 0.0], "E": [0.123456789, 1e-17]}
    scene = _crank_slider({}, extra, frame=["O", "C", "D", "E"])
    mech = build_mechanism(parse_scene(scene))
    for name, link in mech.links.items():
        for p, xy in link.local.items():
            assert xy.tolist() == [float(c) for c in scene["points"][p]], (name, p)


def test_collinear_lengths_beyond_the_end():
    """A point on the rod's line beyond B (AK = AB + BK exactly) is on the line, not 1e-8 off it."""
    scene = _crank_slider({"AB": 0.4, "AM": 0.6, "BM": 0.2})
    scene["points"]["M"] = [2 * scene["points"]["B"][0] - scene["points"]["A"][0] - 0.1,
                            -scene["points"]["A"][1] + 0.01]   # sketched roughly; lengths decide
    mech = build_mechanism(parse_scene(scene))
    local = mech.links["2"].local
    assert _off_line(local["M"], local["A"], local["B"]) <= 4 * EPS * mech.size
    assert abs(np.linalg.norm(local["M"] - local["A"]) - 0.6) <= 4 * EPS


def test_impossible_triangle_is_refused():
    with pytest.raises(SceneError, match="cannot form a triangle"):
        build_mechanism(parse_scene(_crank_slider({"AB": 0.4, "AM": 0.1, "BM": 0.2})))

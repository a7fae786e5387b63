"""Instantaneous centres at their edges: a link at rest up to rounding at a stationary instant
found by root-finding has no centre (null in the JSON, listed as at rest, said on the sheet), a
point named like a centre (P3) does not join the centre's segments, and a point named like the
image of another point on a sliding link (A3) is refused."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

import plans
from plans.checking import inspect_svg
from plans.kinematics.centres import REST_RTOL

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _at(scene, phi: float, draw=("scheme", "velocity", "centres")):
    s = dataclasses.replace(scene, drive=dataclasses.replace(scene.drive, values=(phi,)), draw=draw)
    return plans.render(s, stem="t")


def _stationary_instant() -> float:
    """Where the triad of triad_at_rest stands again (the rod folded back over the crank): the
    root of ω5(φ) between 185° and 190°, by bisection on the solved motion."""
    scene = plans.read_scene(EXAMPLES / "triad_at_rest.toml")

    def w5(phi):
        return float(_at(scene, phi, ("velocity",)).motion.links["5"].omega[0])

    a, b = 185.0, 190.0
    fa = w5(a)
    assert fa * w5(b) < 0
    for _ in range(60):
        m = 0.5 * (a + b)
        fm = w5(m)
        if fm == 0.0:
            return m
        a, b, fa = (m, b, fm) if (fm < 0) == (fa < 0) else (a, m, fa)
    return 0.5 * (a + b)


def test_a_triad_at_rest_at_a_root_found_instant_has_no_centre(tmp_path):
    phi = _stationary_instant()
    assert abs(phi - 180.0) > 1.0                 # not the sketched instant, nor a round angle
    scene = plans.read_scene(EXAMPLES / "triad_at_rest.toml")
    sheets = _at(scene, phi)
    m = sheets.motion
    speed = 0.5                                   # |v_A| = ω1·OA
    for link in ("3", "4", "5"):
        assert abs(float(m.links[link].omega[0])) * m.mechanism.size < REST_RTOL * speed   # rest, up to rounding
    pos = sheets.report["positions"][0]
    assert pos["centres_at_rest"] == ["3", "4", "5"]
    assert all(pos["centres"][k] is None for k in ("3", "4", "5"))
    assert pos["centres"]["2"] is not None        # the rod turns about B
    sheets.save(tmp_path)
    svg = tmp_path / "t-centres.svg"
    assert "links 3, 4, 5 at rest at this instant" in svg.read_text(encoding="utf-8")
    assert inspect_svg(svg).ok
    # a step away the links move again, and have centres
    pos = _at(scene, phi + 0.5).report["positions"][0]
    assert "centres_at_rest" not in pos and pos["centres"]["5"] is not None


def test_the_special_points_cross_check_holds_near_the_stationary_instant():
    # the two solutions of the class III group agree relative to the mechanism's velocities, so
    # an instant a hair from rest is not "please report"
    scene = plans.read_scene(EXAMPLES / "triad_at_rest.toml")
    phi = _stationary_instant()
    for d in (1e-9, 1e-6, 1e-3):
        _at(scene, phi + d)


def test_centres_of_a_four_bar_with_a_point_named_p3_pass_check(tmp_path):
    text = (EXAMPLES / "four_bar.toml").read_text(encoding="utf-8")
    import re
    text = re.sub(r"\bB\b", "P3", text)
    text = text.replace("AB = ", "A-P3 = ").replace("BC = ", "P3-C = ").replace("BM = ", "P3-M = ")
    text = re.sub(r'draw = \[[^\]]*\]', 'draw = ["scheme", "velocity", "centres"]', text)
    scene = tmp_path / "p3.toml"
    scene.write_text(text, encoding="utf-8")
    sheets = plans.render(scene)
    sheets.save(tmp_path / "out")
    files = sorted((tmp_path / "out").glob("*-centres-*.svg"))
    assert files
    for f in files:
        r = inspect_svg(f)
        assert r.ok, (f.name, [c for c in r.closures if not c.ok])
        assert 'data-quantity="r:P3/P3′"' in f.read_text(encoding="utf-8")


def test_a_point_named_like_an_image_on_a_sliding_link_is_refused(tmp_path):
    text = (EXAMPLES / "whitworth.toml").read_text(encoding="utf-8")
    text = text.replace("[links]", "A3 = [0.3, 0.3]\n\n[links]", 1).replace('1 = ["O", "A"]', '1 = ["O", "A", "A3"]')
    scene = tmp_path / "w.toml"
    scene.write_text(text, encoding="utf-8")
    with pytest.raises(plans.SceneError) as err:
        plans.read_scene(scene)
    assert err.value.key == "points.A3" and "link 3 now at A" in str(err.value)

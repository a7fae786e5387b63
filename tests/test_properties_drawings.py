"""Property tests of the drawings of random class II mechanisms.

* drawings: every SVG of ``render_scene`` passes ``check_svg`` and its ``v:X``/``a:X``
  values are the finite-difference-checked magnitudes (``check`` of ``test_properties.py``),
  for every form at random, near-singular and dead-centre positions.

Two bugs found here are fixed and kept as tests: a slider of a group on a known turning guide
(``SLIDER_ON_TURNING_GUIDE``), and an RPP group turning with a known guide (``RPP_TURNING``),
once a strict xfail.
"""

from __future__ import annotations

import json
import math
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from conftest import toml_text
from plans.checking import check_svg
from plans.pipeline import render_scene

from property_cases import Case, build_prp, build_rpp_turning, build_rrp
from property_strategies import cases
#: autouse, module scope: prints ``WORST`` at the end of this module (imported, so ruff sees no use)
from test_properties import _report  # noqa: F401
from test_properties import COMMON, check

#: with filterwarnings = error, hypothesis' report of a failing example (its patch writer
#: imports libcst → mypy_extensions, deprecated) would turn into an INTERNALERROR hiding it
pytestmark = pytest.mark.filterwarnings("ignore:mypy_extensions.TypedDict is deprecated:DeprecationWarning")


# --- drawings: every plan of a random mechanism passes `plans check` --------------------------------

def test_toml_writer_round_trips():
    import tomllib

    case = build_rrp(r=0.1, alpha=0.2, e=-0.01, rod=0.3, phi=1.0, branch=1.0, coupler=(0.5, 0.2), omega=-7.0,
                     epsilon=1e-05)
    assert tomllib.loads(toml_text(case.scene)) == case.scene


def check_drawings(case: Case) -> None:
    """render_scene on the scene written as TOML: every SVG's tagged vectors, measured and
    multiplied by μ, equal their data-value (check_svg), and the data-value of every absolute
    vector v:X, a:X is |v_X|, |a_X| of the motion checked by ``check`` against finite
    differences."""
    motion = check(case)
    scene = dict(case.scene, plans={"draw": ["scheme", "velocity", "acceleration"]})
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "random.toml"
        path.write_text(toml_text(scene), encoding="utf-8")
        rendered = render_scene(path)
        svgs = {name: text for name, text in rendered.files.items() if name.endswith(".svg")}
        assert {n.split("-")[1].split(".")[0] for n in svgs} == {"scheme", "velocity", "acceleration"}
        points = set(case.scene["points"])
        n_absolute = 0
        for name, text in svgs.items():
            svg = Path(tmp) / name
            svg.write_text(text, encoding="utf-8")
            for meas in check_svg(svg):
                assert meas.ok, f"{name}: {meas.quantity} measures {meas.measured:.6g}, value {meas.value:.6g}"
                kind, _, point = meas.quantity.partition(":")
                if point in points and kind in ("v", "a"):
                    exact = (motion.velocity if kind == "v" else motion.acceleration)(point)[0]
                    assert meas.value == pytest.approx(float(np.linalg.norm(exact)), rel=1e-12)
                    n_absolute += 1
        assert n_absolute >= 2       # at least the crank pin's v and a
    data = json.loads(rendered.files["random.json"])
    assert len(data["positions"]) == 1


#: every form; RPP only as Scotch yokes (see test_drawings_rpp_turning_with_a_known_guide)
DRAWABLE = {"RRR": cases("RRR"), "RRP frame guide": cases("RRP", variant="frame guide"),
            "RRP crank slot": cases("RRP", variant="crank slot"), "RPR": cases("RPR"), "PRP": cases("PRP"),
            "RPP yoke": cases("RPP", variant="yoke")}


@pytest.mark.parametrize("kind", list(DRAWABLE))
@settings(max_examples=12, **COMMON)
@given(data=st.data())
def test_drawings_pass_plans_check(kind, data):
    """Four-bars, crank-sliders, rods on a crank slot, slotted levers, tangent mechanisms and
    Scotch yokes, at random, near-singular and dead-centre positions: the rendered plans pass
    `plans check` with the exact values."""
    check_drawings(data.draw(DRAWABLE[kind], label="case"))


#: Regression (fixed in 6fe062e): a slider of the group on a known turning guide (slot in the
#: crank). The acceleration plan's line parallel to the guide must pass through the tip of the
#: Coriolis vector drawn from the guide point's known image, e1 + 2ω×(v_E3 − v_E1); plans drew
#: it from the slider's (unknown) image, so the line passed through e1 itself, |a^k|/μa off the
#: right one, and render_scene's own geometric check refused the plan.
SLIDER_ON_TURNING_GUIDE = {
    # the falsifying example of test_drawings_pass_plans_check
    "RRP rod on a crank slot, E off the slot": Case(
        "RRP", {"title": "random rod on a crank slot",
                "points": {"O": [0.0, 0.0], "K": [-0.9682458365518543, 0.25000000000000006], "C": [1.0, 0.0],
                           "E": [0.5182372542187895, -0.13380828366490877]},
                "links": {"0": ["O", "C"], "1": ["O", "K"], "2": ["C", "E"], "3": ["E"]},
                "sliders": [{"link": "3", "on": "1", "through": "O", "angle": -194.47751218592992}],
                "drive": {"link": "1", "angle": -194.47751218592992, "omega": 1.0, "epsilon": 0.0}},
        -194.47751218592992, note="found by hypothesis"),
    "PRP tangent mechanism, offset slot": build_prp(r=0.3, kappa=0.2, c=0.05, beta=math.pi / 2, e=-0.15, phi=0.5,
                                                   omega=5.0, epsilon=0.0),
    # the slot through O: a_B1 = −ω²·OB lies on the slot, the wrong line passed through the pole
    # and met the frame guide's line there — drawn "right" by accident unless ε ≠ 0
    "PRP tangent mechanism, slot through O, epsilon != 0": build_prp(r=0.3, kappa=0.0, c=0.0, beta=math.pi / 2,
                                                                    e=-0.15, phi=0.5, omega=5.0, epsilon=30.0),
}


@pytest.mark.parametrize("name", list(SLIDER_ON_TURNING_GUIDE))
def test_drawings_slider_on_a_known_turning_guide(name):
    check_drawings(SLIDER_ON_TURNING_GUIDE[name])


#: An RPP group turning with a known guide: link 3 slides on the crank's slot, link 2 (pinned to
#: the frame at C) slides in a slot of link 3. The plans once drew the group's two sliding
#: relations for two different points of link 3 — C3 (pair 2/3) and Q3 (pair 3/1, labelled by
#: link 3's own point Q) — whose images differ because link 3 turns, so the two construction
#: lines met at neither image. (The Scotch yoke's link 3 only translates, so its points share
#: one image and the plan worked.)
RPP_TURNING = {
    "RPP on a crank slot": build_rpp_turning(r=0.3, kappa=0.3, gamma=1.6, c=np.array([0.1, 0.2]),
                                             q=np.array([0.15, 0.05]), phi=0.3, omega=9.0, epsilon=30.0),
    "RPP on a crank slot, Q on the crank's slot": build_rpp_turning(
        r=0.3, kappa=0.0, gamma=math.radians(100.0), c=np.array([0.1, 0.2]), q=np.array([0.1, 0.0]), phi=0.4,
        omega=9.0, epsilon=0.0),
}


@pytest.mark.parametrize("name", list(RPP_TURNING))
def test_drawings_rpp_turning_with_a_known_guide(name):
    """Once a strict xfail: both sliding relations are now written for the outer pin D of the
    group, so their construction lines meet at its image d3."""
    check_drawings(RPP_TURNING[name])


def test_rpp_turning_with_a_known_guide_kinematics_are_right():
    """The same mechanisms pass every kinematic check."""
    for case in RPP_TURNING.values():
        check(case)

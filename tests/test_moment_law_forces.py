"""A moment given as a law in the crank angle (``[[moments]] law``) in the force analysis: the
force plans, the lever and [balance] take its value at each position's turned angle θ_k = k·360°/N
over a cycle of one turn (issue 35 item 3). Over a cycle of several turns a crank position is at
several angles of the cycle, so they are refused in one line.

Checked three ways: against the same scene with the law replaced by a constant moment equal to
the law's value at that position (read off its table by hand); against the machine's reduced
moment (with no masses the balancing moment is −M_r at every position); and the lever's moment
against the force plans' (the pipeline's own agreement check, asserted here at 1e-12).
"""

from __future__ import annotations

import tomllib

import numpy as np
import pytest

from conftest import CRANK_SLIDER_MACHINE, refused_line
from plans.pipeline import render
from plans.scene import parse_scene

#: The rod's moment: (θ°, N·m CCW) linear between; 0 at the cycle's start (the slider's outer extreme).
LAW = [[0.0, 0.0], [90.0, 40.0], [200.0, -30.0], [360.0, 0.0]]


def _scene(moment: str, at: str = "[0, 3, 4, 7, 11]", period: str = "") -> str:
    return 'title = "crank-slider, a moment law on the rod"\n' + CRANK_SLIDER_MACHINE + f"""[[forces]]
link = "3"
at = "B"
vector = [-1000.0, 0.0]
[[moments]]
link = "2"
{moment}
[dynamics]
delta = 0.05
{period}
[plans]
output = "3"
at = {at}
draw = ["forces", "lever", "dynamics"]
"""


def _law_at(theta: float) -> float:
    """LAW at θ (degrees), interpolated by hand."""
    for (x0, y0), (x1, y1) in zip(LAW, LAW[1:]):
        if x0 <= theta <= x1:
            return y0 + (y1 - y0) * (theta - x0) / (x1 - x0)
    raise AssertionError(theta)


@pytest.fixture(scope="module")
def report():
    return render(parse_scene(tomllib.loads(_scene(f"law = {LAW}")))).report


def _balancing(positions) -> list[float]:
    """M_b of the force plans (N·m) at each position of the cycle, θ_k = 30°·k from its start
    (the slider's extreme at φ = 180°)."""
    return [p["forces"]["balance"]["moment"] for p in positions]


def test_the_law_acts_as_its_value_at_each_position(report):
    law = _balancing(report["positions"])
    assert [p["angle"] for p in report["positions"]] == [(180.0 + 30.0 * k) % 360.0 for k in range(12)]
    for k in (0, 3, 4, 7, 11):
        constant = render(parse_scene(tomllib.loads(_scene(f"value = {_law_at(30.0 * k)!r}", at=f"[{k}]")))).report
        assert law[k] == pytest.approx(_balancing(constant["positions"])[k], rel=1e-12, abs=1e-12 * 100.0), k
    for k, p in enumerate(report["positions"]):         # the JSON gives the law's value at each position
        assert p["forces"]["moments"] == {"2": pytest.approx(_law_at(30.0 * k), rel=1e-12, abs=1e-12)}


def test_the_balancing_moment_is_minus_the_reduced_moment(report):
    """No masses: M_b + M_r = 0 at every position (M_r from the dynamics' own reading of the law)."""
    reduced = report["cycle"]["dynamics"]["reduced_moment"]
    for k, mb in enumerate(_balancing(report["positions"])):
        assert mb == pytest.approx(-reduced[k], rel=1e-12, abs=1e-12 * 100.0)
    for p in report["positions"]:
        f = p["forces"]
        assert f["lever"]["moment"] == pytest.approx(f["balance"]["moment"], rel=1e-12, abs=1e-12 * 100.0)


def test_the_law_changes_the_answer(report):
    """The rod's moment matters where the rod turns: at position 4 (θ = 120°, φ = 300°) the
    law's 20.9 N·m on the rod moves M_b away from the force's alone."""
    none = render(parse_scene(tomllib.loads(_scene("value = 0.0", at="[4]")))).report
    assert abs(_balancing(report["positions"])[4] - _balancing(none["positions"])[4]) > 1.0
    assert np.isclose(_law_at(120.0), 40.0 - 70.0 * 30.0 / 110.0)


def test_several_turns_are_refused_in_one_line(tmp_path):
    line = refused_line(tmp_path, _scene("law = [[0, 0], [360, 40], [720, 0]]", period="period = 720"))
    assert "moments[0].law" in line and "period = 360" in line and "2 angles of the cycle" in line

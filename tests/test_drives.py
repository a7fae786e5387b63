"""Drives inside the chain: a coupler's absolute angle and a hydraulic cylinder's stroke.

Each is checked against what does not share its solver: the drive's own coordinate read
back from the solved poses, finite differences of the positions (v = dX/dq·q̇,
a = d²X/dq²·q̇² + dX/dq·q̈), and the same mechanism solved with a crank (closed-form class II
groups) at the crank angle the coupler drive produced.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from plans.cli import main
from plans.errors import AssemblyError, SceneError, StructureError
from plans.kinematics import analyse
from plans.model import build_mechanism
import tomllib

from plans.scene import DriveKind, parse_scene as _parse_mapping
from plans.structure import analyse_structure

from conftest import EXAMPLES

COUPLER = next(p for p in EXAMPLES if p.stem == "four_bar_coupler_drive")
CYLINDER = next(p for p in EXAMPLES if p.stem == "hydraulic_boom")
FOUR_BAR = next(p for p in EXAMPLES if p.stem == "four_bar")


def parse_scene(text: str):
    return _parse_mapping(tomllib.loads(text))


def _solve(text: str, values, order: int = 2):
    mech = build_mechanism(parse_scene(text))
    return analyse(mech, analyse_structure(mech), np.asarray(values, dtype=float), order=order)


def _angle(motion, a: str, b: str) -> np.ndarray:
    d = motion.position(b) - motion.position(a)
    return np.degrees(np.arctan2(d[:, 1], d[:, 0]))


def _fd_check(text: str, values: np.ndarray, h: float, rate_scale: float, speed: float, accel: float,
              points) -> None:
    """Velocities and accelerations against central differences of positions over the drive's
    coordinate q (degrees for an angle: dq/dt = ω·180/π)."""
    motion = _solve(text, values)
    plus, minus = _solve(text, values + h, 0), _solve(text, values - h, 0)
    qdot, qddot = speed * rate_scale, accel * rate_scale
    for p in points:
        x0, xp, xm = motion.position(p), plus.position(p), minus.position(p)
        d1 = (xp - xm) / (2 * h)
        d2 = (xp - 2 * x0 + xm) / (h * h)
        v, a = motion.velocity(p), motion.acceleration(p)
        scale_v = np.max(np.linalg.norm(v, axis=1))
        scale_a = np.max(np.linalg.norm(a, axis=1))
        assert np.max(np.abs(v - d1 * qdot)) <= 1e-7 * scale_v, p
        assert np.max(np.abs(a - (d2 * qdot ** 2 + d1 * qddot))) <= 1e-5 * scale_a, p


# --- coupler -----------------------------------------------------------------------------------

def test_coupler_drive_structure_and_kind():
    mech = build_mechanism(parse_scene(COUPLER.read_text()))
    st = analyse_structure(mech)
    assert mech.drive.kind == DriveKind.COUPLER
    assert st.formula == "I(0-1-2-3)" and st.groups == ()
    assert set(st.driven.links) == {"1", "2", "3"}


def test_coupler_angle_is_held():
    values = np.array([36.0, 42.0, 48.0, 53.0, 58.0, 64.0])
    motion = _solve(COUPLER.read_text(), values)
    assert np.max(np.abs(_angle(motion, "A", "B") - values)) < 1e-10
    assert np.all(motion.links["2"].omega == 2.0) and np.all(motion.links["2"].epsilon == -4.0)


def test_coupler_drive_finite_differences():
    values = np.array([36.0, 45.0, 53.0, 61.0])
    _fd_check(COUPLER.read_text(), values, 1e-3, 180.0 / math.pi, 2.0, -4.0, ["A", "B", "M"])


def test_coupler_drive_agrees_with_the_crank_driven_four_bar():
    """Solve by the coupler's angle, read the crank angle, solve the crank-driven four-bar
    (closed-form RRR group) there with ω1 chosen so that ω2 comes out the same: every point's
    position and velocity agree."""
    values = np.array([36.0, 48.0, 60.0])
    by_coupler = _solve(COUPLER.read_text(), values, 1)
    crank = _angle(by_coupler, "O", "A")
    text = FOUR_BAR.read_text().replace("angle = [0.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0, 210.0, 240.0, "
                                        "270.0, 300.0, 330.0]", "angle = [0.0]")
    for k, phi in enumerate(crank):
        w1 = float(by_coupler.links["1"].omega[k])
        by_crank = _solve(text.replace("omega = 10.0", f"omega = {w1!r}"), [phi], 1)
        for p in ("A", "B", "M"):
            assert np.allclose(by_crank.position(p)[0], by_coupler.position(p)[k], atol=1e-12, rtol=0)
            assert np.allclose(by_crank.velocity(p)[0], by_coupler.velocity(p)[k], atol=1e-12, rtol=0)
        assert abs(float(by_crank.links["2"].omega[0]) - 2.0) < 1e-12


def test_coupler_beyond_its_range_is_refused_clearly():
    text = COUPLER.read_text().replace("angle = [36.0, 42.0, 48.0, 53.0, 58.0, 64.0]", "angle = [75.0]")
    with pytest.raises(AssemblyError) as err:
        _solve(text, [75.0])
    assert "I(0-1-2-3)" in str(err.value)


# --- hydraulic cylinder --------------------------------------------------------------------------

def test_cylinder_structure():
    mech = build_mechanism(parse_scene(CYLINDER.read_text()))
    st = analyse_structure(mech)
    assert mech.drive.kind == DriveKind.CYLINDER
    assert st.formula == "I(0-2-3-4) ← II(5-6)"


def test_cylinder_stroke_and_closed_form():
    """The rod's eye B lies at |AB| = |AB|₀ + s from the cylinder's pivot (A, P, Q, B on the
    axis), and on the circle of the boom about O: the two circles' intersection on the
    sketch's side is B, computed here without the solver."""
    values = np.array([-0.06, -0.02, 0.0, 0.04, 0.06])
    motion = _solve(CYLINDER.read_text(), values)
    scene = parse_scene(CYLINDER.read_text())
    A, O, B0 = (np.array(scene.points[k]) for k in "AOB")
    r1 = np.linalg.norm(B0 - A) + values
    r2 = np.linalg.norm(B0 - O)
    d = np.linalg.norm(A - O)
    x = (d * d + r1 ** 2 - r2 ** 2) / (2 * d)
    y = np.sqrt(r1 ** 2 - x ** 2)
    e = (O - A) / d
    n = np.array([-e[1], e[0]])
    side = np.sign(np.dot(B0 - A, n))
    expected = A + x[:, None] * e + side * y[:, None] * n
    assert np.max(np.abs(motion.position("B") - expected)) < 1e-12
    # the rod stays on the cylinder's axis: P, Q, A, B collinear
    for p in ("P", "Q"):
        u, w = motion.position("B") - motion.position("A"), motion.position(p) - motion.position("A")
        assert np.max(np.abs(u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0])) < 1e-8   # the sketch's 9 decimals


def test_cylinder_drive_finite_differences():
    values = np.array([-0.05, 0.0, 0.05])
    _fd_check(CYLINDER.read_text(), values, 1e-5, 1.0, 0.05, 0.02, ["B", "P", "Q", "D", "E"])


def test_cylinder_report_sliding_is_the_drive(tmp_path):
    assert main(["render", str(CYLINDER), "-o", str(tmp_path), "-q"]) == 0
    report = json.loads((tmp_path / "hydraulic_boom.json").read_text())
    for pos in report["positions"]:
        slide = pos["sliders"]["3/2"]
        assert abs(slide["s"] - pos["displacement"]) < 1e-12
        assert abs(slide["v"] - 0.05) < 1e-12 and abs(slide["a"] - 0.02) < 1e-12
        # Coriolis of the rod in the turning cylinder: 2 ω2 k × v_rel
        w2 = pos["links"]["2"]["omega"]
        u = slide["u"]
        assert np.allclose(slide["coriolis"], [-2 * w2 * 0.05 * u[1], 2 * w2 * 0.05 * u[0]], atol=1e-15)


@pytest.mark.parametrize("path", [COUPLER, CYLINDER], ids=lambda p: p.stem)
def test_drive_sheets_pass_check(path, tmp_path):
    assert main(["render", str(path), "-o", str(tmp_path), "-q"]) == 0
    svgs = sorted(str(p) for p in tmp_path.glob("*-velocity-*.svg")) + \
        sorted(str(p) for p in tmp_path.glob("*-acceleration-*.svg"))
    assert svgs and main(["check", *svgs]) == 0


# --- bad input -------------------------------------------------------------------------------------

def _cylinder_with(drive: str) -> str:
    text = CYLINDER.read_text()
    start = text.index("[drive]")
    end = text.index("[plans]")
    return text[:start] + drive + "\n" + text[end:]


@pytest.mark.parametrize("drive, words", [
    ('[drive]\nlink = "3"\nalong = "3"\ndisplacement = [0.0]\nvelocity = 0.1', "along itself"),
    ('[drive]\nlink = "3"\nalong = "4"\ndisplacement = [0.0]\nvelocity = 0.1', 'link = "3", on = "4"'),
    ('[drive]\nlink = "3"\nalong = "9"\ndisplacement = [0.0]\nvelocity = 0.1', "unknown guide link"),
    ('[drive]\nlink = "3"\nalong = "2"\nangle = [0.0]\nomega = 1.0', "remove it"),
])
def test_bad_cylinder_drives_are_named(drive, words):
    with pytest.raises(SceneError) as err:
        build_mechanism(parse_scene(_cylinder_with(drive)))
    assert words in str(err.value)


def test_coupler_sliding_on_the_frame_is_refused():
    text = """
[points]
O = [0.0, 0.0]
A = [0.1, 0.0]
B = [0.3, 0.1]
[links]
0 = ["O"]
1 = ["O", "A"]
2 = ["A", "B"]
3 = ["B"]
[[sliders]]
link = "3"
on = "0"
through = "B"
angle = 0.0
[drive]
link = "3"
angle = [0.0]
omega = 1.0
"""
    # link 3 has one point: as a coupler its angle needs two
    with pytest.raises(SceneError) as err:
        build_mechanism(parse_scene(text))
    assert "list two" in str(err.value)
    text = text.replace('3 = ["B"]', '3 = ["B", "A3"]').replace('B = [0.3, 0.1]', 'B = [0.3, 0.1]\nA3 = [0.4, 0.1]')
    mech = build_mechanism(parse_scene(text))
    with pytest.raises(StructureError) as err:
        analyse_structure(mech)
    assert "slides on the frame" in str(err.value)


def test_link_pinned_twice_to_the_frame_cannot_be_driven():
    text = COUPLER.read_text().replace('0 = ["O", "C"]', '0 = ["O", "C", "A"]')
    with pytest.raises(SceneError) as err:
        build_mechanism(parse_scene(text.replace('link = "2"', 'link = "1"')))
    assert "cannot turn" in str(err.value)


def test_a_short_step_before_a_requested_value_is_no_jump():
    """Requested strokes put short steps into the walk's grid; the next full step must not
    read as a jump of the branch (moves are compared per unit of stroke)."""
    motion = _solve(CYLINDER.read_text(), [-0.16, -0.12], 0)
    alone = _solve(CYLINDER.read_text(), [-0.16], 0)
    assert np.allclose(motion.position("B")[0], alone.position("B")[0], atol=1e-12, rtol=0)


def test_near_the_coupler_drive_dead_position_the_warning_measures_the_distance():
    """The coupler's smallest angle over a crank turn of the crank-driven four-bar (closed
    form, sampled finely) is the coupler drive's dead position (28.2569°): 28.258° lies within
    the warning's reach of it (its figure, the sine of the angle between crank and rocker, is
    below WARN_SIN), and the warning's distance is 28.258° minus that angle (the search's first
    step, 0.05°, is shortened until it can pose either side)."""
    text = FOUR_BAR.read_text()
    crank = np.linspace(60.0, 140.0, 8001)
    by_crank = _solve(text, crank, 0)
    low = float(np.min(_angle(by_crank, "A", "B")))
    mech = build_mechanism(parse_scene(COUPLER.read_text()))
    motion = analyse(mech, analyse_structure(mech), np.array([28.258]), order=1)
    assert abs(float(motion.sines["I(0-1-2-3)"][0])) < 0.01
    away = motion.singular_distance("I(0-1-2-3)", 0)
    assert away == pytest.approx(28.258 - low, rel=0.05)

"""Walking a mechanism through positions it cannot all reach in one walk, and what the walk
says where it stops.

* A crank that cannot turn fully, asked for angles on both sides of its sketch, is walked a
  few times (one walk per start, the long way only for the angles the short way does not
  reach), with the results of walking each angle alone.
* A drive inside the chain that reaches its limit position says so, with the limit in the
  drive's units (checked against the closed form of the boom and a four-bar sampled finely).
* A cycle needs a crank that turns fully: a coupler's cycle is refused by the scene reader,
  a crank that cannot turn fully says so.
* Messages print angles as the user wrote them (the sketch's own angle, not one turn on), and
  every drive value with its unit.
"""

from __future__ import annotations

import io
import contextlib
import math
import re
import tomllib

import numpy as np
import pytest

from plans.bench.sections.limited import limited_angles, limited_crank
from plans.cli import main
from plans.errors import AssemblyError, SceneError
from plans.kinematics import analyse, solve
from plans.model import build_mechanism
from plans.scene import parse_scene
from plans.structure import analyse_structure

from conftest import EXAMPLES, toml_text

COUPLER = next(p for p in EXAMPLES if p.stem == "four_bar_coupler_drive")
CYLINDER = next(p for p in EXAMPLES if p.stem == "hydraulic_boom")
CRANK_SLIDER = next(p for p in EXAMPLES if p.stem == "crank_slider_central")


def _data(path) -> dict:
    return tomllib.loads(path.read_text(encoding="utf-8"))


def _solve(data: dict, values, order: int = 2):
    mech = build_mechanism(parse_scene(data))
    return analyse(mech, analyse_structure(mech), np.asarray(values, dtype=float), order=order)


def _error(data: dict, values) -> str:
    with pytest.raises(AssemblyError) as err:
        _solve(data, values)
    text = str(err.value)
    assert "\n" not in text
    return text


def _number(pattern: str, text: str) -> float:
    found = re.search(pattern, text)
    assert found, text
    return float(found.group(1))


# --- A. a crank that cannot turn fully, angles on both sides of its sketch ------------------------

def test_a_limited_crank_is_walked_once_per_start_not_once_per_angle(monkeypatch):
    """360 angles of the class III crank that rocks between about −138° and 205° (sketched at
    120°), from −135° to 200° written in [0°, 360°): the walk through all of them fails, and
    each angle was then walked alone (some 440 walks, minutes on a loaded machine); now the
    angles that start alike are walked together — a handful of walks."""
    mech, structure = limited_crank()
    calls = []
    real = solve._positions
    monkeypatch.setattr(solve, "_positions", lambda *a, **k: calls.append(k.get("start")) or real(*a, **k))
    analyse(mech, structure, limited_angles(360), order=0)
    assert len(calls) <= 6, calls


def _short_way_fails(mech, structure, angle: float) -> bool:
    near = mech.drive.sketch_value + 360.0 * round((angle - mech.drive.sketch_value) / 360.0)
    try:
        solve._positions(mech, structure, np.array([angle]), start=near)
    except AssemblyError:
        return True
    return False


def test_a_limited_crank_gives_what_each_angle_walked_alone_gives():
    """The values at a set of angles — on both sides of the sketch, reached the short way and
    the long way — equal those of the single-angle path (analyse at that angle alone): the
    poses to 1e-12 of the size, velocities and accelerations to 1e-12 of their largest."""
    mech, structure = limited_crank()
    angles = limited_angles(360)
    together = analyse(mech, structure, angles, order=2)
    pick = [int(np.argmin(np.abs(angles - a))) for a in (232.0, 262.0, 292.0, 310.0, 350.0, 10.0, 100.0, 190.0)]
    long_way = [i for i in pick if _short_way_fails(mech, structure, float(angles[i]))]
    assert [round(float(angles[i])) for i in long_way] == [232, 262, 292]     # below −60°: only the long way
    for f in ("position", "velocity", "acceleration"):
        scale = mech.size if f == "position" else \
            max(float(np.max(np.abs(getattr(together, f)(p)))) for p in mech.sketch)
        for i in pick:
            alone = analyse(mech, structure, angles[i:i + 1], order=2)
            for p in mech.sketch:
                diff = np.max(np.abs(getattr(together, f)(p)[i] - getattr(alone, f)(p)[0]))
                assert diff <= 1e-12 * scale, (f, p, float(angles[i]), diff / scale)


def test_an_angle_reachable_neither_way_is_reported_as_alone():
    """210° lies between the limits (205° up from the sketch, −138° = 222° down): among many
    reachable angles it is reported with the very message it gets alone, in the sketch's turn."""
    mech, structure = limited_crank()
    with pytest.raises(AssemblyError) as alone:
        analyse(mech, structure, np.array([210.0]))
    with pytest.raises(AssemblyError) as among:
        analyse(mech, structure, np.concatenate([limited_angles(36), [210.0]]))
    assert str(among.value) == str(alone.value)
    assert "at 210°" in str(alone.value) and "the walk from the sketch at 120°" in str(alone.value)


# --- B. a drive inside the chain at its limit position ----------------------------------------

def test_a_cylinder_driven_beyond_its_limit_gives_the_limit_stroke_and_length():
    """The boom's cylinder pivots at A, its rod's eye B is pinned to the boom, which turns about
    O; B lies on the cylinder's axis, so the cylinder's length is |AB| and it is shortest, a
    limit position, when O, B and A are in line: |AB| = |OB| − |OA|, the stroke from the sketch
    that length less the sketch's |AB|."""
    data = _data(CYLINDER)
    text = _error(data, [0.0, -0.4])
    pts = {k: np.array(v) for k, v in data["points"].items()}
    axis = (pts["Q"] - pts["A"]) / np.linalg.norm(pts["Q"] - pts["A"])
    ab = pts["B"] - pts["A"]
    off = float(axis[0] * ab[1] - axis[1] * ab[0])              # B's distance from the axis (0 here)
    shortest = np.linalg.norm(pts["B"] - pts["O"]) - np.linalg.norm(pts["A"] - pts["O"])
    stroke = math.sqrt(shortest ** 2 - off ** 2) - float(np.dot(ab, axis))
    assert "limit position" in text and "falls apart" not in text and "at -0.4 m" in text
    # the message prints :g, 6 significant digits (≤ 5e-6 relative); the limit itself is found to
    # 1e-6 of the search's first step (1e-10 of the size), far closer: rel=1e-5 is twice the printing
    assert _number(r"limit position at (-?[\d.e+-]+) m", text) == pytest.approx(stroke, rel=1e-5)
    assert _number(r"length AB = ([\d.e+-]+) m", text) == pytest.approx(shortest, rel=1e-5)


def _coupler_angles(data: dict) -> np.ndarray:
    """The coupler's angle (A → B, degrees) of the four-bar over a crank turn in 2·10⁶ steps,
    on the sketch's assembly branch (B left of A → C), by circle intersection."""
    pts = {k: np.array(v) for k, v in data["points"].items()}
    o, c = pts["O"], pts["C"]
    r1, r2, r3 = (np.linalg.norm(pts[p] - pts[q]) for p, q in (("A", "O"), ("B", "A"), ("B", "C")))
    phi = np.linspace(0.0, 2 * np.pi, 2_000_000, endpoint=False)
    a = o + r1 * np.column_stack([np.cos(phi), np.sin(phi)])
    d = c - a
    dist = np.linalg.norm(d, axis=1)
    along = (dist ** 2 + r2 ** 2 - r3 ** 2) / (2 * dist)
    across = np.sqrt(r2 ** 2 - along ** 2)
    u = d / dist[:, None]
    b = a + along[:, None] * u + across[:, None] * np.column_stack([-u[:, 1], u[:, 0]])
    return np.degrees(np.arctan2(b[:, 1] - a[:, 1], b[:, 0] - a[:, 0]))


@pytest.mark.parametrize("angle, extreme", [(70.0, np.max), (0.0, np.min)], ids=["above", "below"])
def test_a_coupler_driven_beyond_its_limit_gives_the_limit_angle(angle, extreme):
    """The four-bar driven by its coupler's angle (sketched at 53.04°) reaches its limits where
    that angle is extreme over the crank's turn (crank and rocker parallel)."""
    data = _data(COUPLER)
    text = _error(data, [53.0, angle])
    assert "limit position" in text and "falls apart" not in text and f"at {angle:g}°" in text
    limit = _number(r"limit position at (-?[\d.e+-]+)° \(link 2's angle\)", text)
    # printed :g (≤ 5e-6 relative); the sampled extreme is within ½·|ψ″|·(π/2·10⁶)² ~ 1e-12: rel=1e-5
    assert limit == pytest.approx(float(extreme(_coupler_angles(data))), rel=1e-5)


# --- C. a cycle needs a crank that turns fully ---------------------------------------------------

def test_a_coupler_drive_has_no_cycle():
    data = _data(COUPLER)
    data["drive"]["angle"] = 53.0
    data["drive"]["positions"] = 12
    with pytest.raises(SceneError) as err:
        parse_scene(data)
    assert err.value.key == "drive.positions"
    assert "needs a crank" in str(err.value) and "coupler" in str(err.value)


def _non_grashof(angle) -> dict:
    """A four-bar (OA 0.18, AB 0.2, BC 0.2, OC 0.24 m: s + l = 0.42 > p + q = 0.40) sketched at
    90°: its crank rocks between ±144.1° (|AC| = AB + BC)."""
    a, c = np.array([0.0, 0.18]), np.array([0.24, 0.0])
    half = np.linalg.norm(c - a) / 2
    u = (c - a) / (2 * half)
    b = (a + c) / 2 + math.sqrt(0.2 ** 2 - half ** 2) * np.array([-u[1], u[0]])
    return {"points": {"O": [0.0, 0.0], "C": [0.24, 0.0], "A": [0.0, 0.18], "B": [float(b[0]), float(b[1])]},
            "links": {"0": ["O", "C"], "1": ["O", "A"], "2": ["A", "B"], "3": ["C", "B"]},
            "drive": {"link": "1", "angle": angle, "omega": 10.0}}


def test_a_crank_that_cannot_turn_fully_has_no_cycle():
    import plans

    data = _non_grashof(90.0)
    data["drive"]["positions"] = 12
    data["plans"] = {"draw": ["positions"]}
    with pytest.raises(AssemblyError) as err:
        plans.render(parse_scene(data), stem="rocker")
    assert "needs a crank that turns fully" in str(err.value) and "positions = 12" in str(err.value)


# --- D. angles as the user wrote them --------------------------------------------------------------

@pytest.mark.parametrize("angle", [560.0, -200.0])
def test_the_walk_is_reported_from_the_sketch_as_drawn(angle):
    """560° (200° a turn on) and −200° (160° a turn back) are walked from the sketch moved a
    turn towards them (450°, −270°); the message names the sketch's own 90° and the limit
    passed in its turn, 145° (the first 1° step past 144.1°)."""
    text = _error(_non_grashof([angle]), [angle])
    assert f"at {angle:g}°" in text and "(the walk from the sketch at 90° fails at 145°)" in text, text


def test_a_singular_crossing_is_reported_from_the_sketch_as_drawn():
    """A parallelogram four-bar sketched at 90° passes its change point (all links in line) at
    180°; 560.5° is walked from 450°, and the message names 179° and 180°, not 539° and 540°."""
    data = {"points": {"O": [0.0, 0.0], "C": [0.2, 0.0], "A": [0.0, 0.1], "B": [0.2, 0.1]},
            "links": {"0": ["O", "C"], "1": ["O", "A"], "2": ["A", "B"], "3": ["C", "B"]},
            "drive": {"link": "1", "angle": [560.5], "omega": 10.0}}
    text = _error(data, [560.5])
    assert "at 560.5°" in text and "singular position between 179° and 180°" in text, text


def test_a_balancing_force_with_no_arm_names_the_angle_with_its_unit(tmp_path):
    data = _data(CRANK_SLIDER)
    data["balance"] = {"force_on": "1", "at": "A", "angle": 45.0}    # along the crank, at 45°: no arm
    data["plans"] = {"draw": ["scheme", "forces"]}
    scene = tmp_path / "arm.toml"
    scene.write_text(toml_text(data), encoding="utf-8")
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        assert main(["render", str(scene), "-o", str(tmp_path / "out"), "-q"]) == 2
    line = err.getvalue().strip()
    assert "\n" not in line and "[balance.angle]" in line
    assert "cannot balance the mechanism at 45° (it has no arm" in line, line

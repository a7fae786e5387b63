"""A dynamics handout of a machine whose loads are laws in the crank angle over a cycle of
several turns (issue 35 items 3 and 5): the task states each law with its numbers and the cycle's
turns, a driving law is given (so M_d is not asked), and every marked value is what the chord
method gives at the cycle's positions over the whole period.

The second implementation here (the midpoint rule over Φ/N intervals, M_r and M_d at each
interval's middle, the tangents to the N points) shares with plans only the machine's reduced
moment, inertia and driving law, which tests/test_dynamics_laws.py checks against closed forms.
Before this was built, a 720° cycle's constant moment was found over 2π (twice the true one) and
the driving law's table was not written in the task at all.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from plans.handout import asked
from plans.handout.assignment import loads_cells, task_text, torque_text
from plans.pipeline import render
from plans.pipeline.stages import machine_motion, solve_motion
from plans.scene import parse_scene
from plans.scene.turning import Shape, Torque

ROOT = Path(__file__).resolve().parent.parent
ENGINE = ROOT / "examples" / "flywheel" / "engine_crank_slider.toml"
#: The key's reading of a length, mm (the dynamics sheet's stated ±0.5 mm).
READ_MM = 0.5


def by_hand(scene) -> tuple[float, float, int]:
    """(M_d constant, J_fw, N) as a student finds them: chords with M_r (and a driving law's M_d)
    at each interval's middle over the period Φ, the constant moment closing the cycle, ΔT at the
    N positions, the tangents tan ψ = ω_m²(1 ± δ)/2 to the points (I_r, ΔT)."""
    _, cycle = solve_motion(scene)
    m = machine_motion(scene, cycle)
    n = len(m.theta)
    period = math.radians(m.period)
    h = period / n
    middles = (np.arange(n) + 0.5) * h
    drive = m.driving(middles) if m.driving is not None else np.zeros(n)
    steps = (np.asarray(m.moment(middles), dtype=float) + drive) * h
    constant = 0.0 if m.driving is not None else -float(np.sum(steps)) / period
    energy = np.concatenate([[0.0], np.cumsum(steps)])[:n] + constant * h * np.arange(n)
    inertia = np.asarray(m.inertia(np.arange(n) * h), dtype=float)
    w2, d = m.omega_m ** 2, m.flywheel.delta
    j = (max(energy - 0.5 * w2 * (1 + d) * inertia) - min(energy - 0.5 * w2 * (1 - d) * inertia)) / (w2 * d)
    return m.sense * constant, j, n


@pytest.fixture(scope="module")
def engine():
    data = tomllib.loads(ENGINE.read_text(encoding="utf-8"))
    scene = parse_scene(data)
    return data, scene, render(scene).report


def test_a_driving_law_is_given_and_only_the_flywheel_asked(engine):
    data, scene, report = engine
    items = asked(scene, report)
    _, j, n = by_hand(scene)
    dyn = report["cycle"]["dynamics"]
    assert n == 24 == len(dyn["theta"])                    # 12 a turn over the two turns of the cycle
    assert [a.symbol for a in items] == ["J_{fw}"]
    (a,) = items
    assert math.isclose(a.value, j, rel_tol=1e-9)
    assert a.exact == dyn["flywheel"]["required"] and a.method == "the chord method at the 24 given positions"
    assert math.isclose(a.precision, dyn["sheet"]["wittenbauer"]["reading_error"], rel_tol=1e-12)
    cells, laws = loads_cells(scene)
    text = task_text(scene, items, laws)
    assert "2 turns of link 1" in text and "constant driving moment" not in text and "M_{d}(φ)" in text
    for x, y in data["dynamics"]["driving"]:
        assert f"{x:g}° → {y:g}" in text                   # every corner of the table is stated
    assert "M_{1} = -256.25 N·m" in cells


def test_a_constant_drive_over_two_turns_is_found_over_the_whole_period(engine):
    """The engine turned round: the consumer's moment is the law (the triangles' negative) and
    the drive constant. The chords' M_d is the law's mean over 4π (256.25 N·m, the JSON's, within
    the key's reading of its work graph), not over 2π (512.5)."""
    data, _, _ = engine
    data = {**data, "dynamics": {k: v for k, v in data["dynamics"].items() if k != "driving"},
            "moments": [{"link": "1", "law": [[x, -y] for x, y in data["dynamics"]["driving"]]}]}
    scene = parse_scene(data)
    report = render(scene).report
    dyn = report["cycle"]["dynamics"]
    items = {a.symbol: a for a in asked(scene, report)}
    md, j, n = by_hand(scene)
    assert n == 24 and set(items) == {"M_{d}", "J_{fw}"}
    assert math.isclose(items["M_{d}"].value, md, rel_tol=1e-9) and math.isclose(items["J_{fw}"].value, j, rel_tol=1e-9)
    assert dyn["constant_moment"] == pytest.approx(256.25, rel=1e-9)
    reading = dyn["sheet"]["mu"]["A"] * READ_MM / (4.0 * math.pi)
    assert math.isclose(items["M_{d}"].precision, reading, rel_tol=1e-12)
    assert abs(items["M_{d}"].value - 256.25) <= reading
    cells, laws = loads_cells(scene)
    assert not any(c.startswith("M_{1} =") for c in cells)      # the law is not a constant moment of 0
    assert len(laws) == 1 and "0° → 0, 30° → -3000" in laws[0] and "counter-clockwise +" in laws[0]


def test_every_kind_of_law_is_written_with_its_numbers():
    assert torque_text(Torque(mean=5000.0, harmonics=((1500.0, 3.0, 0.0), (-200.0, 6.0, 30.0)))) == \
        "5000 + 1500·sin(3φ) − 200·sin(6φ + 30°)"
    shapes = (Shape("semicircle", 0.0, 180.0, 5000.0), Shape("triangle", 180.0, 360.0, -1000.0, 270.0),
              Shape("rectangle", 360.0, 540.0, 200.0))
    assert torque_text(Torque(shapes=shapes)) == (
        "the sum of a semicircle from 0° to 180°, peak 5000; a triangle from 180° to 360°, -1000 at 270°; "
        "a rectangle from 360° to 540°, height 200 (zero elsewhere)")
    assert torque_text(Torque(table=((0.0, 0.0), (90.0, 50.0), (180.0, 100.0), (360.0, 0.0)))) == \
        "0° → 0, 180° → 100, 360° → 0 (linear between)"    # a point on the line through its neighbours is left out

"""A dynamics handout marks what its task asks (issue 35 item 5).

The flywheel task asks for the works by graphical integration by chords over the cycle's N
positions (M_r at each interval's middle × Δφ) and Wittenbauer's diagram through the positions'
points. The values it is marked against — the key's page and the Moodle fields — must be what a
student doing exactly that finds: here a second implementation of the method (the midpoint rule
on the machine's reduced moment and the tangents to the N points, written out below, sharing
with plans only the reduced moment and inertia, themselves checked against the key's JSON) must
lie inside each field's tolerance, and that tolerance is never narrower than reading the key's
drawing to ±0.5 mm (the key's own stated reading error). The chords themselves converge: at 72
positions they come within 0.5 % of the exact values, at 12 they do not (so the check can tell).
"""

from __future__ import annotations

import math
import re
import tomllib
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from plans.handout import asked, moodle_xml, random_variants, variant_asked
from plans.handout.graphical import chord_answers, tangent_delta, tangent_inertia
from plans.pipeline import render
from plans.pipeline.stages import machine_motion, solve_motion
from plans.scene import parse_scene

ROOT = Path(__file__).resolve().parent.parent
#: The flywheel base the handout tests use (tests/test_handout_kinds.py, tests/test_moodle.py).
BASE = ROOT / "examples" / "six_link_press_flywheel.toml"
TOLERANCE = 0.02
FIELD = re.compile(r"\{(\d+):NUMERICAL:=([^:}~]+):([^}~]+)\}")
READ_MM = 0.5


def moodle_accepts(response: float, answer: float, tolerance: float) -> bool:
    """Moodle's Cloze NUMERICAL check (nominal tolerance, PHP precision 14)."""
    t = abs(tolerance) + 1e-14 * max(abs(tolerance), abs(answer), 1e-14)
    return answer - t <= response <= answer + t


def by_hand(scene, report=None) -> tuple[float, float, int]:
    """M_d (N·m, CCW +) and J_fw (kg·m²) as the student finds them over the scene's N positions:
    chords with M_r at each interval's middle, the constant moment's line to the chords' end,
    ΔT = A_d − A_r at the positions, then the tangents tan ψ = ω_m²(1 ± δ)/2 to the points
    (I_r, ΔT). ``report``: the key's JSON, whose M_r at the positions the machine must give."""
    _, cycle = solve_motion(scene)
    m = machine_motion(scene, cycle)
    n = len(m.theta)
    h = 2.0 * math.pi / n
    if report is not None:
        reported = np.array(report["cycle"]["dynamics"]["reduced_moment"])
        assert np.allclose(m.sense * m.moment(m.theta), reported, rtol=1e-9, atol=1e-9 * np.max(np.abs(reported)))
    steps = np.array([float(m.moment((k + 0.5) * h)) * h for k in range(n)])     # middle ordinate × Δφ
    loads = np.concatenate([[0.0], np.cumsum(steps)])[:n]                           # ∫M_r at the positions
    constant = -float(np.sum(steps)) / (2.0 * math.pi)                              # its line closes the cycle
    energy = loads + constant * h * np.arange(n)
    inertia = np.array([float(m.inertia(k * h)) for k in range(n)])
    w2, d = m.omega_m ** 2, m.flywheel.delta
    j = (max(energy - 0.5 * w2 * (1 + d) * inertia) - min(energy - 0.5 * w2 * (1 - d) * inertia)) / (w2 * d)
    return m.sense * constant, j, n


@pytest.fixture(scope="module")
def handout():
    h, drawn = random_variants(BASE, 6, 3)
    marked = [variant_asked(d) for d in drawn]
    svg = '<svg xmlns="http://www.w3.org/2000/svg" width="10mm" height="10mm" viewBox="0 0 10 10"/>'
    bank = moodle_xml(h, drawn, marked, tolerance=TOLERANCE, assignments=[svg] * len(drawn))
    return h, drawn, marked, bank


def test_the_fields_hold_what_the_chord_method_gives_at_the_asked_positions(handout):
    _, drawn, marked, bank = handout
    root = ET.fromstring(bank.encode("utf-8"))
    off = 0
    for q, d, items in zip(root.findall("question")[1:], drawn, marked):
        md, j, n = by_hand(d.scene, d.sheets.report)
        assert n == 12
        student = {"M_{d}": md, "J_{fw}": j}
        dyn = d.sheets.report["cycle"]["dynamics"]
        exact = {"M_{d}": dyn["constant_moment"], "J_{fw}": dyn["flywheel"]["required"]}
        sheet = dyn["sheet"]
        reading = {"M_{d}": sheet["mu"]["A"] * READ_MM / (2 * math.pi), "J_{fw}": sheet["wittenbauer"]["reading_error"]}
        fields = FIELD.findall(q.find("questiontext/text").text)
        assert [a.symbol for a in items] == ["M_{d}", "J_{fw}"] and len(fields) == 2
        for (_, answer, tol), a in zip(fields, items):
            value, t = float(answer), float(tol)
            assert moodle_accepts(student[a.symbol], value, t), (d.name, a.symbol, student[a.symbol], value, t)
            assert math.isclose(a.value, student[a.symbol], rel_tol=1e-9), (d.name, a)
            assert a.exact == exact[a.symbol] and a.method == "the chord method at the 12 given positions"
            assert math.isclose(a.precision, reading[a.symbol], rel_tol=1e-12)
            # the tolerance: 2 % of the marked value, never narrower than the key's drawing read to ±0.5 mm
            want = max(TOLERANCE * abs(a.value), reading[a.symbol])
            assert want <= t <= want * (1 + 1e-5) + abs(a.value - value)
            off += not moodle_accepts(student[a.symbol], exact[a.symbol], TOLERANCE * abs(exact[a.symbol]))
    assert off >= 2           # marked against the exact values ±2 %, these students would have been wrong


def test_the_key_page_lists_the_marked_and_the_exact_values(tmp_path):
    from plans.cli import main

    out = tmp_path / "out"
    assert main(["handout", str(BASE), "--random", "1", "--seed", "3", "-o", str(out), "-q"]) == 0
    page = (out / "index.html").read_text(encoding="utf-8")
    folder = out / "variant-01"
    report = (folder / "variant-01.json").read_text(encoding="utf-8")
    scene = parse_scene(tomllib.loads((folder / "variant-01.toml").read_text(encoding="utf-8")))
    import json

    items = asked(scene, json.loads(report))
    md, j, _ = by_hand(scene)
    for a, student in zip(items, (md, j)):
        assert math.isclose(a.value, student, rel_tol=1e-9)
        assert f'<td class="n">{a.value:.6g}</td><td class="n">{a.exact:.6g}</td>' in page
    task = (folder / "variant-01-assignment.svg").read_text(encoding="utf-8")
    words = " ".join("".join(t.itertext()) for t in ET.fromstring(task).iter("{http://www.w3.org/2000/svg}text"))
    assert "by chords" in words and "at its middle" in words


def test_the_chords_converge_to_the_exact_values():
    """The midpoint rule converges: at 72 positions the chords are within 0.5 % of the exact
    M_d and J_fw; at the task's 12 they are not (M_d 3.4 % off), which the check must see."""
    data = tomllib.loads(BASE.read_text(encoding="utf-8"))
    for n, close in ((72, True), (12, False)):
        data["drive"]["positions"] = n
        data["plans"]["at"] = [0]
        scene = parse_scene(data)
        report = render(scene).report["cycle"]["dynamics"]
        c = chord_answers(scene)
        md, j, _ = by_hand(scene)
        assert math.isclose(c.moment, md, rel_tol=1e-9) and math.isclose(c.inertia, j, rel_tol=1e-9)
        worst = max(abs(md / report["constant_moment"] - 1), abs(j / report["flywheel"]["inertia_exact"] - 1))
        assert (worst < 0.005) == close, (n, worst)


def test_tangents_to_points_of_constant_inertia_give_the_textbook_formula():
    """With I_r constant (I0) the tangents give J = (ΔT_max − ΔT_min)/(ω_m²·δ) − I0, and the δ
    a given J reaches is that formula solved for δ."""
    energy, inertia = np.array([0.0, 10.0, -5.0, 3.0]), np.full(4, 2.0)
    assert math.isclose(tangent_inertia(energy, inertia, 10.0, 0.1), 15.0 / (100.0 * 0.1) - 2.0, rel_tol=1e-12)
    assert math.isclose(tangent_delta(energy, inertia, 10.0, 1.0), 15.0 / (100.0 * 3.0), rel_tol=1e-12)


def test_a_given_flywheel_is_marked_by_the_delta_its_tangents_reach():
    """The base with the chords' own J as its given flywheel: the δ marked is the base's 0.05
    (the same tangents read the other way), the exact δ reached beside it."""
    data = tomllib.loads(BASE.read_text(encoding="utf-8"))
    j = chord_answers(parse_scene(data)).inertia
    data["dynamics"] = {"flywheel": j}
    scene = parse_scene(data)
    report = render(scene).report
    items = {a.symbol: a for a in asked(scene, report)}
    delta = items["δ"]
    assert math.isclose(delta.value, 0.05, rel_tol=1e-9)
    assert delta.exact == report["cycle"]["dynamics"]["delta_reached"] and delta.precision > 0.0

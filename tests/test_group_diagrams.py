"""Each group drawn alone beside its force polygon (textbook Fig. 1.27 a, 1.28): its forces at
their points, R^n and R^τ of the outer pins, the arms and the moment equations
(:mod:`plans.constructions.group_diagram`, :mod:`plans.drawing.group_diagram`), read back by
``plans check`` (:mod:`plans.checking_groups`).

The components are checked against the JSON's reactions and the scene's own points (not the
drawing's directions); the equations against the solved reactions; the checker against
doctored sheets."""

from __future__ import annotations

import json
import math
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from plans.checking import inspect_svg
from plans.constructions.group_diagram import group_diagrams
from plans.layout import measure_layout
from plans.pipeline.stages import force_analysis, solve_motion
from plans.scene import read_scene

SVG = "{http://www.w3.org/2000/svg}"
#: Every loaded example with force plans: its stem.
LOADED = ("six_link_press_forces", "class3_forces", "crank_slider_forces", "four_bar_gravity", "compressor_flywheel",
          "shaper_flywheel", "six_link_press_flywheel", "six_link_press_startup")
#: Outer pin → inner pin of each split reaction (the link's line), read from the scene's points.
LINES = {"six_link_press_forces": {"1-2": ("A", "B"), "0-3": ("D", "B"), "2-4": ("C", "E")},
         "class3_forces": {"1-2": ("A", "B"), "0-4": ("D", "C"), "0-5": ("M", "F")}}


def _sheets(out, stem: str) -> dict[str, list[ET.Element]]:
    """Position suffix → the roots of its force sheets."""
    found: dict[str, list[ET.Element]] = {}
    for path in sorted(out.glob(f"{stem}-forces-*.svg")):
        m = re.fullmatch(rf"{stem}-forces-(.+?)(-\d)?\.svg", path.name)
        found.setdefault(m.group(1), []).append(ET.parse(path).getroot())
    return found


def _groups(roots) -> list[ET.Element]:
    return [g for r in roots for g in r.iter(f"{SVG}g") if g.get("data-plan") == "group"]


@pytest.mark.parametrize("stem", LOADED)
def test_every_group_and_the_driving_link_is_drawn_alone(demo_rendered, stem):
    """Every force sheet's position has a diagram of each group of the structure and of the
    driving link; each diagram states its μl and draws the group's links."""
    report = json.loads((demo_rendered / f"{stem}.json").read_text(encoding="utf-8"))
    names = {g["name"] for g in report["structure"]["groups"]}
    sheets = _sheets(demo_rendered, stem)
    assert sheets, stem
    for position, roots in sheets.items():
        drawn = {g.get("data-group") for g in _groups(roots)}
        if not drawn:           # a position with no load at all says so instead
            assert any("no load" in "".join(t.itertext()) for r in roots for t in r.iter(f"{SVG}text")), position
            continue
        assert names <= drawn, (position, names - drawn)
        assert any(n.startswith("I(") for n in drawn), position
        for g in _groups(roots):
            assert float(g.get("data-mu")) > 0
            assert any(l.get("data-construction") == "link" for l in g.iter(f"{SVG}line"))


@pytest.mark.parametrize("stem", sorted(LINES))
def test_each_tangential_component_is_the_reaction_across_its_link(demo_rendered, stem):
    """Rt:i-j = |R_ij × u| and Rn:i-j = |R_ij · u| (u along the link from the outer pin to the
    inner one, from the JSON's points) within 1e-9 of the reaction, at every drawn position."""
    report = json.loads((demo_rendered / f"{stem}.json").read_text(encoding="utf-8"))
    positions = {f"{p['angle']:g}": p for p in report["positions"]}
    checked = 0
    for position, roots in _sheets(demo_rendered, stem).items():
        p = positions[position]
        for g in _groups(roots):
            for line in g.iter(f"{SVG}line"):
                q = line.get("data-quantity") or ""
                if not q.startswith(("Rt:", "Rn:")):
                    continue
                key = q[3:]
                outer, inner = LINES[stem][key]
                u = np.subtract(p["points"][inner]["r"], p["points"][outer]["r"])
                u /= math.hypot(*u)
                r = np.asarray(p["forces"]["reactions"][key])
                exact = abs(r[0] * u[1] - r[1] * u[0]) if q.startswith("Rt:") else abs(r @ u)
                assert float(line.get("data-value")) == pytest.approx(exact, rel=0, abs=1e-9 * math.hypot(*r)), q
                checked += 1
    assert checked >= 4 * len(LINES[stem])


@pytest.mark.parametrize("stem", ["six_link_press_forces", "class3_forces", "crank_slider_forces", "shaper_flywheel"])
def test_the_moment_equations_give_the_solved_reactions(stem):
    """Each equation's unknown, from its own terms, equals the drawn force's value (the
    reaction's projection) to rounding, and its moments sum to zero; a triad's special point
    lies on the lines of the two rods' R^n it is drawn through."""
    from plans.examples import __path__ as where
    scene = read_scene(f"{where[0]}/{stem}.toml")
    motion, cycle = solve_motion(scene)
    forces = force_analysis(scene, motion, cycle)
    seen = 0
    for i in range(len(motion)):
        for d in group_diagrams(motion, forces, i):
            scale = max((f.value for f in d.forces), default=1.0) * motion.mechanism.size
            for e in d.equations:
                assert abs(e.residual) <= 1e-12 * scale
                if e.arm is not None:
                    assert e.value == pytest.approx(d.force(e.unknown).value, rel=1e-9, abs=1e-12 * scale)
                seen += 1
            for _, s in d.special:
                through = [f for f in d.forces if f.quantity.startswith("Rn:")
                           and abs((s[0] - f.at[0]) * f.direction[1] - (s[1] - f.at[1]) * f.direction[0]) < 1e-6]
                assert len(through) >= 2
    assert seen > 0


def test_the_written_equation_is_the_drawn_one(demo_rendered):
    """The six-link press at 60°: the sheet writes R12,τ = (…)/h with the drawn arm's length and
    the result the diagram's tag carries."""
    root = ET.parse(demo_rendered / "six_link_press_forces-forces-60-2.svg").getroot()
    text = [" ".join("".join(t.itertext()).split()) for t in root.iter(f"{SVG}text")]
    g = next(g for g in _groups([root]) if g.get("data-group") == "II(2-3)")
    rt = next(l for l in g.iter(f"{SVG}line") if l.get("data-quantity") == "Rt:1-2")
    arm = next(l for l in g.iter(f"{SVG}line") if l.get("data-quantity") == "h:Rt:1-2")
    mm = math.dist((float(arm.get("x1")), float(arm.get("y1"))), (float(arm.get("x2")), float(arm.get("y2"))))
    row = next(t for t in text if t.startswith("= (") and t.endswith(f"{float(rt.get('data-value')):.5g} N"))
    assert re.search(r"/ ([0-9.]+) = ", row) and float(re.search(r"/ ([0-9.]+) = ", row).group(1)) == \
        pytest.approx(mm, abs=0.005 + 5e-4 * mm)        # written to 4 significant digits


def _doctor(svg: str, quantity: str, attr: str, change) -> str:
    root = ET.fromstring(svg)
    line = next(l for l in root.iter(f"{SVG}line") if l.get("data-quantity") == quantity
                and any(g.get("data-plan") == "group" for g in root.iter(f"{SVG}g") if l in list(g.iter())))
    line.set(attr, repr(change(float(line.get(attr)))))
    return ET.tostring(root, encoding="unicode")


@pytest.mark.parametrize("name", ["six_link_press_forces-forces-60-2.svg", "class3_forces-forces-105.svg"])
def test_check_passes_the_sheets_and_fails_a_doctored_arm_or_component(demo_rendered, tmp_path, name):
    svg = (demo_rendered / name).read_text(encoding="utf-8")
    report = inspect_svg(demo_rendered / name)
    assert not report.problems
    groups = [k for k in report.equations if k.endswith("-group")]
    assert groups and all(report.equations[k] >= 1 for k in groups)
    assert measure_layout(svg).overlapping_labels == 0
    doctored = {
        "arm": _doctor(svg, "h:Rt:1-2", "x2", lambda x: x + 0.3),                # an arm 0.3 mm off its line
        "Rt": _doctor(svg, "Rt:1-2", "data-value", lambda v: v * 1.01),          # R^τ 1 % off its equation
    }
    for what, text in doctored.items():
        path = tmp_path / f"{what}.svg"
        path.write_text(text, encoding="utf-8")
        bad = inspect_svg(path)
        assert bad.problems, what
        assert any("Rt:1-2" in p for p in bad.problems), (what, bad.problems[:3])


def test_an_undrawn_arm_fails(demo_rendered, tmp_path):
    """Deleting a drawn arm leaves its force's moment unmeasured: refused, naming the force."""
    root = ET.parse(demo_rendered / "six_link_press_forces-forces-60-2.svg").getroot()
    for g in root.iter(f"{SVG}g"):
        for line in list(g):
            if line.get("data-quantity") == "h:G:2":
                g.remove(line)
    for g in root.iter(f"{SVG}g"):
        if g.get("data-plan") == "group" and g.get("data-group") == "II(2-3)":
            g.set("data-vectors", str(int(g.get("data-vectors")) - 1))
    path = tmp_path / "no-arm.svg"
    path.write_text(ET.tostring(root, encoding="unicode"), encoding="utf-8")
    assert any("G:2" in p and "not drawn" in p for p in inspect_svg(path).problems)

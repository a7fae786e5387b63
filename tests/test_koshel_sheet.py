"""Koshel's composite sheet: the centre P_j constructed on the scheme, V_S drawn from the
special points in K_V, K_V from the crank pin, the proportion — against the kinematics."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from plans.checking import inspect_svg
from plans.cli import main
from plans.constructions import uncertain_plan
from plans.constructions.koshel import fit_segment, koshel_sheet
from plans.kinematics import special
from plans.kinematics.centres import centres
from plans.pipeline import read_scene, solve_scene
from plans.structure import ComplexGroup

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
SCENES = ["koshel_variant1", "koshel_variant2", "class3_six_link", "triad_sliding_rod"]
#: Drawing precision of a constructed point, mm (the geometry itself is exact to rounding).
PRECISION_MM = 1e-6


def _sheets(name: str):
    motion = solve_scene(read_scene(EXAMPLES / f"{name}.toml"))
    g = next(g for g in motion.structure.groups if isinstance(g, ComplexGroup))
    out = []
    for i in range(len(motion)):
        plan, segment = fit_segment(uncertain_plan(motion, i, g))
        out.append((i, koshel_sheet(motion, i, g, plan, segment)))
    return motion, g, out


@pytest.mark.parametrize("name", SCENES)
def test_centre_is_the_kinematic_centre_and_the_lines_meet_there(name):
    motion, g, sheets = _sheets(name)
    ic = centres(motion)
    drawn = 0
    for i, sheet in sheets:
        P = ic.absolute[g.base].point[i] / sheet.mu_l
        assert len(sheet.lines) >= 2
        if sheet.centre.xy is None:
            continue
        drawn += 1
        assert np.linalg.norm(np.subtract(sheet.centre.xy, P)) <= PRECISION_MM
        for line in sheet.lines:
            a, b = np.array(line.start), np.array(line.end)
            u = (b - a) / np.linalg.norm(b - a)
            assert abs(float(u[0] * (P - a)[1] - u[1] * (P - a)[0])) <= PRECISION_MM, line.through
        for ray in sheet.rays:     # P_j–X, measured in metres
            assert ray.value == pytest.approx(np.linalg.norm(np.subtract(ray.end, ray.start)) * sheet.mu_l, rel=1e-12)
    assert drawn > 0


@pytest.mark.parametrize("name", SCENES)
def test_scale_from_the_crank_pin(name):
    """K_V × py = ω1 · l_OY, Y the crank's pin the driven rod is pinned to."""
    motion, g, sheets = _sheets(name)
    drive = motion.mechanism.drive
    rod = next(r for r in g.rods if r.outer.b != "0")
    assert rod.outer.b == drive.link
    y, o = rod.outer.point, drive.pivot
    for i, sheet in sheets:
        py = next(v for v in sheet.plan.vectors if v.quantity == f"v:{y}")
        l_oy = float(np.linalg.norm(motion.position(y)[i] - motion.position(o)[i]))
        assert sheet.k_v * py.length == pytest.approx(abs(drive.speed) * l_oy, rel=1e-9)
        assert any(s.startswith("4) K_{V}") and f"= {sheet.k_v:.4g} (m/s)/mm" in s for s in sheet.steps)


@pytest.mark.parametrize("name", SCENES)
def test_proportion_holds(name):
    """pb/P_jB = pc/P_jC = pd/P_jD to 1e-9, and each |px| × K_V is |v_X|."""
    motion, g, sheets = _sheets(name)
    for i, sheet in sheets:
        ratios = [q / s for _, q, s in sheet.proportion]
        assert len(ratios) == 3
        assert max(ratios) - min(ratios) <= 1e-9 * max(ratios)
        for pin, q, _ in sheet.proportion:
            assert q * sheet.k_v == pytest.approx(float(np.linalg.norm(motion.velocity(pin, g.base)[i])), rel=1e-9)
        assert sheet.proportion[0][1] == pytest.approx(sheet.segment, rel=1e-12)


@pytest.mark.parametrize("name", SCENES)
def test_special_point_vectors_in_the_plan_scale(name):
    """V_S drawn from S: length × K_V = |v_S| of the special-point solution, direction v_S,
    and the line through S ⊥ V_S passes through P_j."""
    motion, g, sheets = _sheets(name)
    drawn = 0
    for i, sheet in sheets:
        states = {n: s.take(np.array([i])) for n, s in motion.links.items()}
        sol = {p.name: p for p in special.solve_triad(g, motion.mechanism, states, order=1).points}
        for v in sheet.vectors:
            drawn += 1
            p = sol[v.name]
            assert np.linalg.norm(np.subtract(v.tail, p.position[0] / sheet.mu_l)) <= PRECISION_MM
            d = np.subtract(v.head, v.tail)
            assert np.linalg.norm(d) * sheet.k_v == pytest.approx(float(np.linalg.norm(p.v[0])), rel=1e-9)
            assert np.linalg.norm(d / np.linalg.norm(d) - p.v[0] / np.linalg.norm(p.v[0])) <= 1e-9
            if sheet.centre.xy is not None:
                assert abs(float(np.dot(d, np.subtract(sheet.centre.xy, v.tail)))) <= 1e-6 * np.linalg.norm(d) * \
                    max(1.0, np.linalg.norm(np.subtract(sheet.centre.xy, v.tail)))
    assert drawn > 0


def test_variant2_at_45_draws_the_construction(tmp_path):
    """koshel_variant2 at 45°: P5 where AB and KC meet (it is S1), V_S2 drawn from S2, the
    steps on the sheet, and every tagged group measured by plans check."""
    assert main(["render", str(EXAMPLES / "koshel_variant2.toml"), "-o", str(tmp_path), "-q"]) == 0
    svg = tmp_path / "koshel_variant2-koshel-45.svg"
    text = svg.read_text(encoding="utf-8")
    assert 'data-plan="bound"' in text and 'data-quantity="v:S2"' in text
    assert 'data-plan="velocity"' in text and 'data-quantity="r:B/P5"' in text
    for step in ("1)", "2)", "3)", "4)", "5)"):
        assert f">{step} " in text or f">{step}<" in text or step in text
    r = inspect_svg(svg)
    assert r.ok, r.problems
    plans = {m.plan for m in r.measurements}
    assert plans == {"velocity", "centres", "bound"}


def test_every_koshel_sheet_of_the_examples_passes_check(tmp_path, capsys):
    scenes = [str(EXAMPLES / f"{n}.toml") for n in SCENES + ["triad_at_rest"]]
    assert main(["render", *scenes, "-o", str(tmp_path), "-q"]) == 0
    svgs = sorted(str(p) for p in tmp_path.glob("*koshel*.svg"))
    assert len(svgs) >= 20
    capsys.readouterr()
    assert main(["check", *svgs]) == 0
    assert f"0 of {len(svgs)} files failed" in capsys.readouterr().out


def test_bound_vectors_are_measured_not_closed(tmp_path):
    """A V_S drawn too long fails its length check; two of them never form a closure."""
    assert main(["render", str(EXAMPLES / "koshel_variant1.toml"), "-o", str(tmp_path), "-q"]) == 0
    svg = tmp_path / "koshel_variant1-koshel-45.svg"
    r = inspect_svg(svg)
    assert r.ok and not any("special" in c.plan for c in r.closures)
    assert "koshel-45-special" not in r.equations
    src = svg.read_text(encoding="utf-8")
    import re
    m = re.search(r'<line[^>]*data-quantity="v:S1"[^>]*>', src)
    tag = m.group(0)
    x2 = re.search(r'x2="([-0-9.]+)"', tag)
    bad = tag.replace(x2.group(0), f'x2="{float(x2.group(1)) + 5.0:g}"')
    doctored = tmp_path / "bad.svg"
    doctored.write_text(src.replace(tag, bad), encoding="utf-8")
    r = inspect_svg(doctored)
    assert not r.ok and any(mm.quantity == "v:S1" and not mm.ok for mm in r.measurements)

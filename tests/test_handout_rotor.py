"""plans handout on a rotor (issue 37 item 5): random masses, radii, angles and planes around
Khurmi & Gupta's Example 21.2 (examples/balancing/rotor_four_masses.toml), the key the
-balancing sheet and the JSON, the assignment the data table and empty areas for the couple and
force polygons, and Moodle fields for the balancing masses and angles.

The asked values are checked against a second solution written here — each balancing mass from
the couples about the *other* balancing plane (not the textbook's couple-then-force route plans
takes) — and the answers put back on the rotor must balance it; the draws must stay physical:
masses within ±50 %, radii within ±20 %, angles in 15° steps, the planes in the base's order,
the balancing planes where the base has them, the balancing masses within 0.05…20 × the base's.
"""

from __future__ import annotations

import cmath
import json
import math
import re
import tomllib
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from plans.checking import inspect_svg
from plans.cli import main
from plans.handout import (Asked, assignment_sheets, cloze_field, random_variants, read_variants, solve_variant,
                           variant_asked)
from plans.layout import measure_layout
from plans.pipeline import render
from plans.scene import parse_scene

from conftest import refused_handout, sheet_words

ROOT = Path(__file__).resolve().parent.parent
BASE = ROOT / "examples" / "balancing" / "rotor_four_masses.toml"
BASE_DATA = tomllib.loads(BASE.read_text(encoding="utf-8"))
FIELD = re.compile(r"\{1:NUMERICAL:([^}]+)\}")
TOLERANCE = 0.02


def moodle_accepts(response: float, field: str) -> bool:
    """Whether Moodle marks ``response`` right in a NUMERICAL field's answers (``=a:t~=b:u``)."""
    for alternative in field.split("~"):
        a, t = (float(x) for x in alternative.lstrip("=").split(":"))
        slack = t + 1e-14 * max(t, abs(a), 1e-14)
        if a - slack <= response <= a + slack:
            return True
    return False


def by_moments(masses: list[dict], planes: list[float], radii: list[float]) -> list[tuple[float, float]]:
    """(mass kg, angle °) in each balancing plane by taking couples about the other one: the
    mass in L balances the couple of the masses about M, the mass in M the couple about L."""
    def phasor(m: dict) -> complex:
        return m["mass"] * m["radius"] * cmath.exp(1j * math.radians(m["angle"]))

    out = []
    for here, there in ((0, 1), (1, 0)):
        couple = sum(phasor(m) * (m["plane"] - planes[there]) for m in masses)
        u = -couple / (planes[here] - planes[there])           # m·r of the balancing mass here
        out.append((abs(u) / radii[here], math.degrees(cmath.phase(u)) % 360.0))
    return out


def _scene_masses(folder: Path) -> tuple[list[dict], list[float], list[float]]:
    data = tomllib.loads(next(folder.glob("variant-*.toml")).read_text(encoding="utf-8"))["rotor"]
    return data["masses"], data["balance"]["planes"], data["balance"]["radius"]


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("rotor")
    out, bank = tmp / "out", tmp / "quiz.xml"
    assert main(["handout", str(BASE), "--random", "5", "--seed", "4", "-o", str(out), "--moodle", str(bank),
                 "-q"]) == 0
    return out, bank.read_text(encoding="utf-8")


def test_the_hand_solution_of_the_base_is_the_books():
    """The second solution on Example 21.2 itself: the book's masses measured off its polygons,
    X ≈ 355 kg and Y ≈ 182.5 kg (within the 2 % a drawn polygon gives, tests/test_rotor.py)."""
    r = BASE_DATA["rotor"]
    (mx, _), (my, _) = by_moments(r["masses"], r["balance"]["planes"], r["balance"]["radius"])
    assert mx == pytest.approx(355.0, rel=0.02) and my == pytest.approx(182.5, rel=0.02)


def test_every_key_is_the_balancing_sheet_and_passes_plans_check(made):
    out, _ = made
    folders = sorted(out.glob("variant-*"))
    assert len(folders) == 5
    for folder in folders:
        n = folder.name
        assert {p.name for p in folder.iterdir()} == {f"{n}-assignment.svg", f"{n}-assignment.pdf",
                                                      f"{n}-balancing.svg", f"{n}-balancing.pdf", f"{n}.json",
                                                      f"{n}.toml"}
        report = inspect_svg(folder / f"{n}-balancing.svg")
        assert report.ok, report.problems[:3]


def test_the_asked_values_are_the_second_solutions_and_balance_the_rotor(made):
    out, _ = made
    for folder in sorted(out.glob("variant-*")):
        masses, planes, radii = _scene_masses(folder)
        report = json.loads((folder / f"{folder.name}.json").read_text(encoding="utf-8"))
        hand = by_moments(masses, planes, radii)
        for (m, angle), b in zip(hand, report["rotor"]["balancing"]):
            assert b["mass"] == pytest.approx(m, rel=1e-12)
            assert abs((b["angle"] - angle + 180.0) % 360.0 - 180.0) < 1e-9
        # put back on the rotor, the balancing masses leave no force and no couple (to rounding)
        bal = [{"mass": b["mass"], "radius": r, "angle": b["angle"], "plane": p}
               for b, r, p in zip(report["rotor"]["balancing"], radii, planes)]
        every = masses + bal
        force = sum(m["mass"] * m["radius"] * cmath.exp(1j * math.radians(m["angle"])) for m in every)
        couple = sum(m["mass"] * m["radius"] * m["plane"] * cmath.exp(1j * math.radians(m["angle"])) for m in every)
        size = sum(m["mass"] * m["radius"] for m in every)
        assert abs(force) < 1e-12 * size and abs(couple) < 1e-12 * size * max(map(abs, planes + [1.0]))


def test_the_draws_stay_physical():
    h, drawn = random_variants(BASE, 12, 8)
    base = BASE_DATA["rotor"]
    base_balancing = render(parse_scene(BASE_DATA)).report
    places = sorted({m["plane"] for m in base["masses"]} | set(base["balance"]["planes"]))
    for d in drawn:
        r = d.scene.rotor
        assert r.planes == tuple(base["balance"]["planes"]) and r.radii == tuple(base["balance"]["radius"])
        order = []
        for m, m0 in zip(r.masses, base["masses"]):
            assert 0.5 * m0["mass"] * 0.995 <= m.mass <= 1.5 * m0["mass"] * 1.005
            assert 0.8 * m0["radius"] * 0.995 <= m.radius <= 1.2 * m0["radius"] * 1.005
            assert m.angle % 15.0 == 0.0 and 0.0 <= m.angle < 360.0
            k = places.index(m0["plane"])
            gap = min(abs(places[k] - places[j]) for j in (k - 1, k + 1) if 0 <= j < len(places))
            assert abs(m.plane - m0["plane"]) <= 0.4 * gap + 0.0005 and m.plane >= 0.0
            order.append(m.plane)
        every = sorted([(p, "b") for p in r.planes] + [(p, "m") for p in order])
        assert [w for _, w in every] == [w for _, w in sorted([(p, "b") for p in r.planes] +
                                                              [(m["plane"], "m") for m in base["masses"]])]
        assert len({p for p, _ in every}) == len(every)          # distinct: no mass in a balancing plane
        for b, b0 in zip(d.sheets.report["rotor"]["balancing"], base_balancing["rotor"]["balancing"]):
            assert 0.05 <= b["mass"] / b0["mass"] <= 20.0
    assert len({d.scene.rotor.masses[0].angle for d in drawn}) > 3
    again = random_variants(BASE, 12, 8)[0]
    assert again.variants == h.variants                        # the same seed, the same variants


def test_the_assignment_gives_the_data_and_frames_the_polygons(made):
    out, _ = made
    for folder in sorted(out.glob("variant-*")):
        svg = (folder / f"{folder.name}-assignment.svg").read_text(encoding="utf-8")
        assert 'data-sheet="assignment"' in svg and "data-quantity" not in svg      # no answer on it
        report = measure_layout(svg)
        assert report.clean, report
        words = sheet_words(svg)
        assert "couple polygon" in words and "force polygon" in words and "reference plane" in words
        masses = _scene_masses(folder)[0]
        for m in masses:
            for v in (m["mass"], m["radius"], m["angle"], m["plane"]):
                assert f"{v:g}" in words.split("\n"), (folder.name, v)
        assert words.split("\n").count("?") == 4                      # m and θ of L and M
        areas = re.findall(r'data-area="([a-z]+)"', svg)
        assert areas == ["couple", "force"]


def test_the_moodle_fields_mark_the_second_solution_right(made):
    out, bank = made
    root = ET.fromstring(bank.encode("utf-8"))
    questions = root.findall("question")[1:]
    assert len(questions) == 5
    for q, folder in zip(questions, sorted(out.glob("variant-*"))):
        fields = FIELD.findall(q.find("questiontext/text").text)
        assert len(fields) == 4                                        # m_L, θ_L, m_M, θ_M
        hand = by_moments(*_scene_masses(folder))
        for (m, angle), f_m, f_a in zip(hand, fields[0::2], fields[1::2]):
            assert moodle_accepts(m, f_m) and moodle_accepts(m * (1 + 0.999 * TOLERANCE), f_m)
            assert moodle_accepts(angle, f_a)
            t = float(f_a.split("~")[0].split(":")[1])
            assert 1.0 < t < 10.0                                      # ± its drawing precision, in degrees
            assert not moodle_accepts(angle + 1.01 * t, f_a) and not moodle_accepts(angle + 180.0, f_a)


def test_an_angle_near_zero_is_right_either_side_of_it():
    near = Asked("θ_{L}", "°", "angle", 359.5, precision=1.5, angle=True)
    field = FIELD.search(cloze_field(near, TOLERANCE)).group(1)
    assert moodle_accepts(0.4, field) and moodle_accepts(358.1, field) and moodle_accepts(-1.0, field)
    assert not moodle_accepts(1.1, field) and not moodle_accepts(357.9, field)
    low = Asked("θ_{L}", "°", "angle", 0.5, precision=1.5, angle=True)
    field = FIELD.search(cloze_field(low, TOLERANCE)).group(1)
    assert moodle_accepts(359.2, field) and moodle_accepts(1.9, field) and not moodle_accepts(358.9, field)
    mid = Asked("θ_{L}", "°", "angle", 180.0, precision=1.5, angle=True)
    assert "~" not in cloze_field(mid, 0.5)                    # one answer, ±1.5°: never ±50 % of 180°


def test_a_variants_file_sets_the_masses(tmp_path):
    (tmp_path / "v.toml").write_text(f'base = "{BASE.as_posix()}"\n\n[[variant]]\nmasses = [{{ mass = 250.0 }}, {{}}, '
                                     "{ angle = 130.0, plane = 0.45 }]\n", encoding="utf-8")
    h = read_variants(tmp_path / "v.toml")
    d = solve_variant(h, h.variants[0])
    m = d.scene.rotor.masses
    assert (m[0].mass, m[1].mass, m[2].angle, m[2].plane, m[3].mass) == (250.0, 300.0, 130.0, 0.45, 200.0)
    want = by_moments([{"mass": x.mass, "radius": x.radius, "angle": x.angle, "plane": x.plane} for x in m],
                      [0.1, 0.5], [0.1, 0.1])
    got = {a.symbol: a.value for a in variant_asked(d)}
    assert got["m_{L}"] == pytest.approx(want[0][0], rel=1e-12) and got["m_{M}"] == pytest.approx(want[1][0], rel=1e-12)


@pytest.mark.parametrize("variant, words", [
    ("lengths = { OA = 0.1 }", "unknown key 'lengths'"),
    ("masses = [{ colour = 1.0 }]", "unknown key 'colour'"),
    ("masses = [{}, {}, {}, {}, {}]", "at most 4 tables"),
    ("masses = [{ mass = -5.0 }]", "0 kg or more"),
    ("masses = [{ mass = \"heavy\" }]", "must be a number"),
    ("masses = 3", "at most 4 tables"),
])
def test_bad_rotor_variants_are_refused_in_one_line(tmp_path, variant, words):
    (tmp_path / "base.toml").write_text(BASE.read_text(encoding="utf-8"), encoding="utf-8")
    (tmp_path / "class.toml").write_text(f'base = "base.toml"\n\n[[variant]]\n{variant}\n', encoding="utf-8")
    line = refused_handout(tmp_path, str(tmp_path / "class.toml"))
    assert words in line and "class.toml" in line and "variant[0]" in line, line


def test_a_rotor_without_its_sheet_or_needing_no_mass_is_refused(tmp_path):
    text = BASE.read_text(encoding="utf-8")
    (tmp_path / "bare.toml").write_text(text.replace('draw = ["balancing"]', "draw = []"), encoding="utf-8")
    line = refused_handout(tmp_path, str(tmp_path / "bare.toml"), "--random", "2")
    assert "plans.draw" in line and '["balancing"]' in line, line
    # two equal masses opposite in one plane, in plane L: nothing to balance anywhere
    (tmp_path / "still.toml").write_text(
        'title = "balanced"\n[plans]\ndraw = ["balancing"]\n[rotor]\nmasses = [{ mass = 1.0, radius = 0.1, angle = '
        '0.0, plane = 0.3 }, { mass = 1.0, radius = 0.1, angle = 180.0, plane = 0.3 }]\nbalance = { planes = [0.0, '
        '0.6], radius = 0.1 }\n', encoding="utf-8")
    line = refused_handout(tmp_path, str(tmp_path / "still.toml"), "--random", "2")
    assert "needs none in plane L" in line, line


def test_a_static_rotor_asks_one_mass_and_frames_the_force_polygon(tmp_path):
    (tmp_path / "static.toml").write_text(
        'title = "three masses in one plane"\n[plans]\ndraw = ["balancing"]\n[rotor]\nmasses = [{ mass = 5.0, '
        'radius = 0.2, angle = 0.0 }, { mass = 4.0, radius = 0.25, angle = 80.0 }, { mass = 3.0, radius = 0.1, '
        'angle = 200.0 }]\nbalance = { planes = [0.0], radius = 0.2 }\n', encoding="utf-8")
    h, drawn = random_variants(tmp_path / "static.toml", 3, 1)
    for d in drawn:
        items = variant_asked(d)
        assert [a.symbol for a in items] == ["m_{L}", "θ_{L}"]
        u = -sum(m.mass * m.radius * cmath.exp(1j * math.radians(m.angle)) for m in d.scene.rotor.masses)
        assert items[0].value == pytest.approx(abs(u) / 0.2, rel=1e-12)
        sheets = assignment_sheets(h, d, items)
        svg = next(iter(sheets.values()))
        assert re.findall(r'data-area="([a-z]+)"', svg) == ["force"] and measure_layout(svg).clean


def test_twenty_masses_fit_the_sheet_and_twenty_one_are_refused(tmp_path):
    def rotor(n: int) -> str:
        masses = ", ".join(f"{{ mass = {10 + k}.0, radius = 0.1, angle = {15 * k}.0, plane = {0.05 * (k + 1):.2f} }}"
                           for k in range(n))
        return (f'title = "{n} masses"\n[plans]\ndraw = ["balancing"]\n[rotor]\nmasses = [{masses}]\n'
                "balance = { planes = [0.0, 1.2], radius = 0.1 }\n")

    (tmp_path / "twenty.toml").write_text(rotor(20), encoding="utf-8")
    h, drawn = random_variants(tmp_path / "twenty.toml", 1, 0)
    for svg in assignment_sheets(h, drawn[0], variant_asked(drawn[0])).values():
        assert measure_layout(svg).clean, measure_layout(svg)
    (tmp_path / "many.toml").write_text(rotor(21), encoding="utf-8")
    line = refused_handout(tmp_path, str(tmp_path / "many.toml"), "--random", "1")
    assert "21 masses" in line and "at most 20" in line, line


def test_polygons_too_tall_for_one_column_put_the_force_polygon_on_an_answer_sheet(tmp_path):
    """Six masses whose polygons are each some 135 mm tall with their captions: the couple
    polygon's area on the assignment sheet, the force polygon's on answer sheet 2, which the task
    names; both sheets laid out clean."""
    masses = ", ".join(f"{{ mass = {m}, radius = 0.1, angle = {a}, plane = {p} }}" for m, a, p in (
        (2.12, 120.0, 0.1), (5.88, 285.0, 0.2), (8.21, 60.0, 0.3), (7.22, 240.0, 0.4), (1.14, 210.0, 0.5),
        (4.8, 240.0, 0.6)))
    (tmp_path / "tall.toml").write_text(f'title = "six masses"\n[plans]\ndraw = ["balancing"]\n[rotor]\nmasses = '
                                        f"[{masses}]\nbalance = {{ planes = [0.0, 0.7], radius = 0.1 }}\n",
                                        encoding="utf-8")
    (tmp_path / "v.toml").write_text('base = "tall.toml"\n\n[[variant]]\n', encoding="utf-8")
    h = read_variants(tmp_path / "v.toml")
    d = solve_variant(h, h.variants[0])
    sheets = list(assignment_sheets(h, d, variant_asked(d)).items())
    assert [name for name, _ in sheets] == ["variant-01-assignment.svg", "variant-01-assignment-2.svg"]
    (_, first), (_, second) = sheets
    assert re.findall(r'data-area="([a-z]+)"', first) == ["couple"]
    assert re.findall(r'data-area="([a-z]+)"', second) == ["force"]
    assert "Answer sheet 2: Force polygon." in " ".join(sheet_words(first).split("\n"))
    assert measure_layout(first).clean and measure_layout(second).clean


def test_the_written_variants_and_scene_files_give_the_same_keys(made, tmp_path):
    """variants.toml (every mass written) redraws every key byte for byte, and each variant's
    own scene file renders its JSON again."""
    import plans

    out, _ = made
    assert main(["handout", str(out / "variants.toml"), "-o", str(tmp_path / "again"), "-q"]) == 0
    for j in sorted(out.glob("variant-*/*.json")):
        assert (tmp_path / "again" / j.parent.name / j.name).read_bytes() == j.read_bytes()
        direct = plans.render(j.with_suffix(".toml"))
        assert json.loads(direct.json)["rotor"] == json.loads(j.read_text(encoding="utf-8"))["rotor"]

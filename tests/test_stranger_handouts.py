"""plans handout as a teacher who did not write it uses it: representative examples of each
kind handed out (exit 0 or one line naming the key; every SVG passes plans check, each answer
key finite, index.html's links resolve), the command's edge inputs (one line naming the
culprit, exit 2, nothing written), and what a second run into the same folder leaves."""

from __future__ import annotations

import json
import math
import re
import shutil
import xml.etree.ElementTree as ET
from html.parser import HTMLParser
from pathlib import Path

import pytest

from plans.checking import inspect_svg
from plans.cli import main
from plans.handout import parse_tolerance
from plans.errors import OutputError

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
SVG = "{http://www.w3.org/2000/svg}"
ANSWER_SHEET = re.compile(r"-assignment-\d+\.svg$")
#: Half the writer's rounding of a coordinate (Style().precision = 0.0005 mm), two ends: mm.
ENDS_MM = 2 * 0.0005


def _run(capsys, *args: str) -> tuple[int, str]:
    code = main(["handout", *args])
    return code, capsys.readouterr().err


def _refused(capsys, *args: str, words: tuple[str, ...] = ()) -> str:
    code, err = _run(capsys, *args)
    assert code == 2, err
    assert err.count("\n") == 1 and err.startswith("plans: error: ") and "Traceback" not in err, err
    for w in words:
        assert w in err, (w, err)
    return err


class _Links(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.links: list[str] = []

    def handle_starttag(self, tag, attrs) -> None:
        self.links += [v for k, v in attrs if k in ("href", "src") and v and not v.startswith("#")]


def _finite(x, where: str = "") -> None:
    if isinstance(x, dict):
        for k, v in x.items():
            _finite(v, f"{where}.{k}")
    elif isinstance(x, list):
        for k, v in enumerate(x):
            _finite(v, f"{where}[{k}]")
    elif isinstance(x, float):
        assert math.isfinite(x), where


@pytest.mark.parametrize("example", ["four_bar_gravity.toml", "gears/gear_idler_1_18.toml",
                                     "balancing/rotor_four_masses.toml", "flywheel/engine_crank_slider.toml"])
def test_an_example_of_each_kind_hands_out_checked_files(tmp_path, capsys, example):
    """Every sheet but an answer sheet passes plans check (the assignment as a scheme: nothing to
    measure), every key's JSON is finite, every link of index.html is a file written, and every
    SVG written is shown on the page."""
    out = tmp_path / "out"
    code, err = _run(capsys, str(EXAMPLES / example), "--random", "2", "--seed", "1", "-o", str(out), "-q")
    assert code == 0, err
    svgs = sorted(out.glob("variant-*/*.svg"))
    assert svgs
    for svg in svgs:
        if ANSWER_SHEET.search(svg.name):
            continue            # see test_answer_sheets_pass_plans_check
        r = inspect_svg(svg)
        assert r.ok, (svg.name, r.problems)
        if svg.name.endswith("-assignment.svg"):
            assert r.kind == "scheme", svg.name
    for j in out.glob("variant-*/*.json"):
        _finite(json.loads(j.read_text(encoding="utf-8")), j.name)
    page = _Links()
    page.feed((out / "index.html").read_text(encoding="utf-8"))
    assert page.links and all((out / link).is_file() for link in page.links)
    assert {str(p.relative_to(out)) for p in svgs} <= set(page.links)


def test_answer_sheets_pass_plans_check(tmp_path, capsys):
    """An answer sheet (-assignment-2.svg) has only framed areas: plans check reads it as an
    assignment sheet with nothing to measure (it failed them as "not a plan written by plans")."""
    out = tmp_path / "out"
    assert _run(capsys, str(EXAMPLES / "shaking/four_bar_balanced.toml"), "--random", "1", "-o", str(out), "-q")[0] == 0
    sheets = sorted(out.glob("variant-*/*-assignment-*.svg"))
    assert sheets
    reports = [inspect_svg(s) for s in sheets]
    assert all(r.ok and r.kind == "assignment" and not r.measurements for r in reports)


def test_rotor_assignment_is_a_scheme_drawn_at_its_scales(tmp_path, capsys):
    """The shaft's side view and the end view state their μ (plans check then reads the sheet as a
    scheme); the marks' distances × μ are the planes' distances and the masses' radii the
    variant's file gives."""
    out = tmp_path / "out"
    assert _run(capsys, str(EXAMPLES / "balancing/rotor_four_masses.toml"), "--random", "1", "--seed", "3",
                "-o", str(out), "-q")[0] == 0
    import tomllib
    masses = tomllib.loads((out / "variants.toml").read_text(encoding="utf-8"))["variant"][0]["masses"]
    base = tomllib.loads((EXAMPLES / "balancing/rotor_four_masses.toml").read_text(encoding="utf-8"))
    planes = dict(zip(("L", "M"), base["rotor"]["balance"]["planes"]))
    svg = out / "variant-01/variant-01-assignment.svg"
    assert inspect_svg(svg).kind == "scheme"
    root = ET.parse(svg).getroot()
    by_id = {e.get("id"): e for e in root.iter() if e.get("id")}
    shaft, end = by_id["assignment-shaft"], by_id["assignment-end"]
    assert shaft.get("data-plan") == end.get("data-plan") == "scheme"
    mu_l, mu_r = float(shaft.get("data-mu")), float(end.get("data-mu"))
    caption = "".join(t for e in root.iter(f"{SVG}text") for t in e.itertext())
    assert f"μl = {mu_l:g} m/mm" in caption.replace("_", "") and f"μr = {mu_r:g} m/mm" in caption.replace("_", "")
    marks = {"".join(by_id[f"assignment-shaft-n{k}"].itertext()).strip(): float(by_id[f"assignment-shaft-plane{k}"].get("x1"))
             for k in range(len(masses) + 2)}
    at = {**{str(k + 1): m["plane"] for k, m in enumerate(masses)}, **planes}
    for name, x in marks.items():
        assert math.isclose((x - marks["L"]) * mu_l, at[name] - planes["L"], abs_tol=ENDS_MM * mu_l), name
    centre = by_id["assignment-end-shaft"]
    cx, cy = float(centre.get("cx")), float(centre.get("cy"))
    for k, m in enumerate(masses):
        r = by_id[f"assignment-end-r{k}"]
        drawn = math.hypot(float(r.get("x2")) - cx, float(r.get("y2")) - cy)
        assert math.isclose(drawn * mu_r, m["radius"], abs_tol=ENDS_MM * mu_r), k


def test_forces_task_names_the_one_position_it_asks(tmp_path, capsys):
    """A loaded base of 24 positions: the answers are at the first; the task says which, not
    "at the given position" beside a list of 24."""
    out = tmp_path / "out"
    assert _run(capsys, str(EXAMPLES / "crank_slider_forces.toml"), "--random", "1", "--seed", "1",
                "-o", str(out), "-q")[0] == 0
    import tomllib
    angle = tomllib.loads((out / "variants.toml").read_text(encoding="utf-8"))["variant"][0]["angle"]
    root = ET.parse(out / "variant-01/variant-01-assignment.svg").getroot()
    task = next("".join(e.itertext()) for e in root.iter(f"{SVG}text") if "Task:" in "".join(e.itertext()))
    assert f"Task: at φ1 = {angle:g}° (the first given position) draw" in task


def test_a_second_handout_into_a_folder_of_another_is_refused(tmp_path, capsys):
    """The same command again writes the same files over; one with fewer variants, or of another
    scene, would leave the first's sheets among its own (a gear train's key beside a four-bar's
    velocity plan): refused in one line, nothing written; a teacher's own file stays."""
    out = tmp_path / "out"
    out.mkdir()
    (out / "notes.txt").write_text("mine", encoding="utf-8")
    four_bar = str(EXAMPLES / "four_bar.toml")
    assert _run(capsys, four_bar, "--random", "2", "-o", str(out), "-q")[0] == 0
    before = {p: p.read_bytes() for p in out.rglob("*") if p.is_file()}
    assert _run(capsys, four_bar, "--random", "2", "-o", str(out), "-q")[0] == 0
    assert {p: p.read_bytes() for p in out.rglob("*") if p.is_file()} == before
    _refused(capsys, four_bar, "--random", "1", "-o", str(out), "-q", words=("[-o]", "variant-02", "earlier handout"))
    _refused(capsys, str(EXAMPLES / "gears/gear_idler_1_18.toml"), "--random", "2", "-o", str(out), "-q",
             words=("[-o]", "variant-01/variant-01-acceleration", "earlier handout"))
    assert {p: p.read_bytes() for p in out.rglob("*") if p.is_file()} == before
    assert _run(capsys, four_bar, "--random", "3", "-o", str(out), "-q")[0] == 0      # more: all replaced


@pytest.mark.parametrize("extra, words", [
    (("--random", "0"), ("[--random]", "0 is out of range")),
    (("--random", "1000"), ("[--random]", "1 to 999")),
    (("--random", "two"), ("[--random]",)),
    (("--random", "2", "--seed", "-1"), ("[--seed]", "-1 is out of range")),
    (("--random", "2", "--seed", str(2 ** 70)), ("[--seed]", str(2 ** 70))),
    (("--random", "2", "--moodle", "{tmp}"), ("[--moodle]", ".xml")),
    (("--random", "2", "--moodle", "{tmp}/q.xml", "--tolerance", "0"), ("[--tolerance]", "0.01 %")),
    (("--random", "2", "--moodle", "{tmp}/q.xml", "--tolerance", "1e-9"), ("[--tolerance]", "'1e-9'")),
    (("--random", "2", "--moodle", "{tmp}/q.xml", "--tolerance", "100"), ("[--tolerance]", "100 % excluded")),
    (("--random", "2", "--moodle", "{tmp}/q.xml", "--tolerance", "101"), ("[--tolerance]", "'101'")),
    (("--random", "2", "--moodle", "{tmp}/q.xml", "--tolerance", "abc"), ("[--tolerance]", "'abc'")),
    (("--random", "2", "--tolerance", "5"), ("[--tolerance]", "--moodle")),
])
def test_edge_options_are_one_line_naming_the_option(tmp_path, capsys, extra, words):
    out = tmp_path / "out"
    args = [a.replace("{tmp}", str(tmp_path)) for a in extra]
    _refused(capsys, str(EXAMPLES / "four_bar.toml"), *args, "-o", str(out), "-q", words=words)
    assert not out.exists() and not (tmp_path / "q.xml").exists()


def test_output_onto_a_file_is_refused(tmp_path, capsys):
    target = tmp_path / "a.txt"
    target.write_text("x", encoding="utf-8")
    _refused(capsys, str(EXAMPLES / "four_bar.toml"), "--random", "1", "-o", str(target), words=("[-o]", "is a file"))
    assert target.read_text(encoding="utf-8") == "x"


def test_tolerance_bounds():
    assert math.isclose(parse_tolerance("99.99"), 0.9999) and parse_tolerance("0.01") == 1e-4
    with pytest.raises(OutputError, match="100 % excluded"):
        parse_tolerance("100%")


@pytest.mark.parametrize("example, words", [
    ("flywheel/punching_press.toml", ("[operation]", "flywheel problem")),
    ("gears/pair_rack.toml", ("[gear_pair]", "involute pair alone")),
    ("gears/synthesis_type_c.toml", ("[synthesis]", "copy the found wheels into [gears]")),
])
def test_a_scene_with_no_handout_says_why_in_one_line(tmp_path, capsys, example, words):
    _refused(capsys, str(EXAMPLES / example), "--random", "2", "--seed", "1", "-o", str(tmp_path / "o"), words=words)
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("body, words", [
    ("", ("[variant]", "no variants")),
    ("variant = []\n", ("[variant]", "no variants")),
    ("[[variant]]\nomega = 5.0\nspeed = 3\n", ("[variant[0].speed]", "unknown key 'speed'")),
    ("[[variant]]\nlengths = { OC = 0.6 }\n", ("[variant[0]]", "cannot assemble", "0.05 and 0.45 m")),
    ("[[variant]]\nlengths = { AB = 5.0 }\n", ("[variant[0]]", "cannot form a triangle")),
    ("[[variant]]\nomega = 0.0\nepsilon = 0.0\n", ("[variant[0]]", "nothing to find")),
])
def test_a_bad_variants_file_is_one_line_and_nothing_written(tmp_path, capsys, body, words):
    shutil.copy(EXAMPLES / "four_bar.toml", tmp_path / "four_bar.toml")
    (tmp_path / "v.toml").write_text('base = "four_bar.toml"\n' + body, encoding="utf-8")
    _refused(capsys, str(tmp_path / "v.toml"), "-o", str(tmp_path / "o"), words=words)
    assert not (tmp_path / "o").exists()

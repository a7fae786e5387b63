"""plans handout: variants files and random variants, their assignment sheets, answer keys and
index page. Each answer key is compared with a direct plans.render of the variant's scene,
built here from the base scene and the variant's values (not by the code under test)."""

from __future__ import annotations

import io
import json
import math
import re
import shutil
import tempfile
import tomllib
from pathlib import Path

import pytest

import plans
import plans.export
from plans.cli import main
from plans.handout import LENGTH_SPREAD, MARGIN_SIN, SPEED_SERIES, Progress, to_toml

from conftest import EXAMPLES, press_without_cycle

CYCLE_PRESS = next(p for p in EXAMPLES if p.stem == "six_link_press")   # 12 positions and the cycle sheets
#: The six-link press without its cycle (angles 60° and 200°, three sheets each), whose sheets
#: and pages the tests count.
PRESS = press_without_cycle(Path(tempfile.mkdtemp(prefix="plans-press-")))
KEYS = {"angle": "angle", "omega": "omega", "epsilon": "epsilon"}
#: An assignment's sheets (the assignment, then its answer sheets ``-assignment-2.svg`` …): not keys.
ASSIGNMENT = re.compile(r"-assignment(-\d+)?\.svg$")


def _scene(base: Path, lengths: dict, drive: dict) -> plans.Scene:
    """The base scene with ``lengths`` and ``drive`` values replaced, built by hand."""
    data = tomllib.loads(base.read_text(encoding="utf-8"))
    data["lengths"].update(lengths)
    data["drive"].update(drive)
    return plans.parse_scene(data)


def _files(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def _handout(tmp: Path, *args: str) -> Path:
    out = tmp / "out"
    assert main(["handout", *args, "-o", str(out), "-q"]) == 0
    return out


@pytest.fixture(scope="module")
def random3(tmp_path_factory) -> Path:
    return _handout(tmp_path_factory.mktemp("random"), str(PRESS), "--random", "3", "--seed", "7")


def test_variants_file_keys_equal_a_direct_render(tmp_path):
    shutil.copy(PRESS, tmp_path / PRESS.name)
    given = [({"OA": 0.09, "AB": 0.36}, {"angle": 30.0, "omega": 10.0}),
             ({"CE": 0.4}, {"angle": [120.0, 250.0], "omega": -6.0, "epsilon": 2.0})]
    (tmp_path / "class.toml").write_text(
        f'base = "{PRESS.name}"\ntitle = "Homework 2"\n\n[[variant]]\nlengths = {{ OA = 0.09, AB = 0.36 }}\n'
        "angle = 30.0\nomega = 10.0\n\n[[variant]]\nlengths = { CE = 0.4 }\nangle = [120.0, 250.0]\nomega = -6.0\n"
        "epsilon = 2.0\n", encoding="utf-8")
    out = _handout(tmp_path, str(tmp_path / "class.toml"))
    for k, (lengths, drive) in enumerate(given, 1):
        name = f"variant-{k:02d}"
        folder = out / name
        direct = plans.render(_scene(PRESS, lengths, drive), stem=name)
        assert json.loads((folder / f"{name}.json").read_text(encoding="utf-8")) == direct.report
        for sheet in direct:          # every sheet the scene draws, in SVG (the same text) and PDF
            assert (folder / sheet.file).read_text(encoding="utf-8") == sheet.svg
            assert (folder / sheet.file.replace(".svg", ".pdf")).read_bytes().startswith(b"%PDF")
        assert (folder / f"{name}-assignment.svg").is_file() and (folder / f"{name}-assignment.pdf").is_file()
        # the variant's own scene file renders to the same key
        again = plans.render(folder / f"{name}.toml")
        assert again.report == direct.report
    assert len(list((out / "variant-02").glob("*-velocity-*.svg"))) == 2    # two positions: a sheet each
    assert (out / PRESS.name).read_bytes() == PRESS.read_bytes()
    html = (out / "index.html").read_text(encoding="utf-8")
    assert "Homework 2" in html


def test_assignment_sheet_says_the_data_and_leaves_room(tmp_path, random3):
    from conftest import sheet_words

    data = tomllib.loads((random3 / "variants.toml").read_text(encoding="utf-8"))
    v = data["variant"][0]
    svg = (random3 / "variant-01" / "variant-01-assignment.svg").read_text(encoding="utf-8")
    words = sheet_words(svg)
    for name, value in v["lengths"].items():
        assert f"l{name} = {value:g} m" in words
    assert f"φ1 = {v['angle']:g}°" in words and f"ω1 = {v['omega']:g} rad/s" in words
    assert "Velocity plan" in words and "Acceleration plan" in words and "Assignment, variant 01" in words
    assert 'data-area="velocity"' in svg and 'data-area="acceleration"' in svg
    assert plans.export.sheet_size_mm(svg) == (420.0, 297.0)     # A3 landscape
    assert "data-quantity" not in svg                       # no answer on the assignment
    from plans.layout import measure_layout

    layout = measure_layout(svg)
    assert all(v == 0 for v in layout.counts.values()), layout


def test_random_variants_within_ranges_margin_and_equal_direct_render(random3):
    base = tomllib.loads(PRESS.read_text(encoding="utf-8"))
    data = tomllib.loads((random3 / "variants.toml").read_text(encoding="utf-8"))
    assert data["base"] == PRESS.name and len(data["variant"]) == 3
    series = {m * 10.0 ** k for m in SPEED_SERIES for k in range(-1, 3)}
    for k, v in enumerate(data["variant"], 1):
        for name, x in v["lengths"].items():
            b = base["lengths"][name]
            # drawn within the spread, then rounded to 3 significant digits: ±0.5 % at most (exact)
            assert (1 - LENGTH_SPREAD) * b * 0.995 <= x <= (1 + LENGTH_SPREAD) * b * 1.005
            assert float(f"{x:.3g}") == x
        assert 0.0 <= v["angle"] < 360.0 and v["angle"] % 5.0 == 0.0
        assert any(math.isclose(v["omega"], s) for s in series) and 4.0 <= v["omega"] <= 16.0
        name = f"variant-{k:02d}"
        direct = plans.render(_scene(PRESS, v["lengths"], {"angle": v["angle"], "omega": v["omega"]}), stem=name)
        report = json.loads((random3 / name / f"{name}.json").read_text(encoding="utf-8"))
        assert report == direct.report
        for pos in report["positions"]:
            assert min(abs(c) for c in pos["conditioning"].values()) >= MARGIN_SIN
    html = (random3 / "index.html").read_text(encoding="utf-8")
    assert f"|condition| ≥ {MARGIN_SIN:g}" in html and f"II(2-3) {MARGIN_SIN:g}, II(4-5) {MARGIN_SIN:g}" in html


def test_a_class_iv_base_keeps_the_same_margin(tmp_path):
    """A class IV group's figure is the sine of a class II group generalised (0.43–0.74 in the
    example), so it keeps the same margin as any group, MARGIN_SIN, stated on the index page;
    every drawn variant keeps it; the assignment's data table stays tidy."""
    from plans.layout import measure_layout

    base = next(p for p in EXAMPLES if p.stem == "class4_six_link")
    out = _handout(tmp_path, str(base), "--random", "2", "--seed", "3")
    assert f"IV(2-3-4-5) {MARGIN_SIN:g}" in (out / "index.html").read_text(encoding="utf-8")
    for k in (1, 2):
        report = json.loads((out / f"variant-0{k}" / f"variant-0{k}.json").read_text(encoding="utf-8"))
        assert min(abs(c) for pos in report["positions"] for c in pos["conditioning"].values()) >= MARGIN_SIN
        layout = measure_layout((out / f"variant-0{k}" / f"variant-0{k}-assignment.svg").read_text(encoding="utf-8"))
        assert all(v == 0 for v in layout.counts.values()), layout


def test_same_seed_same_bytes_other_seed_other_variants(tmp_path, random3):
    again = _handout(tmp_path / "a", str(PRESS), "--random", "3", "--seed", "7")
    assert _files(again) == _files(random3)
    other = _handout(tmp_path / "b", str(PRESS), "--random", "3", "--seed", "8")
    assert (other / "variants.toml").read_bytes() != (random3 / "variants.toml").read_bytes()
    # the written variants file, beside the base's copy, gives the same answer keys again
    replay = _handout(tmp_path / "c", str(random3 / "variants.toml"))
    for k in (1, 2, 3):
        name = f"variant-{k:02d}"
        for f in (random3 / name).iterdir():
            assert (replay / name / f.name).read_bytes() == f.read_bytes()


def test_plans_check_passes_on_every_answer_key(random3, capsys):
    svgs = sorted(str(p) for p in random3.glob("variant-*/*.svg") if not ASSIGNMENT.search(p.name))
    assert len(svgs) == 9
    assert main(["check", *svgs]) == 0
    assert "0 of 9 files failed" in capsys.readouterr().out


def test_index_lists_every_variant_and_every_sheet(random3):
    html = (random3 / "index.html").read_text(encoding="utf-8")
    srcs = re.findall(r'<img class="sheet" src="([^"]+)"', html)
    on_disk = sorted(str(p.relative_to(random3)) for p in random3.glob("variant-*/*.svg"))
    assert sorted(srcs) == on_disk
    assert srcs[:3] == [f"variant-0{k}/variant-0{k}-assignment.svg" for k in (1, 2, 3)]   # assignments first
    assert "@page" in html and "size: A4" in html and "break-after: page" in html
    assert str(random3) not in html


def _fails(tmp_path, capsys, text: str, *extra: str) -> str:
    shutil.copy(PRESS, tmp_path / PRESS.name)
    (tmp_path / "v.toml").write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    assert main(["handout", str(tmp_path / "v.toml"), *extra, "-o", str(out)]) == 2
    assert not out.exists()
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("plans: error: ")
    return err


@pytest.mark.parametrize("text, words", [
    ('base = "six_link_press.toml"\n[[variant]\n', ["malformed TOML"]),
    ("[[variant]]\nangle = 3.0\n", ["[base]", "missing base"]),
    ('base = "nowhere.toml"\n[[variant]]\nangle = 3.0\n', ["[base]", "not found", "relative to the variants file"]),
    ('base = "six_link_press.toml"\n[[variant]]\nlengths = { XY = 0.1 }\n',
     ["[variant[0].lengths.XY]", "unknown length 'XY'", "OA, AB"]),
    ('base = "six_link_press.toml"\n[[variant]]\nlengths = { OA = -0.1 }\n',
     ["[variant[0].lengths.OA]", "must be positive"]),
    ('base = "six_link_press.toml"\n[[variant]]\nlengths = { OA = nan }\n',
     ["[variant[0].lengths.OA]", "not a finite number"]),
    ('base = "six_link_press.toml"\n[[variant]]\nangle = 3.0\n[[variant]]\nomega = inf\n',
     ["[variant[1].omega]", "not a finite number"]),
    ('base = "six_link_press.toml"\n[[variant]]\nvelocity = 1.0\n', ["[variant[0].velocity]", "use angle, omega"]),
    ('base = "six_link_press.toml"\n', ["[variant]", "no variants"]),
    ('base = "six_link_press.toml"\n[[variant]]\nomega = 1e9\n', ["[variant[0].omega]", "out of range", "variant-01"]),
    ('base = "six_link_press.toml"\n[[variant]]\nangle = 30.0\n[[variant]]\nlengths = { OA = 0.3 }\nangle = 200.0\n',
     ["[variant[1]]", "variant-02 cannot be drawn", "cannot assemble"]),
    ('base = "six_link_press.toml"\n[[variant]]\nlengths = { AB = 0.05 }\n',
     ["[variant[0]]", "variant-01 cannot be built", "triangle", "link 2"]),
])
def test_bad_variants_files_are_one_line_naming_the_key(tmp_path, capsys, text, words):
    err = _fails(tmp_path, capsys, text)
    for w in words:
        assert w in err


def test_bad_random_requests(tmp_path, capsys):
    out = tmp_path / "out"
    for args, words in (([str(PRESS)], ["is a scene", "--random N"]),
                        ([str(PRESS), "--random", "0"], ["[--random]", "from 1 to"]),
                        ([str(PRESS), "--random", "x"], ["not a whole number"]),
                        ([str(PRESS), "--random", "2", "--seed", "-1"], ["[--seed]"])):
        assert main(["handout", *args, "-o", str(out)]) == 2
        err = capsys.readouterr().err
        assert all(w in err for w in words) and err.count("\n") == 1
    assert not out.exists()


@pytest.mark.parametrize("scene", ["gears/planetary_1_21.toml", "gears/press_drive.toml", "four_bar.toml"])
def test_a_scene_given_without_random_says_to_add_it(tmp_path, capsys, scene):
    """A scene (a train alone too, which has no [points] or [drive]) given as if it were a
    variants file: one line naming the file and the fix (--random N), not "missing base"."""
    path = EXAMPLES[0].parent / scene
    out = tmp_path / "out"
    assert main(["handout", str(path), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and path.name in err and "is a scene" in err and "--random N" in err, err
    assert "missing base" not in err and not out.exists()


def test_progress_only_on_a_terminal():
    class Tty(io.StringIO):
        def isatty(self) -> bool:
            return True

    tty, pipe = Tty(), io.StringIO()
    for stream in (tty, pipe):
        bar = Progress(4, "drawing", stream)
        for k in range(1, 5):
            bar(k, f"variant-0{k}")
        bar.close()
    assert pipe.getvalue() == ""
    assert tty.getvalue().count("\r") == 4 and "4/4 variant-04" in tty.getvalue() and tty.getvalue().endswith("\n")


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_to_toml_round_trips_every_example(path):
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    assert tomllib.loads(to_toml(data)) == data


def test_a_cycle_base_gives_keys_with_the_cycle_sheets(tmp_path):
    """The bundled press (12 positions, sheets of their own at two of them, the cycle sheets):
    every random variant's key holds the sheets a direct render of its scene file draws, and
    plans check passes on them."""
    out = _handout(tmp_path, str(CYCLE_PRESS), "--random", "1", "--seed", "3")
    folder = out / "variant-01"
    direct = plans.render(folder / "variant-01.toml")
    names = {s.name for s in direct}
    assert {"positions", "diagrams", "velocities"} <= names
    names = {p.name for p in folder.glob("*.svg")}
    assert {n for n in names if not ASSIGNMENT.search(n)} == {s.file for s in direct}
    assert "variant-01-assignment.svg" in names
    assert main(["check", *(str(folder / s.file) for s in direct)]) == 0


def test_no_output_of_a_variants_folder_writes_over_an_input(tmp_path, capsys):
    """The variants file sits where the first variant's velocity plan (PDF) would go: refused in
    one line before anything is written; the file is unchanged."""
    (tmp_path / "variant-01").mkdir()
    mine = tmp_path / "variant-01" / "variant-01-velocity.pdf"
    text = f'# my class\nbase = "{PRESS.as_posix()}"\n[[variant]]\nangle = [30.0]\n'.encode()
    mine.write_bytes(text)
    assert main(["handout", str(mine), "-o", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "would overwrite the input file" in err and err.count("\n") == 1
    assert mine.read_bytes() == text
    assert sorted(str(p.relative_to(tmp_path)) for p in tmp_path.rglob("*")) == [
        "variant-01", "variant-01/variant-01-velocity.pdf"]


def test_index_page_of_random_variants_without_a_margin_argument():
    """index_html called as the API allows (seed set, no margin given) takes the handout's own
    margins; with none at all it leaves that sentence out instead of failing."""
    from dataclasses import replace

    from plans.handout import random_variants
    from plans.handout.index import index_html

    base = next(p for p in EXAMPLES if p.stem == "four_bar")
    h, drawn = random_variants(base, 1, 3)
    page = index_html(h, drawn)
    assert f"|condition| ≥ {h.margin:g}" in page and "point on a bar kept on it" in page
    bare = index_html(replace(h, margin=None), drawn)
    assert "Drawn at random with seed 3" in bare and "|condition| ≥" not in bare

"""The Python API's save and render arguments, and outputs that would replace inputs: each error
is a PlansError naming the argument (not the command line's flag), and nothing is written."""

from __future__ import annotations

import math
import os
import re
import shutil
import subprocess
import sys
import tomllib
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

import plans
from plans import export
from plans.errors import OutputError

from conftest import plans_cli

ROOT = Path(__file__).resolve().parent.parent
FOUR_BAR = ROOT / "examples" / "four_bar.toml"


@pytest.fixture(scope="module")
def sheets():
    return plans.render(FOUR_BAR)


@pytest.mark.parametrize("dpi", [0, 1, 5, 9.99, -5, math.nan, math.inf, -math.inf, 2401, "300", None, True])
def test_a_bad_dpi_names_dpi_and_writes_nothing(sheets, dpi, tmp_path):
    out = tmp_path / "out"
    with pytest.raises(OutputError) as err:
        sheets.save(out, ("svg", "png"), dpi=dpi)
    assert err.value.key == "dpi" and "--" not in str(err.value)
    assert not out.exists()
    with pytest.raises(OutputError):
        next(iter(sheets)).save(out, "png", dpi=dpi)
    assert not out.exists()


@pytest.mark.parametrize("formats", [None, "gif", "", ["svg", 3], 7, ("png", None)])
def test_bad_formats_name_formats(sheets, formats, tmp_path):
    with pytest.raises(OutputError) as err:
        sheets.save(tmp_path / "out", formats)
    assert err.value.key == "formats" and "--format" not in str(err.value)
    assert not (tmp_path / "out").exists()


def test_a_folder_below_a_file_names_folder(sheets, tmp_path):
    (tmp_path / "afile").write_text("x")
    with pytest.raises(OutputError) as err:
        sheets.save(tmp_path / "afile" / "sub")
    assert err.value.key == "folder" and "-o" not in err.value.message.replace(str(tmp_path), "")


def test_a_dpi_too_large_for_a_late_sheet_is_refused_before_any_png_is_drawn(sheets, tmp_path, monkeypatch):
    from plans import export

    drawn = []
    monkeypatch.setattr(export, "svg_to_png", lambda text, dpi: drawn.append(1) or b"")
    files = dict(sheets.files)
    big = next(n for n in files if n.endswith(".svg"))
    import re

    files["zz-late.svg"] = re.sub(r'(width|height)="([0-9.]+)mm"', lambda m: f'{m[1]}="{float(m[2]) * 10:g}mm"',
                                  files[big], count=2)
    assert files["zz-late.svg"] != files[big]
    with pytest.raises(OutputError) as err:
        export.convert(files, ("png",), 300.0)
    assert "zz-late.svg" in str(err.value) and drawn == []


def test_a_missing_sheet_lists_the_sheets(sheets):
    with pytest.raises(KeyError) as err:
        sheets["nosuch"]
    assert "scheme-0" in str(err.value) and "nosuch" in str(err.value)


@pytest.mark.parametrize("stem", ["a\nb", "a\tb", "a\x00b", "a/b", "..", " ", "x" * 500])
def test_a_stem_that_cannot_name_a_file_is_refused(stem):
    with pytest.raises(OutputError) as err:
        plans.render(FOUR_BAR, stem=stem)
    assert err.value.key == "stem"


def test_version_is_pyprojects():
    version = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["version"]
    assert plans.__version__ == version
    r = subprocess.run([sys.executable, "-m", "plans", "--version"], capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout.strip() == f"plans {version}"


def test_render_never_overwrites_its_own_scene(tmp_path):
    scene = tmp_path / "four_bar.json"               # a scene (TOML text) whose report has its name
    text = FOUR_BAR.read_bytes()
    scene.write_bytes(text)
    r = plans_cli(["render", "four_bar.json", "-o", "."], cwd=tmp_path)
    assert r.returncode == 2 and "would overwrite the input file" in r.stderr, r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    assert scene.read_bytes() == text and sorted(p.name for p in tmp_path.iterdir()) == ["four_bar.json"]


def _phys_dpi(png: bytes) -> float:
    """The resolution a PNG's pHYs chunk states, dots per inch."""
    at = png.index(b"pHYs")
    per_metre = int.from_bytes(png[at + 4:at + 8], "big")
    return per_metre * 25.4 / 1000


@pytest.mark.parametrize("dpi", [np.int64(100), np.float32(100.0), Fraction(100)])
def test_numpy_and_other_real_dpis_are_numbers(sheets, dpi, tmp_path):
    sheet = sheets["scheme-0"]
    written = sheet.save(tmp_path, "png", dpi=dpi)
    assert [p.name for p in written] == ["four_bar-scheme-0.png"]
    png = written[0].read_bytes()
    assert _phys_dpi(png) == pytest.approx(100, abs=0.02)          # round(100 / 25.4 * 1000) px/m
    width_mm = float(re.search(r'width="([0-9.]+)mm"', sheet.svg)[1])
    assert int.from_bytes(png[16:20], "big") == round(width_mm / 25.4 * 100)


def test_the_command_line_checks_every_scenes_png_size_before_drawing_any(tmp_path, monkeypatch, capsys):
    # at 1500 dpi the crank-slider's 297 × 210 mm sheets fit (17539 × 12402 px < 2**28), the
    # four-bar's 420 × 297 mm ones do not (24803 × 17539 px): refused before the first is drawn
    from plans import cli, export

    drawn = []
    monkeypatch.setattr(export, "svg_to_png", lambda text, dpi: drawn.append(1) or b"")
    out = tmp_path / "out"
    code = cli.main(["render", str(ROOT / "examples" / "crank_slider_central.toml"), str(FOUR_BAR),
                     "--format", "png", "--dpi", "1500", "-o", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and drawn == [] and not out.exists()
    assert err.startswith("plans: error: four_bar-") and "[--dpi]" in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("how", ["path", "scene"])
def test_save_never_overwrites_the_scene_it_was_rendered_from(tmp_path, how, monkeypatch):
    scene = tmp_path / "four_bar.json"               # a scene (TOML text) named like its own report
    text = FOUR_BAR.read_bytes()
    scene.write_bytes(text)
    monkeypatch.chdir(tmp_path)
    sheets = plans.render("four_bar.json" if how == "path" else plans.read_scene("four_bar.json"))
    monkeypatch.chdir(ROOT)                          # the scene is found wherever the Python session is
    drawn = []
    monkeypatch.setattr(export, "svg_to_png", lambda text, dpi: drawn.append(1) or b"")
    with pytest.raises(plans.PlansError) as err:
        sheets.save(tmp_path, ("svg", "png"))
    assert err.value.key == "folder" and "would overwrite the input file" in str(err.value)
    assert "-o" not in err.value.message.replace(str(tmp_path), "")
    assert drawn == []                               # refused before any sheet is drawn
    assert scene.read_bytes() == text and [p.name for p in tmp_path.iterdir()] == ["four_bar.json"]


def test_render_refuses_to_overwrite_its_scene_before_drawing_a_png(tmp_path, monkeypatch, capsys):
    from plans import cli

    scene = tmp_path / "four_bar.json"
    text = FOUR_BAR.read_bytes()
    scene.write_bytes(text)
    drawn = []
    monkeypatch.setattr(export, "svg_to_png", lambda text, dpi: drawn.append(1) or b"")
    assert cli.main(["render", str(scene), "--format", "svg,png", "-o", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "[-o]" in err and "would overwrite the input file" in err and len(err.strip().splitlines()) == 1
    assert drawn == [] and scene.read_bytes() == text and [p.name for p in tmp_path.iterdir()] == ["four_bar.json"]


def test_synthesize_names_its_option_when_writing_fails(tmp_path, capsys):
    from plans import cli

    out = tmp_path / "o"
    (out / "synthesis_B_12-gears.svg").mkdir(parents=True)     # a folder where the sheet goes
    code = cli.main(["gears", "synthesize", "--ratio", "12", "--type", "B", "--planets", "3", "-q", "-o", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and "[-o]" in err and "[folder]" not in err and "another -o" in err, err
    assert [p.name for p in out.iterdir()] == ["synthesis_B_12-gears.svg"]
    assert not any((out / "synthesis_B_12-gears.svg").iterdir())


@pytest.mark.parametrize("name", ["a\nb.toml", "a\tb.toml", "a\rb.toml", "a\x1bb.toml"])
def test_a_scene_file_whose_name_cannot_name_files_is_refused(tmp_path, name, capsys):
    from plans import cli

    scene = tmp_path / name
    scene.write_bytes(FOUR_BAR.read_bytes())
    for call in (lambda: plans.render(scene), lambda: plans.render(plans.read_scene(scene))):
        with pytest.raises(plans.PlansError) as err:
            call()
        assert "rename the file" in str(err.value) and len(str(err.value).splitlines()) == 1
    out = tmp_path / "out"
    assert cli.main(["render", str(scene), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "rename the file" in err and not out.exists()
    assert plans.render(scene, stem="ab").stem == "ab"     # a stem given names the files instead


def test_a_copied_package_beside_another_projects_pyproject_keeps_its_own_version(tmp_path):
    from importlib import metadata

    try:
        installed = metadata.version("plans")
    except metadata.PackageNotFoundError:
        pytest.skip("plans is not installed")
    version = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["version"]
    assert installed == version
    shutil.copytree(ROOT / "plans", tmp_path / "plans", ignore=shutil.ignore_patterns("__pycache__"))
    (tmp_path / "pyproject.toml").write_text('[project]\nname = "homework"\nversion = "9.9.9"\n', encoding="utf-8")
    env = {**os.environ, "PYTHONPATH": str(tmp_path)}
    r = subprocess.run([sys.executable, "-c", "import plans; print(plans.__file__); print(plans.__version__)"],
                       capture_output=True, text=True, env=env, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    file, got = r.stdout.split()
    assert Path(file).parent == tmp_path / "plans" and got == version


def test_bench_refuses_a_bad_output_folder_before_measuring(tmp_path, capsys, monkeypatch):
    from plans import bench, cli

    (tmp_path / "afile").write_text("x")
    ran = []
    monkeypatch.setattr(bench, "run", lambda *a, **k: ran.append(a))
    assert cli.main(["bench", "--quick", "-o", str(tmp_path / "afile" / "sub")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("plans: error: ") and "[-o]" in err and "lies below the file" in err
    assert len(err.strip().splitlines()) == 1 and ran == []
    assert [p.name for p in tmp_path.iterdir()] == ["afile"] and (tmp_path / "afile").read_text() == "x"

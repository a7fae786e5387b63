"""The Python API's save and render arguments, and outputs that would replace inputs: each error
is a PlansError naming the argument (not the command line's flag), and nothing is written."""

from __future__ import annotations

import math
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

import plans
from plans.errors import OutputError

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
    r = subprocess.run([sys.executable, "-m", "plans", "render", "four_bar.json", "-o", "."], cwd=tmp_path,
                       capture_output=True, text=True)
    assert r.returncode == 2 and "would overwrite the input file" in r.stderr, r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    assert scene.read_bytes() == text and sorted(p.name for p in tmp_path.iterdir()) == ["four_bar.json"]

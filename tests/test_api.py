"""The Python API: ``plans.render(scene_or_path) -> Sheets``, displayed in Jupyter and saved
with ``.save(folder, formats=…)``."""

from __future__ import annotations

import base64
import json
import os
import re

import pytest

import plans
from plans import OutputError, PlansError, Scene, SceneError, Sheet, Sheets, parse_scene, read_scene
from plans.export import require_cairo
from plans.pipeline import render_scene, stem_of

from conftest import CRANK_SLIDER, EXAMPLES

FOUR_BAR = next(p for p in EXAMPLES if p.stem == "four_bar")

#: A scene as a notebook would write it: no file anywhere.
CRANK_DICT = {
    "title": "Crank-slider mechanism",
    "points": {"O": [0.0, 0.0], "A": [0.0866025, 0.05], "B": [0.4834652, 0.0], "C": [0.2354260, 0.03125]},
    "links": {"0": ["O"], "1": ["O", "A"], "2": ["A", "B", "C"], "3": ["B"]},
    "sliders": [{"link": "3", "on": "0", "through": "B", "angle": 0.0}],
    "drive": {"link": "1", "angle": 30.0, "omega": 10.0},
    "lengths": {"OA": 0.1, "AB": 0.4, "AC": 0.15},
}


@pytest.fixture(scope="module")
def four_bar() -> Sheets:
    return plans.render(FOUR_BAR)


@pytest.fixture
def cairo():
    try:
        require_cairo()
    except OutputError as exc:
        pytest.skip(f"PNG/PDF need cairo, which cannot be loaded here: {exc}")


def test_render_is_the_package_function():
    """``import plans.pipeline`` (or any submodule) leaves ``plans.render`` the function."""
    import plans.pipeline  # noqa: F401

    assert callable(plans.render) and plans.render is plans.pipeline.render
    assert {"render", "Sheets", "Sheet"} <= set(plans.__all__)


@pytest.mark.parametrize("path", [CRANK_SLIDER, FOUR_BAR], ids=lambda p: p.stem)
def test_path_and_scene_give_the_same_bytes(path):
    """From a path (str or Path), from the Scene read from it, and through render_scene (what
    `plans render` writes): the same file names and the same bytes."""
    by_path = plans.render(path)
    by_str = plans.render(str(path))
    by_scene = plans.render(read_scene(path))
    cli = render_scene(path)
    assert by_path.stem == by_scene.stem == path.stem
    for other in (by_str, by_scene, cli):
        assert list(other.files) == list(by_path.files)
        assert all(other.files[n].encode() == by_path.files[n].encode() for n in by_path.files)


def test_sheets_and_their_svg(four_bar):
    """``.sheets`` maps the sheet's name to a Sheet whose ``_repr_svg_`` is its SVG file's text."""
    svgs = {n: t for n, t in four_bar.files.items() if n.endswith(".svg")}
    assert len(four_bar) == len(svgs) == len(four_bar.sheets) >= 3
    for name, sheet in four_bar.sheets.items():
        assert isinstance(sheet, Sheet) and sheet.name == name
        assert sheet.file == f"four_bar-{name}.svg"
        assert sheet._repr_svg_() == sheet.svg == svgs[sheet.file]
        assert sheet.svg.lstrip().startswith("<?xml") or sheet.svg.lstrip().startswith("<svg")
    assert [s.name for s in four_bar] == list(four_bar.sheets)
    first = next(iter(four_bar.sheets))
    assert four_bar[first].svg == four_bar._repr_svg_()
    assert "velocity-30" in four_bar.sheets or "velocity" in four_bar.sheets


def test_html_gallery_holds_every_sheet(four_bar):
    """``_repr_html_`` shows every sheet as an image of its own SVG, in order, named."""
    page = four_bar._repr_html_()
    images = re.findall(r'src="data:image/svg\+xml;base64,([A-Za-z0-9+/=]+)"', page)
    assert [base64.b64decode(i).decode("utf-8") for i in images] == [s.svg for s in four_bar]
    assert all(f"<figcaption>{name}</figcaption>" in page for name in four_bar.sheets)


def test_report_and_motion(four_bar):
    """The JSON report as text and dict, and the Motion it was made from."""
    data = four_bar.report
    assert data == json.loads(four_bar.files["four_bar.json"]) and four_bar.json == four_bar.files["four_bar.json"]
    assert len(data["positions"]) == len(four_bar.motion)
    c = four_bar.motion.velocity("C")
    assert data["positions"][0]["points"]["C"]["v"] == [float(c[0, 0]), float(c[0, 1])]


def test_save_svg_png_pdf(tmp_path, cairo, four_bar):
    """``.save`` writes the formats asked for (and the JSON) as ``plans render --format`` does."""
    out = tmp_path / "sheets"
    written = four_bar.save(out, formats=("svg", "png", "pdf"), dpi=30)
    names = sorted(p.name for p in out.iterdir())
    assert sorted(p.name for p in written) == names
    stems = [n[:-4] for n in four_bar.files if n.endswith(".svg")]
    assert names == sorted([f"{s}.{ext}" for s in stems for ext in ("svg", "png", "pdf")] + ["four_bar.json"])
    assert (out / "four_bar.json").read_text() == four_bar.json
    for s in stems:
        assert (out / f"{s}.svg").read_text(encoding="utf-8") == four_bar.files[f"{s}.svg"]
        assert (out / f"{s}.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert (out / f"{s}.pdf").read_bytes()[:5] == b"%PDF-"
    one = tmp_path / "one"
    sheet = next(iter(four_bar))
    sheet.save(one, "png,pdf", dpi=30)
    assert sorted(p.name for p in one.iterdir()) == sorted([sheet.file[:-4] + ".png", sheet.file[:-4] + ".pdf"])


def test_save_default_is_svg_and_json(tmp_path, four_bar):
    four_bar.save(tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(four_bar.files)


def test_save_is_all_or_nothing(tmp_path, four_bar):
    """A folder that is a file, a folder standing where one file goes, an unknown format:
    one OutputError and nothing written."""
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(OutputError, match="not a folder"):
        four_bar.save(blocker)
    with pytest.raises(OutputError, match="not a folder"):
        four_bar.save(blocker / "below")
    out = tmp_path / "out"
    (out / next(iter(four_bar)).file).mkdir(parents=True)       # a folder where the first sheet goes
    with pytest.raises(OutputError, match="a folder"):
        four_bar.save(out)
    assert [p.name for p in out.iterdir()] == [next(iter(four_bar)).file]
    with pytest.raises(OutputError, match="unknown format"):
        four_bar.save(tmp_path / "new", formats=("svg", "gif"))
    assert not (tmp_path / "new").exists()


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes anywhere")
def test_save_refuses_a_read_only_folder(tmp_path, four_bar):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        with pytest.raises(OutputError):
            four_bar.save(ro)
        assert not any(ro.iterdir())
    finally:
        ro.chmod(0o700)


def test_scene_from_a_dict_needs_no_file(tmp_path, monkeypatch):
    """A Scene parsed from a dict renders with a stem from its title, reads no file, and saves;
    its sheets are those of the same scene read from a file, renamed."""
    monkeypatch.chdir(tmp_path)              # nothing around to read
    scene = parse_scene(CRANK_DICT)
    assert isinstance(scene, Scene) and scene.file is None
    r = plans.render(scene)
    assert r.stem == "crank-slider_mechanism"
    assert sorted(r.sheets) == ["acceleration", "scheme", "velocity"]
    assert set(r.report["positions"][0]["sliders"]) == {"3/0"}
    r.save(tmp_path / "out")
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == sorted(r.files)
    toml = tmp_path / "crank.toml"
    toml.write_text(_toml(CRANK_DICT))
    from_file = plans.render(toml)
    assert [n.replace("crank", "crank-slider_mechanism", 1) for n in from_file.files] == list(r.files)
    assert list(from_file.files.values()) == list(r.files.values())
    named = plans.render(scene, stem="mine")
    assert all(n.startswith("mine") for n in named.files) and list(named.files.values()) == list(r.files.values())


def test_stems_from_titles():
    assert stem_of("Crank-slider mechanism") == "crank-slider_mechanism"
    assert stem_of("  Кулиса / 2 ") == "кулиса_2"
    assert stem_of("../..") == "mechanism"
    assert stem_of("x" * 100) == "x" * 60


def test_bad_arguments():
    with pytest.raises(TypeError, match="Scene or the path"):
        plans.render(42)
    with pytest.raises(OutputError, match="cannot name a file"):
        plans.render(parse_scene(CRANK_DICT), stem="a/b")
    with pytest.raises(SceneError, match="no such scene file"):
        plans.render("no/such/scene.toml")


def test_errors_of_a_scene_without_file_are_plans_errors():
    """A Scene from a dict that cannot assemble: the PlansError of `plans render`, no file name."""
    bad = dict(CRANK_DICT, lengths={"OA": 0.1, "AB": 0.05, "AC": 0.03})
    with pytest.raises(PlansError) as info:
        plans.render(parse_scene(bad))
    assert "None" not in str(info.value)


def _toml(data: dict) -> str:
    """A small TOML writer for CRANK_DICT (strings, numbers, lists, tables, one array of tables)."""
    def value(v):
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, list):
            return "[" + ", ".join(value(x) for x in v) + "]"
        return repr(v)

    lines = [f"title = {value(data['title'])}"]
    for table in ("points", "links", "drive", "lengths"):
        lines.append(f"[{table}]")
        lines += [f"{json.dumps(k)} = {value(v)}" for k, v in data[table].items()]
    for s in data["sliders"]:
        lines.append("[[sliders]]")
        lines += [f"{k} = {value(v)}" for k, v in s.items()]
    return "\n".join(lines) + "\n"

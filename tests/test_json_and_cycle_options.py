"""Strict JSON everywhere plans writes it, and the cycle options at their edges: the crank as the
cycle's output, and ``at = []`` that would draw nothing."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest

import plans
from plans.pipeline.json_report import report_text

from conftest import plans_cli, stem_of

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = sorted((ROOT / "examples").glob("*.toml")) + sorted((ROOT / "examples" / "gears").glob("*.toml"))


def _reject(name: str):
    raise ValueError(f"{name} is not JSON")


@pytest.mark.parametrize("scene", EXAMPLES, ids=lambda p: p.stem)
def test_every_report_of_the_examples_is_strict_json(scene, demo_rendered):
    reports = [p for p in demo_rendered.glob("*.json") if stem_of(p.name) == scene.stem]
    assert reports
    for path in reports:
        json.loads(path.read_text(encoding="utf-8"), parse_constant=_reject)


def test_the_committed_gallery_and_bench_are_strict_json():
    files = sorted((ROOT / "output").glob("*.json")) + sorted((ROOT / "output").glob("bench/*.json"))
    if not files:
        pytest.skip("no output/ in this checkout")
    for f in files:
        json.loads(f.read_text(encoding="utf-8"), parse_constant=_reject)


def test_the_report_writer_refuses_a_non_finite_number():
    with pytest.raises(ValueError):
        report_text({"x": float("inf")})
    assert report_text({"x": -0.0, "y": None}) == '{\n "x": 0.0,\n "y": null\n}\n'


def _cycle_scene(tmp_path: Path, **plans_keys) -> Path:
    text = (ROOT / "examples" / "six_link_press.toml").read_text(encoding="utf-8")
    for key, value in plans_keys.items():
        text = re.sub(rf"^{key} = .*$", f"{key} = {value}", text, flags=re.M)
    p = tmp_path / "c.toml"
    p.write_text(text, encoding="utf-8")
    return p


def test_the_crank_as_the_cycles_output_is_refused(tmp_path):
    with pytest.raises(plans.SceneError) as err:
        plans.read_scene(_cycle_scene(tmp_path, output='"1"'))
    assert err.value.key == "plans.output" and "driving link" in str(err.value)


def test_at_empty_with_nothing_else_to_draw_is_refused(tmp_path):
    with pytest.raises(plans.SceneError) as err:
        plans.read_scene(_cycle_scene(tmp_path, at="[]", draw='["scheme", "velocity"]'))
    assert err.value.key == "plans.at" and "nothing would be drawn" in str(err.value)


def test_at_empty_with_cycle_sheets_draws_them(tmp_path):
    sheets = plans.render(_cycle_scene(tmp_path, at="[]", draw='["scheme", "positions", "diagrams"]'))
    assert sorted(sheets.sheets) == ["diagrams", "positions"]


def test_a_handout_never_writes_over_its_own_variants_file(tmp_path):
    import shutil

    shutil.copy(ROOT / "examples" / "six_link_press.toml", tmp_path / "six_link_press.toml")
    mine = '# my comments, kept\nbase = "six_link_press.toml"\n\n[[variant]]\n[variant.lengths]\nOA = 0.1\n'
    (tmp_path / "variants.toml").write_text(mine, encoding="utf-8")
    r = plans_cli(["handout", "variants.toml", "-o", "."], cwd=tmp_path)
    assert r.returncode == 2 and "would overwrite the input file" in r.stderr, r.stderr
    assert (tmp_path / "variants.toml").read_text(encoding="utf-8") == mine
    assert sorted(p.name for p in tmp_path.iterdir()) == ["six_link_press.toml", "variants.toml"]


def test_the_progress_bar_estimates_the_time_left():
    import io

    from plans.handout import Progress

    class Tty(io.StringIO):
        def isatty(self):
            return True

    bar = Progress(10, "drawing", stream=Tty())
    bar.started -= 2.0                   # two seconds for the first two variants
    assert bar.eta(2) == "about 8 s left" and bar.eta(10) == ""


def _crank_last(tmp_path: Path, draw: str) -> Path:
    """The four-bar with the crank listed last among its links (0, 3, 2, 1): the last moving link is
    the driving link, the one before it the coupler 2 (no frame pivot), the rocker 3 before that."""
    text = (ROOT / "examples" / "four_bar.toml").read_text(encoding="utf-8")
    links = re.search(r"^\[links\].*?\n\n", text, flags=re.M | re.S).group(0)
    text = text.replace(links, '[links]\n0 = ["O", "C"]\n3 = ["C", "B"]\n2 = ["A", "B", "M"]\n1 = ["O", "A"]\n\n')
    text = re.sub(r"^angle = \[.*\]$", "angle = 0.0\npositions = 12", text, flags=re.M)
    text = re.sub(r"^draw = .*$", f"draw = {draw}", text, flags=re.M)
    p = tmp_path / "crank_last.toml"
    p.write_text(text, encoding="utf-8")
    return p


def test_the_default_output_is_the_last_driven_link_not_the_crank(tmp_path):
    """With the crank listed last, the cycle's output is by default the rocker 3 (the last moving
    link but the driving one that turns about a frame pivot): its diagrams and swing are drawn, the
    JSON is strict."""
    sheets = plans.render(_crank_last(tmp_path, '["scheme", "positions", "diagrams"]'))
    cycle = json.loads(sheets.json, parse_constant=_reject)["cycle"]
    assert cycle["output"] == {"link": "3", "kind": "rocker", "point": "B", "unit": "rad"}
    swing = [e["s"] for e in cycle["extremes"]]
    psi = [math.atan2(p["points"]["B"]["r"][1], p["points"]["B"]["r"][0] - 0.24)
           for p in json.loads(sheets.json)["positions"]]
    assert max(psi) <= swing[1] + 1e-12 and min(psi) >= swing[0] - 1e-12      # the extremes bound every position
    assert 0.0 < cycle["diagrams"]["graphical_error"]["v"] < 0.2 and 0.0 < cycle["diagrams"]["graphical_error"]["a"] < 1.0
    assert "diagrams" in sheets.sheets and "inf %" not in sheets["diagrams"].svg


def test_a_lone_crank_draws_its_positions_but_no_diagrams(tmp_path):
    """The driving link alone: its positions sheet is drawn (the output is the crank itself);
    its diagrams would be the crank's own angle against itself, refused in one line."""
    text = ('[points]\nO = [0.0, 0.0]\nA = [0.1, 0.0]\n[links]\n0 = ["O"]\n1 = ["O", "A"]\n'
            '[drive]\nlink = "1"\nangle = 0.0\npositions = 12\nomega = 10.0\n[plans]\ndraw = {}\n')
    p = tmp_path / "lone.toml"
    p.write_text(text.format('["positions"]'), encoding="utf-8")
    assert json.loads(plans.render(p).json, parse_constant=_reject)["cycle"]["output"]["link"] == "1"
    p.write_text(text.format('["positions", "diagrams"]'), encoding="utf-8")
    with pytest.raises(plans.SceneError) as err:
        plans.read_scene(p)
    assert err.value.key == "plans.draw" and "no moving link but the driving link 1" in str(err.value) and '"diagrams"' in str(err.value)

"""Strict JSON everywhere plans writes it, and the cycle options at their edges: the crank as the
cycle's output, and ``at = []`` that would draw nothing."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

import plans
from plans.pipeline.json_report import report_text

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = sorted((ROOT / "examples").glob("*.toml")) + sorted((ROOT / "examples" / "gears").glob("*.toml"))


def _reject(name: str):
    raise ValueError(f"{name} is not JSON")


@pytest.mark.parametrize("scene", EXAMPLES, ids=lambda p: p.stem)
def test_every_report_of_the_examples_is_strict_json(scene):
    for name, text in plans.render(scene).files.items():
        if name.endswith(".json"):
            json.loads(text, parse_constant=_reject)


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
    import subprocess
    import sys

    shutil.copy(ROOT / "examples" / "six_link_press.toml", tmp_path / "six_link_press.toml")
    mine = '# my comments, kept\nbase = "six_link_press.toml"\n\n[[variant]]\n[variant.lengths]\nOA = 0.1\n'
    (tmp_path / "variants.toml").write_text(mine, encoding="utf-8")
    r = subprocess.run([sys.executable, "-m", "plans", "handout", "variants.toml", "-o", "."], cwd=tmp_path,
                       capture_output=True, text=True)
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

"""The ``-assemblies`` sheet (issue 36): every real assembly of each class III/IV group at a
drawn position, numbered in the JSON's order, the chosen one framed, drawn at one μl — each
small scheme's points are the JSON's poses at that scale; ``plans check`` reads it as a scheme
and the layout measurer finds nothing."""

from __future__ import annotations

import json
import math
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import plans
from plans.checking import inspect_svg
from plans.layout import measure_layout
from plans.pipeline import render

SVG = "{http://www.w3.org/2000/svg}"
EXAMPLES = plans.__path__[0] + "/examples"


def _rendered(name: str, folder):
    from pathlib import Path
    text = Path(f"{EXAMPLES}/{name}.toml").read_text(encoding="utf-8")
    text = re.sub(r'^draw = \[', 'draw = ["assemblies", ', text, count=1, flags=re.M)
    path = folder / f"{name}.toml"
    path.write_text(text, encoding="utf-8")
    return render(path)


@pytest.mark.parametrize("name", ["class3_six_link", "class4_six_link"])
def test_the_sheet_draws_every_assembly_at_its_poses(name, tmp_path):
    sheets = _rendered(name, tmp_path)
    report = json.loads(sheets.files[f"{name}.json"])
    drawn = sorted(f for f in sheets.files if "-assemblies" in f)
    assert len(drawn) == len(report["positions"])
    for f, pos in zip(sorted(drawn, key=lambda f: float(f.rsplit("-", 1)[1][:-4])),
                      sorted(report["positions"], key=lambda p: p["angle"])):
        root = ET.fromstring(sheets.files[f])
        schemes = [g for g in root.iter(f"{SVG}g") if g.get("data-assembly") is not None]
        (group, found), = pos["assemblies"].items()
        assert len(schemes) == found["count"]
        for g, pose in zip(schemes, found["poses"]):
            assert (g.get("data-chosen") == "true") == pose["chosen"]
            mu = float(g.get("data-mu"))
            # the joints (circles) in the order of the pose's points, at mu: their shape is the pose's
            circles = [(float(c.get("cx")), float(c.get("cy"))) for c in g.iter(f"{SVG}circle")]
            world = np.array(list(pose["points"].values()))
            paper = np.array(circles)
            d_world = np.hypot(*(world[:, None, :] - world[None, :, :]).transpose(2, 0, 1))
            d_paper = np.hypot(*(paper[:, None, :] - paper[None, :, :]).transpose(2, 0, 1))
            assert np.allclose(d_paper * mu, d_world, atol=2 * math.sqrt(2) * 0.0005 * mu)
            if pose.get("condition") is not None:
                assert f"condition {pose['condition']:+.3f}" in "".join(g.itertext())
        path = tmp_path / f
        path.write_text(sheets.files[f], encoding="utf-8")
        r = inspect_svg(path)
        assert r.kind == "scheme" and not r.problems
        assert measure_layout(sheets.files[f]).clean


def test_the_cycle_reports_each_positions_count(tmp_path):
    """With a cycle, ``cycle.assemblies`` gives each group's count at every cycle position, the same
    as that position's own entry; the positions sheet says whether a count changes."""
    from pathlib import Path
    text = Path(f"{EXAMPLES}/class3_six_link.toml").read_text(encoding="utf-8")
    text = text.replace("angle = [30.0, 120.0, 210.0, 300.0]", "angle = 30.0\npositions = 12")
    text = re.sub(r"^draw = \[.*\]$", 'draw = ["positions", "assemblies"]', text, flags=re.M)
    path = tmp_path / "c3.toml"
    path.write_text(text, encoding="utf-8")
    sheets = render(path)
    report = json.loads(sheets.files["c3.json"])
    counts = report["cycle"]["assemblies"]
    assert list(counts) == ["III(2-3-4-5)"] and len(counts["III(2-3-4-5)"]) == 12
    assert counts["III(2-3-4-5)"] == [p["assemblies"]["III(2-3-4-5)"]["count"] for p in report["positions"]]
    words = "".join(ET.fromstring(sheets.files["c3-positions.svg"]).itertext())
    assert "keeps its count of real assemblies over the cycle: III(2-3-4-5) 2" in words


def test_choosing_another_assembly(tmp_path):
    """[plans] assembly = { group = k }: the walk starts from assembly k at the first position (it is
    the chosen one there, its points those of the default render's pose k), and a number beyond the
    count, or a name that is no group, is refused in one line naming the key."""
    from pathlib import Path

    from plans.errors import SceneError

    base = Path(f"{EXAMPLES}/class3_six_link.toml").read_text(encoding="utf-8")
    plain = tmp_path / "plain.toml"
    plain.write_text(re.sub(r"^draw = \[", 'draw = ["assemblies", ', base, count=1, flags=re.M), encoding="utf-8")
    before = json.loads(render(plain).files["plain.json"])["positions"][0]["assemblies"]["III(2-3-4-5)"]["poses"]
    other = next(k for k, p in enumerate(before) if not p["chosen"]) + 1
    text = re.sub(r"^draw = \[", f'assembly = {{ "III(2-3-4-5)" = {other} }}\ndraw = ["assemblies", ', base,
                  count=1, flags=re.M)
    path = tmp_path / "chosen.toml"
    path.write_text(text, encoding="utf-8")
    after = json.loads(render(path).files["chosen.json"])["positions"]
    poses = after[0]["assemblies"]["III(2-3-4-5)"]["poses"]
    chosen = next(p for p in poses if p["chosen"])
    for name, xy in before[other - 1]["points"].items():
        assert math.dist(xy, chosen["points"][name]) <= 1e-9
        assert math.dist(xy, after[0]["points"][name]["r"]) <= 1e-9
    for bad, words in ((text.replace(f"= {other} }}", "= 7 }"), "has 2 real assemblies at 30°, not 7"),
                       (text.replace('"III(2-3-4-5)"', '"III(9-9)"'), "is no group of this mechanism")):
        path.write_text(bad, encoding="utf-8")
        with pytest.raises(SceneError) as e:
            render(path)
        assert words in str(e.value) and "plans.assembly" in str(e.value)

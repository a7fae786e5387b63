"""The ``-turning`` sheet: the turning-moment diagram of a machine given by its crank torque, its
areas between T and T_res read off the drawing (outline area × μT × μθ) equal to the JSON's, the
energies at the crossings tabulated, ``plans check`` passing on it and failing a doctored area."""

from __future__ import annotations

import json
import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

import plans
from plans.checking import inspect_svg
from plans.layout import measure_layout
from plans.pipeline import render

SVG = "{http://www.w3.org/2000/svg}"
FLYWHEEL = Path(plans.__path__[0]) / "examples" / "flywheel"


def _drawn(name: str, folder: Path):
    text = (FLYWHEEL / f"{name}.toml").read_text(encoding="utf-8")
    if 'draw = ["turning"]' not in text:
        text = text.replace("[turning]", '[plans]\ndraw = ["turning"]\n\n[turning]', 1)
    path = folder / f"{name}.toml"
    path.write_text(text, encoding="utf-8")
    return render(path)


def _area(d: str) -> float:
    pts = [(float(a), float(b)) for a, b in re.findall(r"[ML]\s*([-+0-9.eE]+)\s*,\s*([-+0-9.eE]+)", d)]
    return 0.5 * abs(sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(pts, pts[1:] + pts[:1])))


@pytest.mark.parametrize("name", ["four_stroke_engine", "harmonic_engine"])
def test_the_areas_read_off_the_drawing_are_the_reports(name, tmp_path):
    out = _drawn(name, tmp_path)
    svg = out.files[f"{name}-turning.svg"]
    report = json.loads(out.files[f"{name}.json"])["turning"]
    root = ET.fromstring(svg)
    g = next(e for e in root.iter(f"{SVG}g") if e.get("data-plan") == "turning")
    scale = float(g.get("data-mu-t")) * float(g.get("data-mu-theta"))
    paths = [p for p in g.iter(f"{SVG}path") if p.get("data-area")]
    assert [float(p.get("data-value")) for p in paths] == pytest.approx(report["areas"], rel=1e-12)
    for p, want in zip(paths, report["areas"]):
        pts = re.findall(r"[ML]", p.get("d"))
        # each outline point rounded to 0.0005 mm moves the area by at most perimeter × √2·0.0005
        assert _area(p.get("d")) * scale == pytest.approx(abs(want), abs=len(pts) * 10 * 0.0005 * scale + 1e-9 * abs(want))
    assert sum(report["areas"]) == pytest.approx(0.0, abs=1e-9 * max(abs(a) for a in report["areas"]))
    text = "".join(root.itertext())
    assert f"{report['energy_fluctuation']:.6g}".replace("-", "−") in text
    path = tmp_path / "t.svg"
    path.write_text(svg, encoding="utf-8")
    r = inspect_svg(path)
    assert r.ok and not r.problems and measure_layout(svg).clean
    assert sum(1 for c in r.checks if c.what.startswith("area A")) == len(paths)
    # an area drawn 1 % too large (its outline scaled about its first point) fails
    first = paths[0]
    x0, y0 = (float(v) for v in re.search(r"M\s*([-+0-9.eE]+)\s*,\s*([-+0-9.eE]+)", first.get("d")).groups())
    first.set("d", re.sub(r"([ML])\s*([-+0-9.eE]+)\s*,\s*([-+0-9.eE]+)",
                          lambda m: f"{m.group(1)}{x0 + (float(m.group(2)) - x0) * 1.01:.3f},"
                                    f"{y0 + (float(m.group(3)) - y0):.3f}", first.get("d")))
    path.write_text(ET.tostring(root, encoding="unicode"), encoding="utf-8")
    bad = inspect_svg(path)
    assert any("area A1" in p for p in bad.problems), bad.problems[:3]
    assert math.isfinite(scale)

"""The gear sheet's details (issue 34, item 4): an ω segment or a pitch-point velocity drawn under
5 mm in its picture is drawn again, k× longer, under the pole (``omega:L:detail``,
``vp:a-b:detail``, μ/k), so that it can be measured; a rounded zero (a fixed ring's pitch point,
8.9e-16 m/s) is not one of them. Read off the SVG the way ``plans check`` reads it."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from importlib import resources

import pytest

from plans import render
from plans.checking import inspect_svg

SVG = "{http://www.w3.org/2000/svg}"
SHORT_MM = 5.0


def _lines(root, group_suffix):
    g = next(g for g in root.iter(f"{SVG}g") if (g.get("id") or "").endswith(group_suffix))
    return g, {l.get("data-quantity"): l for l in g.iter(f"{SVG}line") if l.get("data-quantity")}


def _length(line) -> float:
    return math.dist((float(line.get("x1")), float(line.get("y1"))), (float(line.get("x2")), float(line.get("y2"))))


@pytest.fixture(scope="module")
def synthesis(tmp_path_factory):
    out = tmp_path_factory.mktemp("syn")
    scene = resources.files("plans.examples.gears") / "synthesis_type_c.toml"
    render(str(scene)).save(out)
    return out / "synthesis_type_c-gears.svg"


@pytest.mark.parametrize("picture, detail, prefix", [("-omega", "-omega-detail", "omega:"),
                                                      ("-velocity", "-v-detail", "vp:")])
def test_every_short_segment_is_drawn_again_long_enough_to_measure(synthesis, picture, detail, prefix):
    root = ET.parse(synthesis).getroot()
    main, drawn = _lines(root, picture)
    values = [abs(float(l.get("data-value"))) for l in drawn.values()]
    short = {q: l for q, l in drawn.items() if _length(l) < SHORT_MM and abs(float(l.get("data-value"))) >
             1e-9 * max(values)}
    assert short, "the example has a short segment"           # b1's ω and the b1-g pitch velocity
    g, again = _lines(root, detail)
    assert set(again) == {f"{q}:detail" for q in short}
    k = float(main.get("data-mu")) / float(g.get("data-mu"))
    assert k in (2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0)
    for q, line in short.items():
        twin = again[f"{q}:detail"]
        assert float(twin.get("data-value")) == float(line.get("data-value"))
        # both drawn to 0.001 mm: the short one's rounding grows k times
        assert _length(twin) >= SHORT_MM and _length(twin) == pytest.approx(k * _length(line), abs=(k + 1) * 2e-3)
    r = inspect_svg(synthesis)
    assert r.ok, r.problems
    measured = {m.quantity for m in r.measurements}
    assert {f"{q}:detail" for q in short} <= measured


def test_a_doctored_detail_fails_plans_check(synthesis, tmp_path):
    root = ET.parse(synthesis).getroot()
    _, again = _lines(root, "-v-detail")
    line = next(iter(again.values()))
    line.set("x2", repr(float(line.get("x2")) + 0.5))
    bad = tmp_path / "bad.svg"
    bad.write_text(ET.tostring(root, encoding="unicode"), encoding="utf-8")
    assert not inspect_svg(bad).ok

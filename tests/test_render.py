"""End to end: render, check, determinism, the JSON report, bad input."""

from __future__ import annotations

import json
import tomllib
import math
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from plans.checking import check_svg
from plans.cli import main
from plans.constructions.scales import SERIES

from conftest import CRANK_SLIDER, EXAMPLES, stem_of

SVG = "{http://www.w3.org/2000/svg}"


def test_every_example_renders_all_files(rendered):
    for scene in EXAMPLES:
        data = json.loads((rendered / f"{scene.stem}.json").read_text())
        n = len(data["positions"])
        scene_data = tomllib.loads(scene.read_text(encoding="utf-8"))
        if "positions" in scene_data["drive"]:       # a cycle: sheets of their own at [plans] at
            n = len(scene_data["plans"].get("at", range(n)))
        for kind in ("scheme", "velocity", "acceleration"):
            if n == 1:
                assert (rendered / f"{scene.stem}-{kind}.svg").exists()
            else:
                assert len(list(rendered.glob(f"{scene.stem}-{kind}-*.svg"))) == n


def test_check_fails_on_tampered_svg(rendered, tmp_path, capsys):
    src = (rendered / "crank_slider_central-velocity.svg").read_text()
    # move the head of the tagged v:B line by 1 mm
    tampered = re.sub(r'(<line[^>]*data-quantity="v:B"[^>]*x2=")([-0-9.]+)',
                      lambda m: m.group(1) + str(float(m.group(2)) + 1.0), src, count=1)
    if tampered == src:  # attribute order: x2 before data-quantity
        tampered = re.sub(r'(<line[^>]*x2=")([-0-9.]+)("[^>]*data-quantity="v:B")',
                          lambda m: m.group(1) + str(float(m.group(2)) + 1.0) + m.group(3), src, count=1)
    assert tampered != src
    bad = tmp_path / "bad.svg"
    bad.write_text(tampered)
    assert main(["check", str(bad)]) == 1
    assert "FAIL v:B " in capsys.readouterr().out


def test_svg_contract(rendered):
    root = ET.parse(rendered / "quick_return-acceleration-30.svg").getroot()
    w, h = root.get("width"), root.get("height")
    assert w.endswith("mm") and h.endswith("mm")
    assert root.get("viewBox") == f"0 0 {w[:-2]} {h[:-2]}"
    plan = [g for g in root.iter(f"{SVG}g") if g.get("data-mu")]
    assert len(plan) == 1
    quantities = {l.get("data-quantity") for l in plan[0].iter(f"{SVG}line") if l.get("data-quantity")}
    assert {"a:A", "a:E", "a:A3/A2:cor", "a:A3/A2:r", "a:A3/C:n", "a:A3/C:t"} <= quantities
    assert not any(e.get("transform") for e in root.iter())


def test_measured_vectors_equal_json_values(rendered):
    """The absolute vectors measured on the plans equal |v|, |a| of the JSON report."""
    data = json.loads((rendered / "six_link_press.json").read_text())
    for i, angle in ((0, 60), (3, 150)):   # positions 0 and 3 of its 12, drawn on their own ([plans] at)
        pos = data["positions"][i]
        for kind, key in (("velocity", "v"), ("acceleration", "a")):
            for m in check_svg(rendered / f"six_link_press-{kind}-{angle}.svg"):
                if re.fullmatch(rf"{key}:[A-Z]", m.quantity):
                    exact = math.hypot(*pos["points"][m.quantity[2:]][key])
                    assert m.measured == pytest.approx(exact, abs=m.tolerance)


def test_scales_are_standard_and_reference_vectors_80_to_120_mm(rendered):
    for scene in EXAMPLES:
        data = json.loads((rendered / f"{scene.stem}.json").read_text())
        pos = data["positions"][0]
        for mu in pos["scales"].values():
            mantissa = mu / 10 ** math.floor(math.log10(mu) + 1e-12)
            assert any(abs(mantissa - s) < 1e-9 for s in SERIES), (scene.stem, mu)
        drive = [p for p in pos["points"] if math.hypot(*pos["points"][p]["v"]) > 0]
        tip = {"scotch_yoke": "A", "tangent_mechanism": "K"}.get(scene.stem)
        if tip:
            assert 80 <= math.hypot(*pos["points"][tip]["v"]) / pos["scales"]["mu_v"] <= 120 + 1e-9
        assert drive


def test_output_is_deterministic(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    scene = str(CRANK_SLIDER)
    assert main(["render", scene, "-o", str(a), "-q"]) == 0
    assert main(["render", scene, "-o", str(b), "-q"]) == 0
    names = sorted(p.name for p in a.iterdir())
    assert names == sorted(p.name for p in b.iterdir())
    for n in names:
        assert (a / n).read_bytes() == (b / n).read_bytes()


def test_json_report_structure(rendered):
    data = json.loads((rendered / "six_link_press.json").read_text())
    s = data["structure"]
    assert s["dof"] == 1 and s["class"] == 2
    assert s["formula"] == "I(0-1) ← II(2-3) ← II(4-5)"
    assert [g["form"] for g in s["groups"]] == ["RRR", "RRP"]
    pos = data["positions"][0]
    assert pos["angle"] == 60.0
    assert set(pos["points"]) == {"O", "D", "A", "B", "C", "E"}
    assert pos["points"]["O"]["v"] == [0.0, 0.0]
    assert set(pos["links"]) == {"0", "1", "2", "3", "4", "5"}
    assert set(pos["scales"]) == {"mu_l", "mu_v", "mu_a"}


def test_only_what_is_drawn_is_computed(tmp_path):
    text = CRANK_SLIDER.read_text().replace('draw = ["scheme", "velocity", "acceleration"]', 'draw = ["velocity"]')
    scene = tmp_path / "v_only.toml"
    scene.write_text(text)
    assert main(["render", str(scene), "-o", str(tmp_path / "o"), "-q"]) == 0
    data = json.loads((tmp_path / "o" / "v_only.json").read_text())
    pos = data["positions"][0]
    assert all("a" not in p and "v" in p for p in pos["points"].values())
    assert all("epsilon" not in l for l in pos["links"].values())
    assert "mu_a" not in pos["scales"]
    assert sorted(p.name for p in (tmp_path / "o").iterdir()) == ["v_only-velocity.svg", "v_only.json"]


GOOD = CRANK_SLIDER.read_text()


@pytest.mark.parametrize("edit, needle", [
    (lambda t: t.replace("[points]", "[points"), "malformed TOML"),
    (lambda t: t.replace('2 = ["A", "B", "C"]', '2 = ["A", "B", "Q"]'), "unknown point 'Q'"),
    (lambda t: t.replace('3 = ["B"]', '3 = []'), "link has no points"),
    (lambda t: t.replace('link = "3"\non = "0"', 'link = "3"\non = "9"'), "unknown link '9'"),
    (lambda t: t.replace('through = "B"', 'through = "Z"'), "guide is undefined"),
    (lambda t: t.replace("AB = 0.4", "AB = -0.4"), "must be positive"),
    (lambda t: t.replace("AB = 0.4", "AB = 0.0"), "must be positive"),
    (lambda t: t.replace("omega = 10.0", "omega = nan"), "not a finite number"),
    (lambda t: t.replace("omega = 10.0", "omega = inf"), "not a finite number"),
    (lambda t: t.replace("OA = 0.1", "OA = 0.6"), "cannot assemble"),
    (lambda t: t.replace('3 = ["B"]', '3 = ["B"]\n4 = ["B"]'), "W = 3·4"),
    (lambda t: t.replace('link = "1"\nangle', 'link = "7"\nangle'), "unknown driving link"),
])
def test_bad_input_is_one_clear_line(tmp_path, capsys, edit, needle):
    scene = tmp_path / "bad.toml"
    text = edit(GOOD)
    assert text != GOOD
    scene.write_text(text)
    out = tmp_path / "out"
    assert main(["render", str(scene), "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert needle in err and "bad.toml" in err
    assert not out.exists() or not any(out.iterdir())


def test_missing_file_is_reported(tmp_path, capsys):
    assert main(["render", str(tmp_path / "nope.toml"), "-o", str(tmp_path)]) == 2
    assert "no such scene file" in capsys.readouterr().err


def test_demo_renders_packaged_examples(demo_rendered):
    """Every bundled scene: the linkages, the gear trains, the rotors and the flywheel problems."""
    more = sorted(p.stem for sub in ("gears", "balancing", "flywheel", "shaking") for p in (EXAMPLES[0].parent / sub).glob("*.toml"))
    assert more and sorted(p.stem for p in demo_rendered.glob("*.json")) == sorted([p.stem for p in EXAMPLES] + more)


def test_plan_images_are_scaled_velocities(rendered):
    """Image b of the crank-slider sits at v_B/μV from the pole (y flipped on paper)."""
    data = json.loads((rendered / "crank_slider_central.json").read_text())
    pos = data["positions"][0]
    mu = pos["scales"]["mu_v"]
    root = ET.parse(rendered / "crank_slider_central-velocity.svg").getroot()
    lines = {l.get("data-quantity"): l for l in root.iter(f"{SVG}line") if l.get("data-quantity")}
    vb = lines["v:B"]
    d = np.array([float(vb.get("x2")) - float(vb.get("x1")), -(float(vb.get("y2")) - float(vb.get("y1")))])
    assert d * mu == pytest.approx(pos["points"]["B"]["v"], abs=2e-3 * mu)


def test_committed_gallery_is_what_the_examples_render(demo_rendered):
    """output/ (made by the README's first command) holds what the examples, linkages and gears,
    render now: every file there, every non-numeric byte the same, every number within the
    tolerance that tests/gallery.py states and derives (the same bytes with the same numpy, SciPy
    and shapely, whatever the processor). A checkout without output/ has no gallery to compare.
    (`plans check` on every sheet: tests/test_check.py.)"""
    from pathlib import Path

    from gallery import stale

    gallery = Path(__file__).resolve().parent.parent / "output"
    if not gallery.is_dir():
        pytest.skip("no output/ in this checkout: `plans render examples/*.toml -o output` makes it")
    fresh = {p.name: p.read_text(encoding="utf-8") for p in demo_rendered.iterdir() if p.is_file()}
    assert any(stem_of(name) == "planetary_1_21" for name in fresh)
    out = stale(gallery, fresh)
    assert not out, f"output/ is out of date for {len(out)} files, e.g. {out[:3]}: re-render the gallery"


def test_reports_write_no_negative_zero(rendered):
    """A zero's sign is rounding: no report of the examples prints -0.0 (values at rest, on the
    frame, or along a fixed guide come out of the arithmetic as ±0)."""
    import json

    def floats(x):
        if isinstance(x, float):
            yield x
        elif isinstance(x, dict):
            for v in x.values():
                yield from floats(v)
        elif isinstance(x, list):
            for v in x:
                yield from floats(v)

    for path in sorted(rendered.glob("*.json")):
        text = path.read_text(encoding="utf-8")
        zeros = [v for v in floats(json.loads(text)) if v == 0.0]
        assert zeros and not any(math.copysign(1.0, v) < 0 for v in zeros), path.name

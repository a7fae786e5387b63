"""Edges of the gear scenes (issue 32): what a train driving a crank, an involute pair, a gear
scene's [scales], the synthesis command and the Python API's numbers may be, and what ``plans
check`` finds doctored on a gear sheet. Each refusal is one line naming the file and the key,
exit 2, nothing written."""

from __future__ import annotations

import json
import math
import re
import tomllib
from pathlib import Path

import numpy as np
import pytest

from conftest import plans_cli, refused_line
from plans import render
from plans.errors import SceneError
from plans.scene import parse_scene

GEARS = Path(__file__).resolve().parent.parent / "plans" / "examples" / "gears"

#: The central crank-slider (examples/crank_slider_central.toml) whose crank is keyed on wheel f;
#: the train gives its ω, [drive] only the angle. Only the linkage's plans are drawn.
_CRANK_SLIDER = """title = "Crank-slider turned by a gear pair"
[points]
O = [0.0, 0.0]
A = [0.070710678, 0.070710678]
B = [0.464411072, 0.0]
[links]
0 = ["O"]
1 = ["O", "A"]
2 = ["A", "B"]
3 = ["B"]
[[sliders]]
link = "3"
on = "0"
through = "B"
angle = 0.0
[drive]
link = "1"
angle = 45.0
[plans]
draw = ["scheme", "velocity"]
"""


def _driven(rpm: str) -> str:
    """The crank-slider driven through a(90) → f(9): ω1 = −10·n_a·2π/60 rad/s (n_a = ``rpm``)."""
    return _CRANK_SLIDER + f"""[gears.wheels]
a = {{ teeth = 90, module = 2.0 }}
f = {{ teeth = 9, module = 2.0 }}
[gears]
meshes = [["a", "f"]]
output = "f"
[gears.input]
a = {rpm}
"""


# --- 8, 9: the crank's ω from a train meets the bounds of a written omega ----------------------

def test_a_train_turning_the_crank_too_fast_is_refused_at_its_input(tmp_path):
    line = refused_line(tmp_path, _driven("1e7"))
    # ω1 = −10·1e7·2π/60 = −1.047e7 rad/s > 1e6 (MAX_OMEGA): before, drawn with v_B ≈ 1e6 m/s
    assert "bad.toml" in line and "[gears.input.a]" in line
    assert "ω = -1.047e+07 rad/s" in line and "|ω| ≤ 1e+06 rad/s" in line
    assert "9.549e+05 rpm" in line          # the input speed that meets the bound: 1e6 / (10·2π/60)


def test_a_train_turning_the_crank_too_slowly_is_refused_at_its_input(tmp_path):
    line = refused_line(tmp_path, _driven("1e-300"))
    assert "bad.toml" in line and "[gears.input.a]" in line
    assert "ω = -1.047e-300 rad/s" in line and "at least 1e-09 rad/s" in line and "0 (at rest)" in line


def test_a_written_omega_is_refused_alike(tmp_path):
    for omega, words in (("-1.047e7", "|value| ≤ 1e+06"), ("1e-300", "at least 1e-09")):
        line = refused_line(tmp_path, _CRANK_SLIDER.replace('angle = 45.0', f'angle = 45.0\nomega = {omega}'))
        assert "[drive.omega]" in line and words in line


def test_trains_within_the_bounds_still_turn_the_crank():
    data = parse_scene(tomllib.loads(_driven("9.5e5")))
    sheets = render(data, stem="driven")
    w = sheets.report["positions"][0]["links"]["1"]["omega"]
    assert w == pytest.approx(-10.0 * 9.5e5 * 2.0 * math.pi / 60.0, rel=1e-12)      # −9.95e5 rad/s
    assert sheets.report["gears"]["speeds"]["f"]["rpm"] == pytest.approx(-9.5e6, rel=1e-15)


# --- 6: a train drives only a link pivoted on the frame -----------------------------------------

def test_a_train_on_a_coupler_is_refused_as_a_linear_drive_is(tmp_path):
    four_bar = (Path(__file__).resolve().parent.parent / "plans" / "examples" / "four_bar_coupler_drive.toml")
    text = four_bar.read_text(encoding="utf-8").replace("omega = 2.0\n", "")
    text += '[gears.wheels]\na = { teeth = 20 }\nf = { teeth = 40 }\n[gears]\nmeshes = [["a", "f"]]\n' \
            'output = "f"\n[gears.input]\na = 100.0\n'
    line = refused_line(tmp_path, text)
    assert "bad.toml" in line and "[gears.output]" in line
    assert "link 2 is a coupler" in line and "pivoted on the frame" in line
    linear = refused_line(tmp_path, _driven("100.0").replace("angle = 45.0", "displacement = 0.0"))
    assert "[gears.output]" in linear and "linear" in linear


# --- 5: a gear scene's [scales] would be ignored: refused ----------------------------------------

@pytest.mark.parametrize("scene, scale", [("pair_balanced.toml", "mu_l = 0.001"),
                                          ("planetary_1_21.toml", "mu_l = 0.002"),
                                          ("planetary_1_21.toml", "mu_v = 0.05")])
def test_scales_of_a_gear_scene_are_refused_naming_the_key(scene, scale, tmp_path):
    text = (GEARS / scene).read_text(encoding="utf-8") + f"\n[scales]\n{scale}\n"
    line = refused_line(tmp_path, text)
    key = scale.split(" ")[0]
    assert "bad.toml" in line and f"[scales.{key}]" in line and "would be ignored" in line and "remove it" in line


def test_an_unknown_scale_of_a_gear_scene_is_still_told_as_unknown(tmp_path):
    text = (GEARS / "pair_balanced.toml").read_text(encoding="utf-8") + "\n[scales]\nmu_x = 1.0\n"
    line = refused_line(tmp_path, text)
    assert "[scales.mu_x]" in line and "unknown scale" in line


# --- 10: the pair's teeth bounds hold for meshed train wheels ------------------------------------

@pytest.mark.parametrize("z1, z2, named", [(3, 9000, "wheel a has 3 teeth"), (600, 9000, "wheel a has 600 teeth"),
                                           (20, 501, "wheel b has 501 teeth")])
def test_a_meshed_train_pair_keeps_the_pairs_teeth_bounds(z1, z2, named, tmp_path):
    text = f"""[gears.wheels]
a = {{ teeth = {z1}, module = 1.0 }}
b = {{ teeth = {z2}, module = 1.0 }}
[gears]
meshes = [["a", "b"]]
[gears.input]
a = 100.0
[gear_pair]
mesh = ["a", "b"]
[plans]
draw = ["meshing"]
"""
    line = refused_line(tmp_path, text)
    assert "bad.toml" in line and "[gear_pair.mesh]" in line and named in line and "5 … 500 teeth" in line


# --- 16: the default tip radius follows the pressure angle ---------------------------------------

def _pair(table: dict) -> dict:
    return json.loads(render(parse_scene({"gear_pair": table, "plans": {"draw": []}}), stem="p").files["p.json"])


def test_the_default_tip_radius_follows_the_pressure_angle():
    rep = _pair({"z1": 40, "z2": 80, "module": 2.0, "pressure_angle": 14.5})["gear_pair"]
    largest = 0.25 / (1.0 - math.sin(math.radians(14.5)))           # 0.33350: 0.38 does not fit
    assert rep["tip_radius"] == pytest.approx(largest * 2.0, rel=1e-15)
    rep = _pair({"z1": 20, "z2": 40, "module": 2.0, "clearance": 0.1})["gear_pair"]
    assert rep["tip_radius"] == pytest.approx(0.1 / (1.0 - math.sin(math.radians(20.0))) * 2.0, rel=1e-15)
    rep = _pair({"z1": 20, "z2": 40, "module": 2.0, "pressure_angle": 22.0})["gear_pair"]
    assert rep["tip_radius"] == pytest.approx(0.38 * 2.0, rel=1e-15)    # the standard one, where it fits
    # at 25° the corner allows 0.4263, but the tip is (π/4 − 1.25·tan 25°)·m = 0.2025·m wide each side:
    # the two roundings of 0.38 would cross; the full round tip, 0.2025·cos 25°/(1 − sin 25°) = 0.3179
    a = math.radians(25.0)
    rep = _pair({"z1": 20, "z2": 40, "module": 2.0, "pressure_angle": 25.0})["gear_pair"]
    full = (math.pi / 4 - 1.25 * math.tan(a)) * math.cos(a) / (1 - math.sin(a))
    assert 0.25 / (1 - math.sin(a)) > 0.38 > full
    assert rep["tip_radius"] == pytest.approx(full * 2.0, rel=1e-15)
    rep = _pair({"z1": 40, "z2": 80, "module": 2.0, "pressure_angle": 14.5, "tip_radius": 0.3335})["gear_pair"]
    assert rep["tip_radius"] == pytest.approx(0.3335 * 2.0, rel=1e-15)  # the bound written to 4 digits is taken


def test_a_long_addendum_rounds_the_cutters_tip_within_its_width(tmp_path):
    """The cutter of addendum 1.355 (Uicker's pinion) has a tip (π/4 − (ha* + c*)·tan α)·m = 0.201·m
    wide each side: the standard rounding 0.38·m would make its two roundings cross (the cut
    failed in GEOS). The default rounding is then the full round tip, ρ* = 0.2008·cos α/(1 − sin α),
    the sheets are drawn and pass plans check, and a larger ρ* written is refused naming the bound."""
    from plans.checking import inspect_svg
    from plans.scene.gear_pair import largest_tip_radius
    alpha = math.radians(20.0)
    full = (math.pi / 4 - (1.355 + 0.25) * math.tan(alpha)) * math.cos(alpha) / (1 - math.sin(alpha))
    assert largest_tip_radius(20.0, 0.25, 1.355) == pytest.approx(full, rel=1e-15)
    assert largest_tip_radius(20.0, 0.25) == pytest.approx(0.25 / (1 - math.sin(alpha)), rel=1e-15)
    table = {"z1": 12, "z2": 60, "module": 12.7, "addendum": [1.355, 0.762]}
    out = render(parse_scene({"gear_pair": table}), stem="long")
    assert json.loads(out.files["long.json"])["gear_pair"]["tip_radius"] == pytest.approx(full * 12.7, rel=1e-12)
    out.save(tmp_path)
    for sheet in ("long-meshing.svg", "long-cutting.svg"):
        r = inspect_svg(tmp_path / sheet)
        assert r.ok and r.measurements, r.problems
    with pytest.raises(SceneError) as info:
        render(parse_scene({"gear_pair": dict(table, tip_radius=0.3)}), stem="long")
    e = info.value
    assert str(e).startswith(f"[gear_pair.tip_radius]: tip_radius ρ* (in modules) is 0 … {full:.4g}") and "\n" not in str(e)


def test_a_written_tip_radius_that_does_not_fit_is_refused_at_its_key(tmp_path):
    line = refused_line(tmp_path, "[gear_pair]\nz1 = 20\nz2 = 40\nmodule = 2.0\npressure_angle = 14.5\n"
                                  "tip_radius = 0.38\n")
    assert "[gear_pair.tip_radius]" in line and "0.3335" in line and "α = 14.5°" in line and "got 0.38" in line


# --- 17: a malformed --ratio is one line naming --ratio ------------------------------------------

@pytest.mark.parametrize("ratio", ["12\n", "nan", "NaN", "inf", "-inf", "", "1e999", " 12", "1_2", "١٢"])
def test_a_malformed_ratio_is_one_line_naming_it(ratio, tmp_path):
    out = tmp_path / "o"
    r = plans_cli(["gears", "synthesize", f"--ratio={ratio}", "--type", "A", "--planets", "3", "-o", out])
    lines = r.stderr.strip().splitlines()
    assert r.returncode == 2 and len(lines) == 1 and "[--ratio]" in lines[0], r.stderr
    assert "stem" not in lines[0] and not out.exists()


# --- 18: NumPy numbers in a scene given to the Python API ----------------------------------------

def test_numpy_numbers_are_read_as_python_numbers():
    def train(i, f):
        return {"gears": {"wheels": {"1": {"teeth": i(18), "module": f(3.0)}, "2": {"teeth": i(27), "module": f(3.0),
                                                                                   "on": "H"},
                                     "3": {"teeth": i(72), "module": f(3.0), "internal": True}},
                          "carriers": ["H"], "meshes": [["1", "2"], ["2", "3"]], "fixed": ["3"], "planets": i(3),
                          "input": {"1": f(1450.0)}}}
    plain = parse_scene(train(int, float))
    for i, f in ((np.int64, np.float64), (np.int32, np.float32), (np.uint16, np.float64)):
        scene = parse_scene(train(i, f))
        assert scene.gears == plain.gears
        assert all(type(w.teeth) is int for w in scene.gears.wheels) and type(scene.gears.planets) is int
        assert all(type(w.module) is float for w in scene.gears.wheels)
    pair = parse_scene({"gear_pair": {"z1": np.int64(20), "z2": np.int64(40), "module": np.float32(2.0)}}).gear_pair
    assert (pair.z1, pair.z2, pair.module) == (20, 40, 2.0) and type(pair.z1) is int
    with pytest.raises(Exception, match=r"teeth is a whole number 1 … 10000, got np.float64\(18.0\)"):
        parse_scene(train(np.float64, float))          # a float is no number of teeth, NumPy's neither
    with pytest.raises(Exception, match="got np.True_"):
        parse_scene({"gear_pair": {"z1": np.bool_(True), "z2": 40, "module": 2.0}})


def test_numpy_integers_count_positions_too():
    data = tomllib.loads(_CRANK_SLIDER.replace("angle = 45.0", "angle = 45.0\nomega = 10.0"))
    data["drive"]["positions"] = np.int64(12)
    data["plans"] = {"draw": ["positions"], "at": [np.int64(0), np.int64(3)]}
    scene = parse_scene(data)
    assert scene.cycle.positions == 12 and scene.cycle.at == (0, 3) and type(scene.cycle.positions) is int
    assert scene.drive.values[:2] == (45.0, 75.0)


# --- 20, 21: plans check reads the gear sheet's scales and rays ----------------------------------

@pytest.fixture(scope="module")
def gear_sheet(tmp_path_factory) -> str:
    out = tmp_path_factory.mktemp("gears")
    r = plans_cli(["render", GEARS / "planetary_1_21.toml", "-o", out, "-q"])
    assert r.returncode == 0, r.stderr
    return (out / "planetary_1_21-gears.svg").read_text(encoding="utf-8")


def _check(tmp_path: Path, text: str) -> tuple[int, list[str]]:
    path = tmp_path / "sheet.svg"
    path.write_text(text, encoding="utf-8")
    r = plans_cli(["check", path])
    return r.returncode, [ln.strip() for ln in r.stdout.splitlines() if ln.strip().startswith("FAIL")]


def test_the_untouched_gear_sheet_passes(gear_sheet, tmp_path):
    assert _check(tmp_path, gear_sheet) == (0, [])


def test_a_doctored_side_view_scale_fails_the_scale_relation(gear_sheet, tmp_path):
    side = re.search(r'<g data-mu="([^"]+)" data-plan="scheme"[^>]*id="gears-scheme"', gear_sheet)
    assert side and side.group(1) == "0.00125"
    code, fails = _check(tmp_path, gear_sheet.replace(side.group(0), side.group(0).replace("0.00125", "0.0012")))
    # μV/(μl·h) = 0.05/(0.0012 × 20 mm) = 2.0833 where μω = 2: the relation fails by −4 %
    assert code == 1 and len(fails) == 1
    assert "gears-omega" in fails[0] and "scales disagree" in fails[0] and "μω = μV/(μl·h)" in fails[0]
    assert "2.08333" in fails[0] and "-4.00e-02" in fails[0]


def test_a_doctored_pole_distance_fails_the_scale_relation(gear_sheet, tmp_path):
    line = re.search(r'<line data-construction="ω line"[^>]*/>', gear_sheet).group(0)
    y = re.search(r'y1="([^"]+)"', line).group(1)
    moved = line.replace(f'y1="{y}"', f'y1="{float(y) + 1:g}"').replace(f'y2="{y}"', f'y2="{float(y) + 1:g}"')
    code, fails = _check(tmp_path, gear_sheet.replace(line, moved))
    assert code == 1 and any("scales disagree" in f for f in fails), fails


def test_a_ray_that_does_not_start_at_the_pole_fails(gear_sheet, tmp_path):
    ray = re.search(r'<line data-construction="ray" data-ray="1"[^>]*/>', gear_sheet).group(0)
    x1, x2, y1, y2 = (float(re.search(f'{k}="([^"]+)"', ray).group(1)) for k in ("x1", "x2", "y1", "y2"))
    half = ray.replace(f'x1="{x1:g}"', f'x1="{(x1 + x2) / 2:.3f}"').replace(f'y1="{y1:g}"', f'y1="{(y1 + y2) / 2:.3f}"')
    assert half != ray
    code, fails = _check(tmp_path, gear_sheet.replace(ray, half))
    # still parallel to link 1's line and still ending where ω1 ends: only its start is wrong
    assert code == 1 and len(fails) == 1 and fails[0].startswith("FAIL ray of 1 starts") and "from the pole" in fails[0]
    length = math.hypot(x2 - x1, y2 - y1) / 2
    assert f"{length:.3g} mm" in fails[0]


def _idlers(n: int) -> str:
    """A row of ``n`` wheels, each meshing the next, the first driven."""
    wheels = "\n".join(f"w{i} = {{ teeth = {20 + i % 3} }}" for i in range(n))
    meshes = ", ".join(f'["w{i}", "w{i + 1}"]' for i in range(n - 1))
    return f'[gears]\nmeshes = [{meshes}]\n[gears.wheels]\n{wheels}\n[gears.input]\nw0 = 100.0\n'


def test_a_train_of_more_wheels_than_the_bound_is_one_line(tmp_path):
    """200 idlers in a row took 13 s (120: 60 s on a loaded machine): refused at the bound."""
    from plans.scene.gears import MAX_WHEELS

    line = refused_line(tmp_path, _idlers(2 * MAX_WHEELS))
    assert "[gears.wheels]" in line and f"at most {MAX_WHEELS}" in line, line


def test_a_row_of_idlers_at_the_bound_turns_as_the_first_wheel_and_the_teeth_say():
    """MAX_WHEELS idlers in a row: each wheel's speed is n0·(−1)^k·z0/z_k (the idlers between cancel)."""
    import tomllib

    import plans
    from plans.scene.gears import MAX_WHEELS

    from fractions import Fraction

    speeds = plans.render(plans.parse_scene(tomllib.loads(_idlers(MAX_WHEELS))), stem="row").report["gears"]["speeds"]
    for k in (1, 2, MAX_WHEELS - 1):
        assert Fraction(speeds[f"w{k}"]["rpm_exact"]) == 100 * (-1) ** k * Fraction(20, 20 + k % 3)

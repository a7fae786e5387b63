"""The gear scenes tried as a stranger would: values at the edge of `[gear_pair]` and `[gears]`
(teeth 1 … 10⁶, modules 1e-300 … 1e308, pressure angles 0 … 90°, shifts and addenda past their
bounds, rings with too few teeth, a tooth difference of 1, loops, a wheel meshing with itself,
two inputs on one shaft). A refusal is one line naming its key; an accepted edge case gives
finite numbers, checked against the closed forms of the textbooks, and sheets `plans check`
passes, drawn inside the sheet."""

from __future__ import annotations

import math
import re
import time

import pytest

from plans import render
from plans.checking import inspect_svg
from plans.errors import SceneError
from plans.scene import parse_scene


def _inv(a: float) -> float:
    return math.tan(a) - a


def _pair(**kw) -> dict:
    return {"title": "p", "gear_pair": kw}


def _train(wheels: dict, **gears) -> dict:
    return {"title": "t", "gears": {"wheels": wheels, **gears}}


def _w(z, m=2.0, **kw) -> dict:
    return {"teeth": z, **({} if m is None else {"module": m}), **kw}


EXT = {"z1": 20, "z2": 40, "module": 5.0}
RING = {"z1": 20, "z2": 80, "module": 5.0, "internal": True}
RACK = {"z1": 20, "module": 5.0, "rack": True}
#: Textbook Fig. 1.21: sun 1, planet 2 on carrier H, ring 3.
PLANETARY = {"1": _w(18, 3.0), "2": _w(27, 3.0, on="H"), "3": _w(72, 3.0, internal=True)}
#: The same with wheel x on the sun's shaft (a differential: W = 2).
DIFFERENTIAL = {**PLANETARY, "x": _w(20, 3.0, shaft="1")}


def _refused(scene: dict) -> SceneError:
    with pytest.raises(SceneError) as e:
        render(parse_scene(scene))
    assert "\n" not in str(e.value)
    return e.value


PAIR_REFUSALS = [
    ({**EXT, "z1": 4}, "gear_pair.z1", "5 … 500"),
    ({**EXT, "z1": 10 ** 6}, "gear_pair.z1", "5 … 500"),
    ({**EXT, "z1": True}, "gear_pair.z1", "whole"),
    ({**EXT, "z1": -0.0}, "gear_pair.z1", "whole"),
    ({**EXT, "module": 1e-300}, "gear_pair.module", "0.05"),
    ({**EXT, "module": 1e-9}, "gear_pair.module", "0.05"),
    ({**EXT, "module": 1e6}, "gear_pair.module", "range"),
    ({**EXT, "module": 1e308}, "gear_pair.module", "range"),
    ({**EXT, "module": float("nan")}, "gear_pair.module", "finite"),
    ({**EXT, "module": "5"}, "gear_pair.module", "number"),
    *[({**EXT, "pressure_angle": a}, "gear_pair.pressure_angle", "35°") for a in (0.0, 1e-9, 45.0, 89.9, 90.0)],
    ({**EXT, "addendum": -1.0}, "gear_pair.addendum", "0.5 … 1.5"),
    ({**EXT, "addendum": []}, "gear_pair.addendum", "one per wheel"),
    ({**EXT, "addendum": [0.0, 0.0]}, "gear_pair.addendum", "both"),
    ({**EXT, "clearance": -0.1}, "gear_pair.clearance", "0 … 0.5"),
    ({**EXT, "x1": 1e308}, "gear_pair.x1", "range"),
    ({**EXT, "x1": -3.0}, "gear_pair.x1", "too negative"),
    ({**EXT, "x1": 3.0}, "gear_pair.x1", "pointed"),
    ({**EXT, "n1": 0.0}, "gear_pair.n1", "above 0"),
    ({**EXT, "n1": 1e12}, "gear_pair.n1", "range"),
    ({**EXT, "shift": True}, "gear_pair.shift", "balanced"),
    ({**EXT, "colour": 1}, "gear_pair.colour", "unknown"),
    # a pointed tip with no shift given is the addendum's (or the pressure angle's), not x1's
    ({**EXT, "pressure_angle": 35.0, "addendum": 1.5, "clearance": 0.5}, "gear_pair.addendum", "pressure angle"),
    ({**RING, "z2": 20}, "gear_pair.z2", "more teeth"),
    ({**RING, "z2": 19}, "gear_pair.z2", "more teeth"),
    ({**RING, "z2": 21}, "gear_pair", "base circle"),
    ({**RING, "z2": 63}, "gear_pair", "involute interference"),
    # the ring's tooth space (its pinion cutter's tooth) closes before the root circle: was a GEOSException
    ({**RING, "x1": 0.0, "x2": 3.0}, "gear_pair.x2", "root circle"),
    ({**RING, "pressure_angle": 35.0}, "gear_pair.pressure_angle", "root circle"),
    ({**RING, "internal": 1}, "gear_pair.internal", "true"),
    ({**RING, "shift": "balanced"}, "gear_pair.shift", "x1, x2"),
    ({**RACK, "x2": 0.1}, "gear_pair.x2", "not shifted"),
    ({**RACK, "internal": True}, "gear_pair.rack", "not both"),
    ({**RACK, "x1": -0.5}, "gear_pair", "N1"),
    ({**RACK, "x1": -3.0}, "gear_pair.x1", "nearer 0"),
    ({**RACK, "z1": 5, "shift": "no_undercut"}, "gear_pair.x1", "pointed"),
]


@pytest.mark.parametrize("table, key, word", PAIR_REFUSALS)
def test_pair_refusals(table, key, word):
    e = _refused(_pair(**table))
    assert e.key == key and word in str(e)


def test_tooth_difference_one_is_refused_in_finite_words():
    """499 inside 500: the tip circles do not cross; the message gave "-inf rad" before."""
    e = _refused(_pair(z1=499, z2=500, module=5.0, internal=True))
    assert e.key == "gear_pair" and "does not cross" in str(e)
    assert not re.search(r"\b(inf|nan)\b", str(e))


TRAIN_REFUSALS = [
    (_train({"a": _w(0), "b": _w(40)}, meshes=[["a", "b"]], input={"a": 1.0}), "gears.wheels.a.teeth", "1 … 10000"),
    (_train({"a": _w(10001), "b": _w(40)}, meshes=[["a", "b"]], input={"a": 1.0}), "gears.wheels.a.teeth", "10000"),
    (_train({"a": _w("20"), "b": _w(40)}, meshes=[["a", "b"]], input={"a": 1.0}), "gears.wheels.a.teeth", "whole"),
    (_train({"a": _w(20, 1e-9), "b": _w(40, 1e-9)}, meshes=[["a", "b"]], input={"a": 1.0}),
     "gears.wheels.a.module", "0.001"),
    (_train({"a": _w(20), "b": _w(40)}, meshes=[["a", "b"]], input={"a": 1e12}), "gears.input.a", "1e+07"),
    (_train({"a": _w(20), "b": _w(40)}, meshes=[["a", "b"]], input={"a": float("nan")}), "gears.input.a", "finite"),
    (_train({"a": _w(20), "b": _w(40)}, meshes=[["a", "a"], ["a", "b"]], input={"a": 1.0}), "gears.meshes[0]",
     "itself"),
    (_train({"a": _w(20)}, input={"a": 1.0}), "gears.meshes", "pairs"),
    (_train({}, input={}), "gears.wheels", "needs its wheels"),
    (_train({"a": _w(20), "b": _w(20), "c": _w(20)}, meshes=[["a", "b"], ["b", "c"], ["c", "a"]], input={"a": 1.0}),
     "gears", "locked"),
    (_train(PLANETARY, carriers=["H"], meshes=[["1", "2"], ["2", "3"]], fixed=["H", "1"], input={"3": 1.0}),
     "gears", "locked"),
    (_train(DIFFERENTIAL, carriers=["H"], meshes=[["1", "2"], ["2", "3"]], input={"1": 1.0, "x": 1.0}),
     "gears.input.x", "one shaft"),
    (_train({"p": _w(30), "r": _w(30, internal=True)}, meshes=[["p", "r"]], input={"p": 1.0}), "gears.meshes",
     "more teeth"),
    (_train({"p": _w(30), "r": _w(31, internal=True)}, meshes=[["p", "r"]], input={"p": 1.0}), "gears.meshes",
     "interfere"),
    (_train({f"w{i}": _w(20) for i in range(101)}, meshes=[[f"w{i}", f"w{i + 1}"] for i in range(100)],
            input={"w0": 1.0}), "gears.wheels", "at most 100"),
    (_train(PLANETARY, carriers=["H"], meshes=[["1", "2"], ["2", "3"]], fixed=["3"], planets=25, input={"1": 1.0}),
     "gears.planets", "1 … 24"),
    (_train({"a": _w(20), "b": _w(40)}, meshes=[["a", "b"]], input={"a": 1.0}, bogus=1), "gears.bogus", "unknown"),
]


@pytest.mark.parametrize("scene, key, word", TRAIN_REFUSALS)
def test_train_refusals(scene, key, word):
    e = _refused(scene)
    assert e.key == key and word in str(e)


def _clean(sheets, tmp_path) -> dict:
    """The report, after asserting every number finite, every SVG free of nan/inf, passing
    `plans check` and its ink inside the sheet's viewBox."""
    text = sheets.json
    assert not re.search(r"\b(NaN|Infinity)\b", text)
    for name, svg in sheets.files.items():
        if not name.endswith(".svg"):
            continue
        assert not re.search(r"[\s=\"',(-](nan|inf)\b", svg, re.IGNORECASE), name
        path = tmp_path / name
        path.write_text(svg)
        assert inspect_svg(path).ok, name
    return sheets.report


def _ink_extent(svg: str) -> float:
    """The largest |coordinate| of a drawn path or polygon (mm of paper)."""
    out = 0.0
    for m in re.finditer(r"<(?:path|polygon)\b[^>]*?(?:d|points)=\"([^\"]*)\"", svg):
        nums = [abs(float(v)) for v in re.findall(r"-?\d+\.?\d*(?:e-?\d+)?", m.group(1))]
        out = max([out, *nums])
    return out


def _external_ratio(g: dict, z1: int, z2: int, alpha: float) -> float:
    """ε_α = [z1(tan α_a1 − tan α_w) + z2(tan α_a2 − tan α_w)]/2π."""
    aw = math.radians(g["working_pressure_angle"])
    ta = [math.tan(math.acos(db / da)) for db, da in zip(g["db"], g["da"])]
    return (z1 * (ta[0] - math.tan(aw)) + z2 * (ta[1] - math.tan(aw))) / (2 * math.pi)


@pytest.mark.parametrize("module", [0.05, 1000.0])
def test_pair_modules_at_the_bounds(module, tmp_path):
    """The standard 20/40 pair at the smallest and largest module: a_w = m(z1 + z2)/2, ε_α from the
    tip circles d ± 2m; m = 1000 is drawn reduced (1:100) inside the sheet, in seconds (65 s before,
    its general view and detail 30 m off the sheet at 1:1 and 1:100)."""
    t = time.perf_counter()
    sheets = render(parse_scene(_pair(z1=20, z2=40, module=module)))
    g = _clean(sheets, tmp_path)["gear_pair"]
    assert time.perf_counter() - t < 20.0
    assert g["centre_distance"] == pytest.approx(module * 30.0, rel=1e-12)
    a = math.radians(20.0)
    ta = [math.sqrt((z + 2) ** 2 - (z * math.cos(a)) ** 2) / (z * math.cos(a)) for z in (20, 40)]
    eps = (20 * (ta[0] - math.tan(a)) + 40 * (ta[1] - math.tan(a))) / (2 * math.pi)
    assert g["contact_ratio"] == pytest.approx(eps, rel=1e-12)
    for svg in (s for n, s in sheets.files.items() if n.endswith(".svg")):
        assert _ink_extent(svg) <= 420.0
    if module == 1000.0:
        assert "detail 1:100 " in sheets.files["p-meshing.svg"]


def test_ring_gear_closed_forms(tmp_path):
    """20 in 80 at 1e-300 rpm: a_w = m(z2 − z1)/2,
    ε_α = [z1(tan α_a1 − tan α) − z2(tan α_a2 − tan α)]/2π, the sliding velocities finite:
    (ω1 − ω2)·approach, ω = 2πn/60."""
    g = _clean(render(parse_scene(_pair(**RING, n1=1e-300))), tmp_path)["gear_pair"]
    a = math.radians(20.0)
    r1, r2 = 50.0, 200.0
    ta1 = math.sqrt((r1 + 5) ** 2 - (r1 * math.cos(a)) ** 2) / (r1 * math.cos(a))
    ta2 = math.sqrt((r2 - 5) ** 2 - (r2 * math.cos(a)) ** 2) / (r2 * math.cos(a))
    assert g["centre_distance"] == pytest.approx(150.0, rel=1e-12)
    eps = (20 * (ta1 - math.tan(a)) - 80 * (ta2 - math.tan(a))) / (2 * math.pi)
    assert g["contact_ratio"] == pytest.approx(eps, rel=1e-12)
    w = 2 * math.pi * 1e-300 / 60 * (1 - 20 / 80)
    assert g["sliding_velocity"]["engagement"] == pytest.approx(w * g["path_of_approach"] / 1000, rel=1e-12)
    assert g["sliding_velocity"]["engagement"] > 0.0


def test_rack_with_a_shift(tmp_path):
    """Pinion 20 shifted by x1 = 0.5 on a rack: a_w = r1 + x1·m, α_w = α,
    ε_α = z1(tan α_a1 − tan α)/2π + (ha* − x1)/(π sin α cos α)."""
    g = _clean(render(parse_scene(_pair(**RACK, x1=0.5))), tmp_path)["gear_pair"]
    a = math.radians(20.0)
    ra, rb = 50.0 + (1 + 0.5) * 5.0, 50.0 * math.cos(a)
    eps = (20 * (math.sqrt(ra * ra - rb * rb) / rb - math.tan(a)) / (2 * math.pi)
           + 0.5 / (math.pi * math.sin(a) * math.cos(a)))
    assert g["centre_distance"] == pytest.approx(52.5, rel=1e-12)
    assert g["contact_ratio"] == pytest.approx(eps, rel=1e-12)


def test_steep_pressure_angle(tmp_path):
    """α = 35° (the bound): inv α_w = inv α (no shift), ε_α from the closed form; the tips warn thin."""
    sheets = render(parse_scene(_pair(**EXT, pressure_angle=35.0)))
    g = _clean(sheets, tmp_path)["gear_pair"]
    assert g["working_pressure_angle"] == pytest.approx(35.0, rel=1e-12)
    assert g["contact_ratio"] == pytest.approx(_external_ratio(g, 20, 40, math.radians(35.0)), rel=1e-12)
    assert any("thin" in w for w in sheets.warnings)


@pytest.mark.parametrize("rpm", [0.0, 1e-300, -1450.0, 1e7])
def test_train_speeds_at_the_edge(rpm, tmp_path):
    """One external mesh a(1 tooth, m = 1e-3 mm) → b(10 000): n_a = −(z_b/z_a)·n_b exactly."""
    scene = _train({"a": _w(1, 1e-3), "b": _w(10000, 1e-3)}, meshes=[["a", "b"]], input={"b": rpm})
    r = _clean(render(parse_scene(scene)), tmp_path)["gears"]
    assert r["speeds"]["a"]["rpm"] == -10000 * rpm
    assert r["speeds"]["a"]["omega"] == pytest.approx(-10000 * rpm * math.pi / 30, rel=1e-12)
    assert r["geometry"]["pitch_radius_mm"] == {"a": 0.0005, "b": 5.0}


def test_planetary_and_a_hundred_idlers(tmp_path):
    """Fig. 1.21 with ring 3 fixed: n_H = n_1/(1 + z3/z1) = 1450/5; 100 wheels in a row:
    n_last = (−1)^99 · n_0 · z_0/z_99 (the idlers cancel)."""
    r = _clean(render(parse_scene(_train(PLANETARY, carriers=["H"], meshes=[["1", "2"], ["2", "3"]], fixed=["3"],
                                         planets=3, input={"1": 1450.0}))), tmp_path)["gears"]
    assert r["speeds"]["H"]["rpm"] == pytest.approx(290.0, rel=1e-15)
    wheels = {f"w{i}": _w(20 + i % 3, 1.0) for i in range(100)}
    scene = _train(wheels, meshes=[[f"w{i}", f"w{i + 1}"] for i in range(99)], input={"w0": 100.0})
    r = render(parse_scene(scene)).report["gears"]
    assert r["speeds"]["w99"]["rpm"] == pytest.approx(-100.0 * 20 / 20, rel=1e-15)     # z_99 = 20 + 99 % 3 = 20

"""Gear trains (textbook §3): the speeds of every example against an independent tabular method
written here in fractions from the scene's own numbers (not plans.gears), the textbook's closed
forms (1.21) and (1.26), the gear sheet read back by ``plans check`` and the layout measurer,
the train driving the press, and every refusal as one line with nothing written."""

from __future__ import annotations

import json
import math
import re
import tomllib
from fractions import Fraction
from pathlib import Path

import pytest

import plans
from plans.checking import inspect_svg
from plans.layout import measure_layout

from conftest import plans_cli

EXAMPLES = Path(__file__).resolve().parent.parent / "examples" / "gears"
TRAINS = ("gear_compound_1_17", "gear_idler_1_18", "planetary_1_21", "differential_1_21", "planetary_type_b",
          "press_drive")


def _load(name: str) -> dict:
    return tomllib.loads((EXAMPLES / f"{name}.toml").read_text(encoding="utf-8"))["gears"]


# --- an independent solution: the tabular method, from the scene's numbers ---------------------

def _tabular(gears: dict) -> dict[str, Fraction]:
    """Speeds (rpm) by the textbook's tabular method, for a train of at most one carrier whose
    planets mesh its central wheels, plus ordinary stages on fixed axes.

    Step 1 (carrier held): turn the train relative to the carrier, propagating mesh by mesh
    ω_b' = ω_a'·(∓ z_a/z_b), joined wheels alike. Step 2: add n_H to everything. The unknown
    scale of step 1 and n_H come from the inputs and the fixed wheel."""
    wheels = gears["wheels"]
    carriers = gears.get("carriers", [])
    shaft = {n: w.get("shaft") for n, w in wheels.items()}

    def root(n):
        while n in shaft and shaft[n] is not None:
            n = shaft[n]
        return n

    planetary = [m for m in gears["meshes"] if wheels[m[0]].get("on") or wheels[m[1]].get("on")]
    ordinary = [m for m in gears["meshes"] if m not in planetary]
    rel: dict[str, Fraction] = {}           # speeds relative to the carrier, per unit of the first central wheel
    if carriers:
        first = next(n for m in planetary for n in m if not wheels[n].get("on"))
        rel[root(first)] = Fraction(1)
        changed = True
        while changed:
            changed = False
            for a, b in planetary:
                sign = 1 if (wheels[a].get("internal") or wheels[b].get("internal")) else -1
                for x, y in ((a, b), (b, a)):
                    if root(x) in rel and root(y) not in rel:
                        rel[root(y)] = rel[root(x)] * sign * Fraction(wheels[x]["teeth"], wheels[y]["teeth"])
                        changed = True
        h = carriers[0]
        fixed = [root(n) for n in gears.get("fixed", []) if n in wheels]
        inputs = {root(n): Fraction(repr(float(v))) for n, v in gears["input"].items()}
        # unknowns: s (scale of the relative turn) and n_H: n_x = s·rel_x + n_H
        eqs = [(rel[f], Fraction(1), Fraction(0)) for f in fixed if f in rel]
        eqs += [(Fraction(0) if x == h else rel[x], Fraction(1), v) for x, v in inputs.items()]
        (a1, b1, c1), (a2, b2, c2) = eqs[:2]
        det = a1 * b2 - a2 * b1
        s, nh = (c1 * b2 - c2 * b1) / det, (a1 * c2 - a2 * c1) / det
        speed = {x: s * r + nh for x, r in rel.items()}
        speed[h] = nh
        for n in wheels:
            if root(n) == h or shaft.get(n) == h:
                speed[root(n)] = nh
    else:
        speed = {root(n): Fraction(repr(float(v))) for n, v in gears["input"].items()}
    changed = True
    while changed:
        changed = False
        for a, b in ordinary:
            for x, y in ((a, b), (b, a)):
                rx, ry = root(x), root(y)
                if rx in speed and ry not in speed:
                    sign = 1 if (wheels[x].get("internal") or wheels[y].get("internal")) else -1
                    speed[ry] = speed[rx] * sign * Fraction(wheels[x]["teeth"], wheels[y]["teeth"])
                    changed = True
    out = {n: speed[root(n)] for n in wheels}
    out.update({h: speed[h] for h in carriers})
    return out


@pytest.mark.parametrize("name", TRAINS)
def test_speeds_equal_the_tabular_method_exactly(name):
    gears = _load(name)
    scene = plans.read_scene(EXAMPLES / f"{name}.toml")
    analysis = plans.gears.analyse_train(scene.gears)
    expected = _tabular(gears)
    assert dict(analysis.speeds.rpm) == expected
    for n, value in expected.items():
        assert abs(analysis.speeds.omega(n) - float(value) * math.pi / 30) <= 1e-12 * max(1.0, abs(float(value)))


def test_compound_train_is_the_product_of_its_pairs_1_21():
    g = _load("gear_compound_1_17")["wheels"]
    z = {n: Fraction(g[n]["teeth"]) for n in g}
    i16 = (-z["2"] / z["1"]) * (-z["4"] / z["3"]) * (-z["6"] / z["5"])      # three external meshes: minus
    speeds = plans.gears.analyse_train(plans.read_scene(EXAMPLES / "gear_compound_1_17.toml").gears).speeds
    assert speeds.ratio("1", "6") == i16 == -15


def test_idlers_change_only_the_sign():
    g = _load("gear_idler_1_18")["wheels"]
    speeds = plans.gears.analyse_train(plans.read_scene(EXAMPLES / "gear_idler_1_18.toml").gears).speeds
    assert speeds.ratio("1", "4") == -Fraction(g["4"]["teeth"], g["1"]["teeth"])


def test_planetary_ratio_is_one_plus_z3_over_z1_1_26():
    g = _load("planetary_1_21")["wheels"]
    speeds = plans.gears.analyse_train(plans.read_scene(EXAMPLES / "planetary_1_21.toml").gears).speeds
    assert speeds.ratio("1", "H") == 1 + Fraction(g["3"]["teeth"], g["1"]["teeth"])
    w = speeds.willis[0]
    assert w.ratio == -Fraction(g["3"]["teeth"], g["1"]["teeth"]) and abs(w.residual) < 1e-9


def test_differential_satisfies_willis_with_both_inputs():
    gears = _load("differential_1_21")
    z1, z3 = gears["wheels"]["1"]["teeth"], gears["wheels"]["3"]["teeth"]
    n1, n3 = (Fraction(repr(gears["input"][k])) for k in ("1", "3"))
    i13 = -Fraction(z3, z1)
    nh = (n1 - i13 * n3) / (1 - i13)                    # (n1 − nH)/(n3 − nH) = i13^H solved for nH
    speeds = plans.gears.analyse_train(plans.read_scene(EXAMPLES / "differential_1_21.toml").gears).speeds
    assert speeds.structure.mobility == 2 and speeds.rpm["H"] == nh


def _render(name: str, tmp_path: Path) -> Path:
    out = tmp_path / name
    plans.render(EXAMPLES / f"{name}.toml").save(out)
    return out


@pytest.mark.parametrize("name", TRAINS)
def test_gear_sheet_passes_check_and_layout_and_reads_back_omega(name, tmp_path):
    out = _render(name, tmp_path)
    svg = out / f"{name}-gears.svg"
    report = inspect_svg(svg)
    assert report.kind == "plan" and report.ok, (report.problems, [m for m in report.measurements if not m.ok])
    layout = measure_layout(svg.read_text(encoding="utf-8"))
    assert layout.clean, {k: layout.offenders(k) for k, v in layout.counts.items() if v}
    data = json.loads((out / f"{name}.json").read_text(encoding="utf-8"))["gears"]
    text = svg.read_text(encoding="utf-8")
    mu = float(re.search(r'data-mu="([^"]+)" data-plan="gear-omega"', text)[1])
    read = {m[0]: math.hypot(float(m[3]) - float(m[1]), 0.0) for m in
            re.findall(r'data-quantity="omega:([^"]+)"[^>]*?x1="([-0-9.]+)"[^>]*?x2="([-0-9.]+)"', text)
            for m in [(m[0], m[1], None, m[2])]}
    assert read, "no ω segment found"
    for link, length in read.items():
        exact = abs(data["speeds"][link]["omega"])
        assert abs(length * mu - exact) <= mu * 2 * math.sqrt(2) * 5e-4 + 1e-9 * exact


def test_press_crank_turns_at_the_trains_output(tmp_path):
    sheets = plans.render(EXAMPLES / "press_drive.toml")
    report = sheets.report
    expected = float(report["gears"]["speeds"]["f"]["omega"])
    assert expected == pytest.approx(-1450 / 5 * 19 / 72 * math.pi / 30, rel=1e-15)
    assert all(p["links"]["1"]["omega"] == expected for p in report["positions"])
    assert "gears" in sheets.sheets


def test_rendering_a_train_twice_is_byte_identical():
    a = plans.render(EXAMPLES / "planetary_type_b.toml").files
    b = plans.render(EXAMPLES / "planetary_type_b.toml").files
    assert a == b


BASE = """
[gears.wheels]
a = { teeth = 18, module = 3.0 }
g = { teeth = 27, module = 3.0, on = "H" }
b = { teeth = 72, module = 3.0, internal = true }
[gears]
carriers = ["H"]
meshes = [["a", "g"], ["g", "b"]]
fixed = ["b"]
planets = 3
[gears.input]
a = 1450.0
"""

BAD = {
    "two inputs for W = 1": (BASE + 'H = 10.0\n', "W = 1 but [gears.input] gives 2"),
    "no input": (BASE.replace("a = 1450.0\n", ""), "W = 1 but [gears.input] gives 0"),
    "locked": (BASE.replace('fixed = ["b"]', 'fixed = ["b", "H"]'), "locked"),
    "carrier without planet": (BASE.replace('carriers = ["H"]', 'carriers = ["H", "K"]'), "carries no planet"),
    "two ring gears": (BASE.replace('on = "H" }', 'on = "H", internal = true }'), "both ring gears"),
    "input on a fixed link": (BASE.replace('fixed = ["b"]', 'fixed = ["a"]').replace("a = 1450.0", "b = 1450.0")
                              .replace('fixed = ["a"]', 'fixed = ["b"]'), "held still"),
    "modules differ": (BASE.replace('g = { teeth = 27, module = 3.0', 'g = { teeth = 27, module = 2.5'),
                       "different modules"),
    "coaxial": (BASE.replace("teeth = 72", "teeth = 70"), "coaxial condition does not close"),
    "assembly": (BASE.replace("teeth = 18", "teeth = 16").replace("teeth = 27", "teeth = 28")
                 .replace("teeth = 72", "teeth = 72"), "cannot be assembled"),
    "neighbourhood": (BASE.replace("planets = 3", "planets = 9"), "do not fit"),
    "unknown wheel in a mesh": (BASE.replace('["g", "b"]', '["g", "x"]'), "unknown wheel 'x'"),
    "unknown carrier": (BASE.replace('on = "H"', 'on = "K"'), "is not a carrier"),
    "omega with output": (None, "remove omega"),
}


def _bad_scene(tmp_path: Path, text: str | None) -> Path:
    if text is None:
        body = (EXAMPLES / "press_drive.toml").read_text(encoding="utf-8").replace(
            "# omega: from the gear train", "omega = 8.0  #")
        text = body
    p = tmp_path / "bad.toml"
    p.write_text(text, encoding="utf-8")
    return p


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_trains_are_refused_in_one_line_with_nothing_written(case, tmp_path):
    text, words = BAD[case]
    scene = _bad_scene(tmp_path, text)
    out = tmp_path / "out"
    r = plans_cli(["render", scene, "-o", out])
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("plans: error:") and words in lines[0], r.stderr
    assert "Traceback" not in r.stderr
    assert not out.exists() or not any(out.iterdir())


def test_the_assembly_case_above_really_breaks_assembly_only():
    # (z_a + z_b)/k for 16 + 72 = 88 teeth and 3 planets is not whole; coaxial 16 + 2·28 = 72 holds
    assert (16 + 72) % 3 != 0 and 16 + 2 * 28 == 72


def test_without_modules_the_train_is_solved_and_a_note_says_the_geometry_went_unchecked(tmp_path):
    text = re.sub(r", module = [0-9.]+", "", BASE)
    sheets = plans.render(_bad_scene(tmp_path, text))
    assert sheets.report["gears"]["geometry"] is None
    assert any("unchecked" in w for w in sheets.warnings)
    assert sheets.train.speeds.ratio("a", "H") == 5


def test_undercut_is_a_warning(tmp_path):
    text = BASE.replace("teeth = 18", "teeth = 12").replace("teeth = 27", "teeth = 30")
    sheets = plans.render(_bad_scene(tmp_path, text))
    assert any("undercut" in w and "'a'" in w for w in sheets.warnings)


# output/ holding the gear examples' files: tests/test_render.py's committed-gallery test compares
# everything `plans demo` renders, the gear trains with the linkages.

"""The cycle of ``[drive] positions = N``: equal steps, the exact extreme start, the positions,
diagrams and velocities sheets measured from their SVG against independent values (closed
forms of the central crank-slider, fresh analyses at the instants the sheets name), the JSON
table, unreachable positions and bad input."""

from __future__ import annotations

import math
import re
import tomllib
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import plans
from conftest import EXAMPLES, sheet_words
from plans.errors import AssemblyError, PlansError, SceneError
from plans.kinematics import analyse
from plans.model import build_mechanism
from plans.scene import parse_scene
from plans.structure import analyse_structure

SVG = "{http://www.w3.org/2000/svg}"
PRESS = next(p for p in EXAMPLES if p.stem == "six_link_press")
SLIDER = next(p for p in EXAMPLES if p.stem == "crank_slider_central")
FOUR_BAR = next(p for p in EXAMPLES if p.stem == "four_bar")


def load(path) -> dict:
    return tomllib.loads(path.read_text(encoding="utf-8"))


def cycle_scene(path, *, positions=12, start=None, angle=30.0, draw=("positions", "diagrams", "velocities"),
                **plans_keys) -> dict:
    data = load(path)
    data["drive"]["positions"] = positions
    if start is not None:
        data["drive"]["start"] = start
        data["drive"].pop("angle", None)
    else:
        data["drive"]["angle"] = angle
    data["plans"] = {"draw": list(draw), **plans_keys}
    return data


def solved(data: dict, values, order=2):
    mech = build_mechanism(parse_scene({k: v for k, v in data.items() if k != "plans"} |
                                       {"drive": {k: v for k, v in data["drive"].items()
                                                  if k not in ("positions", "start")} | {"angle": 0.0}}))
    return analyse(mech, analyse_structure(mech), np.asarray(values, float), order=order)


def slider_x(phi_deg, r=0.1, l=0.4):
    """The central crank-slider's closed form: x_B, dx_B/dφ, d²x_B/dφ² (per radian)."""
    p = np.radians(phi_deg)
    root = np.sqrt(l * l - (r * np.sin(p)) ** 2)
    x = r * np.cos(p) + root
    dx = -r * np.sin(p) - r * r * np.sin(p) * np.cos(p) / root
    return x, dx


def sliding(motion, key="3/0"):
    sl = motion.sliding[key]
    return sl.s, sl.v, sl.a


# --- the positions ---------------------------------------------------------------------------

def test_positions_are_equal_steps_from_the_angle_in_the_sense_of_rotation():
    sheets = plans.render(PRESS)
    cyc = sheets.report["cycle"]
    phi = np.array(cyc["positions"])
    assert len(phi) == 12 and phi[0] == 60.0
    steps = np.mod(np.diff(phi), 360.0)
    assert np.allclose(steps, 30.0, rtol=0, atol=1e-9)
    assert [p["angle"] for p in sheets.report["positions"]] == cyc["positions"]
    data = cycle_scene(SLIDER, positions=8, angle=10.0)
    data["drive"]["omega"] = -4.0                 # clockwise: the positions follow the crank
    cyc = plans.render(parse_scene(data), stem="cw").report["cycle"]
    assert np.allclose(np.mod(np.diff(cyc["positions"]), 360.0), 360.0 - 45.0, rtol=0, atol=1e-9)


def test_extreme_start_is_where_the_slider_stops_at_its_smallest_displacement():
    """Central crank-slider: x_B is smallest with crank and rod folded (φ = 180°), where
    dx_B/dφ = 0 by the closed form; the solver's sliding velocity there is zero."""
    data = cycle_scene(SLIDER, start="extreme")
    report = plans.render(parse_scene(data), stem="cs").report["cycle"]
    phi0 = report["positions"][0]
    assert phi0 == pytest.approx(180.0, abs=1e-7)
    x, dx = slider_x(phi0)
    assert abs(dx) <= 1e-9 * 0.1
    m = solved(data, [phi0] + list(np.arange(0.0, 360.0, 0.1)), order=1)
    s, v, _ = sliding(m)
    assert abs(v[0]) <= 1e-9 * np.max(np.abs(v))
    assert s[0] <= np.min(s[1:]) + 1e-12
    lo, hi = report["extremes"]
    assert lo["angle"] == pytest.approx(180.0, abs=1e-7) and hi["angle"] % 360.0 == pytest.approx(0.0, abs=1e-7) \
        or hi["angle"] == pytest.approx(360.0, abs=1e-7)
    assert hi["s"] - lo["s"] == pytest.approx(2 * 0.1, rel=1e-12)      # stroke = 2r


@pytest.mark.parametrize("path, output", [(PRESS, "5"), (FOUR_BAR, "3")], ids=["press slider", "four-bar rocker"])
def test_extreme_start_of_a_general_output_has_zero_velocity_and_extreme_displacement(path, output):
    data = cycle_scene(path, start="extreme", draw=("positions",), output=output)
    report = plans.render(parse_scene(data), stem="x").report["cycle"]
    ext = [e["angle"] for e in report["extremes"]]
    assert report["positions"][0] == pytest.approx(ext[0], abs=1e-9)
    grid = np.arange(0.0, 360.0, 0.05)
    m = solved(data, ext + list(grid), order=1)
    if report["output"]["kind"] == "slider":
        s, v, _ = sliding(m, f"{output}/0")
    else:
        s, v = np.unwrap(m.links[output].theta), m.links[output].omega
    assert np.all(np.abs(v[:2]) <= 1e-9 * np.max(np.abs(v)))
    assert s[0] <= np.min(s[2:]) + 1e-12 and s[1] >= np.max(s[2:]) - 1e-12


def test_an_unreachable_position_is_reported_with_its_angle():
    """A four-bar driven by its rocker (C–B, 0.2 m) cannot turn it a full revolution."""
    data = cycle_scene(FOUR_BAR, angle=float(np.degrees(np.arctan2(0.199765243, 0.2303125 - 0.24))),
                       draw=("positions",))
    data["drive"]["link"] = "3"
    with pytest.raises(AssemblyError) as err:
        plans.render(parse_scene(data), stem="rocker")
    assert re.search(r"\d+(\.\d+)?°", str(err.value)), str(err.value)


# --- the diagrams ----------------------------------------------------------------------------

def _graphs(svg: str) -> dict:
    root = ET.fromstring(svg)
    return {g.get("data-diagram"): g for g in root.iter(f"{SVG}g") if g.get("data-diagram")}


def _path_points(d: str) -> np.ndarray:
    return np.array([[float(a), float(b)] for a, b in re.findall(r"([-\d.]+),([-\d.]+)", d)])


def _exact(data, start, omega, t):
    """s − s(start), v, a of the slider at times t (s), from a fresh analysis."""
    phi = start + np.degrees(omega * np.asarray(t))
    m = solved(data, np.concatenate([[start], phi]))
    s, v, a = sliding(m)
    return s[1:] - s[0], v[1:], a[1:]


def test_every_drawn_diagram_point_times_its_scale_is_the_exact_value():
    data = cycle_scene(SLIDER, start="extreme", draw=("diagrams",))
    sheets = plans.render(parse_scene(data), stem="cs")
    start, omega = sheets.report["cycle"]["positions"][0], data["drive"]["omega"]
    precision = 0.0005
    checked = 0
    for q, g in _graphs(sheets["diagrams"].svg).items():
        k = "sva".index(q)
        mu, mu_t = float(g.get("data-scale")), float(g.get("data-mu-t"))
        x0, y0 = map(float, g.get("data-origin").split(","))
        curve = next(p for p in g.iter(f"{SVG}path") if p.get("data-kind") == "exact")
        pts = _path_points(curve.get("d"))
        t = (pts[:, 0] - x0) * mu_t
        drawn = (y0 - pts[:, 1]) * mu
        exact = _exact(data, start, omega, t)[k]
        # both coordinates are rounded to `precision` mm: the ordinate by μ·precision, the
        # abscissa moves the instant by μt·precision, i.e. the value by |slope| × that
        slope = np.max(np.abs(np.diff(exact) / np.diff(t)))
        assert np.all(np.abs(drawn - exact) <= 2 * precision * (mu + slope * mu_t) + 1e-12), q
        assert t[0] == pytest.approx(0.0, abs=mu_t * precision) and len(pts) >= 361
        for dot in g.iter(f"{SVG}circle"):
            if dot.get("data-kind") != "exact":
                continue
            assert (y0 - float(dot.get("cy"))) * mu == pytest.approx(float(dot.get("data-value")), abs=2 * precision * mu)
            t_dot = float(dot.get("data-t"))
            assert float(dot.get("data-value")) == pytest.approx(_exact(data, start, omega, [t_dot])[k][0],
                                                                 abs=1e-9 * max(1.0, np.max(np.abs(exact))))
            checked += 1
    assert checked == 3 * 13


def test_graphical_derivatives_agree_with_the_exact_within_the_error_stated_on_the_sheet():
    data = cycle_scene(SLIDER, start="extreme", draw=("diagrams",))
    sheets = plans.render(parse_scene(data), stem="cs")
    start, omega = sheets.report["cycle"]["positions"][0], data["drive"]["omega"]
    words = sheet_words(sheets["diagrams"].svg).replace("\n", " ")
    stated = dict(zip("va", map(float, re.findall(r"by at most ([\d.]+) %", words))))
    assert set(stated) == {"v", "a"}
    graphs = _graphs(sheets["diagrams"].svg)
    dt = math.radians(30.0) / omega
    t_pos = np.arange(13) * dt
    s_pos = _exact(data, start, omega, t_pos)[0]
    chords = np.diff(s_pos) / dt                       # the chord method, done here
    second = (chords - np.roll(chords, 1)) / dt
    for q in "va":
        dots = [c for c in graphs[q].iter(f"{SVG}circle") if c.get("data-kind") == "graphical"]
        t = np.array([float(c.get("data-t")) for c in dots])
        g = np.array([float(c.get("data-value")) for c in dots])
        k = "sva".index(q)
        exact = _exact(data, start, omega, t)[k]
        peak = np.max(np.abs(_exact(data, start, omega, np.linspace(0, 2 * math.pi / omega, 721))[k]))
        worst = np.max(np.abs(g - exact)) / peak * 100
        assert worst <= stated[q] * (1 + 0.05) + 1e-9, (q, worst, stated[q])    # stated to two digits
        assert worst >= stated[q] * 0.95 - 1e-9
        want = chords if q == "v" else np.append(second, second[0])
        assert np.allclose(g, want, rtol=1e-9, atol=1e-9 * peak)
        assert np.allclose(t, (np.arange(12) + 0.5) * dt if q == "v" else t_pos, rtol=0, atol=1e-12)


def test_the_diagrams_scales_are_from_the_standard_series():
    sheets = plans.render(PRESS)
    dia = sheets.report["cycle"]["diagrams"]
    for mu in [dia["mu_t"], *dia["mu"].values()]:
        mantissa = mu / 10 ** math.floor(math.log10(mu))
        assert any(abs(mantissa - m) < 1e-9 for m in (1, 1.25, 2, 2.5, 4, 5, 8)), mu
    assert dia["mu_phi"] == pytest.approx(8.0 * dia["mu_t"])
    assert dia["period"] == pytest.approx(2 * math.pi / 8.0)


# --- the velocities sheet and the table ------------------------------------------------------

def test_the_table_of_values_is_the_motion_at_every_position():
    sheets = plans.render(PRESS)
    cyc = sheets.report["cycle"]
    table = cyc["table"]
    assert table["points"] == ["A", "B", "C", "E"] and table["links"] == ["2", "3", "4"]
    data = load(PRESS)
    m = solved(data, cyc["positions"], order=1)
    for i, row in enumerate(table["rows"]):
        assert row["angle"] == cyc["positions"][i]
        for p, v in row["v"].items():
            assert v == pytest.approx(np.linalg.norm(m.velocity(p)[i]), rel=1e-12, abs=1e-15)
        for link, w in row["omega"].items():
            assert w == pytest.approx(m.links[link].omega[i], rel=1e-12, abs=1e-15)
    svg = sheets["velocities"].svg
    root = ET.fromstring(svg)
    groups = [g for g in root.iter(f"{SVG}g") if g.get("data-plan") == "velocity"]
    assert len(groups) == 12
    mu = float(groups[0].get("data-mu"))
    for i, g in enumerate(groups):
        for line in g.iter(f"{SVG}line"):
            q = line.get("data-quantity")
            if q and re.fullmatch(r"v:[A-Z]", q):
                length = math.dist((float(line.get("x1")), float(line.get("y1"))),
                                   (float(line.get("x2")), float(line.get("y2"))))
                # both ends rounded to 0.001 mm (≤ 0.0005 a coordinate): the length within √2·0.001 mm
                want = np.linalg.norm(m.velocity(q[2:])[i])
                assert length * mu == pytest.approx(want, abs=(math.sqrt(2) * 0.001 + 1e-9) * mu)
    words = sheet_words(svg)
    assert "0.9641" in words                 # |v_C| at 60°, as the table prints it (4 digits)


def test_the_cycle_sheets_pass_plans_check(tmp_path):
    from plans.checking import inspect_svg

    sheets = plans.render(PRESS)
    for name in ("positions", "diagrams", "velocities"):
        (tmp_path / f"{name}.svg").write_text(sheets[name].svg)
        report = inspect_svg(tmp_path / f"{name}.svg")
        assert report.ok, (name, report)


def test_positions_sheet_draws_every_position_extremes_and_traces():
    sheets = plans.render(PRESS)
    root = ET.fromstring(sheets["positions"].svg)
    ids = {g.get("id"): g for g in root.iter(f"{SVG}g")}
    assert all(f"positions-pos{i}" in ids for i in range(12)) and "positions-pos12" not in ids
    ext = [float(ids[f"positions-ext{j}"].get("data-angle")) for j in range(2)]
    assert ext == pytest.approx([e["angle"] for e in sheets.report["cycle"]["extremes"]])
    trace = next(e for e in root.iter(f"{SVG}path") if e.get("data-point") == "C")
    pts = _path_points(trace.get("d"))
    assert len(pts) >= 360
    words = sheet_words(sheets["positions"].svg)
    assert "E′" in words and "E″" in words and "H = 0.08567 m" in words


# --- bad input -------------------------------------------------------------------------------

@pytest.mark.parametrize("change, key", [
    (lambda d: d["drive"].update(positions=0), "drive.positions"),
    (lambda d: d["drive"].update(positions=-3), "drive.positions"),
    (lambda d: d["drive"].update(positions=1e9), "drive.positions"),
    (lambda d: d["drive"].update(positions=10 ** 9), "drive.positions"),
    (lambda d: d["drive"].update(positions=2.5), "drive.positions"),
    (lambda d: d["drive"].update(positions=True), "drive.positions"),
    (lambda d: d["drive"].update(angle=[0.0, 90.0]), "drive.angle"),
    (lambda d: d["drive"].update(start="nope"), "drive.start"),
    (lambda d: d["drive"].update(start="extreme"), "drive.angle"),        # with angle too
    (lambda d: d["plans"].update(trace=["Z"]), "plans.trace"),
    (lambda d: d["plans"].update(trace="C"), "plans.trace"),
    (lambda d: d["plans"].update(output="9"), "plans.output"),
    (lambda d: d["plans"].update(output=5), "plans.output"),
    (lambda d: d["drive"].update(epsilon=1.0), "drive.epsilon"),
    (lambda d: d["drive"].update(omega=0.0), "drive.omega"),
    (lambda d: d["drive"].pop("positions"), "plans.draw"),
    (lambda d: (d["drive"].pop("positions"), d["plans"].update(draw=["scheme"])), "plans.output"),
])
def test_bad_cycle_input_names_the_key(change, key):
    data = load(PRESS)
    change(data)
    with pytest.raises(SceneError) as err:
        parse_scene(data)
    assert err.value.key == key, str(err.value)


def test_positions_need_a_crank_and_an_output_with_a_displacement():
    data = load(next(p for p in EXAMPLES if p.stem == "elliptic_trammel"))
    data["drive"]["positions"] = 12
    with pytest.raises(SceneError) as err:
        parse_scene(data)
    assert err.value.key == "drive.positions"
    data = cycle_scene(FOUR_BAR, draw=("positions",), output="2")      # the coupler: no frame pivot
    with pytest.raises(PlansError) as err:
        plans.render(parse_scene(data), stem="coupler")
    assert "plans.output" in str(err.value)


@pytest.mark.parametrize("at, words", [([12], "0 to 11"), ([1, 1], "each once"), (["0"], "position numbers"),
                                        ([True], "position numbers")])
def test_bad_at_is_named(at, words):
    data = tomllib.loads(PRESS.read_text(encoding="utf-8"))
    data["plans"]["at"] = at
    with pytest.raises(SceneError) as err:
        parse_scene(data)
    assert err.value.key == "plans.at" and words in str(err.value)


def test_at_without_positions_is_refused():
    data = tomllib.loads(PRESS.read_text(encoding="utf-8"))
    data["drive"].pop("positions")
    data["plans"] = {"draw": ["scheme"], "at": [0]}
    with pytest.raises(SceneError) as err:
        parse_scene(data)
    assert err.value.key == "plans.at"


def test_sheets_of_their_own_only_at_the_listed_positions():
    data = tomllib.loads(PRESS.read_text(encoding="utf-8"))
    data["plans"]["at"] = [1, 11]
    sheets = plans.render(parse_scene(data), stem="press")
    angles = [60.0 + 30.0 * k for k in (1, 11)]
    assert sorted(s.name for s in sheets if s.name.startswith("velocity-")) == \
        sorted(f"velocity-{a % 360:g}" for a in angles)
    assert len(sheets.report["positions"]) == 12

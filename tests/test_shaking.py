"""A linkage's shaking force and moment over the cycle and its counterweights (issue 37, items 3
and 4): ``draw = [..., "shaking"]`` and ``[counterweights]``.

Every check recomputes from the JSON report's own numbers (the accelerations of the centres in
``positions[i].points``, the links' ω and ε and angles) or from closed forms written out here,
never through plans' shaking code. Units: kg, m, s, N, N·m, degrees; moments CCW positive."""

from __future__ import annotations

import cmath
import json
import math
import tomllib

import numpy as np
import pytest

from conftest import EXAMPLES, refused_line, toml_text
from plans import render
from plans.dynamics.shaking import shaking_analysis
from plans.errors import SceneError
from plans.pipeline import record_stages
from plans.pipeline.stages import solve_motion
from plans.scene import parse_scene

RTOL = 1e-9


# --- scenes written here ------------------------------------------------------------------------

def _c(z: complex) -> list[float]:
    return [z.real, z.imag]


def four_bar(positions: int = 36, *, epsilon: float = 0.0, counterweights: dict | None = None,
             draw: tuple[str, ...] = ("shaking",), masses: bool = True) -> dict:
    """A crank-rocker OA = 0.08, AB = 0.25, BC = 0.2, OC = 0.24 sketched at 30°, its centres of
    mass off the links' lines (the coupler's S2 = A + (0.4 + 0.15i)(B − A)), so that the coupler's
    mass splits into complex parts at its pins."""
    o, c = 0j, 0.24 + 0j
    a = cmath.rect(0.08, math.radians(30.0))
    d = abs(c - a)
    x = (0.25 ** 2 - 0.2 ** 2 + d * d) / (2 * d)       # B on circle(A, 0.25) and circle(C, 0.2), above AC
    b = a + (c - a) / d * complex(x, math.sqrt(0.25 ** 2 - x * x))
    s1 = o + (a - o) * complex(0.45, 0.12)
    s2 = a + (b - a) * complex(0.4, 0.15)
    s3 = c + (b - c) * complex(0.55, -0.1)
    data = {"title": "Four-bar shaking",
            "points": {"O": _c(o), "C": _c(c), "A": _c(a), "B": _c(b), "S1": _c(s1), "S2": _c(s2), "S3": _c(s3)},
            "links": {"0": ["O", "C"], "1": ["O", "A", "S1"], "2": ["A", "B", "S2"], "3": ["C", "B", "S3"]},
            "drive": {"link": "1", "angle": 30.0, "positions": positions, "omega": 10.0, "epsilon": epsilon},
            "plans": {"draw": list(draw), "at": []}}
    if masses:
        data["masses"] = {"1": {"mass": 0.8, "inertia": 0.001, "centre": "S1"},
                          "2": {"mass": 2.4, "inertia": 0.02, "centre": "S2"},
                          "3": {"mass": 1.9, "inertia": 0.0065, "centre": "S3"}}
    if counterweights is not None:
        data["counterweights"] = counterweights
    return data


R_CRANK, L_ROD, T_ROD = 0.1, 0.4, 0.3      # crank, rod (n = 4), the rod's centre at 0.3·AB from A
M1, M2, M3 = 1.5, 3.0, 2.5                  # crank (centre on OA at 0.04 m), rod, slider


def crank_slider(positions: int = 72, *, fraction: float | None = 0.6, radius: float = 0.12) -> dict:
    """A central crank-slider on the x axis, the slider to the right of the crank's pivot, every
    centre on its link's line (the textbook's engine)."""
    phi = math.radians(30.0)
    a = complex(R_CRANK * math.cos(phi), R_CRANK * math.sin(phi))
    b = complex(R_CRANK * math.cos(phi) + math.sqrt(L_ROD ** 2 - (R_CRANK * math.sin(phi)) ** 2), 0.0)
    cw = {"radius": radius} if fraction is None else {"radius": radius, "reciprocating": fraction}
    return {"title": "Crank-slider shaking",
            "points": {"O": [0.0, 0.0], "A": _c(a), "S1": _c(a * 0.4), "B": _c(b), "S2": _c(a + T_ROD * (b - a))},
            "links": {"0": ["O"], "1": ["O", "A", "S1"], "2": ["A", "B", "S2"], "3": ["B"]},
            "sliders": [{"link": "3", "on": "0", "through": "B", "angle": 0.0}],
            "drive": {"link": "1", "angle": 30.0, "positions": positions, "omega": 10.0, "epsilon": 0.0},
            "masses": {"1": {"mass": M1, "centre": "S1"}, "2": {"mass": M2, "inertia": 0.04, "centre": "S2"},
                       "3": {"mass": M3, "centre": "B"}},
            "counterweights": {"1": cw},
            "plans": {"draw": ["shaking"], "at": []}}


def report(data: dict) -> dict:
    sheets = render(parse_scene(data), stem="s")
    return json.loads(sheets.files["s.json"])


def bundled_crank_slider() -> dict:
    """examples/crank_slider_forces.toml (masses, 24 positions) drawing its shaking."""
    data = tomllib.loads(next(p for p in EXAMPLES if p.stem == "crank_slider_forces").read_text(encoding="utf-8"))
    data["plans"] = {"draw": ["shaking"], "at": [], "output": "3"}
    return data


# --- the test's own sums ---------------------------------------------------------------------

def sums(data: dict, rep: dict, extra: list[tuple[float, np.ndarray, np.ndarray]] = ()):
    """From the JSON alone: per position Σ −m·a_S (N), Σ (r_S − O) × (−m·a_S) − Σ I·ε about the
    frame's first point (N·m), Σ m·r_S / Σ m (m), and the scale Σ |m·a_S| (N); ``extra`` adds
    point masses (m, r (N, 2), a (N, 2))."""
    o = np.array(data["points"][data["links"]["0"][0]], float)
    force, moment, first, scale, total = [], [], [], [], 0.0
    for i, pos in enumerate(rep["positions"]):
        f, mo, fr, sc = np.zeros(2), 0.0, np.zeros(2), 0.0
        for link, m in data["masses"].items():
            r = np.array(pos["points"][m["centre"]]["r"])
            a = np.array(pos["points"][m["centre"]]["a"])
            fi = -m["mass"] * a
            f += fi
            mo += (r[0] - o[0]) * fi[1] - (r[1] - o[1]) * fi[0] - m.get("inertia", 0.0) * pos["links"][link]["epsilon"]
            fr += m["mass"] * r
            sc += math.hypot(*fi)
        for m, r, a in extra:
            fi = -m * a[i]
            f += fi
            mo += (r[i][0] - o[0]) * fi[1] - (r[i][1] - o[1]) * fi[0]
            fr += m * r[i]
            sc += math.hypot(*fi)
        force.append(f)
        moment.append(mo)
        first.append(fr)
        scale.append(sc)
    total = sum(m["mass"] for m in data["masses"].values()) + sum(m for m, _, _ in extra)
    return np.array(force), np.array(moment), np.array(first) / total, np.array(scale), total


def counterweight_points(rep: dict, link: str) -> tuple[float, np.ndarray, np.ndarray]:
    """A reported counterweight as a point mass (m, r, a) at every position, from the JSON: its
    pivot's r, the link's angle, ω, ε (a = ε k × ρ − ω² ρ about a fixed pivot)."""
    cw = rep["counterweights"][link]
    rs, acc = [], []
    for pos in rep["positions"]:
        lk = pos["links"][link]
        th = math.radians(lk["angle"] + cw["angle"])
        rho = cw["radius"] * np.array([math.cos(th), math.sin(th)])
        rs.append(np.array(pos["points"][cw["pivot"]]["r"]) + rho)
        acc.append(lk["epsilon"] * np.array([-rho[1], rho[0]]) - lk["omega"] ** 2 * rho)
    return cw["mass"], np.array(rs), np.array(acc)


# --- the shaking force, moment and centre of mass -------------------------------------------

@pytest.mark.parametrize("make", [lambda: four_bar(epsilon=3.0), bundled_crank_slider],
                         ids=["four-bar, eps 3", "crank_slider_forces"])
def test_shaking_is_the_sum_of_the_inertia_forces_in_the_json(make):
    data = make()
    rep = report(data)
    sh = rep["cycle"]["shaking"]
    assert "shaking_without" not in rep["cycle"] and "counterweights" not in rep
    force, moment, centre, scale, total = sums(data, rep)
    n = len(rep["cycle"]["positions"])
    assert len(sh["force"]) == len(sh["moment"]) == len(sh["centre_of_mass"]) == len(rep["positions"]) == n
    assert sh["about"] == data["links"]["0"][0] and sh["origin"] == data["points"][sh["about"]]
    assert sh["mass"] == pytest.approx(total, rel=1e-15)
    arm = max(math.hypot(*p) for p in data["points"].values())
    for i in range(n):
        assert np.abs(np.array(sh["force"][i]) - force[i]).max() <= RTOL * scale[i]
        assert abs(sh["moment"][i] - moment[i]) <= RTOL * (scale[i] * arm + 1.0)
        assert np.abs(np.array(sh["centre_of_mass"][i]) - centre[i]).max() <= RTOL * arm
    assert sh["largest_force"] == pytest.approx(np.hypot(force[:, 0], force[:, 1]).max(), rel=RTOL)


def test_the_centre_of_mass_accelerates_as_minus_force_over_mass():
    """Over a fine cycle at constant ω (1° steps): the centre of mass's second derivative in time
    by a five-point stencil, ω²·d²r_G/dφ², against −F/Σm (the stencil's error is ~h⁴/90·r⁽⁶⁾)."""
    data = four_bar(360)
    rep = report(data)
    sh = rep["cycle"]["shaking"]
    r = np.array(sh["centre_of_mass"])
    f = np.array(sh["force"])
    assert np.allclose(np.diff(rep["cycle"]["positions"]) % 360.0, 1.0)
    h = math.radians(1.0)
    d2 = (-np.roll(r, -2, 0) + 16 * np.roll(r, -1, 0) - 30 * r + 16 * np.roll(r, 1, 0) - np.roll(r, 2, 0)) / (12 * h * h)
    a_g = 10.0 ** 2 * d2
    want = -f / sh["mass"]
    assert np.abs(a_g - want).max() <= 1e-6 * np.abs(want).max()


# --- a four-bar fully force-balanced ------------------------------------------------------------

def test_four_bar_with_two_counterweights_keeps_its_centre_of_mass_still():
    data = four_bar(36, epsilon=3.0, counterweights={"1": {"radius": 0.1}, "3": {"radius": 0.08}})
    rep = report(data)
    before, after = rep["cycle"]["shaking_without"], rep["cycle"]["shaking"]
    cws = [counterweight_points(rep, k) for k in ("1", "3")]
    force, moment, centre, scale, total = sums(data, rep, cws)
    size = math.dist(*(np.array(data["points"][p]) for p in ("O", "C")))
    # the report with the counterweights is the test's own sum with them as point masses
    assert after["mass"] == pytest.approx(total, rel=1e-15)
    assert np.abs(np.array(after["force"]) - force).max() <= RTOL * scale.max()
    assert np.abs(np.array(after["moment"]) - moment).max() <= RTOL * scale.max() * size
    # the centre of mass does not move (from the JSON's r and the counterweights as reported) ...
    assert np.abs(centre - centre[0]).max() <= RTOL * size
    assert np.abs(np.array(after["centre_of_mass"]) - after["centre_of_mass"][0]).max() <= RTOL * size
    # ... and the shaking force is gone; the moment stays
    assert np.abs(force).max() <= RTOL * before["largest_force"]
    assert after["largest_force"] <= RTOL * before["largest_force"]
    assert after["largest_moment"] > 0.1 * before["largest_moment"]
    # without them it moves: the test is not trivially satisfied
    c0 = np.array(before["centre_of_mass"])
    assert np.abs(c0 - c0[0]).max() > 1e-3 * size


def test_four_bar_counterweights_satisfy_lowen_berkof():
    """m_c·ρ·e^{iα} on the crank = −(m1·z1(S1) + m2·(1 − λ)·z1(A)), on the rocker −(m3·z3(S3) +
    m2·λ·z3(B)), z_k in the link's frame (first point, x toward the second), λ = (S2 − A)/(B − A)."""
    data = four_bar(12, counterweights={"1": {"radius": 0.1}, "3": {"radius": 0.08}})
    rep = report(data)
    p = {k: complex(*v) for k, v in data["points"].items()}
    lam = (p["S2"] - p["A"]) / (p["B"] - p["A"])
    m = {k: v["mass"] for k, v in data["masses"].items()}
    for link, pivot, second, centre, share in (("1", "O", "A", "S1", m["2"] * (1 - lam)),
                                               ("3", "C", "B", "S3", m["2"] * lam)):
        e = (p[second] - p[pivot]) / abs(p[second] - p[pivot])
        want = -(m[link] * (p[centre] - p[pivot]) / e + share * (p[second] - p[pivot]) / e)
        cw = rep["counterweights"][link]
        got = cmath.rect(cw["mass"] * cw["radius"], math.radians(cw["angle"]))
        assert abs(got - want) <= 1e-12 * abs(want)
        assert cw["pivot"] == pivot and 0.0 <= cw["angle"] < 360.0 and cw["mr"] == pytest.approx(abs(want), rel=1e-12)


# --- a crank-slider: primary and secondary forces -----------------------------------------------

def test_crank_slider_primary_and_secondary_forces_in_closed_form():
    c, omega, n = 0.6, 10.0, L_ROD / R_CRANK
    rep = report(crank_slider(fraction=c))
    rec = rep["cycle"]["reciprocating"]
    m_rec = M3 + M2 * T_ROD                               # the slider and the rod's part at B
    at_pin = M2 * (1.0 - T_ROD)
    assert rec["mass"] == pytest.approx(m_rec, rel=1e-12) and rec["rod_at_pin"] == pytest.approx(at_pin, rel=1e-12)
    assert rec["fraction"] == c and rec["n"] == pytest.approx(n, rel=1e-12) and rec["stroke"] == [1.0, 0.0]
    assert abs(rec["offset"]) <= 1e-15
    # the counterweight: the crank's own m1·0.04 m, the rod's part at A and c of the reciprocating ones, opposite A
    cw = rep["counterweights"]["1"]
    assert cw["mass"] * cw["radius"] == pytest.approx(M1 * 0.4 * R_CRANK + (at_pin + c * m_rec) * R_CRANK, rel=1e-12)
    assert cw["angle"] == pytest.approx(180.0, abs=1e-9)
    theta = np.radians(rep["cycle"]["positions"])           # the crank's angle from the line of stroke (+x)
    base = m_rec * R_CRANK * omega ** 2
    scale = base
    assert np.allclose(np.radians(rec["theta"]) % (2 * np.pi), theta % (2 * np.pi), rtol=0, atol=1e-12)
    assert np.abs(np.array(rec["primary"]) - base * np.cos(theta)).max() <= RTOL * scale
    assert np.abs(np.array(rec["secondary"]) - base * np.cos(2 * theta) / n).max() <= RTOL * scale
    assert np.abs(np.array(rec["primary_after"]) - (1 - c) * base * np.cos(theta)).max() <= RTOL * scale
    assert np.abs(np.array(rec["transverse_after"]) + c * base * np.sin(theta)).max() <= RTOL * scale
    # the exact reciprocating force, −m_rec·a_B along the stroke from the JSON's a_B
    a_b = np.array([p["points"]["B"]["a"][0] for p in rep["positions"]])
    assert np.abs(np.array(rec["exact"]) + m_rec * a_b).max() <= RTOL * scale
    # F_p + F_s is the series to O(1/n³): the next term is −(1/(4n³))·cos 4θ·m_rec·r·ω² and smaller ones
    gap = np.abs(np.array(rec["exact"]) - np.array(rec["primary"]) - np.array(rec["secondary"])).max()
    assert 0.1 * base / (4 * n ** 3) < gap <= base / n ** 3
    # with the counterweight: across the stroke exactly −c·m_rec·r·ω²·sin θ (the rotating masses balanced);
    # along it (1 − c)·F_p + F_s to the same O(1/n³)
    assert np.abs(np.array(rec["across"]["with"]) - np.array(rec["transverse_after"])).max() <= RTOL * scale
    assert np.abs(np.array(rec["across"]["without"])).max() > 0.1 * scale
    along = np.array(rec["along"]["with"]) - np.array(rec["primary_after"]) - np.array(rec["secondary"])
    assert np.abs(along).max() <= base / n ** 3
    f = np.array(rep["cycle"]["shaking"]["force"])
    assert np.abs(f[:, 0] - rec["along"]["with"]).max() <= RTOL * scale


def test_crank_slider_takes_half_the_reciprocating_masses_by_default():
    rep = report(crank_slider(12, fraction=None))
    assert rep["cycle"]["reciprocating"]["fraction"] == 0.5


# --- only what is asked; the pure function ------------------------------------------------------

def test_nothing_is_computed_without_shaking():
    data = four_bar(12, draw=("positions",))
    with record_stages() as stages:
        rep = report(data)
    assert "shaking" not in stages and "shaking" not in rep["cycle"] and "accelerations" not in stages
    with record_stages() as stages:
        report(four_bar(12))
    assert stages[-1] == "shaking" and "accelerations" in stages


def test_the_analysis_holds_what_a_sheet_draws():
    scene = parse_scene(four_bar(12, counterweights={"1": {"radius": 0.1}, "3": {"radius": 0.08}}))
    motion, _ = solve_motion(scene)
    a = shaking_analysis(motion, scene)
    rep = report(four_bar(12, counterweights={"1": {"radius": 0.1}, "3": {"radius": 0.08}}))
    assert np.array_equal(a.angles, np.array(rep["cycle"]["positions"]))
    assert np.array_equal(a.balanced.force, np.array(rep["cycle"]["shaking"]["force"]))
    assert np.array_equal(a.without.moment, np.array(rep["cycle"]["shaking_without"]["moment"]))
    assert np.array_equal(a.without.centre, np.array(rep["cycle"]["shaking_without"]["centre_of_mass"]))
    assert a.shaking is a.balanced and a.reciprocating is None and a.about == "O"
    assert [c.link for c in a.counterweights] == ["1", "3"]


# --- refusals -------------------------------------------------------------------------------------

def _press() -> dict:
    data = tomllib.loads(next(p for p in EXAMPLES if p.stem == "six_link_press").read_text(encoding="utf-8"))
    data["masses"] = {"5": {"mass": 10.0, "centre": "E"}}
    data["counterweights"] = {"1": {"radius": 0.1}}
    data["plans"] = {"draw": ["shaking"], "at": []}
    return data


def _yoke() -> dict:
    data = tomllib.loads(next(p for p in EXAMPLES if p.stem == "scotch_yoke").read_text(encoding="utf-8"))
    data["drive"]["positions"] = 12
    data["masses"] = {"3": {"mass": 4.0, "centre": "Y"}}
    data["counterweights"] = {"1": {"radius": 0.1}}
    data["plans"] = {"draw": ["shaking"], "at": []}
    return data


def _no_cycle(d):
    d["drive"].pop("positions")
    d["plans"] = {"draw": ["shaking"]}


CW2 = {"1": {"radius": 0.1}, "3": {"radius": 0.08}}
REFUSED = [
    (lambda: four_bar(12, masses=False), "plans.draw", "masses"),
    (lambda: _edit(four_bar(12), _no_cycle), "plans.draw", "positions"),
    (lambda: four_bar(12, draw=("positions",), counterweights=CW2), "counterweights", '"shaking"'),
    (lambda: four_bar(12, counterweights={}), "counterweights", "at least one link"),
    (lambda: four_bar(12, counterweights={"1": {"radius": 0.1}}), "counterweights", "Lowen–Berkof"),
    (lambda: four_bar(12, counterweights={**CW2, "2": {"radius": 0.1}}), "counterweights.2", "not pivoted"),
    (lambda: four_bar(12, counterweights={"0": {"radius": 0.1}}), "counterweights.0", "frame does not move"),
    (lambda: four_bar(12, counterweights={"7": {"radius": 0.1}}), "counterweights.7", "unknown link"),
    (lambda: four_bar(12, counterweights={"1": {"radius": 0.0}, "3": {"radius": 0.08}}), "counterweights.1.radius",
     "positive"),
    (lambda: four_bar(12, counterweights={"1": {"radius": 0.1, "mass": 2.0}, "3": {"radius": 0.08}}),
     "counterweights.1.mass", "unknown key"),
    (lambda: four_bar(12, counterweights={"1": {}, "3": {"radius": 0.08}}), "counterweights.1.radius", "radius"),
    (lambda: four_bar(12, counterweights={"1": {"radius": 0.1, "reciprocating": 0.5}, "3": {"radius": 0.08}}),
     "counterweights.1.reciprocating", "four-bar has none"),
    (lambda: _edit(four_bar(12, counterweights=CW2), lambda d: d["links"].update({"3": ["B", "C", "S3"]})),
     "counterweights.3", "list its pivot C first"),
    (lambda: crank_slider(12, fraction=1.5), "counterweights.1.reciprocating", "0 to 1"),
    (lambda: crank_slider(12, fraction=-0.1), "counterweights.1.reciprocating", "0 to 1"),
    (lambda: _edit(crank_slider(12), lambda d: d["counterweights"].update({"2": {"radius": 0.1}})),
     "counterweights.2", "not pivoted"),
    (_press, "counterweights", "5 moving links"),
    (_yoke, "counterweights", "2 revolute and 2 prismatic pairs"),
]


def _edit(data: dict, change) -> dict:
    change(data)
    return data


@pytest.mark.parametrize("make, key, words", REFUSED, ids=[f"{r[1]}:{r[2]}" for r in REFUSED])
def test_refused_in_one_line_naming_the_key(make, key, words):
    with pytest.raises(SceneError) as info:
        render(parse_scene(make()), stem="s")
    text = str(info.value)
    assert info.value.key == key and f"[{key}]" in text and words in text, text
    assert "\n" not in text


def test_the_command_line_refuses_in_one_line(tmp_path):
    line = refused_line(tmp_path, toml_text(four_bar(12, counterweights={"1": {"radius": 0.1}})))
    assert "bad.toml: [counterweights]" in line and "3" in line


def test_the_shaking_sheet_draws_the_reports_forces(tmp_path):
    """The -shaking sheet: each hodograph vector (measured by plans check, length × μF) is the JSON's
    shaking force at its position; with counterweights the hodograph shrinks to the pole and the
    centre of mass is marked still; the sheet passes plans check and the layout measurer."""
    import xml.etree.ElementTree as ET

    from plans.checking import inspect_svg
    from plans.layout import measure_layout

    for data, balanced in ((four_bar(24), False),
                           (four_bar(24, counterweights={"1": {"radius": 0.06}, "3": {"radius": 0.05}}), True)):
        sheets = render(parse_scene(data), stem="s")
        rep = json.loads(sheets.files["s.json"])["cycle"]["shaking"]
        svg = sheets.files["s-shaking.svg"]
        path = tmp_path / "s.svg"
        path.write_text(svg, encoding="utf-8")
        r = inspect_svg(path)
        assert r.ok and not r.problems and measure_layout(svg).clean
        root = ET.fromstring(svg)
        ns = "{http://www.w3.org/2000/svg}"
        tagged = {l.get("data-quantity"): float(l.get("data-value")) for l in root.iter(f"{ns}line")
                  if (l.get("data-quantity") or "").startswith("Fsh@")}
        sizes = [math.hypot(*f) for f in rep["force"]]
        if balanced:
            assert not tagged and "S (still)" in "".join(root.itertext())
        else:
            assert len(tagged) == len(sizes)
            for k, size in enumerate(sizes):
                assert tagged[f"Fsh@{k}"] == pytest.approx(size, rel=1e-12)
            # a doctored vector (its value 2 % off what is drawn) fails plans check, naming it
            line = next(e for e in root.iter(f"{ns}line") if e.get("data-quantity") == "Fsh@3")
            line.set("data-value", repr(float(line.get("data-value")) * 1.02))
            path.write_text(ET.tostring(root, encoding="unicode"), encoding="utf-8")
            bad = inspect_svg(path)
            assert not bad.ok and [m.quantity for m in bad.measurements if not m.ok] == ["Fsh@3"]

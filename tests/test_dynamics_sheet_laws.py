"""The dynamics sheet under a driving law in the crank angle and over a cycle of several turns
(issue 35, item 3): the four-stroke engine of the examples over 720° (a driving law of four
triangles), a rotor under a harmonic driving law over one turn, and a load on the second of two
turns under a constant driving moment. Each sheet passes ``plans check`` and the layout measurer;
its tagged ordinates are the report's ``cycle.dynamics`` arrays; M_d's ordinates are the law
evaluated here (by np.interp of the example's own table, or the harmonic's closed form); the
chords are the middle-ordinate sums of the law and loads evaluated here; and J read off the
drawn Wittenbauer segment kl is within the error the sheet states."""

from __future__ import annotations

import math
import tomllib
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from conftest import EXAMPLES as _ALL
from conftest import refused_line
from test_dynamics_laws import ROTOR, TWO_TURNS

from plans import render
from plans.checking import WRITER_PRECISION, inspect_svg
from plans.layout import measure_layout

SVG = "{http://www.w3.org/2000/svg}"
ENGINE = _ALL[0].parent / "flywheel" / "engine_crank_slider.toml"
SHEET = 'draw = ["dynamics"]'
CASES = {"engine": None, "rotor": ROTOR.replace('draw = ["scheme"]', SHEET),
         "two_turns": TWO_TURNS.replace('draw = ["scheme"]', SHEET),
         "three_turns": TWO_TURNS.replace('draw = ["scheme"]', SHEET).replace("period = 720", "period = 1080")}
_DONE: dict[str, tuple] = {}


def _sheet(name: str, tmp_path_factory) -> tuple[dict, str, object]:
    """(cycle.dynamics, the sheet's SVG text, inspect_svg's report) of a case, rendered once."""
    if name not in _DONE:
        folder = tmp_path_factory.mktemp(name)
        path = ENGINE if CASES[name] is None else folder / f"{name}.toml"
        if CASES[name] is not None:
            path.write_text(CASES[name], encoding="utf-8")
        out = render(path)
        svg = out.files[f"{path.stem}-dynamics.svg"]
        (folder / "sheet.svg").write_text(svg, encoding="utf-8")
        _DONE[name] = (out.report["cycle"]["dynamics"], svg, inspect_svg(folder / "sheet.svg"))
    return _DONE[name]


def _dots(root: ET.Element, group: str) -> list[ET.Element]:
    g = next(e for e in root.iter(f"{SVG}g") if e.get("id") == group)
    return list(g.iter(f"{SVG}circle"))


@pytest.mark.parametrize("name", sorted(CASES))
def test_the_sheet_passes_plans_check_and_the_layout_measurer(name, tmp_path_factory):
    _, svg, report = _sheet(name, tmp_path_factory)
    assert report.ok and not report.problems, report.problems[:3]
    layout = measure_layout(svg)
    assert layout.clean, (layout.overlaps, layout.crossings, layout.off_sheet, layout.outside)
    assert layout.format == "A3"


@pytest.mark.parametrize("name", sorted(CASES))
def test_the_tagged_ordinates_are_the_reports_arrays(name, tmp_path_factory):
    """M_r, M_d (with a law), the works, ΔT at every position of the period, and I_r over one
    turn (it repeats every turn: checked here on the report too), each measured within drawing
    precision and equal to cycle.dynamics."""
    dyn, _, report = _sheet(name, tmp_path_factory)
    by = {m.quantity: m for m in report.measurements}
    assert all(m.ok for m in report.measurements)
    n = len(dyn["theta"])
    turns = round(dyn["period"] / 360.0)
    per_turn = n // turns
    law = dyn["driving"] == "law"
    works = dyn["sheet"]["works"]
    first = dyn["work_resisting"] if works[0] == "A_r" else dyn["work_driving"]
    for k in range(n):
        assert by[f"M@{k}"].value == pytest.approx(abs(dyn["reduced_moment"][k]), rel=1e-12, abs=1e-9)
        assert by[f"T@{k}"].value == pytest.approx(abs(dyn["kinetic_energy_change"][k]), rel=1e-9, abs=1e-9)
        assert by[f"A@{k}"].value == pytest.approx(abs(first[k]), rel=1e-9, abs=1e-9)
        if law:
            assert by[f"Md@{k}"].value == pytest.approx(abs(dyn["driving_moment"][k]), rel=1e-12, abs=1e-9)
            assert by[f"Ar@{k}"].value == pytest.approx(abs(dyn["work_resisting"][k]), rel=1e-9, abs=1e-9)
        # I_r repeats every turn: the turned diagram's row k mod N holds it
        assert dyn["reduced_inertia"][k] == pytest.approx(dyn["reduced_inertia"][k % per_turn], rel=1e-12, abs=1e-15)
    i0 = dyn["sheet"]["wittenbauer"]["i0"]
    name_i = "I" if i0 == 0.0 else "I-I0"
    for k in range(per_turn + 1):
        want = dyn["reduced_inertia"][k % per_turn] + dyn["rotor_inertia"] - i0
        assert by[f"{name_i}@{k}"].value == pytest.approx(abs(want), rel=1e-9, abs=1e-12)
    assert f"{name_i}@{per_turn + 1}" not in by          # one turn only …
    assert f"M@{n}" in by and f"T@{n}" in by and f"M@{n + 1}" not in by      # … the rest over the period
    assert ("Md@0" in by) == law


@pytest.mark.parametrize("name", sorted(CASES))
def test_the_phi_axis_spans_the_period(name, tmp_path_factory):
    """The positions' dots stand at the JSON's crank angles θ (rad = θ° · π/180), the last at the
    period (720° over two turns), and the axis in degrees ends there."""
    dyn, svg, _ = _sheet(name, tmp_path_factory)
    root = ET.fromstring(svg)
    period = math.radians(dyn["period"])
    for graph in ("M", "A", "T"):
        dots = _dots(root, f"dynamics-{graph}-dots")
        phi = [float(c.get("data-phi")) for c in dots]
        assert phi[:-1] == pytest.approx(np.radians(dyn["theta"]), rel=1e-12, abs=1e-12)
        assert phi[-1] == pytest.approx(period, rel=1e-12)
    text = "".join(root.itertext())
    last = _dots(root, "dynamics-T-dots")[-1]
    if dyn["period"] > 360.0 or dyn["driving"] == "law":
        ticks = [e for e in root.iter(f"{SVG}line") if (e.get("id") or "").startswith("dynamics-degrees-t")]
        assert float(ticks[-1].get("x1")) == pytest.approx(float(last.get("cx")), abs=2 * WRITER_PRECISION)
        assert f"{dyn['period']:g}°" in text
    if dyn["period"] > 360.0:
        assert f"{len(dyn['theta'])} positions over {dyn['period']:g}°" in text
        per_turn = len(dyn["theta"]) * 360 // round(dyn["period"])
        assert f"{per_turn}, {2 * per_turn}" in text      # the turned I_r's last row holds both


def _law(theta_deg: np.ndarray) -> np.ndarray:
    """The engine's driving law from its own table, linear between the rows (np.interp)."""
    rows = tomllib.loads(ENGINE.read_text(encoding="utf-8"))["dynamics"]["driving"]
    return np.interp(theta_deg, [r[0] for r in rows], [r[1] for r in rows])


def _harmonic(theta_deg: np.ndarray) -> np.ndarray:
    """ROTOR's driving law: T = 500 + 150·sin(3θ + 20°)."""
    return 500.0 + 150.0 * np.sin(np.radians(3.0 * theta_deg + 20.0))


def test_the_md_curve_is_the_law_at_the_positions(tmp_path_factory):
    """The engine's M_d ordinates (signed, on the dots; measured, on the tagged lines) are its
    table interpolated here at the positions 0, 30, …, 720°; the rotor's, the harmonic's closed form."""
    for name, law in (("engine", _law), ("rotor", _harmonic)):
        dyn, svg, report = _sheet(name, tmp_path_factory)
        theta = np.append(dyn["theta"], dyn["period"])
        want = law(theta)
        dots = [float(c.get("data-value")) for c in _dots(ET.fromstring(svg), "dynamics-M-Md-dots")]
        assert dots == pytest.approx(want, rel=1e-12, abs=1e-9 * np.max(np.abs(want)))
        by = {m.quantity: m for m in report.measurements}
        for k, v in enumerate(want):
            m = by[f"Md@{k}"]
            assert m.length_mm * m.mu == pytest.approx(abs(v), abs=m.tolerance)


def test_the_chords_are_the_middle_ordinate_sums(tmp_path_factory):
    """A_d's chords rise by M_d at each interval's middle × Δφ and A_r's by −M_r there (the
    law evaluated here); the engine's law is linear between positions (its rows at multiples of
    30°), so its chords are the exact work at the positions, and the rotor's exact A_d is
    500θ + 50(cos 20° − cos(3θ + 20°))."""
    for name, law in (("engine", _law), ("rotor", _harmonic)):
        dyn, svg, _ = _sheet(name, tmp_path_factory)
        root = ET.fromstring(svg)
        n = len(dyn["theta"])
        step = math.radians(dyn["period"] / n)
        middles = (np.arange(n) + 0.5) * dyn["period"] / n
        chords_d = np.concatenate([[0.0], np.cumsum(law(middles) * step)])
        chords_r = np.concatenate([[0.0], np.cumsum(-np.array(dyn["reduced_moment"]) * step)])
        drawn_d = np.array([float(c.get("data-value")) for c in _dots(root, "dynamics-A-gdots")])
        drawn_r = np.array([float(c.get("data-value")) for c in _dots(root, "dynamics-A-Ar-gdots")])
        assert drawn_d == pytest.approx(chords_d, rel=1e-9, abs=1e-9 * chords_d[-1])
        assert drawn_r == pytest.approx(chords_r, rel=1e-9, abs=1e-9 * chords_r[-1])
        exact = np.append(dyn["work_driving"], chords_r[-1])       # balanced: A_d = A_r over the cycle
        if name == "engine":
            assert drawn_d == pytest.approx(exact, rel=1e-9, abs=1e-9 * exact[-1])
        else:
            th = np.radians(np.append(dyn["theta"], 360.0))
            closed = 500.0 * th + 50.0 * (math.cos(math.radians(20.0)) - np.cos(3.0 * th + math.radians(20.0)))
            assert exact == pytest.approx(closed, rel=1e-9, abs=1e-9 * closed[-1])
            assert np.max(np.abs(drawn_d - closed)) / np.max(closed) == pytest.approx(
                dyn["sheet"]["graphical_error"]["A"], rel=1e-6)


@pytest.mark.parametrize("name", sorted(CASES))
def test_wittenbauer_read_off_the_sheet_gives_j_within_its_stated_error(name, tmp_path_factory):
    """kl measured on the sheet × its μT (the sheet's own attributes) gives J = kl·μT/(ω_m²δ) − I0
    equal to Wittenbauer's J within the drawn ends' rounding, and to the exact J within the
    reading error the sheet states (kl to ±0.5 mm) and the method's own difference; ΔT(φ) and
    Wittenbauer's diagram share μT and their ΔT = 0 level, the turned I_r(φ) its μI."""
    dyn, svg, _ = _sheet(name, tmp_path_factory)
    root = ET.fromstring(svg)
    fly, sheet = dyn["flywheel"], dyn["sheet"]
    seg = next(e for e in root.iter(f"{SVG}line") if e.get("data-quantity") == "kl")
    kl = math.dist((float(seg.get("x1")), float(seg.get("y1"))), (float(seg.get("x2")), float(seg.get("y2"))))
    groups = {g.get("id"): g for g in root.iter(f"{SVG}g")}
    mu_t = float(groups["dynamics-wittenbauer-kl"].get("data-mu"))
    w = groups["dynamics-wittenbauer"]
    i0 = float(w.get("data-i0"))
    energy = dyn["omega_mean"] ** 2 * fly["delta"]
    j = kl * mu_t / energy - i0
    drawn = 2 * math.sqrt(2) * WRITER_PRECISION * mu_t / energy
    assert abs(j - fly["inertia_wittenbauer"]) <= drawn * 1.001
    stated = sheet["wittenbauer"]["reading_error"]
    assert stated == pytest.approx(mu_t * 0.5 / energy, rel=1e-12)
    assert abs(j - fly["inertia_exact"]) <= stated + abs(fly["inertia_wittenbauer"] - fly["inertia_exact"]) + drawn
    assert f"within ±{stated:.2g} kg·m²" in "".join(root.itertext())
    for which, sign in (("max", 1), ("min", -1)):
        tan = sheet["wittenbauer"]["mu_i"] / mu_t * dyn["omega_mean"] ** 2 * (1 + sign * fly["delta"]) / 2
        assert sheet["wittenbauer"]["psi"][which] == pytest.approx(math.degrees(math.atan(tan)), rel=1e-12)
    t, turned = groups["dynamics-T"], groups["dynamics-I"]
    assert float(t.get("data-scale")) == float(w.get("data-mu-t")) == mu_t
    assert float(turned.get("data-scale")) == float(w.get("data-mu-i")) and turned.get("data-turned") == "90"
    assert float(t.get("data-origin").split(",")[1]) == pytest.approx(float(w.get("data-origin").split(",")[1]),
                                                                    abs=WRITER_PRECISION)


def test_the_engines_flywheel_on_the_sheet(tmp_path_factory):
    """The engine of the examples: J = 17.4775 kg·m² for δ = 0.01 (tests/test_dynamics_laws.py); at
    μT = 80 J/mm kl is 225·(17.4775 + 0.025)/80 = 49.2 mm, read to ±0.5 mm it gives J within
    ±80·0.5/225 = ±0.178 kg·m² (1 %); the sheet draws the period's 24 positions (12 a turn)."""
    dyn, svg, _ = _sheet("engine", tmp_path_factory)
    w = dyn["sheet"]["wittenbauer"]
    assert dyn["flywheel"]["inertia_exact"] == pytest.approx(17.4775, abs=5e-5)
    assert (w["mu_t"], w["i0"]) == (80.0, 0.025)
    assert abs(w["segment"]) / w["mu_t"] == pytest.approx(150.0 ** 2 * 0.01 * (17.4775 + 0.025) / 80.0, abs=1e-3)
    assert w["reading_error"] == pytest.approx(80.0 * 0.5 / (150.0 ** 2 * 0.01), rel=1e-12)
    assert len(dyn["theta"]) == 24 and dyn["period"] == 720.0 and dyn["sheet"]["turned_inertia"] == "one turn"
    turned = next(g for g in ET.fromstring(svg).iter(f"{SVG}g") if g.get("id") == "dynamics-I-ordinates")
    assert turned.get("data-vectors") == "13"


def test_more_positions_than_the_sheet_numbers_are_refused_in_one_line(tmp_path):
    """Over a cycle of several turns the sheet takes at most 36 positions (3 turns × 12 above is
    drawn clean); the engine's 24 a turn over 720° are 48, refused at [drive.positions]."""
    text = ENGINE.read_text(encoding="utf-8")
    assert "positions = 12" in text
    line = refused_line(tmp_path, text.replace("positions = 12", "positions = 24"))
    assert "[drive.positions]" in line and "24 × 2 positions" in line and "positions = 18 or fewer" in line

"""[gear_pair] (issue 19): the scene and its report, the checks, and the wheel cut by the rack
cutter — its flank against the exact involute (the distance along the involute's normal, exact),
and undercut appearing by itself where the rule says it must."""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest
import shapely

from conftest import EXAMPLES as _EXAMPLES, refused_line, sheet_words
from plans import render
from plans.checking import inspect_svg
from plans.layout import measure_layout
from plans.constructions.gear_cutting import cut_wheel, flank_angle, involute_distance
from plans.gears.involute import gear_pair, min_shift
from plans.scene import parse_scene

ALPHA = math.radians(20.0)
#: The standard cutter's tip rounding, the largest that fits its corner: c*/(1 − sin α) = 0.37995 modules.
RHO = 0.25 / (1.0 - math.sin(ALPHA))


def _pair_report(table: dict, draw: list[str] | None = None) -> tuple[dict, tuple[str, ...]]:
    data = {"gear_pair": table}
    if draw is not None:
        data["plans"] = {"draw": draw}
    out = render(parse_scene(data), stem="pair")
    return json.loads(out.files["pair.json"])["gear_pair"], out.warnings


def test_report_holds_the_geometry():
    rep, warnings = _pair_report({"z1": 12, "z2": 24, "module": 3.0, "x1": 0.6, "x2": 0.36})
    g = gear_pair(12, 24, 3.0, x1=0.6, x2=0.36)
    assert rep["x1"] == 0.6 and rep["x2"] == 0.36
    assert rep["working_pressure_angle"] == pytest.approx(math.degrees(g.alpha_w), rel=1e-15)
    assert rep["centre_distance"] == pytest.approx(56.4999, abs=5e-5)       # quoted to 4 decimals: their rounding
    assert rep["contact_ratio"] == pytest.approx(g.contact_ratio, rel=1e-15)
    for key in ("d", "db", "da", "df"):
        assert len(rep[key]) == 2
    assert rep["da"] == pytest.approx([44.840, 79.400], abs=5e-4)           # quoted to 3 decimals: their rounding


def test_shift_rules():
    none, _ = _pair_report({"z1": 20, "z2": 40, "module": 2.0, "shift": "none"})
    assert none["x1"] == none["x2"] == 0.0
    nu, _ = _pair_report({"z1": 12, "z2": 30, "module": 2.0, "shift": "no_undercut"})
    assert nu["x1"] == pytest.approx(min_shift(12), rel=1e-15) and nu["x2"] == 0.0
    assert nu["undercut"] == [False, False]
    bal, _ = _pair_report({"z1": 14, "z2": 40, "module": 5.0, "shift": "balanced"})
    assert bal["x1"] == pytest.approx(-bal["x2"], abs=1e-15) and bal["x1"] >= min_shift(14) - 1e-12
    s = bal["specific_sliding"]
    assert s["wheel1_at_B2"] == pytest.approx(s["wheel2_at_B1"], rel=1e-9)
    assert bal["centre_distance"] == pytest.approx(5.0 * 54 / 2, rel=1e-12)


def test_warnings_for_undercut_and_low_contact_ratio():
    _, warnings = _pair_report({"z1": 12, "z2": 30, "module": 4.0}, draw=["cutting"])
    text = " ".join(warnings)
    assert "undercut" in text and "interference" in text


@pytest.mark.parametrize("table, words", [
    ({"z1": 12, "z2": 30, "module": 4.0}, "interference"),
    ({"z1": 20, "z2": 40, "module": 2.0, "x1": 1.8, "x2": 0.0}, "pointed"),
    ({"z1": 20, "z2": 40, "module": 2.0, "x1": 1.5, "x2": 1.5}, "contact ratio"),
    ({"z1": 20, "z2": 40, "module": -2.0}, "module"),
    ({"z1": 20.5, "z2": 40, "module": 2.0}, "whole number"),
    ({"z1": 20, "z2": 40}, "module is missing"),
    ({"z1": 20, "z2": 40, "module": 2.0, "shift": "best"}, "shift"),
    ({"z1": 20, "z2": 40, "module": 2.0, "shift": "none", "x1": 0.1}, "not both"),
    ({"z1": 20, "z2": 40, "module": 2.0, "tip_radius": 0.6}, "tip_radius"),
    ({"z1": 20, "z2": 40, "module": 2.0, "pressure_angle": 50.0}, "pressure_angle"),
    ({"z1": 20, "z2": 40, "module": 2.0, "mesh": ["a", "b"]}, "mesh takes"),
])
def test_bad_pair_is_one_line(tmp_path, table, words):
    lines = ["[gear_pair]"] + [f"{k} = {json.dumps(v)}" for k, v in table.items()]
    assert words in refused_line(tmp_path, "\n".join(lines) + "\n")


# --- the wheel cut by the rack ---------------------------------------------------------------------------------

def _flank_hausdorff(z: int, m: float, x: float, tolerance: float) -> float:
    """The Hausdorff distance (mm) between the cut flank right of space 0 and the exact involute,
    over the involute part: from the form radius (where the cutter's straight flank ends, or the
    base circle) plus 2 % of the working depth up to the tip less 1 %."""
    g = gear_pair(z, 200, m, x1=x)
    poly = cut_wheel(z, m, ALPHA, x, 1.0, 0.25, RHO * m, g.da[0], tolerance=tolerance, spaces=1)
    rb, r, ra = g.db[0] / 2, g.d[0] / 2, g.da[0] / 2
    h_end = 1.0 * m - x * m                  # the straight flank ends ha*·m below the cutter's reference line
    along = r * math.sin(ALPHA) - h_end / math.sin(ALPHA)
    r_form = math.hypot(rb, along) if along > 0 else rb
    lo, hi = r_form + 0.02 * (ra - r_form), ra - 0.01 * (ra - r_form)
    c = np.array(poly.exterior.coords)
    radius = np.hypot(c[:, 0], c[:, 1])
    beta = np.arctan2(c[:, 0], c[:, 1])
    mine = (radius > lo) & (radius < hi) & (beta > 0) & (beta < math.pi / z)
    assert mine.sum() > 10
    out = float(np.max(involute_distance(c[mine], m, z, ALPHA, x)))
    rs = np.linspace(lo, hi, 400)
    b = flank_angle(rs, m, z, ALPHA, x)
    exact = shapely.points(np.column_stack([rs * np.sin(b), rs * np.cos(b)]))
    back = float(np.max(shapely.distance(exact, poly.exterior)))
    return max(out, back)


@pytest.mark.parametrize("m", [1.0, 4.0, 20.0])
@pytest.mark.parametrize("z, x", [(12, min_shift(12)), (30, 0.0), (60, 0.5), (18, -0.05)])
def test_cut_flank_is_the_involute_within_a_micrometre(m, z, x):
    assert _flank_hausdorff(z, m, x, tolerance=1e-4) <= 1e-3


def _undercut_depth(z: int, x: float, m: float = 20.0) -> float:
    """How far (mm) the cut reaches into the tooth past the involute, above the base circle."""
    g = gear_pair(z, 200, m, x1=x)
    poly = cut_wheel(z, m, ALPHA, x, 1.0, 0.25, RHO * m, g.da[0], tolerance=1e-6, spaces=1)
    c = np.array(poly.exterior.coords)
    radius = np.hypot(c[:, 0], c[:, 1])
    beta = np.arctan2(c[:, 0], c[:, 1])
    rb, r = g.db[0] / 2, g.d[0] / 2
    near = (radius > rb) & (radius < g.da[0] / 2 - 0.01 * m) & (beta > 0) & (beta < math.pi / z)
    a_p = np.arccos(rb / radius[near])
    e = math.pi * m - g.s[0]
    inside = rb * (beta[near] - (np.tan(a_p) - a_p) - (e / (2 * r) - (math.tan(ALPHA) - ALPHA)))
    return float(np.max(inside))


@pytest.mark.parametrize("z", [8, 12, 16])
def test_undercut_appears_by_itself(z):
    """Module 20, the cut within 1 nm (``tolerance=1e-6`` mm): with x = 0 the cut reaches past the
    involute, with x = x_min it does not. The cut polygon is within the tolerance of the true cut,
    so a flank that is not undercut reaches at most 1 nm past the involute (−0.6 nm measured) and
    an undercut one is told apart at twice the tolerance, 2 nm (measured: 11 nm at
    z = 16, 42 µm at z = 12). The fewest teeth, the middle and the last below z_min = 17 (each cut
    costs seconds at 1 nm)."""
    tolerance = 1e-6
    assert _undercut_depth(z, 0.0) > 2 * tolerance, z
    assert _undercut_depth(z, min_shift(z)) < tolerance, z


@pytest.mark.parametrize("z", [18, 20])
def test_no_undercut_from_z_min_on(z):
    """Past z_min = 17 the unshifted cut stays on the involute (under 1 nm): the first tooth
    count above it and the 20 of the standard's example."""
    assert _undercut_depth(z, 0.0) < 1e-6, z


# --- the sheets ----------------------------------------------------------------------------------------------

PAIR_EXAMPLES = sorted(p for p in (_EXAMPLES[0].parent / "gears").glob("pair_*.toml"))


@pytest.fixture(scope="module")
def pair_sheets(tmp_path_factory):
    out = tmp_path_factory.mktemp("pairs")
    for path in PAIR_EXAMPLES:
        render(path).save(out)
    return out


def test_the_pair_examples_draw_their_sheets(pair_sheets):
    names = {p.name for p in pair_sheets.glob("*.svg")}
    assert len(PAIR_EXAMPLES) == 6
    assert "pair_12_unshifted-cutting.svg" in names and "pair_12_unshifted-meshing.svg" not in names
    for stem in ("pair_12_no_undercut", "pair_balanced", "pair_from_train", "pair_internal", "pair_rack"):
        assert {f"{stem}-meshing.svg", f"{stem}-cutting.svg"} <= names
    assert "pair_from_train-gears.svg" in names


def test_pair_sheets_pass_plans_check_and_read_the_contact_ratio(pair_sheets):
    """Every tagged segment of every meshing and cutting sheet measures within drawing precision,
    and the drawn B1B2 over the drawn p_b is the computed ε_α within what the rounding allows."""
    for svg in sorted(pair_sheets.glob("pair_*-*.svg")):
        r = inspect_svg(svg)
        assert r.ok and r.measurements, (svg.name, r.problems[:3])
        if svg.name.endswith("-meshing.svg"):
            rep = json.loads((pair_sheets / (svg.name.split("-")[0] + ".json")).read_text())["gear_pair"]
            by = {m.quantity: m for m in r.measurements}
            measured = by["B1B2"].length_mm / by["pb"].length_mm
            assert measured == pytest.approx(rep["contact_ratio"], abs=2e-4)
            assert any(c.what.startswith("ε_α") and c.ok for c in r.checks)
            radii = {"ra1", "rb1"} | ({"ra2", "rb2"} if rep["kind"] != "rack" else set())
            assert radii | {"aw", "s1", "s2", "sa1", "sa2"} <= set(by)
            assert by["aw"].value == pytest.approx(rep["centre_distance"], rel=1e-15)


def test_a_doctored_contact_ratio_fails(pair_sheets, tmp_path):
    text = (pair_sheets / "pair_balanced-meshing.svg").read_text(encoding="utf-8")
    stated = re.search(r'data-contact-ratio="([^"]+)"', text).group(1)
    doctored = tmp_path / "doctored.svg"
    doctored.write_text(text.replace(f'data-contact-ratio="{stated}"',
                                     f'data-contact-ratio="{float(stated) * 1.01!r}"'), encoding="utf-8")
    r = inspect_svg(doctored)
    assert not r.ok and any("ε_α" in p for p in r.problems)


def test_pair_sheets_layout_is_clean(pair_sheets):
    for svg in sorted(pair_sheets.glob("pair_*.svg")):
        report = measure_layout(svg.read_text(encoding="utf-8"))
        assert not any(report.counts.values()), (svg.name, report)


def test_pair_sheets_write_negative_numbers_with_the_minus_sign(pair_sheets):
    """A negative specific sliding or shift in the notes and title reads −5.955, not -5.955 (a
    hyphen right after a letter, digit, bracket or dot is not a sign: B_1B_2, 1e-05)."""
    import re

    hyphen = re.compile(r"(?<![\w).])-(?=\.?\d)")
    signed = 0
    for svg in sorted(pair_sheets.glob("pair_*.svg")):
        words = sheet_words(svg.read_text(encoding="utf-8"))
        assert not hyphen.findall(words), (svg.name, [w for w in words.splitlines() if hyphen.search(w)][:2])
        signed += len(re.findall(r"−\.?\d", words))
    assert signed >= 3            # the balanced pair's x2 and the specific slidings at B1, B2


def test_cutting_sheet_says_whether_undercut(pair_sheets):
    assert "it is undercut" in sheet_words((pair_sheets / "pair_12_unshifted-cutting.svg").read_text())
    assert "not undercut" in sheet_words((pair_sheets / "pair_12_no_undercut-cutting.svg").read_text())


def test_working_profiles_lie_on_the_cut_flanks_and_touch_on_the_line_of_action():
    """The thick working profiles of the meshing sheet — one pair, the one in contact at P — are on
    their wheel's cut outline (within the cut's tolerance on paper) and each touches the other
    wheel's profile."""
    from shapely.geometry import Polygon

    from plans.constructions.gear_pair import CUT_TOLERANCE, meshing
    from plans.gears.pair import analyse_pair
    from plans.scene import read_scene

    a = analyse_pair(read_scene(_EXAMPLES[0].parent / "gears" / "pair_balanced.toml").gear_pair)
    s = meshing(a)
    wheels = {n: Polygon(o) for n, o in s.outlines}
    profiles = [(n, pts) for n, kind, pts in s.curves if n.startswith("working-profile")]
    assert len(profiles) == 2
    p = a.pair
    # where a pair of involutes touch, their radii of curvature add up to N1N2 = a_w·sin α_w; on
    # the active line B1B2 the smallest are N1B2 and N2B1 (g_i = √(r_a² − r_b²) from N_i to B_j)
    n1n2 = p.a_w * math.sin(p.alpha_w)
    g = [math.sqrt((da / 2) ** 2 - (db / 2) ** 2) for da, db in zip(p.da, p.db)]
    curvature = 1.0 / (n1n2 - g[1]) + 1.0 / (n1n2 - g[0])          # 1/ρ1 + 1/ρ2 at most, 1/mm
    for name, pts in profiles:
        own, other = ("wheel1", "wheel2") if "profile1" in name else ("wheel2", "wheel1")
        d = shapely.distance(shapely.points(pts), wheels[own].exterior)
        # the scallops between the cutter's rolled positions are at most CUT_TOLERANCE deep
        # (step_for: ρ·Δφ²/8 with the largest ρ); as much again for the cutter fillet's polygon
        assert d.max() <= 2.0 * CUT_TOLERANCE * s.k
        # the touching point lies within half a sample step ds of a drawn point, where the gap
        # between the two profiles opens as (ds/2)²·(1/ρ1 + 1/ρ2)/2; plus the cut's tolerance
        ds = float(np.max(np.hypot(*np.diff(pts, axis=0).T))) / s.k
        bound = CUT_TOLERANCE + (ds / 2.0) ** 2 / 2.0 * curvature
        assert shapely.distance(shapely.points(pts), wheels[other].exterior).min() <= bound * s.k

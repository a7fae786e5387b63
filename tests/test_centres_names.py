"""Instantaneous centres at a stationary instant, and names that must not be taken for one
another: a centre P3 beside a point P3, a point A3 beside point A of link 3.

Each scene is written out here, rendered by ``plans render`` and measured by ``plans check``.
"""

from __future__ import annotations

import json
import math
import tomllib
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from conftest import EXAMPLES, sheet_words, toml_text
from plans.cli import main
from plans.constructions.plan_builder import joined_names
from plans.kinematics import analyse
from plans.model import build_mechanism
from plans.scene import parse_scene
from plans.structure import analyse_structure

SVG = "{http://www.w3.org/2000/svg}"


def example(stem: str) -> dict:
    return tomllib.loads(next(p for p in EXAMPLES if p.stem == stem).read_text(encoding="utf-8"))


def render_and_check(tmp_path, data: dict, name: str) -> tuple[dict, object]:
    """Render ``data`` (exit 0), check every SVG (exit 0); the JSON report and the folder."""
    scene = tmp_path / f"{name}.toml"
    scene.write_text(toml_text(data), encoding="utf-8")
    out = tmp_path / f"{name}-out"
    assert main(["render", str(scene), "-o", str(out), "-q"]) == 0
    svgs = sorted(str(p) for p in out.glob("*.svg"))
    assert svgs and main(["check", *svgs]) == 0
    return json.loads((out / f"{name}.json").read_text(encoding="utf-8")), out


def tagged(svg_path) -> dict[str, dict[str, str]]:
    """Every tagged line of a sheet: quantity → its attributes."""
    root = ET.parse(svg_path).getroot()
    return {el.get("data-quantity"): el.attrib for el in root.iter(f"{SVG}line") if el.get("data-quantity")}


def meet(p1, p2, q1, q2) -> np.ndarray:
    """Where line p1–p2 meets line q1–q2."""
    d1, d2 = np.subtract(p2, p1), np.subtract(q2, q1)
    t = np.linalg.solve(np.array([d1, -d2]).T, np.subtract(q1, p1))
    return np.asarray(p1) + t[0] * d1


# --- 1. a centre at rest -------------------------------------------------------------------------

def stationary_angle(data: dict, lo: float, hi: float) -> tuple[float, float]:
    """The crank angles (two adjacent doubles) between which the base link 5's solved ω changes
    sign: bisection on ω5(φ) from [lo, hi], each φ solved alone (walked from the sketch)."""
    mech = build_mechanism(parse_scene(data))
    structure = analyse_structure(mech)

    def omega(phi: float) -> float:
        return float(analyse(mech, structure, np.array([phi])).links["5"].omega[0])

    f_lo = omega(lo)
    assert f_lo * omega(hi) < 0
    while True:
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            return lo, hi
        if (omega(mid) < 0) == (f_lo < 0):
            lo = mid
        else:
            hi = mid


def test_a_triad_at_a_root_found_stationary_instant_is_at_rest(tmp_path):
    """examples/triad_at_rest.toml stands still at 0° (sketched there), and again where the rod
    folds back over the crank: that angle is found here by bisection on the solved ω5, so ω3,
    ω4, ω5 are rounding (~1e-16), not 0. At both bracketing doubles the triad's links are
    reported at rest — no centre, in the JSON and on the centres sheet — while 1e-6° away the
    centre of the base link is a point, where the rockers' lines N–D and K–C meet. (Once the
    centres of the links at rest were points made of rounding — the rockers' pivots, the base
    link's the limit of its centre by chance — and the instant rendered alone stopped with
    "the special-point solution and the Jacobian solution differ": the class III cross-check
    compared each link's rounding with itself.)"""
    data = example("triad_at_rest")
    lo, hi = stationary_angle(data, 185.0, 190.0)
    off = lo - 1e-6
    data["drive"]["angle"] = [lo, hi, off, 90.0]
    report, out = render_and_check(tmp_path, data, "rest")
    omega1 = data["drive"]["omega"]
    for k in (0, 1):
        pos = report["positions"][k]
        links, pts = pos["links"], pos["points"]
        # the stationary instant: crank and rod in line (v_A ⊥ AB, so B stands), the rod back across O
        oa, ab = np.subtract(pts["A"]["r"], pts["O"]["r"]), np.subtract(pts["B"]["r"], pts["A"]["r"])
        assert abs(float(oa[0] * ab[1] - oa[1] * ab[0])) < 1e-12 * np.linalg.norm(oa) * np.linalg.norm(ab)
        assert float(oa @ ab) < 0
        assert 0 < max(abs(links[n]["omega"]) for n in "345") < 1e-13 * omega1   # rounding, not zero
        assert [pos["centres"][n] for n in "345"] == ["at rest"] * 3
        assert [pos["relative_centres"][p] for p in ("3-4", "3-5", "4-5")] == ["at rest"] * 3
        # the rod turns about B, the crank about O; P13 (link 3 at rest) is the crank's own centre O
        assert pos["centres"]["2"] == pytest.approx(pts["B"]["r"], abs=1e-12)
        assert pos["centres"]["1"] == pytest.approx([0.0, 0.0], abs=1e-12)
        assert pos["relative_centres"]["1-3"] == pytest.approx([0.0, 0.0], abs=1e-12)
    # just off the instant the base link moves (ω5 ~ 1e-8 rad/s) and has its centre
    pos = report["positions"][2]
    r = {p: pos["points"][p]["r"] for p in "NDKC"}
    assert 1e-10 < abs(pos["links"]["5"]["omega"]) / omega1 < 1e-8
    assert pos["centres"]["5"] != "at rest"
    assert pos["centres"]["5"] == pytest.approx(meet(r["N"], r["D"], r["K"], r["C"]), rel=1e-6)
    # the sheets at the instant: the note, and no mark of P3, P4, P5; the other two sheets have none
    resting = []
    for sheet in sorted(out.glob("rest-centres-*.svg")):
        words = " ".join(sheet_words(sheet.read_text(encoding="utf-8")).split())
        if "at rest at this position" not in words:      # (the title says "a triad at rest")
            assert {"P3", "P4", "P5"} <= set(words.split())
            continue
        resting.append(sheet.name)
        assert "Links 3, 4 and 5 are at rest at this position" in words
        assert "1e-9 of the fastest point's speed, 0.5 m/s" in words
        assert not {"P3", "P4", "P5"} & set(words.split()) and {"P1", "P2"} <= set(words.split())
        assert not [q for q in tagged(sheet) if q.endswith(("/P3", "/P4", "/P5"))]
    assert len(resting) == 2 and len(list(out.glob("rest-centres-*.svg"))) == 4
    # the instant alone: every position of the render has the triad at rest
    data["drive"]["angle"] = lo
    alone, _ = render_and_check(tmp_path, data, "alone")
    assert [alone["positions"][0]["centres"][n] for n in "345"] == ["at rest"] * 3


def test_the_motion_says_which_centres_are_at_rest():
    """The API: ``Centre.at_rest(i)`` and ``at(i)`` None at the sketched (exact) instant 0°; a
    translating link's centre is at infinity, not at rest (its direction is given)."""
    data = example("triad_at_rest")
    data["drive"]["angle"] = [0.0, 90.0]
    mech = build_mechanism(parse_scene(data))
    ic = analyse(mech, analyse_structure(mech)).centres
    for n in "345":
        assert ic.absolute[n].at_rest(0) and ic.absolute[n].at(0) is None
        assert not ic.absolute[n].at_rest(1) and ic.absolute[n].at(1) is not None
    slider = example("crank_slider_central")
    mech = build_mechanism(parse_scene(slider))
    ic = analyse(mech, analyse_structure(mech)).centres
    block = next(name for name, link in mech.links.items() if name != "0" and len(link.local) == 1)
    c = ic.absolute[block]
    moving = [i for i in range(len(c.rest)) if not c.at_rest(i)]
    assert moving and all(c.at(i) is None and np.linalg.norm(c.direction[i]) == pytest.approx(1.0) for i in moving)


def test_a_mechanism_standing_still_has_no_centre_anywhere(tmp_path):
    """ω1 = 0: every link is at rest, and the centres sheet says so (it once drew no centre
    and said nothing, and the JSON called them all "at infinity")."""
    data = example("four_bar")
    data["drive"] |= {"angle": 30.0, "omega": 0.0, "epsilon": 0.0}
    data["plans"] = {"draw": ["scheme", "centres"]}
    report, out = render_and_check(tmp_path, data, "still")
    assert set(report["positions"][0]["centres"].values()) == {"at rest"}
    words = " ".join(sheet_words((out / "still-centres.svg").read_text(encoding="utf-8")).split())
    assert "Links 1, 2 and 3 are at rest at this position (the whole mechanism stands)" in words


# --- 2. a centre named like a point ------------------------------------------------------------

def four_bar_with_point(name: str) -> dict:
    """A four-bar O, A, <name>, D: crank OA 0.08 m, coupler 0.25 m, rocker D<name> 0.2 m."""
    return {"title": f"Four-bar with a point {name}",
            "points": {"O": [0.0, 0.0], "D": [0.24, 0.0], "A": [0.08, 0.0], name: [0.2303125, 0.199765243]},
            "links": {"0": ["O", "D"], "1": ["O", "A"], "2": ["A", name], "3": ["D", name]},
            "drive": {"link": "1", "angle": 30.0, "omega": 10.0},
            "plans": {"draw": ["scheme", "velocity", "acceleration", "centres"]}}


@pytest.mark.parametrize("name", ["P3", "P2"])
def test_a_point_named_like_a_centre(tmp_path, name):
    """A point P3 (or P2) beside the centre of link 3 (of link 2): the centre is keyed and
    printed P3′ (P2′), so `plans check` no longer joins the ray centre → point P3 end to end
    (it once failed "closure at P3: r:P3/P3 tail, r:P3/P3 head are … mm apart")."""
    link = name[1]
    report, out = render_and_check(tmp_path, four_bar_with_point(name), "named")
    rays = tagged(out / "named-centres.svg")
    centre = report["positions"][0]["centres"][link]
    for q, attrs in rays.items():
        point, _, label = q.partition(":")[2].partition("/")
        assert attrs["data-from"] == label and attrs["data-to"] == point
        assert label != name           # no centre is named like the point
        if label == f"{name}′":
            r = report["positions"][0]["points"][point]["r"]
            assert float(attrs["data-value"]) == pytest.approx(math.dist(r, centre), rel=1e-12)
    assert f"r:{name}/{name}′" in rays      # from the centre of link 3 (2), primed, to the point
    words = sheet_words((out / "named-centres.svg").read_text(encoding="utf-8")).split()
    assert f"{name}′" in words and name in words


def test_koshel_sheet_with_a_point_named_like_the_base_centre(tmp_path):
    """Koshel's variant 1 with its point D (of base link 5) renamed P5: the sheet's centre of
    link 5 is P5′, and every sheet passes `plans check`."""
    data = example("koshel_variant1")
    data["drive"]["angle"] = [45.0]
    data["points"] = {("P5" if p == "D" else p): xy for p, xy in data["points"].items()}
    data["links"] = {k: [("P5" if p == "D" else p) for p in pts] for k, pts in data["links"].items()}
    data.pop("lengths", None)
    report, out = render_and_check(tmp_path, data, "koshel")
    sheet = next(out.glob("koshel-koshel*.svg"))
    rays = tagged(sheet)
    assert "r:P5/P5′" in rays and rays["r:P5/P5′"]["data-from"] == "P5′"


# --- 7. names that read alike ------------------------------------------------------------------

def quick_return_with_a3() -> dict:
    """The quick-return shaper with the top of its lever (point D of link 3) called A3, beside
    the block's pin A seen as a point of the lever (A of link 3, once also named A3)."""
    data = example("quick_return")
    names = {"D": "A3"}
    data["points"] = {names.get(p, p): xy for p, xy in data["points"].items()}
    data["links"] = {k: [names.get(p, p) for p in pts] for k, pts in data["links"].items()}
    data["lengths"] = {"OA": 0.1, "OC": 0.3, "C-A3": 0.55, "A3-E": 0.2}
    data["plans"] = {"draw": ["scheme", "velocity", "acceleration", "centres"]}
    return data


def test_a_point_named_like_another_point_of_a_link(tmp_path):
    """Point A3 beside point A of link 3: the lever's point at A is named A@3 in the
    quantities (and printed a3′), so `plans check` joins no two different images (it once
    failed "closure at a3 = a3′ = A3"); the values are the lever's, ω3 × CA."""
    data = quick_return_with_a3()
    report, out = render_and_check(tmp_path, data, "qr")
    for k, angle in enumerate(data["drive"]["angle"]):
        pos = report["positions"][k]
        v = tagged(out / f"qr-velocity-{angle:g}.svg")
        w3 = pos["links"]["3"]["omega"]
        ca = np.subtract(pos["points"]["A"]["r"], pos["points"]["C"]["r"])
        assert float(v["v:A@3/C"]["data-value"]) == pytest.approx(abs(w3) * np.linalg.norm(ca), rel=1e-12)
        assert v["v:A@3/C"]["data-to"] == "a3′" and v["v:A3"]["data-to"] == "a3"
        v_a3_of_lever = w3 * np.array([-ca[1], ca[0]])
        assert float(v["v:A@3/A2"]["data-value"]) == pytest.approx(
            np.linalg.norm(v_a3_of_lever - pos["points"]["A"]["v"]), rel=1e-9)
        assert float(v["v:A3"]["data-value"]) == pytest.approx(np.linalg.norm(pos["points"]["A3"]["v"]), rel=1e-12)
        a = tagged(out / f"qr-acceleration-{angle:g}.svg")
        assert {"a:A@3/A2:cor", "a:A@3/A2:r", "a:A3", "a:E/A3"} <= set(a)
        assert a["a:A@3/A2:cor"]["data-to"] == "k_A3′A2"


def test_joined_names_are_plain_unless_they_clash():
    """XL, unless a point is called XL or two pairs join alike (A of link 33, A3 of link 3);
    then X@L, primed while that is a point's name too. No name is a point's, no two alike."""
    plain = joined_names(("O", "A", "B"), ("0", "1", "2", "3"))
    assert plain[("A", "3")] == "A3" and plain[("B", "2")] == "B2"
    names = joined_names(("A", "A3", "A@3", "B"), ("0", "3", "33"))
    assert names[("A", "3")] == "A@3′" and names[("B", "3")] == "B3"
    # A of link 33 and A3 of link 3 both join to A33; A@3 of link 3 is plainly A@33
    assert names[("A", "33")] == "A@33′" and names[("A3", "3")] == "A3@3" and names[("A@3", "3")] == "A@33"
    assert len(set(names.values())) == len(names) and not set(names.values()) & {"A", "A3", "A@3", "B"}

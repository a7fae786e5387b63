"""Class III and IV groups: structure, the two independent solutions of a triad (Jacobian
solve and special points), their construction on the plans, instantaneous centres, and the
hard cases (singular and near-singular positions, groups that cannot assemble)."""

from __future__ import annotations

import json
import math
import tomllib

import numpy as np
import pytest
from shapely.geometry import LineString, Point

from conftest import EXAMPLES, toml_text, sheet_words
from reference import Reference
from plans.checking import check_plan
from plans.cli import main
from plans.constructions import acceleration_plan, velocity_plan
from plans.errors import AssemblyError, SingularPositionError
from plans.kinematics import analyse, special
from plans.kinematics.centres import centres
from plans.model import build_mechanism
from plans.scene import parse_scene
from plans.structure import ComplexGroup, analyse_structure

BY_NAME = {p.stem: p for p in EXAMPLES}
TRIADS = ["koshel_variant1", "koshel_variant2", "class3_six_link"]
COMPLEX = TRIADS + ["class4_six_link"]
FULL_TURN = np.arange(24) * 15.0 + 5.0


def _scene(name: str) -> dict:
    return tomllib.loads(BY_NAME[name].read_text(encoding="utf-8"))


def _load(data: dict):
    mech = build_mechanism(parse_scene(data))
    return mech, analyse_structure(mech)


# --- structure ----------------------------------------------------------------------------

@pytest.mark.parametrize("name, klass, order, base", [
    ("koshel_variant1", 3, 3, "5"), ("koshel_variant2", 3, 3, "5"), ("class3_six_link", 3, 3, "3"),
    ("class4_six_link", 4, 2, None)])
def test_structure_of_high_class_examples(name, klass, order, base):
    mech, st = _load(_scene(name))
    (g,) = st.groups
    assert isinstance(g, ComplexGroup) and (g.klass, g.order, g.base) == (klass, order, base)
    assert st.klass == klass and st.formula == f"I(0-1) ← {'III' if klass == 3 else 'IV'}(2-3-4-5)"
    assert len(g.inner) + len(g.outer) == 6 and st.dof == 1


def test_fig_1_9_driven_from_fm_is_class_two():
    """The textbook's remark on Fig. 1.9: with FM driving, the chain splits into two dyads."""
    data = _scene("class3_six_link")
    data["drive"] = {"link": "5", "angle": [-60.0, -62.0], "omega": 5.0, "epsilon": 0.0}   # M→F is at −59.8°
    mech, st = _load(data)
    assert st.klass == 2 and sorted(sorted(g.links) for g in st.groups) == [["1", "2"], ["3", "4"]]
    assert st.formula.startswith("I(0-5) ← II(")
    motion = analyse(mech, st)
    assert np.all(np.isfinite(motion.links["2"].epsilon))


# --- the two independent solutions ----------------------------------------------------------

def _relative_gap(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(a)), 1e-300))


@pytest.mark.parametrize("name", TRIADS)
def test_special_points_agree_with_jacobian_solution(name):
    """Every example, 24 positions a full turn round: ω, ε of every link, and v, a of every
    point, from the special points vs the Jacobian solve, to 1e-9 relative (to the largest)."""
    mech, st = _load(_scene(name))
    motion = analyse(mech, st, FULL_TURN)
    (g,) = st.groups
    sol = special.solve_triad(g, mech, motion.links)
    size = mech.size
    worst = 0.0
    for link in g.links:
        a, b = motion.links[link], sol.links[link]
        pts = [a.point(x) for x in mech.links[link].local.values()]
        v_ref = np.concatenate([a.omega[:, None] * size] + [a.velocity(x) for x in pts], axis=1)
        v_sp = np.concatenate([b.omega[:, None] * size] + [b.velocity(x) for x in pts], axis=1)
        a_ref = np.concatenate([a.epsilon[:, None] * size] + [a.acceleration(x) for x in pts], axis=1)
        a_sp = np.concatenate([b.epsilon[:, None] * size] + [b.acceleration(x) for x in pts], axis=1)
        worst = max(worst, _relative_gap(v_ref, v_sp), _relative_gap(a_ref, a_sp))
    assert worst < 1e-9, worst


@pytest.mark.parametrize("name", COMPLEX)
def test_loop_closure_residual(name):
    """Every pair's two links put the pin at one point, to 1e-12 of the mechanism's size."""
    mech, st = _load(_scene(name))
    motion = analyse(mech, st, FULL_TURN, order=0)
    for r in mech.revolutes:
        a = motion.links[r.a].point(mech.links[r.a].local[r.point])
        b = motion.links[r.b].point(mech.links[r.b].local[r.point])
        assert np.max(np.linalg.norm(a - b, axis=1)) <= 1e-12 * mech.size


# --- constructions --------------------------------------------------------------------------

@pytest.mark.parametrize("name", TRIADS)
def test_special_point_construction_lines_meet_at_analytic_images(name):
    """On both plans, the two lines through the known images (⊥ the rods' axes) meet — by
    shapely — within 1e-6 mm of the special point's image placed from the Jacobian solution;
    and so do the two lines that find each base pin (its rod's own line and the one from the
    special point or from the third pin). One special point per plan: one route is drawn."""
    mech, st = _load(_scene(name))
    motion = analyse(mech, st, FULL_TURN[::3])
    for i in range(len(motion)):
        for plan in (velocity_plan(motion, i, 0.005), acceleration_plan(motion, i, 0.05)):
            assert check_plan(plan) == []
            groups: dict[str, list] = {}
            for line in plan.lines:
                groups.setdefault(line.group, []).append(LineString([line.start, line.end]))
            special_groups = [k for k in groups if ":S" in k]
            assert len(special_groups) == 1
            for key in special_groups + [k for k in groups if ":" in k and ":S" not in k]:
                a, b = groups[key]
                meet = a.intersection(b)
                label = key.split(":")[1].lower()
                assert meet.geom_type == "Point" and meet.distance(Point(plan.point(label))) < 1e-6


# --- instantaneous centres -------------------------------------------------------------------

@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_absolute_centres_agree_with_velocity_field(path):
    """v_X = ω × (X − P) for every point X of every link with a finite centre, to rounding.

    P = k × w/ω with w = v_O − ω·k × O (the link's field at the world origin; O its origin), so
    v_X − ω × (X − P) = 0 exactly and what remains is rounding: about ten operations (X − O,
    X − P, the products by ω, the sums, the division by ω, for each of the two components),
    each rounding by at most eps times one of |v_O|, |ω|·|X|, |ω|·|O|, |ω|·|P|. Hence
    10·eps·(|v_O| + |ω|·(|X| + |O| + |P|)) at each position (measured: at most 0.07 of it)."""
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    mech, st = _load(data)
    values = None if "displacement" in data["drive"] or path.stem in ("tangent_mechanism", "four_bar_coupler_drive") \
        else FULL_TURN
    motion = analyse(mech, st, values, order=1)
    ic = centres(motion)
    checked = 0
    for link, c in ic.absolute.items():
        s = motion.links[link]
        for x in mech.links[link].local.values():
            X = s.point(x)
            v = s.velocity(X)
            finite = ~np.isnan(c.point[:, 0])
            r = X - np.where(finite[:, None], c.point, 0.0)
            field = s.omega[:, None] * np.stack([-r[:, 1], r[:, 0]], axis=1)
            err = np.linalg.norm(v - field, axis=1)[finite]
            terms = np.linalg.norm(s.v, axis=1) + np.abs(s.omega) * (
                np.linalg.norm(X, axis=1) + np.linalg.norm(s.origin, axis=1)
                + np.linalg.norm(np.where(finite[:, None], c.point, 0.0), axis=1))
            assert np.all(err <= 10 * np.finfo(float).eps * terms[finite]), (link, np.max(err / terms[finite]))
            checked += int(finite.sum())
            # where the centre is at infinity the link translates: every point has one velocity
            if (~finite).any():
                assert np.allclose(v[~finite], s.v[~finite] + 0 * v[~finite], atol=1e-12)
    assert checked > 0


@pytest.mark.parametrize("name", ["koshel_variant1", "six_link_press", "quick_return"])
def test_relative_centres_pins_and_kennedy(name):
    """P_ij at a shared pin is the pin; P_ij, P_jk, P_ik are collinear (Aronhold–Kennedy)."""
    data = tomllib.loads(BY_NAME[name].read_text(encoding="utf-8"))
    mech, st = _load(data)
    motion = analyse(mech, st, FULL_TURN[::4], order=1)
    ic = centres(motion)
    for r in mech.revolutes:
        key = tuple(sorted((r.a, r.b), key=list(mech.links).index))
        c = ic.absolute[key[1]] if key[0] == "0" else ic.relative[key]
        assert np.allclose(c.point, motion.position(r.point), atol=1e-12 * mech.size)
    every = {**{("0", k): v for k, v in ic.absolute.items()}, **ic.relative}
    links = list(mech.links)
    for i, j, k in [(a, b, c) for a in links for b in links for c in links if a < b < c]:
        p = [every.get((x, y)) or every.get((y, x)) for x, y in ((i, j), (j, k), (i, k))]
        pts = [c.point for c in p]
        ok = ~np.isnan(np.stack(pts)[:, :, 0]).any(axis=0)
        d1, d2 = pts[1] - pts[0], pts[2] - pts[0]
        area = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])[ok]
        spread = (np.linalg.norm(d1, axis=1) * np.linalg.norm(d2, axis=1))[ok]
        assert np.all(area <= 1e-9 * np.maximum(spread, mech.size ** 2))


def test_centre_at_infinity_is_null_and_drawn_as_direction(tmp_path):
    """The Scotch yoke's slider translates (ω = 0): its centre is null in the JSON, never NaN,
    and the centres sheet draws it as a direction."""
    text = BY_NAME["scotch_yoke"].read_text(encoding="utf-8")
    text = text.replace('draw = ["scheme", "velocity", "acceleration"]', 'draw = ["centres"]')
    scene = tmp_path / "yoke.toml"
    scene.write_text(text, encoding="utf-8")
    assert main(["render", str(scene), "-o", str(tmp_path / "o"), "-q"]) == 0
    raw = (tmp_path / "o" / "yoke.json").read_text(encoding="utf-8")
    assert "NaN" not in raw and "Infinity" not in raw
    data = json.loads(raw)
    for pos in data["positions"]:
        assert pos["centres"]["3"] is None and pos["centres"]["1"] == [0.0, 0.0]
    svgs = sorted((tmp_path / "o").glob("yoke-centres*.svg"))
    assert svgs and all("P3 at ∞" in sheet_words(p.read_text(encoding="utf-8")) for p in svgs)
    assert main(["check", *map(str, svgs)]) == 0


def test_json_carries_centres_and_special_points(rendered):
    data = json.loads((rendered / "koshel_variant1.json").read_text(encoding="utf-8"))
    pos = data["positions"][1]
    assert set(pos["centres"]) == {"1", "2", "3", "4", "5"}
    assert np.allclose(pos["relative_centres"]["2-5"], pos["points"]["B"]["r"], atol=1e-12)
    sp = pos["special_points"]["III(2-3-4-5)"]
    assert set(sp) == {"S1", "S2", "S3"}
    # variant 1: P5 is the special point of the two rockers (S3 = KC ∩ ND)
    assert np.allclose(pos["centres"]["5"], sp["S3"]["r"], atol=1e-12)
    assert data["structure"]["groups"][0]["base_link"] == "5"


# --- hard cases -----------------------------------------------------------------------------

def _concurrent_triad() -> dict:
    """A Koshel-type triad sketched with its three rods' axes meeting at Q (singular)."""
    q = np.array([0.30, 0.55])
    a = np.array([0.035355339, 0.035355339])
    b = a + 0.6 * (q - a)
    c, d = np.array([0.20, 0.25]), np.array([0.45, 0.22])
    k, n = c + 0.55 * (q - c), d + 0.6 * (q - d)
    pts = {"O": [0.0, 0.0], "A": a, "B": b, "C": c, "D": d, "K": k, "N": n}
    return {"title": "singular triad", "points": {p: [float(x) for x in v] for p, v in pts.items()},
            "links": {"0": ["O", "K", "N"], "1": ["O", "A"], "2": ["A", "B"], "3": ["N", "D"], "4": ["K", "C"],
                      "5": ["B", "C", "D"]},
            "drive": {"link": "1", "angle": [45.0], "omega": 10.0, "epsilon": 0.0}}


def test_singular_triad_is_reported():
    mech, st = _load(_concurrent_triad())
    with pytest.raises(SingularPositionError) as exc:
        analyse(mech, st)
    msg = str(exc.value)
    assert "III(2-3-4-5)" in msg and "45°" in msg and "meet in one point" in msg


def _folding_triad() -> dict:
    """A triad whose walk reaches a limit position near φ ≈ 98°."""
    pts = {"O": [0.0, 0.0], "A": [0.035355339, 0.035355339], "B": [0.29, 0.03], "C": [0.26, 0.12],
           "D": [0.40, 0.10], "K": [0.20, 0.32], "N": [0.48, 0.31]}
    return {"title": "folding triad", "points": pts,
            "links": {"0": ["O", "K", "N"], "1": ["O", "A"], "2": ["A", "B"], "3": ["N", "D"], "4": ["K", "C"],
                      "5": ["B", "C", "D"]},
            "drive": {"link": "1", "angle": [45.0], "omega": 10.0, "epsilon": 0.0}}


def test_triad_beyond_its_limit_position_cannot_assemble():
    mech, st = _load(_folding_triad())
    with pytest.raises(AssemblyError) as exc:
        analyse(mech, st, np.array([45.0, 120.0]))
    msg = str(exc.value)
    assert "III(2-3-4-5)" in msg and "120°" in msg and "cannot assemble" in msg


FD1 = np.array([-1, 9, -45, 0, 45, -9, 1]) / 60.0
FD2 = np.array([2, -27, 270, -490, 270, -27, 2]) / 180.0


@pytest.mark.parametrize("delta", [0.5, 0.2])
def test_near_singular_triad_matches_finite_differences(delta):
    """Within 0.5° of the limit position (found by Moore–Spence on the whole mechanism,
    tests/reference.py), v and a still equal 6th-order finite differences to 1e-7."""
    data = _folding_triad()
    mech, st = _load(data)
    ref = Reference(mech)
    fold = ref.fold(ref.solve([97.5])[0]).value
    assert 95.0 < fold < 100.0
    phi = fold - delta
    h = delta / 40.0               # degrees: the stencil reaches 3h, well short of the fold
    motion = analyse(mech, st, np.array([phi]))
    near = analyse(mech, st, phi + h * np.arange(-3, 4), order=0)
    assert abs(motion.sines["III(2-3-4-5)"][0]) < 0.05
    w, hr = mech.drive.speed, math.radians(h)
    for link in mech.moving:
        for p, x in mech.links[link].local.items():
            path = near.links[link].point(x)
            v_fd = w * (FD1 @ path) / hr
            a_fd = w * w * (FD2 @ path) / hr ** 2
            v = motion.links[link].velocity(motion.links[link].point(x))[0]
            a = motion.links[link].acceleration(motion.links[link].point(x))[0]
            scale_v = max(np.linalg.norm(motion.velocity(q, l)[0]) for l in mech.moving for q in mech.links[l].points)
            scale_a = max(np.linalg.norm(motion.acceleration(q, l)[0]) for l in mech.moving
                          for q in mech.links[l].points)
            assert np.linalg.norm(v - v_fd) <= 1e-7 * scale_v
            assert np.linalg.norm(a - a_fd) <= 1e-7 * scale_a


@pytest.mark.parametrize("name", ["koshel_variant1", "koshel_variant2"])
def test_uncertain_scale_plan(name):
    """Koshel's plan: the first vector is 60 mm ⊥ P–X; K_V = V_Y/|py| with Y the crank's pin;
    |pc|/|px| = PC/PX for the base link's other pins (P from the JSON-level centres)."""
    from plans.constructions import uncertain_plan
    mech, st = _load(_scene(name))
    motion = analyse(mech, st, FULL_TURN[::6], order=1)
    ic = centres(motion)
    (g,) = st.groups
    for i in range(len(motion)):
        plan = uncertain_plan(motion, i, g)
        assert plan is not None and check_plan(plan) == []
        vec = {v.quantity: v for v in plan.vectors}
        rod = next(r for r in g.rods if r.outer.b != "0")
        x, y = rod.inner.point, rod.outer.point
        assert vec[f"v:{x}"].length == pytest.approx(60.0, rel=1e-12)
        v_y = np.linalg.norm(motion.velocity(y)[i])
        assert plan.mu == pytest.approx(v_y / vec[f"v:{y}"].length, rel=1e-12)
        P = ic.absolute[g.base].point[i]
        for pin in (p.point for p in g.inner if p.point != x):
            ratio = np.linalg.norm(motion.position(pin)[i] - P) / np.linalg.norm(motion.position(x)[i] - P)
            assert vec[f"v:{pin}"].length / vec[f"v:{x}"].length == pytest.approx(ratio, rel=1e-10)


def test_warning_gives_distance_to_the_limit_position(tmp_path):
    """Near a singular position the terminal warning says how far it is; the estimate (secant
    steps on the condition figure) matches the Moore–Spence fold of tests/reference.py."""
    from plans.kinematics.singular import distance as singular_distance
    mech, st = _load(_folding_triad())
    ref = Reference(mech)
    fold = ref.fold(ref.solve([97.5])[0]).value
    motion = analyse(mech, st, np.array([fold - 0.3]))
    assert singular_distance(motion, "III(2-3-4-5)", 0) == pytest.approx(0.3, rel=1e-3)
    assert abs(analyse(mech, st, np.array([fold - 0.1])).sines["III(2-3-4-5)"][0]) < 1e-2   # warns there
    data = _folding_triad()
    lines = [f'{k} = [{v[0]}, {v[1]}]' for k, v in data["points"].items()]
    links = [f'{k} = {json.dumps(v)}' for k, v in data["links"].items()]
    scene = tmp_path / "fold.toml"
    scene.write_text("\n".join(['title = "fold"', "[points]", *lines, "[links]", *links, "[drive]",
                                'link = "1"', f"angle = {fold - 0.1!r}", "omega = 10.0",
                                "[plans]", 'draw = ["velocity"]']), encoding="utf-8")
    from plans.pipeline import render_scene
    warnings = render_scene(scene).warnings
    assert len(warnings) == 1 and "III(2-3-4-5)" in warnings[0] and "about 0.1° from it" in warnings[0]


def _sliding_rod_triad() -> dict:
    """Koshel's variant 1 with rod 4 turned into a block sliding on a frame guide (horizontal
    through C): a class III group of form RR-PR-RR (its axis is the normal to the guide at C)."""
    pts = {"O": [0.0, 0.0], "A": [0.035355339, 0.035355339], "B": [0.297, 0.0], "C": [0.177, 0.124],
           "D": [0.473, 0.104], "N": [0.394, 0.33]}
    return {"title": "triad with a sliding rod", "points": pts,
            "links": {"0": ["O", "N"], "1": ["O", "A"], "2": ["A", "B"], "3": ["N", "D"], "4": ["C"],
                      "5": ["B", "C", "D"]},
            "sliders": [{"link": "4", "on": "0", "through": "C", "angle": 0.0}],
            "drive": {"link": "1", "angle": [45.0], "omega": 10.0, "epsilon": 3.0}}


def test_triad_with_a_sliding_rod_matches_the_reference_and_renders(tmp_path):
    """Form RR-PR-RR: once a TypeError (a group holding the prismatic pair's dict was hashed)."""
    data = _sliding_rod_triad()
    mech, st = _load(data)
    assert [g.form for g in st.groups if isinstance(g, ComplexGroup)] == ["RR-PR-RR"]
    values = np.arange(12) * 30.0 + 5.0
    motion = analyse(mech, st, values)
    triad = special.solve_triad(st.groups[-1], mech, motion.links, order=2)
    for i, state in enumerate(Reference(mech).solve(values)):
        for link in mech.moving:
            for p in mech.links[link].points:
                for got, want in ((motion.velocity(p, link)[i], state.velocity(p, link)),
                                  (motion.acceleration(p, link)[i], state.acceleration(p, link))):
                    assert np.linalg.norm(got - want) <= 1e-9 * max(1.0, np.linalg.norm(want))
        for link, s in triad.links.items():
            assert abs(s.omega[i] - motion.links[link].omega[i]) <= 1e-9 * abs(mech.drive.speed)
            assert abs(s.epsilon[i] - motion.links[link].epsilon[i]) <= 1e-8 * mech.drive.speed ** 2
    data["drive"]["angle"] = values.tolist()
    data["plans"] = {"draw": ["scheme", "velocity", "acceleration", "centres"]}
    scene = tmp_path / "sliding_rod.toml"
    scene.write_text(toml_text(data), encoding="utf-8")
    out = tmp_path / "out"
    assert main(["render", str(scene), "-o", str(out), "-q"]) == 0
    svgs = sorted(str(p) for p in out.glob("*.svg"))
    assert len(svgs) == 12 * 5          # scheme, velocity, acceleration, centres and Koshel's sheet
    assert main(["check", *svgs]) == 0


"""Regressions found by trying `plans` as a stranger would: each test failed before its fix.

Scenes are written out here (not taken from the gallery) so that each test states the exact
mechanism that once failed.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from conftest import toml_text, sheet_words
from plans.cli import main
from plans.constructions import acceleration_plan, velocity_plan
from plans.kinematics import analyse
from plans.model import build_mechanism
from plans.scene import parse_scene
from plans.structure import analyse_structure

TWELVE = [15.0 + 30.0 * k for k in range(12)]


def render_and_check(tmp_path, data: dict, name: str = "scene") -> dict:
    """Render every sheet of ``data`` (exit 0), check every SVG (exit 0); the JSON report."""
    scene = tmp_path / f"{name}.toml"
    scene.write_text(toml_text(data), encoding="utf-8")
    out = tmp_path / f"{name}-out"
    assert main(["render", str(scene), "-o", str(out), "-q"]) == 0
    svgs = sorted(str(p) for p in out.glob("*.svg"))
    assert svgs and main(["check", *svgs]) == 0
    return json.loads((out / f"{name}.json").read_text(encoding="utf-8"))


def whitworth(lever_slides: bool = False, pivot: str = "Q", end: str = "C") -> dict:
    """Whitworth quick-return: crank OA 0.1 m longer than the centre distance OQ 0.05 m, so
    the slotted lever 3 turns fully; its end C lies on the far side of the pivot Q from the
    block 2 (QC 0.08 m); rod CD 0.25 m drives the ram 5 on a frame guide 0.15 m below O.
    ``lever_slides`` writes the prismatic pair the other way round (lever 3 slides in block 2)."""
    a = [0.1 * math.cos(math.radians(60.0)), 0.1 * math.sin(math.radians(60.0))]
    q = [0.0, -0.05]
    u = np.subtract(a, q) / np.linalg.norm(np.subtract(a, q))
    c = [q[0] - 0.08 * u[0], q[1] - 0.08 * u[1]]
    d = [c[0] + math.sqrt(0.25 ** 2 - (-0.15 - c[1]) ** 2), -0.15]
    slide = {"link": "3", "on": "2"} if lever_slides else {"link": "2", "on": "3"}
    return {"title": "Whitworth quick-return",
            "points": {"O": [0.0, 0.0], pivot: q, "A": a, end: [float(x) for x in c], "D": d},
            "links": {"0": ["O", pivot], "1": ["O", "A"], "2": ["A"], "3": [pivot, end], "4": [end, "D"],
                      "5": ["D"]},
            "sliders": [slide | {"through": [pivot, end]}, {"link": "5", "on": "0", "through": "D", "angle": 0.0}],
            "drive": {"link": "1", "angle": TWELVE, "omega": 10.0, "epsilon": -2.0},
            "plans": {"draw": ["scheme", "velocity", "acceleration", "centres"]}}


@pytest.mark.parametrize("names", [("Q", "C"), ("P", "R")])
def test_whitworth_renders_either_way_round_with_the_same_numbers(tmp_path, names):
    """Block sliding in the lever, or the lever sliding in the block: the same mechanism, the
    same values; both render over a full turn and pass `plans check`. (Once the second form
    named the pair at the lever's pivot and started its acceleration plan from the lever.)"""
    one = render_and_check(tmp_path, whitworth(False, *names), "block")
    two = render_and_check(tmp_path, whitworth(True, *names), "lever")
    for p1, p2 in zip(one["positions"], two["positions"]):
        for point, entry in p1["points"].items():
            for key in ("r", "v", "a"):
                assert entry[key] == pytest.approx(p2["points"][point][key], rel=1e-12, abs=1e-12)


def test_whitworth_images_across_the_pivot_lie_across_the_pole():
    """The lever's end C and its point A3 under the block are on opposite sides of the pivot Q,
    so their images c and a3 are on opposite sides of the pole, in the ratio QC : QA."""
    mech = build_mechanism(parse_scene(whitworth(True)))
    motion = analyse(mech, analyse_structure(mech))
    for i in range(len(motion)):
        for build, mu in ((velocity_plan, 0.01), (acceleration_plan, 0.1)):
            plan = build(motion, i, mu)
            c, a3 = np.array(plan.point("c")), np.array(plan.point("a3"))
            qc = np.linalg.norm(motion.position("C")[i] - motion.position("Q")[i])
            qa = np.linalg.norm(motion.position("A")[i] - motion.position("Q")[i])
            assert float(c @ a3) < 0
            assert np.linalg.norm(c) / np.linalg.norm(a3) == pytest.approx(qc / qa, rel=1e-9)


# --- point names that look like plan labels ----------------------------------------------------

def renamed(data: dict, names: dict[str, str]) -> dict:
    """The scene with its points renamed (lengths written P-Q)."""
    out = {k: v for k, v in data.items() if k not in ("points", "links", "sliders", "lengths")}
    out["points"] = {names.get(p, p): xy for p, xy in data["points"].items()}
    out["links"] = {k: [names.get(p, p) for p in pts] for k, pts in data["links"].items()}
    out["sliders"] = [s | {"through": [names.get(p, p) for p in ([s["through"]] if isinstance(s["through"], str)
                                                                 else s["through"])]}
                      for s in data.get("sliders", [])]
    if "lengths" in data:
        pts = sorted(data["points"], key=len, reverse=True)
        lengths = {}
        for key, value in data["lengths"].items():
            a = next(p for p in pts if key.startswith(p) and key[len(p):] in data["points"])
            lengths[f"{names.get(a, a)}-{names.get(key[len(a):], key[len(a):])}"] = value
        out["lengths"] = lengths
    return out


def oscillating_cylinder() -> dict:
    """Crank OA 0.1 m; the piston rod 2 (A, with its piston head P) slides in cylinder 3
    pivoted on the frame at C, 0.3 m from O (RPR)."""
    a = [0.1 * math.cos(math.radians(40.0)), 0.1 * math.sin(math.radians(40.0))]
    c = [0.3, 0.0]
    u = np.subtract(c, a) / np.linalg.norm(np.subtract(c, a))
    p = [a[0] + 0.12 * u[0], a[1] + 0.12 * u[1]]
    return {"title": "Oscillating cylinder", "points": {"O": [0.0, 0.0], "A": a, "P": p, "C": c},
            "links": {"0": ["O", "C"], "1": ["O", "A"], "2": ["A", "P"], "3": ["C"]},
            "sliders": [{"link": "2", "on": "3", "through": ["A", "P"]}],
            "drive": {"link": "1", "angle": TWELVE, "omega": 8.0, "epsilon": 5.0},
            "plans": {"draw": ["scheme", "velocity", "acceleration", "centres"]}}


def _example(stem: str) -> dict:
    import tomllib
    from conftest import EXAMPLES

    data = tomllib.loads(next(p for p in EXAMPLES if p.stem == stem).read_text(encoding="utf-8"))
    data["drive"]["angle"] = TWELVE
    data["plans"] = {"draw": ["scheme", "velocity", "acceleration", "centres"]}
    return data


CLASHES = {
    "oscillating cylinder, P": (oscillating_cylinder, {}),
    # the Whitworth, refused at every angle with "v:R/P … failed its geometric check":
    # its block pin P got the pole's image
    "Whitworth, block pin P, lever end R": (whitworth, {"A": "P", "C": "R"}),
    "oscillating cylinder, π Π p": (oscillating_cylinder, {"O": "π", "A": "Π", "C": "p"}),
    "four-bar, p a A S1": (lambda: _example("four_bar"), {"O": "p", "A": "a", "B": "A", "M": "S1"}),
    "quick-return, P k_D3D2 n_ED": (lambda: _example("quick_return"), {"C": "P", "A": "k_A3A2", "E": "n_ED"}),
    "Koshel's triad, S1 S2 S3 P": (lambda: _example("koshel_variant1"),
                                   {"O": "P", "K": "S1", "N": "S2", "D": "S3", "C": "p"}),
}


@pytest.mark.parametrize("case", sorted(CLASHES))
def test_point_names_that_look_like_plan_labels(tmp_path, case):
    """A point named like a pole (p, π, P, Π), a special point (S1) or a component's end
    (n_…, k_…) is just a point: every sheet passes `plans check`, and the values equal those
    of the same scene with plain names."""
    build, names = CLASHES[case]
    plain = build()
    if not names:                     # the scene already has its clash: rename it away
        names = {"P": "H"}
        plain = renamed(plain, names)
        names = {"H": "P"}
    base = render_and_check(tmp_path, plain, "plain")
    clash = render_and_check(tmp_path, renamed(plain, names), "clash")
    for p1, p2 in zip(base["positions"], clash["positions"]):
        for point, entry in p1["points"].items():
            assert p2["points"][names.get(point, point)] == entry


def test_pole_label_stays_and_the_clashing_image_is_primed():
    mech = build_mechanism(parse_scene(oscillating_cylinder()))
    motion = analyse(mech, analyse_structure(mech))
    plan = velocity_plan(motion, 0, 0.01)
    labels = [p.label for p in plan.points]
    assert plan.pole == "p" and plan.point("p") == (0.0, 0.0) and len(set(labels)) == len(labels)
    v_p = motion.velocity("P")[0] / 0.01
    assert plan.point("p′") == pytest.approx(tuple(v_p), abs=1e-12)


# --- a class III group momentarily at rest ------------------------------------------------------

#: Koshel's variant 1 has crank OA and rod AB in line here (found by bisection on OA × AB = 0):
#: v_A is then ⊥ AB, B stands still and so does the whole triad.
AT_REST_DEG = 184.6317321208341


def test_triad_at_rest_keeps_every_other_sheet(tmp_path, capsys):
    """The triad momentarily at rest: its links' ω vanish (to rounding), Koshel's sheet at that
    position says why it is empty, and every other sheet and position is written and checked.
    (Once the degenerate Koshel sheet failed its check and the whole render was refused.)"""
    data = _example("koshel_variant1")
    data["drive"]["angle"] = [0.0, AT_REST_DEG, 200.0]
    scene = tmp_path / "rest.toml"
    scene.write_text(toml_text(data), encoding="utf-8")
    out = tmp_path / "out"
    assert main(["render", str(scene), "-o", str(out), "-q"]) == 0
    err = capsys.readouterr().err
    assert "at rest" in err and "Traceback" not in err
    report = json.loads((out / "rest.json").read_text(encoding="utf-8"))
    links = report["positions"][1]["links"]   # rod 2 turns about B, which stands still
    assert max(abs(links[n]["omega"]) for n in ("3", "4", "5")) < 1e-12 * abs(links["1"]["omega"])
    assert np.linalg.norm(report["positions"][1]["points"]["B"]["v"]) < 1e-12
    sfx = [f"{a:g}" for a in data["drive"]["angle"]]
    for kind in ("scheme", "velocity", "acceleration", "centres", "koshel"):
        for s in sfx:
            assert (out / f"rest-{kind}-{s}.svg").exists(), (kind, s)
    sheet = (out / f"rest-koshel-{sfx[1]}.svg").read_text(encoding="utf-8")
    words = sheet_words(sheet)
    assert "at rest" in words and "|vB|" in words and "<tspan" in sheet   # the note's v_B with a real subscript
    measured = [str(p) for p in sorted(out.glob("*.svg")) if p.name != f"rest-koshel-{sfx[1]}.svg"]
    assert main(["check", *measured]) == 0


def test_limited_crank_asked_for_angles_on_both_sides_of_its_sketch():
    """A four-bar whose crank stops at ±144° (sketched at 0°), asked for 30° and 330° at once:
    the one walk through both fails at the limit, each angle is then walked alone (330° the
    long way round) — with its velocities and accelerations, which once were lost (TypeError)."""
    data = {"points": {"O": [0.0, 0.0], "C": [0.24, 0.0], "A": [0.18, 0.0], "B": [0.21, 0.197737199]},
            "links": {"0": ["O", "C"], "1": ["O", "A"], "2": ["A", "B"], "3": ["C", "B"]},
            "drive": {"link": "1", "angle": [30.0, 330.0], "omega": 10.0, "epsilon": 2.0}}
    mech = build_mechanism(parse_scene(data))
    structure = analyse_structure(mech)
    both = analyse(mech, structure)
    for i, angle in enumerate(data["drive"]["angle"]):
        alone = analyse(mech, structure, np.array([angle]))
        for f in (both.position, both.velocity, both.acceleration):
            assert np.array_equal(f("B")[i], getattr(alone, f.__name__)("B")[0])
    # 330° is reached downwards from the sketch, as −30°, on the sketch's branch (B above OC)
    assert both.position("B")[0][1] > 0 and both.position("B")[1][1] > 0


def test_angles_that_print_alike_get_their_own_sheets(tmp_path):
    """10.0000001° and 10.0000002° once both wrote `-10.svg`, the second over the first."""
    data = _example("four_bar")
    data["drive"]["angle"] = [10.0000001, 10.0000002, 30.0]
    data["plans"] = {"draw": ["velocity"]}
    report = render_and_check(tmp_path, data, "alike")
    names = sorted(p.name for p in (tmp_path / "alike-out").glob("*.svg"))
    assert names == ["alike-velocity-10.0000001.svg", "alike-velocity-10.0000002.svg", "alike-velocity-30.svg"]
    assert len(report["positions"]) == 3


def test_guides_parallel_to_a_subnormal_angle_are_parallel_not_an_overflow():
    """Found by hypothesis (test_prp_at_parallel): a guide at 2.2e-309 rad to another gives a
    subnormal cross product; dividing by it overflowed (an error under -W error). The lines are
    parallel (|u1 × u2| ≤ PARALLEL_DET): a finite placeholder, the cross product returned as is."""
    import warnings

    from plans.kinematics.groups import _intersect
    from plans.kinematics.tolerances import PARALLEL_DET

    p1 = np.array([[-28.64934425, 0.0], [-28.64498082, 0.5]])
    u1 = np.array([[0.9998477, 0.01745241], [1.0, 0.0]])
    p2 = np.array([[-28.64934425, 0.0], [-28.64934425, 0.0]])
    u2 = np.array([[1.0, 2.22507386e-309], [1.0, 2.22507386e-309]])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        point, det = _intersect(p1, u1, p2, u2)
    assert np.all(np.isfinite(point))
    assert abs(det[1]) <= PARALLEL_DET and det[1] != 0.0
    # the first row meets at 1° and is solved exactly: the point lies on both lines
    assert abs(det[0]) > PARALLEL_DET
    np.testing.assert_allclose(point[0], p2[0], atol=1e-12)

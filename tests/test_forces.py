"""Kinetostatics: every link in equilibrium, the power balance, hand checks, stages, bad input.

The checks are independent of the solver's bookkeeping: each link's equilibrium is rebuilt
from the JSON report (the reactions, where prismatic ones act, the balancing element) and
loads the test computes itself from the scene and the motion (m·g, −m·a_S, −I·ε, the given
forces and couples); the balancing element is compared with virtual work (Σ F·v + Σ M·ω = 0)
and, on a crank-slider loaded only at its slider, with statics done by hand.
"""

from __future__ import annotations

import contextlib
import io
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

import plans
from plans.cli import main
from plans.errors import PlansError
from plans.kinematics import analyse
from plans.kinetostatics import solve_forces
from plans.model import build_mechanism
from plans.pipeline import record_stages
from plans.scene import FRAME, parse_scene
from plans.structure import analyse_structure

from conftest import EXAMPLES, toml_text

#: Equilibrium and the agreement of the two balancing methods, relative to the largest term.
RTOL = 1e-9
LOADED = [p for p in EXAMPLES if p.stem in ("crank_slider_forces", "six_link_press_forces", "four_bar_gravity",
                                            "class3_forces")]


def data_of(path: Path) -> dict:
    return tomllib.loads(path.read_text(encoding="utf-8"))


def render(data: dict):
    return plans.render(parse_scene(data), stem="scene")


def random_loads(data: dict, seed: int) -> dict:
    """``data`` with a random mass, inertia and centre on every moving link, a random force on
    each of two links at a random point, a random couple, gravity, and only the force
    analysis to do."""
    rng = np.random.default_rng(seed)
    data = dict(data)
    moving = [name for name in data["links"] if name != FRAME]
    data["masses"] = {name: {"mass": float(rng.uniform(0.5, 5.0)), "inertia": float(rng.uniform(0.0, 0.1)),
                             "centre": str(rng.choice(data["links"][name]))} for name in moving}
    data["forces"] = []
    for name in rng.choice(moving, size=2):
        data["forces"].append({"link": str(name), "at": str(rng.choice(data["links"][name])),
                               "vector": [float(x) for x in rng.uniform(-500.0, 500.0, 2)]})
    data["moments"] = [{"link": str(rng.choice(moving)), "value": float(rng.uniform(-20.0, 20.0))}]
    data["gravity"] = 9.81
    data["plans"] = {"draw": ["forces"]}
    return data


def pin_of(data: dict, first: str, second: str) -> str:
    """The point that two links share (their revolute pair)."""
    common = [p for p in data["links"][first] if p in data["links"][second]]
    assert len(common) == 1, (first, second, common)
    return common[0]


def acts(scene, motion, ext, i: int) -> bool:
    """Whether the constant force ``ext`` acts at position ``i``: always, or (``stroke``
    "working"/"return", on the output slider) while its point moves away from / back towards the
    extreme ``from`` along the guide; at rest (an extreme), on the stroke that starts there —
    found here from the point's path over the positions, not from the library's travel."""
    if ext.stroke == "both":
        return True
    assert not ext.law and ext.link == scene.cycle.output
    u = next(p.direction for p in motion.mechanism.prismatics if p.slider == ext.link)
    s = motion.position(ext.at, ext.link) @ u
    v = motion.velocity(ext.at, ext.link) @ u
    sign = 1.0 if ext.origin == "min" else -1.0
    if abs(v[i]) <= 1e-9 * np.max(np.abs(v)):
        start = abs(s[i] - (s.min() if ext.origin == "min" else s.max())) < 0.5 * (s.max() - s.min())
    else:
        start = sign * v[i] > 0.0
    return start if ext.stroke == "working" else not start


def equilibrium_residuals(data: dict, sheets) -> list[float]:
    """Per position and moving link, |ΣF| and |ΣM|/size relative to the largest term acting on
    the link, from the report and loads computed here."""
    motion, report = sheets.motion, sheets.report
    size = motion.mechanism.size
    scene = parse_scene(data)
    out = []
    for i, pos in enumerate(report["positions"]):
        f = pos["forces"]
        acting: dict[str, list] = {name: [] for name in data["links"]}   # (force, point) and (None, couple)

        def at(link, point):
            return motion.position(point, link)[i]

        for name, m in scene.masses.items():
            s = at(name, m.centre)
            if m.mass > 0.0:
                acting[name].append((-m.mass * motion.acceleration(m.centre, name)[i], s))
                if scene.gravity is not None:
                    acting[name].append((np.array([0.0, -m.mass * scene.gravity]), s))
            acting[name].append((None, -m.inertia * motion.links[name].epsilon[i]))
        for ext in scene.forces:
            if acts(scene, motion, ext, i):
                acting[ext.link].append((np.array(ext.vector), at(ext.link, ext.at)))
        for mom in scene.moments:
            acting[mom.link].append((None, mom.value))
        b = f["balance"]
        if "moment" in b:
            acting[b["link"]].append((None, b["moment"]))
        else:
            point = np.array(b["point"])
            if b["at"] in data["links"][b["link"]] and data.get("balance"):     # a given force: at its point
                assert point == pytest.approx(at(b["link"], b["at"]), abs=1e-12 * size)
            acting[b["link"]].append((np.array(b["force"]), point))
            if "reacts_on" in b:
                acting[b["reacts_on"]].append((-np.array(b["force"]), point))
        for key, r in f["reactions"].items():
            first, second = key.split("#")[0].split("-")
            r = np.array(r)
            if key in f.get("prismatic", {}):
                pr = f["prismatic"][key]
                origin = np.array(pr["origin"])
                assert abs(np.dot(r, pr["u"])) <= 1e-12 * max(np.linalg.norm(r), 1.0), "a guide pushes ⊥ to it"
                if pr["point"] is not None:       # where it acts: its moment about the origin
                    arm = np.array(pr["point"]) - origin
                    assert arm[0] * r[1] - arm[1] * r[0] == pytest.approx(pr["moment"], rel=1e-9, abs=1e-9 * size
                                                                          * np.linalg.norm(r))
                acting[second] += [(r, origin), (None, pr["moment"])]
                acting[first] += [(-r, origin), (None, -pr["moment"])]
            else:
                p = at(second, pin_of(data, first, second))
                acting[second].append((r, p))
                acting[first].append((-r, p))
        for name, terms in acting.items():
            if name == FRAME:
                continue
            x = motion.position(data["links"][name][0], name)[i]
            total_f, total_m, scale = np.zeros(2), 0.0, 0.0
            for force, where in terms:
                if force is None:
                    total_m += where
                    scale = max(scale, abs(where) / size)
                else:
                    total_f += force
                    d = where - x
                    total_m += d[0] * force[1] - d[1] * force[0]
                    scale = max(scale, float(np.linalg.norm(force)))
            if scale > 0.0:
                out.append(max(float(np.linalg.norm(total_f)), abs(total_m) / size) / scale)
    return out


@pytest.mark.parametrize("path", LOADED, ids=lambda p: p.stem)
def test_every_link_of_the_loaded_examples_is_in_equilibrium(path):
    data = data_of(path)
    sheets = render(data)
    worst = max(equilibrium_residuals(data, sheets))
    assert worst < RTOL, worst


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_random_loads_on_every_example_balance_every_link_and_the_power(path):
    data = random_loads(data_of(path), seed=len(path.stem))
    sheets = render(data)
    assert max(equilibrium_residuals(data, sheets)) < RTOL
    mech = sheets.motion.mechanism
    for pos in sheets.report["positions"]:
        f = pos["forces"]
        assert len(f["reactions"]) == len(mech.revolutes) + len(mech.prismatics)   # every pair, the frame's too
        if f["power"] is not None:
            assert f["power_residual"] < RTOL
    forces = sheets.forces
    for g in forces.groups:                  # each group's force polygon closes
        total = sum(t.vector for t in g.terms)
        scale = np.max([np.linalg.norm(t.vector, axis=1) for t in g.terms], axis=0)
        assert np.all(np.linalg.norm(total, axis=1) <= 1e-9 * scale), g.group


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_class_ii_closed_forms_agree_with_the_linear_system(path):
    """The textbook's step-by-step solution of each class II group (R^τ from moments about the
    inner pin, R^n from the polygon) gives the reactions the group's full equilibrium system
    gives."""
    data = random_loads(data_of(path), seed=7)
    scene = parse_scene(data)
    mech = build_mechanism(scene)
    motion = analyse(mech, analyse_structure(mech), order=2)
    a, b = solve_forces(motion, scene), solve_forces(motion, scene, closed_forms=False)
    scale = max(float(np.max(np.linalg.norm(r.force, axis=1))) for r in b.reactions.values())
    for key, r in a.reactions.items():
        assert np.max(np.abs(r.force - b.reactions[key].force)) <= 1e-9 * scale, key
        if r.kind == "P":
            assert np.max(np.abs(r.moment - b.reactions[key].moment)) <= 1e-9 * scale * mech.size, key
    assert np.max(np.abs(a.balance.value - b.balance.value)) <= 1e-9 * np.max(np.abs(b.balance.value)) + 1e-12


def test_power_balance_agrees_over_a_whole_turn_of_the_crank_slider():
    """120 positions of the Fig. 1.29 crank-slider, every 3° of a turn: the balancing force
    found group by group and from the power balance alone agree, and every link is in
    equilibrium."""
    data = data_of(next(p for p in LOADED if p.stem == "crank_slider_forces"))
    data["drive"].update(angle=0.0, positions=120)     # its working force needs the cycle's travel
    data["plans"] = {"draw": ["forces"], "output": "3"}
    sheets = render(data)
    f = sheets.forces
    gbg, power = f.balance.value, f.power
    assert np.max(np.abs(gbg - power)) <= RTOL * np.max(np.abs(gbg))
    assert np.max(f.power_residual) < RTOL
    assert max(equilibrium_residuals(data, sheets)) < RTOL


def test_a_force_on_the_slider_alone_by_virtual_work_and_statics_by_hand():
    """Crank-slider, no masses, a force F on the slider only: the balancing moment is −F·v_B/ω1
    (virtual work); the rod carries no load, so it pushes along AB, and the slider's statics
    give the guide's reaction, which acts at B."""
    data = data_of(next(p for p in EXAMPLES if p.stem == "crank_slider_central"))
    data["drive"]["angle"] = [20.0, 75.0, 160.0, 250.0, 330.0]
    fx, fy = -1000.0, 150.0
    data["forces"] = [{"link": "3", "at": "B", "vector": [fx, fy]}]
    data["plans"] = {"draw": ["velocity", "forces"]}
    sheets = render(data)
    m = sheets.motion
    a, b, o = m.position("A"), m.position("B"), m.position("O")
    v_b = m.velocity("B")
    for i, pos in enumerate(sheets.report["positions"]):
        f = pos["forces"]
        assert f["balance"]["moment"] == pytest.approx(-(fx * v_b[i, 0] + fy * v_b[i, 1]) / 10.0, rel=1e-12)
        e = (b[i] - a[i]) / np.linalg.norm(b[i] - a[i])
        k = -fx / e[0]                              # slider along x: k·e_x + F_x = 0
        r23 = k * e
        guide = -(r23 + np.array([fx, fy]))
        assert f["reactions"]["2-3"] == pytest.approx(list(r23), rel=1e-12)
        assert f["reactions"]["0-3"] == pytest.approx([0.0, guide[1]], abs=1e-9 * abs(k))
        assert f["prismatic"]["0-3"]["offset"] == pytest.approx(0.0, abs=1e-12)   # through the pin B
        r12 = r23                                   # the rod passes the force on unchanged
        arm = a[i] - o[i]
        moment_of_rod_on_crank = arm[0] * -r12[1] - arm[1] * -r12[0]
        assert f["balance"]["moment"] == pytest.approx(-moment_of_rod_on_crank, rel=1e-12)
        assert f["power"]["moment"] == pytest.approx(f["balance"]["moment"], rel=1e-12)


def test_inertia_of_a_crank_at_constant_speed_is_centripetal():
    """A crank with its mass at A (constant ω): F_in = m·ω²·OA outwards along OA; with nothing
    else, the frame takes all of it and the balancing moment is zero."""
    data = data_of(next(p for p in EXAMPLES if p.stem == "crank_slider_central"))
    data["masses"] = {"1": {"mass": 2.0, "centre": "A"}}
    data["plans"] = {"draw": ["forces"]}
    f = render(data).report["positions"][0]["forces"]
    a = np.array([0.070710678, 0.070710678])
    expected = 2.0 * 10.0 ** 2 * 0.1 * a / np.linalg.norm(a)
    assert f["inertia"]["1"]["force"] == pytest.approx(list(expected), rel=1e-6)
    assert f["reactions"]["0-1"] == pytest.approx(list(-expected), rel=1e-6)
    assert f["balance"]["moment"] == pytest.approx(0.0, abs=1e-9)


# --- stages: only what the scene asks for ----------------------------------------------------

def stages_of(data: dict) -> list[str]:
    with record_stages() as stages:
        render(data)
    return list(stages)


def test_each_scene_computes_only_the_stages_it_needs():
    base = data_of(next(p for p in EXAMPLES if p.stem == "crank_slider_central"))
    velocity_only = dict(base, plans={"draw": ["scheme", "velocity"]})
    assert stages_of(velocity_only) == ["positions", "velocities"]
    assert stages_of(dict(base, plans={"draw": ["scheme"]})) == ["positions"]
    assert stages_of(base) == ["positions", "velocities", "accelerations"]
    masses = {"2": {"mass": 2.0, "centre": "C"}}
    # masses alone draw nothing of forces: no force analysis, and no accelerations for them
    assert stages_of(dict(velocity_only, masses=masses)) == ["positions", "velocities"]
    # forces without masses: the power balance needs velocities, nothing needs accelerations
    static = dict(velocity_only, forces=[{"link": "3", "at": "B", "vector": [-100.0, 0.0]}],
                  plans={"draw": ["scheme", "forces"]})
    assert stages_of(static) == ["positions", "velocities", "forces"]
    # a [balance] alone asks for the forces; masses then need accelerations
    balanced = dict(base, plans={"draw": ["scheme"]}, masses=masses, balance={"moment_on": "1"})
    assert stages_of(balanced) == ["positions", "velocities", "accelerations", "forces"]
    for path in LOADED:
        assert stages_of(data_of(path)) == ["positions", "velocities", "accelerations", "forces"]


def test_the_api_refuses_inertia_on_a_motion_without_accelerations():
    """The pipeline always solves to the order the loads need; a motion solved by hand to a
    lower order is refused with one line saying what to do."""
    data = data_of(LOADED[0])
    scene = parse_scene(data)
    mech = build_mechanism(scene)
    motion = analyse(mech, analyse_structure(mech), order=1)
    with pytest.raises(PlansError, match="order=2"):
        solve_forces(motion, scene)


def test_no_forces_in_the_report_unless_asked():
    data = data_of(next(p for p in EXAMPLES if p.stem == "crank_slider_central"))
    data["masses"] = {"2": {"mass": 2.0, "centre": "C"}}
    sheets = render(data)
    assert sheets.forces is None and "forces" not in sheets.report["positions"][0]


def test_a_mechanism_at_rest_has_no_power_balance():
    data = data_of(next(p for p in LOADED if p.stem == "crank_slider_forces"))
    data["drive"]["omega"] = 0.0
    data["drive"]["epsilon"] = 2.0
    f = render(data).report["positions"][0]["forces"]
    assert f["power"] is None and f["power_residual"] is None
    assert f["balance"]["force"] is not None


# --- bad input ----------------------------------------------------------------------------------

def run(argv: list[str]) -> tuple[int, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(argv)
    return code, err.getvalue()


BAD = {
    "a mass without a centre": ({"masses": {"2": {"mass": 2.0}}}, "masses.2.centre", "without a centre"),
    "a centre off the link": ({"masses": {"2": {"mass": 2.0, "centre": "O"}}}, "masses.2.centre", "not a point of"),
    "a negative mass": ({"masses": {"2": {"mass": -1.0, "centre": "C"}}}, "masses.2.mass", "negative"),
    "a negative inertia": ({"masses": {"2": {"inertia": -0.1, "centre": "C"}}}, "masses.2.inertia", "negative"),
    "a NaN mass": ({"masses": {"2": {"mass": math.nan, "centre": "C"}}}, "masses.2.mass", "finite"),
    "a mass on the frame": ({"masses": {"0": {"mass": 1.0, "centre": "O"}}}, "masses.0", "frame"),
    "a force at an unknown point": ({"forces": [{"link": "3", "at": "Q", "vector": [1.0, 0.0]}]}, "forces[0].at",
                                    "unknown point"),
    "a force at a point of another link": ({"forces": [{"link": "3", "at": "A", "vector": [1.0, 0.0]}]},
                                           "forces[0].at", "not a point of that link"),
    "an infinite force": ({"forces": [{"link": "3", "at": "B", "vector": [math.inf, 0.0]}]}, "forces[0].vector",
                          "finite"),
    "a force with no size": ({"forces": [{"link": "3", "at": "B", "angle": 30.0}]}, "forces[0]", "magnitude"),
    "a NaN moment": ({"moments": [{"link": "2", "value": math.nan}]}, "moments[0].value", "finite"),
    "a NaN gravity": ({"gravity": math.nan}, "gravity", "finite"),
    "a balance on another link": ({"balance": {"moment_on": "2"}}, "balance.moment_on", "driving link 1"),
    "a balancing force without its line": ({"balance": {"force_on": "1", "at": "A"}}, "balance.angle", "angle"),
    "a balancing force off the link": ({"balance": {"force_on": "1", "at": "B", "angle": 90.0}}, "balance.at",
                                       "not a point of that link"),
    "a balancing force through the pivot": ({"balance": {"force_on": "1", "at": "A", "angle": 45.0}},
                                            "balance.angle", "cannot balance"),
    "both balancing elements": ({"balance": {"moment_on": "1", "force_on": "1", "at": "A", "angle": 90.0}},
                                "balance", "one balancing element"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_loads_are_one_line_exit_2_and_no_files(tmp_path, case):
    extra, key, words = BAD[case]
    data = data_of(next(p for p in EXAMPLES if p.stem == "crank_slider_central"))
    data.update(extra)
    data["plans"] = {"draw": ["scheme", "forces"]}
    text = toml_text(data)
    scene = tmp_path / "bad.toml"
    scene.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    code, err = run(["render", str(scene), "-o", str(out), "-q"])
    assert code == 2, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and f"[{key}]" in lines[0] and words in lines[0], err
    assert not out.exists()


def test_a_moment_cannot_balance_a_slider_drive():
    data = data_of(next(p for p in EXAMPLES if p.stem == "elliptic_trammel"))
    data["balance"] = {"moment_on": data["drive"]["link"]}
    with pytest.raises(PlansError, match=r"\[balance.moment_on\].*cannot turn"):
        parse_scene(data)


# --- Zhukovsky's lever: the third figure ---------------------------------------------------------

def _three_figures(sheets) -> tuple[float, float]:
    """The largest differences, relative to the largest |balancing figure|, of the lever's and
    the power balance's figures from the group-by-group one, at every position of ``sheets``."""
    from plans.constructions import velocity_plan
    from plans.constructions.kinetostatics import lever

    f = sheets.forces
    gbg = f.balance.value
    ref = float(np.max(np.abs(gbg)))
    levers = []
    for i in range(len(sheets.motion)):
        result = lever(sheets.motion, f, i, velocity_plan(sheets.motion, i, sheets.scales.mu_v))
        levers.append(abs(result.result - gbg[i]))
    power = float(np.max(np.abs(f.power - gbg))) if f.power is not None else 0.0
    return max(levers, default=0.0) / ref, power / ref


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_lever_power_and_groups_agree_on_every_example(path):
    """Random loads on every example (all class II forms, class III/IV, the drives): the
    balancing figure read off Zhukovsky's lever (moments about the pole of the turned velocity
    plan), the power balance and the group-by-group analysis agree to 1e-9 at every position."""
    data = random_loads(data_of(path), seed=3)
    data["plans"]["draw"] = sorted(set(data["plans"].get("draw", [])) | {"velocity", "forces"})
    sheets = render(data)
    if sheets.forces.power is None:
        pytest.skip("no lever: the drive stands")
    lever_diff, power_diff = _three_figures(sheets)
    assert lever_diff < RTOL and power_diff < RTOL


def test_lever_agrees_over_a_whole_turn_of_the_crank_slider():
    """Every 3° of a turn (120 lever sheets): lever, groups and power balance agree."""
    data = data_of(next(p for p in LOADED if p.stem == "crank_slider_forces"))
    data["drive"].update(angle=0.0, positions=120)     # its working force needs the cycle's travel
    data["plans"] = {"draw": ["velocity", "forces"], "output": "3"}
    lever_diff, power_diff = _three_figures(render(data))
    assert lever_diff < RTOL and power_diff < RTOL


def test_the_report_gives_the_three_figures_and_their_agreement():
    sheets = render(data_of(next(p for p in LOADED if p.stem == "crank_slider_forces")))
    for pos in sheets.report["positions"]:
        f = pos["forces"]
        assert f["lever"]["value"] == pytest.approx(f["balance"]["value"], rel=RTOL)
        assert f["power"]["value"] == pytest.approx(f["balance"]["value"], rel=RTOL)
        assert f["agreement"]["lever"] < RTOL and f["agreement"]["power"] < RTOL
    assert any(s.name.startswith("lever") for s in sheets) and any(s.name.startswith("forces") for s in sheets)

"""plans handout on every kind of assignment beyond linkage kinematics: a loaded scene (the
reactions and the balancing moment; the key holds the force plans and the lever), a gear train
(the speeds and the ratio; the key holds the velocity pictures) and a machine's dynamics (the
flywheel; the key holds the dynamics sheet). The keys must pass plans check, the assignment
sheets the layout measurer, and the asked values agree with closed forms written here."""

from __future__ import annotations

import json
import math
import re
import tomllib
from fractions import Fraction
from pathlib import Path

import pytest

from plans.checking import inspect_svg
from plans.cli import main
from plans.handout import asked, kind_of, random_variants, variant_asked
from plans.layout import measure_layout
from plans.scene import parse_scene

from conftest import refused_handout as _refused

ROOT = Path(__file__).resolve().parent.parent
EX = ROOT / "examples"
KINDS = {"forces": EX / "six_link_press_forces.toml", "gears": EX / "gears" / "planetary_1_21.toml",
         "dynamics": EX / "six_link_press_flywheel.toml"}
#: What a key of each kind must hold (sheet names) and what the assignment's task names.
KEY_SHEETS = {"forces": ("forces", "lever"), "gears": ("gears",), "dynamics": ("dynamics",)}
TASK_WORDS = {"forces": ("reactions", "balancing moment", "Zhukovsky"), "gears": ("velocity pictures", "Willis"),
              "dynamics": ("flywheel", "Wittenbauer")}


def _handout(out: Path, *args: str) -> Path:
    assert main(["handout", *args, "-o", str(out), "-q"]) == 0
    return out


@pytest.fixture(scope="module", params=list(KINDS))
def made(request, tmp_path_factory):
    kind = request.param
    out = _handout(tmp_path_factory.mktemp(kind) / "out", str(KINDS[kind]), "--random", "2", "--seed", "3")
    return kind, out


def test_the_kind_is_told_by_the_base_scene():
    for kind, path in KINDS.items():
        assert kind_of(parse_scene(tomllib.loads(path.read_text(encoding="utf-8")))) == kind
    assert kind_of(parse_scene(tomllib.loads((EX / "four_bar.toml").read_text(encoding="utf-8")))) == "kinematics"


def test_every_key_sheet_passes_plans_check(made):
    kind, out = made
    svgs = sorted(out.glob("variant-*/*.svg"))
    keys = [p for p in svgs if not re.search(r"-assignment(-\d+)?\.svg$", p.name)]   # its answer sheets: not keys
    for name in KEY_SHEETS[kind]:
        assert any(f"-{name}" in p.name for p in keys), (kind, name, [p.name for p in keys])
    for p in keys:
        report = inspect_svg(p)
        assert report.ok, (p.name, report.problems[:3])
    assert main(["check", *map(str, keys)]) == 0


def test_assignment_sheet_asks_the_kinds_quantities_and_is_clean(made):
    kind, out = made
    for p in sorted(out.glob("variant-*/*-assignment.svg")):
        text = p.read_text(encoding="utf-8")
        assert 'data-sheet="assignment"' in text
        flat = " ".join(text.replace("<tspan", " <tspan").split())
        words = "".join(ch for ch in flat)
        for w in TASK_WORDS[kind]:
            assert w in words, (p.name, w)
        assert measure_layout(text).clean, measure_layout(text)
        assert "data-quantity" not in text          # the answers are not on the assignment


def test_index_lists_the_asked_values(made):
    kind, out = made
    page = (out / "index.html").read_text(encoding="utf-8")
    for folder in sorted(out.glob("variant-*")):
        report = json.loads((folder / f"{folder.name}.json").read_text(encoding="utf-8"))
        scene = parse_scene(tomllib.loads((folder / f"{folder.name}.toml").read_text(encoding="utf-8")))
        for a in asked(scene, report):
            assert f'<td class="n">{a.value:.6g}</td>' in page


def test_variants_file_written_by_a_handout_gives_the_same_keys(made, tmp_path):
    kind, out = made
    again = _handout(tmp_path / "again", str(out / "variants.toml"))
    for j in sorted(out.glob("variant-*/*.json")):
        assert (again / j.parent.name / j.name).read_bytes() == j.read_bytes()


def test_planetary_speeds_match_willis_for_the_drawn_teeth():
    h, drawn = random_variants(KINDS["gears"], 12, 21)
    for d in drawn:
        z = {w.name: w.teeth for w in d.scene.gears.wheels}
        n1 = Fraction(dict(d.scene.gears.inputs)["1"]).limit_denominator()
        nh = n1 * z["1"] / (z["1"] + z["3"])
        got = {a.symbol: a.value for a in variant_asked(d)}
        assert math.isclose(got["n_{H}"], float(nh), rel_tol=1e-12)
        assert math.isclose(got["n_{2}"], float(nh - Fraction(z["1"], z["2"]) * (n1 - nh)), rel_tol=1e-12)
        assert math.isclose(got["i_{1H}"], 1 + z["3"] / z["1"], rel_tol=1e-12)


def test_compound_and_type_b_trains_keep_their_conditions():
    h, drawn = random_variants(EX / "gears" / "gear_compound_1_17.toml", 8, 2)
    for d in drawn:
        z = {w.name: w.teeth for w in d.scene.gears.wheels}
        i16 = -(z["2"] / z["1"]) * (z["4"] / z["3"]) * (z["6"] / z["5"])
        got = {a.symbol: a.value for a in variant_asked(d)}
        assert math.isclose(got["i_{16}"], i16, rel_tol=1e-12) and min(z.values()) >= 17
    h, drawn = random_variants(EX / "gears" / "planetary_type_b.toml", 8, 2)
    for d in drawn:
        z = {w.name: w.teeth for w in d.scene.gears.wheels}
        assert z["a"] + z["g"] == z["b"] - z["g2"]                           # coaxial, one module
        k = 3
        assert (z["a"] * z["g2"] + z["b"] * z["g"]) % (k * math.gcd(z["g"], z["g2"])) == 0   # assembly
        got = {a.symbol: a.value for a in variant_asked(d)}
        assert math.isclose(got["i_{aH}"], 1 + z["g"] * z["b"] / (z["a"] * z["g2"]), rel_tol=1e-12)


def test_dynamics_variants_keep_the_cycle_and_vary_lengths_and_speed():
    h, drawn = random_variants(KINDS["dynamics"], 4, 9)
    assert h.kind == "dynamics"
    for d in drawn:
        assert d.variant.values is None                     # the cycle starts at the output's extreme
        r = d.sheets.report
        assert r["cycle"]["start"] == "extreme" and len(r["positions"]) == 12
        dyn = r["cycle"]["dynamics"]
        assert math.isclose(dyn["omega_mean"], d.scene.drive.speed, rel_tol=1e-12)
        j = next(a.exact for a in variant_asked(d) if a.symbol == "J_{fw}")    # marked: the chords' (its own test)
        assert j == dyn["flywheel"]["required"] and math.isclose(j, dyn["flywheel"]["inertia_wittenbauer"],
                                                                   rel_tol=1e-3)
    assert len({d.scene.drive.speed for d in drawn}) > 1


def test_forces_asked_balance_agrees_with_the_lever_and_power():
    h, drawn = random_variants(KINDS["forces"], 4, 9)
    for d in drawn:
        f = d.sheets.report["positions"][0]["forces"]
        mb = next(a.value for a in variant_asked(d) if a.symbol == "M_{b}")
        assert math.isclose(mb, f["lever"]["moment"], rel_tol=1e-9)
        assert math.isclose(mb, f["power"]["moment"], rel_tol=1e-9)
        reactions = [a for a in variant_asked(d) if a.symbol.startswith("R_")]
        assert len(reactions) == len(f["reactions"])


@pytest.mark.parametrize("variant, words", [
    ('teeth = { "7" = 20 }', "unknown wheel '7'"),
    ('teeth = { "1" = 20.5 }', "positive whole number"),
    ('teeth = { "1" = 0 }', "positive whole number"),
    ('input = { "2" = 100.0 }', "unknown input '2'"),
    ('input = { "1" = "fast" }', "must be a number"),
    ('lengths = { OA = 0.1 }', "unknown key 'lengths'"),
    ('teeth = { "1" = 20 }', "coaxial"),
])
def test_bad_gear_variants_are_refused_in_one_line(tmp_path, variant, words):
    base = tmp_path / "train.toml"
    base.write_text(KINDS["gears"].read_text(encoding="utf-8"), encoding="utf-8")
    (tmp_path / "class.toml").write_text(f'base = "train.toml"\n\n[[variant]]\n{variant}\n', encoding="utf-8")
    line = _refused(tmp_path, str(tmp_path / "class.toml"))
    assert words in line and "class.toml" in line, line


@pytest.mark.parametrize("scene, words", [
    ("gears/synthesis_type_c.toml", "[synthesis]"),
    ("gears/pair_balanced.toml", "involute pair alone"),
])
def test_scenes_without_a_handout_are_refused(tmp_path, scene, words):
    line = _refused(tmp_path, str(EX / scene), "--random", "2")
    assert words in line, line


def test_a_laws_corners_give_the_same_law():
    """The task text writes a load law by its corners only: read linearly between them, it is
    the scene's law at every travel (np.interp as the reader), and a flat run is two points."""
    import numpy as np

    from plans.handout.assignment import law_corners

    rng = np.random.default_rng(20)
    for _ in range(200):
        n = int(rng.integers(2, 40))
        x = np.cumsum(rng.uniform(0.001, 0.02, n)) - 0.001
        x[0] = 0.0
        F = rng.choice([0.0, 3015.9, -120.0], n)                  # flat runs of repeated values
        ramp = rng.random(n) < 0.3
        F[ramp] = rng.uniform(-5e3, 5e3, int(ramp.sum()))
        law = tuple(zip(x.tolist(), F.tolist()))
        kept = law_corners(law)
        assert kept[0] == law[0] and kept[-1] == law[-1] and set(kept) <= set(law)
        kx, kF = np.array(kept).T
        probe = np.linspace(0.0, x[-1], 997)
        assert np.allclose(np.interp(probe, kx, kF), np.interp(probe, x, F), rtol=0, atol=1e-6 * max(1.0, abs(F).max()))
        # and no point is kept that its kept neighbours' line passes through
        for k in range(1, len(kept) - 1):
            (x0, f0), (xk, fk), (x1, f1) = kept[k - 1], kept[k], kept[k + 1]
            assert abs(f0 + (f1 - f0) * (xk - x0) / (x1 - x0) - fk) > 1e-12 * max(1.0, abs(F).max())
    flat = tuple((0.01 * k, 3015.9) for k in range(11))
    assert law_corners(flat) == (flat[0], flat[-1])
    assert law_corners(((0.0, 1.0), (0.1, 5.0))) == ((0.0, 1.0), (0.1, 5.0))


#: A working force whose physics drives its slider on one stroke, exempt from the rule below:
#: the compressor's re-expansion law (its indicator diagram: the gas left in the clearance pushes
#: the piston away from the head as it re-expands, before the suction valve opens).
DRIVES_BY_PHYSICS = {("compressor_flywheel", 1)}


def _working_forces(path: Path):
    """The scene of ``path`` solved at its own positions, and each force on a link that slides on
    the frame (a ram, a slider, a piston: its working force) with its (N, 2) values there, the
    velocity of its point, and the guide's direction."""
    import numpy as np

    from plans.kinetostatics.loads import external_force
    from plans.pipeline.stages import output_travel, solve_motion

    scene = parse_scene(tomllib.loads(path.read_text(encoding="utf-8")))
    motion, cycle = solve_motion(scene)
    travel = output_travel(scene, cycle)
    guides = {s.link: s for s in scene.sliders if s.on == "0"}
    out = []
    for k, f in enumerate(scene.forces):
        if f.link in guides:
            u = motion.mechanism.prismatics[guides[f.link].index].direction
            out.append((k, f, external_force(f, motion, travel), motion.velocity(f.at, f.link), np.asarray(u)))
    return scene, out


def test_every_loaded_examples_working_force_resists_its_working_stroke_only():
    """The rule: a working (technological) force on a slider never drives it — F·v ≤ 0 at every
    analysed position (1e-9 of |F|·max|v|: a slider at rest does no work) — and acts on one
    stroke only: wherever it is not 0 and the slider moves, the slider moves the same way along
    its guide (the stroke it works on; on the other it is 0). Every example with a force on a
    link sliding on the frame is checked (class3_forces has none: its 300 N loads the class III
    group's triangle, no ram); a force whose physics drives (DRIVES_BY_PHYSICS) is left out."""
    import numpy as np

    checked = set()
    for path in sorted(EX.glob("*.toml")):
        if "[[forces]]" not in path.read_text(encoding="utf-8"):
            continue
        scene, forces = _working_forces(path)
        for k, f, F, v, u in forces:
            if (path.stem, k) in DRIVES_BY_PHYSICS:
                continue
            checked.add(path.stem)
            power = np.einsum("ij,ij->i", F, v)
            size = np.hypot(F[:, 0], F[:, 1])
            vmax = float(np.max(np.hypot(v[:, 0], v[:, 1])))
            assert np.all(power <= 1e-9 * size * vmax), (path.stem, k, power)
            along = v @ u
            moving = (size > 0.0) & (np.abs(along) > 1e-9 * vmax)
            assert len(set(np.sign(along[moving]))) == 1, (path.stem, k, along[moving])
            assert np.any(size == 0.0), (path.stem, k, "acts on both strokes")
    assert checked >= {"six_link_press_forces", "six_link_press_flywheel", "six_link_press_startup",
                       "crank_slider_forces", "compressor_flywheel", "shaper_flywheel"}, checked


def test_forces_handout_variants_have_their_working_force_on_its_stroke():
    """A forces handout's variants are drawn at a position of the working stroke: the working
    force acts there (not 0) and resists the ram (F·v < 0), as the lever's M_b then shows."""
    import numpy as np

    h, drawn = random_variants(KINDS["forces"], 4, 11)
    for d in drawn:
        f = next(f for f in d.scene.forces if f.link == "5")
        load = [x for x in d.sheets.forces.loads if x.kind == "external"][d.scene.forces.index(f)]
        F, v = load.force[0], d.sheets.motion.velocity("E", "5")[0]
        assert np.hypot(*F) == 4000.0 and float(F @ v) < 0.0, (d.name, F, v)

"""plans handout's random draws and what a variant asks: every link keeps its shape (a point on a
bar's line in the base stays on it, at the same ratio), nothing at rounding level is asked, a
variant with nothing to find is refused in one line, a train-driven crank leaves ω to the train,
and a speed too small to draw around is refused naming the file, the key and the fix."""

from __future__ import annotations

import itertools
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

import plans
from plans.handout import asked, random_variants, read_base, solve_variant, variant_asked
from plans.handout.asked import ZERO
from plans.handout.variants import Variant
from plans.model import build_mechanism
from plans.scene import parse_scene

from conftest import refused_handout as _refused

ROOT = Path(__file__).resolve().parent.parent
EX = ROOT / "plans" / "examples"
#: Every example with a linkage whose lengths a random handout draws (the gears folder's press
#: drive: a crank turned by a train).
LINKAGES = sorted(EX.glob("*.toml")) + [EX / "gears" / "press_drive.toml"]
#: A point is on the line of two others of its link within this × the link's size (the brief's bound).
ON_LINE = 1e-9


def _data(path: Path) -> dict:
    return tomllib.loads(path.read_text(encoding="utf-8"))


def _size(local: dict, pts: tuple[str, ...]) -> float:
    return max((math.dist(local[a], local[b]) for a, b in itertools.combinations(pts, 2)), default=0.0)


def _off_line(local: dict, a: str, b: str, c: str) -> float:
    """Distance (m) of point c from the line through a and b."""
    (ax, ay), (bx, by), (cx, cy) = local[a], local[b], local[c]
    return abs((bx - ax) * (cy - ay) - (by - ay) * (cx - ax)) / math.dist(local[a], local[b])


def _on_lines(mech) -> list[tuple[str, str, str, str]]:
    """(link, a, b, c): point c on the line of a and b of the same link, in ``mech``."""
    out = []
    for name, link in mech.links.items():
        size = _size(link.local, link.points)
        for a, b in itertools.combinations(link.points, 2):
            for c in link.points:
                if c not in (a, b) and _off_line(link.local, a, b, c) <= ON_LINE * size:
                    out.append((name, a, b, c))
    return out


def _variant_mechanism(base: dict, lengths: dict):
    data = dict(base, lengths={**base.get("lengths", {}), **lengths})
    return build_mechanism(parse_scene(data))


@pytest.mark.parametrize("path", LINKAGES, ids=lambda p: p.stem)
def test_random_lengths_keep_every_point_on_its_links_line(path):
    """Eight draws of every example's random handout (the lengths as --random draws them, before
    any solving): a point on the line of two others of its link in the base is on it in every
    draw (within 1e-9 of the link's size), at the same place along it (AS/AB as the base's)."""
    from plans.handout.draws import _draw, length_plan

    h = read_base(path)
    base = build_mechanism(parse_scene(h.base_data))
    lines = _on_lines(base)
    rng = np.random.default_rng(5)
    plan = length_plan(h)
    built = 0
    for k in range(8):
        v = _draw(h, rng, k + 1, plan)
        try:
            mech = _variant_mechanism(h.base_data, dict(v.lengths))
        except plans.SceneError:
            continue                    # lengths that form no link: the handout draws again
        built += 1
        for link, a, b, c in lines:
            local, pts = mech.links[link].local, mech.links[link].points
            assert _off_line(local, a, b, c) <= ON_LINE * _size(local, pts), (link, a, b, c, v.lengths)
            ratio = math.dist(local[a], local[c]) / math.dist(local[a], local[b])
            was = math.dist(base.links[link].local[a], base.links[link].local[c]) / \
                math.dist(base.links[link].local[a], base.links[link].local[b])
            if {frozenset((a, c)), frozenset((a, b))} <= set(parse_scene(h.base_data).lengths):
                assert math.isclose(ratio, was, rel_tol=1e-12), (link, a, b, c, ratio, was)
    assert built >= 2


@pytest.mark.parametrize("stem, centres", [
    ("six_link_press_forces", {"2": ("A", "B", "S2"), "3": ("D", "B", "S3"), "4": ("C", "E", "S4")}),
    ("crank_slider_forces", {"1": ("O", "A", "S1")}),
])
def test_random_variants_keep_the_centres_of_mass_on_their_bars(stem, centres):
    """The drawn variants of the loaded examples: each centre of mass stays the middle of its bar
    (AS2 = BS2 = AB/2, as in the base) at the asked position, where its inertia force acts."""
    h, drawn = random_variants(EX / f"{stem}.toml", 2, 4)
    for d in drawn:
        pos = d.sheets.report["positions"][0]["points"]
        for link, (a, b, s) in centres.items():
            ra, rb, rs = (np.array(pos[p]["r"]) for p in (a, b, s))
            assert np.linalg.norm(rs - (ra + rb) / 2.0) <= ON_LINE * np.linalg.norm(rb - ra), (d.name, link, s)
        mass = d.scene.masses
        for link, (a, b, s) in centres.items():
            assert mass[link].centre == s


def _loaded_crank_slider(angle: float) -> dict:
    """The central crank-slider loaded by 500 N on its slider (no weights), the balancing
    moment on the crank: at 0° and 180° the slider stands and M_b is 0 exactly."""
    data = _data(EX / "crank_slider_central.toml")
    data["drive"]["angle"] = angle
    data["masses"] = {"3": {"mass": 2.0, "centre": "B"}}
    data["forces"] = [{"link": "3", "at": "B", "vector": [-500.0, 0.0]}]
    data["balance"] = {"moment_on": "1"}
    data["plans"] = {"draw": ["scheme", "velocity", "acceleration", "forces", "lever"]}
    return data


def test_a_rounding_zero_balancing_moment_is_not_asked():
    """At the dead centres the computed M_b is ~1e-15 N·m; beside its scale (the largest |R|
    times the mechanism's size, ~240 N·m) that is an exact zero: not asked. At 45° it is."""
    for angle in (0.0, 180.0):
        scene = parse_scene(_loaded_crank_slider(angle))
        report = plans.render(scene).report
        mb = report["positions"][0]["forces"]["balance"]["moment"]
        assert abs(mb) < 1e-13                              # the rounding the old code asked
        symbols = [a.symbol for a in asked(scene, report)]
        assert "M_{b}" not in symbols and symbols, symbols
    scene = parse_scene(_loaded_crank_slider(45.0))
    report = plans.render(scene).report
    got = {a.symbol: a.value for a in asked(scene, report)}
    assert got["M_{b}"] == report["positions"][0]["forces"]["balance"]["moment"] and abs(got["M_{b}"]) > 1.0


def test_a_variant_whose_balancing_moment_is_zero_is_refused_in_one_line(tmp_path):
    """A variants file setting the dead centre: its task (find M_b) has no answer; refused in one
    line naming the variant, with the fix."""
    base = tmp_path / "loaded.toml"
    from conftest import toml_text
    base.write_text(toml_text(_loaded_crank_slider(45.0)), encoding="utf-8")
    (tmp_path / "class.toml").write_text('base = "loaded.toml"\n[[variant]]\nangle = 0.0\n', encoding="utf-8")
    line = _refused(tmp_path, str(tmp_path / "class.toml"))
    assert "[variant[0]]" in line and "balancing moment M_b is 0" in line and "another angle" in line, line


def test_rounding_level_angular_rates_are_not_asked():
    """The central crank-slider at 0° and 270°: ε2 (2e-16 rad/s²) and ω2 (4e-16 rad/s) are
    zeros beside the crank's ω1 = 10 rad/s, ω1² = 100 rad/s², though the largest of the asked
    links' own (they are the only one asked)."""
    data = _data(EX / "crank_slider_central.toml")
    for angle, symbol in ((0.0, "ε_{2}"), (270.0, "ω_{2}")):
        data["drive"]["angle"] = angle
        scene = parse_scene(data)
        report = plans.render(scene).report
        link = report["positions"][0]["links"]["2"]
        value = abs(link["epsilon" if symbol.startswith("ε") else "omega"])
        assert 0.0 < value < 1e-14
        assert symbol not in [a.symbol for a in asked(scene, report)]


def test_a_machine_loaded_by_weights_does_not_ask_its_zero_driving_moment():
    """Weights do no work over a cycle: M_d is ~6e-16 N·m beside a reduced moment of ~10 N·m;
    not asked; the flywheel's J still is."""
    data = _data(EX / "six_link_press_flywheel.toml")
    data.pop("forces")
    scene = parse_scene(data)
    report = plans.render(scene).report
    dyn = report["cycle"]["dynamics"]
    assert abs(dyn["constant_moment"]) <= ZERO * max(abs(m) for m in dyn["reduced_moment"])
    got = {a.symbol: a.exact for a in asked(scene, report)}     # the exact values (marked: the chords')
    assert "M_{d}" not in got and got["J_{fw}"] == dyn["flywheel"]["required"] > 0.0


def test_a_rounding_zero_speed_of_a_train_is_not_asked():
    """The differential with n3 = −n1/4: its carrier stands (n_H = (z1·n1 + z3·n3)/(z1 + z3) = 0),
    computed −8e-15 rpm; beside the inputs' 1595 rpm that is an exact zero, not asked."""
    data = _data(EX / "gears" / "differential_1_21.toml")
    data["gears"]["input"] = {"1": 1450.0 * 1.1, "3": -1450.0 * 1.1 / 4}
    scene = parse_scene(data)
    report = plans.render(scene).report
    assert 0.0 < abs(report["gears"]["speeds"]["H"]["rpm"]) < 1e-12
    got = {a.symbol: a.value for a in asked(scene, report)}
    assert "n_{H}" not in got and math.isclose(got["n_{2}"], report["gears"]["speeds"]["2"]["rpm"])


def _with(tmp_path: Path, source: Path, old: str, new: str) -> Path:
    text = source.read_text(encoding="utf-8")
    assert old in text
    path = tmp_path / source.name
    path.write_text(text.replace(old, new), encoding="utf-8")
    return path


@pytest.mark.parametrize("source, old, new, key", [
    (EX / "gears" / "planetary_1_21.toml", '"1" = 1450.0', '"1" = 0.0', "[gears.input.1]"),
    (EX / "four_bar.toml", "omega = 10.0", "omega = 0.0", "[drive.omega]"),
])
def test_a_base_at_rest_is_refused_in_one_line(tmp_path, source, old, new, key):
    """A train whose input stands, a linkage with ω = ε = 0: every variant would have nothing
    to find (the draws keep a zero speed zero): refused at once, naming the file and the key."""
    line = _refused(tmp_path, str(_with(tmp_path, source, old, new)), "--random", "2")
    assert source.name in line and key in line and "nothing to find" in line and "nonzero" in line, line


def test_a_variant_at_rest_is_refused_in_one_line(tmp_path):
    base = _with(tmp_path, EX / "four_bar.toml", "omega = 10.0", "omega = 10.0")
    (tmp_path / "class.toml").write_text(f'base = "{base.name}"\n[[variant]]\nomega = 2.0\n[[variant]]\nomega = 0.0\n',
                                         encoding="utf-8")
    line = _refused(tmp_path, str(tmp_path / "class.toml"))
    assert "[variant[1]]" in line and "variant-02" in line and "nothing to find" in line and "omega" in line, line


def test_a_train_driven_crank_draws_its_variants_leaving_omega_to_the_train():
    h, drawn = random_variants(EX / "gears" / "press_drive.toml", 2, 0)
    base_omega = plans.render(EX / "gears" / "press_drive.toml").report["positions"][0]["links"]["1"]["omega"]
    for d in drawn:
        assert d.variant.speed is None and d.variant.lengths
        assert d.sheets.report["positions"][0]["links"]["1"]["omega"] == base_omega


@pytest.mark.parametrize("rpm, words", [
    ("5e-324", ["too small to draw around", "at least 1e-09 rpm"]),
    ("1e-300", ["too small to draw around", "at least 1e-09 rpm"]),
    ("1e308", ["out of range"]),
])
def test_a_train_input_beyond_what_can_be_drawn_is_one_line(tmp_path, rpm, words):
    path = _with(tmp_path, EX / "gears" / "planetary_1_21.toml", '"1" = 1450.0', f'"1" = {rpm}')
    line = _refused(tmp_path, str(path), "--random", "1")
    assert "planetary_1_21.toml" in line and "[gears.input.1]" in line, line
    for w in words:
        assert w in line, line


def test_a_shape_changing_variant_is_refused_naming_the_point(tmp_path):
    """A variants file that shortens the press's AB alone lifts S2 off AB (AS2 = BS2 = 0.175 m,
    AB = 0.34 m: 42 mm off): refused in one line, naming the points and the link; in proportion,
    AB = 0.34 m with AS2 = BS2 = 0.17 m, the variant is made."""
    import shutil

    shutil.copy(EX / "six_link_press_forces.toml", tmp_path / "press.toml")
    (tmp_path / "class.toml").write_text('base = "press.toml"\n[[variant]]\nlengths = { AB = 0.34 }\n',
                                         encoding="utf-8")
    line = _refused(tmp_path, str(tmp_path / "class.toml"))
    assert "[variant[0].lengths]" in line and "A, B and S2 of link 2" in line and "off it" in line, line
    h = read_base(tmp_path / "press.toml")
    d = solve_variant(h, Variant(1, lengths={"AB": 0.34, "AS2": 0.17, "BS2": 0.17}, values=(240.0,)))
    assert d.scene.lengths[frozenset(("A", "B"))] == 0.34 and variant_asked(d)

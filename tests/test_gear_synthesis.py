"""Planetary synthesis: every candidate printed for ratios 4, 7.5, 12, 25 and 60 with three
planets meets the four conditions, checked here independently of plans.gears:

- coaxial: the two meshes give one arm (pitch radii in modules);
- assembly: each planet j at 2πj/k can be turned so that both its wheels mesh, found by trying
  every tooth position of the planet in exact fractions of a turn (no formula);
- neighbourhood: adjacent planets' tip circles do not touch;
- no undercut: external wheels have at least 17 teeth (standard, α = 20°);

and its ratio, recomputed from the teeth by Willis' formula, is within the tolerance."""

from __future__ import annotations

import math
from fractions import Fraction

import pytest

from plans.gears.synthesis import synthesize

from conftest import plans_cli

K = 3
RATIOS = (4, 7.5, 12, 25, 60)


def _scheme(kind: str, teeth: dict[str, int]):
    """(central 1, planet wheel on it, planet wheel on central 2, central 2, internal 1, internal 2)."""
    if kind == "A":
        return teeth["a"], teeth["g"], teeth["g"], teeth["b"], False, True
    if kind == "C":
        return teeth["b1"], teeth["g"], teeth["g2"], teeth["b2"], True, True
    return teeth["a"], teeth["g"], teeth["g2"], teeth["b"], False, kind == "B"


def _mesh_phase(z_c: int, z_p: int, internal: bool, psi: Fraction, beta: Fraction) -> Fraction:
    """The meshing condition's left side, in turns (mod 1): the central wheel's tooth phase at the
    contact point plus (external) or minus (internal) the planet's, the planet turned by ``beta``."""
    if internal:            # the contact is outward from the planet, at angle psi from its centre
        return (z_c * psi - z_p * (psi - beta)) % 1
    return (z_c * psi + z_p * (psi + Fraction(1, 2) - beta)) % 1


def _assembles(kind: str, teeth: dict[str, int], k: int) -> bool:
    """Planet 0 meshes (its phases define the constants); every other planet must find a turn β of
    its own (same planet: the two wheels keep their relative phase) meeting both constants."""
    z1, zg, zg2, z2, int1, int2 = _scheme(kind, teeth)
    c1 = _mesh_phase(z1, zg, int1, Fraction(0), Fraction(0))
    c2 = _mesh_phase(z2, zg2, int2, Fraction(0), Fraction(0))
    for j in range(1, k):
        psi = Fraction(j, k)
        ok = False
        # the first mesh's phase is linear in β with slope ∓z_g: its solutions are z_g turns apart
        slope = zg if int1 else -zg
        a0 = _mesh_phase(z1, zg, int1, psi, Fraction(0))
        for n in range(abs(slope)):
            beta = (c1 - a0 + n) / slope
            assert _mesh_phase(z1, zg, int1, psi, beta) == c1
            if _mesh_phase(z2, zg2, int2, psi, beta) == c2:
                ok = True
                break
        if not ok:
            return False
    return True


def _independent_ratio(kind: str, teeth: dict[str, int]) -> Fraction:
    z1, zg, zg2, z2, int1, int2 = _scheme(kind, teeth)
    s1 = 1 if int1 else -1
    s2 = 1 if int2 else -1
    i12h = Fraction(s1 * zg, z1) * Fraction(s2 * z2, zg2)       # (n1 − nH)/(n2 − nH), central 2 fixed
    n1_over_nh = 1 - i12h
    return n1_over_nh if kind in ("A", "B") else 1 / n1_over_nh


@pytest.mark.parametrize("ratio", RATIOS)
@pytest.mark.parametrize("kind", "ABCD")
def test_every_candidate_meets_the_four_conditions(kind, ratio):
    found = synthesize(ratio, kind, K)
    for c in found:
        z1, zg, zg2, z2, int1, int2 = _scheme(kind, c.teeth)
        arm1 = (z1 - zg) if int1 else (z1 + zg)
        arm2 = (z2 - zg2) if int2 else (z2 + zg2)
        assert arm1 == arm2, c.teeth                                  # coaxial (in modules × 2)
        assert _assembles(kind, c.teeth, K), c.teeth
        assert arm1 * math.sin(math.pi / K) > max(zg, zg2) + 2, c.teeth   # tips of neighbours apart
        external = [z for z, inner in ((z1, int1), (zg, False), (zg2, False), (z2, int2)) if not inner]
        assert min(external) >= 17, c.teeth
        exact = _independent_ratio(kind, c.teeth)
        assert exact == c.ratio and abs(float(exact) - ratio) <= 0.01 * ratio
    sizes = [c.size for c in found]
    assert sizes == sorted(sizes)


def test_the_assembly_check_here_can_fail():
    # 16 + 72 = 88 is not a multiple of 3: the third planet cannot be put in
    assert not _assembles("A", {"a": 16, "g": 28, "b": 72}, 3)
    assert _assembles("A", {"a": 18, "g": 27, "b": 72}, 3)


def test_reachable_types_find_candidates_and_the_others_say_so(tmp_path):
    assert synthesize(60, "C", K) and not synthesize(60, "A", K)
    r = plans_cli(["gears", "synthesize", "--ratio", "60", "--type", "A", "--planets", "3", "-o", tmp_path / "out"])
    assert r.returncode == 0 and "cannot reach" in r.stdout
    assert not (tmp_path / "out").exists()


def test_the_best_is_drawn_and_checked(tmp_path):
    out = tmp_path / "out"
    r = plans_cli(["gears", "synthesize", "--ratio", "12", "--type", "B", "--planets", "3", "--module", "2", "-o", out])
    assert r.returncode == 0, r.stderr
    svg = out / "synthesis_B_12-gears.svg"
    assert svg.exists()
    c = plans_cli(["check", svg])
    assert c.returncode == 0, c.stdout


@pytest.mark.parametrize("args, words", [
    (["--ratio", "x"], "[--ratio]"), (["--ratio", "0.5"], "beyond ±1"), (["--type", "E"], "unknown scheme"),
    (["--planets", "1"], "[--planets]"), (["--planets", "2.5"], "whole number"),
    (["--tolerance", "5"], "[--tolerance]"), (["--module", "nan"], "[--module]")])
def test_bad_options_are_one_line(args, words, tmp_path):
    base = {"--ratio": "7.5", "--type": "B", "--planets": "3"}
    for k in range(0, len(args), 2):
        base[args[k]] = args[k + 1]
    cmd = ["gears", "synthesize", "-o", str(tmp_path / "o")]
    for k, v in base.items():
        cmd += [k, v]
    r = plans_cli(cmd)
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and words in r.stderr, r.stderr
    assert not (tmp_path / "o").exists()


def test_the_trains_assembly_condition_agrees_with_trying_every_planet_turn():
    """plans.gears' assembly number is whole exactly when the planets go in, over many trains of
    types B and C (compound planets), both outcomes represented."""
    import random

    from plans.gears import assembly_number, train_structure
    from plans.gears.synthesis import _train

    rng = random.Random(7)
    seen = set()
    for _ in range(300):
        kind = rng.choice("BC")
        g, g2 = rng.randint(17, 40), rng.randint(17, 40)
        first = rng.randint(17, 40) if kind == "B" else rng.randint(max(g, g2) + 8, 90)
        second = first + g + g2 if kind == "B" else first - g + g2
        if kind == "C" and second - g2 < 8:
            continue
        k = rng.choice((2, 3, 4, 5))
        z = (first, g, g2, second)
        train = _train(kind, z, k, 1.0)
        number = assembly_number(train_structure(train), "H")
        teeth = {w.name: w.teeth for w in train.wheels}
        whole = number.denominator == 1
        assert whole == _assembles(kind, teeth, k), (kind, z, k, number)
        seen.add(whole)
    assert seen == {True, False}


def test_a_synthesis_scene_draws_the_best_and_lists_the_candidates(tmp_path):
    import plans

    scene = tmp_path / "s.toml"
    scene.write_text('[synthesis]\nratio = 25.0\ntype = "B"\nplanets = 3\nmodule = 2.0\n', encoding="utf-8")
    sheets = plans.render(scene)
    data = sheets.report
    listed = data["synthesis"]["candidates"]
    best = synthesize(25.0, "B", 3, module=2.0)
    assert [c["teeth"] for c in listed] == [c.teeth for c in best]
    assert data["gears"]["geometry"]["pitch_radius_mm"]["a"] == best[0].teeth["a"] * 2.0 / 2
    assert "s-gears.svg" in sheets.files


@pytest.mark.parametrize("body, words", [
    ('ratio = 60.0\ntype = "A"\nplanets = 3\n', "cannot reach"),
    ('ratio = 6.0\ntype = "Q"\nplanets = 3\n', "synthesis.type"),
    ('ratio = 6.0\ntype = "A"\n', "missing planets"),
    ('ratio = 0.5\ntype = "A"\nplanets = 3\n', "beyond ±1"),
    ('ratio = 6.0\ntype = "A"\nplanets = 3\nspeed = 1\n', "unknown key 'speed'")])
def test_bad_synthesis_sections_are_one_line(body, words, tmp_path):
    scene = tmp_path / "s.toml"
    scene.write_text("[synthesis]\n" + body, encoding="utf-8")
    r = plans_cli(["render", scene, "-o", tmp_path / "o"])
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and words in r.stderr, r.stderr
    assert not (tmp_path / "o").exists()

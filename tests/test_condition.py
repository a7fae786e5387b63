"""The condition figure means the same closeness to a singular position for every kind of group.

A class II group's figure is sin μ, the sine of the angle between its two unknown directions
(its transmission angle). Class IV groups and a drive inside the chain report the same sine
generalised (plans.kinematics.figure): checked here to BE the class II sine when the generic
pair equations are written for a class II group (all five forms), to be the transmission sine
of the two drives inside the chain (closed forms from the points), and to measure the same
closeness at the warning threshold.

The closeness is the angle (rad) by which the group's links must still turn relative to each
other to reach the dead position, the largest |Δ(θ_i − θ_j)| over two of the group's links. At
a limit position each relative angle goes like the square root of the drive's distance δ to
it, so the closeness is 2·δ·max|ω_i − ω_j| / |ω_drive| (δ in rad, or m for a stroke, the
exact distance of Motion.singular_distance; ω per unit of the drive's rate): to first order
in δ, which at the warning threshold is a few thousandths of a degree (hundredths of a mm).
For a class II group at a limit position the closeness is μ itself, so sin μ / closeness → 1.
"""

from __future__ import annotations

import itertools
import math
import tomllib

import numpy as np
import pytest

from conftest import EXAMPLES, folding_four_bar
from plans.handout import MARGIN_SIN
from plans.kinematics import WARN_SIN, analyse
from plans.kinematics.generic import GroupEquations
from plans.model import build_mechanism
from plans.pipeline.motion_checks import motion_warnings
from plans.scene import parse_scene
from plans.structure import FORMS, Group, Pair, analyse_structure

#: The band within which the figure at the warning threshold must match the closeness
#: (figure / closeness): 1 for a class II group and a cylinder's triangle by construction,
#: 0.80 for the class IV group below; σmin/σmax (the figure before) gave 0.02–0.05.
BAND = (0.5, 2.0)


def _example(stem: str, points: dict | None = None) -> dict:
    data = tomllib.loads(next(p for p in EXAMPLES if p.stem == stem).read_text(encoding="utf-8"))
    data["points"].update(points or {})
    return data


def _load(data: dict):
    scene = parse_scene(data)
    mech = build_mechanism(scene)
    return scene, mech, analyse_structure(mech)


def _long_crank_class4() -> dict:
    """class4_six_link with the crank lengthened from 0.05 to 0.1 m: it no longer turns fully,
    the class IV group reaches a dead position at φ ≈ 96.33°."""
    a = 0.1 / math.sqrt(2.0)
    return _example("class4_six_link", {"A": [a, a]})


def _pairs(g: Group) -> tuple[Pair, ...]:
    """A class II group's three pairs as the generic pair equations take them."""
    return tuple(Pair(j.kind, link, j.other, j.point, j.prismatic) for j, link in ((g.d, g.m), (g.e, g.m), (g.f, g.n)))


def _sin(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """|sin| of the angle between the vectors u and v (N, 2)."""
    return np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]) / np.linalg.norm(u, axis=1) / np.linalg.norm(v, axis=1)


def test_the_generic_figure_of_a_class_ii_group_is_its_transmission_sine():
    """Every class II group of every example written as generic pair equations (as class IV
    groups are): its figure is |sin μ| of the closed form, to rounding, in all five forms."""
    forms = set()
    for path in EXAMPLES:
        scene, mech, st = _load(tomllib.loads(path.read_text(encoding="utf-8")))
        motion = analyse(mech, st, np.asarray(mech.drive.values, dtype=float), order=1)
        for g in st.groups:
            if isinstance(g, Group):
                got = GroupEquations(mech, g.links, _pairs(g)).condition(motion.links)
                assert np.allclose(np.abs(got), np.abs(motion.sines[g.name]), rtol=0, atol=1e-12), (path.stem, g.name)
                forms.add(g.form)
    assert forms == set(FORMS)


def test_the_drives_inside_the_chain_report_their_transmission_sine():
    """A cylinder pinned to a boom (hydraulic_boom): the figure is the sine of the angle at the
    rod's eye B between the cylinder's axis B→A and the boom B→O, from the points; a coupler's
    angle (four_bar_coupler_drive): the sine of the angle between crank O→A and rocker C→B —
    0 where they are parallel, its dead position."""
    _, mech, st = _load(_example("hydraulic_boom"))
    strokes = np.array([-0.185, -0.18, -0.16, -0.12, -0.06, 0.0, 0.06, 0.12, 0.18])
    motion = analyse(mech, st, strokes, order=1)
    b = motion.position("B")
    want = _sin(motion.position("A") - b, motion.position("O") - b)
    assert np.allclose(np.abs(motion.sines["I(0-2-3-4)"]), want, rtol=0, atol=1e-12)
    assert want[0] < 0.06 and want[-1] > 0.6                     # 0.5 mm from its dead position, and far

    _, mech, st = _load(_example("four_bar_coupler_drive"))
    motion = analyse(mech, st, np.asarray(mech.drive.values, dtype=float), order=1)
    want = _sin(motion.position("A") - motion.position("O"), motion.position("B") - motion.position("C"))
    assert np.allclose(np.abs(motion.sines["I(0-1-2-3)"]), want, rtol=0, atol=1e-12)


def _closeness(motion, group: str, links: tuple[str, ...], i: int) -> tuple[float, float]:
    """The drive's exact distance δ to the dead position (° or m) and the relative turning
    still to go there, 2·δ·max|ω_i − ω_j|/|ω_drive| (rad)."""
    mech = motion.mechanism
    away = motion.singular_distance(group, i)
    assert away is not None
    delta = math.radians(away) if mech.drive.kind.angular else away
    spread = max(abs(float(motion.links[a].omega[i] - motion.links[b].omega[i])) for a, b in itertools.combinations(links, 2))
    return away, 2.0 * delta * spread / abs(mech.drive.speed)


CASES = {
    # kind: (scene, a position before its dead position, the side the dead position lies on)
    "class II": (folding_four_bar(), 92.0, 1.0),
    "class IV": (_long_crank_class4(), 95.0, 1.0),
    "driven": (_example("hydraulic_boom"), -0.18, -1.0),
}


@pytest.mark.parametrize("kind", list(CASES))
def test_the_warning_threshold_means_the_same_closeness_for_every_kind(kind):
    """Where the figure falls to WARN_SIN, the group's links are WARN_SIN rad (to within BAND) of
    relative turning from the dead position, for a class II group, a class IV group and a drive
    inside the chain alike. The threshold is found from the square-root law: |figure|² is
    linear in δ, so δ·(WARN_SIN/figure)² is the onset, refined twice."""
    data, start, side = CASES[kind]
    _, mech, st = _load(data)
    groups = ([st.driven] if st.driven is not None else []) + list(st.groups)
    g = next(g for g in groups if not isinstance(g, Group)) if kind != "class II" else st.groups[0]
    motion = analyse(mech, st, np.array([start]), order=1)
    dead = start + side * motion.singular_distance(g.name, 0)
    x = start
    for _ in range(3):
        motion = analyse(mech, st, np.array([x]), order=1)
        away = motion.singular_distance(g.name, 0)
        x = dead - side * away * (WARN_SIN / float(motion.sines[g.name][0])) ** 2
    motion = analyse(mech, st, np.array([x]), order=1)
    figure = abs(float(motion.sines[g.name][0]))
    assert figure == pytest.approx(WARN_SIN, rel=0.05)
    away, closeness = _closeness(motion, g.name, g.links, 0)
    assert away < (0.01 if mech.drive.kind.angular else 1e-4)   # a few thousandths of a degree (0.02 mm) from it
    assert BAND[0] <= figure / closeness <= BAND[1], (kind, away, figure, closeness)


def _warned(scene, motion) -> list[str]:
    return [w for w in motion_warnings(scene, motion, (False, False), "t") if "near a singular position" in w]


def test_class4_six_link_warns_only_near_a_dead_position():
    """The example's crank turns fully: at every whole degree its class IV group keeps
    |figure| ≥ MARGIN_SIN (the figure before, σmin/σmax, was 0.024–0.045) and nothing warns.
    With the crank lengthened to 0.1 m the group reaches a dead position at 96.331°: 1° before
    it the links still have 0.19 rad of relative turning to go and nothing warns (σmin/σmax,
    0.008, warned); 0.002° before it (about 0.006 rad to go) the warning says how far it is."""
    scene, mech, st = _load(_example("class4_six_link"))
    motion = analyse(mech, st, np.arange(0.0, 360.0, 1.0), order=1)
    assert float(np.min(np.abs(motion.sines["IV(2-3-4-5)"]))) >= MARGIN_SIN
    assert _warned(scene, motion) == []

    scene, mech, st = _load(_long_crank_class4())
    dead = 95.0 + analyse(mech, st, np.array([95.0]), order=1).singular_distance("IV(2-3-4-5)", 0)
    assert dead == pytest.approx(96.331, abs=1e-3)       # the 3 decimals quoted: ±5e-4 of rounding, ×2
    motion = analyse(mech, st, dead - np.array([1.0, 0.01, 0.002]), order=1)
    warned = _warned(scene, motion)
    assert len(warned) == 1 and f"at {dead - 0.002:g}°" in warned[0] and "about 0.002° from it" in warned[0]


def test_hydraulic_boom_warns_only_near_its_dead_position():
    """Over the piston's travel (−0.16 … +0.2 m) nothing warns (σmin/σmax, below 0.01 from
    −0.14 m on, did); the original mechanism's dead position (A, O, B in line: the cylinder's
    length AB = OB − OA) is at −0.185553 m: 1e-4 m before it nothing warns, 1e-5 m before it
    the warning says how far it is."""
    scene, mech, st = _load(_example("hydraulic_boom"))
    motion = analyse(mech, st, np.round(np.arange(-0.16, 0.2001, 0.02), 6), order=1)
    assert _warned(scene, motion) == []
    a, b, o = (np.asarray(scene.points[p]) for p in "ABO")
    sketch_length = float(np.linalg.norm(b - a))
    dead = (np.linalg.norm(b - o) - np.linalg.norm(a - o)) - sketch_length          # the stroke where AB = OB − OA
    assert dead == pytest.approx(-0.185553, abs=1e-6)    # the 6 decimals quoted: ±5e-7 of rounding, ×2
    warned = [_warned(scene, analyse(mech, st, np.array([dead + d]), order=1)) for d in (1e-3, 1e-4, 1e-5)]
    assert warned[:2] == [[], []]
    assert len(warned[2]) == 1 and "I(0-2-3-4)" in warned[2][0] and "about 1e-05 m from it" in warned[2][0]


def _moved(data: dict, scale: float, shift: tuple[float, float]) -> dict:
    """The scene with every point scaled about the origin and shifted (m); a linear drive's
    strokes scaled too."""
    out = {**data, "points": {p: [scale * x + shift[0], scale * y + shift[1]] for p, (x, y) in data["points"].items()}}
    if "displacement" in data["drive"]:
        out["drive"] = {**data["drive"], "displacement": [scale * s for s in data["drive"]["displacement"]]}
    return out


@pytest.mark.parametrize("stem", ["class4_six_link", "hydraulic_boom", "four_bar_coupler_drive"])
def test_the_figure_does_not_depend_on_the_origin_or_the_unit(stem):
    """A geometric figure: the scene drawn 3× larger and 5 m away from the origin gives the same
    figure to rounding (σmin/σmax of the pose Jacobian changed with both)."""
    data = _example(stem)
    figures = []
    for scale, shift in ((1.0, (0.0, 0.0)), (3.0, (5.0, -2.0))):
        _, mech, st = _load(_moved(data, scale, shift))
        figures.append(analyse(mech, st, np.asarray(mech.drive.values, dtype=float), order=1).sines)
    assert figures[0].keys() == figures[1].keys()
    for g in figures[0]:
        assert np.allclose(figures[0][g], figures[1][g], rtol=0, atol=1e-9), g


def test_a_class_iii_group_with_a_sliding_pair_without_special_points(monkeypatch):
    """A class III/IV group with a prismatic pair takes its figure from the pair equations (the
    compiled blocks serve revolute pairs only): the triad with a sliding rod of test_complex.py,
    its special points set aside, reports the generic figure along the walk and in the rate
    solve — within (0, 1], the same at the same poses through GroupEquations, and independent
    of the origin as above."""
    from plans.kinematics import special
    from test_complex import _sliding_rod_triad

    monkeypatch.setattr(special, "supports", lambda g: False)
    values = np.arange(12) * 30.0 + 5.0
    figures = []
    for scale, shift in ((1.0, (0.0, 0.0)), (3.0, (5.0, -2.0))):
        data = _moved(_sliding_rod_triad(), scale, shift)
        data["drive"]["angle"] = values.tolist()
        _, mech, st = _load(data)
        motion = analyse(mech, st, values, order=2)
        (g,) = st.groups
        got = motion.sines[g.name]
        assert np.all((np.abs(got) > 0.05) & (np.abs(got) <= 1.0))
        assert np.allclose(got, GroupEquations(mech, g.links, g.pairs).condition(motion.links), rtol=0, atol=1e-12)
        figures.append(got)
    assert np.allclose(figures[0], figures[1], rtol=0, atol=1e-9)

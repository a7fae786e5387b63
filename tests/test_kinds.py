"""One solver per kind of group, behind one protocol (plans.kinematics.kinds): every kind the
structure makes has a solver; the chain's solver and the singular search never ask what kind a
group is; a new kind is one class and one registry line; the protocol's answers agree with
what the motion reports."""

from __future__ import annotations

import ast
import dataclasses
import inspect
import math
from pathlib import Path

import numpy as np
import pytest

from conftest import EXAMPLES
from plans.kinematics import analyse, kinds, solve
from plans.kinematics.kinds import SOLVERS, GroupSolver, chain
from plans.kinematics.kinds.dyad import Dyad
from plans.model import build_mechanism
from plans.scene import parse_scene, read_scene
from plans.structure import Group, analyse_structure

KINEMATICS = Path(__file__).resolve().parent.parent / "plans" / "kinematics"
PROTOCOL = [name for name, v in vars(GroupSolver).items() if inspect.isfunction(v)]


def _load(stem: str):
    mech = build_mechanism(read_scene(next(p for p in EXAMPLES if p.stem == stem)))
    return mech, analyse_structure(mech)


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_every_group_of_every_example_has_a_solver_that_follows_the_protocol(path):
    mech = build_mechanism(read_scene(path))
    st = analyse_structure(mech)
    solvers = chain(mech, st)
    names = ([st.driven.name] if st.driven is not None else []) + [g.name for g in st.groups]
    assert [s.group.name for s in solvers] == names
    for s in solvers:
        assert type(s) is SOLVERS[s.group.kind]
        missing = [m for m in PROTOCOL + ["closed_form"] if not hasattr(s, m)]
        assert missing == []


def test_each_kind_registered_is_made_by_the_structure():
    kinds_seen = set()
    for path in EXAMPLES:
        mech = build_mechanism(read_scene(path))
        st = analyse_structure(mech)
        kinds_seen |= {g.kind for g in st.groups} | ({st.driven.kind} if st.driven is not None else set())
    assert kinds_seen == set(SOLVERS)


@pytest.mark.parametrize("module", ["solve.py", "singular.py"])
def test_the_chain_never_asks_what_kind_a_group_is(module):
    """No isinstance, no group class, no ``.kind`` test in the chain's solver and the singular search."""
    tree = ast.parse((KINEMATICS / module).read_text(encoding="utf-8"))
    names = {n.id for n in ast.walk(tree) if isinstance(n, ast.Name)}
    assert "isinstance" not in names
    assert not names & {"ComplexGroup", "DrivenGroup", "Group"}
    assert _only_drive_kind(tree)


def _only_drive_kind(tree: ast.Module) -> bool:
    """``.kind`` read only as the drive's (``mech.drive.kind``)."""
    return all(isinstance(n.value, ast.Attribute) and n.value.attr == "drive"
               for n in ast.walk(tree) if isinstance(n, ast.Attribute) and n.attr == "kind")


@dataclasses.dataclass(frozen=True)
class _TracedGroup(Group):
    """A class II group of a new kind, for the test below."""

    kind = "traced"


class _Traced(Dyad):
    """A new kind's solver: a dyad that counts the protocol's calls."""

    calls: list[str] = []

    def branches(self, states, tol, branch=None):
        self.calls.append("branches")
        return super().branches(states, tol, branch)

    def positions(self, states, walk):
        self.calls.append("positions")
        super().positions(states, walk)

    def rates(self, states, values, pre=None):
        self.calls.append("rates")
        return super().rates(states, values, pre)

    def accelerations(self, states, rates):
        self.calls.append("accelerations")
        super().accelerations(states, rates)


def _traced(st, k: int):
    """``st`` with its group k made of the new kind (the same links and pairs)."""
    return dataclasses.replace(st, groups=tuple(
        _TracedGroup(**{f.name: getattr(g, f.name) for f in dataclasses.fields(Group)}) if i == k else g
        for i, g in enumerate(st.groups)))


def _triple_rocker(angles: list[float]):
    """A non-Grashof four-bar (OA 1.2, AB 1.5, BD 1, OD 2 m): the crank stops where A, B, D line
    up, at φ = arccos((1.2² + 2² − 2.5²)/(2·1.2·2)) ≈ 99.715°, the RRR group's dead centre."""
    phi = math.radians(60.0)
    a = np.array([1.2 * math.cos(phi), 1.2 * math.sin(phi)])
    d = np.array([2.0, 0.0])
    r = np.linalg.norm(d - a)
    along = (1.5 ** 2 - 1.0 ** 2 + r * r) / (2 * r)
    u = (d - a) / r
    b = a + along * u + math.sqrt(1.5 ** 2 - along ** 2) * np.array([-u[1], u[0]])
    scene = parse_scene({"title": "Triple rocker", "points": {"O": [0.0, 0.0], "A": a.tolist(), "B": b.tolist(),
                                                               "D": [2.0, 0.0]},
                         "links": {"0": ["O", "D"], "1": ["O", "A"], "2": ["A", "B"], "3": ["B", "D"]},
                         "drive": {"link": "1", "angle": angles, "omega": 1.0}})
    mech = build_mechanism(scene)
    return mech, analyse_structure(mech)


def test_a_new_kind_is_one_class_and_one_registry_line(monkeypatch):
    """A group of a kind the solver has never seen, registered with one line, is solved through
    the protocol alone, with the same values as the dyad it wraps."""
    mech, st = _load("six_link_press")
    values = np.arange(0.0, 360.0, 15.0)
    plain = analyse(mech, st, values, order=2)
    traced_st = _traced(st, 1)
    monkeypatch.setitem(SOLVERS, "traced", _Traced)          # the registry line
    monkeypatch.setattr(_Traced, "calls", [])
    traced = analyse(mech, traced_st, values, order=2)
    assert {"branches", "rates", "accelerations"} <= set(_Traced.calls)     # the direct path of a class II chain
    for name, s in plain.links.items():
        t = traced.links[name]
        for f in ("theta", "origin", "omega", "v", "epsilon", "a"):
            assert np.array_equal(getattr(s, f), getattr(t, f)), (name, f)
    _Traced.calls.clear()
    monkeypatch.setattr(solve, "_direct", lambda *a: None)              # the walk through every step
    walked = analyse(mech, traced_st, values, order=0)
    assert "positions" in _Traced.calls
    for name, s in plain.links.items():
        assert np.array_equal(s.origin, walked.links[name].origin) and np.array_equal(s.theta, walked.links[name].theta)
    with pytest.raises(KeyError):
        kinds.solver(mech, type("Unknown", (), {"kind": "no such kind"})())


def test_a_new_kind_finds_the_singular_position_through_the_protocol(monkeypatch):
    """The distance to the dead centre, searched through the protocol's local continuation, is
    the closed form's, for the dyad and for the same group registered as a new kind."""
    dead = math.degrees(math.acos((1.2 ** 2 + 2.0 ** 2 - 2.5 ** 2) / (2 * 1.2 * 2.0)))
    mech, st = _triple_rocker([60.0, 99.0, 99.5])
    monkeypatch.setitem(SOLVERS, "traced", _Traced)
    for structure in (st, _traced(st, 0)):
        motion = analyse(mech, structure, order=1)
        g = structure.groups[0].name
        # the secant search stops when its step is under 1e-6 of its first (0.05°); it converges
        # superlinearly, so its error is below that last step: 5e-8°
        assert motion.singular_distance(g, 1) == pytest.approx(dead - 99.0, abs=1e-6 * 0.05)
        assert motion.singular_distance(g, 2) == pytest.approx(dead - 99.5, abs=1e-6 * 0.05)
        assert motion.singular_distance(g, 0) is None        # 40° away: beyond the local search


def test_special_points_through_the_protocol_are_the_motions():
    mech, st = _load("class3_six_link")
    motion = analyse(mech, st, np.array([30.0, 120.0, 210.0]), order=1)
    seen = 0
    for s in chain(mech, st):
        points = s.special_points(motion.links)
        if s.group.name not in motion.special_points:
            assert points is None
            continue
        seen += 1
        expected = motion.special_points[s.group.name].points
        assert [p.name for p in points] == [p.name for p in expected]
        for p, q in zip(points, expected):
            assert np.allclose(p.position, q.position, rtol=0, atol=1e-12 * mech.size)
    assert seen == 1


@pytest.mark.parametrize("stem", ["class3_six_link", "class4_six_link", "four_bar_coupler_drive", "six_link_press"])
def test_condition_through_the_protocol_is_the_motions_figure(stem):
    """Each solver's condition figure at the solved poses is the figure the motion reports."""
    mech, st = _load(stem)
    values = np.asarray(mech.drive.values, float)
    motion = analyse(mech, st, values, order=1)
    for s in chain(mech, st):
        got = s.condition(motion.links, values)
        assert np.allclose(got, motion.sines[s.group.name], rtol=1e-9, atol=1e-12), s.group.name

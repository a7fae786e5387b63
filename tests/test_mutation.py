"""Mutation tests: the property checks of test_properties.py catch a wrong Coriolis term.

Each test reads the source of ``plans.kinematics.groups``, replaces one exact expression by a
deliberately wrong one, executes the result as a fresh module and points every reference to
the original functions (``solve`` imports them by name) at the mutant's, for the duration of
the test only. The checks must pass on the original code and fail on the mutant, with the
failure reported by the checks that should see it. If the expression to mutate is not in the
source any more (a refactor), the test fails and says so: it can never pass vacuously.
"""

from __future__ import annotations

import math
import sys
import types
from pathlib import Path

import numpy as np
import pytest

import plans.kinematics.groups as groups

import test_properties as tp
from test_properties import build_prp, build_rpp_turning, build_rpr, build_rrp_slot, check, measure

#: with filterwarnings = error, hypothesis' report of a failing example (its patch writer
#: imports libcst → mypy_extensions, deprecated) would turn into an INTERNALERROR hiding it
pytestmark = pytest.mark.filterwarnings("ignore:mypy_extensions.TypedDict is deprecated:DeprecationWarning")


@pytest.fixture(autouse=True)
def _own_records(monkeypatch):
    """The mutants' (large) errors must not enter test_properties' report of worst errors."""
    monkeypatch.setattr(tp, "WORST", {})


#: (name, exact source text, its replacement, what the mutant does)
MUTATIONS = {
    "RPR Coriolis sign": (
        "rhs = _scaled(sq(w), D - F, aD - aF) - cor(w, s, u)",
        "rhs = _scaled(sq(w), D - F, aD - aF) + cor(w, s, u)",
        "the slotted lever's acceleration equation with the Coriolis term of the wrong sign"),
    "RRP Coriolis sign": (
        "rhs = _scaled(sq(m.omega), E - D, aD - aEp, -1.0) - cor(p.omega, s, u)",
        "rhs = _scaled(sq(m.omega), E - D, aD - aEp, -1.0) + cor(p.omega, s, u)",
        "RRP on a turning guide: its acceleration equation with the Coriolis term of the wrong sign"),
    "Coriolis helper sign": (
        "return _scaled(2.0 * (w * s), J(u))",
        "return _scaled(-2.0 * (w * s), J(u))",
        "2·ω × σu of the wrong sign everywhere (RRP, RPR, PRP, RPP)"),
    "Coriolis helper factor": (
        "return _scaled(2.0 * (w * s), J(u))",
        "return _scaled(1.0 * (w * s), J(u))",
        "ω × σu instead of 2·ω × σu (the classic slip)"),
}


def mutant(old: str, new: str) -> types.ModuleType:
    """``plans.kinematics.groups`` with the one occurrence of ``old`` replaced by ``new``."""
    source = Path(groups.__file__).read_text(encoding="utf-8")
    count = source.count(old)
    if count != 1:
        pytest.fail(f"the text to mutate occurs {count} times in {groups.__file__} (expected once): {old!r} — "
                    "update tests/test_mutation.py to the refactored source")
    mod = types.ModuleType(groups.__name__ + "_mutant")
    mod.__file__ = groups.__file__
    mod.__package__ = groups.__package__
    sys.modules[mod.__name__] = mod      # dataclasses look their module up while the class is made
    try:
        exec(compile(source.replace(old, new), groups.__file__ + " (mutant)", "exec"), mod.__dict__)
    finally:
        del sys.modules[mod.__name__]
    return mod


def install(monkeypatch, mod: types.ModuleType) -> int:
    """Point every module attribute of plans that is a function of ``groups`` at the mutant's
    function of the same name; returns how many references were replaced."""
    originals = {id(obj): name for name, obj in vars(groups).items()
                 if callable(obj) and getattr(obj, "__module__", None) == groups.__name__}
    replaced = 0
    for mname, module in list(sys.modules.items()):
        if module is None or not (mname == "plans" or mname.startswith("plans.")) or module is mod:
            continue
        for attr, value in list(vars(module).items()):
            name = originals.get(id(value))
            if name is not None and hasattr(mod, name):
                monkeypatch.setattr(module, attr, getattr(mod, name))
                replaced += 1
    assert replaced, "no reference to plans.kinematics.groups' functions was found to replace"
    return replaced


#: fixed cases where the Coriolis term is large: σ and ω of the guide both well away from zero
CASES = {
    "RPR oscillating lever, offset slot": build_rpr(r=0.1, d=0.3, gamma=-math.pi / 2, h=0.05, phi=0.5, branch=1.0,
                                                    lever=(0.2, 0.3), omega=6.0, epsilon=3.0),
    "RPR rotating lever, slot through C": build_rpr(r=0.3, d=0.1, gamma=1.0, h=0.0, phi=2.0, branch=-1.0,
                                                    lever=(0.2, -1.0), omega=-4.0, epsilon=0.0),
    "RRP rod on a crank slot": build_rrp_slot(r=0.3, kappa=0.0, h=0.02, c_dist=0.05, c_dir=-0.9, lm=0.25, phi=0.3,
                                              branch=1.0, omega=7.0, epsilon=-15.0),
    "PRP offset slot": build_prp(r=0.3, kappa=0.2, c=0.05, beta=math.pi / 2, e=-0.15, phi=0.5, omega=5.0,
                                 epsilon=10.0),
    "RPP yoke on a crank slot": build_rpp_turning(r=0.3, kappa=0.3, gamma=1.6, c=np.array([0.1, 0.2]),
                                                  q=np.array([0.15, 0.05]), phi=0.3, omega=9.0, epsilon=30.0),
}

#: which cases each mutant reaches (the helper reaches every group with a turning guide)
REACHES = {
    "RPR Coriolis sign": ["RPR oscillating lever, offset slot", "RPR rotating lever, slot through C"],
    "RRP Coriolis sign": ["RRP rod on a crank slot"],
    "Coriolis helper sign": list(CASES),
    "Coriolis helper factor": list(CASES),
}


@pytest.mark.parametrize("name", list(CASES))
def test_original_code_passes(name):
    check(CASES[name])


@pytest.mark.parametrize("mutation", list(MUTATIONS))
def test_mutant_is_caught_by_two_independent_checks(mutation, monkeypatch):
    """On every case the mutant reaches, both the finite-difference comparison of the
    accelerations and a pair identity fail — (a_slider − a_guide)·n = 2·ω_guide·σ, or the pin
    between the group's links having one acceleration — and nothing at velocity level or below
    (positions, velocities, rigidity are untouched by an acceleration formula)."""
    old, new, _ = MUTATIONS[mutation]
    before = {name: measure(CASES[name])[0].failures() for name in REACHES[mutation]}
    assert before == {name: [] for name in REACHES[mutation]}
    install(monkeypatch, mutant(old, new))
    for name in REACHES[mutation]:
        failures = measure(CASES[name])[0].failures()
        kinds = {f.split(":")[0] + ":" + f.split(":")[1] for f in failures}
        assert "FD: acceleration" in kinds, f"{mutation} survived the finite differences on {name}: {failures}"
        # the Coriolis identity of the prismatic pair, or (RRP, whose slider keeps the right
        # term) the revolute pair between the group's two links
        assert kinds & {"pair: Coriolis (a_s - a_g).n = 2 w sigma", "pair: revolute acceleration"}, \
            f"{mutation} survived the pair identities on {name}: {failures}"
        assert not any(k.startswith(("closure", "FD: velocity", "FD: omega", "pair: revolute velocity",
                                     "pair: slider velocity", "rigid: (vB")) for k in kinds), failures
        with pytest.raises(AssertionError):
            check(CASES[name])


@pytest.mark.parametrize("mutation, test", [("RPR Coriolis sign", "test_rpr_regular"),
                                            ("RRP Coriolis sign", "test_rrp_regular"),
                                            ("Coriolis helper factor", "test_prp_near_parallel")])
def test_mutant_is_caught_by_the_property_test_itself(mutation, test, monkeypatch):
    """The hypothesis property test, run unchanged on the mutant, finds a falsifying example
    (the same test passes in test_properties.py on the original code)."""
    old, new, _ = MUTATIONS[mutation]
    install(monkeypatch, mutant(old, new))
    with pytest.raises(AssertionError, match="FD: acceleration"):
        getattr(tp, test)()


def test_identity_mutant_reproduces_plans_bit_for_bit(monkeypatch):
    """Sanity of the machinery: the identity 'mutation', installed, is really what analyse runs
    (the references are replaced) and gives plans' numbers bit for bit."""
    case = CASES["RPR oscillating lever, offset slot"]
    before = measure(case)[1]
    text = MUTATIONS["Coriolis helper sign"][0]
    mod = mutant(text, text)
    assert mod is not groups and mod.accelerations is not groups.accelerations
    assert install(monkeypatch, mod) >= 2          # groups' own name and the solver's import
    assert groups.accelerations is mod.accelerations
    after = measure(case)[1]
    for name, state in before.links.items():
        assert np.array_equal(state.a, after.links[name].a) and np.array_equal(state.epsilon, after.links[name].epsilon)

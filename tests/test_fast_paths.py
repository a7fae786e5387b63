"""The fast paths of the kinematic solver agree with the straightforward computations they
replace: a class III/IV group's compiled rate solves (:class:`plans.kinematics.compiled.GroupRates`)
with the generic pair equations (:class:`plans.kinematics.generic.GroupEquations`), to rounding."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import EXAMPLES
from plans.kinematics import analyse, special
from plans.kinematics.compiled import GroupRates
from plans.kinematics.generic import GroupEquations
from plans.kinematics.groups import accelerations, velocities
from plans.kinematics.solve import _set_drive_rates
from plans.model import build_mechanism
from plans.scene import read_scene
from plans.structure import ComplexGroup, analyse_structure

#: Largest relative difference between the two rate solves: both are exact to rounding,
#: amplified by the groups' conditioning (1/|figure| ≲ 1e2 at the positions tested).
RATES_RTOL = 1e-12


def _complex_examples() -> list:
    out = []
    for path in EXAMPLES:
        mech = build_mechanism(read_scene(path))
        st = analyse_structure(mech)
        if any(isinstance(g, ComplexGroup) for g in st.groups):
            out.append(pytest.param(mech, st, id=path.stem))
    return out


def _generic(mech, st, values: np.ndarray):
    """Rates and condition figures at ``values`` by GroupEquations (the reference path)."""
    states = dict(analyse(mech, st, values, order=0).links)
    _set_drive_rates(mech, states, values)
    sliding, eqs, figures = {}, {}, {}
    for g in st.groups:
        if isinstance(g, ComplexGroup):
            eq = GroupEquations(mech, g.links, g.pairs)
            a = eq.scaled_jacobian(states)
            eqs[g.name] = eq, a
            figures[g.name] = eq.condition(states, a)
            eq.velocities(states, a)
        else:
            sliding[g.name], figures[g.name] = velocities(g, mech, states)
    for g in st.groups:
        if isinstance(g, ComplexGroup):
            eq, a = eqs[g.name]
            eq.accelerations(states, a)
        else:
            accelerations(g, mech, states, sliding[g.name])
    return states, figures


def _relative(x: np.ndarray, y: np.ndarray) -> float:
    return float(np.max(np.abs(x - y)) / max(float(np.max(np.abs(y))), 1e-300))


@pytest.mark.parametrize("mech, st", _complex_examples())
def test_compiled_rates_agree_with_generic_equations(mech, st):
    values = np.asarray(mech.drive.values, dtype=float)
    values = np.concatenate([values, values[0] + np.linspace(-3.0, 3.0, 7)])
    motion = analyse(mech, st, values, order=2)
    states, figures = _generic(mech, st, values)
    for name, s in motion.links.items():
        for field in ("omega", "v", "epsilon", "a"):
            assert _relative(getattr(s, field), getattr(states[name], field)) <= RATES_RTOL, (name, field)
    for g in st.groups:
        if isinstance(g, ComplexGroup):
            rates = GroupRates(mech, g.links, g.pairs, motion.links)
            assert np.max(np.abs(rates.condition() / figures[g.name] - 1.0)) <= RATES_RTOL
            if not special.supports(g):
                assert np.array_equal(motion.sines[g.name], rates.condition())


def test_compiled_rates_near_a_limit_position():
    """Within 0.2°–1° of a triad's limit position (figure ≲ 0.05) the two solves still agree."""
    from reference import Reference
    from test_complex import _folding_triad
    from plans.scene import parse_scene
    mech = build_mechanism(parse_scene(_folding_triad()))
    st = analyse_structure(mech)
    ref = Reference(mech)
    fold = ref.fold(ref.solve([97.5])[0]).value
    values = fold - np.array([1.0, 0.5, 0.2])
    motion = analyse(mech, st, values, order=2)
    states, figures = _generic(mech, st, values)
    (g,) = st.groups
    assert np.all(np.abs(figures[g.name]) < 0.1)
    for name, s in motion.links.items():
        for field in ("omega", "v", "epsilon", "a"):
            assert _relative(getattr(s, field), getattr(states[name], field)) <= RATES_RTOL, (name, field)
    rates = GroupRates(mech, g.links, g.pairs, motion.links)
    assert np.max(np.abs(rates.condition() / figures[g.name] - 1.0)) <= RATES_RTOL

"""The fast paths of the kinematic solver agree with the straightforward computations they
replace: a class III/IV group's compiled rate solves (:class:`plans.kinematics.compiled_rates.GroupRates`)
with the generic pair equations (:class:`plans.kinematics.generic.GroupEquations`), to rounding;
a large class II request solved in blocks (``solve._direct_motion``) with the same request
solved at once, to the last bit."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import EXAMPLES
from plans.errors import PlansError
from plans.kinematics import analyse, solve, special
from plans.kinematics.compiled_rates import GroupRates
from plans.kinematics.generic import GroupEquations
from plans.kinematics.groups import accelerations, velocities
from plans.kinematics.walk import set_drive_rates as _set_drive_rates
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


# --- a large class II request solved in blocks (solve._direct_motion) -----------------------

def _class_ii_examples() -> list:
    out = []
    for path in EXAMPLES:
        mech = build_mechanism(read_scene(path))
        st = analyse_structure(mech)
        if not any(isinstance(g, ComplexGroup) for g in st.groups):
            out.append(pytest.param(mech, st, id=path.stem))
    return out


def _outcome(fn):
    try:
        return fn(), None
    except PlansError as e:
        return None, (type(e), str(e))


@pytest.mark.parametrize("mech, st", _class_ii_examples())
def test_blocked_request_equals_unblocked(mech, st, monkeypatch):
    """Blocks of DIRECT_BLOCK values give every pose, rate, cos θ, sin θ and sin of the whole
    request at once to the last bit (or the same refusal). The blocks are made 64 values long
    here (the code path is the same at any length; 4096 made the request 8229 positions)."""
    block = 64
    s = mech.drive.sketch_value
    span = np.linspace(-200.0, 500.0, 2 * block + 37) if mech.drive.kind == "rotary" \
        else np.linspace(-0.3, 0.3, 2 * block + 37) * mech.size
    values = s + span
    with monkeypatch.context() as m:
        m.setattr(solve, "DIRECT_BLOCK", block)
        blocked, blocked_err = _outcome(lambda: analyse(mech, st, values, order=2))
    with monkeypatch.context() as m:
        m.setattr(solve, "DIRECT_BLOCK", 10 ** 9)
        whole, whole_err = _outcome(lambda: analyse(mech, st, values, order=2))
    assert blocked_err == whole_err
    if whole is None:
        return
    assert list(blocked.links) == list(whole.links) and blocked.sines.keys() == whole.sines.keys()
    for name, a in blocked.links.items():
        b = whole.links[name]
        for field in ("theta", "origin", "omega", "v", "epsilon", "a"):
            assert np.array_equal(getattr(a, field), getattr(b, field)), (name, field)
        ca, cb = a.__dict__.get("_cos_sin"), b.__dict__.get("_cos_sin")
        assert (ca is None) == (cb is None)
        if ca is not None:
            assert all(np.array_equal(x, y) for x, y in zip(ca, cb))
    for g, sin in blocked.sines.items():
        assert np.array_equal(sin, whole.sines[g])


def test_blocked_path_is_used_and_falls_back(monkeypatch):
    """The crank-slider's 100 000 positions go through the blocks; a block that fails the
    direct path's checks hands the whole request to the walk, which reports as before."""
    mech = build_mechanism(read_scene(next(p for p in EXAMPLES if p.stem == "crank_slider_central")))
    st = analyse_structure(mech)
    calls = []
    block = solve._direct_block

    def spy(*a):
        calls.append(len(a[3]))
        return block(*a)

    monkeypatch.setattr(solve, "_direct_block", spy)
    values = np.linspace(0.0, 360.0, 100_000, endpoint=False)
    motion = analyse(mech, st, values, order=1)
    assert calls[0] == solve.DIRECT_BLOCK and sum(calls) == len(values) and motion.order == 1
    assert set(motion.sines) == {g.name for g in st.groups}
    assert all(motion.links[link].epsilon is None for g in st.groups for link in g.links)
    # a block refused (as if a value were singular): the ordinary path solves the request
    monkeypatch.setattr(solve, "_direct_block", lambda *a: None)
    again = analyse(mech, st, values, order=1)
    for name, s in again.links.items():
        np.testing.assert_allclose(s.omega, motion.links[name].omega, rtol=1e-12, atol=1e-12)


# --- the compiled group's shortcuts ---------------------------------------------------------

@pytest.mark.parametrize("mech, st", _complex_examples())
def test_compiled_difference_and_trigonometry(mech, st):
    """Φ(q, i) − Φ(q, j) without evaluation (revolute pairs only) equals the difference of two
    evaluations to rounding; the cos θ, sin θ route by batch size changes them by a few ulps at most."""
    from plans.kinematics import compiled
    values = np.asarray(mech.drive.values, dtype=float)
    values = values[0] + np.linspace(-4.0, 4.0, 3 * compiled.TRIG_BATCH)
    motion = analyse(mech, st, values, order=0)
    for g in st.groups:
        if not isinstance(g, ComplexGroup):
            continue
        rates = GroupRates(mech, g.links, g.pairs, motion.links)
        group, q = rates.group, rates.q
        i, j = np.arange(1, len(values)), np.arange(len(values) - 1)
        both = group.difference(q[i], i, j)
        direct = group.evaluate(q[i], i, jacobian=False) - group.evaluate(q[i], j, jacobian=False)
        assert np.max(np.abs(both - direct)) <= 1e-15 * mech.size
        th = q[:, 2::3]
        c, s = compiled._cos_sin(th)
        # cos = (1 − t²)/(1 + t²), sin = 2t/(1 + t²) with t = tan(θ/2): tan's relative error δ
        # (≤ 1 ulp: |δ| ≤ 2u, u = eps/2) moves cos by sin²θ·δ (≤ 2u) and sin by sinθ·cosθ·δ
        # (≤ u); t², 1 + t², 1/(…), 1 − t² and the product round once each: ≤ ½u + 4u·|cos|
        # (≤ 4u for sin); np.cos, np.sin err by ≤ 1 ulp (≤ u below 1). So ≤ 7.5u for cos and
        # 6u for sin: the bound 8u = 4 eps.
        # (Measured: 2u, from 2·10⁶ random angles too, with and without numpy's AVX-512 kernels.)
        bound = 4 * np.finfo(float).eps
        assert np.max(np.abs(c - np.cos(th))) <= bound and np.max(np.abs(s - np.sin(th))) <= bound


def test_compiled_constants_are_per_mechanism():
    """The cached constants of a group belong to one mechanism: another mechanism with the same
    link and pair names but other dimensions gets its own."""
    from test_complex import _folding_triad
    from plans.kinematics import compiled
    from plans.scene import parse_scene
    data = _folding_triad()
    first = build_mechanism(parse_scene(data))
    data["points"]["D"] = [0.41, 0.11]
    second = build_mechanism(parse_scene(data))
    (g1,), (g2,) = analyse_structure(first).groups, analyse_structure(second).groups
    c1 = compiled._constants(first, g1.links, g1.pairs)
    c2 = compiled._constants(second, g2.links, g2.pairs)
    assert c1 is compiled._constants(first, g1.links, g1.pairs)
    assert not np.array_equal(c1.ms, c2.ms)


def test_compiled_rates_keep_a_link_at_rest_at_rest():
    """triad_at_rest at 0°: links 3, 4 and 5 stand still; the compiled rates say so exactly (as the
    generic solve does), so the cross-check against the special points, relative to each link's
    own values, passes."""
    mech = build_mechanism(read_scene(next(p for p in EXAMPLES if p.stem == "triad_at_rest")))
    st = analyse_structure(mech)
    motion = analyse(mech, st, np.array([0.0]), order=2)
    for link in ("3", "4", "5"):
        assert motion.links[link].omega[0] == 0.0 and not motion.links[link].v.any()
    for triad in special.triads(motion).values():
        assert special.disagreement(motion, triad) <= special.CROSS_CHECK_RTOL


def test_matrix_product_of_many_positions():
    """Products of many positions (the compiled groups' T·q + Mc·cos θ + Ms·sin θ, by
    plans.linalg's fixed-order sums): numpy's product to rounding (K = 20 terms: |error| ≤
    20 ε Σ|a||w| ≈ 20 × 2.2e-16 × 20 ≈ 1e-13 for standard normal entries)."""
    from plans import linalg as la
    rng = np.random.default_rng(3)
    a, w = rng.standard_normal((1543, 20)), rng.standard_normal((20, 12))
    np.testing.assert_allclose(la.matmul(a, w), a @ w, rtol=0, atol=1e-13)
    assert la.matmul(a[:5], w).shape == (5, 12)


def test_four_by_four_determinant():
    """Laplace's expansion gives numpy's determinant to rounding, with its sign, down to
    matrices a 1e-9 step from singular."""
    from plans.kinematics import compiled
    rng = np.random.default_rng(5)
    m = rng.standard_normal((2000, 4, 4))
    u, s, vt = np.linalg.svd(m)
    s[:, -1] = s[:, 0] * 10.0 ** rng.uniform(-9.0, 0.0, len(m))
    m = (u * s[:, None, :]) @ vt
    exact, fast = np.linalg.det(m), compiled._det(m)
    assert np.array_equal(np.sign(exact), np.sign(fast))
    scale = np.prod(np.linalg.norm(m, axis=2), axis=1)       # Hadamard's bound on |det|
    assert np.max(np.abs(fast - exact) / scale) <= 1e-14
    assert np.allclose(compiled._det(m[:, :3, :3]), np.linalg.det(m[:, :3, :3]))

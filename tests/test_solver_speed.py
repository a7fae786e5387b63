"""The fast class III/IV position solve (plans.kinematics.compiled) against the step-by-step
walk, and the local near-singular distance (plans.kinematics.singular) against the search
that re-analyses the whole mechanism. Correctness only: timings are in
benchmarks/complex_groups.py."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from plans.errors import AssemblyError, PlansError
from plans.kinematics import Motion, analyse, continuation
from plans.kinematics.singular import SHORT_OF_ROOT
from plans.model import build_mechanism
from plans.scene import read_scene
from plans.structure import ComplexGroup, analyse_structure

from conftest import folding_four_bar
from test_complex import _folding_triad, _load
from reference import Reference

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
COMPLEX = ["class3_six_link", "class4_six_link", "triad_sliding_rod", "koshel_variant1", "koshel_variant2",
           "triad_at_rest"]
TURN = np.linspace(0.0, 360.0, 72, endpoint=False)


def _example(name):
    mech = build_mechanism(read_scene(EXAMPLES / f"{name}.toml"))
    return mech, analyse_structure(mech)


def _values(mech):
    return TURN if mech.drive.kind == "rotary" else np.asarray(mech.drive.values, float)


def _slow(monkeypatch):
    monkeypatch.setattr(continuation, "fast_walk", lambda *a, **k: (None, None))


def _close(a, b, rel=1e-12):
    for name, s in a.links.items():
        t = b.links[name]
        for f in ("theta", "origin", "omega", "v", "epsilon", "a"):
            x, y = getattr(s, f), getattr(t, f)
            if x is None:
                assert y is None
                continue
            scale = max(1.0, float(np.max(np.abs(y))))
            assert np.max(np.abs(x - y)) <= rel * scale, (name, f)


@pytest.mark.parametrize("name", COMPLEX)
def test_batched_equals_step_by_step(name, monkeypatch):
    mech, st = _example(name)
    assert any(isinstance(g, ComplexGroup) for g in st.groups)
    values = _values(mech)
    fast = analyse(mech, st, values, order=2)
    _slow(monkeypatch)
    slow = analyse(mech, st, values, order=2)
    _close(fast, slow)


@pytest.mark.parametrize("name", ["class3_six_link", "class4_six_link"])
def test_fast_path_is_taken(name, monkeypatch):
    """The examples never fall back to the step-by-step walk."""
    mech, st = _example(name)

    def boom(*a, **k):
        raise AssertionError("fell back to the step-by-step walk")

    monkeypatch.setattr(continuation, "newton_walk", boom)
    analyse(mech, st, TURN, order=2)


@pytest.mark.parametrize("name", ["class3_six_link", "class4_six_link"])
def test_branch_kept_over_two_turns(name):
    mech, st = _example(name)
    values = np.arange(0.0, 720.0, 5.0)
    m = analyse(mech, st, values, order=0)
    half = len(values) // 2
    for link, s in m.links.items():
        d = s.theta[half:] - s.theta[:half]
        assert np.allclose(np.sin(d), 0.0, atol=1e-9) and np.allclose(np.cos(d), 1.0, atol=1e-9)
        assert np.allclose(s.origin[half:], s.origin[:half], atol=1e-9 * mech.size)


def test_limit_position_refused_as_before(monkeypatch):
    mech, st = _load(_folding_triad())
    with pytest.raises(AssemblyError) as fast:
        analyse(mech, st, np.array([45.0, 120.0]))
    _slow(monkeypatch)
    with pytest.raises(AssemblyError) as slow:
        analyse(mech, st, np.array([45.0, 120.0]))
    assert str(fast.value) == str(slow.value)
    assert "III(2-3-4-5)" in str(fast.value) and "120°" in str(fast.value)


def test_near_limit_values_agree(monkeypatch):
    """Close to the fold (where the coarse continuation must shorten its steps) the fast
    solve still gives the walk's values."""
    mech, st = _load(_folding_triad())
    ref = Reference(mech)
    fold = ref.fold(ref.solve([97.5])[0]).value
    values = np.concatenate([np.linspace(0.0, fold - 0.05, 40), [fold - 0.01]])
    fast = analyse(mech, st, values, order=2)
    _slow(monkeypatch)
    slow = analyse(mech, st, values, order=2)
    _close(fast, slow, rel=1e-9)


@pytest.mark.parametrize("delta", [0.3, 1.0])
def test_local_singular_distance_matches_full_search(delta):
    """The local search finds the fold δ away (to 1e-3: the fold itself is Moore–Spence's, the
    distance a secant's); at δ = 0.3 the previous full search (33 whole analyses, the suite's
    costliest second opinion, run once) agrees within the two searches' stopping steps."""
    from plans.kinematics.singular import distance
    mech, st = _load(_folding_triad())
    ref = Reference(mech)
    fold = ref.fold(ref.solve([97.5])[0]).value
    motion = analyse(mech, st, np.array([fold - delta]))
    d = distance(motion, "III(2-3-4-5)", 0)
    assert d == pytest.approx(delta, rel=1e-3)
    if delta == 0.3:
        # both stop when a step is under 1e-6 of the first (0.05°), each within that of the fold
        assert d == pytest.approx(_full_search(motion, "III(2-3-4-5)", 0), abs=2e-6 * 0.05)


@pytest.mark.parametrize("delta", [0.05, 0.3])
def test_local_singular_distance_class_ii(delta):
    """A class II group near its limit position: the same answer as the full search."""
    from plans.kinematics.singular import distance
    mech, st = _load(folding_four_bar())
    lo, hi = 90.0, 95.0                       # the limit position, by bisection on assembly
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        try:
            analyse(mech, st, np.array([mid]), order=0)
            lo = mid
        except AssemblyError:
            hi = mid
    motion = analyse(mech, st, np.array([lo - delta]))
    (g,) = motion.sines
    new, old = distance(motion, g, 0), _full_search(motion, g, 0)
    # each search stops when its step is under 1e-6 of its first (0.05°) and converges
    # superlinearly: within 5e-8° of the limit position (bisected to 5°/2⁵⁰ here), 1e-7° of each other
    assert new == pytest.approx(delta, abs=1e-6 * 0.05)
    assert new == pytest.approx(old, abs=2e-6 * 0.05)


def _full_search(motion: Motion, group: str, i: int) -> float | None:
    """The previous, independent method (kept here as a second opinion): how far the drive is
    from the singular position of ``group`` nearest position i, re-running the whole analysis
    at every trial
    (degrees or metres), or None when it cannot be found nearby. Secant steps on the squared
    condition figure c², which falls to zero linearly at a limit position (c ~ √δ there) and
    quadratically where a branch crosses (c ~ δ); a step that lands past a limit position
    (the group no longer assembles) is halved."""
    mech, structure = motion.mechanism, motion.structure
    h = 0.05 if mech.drive.kind == "rotary" else 1e-4 * mech.size

    def f(x: float) -> float | None:
        try:
            return float(analyse(mech, structure, np.array([x]), order=1).sines[group][0]) ** 2
        except PlansError:
            return None

    start = float(motion.values[i])
    x0, f0 = start, float(motion.sines[group][i]) ** 2
    x1 = start + h
    f1 = f(x1)
    if f1 is None:
        x1, f1 = start - h, f(start - h)
    for _ in range(16):
        if f1 is None or f1 == f0:
            return None
        x2 = x1 - f1 * (x1 - x0) / (f1 - f0)
        if abs(x2 - start) > 20.0 * h + 10.0 * abs(x1 - start):
            return None
        f2 = f(x2)
        if f2 is None:      # past a limit position, where c² is nearly linear: the root is just short
            x2 = x1 + (1.0 - SHORT_OF_ROOT) * (x2 - x1)
            f2 = f(x2)
        tries = 0
        while f2 is None and tries < 30:      # past a limit position: step back towards x1
            x2 = 0.5 * (x1 + x2)
            f2, tries = f(x2), tries + 1
        if f2 is None:
            return None
        if abs(x2 - x1) < 1e-6 * h:
            return abs(x2 - start)
        x0, f0, x1, f1 = x1, f1, x2, f2
    return abs(x1 - start)

"""The direct evaluation of class II mechanisms (solve._direct) against the full walk.

The full walk solves every group at every 1° step and at every requested value; the direct
path walks the steps only and then solves the chosen assembly branch at the values. Both must
give the same poses and motions, and the same refusals, with the same messages.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from plans.errors import PlansError
from plans.kinematics import analyse, solve
from plans.model import build_mechanism
from plans.scene import read_scene
from plans.structure import ComplexGroup, analyse_structure

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _load(path: Path):
    mech = build_mechanism(read_scene(path))
    return mech, analyse_structure(mech)


CLASS_II = [p.stem for p in sorted(EXAMPLES.glob("*.toml"))
            if not any(isinstance(g, ComplexGroup) for g in _load(p)[1].groups)]


def _full(monkeypatch, mech, structure, values, order=2):
    with monkeypatch.context() as m:
        m.setattr(solve, "_direct", lambda *a: None)
        m.setattr(solve, "_direct_motion", lambda *a: None)     # its blocked form, for large requests
        return analyse(mech, structure, values, order=order)


def _outcome(fn):
    try:
        return fn(), None
    except PlansError as e:
        return None, (type(e), str(e))


def _values(mech) -> list[np.ndarray]:
    s = mech.drive.sketch_value
    if mech.drive.kind == "rotary":
        return [s + np.linspace(-30.0, 30.0, 241) + 0.37,          # between the walk's steps
                s + np.linspace(0.0, 720.0, 1001, endpoint=False),  # beyond a full turn
                s + np.linspace(-725.3, -361.1, 97),
                s + np.array([0.0, 0.5, 359.75, -0.25, 1e-9])]
    span = mech.size
    return [s + np.linspace(-0.05, 0.05, 201) * span + 1e-4 * span,
            s + np.linspace(-0.5, 0.5, 333) * span]


def _compare(fast, full, size):
    assert set(fast.links) == set(full.links)
    for name, a in fast.links.items():
        b = full.links[name]
        np.testing.assert_allclose(a.theta, b.theta, rtol=1e-15, atol=1e-15)
        np.testing.assert_allclose(a.origin, b.origin, rtol=1e-15, atol=1e-15 * size)
        for f in ("omega", "v", "epsilon", "a"):
            x, y = getattr(a, f), getattr(b, f)
            scale = max(1.0, float(np.max(np.abs(y))))
            np.testing.assert_allclose(x, y, rtol=1e-12, atol=1e-12 * scale)
    for g, s in fast.sines.items():
        np.testing.assert_allclose(s, full.sines[g], rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("stem", CLASS_II)
def test_direct_matches_full_walk(stem, monkeypatch):
    mech, structure = _load(EXAMPLES / f"{stem}.toml")
    for values in _values(mech):
        fast, fast_err = _outcome(lambda: analyse(mech, structure, values, order=2))
        full, full_err = _outcome(lambda: _full(monkeypatch, mech, structure, values))
        assert fast_err == full_err
        if fast is not None:
            _compare(fast, full, mech.size)


def test_direct_path_is_used(monkeypatch):
    """At 100 000 positions the walk's steps are solved with the values, on one branch: the
    step-by-step walk (which would insert every value into its grid) never runs."""
    mech, structure = _load(EXAMPLES / "crank_slider_central.toml")
    calls = []
    walk = solve._positions

    def spy(mech_, structure_, values, *a, **k):
        calls.append(len(values))
        return walk(mech_, structure_, values, *a, **k)

    monkeypatch.setattr(solve, "_positions", spy)
    values = np.linspace(0.0, 360.0, 100_000, endpoint=False)
    motion = analyse(mech, structure, values, order=2)
    assert calls == []
    monkeypatch.undo()
    _compare(motion, _full(monkeypatch, mech, structure, values), mech.size)


def _limit(mech, structure, monkeypatch):
    """A crank angle where the full walk from the sketch first fails, bracketed to 1e-7°."""
    s = mech.drive.sketch_value
    ok, bad = s, None
    for k in range(1, 361):
        _, err = _outcome(lambda: _full(monkeypatch, mech, structure, np.array([s + k]), order=0))
        if err is not None:
            bad = s + k
            break
        ok = s + k
    if bad is None:
        return None
    while bad - ok > 1e-7:
        mid = 0.5 * (ok + bad)
        _, err = _outcome(lambda: _full(monkeypatch, mech, structure, np.array([mid]), order=0))
        ok, bad = (mid, bad) if err is None else (ok, mid)
    return ok, bad


def test_limit_between_walk_step_and_value_is_refused(monkeypatch):
    """A value just past a limit (or singular) position that lies between the walk's last
    step and the value is refused as the full walk refuses it, with the same message."""
    tested = 0
    for stem in CLASS_II:
        mech, structure = _load(EXAMPLES / f"{stem}.toml")
        if mech.drive.kind != "rotary":
            continue
        found = _limit(mech, structure, monkeypatch)
        if found is None:
            continue
        ok, bad = found
        values = np.array([mech.drive.sketch_value, ok, bad + 1e-6])
        _, fast_err = _outcome(lambda: analyse(mech, structure, values, order=2))
        _, full_err = _outcome(lambda: _full(monkeypatch, mech, structure, values))
        assert fast_err is not None and fast_err == full_err
        fine, _ = _outcome(lambda: analyse(mech, structure, values[:2], order=0))
        assert fine is not None
        tested += 1
    assert tested, "no class II example has a limit position within a turn of its sketch"

"""Property tests of the continuation of random class II mechanisms: a drive angle far from the sketch's.

* after a walk of up to 179° from the sketch (never across a singular angle) every point is
  where the builder's closed form puts it on the sketch's branch (``Case.rebuild``), and the
  velocities and accelerations are those of the mechanism sketched there (``check`` of
  ``test_properties.py``).

A bug found here is fixed and kept as a test, once a strict xfail: a walk longer than half a
turn that depended on the other requested angles (``WALK_CASE``).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from plans.kinematics import analyse

from property_cases import Case, _u
from property_strategies import STRATEGIES, _f, cases
#: autouse, module scope: prints ``WORST`` at the end of this module (imported, so ruff sees no use)
from test_properties import _report  # noqa: F401
from test_properties import COMMON, EPS, check, event, load, record

#: with filterwarnings = error, hypothesis' report of a failing example (its patch writer
#: imports libcst → mypy_extensions, deprecated) would turn into an INTERNALERROR hiding it
pytestmark = pytest.mark.filterwarnings("ignore:mypy_extensions.TypedDict is deprecated:DeprecationWarning")


# --- continuation: a drive angle far from the sketch's ---------------------------------------------

#: positions after a walk against the builders' closed forms at the same angle, relative to the
#: mechanism's extent (two different formulas for the same point: a few ulps, amplified by the
#: group's conditioning 1/|sin|, which the regular cases keep below ~30)
TOL_WALK = 1e-12


def _free_arc(case: Case) -> tuple[float, float]:
    """How far (rad) the drive may turn down and up from the sketch before a singular angle."""
    phi = math.radians(case.phi)
    ups = [(s - phi) % (2 * math.pi) for s in case.singular]
    return (min((2 * math.pi - u for u in ups), default=math.inf), min(ups, default=math.inf))


@settings(max_examples=100, **COMMON)
@given(case=st.one_of([cases(form, mode="regular") for form in STRATEGIES]), t=_f(0.0, 1.0))
def test_walk_from_the_sketch_keeps_the_branch(case, t):
    """Requested 0..179° away from the sketch (never across a singular angle, which plans
    refuses), alone or together with the sketch's angle: every point is where the builder's
    closed form puts it on the sketch's branch at the requested angle, and the velocities and
    accelerations are those of the same mechanism sketched at that angle, which pass every
    check of ``check``."""
    down, up = _free_arc(case)
    margin = math.radians(0.5)
    # at most half a turn, so that the angle alone and with the sketch's are walked to along the
    # same steps (compared bit for bit below); longer walks: test_walk_longer_than_half_a_turn
    lo, hi = -min(down - margin, math.radians(179.0)), min(up - margin, math.radians(179.0))
    turn = lo + t * (hi - lo)
    target = case.rebuild(math.radians(case.phi) + turn)
    event("full turn" if not case.singular else "limited turn")
    mech, structure = load(case.scene)
    m = analyse(mech, structure, np.array([target.phi]))
    both = analyse(mech, structure, np.array([case.phi, target.phi]), order=0)
    assert all(np.array_equal(both.links[n].origin[1], m.links[n].origin[0]) for n in m.links)
    size = max(mech.size, load(target.scene)[0].size)
    err = max(np.linalg.norm(m.position(p)[0] - np.asarray(xy)) for p, xy in target.scene["points"].items()) / size
    record(f"{case.form}: walk: |r - r_closed form| / size", err, f"{case.label} → {target.phi:.6g}°")
    # two formulas for one pose differ by a few ulps amplified by 1/|sin| (the group's
    # conditioning there; the walk may end 0.5° from a singular angle, |sin| ~ 0.009);
    # velocities from the two poses differ by that times 1/|sin| again, accelerations twice
    cond = min([1.0] + [abs(float(s[0])) for s in m.sines.values()])
    tol = {k: max(TOL_WALK, 16 * EPS / cond ** (k + 1)) for k in range(3)}
    assert err < tol[0], f"{case.label}: walked to {target.phi:g}°, a point is {err:.3g}·size off"
    there = check(target)
    for k, qty in ((1, "velocity"), (2, "acceleration")):
        got = {p: getattr(m, qty)(p)[0] for p in target.scene["points"]}
        want = {p: getattr(there, qty)(p)[0] for p in target.scene["points"]}
        scale = max(np.linalg.norm(v) for v in want.values())
        err = max(np.linalg.norm(got[p] - want[p]) for p in got) / scale
        record(f"{case.form}: walk: {qty} vs sketched there", err, f"{case.label} → {target.phi:.6g}°")
        assert err < tol[k], f"{case.label}: walked to {target.phi:g}°, {qty} off by {err:.3g} (tol {tol[k]:.1e})"


#: A slotted lever whose crank cannot turn fully (limit positions at ±36.3°), sketched at
#: −108.17°: −308.17° is reached by turning the crank 200° down, without passing a limit.
WALK_CASE = Case("RPR", {"title": "random slotted lever",
                         "points": {"O": [0.0, 0.0], "C": [0.1875, 0.0],
                                    "A": [-0.11692679333668564, -0.35630482034348065],
                                    "T": [0.043634633589446636, -0.989597269775719]},
                         "links": {"0": ["O", "C"], "1": ["O", "A"], "2": ["A"], "3": ["C", "T"]},
                         "sliders": [{"link": "2", "on": "3", "through": "A", "angle": -98.27158059498339}],
                         "drive": {"link": "1", "angle": -108.16802875730697, "omega": 1.0, "epsilon": 0.0}},
                 -108.16802875730697, singular=(0.6341838408240408, -0.6341838408240408),
                 delta=1.2537044063828762, note="regular")


def test_walk_longer_than_half_a_turn():
    """Found by test_walk_from_the_sketch_keeps_the_branch (turn −200°) before it was limited to
    half a turn; once a strict xfail (alone, −308.17° was walked to from −468.17°, up across the
    limit position at −396.17°, and refused). The same angle, requested alone and with the
    sketch's, gives the same pose: alone it is now walked the long way round when the short
    way passes a limit position."""
    mech, structure = load(WALK_CASE.scene)
    target = WALK_CASE.phi - 200.0
    together = analyse(mech, structure, np.array([target, WALK_CASE.phi]), order=0)
    r = math.hypot(*WALK_CASE.scene["points"]["A"])
    assert np.linalg.norm(together.position("A", "2")[0] - r * _u(math.radians(target))) < 1e-12
    alone = analyse(mech, structure, np.array([target]), order=0)
    for link in ("2", "3"):
        assert np.array_equal(alone.links[link].theta[0], together.links[link].theta[0])
        assert np.array_equal(alone.links[link].origin[0], together.links[link].origin[0])

"""Continuation: no branch jumps.

Full revolutions at 1° steps against the reference's own continuation (``tests/reference.py``):
every step bounded by the reference's largest rate, every link back to its pose after a full
turn, the same positions whichever values are requested together and in whichever direction
the walk goes; and the RPR branch when links carry only their pivots.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from plans.kinematics import analyse

#: autouse, module scope: prints ``WORST`` at the end of this module (imported, so ruff sees no use)
from kinematics_cases import _report  # noqa: F401
from kinematics_cases import (CASES, EXAMPLES, TOL_REF, Reference, _load, _size, compare_with_reference, record,
                              scene_slotted_lever)


# --- continuation: no branch jumps --------------------------------------------------------------

def test_four_bar_continuation_never_jumps_branch():
    """A full revolution of the four-bar at 1° steps: the coupler point M moves at most
    1.05·max|dM/dφ|·1° between steps (max|dM/dφ| = max|v_M|/ω from the reference at the same 1°
    steps), ends where it started, agrees with the reference's own continuation at every step,
    and does not depend on which values were requested together or on the walk's direction."""
    mech, structure = _load(EXAMPLES / "four_bar.toml")
    values = np.arange(0.0, 361.0, 1.0)
    M = analyse(mech, structure, values, order=0).position("M", "2")
    states = Reference(mech).solve(values)
    rate = max(np.linalg.norm(s.velocity("M", "2")) for s in states) / mech.drive.speed
    bound = 1.05 * rate * math.radians(1.0)
    steps = np.linalg.norm(np.diff(M, axis=0), axis=1)
    record("continuation: largest step / bound", float(steps.max() / bound), "four_bar")
    assert steps.max() < bound
    assert np.linalg.norm(M[-1] - M[0]) < 1e-12
    err = max(np.linalg.norm(M[i] - s.position("M", "2")) for i, s in enumerate(states))
    record("continuation: |M - M_ref| / size", float(err / _size(mech)), "four_bar")
    assert err < 1e-12
    backwards = analyse(mech, structure, -values, order=0).position("M", "2")
    assert np.max(np.abs(backwards[::-1] - M)) < 1e-12
    for v in (179.0, 359.0, -181.0, 719.0):
        alone = analyse(mech, structure, np.array([v]), order=0).position("M", "2")[0]
        assert np.linalg.norm(alone - M[int(v) % 360]) < 1e-12


@pytest.mark.parametrize("name", ["six_link_press", "quick_return", "prp_moving_guides", "rpr_moving_pivots"])
def test_continuation_of_multi_group_mechanisms_is_continuous(name):
    """Every link's angle changes by at most 1.05·max|ω|/ω_drive·1° per 1° step (max|ω| from
    the reference), and every link comes back to its pose after a full turn."""
    src, _, _ = CASES[name]
    mech, structure = _load(src)
    values = np.arange(0.0, 361.0, 1.0) + 10.0
    m = analyse(mech, structure, values, order=0)
    states = Reference(mech).solve(values)
    for n in mech.links:
        if mech.links[n].is_frame:
            continue
        st = m.links[n]
        bound = 1.05 * math.radians(1.0) * max(abs(s.omega(n)) for s in states) / abs(mech.drive.speed) + 1e-12
        theta = np.unwrap(st.theta)
        assert np.abs(np.diff(theta)).max() < bound, f"link {n}: jump of {np.abs(np.diff(theta)).max():.3g} rad"
        assert abs(math.remainder(theta[-1] - theta[0], 2 * math.pi)) < 1e-12
        assert np.linalg.norm(st.origin[-1] - st.origin[0]) < 1e-12 * max(1.0, float(np.abs(st.origin).max()))


def test_rpr_branch_when_links_carry_only_their_pivots():
    """An offset slot in a lever that carries only its pivot C, and a block that carries only A:
    the two RPR branches put every named point at the same place but differ in θ and ω.
    Regression: the branch was chosen from the named points only, so it was picked by rounding
    noise (ω3 = 0 instead of 2.3077 rad/s at the sketch angle 30° itself)."""
    mech, structure = _load(scene_slotted_lever(0.25, 30.0, lever_points=("C",)))
    values = np.array([30.0, 0.0, 60.0, 100.0, 150.0])
    compare_with_reference(mech, analyse(mech, structure, values), Reference(mech).solve(values), TOL_REF,
                           "RPR pivots only", kind="RPR, links with only their pivots")

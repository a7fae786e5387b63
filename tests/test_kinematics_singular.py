"""Kinematics near and at singular positions, every form, against independent computations.

The singular positions are found by the reference (``tests/reference.py``: Moore–Spence
extended system on its Jacobian) or by exact geometry. 0.9° and 0.5° from them, on the side
where the mechanism assembles, plans agrees with the reference's Jacobian solve (relative to
the largest magnitude of the same quantity, as in ``test_kinematics.py``); where two branches
cross, both are checked against the four-bar solved in 50 digits. Closing in (10⁻² .. 10⁻¹³
degrees) gives finite values or an error, exactly there analyse raises, beyond a limit position
the mechanism cannot assemble; the tangent mechanism's walk does not cross its pole, and an RPP
whose guides are almost parallel is near-singular at every position.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from plans.errors import AssemblyError, SingularPositionError
from plans.kinematics import analyse

#: autouse, module scope: prints ``WORST`` at the end of this module (imported, so ruff sees no use)
from kinematics_cases import _report  # noqa: F401
from kinematics_cases import (EXAMPLES, Reference, _four_bar_in_50_digits, _fourbar_points, _load, _pairs, _pt,
                              _size, compare_with_reference, record, scene_slotted_lever)

#: plans against the reference near singular positions (0.5° .. 1° away)
TOL_NEAR = 1e-9
#: the same where two branches cross (sin ∝ distance, not √distance): accelerations there are
#: conditioned like eps/sin³, and a 50-digit closed form shows double precision cannot do better
TOL_NEAR_CROSSING = 1e-7


# --- near and at singular positions, every form -----------------------------------------------

def scene_four_bar(r, d, lm, ln, phi0, omega=10.0, epsilon=0.0) -> dict:
    O, A, B, C = _fourbar_points(r, d, lm, ln, phi0)
    return {"points": {"O": _pt(O), "C": _pt(C), "A": _pt(A), "B": _pt(B)},
            "links": {"0": ["O", "C"], "1": ["O", "A"], "2": ["A", "B"], "3": ["C", "B"]},
            "drive": {"link": "1", "angle": phi0, "omega": omega, "epsilon": epsilon},
            "lengths": {"OA": r, "OC": abs(d), "AB": lm, "BC": ln}}


def scene_crank_slider(r, l, guide_y, phi0, omega=10.0, epsilon=5.0) -> dict:
    A = r * np.array([math.cos(math.radians(phi0)), math.sin(math.radians(phi0))])
    B = np.array([A[0] + math.sqrt(l * l - (A[1] - guide_y) ** 2), guide_y])
    return {"points": {"O": [0.0, 0.0], "A": _pt(A), "B": _pt(B)},
            "links": {"0": ["O"], "1": ["O", "A"], "2": ["A", "B"], "3": ["B"]},
            "sliders": [{"link": "3", "on": "0", "through": "B", "angle": 0.0}],
            "drive": {"link": "1", "angle": phi0, "omega": omega, "epsilon": epsilon},
            "lengths": {"OA": r, "AB": l}}


def scene_yoke(slot_angle, phi0=60.0) -> dict:
    """Scotch yoke whose slot makes ``slot_angle`` degrees with the yoke's frame guide (RPP)."""
    A = [0.1 * math.cos(math.radians(phi0)), 0.1 * math.sin(math.radians(phi0))]
    return {"points": {"O": [0.0, 0.0], "A": A, "Y": [0.25, 0.0]},
            "links": {"0": ["O"], "1": ["O", "A"], "2": ["A"], "3": ["Y"]},
            "sliders": [{"link": "2", "on": "3", "through": "A", "angle": slot_angle},
                        {"link": "3", "on": "0", "through": "Y", "angle": 0.0}],
            "drive": {"link": "1", "angle": phi0, "omega": 10.0, "epsilon": -20.0}}


def _fold(mech, near: float) -> float:
    """The drive value of the singular (limit) position next to ``near``, found by the reference
    (Moore–Spence extended system on its Jacobian)."""
    ref = Reference(mech)
    return ref.fold(ref.solve([near])[0]).value


def _parallel_slot_angle(mech) -> float:
    """Tangent mechanism: the crank angle at which the slot of link 1 (its local direction, from
    the model) is parallel to the frame guide. The example's 9-digit sketch puts the slot
    1.2e-7° off the crank arm O→K, so this is 90.00000012°, not 90°."""
    pr = {p.slider: p for p in mech.prismatics}
    local = mech.links[mech.drive.link].local
    arm = local[mech.drive.tip] - local[mech.drive.pivot]
    slot, guide = pr["2"].direction, pr["3"].direction
    return math.degrees(math.atan2(guide[1], guide[0]) + math.atan2(arm[1], arm[0]) - math.atan2(slot[1], slot[0]))


def _singular_rrr_fold():
    """Non-Grashof four-bar (OA 0.2, OC 0.3, AB 0.25, BC 0.2): the crank stops where coupler and
    rocker are collinear, |AC| = AB + BC; by the law of cosines 0.45² = 0.2² + 0.3² − 0.12·cos φ."""
    mech, structure = _load(scene_four_bar(0.2, 0.3, 0.25, 0.2, 60.0, epsilon=-7.0))
    phi = _fold(mech, 126.0)
    assert phi == pytest.approx(math.degrees(math.acos((0.04 + 0.09 - 0.45 ** 2) / 0.12)), abs=1e-10)
    return mech, structure, [phi], -1.0, "RRR", TOL_NEAR


def _singular_rrr_change_of_branch():
    """OA 0.125, OC 0.5 (C behind O), AB 0.375, BC 0.25: |AC| = AB + BC exactly at φ = 0 and
    less elsewhere, so coupler and rocker are collinear there (every number binary-exact)."""
    mech, structure = _load(scene_four_bar(0.125, -0.5, 0.375, 0.25, 90.0))
    return mech, structure, [0.0], 1.0, "RRR", TOL_NEAR_CROSSING


def _singular_rrp():
    """Crank 0.2 m, rod 0.1 m, guide through O: the rod is perpendicular to the guide (and the
    crank stops) where 0.2·sin φ = 0.1, φ = 30°."""
    mech, structure = _load(scene_crank_slider(0.2, 0.1, 0.0, 10.0))
    phi = _fold(mech, 29.0)
    assert phi == pytest.approx(30.0, abs=1e-10)
    return mech, structure, [phi, 30.0], -1.0, "RRP", TOL_NEAR


def _singular_rpr():
    """Slot 0.25 m from the lever pivot C and |AC|² = 0.1 + 0.06·sin φ: the slot is
    perpendicular to AC (D, E, F a right angle at D) where |AC| = 0.25, sin φ = −0.625."""
    mech, structure = _load(scene_slotted_lever(0.25, 30.0))
    phi = _fold(mech, -37.0)
    assert phi == pytest.approx(math.degrees(math.asin(-0.625)), abs=1e-10)
    return mech, structure, [phi], 1.0, "RPR", TOL_NEAR


def _singular_prp(side):
    def build():
        """Tangent mechanism: the slot is parallel to the frame guide at φ ≈ ±90°."""
        mech, structure = _load(EXAMPLES / "tangent_mechanism.toml")
        phi = _parallel_slot_angle(mech) - (180.0 if side < 0 else 0.0)
        assert phi == pytest.approx(90.0 * side, abs=1e-6)
        return mech, structure, [phi], -side, "PRP", TOL_NEAR
    return build


SINGULAR = {
    "RRR fold": _singular_rrr_fold,
    "RRR change of branch": _singular_rrr_change_of_branch,
    "RRP": _singular_rrp,
    "RPR": _singular_rpr,
    "PRP +90": _singular_prp(1.0),
    "PRP -90": _singular_prp(-1.0),
}


@pytest.mark.parametrize("case", list(SINGULAR))
def test_near_singular_position(case):
    """plans against the reference 0.9° and 0.5° from the singular position (on the side where
    the mechanism assembles), and no inf/NaN while closing in (10⁻² .. 10⁻¹³ degrees away:
    either finite values or an error)."""
    mech, structure, singular, side, form, tol = SINGULAR[case]()
    assert [g.form for g in structure.groups] == [form]
    values = singular[0] + side * np.array([0.9, 0.5])
    states = Reference(mech).solve(values)
    motion = analyse(mech, structure, values)
    sines = np.abs(next(iter(motion.sines.values())))
    assert np.all(sines > 1e-3) and np.all(sines < 0.5)           # near-singular, not singular
    kind = "near-singular" if tol == TOL_NEAR else "near-singular (crossing)"
    compare_with_reference(mech, motion, states, tol, case, kind=kind)
    for k in range(2, 14):
        try:
            m = analyse(mech, structure, np.array([singular[0] + side * 10.0 ** -k]))
        except (SingularPositionError, AssemblyError):
            continue
        for n, p in _pairs(mech):
            assert np.all(np.isfinite(m.acceleration(p, n))) and np.all(np.isfinite(m.velocity(p, n)))


@pytest.mark.parametrize("delta", [0.9, 0.5])
def test_crossing_against_50_digit_four_bar(delta):
    """Where two branches cross, double precision itself limits the accuracy: plans and the
    reference against the four-bar solved in 50 digits (both to TOL_NEAR_CROSSING)."""
    mech, structure, singular, side, _, tol = SINGULAR["RRR change of branch"]()
    phi = singular[0] + side * delta
    m = analyse(mech, structure, np.array([phi]))
    r = Reference(mech).solve([phi])[0]
    exact = _four_bar_in_50_digits(mech, phi, r.position("B", "3"))     # the reference's branch
    size = _size(mech)
    for who, B, vB, aB, w, e in (
            ("plans", m.position("B", "3")[0], m.velocity("B", "3")[0], m.acceleration("B", "3")[0],
             np.array([m.links["2"].omega[0], m.links["3"].omega[0]]),
             np.array([m.links["2"].epsilon[0], m.links["3"].epsilon[0]])),
            ("reference", r.position("B", "3"), r.velocity("B", "3"), r.acceleration("B", "3"),
             np.array([r.omega("2"), r.omega("3")]), np.array([r.epsilon("2"), r.epsilon("3")]))):
        errs = {"position": np.linalg.norm(B - exact["B"]) / size,
                "velocity": np.linalg.norm(vB - exact["v_B"]) / np.linalg.norm(exact["v_B"]),
                "acceleration": np.linalg.norm(aB - exact["a_B"]) / np.linalg.norm(exact["a_B"]),
                "omega": np.max(np.abs(w - exact["w"])) / np.max(np.abs(exact["w"])),
                "epsilon": np.max(np.abs(e - exact["e"])) / max(np.max(np.abs(exact["e"])),
                                                                np.linalg.norm(exact["a_B"]) / size)}
        for qty, err in errs.items():
            record(f"50-digit crossing, {who}: {qty}", float(err), f"@ {phi:g}")
            assert err < tol, f"{who} {qty} at {phi}: {err:.3g}"


@pytest.mark.parametrize("case", list(SINGULAR))
def test_singular_position_raises(case):
    """Exactly at the singular position (as found by the reference or by exact geometry) analyse
    raises SingularPositionError (or AssemblyError, when rounding puts it just outside), also
    when the singular value is one of several requested.

    Regression (RRP): with SINGULAR_SIN = 1e-9, below the rounding floor of a dead centre
    (|sin| ~ √eps ~ 1e-8 there), analyse returned v_B ≈ −7.6e7 m/s at exactly φ = 30°."""
    mech, structure, singular, side, _, _ = SINGULAR[case]()
    for phi in singular:
        with pytest.raises((SingularPositionError, AssemblyError)):
            analyse(mech, structure, np.array([phi]))
        with pytest.raises((SingularPositionError, AssemblyError)):
            analyse(mech, structure, np.array([phi + side * 0.5, phi]))


@pytest.mark.parametrize("case", ["RRR fold", "RRP", "RPR"])
def test_beyond_a_limit_position_cannot_assemble(case):
    mech, structure, singular, side, _, _ = SINGULAR[case]()
    with pytest.raises(AssemblyError) as info:
        analyse(mech, structure, np.array([singular[0] - side * 0.5]))
    assert not isinstance(info.value, SingularPositionError)


@pytest.mark.parametrize("target", [100.0, 90.5, -95.0])
def test_walk_does_not_cross_parallel_guides(target):
    """The tangent mechanism cannot pass φ = ±90° (the slider would go through infinity).
    Regression: the walk checked each 1° step for assembly only, crossed the pole and returned
    B = (0.15, −0.851) m at φ = 100°."""
    mech, structure = _load(EXAMPLES / "tangent_mechanism.toml")
    with pytest.raises(AssemblyError):
        analyse(mech, structure, np.array([target]))


@pytest.mark.parametrize("slot_angle", [0.5, 0.9, -0.5])
def test_rpp_near_parallel_guides(slot_angle):
    """RPP: the two guides of the yoke keep their angle, so the group is near-singular at every
    position when the slot is almost parallel to the frame guide."""
    mech, structure = _load(scene_yoke(slot_angle))
    assert [g.form for g in structure.groups] == ["RPP"]
    values = np.array([-100.0, 15.0, 60.0, 130.0])
    motion = analyse(mech, structure, values)
    assert np.all(np.abs(motion.sines["II(2-3)"]) < 0.02)
    compare_with_reference(mech, motion, Reference(mech).solve(values), TOL_NEAR, f"RPP slot {slot_angle}°",
                           kind="near-singular")


def test_rpp_parallel_guides_is_an_error():
    mech, structure = _load(scene_yoke(0.0))
    with pytest.raises((SingularPositionError, AssemblyError)):
        analyse(mech, structure, np.array([60.0]))

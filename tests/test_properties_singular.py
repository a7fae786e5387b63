"""Property tests at and next to the singular positions of random class II mechanisms.

The mechanisms are those of ``test_properties.py`` (``property_strategies.py``), drawn 1° from
a singular drive angle found analytically:

* exactly at a singular position analyse raises (SingularPositionError or AssemblyError),
  alone or among other requested angles, and closer than 10⁻³° it either raises or returns
  finite numbers; an RPP group with exactly parallel guides raises at every φ;
* four-bars near their folds against the four-bar solved in 50 digits (1e-7, no floor).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from plans.errors import AssemblyError, SingularPositionError
from plans.kinematics import analyse

from property_strategies import SIGN, _f, cases, rpp_cases
#: autouse, module scope: prints ``WORST`` at the end of this module (imported, so ruff sees no use)
from test_properties import _report  # noqa: F401
from test_properties import COMMON, TOL_CLOSURE, TOL_FD, event, load, record

#: with filterwarnings = error, hypothesis' report of a failing example (its patch writer
#: imports libcst → mypy_extensions, deprecated) would turn into an INTERNALERROR hiding it
pytestmark = pytest.mark.filterwarnings("ignore:mypy_extensions.TypedDict is deprecated:DeprecationWarning")


# --- at and closer than 10⁻³° to the singular position: an error, never inf or NaN ------------------

def _raises_or_finite(mech, structure, values) -> str:
    try:
        m = analyse(mech, structure, np.asarray(values, float))
    except (SingularPositionError, AssemblyError):
        return "raised"
    for name, s in m.links.items():
        for arr in (s.theta, s.origin, s.omega, s.v, s.epsilon, s.a):
            assert np.all(np.isfinite(arr)), f"link {name}: non-finite state at {values}"
    return "finite"


def _singular_test(form: str, doc: str):
    @settings(max_examples=N_SINGULAR, **COMMON)
    @given(case=cases(form, mode="near", delta_deg=1.0), closer=st.lists(_f(-13.0, -3.0), min_size=3, max_size=3))
    def test(case, closer):
        mech, structure = load(case.scene)
        # the nearest singular drive angle, continued to the sketch's turn
        target = case.phi + math.degrees(min((math.remainder(s_ - math.radians(case.phi), 2 * math.pi)
                                              for s_ in case.singular), key=abs))
        assert abs(abs(target - case.phi) - 1.0) < 1e-9
        side = math.copysign(1.0, case.phi - target)
        for values in ([target], [case.phi, target], [target, case.phi + side * 0.5]):
            with pytest.raises((SingularPositionError, AssemblyError)):
                analyse(mech, structure, np.array(values))
        # closer than the accuracy range: an error or finite numbers
        for k in sorted(closer):
            event(_raises_or_finite(mech, structure, [target + side * 10.0 ** k]))
    test.__doc__ = doc
    return test


N_SINGULAR = 25
test_rrr_at_fold = _singular_test("RRR", "Four-bars exactly at coupler-rocker collinear (sketch 1° away).")
test_rrp_at_fold = _singular_test("RRP", "RRP exactly at rod ⟂ guide (frame guide and crank slot).")
test_rpr_at_fold = _singular_test("RPR", "Slotted levers exactly at |AC| = slot offset.")
test_prp_at_parallel = _singular_test("PRP", "Tangent mechanisms exactly at parallel guides.")


@settings(max_examples=N_SINGULAR, **COMMON)
@given(case=rpp_cases(mode="regular", gamma=st.one_of(
    st.sampled_from([0.0, math.pi]),
    st.tuples(SIGN, _f(-13.0, -3.0)).map(lambda t: t[0] * math.radians(10.0 ** t[1])))).filter(lambda c: c is not None))
def test_rpp_at_parallel(case):
    """RPP with exactly parallel guides (γ = 0 or π) raises at every φ; 1e-13..1e-3° from
    parallel it raises or returns finite numbers."""
    mech, structure = load(case.scene)
    values = case.phi + np.array([0.0, 1.0, 90.0])
    if case.parallel == 0.0:
        with pytest.raises((SingularPositionError, AssemblyError)):
            analyse(mech, structure, values)
    else:
        event(_raises_or_finite(mech, structure, values))


# --- an exact oracle where one is cheap: the four-bar near its folds in 50 digits ----------------

@settings(max_examples=40, **COMMON)
@given(case=cases("RRR", mode="near"))
def test_rrr_near_fold_against_50_digit_closed_form(case):
    """1e-3..1° from a fold, v_B, a_B, ω and ε of coupler and rocker against the four-bar solved
    in 50-digit arithmetic from the model's own float data (kinematics_cases'
    ``_four_bar_in_50_digits``): relative 1e-7, no floor — double precision has enough digits
    here (plans' error grows like eps/sin³, sin ≥ ~2e-3 at 1e-3° from a fold)."""
    from kinematics_cases import _four_bar_in_50_digits

    mech, structure = load(case.scene)
    m = analyse(mech, structure, np.array([case.phi]))
    exact = _four_bar_in_50_digits(mech, case.phi, m.position("B", "3")[0])
    size = mech.size
    errs = {"position": np.linalg.norm(m.position("B", "3")[0] - exact["B"]) / size,
            "velocity": np.linalg.norm(m.velocity("B", "3")[0] - exact["v_B"]) / np.linalg.norm(exact["v_B"]),
            "acceleration": np.linalg.norm(m.acceleration("B", "3")[0] - exact["a_B"]) / max(
                np.linalg.norm(exact["a_B"]), abs(mech.drive.speed) * np.linalg.norm(exact["v_B"])),
            "omega": np.max(np.abs([m.links["2"].omega[0] - exact["w"][0], m.links["3"].omega[0] - exact["w"][1]]))
            / np.max(np.abs(exact["w"])),
            "epsilon": np.max(np.abs([m.links["2"].epsilon[0] - exact["e"][0],
                                      m.links["3"].epsilon[0] - exact["e"][1]]))
            / max(np.max(np.abs(exact["e"])), np.linalg.norm(exact["a_B"]) / size)}
    for qty, err in errs.items():
        record(f"RRR: 50-digit near fold: {qty}", float(err), case.label)
        assert err < (TOL_CLOSURE if qty == "position" else TOL_FD), f"{case.label}: {qty} {err:.3g}"

"""Kinematics of plans checked against independent computations.

Every expected number here comes from somewhere other than plans' closed forms:

* the generic Jacobian solver of ``tests/reference.py`` (Newton continuation from the sketch,
  then Φ_q·q̇ = −Φ_t and Φ_q·q̈ = γ);
* central finite differences of plans' own *positions* (``order=0``) along the drive;
* textbook closed forms of the crank-slider;
* identities every rigid body and every pair must satisfy.

Errors are measured relative to the largest magnitude of the same quantity at the same
position (the largest point velocity, the largest |ω|, ...). The worst relative error of each
kind is collected in ``WORST`` and printed at the end of each module (run pytest with ``-s``).

Here: the examples and extra scenes at regular positions against the reference, finite
differences, the crank-slider's closed forms and the identities. Near and at singular positions:
``test_kinematics_singular.py``; continuation (no branch jumps): ``test_kinematics_continuation.py``;
the shared scenes, ``compare_with_reference`` and ``WORST``: ``kinematics_cases.py``.
"""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from plans.kinematics import analyse

#: autouse, module scope: prints ``WORST`` at the end of this module (imported, so ruff sees no use)
from kinematics_cases import _report  # noqa: F401
from kinematics_cases import (CASES, TOL_REF, Reference, _load, _pairs, _size, compare_with_reference,
                              record)

#: plans against finite differences of its positions: velocities, accelerations. The 6th-order
#: differences err by truncation, h⁶/140·|r⁽⁷⁾| and h⁶/560·|r⁽⁸⁾|, plus the positions' rounding δ
#: amplified by Σ|FD1|/h = 1.83/h and Σ|FD2|/h² = 6.04/h². The two worst cases: the tangent
#: mechanism 5° from its pole (s ∝ tan φ, r⁽ᵏ⁾ ~ k!/δᵏ⁺¹ against v ~ 1/δ²: 7!/140·(h/δ)⁶ =
#: 36·(0.05°/5°)⁶ = 3.6e-11 of v, measured 3.6e-11) and the hydraulic boom's accelerations
#: (h = 0.3 mm, positions up to 2 m: 6.04·eps·|r|/h² = 5e-10 of max|a| for each eps·|r| of δ;
#: measured 2.3e-9). The tolerances allow δ ≤ 16 eps·|r| (8e-9) and ~3× that truncation.
TOL_FD_V = 1e-10
TOL_FD_A = 1e-8
#: textbook closed forms
TOL_CLOSED = 1e-12
#: rigidity identities (relative to |v|·size, |a|·size)
TOL_RIGID = 1e-12

# 6th-order central differences on offsets -3..3: first and second derivative
FD1 = np.array([-1 / 60, 3 / 20, -3 / 4, 0.0, 3 / 4, -3 / 20, 1 / 60])
FD2 = np.array([1 / 90, -3 / 20, 3 / 2, -49 / 18, 3 / 2, -3 / 20, 1 / 90])
OFFSETS = np.arange(-3, 4)


def test_the_seven_examples_are_covered():
    assert {"crank_slider_central", "crank_slider_offset", "four_bar", "quick_return", "scotch_yoke",
            "six_link_press", "tangent_mechanism"} <= set(CASES)


def test_extra_scenes_cover_every_form():
    forms = {g.form for name, (src, _, _) in CASES.items() for g in _load(src)[1].groups if g.klass == 2}
    assert forms == {"RRR", "RRP", "RPR", "PRP", "RPP"}


def _si(mech, value: float) -> float:
    return math.radians(value) if mech.drive.kind.angular else value


# --- (a) plans against the generic Jacobian solve ---------------------------------------------

@pytest.mark.parametrize("name", sorted(CASES))
def test_against_reference_jacobian_solve(name):
    src, values, _ = CASES[name]
    mech, structure = _load(src)
    states = Reference(mech).solve(values)          # continuation from the sketch, independent of plans
    motion = analyse(mech, structure, values)
    compare_with_reference(mech, motion, states, TOL_REF, name)


@pytest.mark.parametrize("name", ["four_bar", "quick_return", "prp_moving_guides", "linear_drive"])
def test_reference_newton_from_perturbed_plans_pose(name):
    """The reference's Newton, started from plans' poses perturbed by 1e-3, lands on the same
    positions (plans' positions satisfy every pair's constraint equations)."""
    src, values, _ = CASES[name]
    mech, structure = _load(src)
    motion = analyse(mech, structure, values)
    ref = Reference(mech)
    rng = np.random.default_rng(1)
    states = []
    for i, v in enumerate(values):
        q = np.concatenate([[*motion.links[n].origin[i], motion.links[n].theta[i]] for n in ref.moving])
        states.append(ref.at(v, q + 1e-3 * rng.standard_normal(q.shape)))
    compare_with_reference(mech, motion, states, TOL_REF, name, kind="ref-newton")


@pytest.mark.parametrize("name", ["four_bar", "quick_return", "tangent_mechanism", "linear_drive",
                                  "prp_moving_guides", "rpp_rotating"])
def test_reference_is_consistent_with_its_own_positions(name):
    """Self-check of the reference (γ in particular): its q̇, q̈ against central differences of
    its own Newton positions."""
    src, values, step = CASES[name]
    mech, _ = _load(src)
    ref = Reference(mech)
    w, e = mech.drive.speed, mech.drive.rate
    h = _si(mech, step)
    for state in ref.solve(values[::3]):
        qs = np.array([ref.newton(state.q, state.value + k * step) for k in OFFSETS])
        d1, d2 = FD1 @ qs / h, FD2 @ qs / h ** 2
        for got, want, kind in ((state.qd, w * d1, "velocity"), (state.qdd, w * w * d2 + e * d1, "acceleration")):
            err = np.max(np.abs(got - want)) / np.max(np.abs(want))
            record(f"reference vs own FD: {kind}", err, f"{name} @ {state.value:g}")
            assert err < (TOL_FD_V if kind == "velocity" else TOL_FD_A)


# --- (b) plans against finite differences of its own positions --------------------------------

@pytest.mark.parametrize("name", sorted(CASES))
def test_against_finite_differences(name):
    """v = V·dr/ds, a = V²·d²r/ds² + A·dr/ds (s the drive coordinate in rad or m, V and A its
    rate and acceleration), the derivatives by 6th-order central differences of plans'
    positions; the same for θ of every link (ω, ε)."""
    src, values, step = CASES[name]
    mech, structure = _load(src)
    motion = analyse(mech, structure, values)
    w, e = mech.drive.speed, mech.drive.rate
    h = _si(mech, step)
    size = _size(mech)
    pts = _pairs(mech)
    moving = [n for n in mech.links if not mech.links[n].is_frame]
    for i, v in enumerate(values):
        near = analyse(mech, structure, v + step * OFFSETS, order=0)
        where = f"{name} @ {v:g}"
        for qty, fd, got_of in (("velocity", lambda P: w * (FD1 @ P) / h, motion.velocity),
                                ("acceleration", lambda P: w * w * (FD2 @ P) / h ** 2 + e * (FD1 @ P) / h,
                                 motion.acceleration)):
            want = {k: fd(near.position(k[1], k[0])) for k in pts}
            scale = max(np.linalg.norm(x) for x in want.values())
            err = max(np.linalg.norm(got_of(k[1], k[0])[i] - want[k]) for k in pts) / scale
            record(f"FD: {qty}", err, where)
            assert err < (TOL_FD_V if qty == "velocity" else TOL_FD_A), f"{qty} at {where}: {err:.3g}"
        theta = {n: np.unwrap(near.links[n].theta) for n in moving}
        om = {n: w * (FD1 @ theta[n]) / h for n in moving}
        ep = {n: w * w * (FD2 @ theta[n]) / h ** 2 + e * (FD1 @ theta[n]) / h for n in moving}
        vmax = max(np.linalg.norm(motion.velocity(p, n)[i]) for n, p in pts)
        amax = max(np.linalg.norm(motion.acceleration(p, n)[i]) for n, p in pts)
        err = max(abs(motion.links[n].omega[i] - om[n]) for n in moving) / max(
            max(abs(x) for x in om.values()), vmax / size)
        record("FD: omega", err, where)
        assert err < TOL_FD_V
        err = max(abs(motion.links[n].epsilon[i] - ep[n]) for n in moving) / max(
            max(abs(x) for x in ep.values()), amax / size)
        record("FD: epsilon", err, where)
        assert err < TOL_FD_A


# --- textbook closed forms: the crank-slider --------------------------------------------------

@pytest.mark.parametrize("name", ["crank_slider_central", "crank_slider_offset"])
def test_crank_slider_closed_form(name):
    """x_B = r cos φ + √(l² − (r sin φ − y_g)²) for a crank of radius r about the origin and a
    horizontal guide y = y_g (y_g = 0 central, −e offset); its φ-derivatives by hand:
    s = r sin φ − y_g, w = √(l² − s²),
    x' = −r sin φ − s s'/w,   x'' = −r cos φ − (s'² + s s'')/w − s² s'²/w³,
    rod angle β = atan2(−s, w): β' = −s'/w,  β'' = −s''/w − s s'²/w³;
    v = ω·(.)', a = ω²·(.)'' + ε·(.)'. Dimensions read from the TOML, not from plans."""
    path, values, _ = CASES[name]
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    r, l = data["lengths"]["OA"], data["lengths"]["AB"]
    yg = data["points"]["B"][1]
    assert data["points"]["O"] == [0.0, 0.0] and data["sliders"][0]["angle"] == 0.0
    om, ep = data["drive"]["omega"], data["drive"].get("epsilon", 0.0)
    mech, structure = _load(path)
    phi_deg = np.arange(0.0, 360.0, 15.0) + 2.5
    motion = analyse(mech, structure, phi_deg)
    phi = np.radians(phi_deg)
    s, s1, s2 = r * np.sin(phi) - yg, r * np.cos(phi), -r * np.sin(phi)
    w = np.sqrt(l * l - s * s)
    x = r * np.cos(phi) + w
    x1 = -r * np.sin(phi) - s * s1 / w
    x2 = -r * np.cos(phi) - (s1 * s1 + s * s2) / w - s * s * s1 * s1 / w ** 3
    b1 = -s1 / w
    b2 = -s2 / w - s * s1 * s1 / w ** 3
    B, vB, aB = motion.position("B", "3"), motion.velocity("B", "3"), motion.acceleration("B", "3")
    checks = {
        "x_B": (B[:, 0], x, np.abs(x)),
        "y_B": (B[:, 1], np.full_like(x, yg), np.abs(x)),
        "v_B": (vB[:, 0], om * x1, np.full_like(x, r * abs(om))),
        "v_B (y)": (vB[:, 1], 0.0 * x, np.full_like(x, r * abs(om))),
        "a_B": (aB[:, 0], om * om * x2 + ep * x1, np.full_like(x, r * math.hypot(om * om, ep))),
        "a_B (y)": (aB[:, 1], 0.0 * x, np.full_like(x, r * math.hypot(om * om, ep))),
        "omega_2": (motion.links["2"].omega, om * b1, np.full_like(x, abs(om))),
        "epsilon_2": (motion.links["2"].epsilon, om * om * b2 + ep * b1, np.full_like(x, math.hypot(om * om, ep))),
        "omega_3": (motion.links["3"].omega, 0.0 * x, np.full_like(x, abs(om))),
    }
    for key, (got, want, scale) in checks.items():
        err = float(np.max(np.abs(got - want) / scale))
        record(f"closed form crank-slider: {key}", err, name)
        assert err < TOL_CLOSED, f"{key}: {err:.3g}"


# --- rigidity and pair identities --------------------------------------------------------------

@pytest.mark.parametrize("name", sorted(CASES))
def test_rigid_body_and_pair_identities(name):
    """For any two points P, Q of one link: (v_Q − v_P)·(Q − P) = 0 and
    (a_Q − a_P)·(Q − P) + |v_Q − v_P|² = 0 (the distance is constant). For a revolute pair,
    the pin has one velocity and acceleration in both links. For a prismatic pair, ω and ε
    agree and the slider's anchor moves relative to the guide's coincident point along the
    guide: (v_s − v_g)·n = 0."""
    src, values, _ = CASES[name]
    mech, structure = _load(src)
    m = analyse(mech, structure, values)
    size = _size(mech)
    vmax = max(np.max(np.linalg.norm(m.velocity(p, n), axis=1)) for n, p in _pairs(mech))
    amax = max(np.max(np.linalg.norm(m.acceleration(p, n), axis=1)) for n, p in _pairs(mech))
    worst_v = worst_a = 0.0
    for lname, link in mech.links.items():
        probe = {p: (m.position(p, lname), m.velocity(p, lname), m.acceleration(p, lname)) for p in link.points}
        # the link's own origin as a further material point
        if not link.is_frame:
            st = m.links[lname]
            probe["<origin>"] = (st.origin, st.velocity(st.origin), st.acceleration(st.origin))
        keys = list(probe)
        for i, p in enumerate(keys):
            for q in keys[i + 1:]:
                (P, vP, aP), (Q, vQ, aQ) = probe[p], probe[q]
                d, dv, da = Q - P, vQ - vP, aQ - aP
                worst_v = max(worst_v, np.max(np.abs(np.einsum("ij,ij->i", dv, d))) / (vmax * size))
                worst_a = max(worst_a, np.max(np.abs(np.einsum("ij,ij->i", da, d) + np.einsum("ij,ij->i", dv, dv)))
                              / (amax * size))
    for r in mech.revolutes:
        for f, scale in ((m.position, size), (m.velocity, vmax), (m.acceleration, amax)):
            err = np.max(np.abs(f(r.point, r.a) - f(r.point, r.b))) / scale
            worst_v = max(worst_v, err)
    for p in mech.prismatics:
        s, g = m.links[p.slider], m.links[p.guide]
        X = s.point(p.anchor[p.slider])
        n = g.direction(p.normal)
        worst_v = max(worst_v, np.max(np.abs(np.einsum("ij,ij->i", s.velocity(X) - g.velocity(X), n))) / vmax,
                      np.max(np.abs(np.einsum("ij,ij->i", X - g.point(p.anchor[p.guide]), n))) / size,
                      np.max(np.abs(s.omega - g.omega)) * size / vmax)
        worst_a = max(worst_a, np.max(np.abs(s.epsilon - g.epsilon)) * size / amax)
    record("identities: velocity/position", worst_v, name)
    record("identities: acceleration", worst_a, name)
    assert worst_v < TOL_RIGID and worst_a < TOL_RIGID

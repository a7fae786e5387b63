"""Kinematics of plans checked against independent computations.

Every expected number here comes from somewhere other than plans' closed forms:

* the generic Jacobian solver of ``tests/reference.py`` (Newton continuation from the sketch,
  then Φ_q·q̇ = −Φ_t and Φ_q·q̈ = γ);
* central finite differences of plans' own *positions* (``order=0``) along the drive;
* textbook closed forms of the crank-slider;
* identities every rigid body and every pair must satisfy.

Errors are measured relative to the largest magnitude of the same quantity at the same
position (the largest point velocity, the largest |ω|, ...). The worst relative error of each
kind is collected in ``WORST`` and printed at the end of the module (run pytest with ``-s``).
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from plans.errors import AssemblyError, SingularPositionError
from plans.kinematics import analyse
from plans.model import build_mechanism
from plans.scene import parse_scene, read_scene
from plans.structure import analyse_structure

try:
    from tests.reference import Reference
except ImportError:  # tests/ on sys.path instead of the project root
    from reference import Reference

EXAMPLES = Path(__file__).resolve().parent.parent / "plans" / "examples"

#: plans against the reference Jacobian solve, regular positions
TOL_REF = 1e-10
#: plans against the reference near singular positions (0.5° .. 1° away)
TOL_NEAR = 1e-9
#: the same where two branches cross (sin ∝ distance, not √distance): accelerations there are
#: conditioned like eps/sin³, and a 50-digit closed form shows double precision cannot do better
TOL_NEAR_CROSSING = 1e-7
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

WORST: dict[str, tuple[float, str]] = {}


def record(kind: str, err: float, where: str) -> float:
    if err >= WORST.get(kind, (-1.0, ""))[0]:
        WORST[kind] = (err, where)
    return err


@pytest.fixture(scope="module", autouse=True)
def _report():
    yield
    print("\nworst relative errors seen (kind: error at where)")
    for kind in sorted(WORST):
        err, where = WORST[kind]
        print(f"  {kind:42s} {err:9.2e}  {where}")


# --- scenes ---------------------------------------------------------------------------------

def _deg(v) -> float:
    return math.degrees(math.atan2(v[1], v[0]))


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _pt(x) -> list[float]:
    return [float(x[0]), float(x[1])]


def _fourbar_points(r, d, lm, ln, phi, sign=1.0):
    """O, A, B, C of a four-bar (O at the origin, C on +x) assembled at crank angle phi."""
    A = r * np.array([math.cos(math.radians(phi)), math.sin(math.radians(phi))])
    C = np.array([d, 0.0])
    L = float(np.linalg.norm(C - A))
    x = (lm * lm - ln * ln + L * L) / (2 * L)
    h = math.sqrt(lm * lm - x * x)
    ex = (C - A) / L
    B = A + x * ex + sign * h * np.array([-ex[1], ex[0]])
    return np.zeros(2), A, B, C


def scene_linear_drive() -> dict:
    """RRR group driven by a slider on an inclined frame guide (linear drive)."""
    return {"points": {"S": [0.0, 0.0], "B": [0.12, 0.26], "C": [0.33, 0.08], "G": [0.05, 0.30]},
            "links": {"0": ["C"], "1": ["S"], "2": ["S", "B", "G"], "3": ["C", "B"]},
            "sliders": [{"link": "1", "on": "0", "through": "S", "angle": 20.0}],
            "drive": {"link": "1", "displacement": 0.0, "velocity": 1.5, "acceleration": -4.0}}


def scene_rrp_rotating_guide() -> dict:
    """RRP whose guide turns: link 3 slides along the slot of the driving crank 1 (E off the
    slot line), link 2 joins it to the frame at C."""
    O, K = np.zeros(2), np.array([0.3, 0.1])
    u = K / np.linalg.norm(K)
    E = 0.25 * u + 0.02 * np.array([-u[1], u[0]])
    return {"points": {"O": _pt(O), "K": _pt(K), "C": [0.03, -0.04], "E": _pt(E)},
            "links": {"0": ["O", "C"], "1": ["O", "K"], "2": ["C", "E"], "3": ["E"]},
            "sliders": [{"link": "3", "on": "1", "through": ["O", "K"]}],
            "drive": {"link": "1", "angle": _deg(K), "omega": 7.0, "epsilon": -15.0}}


def scene_rpp_rotating() -> dict:
    """RPP turning with the crank: link 3 slides along the crank's slot, link 2 (pinned to the
    frame at C) slides in a slot of link 3 at 100° to it."""
    return {"points": {"O": [0.0, 0.0], "K": [0.3, 0.1], "Q": [0.15, 0.05], "C": [0.1, 0.2]},
            "links": {"0": ["O", "C"], "1": ["O", "K"], "2": ["C"], "3": ["Q"]},
            "sliders": [{"link": "3", "on": "1", "through": ["O", "K"]},
                        {"link": "2", "on": "3", "through": "C", "angle": _deg([0.3, 0.1]) + 100.0}],
            "drive": {"link": "1", "angle": _deg([0.3, 0.1]), "omega": 9.0, "epsilon": 30.0}}


def _four_bar_base() -> tuple[dict, dict]:
    O, A, B, C = _fourbar_points(0.08, 0.24, 0.25, 0.2, 0.0)
    M = np.array([0.057811889, 0.148349883])
    points = {"O": _pt(O), "C": _pt(C), "A": _pt(A), "B": _pt(B), "M": _pt(M)}
    links = {"0": ["O", "C"], "1": ["O", "A"], "2": ["A", "B", "M"], "3": ["C", "B"]}
    return points, links


def scene_prp_moving_guides() -> dict:
    """Four-bar plus a PRP group whose guides are the rocker's line C-B and a line of the
    coupler through M parallel to AB (both guides turn, with different ω and ε)."""
    points, links = _four_bar_base()
    A, B, C, M = (np.array(points[k]) for k in "ABCM")
    u1, u2 = (B - C), (B - A)
    t = _cross(M - C, u2) / _cross(u1, u2)
    points["E"] = _pt(C + t * u1)
    links |= {"4": ["E"], "5": ["E"]}
    return {"points": points, "links": links,
            "sliders": [{"link": "4", "on": "3", "through": ["C", "B"]},
                        {"link": "5", "on": "2", "through": "M", "angle": _deg(u2)}],
            "drive": {"link": "1", "angle": 0.0, "omega": 10.0, "epsilon": 25.0}}


def scene_rpr_moving_pivots() -> dict:
    """Four-bar plus an RPR group between the coupler point M (block 4) and a slotted link 5
    pinned to the rocker at H: both outer pairs move."""
    points, links = _four_bar_base()
    points["H"] = [0.30, 0.12]
    points["T"] = [0.36, 0.10]        # a second point of the slotted link fixes its orientation
    links["3"] = ["C", "B", "H"]
    links |= {"4": ["M"], "5": ["H", "T"]}
    return {"points": points, "links": links,
            "sliders": [{"link": "4", "on": "5", "through": ["M", "H"]}],
            "drive": {"link": "1", "angle": 0.0, "omega": 10.0, "epsilon": -40.0}}


def _load(source) -> tuple:
    scene = read_scene(source) if isinstance(source, Path) else parse_scene(source)
    mech = build_mechanism(scene)
    return mech, analyse_structure(mech)


TWELVE = np.arange(12) * 30.0 + 10.0
#: FD steps: 0.25° balances rounding in the second difference against the 6th-order truncation
#: (~h⁶). Rounding: Newton positions of a class III group carry ~5e-15 rad of noise (tens of ulp,
#: amplified by the group's condition figure ~0.3), and Σ|FD2|·5e-15/h² ≈ 6e-10 at 0.25° but 4e-9
#: at 0.1° (measured up to 1e-8 there on koshel_variant2); truncation at 0.25° stays below 1e-10.
#: The tangent mechanism near ±85° needs a finer step.
FD_STEP_DEG = 0.25
#: example scenes that do not turn fully: (values, FD step)
EXAMPLE_RANGES = {"tangent_mechanism": (np.linspace(-85.0, 85.0, 12), 0.05),
                  "four_bar_coupler_drive": (np.linspace(34.0, 66.0, 12), 0.05)}   # the coupler's swing


def _example_case(path: Path) -> tuple:
    """Every example: 12 crank angles a full turn round (or its own range); a linear drive
    uses the scene's own displacements."""
    if path.stem in EXAMPLE_RANGES:
        return (path, *EXAMPLE_RANGES[path.stem])
    drive = tomllib.loads(path.read_text(encoding="utf-8"))["drive"]
    if "displacement" in drive:
        values = np.atleast_1d(np.asarray(drive["displacement"], float))
        return path, values, 1e-3 * float(np.ptp(values) or 1.0)
    return path, TWELVE, FD_STEP_DEG


#: name -> (scene, drive values, FD step in the drive's unit)
CASES = {path.stem: _example_case(path) for path in sorted(EXAMPLES.glob("*.toml"))} | {
    "linear_drive": (scene_linear_drive(), np.linspace(-0.1, 0.1, 12), 2e-3),
    "rrp_rotating_guide": (scene_rrp_rotating_guide(), TWELVE, FD_STEP_DEG),
    "rpp_rotating": (scene_rpp_rotating(), TWELVE, FD_STEP_DEG),
    "prp_moving_guides": (scene_prp_moving_guides(), TWELVE, FD_STEP_DEG),
    "rpr_moving_pivots": (scene_rpr_moving_pivots(), TWELVE, FD_STEP_DEG),
}


def test_the_seven_examples_are_covered():
    assert {"crank_slider_central", "crank_slider_offset", "four_bar", "quick_return", "scotch_yoke",
            "six_link_press", "tangent_mechanism"} <= set(CASES)


def test_extra_scenes_cover_every_form():
    forms = {g.form for name, (src, _, _) in CASES.items() for g in _load(src)[1].groups if g.klass == 2}
    assert forms == {"RRR", "RRP", "RPR", "PRP", "RPP"}


# --- comparison helpers ---------------------------------------------------------------------

def _pairs(mech):
    return [(name, p) for name, link in mech.links.items() for p in link.points]


def _size(mech) -> float:
    pts = np.array([np.asarray(v, float) for v in mech.sketch.values()])
    return float(np.hypot(*(pts.max(axis=0) - pts.min(axis=0))))


def compare_with_reference(mech, motion, states, tol: float, label: str, kind: str = "ref") -> None:
    """plans' Motion against reference states, point by point and link by link."""
    size = _size(mech)
    pts = _pairs(mech)
    for i, r in enumerate(states):
        where = f"{label} @ {motion.values[i]:g}"
        for qty, got_of, want_of in (
                ("position", motion.position, r.position),
                ("velocity", motion.velocity, r.velocity),
                ("acceleration", motion.acceleration, r.acceleration)):
            if qty != "position" and motion.order < (1 if qty == "velocity" else 2):
                continue
            want = {key: want_of(key[1], key[0]) for key in pts}
            scale = max(np.linalg.norm(w) for w in want.values())
            got = {key: got_of(key[1], key[0])[i] for key in pts}
            assert all(np.all(np.isfinite(g)) for g in got.values())
            err = max(np.linalg.norm(got[k] - want[k]) for k in pts) / scale
            record(f"{kind}: {qty}", err, where)
            assert err < tol, f"{qty} at {where}: relative error {err:.3g}"
        moving = [n for n in mech.links if not mech.links[n].is_frame]
        if motion.order >= 1:
            vmax = max(np.linalg.norm(r.velocity(p, n)) for n, p in pts)
            scale = max(max(abs(r.omega(n)) for n in moving), vmax / size)
            err = max(abs(motion.links[n].omega[i] - r.omega(n)) for n in moving) / scale
            record(f"{kind}: omega", err, where)
            assert err < tol, f"omega at {where}: relative error {err:.3g}"
        if motion.order >= 2:
            amax = max(np.linalg.norm(r.acceleration(p, n)) for n, p in pts)
            scale = max(max(abs(r.epsilon(n)) for n in moving), amax / size)
            err = max(abs(motion.links[n].epsilon[i] - r.epsilon(n)) for n in moving) / scale
            record(f"{kind}: epsilon", err, where)
            assert err < tol, f"epsilon at {where}: relative error {err:.3g}"


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


def scene_slotted_lever(offset, phi0, *, lever_points=("C", "T"), omega=6.0, epsilon=3.0) -> dict:
    """Crank OA (0.1 m, O 0.3 m above the lever pivot C); block 2 on the pin A slides in a slot
    of lever 3 that runs at distance ``offset`` from C (RPR group). T is a further point of the
    lever (its far end), when listed."""
    O = np.array([0.0, 0.3])
    A = O + 0.1 * np.array([math.cos(math.radians(phi0)), math.sin(math.radians(phi0))])
    L = float(np.linalg.norm(A))
    alpha = _deg(A) - math.degrees(math.asin(offset / L))
    points = {"O": _pt(O), "C": [0.0, 0.0], "A": _pt(A), "T": [0.02, -0.12]}
    if "T" not in lever_points:
        del points["T"]
    return {"points": points,
            "links": {"0": ["O", "C"], "1": ["O", "A"], "2": ["A"], "3": list(lever_points)},
            "sliders": [{"link": "2", "on": "3", "through": "A", "angle": alpha}],
            "drive": {"link": "1", "angle": phi0, "omega": omega, "epsilon": epsilon}}


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


def _four_bar_in_50_digits(mech, phi_deg: float, branch_point: np.ndarray) -> dict:
    """The four-bar O-A-B-C (crank 1, coupler 2, rocker 3) in 50-digit arithmetic from the
    model's float data: circle intersection for B (the root nearest ``branch_point``), then
    the velocity and acceleration loops v_A + ω2 k×AB = ω3 k×CB, solved exactly."""
    mp = pytest.importorskip("mpmath")
    with mp.workdps(50):
        return _four_bar_mp(mp, mech, phi_deg, branch_point)


def _four_bar_mp(mp, mech, phi_deg: float, branch_point: np.ndarray) -> dict:
    L0, L1, L2, L3 = (mech.links[k].local for k in "0123")

    def vec(x):
        return mp.matrix([mp.mpf(float(x[0])), mp.mpf(float(x[1]))])

    def k_x(v):
        return mp.matrix([-v[1], v[0]])

    def norm(v):
        return mp.sqrt(v[0] ** 2 + v[1] ** 2)

    r = norm(vec(L1["A"]) - vec(L1["O"]))
    lm, ln = norm(vec(L2["B"]) - vec(L2["A"])), norm(vec(L3["B"]) - vec(L3["C"]))
    O, C = vec(L0["O"]), vec(L0["C"])
    ph = mp.radians(mp.mpf(float(phi_deg)))
    A = O + r * mp.matrix([mp.cos(ph), mp.sin(ph)])
    d = C - A
    L = norm(d)
    x = (lm ** 2 - ln ** 2 + L ** 2) / (2 * L)
    h = mp.sqrt(lm ** 2 - x ** 2)
    roots = [A + x * d / L + s * h * k_x(d / L) for s in (1, -1)]
    B = min(roots, key=lambda b: float(norm(b - vec(branch_point))))
    w1, e1 = mp.mpf(mech.drive.speed), mp.mpf(mech.drive.rate)
    vA, aA = w1 * k_x(A - O), e1 * k_x(A - O) - w1 ** 2 * (A - O)
    Mx = mp.matrix([[k_x(B - A)[0], -k_x(B - C)[0]], [k_x(B - A)[1], -k_x(B - C)[1]]])
    w2, w3 = mp.lu_solve(Mx, -vA)
    e2, e3 = mp.lu_solve(Mx, -aA + w2 ** 2 * (B - A) - w3 ** 2 * (B - C))
    vB, aB = w3 * k_x(B - C), e3 * k_x(B - C) - w3 ** 2 * (B - C)
    return {"B": np.array([float(B[0]), float(B[1])]), "v_B": np.array([float(vB[0]), float(vB[1])]),
            "a_B": np.array([float(aB[0]), float(aB[1])]), "w": np.array([float(w2), float(w3)]),
            "e": np.array([float(e2), float(e3)])}


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

"""Shared scenes and comparison helpers of the kinematics tests (``test_kinematics*.py``).

Every expected number in those tests comes from somewhere other than plans' closed forms; the
reference is the generic Jacobian solver of ``tests/reference.py`` (Newton continuation from
the sketch, then Φ_q·q̇ = −Φ_t and Φ_q·q̈ = γ), compared point by point and link by link by
``compare_with_reference``, and the four-bar solved in 50-digit arithmetic
(``_four_bar_in_50_digits``, also used by ``test_properties_singular.py``).

Errors are measured relative to the largest magnitude of the same quantity at the same
position (the largest point velocity, the largest |ω|, ...). The worst relative error of each
kind is collected in ``WORST`` and printed at the end of each test module that imports the
``_report`` fixture (run pytest with ``-s``).
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from plans.model import build_mechanism
from plans.scene import parse_scene, read_scene
from plans.structure import analyse_structure

#: re-exported: the test modules take the reference from here (one import path for all of them)
try:
    from tests.reference import Reference
except ImportError:  # tests/ on sys.path instead of the project root
    from reference import Reference  # noqa: F401


EXAMPLES = Path(__file__).resolve().parent.parent / "plans" / "examples"

#: plans against the reference Jacobian solve, regular positions
TOL_REF = 1e-10

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

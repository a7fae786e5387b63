"""Sliding along the guides and the links' angles (plans/kinematics/sliders.py, the JSON's
``sliders`` and ``links.*.angle``) against finite differences of positions.

Everything expected here comes from positions only: the sliding displacement s(φ) and the
link angles θ(φ) at φ − h, φ, φ + h (``analyse``'s positions; velocities and accelerations
are not used to make the expectation), differentiated by central differences and turned into
time derivatives with the drive's law: d/dt = ω1 d/dφ, d²/dt² = ω1² d²/dφ² + ε1 d/dφ.

Step and tolerances: h = 1e-4 rad. The central difference of the first derivative errs by
h²/6·|s'''| + eps·|s|/h, of the second by h²/12·|s''''| + 4·eps·|s|/h² (eps = 2.2e-16). In
these scenes |s'''|, |s''''| stay below about 50 L (L = the mechanism's size; the tangent
mechanism at 60° is the largest, s = h·tan φ) and |s| < L, so the errors are below
1e-8·50/6 + 2e-12 ≈ 1e-7 (first) and 1e-9·50/12 + 9e-8 ≈ 1e-7 (second) in units of L; the
measured worst are 7e-8 and 4e-7 relative to ω1·L and (ω1² + |ε1|)·L. The tolerances below
take 10 times those bounds: far from any true error (a wrong sign, a missing Coriolis term or
factor 2 is of order 1).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from plans.kinematics import analyse, link_angles, sliding
from plans.kinematics.state import J
from plans.model import build_mechanism
from plans.pipeline import report, solve_scene
from plans.pipeline.scales import scene_scales as _scales
from plans.scene import parse_scene, read_scene
from plans.structure import analyse_structure

EXAMPLES = Path(__file__).resolve().parent.parent / "plans" / "examples"

#: the finite-difference step, radians of the drive
H = 1e-4
#: velocities relative to ω1·L, accelerations relative to (ω1² + |ε1|)·L (see the module)
TOL_V = 1e-6
TOL_A = 1e-5

#: scene → drive angles (degrees) within its reach; offsets keep off the sketch's own angle
SCENES = {
    "crank_slider_offset": np.arange(-170.0, 181.0, 17.0),   # guide on the frame, ε1 ≠ 0
    "quick_return": np.arange(-170.0, 181.0, 17.0),          # block on a turning slotted lever
    "whitworth": np.arange(-170.0, 181.0, 17.0),             # lever turning fully
    "tangent_mechanism": np.arange(-60.0, 61.0, 7.0),        # block on the driven slotted crank
}
#: prismatic pairs whose guide turns (Coriolis ≠ 0)
TURNING = {"quick_return": "2/3", "whitworth": "2/3", "tangent_mechanism": "2/1"}


class FD:
    """A scene solved at φ − h, φ, φ + h for every angle; ``mid`` the motion at φ."""

    def __init__(self, name: str, angles: np.ndarray):
        self.mech = build_mechanism(read_scene(EXAMPLES / f"{name}.toml"))
        structure = analyse_structure(self.mech)
        self.n = len(angles)
        hd = math.degrees(H)
        self.positions = analyse(self.mech, structure, np.concatenate([angles - hd, angles + hd]), order=0)
        self.mid = analyse(self.mech, structure, angles, order=2)
        self.w, self.e = self.mech.drive.speed, self.mech.drive.rate
        self.L = self.mech.size

    def derivatives(self, before: np.ndarray, at: np.ndarray, after: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Time derivatives (first, second) of a quantity given at φ − h, φ, φ + h."""
        d1 = (after - before) / (2 * H)
        d2 = (after - 2 * at + before) / H ** 2
        return d1 * self.w, d2 * self.w ** 2 + d1 * self.e

    def split(self, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return values[:self.n], values[self.n:]

    def sliding(self, key: str):
        """s at φ ± h (positions only) and the pair's Sliding at φ."""
        before, after = self.split(sliding(self.positions)[key].s)
        return before, after, sliding(self.mid)[key]

    def angle_rates(self, link: str) -> tuple[np.ndarray, np.ndarray]:
        """dθ/dt and d²θ/dt² of a link (rad/s, rad/s²) from its angles (degrees, modulo a turn)."""
        before, after = self.split(link_angles(self.positions)[link])
        at = link_angles(self.mid)[link]
        turn = lambda d: np.radians((d + 180.0) % 360.0 - 180.0)   # a difference within half a turn
        d1 = (turn(after - at) + turn(at - before)) / (2 * H)
        d2 = (turn(after - at) - turn(at - before)) / H ** 2
        return d1 * self.w, d2 * self.w ** 2 + d1 * self.e


@pytest.fixture(scope="module", params=sorted(SCENES))
def fd(request) -> FD:
    return FD(request.param, SCENES[request.param])


def test_sliding_velocity_and_acceleration_are_the_derivatives_of_s(fd):
    """σ = ds/dt and σ̇ = d²s/dt² for every pair (guides on the frame and turning)."""
    assert fd.mech.prismatics
    for key in sliding(fd.mid):
        before, after, sl = fd.sliding(key)
        v, a = fd.derivatives(before, sl.s, after)
        assert np.max(np.abs(sl.v - v)) <= TOL_V * abs(fd.w) * fd.L, key
        assert np.max(np.abs(sl.a - a)) <= TOL_A * (fd.w ** 2 + abs(fd.e)) * fd.L, key


def test_link_angles_turn_at_omega_and_epsilon(fd):
    """ω = dθ/dt, ε = d²θ/dt² of every link, θ its reported angle."""
    for name, state in fd.mid.links.items():
        omega, epsilon = fd.angle_rates(name)
        assert np.max(np.abs(state.omega - omega)) <= TOL_V * abs(fd.w), name
        assert np.max(np.abs(state.epsilon - epsilon)) <= TOL_A * (fd.w ** 2 + abs(fd.e)), name


def test_crank_angle_is_the_drive_angle(fd):
    """The crank (pivot first) reads the drive's φ, modulo a turn."""
    crank = link_angles(fd.mid)[fd.mech.drive.link]
    want = np.mod(fd.mid.values, 360.0)
    diff = (crank - want + 180.0) % 360.0 - 180.0
    assert np.max(np.abs(diff)) < 1e-9
    assert np.all((crank >= 0.0) & (crank < 360.0))


@pytest.mark.parametrize("name", sorted(TURNING))
def test_coriolis_from_independent_omega_and_sigma(name):
    """Coriolis = 2 ω_guide k × (σ u), with ω_guide = dθ_guide/dt and σ = ds/dt by finite
    differences and u the direction guide anchor → slider's point from positions alone (s > 0
    in these scenes: the block never passes the guide's anchor). It is not zero, and it is
    the part of a_S − a_G across the guide (a_S = a_G + σ̇ u + coriolis, exact)."""
    fd = FD(name, SCENES[name])
    key = TURNING[name]
    before, after, sl = fd.sliding(key)
    pair = next(p for p in fd.mech.prismatics if f"{p.slider}/{p.guide}" == key)
    sigma, _ = fd.derivatives(before, sl.s, after)
    omega, _ = fd.angle_rates(pair.guide)
    anchor = next(t for t in fd.mech.links[pair.guide].points if np.allclose(
        fd.mech.links[pair.guide].local[t], pair.anchor[pair.guide]))
    r = fd.mid.position(pair.label, pair.slider) - fd.mid.position(anchor, pair.guide)
    assert np.all(sl.s > 0.0)
    u = r / np.linalg.norm(r, axis=1)[:, None]
    assert np.max(np.abs(u - sl.u)) < 1e-12
    want = 2.0 * omega[:, None] * J(sigma[:, None] * u)
    scale = fd.w ** 2 * fd.L
    assert np.max(np.abs(sl.coriolis - want)) <= 2 * TOL_V * scale
    assert np.max(np.linalg.norm(sl.coriolis, axis=1)) > 0.01 * scale     # not zero: far above the tolerance
    x = fd.mid.position(pair.label, pair.slider)
    rel = fd.mid.links[pair.slider].acceleration(x) - fd.mid.links[pair.guide].acceleration(x)
    assert np.max(np.abs(rel - (sl.a[:, None] * sl.u + sl.coriolis))) < 1e-12 * (fd.w ** 2 + abs(fd.e)) * fd.L * 10


def test_guide_on_the_frame_has_no_coriolis_and_a_fixed_direction():
    fd = FD("crank_slider_offset", SCENES["crank_slider_offset"])
    (sl,) = sliding(fd.mid).values()
    assert not np.any(sl.coriolis)
    assert np.array_equal(sl.u, np.broadcast_to([1.0, 0.0], sl.u.shape))
    # the slider's pin B lies on the guide: s is its x less the sketch's
    b = fd.mid.position("B")
    assert np.max(np.abs(sl.s - (b[:, 0] - fd.mech.sketch["B"][0]))) < 1e-15 * 10


def test_linear_drive_slides_as_driven():
    """The elliptic trammel's driven block: s is the drive's displacement, σ its velocity, σ̇ its
    acceleration."""
    mech = build_mechanism(read_scene(EXAMPLES / "elliptic_trammel.toml"))
    motion = analyse(mech, analyse_structure(mech), order=2)
    d = mech.drive
    sl = next(s for s in sliding(motion).values() if s.slider == d.link and s.guide == "0")
    assert sl.s == pytest.approx(motion.values, abs=1e-15)
    assert sl.v == pytest.approx(np.full(len(motion), d.speed), rel=1e-12)
    assert sl.a == pytest.approx(np.full(len(motion), d.rate), abs=1e-12 * max(1.0, abs(d.speed) ** 2))


def test_report_carries_sliders_and_angles():
    """The JSON's per-position ``sliders`` (point, u, s, v, a, coriolis) and ``links.*.angle``
    are the kinematics module's numbers."""
    scene = read_scene(EXAMPLES / "quick_return.toml")
    motion = solve_scene(scene)
    data = report(scene, motion, _scales(scene, motion))
    slides, angles = sliding(motion), link_angles(motion)
    for i, pos in enumerate(data["positions"]):
        assert set(pos["sliders"]) == {"2/3", "5/0"}
        for key, entry in pos["sliders"].items():
            sl = slides[key]
            assert list(entry) == ["point", "u", "s", "v", "a", "coriolis"]
            assert entry["point"] == sl.point
            assert entry["u"] == list(sl.u[i]) and entry["s"] == sl.s[i]
            assert entry["v"] == sl.v[i] and entry["a"] == sl.a[i] and entry["coriolis"] == list(sl.coriolis[i])
        for name, link in pos["links"].items():
            assert link["angle"] == angles[name][i]
            assert 0.0 <= link["angle"] < 360.0


@pytest.mark.parametrize("draw, keys, link_keys", [
    (["scheme"], ["point", "u", "s"], ["angle"]),
    (["scheme", "velocity"], ["point", "u", "s", "v"], ["angle", "omega"]),
    (["velocity", "acceleration"], ["point", "u", "s", "v", "a", "coriolis"], ["angle", "omega", "epsilon"]),
])
def test_report_fields_follow_the_order(draw, keys, link_keys):
    """Velocity fields only when velocities are computed, accelerations only at order 2."""
    scene = parse_scene({
        "title": "Crank-slider",
        "points": {"O": [0.0, 0.0], "A": [0.0866025, 0.05], "B": [0.4834652, 0.0]},
        "links": {"0": ["O"], "1": ["O", "A"], "2": ["A", "B"], "3": ["B"]},
        "sliders": [{"link": "3", "on": "0", "through": "B", "angle": 0.0}],
        "drive": {"link": "1", "angle": 30.0, "omega": 10.0},
        "plans": {"draw": draw},
    })
    motion = solve_scene(scene)
    pos = report(scene, motion, _scales(scene, motion))["positions"][0]
    assert list(pos["sliders"]["3/0"]) == keys
    assert all(list(link) == link_keys for link in pos["links"].values())

"""The machine's motion under its loads over one steady cycle of the crank (the second problem
of dynamics): the reduced moment and inertia over the revolution, the work of the loads and of
the driving moment, the change of kinetic energy, the flywheel for an allowed coefficient of
speed fluctuation δ (exactly, and by Wittenbauer's energy–mass diagram), and the true speed
ω1(φ) and ε1(φ) with it.

Angles here are the crank's turned angle θ = sense·(φ − φ_start) in radians (0 … 2π over the
cycle, growing in the crank's sense of rotation; 0 … 2π·turns over a cycle of several turns,
``[dynamics] period``, the linkage repeating every turn and the laws over the period) and
moments are taken in that sense (positive when they drive), so that work is ∫M dθ whatever way
the crank turns. The reported M_r (CCW positive) is sense × that. The driving moment is constant
(the loads' mean) or a law in θ (:mod:`.laws`), whose work over the cycle must balance the loads'.

Exactness: the loads are sampled at the Gauss nodes of panels of at most 1° whose edges
include every point where a load kinks or jumps (a law's knot crossed by the output's travel,
the ends of the strokes, the rest points of a force opposing its point's velocity, a row or a
shape's end of a law in the crank angle, :func:`.laws.law_edges`), found by
root-finding to ~1e-13 rad; on each panel the samples define a polynomial of degree 7
(:mod:`.piecewise`), so the integrals and the searches for the largest and smallest values are
exact to ~1e-13 of their size, far below the 1e-9 asked.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, replace

import numpy as np

from .. import linalg as la

from ..errors import SceneError
from ..kinematics import analyse
from ..kinematics.cycle import Cycle, output_motion
from ..kinetostatics import Travel, forces_following
from ..scene import MIN_RATE, Scene
from .laws import balanced, check_laws, law_edges, panel_deg, torque_at
from .piecewise import Piecewise, combine, fit, nodes_of
from .reduced import Reduced, reduce

__all__ = ["MachineDynamics", "Flywheel", "machine_dynamics", "flywheel_for", "PANEL_DEG", "BREAK_TOL"]

#: Longest panel of the quadrature, degrees of the crank.
PANEL_DEG = 1.0
#: A kink of a load (the output's travel crossing a law's knot, a force's point coming to rest)
#: is located to this many radians of the crank.
BREAK_TOL = 1e-13
#: Steps of the bracketing grid for kinks, per revolution (every kink is bracketed on it).
BRACKETS = 1440


@dataclass(frozen=True, eq=False)
class Flywheel:
    """The flywheel for ``delta`` δ at the mean speed ``omega_m`` (rad/s, > 0):
    ``inertia_exact`` J (kg·m²) from the energy equation with ω_max,min = ω_m(1 ± δ/2);
    ``inertia_wittenbauer`` from the textbook's tangents tan ψ = ω_m²(1 ± δ)/2;
    ``tangent_max``/``tangent_min``: (θ rad, slope J/(kg·m²), intercept J) of the two tangents
    on the energy–mass curve ΔT(I) (Wittenbauer's); ``required``: J before it is taken
    non-negative (negative when the machine's own inertia keeps δ without a flywheel);
    ``given``: whether J was given ([dynamics] flywheel) and δ found."""

    delta: float
    omega_m: float
    inertia_exact: float
    inertia_wittenbauer: float | None
    tangent_max: tuple[float, float, float] | None
    tangent_min: tuple[float, float, float] | None
    required: float | None
    given: bool


@dataclass(frozen=True, eq=False)
class MachineDynamics:
    """One steady cycle of the machine. ``sense`` +1 (CCW) or −1, ``start`` φ at θ = 0 (°),
    ``omega_m`` the mean |ω1|; as functions of θ (:class:`~.piecewise.Piecewise`): ``moment``
    the loads' reduced moment in the sense of rotation, ``inertia`` I_r plus the rotor's,
    ``slope`` dI/dθ, ``work`` ∫moment dθ, ``energy`` ΔT = work + constant·θ (with a driving law,
    ∫(moment + M_d) dθ); ``constant`` the
    constant moment on the crank (N·m in the sense of rotation: positive a motor, negative a
    consumer when the loads drive, as in an engine); ``at``: M_r, I_r, dI_r/dφ (CCW, as
    :class:`~.reduced.Reduced`) at the cycle's N positions (N per turn); ``theta`` those positions' θ;
    ``breaks`` the θ where a load kinks; ``flywheel``; ``kinetic0`` T0, T at θ = 0 (J), with the
    flywheel's J, so that ω(θ) = √(2(T0 + ΔT)/(I + J)); ``excess`` e0 = T0 − ½ω_m²·J (J, of the
    size of ΔT) and ``rise`` ω² − ω_m² = 2(e0 + ΔT − ½ω_m²·I)/(I + J) (rad²/s²): the speed's
    departure from ω_m without the cancellation of T0 + ΔT against T0 when J is large (small δ);
    ``period`` the cycle (crank degrees: θ runs over 0 … its radians); ``driving`` the driving
    law's moment M_d(θ) in the sense of rotation (None: constant, and then ``constant`` is it;
    with a law ``constant`` is the law's mean)."""

    sense: float
    start: float
    omega_m: float
    rotor: float
    moment: Piecewise
    inertia: Piecewise
    slope: Piecewise
    work: Piecewise
    energy: Piecewise
    constant: float
    at: Reduced
    theta: np.ndarray
    breaks: np.ndarray
    flywheel: Flywheel
    kinetic0: float
    excess: float
    rise: Piecewise
    period: float = 360.0
    driving: Piecewise | None = None

    @property
    def J(self) -> float:
        return self.flywheel.inertia_exact

    def driving_moment(self, theta: np.ndarray | float) -> np.ndarray:
        """M_d (N·m, in the sense of rotation) at θ: the constant moment, or the driving law."""
        theta = np.asarray(theta, dtype=float)
        return np.full(theta.shape, self.constant) if self.driving is None else self.driving(theta)

    @functools.cached_property
    def _driving_work(self) -> Piecewise:
        return self.driving.integral(0.0)

    def omega(self, theta: np.ndarray | float) -> np.ndarray:
        """|ω1| (rad/s) at θ: √(ω_m² + 2(e0 + ΔT − ½ω_m²·I)/(I + J))."""
        w2 = self.omega_m * self.omega_m
        inertia = self.inertia(theta)
        gain = self.excess + self.energy(theta) - 0.5 * w2 * inertia
        return np.sqrt(np.maximum(w2 + 2.0 * gain / (inertia + self.J), 0.0))

    def epsilon(self, theta: np.ndarray | float) -> np.ndarray:
        """dω/dt in the sense of rotation (rad/s²) at θ: (dΔT/dθ − ½ω²·dI/dθ)/(I + J)."""
        w = self.omega(theta)
        drive = self.constant if self.driving is None else self.driving(theta)
        return (self.moment(theta) + drive - 0.5 * w * w * self.slope(theta)) / (self.inertia(theta) + self.J)

    def driving_work(self, theta: np.ndarray | float) -> np.ndarray:
        """A_d: the work of what drives (the constant moment or the driving law, or the loads of
        an engine), J."""
        theta = np.asarray(theta, dtype=float)
        if self.driving is not None:
            return self._driving_work(theta)
        return self.constant * theta if self.constant >= 0.0 else self.work(theta)

    def resisting_work(self, theta: np.ndarray | float) -> np.ndarray:
        """A_r: the work done against what resists (the loads, or an engine's consumer), J."""
        theta = np.asarray(theta, dtype=float)
        return -self.work(theta) if self.constant >= 0.0 or self.driving is not None else -self.constant * theta

    def delta_reached(self) -> tuple[float, float, float]:
        """(ω_max, ω_min, δ) of the true speed, found on the cycle (δ = (ω_max − ω_min)/their
        mean, from their departures from ω_m: no cancellation at small δ)."""
        return _reached(self.rise, self.omega_m)


def machine_dynamics(scene: Scene, cycle: Cycle) -> MachineDynamics:
    """The steady cycle of ``scene`` (with ``[dynamics]``) over the solved ``cycle``."""
    dyn = scene.dynamics
    check_laws(scene)
    mech = cycle.motion.mechanism
    structure = cycle.motion.structure
    w1 = float(mech.drive.speed)
    _check_speed(scene, w1)
    turns = int(round(dyn.period / 360.0))
    span = 2 * np.pi * turns
    sense = 1.0 if w1 > 0.0 else -1.0
    start = float(cycle.start)
    follows = forces_following(scene, cycle)
    low = high = 0.0
    if cycle.extreme_output is not None:
        low, high = float(cycle.extreme_output.s[0]), float(cycle.extreme_output.s[1])

    def phi_of(theta: np.ndarray) -> np.ndarray:
        return start + sense * np.degrees(theta)

    scale = 1.0      # the output's largest speed, as the force analysis takes it (its positions' |v|)
    if follows:
        v = cycle.output.v if cycle.output.v is not None else \
            output_motion(analyse(mech, structure, phi_of(np.linspace(0, 2 * np.pi, 361)), order=1),
                          cycle.output.link).v
        scale = float(np.max(np.abs(v)))

    def solve(theta: np.ndarray, order: int):
        theta = np.asarray(theta, float)
        if turns > 1:                   # the linkage repeats every turn
            theta = np.mod(theta, 2 * np.pi)
        motion = analyse(mech, structure, phi_of(theta), order=order)
        travel = None
        if follows:
            out = output_motion(motion, cycle.output.link)
            v = out.v if out.v is not None else np.zeros(len(motion))
            travel = Travel(out.link, out.kind, out.s, v, low, high, scale)
        return motion, travel

    breaks = _breaks(scene, cycle, solve, sense, start)
    if turns > 1:
        breaks = np.concatenate([breaks + 2 * np.pi * k for k in range(turns)])
    laws = law_edges(scene)
    breaks = np.unique(np.concatenate([breaks, laws[(laws > 0.0) & (laws < span)]]))
    panels = int(math.ceil(360.0 * turns / panel_deg(scene, PANEL_DEG) - 1e-9))
    uniform = np.linspace(0.0, span, panels + 1)
    edges = np.unique(np.concatenate([uniform, breaks]))
    edges = edges[np.concatenate([[True], np.diff(edges) > 1e-12])]
    edges[-1] = span
    x = nodes_of(edges)
    motion, travel = solve(x, 2)
    red = reduce(motion, scene, travel, theta=x)
    moment = fit(edges, sense * red.moment)
    inertia = fit(edges, red.inertia + dyn.rotor_inertia)
    slope = fit(edges, sense * red.slope)
    work = moment.integral(0.0)
    driving = None
    if dyn.torque is None:
        constant = -moment.total() / span
        half = 0.5 * np.diff(edges)
        line = Piecewise(edges, np.column_stack([constant * (edges[:-1] + half), constant * half]))
    else:
        m_d = torque_at(dyn.torque, dyn.period, np.degrees(x))
        driving = fit(edges, m_d)
        constant = balanced(driving, moment, float(np.max(np.abs(m_d)) + np.max(np.abs(sense * red.moment))), span)
    # ΔT: with a law, ∫(M_r + M_d) dθ at once (the works' sum, not the difference of the two large works)
    energy = combine((1.0, work), (1.0, line)) if driving is None else \
        combine((1.0, moment), (1.0, driving)).integral(0.0)
    theta = np.arange(len(cycle.motion) * turns) * (2 * np.pi / len(cycle.motion))
    pos_motion, pos_travel = solve(theta, 2)
    at = reduce(pos_motion, scene, pos_travel, theta=theta)
    omega_m = abs(w1)
    wheel, excess = _flywheel(energy, inertia, omega_m, dyn.delta, dyn.flywheel)
    x = nodes_of(edges)
    rise = _rise(edges, excess, energy(x), inertia(x), wheel.inertia_exact, omega_m)
    return MachineDynamics(sense=sense, start=start, omega_m=omega_m, rotor=dyn.rotor_inertia, moment=moment,
                           inertia=inertia, slope=slope, work=work, energy=energy, constant=constant, at=at,
                           theta=theta, breaks=breaks, flywheel=wheel,
                           kinetic0=0.5 * omega_m * omega_m * wheel.inertia_exact + excess, excess=excess, rise=rise,
                           period=dyn.period, driving=driving)


def _check_speed(scene: Scene, w1: float) -> None:
    """The crank's mean speed must be at least MIN_RATE rad/s (the drive's own bound: the squares
    of slower velocities underflow; the flywheel grows as 1/ω_m²). A written [drive] omega is read
    against it; a gear train at 0 rpm (the kinematics' mechanism at rest) is refused here, at its
    input, and so is a slower train's output when the reader has not refused it first."""
    if abs(w1) >= MIN_RATE:
        return
    if scene.gears is not None and scene.gears.output is not None:
        given = ", ".join(f"{name} = {rpm:g} rpm" for name, rpm in scene.gears.inputs)
        raise SceneError(f"[dynamics] needs the crank turning: the gear train's output {scene.gears.output!r} turns "
                         f"it at ω_m = {abs(w1):g} rad/s ({given}), below {MIN_RATE:g} rad/s (the least speed "
                         "plans computes with: slower velocities' squares underflow, and the flywheel grows as "
                         "1/ω_m²); give the train's input a speed", key="gears.input")
    raise SceneError(f"[dynamics] needs the crank turning at its mean speed: ω_m = {abs(w1):g} rad/s is below "
                     f"{MIN_RATE:g} rad/s; give omega", key="drive.omega")


def flywheel_for(energy: Piecewise, inertia: Piecewise, omega_m: float, *, delta: float | None = None,
                 flywheel: float | None = None) -> tuple[Flywheel, float]:
    """The flywheel and T0 (the kinetic energy at θ = 0, J) of a steady cycle whose change of
    kinetic energy is ``energy`` ΔT(θ) (J, periodic: 0 at both ends) and reduced inertia
    ``inertia`` I(θ) (kg·m²), at the mean speed ``omega_m`` (rad/s): for ``delta``, J exactly from
    J = (max(ΔT − ½ω_max²·I) − min(ΔT − ½ω_min²·I)) / (½(ω_max² − ω_min²)) — the tangents of
    the energy–mass curve, with ½(ω_max² − ω_min²) = ω_m²·δ exactly — and Wittenbauer's the
    same with ½ω_m²(1 ± δ); for a given J, T0 such that (ω_max + ω_min)/2 = ω_m, and δ."""
    wheel, excess = _flywheel(energy, inertia, omega_m, delta, flywheel)
    return wheel, 0.5 * omega_m * omega_m * wheel.inertia_exact + excess


def _flywheel(energy: Piecewise, inertia: Piecewise, omega_m: float, delta: float | None,
              flywheel: float | None) -> tuple[Flywheel, float]:
    """:func:`flywheel_for`, returning e0 = T0 − ½ω_m²·J (J) instead of T0: the kinetic energy
    beyond the flywheel's at ω_m, of the size of ΔT however large J is.

    No difference of nearly equal numbers at small δ: ω_max² − ω_min² = 2ω_m²·δ exactly (not the
    difference of the two squares, which loses log10(1/δ) digits), and with the tangent at ω_max
    touching at θ_a, T0 = ½ω_max²(J + I_a) − ΔT_a, so e0 = ½ω_m²·δ(1 + δ/4)·J − c_max."""
    def tangent(k: float, sign: float) -> tuple[float, float, float]:
        f = combine((1.0, energy), (-k, inertia))
        th, c = f.extreme(sign)
        return th, k, c

    if (delta is None) == (flywheel is None):
        raise ValueError("give delta or flywheel")
    w2 = omega_m * omega_m
    if delta is not None:
        d = delta
        if not d > 0.0 or not w2 > 0.0:
            raise ValueError(f"the flywheel for δ needs δ > 0 and ω_m > 0, got δ = {d!r}, ω_m = {omega_m!r}")
        k_hi, k_lo = 0.5 * (omega_m * (1 + d / 2)) ** 2, 0.5 * (omega_m * (1 - d / 2)) ** 2
        hi, lo = tangent(k_hi, 1.0), tangent(k_lo, -1.0)
        j = (hi[2] - lo[2]) / (w2 * d)                   # k_hi − k_lo = ω_m²·δ
        w_hi, w_lo = tangent(0.5 * w2 * (1 + d), 1.0), tangent(0.5 * w2 * (1 - d), -1.0)
        jw = (w_hi[2] - w_lo[2]) / (w2 * d)
        if j > 0.0:
            excess = 0.5 * w2 * d * (1 + d / 4) * j - hi[2]
            return Flywheel(d, omega_m, j, jw, w_hi, w_lo, j, False), excess
        required, j = j, 0.0
        wheel = Flywheel(d, omega_m, 0.0, max(jw, 0.0), w_hi, w_lo, required, False)
        key = "dynamics"
    else:
        j = flywheel
        wheel = Flywheel(0.0, omega_m, j, None, None, None, None, True)
        key = "dynamics.flywheel"
    _check_inertia(inertia, j, key)
    excess = _excess(omega_m, energy, inertia, j, key)
    x = nodes_of(energy.edges)
    _, _, reached = _reached(_rise(energy.edges, excess, energy(x), inertia(x), j, omega_m), omega_m)
    return replace(wheel, delta=reached), excess


def _check_inertia(inertia: Piecewise, j: float, key: str) -> None:
    """I(θ) + J > 0 over the cycle, or a one-line refusal at ``key``: where the machine holds no
    kinetic energy at a speed, the speed is not defined by its energy."""
    th = np.concatenate([np.linspace(inertia.edges[0], inertia.edges[-1], 721), nodes_of(inertia.edges)])
    total = inertia(th) + j
    if np.all(total > 0.0):
        return
    fix = "give [masses] of the links, rotor_inertia (the motor and gears reduced to the crank) or a flywheel > 0"
    if not np.any(total > 0.0):
        raise SceneError("the machine has no inertia at all (no masses, no rotor_inertia, no flywheel): its speed is "
                         f"not defined by its energy; {fix}", key=key)
    at = float(th[int(np.argmin(total))])
    raise SceneError(f"the machine's reduced inertia is 0 at θ = {math.degrees(at):.6g}° from the first position "
                     f"(nothing that moves there has mass, and there is no flywheel): its speed is not defined by "
                     f"its energy there; {fix}", key=key)


def _rise(edges: np.ndarray, excess: float, energy: np.ndarray, inertia: np.ndarray, j: float,
          omega_m: float) -> Piecewise:
    """ω² − ω_m² = 2(e0 + ΔT − ½ω_m²·I)/(I + J) (rad²/s²) from ΔT and I at the nodes of ``edges``."""
    gain = excess + energy - 0.5 * omega_m * omega_m * inertia
    return fit(edges, 2.0 * gain / (inertia + j))


def _reached(rise: Piecewise, omega_m: float) -> tuple[float, float, float]:
    """(ω_max, ω_min, δ) from the rise ω² − ω_m²: ω − ω_m = (ω² − ω_m²)/(ω + ω_m), so that
    ω_max − ω_min is the difference of two small departures of opposite sign, not of two
    nearly equal speeds; δ = (ω_max − ω_min)/((ω_max + ω_min)/2). ω_min is 0 where the crank
    would stop."""
    (hi, up), (lo, down) = (_departure(rise.extreme(s)[1], omega_m) for s in (1.0, -1.0))
    return hi, lo, (up - down) / (omega_m + 0.5 * (up + down))


def _departure(rise: float, omega_m: float) -> tuple[float, float]:
    """(ω, ω − ω_m) for ω² − ω_m² = ``rise`` (rad/s; ω = 0 when ω² would be negative)."""
    w2 = omega_m * omega_m + rise
    if not w2 > 0.0:
        return 0.0, -omega_m
    w = math.sqrt(w2)
    return w, rise / (w + omega_m)


def _excess(omega_m: float, energy: Piecewise, inertia: Piecewise, j: float, key: str) -> float:
    """e0 = T0 − ½ω_m²·J (J) such that (ω_max + ω_min)/2 = ω_m with the flywheel J: the root of
    the mean's departure from ω_m, which grows with e0 (regula falsi, Illinois, bracketed), found
    on e0 itself — of the size of ΔT — not on T0 = ½ω_m²·J + e0, whose last bits would be
    larger than the cycle's swing when J is large."""
    edges = energy.edges
    x = nodes_of(edges)
    e, i = energy(x), inertia(x)
    base = e - 0.5 * omega_m * omega_m * i

    def departure(e0: float) -> float:
        rise = fit_rise(e0)
        _, up = _departure(rise.extreme(1.0)[1], omega_m)
        _, down = _departure(rise.extreme(-1.0)[1], omega_m)
        return 0.5 * (up + down)

    def fit_rise(e0: float) -> Piecewise:
        return _rise(edges, e0, e, i, j, omega_m)

    # e0 = −max(base): the gain e0 + base ≤ 0 everywhere, ω ≤ ω_m; e0 = −min(base): ω ≥ ω_m
    lo, hi = -float(np.max(base)), -float(np.min(base))
    width = max(hi - lo, 1e-12 * max(abs(lo), abs(hi)), 1e-300)
    f_lo, f_hi = departure(lo), departure(hi)
    for _ in range(60):                  # the fit between the nodes may stray past them
        if f_lo <= 0.0:
            break
        hi, f_hi, lo = lo, f_lo, lo - width
        f_lo, width = departure(lo), 2.0 * width
    for _ in range(60):
        if f_hi >= 0.0:
            break
        lo, f_lo, hi = hi, f_hi, hi + width
        f_hi, width = departure(hi), 2.0 * width
    root, f_root, side = (lo, f_lo, 0) if abs(f_lo) <= abs(f_hi) else (hi, f_hi, 0)
    for _ in range(200):
        if f_root == 0.0 or abs(f_root) <= 4e-16 * omega_m or hi - lo <= 4.0 * math.ulp(max(abs(lo), abs(hi))):
            break
        x_new = (lo * f_hi - hi * f_lo) / (f_hi - f_lo) if f_hi != f_lo else 0.5 * (lo + hi)
        if not lo < x_new < hi:
            x_new = 0.5 * (lo + hi)
        f_new = departure(x_new)
        if f_new < 0.0:
            lo, f_lo = x_new, f_new
            f_hi = 0.5 * f_hi if side == -1 else f_hi       # Illinois: halve the end kept twice
            side = -1
        else:
            hi, f_hi = x_new, f_new
            f_lo = 0.5 * f_lo if side == 1 else f_lo
            side = 1
        root, f_root = x_new, f_new
    if not omega_m * omega_m + fit_rise(root).extreme(-1.0)[1] > 0.0:
        raise SceneError(f"with a flywheel of {j:g} kg·m² the crank stops within the cycle at ω_m = {omega_m:g} rad/s "
                         "(the loads take more energy than the machine holds at that speed): give a larger flywheel, "
                         "or delta (the flywheel is then found for it)", key=key)
    return root


def _breaks(scene: Scene, cycle: Cycle, solve, sense: float, start: float) -> np.ndarray:
    """θ (rad, in (0, 2π)) where a load kinks or jumps: the output's extremes (a stroke's ends),
    where its travel crosses a law's knot, where the point of a force that opposes its velocity
    comes to rest (along the force's line)."""
    out: list[float] = []
    forces = [f for f in scene.forces if f.follows_output or f.oppose]
    if not forces:
        return np.array([])
    if cycle.extremes is not None and any(f.follows_output for f in forces):
        out += [float(np.mod(sense * np.radians(a - start), 2 * np.pi)) for a in cycle.extremes.values]
    grid = np.linspace(0.0, 2 * np.pi, BRACKETS + 1)
    motion, travel = solve(grid, 1)
    probes = []       # functions of (motion, travel) whose sign changes are kinks
    for f in forces:
        if f.law:
            for x_k, _ in f.law:
                probes.append(lambda m, t, f=f, x_k=x_k: t.x(f.origin) - x_k)
        if f.oppose:
            if f.vector is not None:        # its point's velocity along the force's line
                probes.append(lambda m, t, f=f, d=np.array(f.vector, float): la.matmul(m.velocity(f.at, f.link), d))
            else:                           # along the velocity itself: where it reverses
                v = motion.velocity(f.at, f.link)
                flip = np.flatnonzero(np.sum(v[:-1] * v[1:], axis=1) < 0.0)
                for j in flip:
                    ref = v[j].copy()
                    out += _refine(lambda m, t, ref=ref, f=f: la.matmul(m.velocity(f.at, f.link), ref), solve,
                                   grid[j:j + 1], grid[j + 1:j + 2], 1)
    for probe in probes:
        g = probe(motion, travel)
        j = np.flatnonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0)
        if j.size:
            out += _refine(probe, solve, grid[j], grid[j + 1], 1)
    return np.unique(np.mod(np.array(out), 2 * np.pi)) if out else np.array([])


def _refine(probe, solve, lo: np.ndarray, hi: np.ndarray, order: int) -> list[float]:
    """Roots of ``probe`` in the brackets [lo, hi] (one sign change each), by the Illinois
    variant of regula falsi to :data:`BREAK_TOL`."""
    lo, hi = lo.astype(float).copy(), hi.astype(float).copy()
    m, t = solve(np.concatenate([lo, hi]), order)
    g = probe(m, t)
    glo, ghi = g[:len(lo)].copy(), g[len(lo):].copy()
    side = np.zeros(len(lo))
    for _ in range(100):
        with np.errstate(divide="ignore", invalid="ignore"):
            x = (lo * ghi - hi * glo) / (ghi - glo)
        x = np.where(np.isfinite(x) & (x > lo) & (x < hi), x, 0.5 * (lo + hi))
        m, t = solve(x, order)
        gx = probe(m, t)
        left = np.sign(gx) == np.sign(glo)
        # Illinois: halve the value kept on the side that stays twice
        ghi = np.where(left & (side == 1), 0.5 * ghi, ghi)
        glo = np.where(~left & (side == -1), 0.5 * glo, glo)
        lo, glo = np.where(left, x, lo), np.where(left, gx, glo)
        hi, ghi = np.where(left, hi, x), np.where(left, ghi, gx)
        side = np.where(left, 1, -1)
        if np.all((hi - lo <= BREAK_TOL) | (gx == 0.0)):
            break
    return list(0.5 * (lo + hi))

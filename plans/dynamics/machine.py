"""The machine's motion under its loads over one steady cycle of the crank (the second problem
of dynamics): the reduced moment and inertia over the revolution, the work of the loads and of
the driving moment, the change of kinetic energy, the flywheel for an allowed coefficient of
speed fluctuation δ (exactly, and by Wittenbauer's energy–mass diagram), and the true speed
ω1(φ) and ε1(φ) with it.

Angles here are the crank's turned angle θ = sense·(φ − φ_start) in radians (0 … 2π over the
cycle, growing in the crank's sense of rotation) and moments are taken in that sense (positive
when they drive), so that work is ∫M dθ whatever way the crank turns. The reported M_r (CCW
positive) is sense × that.

Exactness: the loads are sampled at the Gauss nodes of panels of at most 1° whose edges
include every point where a load kinks or jumps (a law's knot crossed by the output's travel,
the ends of the strokes, the rest points of a force opposing its point's velocity), found by
root-finding to ~1e-13 rad; on each panel the samples define a polynomial of degree 7
(:mod:`.piecewise`), so the integrals and the searches for the largest and smallest values are
exact to ~1e-13 of their size, far below the 1e-9 asked.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from .. import linalg as la

from ..errors import PlansError
from ..kinematics import analyse
from ..kinematics.cycle import Cycle, output_motion
from ..kinetostatics import Travel, forces_following
from ..scene import Scene
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
    ``slope`` dI/dθ, ``work`` ∫moment dθ, ``energy`` ΔT = work + constant·θ; ``constant`` the
    constant moment on the crank (N·m in the sense of rotation: positive a motor, negative a
    consumer when the loads drive, as in an engine); ``at``: M_r, I_r, dI_r/dφ (CCW, as
    :class:`~.reduced.Reduced`) at the cycle's N positions; ``theta`` those positions' θ;
    ``breaks`` the θ where a load kinks; ``flywheel`` and ``kinetic0`` T at θ = 0 (J), with the
    flywheel's J, so that ω(θ) = √(2(T0 + ΔT)/(I + J))."""

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
    omega_sq: Piecewise

    @property
    def J(self) -> float:
        return self.flywheel.inertia_exact

    def omega(self, theta: np.ndarray | float) -> np.ndarray:
        """|ω1| (rad/s) at θ."""
        e = self.kinetic0 + self.energy(theta)
        return np.sqrt(np.maximum(2.0 * e / (self.inertia(theta) + self.J), 0.0))

    def epsilon(self, theta: np.ndarray | float) -> np.ndarray:
        """dω/dt in the sense of rotation (rad/s²) at θ: (dΔT/dθ − ½ω²·dI/dθ)/(I + J)."""
        w = self.omega(theta)
        return (self.moment(theta) + self.constant - 0.5 * w * w * self.slope(theta)) / (self.inertia(theta) + self.J)

    def driving_work(self, theta: np.ndarray | float) -> np.ndarray:
        """A_d: the work of what drives (the constant moment, or the loads of an engine), J."""
        theta = np.asarray(theta, dtype=float)
        return self.constant * theta if self.constant >= 0.0 else self.work(theta)

    def resisting_work(self, theta: np.ndarray | float) -> np.ndarray:
        """A_r: the work done against what resists (the loads, or an engine's consumer), J."""
        theta = np.asarray(theta, dtype=float)
        return -self.work(theta) if self.constant >= 0.0 else -self.constant * theta

    def delta_reached(self) -> tuple[float, float, float]:
        """(ω_max, ω_min, δ) of the true speed, found on the cycle."""
        hi = math.sqrt(self.omega_sq.extreme(1.0)[1])
        lo = math.sqrt(max(self.omega_sq.extreme(-1.0)[1], 0.0))
        return hi, lo, (hi - lo) / (0.5 * (hi + lo))


def machine_dynamics(scene: Scene, cycle: Cycle) -> MachineDynamics:
    """The steady cycle of ``scene`` (with ``[dynamics]``) over the solved ``cycle``."""
    dyn = scene.dynamics
    mech = cycle.motion.mechanism
    structure = cycle.motion.structure
    w1 = float(mech.drive.speed)
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
        motion = analyse(mech, structure, phi_of(np.asarray(theta, float)), order=order)
        travel = None
        if follows:
            out = output_motion(motion, cycle.output.link)
            v = out.v if out.v is not None else np.zeros(len(motion))
            travel = Travel(out.link, out.kind, out.s, v, low, high, scale)
        return motion, travel

    breaks = _breaks(scene, cycle, solve, sense, start)
    uniform = np.linspace(0.0, 2 * np.pi, int(round(360.0 / PANEL_DEG)) + 1)
    edges = np.unique(np.concatenate([uniform, breaks]))
    edges = edges[np.concatenate([[True], np.diff(edges) > 1e-12])]
    edges[-1] = 2 * np.pi
    motion, travel = solve(nodes_of(edges), 2)
    red = reduce(motion, scene, travel)
    moment = fit(edges, sense * red.moment)
    inertia = fit(edges, red.inertia + dyn.rotor_inertia)
    slope = fit(edges, sense * red.slope)
    work = moment.integral(0.0)
    constant = -moment.total() / (2 * np.pi)
    half = 0.5 * np.diff(edges)
    line = Piecewise(edges, np.column_stack([constant * (edges[:-1] + half), constant * half]))
    energy = combine((1.0, work), (1.0, line))
    theta = np.arange(len(cycle.motion)) * (2 * np.pi / len(cycle.motion))
    pos_motion, pos_travel = solve(theta, 2)
    at = reduce(pos_motion, scene, pos_travel)
    omega_m = abs(w1)
    wheel, t0 = flywheel_for(energy, inertia, omega_m, delta=dyn.delta, flywheel=dyn.flywheel)
    w2 = fit(edges, 2.0 * (t0 + energy(nodes_of(edges))) / (inertia(nodes_of(edges)) + wheel.inertia_exact))
    return MachineDynamics(sense=sense, start=start, omega_m=omega_m, rotor=dyn.rotor_inertia, moment=moment,
                           inertia=inertia, slope=slope, work=work, energy=energy, constant=constant, at=at,
                           theta=theta, breaks=breaks, flywheel=wheel, kinetic0=t0, omega_sq=w2)


def flywheel_for(energy: Piecewise, inertia: Piecewise, omega_m: float, *, delta: float | None = None,
                 flywheel: float | None = None) -> tuple[Flywheel, float]:
    """The flywheel and T0 (the kinetic energy at θ = 0) of a steady cycle whose change of
    kinetic energy is ``energy`` ΔT(θ) (J, periodic: 0 at both ends) and reduced inertia
    ``inertia`` I(θ) (kg·m²), at the mean speed ``omega_m`` (rad/s): for ``delta``, J exactly from
    J = (max(ΔT − ½ω_max²·I) − min(ΔT − ½ω_min²·I)) / (½(ω_max² − ω_min²)) — the tangents of
    the energy–mass curve — and Wittenbauer's the same with ½ω_m²(1 ± δ); for a given J, T0
    such that (ω_max + ω_min)/2 = ω_m, and δ."""
    def tangent(k: float, sign: float) -> tuple[float, float, float]:
        f = combine((1.0, energy), (-k, inertia))
        th, c = f.extreme(sign)
        return th, k, c

    if (delta is None) == (flywheel is None):
        raise ValueError("give delta or flywheel")
    if delta is not None:
        d = delta
        k_hi, k_lo = 0.5 * (omega_m * (1 + d / 2)) ** 2, 0.5 * (omega_m * (1 - d / 2)) ** 2
        hi, lo = tangent(k_hi, 1.0), tangent(k_lo, -1.0)
        j = (hi[2] - lo[2]) / (k_hi - k_lo)
        w_hi, w_lo = tangent(0.5 * omega_m ** 2 * (1 + d), 1.0), tangent(0.5 * omega_m ** 2 * (1 - d), -1.0)
        jw = (w_hi[2] - w_lo[2]) / (omega_m ** 2 * d)
        if j >= 0.0:
            t0 = k_hi * j - hi[2]
            return Flywheel(d, omega_m, j, jw, w_hi, w_lo, j, False), t0
        required, j = j, 0.0
        wheel = Flywheel(d, omega_m, 0.0, max(jw, 0.0), w_hi, w_lo, required, False)
    else:
        j = flywheel
        wheel = Flywheel(0.0, omega_m, j, None, None, None, None, True)
    t0 = _mean_speed(omega_m, energy, inertia, j)
    if j + float(np.min(inertia(np.linspace(energy.edges[0], energy.edges[-1], 721)))) <= 0.0:
        raise PlansError("the machine has no inertia at all (no masses, no rotor_inertia, no flywheel): its speed is "
                         "not defined by its energy; give masses, rotor_inertia or a flywheel")
    w2 = lambda th: 2.0 * (t0 + energy(th)) / (inertia(th) + j)      # noqa: E731
    edges = energy.edges
    sq = fit(edges, w2(nodes_of(edges)))
    hi, lo = math.sqrt(sq.extreme(1.0)[1]), math.sqrt(max(sq.extreme(-1.0)[1], 0.0))
    return replace(wheel, delta=(hi - lo) / omega_m), t0


def _mean_speed(omega_m: float, energy: Piecewise, inertia: Piecewise, j: float) -> float:
    """T0 such that (ω_max + ω_min)/2 = ω_m with the flywheel J (bisection on T0, where the mean
    grows with T0)."""
    edges = energy.edges
    x = nodes_of(edges)
    e, i = energy(x), inertia(x) + j

    def mean(t0: float) -> float:
        sq = fit(edges, 2.0 * (t0 + e) / i)
        return 0.5 * (math.sqrt(sq.extreme(1.0)[1]) + math.sqrt(max(sq.extreme(-1.0)[1], 0.0)))

    lo = float(np.max(-e)) * (1 + 1e-12) + 1e-300      # T ≥ 0 everywhere
    if mean(lo) >= omega_m:
        raise PlansError(f"with a flywheel of {j:g} kg·m² the crank stops within the cycle at ω_m = {omega_m:g} rad/s "
                         "(the loads take more energy than the machine holds): give a larger flywheel")
    hi = max(lo, 0.0) + 0.5 * float(np.max(i)) * omega_m ** 2 * 4 + 1.0
    while mean(hi) < omega_m:
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mean(mid) < omega_m:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-15 * abs(hi):
            break
    return 0.5 * (lo + hi)


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

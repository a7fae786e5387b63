"""The start-up of the machine by its motor, in time, from rest: the reduced equation of motion

    (I_r + J)·dω/dt + ½·(dI_r/dφ)·ω² = M_motor(ω) + M_r(φ)

(moments in the crank's sense of rotation, M_r the loads' reduced moment: negative where they
resist) integrated by SciPy's ``solve_ivp`` (DOP853, an explicit Runge–Kutta of order 8 with
error control, its sums in fixed order: :mod:`.dop853`; ``rtol``/``atol`` are its tolerances) until ``t_end``,
stopped and restarted at every kink of the loads (the steady cycle's ``breaks``), so that no
step has one inside and the error control holds on every step. The loads are those of the
steady cycle (:mod:`.machine`): a force that opposes its point's velocity, or acts on a stroke,
takes the sense it has with the crank turning forward.

Beside it, the steady cycle the motor settles into: the periodic solution of the energy
equation dT/dφ = M_motor(ω) + M_r(φ), T = ½(I_r + J)·ω², found by shooting over one revolution
(secant on ω at φ = 0, from the simulation's last revolution), with its ω_max, ω_min and δ.
The time to steady state is the first instant after which ω stays within the steady cycle's
band widened by :data:`STEADY_BAND` of ω_m on each side.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import PlansError
from ..scene.dynamics import Motor
from .machine import MachineDynamics
from .dop853 import DOP853
from .motor import motor_moment

__all__ = ["Startup", "Steady", "startup", "RTOL", "ATOL", "STEADY_BAND", "SAMPLES"]

#: The integrator's relative and absolute tolerances (absolute: rad and rad/s).
RTOL = 1e-10
ATOL = 1e-12
#: The steady band's margin, a fraction of ω_m on each side.
STEADY_BAND = 0.01
#: Samples of the start-up kept for the report and the sheet.
SAMPLES = 1201


@dataclass(frozen=True)
class Steady:
    """The periodic cycle under the motor: ``omega_mean`` (ω_max + ω_min)/2, ``omega_max``,
    ``omega_min`` (rad/s), ``delta`` (ω_max − ω_min)/ω_m, ``omega0`` ω at φ = position 0."""

    omega_mean: float
    omega_max: float
    omega_min: float
    delta: float
    omega0: float


@dataclass(frozen=True, eq=False)
class Startup:
    """The start-up: ``t`` (s), ``theta`` turned angle (rad), ``omega`` (rad/s, in the sense of
    rotation), ``motor`` and ``load`` (N·m at the crank, the motor's and the loads' reduced
    moments in that sense) at :data:`SAMPLES` instants; ``t_end``, ``rtol``, ``atol``,
    ``evaluations`` of the right side; ``steady`` the cycle it settles into, ``last`` (ω_max,
    ω_min, δ) over the last whole revolution simulated, ``time_to_steady`` (s, None when not
    reached by t_end) and ``inertia`` J + the rotor's."""

    t: np.ndarray
    theta: np.ndarray
    omega: np.ndarray
    motor: np.ndarray
    load: np.ndarray
    t_end: float
    rtol: float
    atol: float
    evaluations: int
    steady: Steady | None
    last: tuple[float, float, float] | None
    time_to_steady: float | None
    solution: object


def _pieces(machine: MachineDynamics) -> np.ndarray:
    """The edges (in [0, 2π]) between which the loads are smooth: 0, the kinks, 2π."""
    two_pi = 2.0 * math.pi
    edges = np.unique(np.concatenate([[0.0], np.mod(machine.breaks, two_pi), [two_pi]]))
    return edges[np.concatenate([np.diff(edges) > 1e-12, [True]])]


def _equation(machine: MachineDynamics, motor: Motor, lo: float, hi: float, base: float):
    """The right side for θ − ``base`` in [``lo``, ``hi``] (one smooth piece of a revolution),
    its loads continued smoothly beyond both ends."""
    j = machine.J
    moment, slope, inertia = (f.between(lo, hi) for f in (machine.moment, machine.slope, machine.inertia))

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        th = y[0] - base
        w = y[1]
        num = float(motor_moment(motor, w)) + moment.at(th) - 0.5 * slope.at(th) * w * w
        return np.array([w, num / (inertia.at(th) + j)])
    return rhs


@dataclass(frozen=True, eq=False)
class Solution:
    """The start-up's dense solution over all its pieces: ``sol(t)`` → (θ, ω) (a SciPy
    ``OdeSolution``), ``t`` the integrator's step ends, ``nfev`` its evaluations."""

    sol: object
    t: np.ndarray
    nfev: int


def _integrate(machine: MachineDynamics, motor: Motor, t_end: float, rtol: float, atol: float) -> Solution:
    """DOP853 from rest, stopped at every kink of the loads (θ at a break of a revolution) and
    restarted from there: no step has a kink inside, so the error control holds on every step
    (a step over a kink errs by ~0.08·ΔM′·(ω·h)², far beyond rtol, while the error estimate
    sees little of it). Raises PlansError when the crank stalls."""
    from scipy.integrate import OdeSolution, solve_ivp       # imported only when a start-up is simulated
    two_pi = 2.0 * math.pi
    edges = _pieces(machine)

    def stalls(t: float, y: np.ndarray) -> float:
        return y[1] if t > 0.0 else 1.0
    stalls.terminal, stalls.direction = True, -1

    t0, y0, k, turn, first = 0.0, np.array([0.0, 0.0]), 0, 0, None
    ts, parts, nfev = [np.array([0.0])], [], 0
    while True:
        base, target = turn * two_pi, turn * two_pi + edges[k + 1]

        def reaches(t: float, y: np.ndarray, target=target) -> float:
            return y[0] - target
        reaches.terminal, reaches.direction = True, 1

        rhs = _equation(machine, motor, edges[k], edges[k + 1], base)
        sol = solve_ivp(rhs, (t0, t_end), y0, method=DOP853, rtol=rtol, atol=atol, dense_output=True,
                        events=(stalls, reaches), first_step=first)
        nfev += sol.nfev
        if not sol.success:
            raise PlansError(f"the start-up could not be integrated: {sol.message}")
        ts.append(sol.sol.ts[1:])
        parts += sol.sol.interpolants
        if sol.status == 1 and len(sol.t_events[0]):
            ts_ = float(sol.t_events[0][0])
            th = float(sol.y_events[0][0][0])
            raise PlansError(f"the motor cannot start the load: the crank stops at t = {ts_:.4g} s, "
                             f"φ = {(machine.start + machine.sense * math.degrees(th)) % 360:.6g}° (the loads' "
                             f"reduced moment there is {float(machine.moment(th % two_pi)):.4g} N·m); give a "
                             "stronger motor, a larger ratio or a larger flywheel")
        if sol.status != 1:
            break
        # the state at the kink by a step of the method that ends there (error-controlled),
        # not by the dense output of the step that overshot it (order 7, not controlled)
        over = parts.pop()
        t_n, t0 = over.t_min, float(sol.t_events[1][0])
        ts[-1] = ts[-1][:-1]
        if t0 > t_n:
            sol = solve_ivp(rhs, (t_n, t0), over(t_n), method=DOP853, rtol=rtol, atol=atol, dense_output=True,
                            first_step=t0 - t_n)
            nfev += sol.nfev
            ts.append(sol.sol.ts[1:])
            parts += sol.sol.interpolants
            y0 = sol.y[:, -1]
        else:
            y0 = over(t_n)
        first = min(over.t_max - over.t_min, t_end - t0) or None
        if t0 >= t_end:
            break
        k += 1
        if k == len(edges) - 1:
            k, turn = 0, turn + 1
    t = np.concatenate(ts)
    return Solution(sol=OdeSolution(t, parts), t=t, nfev=nfev)


def startup(machine: MachineDynamics, motor: Motor, t_end: float, *, rtol: float = RTOL,
            atol: float = ATOL) -> Startup:
    """The start-up from rest at position 0 to ``t_end`` s (see the module)."""
    m0, l0 = float(motor_moment(motor, 0.0)), float(machine.moment(0.0))
    if m0 + l0 <= 0.0:
        raise PlansError(f"the motor cannot start the load: its starting moment at the crank is {m0:.4g} N·m and the "
                         f"loads resist with {-l0:.4g} N·m at the first position (φ = {machine.start % 360:.6g}°); "
                         "give a stronger motor or a larger ratio")
    sol = _integrate(machine, motor, t_end, rtol, atol)
    t = np.linspace(0.0, t_end, SAMPLES)
    y = sol.sol(t)
    th, w = y[0], y[1]
    motor_m = motor_moment(motor, w)
    load = machine.moment(np.mod(th, 2 * math.pi))
    turns = int(th[-1] // (2 * math.pi))
    steady = last = when = None
    if turns >= 2:
        # the last whole revolution simulated: from the last time θ passed a multiple of 2π
        t_a = _time_at(sol, (turns - 1) * 2 * math.pi, t_end)
        t_b = _time_at(sol, turns * 2 * math.pi, t_end)
        ws = sol.sol(np.linspace(t_a, t_b, 4001))[1]
        hi, lo = float(np.max(ws)), float(np.min(ws))
        last = (hi, lo, (hi - lo) / (0.5 * (hi + lo)))
        steady = steady_cycle(machine, motor, float(sol.sol(t_b)[1]), rtol=rtol)
        if steady is not None:
            band = STEADY_BAND * steady.omega_mean
            out = np.flatnonzero((w < steady.omega_min - band) | (w > steady.omega_max + band))
            if out.size == 0 or out[-1] < len(t) - 1:
                when = float(t[out[-1] + 1]) if out.size else 0.0
    return Startup(t=t, theta=th, omega=w, motor=motor_m, load=load, t_end=t_end, rtol=rtol, atol=atol,
                   evaluations=int(sol.nfev), steady=steady, last=last, time_to_steady=when, solution=sol)


def _time_at(sol, theta: float, t_end: float) -> float:
    """The instant the simulated θ reaches ``theta`` (bisection on the dense output; θ grows)."""
    lo, hi = 0.0, t_end
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if sol.sol(mid)[0] < theta:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-13 * max(t_end, 1.0):
            break
    return 0.5 * (lo + hi)


def steady_cycle(machine: MachineDynamics, motor: Motor, guess: float, *, rtol: float = RTOL) -> Steady | None:
    """The periodic cycle under the motor (see the module) from a guess of ω at position 0, or
    None when the shooting does not converge (the motor cannot keep the machine turning)."""
    from scipy.integrate import solve_ivp
    j = machine.J
    two_pi = 2.0 * math.pi

    def de(th: float, e: np.ndarray) -> np.ndarray:
        w = math.sqrt(max(2.0 * e[0] / (machine.inertia.at(th) + j), 0.0))
        return np.array([float(motor_moment(motor, w)) + machine.moment.at(th)])

    i0 = float(machine.inertia(0.0)) + j

    def shoot(w0: float, dense: bool = False):
        edges = np.unique(np.concatenate([[0.0], machine.breaks, [two_pi]]))
        e = 0.5 * i0 * w0 * w0
        pieces = []
        for a, b in zip(edges[:-1], edges[1:]):        # a jump of a load is an edge, never a step's inside
            s = solve_ivp(de, (a, b), [e], method=DOP853, rtol=rtol, atol=1e-12 * max(e, 1.0), dense_output=dense)
            if not s.success or s.y[0, -1] <= 0.0:
                return None, pieces
            e = float(s.y[0, -1])
            pieces.append(s)
        return math.sqrt(2.0 * e / i0), pieces

    x0, x1 = guess, guess * (1.0 + 1e-4)
    f0 = (shoot(x0)[0] or 0.0) - x0
    f1 = (shoot(x1)[0] or 0.0) - x1
    for _ in range(60):
        if f1 == f0:
            break
        x2 = x1 - f1 * (x1 - x0) / (f1 - f0)
        if not x2 > 0.0:
            return None
        end = shoot(x2)[0]
        if end is None:
            return None
        x0, f0, x1, f1 = x1, f1, x2, end - x2
        if abs(f1) <= 1e-12 * x1:
            break
    if abs(f1) > 1e-8 * x1:
        return None
    _, pieces = shoot(x1, dense=True)
    ws = []
    for s in pieces:
        th = np.linspace(s.t[0], s.t[-1], max(int(4000 * (s.t[-1] - s.t[0]) / two_pi), 8))
        e = s.sol(th)[0]
        ws.append(np.sqrt(np.maximum(2.0 * e / (machine.inertia(th) + j), 0.0)))
    ws = np.concatenate(ws)
    hi, lo = float(np.max(ws)), float(np.min(ws))
    mean = 0.5 * (hi + lo)
    return Steady(omega_mean=mean, omega_max=hi, omega_min=lo, delta=(hi - lo) / mean, omega0=x1)

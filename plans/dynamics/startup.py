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

from ..errors import SceneError
from ..scene.dynamics import Motor
from .machine import MachineDynamics
from .dop853 import DOP853
from .motor import RPM, motor_moment, no_load_speed

__all__ = ["Startup", "Steady", "startup", "RTOL", "ATOL", "STEADY_BAND", "SAMPLES", "MAX_TURNS", "MAX_STIFFNESS",
           "MAX_EVALUATIONS", "MAX_SHOOTING_EVALUATIONS", "motor_stiffness"]

#: The integrator's relative and absolute tolerances (absolute: rad and rad/s).
RTOL = 1e-10
ATOL = 1e-12
#: The steady band's margin, a fraction of ω_m on each side.
STEADY_BAND = 0.01
#: Samples of the start-up kept for the report and the sheet.
SAMPLES = 1201
#: Most turns of the crank a start-up may simulate, t_end·ω_0/2π with ω_0 the motor's no-load
#: speed at the crank (the mean speed never exceeds it while the loads resist): a start-up
#: settles within tens of turns (the press in 9), the steady cycle after it is found by shooting
#: over one turn, and a turn costs ~760 evaluations of the equation (~30 ms) with the press's
#: 8 kinks a turn, so 200 turns take ~6 s.
MAX_TURNS = 200
#: Largest t_end/τ, τ = min(I_r + J)/max|dM_motor/dω| (s) the time in which the motor's
#: characteristic pulls ω back (its slope at the crank, the ratio counted squared): DOP853 is
#: explicit, and a motor far stiffer than the machine's inertia holds its steps near 2.7·τ
#: (measured: 4.4 evaluations per τ), so 2e4 τ take ~90 000 evaluations (~4 s); ω has long
#: settled by then.
MAX_STIFFNESS = 2e4
#: Most evaluations of the equation's right side in a start-up (~12 s), a guard behind the two
#: bounds above (a machine with many kinks a turn restarts the integrator at each): past it the
#: start-up is refused, naming the instant reached.
MAX_EVALUATIONS = 300_000
#: Most evaluations of the shooting for the steady cycle (its secant's revolutions); past it
#: the steady cycle is reported as not found.
MAX_SHOOTING_EVALUATIONS = 75_000


class _OverBudget(Exception):
    """Raised from the right side once the evaluations run out; ``t`` the time (or angle) reached."""

    def __init__(self, t: float) -> None:
        super().__init__(t)
        self.t = t


class _Budget:
    """A count of the right side's evaluations, raising :class:`_OverBudget` past ``limit``."""

    def __init__(self, limit: int) -> None:
        self.left = limit

    def spend(self, t: float) -> None:
        self.left -= 1
        if self.left < 0:
            raise _OverBudget(t)


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


def _equation(machine: MachineDynamics, motor: Motor, lo: float, hi: float, base: float, budget: _Budget):
    """The right side for θ − ``base`` in [``lo``, ``hi``] (one smooth piece of a revolution),
    its loads continued smoothly beyond both ends; each call spends one of ``budget``."""
    j = machine.J
    moment, slope, inertia = (f.between(lo, hi) for f in (machine.moment, machine.slope, machine.inertia))

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        budget.spend(t)
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
    sees little of it). Refused (SceneError) when the crank stalls or the evaluations exceed
    :data:`MAX_EVALUATIONS`."""
    budget = _Budget(MAX_EVALUATIONS)
    try:
        return _pieces_integrated(machine, motor, t_end, rtol, atol, budget)
    except _OverBudget as over:
        raise SceneError(f"the start-up took more than {MAX_EVALUATIONS} evaluations of its equation (the bound: "
                         f"about 12 s of computing) and reached only t = {over.t:.4g} s of t_end = {t_end:g} s; give "
                         f"t_end ≤ {_rounded_down(over.t)} s", key="dynamics.simulate.t_end") from None


def _pieces_integrated(machine: MachineDynamics, motor: Motor, t_end: float, rtol: float, atol: float,
                       budget: _Budget) -> Solution:
    """:func:`_integrate`'s work, every evaluation spent from ``budget``."""
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

        rhs = _equation(machine, motor, edges[k], edges[k + 1], base, budget)
        sol = solve_ivp(rhs, (t0, t_end), y0, method=DOP853, rtol=rtol, atol=atol, dense_output=True,
                        events=(stalls, reaches), first_step=first)
        nfev += sol.nfev
        if not sol.success:
            raise SceneError(f"the start-up could not be integrated past t = {t0:.4g} s ({sol.message}); give a "
                             "smaller t_end", key="dynamics.simulate.t_end")
        ts.append(sol.sol.ts[1:])
        parts += sol.sol.interpolants
        if sol.status == 1 and len(sol.t_events[0]):
            ts_ = float(sol.t_events[0][0])
            th = float(sol.y_events[0][0][0])
            raise SceneError(f"the motor cannot start the load: the crank stops at t = {ts_:.4g} s, "
                             f"φ = {(machine.start + machine.sense * math.degrees(th)) % 360:.6g}° (the loads' "
                             f"reduced moment there is {float(machine.moment(th % two_pi)):.4g} N·m); give a "
                             "stronger motor (power, or its torque table), a larger ratio, or a larger flywheel "
                             "([dynamics] flywheel, or a smaller delta)", key="motor")
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
    """The start-up from rest at position 0 to ``t_end`` s (see the module). Refused in one
    line (SceneError) when the motor cannot start the load, or the start-up exceeds
    :data:`MAX_TURNS`, :data:`MAX_STIFFNESS` or :data:`MAX_EVALUATIONS`."""
    m0, l0 = float(motor_moment(motor, 0.0)), float(machine.moment(0.0))
    if m0 + l0 <= 0.0:
        raise SceneError(f"the motor cannot start the load: its starting moment at the crank is {m0:.4g} N·m and the "
                         f"loads resist with {-l0:.4g} N·m at the first position (φ = {machine.start % 360:.6g}°); "
                         "give a stronger motor (power, or its torque table) or a larger ratio", key="motor")
    _check_length(machine, motor, t_end)
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


def motor_stiffness(motor: Motor) -> float:
    """The largest |dM/dω| of the motor's moment at the crank (N·m·s): i² times its shaft's —
    Kloss' at synchronous speed, 2·M_k/(s_k·ω_sync); a table's steepest row (or its continuation)."""
    i2 = motor.ratio * motor.ratio
    if motor.torque:
        rows = motor.torque
        return i2 * max(abs((b[1] - a[1]) / (b[0] - a[0])) for a, b in zip(rows, rows[1:])) / RPM
    lam = motor.breakdown
    s_k = (1.0 - motor.rated_rpm / motor.synchronous_rpm) * (lam + math.sqrt(lam * lam - 1.0))
    m_k = lam * motor.power / (motor.rated_rpm * RPM)
    return i2 * 2.0 * m_k / (s_k * motor.synchronous_rpm * RPM)


def _check_length(machine: MachineDynamics, motor: Motor, t_end: float) -> None:
    """Refuse a start-up longer than :data:`MAX_TURNS` turns at the motor's no-load speed, or than
    :data:`MAX_STIFFNESS` of the motor's time constant on the machine's inertia."""
    w0 = no_load_speed(motor)
    if not math.isfinite(w0) or not w0 > 0.0:
        raise SceneError("the motor cannot start the load: its torque table gives no driving moment at any speed; "
                         "give a torque table with positive moments (N·m) below its no-load speed", key="motor.torque")
    turns = t_end * w0 / (2.0 * math.pi)
    if turns > MAX_TURNS:
        raise SceneError(f"t_end = {t_end:g} s would turn the crank about {turns:.4g} times at the motor's no-load speed "
                         f"{w0:.4g} rad/s, beyond {MAX_TURNS} turns (a start-up settles within tens of turns, and the "
                         f"steady cycle after it is found by shooting; each turn costs ~30 ms); give t_end ≤ "
                         f"{_rounded_down(MAX_TURNS * 2.0 * math.pi / w0)} s", key="dynamics.simulate.t_end")
    th = np.concatenate([np.linspace(0.0, 2.0 * math.pi, 721), machine.inertia.edges])
    held = float(np.min(machine.inertia(th))) + machine.J
    stiff = motor_stiffness(motor)
    if not stiff > 0.0:
        return
    tau = held / stiff
    if t_end > MAX_STIFFNESS * tau:
        raise SceneError(f"the motor's moment changes by {stiff:.4g} N·m per rad/s of the crank (the ratio counts "
                         f"squared) against an inertia of {held:.4g} kg·m²: ω settles within τ = {tau:.4g} s, and "
                         f"t_end = {t_end:g} s is {t_end / tau:.4g} τ, beyond {MAX_STIFFNESS:g} τ (an explicit "
                         f"integrator steps ~2.7 τ at most: over {4.4 * MAX_STIFFNESS:.0f} evaluations); give t_end ≤ "
                         f"{_rounded_down(MAX_STIFFNESS * tau)} s, a larger flywheel, or a weaker motor or smaller "
                         "ratio", key="dynamics.simulate.t_end")


def _rounded_down(x: float) -> str:
    """``x`` to 3 significant digits, rounded toward 0 (a bound given back must be within it)."""
    if not x > 0.0:
        return "0"
    step = 10.0 ** (math.floor(math.log10(x)) - 2)
    return f"{math.floor(x / step) * step:.3g}"


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
    None when the shooting does not converge (the motor cannot keep the machine turning) or
    takes more than :data:`MAX_SHOOTING_EVALUATIONS` evaluations."""
    try:
        return _steady_cycle(machine, motor, guess, rtol)
    except _OverBudget:
        return None


def _steady_cycle(machine: MachineDynamics, motor: Motor, guess: float, rtol: float) -> Steady | None:
    """:func:`steady_cycle`'s shooting; raises :class:`_OverBudget` past its evaluations."""
    from scipy.integrate import solve_ivp
    j = machine.J
    two_pi = 2.0 * math.pi

    budget = _Budget(MAX_SHOOTING_EVALUATIONS)

    def de(th: float, e: np.ndarray) -> np.ndarray:
        budget.spend(th)
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

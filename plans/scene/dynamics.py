"""The reader of ``[dynamics]``: the machine's motion under its loads over a steady cycle
(the flywheel for an allowed coefficient of speed fluctuation δ, or the speed a given flywheel
keeps).

Imports only plans.errors and modules of plans.scene (and the standard library).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

from ..errors import SceneError
from .checks import SHOW, number

__all__ = ["Dynamics", "Motor", "Simulation", "read_dynamics", "read_period", "DRIVINGS", "MAX_DELTA", "MIN_DELTA",
           "MAX_TURNS"]

#: How the crank is driven over the steady cycle: a constant moment, or a law in the crank angle
#: (a torque as [turning] writes it: a table, harmonics or shapes).
DRIVINGS = ("constant", "law")
#: Most turns of the crank in one cycle (``period`` = 360·turns degrees; [turning]'s longest cycle).
MAX_TURNS = 10
#: Longest start-up simulated, s.
MAX_T_END = 3600.0
#: Largest coefficient of speed fluctuation δ: at δ = 2 the crank would stop (ω_min = ω_m(1 − δ/2));
#: a machine is designed for δ of 1/5 at most (pumps ~1/30, presses 1/10–1/20, generators 1/200).
MAX_DELTA = 0.5
#: Smallest δ: a thousand times tighter than the tightest machines are built for (AC generators
#: run in parallel at 1/300, aircraft engines at 1/1000). The flywheel grows as 1/δ: below this it
#: would hold a million times the energy the machine exchanges over its cycle.
MIN_DELTA = 1e-6
#: Largest inertia (kg·m²) a flywheel or rotor may have.
MAX_INERTIA = 1e20


@dataclass(frozen=True)
class Motor:
    """``[motor]``, its moment reduced to the crank through ``ratio`` i = n_motor/n_crank (the
    gears' losses neglected): either ``torque`` a table ((rpm, N·m), …) of the motor's shaft,
    speeds strictly increasing, linear between and beyond its ends; or an induction motor by
    Kloss' formula M = 2·M_k/(s/s_k + s_k/s) from ``power`` (rated, W), ``rated_rpm``,
    ``synchronous_rpm`` and ``breakdown`` λ = M_k/M_rated (s the slip, s_k = s_r(λ + √(λ² − 1)))."""

    ratio: float = 1.0
    torque: tuple[tuple[float, float], ...] = ()
    power: float | None = None
    rated_rpm: float | None = None
    synchronous_rpm: float | None = None
    breakdown: float | None = None


@dataclass(frozen=True)
class Simulation:
    """``[dynamics] simulate``: the start-up in time from rest to ``t_end`` (s)."""

    t_end: float
    start: str = "rest"


@dataclass(frozen=True)
class Dynamics:
    """``[dynamics]``: ``delta`` the allowed coefficient of speed fluctuation
    δ = (ω_max − ω_min)/ω_m (the flywheel is found for it), or ``flywheel`` a given flywheel's
    inertia J (kg·m², the δ it keeps is found); ``rotor_inertia`` (kg·m²) the motor's and gears'
    inertia reduced to the crank, always turning with it; ``driving``: "constant", the moment on
    the crank constant over the steady cycle and equal to the mean of the loads' reduced moment,
    or "law": ``torque`` (a :class:`~plans.scene.turning.Torque`, typed loosely here since that
    module imports this one's bounds; read by :func:`plans.scene.laws.read_dynamics_with_laws`:
    N·m on the crank, positive in its sense of rotation) against θ, the crank's turned angle in
    degrees from the cycle's first position; ``period`` the cycle in crank
    degrees (360·turns: 720 for a four-stroke engine; the linkage repeats every turn, the laws
    over the period); ``motor`` the ``[motor]`` and ``simulate`` its start-up (needs the motor);
    ``true_speed``: the positions' kinematics and forces at the true ω1(φ), ε1(φ) instead of the
    constant ω1."""

    delta: float | None = None
    flywheel: float | None = None
    rotor_inertia: float = 0.0
    driving: str = "constant"
    motor: Motor | None = None
    simulate: Simulation | None = None
    true_speed: bool = False
    period: float = 360.0
    torque: object | None = None


def read_period(table: Any) -> float | None:
    """``[dynamics] period`` (crank degrees of one cycle: 360·turns, 1 … :data:`MAX_TURNS` turns;
    360 by default); None without ``[dynamics]`` (``table`` None)."""
    if table is None:
        return None
    if not isinstance(table, Mapping):
        raise SceneError("[dynamics] must be a table: delta = 0.05 (the allowed coefficient of speed fluctuation)",
                         key="dynamics")
    period = number(table.get("period", 360.0), "dynamics.period", bound=360.0 * MAX_TURNS, why="°")
    turns = period / 360.0
    if not (turns == round(turns) and 1 <= turns <= MAX_TURNS):
        raise SceneError(f"period is the cycle in crank degrees, a whole number of turns: 360, 720 (a four-stroke "
                         f"engine), … up to {360 * MAX_TURNS}; got {period:g}", key="dynamics.period")
    return period


def read_dynamics(table: Any, motor: Any = None) -> Dynamics:
    """``[dynamics]``: delta or flywheel, rotor_inertia, driving, simulate; ``motor`` the
    ``[motor]`` table, if any."""
    if not isinstance(table, Mapping):
        raise SceneError("[dynamics] must be a table: delta = 0.05 (the allowed coefficient of speed fluctuation)",
                         key="dynamics")
    allowed = {"delta", "flywheel", "rotor_inertia", "driving", "simulate", "true_speed", "period"}
    extra = sorted(str(k) for k in set(table) - allowed)
    if extra:
        raise SceneError(f"unknown key {extra[0]!r}; [dynamics] has {', '.join(sorted(allowed))}",
                         key=f"dynamics.{extra[0]}")
    if ("delta" in table) == ("flywheel" in table):
        raise SceneError("give delta (the allowed coefficient of speed fluctuation, e.g. 0.05: the flywheel is found "
                         "for it) or flywheel (a given flywheel's inertia, kg·m²: the δ it keeps is found), one of "
                         "the two", key="dynamics")
    delta = flywheel = None
    if "delta" in table:
        delta = number(table["delta"], "dynamics.delta")
        if not MIN_DELTA <= delta <= MAX_DELTA:
            raise SceneError(f"delta = (ω_max − ω_min)/ω_m is a small positive fraction (e.g. 1/20 = 0.05), from "
                             f"{MIN_DELTA:g} (a thousand times tighter than the tightest machines, 1/1000: the flywheel "
                             f"grows as 1/δ) to {MAX_DELTA:g}; got {delta:g}", key="dynamics.delta")
    else:
        flywheel = number(table["flywheel"], "dynamics.flywheel", bound=MAX_INERTIA, why=" kg·m²")
        if flywheel < 0.0:
            raise SceneError(f"a flywheel's inertia is 0 or more, got {flywheel:g} kg·m²", key="dynamics.flywheel")
    rotor = number(table.get("rotor_inertia", 0.0), "dynamics.rotor_inertia", bound=MAX_INERTIA, why=" kg·m²")
    if rotor < 0.0:
        raise SceneError(f"rotor_inertia is 0 or more, got {rotor:g} kg·m²", key="dynamics.rotor_inertia")
    period = read_period(table)
    driving = table.get("driving", "constant")
    if driving != "constant":           # a law is read by plans.scene.laws, which takes it out of the table
        raise SceneError(f"driving is \"constant\" (the moment on the crank constant over the steady cycle; a [motor] "
                         f"is run by simulate) or a law in the crank angle: a table [[deg, N·m], …], harmonics or "
                         f"shapes, as [turning] writes its torque; got {SHOW.repr(driving)}", key="dynamics.driving")
    engine = read_motor(motor) if motor is not None else None
    simulate = None
    if "simulate" in table:
        simulate = _read_simulation(table["simulate"])
        if engine is None:
            raise SceneError("simulate runs the start-up under the motor's moment: add [motor]", key="dynamics.simulate")
    elif engine is not None:
        raise SceneError('[motor] drives the start-up: add simulate = { t_end = 10.0 } to [dynamics] (the steady '
                         "cycle is found with a constant driving moment)", key="motor")
    true_speed = table.get("true_speed", False)
    if not isinstance(true_speed, bool):
        raise SceneError(f"true_speed is true or false, got {SHOW.repr(true_speed)}", key="dynamics.true_speed")
    if period != 360.0:
        for key, on in (("simulate", simulate is not None), ("true_speed", true_speed)):
            if on:
                raise SceneError(f"{key} is not done yet over a cycle of {period:g}° (it takes the positions of one "
                                 f"turn, and the speed differs from turn to turn): remove {key} or give period = 360",
                                 key=f"dynamics.{key}")
    return Dynamics(delta=delta, flywheel=flywheel, rotor_inertia=rotor, driving=driving, motor=engine,
                    simulate=simulate, true_speed=true_speed, period=period)


def _read_simulation(table: Any) -> Simulation:
    if not isinstance(table, Mapping) or "t_end" not in table:
        raise SceneError('simulate is a table: { t_end = 10.0, from = "rest" } (seconds of the start-up)',
                         key="dynamics.simulate")
    extra = sorted(str(k) for k in set(table) - {"t_end", "from"})
    if extra:
        raise SceneError(f"unknown key {extra[0]!r}; simulate has t_end and from", key=f"dynamics.simulate.{extra[0]}")
    t_end = number(table["t_end"], "dynamics.simulate.t_end", bound=MAX_T_END, why=" s")
    if not t_end > 0.0:
        raise SceneError(f"t_end is the start-up's duration, more than 0 s, got {t_end:g}",
                         key="dynamics.simulate.t_end")
    start = table.get("from", "rest")
    if start != "rest":
        raise SceneError(f'from is "rest" (the start-up begins with the crank at rest at its first position); '
                         f"got {SHOW.repr(start)}", key="dynamics.simulate.from")
    return Simulation(t_end=t_end, start=start)


def read_motor(table: Any) -> Motor:
    """``[motor]``: ratio, and a torque table or power, rated_rpm, synchronous_rpm, breakdown."""
    if not isinstance(table, Mapping):
        raise SceneError("[motor] must be a table: torque = [[rpm, N·m], ...] or power, rated_rpm, synchronous_rpm, "
                         "breakdown", key="motor")
    kloss = ("power", "rated_rpm", "synchronous_rpm", "breakdown")
    allowed = {"ratio", "torque", *kloss}
    extra = sorted(str(k) for k in set(table) - allowed)
    if extra:
        raise SceneError(f"unknown key {extra[0]!r}; [motor] has {', '.join(sorted(allowed))}", key=f"motor.{extra[0]}")
    ratio = number(table.get("ratio", 1.0), "motor.ratio", bound=1e6)
    if not ratio > 0.0:
        raise SceneError(f"ratio = n_motor/n_crank is positive, got {ratio:g}", key="motor.ratio")
    has_table, has_kloss = "torque" in table, any(k in table for k in kloss)
    if has_table == has_kloss:
        raise SceneError("give the motor's torque = [[rpm, N·m], ...] or its power, rated_rpm, synchronous_rpm and "
                         "breakdown (Kloss' formula), one of the two", key="motor")
    if has_table:
        rows = table["torque"]
        if not isinstance(rows, list) or len(rows) < 2:
            raise SceneError("torque is a table of at least two [rpm, N·m] rows, speeds increasing",
                             key="motor.torque")
        pts = []
        for k, row in enumerate(rows):
            if not isinstance(row, list) or len(row) != 2:
                raise SceneError(f"torque row {k} must be [rpm, N·m], got {SHOW.repr(row)}", key="motor.torque")
            pts.append((number(row[0], f"motor.torque[{k}][0]", bound=1e7, why=" rpm"),
                        number(row[1], f"motor.torque[{k}][1]", bound=1e12, why=" N·m")))
        for k in range(1, len(pts)):
            if not pts[k][0] > pts[k - 1][0]:
                raise SceneError(f"torque's speeds must increase strictly: row {k} has {pts[k][0]:g} rpm after "
                                 f"{pts[k - 1][0]:g}", key="motor.torque")
        if pts[0][0] < 0.0:
            raise SceneError(f"torque's speeds start at 0 rpm or more, got {pts[0][0]:g}", key="motor.torque")
        _check_no_load(pts)
        return Motor(ratio=ratio, torque=tuple(pts))
    missing = [k for k in kloss if k not in table]
    if missing:
        raise SceneError(f"an induction motor by Kloss' formula needs {', '.join(kloss)}: {missing[0]} is missing",
                         key=f"motor.{missing[0]}")
    power = number(table["power"], "motor.power", bound=1e9, why=" W")
    rated = number(table["rated_rpm"], "motor.rated_rpm", bound=1e6, why=" rpm")
    sync = number(table["synchronous_rpm"], "motor.synchronous_rpm", bound=1e6, why=" rpm")
    lam = number(table["breakdown"], "motor.breakdown", bound=100.0)
    if not power > 0.0:
        raise SceneError(f"power is the rated power, more than 0 W, got {power:g}", key="motor.power")
    if not 0.0 < rated < sync:
        raise SceneError(f"rated_rpm is below synchronous_rpm (the slip is positive) and above 0: got {rated:g} "
                         f"and {sync:g}", key="motor.rated_rpm")
    if not lam > 1.0:
        raise SceneError(f"breakdown λ = M_max/M_rated is more than 1 (about 2–3), got {lam:g}", key="motor.breakdown")
    return Motor(ratio=ratio, power=power, rated_rpm=rated, synchronous_rpm=sync, breakdown=lam)


def _check_no_load(pts: list[tuple[float, float]]) -> None:
    """A torque table must fall to 0 N·m beyond its largest moment (between two rows, or on the
    line through its last two rows, as it is continued): a motor has a no-load speed. One whose
    moment keeps growing with speed would speed the crank up without end (the start-up has no
    steady state, and its ω grows exponentially)."""
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    k = max(range(len(ys)), key=lambda j: ys[j])
    if ys[k] <= 0.0:
        return                      # it never drives: the start-up refuses it (cannot start the load)
    if any(ys[j] > 0.0 >= ys[j + 1] for j in range(k, len(ys) - 1)):
        return
    if ys[-1] > 0.0 and ys[-1] < ys[-2]:
        return                      # the last rows' line comes down to 0 beyond them
    raise SceneError(f"torque must fall to 0 N·m at some speed beyond its largest moment ({ys[k]:g} N·m at "
                     f"{xs[k]:g} rpm; rows are continued by the line through the last two): a motor has a no-load "
                     "speed, and one whose moment keeps growing would speed the crank up without end; add a row "
                     "at the no-load speed, [rpm, 0.0]", key="motor.torque")

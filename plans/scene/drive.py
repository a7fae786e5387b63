"""Reader of ``[drive]``: the driving link and its law of motion (a crank or a coupler: angles
in degrees, ω rad/s, ε rad/s²; a slider or a cylinder: displacements m, v m/s, a m/s²), and
the bound on the continuation walk its values ask of the solver.

Imports only plans.errors and modules of plans.scene (and the standard library).
"""

from __future__ import annotations

from typing import Any, Mapping

from ..errors import SceneError
from .checks import COORD_WHY, link_ref, number, sketch_size
from .options import cycle_positions
from .values import (FRAME, LINEAR_STEPS_PER_SIZE, MAX_ACCELERATION, MAX_ANGLE_DEG, MAX_COORD_M, MAX_EPSILON,
                     MAX_OMEGA, MAX_POSITIONS, MAX_SPEED, MAX_WALK_STEPS, MIN_RATE, STEP_DEG, Drive, DriveKind,
                     Slider)


def read_drive(table: Mapping[str, Any], links: Mapping[str, Any], sliders: tuple[Slider, ...],
               points: Mapping[str, tuple[float, float]], cycle: Mapping[str, Any] | None = None) -> Drive:
    """``[drive]`` without the cycle keys, which come as ``cycle`` (``positions``, ``start``): with
    them the angles are the N equal steps of one revolution from the first."""
    link = link_ref(table.get("link"), "drive.link", links, "driving link")
    if link == FRAME:
        raise SceneError("the frame cannot be the driving link", key="drive.link")
    rotary_keys, linear_keys = {"angle", "omega", "epsilon"}, {"displacement", "velocity", "acceleration"}
    extra = sorted(str(k) for k in set(table) - rotary_keys - linear_keys - {"link", "along"})
    if extra:
        raise SceneError(f"unknown key {extra[0]!r}; [drive] has link, angle, omega, epsilon (a crank or a coupler; "
                         "positions, start for a crank's cycle) or link, along, displacement, velocity, acceleration "
                         "(a slider or a cylinder)", key=f"drive.{extra[0]}")
    if set(table) & rotary_keys and set(table) & linear_keys:
        raise SceneError("mixes a rotary drive (angle, omega) with a linear one (displacement, velocity)",
                         key="drive")
    linear = bool(set(table) & linear_keys)
    if not linear and "along" in table:     # along = "0" too: it would do nothing
        raise SceneError(_not_for("along", "an angle drive (a crank or a coupler: angle, omega)",
                                  "link, angle, omega, epsilon, positions, start"), key="drive.along")
    along = link_ref(table["along"], "drive.along", links, "guide link") if "along" in table else FRAME
    if along == link:
        raise SceneError("a link cannot be driven along itself; `along` names the link carrying its guide "
                         "(the cylinder of a hydraulic drive)", key="drive.along")
    if linear:
        kind, pos_key, speed_key, rate_key = DriveKind.LINEAR, "displacement", "velocity", "acceleration"
        if along != FRAME:
            kind = DriveKind.CYLINDER
        if not any(s.link == link and s.on == along for s in sliders):
            where = "on the frame" if along == FRAME else f"in link {along}"
            raise SceneError(f"a linear drive needs link {link} to slide {where}: add a [[sliders]] "
                             f'with link = "{link}", on = "{along}"', key="drive.link")
        pos_bound, pos_why = MAX_COORD_M, COORD_WHY
        bounds = ((MAX_SPEED, "m/s"), (MAX_ACCELERATION, "m/s²"))
    else:
        kind, pos_key, speed_key, rate_key = DriveKind.ROTARY, "angle", "omega", "epsilon"
        pos_bound, pos_why = MAX_ANGLE_DEG, "° (about 2800 turns; beyond that a double cannot hold the angle exactly)"
        bounds = ((MAX_OMEGA, "rad/s"), (MAX_EPSILON, "rad/s²"))
    if cycle:
        if kind != DriveKind.ROTARY:
            key = "positions" if "positions" in cycle else "start"
            raise SceneError(_not_for(key, f"a linear drive ({'a cylinder' if along != FRAME else 'a slider'}: "
                                      "displacement, velocity)", "link, along, displacement, velocity, acceleration",
                                      fix="positions = N divides one revolution of a crank; list the drive's "
                                      "values instead"), key=f"drive.{key}")
        key = "positions" if "positions" in cycle else "start"
        if not set(links[link]) & set(links[FRAME]):
            raise SceneError(f"a cycle turns a crank through one revolution, and link {link} is a coupler (no point "
                             "on the frame), whose angle need not turn fully: a cycle needs a crank (a drive that "
                             f"turns fully); list the coupler's angles instead of {key}", key=f"drive.{key}")
        count = cycle_positions(cycle)
        if isinstance(table.get(pos_key), list):
            raise SceneError("positions = N gives N equal steps from one first angle; give angle as one number "
                             "(the first position), not a list, or leave positions out", key="drive.angle")
        if cycle.get("start") == "extreme":
            if pos_key in table:
                raise SceneError('start = "extreme" finds the first position itself (the output link\'s '
                                 'extreme); remove angle, or remove start to begin at angle', key="drive.angle")
            table = dict(table, angle=0.0)      # placeholder steps: the kinematics finds the start
        elif pos_key not in table:
            raise SceneError('missing angle: the first of the positions (or start = "extreme")', key="drive.angle")
        first = number(table[pos_key], "drive.angle", bound=MAX_ANGLE_DEG, why="°")
        table = dict(table, angle=[first + 360.0 * k / count for k in range(count)])
    if pos_key not in table:
        raise SceneError(f"missing {pos_key}", key=f"drive.{pos_key}")
    raw = table[pos_key]
    raw_list = raw if isinstance(raw, list) else [raw]
    if not raw_list:
        raise SceneError(f"{pos_key} list is empty; give at least one value", key=f"drive.{pos_key}")
    if len(raw_list) > MAX_POSITIONS:
        raise SceneError(f"{pos_key} lists {len(raw_list)} positions; at most {MAX_POSITIONS} (each position "
                         "writes up to five sheets)", key=f"drive.{pos_key}")
    values = tuple(number(v, f"drive.{pos_key}", bound=pos_bound, why=pos_why) for v in raw_list)
    if len(set(values)) != len(values):
        raise SceneError(f"{pos_key} list repeats a value", key=f"drive.{pos_key}")
    _walk(kind, values, points, f"drive.{pos_key}")
    if speed_key not in table:
        raise SceneError(f"missing {speed_key}", key=f"drive.{speed_key}")
    speed, rate = (_rate(table.get(k, 0.0), f"drive.{k}", bound, unit)
                   for k, (bound, unit) in zip((speed_key, rate_key), bounds))
    for k, x, unit, when in ((speed_key, speed, bounds[0][1], ""),
                             (rate_key, rate if speed == 0.0 else 0.0, bounds[1][1], f" while {speed_key} = 0")):
        if 0.0 < abs(x) < MIN_RATE:
            raise SceneError(f"{x:g} {unit}{when} is too small to compute with: give 0 (at rest) or at least "
                             f"{MIN_RATE:g} {unit} in magnitude", key=f"drive.{k}")
    return Drive(link=link, kind=kind, values=values, speed=speed, rate=rate, along=along)


def check_train_speed(omega: float, epsilon: float, key: str, per_input: float | None = None) -> None:
    """Refuse the crank's ω (rad/s) that a gear train gives it where a written ``omega`` would be
    refused: |ω| ≤ MAX_OMEGA, and 0 or |ω| ≥ MIN_RATE (then ε too, rad/s²). ``key`` names the
    train's input (``gears.input.a``); ``per_input``, ω per rpm of that input when it is the only
    one, turns the bounds into the input speeds that meet them."""
    def rpm(sign: str, bound: float) -> str:
        return f": |{key.rsplit('.', 1)[-1]}| {sign} {bound / abs(per_input):.4g} rpm here" if per_input else ""
    if abs(omega) > MAX_OMEGA:
        raise SceneError(f"the gear train turns the crank at ω = {omega:.4g} rad/s, out of range: "
                         f"|ω| ≤ {MAX_OMEGA:g} rad/s, as for a written omega (beyond any machine; keeps velocities "
                         f"and accelerations far from overflow); give an input speed that turns it no faster"
                         f"{rpm('≤', MAX_OMEGA)}", key=key)
    if 0.0 < abs(omega) < MIN_RATE:
        raise SceneError(f"the gear train turns the crank at ω = {omega:.4g} rad/s, too slow to compute with, as for "
                         f"a written omega: give an input speed of 0 (at rest) or one that turns it at least "
                         f"{MIN_RATE:g} rad/s in magnitude{rpm('≥', MIN_RATE)}", key=key)
    if omega == 0.0 and 0.0 < abs(epsilon) < MIN_RATE:
        raise SceneError(f"{epsilon:g} rad/s² while the gear train holds the crank at rest is too small to compute "
                         f"with: give 0 or at least {MIN_RATE:g} rad/s² in magnitude", key="drive.epsilon")


def _not_for(key: str, kind: str, keys: str, fix: str = "remove it") -> str:
    """The words refusing a [drive] key that means nothing for this kind of drive, as an unknown
    key is refused: the key, the drive's kind and the keys that apply to it."""
    return f"{key} does not apply to {kind}, whose [drive] keys are {keys}: {fix}"


def _rate(value: Any, key: str, bound: float, unit: str) -> float:
    """The drive's speed or acceleration, within ``bound`` in magnitude (0: at rest)."""
    return number(value, key, bound=bound, why=f" {unit} (beyond any machine; keeps velocities and accelerations "
                                               "far from overflow)")


def _walk(kind: DriveKind, values: tuple[float, ...], points: Mapping[str, tuple[float, float]], key: str) -> None:
    """Refuse drive values whose continuation walk from the sketch would take more than
    MAX_WALK_STEPS steps (kinematics/walk.py ``walk_to``: a crank's walk starts within half a turn
    of the values' median and steps 1°; a slider's starts at 0 and steps size/200)."""
    lo, hi = min(values), max(values)
    if kind.angular:
        step, unit = STEP_DEG, "°"
        steps = (hi - lo + 360.0) / step
    else:
        size = sketch_size(points) or 1.0
        step, unit = size / LINEAR_STEPS_PER_SIZE, " m"
        steps = (max(hi, 0.0) - min(lo, 0.0)) / step
    if steps > MAX_WALK_STEPS:
        reach = (MAX_WALK_STEPS - (360.0 if kind.angular else 0.0)) * step
        raise SceneError(f"values from {lo:g} to {hi:g}{unit} need a walk of {steps:.3g} steps of {step:.3g}{unit} "
                         f"from the sketch (the solver follows the mechanism step by step); keep them within a span of "
                         f"{reach:.4g}{unit}" + ("" if kind.angular else " including 0 (the sketch)"), key=key)

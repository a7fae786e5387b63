"""Flywheel problems as textbooks pose them, with no linkage: ``[turning]`` (a machine given by its
crank torque over one cycle against a resisting torque, at a mean speed), ``[operation]`` (a
punching or riveting machine: an operation's energy taken in a short time, a motor working all
the time) and ``[flywheel]`` (its radius of gyration, its mass, its rim).

Torques are written as a table ([deg, N·m] rows, linear between), harmonics
(``{ mean = T0, harmonics = [[A, k, φ°], …] }``: T0 + Σ A·sin(kθ + φ)), shapes (``{ shapes = [{
kind = "semicircle" | "triangle" | "rectangle", from, to, peak, at }] }``, their sum, 0 outside
them), a number (constant) or ``"mean"`` (constant, the other torque's mean).

Imports only plans.errors and plans.scene.checks (and the standard library).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

from ..errors import SceneError
from .checks import SHOW, is_number, number, read_own_draw
from .dynamics import MAX_DELTA, MAX_INERTIA, MIN_DELTA

__all__ = ["Shape", "Torque", "TurningSpec", "RimSpec", "FlywheelSpec", "OperationSpec", "read_turning",
           "read_flywheel", "read_operation", "SHAPES", "MAX_PERIOD"]

#: The shapes a torque may be built of.
SHAPES = ("semicircle", "triangle", "rectangle")
#: Longest cycle, crank degrees (ten turns: textbook machines repeat within three).
MAX_PERIOD = 3600.0
#: Largest |torque| (N·m), energy (J), power (W): far beyond any machine.
MAX_TORQUE = 1e12
#: Largest speed, rpm (and its ω in rad/s).
MAX_RPM = 1e6
#: Smallest mean speed ω (rad/s) and rim or flywheel speed (m/s), as a linkage drive's MIN_RATE:
#: one turn in 200 years. Slower, ω² underflows and J = ΔE/(ω²·δ) is no longer a double.
MIN_OMEGA, MIN_SPEED = 1e-9, 1e-9
#: Smallest radius of gyration (m), as a sketch's MIN_SIZE_M: J = m·k² and m = J/k² stay doubles.
MIN_RADIUS = 1e-6
#: Most repeats of a [turning] harmonic over the cycle (k·period/360): the -turning sheet draws
#: each of its lobes on a 250 mm axis, chords fine enough for plans check to measure its areas.
MAX_REPEATS = 100
#: Most rows of a torque table, harmonics, shapes, and angles in ``at``.
MAX_ROWS = 10000
#: A harmonic's order k must make k·period/360 a whole number within this.
ORDER_TOL = 1e-9
#: Largest density (kg/m³; osmium is 22 600), stress (Pa), time (s), rim speed (m/s).
MAX_DENSITY, MAX_STRESS, MAX_TIME, MAX_SPEED = 1e5, 1e10, 1e6, 1e4


@dataclass(frozen=True)
class Shape:
    """One shape of a torque diagram: ``kind`` "semicircle" (p·√(1 − u²), u from −1 at ``start``
    to 1 at ``end``: a semicircle drawn to its scales), "triangle" (0 at both ends, ``peak`` at
    ``apex``) or "rectangle" (``peak`` from ``start`` up to ``end``); angles in degrees, N·m."""

    kind: str
    start: float
    end: float
    peak: float
    apex: float | None = None


@dataclass(frozen=True)
class Torque:
    """A torque over the cycle: ``table`` ((deg, N·m), …) linear between its rows, or ``mean`` T0
    plus ``harmonics`` ((A N·m, k, φ°), …) T0 + Σ A·sin(kθ + φ), or ``shapes`` (their sum), or
    ``mean`` alone (a constant); ``other_mean``: constant, the other torque's mean ("mean")."""

    table: tuple[tuple[float, float], ...] = ()
    mean: float = 0.0
    harmonics: tuple[tuple[float, float, float], ...] = ()
    shapes: tuple[Shape, ...] = ()
    other_mean: bool = False

    @property
    def constant(self) -> bool:
        """Whether the torque is the same all over the cycle."""
        return not (self.table or self.harmonics or self.shapes)


@dataclass(frozen=True)
class TurningSpec:
    """``[turning]``: ``period`` (crank degrees of one cycle), the mean speed ``omega`` (rad/s),
    ``delta`` δ (the flywheel is found for it) or ``inertia`` J (kg·m², δ is found), the driving
    ``torque`` and the ``resisting`` torque, and ``at`` ((as written, deg), …) where the
    flywheel's angular acceleration is asked."""

    omega: float
    torque: Torque
    resisting: Torque
    period: float = 360.0
    delta: float | None = None
    inertia: float | None = None
    at: tuple[tuple[str, float], ...] = ()

    @property
    def rpm(self) -> float:
        return self.omega * 30.0 / math.pi


@dataclass(frozen=True)
class RimSpec:
    """``[flywheel] rim``: ``density`` ρ (kg/m³), the allowed hoop ``stress`` σ (Pa: v = √(σ/ρ))
    or the mean ``diameter`` D (m), ``width_to_thickness`` b/t of its rectangular section, and
    ``share`` the part of J the rim carries (1: the whole; 0.95 when hub and arms give 5 %)."""

    density: float
    width_to_thickness: float
    stress: float | None = None
    diameter: float | None = None
    share: float = 1.0


@dataclass(frozen=True)
class FlywheelSpec:
    """``[flywheel]``: ``radius`` of gyration k (m), ``mass`` m (kg: with k, J = m·k² is known),
    ``rim``."""

    radius: float | None = None
    mass: float | None = None
    rim: RimSpec | None = None

    @property
    def inertia(self) -> float | None:
        """J = m·k² (kg·m²) when both are given."""
        return None if self.mass is None or self.radius is None else self.mass * self.radius ** 2


@dataclass(frozen=True)
class OperationSpec:
    """``[operation]``: ``energy`` E (J) one operation takes in ``duration`` t (s), the motor's
    ``power`` P (W) and/or ``every`` (s between operations), and the flywheel's speed: its speed
    ``rpm_before`` the operation with ``rpm_after`` (J is found) or without (J from [flywheel]);
    or the mean ``rpm`` with ``delta``; or the mean ``speed`` (m/s at the radius of gyration)
    with ``delta`` (the mass is found: m = ΔE/(v²δ))."""

    energy: float
    duration: float
    power: float | None = None
    every: float | None = None
    rpm_before: float | None = None
    rpm_after: float | None = None
    rpm: float | None = None
    delta: float | None = None
    speed: float | None = None


def _keys(table: Any, key: str, allowed: set[str], example: str) -> Mapping[str, Any]:
    """``table`` (at ``key``: "turning", "turning.torque.shapes[0]") when a table of ``allowed`` keys."""
    name = f"[{key}]" if "." not in key else key
    if not isinstance(table, Mapping):
        raise SceneError(f"{name} must be a table: {example}", key=key)
    extra = sorted(str(k) for k in set(table) - allowed)
    if extra:
        raise SceneError(f"unknown key {extra[0]!r}; {name} has {', '.join(sorted(allowed))}", key=f"{key}.{extra[0]}")
    return table


def _positive(value: Any, key: str, bound: float, unit: str, least: float = 0.0) -> float:
    """A finite number more than 0 (at least ``least`` when given) and at most ``bound`` (in ``unit``)."""
    unit = unit if unit in ("", "°") else f" {unit}"
    x = number(value, key, bound=bound, why=unit)
    if not x > 0.0:
        raise SceneError(f"must be more than 0{unit}, got {x:g}", key=key)
    if x < least:
        raise SceneError(f"{x:g}{unit} is below the least {least:g}{unit} taken (the flywheel's J, mass and speed "
                         "would leave the range of a double)", key=key)
    return x


def _delta(value: Any, key: str) -> float:
    d = number(value, key)
    if not MIN_DELTA <= d <= MAX_DELTA:
        raise SceneError(f"delta = (ω_max − ω_min)/ω_m is a small positive fraction (e.g. 0.02 for ±1 %), from "
                         f"{MIN_DELTA:g} to {MAX_DELTA:g}; got {d:g}", key=key)
    return d


def _rows(value: Any, key: str, width: int, what: str) -> list[list[Any]]:
    if not isinstance(value, list) or not value or len(value) > MAX_ROWS:
        raise SceneError(f"{what} is a list of 1 … {MAX_ROWS} rows, got {SHOW.repr(value)}", key=key)
    for k, row in enumerate(value):
        if not isinstance(row, list) or len(row) != width:
            raise SceneError(f"row {k} of {what} must be {width} numbers, got {SHOW.repr(row)}", key=key)
    return value


def _angle(value: Any, key: str, period: float) -> float:
    x = number(value, key, bound=MAX_PERIOD, why="°")
    if not 0.0 <= x <= period:
        raise SceneError(f"{x:g}° is outside the cycle: angles run from 0 to the period, {period:g}°", key=key)
    return x


def read_torque(value: Any, key: str, period: float) -> Torque:
    """A torque (see :class:`Torque`) over a cycle of ``period`` degrees."""
    if value == "mean":
        return Torque(other_mean=True)
    if is_number(value):
        return Torque(mean=number(value, key, bound=MAX_TORQUE, why=" N·m"))
    if isinstance(value, list):
        rows = _rows(value, key, 2, "a torque table [deg, N·m]")
        pts = [(number(r[0], f"{key}[{k}][0]", bound=MAX_PERIOD, why="°"),
                number(r[1], f"{key}[{k}][1]", bound=MAX_TORQUE, why=" N·m")) for k, r in enumerate(rows)]
        if len(pts) < 2 or pts[0][0] != 0.0 or pts[-1][0] != period:
            raise SceneError(f"a torque table spans exactly one cycle: its first angle 0°, its last the period "
                             f"{period:g}°; got {pts[0][0]:g}° … {pts[-1][0]:g}°", key=key)
        bad = next((k for k in range(1, len(pts)) if not pts[k][0] > pts[k - 1][0]), None)
        if bad is not None:
            raise SceneError(f"a torque table's angles increase: row {bad} has {pts[bad][0]:g}° after "
                             f"{pts[bad - 1][0]:g}°", key=key)
        return Torque(table=tuple(pts))
    if isinstance(value, Mapping) and "shapes" in value:
        _keys(value, key, {"shapes"}, "{ shapes = [...] }")
        shapes = value["shapes"]
        if not isinstance(shapes, list) or not shapes or len(shapes) > MAX_ROWS:
            raise SceneError("shapes is a list of tables { kind, from, to, peak }", key=f"{key}.shapes")
        return Torque(shapes=tuple(_shape(s, f"{key}.shapes[{k}]", period) for k, s in enumerate(shapes)))
    if isinstance(value, Mapping) and ("mean" in value or "harmonics" in value):
        _keys(value, key, {"mean", "harmonics"}, "{ mean = 5000, harmonics = [[1500, 3, 0]] }")
        mean = number(value.get("mean", 0.0), f"{key}.mean", bound=MAX_TORQUE, why=" N·m")
        if "harmonics" not in value:
            return Torque(mean=mean)
        terms = []
        for k, r in enumerate(_rows(value["harmonics"], f"{key}.harmonics", 3, "harmonics [A N·m, k, φ°]")):
            at = f"{key}.harmonics[{k}]"
            amp = number(r[0], at, bound=MAX_TORQUE, why=" N·m")
            order = _positive(r[1], at, 1e4, "")
            turns = order * period / 360.0
            if round(turns) < 1 or abs(turns - round(turns)) > ORDER_TOL * max(1.0, turns):
                raise SceneError(f"A·sin(kθ + φ) with k = {order:g} does not repeat over the period {period:g}°: "
                                 "k·period/360 must be a whole number", key=at)
            terms.append((amp, order, number(r[2], at, bound=1e6, why="°")))
        return Torque(mean=mean, harmonics=tuple(terms))
    raise SceneError("a torque is a table [[deg, N·m], …], { mean = T0, harmonics = [[A, k, φ], …] }, "
                     f"{{ shapes = [...] }}, a number or \"mean\"; got {SHOW.repr(value)}", key=key)


def _shape(value: Any, key: str, period: float) -> Shape:
    t = _keys(value, key, {"kind", "from", "to", "peak", "at"}, '{ kind = "triangle", from = 0, to = 180, peak = 5000 }')
    kind = t.get("kind")
    if kind not in SHAPES:
        raise SceneError(f"kind is {', '.join(repr(s) for s in SHAPES)}; got {SHOW.repr(kind)}", key=f"{key}.kind")
    missing = next((k for k in ("from", "to", "peak") if k not in t), None)
    if missing:
        raise SceneError(f"a {kind} needs from, to (deg) and peak (N·m): {missing} is missing", key=f"{key}.{missing}")
    start, end = _angle(t["from"], f"{key}.from", period), _angle(t["to"], f"{key}.to", period)
    if not end > start:
        raise SceneError(f"a shape runs from a smaller angle to a larger: from = {start:g}°, to = {end:g}°",
                         key=f"{key}.to")
    peak = number(t["peak"], f"{key}.peak", bound=MAX_TORQUE, why=" N·m")
    apex = None
    if "at" in t:
        if kind != "triangle":
            raise SceneError(f"at places a triangle's apex; a {kind} has none (remove at)", key=f"{key}.at")
        apex = number(t["at"], f"{key}.at", bound=MAX_PERIOD, why="°")
        if not start <= apex <= end:
            raise SceneError(f"the apex at {apex:g}° is outside the triangle, {start:g}° … {end:g}°", key=f"{key}.at")
    elif kind == "triangle":
        apex = 0.5 * (start + end)
    return Shape(kind=kind, start=start, end=end, peak=peak, apex=apex)


def _speed(table: Mapping[str, Any], name: str) -> float:
    """ω (rad/s) from ``rpm`` or ``omega``, one of the two."""
    if ("rpm" in table) == ("omega" in table):
        raise SceneError("give the mean speed: rpm (rev/min) or omega (rad/s), one of the two", key=name)
    if "rpm" in table:
        return _positive(table["rpm"], f"{name}.rpm", MAX_RPM, "rpm", MIN_OMEGA * 30.0 / math.pi) * math.pi / 30.0
    return _positive(table["omega"], f"{name}.omega", MAX_RPM * math.pi / 30.0, "rad/s", MIN_OMEGA)


def read_turning(table: Any, flywheel: FlywheelSpec | None) -> TurningSpec:
    """``[turning]`` (see :class:`TurningSpec`) and its use of ``[flywheel]``."""
    t = _keys(table, "turning", {"period", "rpm", "omega", "delta", "inertia", "torque", "resisting", "at"},
              "period = 360, rpm = 300, delta = 0.02, torque = [[0, 0], [180, 5000], [360, 0]]")
    period = _positive(t.get("period", 360.0), "turning.period", MAX_PERIOD, "°")
    omega = _speed(t, "turning")
    sources = [k for k in ("delta", "inertia") if k in t]
    if flywheel is not None and flywheel.mass is not None:
        sources.append("flywheel.mass")
    if len(sources) > 1:
        raise SceneError(f"{sources[0]} and {sources[1]} both fix the flywheel: give delta (J is found), inertia, or "
                         "[flywheel] mass with radius (δ is found), one of them",
                         key=sources[1] if "." in sources[1] else f"turning.{sources[1]}")
    delta = _delta(t["delta"], "turning.delta") if "delta" in t else None
    inertia = None
    if "inertia" in t:
        inertia = _positive(t["inertia"], "turning.inertia", MAX_INERTIA, "kg·m²")
    elif flywheel is not None and flywheel.inertia is not None:
        inertia = flywheel.inertia
    if "torque" not in t:
        raise SceneError("[turning] needs the crank torque over the cycle: torque = [[0, 0], [90, 5000], "
                         "[180, 0], …] (deg, N·m)", key="turning.torque")
    torque = read_torque(t["torque"], "turning.torque", period)
    resisting = read_torque(t.get("resisting", "mean"), "turning.resisting", period)
    if torque.other_mean and resisting.other_mean:
        raise SceneError('torque and resisting cannot both be "mean": give one of them over the cycle',
                         key="turning.resisting")
    for which, law in (("torque", torque), ("resisting", resisting)):
        j = next((j for j, (_, k, _) in enumerate(law.harmonics) if k * period / 360.0 > MAX_REPEATS), None)
        if j is not None:
            k = law.harmonics[j][1]
            raise SceneError(f"A·sin(kθ + φ) with k = {k:g} repeats {k * period / 360.0:g} times over the period, "
                             f"beyond the {MAX_REPEATS} the turning-moment diagram draws",
                             key=f"turning.{which}.harmonics[{j}]")
    if torque.constant and resisting.constant:
        raise SceneError("neither torque varies over the cycle: nothing fluctuates and no flywheel is needed; "
                         "give the torque (or the resisting torque) over the cycle", key="turning.torque")
    at = []
    if "at" in t:
        if delta is None and inertia is None:
            raise SceneError("the flywheel's acceleration (T − T_res)/J needs J: give delta, inertia, or [flywheel] "
                             "mass and radius", key="turning.at")
        raw = t["at"]
        if not isinstance(raw, list) or not raw or len(raw) > MAX_ROWS:
            raise SceneError(f"at is a list of crank angles (deg), e.g. [45.0]; got {SHOW.repr(raw)}", key="turning.at")
        for k, a in enumerate(raw):
            x = _angle(a, f"turning.at[{k}]", period)
            label = repr(float(a)) if isinstance(a, float) else str(int(a))
            if any(label == seen for seen, _ in at):
                raise SceneError(f"at lists {label} twice", key=f"turning.at[{k}]")
            at.append((label, x))
    if flywheel is not None and flywheel.rim is not None and delta is None and inertia is None:
        raise SceneError("the rim carries the flywheel's J: give delta, inertia, or [flywheel] mass and radius",
                         key="flywheel.rim")
    return TurningSpec(omega=omega, torque=torque, resisting=resisting, period=period, delta=delta,
                       inertia=inertia, at=tuple(at))


def read_flywheel(table: Any) -> FlywheelSpec:
    """``[flywheel]``: radius, mass, rim."""
    t = _keys(table, "flywheel", {"radius", "mass", "rim"}, "radius = 0.6 (m, the radius of gyration)")
    radius = _positive(t["radius"], "flywheel.radius", 1e3, "m", MIN_RADIUS) if "radius" in t else None
    mass = _positive(t["mass"], "flywheel.mass", MAX_INERTIA, "kg") if "mass" in t else None
    if mass is not None and radius is None:
        raise SceneError("a mass gives J = m·k² with the radius of gyration: add radius (m)", key="flywheel.mass")
    rim = None
    if "rim" in t:
        r = _keys(t["rim"], "flywheel.rim", {"density", "stress", "diameter", "width_to_thickness", "share"},
                  "{ density = 7200, stress = 6e6, width_to_thickness = 2.0 }")
        if "density" not in r:
            raise SceneError("the rim needs density (kg/m³, 7200 for cast iron): its section is m/(ρ·π·D)"
                             + (" and its speed √(σ/ρ)" if "stress" in r else ""), key="flywheel.rim.density")
        if ("stress" in r) == ("diameter" in r):
            raise SceneError("give the rim's allowed hoop stress (Pa: its speed is √(σ/ρ)) or its mean diameter "
                             "(m), one of the two", key="flywheel.rim")
        if "width_to_thickness" not in r:
            raise SceneError("give the rim's width_to_thickness b/t (2.0: twice as wide as thick)",
                             key="flywheel.rim.width_to_thickness")
        share = number(r.get("share", 1.0), "flywheel.rim.share")
        if not 0.0 < share <= 1.0:
            raise SceneError(f"share is the part of J the rim carries, more than 0 and at most 1; got {share:g}",
                             key="flywheel.rim.share")
        rim = RimSpec(density=_positive(r["density"], "flywheel.rim.density", MAX_DENSITY, "kg/m³"),
                      width_to_thickness=_positive(r["width_to_thickness"], "flywheel.rim.width_to_thickness",
                                                   1e3, ""),
                      stress=_positive(r["stress"], "flywheel.rim.stress", MAX_STRESS, "Pa") if "stress" in r
                      else None,
                      diameter=_positive(r["diameter"], "flywheel.rim.diameter", 1e3, "m") if "diameter" in r
                      else None, share=share)
    return FlywheelSpec(radius=radius, mass=mass, rim=rim)


def read_operation(table: Any, flywheel: FlywheelSpec | None) -> OperationSpec:
    """``[operation]`` (see :class:`OperationSpec`) and its use of ``[flywheel]``."""
    keys = {"energy", "duration", "power", "every", "rpm_before", "rpm_after", "rpm", "delta", "speed"}
    t = _keys(table, "operation", keys, "energy = 10000.0, duration = 1.0, power = 3000.0, rpm_before = 300.0")
    for k in ("energy", "duration"):
        if k not in t:
            raise SceneError(f"[operation] needs energy (J, one operation) and duration (s it lasts): {k} is missing",
                             key=f"operation.{k}")
    energy = _positive(t["energy"], "operation.energy", MAX_TORQUE, "J")
    duration = _positive(t["duration"], "operation.duration", MAX_TIME, "s")
    if "power" not in t and "every" not in t:
        raise SceneError("give the motor's power (W) or every (s from one operation to the next: the motor works "
                         "all the time, P = E/every)", key="operation")
    power = _positive(t["power"], "operation.power", MAX_TORQUE, "W") if "power" in t else None
    every = _positive(t["every"], "operation.every", MAX_TIME, "s") if "every" in t else None
    if every is not None and duration > every:
        raise SceneError(f"an operation of {duration:g} s cannot come every {every:g} s: the next would begin before it "
                         "ends", key="operation.duration")
    if power is not None and every is not None and power * every < energy:
        raise SceneError(f"the motor cannot supply the energy over the cycle: {power:g} W × {every:g} s = "
                         f"{power * every:g} J < {energy:g} J per operation; a larger power or fewer operations",
                         key="operation.power")
    motor = (power if power is not None else energy / every) * duration
    if motor >= energy:
        raise SceneError(f"the motor alone gives {motor:g} J while the operation lasts, at least its {energy:g} J: "
                         "the flywheel gives nothing and none is needed", key="operation.duration")
    case = {k for k in ("rpm_before", "rpm_after", "rpm", "delta", "speed") if k in t}
    known = flywheel is not None and flywheel.inertia is not None
    ways = ({"rpm_before", "rpm_after"}, {"rpm_before"}, {"rpm", "delta"}, {"speed", "delta"})
    if case not in ways:
        raise SceneError("give the flywheel's speed: rpm_before with rpm_after (its mass is found), rpm_before alone "
                         "([flywheel] mass and radius given: rpm_after is found), rpm with delta, or speed (m/s at "
                         f"its radius of gyration) with delta; got {', '.join(sorted(case)) or 'none'}",
                         key="operation")
    out = {k: _positive(t[k], f"operation.{k}", MAX_RPM, "rpm", MIN_OMEGA * 30.0 / math.pi)
           for k in ("rpm_before", "rpm_after", "rpm") if k in t}
    if "speed" in t:
        out["speed"] = _positive(t["speed"], "operation.speed", MAX_SPEED, "m/s", MIN_SPEED)
    if "delta" in t:
        out["delta"] = _delta(t["delta"], "operation.delta")
    if case == {"rpm_before"} and not known:
        raise SceneError("with rpm_before alone the flywheel is given: add [flywheel] mass and radius (J = m·k²), or "
                         "rpm_after (then its mass is found)", key="operation.rpm_before")
    if case != {"rpm_before"} and flywheel is not None and flywheel.mass is not None:
        raise SceneError("the flywheel's mass is what this operation finds; remove [flywheel] mass (or give "
                         "rpm_before alone, and rpm_after is found)", key="flywheel.mass")
    if case in ({"rpm_before", "rpm_after"}, {"rpm", "delta"}) and (flywheel is None or flywheel.radius is None):
        raise SceneError("the mass is J/k²: add [flywheel] radius (m, the radius of gyration)", key="flywheel.radius")
    if case == {"rpm_before", "rpm_after"} and not out["rpm_after"] < out["rpm_before"]:
        raise SceneError(f"the flywheel gives energy and slows down: rpm_after < rpm_before, got {out['rpm_after']:g} "
                         f"after {out['rpm_before']:g}", key="operation.rpm_after")
    return OperationSpec(energy=energy, duration=duration, power=power, every=every, **out)


#: The tables of a flywheel problem alone (no [points], [links], [drive]).
FLYWHEEL_KEYS = {"title", "description", "plans", "turning", "flywheel", "operation"}
#: What a flywheel problem may draw (by default nothing: the JSON report alone).
FLYWHEEL_SHEETS = ("turning",)


def read_flywheel_scene(data: Mapping[str, Any]) -> tuple[TurningSpec | None, FlywheelSpec | None,
                                                          OperationSpec | None, tuple[str, ...]]:
    """The tables of a flywheel problem alone: ``[turning]``, ``[flywheel]``, ``[operation]`` and
    ``[plans] draw`` (``"turning"`` or nothing); a linkage beside them is refused."""
    own = [k for k in ("turning", "operation", "flywheel") if k in data]
    linkage = [k for k in ("points", "links", "drive") if k in data]
    if linkage:
        raise SceneError(f"[{own[0]}] is a flywheel problem without a linkage; a linkage's flywheel is found from its "
                         f"loads by [dynamics] (delta or flywheel): remove [{own[0]}] or [{linkage[0]}]", key=own[0])
    extra = sorted(str(k) for k in set(data) - FLYWHEEL_KEYS)
    if extra:
        raise SceneError(f"[{extra[0]}] has no place in a flywheel problem without a linkage, which has "
                         f"{', '.join(sorted(FLYWHEEL_KEYS))}", key=extra[0])
    if "turning" not in data and "operation" not in data:
        raise SceneError("[flywheel] belongs to [turning] (a crank torque over a cycle) or [operation] (punching, "
                         "riveting): add one of them", key="flywheel")
    flywheel = read_flywheel(data["flywheel"]) if "flywheel" in data else None
    if flywheel is not None and flywheel.rim is not None and "turning" not in data:
        raise SceneError("the rim is sized for the mean speed of a [turning] cycle: add [turning] or remove rim",
                         key="flywheel.rim")
    turning = read_turning(data["turning"], flywheel) if "turning" in data else None
    operation = read_operation(data["operation"], flywheel) if "operation" in data else None
    draw = read_own_draw(data, FLYWHEEL_SHEETS, "a flywheel problem")
    if draw and turning is None:
        raise SceneError('"turning" draws the turning-moment diagram of [turning]; add it or remove "turning" from '
                         "draw", key="plans.draw")
    return turning, flywheel, operation, tuple(dict.fromkeys(draw))

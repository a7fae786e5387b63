"""The reader of ``[rotor]``: masses rotating with a shaft, each at a radius and an angle in a
plane along the shaft, and the planes (one or two) and radii of the masses that balance them
(one plane: static balance; two planes: dynamic balance); optionally the shaft's speed.

A scene with ``[rotor]`` is a rotor alone: title, description, ``[plans] draw`` (``[]``, the
report alone, or ``["balancing"]``) and nothing of a linkage or a gear train.

Imports only plans.errors and plans.scene.checks (and the standard library).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

from ..errors import SceneError
from .checks import SHOW, number, read_own_draw

__all__ = ["RotorMass", "RotorSpec", "read_rotor", "read_rotor_scene", "ROTOR_KEYS", "ROTOR_SHEETS",
           "MAX_ROTOR_MASSES", "MIN_PLANE_GAP"]

#: The top-level keys of a scene of a rotor alone.
ROTOR_KEYS = {"title", "description", "plans", "rotor"}
#: What a scene of a rotor alone may draw: the force and couple polygons of its balancing.
ROTOR_SHEETS = ("balancing",)
_KEYS = {"masses", "balance", "rpm"}
_MASS_KEYS = {"mass", "radius", "angle", "plane"}
_BALANCE_KEYS = {"planes", "radius"}
#: Most masses on one rotor: each is a side of the force and the couple polygon drawn on one sheet.
MAX_ROTOR_MASSES = 100
#: Largest mass (kg), as MAX_LOAD of a linkage.
MAX_MASS = 1e20
#: Largest radius and |plane| (m), as MAX_COORD_M of a sketch: m·r·l ≤ 1e60 stays an ordinary double.
MAX_LENGTH = 1e20
#: Largest |angle| of a mass (degrees), as MAX_ANGLE_DEG of a drive.
MAX_ANGLE = 1e6
#: Largest shaft speed, rpm (ω ≈ 1e5 rad/s: ω²·m·r stays far from overflow).
MAX_RPM = 1e6
#: Two balancing planes closer than this fraction of the rotor's length (the span of every plane,
#: the masses' and the balancing ones) are at one place: the couple would ask a mass that grows
#: as 1/gap; 1e-6 is as MIN_LENGTH_RATIO of a linkage.
MIN_PLANE_GAP = 1e-6


@dataclass(frozen=True)
class RotorMass:
    """One rotating mass (``[rotor] masses[i]``): ``mass`` (kg, ≥ 0), ``radius`` of its centre
    from the axis (m, > 0), ``angle`` (degrees, counter-clockwise from the reference angle 0, as
    given) and ``plane``, its place along the shaft (m; None when not given, allowed only with one
    balancing plane: the mass is then in that plane). ``index`` is its place in the list."""

    mass: float
    radius: float
    angle: float
    plane: float | None
    index: int

    @property
    def key(self) -> str:
        return f"rotor.masses[{self.index}]"


@dataclass(frozen=True)
class RotorSpec:
    """``[rotor]``: the ``masses`` and the balancing ``planes`` (m along the shaft, as given; the
    first is the reference plane) with their ``radii`` (m), one per plane; ``rpm`` the shaft's
    speed (None: not given, then no forces are reported)."""

    masses: tuple[RotorMass, ...]
    planes: tuple[float, ...]
    radii: tuple[float, ...]
    rpm: float | None = None

    @property
    def dynamic(self) -> bool:
        """Whether the rotor is balanced in two planes (forces and couples), not in one (forces)."""
        return len(self.planes) == 2


def _extra(table: Mapping, allowed: set[str], key: str, what: str) -> None:
    extra = sorted(str(k) for k in set(table) - allowed)
    if extra:
        raise SceneError(f"unknown key {extra[0]!r}; {what} has {', '.join(sorted(allowed))}",
                         key=f"{key}.{extra[0]}")


def _mass(value: Any, index: int) -> RotorMass:
    key = f"rotor.masses[{index}]"
    if not isinstance(value, Mapping):
        raise SceneError(f"a mass is a table {{ mass = 200.0, radius = 0.2, angle = 0.0, plane = 0.0 }}, got "
                         f"{SHOW.repr(value)}", key=key)
    _extra(value, _MASS_KEYS, key, "a rotating mass")
    missing = [k for k in ("mass", "radius", "angle") if k not in value]
    if missing:
        raise SceneError(f"a rotating mass has mass (kg), radius (m) and angle (degrees): {missing[0]} is missing",
                         key=f"{key}.{missing[0]}")
    mass = number(value["mass"], f"{key}.mass", bound=MAX_MASS, why=" kg")
    if mass < 0.0:
        raise SceneError(f"a mass is 0 kg or more, got {mass:g}", key=f"{key}.mass")
    radius = number(value["radius"], f"{key}.radius", bound=MAX_LENGTH, why=" m")
    if not radius > 0.0:
        raise SceneError(f"the radius of the mass's centre from the axis is above 0 m, got {radius:g} (a mass on "
                         "the axis unbalances nothing: remove it)", key=f"{key}.radius")
    angle = number(value["angle"], f"{key}.angle", bound=MAX_ANGLE, why="°")
    plane = number(value["plane"], f"{key}.plane", bound=MAX_LENGTH, why=" m") if "plane" in value else None
    return RotorMass(mass=mass + 0.0, radius=radius, angle=angle + 0.0, plane=None if plane is None else plane + 0.0,
                     index=index)


def _balance(value: Any) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """The balancing planes and their radii (``balance = { planes = [...], radius = [...] }``; a
    single radius number stands for every plane)."""
    if not isinstance(value, Mapping):
        raise SceneError("balance is a table: balance = { planes = [0.1, 0.9], radius = [0.25, 0.25] }",
                         key="rotor.balance")
    _extra(value, _BALANCE_KEYS, "rotor.balance", "balance")
    if "planes" not in value:
        raise SceneError("balance names its planes along the shaft (m): planes = [0.1, 0.9] (two: dynamic "
                         "balance) or [0.0] (one: static balance)", key="rotor.balance.planes")
    planes = value["planes"]
    if not isinstance(planes, list) or not planes:
        raise SceneError(f"planes is a list of one or two places along the shaft (m), got {SHOW.repr(planes)}",
                         key="rotor.balance.planes")
    if len(planes) > 2:
        raise SceneError(f"a rotor is balanced in one plane (static) or two (dynamic), not {len(planes)}; give "
                         "planes = [a, b]", key="rotor.balance.planes")
    where = tuple(number(p, "rotor.balance.planes", bound=MAX_LENGTH, why=" m") + 0.0 for p in planes)
    if "radius" not in value:
        raise SceneError("balance gives the radius (m) of each balancing mass: radius = [0.25, 0.25]",
                         key="rotor.balance.radius")
    radius = value["radius"]
    radii = radius if isinstance(radius, list) else [radius]
    if isinstance(radius, list) and len(radius) != len(where):
        raise SceneError(f"radius gives one radius a balancing plane: {len(where)} planes, {len(radius)} radii",
                         key="rotor.balance.radius")
    out = tuple(number(r, "rotor.balance.radius", bound=MAX_LENGTH, why=" m") for r in radii)
    bad = next((r for r in out if not r > 0.0), None)
    if bad is not None:
        raise SceneError(f"a balancing mass's radius is above 0 m, got {bad:g}", key="rotor.balance.radius")
    return where, out * len(where) if len(out) == 1 else out


def read_rotor(table: Any) -> RotorSpec:
    """``[rotor]`` (see :class:`RotorSpec`), its values checked."""
    if not isinstance(table, Mapping):
        raise SceneError("[rotor] must be a table: masses = [...], balance = { planes = [...], radius = [...] }",
                         key="rotor")
    _extra(table, _KEYS, "rotor", "[rotor]")
    for k in ("masses", "balance"):
        if k not in table:
            raise SceneError(f"[rotor] needs masses (the rotating masses) and balance (the balancing planes): {k} is "
                             "missing", key=f"rotor.{k}")
    masses = table["masses"]
    if not isinstance(masses, list) or not masses:
        raise SceneError("masses is a non-empty list of { mass = 200.0, radius = 0.2, angle = 0.0, plane = 0.0 }, "
                         f"got {SHOW.repr(masses)}", key="rotor.masses")
    if len(masses) > MAX_ROTOR_MASSES:
        raise SceneError(f"{len(masses)} masses; a rotor has at most {MAX_ROTOR_MASSES} (each is a side of the "
                         "polygons drawn on one sheet)", key="rotor.masses")
    spec = tuple(_mass(m, i) for i, m in enumerate(masses))
    planes, radii = _balance(table["balance"])
    placed = [m.plane is not None for m in spec]
    if len(planes) == 2:
        lost = next((m for m in spec if m.plane is None), None)
        if lost is not None:
            raise SceneError("two balancing planes balance the couples too: give the mass's plane along the shaft "
                             "(m), plane = 0.3", key=f"{lost.key}.plane")
        every = (*planes, *(m.plane for m in spec))
        span = max(every) - min(every)
        if abs(planes[1] - planes[0]) <= MIN_PLANE_GAP * span:
            raise SceneError(f"the two balancing planes are at one place ({planes[0]:g} and {planes[1]:g} m); put "
                             "them apart along the shaft, or balance in one plane (planes = [a])",
                             key="rotor.balance.planes")
    elif any(placed) and not all(placed):
        lost = spec[placed.index(False)]
        raise SceneError("give plane for every mass or for none (none: every mass turns in the balancing plane)",
                         key=f"{lost.key}.plane")
    rpm = None
    if "rpm" in table:
        rpm = number(table["rpm"], "rotor.rpm", bound=MAX_RPM, why=" rpm")
        if not rpm > 0.0:
            raise SceneError(f"rpm is the shaft's speed, above 0 (leave it out for no forces), got {rpm:g}",
                             key="rotor.rpm")
    return RotorSpec(masses=spec, planes=planes, radii=radii, rpm=rpm)


def read_rotor_scene(data: Mapping[str, Any]) -> tuple[RotorSpec, tuple[str, ...]]:
    """A scene of a rotor alone: its ``[rotor]`` and what it draws (``[plans] draw``: by default
    nothing, the JSON report alone); any table of a linkage or a gear train is refused."""
    extra = sorted(str(k) for k in set(data) - ROTOR_KEYS)
    if extra:
        raise SceneError(f"[{extra[0]}] does not belong with [rotor]: a rotor is balanced in a scene of its own, "
                         f"which has {', '.join(sorted(ROTOR_KEYS))}", key=extra[0])
    draw = read_own_draw(data, ROTOR_SHEETS, "a rotor")
    return read_rotor(data["rotor"]), draw


"""The involute pair of a scene (``[gear_pair]``): the teeth, module and basic rack of one spur
pair — external, internal (``internal = true``: wheel 2 a ring gear) or a pinion with a rack
(``rack = true``: no z2) — its profile shifts (numbers, or a rule), the addenda (one, or one per
wheel) and the pinion's speed ``n1``; or a mesh of the scene's gear train.

Imports only plans.errors and plans.scene.checks (and the standard library).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

from ..errors import SceneError
from .checks import SHOW, number, whole

__all__ = ["GearPairSpec", "read_gear_pair", "SHIFTS", "MIN_PAIR_TEETH", "MAX_PAIR_TEETH", "STANDARD_TIP_RADIUS",
           "largest_tip_radius", "default_tip_radius"]

#: The rules for the shifts when x1, x2 are not given.
SHIFTS = ("none", "no_undercut", "balanced")
#: Teeth of a wheel of the pair: the generation is drawn tooth by tooth.
MIN_PAIR_TEETH, MAX_PAIR_TEETH = 5, 500
#: The standard cutter's tip radius ρ*, in modules (α = 20°, c* = 0.25: c*/(1 − sin α) ≈ 0.38).
STANDARD_TIP_RADIUS = 0.38
_KEYS = {"z1", "z2", "module", "pressure_angle", "addendum", "clearance", "x1", "x2", "shift", "tip_radius", "mesh",
         "internal", "rack", "n1"}
#: Bounds of one wheel's addendum coefficient in ``addendum = [ha1, ha2]``.
MAX_WHEEL_ADDENDUM = 2.5
#: The largest pinion speed, rpm.
MAX_RPM = 1e6


@dataclass(frozen=True)
class GearPairSpec:
    """``[gear_pair]``: teeth ``z1`` (the pinion) and ``z2``, ``module`` m (mm), the basic rack
    (``pressure_angle`` α in degrees, ``addendum`` ha*, ``clearance`` c*, ``tip_radius`` ρ of the
    cutter's tip rounding in modules: by default 0.38, or c*/(1 − sin α) where 0.38 does not fit),
    and the shifts ``x1``, ``x2`` or the ``shift`` rule ("none"; "no_undercut": the smallest shifts,
    0 or more, that avoid undercut; "balanced": x1 = −x2, equal specific sliding at the two ends of
    the active line). ``mesh`` names two wheels of ``[gears]`` instead of z1, z2, module (a ring
    gear among them makes the pair internal). ``addenda`` (ha1*, ha2*) when the scene gives one per
    wheel (``addendum`` is then their larger, the cutter's); ``internal`` wheel 2 is a ring gear;
    ``rack`` wheel 2 is a rack (``z2`` None); ``n1`` the pinion's speed, rpm (None: not given)."""

    z1: int | None = None
    z2: int | None = None
    module: float | None = None
    pressure_angle: float = 20.0
    addendum: float = 1.0
    clearance: float = 0.25
    x1: float | None = None
    x2: float | None = None
    shift: str | None = None
    tip_radius: float = STANDARD_TIP_RADIUS
    mesh: tuple[str, str] | None = None
    addenda: tuple[float, float] | None = None
    internal: bool = False
    rack: bool = False
    n1: float | None = None


def _teeth(value: Any, key: str) -> int:
    z = whole(value)
    if z is None:
        raise SceneError(f"teeth are a whole number, got {SHOW.repr(value)}", key=key)
    if not MIN_PAIR_TEETH <= z <= MAX_PAIR_TEETH:
        raise SceneError(f"a wheel of the pair has {MIN_PAIR_TEETH} … {MAX_PAIR_TEETH} teeth, got {z}", key=key)
    return z


def largest_tip_radius(pressure_angle: float, clearance: float, addendum: float = 1.0) -> float:
    """The largest tip radius ρ* of the cutter (in modules) that fits its tip corner: the rounding
    ends on the flank within the clearance, ρ* ≤ c*/(1 − sin α) (0.38 for the standard rack, α =
    20°, c* = 0.25), and the two roundings of a tooth do not cross, ρ* ≤ (π/4 − (ha* + c*)·tan α)·
    cos α/(1 − sin α) (a full round tip; binding for a long addendum: 0.287 at ha* = 1.355), α in
    degrees, ``addendum`` ha* the cutter's (the larger of a pair's)."""
    a = math.radians(pressure_angle)
    corner = clearance / (1.0 - math.sin(a))
    full_round = (math.pi / 4.0 - (addendum + clearance) * math.tan(a)) * math.cos(a) / (1.0 - math.sin(a))
    return max(min(corner, full_round), 0.0)


def default_tip_radius(pressure_angle: float, clearance: float, addendum: float = 1.0) -> float:
    """ρ* when the scene gives none: the standard 0.38 where it fits the rack's tip corner, else the
    largest that does (:func:`largest_tip_radius`: 0.3335 at α = 14.5°, c* = 0.25)."""
    largest = largest_tip_radius(pressure_angle, clearance, addendum)
    return STANDARD_TIP_RADIUS if STANDARD_TIP_RADIUS <= _allowed(largest) else largest


def _allowed(largest: float) -> float:
    """The largest ρ* a scene may write: the bound, or its rounding to the two decimals a designer
    writes where that is larger (0.38 at α = 20°, c* = 0.25, whose bound is 0.37995); what is given
    beyond the exact bound is clipped to it."""
    return max(largest, round(largest, 2)) + 1e-12


def read_gear_pair(table: Any) -> GearPairSpec:
    """``[gear_pair]`` (see :class:`GearPairSpec`), its numbers checked."""
    if not isinstance(table, Mapping):
        raise SceneError("[gear_pair] must be a table: z1 = 12, z2 = 30, module = 4.0", key="gear_pair")
    extra = sorted(str(k) for k in set(table) - _KEYS)
    if extra:
        raise SceneError(f"unknown key {extra[0]!r}; [gear_pair] has {', '.join(sorted(_KEYS))}",
                         key=f"gear_pair.{extra[0]}")
    internal, rack = (_flag(table, k) for k in ("internal", "rack"))
    if internal and rack:
        raise SceneError("wheel 2 is a ring gear or a rack, not both; remove internal or rack", key="gear_pair.rack")
    if rack and "mesh" in table:
        raise SceneError("mesh names two wheels of [gears], and a rack is none of them; remove rack or mesh",
                         key="gear_pair.rack")
    if internal and "mesh" in table:
        raise SceneError("mesh takes the wheels' kind from [gears] (a ring gear there has internal = true); "
                         "remove internal", key="gear_pair.internal")
    if rack and "z2" in table:
        raise SceneError("a rack has no teeth count z2; remove z2 (rack = true makes wheel 2 a rack)",
                         key="gear_pair.z2")
    mesh = None
    if "mesh" in table:
        m = table["mesh"]
        if not (isinstance(m, list) and len(m) == 2 and all(isinstance(w, str) for w in m)) or m[0] == m[1]:
            raise SceneError(f'mesh names two wheels of [gears]: mesh = ["a", "g"], got {SHOW.repr(m)}',
                             key="gear_pair.mesh")
        clash = sorted({"z1", "z2", "module"} & set(table))
        if clash:
            raise SceneError(f"mesh takes the teeth and the module from [gears]; remove {clash[0]}",
                             key=f"gear_pair.{clash[0]}")
        mesh = (m[0], m[1])
    else:
        need = ("z1", "module") if rack else ("z1", "z2", "module")
        missing = [k for k in need if k not in table]
        if missing:
            what = "z1 and module (rack = true)" if rack else "z1, z2 and module (or mesh = [\"a\", \"g\"])"
            raise SceneError(f"[gear_pair] needs {what}: {missing[0]} is missing", key=f"gear_pair.{missing[0]}")
    z1 = _teeth(table["z1"], "gear_pair.z1") if "z1" in table else None
    z2 = _teeth(table["z2"], "gear_pair.z2") if "z2" in table else None
    if internal and z1 is not None and z2 is not None and z2 <= z1:
        raise SceneError(f"a ring gear has more teeth than the pinion inside it: z2 = {z2} ≤ z1 = {z1}; give z2 > z1",
                         key="gear_pair.z2")
    module = None
    if "module" in table:
        module = number(table["module"], "gear_pair.module", bound=1e3, why=" mm")
        if not module >= 0.05:
            raise SceneError(f"the module is 0.05 mm or more, got {module:g}", key="gear_pair.module")
    alpha = number(table.get("pressure_angle", 20.0), "gear_pair.pressure_angle", bound=90.0, why="°")
    if not 10.0 <= alpha <= 35.0:
        raise SceneError(f"pressure_angle is 10° … 35° (20° standard), got {alpha:g}", key="gear_pair.pressure_angle")
    ha, addenda = _addendum(table.get("addendum", 1.0))
    c = number(table.get("clearance", 0.25), "gear_pair.clearance", bound=10.0)
    if not 0.0 <= c <= 0.5:
        raise SceneError(f"clearance c* is 0 … 0.5 (0.25 standard), got {c:g}", key="gear_pair.clearance")
    largest = largest_tip_radius(alpha, c, ha)     # the rounding fills the tip corner (0.38 standard)
    if "tip_radius" in table:
        rho = number(table["tip_radius"], "gear_pair.tip_radius", bound=10.0)
        if not 0.0 <= rho <= _allowed(largest):
            raise SceneError(f"tip_radius ρ* (in modules) is 0 … {largest:.4g} with α = {alpha:g}°, c* = {c:g} and "
                             f"the cutter's addendum {ha:g} (the rounding must fit the cutter's tip corner, "
                             f"c*/(1 − sin α), and its two roundings must not cross), got {rho:g}",
                             key="gear_pair.tip_radius")
    else:
        rho = default_tip_radius(alpha, c, ha)
    rho = min(rho, largest)
    has_x = "x1" in table or "x2" in table
    if has_x and "shift" in table:
        raise SceneError("give the shifts x1, x2 or a shift rule, not both", key="gear_pair.shift")
    if rack and "x2" in table:
        raise SceneError("a rack is not shifted: its reference line keeps its place; shift the pinion with x1 "
                         "and remove x2", key="gear_pair.x2")
    x1 = number(table.get("x1", 0.0), "gear_pair.x1", bound=3.0) if has_x else None
    x2 = number(table.get("x2", 0.0), "gear_pair.x2", bound=3.0) if has_x else None
    shift = None
    if not has_x:
        shift = table.get("shift", "none")
        if shift not in SHIFTS:
            raise SceneError(f"shift is {', '.join(repr(s) for s in SHIFTS)}, got {SHOW.repr(shift)}",
                             key="gear_pair.shift")
        if (internal and shift != "none") or (rack and shift == "balanced"):
            rule_for, give = ("an external pair", "x1, x2 for an internal pair") if internal else \
                ("two wheels", "x1 for a rack")
            raise SceneError(f"shift = {shift!r} is a rule for {rule_for}; give {give}", key="gear_pair.shift")
    n1 = None
    if "n1" in table:
        n1 = number(table["n1"], "gear_pair.n1", bound=MAX_RPM, why=" rpm")
        if not n1 > 0.0:
            raise SceneError(f"n1 is the pinion's speed, above 0 rpm, got {n1:g}", key="gear_pair.n1")
    return GearPairSpec(z1=z1, z2=z2, module=module, pressure_angle=alpha, addendum=ha, clearance=c, x1=x1, x2=x2,
                        shift=shift, tip_radius=rho, mesh=mesh, addenda=addenda, internal=internal, rack=rack, n1=n1)


def _flag(table: Mapping, key: str) -> bool:
    value = table.get(key, False)
    if not isinstance(value, bool):
        what = "wheel 2 is a ring gear" if key == "internal" else "wheel 2 is a rack"
        raise SceneError(f"{key} is true ({what}) or false, got {SHOW.repr(value)}", key=f"gear_pair.{key}")
    return value


def _addendum(value: Any) -> tuple[float, tuple[float, float] | None]:
    """ha* of the cutter and the addenda per wheel (None when one number is given): one number
    0.5 … 1.5, or [ha1, ha2] each 0 … 2 (the cutter's ha* then their larger)."""
    if isinstance(value, (list, tuple)):
        if len(value) != 2:
            raise SceneError(f"addendum is one number or one per wheel, [ha1, ha2]; got {len(value)} numbers",
                             key="gear_pair.addendum")
        pair = tuple(number(v, "gear_pair.addendum", bound=10.0) for v in value)
        for k, v in enumerate(pair):
            if not 0.0 <= v <= MAX_WHEEL_ADDENDUM:
                raise SceneError(f"the addendum of wheel {k + 1} (in modules: an addendum in mm over m) is 0 … "
                                 f"{MAX_WHEEL_ADDENDUM:g}, got {v:g}", key="gear_pair.addendum")
        if max(pair) == 0.0:
            raise SceneError("both addenda are 0: the teeth would not meet; give ha1 or ha2 above 0",
                             key="gear_pair.addendum")
        return max(pair), (pair[0], pair[1])
    ha = number(value, "gear_pair.addendum", bound=10.0)
    if not 0.5 <= ha <= 1.5:
        raise SceneError(f"addendum ha* is 0.5 … 1.5 (1 standard), got {ha:g}", key="gear_pair.addendum")
    return ha, None

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

__all__ = ["Dynamics", "read_dynamics", "DRIVINGS", "MAX_DELTA"]

#: How the crank is driven over the steady cycle.
DRIVINGS = ("constant",)
#: Largest coefficient of speed fluctuation δ: at δ = 2 the crank would stop (ω_min = ω_m(1 − δ/2));
#: a machine is designed for δ of 1/5 at most (pumps ~1/30, presses 1/10–1/20, generators 1/200).
MAX_DELTA = 0.5
#: Largest inertia (kg·m²) a flywheel or rotor may have.
MAX_INERTIA = 1e20


@dataclass(frozen=True)
class Dynamics:
    """``[dynamics]``: ``delta`` the allowed coefficient of speed fluctuation
    δ = (ω_max − ω_min)/ω_m (the flywheel is found for it), or ``flywheel`` a given flywheel's
    inertia J (kg·m², the δ it keeps is found); ``rotor_inertia`` (kg·m²) the motor's and gears'
    inertia reduced to the crank, always turning with it; ``driving``: "constant", the moment on
    the crank constant over the steady cycle and equal to the mean of the loads' reduced moment."""

    delta: float | None = None
    flywheel: float | None = None
    rotor_inertia: float = 0.0
    driving: str = "constant"


def read_dynamics(table: Any) -> Dynamics:
    """``[dynamics]``: delta or flywheel, rotor_inertia, driving."""
    if not isinstance(table, Mapping):
        raise SceneError("[dynamics] must be a table: delta = 0.05 (the allowed coefficient of speed fluctuation)",
                         key="dynamics")
    allowed = {"delta", "flywheel", "rotor_inertia", "driving"}
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
        if not 0.0 < delta <= MAX_DELTA:
            raise SceneError(f"delta = (ω_max − ω_min)/ω_m is a small positive fraction (e.g. 1/20 = 0.05, at most "
                             f"{MAX_DELTA:g}), got {delta:g}", key="dynamics.delta")
    else:
        flywheel = number(table["flywheel"], "dynamics.flywheel", bound=MAX_INERTIA, why=" kg·m²")
        if flywheel < 0.0:
            raise SceneError(f"a flywheel's inertia is 0 or more, got {flywheel:g} kg·m²", key="dynamics.flywheel")
    rotor = number(table.get("rotor_inertia", 0.0), "dynamics.rotor_inertia", bound=MAX_INERTIA, why=" kg·m²")
    if rotor < 0.0:
        raise SceneError(f"rotor_inertia is 0 or more, got {rotor:g} kg·m²", key="dynamics.rotor_inertia")
    driving = table.get("driving", "constant")
    if driving not in DRIVINGS:
        raise SceneError(f"driving is {' or '.join(repr(d) for d in DRIVINGS)} (the moment on the crank constant "
                         f"over the steady cycle); got {SHOW.repr(driving)}", key="dynamics.driving")
    return Dynamics(delta=delta, flywheel=flywheel, rotor_inertia=rotor, driving=driving)

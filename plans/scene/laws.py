"""Laws in the crank angle of a linkage's dynamics: ``[dynamics] driving`` and ``[[moments]] law``,
written as ``[turning]`` writes a torque and read by its reader (:func:`.turning.read_torque`: a
table, harmonics, shapes) over ``[dynamics] period``, against θ, the crank's turned angle in
degrees from the cycle's first position.

Here, not in :mod:`.dynamics`, because :mod:`.turning` imports that module's bounds.
Imports only plans.errors and modules of plans.scene (and the standard library).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any, Mapping

from ..errors import SceneError
from .checks import is_number
from .dynamics import Dynamics, read_dynamics, read_period
from .turning import Torque, read_torque

__all__ = ["read_law", "read_dynamics_with_laws", "MAX_ORDER"]

#: Highest order k of a harmonic in a linkage's law (the quadrature's panels shrink as 1/k: at
#: k = 100 they are 0.2°, and the linkage is solved at 8 points of each).
MAX_ORDER = 100.0
#: Narrowest shape of a linkage's law, degrees: the machine's panels halve towards a semicircle's
#: ends down to 2⁻²⁶° (plans.dynamics.laws.GRADE_DEG); a shape narrower than this is not resolved.
MIN_SHAPE_DEG = 1e-6


def read_law(value: Any, key: str, period: float, what: str) -> Torque:
    """A law in the crank angle θ (degrees from the cycle's first position, 0 … ``period``) as
    [turning] writes a torque: a table, harmonics or shapes, varying over the cycle (``what``
    says how a constant one is written instead)."""
    if value == "mean" or is_number(value):
        raise SceneError(f"a law in the crank angle is a table [[deg, N·m], …], {{ mean = T0, harmonics = [[A, k, φ°], "
                         f"…] }} or {{ shapes = [...] }} over the period {period:g}°; {what}", key=key)
    law = read_torque(value, key, period)
    narrow = next((k for k, sh in enumerate(law.shapes) if sh.end - sh.start < MIN_SHAPE_DEG), None)
    if narrow is not None:
        raise SceneError(f"shape {narrow} is {law.shapes[narrow].end - law.shapes[narrow].start:g}° wide, below the "
                         f"{MIN_SHAPE_DEG:g}° a linkage's cycle resolves (its panels); widen it or leave it out",
                         key=f"{key}.shapes[{narrow}]")
    if law.constant:
        raise SceneError(f"this law is constant over the cycle; {what}", key=key)
    high = max((k for _, k, _ in law.harmonics), default=0.0)
    if high > MAX_ORDER:
        raise SceneError(f"a harmonic of order k = {high:g} is beyond the {MAX_ORDER:g} a linkage's law takes (the "
                         f"cycle's panels shrink as 1/k)", key=key)
    return law


def read_dynamics_with_laws(table: Any, motor: Any = None) -> Dynamics:
    """``[dynamics]`` (:func:`.dynamics.read_dynamics`) with ``driving`` a law in the crank angle:
    the moment on the crank (N·m, positive in its sense of rotation), whose work over the cycle
    must balance the loads' (checked when the cycle is solved)."""
    period = read_period(table)
    driving = table.get("driving") if isinstance(table, Mapping) else None
    if not isinstance(driving, (list, Mapping)):
        return read_dynamics(table, motor)
    law = read_law(driving, "dynamics.driving", period, 'driving = "constant" is the loads\' mean')
    dynamics = read_dynamics({k: v for k, v in table.items() if k != "driving"}, motor)
    if dynamics.simulate is not None:
        raise SceneError('the start-up is driven by [motor]: a driving law and simulate do not go together; give '
                         'driving = "constant" or remove simulate', key="dynamics.simulate")
    return replace(dynamics, driving="law", torque=law)

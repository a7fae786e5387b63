"""The ``-shaking`` sheet's geometry (paper mm, y up): the hodograph of the shaking force (each
position's force drawn from one pole, the tips joined in order: its polar diagram), the trajectory
of the total centre of mass, and the shaking moment against the crank's angle — each with the
counterweights and, faintly, without them.

Reads a solved :class:`~plans.dynamics.shaking.ShakingAnalysis`; computes nothing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..dynamics.shaking import ShakingAnalysis
from .diagrams import Graph, make_graph
from .scales import fitting_scale

__all__ = ["Hodograph", "Trajectory", "ShakingSheet", "shaking_sheet", "PANEL_MM", "MOMENT_MM"]

#: The largest extent of the hodograph and of the trajectory, mm; the moment graph's φ axis and height.
PANEL_MM = 90.0
MOMENT_MM = (200.0, 40.0)


@dataclass(frozen=True)
class Hodograph:
    """``mu`` (N/mm); per position the force's tip (mm from the pole at the origin) and value (N);
    ``before``: the tips without the counterweights (empty when there are none)."""

    mu: float
    tips: tuple[tuple[float, float, float], ...]
    before: tuple[tuple[float, float], ...]


@dataclass(frozen=True)
class Trajectory:
    """``mu`` (m/mm); the centre of mass at each position (mm, from the frame's first pivot) and,
    ``before``, without the counterweights; ``still`` when it moves less than 1e-9 of the span."""

    mu: float
    points: tuple[tuple[float, float], ...]
    before: tuple[tuple[float, float], ...]
    still: bool


@dataclass(frozen=True)
class ShakingSheet:
    """The three panels, and ``moment`` the shaking moment against φ (a :class:`Graph`, μφ rad/mm)."""

    hodograph: Hodograph
    trajectory: Trajectory
    moment: Graph
    mu_phi: float
    length: float


def shaking_sheet(a: ShakingAnalysis) -> ShakingSheet:
    """The sheet of a solved shaking (see the module)."""
    now = a.shaking
    before = a.without if a.balanced is not None else None
    forces = [now.force] + ([before.force] if before is not None else [])
    top = max(float(np.max(np.hypot(f[:, 0], f[:, 1]))) for f in forces)
    mu_f = fitting_scale(2.0 * top if top > 0 else 1.0, PANEL_MM)
    tips = tuple((float(f[0] / mu_f), float(f[1] / mu_f), float(math.hypot(*f))) for f in now.force)
    old = tuple((float(f[0] / mu_f), float(f[1] / mu_f)) for f in before.force) if before is not None else ()
    centres = [now.centre] + ([before.centre] if before is not None else [])
    allc = np.vstack(centres) - a.origin
    span = float(np.max(np.ptp(allc, axis=0)))
    size = max(span, 1e-3 * float(np.max(np.abs(allc))) if allc.size else 1.0, 1e-12)
    mu_c = fitting_scale(size, PANEL_MM)
    pts = tuple((float(c[0] / mu_c), float(c[1] / mu_c)) for c in now.centre - a.origin)
    old_c = tuple((float(c[0] / mu_c), float(c[1] / mu_c)) for c in before.centre - a.origin) \
        if before is not None else ()
    moved = float(np.max(np.ptp(now.centre, axis=0)))
    still = moved <= 1e-9 * max(span, float(np.max(np.abs(allc))), 1e-12)
    phi = np.radians(np.mod(np.asarray(a.angles, float) - float(a.angles[0]), 360.0))    # from the first, turning on
    mu_phi = fitting_scale(2.0 * math.pi, MOMENT_MM[0])
    x = phi / mu_phi
    moment = make_graph("Msh", "M_{sh}", "N·m", top=-PANEL_MM - 30.0, x=x, values=np.asarray(now.moment, float),
                        at=np.arange(len(x)), extra=np.asarray(before.moment, float) if before is not None else None,
                        extra_symbol="without" if before is not None else "", height=MOMENT_MM[1])
    return ShakingSheet(Hodograph(mu_f, tips, old), Trajectory(mu_c, pts, old_c, still), moment, mu_phi,
                        2.0 * math.pi / mu_phi)

"""A linkage's shaking force and moment over the cycle (``draw = [..., "shaking"]``), with and
without counterweights.

Definitions (SI; x right, y up; moments counter-clockwise positive):

* the **shaking force** is the sum of the moving links' inertia forces, F = Σ −m_k·a_Sk = −M·a_G
  (M = Σ m_k, G the moving links' total centre of mass): what the frame would have to supply is
  its opposite; a counterweight adds its own −m_c·a_c;
* the **shaking moment** about the frame's first pivot O (the first point of link "0"):
  M_O = Σ (r_Sk − O) × (−m_k·a_Sk) + Σ (−I_Sk·ε_k), a counterweight adding (r_c − O) × (−m_c·a_c)
  (a counterweight is a point mass: no inertia of its own);
* the **centre of mass** r_G = Σ m_k·r_Sk / Σ m_k of the moving links (and counterweights).

Numeric; reads a solved :class:`~plans.kinematics.Motion` (its Motion's reads only) and the
scene's masses; never draws. :func:`shaking_analysis` is what a sheet and the JSON report need.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..kinematics import Motion
from ..kinematics.state import cross
from ..scene import FRAME, Scene
from .counterweights import Counterweight, Reciprocating, find_counterweights

__all__ = ["ShakingForces", "ShakingAnalysis", "shaking_analysis", "shaking_of", "counterweight_position"]


@dataclass(frozen=True, eq=False)
class ShakingForces:
    """The shaking at N positions: ``mass`` Σ m (kg), ``force`` (N, 2) N = Σ −m·a_S,
    ``moment`` (N,) N·m about the analysis's point O (CCW positive), ``centre`` (N, 2) m the
    total centre of mass."""

    mass: float
    force: np.ndarray
    moment: np.ndarray
    centre: np.ndarray


@dataclass(frozen=True, eq=False)
class ShakingAnalysis:
    """What a shaking sheet and the report need, at the cycle's N positions.

    ``angles`` the crank's angles (deg, the motion's drive values), ``omega`` the crank's ω1
    (rad/s) at each; ``about`` the point O of the moments (its name and ``origin`` (2,) m);
    ``without`` the links alone; ``balanced`` with the counterweights (None when none are asked);
    ``counterweights`` the counterweights found (mass, angle, radius); ``reciprocating`` a
    crank-slider's primary and secondary forces (None otherwise)."""

    angles: np.ndarray
    omega: np.ndarray
    about: str
    origin: np.ndarray
    without: ShakingForces
    balanced: ShakingForces | None
    counterweights: tuple[Counterweight, ...]
    reciprocating: Reciprocating | None

    @property
    def shaking(self) -> ShakingForces:
        """The shaking as the mechanism runs: with its counterweights when it has any."""
        return self.without if self.balanced is None else self.balanced


def shaking_of(motion: Motion, scene: Scene, origin: np.ndarray,
               counterweights: tuple[Counterweight, ...] = ()) -> ShakingForces:
    """The shaking force, moment about ``origin`` (2,) m and centre of mass of the moving links
    with ``scene.masses`` (and ``counterweights``, point masses on their links) over ``motion``,
    which must hold accelerations (order 2)."""
    n = len(motion)
    force = np.zeros((n, 2))
    moment = np.zeros(n)
    first = np.zeros((n, 2))         # Σ m·r
    total = 0.0
    items = []
    for mass in scene.masses.values():
        if mass.mass > 0.0:
            items.append((mass.mass, motion.position(mass.centre, mass.link),
                          motion.acceleration(mass.centre, mass.link)))
        if mass.inertia > 0.0:
            moment -= mass.inertia * motion.links[mass.link].epsilon
    for c in counterweights:
        if c.mass > 0.0:
            r = counterweight_position(motion, c)
            items.append((c.mass, r, motion.acceleration_at(c.link, r)))
    for m, r, a in items:
        f = -m * a
        force += f
        moment += cross(r - origin, f)
        first += m * r
        total += m
    centre = first / total if total > 0.0 else np.full((n, 2), np.nan)
    return ShakingForces(mass=total, force=force, moment=moment, centre=centre)


def counterweight_position(motion: Motion, c: Counterweight) -> np.ndarray:
    """Where counterweight ``c`` is at every position (N, 2) m: at its radius from its link's
    pivot, at its angle from the link's line first point → second point (CCW)."""
    pivot = motion.position(c.pivot, c.link)
    theta = np.radians(motion.angles[c.link] + c.angle)
    out = np.empty((len(motion), 2))
    out[:, 0] = pivot[:, 0] + c.radius * np.cos(theta)
    out[:, 1] = pivot[:, 1] + c.radius * np.sin(theta)
    return out


def shaking_analysis(motion: Motion, scene: Scene) -> ShakingAnalysis:
    """The shaking force, moment and centre of mass at the motion's positions (a cycle's),
    without and — with ``[counterweights]`` — with the counterweights found for the mechanism
    (:func:`~plans.dynamics.counterweights.find_counterweights`; SceneError naming
    ``counterweights`` when the links named cannot balance it). Pure: reads ``motion`` (solved
    to order 2) and ``scene``."""
    about = scene.links[FRAME][0]
    origin = np.asarray(motion.mechanism.sketch[about], float).copy()
    without = shaking_of(motion, scene, origin)
    found, recip = (), None
    balanced = None
    if scene.counterweights:
        found, recip = find_counterweights(motion, scene)
        balanced = shaking_of(motion, scene, origin, found)
    crank = motion.mechanism.drive.link
    omega = motion.links[crank].omega
    omega = np.full(len(motion), float(motion.mechanism.drive.speed)) if omega is None else np.asarray(omega)
    return ShakingAnalysis(angles=np.asarray(motion.values, float) % 360.0, omega=omega, about=about,
                           origin=origin, without=without, balanced=balanced, counterweights=found,
                           reciprocating=recip)


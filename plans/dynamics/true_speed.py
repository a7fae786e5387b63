"""The mechanism's motion at the crank's true speed: ω1(φ), ε1(φ) of the machine under its loads
(:mod:`.machine`) instead of a constant ω1.

Velocities are linear in ω1 and accelerations in (ε1, ω1²) at a given position: with
J(φ) = dr/dφ, v = ω1·J and a = ε1·J + ω1²·J′. So from the motion solved at a constant ω0
(ε = 0: v0 = ω0·J, a0 = ω0²·J′), with k = ω1/ω0 at each position:

    ω_j = k·ω_j0,  v = k·v0,  ε_j = (ε1/ω0)·ω_j0 + k²·ε_j0,  a = (ε1/ω0)·v0 + k²·a0,

exactly (no second solve), for every link and point.
"""

from __future__ import annotations

import numpy as np

from ..kinematics import Motion
from ..kinematics.state import LinkState

__all__ = ["at_true_speed"]


def at_true_speed(motion: Motion, omega: np.ndarray, epsilon: np.ndarray) -> Motion:
    """``motion`` (solved to accelerations at the constant ω0 = the drive's speed, ε = 0) at the
    crank's ``omega`` ω1 and ``epsilon`` ε1 (rad/s, rad/s², CCW; one value per position)."""
    w0 = float(motion.mechanism.drive.speed)
    if motion.order < 2 or w0 == 0.0 or motion.mechanism.drive.rate != 0.0:
        raise ValueError("at_true_speed needs a motion solved to accelerations at a constant ω ≠ 0")
    k = np.asarray(omega, float) / w0
    e = np.asarray(epsilon, float) / w0
    links = {}
    for name, s in motion.links.items():
        links[name] = LinkState(theta=s.theta, origin=s.origin, omega=k * s.omega, v=k[:, None] * s.v,
                                epsilon=e * s.omega + k * k * s.epsilon,
                                a=e[:, None] * s.v + (k * k)[:, None] * s.a)
    return Motion(motion.mechanism, motion.structure, motion.values, motion.order, links, motion.sines)

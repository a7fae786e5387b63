"""The machine reduced to its driving link at N positions: the reduced moment of the given loads
M_r = Σ(F·v + M·ω)/ω1 (N·m, CCW positive: forces, couples and weights — not inertia), the reduced
moment of inertia I_r = Σ(m·v_S² + I_S·ω²)/ω1² (kg·m²) and dI_r/dφ (kg·m²/rad).

The motion is one solved with the crank at a constant ω1 (ε1 = 0), so that the velocity ratios
v/ω1, ω/ω1 are exact and d(v_S²)/dφ = 2·v_S·a_S/ω1 — no finite differences.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..kinematics import Motion
from ..kinetostatics import Travel, applied_loads
from ..scene import Scene
from .laws import law_values

__all__ = ["Reduced", "reduce"]


@dataclass(frozen=True, eq=False)
class Reduced:
    """``moment`` M_r (N,) N·m CCW positive, ``inertia`` I_r (N,) kg·m², ``slope`` dI_r/dφ (N,)
    kg·m² per radian of the crank's angle φ (CCW positive), at the motion's positions."""

    moment: np.ndarray
    inertia: np.ndarray
    slope: np.ndarray


def reduce(motion: Motion, scene: Scene, travel: Travel | None = None, theta: np.ndarray | None = None) -> Reduced:
    """The reduced moment, inertia and dI_r/dφ of ``scene``'s loads and masses on ``motion``
    (order 2, the crank at its constant ω1 ≠ 0, ε1 = 0); ``travel`` for forces that follow
    the output; ``theta`` the crank's turned angle (rad, from the cycle's first position) at the
    motion's positions, for the moments with a law in it. The crank's own mass counts like any
    link's."""
    w1 = float(motion.mechanism.drive.speed)
    laws = None
    if any(m.law is not None for m in scene.moments):
        if theta is None:
            raise ValueError("a moment with a law in the crank angle needs theta, the crank's turned angle")
        laws = law_values(scene, theta)
    loads, couples = applied_loads(motion, scene, travel, inertia=False, laws=laws)
    n = len(motion)
    power = np.zeros(n)
    for load in loads:
        power += np.sum(load.force * motion.links[load.link].velocity(load.point), axis=1)
    for couple in couples:
        power += couple.moment * motion.links[couple.link].omega
    energy2 = np.zeros(n)       # 2T/ω1² summed: m·v² + I·ω²
    rate = np.zeros(n)          # d(m·v² + I·ω²)/dt = 2(m·v·a + I·ω·ε)
    for mass in scene.masses.values():
        state = motion.links[mass.link]
        if mass.mass > 0.0:
            v = motion.velocity(mass.centre, mass.link)
            a = motion.acceleration(mass.centre, mass.link)
            energy2 += mass.mass * np.sum(v * v, axis=1)
            rate += 2.0 * mass.mass * np.sum(v * a, axis=1)
        if mass.inertia > 0.0:
            energy2 += mass.inertia * state.omega ** 2
            rate += 2.0 * mass.inertia * state.omega * state.epsilon
    return Reduced(moment=power / w1, inertia=energy2 / w1 ** 2, slope=rate / w1 ** 3)

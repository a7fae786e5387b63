"""The loads of a force analysis, per link, over N positions (d'Alembert).

Every load is either a force applied at a point of a link or a couple on a link:

* the inertia force of a link with a mass, F_in = −m·a_S, applied at its centre of mass S
  (``F:in:<link>``), and the couple of its inertia forces, M_in = −I_S·ε (``M:in:<link>``);
* its weight G = m·g, acting −y at S (``G:<link>``), when the scene gives ``gravity``;
* the scene's external forces (``F:ext:<point>``), fixed in the x, y frame, and couples
  (``M:ext:<link>``, CCW positive);
* the balancing element (``F:bal``, ``M:bal``), the reactions of the pairs (``R:i-j``, the
  force of link i on link j) — added by the solver as it finds them.

Forces are (N, 2) arrays in newtons, points (N, 2) in metres, couples (N,) in N·m. A load
smaller than :data:`MIN_LOAD` at a position is no load there: it is 0 at that position.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import PlansError
from ..kinematics import Motion
from ..kinematics.state import cross
from ..scene import Scene

__all__ = ["Load", "Couple", "applied_loads", "MIN_LOAD"]

#: A force below this (N), or a moment below this (N·m), at a position is no load there (it is
#: taken as 0): nothing a machine feels is this small, and a load near the end of the double
#: range (1e-300 N) rounds away in some of the products the analysis and the lever take (its
#: square underflows), so the force plans and the lever would disagree on whether it is there.
MIN_LOAD = 1e-100


@dataclass(frozen=True, eq=False)
class Load:
    """A force ``force`` (N, 2) in N on link ``link`` applied at ``point`` (N, 2) in m;
    ``quantity`` tags it (``G:3``, ``F:in:2``, ``F:ext:B``, ``F:bal``, ``R:0-3``), ``kind`` is
    ``gravity``, ``inertia``, ``external``, ``balance`` or ``reaction``."""

    quantity: str
    link: str
    point: np.ndarray
    force: np.ndarray
    kind: str


@dataclass(frozen=True, eq=False)
class Couple:
    """A couple ``moment`` (N,) in N·m, CCW positive, on link ``link`` (``M:in:2``,
    ``M:ext:2``, ``M:bal``; a prismatic pair's reaction carries one about its reference
    point, tagged as the reaction)."""

    quantity: str
    link: str
    moment: np.ndarray
    kind: str


def applied_loads(motion: Motion, scene: Scene) -> tuple[tuple[Load, ...], tuple[Couple, ...]]:
    """The given loads of ``scene`` on the solved ``motion``: inertia (links with a mass or an
    inertia only), gravity (when set), external forces and couples. The balancing element is
    not among them (the solver finds it).

    Inertia needs accelerations: a motion solved to a lower order raises PlansError (the
    pipeline always solves to the order the loads need)."""
    loads: list[Load] = []
    couples: list[Couple] = []
    n = len(motion)
    inertial = [m for m in scene.masses.values() if m.mass > 0.0 or m.inertia > 0.0]
    if inertial and motion.order < 2:
        raise PlansError(f"link {inertial[0].link} has a mass or an inertia, and its inertia needs accelerations: "
                         "solve the motion with order=2 (plans.kinematics.analyse(..., order=2))")
    for mass in scene.masses.values():
        link = mass.link
        s = motion.position(mass.centre, link)
        if mass.mass > 0.0:
            if scene.gravity is not None:
                g = np.zeros((n, 2))
                g[:, 1] = -mass.mass * scene.gravity
                loads.append(Load(f"G:{link}", link, s, _force(g), "gravity"))
            a_s = motion.acceleration(mass.centre, link)
            loads.append(Load(f"F:in:{link}", link, s, _force(-mass.mass * a_s), "inertia"))
        if mass.inertia > 0.0:
            couples.append(Couple(f"M:in:{link}", link, _moment(-mass.inertia * motion.links[link].epsilon),
                                  "inertia"))
    tags = _tags([f"F:ext:{f.at}" for f in scene.forces])
    for f, tag in zip(scene.forces, tags):
        vec = np.broadcast_to(np.array(f.vector, float), (n, 2)).copy()
        loads.append(Load(tag, f.link, motion.position(f.at, f.link), _force(vec), "external"))
    tags = _tags([f"M:ext:{m.link}" for m in scene.moments])
    for m, tag in zip(scene.moments, tags):
        couples.append(Couple(tag, m.link, _moment(np.full(n, m.value)), "external"))
    return tuple(loads), tuple(couples)


def _force(f: np.ndarray) -> np.ndarray:
    """Forces (N, 2), N, with each one below :data:`MIN_LOAD` taken as 0."""
    small = np.hypot(f[:, 0], f[:, 1]) < MIN_LOAD
    return np.where(small[:, None], 0.0, f) if small.any() else f


def _moment(m: np.ndarray) -> np.ndarray:
    """Moments (N,), N·m, with each one below :data:`MIN_LOAD` taken as 0."""
    small = np.abs(m) < MIN_LOAD
    return np.where(small, 0.0, m) if small.any() else m


def _tags(names: list[str]) -> list[str]:
    """``names`` with ``#k`` (k = 2, 3, …) appended to the second and later repeats."""
    seen: dict[str, int] = {}
    out = []
    for name in names:
        seen[name] = seen.get(name, 0) + 1
        out.append(name if seen[name] == 1 else f"{name}#{seen[name]}")
    return out


def force_sum(loads: list[Load]) -> np.ndarray:
    """ΣF (N, 2) of ``loads`` (at least one position is implied by the first)."""
    return np.sum([l.force for l in loads], axis=0)


def moment_about(loads: list[Load], couples: list[Couple], x: np.ndarray) -> np.ndarray:
    """ΣM about the points ``x`` (N, 2): Σ (P − X) × F + Σ couples, N·m, CCW positive."""
    total = np.zeros(len(x))
    for l in loads:
        total += cross(l.point - x, l.force)
    for c in couples:
        total += c.moment
    return total

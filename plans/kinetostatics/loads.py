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

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np

from .. import linalg as la

from ..errors import PlansError, SceneError
from ..kinematics import Motion
from ..kinematics.cycle import Cycle
from ..kinematics.state import cross
from ..scene import Scene
from ..scene.values import AppliedForce

__all__ = ["Load", "Couple", "Travel", "applied_loads", "external_force", "forces_following", "MIN_LOAD", "REST_RTOL"]

#: A force below this (N), or a moment below this (N·m), at a position is no load there (it is
#: taken as 0): nothing a machine feels is this small, and a load near the end of the double
#: range (1e-300 N) rounds away in some of the products the analysis and the lever take (its
#: square underflows), so the force plans and the lever would disagree on whether it is there.
MIN_LOAD = 1e-100


#: A point (or the output) whose speed is at most this fraction of the largest over the
#: positions given is at rest there: a force against its velocity is 0 there, and a
#: stroke-limited force takes the stroke that starts at the nearer extreme.
REST_RTOL = 1e-9


@dataclass(frozen=True, eq=False)
class Travel:
    """The output link's travel at N positions, for the loads that follow the cycle: ``kind``
    "slider" (``s`` m along its guide) or "rocker" (``s`` its angle, rad), ``v`` = ds/dt, and
    ``low``, ``high`` its displacement (angle) at its two extreme positions; ``scale`` is the
    largest |v| over the cycle (what "at rest" is measured against)."""

    link: str
    kind: str
    s: np.ndarray
    v: np.ndarray
    low: float
    high: float
    scale: float

    def x(self, origin: str) -> np.ndarray:
        """The travel from the extreme ``origin`` ("min" or "max"), ≥ 0: m for a slider,
        degrees for a rocker."""
        d = self.s - self.low if origin == "min" else self.high - self.s
        if self.kind != "slider":        # angles: the same branch whatever the unwrapping
            d = np.degrees(np.mod(d + np.pi, 2 * np.pi) - np.pi)
        return np.maximum(d, 0.0)

    def working(self, origin: str) -> np.ndarray:
        """Whether the output moves away from ``origin`` (its working stroke) at each position;
        at rest (an extreme), whether it is nearer ``origin`` than the other extreme."""
        away = self.v > 0.0 if origin == "min" else self.v < 0.0
        rest = np.abs(self.v) <= REST_RTOL * self.scale
        span = abs(self.high - self.low)
        if self.kind != "slider":
            span = np.degrees(span)
        return np.where(rest, self.x(origin) <= 0.5 * span, away)


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


def forces_following(scene: Scene, cycle: Cycle) -> list[AppliedForce]:
    """The forces that follow the output link's travel (a law or a stroke). A cycle whose output
    turns fully has no extreme to measure the travel from: refused in one line, naming the force."""
    follows = [f for f in scene.forces if f.follows_output]
    if follows and cycle.extreme_output is None:
        f, link = follows[0], cycle.output.link
        raise SceneError(f"the force at {f.at} follows the travel of the output link {link} from its extreme "
                         f"position, and link {link} turns fully and has none; name a slider or a rocker in "
                         "[plans] output", key=f"forces[{f.index}]")
    return follows


def applied_loads(motion: Motion, scene: Scene, travel: Travel | None = None, *,
                  inertia: bool = True, laws: Mapping[int, np.ndarray] | None = None
                  ) -> tuple[tuple[Load, ...], tuple[Couple, ...]]:
    """The given loads of ``scene`` on the solved ``motion``: inertia (links with a mass or an
    inertia only; left out when ``inertia`` is False), gravity (when set), external forces
    (a force with a law or a stroke reads the output's ``travel`` at the motion's positions)
    and couples (a couple with a law in the crank angle takes its values at the positions from
    ``laws``: the moment's index → N·m, CCW positive). The balancing element is not among them
    (the solver finds it).

    Inertia needs accelerations: a motion solved to a lower order raises PlansError (the
    pipeline always solves to the order the loads need)."""
    loads: list[Load] = []
    couples: list[Couple] = []
    n = len(motion)
    inertial = [m for m in scene.masses.values() if m.mass > 0.0 or m.inertia > 0.0] if inertia else []
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
            if inertia:
                a_s = motion.acceleration(mass.centre, link)
                loads.append(Load(f"F:in:{link}", link, s, _force(-mass.mass * a_s), "inertia"))
        if mass.inertia > 0.0 and inertia:
            couples.append(Couple(f"M:in:{link}", link, _moment(-mass.inertia * motion.links[link].epsilon),
                                  "inertia"))
    tags = _tags([f"F:ext:{f.at}" for f in scene.forces])
    for f, tag in zip(scene.forces, tags):
        vec = external_force(f, motion, travel)
        loads.append(Load(tag, f.link, motion.position(f.at, f.link), _force(vec), "external"))
    tags = _tags([f"M:ext:{m.link}" for m in scene.moments])
    for m, tag in zip(scene.moments, tags):
        if m.law is not None and (laws is None or m.index not in laws):
            raise PlansError(f"the moment on link {m.link} follows a law in the crank angle: give its values at the "
                             f"motion's positions (laws = {{{m.index}: N·m, …}}; plans.dynamics.laws.law_values)")
        value = np.asarray(laws[m.index], dtype=float) if m.law is not None else np.full(n, m.value)
        couples.append(Couple(tag, m.link, _moment(value), "external"))
    return tuple(loads), tuple(couples)


def external_force(f: AppliedForce, motion: Motion, travel: Travel | None) -> np.ndarray:
    """The force ``f`` (N, 2) N at the motion's positions: its vector, or its law's value along
    its direction at the output's travel, on the stroke it acts on, against the velocity of its
    point when it opposes it (0 where that point is at rest)."""
    n = len(motion)
    if f.constant:
        return np.broadcast_to(np.array(f.vector, float), (n, 2)).copy()
    if f.follows_output and travel is None:
        raise PlansError(f"the force at {f.at} follows the output link's travel (a law or a stroke), which needs the "
                         "cycle: add [drive] positions = N")
    if f.law:
        xs, fs = np.array([p[0] for p in f.law]), np.array([p[1] for p in f.law])
        mag = np.interp(travel.x(f.origin), xs, fs)
    else:
        mag = np.full(n, f.magnitude if f.vector is None else math.hypot(*f.vector))
    if f.stroke != "both":
        on = travel.working(f.origin)
        mag = np.where(on if f.stroke == "working" else ~on, mag, 0.0)
    if not f.oppose:
        return mag[:, None] * np.array(f.vector, float) if f.law else \
            np.where((mag > 0.0)[:, None], np.array(f.vector, float), 0.0)
    if motion.order < 1:
        raise PlansError(f"the force at {f.at} acts against the velocity of its point, which needs velocities: solve "
                         "the motion with order ≥ 1")
    v = motion.velocity(f.at, f.link)
    speed = np.hypot(v[:, 0], v[:, 1])
    rest = speed <= REST_RTOL * max(float(speed.max(initial=0.0)), 1e-300)
    if f.vector is None:
        with np.errstate(invalid="ignore", divide="ignore"):
            d = np.where(rest[:, None], 0.0, -v / np.where(rest, 1.0, speed)[:, None])
        return np.abs(mag)[:, None] * d
    d = np.array(f.vector, float)
    d = d / math.hypot(*d)
    along = la.matmul(v, d)
    sense = np.where(rest | (np.abs(along) <= REST_RTOL * speed.max(initial=0.0)), 0.0, -np.sign(along))
    return (np.abs(mag) * sense)[:, None] * d


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

"""Instantaneous centres of velocity: absolute (each link relative to the frame) and
relative (each pair of links), from the solved motion.

The centre P_ij of links i and j is the point whose velocity is the same in both:

    v_i(X) = v_j(X)  ⇔  (ω_i − ω_j)·k × X = −w,  w = (v_oi − ω_i k×o_i) − (v_oj − ω_j k×o_j)
    ⇒  X = k × w / (ω_i − ω_j)

With j the frame this is the absolute centre P_i = o_i + k × v_oi / ω_i. When ω_i = ω_j
(to a relative ``INFINITY_RTOL`` of the link's velocities over the mechanism's size) the
centre is at infinity: it is reported as ``None`` and its direction — normal to the common
relative velocity — is given instead; nothing is divided by zero. By Aronhold–Kennedy's
theorem P_ij, P_jk and P_ik lie on one line.

**At rest.** When link i does not move relative to j at all — |ω_i − ω_j|·size and the
relative speed of i's first point both at most ``REST_RTOL`` (1e-9) × the speed of the
mechanism's fastest point at that position
(:meth:`~plans.kinematics.state.Solution.rate_scale`) — there is no centre: ``rest`` is True,
the point is NaN and the direction zero. This is what a stationary instant found by
root-finding gives (ω ~ 1e-16: without the test, X = k × w / (ω_i − ω_j) would be rounding
over rounding); the centre's limit as the instant is approached (the link's acceleration
pole) is not reported.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

import numpy as np

from ..scene import FRAME
from .tolerances import INFINITY_RTOL, REST_RTOL
from .state import J, Solution
from .. import linalg as la

__all__ = ["Centre", "Centres", "centres", "centre_from", "INFINITY_RTOL", "REST_RTOL"]



@dataclass(frozen=True)
class Centre:
    """P_ij at N positions: ``point`` (N, 2) in metres, NaN where at infinity or at rest;
    ``direction`` (N, 2), a unit vector towards the centre at infinity (zero where finite or
    at rest); ``rest`` (N,), True where the two links do not move relative to each other (to
    ``REST_RTOL`` of the speed of the mechanism's fastest point): no centre."""

    links: tuple[str, str]
    point: np.ndarray
    direction: np.ndarray
    rest: np.ndarray

    @property
    def name(self) -> str:
        i, j = self.links
        return f"P{i}" if j == FRAME else f"P{i}{j}" if len(i + j) == 2 else f"P{i},{j}"

    def at(self, n: int) -> tuple[float, float] | None:
        """The centre at position n (m), or None when it is at infinity or at rest."""
        p = self.point[n]
        return None if np.isnan(p[0]) else (float(p[0]), float(p[1]))

    def at_rest(self, n: int) -> bool:
        """Whether the two links are at rest relative to each other at position n (no centre)."""
        return bool(self.rest[n])


@dataclass(frozen=True)
class Centres:
    """Absolute centres (moving link → Centre) and relative ones ((i, j) → Centre)."""

    absolute: dict[str, Centre]
    relative: dict[tuple[str, str], Centre]


def _centre(motion: Solution, i: str, j: str, scale: np.ndarray) -> Centre:
    """P_ij; ``scale`` (N,) the speed of the mechanism's fastest point at each position (m/s),
    for the rest test."""
    si, sj = motion.links[i], motion.links[j]
    size = motion.mechanism.size
    w = (si.v - si.omega[:, None] * J(si.origin)) - (sj.v - sj.omega[:, None] * J(sj.origin))
    dw = si.omega - sj.omega
    # the relative velocity field at a point of the link, for the infinity test
    x = si.origin
    v_rel = si.velocity(x) - sj.velocity(x)
    speed = np.maximum(la.norm(v_rel, axis=1), np.abs(dw) * size)
    # at rest: the relative field v_rel(X0) + (ω_i − ω_j)·k × (X − X0) is below the bound at the
    # link's first point X0 and turns by no more than it over the mechanism's size
    x0 = si.point(next(iter(motion.mechanism.links[i].local.values())))
    still = np.maximum(la.norm(si.velocity(x0) - sj.velocity(x0), axis=1), np.abs(dw) * size)
    rest = still <= REST_RTOL * scale
    finite = (np.abs(dw) * size > INFINITY_RTOL * speed) & ~rest
    safe = np.where(finite, dw, 1.0)
    point = np.where(finite[:, None], J(w) / safe[:, None], np.nan)
    norm = la.norm(v_rel, axis=1)
    infinite = ~finite & ~rest & (norm > 0.0)
    direction = np.where(infinite[:, None], J(v_rel) / np.where(norm > 0.0, norm, 1.0)[:, None], 0.0)
    return Centre((i, j), point, direction, rest)


def centres(motion: Solution) -> Centres:
    """Every absolute and relative centre of the mechanism (needs velocities); a pair of links
    at rest relative to each other (see the module's docstring, ``REST_RTOL``) has none."""
    if motion.order < 1:
        raise ValueError("instantaneous centres need the velocities: solve with order >= 1")
    moving = motion.mechanism.moving
    scale = motion.rate_scale(1)
    absolute = {name: _centre(motion, name, FRAME, scale) for name in moving}
    if any(motion.links[name].v is None for name in moving):
        relative = {(a, b): _centre(motion, a, b, scale) for a, b in combinations(moving, 2)}
    else:
        relative = _relative(motion, moving, scale)
    return Centres(absolute, relative)


def _spin_many(v: np.ndarray, w: np.ndarray, r: np.ndarray) -> np.ndarray:
    """v + w·k×r over stacked links (..., N, 2), operation for operation as
    :meth:`~plans.kinematics.state.LinkState.velocity` computes it for one."""
    out = np.empty(np.broadcast_shapes(v.shape, r.shape))
    np.subtract(v[..., 0], w * r[..., 1], out=out[..., 0])
    np.add(v[..., 1], w * r[..., 0], out=out[..., 1])
    return out


def _relative(motion: Solution, moving: tuple[str, ...], scale: np.ndarray) -> dict[tuple[str, str], Centre]:
    """:func:`_centre` of every pair (i, j), i before j in ``moving``: each link's quantities
    once, then for each i all its j at once (the same operations, so the same bits): time
    linear in the pairs, of which there are n(n − 1)/2."""
    states = [motion.links[name] for name in moving]
    size = motion.mechanism.size
    v = np.stack([s.v for s in states])                              # (L, N, 2)
    omega = np.stack([s.omega for s in states])                      # (L, N)
    origin = np.stack([s.origin for s in states])
    base = np.stack([s.v - s.omega[:, None] * J(s.origin) for s in states])
    out: dict[tuple[str, str], Centre] = {}
    for i, name in enumerate(moving[:-1]):
        si, j = states[i], slice(i + 1, None)
        x0 = si.point(next(iter(motion.mechanism.links[name].local.values())))
        w = base[i] - base[j]
        dw = si.omega - omega[j]
        x = si.origin
        v_rel = si.velocity(x) - _spin_many(v[j], omega[j], x - origin[j])
        speed = np.maximum(la.norm(v_rel, axis=-1), np.abs(dw) * size)
        still = np.maximum(la.norm(si.velocity(x0) - _spin_many(v[j], omega[j], x0 - origin[j]), axis=-1),
                           np.abs(dw) * size)
        rest = still <= REST_RTOL * scale
        finite = (np.abs(dw) * size > INFINITY_RTOL * speed) & ~rest
        safe = np.where(finite, dw, 1.0)
        point = np.where(finite[..., None], J(w) / safe[..., None], np.nan)
        norm = la.norm(v_rel, axis=-1)
        infinite = ~finite & ~rest & (norm > 0.0)
        direction = np.where(infinite[..., None], J(v_rel) / np.where(norm > 0.0, norm, 1.0)[..., None], 0.0)
        for k, other in enumerate(moving[i + 1:]):
            out[(name, other)] = Centre((name, other), point[k], direction[k], rest[k])
    return out


def centre_from(motion: Solution, link: str, point: str, i: int) -> np.ndarray | None:
    """The absolute centre of ``link`` at position ``i`` (m) from the velocity of its point
    ``point``: P = X + k × v_X / ω (the point of :func:`centres` up to rounding, as a
    draughtsman finds it from one velocity); None when ω = 0 (the link translates)."""
    omega = float(motion.links[link].omega[i])
    if omega == 0.0:
        return None
    return motion.position(point)[i] + J(motion.velocity(point, link)[i]) / omega

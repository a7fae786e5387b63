"""The pairs as the force solver sees them: :class:`_Pair` (the force of ``first`` on
``second`` at a pin or a prismatic pair), their pins, guides and reference points
(:class:`_Geometry`, computed once per pair), and two small vector helpers.

Reads the solved motion's positions; must not import the solver, the results or anything
above the kinetostatics.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..kinematics import Motion
from ..kinematics.state import J, cross
from ..model import Prismatic


@dataclass(frozen=True, eq=False)
class _Pair:
    """A pair to solve: the force of ``first`` on ``second``; a pin at ``point`` or a
    prismatic pair ``prismatic``."""

    first: str
    second: str
    kind: str
    point: str | None = None
    prismatic: Prismatic | None = None


class _Geometry:
    """Pins, guides and reference points of the pairs, computed once per pair."""

    def __init__(self, motion: Motion):
        self.motion = motion
        self._cache: dict = {}

    def pin(self, point: str) -> np.ndarray:
        key = ("pin", point)
        if key not in self._cache:
            self._cache[key] = self.motion.position(point)
        return self._cache[key]

    def guide(self, p: Prismatic) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """u (the guide's unit direction), ν = k × u and the reference point r0 (the pair's
        label point projected on the common line), each (N, 2)."""
        key = ("guide", id(p))
        if key not in self._cache:
            m = self.motion
            u = m.links[p.guide].direction(p.direction)
            on_line = m.links[p.slider].point(p.anchor[p.slider])
            label = m.position(p.label)
            r0 = on_line + np.sum((label - on_line) * u, axis=1)[:, None] * u
            self._cache[key] = (u, J(u), r0)
        return self._cache[key]

    def anchor(self, pair: _Pair) -> np.ndarray:
        """Where the pair's unknown force is applied in the equations: the pin, or r0."""
        return self.pin(pair.point) if pair.kind == "R" else self.guide(pair.prismatic)[2]


def _split(f: np.ndarray, a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """x, y (N,) with f = x·a + y·b (Cramer's rule; a, b (N, 2) not parallel)."""
    det = cross(a, b)
    return cross(f, b) / det, cross(a, f) / det


def _unit(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    length = np.hypot(v[:, 0], v[:, 1])
    return v / length[:, None], length

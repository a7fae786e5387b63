"""Link states over N positions and the rigid-body relations between their points.

Vectors are numpy arrays of shape (N, 2), scalars of shape (N,). ``J`` turns a vector by
+90° (k × v). A link's pose maps a local point x to o + R(θ)·x; its motion is given by
the velocity v and acceleration a of the (possibly virtual) point o, and ω, ε (CCW > 0):

    v_X = v_o + ω k × (X − o)
    a_X = a_o + ε k × (X − o) − ω² (X − o)
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cached_property
from typing import Mapping

import numpy as np

__all__ = ["J", "cross", "rotate", "LinkState", "Motion"]


def J(v: np.ndarray) -> np.ndarray:
    """k × v: the vector turned by +90°."""
    out = np.empty(np.shape(v))
    out[..., 0] = -v[..., 1]
    out[..., 1] = v[..., 0]
    return out


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The scalar (z) cross product a × b of plane vectors."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def rotate(local: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """R(θ)·x for one local vector x (2,) and angles θ (N,): shape (N, 2)."""
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c * local[0] - s * local[1], s * local[0] + c * local[1]], axis=-1)


@dataclass(frozen=True)
class LinkState:
    """Pose and (when computed) motion of one link at N positions."""

    theta: np.ndarray
    origin: np.ndarray
    omega: np.ndarray | None = None
    v: np.ndarray | None = None
    epsilon: np.ndarray | None = None
    a: np.ndarray | None = None

    @cached_property
    def _cos_sin(self) -> tuple[np.ndarray, np.ndarray]:
        """cos θ, sin θ, computed once per state (every point of the link uses them)."""
        return np.cos(self.theta), np.sin(self.theta)

    def point(self, local: np.ndarray) -> np.ndarray:
        """World position of a local point (m)."""
        return self.origin + self.direction(local)

    def direction(self, local: np.ndarray) -> np.ndarray:
        """World direction of a local direction vector."""
        c, s = self._cos_sin
        out = np.empty(self.origin.shape)
        out[:, 0] = c * local[0] - s * local[1]
        out[:, 1] = s * local[0] + c * local[1]
        return out

    def velocity(self, x: np.ndarray) -> np.ndarray:
        """v_X of the link's point now at world position ``x`` (m/s)."""
        return self.v + self.omega[:, None] * J(x - self.origin)

    def acceleration(self, x: np.ndarray) -> np.ndarray:
        """a_X of the link's point now at world position ``x`` (m/s²)."""
        r = x - self.origin
        return self.a + self.epsilon[:, None] * J(r) - (self.omega ** 2)[:, None] * r

    def with_velocity(self, omega: np.ndarray, x: np.ndarray, v_x: np.ndarray) -> "LinkState":
        """The state with ω and the velocity ``v_x`` of its point at ``x``."""
        omega = np.broadcast_to(np.asarray(omega, float), self.theta.shape).copy()
        return self._keep_cos_sin(replace(self, omega=omega, v=v_x + omega[:, None] * J(self.origin - x)))

    def with_acceleration(self, epsilon: np.ndarray, x: np.ndarray, a_x: np.ndarray) -> "LinkState":
        """The state with ε and the acceleration ``a_x`` of its point at ``x``."""
        epsilon = np.broadcast_to(np.asarray(epsilon, float), self.theta.shape).copy()
        r = self.origin - x
        return self._keep_cos_sin(replace(self, epsilon=epsilon,
                                          a=a_x + epsilon[:, None] * J(r) - (self.omega ** 2)[:, None] * r))

    def take(self, index: np.ndarray) -> "LinkState":
        """The state at a subset of positions (cos θ, sin θ taken along when known)."""
        out = LinkState(*(None if f is None else f[index] for f in
                          (self.theta, self.origin, self.omega, self.v, self.epsilon, self.a)))
        if "_cos_sin" in self.__dict__:
            c, s = self.__dict__["_cos_sin"]
            out.__dict__["_cos_sin"] = (c[index], s[index])
        return out

    def _keep_cos_sin(self, other: "LinkState") -> "LinkState":
        """``other`` (this pose with more motion) keeps this state's cos θ, sin θ."""
        if "_cos_sin" in self.__dict__:
            other.__dict__["_cos_sin"] = self.__dict__["_cos_sin"]
        return other


@dataclass(frozen=True)
class Motion:
    """The solved mechanism at N drive positions.

    ``values`` are the drive's values as requested (degrees or metres); ``order`` is 0
    (positions), 1 (+ velocities) or 2 (+ accelerations); ``sines`` holds, per group, the
    normalised determinant of its velocity equations (1 = well conditioned, 0 = singular).
    """

    mechanism: "object"
    structure: "object"
    values: np.ndarray
    order: int
    links: Mapping[str, LinkState]
    sines: Mapping[str, np.ndarray]

    def carrier(self, point: str) -> str:
        """The first link (scene order) that carries ``point``."""
        return next(name for name, l in self.mechanism.links.items() if point in l.local)

    def position(self, point: str, link: str | None = None) -> np.ndarray:
        link = link or self.carrier(point)
        return self.links[link].point(self.mechanism.links[link].local[point])

    def velocity(self, point: str, link: str | None = None) -> np.ndarray:
        link = link or self.carrier(point)
        return self.links[link].velocity(self.position(point, link))

    def acceleration(self, point: str, link: str | None = None) -> np.ndarray:
        link = link or self.carrier(point)
        return self.links[link].acceleration(self.position(point, link))

    def __len__(self) -> int:
        return len(self.values)

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
from .. import linalg as la

__all__ = ["J", "cross", "rotate", "cos_sin", "LinkState", "Solution"]

def J(v: np.ndarray) -> np.ndarray:
    """k × v: the vector turned by +90°."""
    out = _pair(len(v)) if np.ndim(v) == 2 else np.empty(np.shape(v))
    np.negative(v[..., 1], out=out[..., 0])
    out[..., 1] = v[..., 0]
    return out


def _pair(n: int) -> np.ndarray:
    """An empty (n, 2) array of vectors stored by columns (x, then y), so that the column
    arithmetic of the rigid-body relations runs on contiguous memory."""
    return np.empty((2, n)).T


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The scalar (z) cross product a × b of plane vectors."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def cos_sin(theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """cos θ, sin θ from t = tan(θ/2): cos = (1 − t²)/(1 + t²), sin = 2t/(1 + t²), within one
    unit in the last place of np.cos, np.sin (|error| ≤ 2.3e-16) and several times faster
    (numpy's tan is vectorised, its float64 sin and cos are not)."""
    t = np.tan(0.5 * theta)
    t2 = t * t
    q = 1.0 / (1.0 + t2)
    return (1.0 - t2) * q, (t + t) * q


def _rotated(local: np.ndarray, c: np.ndarray, s: np.ndarray, base: np.ndarray | None = None,
             sign: float = 1.0) -> np.ndarray:
    """base + sign·R·local (base (N, 2) or None for 0) from cos θ, sin θ: shape (N, 2)."""
    x, y = float(local[0]), float(local[1])
    out = _pair(len(c))
    if x == 0.0 and y == 0.0:
        out[...] = 0.0 if base is None else base
        return out
    rx = c * x - s * y if y != 0.0 else c * x
    ry = s * x + c * y if y != 0.0 else s * x
    if base is None:
        if sign < 0.0:
            np.negative(rx, out=rx)
            np.negative(ry, out=ry)
        out[:, 0], out[:, 1] = rx, ry
    elif sign < 0.0:
        np.subtract(base[:, 0], rx, out=out[:, 0])
        np.subtract(base[:, 1], ry, out=out[:, 1])
    else:
        np.add(base[:, 0], rx, out=out[:, 0])
        np.add(base[:, 1], ry, out=out[:, 1])
    return out


def rotate(local: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """R(θ)·x for one local vector x (2,) and angles θ (N,): shape (N, 2)."""
    return _rotated(local, *cos_sin(theta))


def _spin(v: np.ndarray | None, w: np.ndarray, r: np.ndarray, w2: np.ndarray | None = None,
          e: np.ndarray | None = None) -> np.ndarray:
    """v + w·k×r (− w2·r with w2, the ω² term, when ``e`` (then the k× factor) is given):
    the rigid-body relations, in columns. v None is 0."""
    rx, ry = r[:, 0], r[:, 1]
    out = _pair(len(r))
    if e is None:
        x, y = w * ry, w * rx
    else:
        x = e * ry
        x += w2 * rx
        y = e * rx
        y -= w2 * ry
    if v is None:
        np.negative(x, out=out[:, 0])
        out[:, 1] = y
    else:
        np.subtract(v[:, 0], x, out=out[:, 0])
        np.add(v[:, 1], y, out=out[:, 1])
    return out


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
        return cos_sin(self.theta)

    def seeded(self, c: np.ndarray, s: np.ndarray) -> "LinkState":
        """This state, with cos θ, sin θ given (known without trigonometry); returns self."""
        self.__dict__["_cos_sin"] = (c, s)
        return self

    def point(self, local: np.ndarray) -> np.ndarray:
        """World position of a local point (m)."""
        return _rotated(local, *self._cos_sin, base=self.origin)

    def direction(self, local: np.ndarray) -> np.ndarray:
        """World direction of a local direction vector."""
        return _rotated(local, *self._cos_sin)

    def velocity(self, x: np.ndarray) -> np.ndarray:
        """v_X of the link's point now at world position ``x`` (m/s)."""
        return _spin(self.v, self.omega, x - self.origin)

    def acceleration(self, x: np.ndarray) -> np.ndarray:
        """a_X of the link's point now at world position ``x`` (m/s²)."""
        w = self.omega
        return _spin(self.a, w, x - self.origin, w * w, self.epsilon)

    def with_velocity(self, omega: np.ndarray, x: np.ndarray, v_x: np.ndarray | None, own: bool = False
                      ) -> "LinkState":
        """The state with ω and the velocity ``v_x`` (None: 0) of its point at ``x``; ``own``:
        ``omega`` is a fresh float array of the state's shape, kept without a copy."""
        if not own:
            omega = np.broadcast_to(np.asarray(omega, float), self.theta.shape).copy()
        return self._keep_cos_sin(replace(self, omega=omega, v=_spin(v_x, omega, self.origin - x)))

    def with_acceleration(self, epsilon: np.ndarray, x: np.ndarray, a_x: np.ndarray | None, own: bool = False
                          ) -> "LinkState":
        """The state with ε and the acceleration ``a_x`` (None: 0) of its point at ``x``; ``own``
        as for :meth:`with_velocity`."""
        if not own:
            epsilon = np.broadcast_to(np.asarray(epsilon, float), self.theta.shape).copy()
        w = self.omega
        return self._keep_cos_sin(replace(self, epsilon=epsilon, a=_spin(a_x, w, self.origin - x, w * w, epsilon)))

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
class Solution:
    """The solved links of a mechanism at N drive positions: what the solver found, and the
    rigid-body reads of it (a point's position, velocity, acceleration). The modules that
    derive more from it (centres, special points, sliding) take a Solution; the one object
    users read, :class:`plans.kinematics.motion.Motion`, adds those on top.

    ``values`` are the drive's values as requested (degrees or metres); ``order`` is 0
    (positions), 1 (+ velocities) or 2 (+ accelerations); ``sines`` holds, per group, its
    condition figure: the sine of its transmission angle, generalised (:mod:`plans.kinematics.figure`;
    the rods' axes for a class III group), 1 = well conditioned, 0 = singular.
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

    def velocity_at(self, link: str, xy: np.ndarray, i: int | None = None) -> np.ndarray:
        """v (m/s) of the point of ``link`` now at world position ``xy`` (m): ``xy`` (N, 2) at
        every position, or, with ``i``, ``xy`` (2,) at position i (returns (2,))."""
        if i is None:
            return self.links[link].velocity(xy)
        return self.links[link].take(np.array([i])).velocity(np.asarray(xy, float)[None, :])[0]

    def acceleration_at(self, link: str, xy: np.ndarray, i: int | None = None) -> np.ndarray:
        """a (m/s²) of the point of ``link`` now at world position ``xy`` (m), as for
        :meth:`velocity_at`."""
        if i is None:
            return self.links[link].acceleration(xy)
        return self.links[link].take(np.array([i])).acceleration(np.asarray(xy, float)[None, :])[0]

    def rate_scale(self, order: int = 1) -> np.ndarray:
        """How fast the mechanism moves at each position, (N,): the speed of its fastest point,
        the largest |v| of any point of any moving link (m/s; ``order`` 2: the largest |a|,
        m/s²). The scale against which a value is zero up to rounding (a link at rest, the
        class III cross-check's difference)."""
        mech, out = self.mechanism, np.zeros(len(self.values))
        for name in mech.moving:
            s = self.links[name]
            field = s.velocity if order == 1 else s.acceleration
            for local in mech.links[name].local.values():
                np.maximum(out, la.norm(field(s.point(local)), axis=1), out=out)
        return out

    def __len__(self) -> int:
        return len(self.values)

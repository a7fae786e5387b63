"""A drive inside the chain: the original mechanism's links solved together with the drive.

A coupler's absolute angle, or a hydraulic cylinder's stroke, fixes no link by itself: the
links of the original mechanism (:class:`~plans.structure.DrivenGroup`, 3n unknowns) have
2p = 3n − 1 pair equations (those of :class:`~plans.kinematics.generic.GroupEquations`) and
the drive gives the last one, rheonomic (it holds the drive's value at the position):

* coupler c, its line turned θ_c from the sketch:  θ_c − (φ − φ₀) = 0   (rad; φ₀ the sketch's angle)
* cylinder, rod s sliding in guide link g:          (X_s − Y_g)·u_g − σ₀ − s = 0   (m)

(X_s, Y_g: the pair's anchor points on each link, u_g the guide's direction turned with g,
σ₀ their offset along it in the sketch.) Its time derivatives give the drive's row of the
rate solves: θ̇_c = ω, θ̈_c = ε for a coupler; for a cylinder the relative sliding velocity
σ̇ = v and acceleration σ̈ = a along the guide, with the terms the guide's turning adds
(the same as a prismatic pair's normal row, with u_g for n_g):

    σ̇ = (V_s − V_g)·u_g + ω_g (X_s − Y_g)·(k × u_g)
    σ̈ = (A_s − A_g)·u_g + 2ω_g (V_s − V_g)·(k × u_g) + (X_s − Y_g)·(ε_g k × u_g − ω_g² u_g)
"""

from __future__ import annotations

import math

import numpy as np

from ..model import Mechanism
from ..scene import DriveKind
from ..structure import DrivenGroup
from .generic import GroupEquations, States, _dot
from .. import linalg as la

__all__ = ["DrivenEquations"]


class DrivenEquations(GroupEquations):
    """The driven group's pair equations and the drive's, at drive ``values`` (degrees for a
    coupler, metres for a cylinder; one per position)."""

    def __init__(self, mech: Mechanism, group: DrivenGroup, values: np.ndarray):
        self.mech = mech
        self.links = tuple(group.links)
        self.pairs = tuple(group.pairs)
        self.col = {name: 3 * i for i, name in enumerate(self.links)}
        self.size = mech.size
        if 2 * len(self.pairs) + 1 != 3 * len(self.links):
            raise ValueError("a driven group has 3 equations per link: 2 per pair and the drive's")
        self.drive = d = mech.drive
        self.angular = d.kind == DriveKind.COUPLER
        values = np.asarray(values, dtype=float)
        if self.angular:
            self.target = np.radians(values) - math.radians(d.sketch_value)
        else:
            p = d.guide
            # the anchors' offset along the guide in the sketch, where every pose is the identity
            self.target = values + float(la.dot(p.anchor[p.slider] - p.anchor[p.guide], p.direction))

    def at(self, i: int) -> "DrivenEquations":
        """The same equations at position ``i`` alone (its drive value)."""
        out = object.__new__(DrivenEquations)
        out.__dict__.update(self.__dict__)
        out.target = self.target[i:i + 1]
        return out

    # -- the drive's row -------------------------------------------------------------------
    def _slide(self, states: States):
        """The cylinder's pair, its anchors' world points and the guide's direction u now."""
        p = self.drive.guide
        xs, yg = states[p.slider].point(p.anchor[p.slider]), states[p.guide].point(p.anchor[p.guide])
        return p, xs, yg, states[p.guide].direction(p.direction)

    def residual(self, states: States) -> np.ndarray:
        if self.angular:
            row = states[self.drive.link].theta - self.target
        else:
            _, xs, yg, u = self._slide(states)
            row = _dot(xs - yg, u) - self.target
        return np.column_stack([super().residual(states), row])

    def jacobian(self, states: States) -> np.ndarray:
        a = super().jacobian(states)
        row = np.zeros((a.shape[0], 1, a.shape[2]))
        if self.angular:
            row[:, 0, self.col[self.drive.link] + 2] = 1.0
        else:
            p, xs, yg, u = self._slide(states)
            self._offset_jacobian(row[:, 0], p, states, xs, yg, u)
        return np.concatenate([a, row], axis=1)

    def velocity_terms(self, states: States) -> np.ndarray:
        return np.column_stack([super().velocity_terms(states), self._drive_rate(states, 1) - self.drive.speed])

    def acceleration_terms(self, states: States) -> np.ndarray:
        return np.column_stack([super().acceleration_terms(states), self._drive_rate(states, 2) - self.drive.rate])

    def _drive_rate(self, states: States, order: int) -> np.ndarray:
        """θ̇_c, θ̈_c of the coupler, or σ̇, σ̈ of the stroke, with the group's unknown rates of
        that order at zero (N,)."""
        if self.angular:
            link = states[self.drive.link]
            return link.omega if order == 1 else link.epsilon
        p, xs, yg, u = self._slide(states)
        return self._offset_rate(p, states, xs, yg, u, order)

    def _figure_rows(self, states: States, a: np.ndarray):
        """As for a group (the reduced figure's rows), with the drive: a coupler turned by it, or
        the cylinder's stroke given (its offset along the guide is the drive's row: no sliding
        rate is unknown)."""
        rows, ties, sliding = super()._figure_rows(states, a)
        if self.angular:
            ties.append((self.drive.link, None))
        else:
            sliding = [(r, p) for r, p in sliding if p != self.drive.guide]
        return rows, ties, sliding

    def _scale_rows(self, m: np.ndarray) -> np.ndarray:
        """As for a group, and a coupler's angle row ×size too (every entry dimensionless)."""
        m = super()._scale_rows(m)
        if self.angular:
            m[:, -1] *= self.size
        return m


"""The value types of a velocity or acceleration plan, in plan millimetres (pole at the
origin, y up): images (:class:`PlanPoint`), vectors tagged with their quantity
(:class:`PlanVector`), construction lines and the :class:`Plan` that holds them.

Plain data: imports nothing of the package; must not import kinematics or the plan
constructions that fill these types.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["PlanPoint", "PlanVector", "ConstructionLine", "Plan", "EXTENSION_MM", "MIN_DRAWN_MM"]

#: How far a construction line runs beyond the points it passes through, mm.
EXTENSION_MM = 12.0
#: Vectors shorter than this are not drawn (their value is zero to drawing precision), mm.
MIN_DRAWN_MM = 1e-6


@dataclass(frozen=True)
class PlanPoint:
    """An image on a plan: label (``b``, ``a3``, ``n_BA``, ``k_A3A2``) and position (mm)."""

    label: str
    xy: tuple[float, float]


@dataclass(frozen=True)
class PlanVector:
    """A drawn vector: ``quantity`` tag, tail and head (mm), exact magnitude ``value`` (SI)."""

    quantity: str
    tail: tuple[float, float]
    head: tuple[float, float]
    value: float
    kind: str  # absolute, relative, normal, tangential, coriolis, sliding

    @property
    def length(self) -> float:
        return float(np.hypot(self.head[0] - self.tail[0], self.head[1] - self.tail[1]))


@dataclass(frozen=True)
class ConstructionLine:
    """A line of known direction through a known image: its two end points (mm), and the
    tag of the vector that must lie on it."""

    start: tuple[float, float]
    end: tuple[float, float]
    quantity: str
    group: str


@dataclass(frozen=True)
class Plan:
    """One plan at one position: ``kind`` is ``velocity`` or ``acceleration``."""

    kind: str
    mu: float
    pole: str
    points: tuple[PlanPoint, ...]
    vectors: tuple[PlanVector, ...]
    lines: tuple[ConstructionLine, ...]
    similar: tuple[tuple[str, tuple[str, ...]], ...]  # link → labels of its images (similarity)

    def point(self, label: str) -> tuple[float, float]:
        return next(p.xy for p in self.points if p.label == label)

"""The value types of a group drawn alone (:mod:`.group_diagram`): its forces and couples, the
arms, the moment equations' terms and the equations, and the whole diagram. Diagram mm (x right,
y up), forces in N, moments in N·m counter-clockwise positive, arms in m.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["DiagramForce", "DiagramCouple", "Arm", "MomentTerm", "MomentEquation", "GroupDiagram"]


@dataclass(frozen=True)
class DiagramForce:
    """A force drawn on the diagram: ``quantity`` its tag (``G:2``, ``F:in:2``, ``R:4-2`` a
    known reaction, ``Rt:1-2``/``Rn:1-2`` the components of an outer pin's reaction, ``R:0-5``
    an outer reaction drawn whole, ``F:bal``), the ``link`` it acts on, ``at`` its point of
    application (mm) and that point's name, ``vector`` (N), ``kind`` (gravity, inertia,
    external, reaction, reaction_n, reaction_t, balance) and whether it was ``known`` before
    this group was solved."""

    quantity: str
    link: str
    at: tuple[float, float]
    point: str
    vector: tuple[float, float]
    kind: str
    known: bool

    @property
    def value(self) -> float:
        return float(math.hypot(*self.vector))

    @property
    def direction(self) -> tuple[float, float]:
        v = self.value
        return (self.vector[0] / v, self.vector[1] / v) if v > 0 else (1.0, 0.0)


@dataclass(frozen=True)
class DiagramCouple:
    """A couple on a link: ``quantity`` (``M:in:2``, ``M:ext:4``, ``M:bal``), ``value`` N·m
    (counter-clockwise positive), drawn round ``at`` (mm, the link's centre or pivot)."""

    quantity: str
    link: str
    at: tuple[float, float]
    value: float
    known: bool


@dataclass(frozen=True)
class Arm:
    """The arm of ``force`` about ``centre`` (named ``about``): from the centre to ``foot``, the
    foot of the perpendicular on the force's line, mm; ``value`` its length in m."""

    force: str
    about: str
    centre: tuple[float, float]
    foot: tuple[float, float]
    value: float
    number: int


@dataclass(frozen=True)
class MomentTerm:
    """One term of a moment equation: ``quantity``, its magnitude ``value`` (N, or N·m for a
    couple), its ``arm`` (m; None for a couple) and ``sign`` (+1 counter-clockwise)."""

    quantity: str
    value: float
    arm: float | None
    sign: float

    @property
    def moment(self) -> float:
        """N·m, counter-clockwise positive."""
        return self.sign * self.value * (1.0 if self.arm is None else self.arm)


@dataclass(frozen=True)
class MomentEquation:
    """ΣM_centre(links) = 0 solved for ``unknown``: ``terms`` the known moments, the unknown's
    ``arm`` (m; None for a couple) and ``sign`` (the moment's sense of the drawn, positive,
    unknown); ``value`` = −Σ terms / (sign · arm), > 0 in the drawn sense."""

    unknown: str
    links: tuple[str, ...]
    about: str
    centre: tuple[float, float]
    terms: tuple[MomentTerm, ...]
    arm: float | None
    sign: float
    value: float

    @property
    def residual(self) -> float:
        """Σ of every moment with the unknown's value, N·m (0 to rounding)."""
        return sum(t.moment for t in self.terms) + self.sign * self.value * (1.0 if self.arm is None else self.arm)


@dataclass(frozen=True)
class GroupDiagram:
    """One group (or the driving link, ``I(0-1)``) drawn alone at ``mu`` (m/mm).

    ``bars``: each link's outline as (link, point names, their mm positions); ``joints`` every
    named point of the group (mm); ``forces``, ``couples``, ``arms``, ``equations`` as above;
    ``special``: points of the construction not on a link (Assur's special point S), mm;
    ``method``: how the reactions are found, one line; ``notes``: what else the sheet says
    (a slider's offset)."""

    group: str
    mu: float
    bars: tuple[tuple[str, tuple[str, ...], tuple[tuple[float, float], ...]], ...]
    joints: tuple[tuple[str, tuple[float, float]], ...]
    forces: tuple[DiagramForce, ...]
    couples: tuple[DiagramCouple, ...]
    arms: tuple[Arm, ...]
    equations: tuple[MomentEquation, ...]
    special: tuple[tuple[str, tuple[float, float]], ...]
    method: str
    notes: tuple[str, ...] = ()

    kind = "group"

    def force(self, quantity: str) -> DiagramForce:
        return next(f for f in self.forces if f.quantity == quantity)

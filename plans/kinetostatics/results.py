"""What the force analysis finds, at N positions: the force polygons' terms (:class:`ForceTerm`,
:class:`GroupForces`), each pair's :class:`Reaction`, the :class:`Balancing` element and the
whole :class:`Forces`. Forces in N, moments in N·m (CCW positive), ``R:i-j`` the force of
link i on link j.

Value types only; must not import the solver or anything above the kinetostatics.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

import numpy as np

from .loads import Couple, Load

__all__ = ["ForceTerm", "GroupForces", "Reaction", "Balancing", "Forces"]


@dataclass(frozen=True, eq=False)
class ForceTerm:
    """One side of a force polygon: ``vector`` (N, 2) in N. ``quantity``: ``G:3``, ``F:in:2``,
    ``F:ext:B``, ``F:bal``, ``R:0-3`` (the force of link 0 on link 3; ``:n``/``:t`` for the
    normal and tangential components of a class II group's outer revolute pair); ``kind``:
    ``gravity``, ``inertia``, ``external``, ``balance`` or ``reaction``."""

    quantity: str
    vector: np.ndarray
    kind: str


@dataclass(frozen=True, eq=False)
class GroupForces:
    """The force polygon of one group (or of the original mechanism, ``I(0-1)``): ``terms`` in
    the order they are drawn, summing to zero at every position; ``inner``: the reactions of
    its inner pairs (``R:i-j``, the force of i on j), found from one link's polygon."""

    group: str
    links: tuple[str, ...]
    terms: tuple[ForceTerm, ...]
    inner: tuple[ForceTerm, ...]


@dataclass(frozen=True, eq=False)
class Reaction:
    """The reaction of one pair: ``force`` (N, 2) N, of link ``first`` on link ``second``.

    A revolute pair (``kind`` ``"R"``): ``point`` is the pin (N, 2) m. A prismatic pair
    (``"P"``): ``u`` the guide's unit direction (N, 2); ``origin`` (N, 2) the reference point,
    the pair's point ``at`` projected on the guide; ``moment`` (N,) N·m the reaction's moment
    about ``origin``; ``offset`` (N,) m = moment / (force · ν), where along u from ``origin``
    the reaction acts, and ``point`` = origin + offset·u — both NaN where the reaction is
    (nearly) zero and acts nowhere in particular."""

    key: str
    first: str
    second: str
    kind: str
    force: np.ndarray
    point: np.ndarray
    at: str | None = None
    u: np.ndarray | None = None
    origin: np.ndarray | None = None
    moment: np.ndarray | None = None
    offset: np.ndarray | None = None


@dataclass(frozen=True, eq=False)
class Balancing:
    """The balancing element on the driving link ``link``: ``kind`` ``"moment"`` (``value``
    (N,) N·m, CCW positive), ``"force"`` (``value`` (N,) N along ``direction`` (N, 2) at
    ``point`` (N, 2), the link's point ``at``) or ``"actuator"`` (a cylinder's force
    ``value`` along the guide ``direction`` on the rod ``link`` at ``point``, and its opposite
    on the cylinder ``reacts_on``). ``vector`` = value·direction (N, 2) for a force."""

    link: str
    kind: str
    value: np.ndarray
    at: str | None = None
    direction: np.ndarray | None = None
    point: np.ndarray | None = None
    reacts_on: str | None = None

    @property
    def vector(self) -> np.ndarray | None:
        return None if self.direction is None else self.value[:, None] * self.direction


@dataclass(frozen=True, eq=False)
class Forces:
    """The force analysis at N positions.

    ``loads``/``couples``: every load the lever takes (gravity, inertia, external and the
    balancing element, ``F:bal``/``M:bal``), each with its link and point of application;
    ``reactions``: key ``"i-j"`` → :class:`Reaction` for every pair (the frame's too);
    ``groups``: the force polygons in the order solved (farthest group first, the original
    mechanism last); ``balance``: the balancing element from the group-by-group solution;
    ``power``: the same element's value from the power balance alone,
    −(Σ F·v + Σ M·ω)/(its velocity factor) over every other load, None when the drive stands;
    ``power_residual``: |Σ F·v + Σ M·ω| over every load and the group-by-group balance, over
    the largest single |term| (0 when all are 0; None when the drive stands)."""

    loads: tuple[Load, ...]
    couples: tuple[Couple, ...]
    reactions: Mapping[str, Reaction]
    groups: tuple[GroupForces, ...]
    balance: Balancing
    power: np.ndarray | None
    power_residual: np.ndarray | None

    def on_link(self, link: str) -> tuple[list[Load], list[Couple]]:
        """Every force and couple acting on ``link``: its loads, the balancing element, and
        each pair's reaction (a prismatic one as its force at the reference point plus its
        moment about it)."""
        loads = [l for l in self.loads if l.link == link]
        couples = [c for c in self.couples if c.link == link]
        for r in self.reactions.values():
            for who, sign, tag in ((r.second, 1.0, f"R:{r.first}-{r.second}"), (r.first, -1.0, f"R:{r.second}-{r.first}")):
                if who != link:
                    continue
                at = r.point if r.kind == "R" else r.origin
                loads.append(Load(tag, link, at, sign * r.force, "reaction"))
                if r.kind == "P":
                    couples.append(Couple(tag, link, sign * r.moment, "reaction"))
        return loads, couples

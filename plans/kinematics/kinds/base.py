"""The protocol every kind of group's solver follows, and the small values it hands back.

A solver is made for one structural group of one mechanism (``Solver(mech, group)``) and
holds no results: the links' states it reads and sets are passed in. The solver of a chain
(:mod:`plans.kinematics.solve`) and the search for the nearest singular position
(:mod:`plans.kinematics.singular`) call these methods and never ask what kind a group is.
This module imports nothing of plans but the states.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping, Protocol

import numpy as np

from ..state import LinkState
from ..walk import Walk

__all__ = ["GroupSolver", "Rates", "Seed", "States"]

States = Mapping[str, LinkState]


@dataclass(frozen=True)
class Rates:
    """What a group's velocity step found: its ``condition`` figure at every position (±1 well
    conditioned, 0 singular; its sign changes across a singular position) and the solver's own
    ``solve`` (what its velocity and acceleration solves share: a Jacobian, the sliding speeds)."""

    condition: np.ndarray
    solve: Any


@dataclass(frozen=True)
class Seed:
    """Where a group's local continuation stands at one drive value: its ``pose`` vector
    ((x_o, y_o, θ) per link, m and rad; empty for a group in closed form) and, for a group in
    closed form, the assembly ``branch`` it keeps."""

    pose: np.ndarray
    branch: int = 0


class GroupSolver(Protocol):
    """One kind of Assur group (or the original mechanism of a drive inside the chain).

    ``closed_form``: its positions at any drive value need no walk (class II): a chain of such
    groups may be solved directly at the requested values (then it also offers ``branches``).
    """

    group: Any
    closed_form: bool

    def reason(self) -> str:
        """Why the group has no unique solution at a singular position (for messages)."""

    def positions(self, states: dict[str, LinkState], walk: Walk) -> None:
        """Poses of the group's links along ``walk`` (set in ``states``, which holds the known
        links there), keeping the sketch's assembly branch; an AssemblyError where the group
        falls apart or passes a singular position before a requested value."""

    def condition(self, states: States, values: np.ndarray) -> np.ndarray:
        """The condition figure at the poses in ``states`` (drive ``values``) (N,)."""

    def rates(self, states: dict[str, LinkState], values: np.ndarray, pre: dict | None = None) -> Rates:
        """The velocity step's condition figure (and whatever both rate solves share)."""

    def velocities(self, states: dict[str, LinkState], rates: Rates) -> None:
        """ω and v of the group's links, set in ``states`` (after :meth:`rates`, once the
        position is known to be clear of a singular one)."""

    def accelerations(self, states: dict[str, LinkState], rates: Rates) -> None:
        """ε and a of the group's links, set in ``states`` (velocities set)."""

    def local_start(self, states: dict[str, LinkState], here: States, x: float) -> Seed:
        """Start a local continuation from the solved poses ``here`` (one position, drive value
        ``x``): the group's links set in ``states`` as there."""

    def local_pose(self, states: dict[str, LinkState], x: float, seed: Seed) -> Seed | None:
        """Poses at drive value ``x`` near ``seed`` (set in ``states``), or None when the
        group does not assemble there."""

    def special_points(self, states: States) -> tuple | None:
        """The group's special points (class III: Assur's points S1, S2, S3), None when it has none."""

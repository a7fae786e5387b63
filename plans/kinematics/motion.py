"""Motion: the solved mechanism as users read it, with everything the kinematics knows.

It sits on top of the modules it aggregates: the raw solution (:class:`~plans.kinematics.state.Solution`,
the links' states) is solved by :mod:`plans.kinematics.solve`; the instantaneous centres, the
class III groups' special points and second solution, the sliding of prismatic pairs, the links'
angles and the distance to a singular position are computed by the modules below, each of which
reads a Solution and imports nothing above it. Constructions and drawing compute none of it.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .centres import Centres, centre_from, centres
from .singular import distance
from .sliders import Sliding, link_angles, sliding
from .special import GroupPoints, TriadSolution, disagreements, group_points, triads
from ..scene import DriveKind
from .state import Solution

__all__ = ["Motion"]


@dataclass(frozen=True)
class Motion(Solution):
    """The solved mechanism at N drive positions (see :class:`~plans.kinematics.state.Solution`
    for its fields and the rigid-body reads).

    Motion carries everything the kinematics knows, so that constructions and drawing compute
    none of it: the values derived from the links' states (``sliding``, ``angles``,
    ``centres``, the class III groups' ``special_points``, their second solution ``triads``
    and its cross-check ``triad_disagreement``) are computed once, when first read.
    """

    def drive_rates(self, i: int) -> tuple[float, float]:
        """The crank's ω1, ε1 (rad/s, rad/s², CCW) at position i: its state's, which differ from
        position to position at the true speed of a machine (see
        :func:`plans.dynamics.at_true_speed`); the given ω, ε for other drives or before they
        are solved."""
        d = self.mechanism.drive
        s = self.links.get(d.link)
        if d.kind != DriveKind.ROTARY or s is None or s.omega is None:
            return float(d.speed), float(d.rate)
        return float(s.omega[i]), float(s.epsilon[i]) if s.epsilon is not None else float(d.rate)

    @cached_property
    def special_points(self) -> dict[str, GroupPoints]:
        """Every class III group's axes and special points, with the velocities and accelerations
        the plans read at them (group name → :class:`plans.kinematics.special.GroupPoints`)."""
        return group_points(self)

    @cached_property
    def triads(self) -> dict[str, TriadSolution]:
        """Every class III group solved a second, independent way, through its special points
        (group name → :class:`plans.kinematics.special.TriadSolution`; positions only at order 0)."""
        return {g.name: t for g, t in triads(self).items()}

    @cached_property
    def triad_disagreement(self) -> dict[str, float]:
        """The cross-check of :attr:`triads` with this motion: per group, the largest relative
        difference of ω, v (ε, a) (:func:`plans.kinematics.special.disagreement`)."""
        return disagreements(self)

    @cached_property
    def centres(self) -> Centres:
        """Every absolute and relative instantaneous centre (:class:`plans.kinematics.centres.Centres`,
        m); needs velocities (ValueError at order 0)."""
        return centres(self)

    def centre_from(self, link: str, point: str, i: int) -> np.ndarray | None:
        """The absolute centre of ``link`` at position i (m) found from its point ``point``'s
        velocity, X + k × v_X / ω; None when ω = 0 (:func:`plans.kinematics.centres.centre_from`)."""
        return centre_from(self, link, point, i)

    @cached_property
    def angles(self) -> dict[str, np.ndarray]:
        """Each link's angle at every position, degrees CCW from +x in [0, 360)
        (:func:`plans.kinematics.sliders.link_angles`)."""
        return link_angles(self)

    def singular_distance(self, group: str, i: int) -> float | None:
        """How far (degrees or metres of drive) position i is from ``group``'s nearest singular
        position, None when none is found (:func:`plans.kinematics.singular.distance`)."""
        return distance(self, group, i)

    @cached_property
    def sliding(self) -> dict[str, Sliding]:
        """Every prismatic pair's sliding (:func:`plans.kinematics.sliders.sliding`), computed
        once for all the plans and the report that read it."""
        return sliding(self)

"""The enlarged detail of Zhukovsky's lever round its pole, when loaded images crowd the pole.

The lever is the velocity plan turned, scaled by its largest velocity: the images of slow
points (and the forces applied at them, and their arms) may gather within a few millimetres of
the pole while one image lies far off. :func:`lever_detail` finds such a crowd (two or more
distinct places of images carrying a force within :data:`~plans.constructions.detail.NEAR_MM`
of the pole, the pole itself one of them when a force is applied there) and draws the region
round the pole × k beside the lever, as the plans' pole detail does
(:mod:`plans.constructions.detail`: same k, same free place): the turned images there at k ×
their distances from the pole (μV/k), the forces applied at them that are short on the lever
(under :data:`LEGIBLE_MM`) at a force scale μF′ of their own (the largest
:data:`DETAIL_FORCE_MM` long) and their arms k·h from the detail's pole. The detail is a
:class:`~plans.constructions.zhukovsky.Lever` of its own (its ``mu_v`` = μV/k, ``mu`` = μF′,
its pole the detail's pole; each force's ``moment`` = ± F·k·h, about that pole); it holds
only some of the lever's forces, so its moments need not sum to zero. Geometry in plan millimetres; it draws nothing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from .detail import AT_POLE_MM, NEAR_MM, PoleRegion, _factor, _reach, _region
from .plan_values import ConstructionLine, Plan, PlanPoint, PlanVector
from .scales import standard_scale
from .zhukovsky import Lever

__all__ = ["LeverDetail", "lever_crowd", "lever_detail", "DETAIL_FORCE_MM"]

#: Wanted drawn length of the largest force in the detail, mm.
DETAIL_FORCE_MM = (10.0, 16.0)
#: A force drawn on the lever at least this long is legible there: it is not drawn again in the
#: detail (its name, arm and the arm's label stay on the lever), mm.
LEGIBLE_MM = 10.0
#: The detail's frame runs this far beyond its farthest image: the longest arrow and its letter, mm.
ARROW_ROOM_MM = DETAIL_FORCE_MM[1] + 4.0


@dataclass(frozen=True)
class LeverDetail(PoleRegion):
    """The detail ×``k`` of a lever's pole region (:class:`~.detail.PoleRegion`): ``lever``
    the enlarged lever (its images, segments and forces inside the region, at μV/k and μF′)."""

    lever: Lever | None = None

    @property
    def quantities(self) -> frozenset[str]:
        """The forces drawn again in the detail."""
        return frozenset(f.quantity for f in self.lever.forces)


def lever_crowd(lever: Lever, near: float = NEAR_MM) -> float | None:
    """The largest distance from the pole (mm) of the loaded images crowding it (within
    ``near`` mm, not at it), or None when there is no crowd or the lever as a whole is no
    larger than four times ``near``. A crowd is two or more distinct places, the pole counting
    as one when a force is applied there (its forces' names and arms gather there too)."""
    pole = lever.pole_xy
    places: list[tuple[float, float]] = []
    at_pole = False
    for f in lever.forces:
        d = math.dist(f.point, pole)
        at_pole = at_pole or d <= AT_POLE_MM
        if AT_POLE_MM < d < near and not any(math.dist(f.point, q) < AT_POLE_MM for q in places):
            places.append(f.point)
    extent = max([math.dist(p.xy, pole) for p in lever.points] + [math.dist(f.head, pole) for f in lever.forces])
    if not places or len(places) + at_pole < 2 or extent < 4.0 * near:
        return None
    return max(math.dist(q, pole) for q in places)


def _as_plan(lever: Lever) -> Plan:
    """The lever as a plan for :func:`~plans.constructions.detail._place`: its images, its
    turned segments and, as lines to keep clear of, its forces and arms."""
    vectors = tuple(PlanVector(f"s{k}", a, b, 0.0, "absolute") for k, (a, b) in enumerate(lever.segments))
    lines = tuple(ConstructionLine(f.tail, f.head, f.quantity, "force") for f in lever.forces) + \
        tuple(ConstructionLine(lever.pole_xy, f.foot, f.quantity, "arm") for f in lever.forces if f.arm > 0)
    pole = PlanPoint(lever.pole, lever.pole_xy)
    points = (pole,) + tuple(p for p in lever.points if p.label != lever.pole)
    return Plan("velocity", lever.mu_v, lever.pole, points, vectors, lines, ())


def lever_detail(lever: Lever, *, sizes: tuple[tuple[float, float], ...], room: float,
                 caption: Callable[[int, float], tuple[float, float]], near: float = NEAR_MM) -> LeverDetail | None:
    """The detail of ``lever``'s pole region (see the module docstring), or None when no crowd
    or no free place. ``sizes``: the boxes (width, height, mm) the lever and its detail may
    fill together; ``room``: the letters' room round each (mm); ``caption(k, μF′)``: the
    caption's width and height, mm."""
    radius = lever_crowd(lever, near)
    if radius is None:
        return None
    inside = [f for f in lever.forces if _redrawn(f, lever, radius)]
    if not inside:
        return None
    fmax = max(f.value for f in inside)
    mu = standard_scale(fmax, window=DETAIL_FORCE_MM) if fmax > 0 else lever.mu
    found = _region(_as_plan(lever), _factor(radius), radius, sizes=sizes, room=room,
                    caption=lambda k: caption(k, mu), reach=ARROW_ROOM_MM)
    if found is None:
        return None
    return LeverDetail(**found.fields(), lever=_enlarged(lever, found.k, radius, found.middle, found.centre, mu))


def _redrawn(f, lever: Lever, radius: float) -> bool:
    """Whether force ``f`` is drawn again in the detail: applied inside the region, and short
    on the lever."""
    return math.dist(f.point, lever.pole_xy) <= _reach(radius) and f.length < LEGIBLE_MM


def _enlarged(lever: Lever, k: int, radius: float, middle, centre, mu: float) -> Lever:
    """The images, segments and forces of ``lever`` within the region, × k about ``middle``
    (which goes to ``centre``), the forces at ``mu``, arms and moments about the new pole."""
    pole = lever.pole_xy

    def inside(xy) -> bool:
        return math.dist(xy, pole) <= _reach(radius)

    def s(xy) -> tuple[float, float]:
        return (centre[0] + k * (float(xy[0]) - middle[0]), centre[1] + k * (float(xy[1]) - middle[1]))

    new_pole = s(pole)
    forces = []
    for f in lever.forces:
        if not _redrawn(f, lever, radius):
            continue
        p = s(f.point)
        u = np.asarray(f.direction, dtype=float)
        head = (p[0] + f.force[0] / mu, p[1] + f.force[1] / mu)
        forces.append(replace(f, point=p, tail=p, head=head, arm=k * f.arm, moment=k * f.moment,
                              foot=s(f.foot) if f.arm > 0 else new_pole, direction=(float(u[0]), float(u[1]))))
    points = tuple(PlanPoint(q.label, s(q.xy)) for q in lever.points if inside(q.xy))
    segments = tuple((s(a), s(b)) for a, b in lever.segments if inside(a) and inside(b))
    return replace(lever, mu_v=lever.mu_v / k, mu=mu, pole_xy=new_pole, points=points, segments=segments,
                   forces=tuple(forces))

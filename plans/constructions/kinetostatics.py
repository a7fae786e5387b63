"""The force analysis laid out at one position: each group's force polygon and Zhukovsky's
lever, from a solved :class:`~plans.kinematics.Motion` and its
:class:`~plans.kinetostatics.Forces` (read, never computed here).

The lever takes every load at the velocity image of its point (``Motion.velocity_at`` ÷ μV,
the same images as the velocity plan's), every couple at the images of two points of its
link, and the balancing element of the force analysis (a moment on the driving link between
the images of its pivot and tip, or a force at the image of its point along its direction).
A cylinder's balancing force pair (an actuator: F on the rod, −F on the cylinder, at one
point) has, about the pole, the moment of F alone at the difference of the two images — the
image of the rod's velocity relative to the cylinder — and is applied there.
"""

from __future__ import annotations

import math
from typing import Mapping

import numpy as np

from ..kinematics import Motion
from ..kinetostatics import Forces
from .force_polygon import FORCE_PLAN_MAX_MM
from .forces import (BalanceForce, BalanceMoment, ForcePlan, ForceTerm, Lever, LeverCouple, LeverLoad, force_plan,
                     zhukovsky_lever)
from .plans import Plan
from .scales import fitting_scale
from .. import linalg as la

__all__ = ["group_force_plans", "BESIDE_DIAGRAM_MM", "lever", "lever_value", "lever_scale", "lever_plan_scale", "LEVER_PLAN_MM"]


def _pt(v) -> tuple[float, float]:
    return (float(v[0]) + 0.0, float(v[1]) + 0.0)


def group_force_plans(forces: Forces, i: int, *, limit: float = FORCE_PLAN_MAX_MM,
                      first_normal: Mapping[str, str] | None = None) -> tuple[ForcePlan, ...]:
    """Every group's force polygon at position ``i``, farthest group first (the order solved);
    a group with no force at all (no load on it or beyond it) has no polygon. ``limit``: the
    largest extent of a polygon, mm (:data:`BESIDE_DIAGRAM_MM` where it shares its panel with
    the group drawn alone). A reaction's components are of kind ``reaction_n``/``reaction_t``
    (the normal ones get their direction lines). ``first_normal``: group → the normal component
    found first (a triad's, from the moments about Assur's special point), laid before the two
    that close the polygon."""
    out = []
    for g in forces.groups:
        terms = [ForceTerm(t.quantity, _pt(t.vector[i]), _component_kind(t.quantity, t.kind)) for t in g.terms]
        if not any(t.vector != (0.0, 0.0) for t in terms):
            continue
        first = (first_normal or {}).get(g.group)
        if first is not None:
            lead = [t for t in terms if t.quantity == first]
            rest = [t for t in terms if t.quantity != first]
            at = next((k for k, t in enumerate(rest) if t.quantity.endswith(":n")), len(rest))
            terms = rest[:at] + lead + rest[at:]
        inner = [ForceTerm(t.quantity, _pt(t.vector[i]), t.kind) for t in (g.inner or ())]
        # an inner reaction is drawn as the diagonal it equals, where the forces on its link are
        # consecutive sides (a class II group's); a class III/IV polygon lists them by kind
        two = sum(1 for t in terms if t.vector != (0.0, 0.0)) <= 2      # R21 + R01 = 0: a line, drawn small
        out.append(force_plan(g.group, terms, internal=inner, unmatched="skip",
                              limit=min(limit, TWO_FORCE_MM) if two else limit))
    return tuple(out)


def _component_kind(quantity: str, kind: str) -> str:
    if kind == "reaction" and quantity.startswith("R:") and quantity.endswith((":n", ":t")):
        return "reaction_" + quantity[-1]
    return kind


def _ends(motion: Motion, link: str, i: int) -> tuple[np.ndarray, np.ndarray]:
    """Two world points (m) of ``link`` at position i: its first two points, or its one point
    and the point a tenth of the mechanism's size along +x from it (a block)."""
    pts = motion.mechanism.links[link].points
    a = motion.position(pts[0], link)[i]
    b = motion.position(pts[1], link)[i] if len(pts) > 1 else a + np.array([0.1 * motion.mechanism.size, 0.0])
    return a, b


def _end_names(motion: Motion, link: str) -> tuple[str, str]:
    """The printed names of a couple's two ends: the link's points (lower case, as images are
    named), so that the two forces of a couple never share a name even where their images
    coincide (a coupler momentarily translating)."""
    pts = motion.mechanism.links[link].points
    first = pts[0].lower()
    return first, (pts[1].lower() if len(pts) > 1 else first + "′")


#: Largest extent of a force polygon drawn beside its group's diagram, mm: the diagram, its
#: written equations, the polygon and the table share an A3 panel, and the driving link's
#: panel goes beside the last group's.
BESIDE_DIAGRAM_MM = 130.0
#: Largest extent of a polygon of two forces (equal and opposite), mm.
TWO_FORCE_MM = 70.0

#: A load (or moment, over the mechanism's size) below this fraction of the largest is zero.
ZERO_REL = 1e-12

LEVER_PLAN_MM = 150.0
"""Largest extent of the velocity plan a lever is drawn on, mm: the lever's plan is drawn to the
finest series scale μV that keeps it within this (its forces, arms and labels need room)."""


def lever_plan_scale(plan: Plan) -> float:
    """The μV of the lever's plan: the finest series scale drawing ``plan``'s images within
    :data:`LEVER_PLAN_MM` (never coarser than the velocity plan's own)."""
    xy = np.array([p.xy for p in plan.points])
    span = float(np.max(np.ptp(xy, axis=0))) * plan.mu
    return min(plan.mu, fitting_scale(span, LEVER_PLAN_MM)) if span > 0.0 else plan.mu


def lever(motion: Motion, forces: Forces, i: int, plan: Plan) -> Lever:
    """Zhukovsky's lever at position ``i`` on the velocity plan ``plan`` of that position."""
    b = forces.balance
    mu = plan.mu

    def image(link: str, xy) -> tuple[float, float]:
        return _pt(motion.velocity_at(link, np.asarray(xy, float), i) / mu)

    # a load or moment below ZERO_REL of the largest (a rounding zero, e.g. I·ε at a dead
    # centre) has no line of action to speak of: it is left off the lever
    given = [l for l in forces.loads if l.kind != "balance"]
    biggest = max([float(la.norm(l.force[i])) for l in given] + [0.0])
    size = motion.mechanism.size
    biggest = max([biggest * size] + [abs(float(c.moment[i])) for c in forces.couples if c.kind != "balance"]) / size
    loads = [LeverLoad(l.quantity, image(l.link, l.point[i]), _pt(l.force[i]))
             for l in given if float(la.norm(l.force[i])) > ZERO_REL * biggest]
    couples = []
    for c in forces.couples:
        if c.kind == "balance" or abs(float(c.moment[i])) <= ZERO_REL * biggest * size:
            continue
        a, e = _ends(motion, c.link, i)
        names = _end_names(motion, c.link)
        couples.append(LeverCouple(c.quantity, float(c.moment[i]), (image(c.link, a), image(c.link, e)),
                                   float(la.norm(e - a)), _pt(e - a), labels=names))
    if b.kind == "moment":
        d = motion.mechanism.drive
        a, e = motion.position(d.pivot, d.link)[i], motion.position(d.tip, d.link)[i]
        balance = BalanceMoment((image(d.link, a), image(d.link, e)), float(la.norm(e - a)), _pt(e - a))
    elif b.kind == "actuator":      # F on the rod, −F on the cylinder: F at the relative image
        rod, cyl = image(b.link, b.point[i]), image(b.reacts_on, b.point[i])
        pole = plan.point(plan.pole)
        balance = BalanceForce((rod[0] - cyl[0] + pole[0], rod[1] - cyl[1] + pole[1]), _pt(b.direction[i]),
                               label=f"{b.at}{b.link}{b.reacts_on}")
    else:
        balance = BalanceForce(image(b.link, b.point[i]), _pt(b.direction[i]))
    return zhukovsky_lever(plan, loads, balance, couples=couples)


def lever_scale(result: Lever) -> float:
    """The scale of the loads' moments on the lever ``result``, in the balancing element's unit
    (N·m for a moment, N for a force): Σ|F_i| · max|p x| / |k| — every force on the lever (a
    couple as its two forces M/l) times the largest distance of a point of the turned plan from
    its pole, over the lever moment k of a unit balancing element. For a balancing moment that
    is Σ|F_i|·v_max/ω1 (v_max the largest velocity on the plan); for a force, Σ|F_i|·v_max over
    the velocity of its point along its line. The velocities are exact to rounding relative to
    v_max, so two figures of the balancing element differ by rounding relative to this, however
    small the element itself is (an extreme position, where the loaded point is at rest).
    0 with no load on the lever."""
    pole = result.pole_xy
    size = max([math.dist(p.xy, pole) for p in result.points] + [0.0])
    reach = sum(f.value for f in result.forces if f.kind != "balance") * size
    return reach / abs(result.unit_moment) if result.unit_moment else 0.0


def lever_value(result: Lever, forces: Forces, i: int) -> dict:
    """The lever's balancing element in the report's form: ``{"moment": M}`` (N·m, CCW
    positive) or ``{"force": [Fx, Fy], "value": F}`` (N along the balancing direction)."""
    if forces.balance.kind == "moment":
        return {"moment": float(result.result)}
    return {"force": [float(c) for c in result.result * forces.balance.direction[i]], "value": float(result.result)}

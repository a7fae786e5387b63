"""Class III groups on the plans: one route through one special point S (the meeting point
of two rods' axes), chosen at each position as the best conditioned of the three.

The axes, special points and known acceleration terms are the motion's; must not import the
plan assembly (:mod:`.plans`).
"""

from __future__ import annotations

from itertools import count

import numpy as np

from ..kinematics import special
from ..structure import ComplexGroup
from .plan_builder import PRIME, _Builder
from .plan_vectors import _rigid
from .relations import Relation
from .. import linalg as la


def _special(b: _Builder, g: ComplexGroup, sym: str) -> None:
    """A class III group along one route, as with ruler and set square: the special point S
    (meeting point of the axes of rods i and j, a point of the base link) from the known
    images of the two rods' outer pairs along the two directions ⊥ the axes; the third rod's
    pin k from s (⊥ S–k) and its rod's own line (drawn with the group's relations); then the
    pins of rods i and j from k (⊥ k–pin), each with its rod's own line (its axis passes
    through S, so s gives it no second direction). The route is the one whose line pairs are
    the farthest from parallel (:func:`_route`); the base triangle is closed by
    :func:`_close_figures`. The axes, special points and known acceleration terms are the
    motion's (:attr:`~plans.kinematics.Motion.special_points`)."""
    motion, i = b.motion, b.i
    mech = motion.mechanism
    found = motion.special_points[g.name]
    ax = found.axes
    route = _route(ax, found.points, i)
    p = found.points[route]
    # S1, S2, S3 — primed if the scene has points of those names
    s_name = p.name + PRIME * next(k for k in count() if p.name + PRIME * k not in mech.sketch)
    b.extra[s_name] = p.position[i]
    s_img = b.image(s_name, g.base)
    for r in p.rods:
        rod = ax[r].rod
        pin = rod.inner.point if rod.form == "PR" else rod.outer.point
        k_lab, k_name = b.label(pin, ax[r].known), b.name(pin, ax[r].known)    # printed, in quantities
        k_img = b.image(pin, ax[r].known)
        e = ax[r].normal[i]
        q = f"{sym}:{s_name}/{k_name}"
        total = b.quantity(s_name, g.base) - b.quantity(pin, ax[r].known)
        if sym == "v":
            b.vector(q, k_img, s_img, float(la.norm(total)), "relative")
            b.line(k_img, e, [s_img], q, f"{g.name}:{s_name}")
            continue
        c = found.known[(route, r)][i] - b.quantity(pin, ax[r].known)      # normal (and Coriolis) components, known
        n_xy = b.put(("n", s_name, k_name), f"n_{s_name}{k_lab}", np.add(k_img, c / b.mu))
        b.vector(f"{q}:n", k_img, n_xy, float(la.norm(c)), "normal")
        b.vector(f"{q}:t", n_xy, s_img, float(la.norm(total - c)), "tangential")
        b.line(n_xy, e, [s_img], f"{q}:t", f"{g.name}:{s_name}")
    third = next(r for r in range(3) if r not in p.rods)
    pins = [_base_point(x) for x in ax]
    _rigid(b, Relation("rigid", g.base, pins[third], s_name, group=g.name,
                       lines=f"{g.name}:{b.label(pins[third], g.base)}"), sym)
    for r in p.rods:
        _rigid(b, Relation("rigid", g.base, pins[r], pins[third], group=g.name,
                           lines=f"{g.name}:{b.label(pins[r], g.base)}"), sym)


def _base_point(ax: special.Axis) -> str:
    """The base link's point on a rod's axis whose image the rod's own line finds: the inner
    pin (R–R, P–R), or the point of the base under the outer pin (R–P)."""
    rod = ax.rod
    return rod.inner.point if rod.inner.kind == "R" else rod.outer.point


def _route(ax: tuple[special.Axis, ...], pts: tuple[special.SpecialPoint, ...], i: int) -> int:
    """Index of the special point to draw from at position i: each route meets four pairs of
    lines (s; the third pin from s; the two other pins from it), the route whose worst pair is
    the farthest from parallel (largest smallest |sin|) is drawn."""
    def sin(u: np.ndarray, d: np.ndarray) -> float:   # |sin| between a segment u and a unit direction d
        n = float(la.norm(u))
        return abs(float(u[0] * d[1] - u[1] * d[0])) / n if n > 0.0 else 0.0

    n = i
    scores = []
    for p in pts:
        i, j = p.rods
        k = next(r for r in range(3) if r not in p.rods)
        s, pk = p.position[n], ax[k].pin[n]
        scores.append(min(abs(float(p.sin[n])), sin(pk - s, ax[k].direction[n]),
                          sin(ax[i].pin[n] - pk, ax[i].direction[n]), sin(ax[j].pin[n] - pk, ax[j].direction[n])))
    return int(np.argmax(scores))

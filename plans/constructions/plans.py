"""Velocity and acceleration plans as geometry in plan millimetres (pole at the origin, y up).

The image of a point X is v_X/μV (a_X/μa). Each vector of the plan is a
:class:`PlanVector` tagged with its quantity:

- ``v:X``, ``a:X`` — absolute velocity / acceleration of scene point X (from the pole);
- ``v:X/Y`` — velocity of X relative to Y, both on one link (⊥ XY);
- ``a:X/Y:n`` — normal component ω²·XY, from y towards n, directed X → Y;
- ``a:X/Y:t`` — tangential component ε·XY, from n to x, ⊥ XY;
- ``a:X/Y`` — the whole relative acceleration |a_X − a_Y|, from y to x: drawn for every
  rigid relation of the plan beside its components (as the textbook draws a→b beside
  a→n_BA→b), for the similarity images of extra points, and for the sides of similar
  figures; left out where the absolute ``a:X`` draws that very segment (y at the pole: Y
  fixed, or its acceleration zero now), where one component is zero (the other one is the
  whole), and relative to a special point S (no side of the link);
- ``v:P3/P2`` — velocity of the point P of guide link 3 relative to the coincident point
  of slider link 2 (∥ guide); ``a:P3/P2:cor`` the Coriolis component 2·ω × v_rel (to
  point k), ``a:P3/P2:r`` the relative sliding acceleration (∥ guide, from k).

A point name followed by a link name (``A3``) is the point of that link now at X.

How the plans are built (:func:`_plan`, one :class:`_Builder` per plan): the relations of
:func:`relations`, group by group, each drawn as its vector(s) and the construction line of
the direction that defines an image (a group's two lines meet at the image they find);
then the class III groups' special-point route (:func:`_special`); the absolute vectors;
then the sides still missing of every link's similar figure (:func:`_close_figures`),
so the images of a link with three or more points always form a closed polygon of vectors
on both plans; last, each segment is kept once (:meth:`_Builder.finish`): no quantity is
drawn twice, and no relative vector retraces an absolute one, either way (a point
momentarily at rest has its image at the pole; the vector into it is the absolute one
reversed). No vector ends at the image of a fixed point.

- **Class II** groups: their pairs' relations (rigid, sliding with Coriolis).
- **Class III** groups, *one* route through one special point S (the meeting point of the
  axes of rods i and j; the best conditioned of the three): s from the two directions ⊥
  those axes through the rods' known images; the third rod's pin k from s (⊥ S–k) and its
  rod's own line; the pins of rods i and j from k (⊥ k–pin) and their rods' own lines; each
  pin's two lines form the group ``III(…):B``. The other routes (the other special points)
  are not drawn: the whole group is solved a second way, numerically, as a cross-check
  (:attr:`plans.kinematics.Motion.triad_disagreement`).
- **Class IV** groups: each link with an outer pair O gives its other pins relative to O, and
  each link without one gives its pin on the far side relative to the pin nearer the frame;
  every relation gets its construction line (group ``IV(…):X`` per image x) and, on the
  acceleration plan, n and τ components and the total, like a class II rigid relation. No
  relation ends at a fixed point (one from the frame pivot starts at the pole, along the
  absolute vector, like the four-bar's ``v:B/C``), and no quantity is drawn twice.

**Labels.** Images of scene points are their lower-case names (``b``, ``a3``); the pole is
``p`` or ``π``; special points ``s1``. Ends of components are ``n_XY`` (normal) and
``k_XY`` (Coriolis), printed as the letter n or k with the subscript XY. Images of scene
points win: when any image of the plan is printed with the letter n (a point N, or a point
named ``n_…``), every normal component's end is written ``n′_XY`` instead (``n″`` if ``n′``
is taken too, and so on), and likewise ``k′_XY`` for the Coriolis ends in a scene with a
point K, so a printed letter never means both a point's image and a component's end. Images
are keyed by identity (:meth:`_Builder.put`), and a label repeating another gets a prime.

The value types are in :mod:`.plan_values`, the builder and labels in :mod:`.plan_builder`,
the relations in :mod:`.relations`, the vectors of each relation in :mod:`.plan_vectors`,
the class III route in :mod:`.special_route`, Koshel's plan in :mod:`.uncertain`; this
module assembles the plans and keeps every name importable from here. Must not import
drawing, checking or anything above the constructions.
"""

from __future__ import annotations

from ..kinematics import Motion, special
from ..scene import FRAME
# every name importable from this module before the split stays importable from here
from .plan_builder import COMPONENT_ENDS, PRIME, _Builder, _at_pole, _label, _same
from .plan_values import EXTENSION_MM, MIN_DRAWN_MM, ConstructionLine, Plan, PlanPoint, PlanVector
from .plan_vectors import _close_figures, _rigid, _slide, _solved_before
from .relations import Relation, _complex_relations, _driven_relations, relations
from .special_route import _base_point, _route, _special
from .uncertain import AT_REST, UNCERTAIN_MM, uncertain_plan
from .. import linalg as la

__all__ = ["PlanPoint", "PlanVector", "ConstructionLine", "Plan", "Relation", "relations",
           "velocity_plan", "acceleration_plan", "uncertain_plan", "EXTENSION_MM", "UNCERTAIN_MM"]


def velocity_plan(motion: Motion, i: int, mu_v: float) -> Plan:
    """The velocity plan at position ``i`` in scale ``mu_v`` ((m/s)/mm)."""
    return _plan(motion, i, mu_v, "velocity")


def acceleration_plan(motion: Motion, i: int, mu_a: float) -> Plan:
    """The acceleration plan at position ``i`` in scale ``mu_a`` ((m/s²)/mm)."""
    return _plan(motion, i, mu_a, "acceleration")


def _plan(motion: Motion, i: int, mu: float, kind: str) -> Plan:
    b = _Builder(motion, i, mu, kind)
    mech = motion.mechanism
    sym = "v" if kind == "velocity" else "a"
    pole = b.put(("pole",), "p" if kind == "velocity" else "π", (0.0, 0.0))
    for rel in relations(motion):
        if rel.kind == "rigid":
            _rigid(b, rel, sym)
        else:
            _slide(b, rel, sym, pole)
    for g in special.triad_groups(motion.structure):
        _special(b, g, sym)
    for name in mech.sketch:  # absolute vectors of every moving scene point
        link = motion.carrier(name)
        if link == FRAME:
            continue
        head = b.image(name, link)
        b.vector(f"{sym}:{name}", pole, head, float(la.norm(b.quantity(name, link))), "absolute")
    _close_figures(b, sym)
    b.finish()
    points, final = b.plan_points()
    similar = tuple((link, tuple(final[b.image_key(p, link)] for p in mech.links[link].points))
                    for link in mech.moving if len(mech.links[link].points) >= 3)
    return Plan(kind=kind, mu=mu, pole=final[("pole",)], points=points,
                vectors=tuple(b.vectors), lines=tuple(b.lines), similar=similar)

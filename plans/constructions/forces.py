"""Kinetostatics as geometry in paper millimetres (y up): force plans of groups and
Zhukovsky's lever, from plain values at one position.

Nothing here computes forces of a mechanism: the forces arrive as numbers (newtons), found
by the force analysis; this module lays them out to a force scale μF (N/mm) from the
standard series and returns frozen values that the drawing package turns into SVG.

**Quantity tags** (the ``data-quantity`` of the drawn vectors): ``G:3`` gravity of link 3,
``F:in:2`` inertia force of link 2, ``F:ext:B`` an external force at B, ``R:0-3`` the
reaction of link 0 on link 3 with its components ``R:0-3:n`` (along the link) and ``R:0-3:t``
(⊥ the link), ``F:bal`` the balancing force; moments ``M:2``, ``M:bal`` (never a side of a
polygon; on the lever a moment is a couple of forces ``F:M:2:a``, ``F:M:2:b`` at two images).

**Force plan** (:func:`force_plan`): the group's forces head to tail in the order of its
vector equation, from the start point ``a``; the vertices are lettered a, b, c, … in turn and
the last force ends at ``a`` again (the forces sum to zero: the polygon closes). When both
components of a reaction are sides next to each other, the whole reaction is drawn too, from
the first one's tail to the second one's head (R = Rⁿ + Rᵗ), and the line of each normal
component's direction is drawn through it (where two such lines meet, the polygon closes, as
the graphical solution finds it). Reactions between the group's own links (``internal``) are
drawn as the diagonals they are: R_32 closes the forces on link 2 alone.

**Zhukovsky's lever** (:func:`zhukovsky_lever`): the velocity plan turned by 90° *clockwise*
about its pole p; each force applied, parallel to itself, at the turned image of its point;
a moment M on a link replaced by the couple M / l_AB of forces ⊥ AB at A and B (on the
lever: at the turned images a and b, for ab ∥ AB there). The moment of a force F at the turned
image r′ of a point about the pole is (r′ − p) × F = (r − p)·F (r the unturned image, the
turn being clockwise), that is F·v / μV: the lever's equilibrium Σ M_p = 0 is the power
balance Σ F·v + Σ M·ω = 0, whence the balancing force (or moment).

The force plans are built in :mod:`.force_polygon`, the lever in :mod:`.zhukovsky`; this
module keeps every name importable from here. Must not import kinematics, kinetostatics,
drawing or anything above the constructions.
"""

from __future__ import annotations

from .force_polygon import (CLOSURE_REL, FORCE_PLAN_MAX_MM, FORCE_REFERENCE_MM, KINDS, SHORT_SIDE_MM, ZERO_REL,
                            ForceDetail, ForcePlan, ForceTerm, ForceVector, _check_terms, _letters, _pt, _totals, _vec,
                            component_of, force_details, force_plan, force_scale)
from .zhukovsky import (LEVER_FORCE_MM, PERPENDICULAR_REL, SENSE, BalanceForce, BalanceMoment, Lever, LeverCouple,
                        LeverForce, LeverLoad, _couple_direction, _cross, _fallback, _label_of, _turn, _unit,
                        zhukovsky_lever)

__all__ = ["ForceTerm", "ForceVector", "ForcePlan", "force_plan", "KINDS", "CLOSURE_REL", "FORCE_REFERENCE_MM",
           "FORCE_PLAN_MAX_MM", "LeverLoad", "LeverCouple", "BalanceForce", "BalanceMoment", "LeverForce", "Lever",
           "zhukovsky_lever", "LEVER_FORCE_MM", "SENSE", "component_of", "ForceDetail", "force_details",
           "force_scale", "SHORT_SIDE_MM"]

"""Measuring drawings: every tagged vector of an SVG, and every construction with shapely.

``inspect_svg`` reads an SVG back (ElementTree) and checks, plan by plan (a ``<g>`` with
``data-mu``), what the drawing claims:

1. **length** — each ``<line data-quantity>`` measured in millimetres × the plan's
   ``data-mu`` equals ``data-value`` within ``mu · 2√2 · precision + 1e-9 · value`` (two end
   points, each rounded by at most ``precision`` per coordinate);
2. **direction** — the drawn direction ``(x2 − x1, y2 − y1)`` agrees with
   ``data-direction`` (degrees, SVG paper frame: x right, y down, tail → head). The exact
   vector is ``e = (value/μ)·(cos θ, sin θ)`` mm; two rounded ends move the drawn vector by at
   most ``r = 2√2 · precision`` mm, so the angle between drawn and exact may reach
   ``asin(r/|e|)`` ≈ ``2√2 · precision / |e|`` (+ 1e-9 rad): short vectors get a looser
   angular tolerance, and a vector shorter than ``r`` has no measurable direction;
3. **closure** — the vector equations close graphically. Each vector's ends are points
   (images) named twice: by the writer's labels ``data-from``/``data-to`` and by the
   quantity's name — ``v:X`` runs from the pole to x; ``v:X/Y`` (``a:X/Y``, ``r:X/Y``) from
   y to x; ``a:X/Y:n`` from y to n_XY and ``a:X/Y:t`` from n_XY to x; ``a:X/Y:cor`` from y to
   k_XY and ``a:X/Y:r`` from k_XY to x. Ends named alike (by either name) form one point,
   and all its ends must coincide within ``2√2 · precision`` — so ``p→a`` plus ``a→b`` ends
   where ``p→b`` ends. A name of another form adds no equation (never a failure); each
   plan's number of equations checked is reported (:attr:`SvgReport.equations`);
4. **the file itself** — the user unit is the millimetre (``width``/``height`` in mm equal
   to the ``viewBox``, origin 0 0); no ``transform`` (attribute or CSS) on a tagged line
   or any element above it, whose ancestors are ``<g>`` and the root ``<svg>`` only;
   ``data-mu`` positive and finite; ``data-value`` finite and ≥ 0; every ``<line>`` of a
   plan either a tagged vector or a construction line (``data-construction``).

**Precision.** The tolerance never comes from the file. ``plans check`` measures against
:data:`WRITER_PRECISION`, the rounding of plans' own writer (``Style().precision``); a
library caller that wrote with another :class:`~plans.drawing.style.Style` passes its
``precision``, and with ``precision=None`` it is the rounding of the coordinates actually
written (``0.5 · 10^-D``, D the most decimals of any vector coordinate). A root
``data-precision`` looser than that precision, or not a positive number, is a failure.

**Sheets.** Each plan's ``<g>`` states how many vectors its writer drew
(``data-vectors``); the tagged lines found must be that many. A file whose only plan group is
the scheme (``data-plan="scheme"``) has nothing to measure: it is reported as a scheme and is
not a failure; nor is a plan drawn with no vector (``data-vectors="0"``: the pole alone — a
mechanism at rest, or a construction not drawn at that position, as its subtitle says). Any
other file without a tagged vector — a plan whose tags were removed, or an SVG not written by
plans — fails ("no tagged vectors: not a plan written by plans"). A centres sheet's measured
segments ``r:X/Pj`` run from the centre Pj to the point X and are checked like vectors.
**Kinetostatics.** A force plan (``data-plan="force"``, μ = μF in N/mm) is measured like
any plan (length × μF = the force in N, direction, ends named alike by their vertex labels
coincide — so a whole reaction ends where its two components do, and a reaction between the
group's links joins the vertices it must); besides, its sides (``data-role="side"``) must
sum to zero: drawn, within ``n · 2√2 · precision`` mm for n sides, and as recorded (value ×
direction), within :data:`FORCE_CLOSURE_REL` of Σ values. Zhukovsky's lever
(``data-plan="lever"``, μ = μF, the pole's paper position in ``data-pole``): every force is
measured as a vector; its arm about the pole — the distance from the pole to the line
through its drawn tail in its recorded direction — must equal its ``data-h`` within
``2√2 · precision`` (two rounded points); each drawn arm (``data-construction="arm"``,
``data-arm`` = the force) must start at the pole, end on that line and be that long; and the
moments ± F·h with the drawn arms must sum to zero, Σ M_p = 0, within Σ F · 2√2 · precision
(+ 1e-9 relative). Each of these is a :class:`Check`; a failed one is also a problem.

A group with ``data-plan="bound"`` holds vectors drawn at their points of application on a
scheme (Koshel's V_S1, V_S2 drawn from S1, S2 in the plan's scale): each is measured for
length and direction, but its ends are no plan images, so it adds no closure equation.

The package: :mod:`.report` (what is found), :mod:`.reading` (reading tagged vectors back),
:mod:`.svg_checks` (the checks of a file) and :mod:`.plan_geometry` (shapely checks of a
constructed plan). Each imports only those before it; nothing here imports the pipeline or
anything above it.
"""

from __future__ import annotations

from .plan_geometry import GEOMETRY_TOL_MM, check_plan, similarity_ratio
from .report import Check, Closure, Measurement, SvgReport
from .svg_checks import (BOUND, EMPTY, FORCE, FORCE_CLOSURE_REL, LEVER, MIN_ARM_MM, SCHEME, WRITER_PRECISION,
                         check_svg, inspect_svg)

__all__ = ["Measurement", "Closure", "Check", "SvgReport", "inspect_svg", "check_svg", "check_plan", "GEOMETRY_TOL_MM",
           "WRITER_PRECISION", "similarity_ratio", "FORCE_CLOSURE_REL", "FORCE", "LEVER", "MIN_ARM_MM", "SCHEME",
           "BOUND", "EMPTY"]

"""The layout of a sheet measured from its SVG text alone.

:func:`measure_layout` reads an SVG sheet the way a reader of the paper would see it, without
the bookkeeping of the code that drew it: it parses every ``<text>`` (position, anchor, font
size and style, ``<tspan>`` runs with their ``dx``/``dy`` shifts), sizes each with the metrics
of the sheet's font (:mod:`plans.drawing.text`: advance widths, ascent and descent), and every
inked shape (``<line>``, ``<path>``, ``<polygon>``, ``<polyline>``, ``<rect>``, ``<circle>``,
``<ellipse>``: a stroke is its centreline buffered by half its stroke width, a dark fill is its
area; a pale fill, white or the plates' tint, is paper). It counts six faults:

- ``overlapping_labels`` — two text boxes whose interiors meet (touching edges is fine);
- ``labels_crossing_lines`` — a text box meeting inked geometry; a leader
  (``<line class="leader">``) never crosses the label its end point touches, and the texts of
  the title block are not measured against the title block's own cells or the frame (they
  must stay inside the frame instead);
- ``labels_off_sheet`` — a text box not inside the frame's inner area (``<rect class="frame">``
  less half its stroke; the paper when there is no frame), or, for any text but the title
  block's, not inside the drawing area (the frame's inner area less the title block's rect);
- ``long_heads`` — an arrowhead (``<path class="head" data-for=ID>``) longer, tip to the middle
  of its base, than the vector ``<line id=ID>`` it ends (or, for a drawn arc ``<path id=ID>``,
  the arc and on to the tip); or a tagged vector (``<line data-quantity>`` in a plan group)
  shorter than :data:`NO_HEAD_MM` that has a head;
- ``beyond_a3`` — a sheet larger than A3 (297 mm × 420 mm, either way round);
- ``overlapping_vertex_letters`` — two vertex letters of one force plan (``<g
  data-plan="force">``: texts of the group reading exactly a vertex name its tagged vectors
  join by ``data-from``/``data-to``) whose boxes overlap, or which name vertices nearer than
  :data:`VERTEX_SPOT_MM` (they sit on one spot: no reader can tell which letter is which).

A label crossing one element counts once, however many strokes of it (hatching) it meets.
White space is read as SVG 1.1 renders it: a run of spaces is one space. A head whose
``data-for`` names no ``<line>`` or ``<path>`` (and no line ends at its tip) cannot be
measured: it is listed in :attr:`LayoutReport.unmatched_heads`, not counted.

The package: :mod:`.parsing` (small SVG parsers), :mod:`.sheet` (what a sheet holds: texts,
ink, vectors, heads, frame, title block) and :mod:`.measure` (the six counts). Each imports
only those before it; nothing here imports a module that draws.
"""

from __future__ import annotations

from .measure import (A3_MM, FORMATS, LEADER_TOUCH_MM, NO_HEAD_MM, ROUNDING_MM, SHOWN, SIZE_TOLERANCE_MM,
                      VERTEX_SPOT_MM, LayoutReport, measure_layout)
from .parsing import PALE

__all__ = ["LayoutReport", "measure_layout", "A3_MM", "NO_HEAD_MM", "SHOWN", "SIZE_TOLERANCE_MM", "FORMATS",
           "ROUNDING_MM", "LEADER_TOUCH_MM", "PALE", "VERTEX_SPOT_MM"]

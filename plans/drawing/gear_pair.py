"""The involute pair's sheets (``-meshing``, ``-cutting``) from their paper geometry
(:mod:`plans.constructions.gear_pair`): the wheels' outlines filled light, their circles, the
line of action and its active part, the cutter, and the measured segments in ``<g
data-plan="bound">`` groups (``data-mu`` = 1/k mm per paper mm; the specific-sliding
diagram's ordinates λ1, λ2 at B1, B2 in a group of their own, ``data-mu`` = μλ per paper mm),
so that ``plans check`` measures them; the meshing sheet's group also states
``data-contact-ratio``, which ``plans check`` compares with the drawn B1B2 over the drawn p_b,
and ``data-pitch-point`` (P on the paper), which must lie on both working profiles drawn
(``<path data-working-profile="1">``, ``"2"``) within drawing precision.
"""

from __future__ import annotations

import math

from ..constructions.gear_pair import PairSheet
from .canvas import fmt
from .sheet import FORMATS, TitleBlock, new_sheet, note_lines
from .style import Style
from .svg import Heading, _tag
from .text import wrap

__all__ = ["draw_pair_sheet"]

_FILL = {"wheel": "#dfe8f3", "wheel2": "#e4efdf", "cutter": "#f2e3c9"}
_NAMES = {"B1B2": "B_{1}B_{2}", "pb": "p_b", "aw": "a_w", "xm": "x·m", "s1": "s̄_1", "s2": "s̄_2", "sa1": "s̄_{a1}",
          "sa2": "s̄_{a2}", "ra1": "r_{a1}", "ra2": "r_{a2}", "rb1": "r_{b1}", "rb2": "r_{b2}", "p": "p", "h": "h"}


def draw_pair_sheet(s: PairSheet, heading: Heading, *, ident: str, style: Style = Style(),
                    notes: tuple[str, ...] = (), scales: str = "", contact_ratio: float | None = None) -> str:
    """SVG text of a pair sheet (see the module)."""
    area = FORMATS[2].area
    rows = sum(len(wrap(line, area.x1 - area.x0 - 6.0, style.small_text)) for line in notes)
    x0, y0, x1, y1 = s.bounds()
    box = (x0 - 12.0, y0 - 12.0 - 4.0 * rows, x1 + 12.0, y1 + 12.0)
    dwg, canvas = new_sheet(FORMATS[2], box, ident=ident, style=style,
                            block=TitleBlock(heading.mechanism, heading.sheet, heading.position, scales))
    thin, vec = fmt(style.thin, 3), fmt(style.vector, 3)
    bodies = dwg.add(dwg.g(id=f"{ident}-bodies", stroke=style.colour, stroke_width=vec))
    for name, pts in s.outlines:
        fill = _FILL["cutter" if name.startswith("cutter") else "wheel2" if name.startswith("wheel2") else "wheel"]
        canvas.polygon(bodies, [tuple(p) for p in pts], filled=True, width=style.vector, fill=fill,
                       id=f"{ident}-{name}")
    lines = dwg.add(dwg.g(id=f"{ident}-lines", fill="none", stroke=style.colour))
    for name, kind, pts in s.curves:
        attrs = {"stroke_width": thin}
        if kind == "dash":
            attrs["stroke_dasharray"] = "3 1.5"
        elif kind == "axis":
            attrs["stroke_dasharray"] = "8 1.5 1 1.5"
        elif kind in ("thick", "thickdash", "arc"):
            attrs["stroke_width"] = fmt(style.link, 3)
            attrs["stroke"] = style.component_colour if kind == "arc" else style.vector_colour
            if kind == "thickdash":
                attrs["stroke_dasharray"] = "4 1.5"
        heavy = kind in ("thick", "thickdash", "arc")
        el = canvas.polyline(lines, [tuple(p) for p in pts], width=style.link if heavy else style.thin,
                             id=f"{ident}-{name}", **attrs)
        if name.startswith("working-profile"):
            el.attribs["data-working-profile"] = name.removeprefix("working-profile")
    for group, mu in (("detail", 1.0 / s.k), ("overview", 1.0 / s.k0 if s.k0 else 0.0), ("sliding", s.mu_sliding)):
        tags = [t for t in s.tags if t.group == group]
        if not tags:
            continue
        g = dwg.g(id=f"{ident}-{group}", stroke=style.component_colour, stroke_width=fmt(style.link, 3))
        g.attribs["data-mu"] = repr(mu)
        g.attribs["data-plan"] = "bound"
        g.attribs["data-vectors"] = str(len(tags))
        if group == "detail" and contact_ratio is not None:
            g.attribs["data-contact-ratio"] = repr(contact_ratio)
        pitch = next((xy for name, xy in s.points if name == "P"), None)
        if group == "detail" and any(n.startswith("working-profile") for n, _, _ in s.curves) and pitch is not None:
            g.attribs["data-pitch-point"] = ",".join(canvas.xy(pitch))
        for t in tags:
            el = canvas.line(g, t.a, t.b, width=style.link, id=f"{ident}-{t.quantity}")
            _tag(el, canvas, t.quantity, t.value, t.a, t.b, *t.ends)
            if group == "sliding":
                continue                     # its curves are labelled λ1, λ2 (the ordinates at B1, B2 measured)
            mid = (0.5 * (t.a[0] + t.b[0]), 0.5 * (t.a[1] + t.b[1]))
            text = _NAMES.get(t.quantity, t.quantity)
            if s.dimensions:                 # a dimension line: arrows at both ends and its value
                for end, other, side in ((t.b, t.a, "b"), (t.a, t.b, "a")):
                    h = canvas.head(g, other, end, min(style.arrow_length, 0.3 * math.dist(t.a, t.b)),
                                    fill=style.component_colour, stroke="none", id=f"{ident}-{t.quantity}-h{side}")
                    h.attribs["class"] = "head"
                    h.attribs["data-for"] = f"{ident}-{t.quantity}"
                text = f"{text} = {t.value:.4g} mm"
            canvas.label(g, mid, text, size=style.text, ident=f"{ident}-{t.quantity}-l", fill=style.component_colour)
        dwg.add(g)
    marks = dwg.add(dwg.g(id=f"{ident}-points", fill=style.colour, stroke="none"))
    for name, xy in s.points:
        canvas.circle(marks, xy, 0.6, filled=True, id=f"{ident}-pt-{name}")
        canvas.label(marks, xy, name, size=style.text, ident=f"{ident}-pn-{name}", near=0.7)
    for text, xy, prefer in s.labels:
        canvas.label(marks, xy, text, size=style.text, prefer=prefer, ident=f"{ident}-lb-{text}")
    if notes:
        note_lines(canvas, dwg.add(dwg.g(id=f"{ident}-notes")), notes, style)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))
    return dwg.tostring()

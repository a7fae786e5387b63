"""The kinematic diagrams sheet: three aligned graphs s(t), v(t), a(t) of the output link.

Each graph has its value axis with ticks and numbers, the time axis (the zero line) with the
positions' ordinates numbered 0 … N below the graph, the exact curve (solid), its values at
the positions (dots), and the graphical differentiation by chords (dashed red polyline with
dots at the instants where the chord method gives its values). A time axis in seconds is
drawn below the last graph. Every graph's ``<g>`` states its scales and origin:
``data-mu`` (value per mm), ``data-mu-t`` (s/mm), ``data-origin`` (paper x, y of t = 0,
value 0); each dot carries ``data-value`` (SI) and ``data-t`` (s), so that a reader
measures y × μ = value and x × μt = t from the SVG alone.
"""

from __future__ import annotations

from ..constructions.diagrams import Diagrams, Graph
from .canvas import Canvas, fmt
from .marks import arrow
from .sheet import FORMATS, TitleBlock, new_sheet, note_lines
from .style import Style
from .svg import Heading, _tag
from .text import significant
from .positions import width_of

__all__ = ["draw_diagrams", "draw_graph", "time_axis", "LEFT_MM", "RIGHT_MM"]

#: Room left of the value axes (numbers, names) and right of the time axes, mm.
LEFT_MM = 24.0
RIGHT_MM = 14.0
#: Room below the last graph for the time axis, and for the notes, mm.
TIME_AXIS_MM = 16.0
NOTES_MM = 14.0


def draw_diagrams(d: Diagrams, heading: Heading, *, ident: str, style: Style = Style(),
                  notes: tuple[str, ...] = ()) -> str:
    """SVG text of the diagrams sheet (see the module)."""
    last = d.graphs[-1]
    bottom = last.origin[1] + last.low - TIME_AXIS_MM - NOTES_MM
    top = d.graphs[0].origin[1] + d.graphs[0].high + 8.0
    box = (-LEFT_MM, bottom, d.length + RIGHT_MM, top)
    scales = f"μ_t = {d.mu_t:g} s/mm, μ_φ = {d.mu_phi:.4g} rad/mm; " + ", ".join(
        f"μ_{g.quantity} = {g.mu:g} {g.unit}/mm" for g in d.graphs)
    dwg, canvas = new_sheet(FORMATS[2], box, ident=ident, style=style,
                            block=TitleBlock(heading.mechanism, heading.sheet, heading.position, scales))
    for k, g in enumerate(d.graphs):
        draw_graph(dwg, canvas, g, f"{ident}-{g.quantity}", style, mu_x=d.mu_t, length=d.length)
    time_axis(dwg, canvas, d.length, d.time_ticks, last, ident, style)
    if notes:
        note_lines(canvas, dwg.add(dwg.g(id=f"{ident}-notes")), notes, style)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))
    return dwg.tostring()


def draw_graph(dwg, canvas: Canvas, g: Graph, ident: str, style: Style, *, mu_x: float, length: float,
               abscissa: str = "t", numbered: bool = True) -> None:
    """One graph (see the module) against ``abscissa`` ("t" in s, or "φ" in rad) at ``mu_x`` per
    mm over ``length`` mm; its group says ``data-mu-t`` (or ``data-mu-phi``) and each dot
    ``data-t`` (``data-phi``)."""
    attr = "t" if abscissa == "t" else "phi"
    ox, oy = g.origin
    grp = dwg.g(id=ident, stroke=style.colour, fill="none", stroke_linecap="round")
    grp.attribs["data-diagram"] = g.quantity
    grp.attribs["data-scale"] = repr(g.mu)
    grp.attribs[f"data-mu-{attr}"] = repr(mu_x)
    px, py = canvas.paper(g.origin)
    grp.attribs["data-origin"] = f"{fmt(px, style.decimals)},{fmt(py, style.decimals)}"
    grp.attribs["data-error"] = repr(g.error)
    thin, vec = fmt(style.thin, 3), fmt(style.vector, 3)
    texts = dwg.g(id=f"{ident}-text", fill=style.colour)
    # ordinates at the positions, from the time axis to the curve: measured segments, each
    # tagged as a plan's vector is (length × μ = |exact value|), so that plans check reads them
    ords = dwg.g(id=f"{ident}-ordinates", stroke=style.construction_colour, stroke_width=thin)
    ords.attribs["data-mu"] = repr(g.mu)
    ords.attribs["data-plan"] = "bound"      # drawn at their instants: measured, no plan images to close
    ords.attribs["data-vectors"] = str(len(g.at_positions))
    for k, (x, y, value) in enumerate(g.at_positions):
        el = canvas.line(ords, (x, oy), (x, y), width=style.thin, ink=abs(y - oy) > 0.3, id=f"{ident}-ord{k}")
        _tag(el, canvas, f"{g.quantity}@{k}", abs(value), (x, oy), (x, y) if y != oy else (x, oy + 1.0),
             f"t{k}", f"{g.quantity}{k}")
    grp.add(ords)
    # axes: the value axis with its arrow, the time axis (zero line) with its arrow
    y_top, y_bot = oy + g.high + 6.0, oy + g.low
    axis = canvas.line(grp, (ox, y_bot), (ox, y_top), width=style.vector, stroke_width=vec, id=f"{ident}-yaxis")
    arrow(canvas, grp, (ox, y_bot), (ox, y_top), style.colour, f"{ident}-yhead", style, of=f"{ident}-yaxis")
    x_end = length + 7.0
    canvas.line(grp, (ox, oy), (x_end, oy), width=style.vector, stroke_width=vec, id=f"{ident}-taxis")
    arrow(canvas, grp, (ox, oy), (x_end, oy), style.colour, f"{ident}-thead", style, of=f"{ident}-taxis")
    del axis
    for k, (value, y) in enumerate(g.ticks):
        canvas.line(grp, (ox - 1.5, y), (ox, y), width=style.thin, stroke_width=thin, id=f"{ident}-yt{k}")
        num = significant(value)
        canvas.text(texts, canvas.paper((ox - 2.5 - width_of(num, style.small_text), y - 0.9)), num,
                    size=style.small_text, ident=f"{ident}-ytn{k}")
    name = f"{g.symbol}, {g.unit}"
    canvas.text(texts, canvas.paper((ox - 2.0 - width_of(name, style.text), y_top + 1.5)), name, size=style.text,
                ident=f"{ident}-name")
    canvas.text(texts, canvas.paper((x_end + 1.5, oy - 1.2)), abscissa, size=style.text, italic=True,
                ident=f"{ident}-tname")
    # the position numbers below the graph
    if numbered:
        below = oy + g.low - 4.0
        for k, (x, _, _) in enumerate(g.at_positions):
            canvas.line(grp, (x, oy - 0.8), (x, oy + 0.8), width=style.thin, stroke_width=thin, id=f"{ident}-pt{k}")
            canvas.text(texts, canvas.paper((x - width_of(str(k), style.small_text) / 2, below)), str(k),
                        size=style.small_text, ident=f"{ident}-pn{k}")
    # the exact curve and its values at the positions
    curve = canvas.polyline(grp, g.exact, width=style.vector, stroke_width=vec, id=f"{ident}-exact",
                            stroke=style.vector_colour)
    curve.attribs["data-kind"] = "exact"
    grp.add(_dots(dwg, canvas, g.at_positions, "exact", style.vector_colour, 0.55, f"{ident}-dots", f"{ident}-e",
                  mu_x, attr))
    if g.extra:
        more = canvas.polyline(grp, g.extra, width=style.vector, stroke_width=vec, id=f"{ident}-extra",
                               stroke=style.colour)
        more.attribs["data-kind"] = "exact"
    if g.graphical:
        chords = canvas.polyline(grp, [(x, y) for x, y, _ in g.graphical], width=style.thin, stroke_width=thin,
                                 stroke=style.component_colour, stroke_dasharray="2 1", id=f"{ident}-graphical")
        chords.attribs["data-kind"] = "graphical"
        grp.add(_dots(dwg, canvas, g.graphical, "graphical", style.component_colour, 0.5, f"{ident}-gdots",
                      f"{ident}-g", mu_x, attr))
    grp.add(texts)
    dwg.add(grp)


def time_axis(dwg, canvas: Canvas, length: float, ticks, last: Graph, ident: str, style: Style) -> None:
    """A time axis in seconds below the ``last`` graph, aligned with the graphs' time axes
    (``length`` mm, ``ticks`` (t s, x mm))."""
    y = last.origin[1] + last.low - 9.0
    g = dwg.g(id=f"{ident}-time", stroke=style.colour, fill="none")
    texts = dwg.g(id=f"{ident}-time-text", fill=style.colour)
    x_end = length + 7.0
    canvas.line(g, (0.0, y), (x_end, y), width=style.vector, stroke_width=fmt(style.vector, 3), id=f"{ident}-time-axis")
    arrow(canvas, g, (0.0, y), (x_end, y), style.colour, f"{ident}-time-head", style, of=f"{ident}-time-axis")
    for k, (t, x) in enumerate(ticks):
        canvas.line(g, (x, y), (x, y - 1.5), width=style.thin, stroke_width=fmt(style.thin, 3), id=f"{ident}-tt{k}")
        num = significant(t)
        canvas.text(texts, canvas.paper((x - width_of(num, style.small_text) / 2, y - 4.5)), num,
                    size=style.small_text, ident=f"{ident}-ttn{k}")
    canvas.text(texts, canvas.paper((x_end + 1.5, y - 1.2)), "t, s", size=style.text, ident=f"{ident}-time-name")
    dwg.add(g)
    dwg.add(texts)


def _dots(dwg, canvas: Canvas, points, kind: str, colour: str, radius: float, group: str, prefix: str, mu_x: float,
          attr: str = "t"):
    """A group of dots at ``points`` ((x, y, value) in mm and the value's unit), each tagged with
    its ``kind``, value and abscissa (``data-t`` = x·μt in s, or ``data-phi`` in rad), so that a
    test can read the curve back."""
    g = dwg.g(id=group, fill=colour, stroke="none")
    for k, (x, y, value) in enumerate(points):
        el = canvas.circle(g, (x, y), radius, filled=True, id=f"{prefix}{k}")
        el.attribs["data-kind"] = kind
        el.attribs["data-value"] = repr(value)
        el.attribs[f"data-{attr}"] = repr(x * mu_x)
    return g

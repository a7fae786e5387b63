"""The ``-turning`` sheet (:mod:`plans.constructions.turning`): the turning-moment diagram to scale
with the T_res line and each area between them shaded and labelled with its sign and energy, the
greatest and least speed's angles marked, and the table of energies at the crossings with ΔE_max.

The diagram is a ``<g data-plan="turning" data-mu-t="μT" data-mu-theta="μθ">``: each area a closed
``<path data-area="k" data-value="<J, signed>">``, whose area in mm² × μT × μθ ``plans check``
compares with its value (:mod:`plans.checking_areas`); the ordinates of T at the table's vertices
and at the crossings are measured segments (``data-plan="bound"``, μ = μT).
"""

from __future__ import annotations

from ..constructions.turning import TurningDiagram
from ..dynamics.turning import TurningAnalysis
from .canvas import Canvas, fmt
from .marks import arrow
from .positions import width_of
from .sheet import FORMATS, TitleBlock, new_sheet, note_lines
from .style import Style
from .svg import Heading, _tag
from .text import significant

__all__ = ["draw_turning"]

TEXT_MM = 2.8
LEAD_MM = 4.4
_FILL = {True: "#eef6ea", False: "#fcefed"}     # pale: shading, not ink


def draw_turning(d: TurningDiagram, a: TurningAnalysis, heading: Heading, *, ident: str, style: Style = Style(),
                 notes: tuple[str, ...] = ()) -> str:
    """SVG text of the sheet (see the module)."""
    table_w = 70.0
    box = (-22.0, min(d.low, 0.0) - 16.0 - 4.5 * (len(notes) + 1), d.length + 14.0 + table_w, d.high + 14.0)
    dwg, canvas = new_sheet(FORMATS[2], box, ident=ident, style=style,
                            block=TitleBlock(heading.mechanism, heading.sheet, heading.position,
                                             f"μ_T = {d.mu_t:g} N·m/mm, μ_θ = {d.mu_theta:g} rad/mm"))
    thin, vec = fmt(style.thin, 3), fmt(style.vector, 3)
    g = dwg.g(id=f"{ident}-diagram", stroke=style.colour, fill="none")
    g.attribs["data-plan"] = "turning"
    g.attribs["data-mu-t"] = repr(d.mu_t)
    g.attribs["data-mu-theta"] = repr(d.mu_theta)
    texts = dwg.g(id=f"{ident}-texts", fill=style.colour)
    labels = dwg.g(id=f"{ident}-labels", fill=style.colour)
    for ar in d.areas:
        el = canvas.polyline(g, ar.outline, closed=True, stroke="none", fill=_FILL[ar.energy >= 0.0],
                             id=f"{ident}-area{ar.number}")
        el.attribs["data-area"] = str(ar.number)
        el.attribs["data-value"] = repr(ar.energy)
        sign = "+" if ar.energy >= 0 else "−"
        canvas.label(labels, ar.label_at, f"{sign}A_{{{ar.number}}} = {significant(abs(ar.energy), 5)} J", size=style.small_text + 0.5,
                     prefer=(0.0, 1.0 if ar.energy >= 0 else -1.0), ident=f"{ident}-al{ar.number}", digits=False,
                     near=0.5)
    # axes
    top = d.high + 8.0
    canvas.line(g, (0.0, d.low - 2.0), (0.0, top), width=style.vector, stroke_width=vec, id=f"{ident}-taxis")
    arrow(canvas, g, (0.0, d.low - 2.0), (0.0, top), style.colour, f"{ident}-thead", style, of=f"{ident}-taxis")
    end = d.length + 8.0
    canvas.line(g, (0.0, 0.0), (end, 0.0), width=style.vector, stroke_width=vec, id=f"{ident}-xaxis")
    arrow(canvas, g, (0.0, 0.0), (end, 0.0), style.colour, f"{ident}-xhead", style, of=f"{ident}-xaxis")
    canvas.text(texts, canvas.paper((-2.0 - width_of("T, N·m", style.text), top + 1.5)), "T, N·m", size=style.text,
                ident=f"{ident}-tname")
    canvas.text(texts, canvas.paper((end + 1.5, -1.2)), "θ, °", size=style.text, ident=f"{ident}-xname")
    for k, (v, y) in enumerate(d.t_ticks):
        canvas.line(g, (-1.5, y), (0.0, y), width=style.thin, stroke_width=thin, id=f"{ident}-tt{k}")
        canvas.text(texts, canvas.paper((-2.5 - width_of(significant(v, 5), style.small_text), y - 0.9)), significant(v, 5),
                    size=style.small_text, ident=f"{ident}-ttn{k}")
    below = d.low - 5.0
    for k, (deg, x) in enumerate(d.theta_ticks):
        canvas.line(g, (x, -0.8), (x, 0.8), width=style.thin, stroke_width=thin, id=f"{ident}-xt{k}")
        canvas.text(texts, canvas.paper((x - width_of(significant(deg, 5), style.small_text) / 2, below)), significant(deg, 5),
                    size=style.small_text, ident=f"{ident}-xtn{k}")
    # the curves
    canvas.polyline(g, d.torque, width=style.vector, stroke=style.vector_colour, stroke_width=vec, id=f"{ident}-T")
    canvas.polyline(g, d.resisting, width=style.vector, stroke=style.component_colour, stroke_width=vec,
                    stroke_dasharray=style.dash, id=f"{ident}-Tres")
    canvas.label(labels, d.torque[len(d.torque) // 3], "T", size=style.text, prefer=(0.0, 1.0), ident=f"{ident}-Tl",
                 fill=style.vector_colour)
    canvas.label(labels, d.resisting[-1], "T_{res}", size=style.text, prefer=(1.0, 0.4), ident=f"{ident}-Trl",
                 fill=style.component_colour)
    # the measured ordinates
    ords = dwg.g(id=f"{ident}-ordinates", stroke=style.construction_colour, stroke_width=thin)
    ords.attribs["data-mu"] = repr(d.mu_t)
    ords.attribs["data-plan"] = "bound"
    drawn = [(deg, x, y, v) for deg, x, y, v in d.ordinates if abs(y) > 1e-9]
    ords.attribs["data-vectors"] = str(len(drawn))
    for k, (deg, x, y, v) in enumerate(drawn):
        el = canvas.line(ords, (x, 0.0), (x, y), width=style.thin, id=f"{ident}-ord{k}")
        _tag(el, canvas, f"T@{deg:g}", abs(v), (x, 0.0), (x, y), f"theta{k}", f"T{k}")
    g.add(ords)
    # the speed's extremes
    for which, deg, x in d.extremes:
        canvas.line(g, (x, d.low - 2.0), (x, d.high + 4.0), width=style.thin, stroke=style.construction_colour,
                    stroke_width=thin, stroke_dasharray="4 1.5 1 1.5", id=f"{ident}-w{which}")
        canvas.label(labels, (x, d.high + 4.0), f"ω_{{{which}}} ({significant(deg, 4)}°)", size=style.small_text + 0.5,
                     prefer=(0.0, 1.0), ident=f"{ident}-wl{which}", digits=False)
    g.add(labels)
    dwg.add(g)
    _table(canvas, texts, a, (d.length + 16.0, d.high), ident, style)
    dwg.add(texts)
    if notes:
        note_lines(canvas, dwg.add(dwg.g(id=f"{ident}-notes")), notes, style)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))
    return dwg.tostring()


def _table(canvas: Canvas, texts, a: TurningAnalysis, at: tuple[float, float], ident: str, style: Style) -> None:
    """The energies at 0° and each crossing (E = ∫(T − T_res)dθ from 0°), the greatest and least
    marked, and ΔE_max."""
    x0, y0 = at
    rows = [("θ, °", "E, J", "")] + [("0", "0", "max" if a.energy_max_at == 0.0 else
                                      "min" if a.energy_min_at == 0.0 else "")]
    for c, e in zip(a.crossings, a.energy_at_crossings):
        if c <= 0.0:
            continue
        mark = "max (ω_max)" if c == a.energy_max_at else "min (ω_min)" if c == a.energy_min_at else ""
        rows.append((significant(float(c), 5), significant(float(e), 6), mark))
    rows.append(("ΔE_max", significant(a.energy_fluctuation, 6), "= E_max − E_min"))
    for r, row in enumerate(rows):
        for c, cell in enumerate(row):
            canvas.text(texts, canvas.paper((x0 + (0.0, 18.0, 38.0)[c], y0 - LEAD_MM * r)), cell, size=TEXT_MM,
                        ident=f"{ident}-tab{r}-{c}")

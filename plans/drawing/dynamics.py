"""The dynamics sheets. The steady cycle: M_r, the works A_r and A_d and ΔT against the crank's angle φ (the
graphs of :mod:`.diagrams`, against φ instead of t), and Wittenbauer's energy–mass diagram to
their right, built by projection: its ΔT = 0 level is ΔT(φ)'s and its μT the same, so each
position's ΔT is carried across by a thin dashed line; under it I_r(φ) turned through 90° (I
along x at Wittenbauer's μI from the same I0 — its axis is Wittenbauer's I scale — φ downwards),
each position's I_r carried up by a thin dashed line; with its two tangents and the segment kl
they cut on the ΔT axis. The turned I_r(φ) is a ``<g data-diagram="I" data-turned="90">`` whose
ordinates (from its φ axis to the curve, horizontal) are measured like the other graphs'.

Wittenbauer's ``<g>`` states ``data-mu-i`` (kg·m²/mm), ``data-mu-t`` (J/mm), ``data-i0`` and
``data-origin`` (paper x, y of I = I0, ΔT = 0); kl is a measured segment (``data-plan="bound"``,
length × μT = its energy) and each dot of the curve carries ``data-inertia`` and ``data-energy``.
The start-up: ω(t) and the moments against time, as the kinematic diagrams are drawn.
"""

from __future__ import annotations

import math

from ..constructions.diagrams import Graph
from ..constructions.dynamics import DynamicsDiagrams, StartupDiagrams, Wittenbauer
from .canvas import Canvas, fmt
from .diagrams import LEFT_MM, RIGHT_MM, draw_graph, time_axis
from .marks import arrow
from .positions import width_of
from .sheet import FORMATS, TitleBlock, new_sheet, note_lines
from .style import Style
from .svg import Heading, _tag
from .text import significant, wrap

__all__ = ["draw_dynamics", "draw_startup"]

#: Room between the graphs' right end and Wittenbauer's ΔT axis (its numbers included), mm.
BETWEEN_MM = 34.0
#: Room below the lowest drawing for the position numbers and the I_r scale, mm.
BELOW_MM = 14.0
#: Room for the notes: this much per line, mm.
NOTE_LINE_MM = 4.0


def draw_dynamics(d: DynamicsDiagrams, heading: Heading, *, ident: str, style: Style = Style(),
                  notes: tuple[str, ...] = (), scales: str = "") -> str:
    """SVG text of the dynamics sheet (see the module), ``scales`` for the title block."""
    w = d.wittenbauer
    m, a, t, i = d.graphs
    note_rows = _note_rows(notes, style)
    wx = d.length + RIGHT_MM + BETWEEN_MM            # Wittenbauer's ΔT axis
    wy = t.origin[1]                                 # its ΔT = 0 level: ΔT(φ)'s, projected across
    ys = wy + w.low - 9.0                            # its I scale: the turned I_r(φ)'s I axis
    phi_end = 2.0 * math.pi / d.mu_phi_turned
    bottom = min(t.origin[1] + t.low, ys - phi_end - 8.0) - BELOW_MM - NOTE_LINE_MM * note_rows
    top = max(m.origin[1] + m.high, wy + w.high) + 10.0
    box = (-LEFT_MM, bottom, wx + w.width + RIGHT_MM, top)
    dwg, canvas = new_sheet(FORMATS[2], box, ident=ident, style=style,
                            block=TitleBlock(heading.mechanism, heading.sheet, heading.position, scales))
    for g in (m, a, t):
        draw_graph(dwg, canvas, g, f"{ident}-{g.quantity}", style, mu_x=d.mu_phi, length=d.length, abscissa="φ")
        if g.extra:           # the works; M_r and the constant moment
            names = d.works if g.quantity == "A" else (g.symbol, g.extra_symbol)
            _name_curves(dwg, canvas, g, names, f"{ident}-{g.quantity}", style)
    _wittenbauer(dwg, canvas, w, (wx, wy), f"{ident}-wittenbauer", style)
    _turned_inertia(dwg, canvas, d, (wx, ys), f"{ident}-I", style)
    _projections(dwg, canvas, d, (wx, wy), (wx, ys), f"{ident}-projection", style)
    if notes:
        note_lines(canvas, dwg.add(dwg.g(id=f"{ident}-notes")), notes, style)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))
    return dwg.tostring()


def _note_rows(notes: tuple[str, ...], style: Style) -> int:
    """Rows the notes take, wrapped to the A3 drawing area's width as :func:`note_lines` wraps them."""
    area = FORMATS[2].area
    return sum(len(wrap(line, area.x1 - area.x0 - 6.0, style.small_text)) for line in notes)


def _name_curves(dwg, canvas: Canvas, g: Graph, names: tuple[str, str], ident: str, style: Style) -> None:
    """Name a graph's two curves (``exact`` and ``extra``) where they lie farthest apart, each on
    its own side."""
    group = dwg.add(dwg.g(id=f"{ident}-names", fill=style.colour))
    j = max(range(len(g.exact)), key=lambda k: abs(g.exact[k][1] - g.extra[k][1]))
    up = 1.0 if g.exact[j][1] >= g.extra[j][1] else -1.0
    for pts, name, key, side in ((g.exact, names[0], "a", up), (g.extra, names[1], "b", -up)):
        canvas.label(group, pts[j], name, size=style.text, prefer=(0.3, side), ident=f"{ident}-name-{key}")


def _wittenbauer(dwg, canvas: Canvas, w: Wittenbauer, at: tuple[float, float], ident: str, style: Style) -> None:
    ox, oy = at

    def p(x: float, y: float) -> tuple[float, float]:
        return ox + x, oy + y

    thin, vec = fmt(style.thin, 3), fmt(style.vector, 3)
    grp = dwg.g(id=ident, stroke=style.colour, fill="none", stroke_linecap="round")
    grp.attribs["data-diagram"] = "wittenbauer"
    grp.attribs["data-mu-i"] = repr(w.mu_i)
    grp.attribs["data-mu-t"] = repr(w.mu_t)
    grp.attribs["data-i0"] = repr(w.i0)
    px, py = canvas.paper(p(0.0, 0.0))
    grp.attribs["data-origin"] = f"{fmt(px, style.decimals)},{fmt(py, style.decimals)}"
    texts = dwg.g(id=f"{ident}-text", fill=style.colour)
    labels = dwg.g(id=f"{ident}-labels", fill=style.colour)
    # the ΔT axis at I = I0, and the I axis at ΔT = 0
    y_top = w.high + 6.0
    canvas.line(grp, p(0.0, w.low), p(0.0, y_top), width=style.vector, stroke_width=vec, id=f"{ident}-taxis")
    arrow(canvas, grp, p(0.0, w.low), p(0.0, y_top), style.colour, f"{ident}-thead", style, of=f"{ident}-taxis")
    x_end = w.width + 5.0
    canvas.line(grp, p(0.0, 0.0), p(x_end, 0.0), width=style.vector, stroke_width=vec, id=f"{ident}-iaxis")
    arrow(canvas, grp, p(0.0, 0.0), p(x_end, 0.0), style.colour, f"{ident}-ihead", style, of=f"{ident}-iaxis")
    for k, (value, y) in enumerate(w.t_ticks):
        canvas.line(grp, p(-1.5, y), p(0.0, y), width=style.thin, stroke_width=thin, id=f"{ident}-tt{k}")
        num = significant(value)
        canvas.text(texts, canvas.paper(p(-2.5 - width_of(num, style.small_text), y - 0.9)), num,
                    size=style.small_text, ident=f"{ident}-ttn{k}")
    name = "ΔT, J"
    canvas.text(texts, canvas.paper(p(-2.0 - width_of(name, style.text), y_top + 1.5)), name, size=style.text,
                ident=f"{ident}-tname")
    canvas.text(texts, canvas.paper(p(x_end + 1.5, -1.2)), "I_r", size=style.text, italic=True,
                ident=f"{ident}-iname")
    # the I scale below the diagram
    ys = w.low - 9.0
    canvas.line(grp, p(0.0, ys), p(x_end, ys), width=style.vector, stroke_width=vec, id=f"{ident}-iscale")
    arrow(canvas, grp, p(0.0, ys), p(x_end, ys), style.colour, f"{ident}-iscale-head", style, of=f"{ident}-iscale")
    for k, (value, x) in enumerate(w.i_ticks):
        canvas.line(grp, p(x, ys), p(x, ys - 1.5), width=style.thin, stroke_width=thin, id=f"{ident}-it{k}")
        num = significant(value)
        canvas.text(texts, canvas.paper(p(x - width_of(num, style.small_text) / 2, ys + 1.6)), num,
                    size=style.small_text, ident=f"{ident}-itn{k}")      # above: the turned I_r(φ) hangs below
    canvas.text(texts, canvas.paper(p(x_end + 1.5, ys - 1.2)), "I_r, kg·m²", size=style.text,
                ident=f"{ident}-iscale-name")
    # the energy–mass curve and the positions on it
    curve = canvas.polyline(grp, [p(x, y) for x, y in w.curve], width=style.vector, stroke_width=vec,
                            stroke=style.vector_colour, id=f"{ident}-curve")
    curve.attribs["data-kind"] = "exact"
    dots = dwg.g(id=f"{ident}-dots", fill=style.vector_colour, stroke="none")
    for k, (x, y, inertia, energy) in enumerate(w.at_positions):
        el = canvas.circle(dots, p(x, y), 0.55, filled=True, id=f"{ident}-e{k}")
        el.attribs["data-inertia"] = repr(inertia)
        el.attribs["data-energy"] = repr(energy)
        canvas.label(labels, p(x, y), str(k), size=style.small_text, italic=False, prefer=(-1.0, 1.0),
                     ident=f"{ident}-pn{k}", near=0.6)
    grp.add(dots)
    # the tangents, their touch points, and the segment kl they cut on the ΔT axis
    for tg, letter in zip(w.tangents, "kl"):
        el = canvas.line(grp, p(*tg.start), p(*tg.end), width=style.thin, stroke_width=thin,
                         stroke=style.component_colour, id=f"{ident}-tangent-{tg.which}")
        el.attribs["data-psi"] = repr(tg.psi)
        canvas.circle(grp, p(*tg.touch), 0.7, id=f"{ident}-touch-{tg.which}", stroke=style.component_colour,
                      stroke_width=thin)
        canvas.label(labels, p(*tg.end), f"ψ_{tg.which}", size=style.text, prefer=(1.0, 0.0),
                     ident=f"{ident}-psi-{tg.which}")
        canvas.label(labels, p(*tg.start), letter, size=style.text, prefer=(1.0, 0.3 if letter == "k" else -0.3),
                     ident=f"{ident}-{letter}")
    if w.segment is not None:
        k, l_ = w.tangents[0].start, w.tangents[1].start
        seg = dwg.g(id=f"{ident}-kl", stroke=style.component_colour, stroke_width=fmt(style.link, 3))
        seg.attribs["data-mu"] = repr(w.mu_t)
        seg.attribs["data-plan"] = "bound"
        seg.attribs["data-vectors"] = "1"
        el = canvas.line(seg, p(*l_), p(*k), width=style.link, id=f"{ident}-segment")
        _tag(el, canvas, "kl", abs(w.segment), p(*l_), p(*k), "l", "k")
        grp.add(seg)
    grp.add(texts)
    dwg.add(grp)
    dwg.add(labels)


def _turned_inertia(dwg, canvas: Canvas, d: DynamicsDiagrams, at: tuple[float, float], ident: str,
                    style: Style) -> None:
    """I_r(φ) turned through 90° under Wittenbauer's diagram: its φ axis down from ``at`` (I = I0,
    φ = 0), I along x at Wittenbauer's μI; each position's ordinate (horizontal, φ axis → curve)
    measured, its number beside the φ axis."""
    g, w = d.graphs[3], d.wittenbauer
    ox, oy = at
    mu, mu_phi = w.mu_i, d.mu_phi_turned
    thin, vec = fmt(style.thin, 3), fmt(style.vector, 3)

    def p(inertia: float, phi: float) -> tuple[float, float]:
        return ox + (inertia - w.i0) / mu, oy - phi / mu_phi

    grp = dwg.g(id=ident, stroke=style.colour, fill="none", stroke_linecap="round")
    grp.attribs["data-diagram"] = g.quantity
    grp.attribs["data-turned"] = "90"
    grp.attribs["data-scale"] = repr(mu)
    grp.attribs["data-mu-phi"] = repr(mu_phi)
    px, py = canvas.paper(at)
    grp.attribs["data-origin"] = f"{fmt(px, style.decimals)},{fmt(py, style.decimals)}"
    texts = dwg.g(id=f"{ident}-text", fill=style.colour)
    ords = dwg.g(id=f"{ident}-ordinates", stroke=style.construction_colour, stroke_width=thin)
    ords.attribs["data-mu"] = repr(mu)
    ords.attribs["data-plan"] = "bound"
    ords.attribs["data-vectors"] = str(len(g.at_positions))
    name = "I" if w.i0 == 0.0 else "I-I0"
    for k, (x, _, value) in enumerate(g.at_positions):
        phi = x * d.mu_phi
        a, b = p(w.i0, phi), p(value, phi)
        el = canvas.line(ords, a, b, width=style.thin, ink=abs(b[0] - a[0]) > 0.3, id=f"{ident}-ord{k}")
        _tag(el, canvas, f"{name}@{k}", abs(value - w.i0), a, b if b != a else (a[0] + 1.0, a[1]), f"phi{k}",
             f"{g.quantity}{k}")
        canvas.text(texts, canvas.paper((ox - 2.0 - width_of(str(k), style.small_text), a[1] - 0.9)), str(k),
                    size=style.small_text, ident=f"{ident}-pn{k}")
    grp.add(ords)
    end = (ox, oy - 2.0 * math.pi / mu_phi - 6.0)
    canvas.line(grp, (ox, oy), end, width=style.vector, stroke_width=vec, id=f"{ident}-phiaxis")
    arrow(canvas, grp, (ox, oy), end, style.colour, f"{ident}-phihead", style, of=f"{ident}-phiaxis")
    canvas.text(texts, canvas.paper((ox + 1.5, end[1] + 1.0)), "φ", size=style.text, italic=True,
                ident=f"{ident}-phiname")
    curve = canvas.polyline(grp, [p(w.i0 + (y - g.origin[1]) * mu, (x - g.origin[0]) * d.mu_phi) for x, y in g.exact],
                            width=style.vector, stroke_width=vec, id=f"{ident}-exact", stroke=style.vector_colour)
    curve.attribs["data-kind"] = "exact"
    dots = dwg.g(id=f"{ident}-dots", fill=style.vector_colour, stroke="none")
    for k, (x, _, value) in enumerate(g.at_positions):
        el = canvas.circle(dots, p(value, x * d.mu_phi), 0.55, filled=True, id=f"{ident}-e{k}")
        el.attribs["data-kind"] = "exact"
        el.attribs["data-value"] = repr(value)
        el.attribs["data-phi"] = repr(x * d.mu_phi)
    grp.add(dots)
    grp.add(texts)
    dwg.add(grp)


def _projections(dwg, canvas: Canvas, d: DynamicsDiagrams, witt: tuple[float, float], turned: tuple[float, float],
                 ident: str, style: Style) -> None:
    """The construction of Wittenbauer's curve: from each position's ΔT on ΔT(φ) across, and from
    its I_r on the turned I_r(φ) up, to the point of the curve where the two meet."""
    t, w = d.graphs[2], d.wittenbauer
    g = dwg.add(dwg.g(id=ident, stroke=style.construction_colour, stroke_width=fmt(style.thin, 3), fill="none",
                      stroke_dasharray="1.2 1.2"))
    # each line broken where the axes' numbers are: past the φ axis's end and before Wittenbauer's
    # ΔT numbers; between the I scale's numbers and its line
    stop, resume = d.length + 7.0, witt[0] - 1.5
    for k, ((x, y, _), (xi, _, inertia)) in enumerate(zip(t.at_positions[:-1], d.graphs[3].at_positions[:-1])):
        wxk, wyk, _, _ = w.at_positions[k]
        point = (witt[0] + wxk, witt[1] + wyk)
        if stop > x:
            canvas.line(g, (x, y), (stop, y), width=style.thin, id=f"{ident}-t{k}")
        canvas.line(g, (resume, y), point, width=style.thin, id=f"{ident}-t{k}b")
        below = (turned[0] + (inertia - w.i0) / w.mu_i, turned[1] - xi * d.mu_phi / d.mu_phi_turned)
        if below[1] < turned[1]:
            canvas.line(g, below, (below[0], turned[1]), width=style.thin, id=f"{ident}-i{k}")
        canvas.line(g, (below[0], turned[1] + 5.5), point, width=style.thin, id=f"{ident}-i{k}b")


def draw_startup(d: StartupDiagrams, heading: Heading, *, ident: str, style: Style = Style(),
                 notes: tuple[str, ...] = (), scales: str = "") -> str:
    """SVG text of the start-up sheet: ω(t) with the steady cycle's ω_max and ω_min (dashed),
    and the motor's and the loads' moments at the crank against time."""
    last = d.graphs[-1]
    bottom = last.origin[1] + last.low - 16.0 - NOTE_LINE_MM * _note_rows(notes, style)
    box = (-LEFT_MM, bottom, d.length + RIGHT_MM + 8.0, 10.0)
    dwg, canvas = new_sheet(FORMATS[2], box, ident=ident, style=style,
                            block=TitleBlock(heading.mechanism, heading.sheet, heading.position, scales))
    for g in d.graphs:
        draw_graph(dwg, canvas, g, f"{ident}-{g.quantity}", style, mu_x=d.mu_t, length=d.length, numbered=False)
    if d.steady is not None:
        band = dwg.add(dwg.g(id=f"{ident}-steady", stroke=style.component_colour, fill="none"))
        for y, key in zip(d.steady, ("max", "min")):
            canvas.line(band, (0.0, y), (d.length, y), width=style.thin, stroke_width=fmt(style.thin, 3),
                        stroke_dasharray="2 1", id=f"{ident}-steady-{key}")
    _name_curves(dwg, canvas, d.graphs[1], ("M_motor", "M_r"), f"{ident}-M", style)
    time_axis(dwg, canvas, d.length, d.time_ticks, last, ident, style)
    if notes:
        note_lines(canvas, dwg.add(dwg.g(id=f"{ident}-notes")), notes, style)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))
    return dwg.tostring()

"""The dynamics sheets. The steady cycle: M_r, the works A_r and A_d and ΔT against the crank's angle φ (the
graphs of :mod:`.diagrams`, against φ instead of t), and Wittenbauer's energy–mass diagram to
their right, built by projection: its ΔT = 0 level is ΔT(φ)'s and its μT the same, so each
position's ΔT is carried across by a thin dashed line; under it I_r(φ) turned through 90° (I
along x at Wittenbauer's μI from the same I0 — its axis is Wittenbauer's I scale — φ downwards),
each position's I_r carried up by a thin dashed line; with its two tangents and the segment kl
they cut on the ΔT axis. With a driving law, M_d(φ) is drawn on M_r's graph and A_r's chords
beside A_d's, each second curve's ordinates measured too (``Md@k``, ``Ar@k``); over a cycle of
several turns every graph spans the period, a φ scale in degrees runs under ΔT(φ), and the
turned I_r(φ), which repeats every turn, is drawn over one turn (its rows numbered with every
position they hold: "1, 13"). The turned I_r(φ) is a ``<g data-diagram="I" data-turned="90">`` whose
ordinates (from its φ axis to the curve, horizontal) are measured like the other graphs'.

Wittenbauer's ``<g>`` states ``data-mu-i`` (kg·m²/mm), ``data-mu-t`` (J/mm), ``data-i0`` and
``data-origin`` (paper x, y of I = I0, ΔT = 0); kl is a measured segment (``data-plan="bound"``,
length × μT = its energy) and each dot of the curve carries ``data-inertia`` and ``data-energy``.
The start-up: ω(t) and the moments against time, as the kinematic diagrams are drawn.
"""

from __future__ import annotations

import math

from ..constructions.diagrams import Graph
from ..constructions.dynamics import DynamicsDiagrams, Second, StartupDiagrams, Wittenbauer
from ..errors import SceneError
from .canvas import Canvas, fmt
from .diagrams import LEFT_MM, RIGHT_MM, _dots, draw_graph, time_axis
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
#: When the content is taller than A3's drawing area less TOP_SLACK_MM (the top graph's name
#: stands that far above the content's box, which is centred), the room below shrinks down to
#: MIN_BELOW_MM, mm.
TOP_SLACK_MM = 2.0
MIN_BELOW_MM = 4.0
#: Least distance between two numbered rows of the turned I_r(φ), mm (closer, every other row
#: is numbered, and so on).
ROW_MM = 3.0
#: Room for the notes: this much per line, mm.
NOTE_LINE_MM = 4.0
#: The φ scale in degrees under ΔT(φ) (a law or several turns): its depth below the graph, mm.
DEGREES_MM = 9.0


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
    extended = d.turns > 1 or bool(d.seconds)          # a law or several turns: the φ scale in degrees
    low_left = t.origin[1] + t.low - (DEGREES_MM if extended else 0.0)
    lowest = min(low_left, ys - phi_end - 8.0)
    top = max(m.origin[1] + m.high, wy + w.high) + 10.0
    area = FORMATS[2].area
    over = top - lowest + BELOW_MM + NOTE_LINE_MM * note_rows - (area.y1 - area.y0 - TOP_SLACK_MM)
    if over > BELOW_MM - MIN_BELOW_MM:        # taller than A3 holds: Wittenbauer's tangents run far off
        raise SceneError(f"the dynamics sheet would be {over - BELOW_MM + MIN_BELOW_MM:.3g} mm taller than A3: "
                         f"Wittenbauer's diagram spans {w.high - w.low:.4g} mm, its tangents tan ψ = ω_m²(1 ± δ)/2 so "
                         "steep that ½·ω_m²·I_r dwarfs ΔT; remove \"dynamics\" from draw (the report keeps J)",
                         key="plans.draw")
    bottom = lowest - (BELOW_MM if over <= 0.0 else max(MIN_BELOW_MM, BELOW_MM - over)) - NOTE_LINE_MM * note_rows
    box = (-LEFT_MM, bottom, wx + w.width + RIGHT_MM, top)
    dwg, canvas = new_sheet(FORMATS[2], box, ident=ident, style=style,
                            block=TitleBlock(heading.mechanism, heading.sheet, heading.position, scales))
    for g in (m, a, t):
        draw_graph(dwg, canvas, g, f"{ident}-{g.quantity}", style, mu_x=d.mu_phi, length=d.length, abscissa="φ")
        if g.extra:           # the works; M_r and the constant moment
            names = d.works if g.quantity == "A" else ("M_r", g.extra_symbol)     # the axis may name both
            _name_curves(dwg, canvas, g, names, f"{ident}-{g.quantity}", style)
    for sec in d.seconds:
        _second(dwg, canvas, next(g for g in d.graphs if g.quantity == sec.quantity), sec,
                f"{ident}-{sec.quantity}-{sec.name}", style, d.mu_phi)
    if extended:
        _degrees(dwg, canvas, d, t, f"{ident}-degrees", style)
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
    rows = _turn(d, g.at_positions)
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
    ords.attribs["data-vectors"] = str(len(rows))
    name = "I" if w.i0 == 0.0 else "I-I0"
    gap = 2.0 * math.pi / (len(rows) - 1) / mu_phi             # mm between two rows
    every = max(1, math.ceil(ROW_MM / gap))                      # rows numbered: every one, or every 2nd, …
    for k, (x, _, value) in enumerate(rows):
        phi = x * d.mu_phi
        a, b = p(w.i0, phi), p(value, phi)
        el = canvas.line(ords, a, b, width=style.thin, ink=abs(b[0] - a[0]) > 0.3, id=f"{ident}-ord{k}")
        _tag(el, canvas, f"{name}@{k}", abs(value - w.i0), a, b if b != a else (a[0] + 1.0, a[1]), f"phi{k}",
             f"{g.quantity}{k}")
        if k % every and k != len(rows) - 1:
            continue
        number = _row_name(d, k)
        canvas.text(texts, canvas.paper((ox - 2.0 - width_of(number, style.small_text), a[1] - 0.9)), number,
                    size=style.small_text, ident=f"{ident}-pn{k}")
    grp.add(ords)
    end = (ox, oy - 2.0 * math.pi / mu_phi - 6.0)
    canvas.line(grp, (ox, oy), end, width=style.vector, stroke_width=vec, id=f"{ident}-phiaxis")
    arrow(canvas, grp, (ox, oy), end, style.colour, f"{ident}-phihead", style, of=f"{ident}-phiaxis")
    canvas.text(texts, canvas.paper((ox + 1.5, end[1] + 1.0)), "φ", size=style.text, italic=True,
                ident=f"{ident}-phiname")
    exact = g.exact if d.turns == 1 else [(x, y) for x, y in g.exact if x <= rows[-1][0] + 1e-9]
    curve = canvas.polyline(grp, [p((y - g.origin[1]) * mu, (x - g.origin[0]) * d.mu_phi) for x, y in exact],
                            width=style.vector, stroke_width=vec, id=f"{ident}-exact", stroke=style.vector_colour)
    curve.attribs["data-kind"] = "exact"
    dots = dwg.g(id=f"{ident}-dots", fill=style.vector_colour, stroke="none")
    for k, (x, _, value) in enumerate(rows):
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
    rows = _turn(d, d.graphs[3].at_positions)
    for k, (x, y, _) in enumerate(t.at_positions[:-1]):
        xi, _, inertia = rows[k % (len(rows) - 1)]      # I_r repeats every turn: the turned diagram's row
        wxk, wyk, _, _ = w.at_positions[k]
        point = (witt[0] + wxk, witt[1] + wyk)
        if stop > x:
            canvas.line(g, (x, y), (stop, y), width=style.thin, id=f"{ident}-t{k}")
        canvas.line(g, (resume, y), point, width=style.thin, id=f"{ident}-t{k}b")
        below = (turned[0] + (inertia - w.i0) / w.mu_i, turned[1] - xi * d.mu_phi / d.mu_phi_turned)
        if below[1] < turned[1]:
            canvas.line(g, below, (below[0], turned[1]), width=style.thin, id=f"{ident}-i{k}")
        canvas.line(g, (below[0], turned[1] + 5.5), point, width=style.thin, id=f"{ident}-i{k}b")


def _turn(d: DynamicsDiagrams, at_positions: tuple) -> tuple:
    """The positions of the turned I_r(φ): all N + 1 over one turn; over several turns, the
    first turn's (I_r repeats every turn)."""
    return at_positions if d.turns == 1 else at_positions[:d.per_turn + 1]


def _row_name(d: DynamicsDiagrams, k: int) -> str:
    """The number of the turned I_r(φ)'s row ``k``: ``k``; over several turns every position it
    holds, k, k + N, … (row 0 holds position 0 alone: N, 2N, … are row N's)."""
    if d.turns == 1:
        return str(k)
    held = [k] if k == 0 else list(range(k, d.positions + 1, d.per_turn))
    return ", ".join(str(j) for j in held)


def _second(dwg, canvas: Canvas, g: Graph, sec: Second, ident: str, style: Style, mu_phi: float) -> None:
    """A graph's second curve at the positions (a driving law: M_d on M_r's graph, A_r on the
    works'): its ordinates from the φ axis measured (``Md@k``, ``Ar@k``: length × μ = |value|),
    its dots, and for a work its chords (dashed, as the graph's own)."""
    oy = g.origin[1]
    thin = fmt(style.thin, 3)
    grp = dwg.g(id=ident, stroke=style.colour, fill="none", stroke_linecap="round")
    grp.attribs["data-diagram"] = f"{g.quantity}-{sec.name}"
    grp.attribs["data-scale"] = repr(g.mu)
    grp.attribs["data-mu-phi"] = repr(mu_phi)
    px, py = canvas.paper(g.origin)
    grp.attribs["data-origin"] = f"{fmt(px, style.decimals)},{fmt(py, style.decimals)}"
    grp.attribs["data-error"] = repr(sec.error)
    ords = dwg.g(id=f"{ident}-ordinates", stroke=style.construction_colour, stroke_width=thin)
    ords.attribs["data-mu"] = repr(g.mu)
    ords.attribs["data-plan"] = "bound"
    ords.attribs["data-vectors"] = str(len(sec.at_positions))
    for k, (x, y, value) in enumerate(sec.at_positions):
        el = canvas.line(ords, (x, oy), (x, y), width=style.thin, ink=abs(y - oy) > 0.3, id=f"{ident}-ord{k}")
        _tag(el, canvas, f"{sec.name}@{k}", abs(value), (x, oy), (x, y) if y != oy else (x, oy + 1.0), f"t{k}",
             f"{sec.name}{k}")
    grp.add(ords)
    grp.add(_dots(dwg, canvas, sec.at_positions, "exact", style.colour, 0.5, f"{ident}-dots", f"{ident}-e", mu_phi,
                  "phi"))
    if sec.chords:
        chords = canvas.polyline(grp, [(x, y) for x, y, _ in sec.chords], width=style.thin, stroke_width=thin,
                                 stroke=style.component_colour, stroke_dasharray="2 1", id=f"{ident}-graphical")
        chords.attribs["data-kind"] = "graphical"
        grp.add(_dots(dwg, canvas, sec.chords, "graphical", style.component_colour, 0.5, f"{ident}-gdots",
                      f"{ident}-g", mu_phi, "phi"))
    dwg.add(grp)


def _degrees(dwg, canvas: Canvas, d: DynamicsDiagrams, last: Graph, ident: str, style: Style) -> None:
    """The crank angle in degrees under ``last`` (ΔT(φ)), aligned with the graphs' φ axes: a tick
    every 90° (every 360° past four turns), the turns' ends marked longer."""
    step = 90.0 if d.turns <= 4 else 360.0
    ticks = [(k * step, math.radians(k * step) / d.mu_phi) for k in range(round(360.0 * d.turns / step) + 1)]
    y = last.origin[1] + last.low - 9.0
    g = dwg.add(dwg.g(id=ident, stroke=style.colour, fill="none"))
    texts = dwg.add(dwg.g(id=f"{ident}-text", fill=style.colour))
    x_end = d.length + 7.0
    canvas.line(g, (0.0, y), (x_end, y), width=style.vector, stroke_width=fmt(style.vector, 3), id=f"{ident}-axis")
    arrow(canvas, g, (0.0, y), (x_end, y), style.colour, f"{ident}-head", style, of=f"{ident}-axis")
    canvas.text(texts, canvas.paper((x_end + 1.5, y - 1.2)), "φ, °", size=style.text, ident=f"{ident}-name")
    for k, (deg, x) in enumerate(ticks):
        tall = 2.5 if deg % 360.0 == 0.0 else 1.5
        canvas.line(g, (x, y), (x, y - tall), width=style.thin, stroke_width=fmt(style.thin, 3), id=f"{ident}-t{k}")
        num = f"{deg:g}°"
        canvas.text(texts, canvas.paper((x - width_of(num, style.small_text) / 2, y - 5.0)), num,
                    size=style.small_text, ident=f"{ident}-n{k}")


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

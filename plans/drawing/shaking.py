"""The ``-shaking`` sheet (:mod:`plans.constructions.shaking`): the hodograph of the shaking force
(every position's force from one pole, tagged and measured: ``<g data-plan="bound">`` with μF;
the tips joined in order), the trajectory of the total centre of mass (its points numbered), and
the shaking moment against φ (a graph whose ordinates are measured); with counterweights, the
curves without them dashed and grey.
"""

from __future__ import annotations

from ..constructions.shaking import PANEL_MM, ShakingSheet
from .canvas import Canvas, fmt
from .diagrams import draw_graph
from .marks import vector
from .sheet import FORMATS, TitleBlock, new_sheet, note_lines
from .style import Style
from .svg import Heading, _tag

__all__ = ["draw_shaking"]

GAP_MM = 30.0


def draw_shaking(s: ShakingSheet, heading: Heading, *, ident: str, style: Style = Style(),
                 notes: tuple[str, ...] = ()) -> str:
    """SVG text of the sheet (see the module)."""
    half = PANEL_MM / 2
    m = s.moment
    box = (-half - 18.0, m.origin[1] + m.low - 14.0 - 4.5 * (len(notes) + 1), max(PANEL_MM * 2 + GAP_MM + half,
                                                                              s.length + 20.0), half + 14.0)
    dwg, canvas = new_sheet(FORMATS[2], box, ident=ident, style=style,
                            block=TitleBlock(heading.mechanism, heading.sheet, heading.position,
                                             f"μ_F = {s.hodograph.mu:g} N/mm; μ_l = {s.trajectory.mu:g} m/mm; "
                                             f"μ_M = {m.mu:g} N·m/mm, μ_φ = {s.mu_phi:g} rad/mm"))
    labels = dwg.g(id=f"{ident}-labels", fill=style.colour)
    texts = dwg.add(dwg.g(id=f"{ident}-texts", fill=style.colour))
    _hodograph(dwg, canvas, s, (0.0, 0.0), f"{ident}-hodograph", style, labels)
    _trajectory(dwg, canvas, s, (PANEL_MM + GAP_MM, 0.0), f"{ident}-centre", style, labels)
    canvas.text(texts, canvas.paper((-half, half + 8.0)), f"Hodograph of the shaking force Σ(−m·a_S), μ_F = "
                f"{s.hodograph.mu:g} N/mm", size=style.small_text + 0.5, ident=f"{ident}-cap0")
    canvas.text(texts, canvas.paper((PANEL_MM + GAP_MM - half, half + 8.0)), "Trajectory of the total centre of "
                f"mass, μ_l = {s.trajectory.mu:g} m/mm (from the frame's first pivot)", size=style.small_text + 0.5,
                ident=f"{ident}-cap1")
    draw_graph(dwg, canvas, m, f"{ident}-moment", style, mu_x=s.mu_phi, length=s.length, abscissa="φ")
    dwg.add(labels)
    if notes:
        note_lines(canvas, dwg.add(dwg.g(id=f"{ident}-notes")), notes, style)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))
    return dwg.tostring()


def _hodograph(dwg, canvas: Canvas, s: ShakingSheet, at: tuple[float, float], ident: str, style: Style,
               labels) -> None:
    h = s.hodograph
    ox, oy = at
    g = dwg.g(id=ident, stroke=style.colour, fill="none")
    g.attribs["data-plan"] = "bound"
    g.attribs["data-mu"] = repr(h.mu)
    drawn = [(k, t) for k, t in enumerate(h.tips) if (t[0] ** 2 + t[1] ** 2) ** 0.5 > 1e-6]
    g.attribs["data-vectors"] = str(len(drawn))
    if h.before:
        canvas.polyline(g, [(ox + x, oy + y) for x, y in h.before], closed=True, width=style.thin,
                        stroke=style.construction_colour, stroke_width=fmt(style.thin, 3), stroke_dasharray="2 1.2",
                        id=f"{ident}-before")
    if len(h.tips) > 1:
        canvas.polyline(g, [(ox + x, oy + y) for x, y, _ in h.tips], closed=True, width=style.thin,
                        stroke=style.vector_colour, stroke_width=fmt(style.thin, 3), id=f"{ident}-tips")
    for k, (x, y, value) in drawn:
        el = vector(canvas, g, (ox, oy), (ox + x, oy + y), style.vector_colour, f"{ident}-f{k}", f"{ident}-fh{k}",
                    style)
        _tag(el, canvas, f"Fsh@{k}", value, (ox, oy), (ox + x, oy + y), "o", f"f{k}")
        if k % max(1, len(drawn) // 12) == 0:
            canvas.label(labels, (ox + x, oy + y), str(k), size=style.small_text, italic=False, prefer=(x, y),
                         ident=f"{ident}-n{k}", near=0.8)
    canvas.circle(g, (ox, oy), 0.7, filled=True, id=f"{ident}-pole")
    canvas.label(labels, (ox, oy), "o", size=style.text, prefer=(-1.0, -1.0), ident=f"{ident}-pl", near=0.8)
    dwg.add(g)


def _trajectory(dwg, canvas: Canvas, s: ShakingSheet, at: tuple[float, float], ident: str, style: Style,
                labels) -> None:
    t = s.trajectory
    ox, oy = at
    xs = [x for x, _ in t.points + t.before]
    ys = [y for _, y in t.points + t.before]
    cx, cy = (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2

    def p(q) -> tuple[float, float]:
        return ox + q[0] - cx, oy + q[1] - cy

    g = dwg.g(id=ident, stroke=style.colour, fill="none")
    if t.before:
        canvas.polyline(g, [p(q) for q in t.before], closed=True, width=style.thin, stroke=style.construction_colour,
                        stroke_width=fmt(style.thin, 3), stroke_dasharray="2 1.2", id=f"{ident}-before")
    if t.still:
        canvas.circle(g, p(t.points[0]), 1.0, filled=True, id=f"{ident}-still")
        canvas.label(labels, p(t.points[0]), "S (still)", size=style.text, prefer=(1.0, 1.0), ident=f"{ident}-sl")
    else:
        canvas.polyline(g, [p(q) for q in t.points], closed=True, width=style.vector, stroke=style.vector_colour,
                        stroke_width=fmt(style.vector, 3), id=f"{ident}-path")
        for k, q in enumerate(t.points):
            if k % max(1, len(t.points) // 6) == 0:      # a few positions marked: the points are close
                canvas.circle(g, p(q), 0.45, filled=True, id=f"{ident}-d{k}")
                canvas.label(labels, p(q), str(k), size=style.small_text, italic=False, prefer=(q[0] - cx, q[1] - cy),
                             ident=f"{ident}-n{k}", near=1.2)
    dwg.add(g)

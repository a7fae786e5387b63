"""The kinematic scheme's symbols on a sheet: links and plates, slider blocks, guides,
frame supports, pins, the drive's arrow, and the labels of points and links."""

from __future__ import annotations

import math

import numpy as np

from ..constructions.scheme import BLOCK_MM, Scheme
from .canvas import Canvas, fmt
from .marks import arrow as _arrow, markup as _markup
from .style import Style

__all__ = ["scheme_layers"]


def _hatch(a, b, side: float, style: Style) -> list[tuple[tuple[float, float], tuple[float, float]]]:
    """45° hatch strokes along segment a→b (paper mm, y up) on the ``side`` (+1 left, −1 right)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    L = float(np.linalg.norm(b - a))
    u = (b - a) / L
    n = side * np.array([-u[1], u[0]])
    d = (n - u) / math.sqrt(2.0) * style.hatch_length
    count = max(int(L / style.hatch_step), 1)
    return [(tuple(a + u * (t + 0.5) * L / count), tuple(a + u * (t + 0.5) * L / count + d)) for t in range(count)]



def scheme_layers(dwg, canvas: Canvas, sch: Scheme, ident: str, style: Style) -> None:
    g = dwg.g(id=f"{ident}-scheme", stroke=style.colour, fill="none", stroke_linecap="round")
    g.attribs["data-mu"] = repr(sch.mu_l)
    g.attribs["data-plan"] = "scheme"
    thin = fmt(style.thin, 3)
    for k, gd in enumerate(sch.guides):
        w = style.link if not gd.fixed else style.vector
        canvas.line(g, gd.start, gd.end, width=w, stroke_width=fmt(w, 3), id=f"{ident}-guide{k}")
        if gd.fixed:
            off = BLOCK_MM[1] / 2
            u = np.subtract(gd.end, gd.start) / np.linalg.norm(np.subtract(gd.end, gd.start))
            n = np.array([-u[1], u[0]])
            a, b = np.add(gd.start, -off * n), np.add(gd.end, -off * n)
            canvas.line(g, a, b, width=style.vector, stroke_width=fmt(style.vector, 3), id=f"{ident}-gb{k}")
            canvas.strokes(g, _hatch(a, b, -1.0, style), stroke_width=thin, id=f"{ident}-gh{k}")
    plates = [(name, pts) for name, pts in sch.links if len(pts) >= 3]
    bars = [(name, pts) for name, pts in sch.links if len(pts) == 2]
    for name, pts in plates:   # plates first: bars pinned to them are drawn over their fill
        canvas.polygon(g, [sch.points[p] for p in pts], width=style.link, stroke_width=fmt(style.link, 3),
                       fill="#eef2fb", stroke_linejoin="round", id=f"{ident}-link{name}")
    for name, pts in bars:
        canvas.line(g, sch.points[pts[0]], sch.points[pts[1]], width=style.link, stroke_width=fmt(style.link, 3),
                    id=f"{ident}-link{name}")
    for k, b in enumerate(sch.blocks):
        u = np.array([math.cos(math.radians(b.angle)), math.sin(math.radians(b.angle))])
        n = np.array([-u[1], u[0]])
        hl, hw = BLOCK_MM[0] / 2, BLOCK_MM[1] / 2
        corners = [np.add(b.center, sx * hl * u + sy * hw * n) for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        canvas.polygon(g, corners, width=style.link, fill="#fff", stroke_width=fmt(style.link, 3),
                       id=f"{ident}-block{b.link}")
    for k, p in enumerate(sch.supports):
        c = np.asarray(sch.points[p])
        s = style.support_size
        canvas.polygon(g, [c, c + (-s / 2, -s), c + (s / 2, -s)], width=style.vector, fill="#fff",
                       stroke_width=fmt(style.vector, 3), id=f"{ident}-sup{k}")
        a, b = c + (-s, -s), c + (s, -s)
        canvas.line(g, a, b, width=style.vector, stroke_width=fmt(style.vector, 3), id=f"{ident}-supb{k}")
        canvas.strokes(g, _hatch(a, b, -1.0, style), stroke_width=thin, id=f"{ident}-suph{k}")
    for k, p in enumerate(sch.joints):
        canvas.circle(g, sch.points[p], style.joint_radius, filled=True, fill="#fff", stroke_width=fmt(style.vector, 3),
                      id=f"{ident}-j{k}")
    labels = dwg.g(id=f"{ident}-labels", fill=style.colour)
    if sch.drive_pivot:
        c = np.asarray(sch.points[sch.drive_pivot])
        r = 9.0
        sgn = 1.0 if sch.omega >= 0 else -1.0
        angles = np.radians(np.linspace(20.0, 110.0, 10)) * sgn + (0.0 if sgn > 0 else math.pi)
        arc = [c + r * np.array([math.cos(t), math.sin(t)]) for t in angles]
        canvas.polyline(g, arc[:-1], stroke_width=thin, id=f"{ident}-omega")
        _arrow(canvas, g, arc[-3], arc[-1], style.colour, f"{ident}-omegah", style)
        canvas.label(labels, arc[-1], "ω_1", size=style.text, prefer=arc[-1] - c, ident=f"{ident}-omegal", digits=False)
    dwg.add(g)
    centre = np.mean(list(sch.points.values()), axis=0)
    on_block = {b.center for b in sch.blocks}
    for k, (name, xy) in enumerate(sch.points.items()):
        near = 0.5 * math.hypot(*BLOCK_MM) if xy in on_block else style.joint_radius + 0.3
        canvas.label(labels, xy, _markup(name), size=style.text, prefer=np.subtract(xy, centre), ident=f"{ident}-p{k}",
                     digits=False, near=near)
    for name, pts in sch.links:
        xy = np.array([sch.points[p] for p in pts])
        mid = xy.mean(axis=0)
        if len(pts) >= 2:
            u = xy[1] - xy[0]
            u = u / (np.linalg.norm(u) or 1.0)
            prefer = np.array([-u[1], u[0]])
            near = 0.6
        else:
            prefer, near = np.array([0.0, 1.0]), BLOCK_MM[1] / 2 + 0.5
        canvas.label(labels, tuple(mid), name, size=style.small_text, italic=False, prefer=prefer,
                     ident=f"{ident}-n{name}", digits=False, near=near)
    dwg.add(labels)

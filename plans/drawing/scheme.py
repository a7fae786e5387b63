"""The kinematic scheme's symbols on a sheet: guides (a slot joined to its link by a stem),
links and plates (bars over plates), slider blocks (a block moved off a shared pin on its
rod), hydraulic cylinders (barrel, piston, rod; ``data-part`` names each), frame supports,
pins, coupler points as dots, the drive's angle φ1 and arc arrows ω1, ε1 (and the links' ω_j,
ε_j when the scheme has them), a linear drive's input arrows v, a, and the labels of points and
links."""

from __future__ import annotations

import math

import numpy as np

from ..constructions.scheme import BLOCK_MM, REFERENCE_OVERRUN_MM, Arc, Scheme
from ..constructions.scheme_drive import ARROW_HEAD_MM, BARREL_MM, Cylinder, DriveArrow
from .canvas import Canvas, fmt
from .marks import markup as _markup
from .style import Style
from .. import linalg as la

__all__ = ["scheme_layers", "DOT_MM"]

#: Radius of the dot that marks a coupler point (a point of a link that is no pair), mm.
DOT_MM = 0.75
#: Largest angle step of a drawn arc, degrees.
ARC_STEP = 3.0


def _hatch(a, b, side: float, style: Style) -> list[tuple[tuple[float, float], tuple[float, float]]]:
    """45° hatch strokes along segment a→b (paper mm, y up) on the ``side`` (+1 left, −1 right)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    L = float(la.norm(b - a))
    u = (b - a) / L
    n = side * np.array([-u[1], u[0]])
    d = (n - u) / math.sqrt(2.0) * style.hatch_length
    count = max(int(L / style.hatch_step), 1)
    return [(tuple(a + u * (t + 0.5) * L / count), tuple(a + u * (t + 0.5) * L / count + d)) for t in range(count)]


def _arc_points(arc: Arc, start: float, end: float) -> list[tuple[float, float]]:
    n = max(int(math.ceil(abs(end - start) / ARC_STEP)), 1)
    return [arc.at(start + (end - start) * k / n) for k in range(n + 1)]


def _draw_arc(canvas: Canvas, g, labels, arc: Arc, ident: str, style: Style) -> None:
    """An arc (φ: with its reference line) or an arc arrow (ω, ε: head at the end), labelled."""
    thin = fmt(style.thin, 3)
    key = f"{ident}-{arc.kind}"
    if arc.kind == "phi":
        ref = arc.at(arc.start)
        far = np.add(arc.centre, (arc.radius + REFERENCE_OVERRUN_MM) / arc.radius * np.subtract(ref, arc.centre))
        canvas.line(g, arc.centre, far, width=style.thin, stroke_width=thin, id=f"{key}{arc.link}ref")
        pts = _arc_points(arc, arc.start, arc.end)
        el = canvas.polyline(g, pts, width=style.thin, stroke_width=thin, id=f"{key}{arc.link}")
    else:
        back = math.copysign(math.degrees(arc.head / arc.radius), arc.sweep)
        pts = _arc_points(arc, arc.start, arc.end - back)
        el = canvas.polyline(g, pts, width=style.thin, stroke_width=thin, id=f"{key}{arc.link}")
        h = canvas.head(g, pts[-1], arc.at(arc.end), arc.head, fill=style.colour, stroke="none",
                        id=f"{key}{arc.link}h")
        h.attribs["class"] = "head"
        h.attribs["data-for"] = f"{key}{arc.link}"
    el.attribs["data-kind"] = arc.kind
    el.attribs["data-link"] = arc.link
    mid = arc.at(arc.start + arc.sweep / 2 if arc.kind == "phi" else arc.end)
    canvas.label(labels, mid, arc.label, size=style.text, prefer=np.subtract(mid, arc.centre),
                 ident=f"{key}{arc.link}l", digits=False, near=0.5)


def _cylinder(canvas: Canvas, g, cyl: Cylinder, ident: str, style: Style) -> None:
    """A hydraulic cylinder: the eye from its pivot, the barrel (an outline), the piston across
    it and the piston rod on to its pin."""
    w = fmt(style.link, 3)
    key = f"{ident}-cyl{cyl.barrel_link}{cyl.rod_link}"
    if cyl.eye is not None:
        el = canvas.line(g, cyl.eye[0], cyl.eye[1], width=style.link, stroke_width=w, id=f"{key}eye")
        el.attribs["data-part"] = "eye"
    el = canvas.line(g, cyl.rod[0], cyl.rod[1], width=style.link, stroke_width=w, id=f"{key}rod")
    el.attribs["data-part"] = "rod"
    el.attribs["data-link"] = cyl.rod_link
    # an outline (the rod shows inside it) that labels keep out of, as of a filled shape
    el = canvas.polygon(g, cyl.barrel, width=style.link, stroke_width=w, stroke_linejoin="round", id=f"{key}barrel")
    canvas.keep_out(cyl.barrel)
    el.attribs["data-part"] = "barrel"
    el.attribs["data-link"] = cyl.barrel_link
    el = canvas.line(g, cyl.piston[0], cyl.piston[1], width=1.5 * style.link, stroke_width=fmt(1.5 * style.link, 3),
                     stroke_linecap="butt", id=f"{key}piston")
    el.attribs["data-part"] = "piston"


def _input_arrow(canvas: Canvas, g, labels, arrow: DriveArrow, ident: str, style: Style) -> None:
    """A linear drive's input arrow (v or a) along its guide, labelled."""
    key = f"{ident}-input{arrow.kind}{arrow.link}"
    u = np.subtract(arrow.end, arrow.start)
    u = u / la.norm(u)
    stop = np.subtract(arrow.end, 0.8 * ARROW_HEAD_MM * u)
    el = canvas.line(g, arrow.start, stop, width=style.vector, stroke_width=fmt(style.vector, 3), id=key)
    el.attribs["data-kind"] = f"input-{arrow.kind}"
    el.attribs["data-link"] = arrow.link
    h = canvas.head(g, arrow.start, arrow.end, ARROW_HEAD_MM, fill=style.colour, stroke="none", id=f"{key}h")
    h.attribs["class"] = "head"
    h.attribs["data-for"] = key
    mid = np.add(arrow.start, 0.5 * np.subtract(arrow.end, arrow.start))
    canvas.label(labels, tuple(mid), arrow.label, size=style.text, prefer=(-u[1], u[0]), ident=f"{key}l",
                 digits=False, near=0.5)


def frame_guide(canvas: Canvas, g, gd, k: int, ident: str, style: Style) -> None:
    """The hatched ground line of frame guide ``gd`` (its ``k``-th), half a block below it."""
    off = BLOCK_MM[1] / 2
    u = np.subtract(gd.end, gd.start) / la.norm(np.subtract(gd.end, gd.start))
    n = np.array([-u[1], u[0]])
    a, b = np.add(gd.start, -off * n), np.add(gd.end, -off * n)
    canvas.line(g, a, b, width=style.vector, stroke_width=fmt(style.vector, 3), id=f"{ident}-gb{k}")
    canvas.strokes(g, _hatch(a, b, -1.0, style), stroke_width=fmt(style.thin, 3), id=f"{ident}-gh{k}")


def support(canvas: Canvas, g, xy, k: int, ident: str, style: Style) -> None:
    """A frame pivot at ``xy`` (mm; the ``k``-th): a triangle on a hatched ground line."""
    c = np.asarray(xy)
    s = style.support_size
    canvas.polygon(g, [c, c + (-s / 2, -s), c + (s / 2, -s)], width=style.vector, fill="#fff",
                   stroke_width=fmt(style.vector, 3), id=f"{ident}-sup{k}")
    a, b = c + (-s, -s), c + (s, -s)
    canvas.line(g, a, b, width=style.vector, stroke_width=fmt(style.vector, 3), id=f"{ident}-supb{k}")
    canvas.strokes(g, _hatch(a, b, -1.0, style), stroke_width=fmt(style.thin, 3), id=f"{ident}-suph{k}")


def block_corners(b) -> list[np.ndarray]:
    """The four corners (mm) of slider block ``b``, BLOCK_MM long along its guide."""
    u = np.array([math.cos(math.radians(b.angle)), math.sin(math.radians(b.angle))])
    n = np.array([-u[1], u[0]])
    hl, hw = BLOCK_MM[0] / 2, BLOCK_MM[1] / 2
    return [np.add(b.center, sx * hl * u + sy * hw * n) for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]


def scheme_layers(dwg, canvas: Canvas, sch: Scheme, ident: str, style: Style) -> None:
    g = dwg.g(id=f"{ident}-scheme", stroke=style.colour, fill="none", stroke_linecap="round")
    g.attribs["data-mu"] = repr(sch.mu_l)
    g.attribs["data-plan"] = "scheme"
    link_w = fmt(style.link, 3)
    barrel_links = {c.barrel_link for c in sch.cylinders}
    in_cylinder = barrel_links | {c.rod_link for c in sch.cylinders}
    for k, gd in enumerate(sch.guides):
        if not gd.fixed and gd.link in barrel_links:
            continue   # the barrel is the rod's guide
        w = style.link if not gd.fixed else style.vector
        canvas.line(g, gd.start, gd.end, width=w, stroke_width=fmt(w, 3), id=f"{ident}-guide{k}")
        if gd.stem is not None:   # the slot is rigid with its link: one piece, as a yoke
            canvas.line(g, gd.stem[0], gd.stem[1], width=style.link, stroke_width=link_w, id=f"{ident}-stem{k}")
        if gd.fixed:
            frame_guide(canvas, g, gd, k, ident, style)
    plates = [(name, pts) for name, pts in sch.links if len(pts) >= 3]
    bars = [(name, pts) for name, pts in sch.links if len(pts) == 2]
    for name, pts in plates:   # plates first: bars pinned to them are drawn over their fill
        canvas.polygon(g, [sch.points[p] for p in pts], width=style.link, stroke_width=link_w,
                       fill="#eef2fb", stroke_linejoin="round", id=f"{ident}-link{name}")
    for name, pts in bars:
        if name in in_cylinder:
            continue
        canvas.line(g, sch.points[pts[0]], sch.points[pts[1]], width=style.link, stroke_width=link_w,
                    id=f"{ident}-link{name}")
    for b in sch.blocks:
        if b.pin is not None:   # a block moved off its pin: carried on a rod along its guide
            canvas.line(g, b.pin, b.center, width=style.link, stroke_width=link_w, id=f"{ident}-rod{b.link}")
    for b in sch.blocks:
        canvas.polygon(g, block_corners(b), width=style.link, fill="#fff", stroke_width=link_w,
                       id=f"{ident}-block{b.link}")
    for cyl in sch.cylinders:
        _cylinder(canvas, g, cyl, ident, style)
    labels = dwg.g(id=f"{ident}-labels", fill=style.colour)
    for arrow in sch.inputs:
        _input_arrow(canvas, g, labels, arrow, ident, style)
    for arc in sch.arcs:   # under the supports and pins: a pin's circle covers the lines' ends
        _draw_arc(canvas, g, labels, arc, ident, style)
    for k, p in enumerate(sch.supports):
        support(canvas, g, sch.points[p], k, ident, style)
    for k, p in enumerate(sch.joints):
        canvas.circle(g, sch.points[p], style.joint_radius, filled=True, fill="#fff", stroke_width=fmt(style.vector, 3),
                      id=f"{ident}-j{k}")
    for k, p in enumerate(sch.dots):   # coupler points: small filled dots, not pins
        canvas.circle(g, sch.points[p], DOT_MM, filled=True, fill=style.colour, stroke="none", id=f"{ident}-dot{k}")
    dwg.add(g)
    centre = np.mean(list(sch.points.values()), axis=0)
    on_block = {b.center for b in sch.blocks}
    for k, (name, xy) in enumerate(sch.points.items()):
        near = 0.5 * math.hypot(*BLOCK_MM) if xy in on_block else style.joint_radius + 0.3
        canvas.label(labels, xy, _markup(name), size=style.text, prefer=np.subtract(xy, centre), ident=f"{ident}-p{k}",
                     digits=False, near=near)
    blocks = {b.link: b for b in sch.blocks}
    barrels = {c.barrel_link: c for c in sch.cylinders}
    rods = {c.rod_link: c for c in sch.cylinders}
    for name, pts in sch.links:
        xy = np.array([sch.points[p] for p in pts])
        mid = xy.mean(axis=0)
        if name in barrels:   # by the barrel
            c = barrels[name]
            prefer = np.array([-c.axis[1], c.axis[0]])
            arrows = [a for a in sch.inputs if a.link == c.rod_link]
            if any(float(la.dot(np.subtract(a.start, c.rod[0]), prefer)) < 0 for a in arrows):
                prefer = -prefer   # the drive's arrows' side (they stand by the mouth), clear of the piston's name
            bottom = 0.5 * np.add(c.barrel[0], c.barrel[3])
            top = 0.5 * np.add(c.barrel[1], c.barrel[2])
            mid, near = bottom + 0.25 * (top - bottom) + 0.5 * BARREL_MM * prefer, 0.6   # by the barrel's foot
        elif name in rods:    # by the rod where it leaves the barrel
            c = rods[name]
            mid = 0.5 * np.add(np.mean(c.barrel[1:3], axis=0), c.rod[1])
            prefer, near = np.array([-c.axis[1], c.axis[0]]), 0.6
        elif len(pts) >= 2:
            u = xy[1] - xy[0]
            u = u / (la.norm(u) or 1.0)
            prefer = np.array([-u[1], u[0]])
            near = 0.6
        else:   # a block: its number by the block (moved off the pin, by the moved block)
            b = blocks.get(name)
            mid = np.asarray(b.center) if b else mid
            prefer = np.array([0.0, 1.0]) if b is None or b.pin is None else np.subtract(b.center, b.pin)
            near = BLOCK_MM[1] / 2 + 0.5
        canvas.label(labels, tuple(mid), name, size=style.small_text, italic=False, prefer=prefer,
                     ident=f"{ident}-n{name}", digits=False, near=near)
    dwg.add(labels)

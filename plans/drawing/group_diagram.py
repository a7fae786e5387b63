"""A group drawn alone with its forces (:class:`~plans.constructions.group_diagram.GroupDiagram`),
on a force sheet beside the group's polygon, and the moment equations written out.

The links are drawn at the diagram's μl; each force is an arrow of :data:`FORCE_ARROW_MM` from
its point of application in its own direction (its value is the polygon's to show: the diagram
shows where each force acts and its line); each couple a curved arrow round its link's centre;
each arm a thin line from the moment centre to the foot of the perpendicular on the force's
line, labelled h_k, the line of action drawn on (thin, dashed) where the foot is off the arrow.

What ``plans check`` reads (:mod:`plans.checking_groups`): the diagram's ``<g>`` has
``data-plan="group"``, ``data-group``, ``data-mu`` = μl (m/mm) and ``data-vectors`` (its tagged
lines). Each force line ``data-quantity`` (``Rt:i-j`` and ``Rn:i-j`` for an outer pin's
components), ``data-value`` (N), ``data-direction``, ``data-link``, its tail at the point of
application; each arm ``<line data-quantity="h:<force>" data-value="<m>" data-about="<centre>">``
from the centre to the foot; each couple a ``<path data-couple=… data-moment="<N·m, CCW +>"
data-link=…>``; each moment equation an empty ``<g data-equation="<unknown>" data-links="2 3"
data-about="B" data-centre="x,y">`` (paper mm).
"""

from __future__ import annotations

import math

import numpy as np

from ..constructions.group_diagram import GroupDiagram, MomentEquation
from .canvas import Canvas, fmt
from .force_marks import _colour, _number, _solid_vector, _sub, symbol
from .marks import bounds
from .style import Style
from .svg import _tag

__all__ = ["diagram_box", "draw_group_diagram", "diagram_rows", "FORCE_ARROW_MM", "COUPLE_RADIUS_MM", "name"]

#: Drawn length of every force on a group diagram, mm (direction and point of application only).
FORCE_ARROW_MM = 14.0
#: Radius of a couple's curved arrow, mm.
COUPLE_RADIUS_MM = 5.0


def name(quantity: str) -> str:
    """The printed name of a diagram's tag: ``Rt:1-2`` → R₁₂,τ, ``Rn:1-2`` → R₁₂,ₙ, ``h:G:2``
    → h, the rest as :func:`~plans.drawing.forces.symbol`."""
    if quantity.startswith(("Rt:", "Rn:")):
        return symbol(f"R:{quantity[3:]}:{'t' if quantity[1] == 't' else 'n'}")
    if quantity == "M:bal":
        return "M_{bal}"
    return symbol(quantity)


def _head(d: GroupDiagram, f) -> tuple[float, float]:
    u = f.direction
    return (f.at[0] + FORCE_ARROW_MM * u[0], f.at[1] + FORCE_ARROW_MM * u[1])


def diagram_box(d: GroupDiagram) -> tuple[float, float, float, float]:
    """The diagram's content box, mm (y up), labels' room included."""
    pts = [xy for _, xy in d.joints] + [f.at for f in d.forces] + [_head(d, f) for f in d.forces]
    pts += [a.foot for a in d.arms] + [xy for _, xy in d.special]
    r = COUPLE_RADIUS_MM
    pts += [(c.at[0] + dx, c.at[1] + dy) for c in d.couples for dx, dy in ((-r, -r), (r, r))]
    return bounds(pts)


def draw_group_diagram(dwg, canvas: Canvas, d: GroupDiagram, ident: str, style: Style) -> None:
    """The diagram's plan group on ``canvas`` (placed by the caller): links, forces, couples,
    arms, the equations' tags; labels are requested (placed by the caller's place_labels)."""
    g = dwg.g(id=f"{ident}-group")
    g.attribs["data-plan"] = "group"
    g.attribs["data-group"] = d.group
    g.attribs["data-mu"] = repr(d.mu)
    g.attribs["data-vectors"] = str(len(d.forces) + len(d.arms))
    labels = dwg.g(id=f"{ident}-glabels", fill=style.colour)
    thin = fmt(style.thin, 3)
    links = dwg.g(id=f"{ident}-links", stroke=style.colour, stroke_width=fmt(style.link, 3), fill="none")
    for k, (link, names, xy) in enumerate(d.bars):
        pts = list(xy)
        if len(pts) > 2:                # a plate: its outline through its points in order
            pts = pts + pts[:1]
        for j in range(len(pts) - 1):
            el = canvas.line(links, pts[j], pts[j + 1], width=style.link, id=f"{ident}-b{k}-{j}")
            el.attribs["data-construction"] = "link"
    g.add(links)
    for k, (p, xy) in enumerate(d.joints):
        canvas.circle(g, xy, 0.8, fill="#fff", stroke=style.colour, stroke_width=thin, id=f"{ident}-j{k}")
        canvas.label(labels, xy, p, size=style.small_text + 0.5, prefer=(-0.7, 0.7), ident=f"{ident}-jl{k}",
                     digits=True, near=0.9)
    cons = dwg.g(id=f"{ident}-gcons", stroke=style.construction_colour, stroke_width=thin, fill="none",
                 stroke_dasharray=style.dash)
    for k, (p, xy) in enumerate(d.special):
        canvas.circle(g, xy, 0.6, filled=True, id=f"{ident}-s{k}")
        canvas.label(labels, xy, p, size=style.text, prefer=(0.7, 0.7), ident=f"{ident}-sl{k}", near=0.6)
        for f in d.forces:              # the lines of the rods' R^n through S
            if f.quantity.startswith("Rn:") and abs(_cross_at(f, xy)) < 1e-6 * max(1.0, math.dist(f.at, xy)):
                el = canvas.line(cons, f.at, xy, id=f"{ident}-sline{k}-{f.quantity}")
                el.attribs["data-construction"] = "special"
    for k, f in enumerate(d.forces):
        colour = _colour(style, f.kind) if f.known or f.kind.startswith("reaction_") else style.colour
        el = _solid_vector(canvas, g, f.at, _head(d, f), colour, f"{ident}-f{k}", f"{ident}-fh{k}", style)
        _tag(el, canvas, f.quantity, f.value, f.at, _head(d, f), None, None)
        el.attribs["data-link"] = f.link
        el.attribs["data-drawn"] = "direction"
        u = f.direction
        canvas.label(labels, _head(d, f), name(f.quantity), size=style.text, prefer=u, ident=f"{ident}-fl{k}",
                     digits=False, fill=colour, near=0.4)
    for k, c in enumerate(d.couples):
        _couple(canvas, g, labels, c, f"{ident}-c{k}", style)
    arms = dwg.g(id=f"{ident}-arms", stroke=style.construction_colour, stroke_width=thin, fill="none")
    for k, a in enumerate(d.arms):
        f = d.force(a.force)
        el = canvas.line(arms, a.centre, a.foot, id=f"{ident}-a{k}")
        el.attribs["data-quantity"] = f"h:{a.force}"
        el.attribs["data-value"] = repr(float(a.value))
        el.attribs["data-about"] = a.about
        # the line of action drawn on where the foot is off the arrow
        s = (a.foot[0] - f.at[0]) * f.direction[0] + (a.foot[1] - f.at[1]) * f.direction[1]
        if s < 0 or s > FORCE_ARROW_MM:
            end = f.at if s < 0 else _head(d, f)
            ext = canvas.line(cons, end, a.foot, id=f"{ident}-ax{k}")
            ext.attribs["data-construction"] = "action"
        mid = ((a.centre[0] + a.foot[0]) / 2, (a.centre[1] + a.foot[1]) / 2)
        canvas.label(labels, mid, f"h_{_sub(str(a.number))}", size=style.small_text + 0.5,
                     prefer=(-(a.foot[1] - a.centre[1]), a.foot[0] - a.centre[0]), ident=f"{ident}-al{k}",
                     digits=False, fill=style.construction_colour, near=0.3,
                     also=tuple((a.centre[0] + t * (a.foot[0] - a.centre[0]), a.centre[1] + t * (a.foot[1] - a.centre[1]))
                                for t in (0.7, 0.3, 0.85, 0.15)))
    g.add(cons)
    g.add(arms)
    for k, e in enumerate(d.equations):
        eg = dwg.g(id=f"{ident}-eq{k}")
        eg.attribs["data-equation"] = e.unknown
        eg.attribs["data-links"] = " ".join(e.links)
        eg.attribs["data-about"] = e.about
        eg.attribs["data-centre"] = ",".join(canvas.xy(e.centre))
        g.add(eg)
    g.add(labels)
    dwg.add(g)


def _cross_at(f, xy) -> float:
    """How far ``xy`` is off force f's line, mm (signed)."""
    u = f.direction
    return (xy[0] - f.at[0]) * u[1] - (xy[1] - f.at[1]) * u[0]


def _couple(canvas: Canvas, g, labels, c, ident: str, style: Style) -> None:
    """A curved arrow of 240° round the couple's point, counter-clockwise for a positive value."""
    r, sense = COUPLE_RADIUS_MM, 1.0 if c.value > 0 else -1.0
    start = math.radians(-30.0) if sense > 0 else math.radians(210.0)
    sweep = sense * math.radians(240.0)
    n = 24
    pts = [(c.at[0] + r * math.cos(start + sweep * t / n), c.at[1] + r * math.sin(start + sweep * t / n))
           for t in range(n + 1)]
    back = style.arrow_length / r
    cut = [p for t, p in enumerate(pts) if abs(sweep) * t / n <= abs(sweep) - back * 0.8]
    colour = style.vector_colour if c.known else style.component_colour
    el = canvas.polyline(g, cut, width=style.vector, stroke=colour, stroke_width=fmt(style.vector, 3), fill="none",
                         id=ident)
    el.attribs["data-couple"] = c.quantity
    el.attribs["data-moment"] = repr(float(c.value))
    el.attribs["data-link"] = c.link
    tip = pts[-1]
    before = (c.at[0] + r * math.cos(start + sweep - sense * back), c.at[1] + r * math.sin(start + sweep - sense * back))
    h = canvas.head(g, before, tip, style.arrow_length, fill=colour, stroke="none", id=f"{ident}h")
    h.attribs["class"] = "head"
    h.attribs["data-for"] = ident
    mid = pts[n // 2]
    canvas.label(labels, mid, name(c.quantity), size=style.text, prefer=np.subtract(mid, c.at), ident=f"{ident}l",
                 digits=False, fill=colour, near=0.4)


# --- the written equations -------------------------------------------------------------------

def _links(e: MomentEquation) -> str:
    return ", ".join(e.links)


def diagram_rows(d: GroupDiagram) -> list[str]:
    """The diagram's written part (rows of label markup): its scale and method, then each
    moment equation with its terms, its numbers (forces in N, arms in mm as drawn, couples in
    N·m divided by μl) and its result, and the notes."""
    rows = [f"{'Driving link' if d.group.startswith('I(') else 'Group'} {d.group} alone, μ_l = {d.mu:g} m/mm "
            f"(arrows: lines of action only): {d.method.replace('R^τ', 'R_{τ}').replace('R^n', 'R_{n}')}."]
    numbers = {(a.force, a.about): a.number for a in d.arms}
    for e in d.equations:
        rows += _equation_rows(d, e, numbers)
    rows += list(d.notes)
    return rows


def _equation_rows(d: GroupDiagram, e: MomentEquation, numbers: dict) -> list[str]:
    mu = d.mu
    x = name(e.unknown)
    terms = [t for t in e.terms if t.arm is None or t.arm / mu >= 1e-9]
    sym, num = [], []
    # X = Σ (−s_x·s_k) F_k h_k (+ couples / μl) over the unknown's arm (mm), or × μl for a couple
    for t in terms:
        s = -e.sign * t.sign
        sign = "+" if s > 0 else "−"
        if t.arm is None:
            sym.append(f"{sign} {name(t.quantity)}/μ_l")
            num.append(f"{sign} {_number(t.value)}/{mu:g}")
        else:
            h = numbers.get((t.quantity, e.about))          # an arm under ARM_MM is not drawn: its length
            hs = f"h_{_sub(str(h))}" if h is not None else _number(t.arm / mu)
            sym.append(f"{sign} {name(t.quantity)}·{hs}")
            num.append(f"{sign} {_number(t.value)}·{_number(t.arm / mu)}")
    lhs = " ".join(sym).lstrip("+ ") or "0"
    nums = " ".join(num).lstrip("+ ") or "0"
    head = f"ΣM_{_sub(e.about)}({_links(e)}) = 0:"
    if e.arm is None:
        return [f"{head}  {x} = ({lhs})·μ_l", f"   = ({nums})·{mu:g} = {_number(e.value, 5)} N·m"]
    hx = numbers.get((e.unknown, e.about))
    hx = f"h_{_sub(str(hx))}" if hx is not None else "h"
    return [f"{head}  {x} = ({lhs}) / {hx}",
            f"   = ({nums}) / {_number(e.arm / mu)} = {_number(e.value, 5)} N"]

"""SVG output with svgwrite, one user unit = one millimetre of paper.

Geometry arrives in paper millimetres with y up; it is shifted and flipped here (no SVG
transforms), rounded to ``Style.decimals`` and written with explicit ids only, so the
same constructions always give the same bytes. Every plan vector is one ``<line>`` from
tail to head carrying ``data-quantity`` and ``data-value``; its arrowhead is a separate
filled path and the visible shaft stops under the head (``stroke-dasharray``), so the
line itself measures the whole vector.

What ``plans check`` reads (:mod:`plans.checking`), on every tagged ``<line>``:

- ``data-quantity`` — the tag (``v:B``, ``a:B/A:n``, ``r:B/P3`` …);
- ``data-value`` — the exact magnitude, SI (a finite number ≥ 0);
- ``data-direction`` — the exact direction of the vector, tail → head, in degrees in the
  SVG paper frame (x right, y down, so positive angles turn clockwise on the screen):
  ``(x2 − x1, y2 − y1)`` is parallel to ``(cos θ, sin θ)`` up to rounding;
- ``data-from`` / ``data-to`` — the labels of the images (points) the vector joins, as
  printed on the sheet (``p``, ``a``, ``a3``, ``n_BA``, ``k_A3A2``; centres ``P3``); two
  ends with one label are one point, so the vector equations close graphically.

and on each plan's ``<g>``: ``data-mu`` (scale), ``data-plan`` (velocity, acceleration,
centres, scheme) and, but on the scheme, ``data-vectors`` (how many tagged vectors it
holds; "0": a plan drawn as the pole alone). The root ``data-precision`` states the
writer's rounding (mm); the checker takes its tolerance from its own rules, never from it.
"""

from __future__ import annotations

import math
from typing import Iterable, Sequence

import numpy as np
import svgwrite

from ..constructions.centres import CentresSheet
from ..constructions.plans import Plan
from ..constructions.scheme import BLOCK_MM, Scheme
from .style import Style

__all__ = ["draw_plan", "draw_scheme", "fmt"]

_SUBSCRIPT_SPLIT = "_"


def fmt(x: float, decimals: int) -> str:
    """A coordinate rounded to ``decimals`` with trailing zeros stripped (never "-0")."""
    s = f"{round(x, decimals):.{decimals}f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


class _Paper:
    """Maps y-up construction millimetres to SVG paper millimetres."""

    def __init__(self, bbox: tuple[float, float, float, float], style: Style, width_min: float = 120.0):
        x0, y0, x1, y1 = bbox
        self.style = style
        content_w = x1 - x0
        self.width = max(content_w + 2 * style.margin, width_min)
        self.height = (y1 - y0) + 2 * style.margin + style.header + style.footer
        self.dx = -x0 + (self.width - content_w) / 2
        self.y1 = y1

    def __call__(self, p: Sequence[float]) -> tuple[float, float]:
        return (p[0] + self.dx, self.y1 - p[1] + self.style.margin + self.style.header)

    def f(self, x: float) -> str:
        return fmt(x, self.style.decimals)

    def xy(self, p: Sequence[float]) -> tuple[str, str]:
        q = self(p)
        return self.f(q[0]), self.f(q[1])


#: Two plan images closer than this (mm) are one point for ``data-from``/``data-to``; the
#: pole is matched first, so a fixed point's image (at the pole) is labelled as the pole.
SAME_IMAGE_MM = 1e-9


def _direction(paper: _Paper, tail, head) -> str:
    """The exact direction tail → head in degrees, SVG paper frame (y down)."""
    (x0, y0), (x1, y1) = paper(tail), paper(head)
    return repr(math.degrees(math.atan2(y1 - y0, x1 - x0)) + 0.0)


def _image_label(plan: Plan, xy) -> str | None:
    """The label of the plan image at ``xy`` (the first within SAME_IMAGE_MM: the pole first)."""
    for p in plan.points:
        if math.hypot(p.xy[0] - xy[0], p.xy[1] - xy[1]) <= SAME_IMAGE_MM:
            return p.label
    return None


def _tag(el, paper: _Paper, quantity: str, value: float, tail, head, start: str | None, end: str | None) -> None:
    """The attributes ``plans check`` measures a vector by (see the module docstring)."""
    el.attribs["data-quantity"] = quantity
    el.attribs["data-value"] = repr(float(value))
    el.attribs["data-direction"] = _direction(paper, tail, head)
    if start is not None:
        el.attribs["data-from"] = start
    if end is not None:
        el.attribs["data-to"] = end


def _drawing(paper: _Paper, ident: str) -> svgwrite.Drawing:
    w, h = fmt(paper.width, 1), fmt(paper.height, 1)
    dwg = svgwrite.Drawing(size=(f"{w}mm", f"{h}mm"), viewBox=f"0 0 {w} {h}", debug=False, profile="full")
    dwg.attribs["id"] = ident
    dwg.attribs["data-precision"] = fmt(paper.style.precision, 10)
    dwg.add(dwg.rect(insert=(0, 0), size=(w, h), fill="#fff", id=f"{ident}-paper"))
    return dwg


def _text(dwg: svgwrite.Drawing, paper: _Paper, at: tuple[float, float], label: str, *, size: float,
          italic: bool = True, anchor: str = "middle", ident: str | None = None, paper_xy: bool = False,
          subscript: bool = True):
    """A label; with ``subscript``, ``name_sub`` is written with the part after '_' as a
    subscript (image labels such as n_BA); titles and notes are written as they are."""
    x, y = (at if paper_xy else paper(at))
    t = dwg.text("", insert=(paper.f(x), paper.f(y)), font_size=fmt(size, 2), text_anchor=anchor,
                 font_family=paper.style.font, font_style="italic" if italic else "normal", stroke="none",
                 fill=paper.style.colour)
    if ident:
        t.attribs["id"] = ident
    main, _, sub = label.partition(_SUBSCRIPT_SPLIT) if subscript else (label, "", "")
    t.add(dwg.tspan(main))
    if sub:
        t.add(dwg.tspan(sub, font_size=fmt(size * 0.7, 2), dy=[fmt(size * 0.3, 2)]))
    return t


def _arrow_head(paper: _Paper, tail, head) -> str:
    s = paper.style
    (x0, y0), (x1, y1) = paper(tail), paper(head)
    L = math.hypot(x1 - x0, y1 - y0)
    ux, uy = (x1 - x0) / L, (y1 - y0) / L
    al = min(s.arrow_length, 0.5 * L)
    aw = s.arrow_width * al / s.arrow_length
    bx, by = x1 - al * ux, y1 - al * uy
    pts = [(x1, y1), (bx - aw * uy, by + aw * ux), (bx + aw * uy, by - aw * ux)]
    return "M" + " L".join(f"{paper.f(a)},{paper.f(b)}" for a, b in pts) + " Z"


def _bbox(points: Iterable[Sequence[float]]) -> tuple[float, float, float, float]:
    arr = np.array(list(points), dtype=float).reshape(-1, 2)
    (x0, y0), (x1, y1) = arr.min(axis=0), arr.max(axis=0)
    return float(x0) - 6, float(y0) - 6, float(x1) + 6, float(y1) + 6


def _header(dwg: svgwrite.Drawing, paper: _Paper, title: str, subtitle: str, ident: str):
    """Title and subtitle, centred at the top of the sheet."""
    s = paper.style
    head = dwg.g(id=f"{ident}-head")
    head.add(_text(dwg, paper, (paper.width / 2, s.margin + 2), title, size=s.title_text, italic=False, paper_xy=True,
                   subscript=False))
    head.add(_text(dwg, paper, (paper.width / 2, s.margin + 8), subtitle, size=s.small_text, italic=False,
                   paper_xy=True, subscript=False))
    return head


def _legend(dwg: svgwrite.Drawing, paper: _Paper, ident: str, *rows: tuple[str, float]):
    """Lines of text (text, height) at the bottom left of the sheet."""
    s = paper.style
    foot = dwg.g(id=f"{ident}-legend")
    y = paper.height - s.footer + 8 - 6 * max(0, len(rows) - 2)   # more than two rows: the sheet grew for them
    for k, (text, size) in enumerate(rows):
        foot.add(_text(dwg, paper, (s.margin, y + 6 * k), text, size=size, italic=False, anchor="start", paper_xy=True,
                       subscript=False))
    return foot


def _title_width(title: str, style: Style) -> float:
    """Paper width that holds a title line (serif glyphs average about 0.55 of the text height)."""
    return len(title) * 0.55 * style.title_text + 2 * style.margin


def _unit(mu_kind: str) -> str:
    return {"velocity": "(m/s)/mm", "acceleration": "(m/s²)/mm", "scheme": "m/mm"}[mu_kind]


def draw_plan(plan: Plan, *, title: str, subtitle: str, ident: str, style: Style = Style(),
              notes: Sequence[str] = ()) -> str:
    """SVG text of a velocity or acceleration plan; ``notes``: lines of text under it (why a
    plan is drawn as its pole alone)."""
    coords = [p.xy for p in plan.points] + [l.start for l in plan.lines] + [l.end for l in plan.lines]
    paper = _Paper(_bbox(coords), style, width_min=max(_title_width(title, style),
                                                         _title_width(subtitle, style) * style.small_text
                                                         / style.title_text))
    paper.height += 6.0 * len(notes)
    dwg = _drawing(paper, ident)
    dwg.add(_header(dwg, paper, title, subtitle, ident))
    g = dwg.g(id=f"{ident}-plan")
    g.attribs["data-mu"] = repr(plan.mu)
    g.attribs["data-plan"] = plan.kind
    g.attribs["data-vectors"] = str(len(plan.vectors))
    lines = dwg.g(id=f"{ident}-construction", stroke=style.construction_colour, stroke_width=fmt(style.thin, 3),
                  stroke_dasharray=style.dash, fill="none")
    for k, l in enumerate(plan.lines):
        (x1, y1), (x2, y2) = paper.xy(l.start), paper.xy(l.end)
        el = dwg.line(start=(x1, y1), end=(x2, y2), id=f"{ident}-cl{k}")
        el.attribs["data-construction"] = l.quantity
        lines.add(el)
    g.add(lines)
    for k, v in enumerate(plan.vectors):
        colour = style.vector_colour if v.kind in ("absolute", "relative") else style.component_colour
        (x1, y1), (x2, y2) = paper.xy(v.tail), paper.xy(v.head)
        shaft = max(v.length - min(style.arrow_length, 0.5 * v.length) * 0.8, 0.0)
        el = dwg.line(start=(x1, y1), end=(x2, y2), id=f"{ident}-v{k}", stroke=colour,
                      stroke_width=fmt(style.vector, 3), stroke_dasharray=f"{fmt(shaft, 3)} {fmt(v.length + 1, 3)}")
        _tag(el, paper, v.quantity, v.value, v.tail, v.head, _image_label(plan, v.tail), _image_label(plan, v.head))
        g.add(el)
        g.add(dwg.path(d=_arrow_head(paper, v.tail, v.head), fill=colour, stroke="none", id=f"{ident}-h{k}"))
    labels = dwg.g(id=f"{ident}-labels", fill=style.colour)
    placed: list[tuple[float, float]] = []
    centre = np.mean([p.xy for p in plan.points], axis=0)
    for k, p in enumerate(plan.points):
        if any(math.hypot(p.xy[0] - q[0], p.xy[1] - q[1]) < 0.5 for q in placed):
            continue  # images that coincide (fixed points at the pole) get one label
        placed.append(p.xy)
        away = np.subtract(p.xy, centre)
        norm = float(np.linalg.norm(away))
        away = away / norm if norm > 1e-9 else np.array([0.6, 0.8])   # a lone image: label up and right
        at = (p.xy[0] + 3.2 * away[0], p.xy[1] + 3.2 * away[1] - 1.2)
        labels.add(_text(dwg, paper, at, p.label, size=style.text, ident=f"{ident}-l{k}"))
        labels.add(dwg.circle(center=paper.xy(p.xy), r=fmt(0.45, 2), id=f"{ident}-d{k}"))
    g.add(labels)
    dwg.add(g)
    unit = _unit(plan.kind)
    sym = "μV" if plan.kind == "velocity" else "μa"
    if plan.vectors:
        dwg.add(_legend(dwg, paper, ident, (f"{sym} = {plan.mu:g} {unit}", style.text),
                        (f"pole {plan.pole}; every vector = drawn length × {sym}", style.small_text)))
    else:
        dwg.add(_legend(dwg, paper, ident, *((n, style.small_text) for n in notes),
                        (f"pole {plan.pole} alone: no vector to draw, no scale {sym}", style.text)))
    return dwg.tostring()


def _hatch(paper: _Paper, a, b, side: float, style: Style) -> list[tuple[tuple[float, float], tuple[float, float]]]:
    """45° hatch strokes along segment a→b (paper mm, y up) on the ``side`` (+1 left, −1 right)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    L = float(np.linalg.norm(b - a))
    u = (b - a) / L
    n = side * np.array([-u[1], u[0]])
    d = (n - u) / math.sqrt(2.0) * style.hatch_length
    count = max(int(L / style.hatch_step), 1)
    return [(tuple(a + u * (t + 0.5) * L / count), tuple(a + u * (t + 0.5) * L / count + d)) for t in range(count)]


def _scheme_coords(sch: Scheme) -> list:
    return list(sch.points.values()) + [g.start for g in sch.guides] + [g.end for g in sch.guides]


def draw_scheme(sch: Scheme, *, title: str, subtitle: str, formula: str, ident: str, style: Style = Style()) -> str:
    """SVG text of the kinematic scheme."""
    paper = _Paper(_bbox(_scheme_coords(sch)), style, width_min=max(140.0, _title_width(title, style)))
    dwg = _drawing(paper, ident)
    dwg.add(_header(dwg, paper, title, subtitle, ident))
    _scheme_layers(dwg, paper, sch, ident, style)
    dwg.add(_legend(dwg, paper, ident, (f"μl = {sch.mu_l:g} m/mm", style.text), (formula, style.text)))
    return dwg.tostring()


def draw_centres(sheet: CentresSheet, *, title: str, subtitle: str, formula: str, ident: str,
                 style: Style = Style()) -> str:
    """SVG text of the instantaneous-centres sheet: the scheme, the centres, the measured
    segments centre → point (tagged, length × μl = distance in m) and the construction lines."""
    marks = [m.xy for m in sheet.marks if m.xy is not None]
    tips = [tuple(np.add(m.anchor, np.multiply(m.direction, 18.0))) for m in sheet.marks if m.xy is None]
    coords = _scheme_coords(sheet.scheme) + marks + tips + [xy for _, xy in sheet.special] + \
        [p for line in sheet.lines for p in line]
    paper = _Paper(_bbox(coords), style, width_min=max(140.0, _title_width(title, style)))
    dwg = _drawing(paper, ident)
    dwg.add(_header(dwg, paper, title, subtitle, ident))
    cons = dwg.g(id=f"{ident}-construction", stroke=style.construction_colour, stroke_width=fmt(style.thin, 3),
                 stroke_dasharray=style.dash, fill="none")
    for k, (a, b) in enumerate(sheet.lines):
        cons.add(dwg.line(start=paper.xy(a), end=paper.xy(b), id=f"{ident}-cl{k}"))
    dwg.add(cons)
    _scheme_layers(dwg, paper, sheet.scheme, ident, style)
    g = dwg.g(id=f"{ident}-centres", stroke=style.component_colour, stroke_width=fmt(style.thin, 3),
              stroke_dasharray=style.dash, fill="none")
    g.attribs["data-mu"] = repr(sheet.mu_l)
    g.attribs["data-plan"] = "centres"
    g.attribs["data-vectors"] = str(len(sheet.rays))
    for k, r in enumerate(sheet.rays):
        el = dwg.line(start=paper.xy(r.start), end=paper.xy(r.end), id=f"{ident}-r{k}")
        point, _, centre = r.quantity.partition(":")[2].partition("/")
        _tag(el, paper, r.quantity, r.value, r.start, r.end, centre, point)
        g.add(el)
    dwg.add(g)
    labels = dwg.g(id=f"{ident}-marks", fill=style.component_colour)
    for k, m in enumerate(sheet.marks):
        if m.xy is not None:
            labels.add(dwg.circle(center=paper.xy(m.xy), r=fmt(0.9, 2), id=f"{ident}-c{k}"))
            labels.add(_text(dwg, paper, (m.xy[0] + 1.8, m.xy[1] + 1.6), m.name, size=style.text,
                             ident=f"{ident}-cl{k}t"))
            continue
        tip = tuple(np.add(m.anchor, np.multiply(m.direction, 18.0)))
        labels.add(dwg.line(start=paper.xy(m.anchor), end=paper.xy(tip), stroke=style.component_colour,
                            stroke_width=fmt(style.thin, 3), id=f"{ident}-cd{k}"))
        labels.add(dwg.path(d=_arrow_head(paper, m.anchor, tip), stroke="none", id=f"{ident}-ch{k}"))
        note = f"{m.name} at ∞" if m.infinite else f"{m.name} (off the sheet)"
        labels.add(_text(dwg, paper, (tip[0] + 1.5, tip[1] + 1.0), note, size=style.small_text,
                         ident=f"{ident}-ct{k}"))
    for k, (name, xy) in enumerate(sheet.special):
        labels.add(dwg.circle(center=paper.xy(xy), r=fmt(0.7, 2), fill="#fff", stroke=style.component_colour,
                              stroke_width=fmt(style.thin, 3), id=f"{ident}-s{k}"))
        labels.add(_text(dwg, paper, (xy[0] + 1.8, xy[1] - 3.2), name, size=style.small_text,
                         ident=f"{ident}-st{k}"))
    dwg.add(labels)
    dwg.add(_legend(dwg, paper, ident, (f"μl = {sheet.mu_l:g} m/mm; Pj = centre of link j, dashed Pj–X ⊥ v of X",
                                        style.text), (formula, style.text)))
    return dwg.tostring()


def _scheme_layers(dwg: svgwrite.Drawing, paper: _Paper, sch: Scheme, ident: str, style: Style) -> None:
    g = dwg.g(id=f"{ident}-scheme", stroke=style.colour, fill="none", stroke_linecap="round")
    g.attribs["data-mu"] = repr(sch.mu_l)
    g.attribs["data-plan"] = "scheme"
    thin = fmt(style.thin, 3)
    for k, gd in enumerate(sch.guides):
        g.add(dwg.line(start=paper.xy(gd.start), end=paper.xy(gd.end), stroke_width=fmt(style.link if not gd.fixed
                       else style.vector, 3), id=f"{ident}-guide{k}"))
        if gd.fixed:
            off = BLOCK_MM[1] / 2
            u = np.subtract(gd.end, gd.start) / np.linalg.norm(np.subtract(gd.end, gd.start))
            n = np.array([-u[1], u[0]])
            a, b = np.add(gd.start, -off * n), np.add(gd.end, -off * n)
            g.add(dwg.line(start=paper.xy(a), end=paper.xy(b), stroke_width=fmt(style.vector, 3), id=f"{ident}-gb{k}"))
            path = " ".join(f"M{paper.f(paper(s)[0])},{paper.f(paper(s)[1])} L{paper.f(paper(e)[0])},{paper.f(paper(e)[1])}"
                            for s, e in _hatch(paper, a, b, -1.0, style))
            g.add(dwg.path(d=path, stroke_width=thin, id=f"{ident}-gh{k}"))
    for name, pts in sch.links:
        xy = [sch.points[p] for p in pts]
        if len(xy) == 2:
            g.add(dwg.line(start=paper.xy(xy[0]), end=paper.xy(xy[1]), stroke_width=fmt(style.link, 3),
                           id=f"{ident}-link{name}"))
        elif len(xy) >= 3:
            g.add(dwg.polygon([paper.xy(p) for p in xy], stroke_width=fmt(style.link, 3), fill="#eef2fb",
                              stroke_linejoin="round", id=f"{ident}-link{name}"))
    for k, b in enumerate(sch.blocks):
        u = np.array([math.cos(math.radians(b.angle)), math.sin(math.radians(b.angle))])
        n = np.array([-u[1], u[0]])
        hl, hw = BLOCK_MM[0] / 2, BLOCK_MM[1] / 2
        corners = [np.add(b.center, sx * hl * u + sy * hw * n) for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        g.add(dwg.polygon([paper.xy(c) for c in corners], fill="#fff", stroke_width=fmt(style.link, 3),
                          id=f"{ident}-block{b.link}"))
    for k, p in enumerate(sch.supports):
        c = np.asarray(sch.points[p])
        s = style.support_size
        tri = [c, c + (-s / 2, -s), c + (s / 2, -s)]
        g.add(dwg.polygon([paper.xy(t) for t in tri], fill="#fff", stroke_width=fmt(style.vector, 3),
                          id=f"{ident}-sup{k}"))
        a, b = c + (-s, -s), c + (s, -s)
        g.add(dwg.line(start=paper.xy(a), end=paper.xy(b), stroke_width=fmt(style.vector, 3), id=f"{ident}-supb{k}"))
        path = " ".join(f"M{paper.f(paper(s0)[0])},{paper.f(paper(s0)[1])} L{paper.f(paper(e)[0])},{paper.f(paper(e)[1])}"
                        for s0, e in _hatch(paper, a, b, -1.0, style))
        g.add(dwg.path(d=path, stroke_width=thin, id=f"{ident}-suph{k}"))
    for k, p in enumerate(sch.joints):
        g.add(dwg.circle(center=paper.xy(sch.points[p]), r=fmt(style.joint_radius, 3), fill="#fff",
                         stroke_width=fmt(style.vector, 3), id=f"{ident}-j{k}"))
    if sch.drive_pivot:
        c = np.asarray(sch.points[sch.drive_pivot])
        r = 9.0
        sgn = 1.0 if sch.omega >= 0 else -1.0
        angles = np.radians(np.linspace(20.0, 110.0, 10)) * sgn + (0.0 if sgn > 0 else math.pi)
        arc = [c + r * np.array([math.cos(t), math.sin(t)]) for t in angles]
        d = "M" + " L".join(f"{paper.f(paper(q)[0])},{paper.f(paper(q)[1])}" for q in arc)
        g.add(dwg.path(d=d, stroke_width=thin, id=f"{ident}-omega"))
        g.add(dwg.path(d=_arrow_head(paper, arc[-2], arc[-1]), fill=style.colour, stroke="none",
                       id=f"{ident}-omegah"))
        g.add(_text(dwg, paper, tuple(arc[-1] + (2.5 * sgn, 2.0)), "ω_1", size=style.text, ident=f"{ident}-omegal"))
    dwg.add(g)
    labels = dwg.g(id=f"{ident}-labels", fill=style.colour)
    centre = np.mean(list(sch.points.values()), axis=0)
    on_block = {b.center for b in sch.blocks}
    for k, (name, xy) in enumerate(sch.points.items()):
        away = np.subtract(xy, centre)
        away = away / (np.linalg.norm(away) or 1.0)
        reach = 9.0 if xy in on_block else 4.5   # clear of a slider block, else of the joint circle
        at = (xy[0] + reach * away[0] - 1.0, xy[1] + reach * away[1] - 1.2)
        labels.add(_text(dwg, paper, at, name, size=style.text, ident=f"{ident}-p{k}"))
    for name, pts in sch.links:
        xy = np.array([sch.points[p] for p in pts])
        mid = xy.mean(axis=0)
        if len(pts) >= 2:
            u = xy[1] - xy[0]
            u = u / (np.linalg.norm(u) or 1.0)
            mid = mid + 3.0 * np.array([-u[1], u[0]])
        else:
            mid = mid + (0.0, BLOCK_MM[1] / 2 + 2.0)
        labels.add(_text(dwg, paper, (mid[0], mid[1]), name, size=style.small_text, italic=False,
                         ident=f"{ident}-n{name}"))
    dwg.add(labels)

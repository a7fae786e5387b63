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
holds; "0": a plan drawn as the pole alone). A detail of the pole region (images crowding
the pole, :func:`detail_layers`) is a plan group of its own, same ``data-plan``, ``data-mu``
= μ/k. The root ``data-precision`` states the
writer's rounding (mm); the checker takes its tolerance from its own rules, never from it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ..constructions.centres import CentresSheet
from ..constructions.detail import PlanDetail, pole_detail
from ..constructions.plans import Plan
from ..constructions.scheme import Scheme
from .canvas import Canvas, fmt
from .marks import LABEL_ROOM_MM, arrow as _arrow, bounds, markup as _markup, union, vector as _vector
from .scheme import scheme_layers
from .sheet import FORMATS, TitleBlock, choose_format, new_sheet, note_lines
from .style import Style
from .text import ASCENT, DESCENT, minus_signs, runs, width as text_width
from .. import linalg as la
from ..spatial import PointGrid

__all__ = ["Heading", "minus_signs", "draw_plan", "draw_scheme", "draw_centres", "plan_layers", "centre_rays", "fmt",
           "detail_of", "detail_caption", "detail_layers"]

#: Images closer than this share one label ("p ≡ b"), mm.
COINCIDE_MM = 0.3
#: Two plan images closer than this (mm) are one point for ``data-from``/``data-to``; the
#: pole is matched first, so a fixed point's image (at the pole) is labelled as the pole.
SAME_IMAGE_MM = 1e-9


@dataclass(frozen=True)
class Heading:
    """The words of a sheet's title block: mechanism, sheet name, position. A negative number
    in the position (``s = -0.12 m``) is written with the minus sign: ``s = −0.12 m``."""

    mechanism: str
    sheet: str
    position: str

    def __post_init__(self) -> None:
        object.__setattr__(self, "position", minus_signs(self.position))



def direction_text(dx: float, dy: float) -> str:
    """The direction of (dx, dy) in degrees, in (−180°, 180°]: a vector along −x reads 180
    whatever the sign of the rounding noise in dy (atan2 gives −180 for dy = −0.0)."""
    deg = math.degrees(math.atan2(dy, dx)) + 0.0
    return repr(180.0 if deg == -180.0 else deg)


#: Below this length on paper (mm) a vector is a rounding zero: its direction reads 0.0, not
#: whichever way the noise points (a diagram's ordinate of 1e-13 J drawn 1e-14 mm long).
ZERO_LENGTH_MM = 1e-9


def _direction(canvas: Canvas, tail, head) -> str:
    """The exact direction tail → head in degrees, SVG paper frame (y down)."""
    (x0, y0), (x1, y1) = canvas.paper(tail), canvas.paper(head)
    if math.hypot(x1 - x0, y1 - y0) < ZERO_LENGTH_MM:
        return "0.0"
    return direction_text(x1 - x0, y1 - y0)


def _image_label(plan: Plan, xy, images: PointGrid | None = None) -> str | None:
    """The label of the plan image at ``xy`` (the first within SAME_IMAGE_MM: the pole first);
    ``images``: the plan's points in a :class:`~plans.spatial.PointGrid` (:func:`_images`), to
    look only near ``xy``."""
    for k in range(len(plan.points)) if images is None else images.near(xy):
        p = plan.points[k]
        if math.hypot(p.xy[0] - xy[0], p.xy[1] - xy[1]) <= SAME_IMAGE_MM:
            return p.label
    return None


def _images(plan: Plan) -> PointGrid:
    """The plan's images in a grid, for :func:`_image_label`."""
    grid = PointGrid(SAME_IMAGE_MM)
    for p in plan.points:
        grid.add(p.xy)
    return grid


def _tag(el, canvas: Canvas, quantity: str, value: float, tail, head, start: str | None, end: str | None) -> None:
    """The attributes ``plans check`` measures a vector by (see the module docstring)."""
    el.attribs["data-quantity"] = quantity
    el.attribs["data-value"] = repr(float(value))
    el.attribs["data-direction"] = _direction(canvas, tail, head)
    if start is not None:
        el.attribs["data-from"] = start
    if end is not None:
        el.attribs["data-to"] = end


def _sheet(bounds, heading: Heading, scales: str, ident: str, style: Style):
    """The smallest standard sheet holding ``bounds`` (A3 landscape when none does: the
    scales are chosen so that it never happens, see constructions.scales)."""
    w, h = bounds[2] - bounds[0], bounds[3] - bounds[1]
    f = choose_format(w, h) or FORMATS[2]
    return new_sheet(f, bounds, ident=ident, style=style,
                     block=TitleBlock(heading.mechanism, heading.sheet, heading.position, scales))


def _preferred(xy, segments: list[tuple[tuple[float, float], tuple[float, float]]], centre,
               ends: PointGrid | None = None) -> np.ndarray:
    """Where a label of image ``xy`` goes: away from the segments that meet there, else away
    from the plan's centre. ``ends``: the segments' ends (2k: the start of segment k, 2k + 1
    its end) in a :class:`~plans.spatial.PointGrid` of reach 1e-6, to look only near ``xy``."""
    pull = np.zeros(2)
    for e in range(2 * len(segments)) if ends is None else ends.near(xy):
        a, b = segments[e // 2]
        end, other = (a, b) if e % 2 == 0 else (b, a)
        if math.dist(end, xy) < 1e-6:
            d = np.subtract(other, end)
            n = float(la.norm(d))
            if n > 1e-9:
                pull += d / n
    if la.norm(pull) > 1e-6:
        return -pull
    away = np.subtract(xy, centre)
    return away if la.norm(away) > 1e-9 else np.array([0.6, 0.8])


def draw_plan(plan: Plan, heading: Heading, *, ident: str, style: Style = Style(), notes: Sequence[str] = ()) -> str:
    """SVG text of a velocity or acceleration plan; ``notes``: lines of text on the sheet
    (why a plan is drawn as its pole alone, which scale rule gave way). Images crowding the
    pole get an enlarged detail beside the plan (:func:`detail_layers`)."""
    coords = [p.xy for p in plan.points] + [l.start for l in plan.lines] + [l.end for l in plan.lines]
    sym = "μ_V" if plan.kind == "velocity" else "μ_a"
    unit = {"velocity": "(m/s)/mm", "acceleration": "(m/s²)/mm"}[plan.kind]
    scale = f"{sym} = {plan.mu:g} {unit}; vector = drawn length × {sym}" if plan.vectors else \
        f"pole {plan.pole} alone: no vector to draw, no scale {sym}"
    detail = detail_of(plan, tuple((a.x1 - a.x0, a.y1 - a.y0) for a in (f.area for f in FORMATS)), style) \
        if plan.vectors else None
    box = bounds(coords)
    if detail is not None:
        box = union(box, detail.box)
    dwg, canvas = _sheet(box, heading, scale, ident, style)
    plan_layers(dwg, canvas, plan, ident, style, unlabelled=_crowd(detail))
    if detail is not None:
        detail_layers(dwg, canvas, plan, detail, ident, style)
    if notes:
        note_lines(canvas, dwg.add(dwg.g(id=f"{ident}-notes")), notes, style)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))   # outside the plan: not vectors
    return dwg.tostring()


def detail_caption(plan: Plan, k: int, symbol: str | None = None) -> str:
    """The statement of a detail ×k of ``plan``: its factor and its own scale, written
    ``symbol`` (μ_V or μ_a by the plan's kind when None)."""
    sym = symbol or ("μ_V" if plan.kind == "velocity" else "μ_a")
    unit = {"velocity": "(m/s)/mm", "acceleration": "(m/s²)/mm"}.get(plan.kind, "per mm")
    return f"detail ×{k}, {sym} = {_decimal(plan.mu / k)} {unit}"


def _decimal(x: float, digits: int = 4) -> str:
    """``x`` to ``digits`` significant digits, written without an exponent between 1e-9 and
    1e9 (0.00001693, as a teacher writes a scale), with one beyond."""
    if x == 0 or not 1e-9 <= abs(x) < 1e9:
        return f"{x:.{digits}g}"
    decimals = max(0, digits - 1 - math.floor(math.log10(abs(x))))
    text = f"{round(x, decimals):.{decimals}f}"
    return text.rstrip("0").rstrip(".") if "." in text else text


def detail_of(plan: Plan, sizes: tuple[tuple[float, float], ...], style: Style,
              symbol: str | None = None) -> PlanDetail | None:
    """The detail of ``plan``'s pole region (:func:`~plans.constructions.detail.pole_detail`)
    placed so that the plan and it, with room for their letters, fit one of ``sizes`` (mm)."""
    def caption(k: int) -> tuple[float, float]:
        return text_width(runs(detail_caption(plan, k, symbol)), style.small_text, False), \
            (ASCENT + DESCENT) * style.small_text + 0.5

    return pole_detail(plan, sizes=sizes, room=LABEL_ROOM_MM, caption=caption)


def _crowd(detail: PlanDetail | None) -> frozenset[str]:
    """The images the detail names, but the pole (their letters are left off the plan itself)."""
    if detail is None:
        return frozenset()
    return frozenset(p.label for p in detail.plan.points if p.label != detail.plan.pole)


def detail_layers(dwg, canvas: Canvas, plan: Plan, detail: PlanDetail, ident: str, style: Style,
                  symbol: str | None = None) -> None:
    """The detail ×k of ``plan``'s pole region: a thin circle round the region on the plan,
    the detail's own circle, its caption and the detail itself, a plan group of its own
    (``{ident}-detail-plan``, μ/k) measured by ``plans check`` like the plan."""
    detail_frame(dwg, canvas, detail, detail_caption(plan, detail.k, symbol), ident, style)
    plan_layers(dwg, canvas, detail.plan, f"{ident}-detail", style)


def detail_frame(dwg, canvas: Canvas, region, caption: str, ident: str, style: Style) -> None:
    """A detail's frame (:class:`~plans.constructions.detail.PoleRegion`): a thin circle round
    the region on the drawing, the detail's own circle and its ``caption`` above it."""
    marks = dwg.g(id=f"{ident}-detail-marks", stroke=style.construction_colour, stroke_width=fmt(style.thin, 3),
                  fill="none")
    canvas.circle(marks, region.middle, region.region, id=f"{ident}-detail-region")
    canvas.circle(marks, region.centre, region.frame, id=f"{ident}-detail-frame")
    dwg.add(marks)
    text = dwg.g(id=f"{ident}-detail-caption")
    x, y = canvas.paper(region.caption)
    canvas.text(text, (x, y - DESCENT * style.small_text - 0.25), caption, size=style.small_text,
                ident=f"{ident}-detail-statement")
    dwg.add(text)


def draw_empty(kind: str, heading: Heading, *, ident: str, style: Style = Style(), notes: Sequence[str] = ()) -> str:
    """A sheet of ``kind`` (``force``, ``lever`` …) asked for but with nothing to draw at this
    position: a plan group with no vector (``data-vectors="0"``, which ``plans check`` reports as
    empty) and ``notes`` saying why."""
    dwg, canvas = _sheet((0.0, 0.0, 120.0, 60.0), heading, "nothing to draw: no scale", ident, style)
    g = dwg.g(id=f"{ident}-plan")
    g.attribs["data-mu"] = "1.0"
    g.attribs["data-plan"] = kind
    g.attribs["data-vectors"] = "0"
    dwg.add(g)
    if notes:
        note_lines(canvas, dwg.add(dwg.g(id=f"{ident}-notes")), notes, style)
    return dwg.tostring()


def plan_group(dwg, canvas: Canvas, plan, kind: str, ident: str, style: Style):
    """The group of a plan of ``kind`` (velocity, acceleration, force …) that ``plans check``
    reads: its scale (``data-mu``), kind and vector count, holding the plan's construction
    lines (dashed, each tagged with the quantity it constructs). ``plan`` has ``mu``,
    ``vectors`` and ``lines``."""
    g = dwg.g(id=f"{ident}-plan")
    g.attribs["data-mu"] = repr(plan.mu)
    g.attribs["data-plan"] = kind
    g.attribs["data-vectors"] = str(len(plan.vectors))
    lines = dwg.g(id=f"{ident}-construction", stroke=style.construction_colour, stroke_width=fmt(style.thin, 3),
                  stroke_dasharray=style.dash, fill="none")
    for k, l in enumerate(plan.lines):
        el = canvas.line(lines, l.start, l.end, id=f"{ident}-cl{k}")
        el.attribs["data-construction"] = l.quantity
    g.add(lines)
    return g


def plan_layers(dwg, canvas: Canvas, plan: Plan, ident: str, style: Style, *,
                unlabelled: frozenset[str] = frozenset()) -> None:
    """A plan's group on ``canvas``: construction lines, tagged vectors with their heads, the
    images' dots, and label requests (placed by the caller's ``canvas.place_labels``); the
    images in ``unlabelled`` (named on a detail instead) keep their dot but get no letter."""
    g = plan_group(dwg, canvas, plan, plan.kind, ident, style)
    images = _images(plan)
    for k, v in enumerate(plan.vectors):
        colour = style.vector_colour if v.kind in ("absolute", "relative") else style.component_colour
        el = _vector(canvas, g, v.tail, v.head, colour, f"{ident}-v{k}", f"{ident}-h{k}", style)
        _tag(el, canvas, v.quantity, v.value, v.tail, v.head, _image_label(plan, v.tail, images),
             _image_label(plan, v.head, images))
    labels = dwg.g(id=f"{ident}-labels", fill=style.colour)
    segments = [(v.tail, v.head) for v in plan.vectors] + [(l.start, l.end) for l in plan.lines]
    ends = PointGrid(1e-6)
    for a, b in segments:
        ends.add(a)
        ends.add(b)
    centre = np.mean([p.xy for p in plan.points], axis=0)
    groups: list[list] = []
    firsts = PointGrid(COINCIDE_MM)     # each group's first image, to find a coinciding one near
    for p in plan.points:
        same = next((groups[k] for k in firsts.near(p.xy) if math.dist(groups[k][0].xy, p.xy) < COINCIDE_MM), None)
        if same is None:
            groups.append([p])
            firsts.add(p.xy)
        else:
            same.append(p)
    for k, grp in enumerate(groups):
        xy = grp[0].xy
        canvas.circle(labels, xy, 0.45, filled=True, id=f"{ident}-d{k}")
        named = [p for p in grp if p.label not in unlabelled]
        if not named:
            continue
        text = " ≡ ".join(_markup(p.label) for p in named)
        canvas.label(labels, xy, text, size=style.text, prefer=_preferred(xy, segments, centre, ends),
                     ident=f"{ident}-l{k}", digits=False, near=0.5)
    g.add(labels)
    dwg.add(g)


def _scheme_coords(sch: Scheme) -> list:
    return list(sch.points.values()) + [g.start for g in sch.guides] + [g.end for g in sch.guides] + \
        [p for c in sch.cylinders for p in c.barrel] + [p for a in sch.inputs for p in (a.start, a.end)]


def draw_scheme(sch: Scheme, heading: Heading, *, formula: str, ident: str, style: Style = Style()) -> str:
    """SVG text of the kinematic scheme."""
    dwg, canvas = _sheet(bounds(_scheme_coords(sch)), heading, f"μ_l = {sch.mu_l:g} m/mm;  {formula}", ident, style)
    scheme_layers(dwg, canvas, sch, ident, style)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))
    return dwg.tostring()


def centre_rays(dwg, canvas: Canvas, rays, mu_l: float, *, ident: str, group: str, style: Style, **attrs):
    """The group of measured segments centre → point (``CentreRay``), each tagged so that
    ``plans check`` reads length × μl = |X P| in metres; ``attrs`` style the group."""
    g = dwg.g(id=group, stroke=style.component_colour, stroke_width=fmt(style.thin, 3), fill="none", **attrs)
    g.attribs["data-mu"] = repr(mu_l)
    g.attribs["data-plan"] = "centres"
    g.attribs["data-vectors"] = str(len(rays))
    for k, r in enumerate(rays):
        el = canvas.line(g, r.start, r.end, id=f"{ident}-r{k}")
        point, _, centre = r.quantity.partition(":")[2].partition("/")
        _tag(el, canvas, r.quantity, r.value, r.start, r.end, centre, point)
    return g


def draw_centres(sheet: CentresSheet, heading: Heading, *, formula: str, ident: str, style: Style = Style()) -> str:
    """SVG text of the instantaneous-centres sheet: the scheme, the centres, the measured
    segments centre → point (tagged, length × μl = distance in m) and the construction lines."""
    marks = [m.xy for m in sheet.marks if m.xy is not None]
    tips = [tuple(np.add(m.anchor, np.multiply(m.direction, 18.0))) for m in sheet.marks if m.xy is None]
    coords = _scheme_coords(sheet.scheme) + marks + tips + [xy for _, xy in sheet.special] + \
        [p for line in sheet.lines for p in line]
    dwg, canvas = _sheet(bounds(coords), heading, f"μ_l = {sheet.mu_l:g} m/mm; P_j: centre of link j, "
                         f"P_j–X ⊥ v_X;  {formula}", ident, style)
    cons = dwg.g(id=f"{ident}-construction", stroke=style.construction_colour, stroke_width=fmt(style.thin, 3),
                 stroke_dasharray=style.dash, fill="none")
    for k, (a, b) in enumerate(sheet.lines):
        canvas.line(cons, a, b, id=f"{ident}-cl{k}")
    dwg.add(cons)
    scheme_layers(dwg, canvas, sheet.scheme, ident, style)
    dwg.add(centre_rays(dwg, canvas, sheet.rays, sheet.mu_l, ident=ident, group=f"{ident}-centres", style=style,
                        stroke_dasharray=style.dash))
    labels = dwg.g(id=f"{ident}-marks", fill=style.component_colour)
    for k, m in enumerate(sheet.marks):
        if m.xy is not None:
            canvas.circle(labels, m.xy, 0.9, filled=True, id=f"{ident}-c{k}")
            canvas.label(labels, m.xy, _markup(m.name), size=style.text, prefer=(1.0, 1.0), ident=f"{ident}-cl{k}t",
                         digits=False, near=0.6, fill=style.component_colour)
            continue
        tip = tuple(np.add(m.anchor, np.multiply(m.direction, 18.0)))
        canvas.line(labels, m.anchor, tip, stroke=style.component_colour, stroke_width=fmt(style.thin, 3),
                    id=f"{ident}-cd{k}")
        _arrow(canvas, labels, m.anchor, tip, style.component_colour, f"{ident}-ch{k}", style, of=f"{ident}-cd{k}")
        note = f"{_markup(m.name)} at ∞" if m.infinite else f"{_markup(m.name)} (off the sheet)"
        canvas.label(labels, tip, note, size=style.small_text, prefer=m.direction, ident=f"{ident}-ct{k}",
                     digits=False, fill=style.component_colour)
    for k, (name, xy) in enumerate(sheet.special):
        canvas.circle(labels, xy, 0.7, fill="#fff", stroke=style.component_colour, stroke_width=fmt(style.thin, 3),
                      id=f"{ident}-s{k}")
        canvas.label(labels, xy, _markup(name), size=style.small_text, prefer=(1.0, -1.0), ident=f"{ident}-st{k}",
                     digits=False, near=0.5, fill=style.component_colour)
    dwg.add(labels)
    if sheet.notes:
        note_lines(canvas, dwg.add(dwg.g(id=f"{ident}-notes")), sheet.notes, style)
    canvas.place_labels(labels)
    return dwg.tostring()

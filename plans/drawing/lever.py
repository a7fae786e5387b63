"""Zhukovsky's lever sheet, in SVG.

**Lever** (:func:`draw_lever`): the velocity plan turned 90° clockwise (thin), the forces at
the turned images as arrows in μF (a moment's couple dashed, the balancing element red), the
arms h_i from the pole as thin lines to the foot of each perpendicular (the line of action
drawn on, dashed, when the foot is off the arrow), and beside it the written equation
Σ M_p = 0 term by term and the balancing result (an arm of 0 — a line through the pole —
written as such). When loaded images crowd the pole, an enlarged detail ×k of the pole region
(:mod:`plans.constructions.lever_detail`) is drawn beside the lever, captioned "detail ×k,
μV = …, μF = …": a lever of its own, its images, forces at their own μF′ and arms k·h
labelled h_i as on the lever, which leaves off its letters of those images, short forces and
arms. The labels are asked for in the orders of :data:`LABEL_ORDERS` in turn, until one
places them all clear.

What ``plans check`` reads: see :mod:`.forces`.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import DrawingError
from ..constructions.forces import Lever, LeverForce
from ..constructions.detail import NEAR_MM
from ..constructions.lever_detail import LeverDetail, lever_detail
from .canvas import Canvas, fmt
from .force_marks import (PANEL_GAP_MM, TABLE_LEAD_MM, TABLE_TEXT_MM, _dashed_vector, _number, _place, _signed,
                          _solid_vector, _sub, symbol)
from .marks import LABEL_ROOM_MM, bounds, markup as _markup, union
from .sheet import FORMATS, TitleBlock, choose_format, new_sheet
from .style import Style
from .svg import Heading, _decimal, _tag, detail_frame, direction_text
from .text import ASCENT, DESCENT, runs, width, wrap
from .. import linalg as la

__all__ = ["draw_lever", "lever_caption", "MIN_ARM_MM"]

#: Width of the lever's written computation, mm.
LEVER_TEXT_MM = 118.0
#: Arms shorter than this are not drawn (their force's line passes through the pole), mm.
MIN_ARM_MM = 0.5
#: Where else along its arm (a fraction from the pole) an arm's label h_i may go, tried in
#: turn after the arm's middle.
ARM_LABEL_AT = (0.65, 0.35, 0.8, 0.2)
#: Side of the right-angle mark at the foot of an arm, mm.
RIGHT_ANGLE_MM = 1.8


def _arm_numbers(lever: Lever, detail: LeverDetail | None = None) -> dict[int, int]:
    """Index of a force on the lever → the number of its drawn arm (1, 2, … in order): drawn
    on the lever, or in its pole detail."""
    again = {f.quantity: f for f in detail.lever.forces} if detail is not None else {}
    drawn = [k for k, f in enumerate(lever.forces)
             if f.arm >= MIN_ARM_MM or (f.quantity in again and again[f.quantity].arm >= MIN_ARM_MM)]
    return {k: n + 1 for n, k in enumerate(drawn)}


def _arm_text(f: LeverForce, h: str) -> str:
    """A load's row: its value, arm and moment about p; an arm of 0 (its line through p) as such."""
    if f.arm == 0.0:
        return f"  {symbol(f.quantity)} = {_number(f.value)} N, {h} = 0 (its line passes through p):  0"
    return f"  {symbol(f.quantity)} = {_number(f.value)} N, {h} = {_number(f.arm)} mm:  {_signed(f.moment, 5)}"


def _lever_text(lever: Lever, note: str = "", detail: LeverDetail | None = None) -> list[str]:
    """The written computation of the lever (rows of label markup); ``note``: why no load is
    on it (the first row after the plan's, when there is none); ``detail``: its pole detail."""
    rows = [f"Velocity plan turned 90° {lever.sense} about the pole {lever.pole} (μ_V = {lever.mu_v:g} (m/s)/mm);"]
    if lever.forces:
        rows += [f"forces applied at the images of their points, μ_F = {lever.mu:g} N/mm; arms h in mm;",
                 "moments about p, counter-clockwise positive (N·mm):"]
    loads = [f for f in lever.forces if f.kind != "balance"]
    numbers = _arm_numbers(lever, detail)
    couples: dict[str, LeverForce] = {}
    for f in lever.forces:
        if f.kind == "couple":
            couples.setdefault(f.source, f)
    for src, f in couples.items():
        rows.append(f"  {symbol(src)} as the couple {symbol(f.quantity)} = {symbol(src)} / l = {_number(f.value)} N "
                    "⊥ the link at the images of its two points (dashed)")
    for f in loads:
        k = lever.forces.index(f)
        rows.append(_arm_text(f, f"h_{_sub(str(numbers[k]))}" if k in numbers else "h"))
    if not loads:
        rows.append((note or "no load acts at this position") + ";")
    if not any(f.kind == "balance" for f in lever.forces):      # exactly 0: no force, nothing drawn
        unit = "N" if lever.balance == "force" else "N·m"
        rows.append(f"Σ M_p(loads) = 0 N·mm, so {symbol(lever.balance_quantity)} = 0 {unit}: nothing to balance "
                    "(none drawn)")
        return rows
    rows.append(f"Σ M_p(loads) = {_signed(lever.moment_sum, 5)} N·mm;  Σ M_p = 0 gives")
    if lever.balance == "force":
        f = lever.forces[-1]
        k = lever.forces.index(f)
        h = f"h_{_sub(str(numbers[k]))}" if k in numbers else "h"
        rows.append(f"  {symbol(lever.balance_quantity)} = −Σ M_p(loads) / (±{h}) = "
                    f"{_signed(-lever.moment_sum, 5)} / ({_signed(lever.unit_moment, 4)}) = "
                    f"{_number(lever.result, 5)} N")
        rows.append(f"  (along the given direction; |{symbol(lever.balance_quantity)}| = {_number(abs(lever.result), 5)}"
                    " N)")
    else:
        m = symbol(lever.balance_quantity)
        rows.append(f"  {m} as the couple F′ = {m} / l_{{OA}} ⊥ OA at o and a: its moment about p is {m}·k, "
                    f"k = {_signed(lever.unit_moment, 4)} mm/m;")
        sense = "counter-clockwise" if lever.result > 0 else "clockwise" if lever.result < 0 else "no moment"
        rows.append(f"  {m} = −Σ M_p(loads) / k = {_number(lever.result, 5)} N·m ({sense})")
        if lever.omega and lever.result:
            drive = "driving" if lever.result * lever.omega > 0 else "braking"
            rows.append(f"  ω_1 = {_number(lever.omega, 4)} rad/s: {m} is {drive}")
    return rows


#: A lever force drawn shorter than this (mm) records the direction of its line, not of its ends.
SHORT_MM = 1e-6


def lever_caption(lever: Lever, k: int, mu: float) -> str:
    """The statement of the lever's pole detail ×k: its factor and its two scales."""
    return f"detail ×{k}, μ_V = {_decimal(lever.mu_v / k)} (m/s)/mm, μ_F = {mu:g} N/mm"


def _lever_detail(lever: Lever, text_w: float, text_h: float, style: Style) -> LeverDetail | None:
    """The pole detail of ``lever`` placed so that the lever, it and the written computation
    (``text_w`` × ``text_h`` mm, beside or below) fit one sheet's drawing area."""
    sizes = []
    for f in FORMATS:
        aw, ah = f.area.x1 - f.area.x0, f.area.y1 - f.area.y0
        sizes += [(aw - PANEL_GAP_MM - text_w, ah), (aw, ah - PANEL_GAP_MM - text_h)]

    def caption(k: int, mu: float) -> tuple[float, float]:
        return width(runs(lever_caption(lever, k, mu)), style.small_text, False), \
            (ASCENT + DESCENT) * style.small_text + 0.5

    return lever_detail(lever, sizes=tuple((w, h) for w, h in sizes if w > 0 and h > 0), room=LABEL_ROOM_MM,
                        caption=caption)


def _rows(lever: Lever, note: str, detail: LeverDetail | None) -> tuple[list[str], float, float]:
    rows = [r for row in _lever_text(lever, note, detail) for r in wrap(row, LEVER_TEXT_MM, TABLE_TEXT_MM,
                                                                        indent="      ")]
    return rows, max(width(runs(r), TABLE_TEXT_MM, False) for r in rows) + 2.0, TABLE_LEAD_MM * (len(rows) + 1)


def draw_lever(lever: Lever, heading: Heading, *, ident: str, style: Style = Style(), note: str = "") -> str:
    """SVG text of Zhukovsky's lever at one position (see the module docstring); ``note``: why
    no load is on it, written in its computation when none is. Loaded images crowding the pole
    get an enlarged detail beside the lever (:func:`~plans.constructions.lever_detail.lever_detail`)."""
    coords = [p.xy for p in lever.points] + [f.head for f in lever.forces] + [f.foot for f in lever.forces]
    content = bounds(coords)
    rows, text_w, text_h = _rows(lever, note, None)
    detail = _lever_detail(lever, text_w, text_h, style) if lever.forces else None
    if detail is not None:
        rows, text_w, text_h = _rows(lever, note, detail)
        content = union(content, detail.box)
    cw, ch = content[2] - content[0], content[3] - content[1]
    beside = (cw + PANEL_GAP_MM + text_w, max(ch, text_h))
    below = (max(cw, text_w), ch + PANEL_GAP_MM + text_h)
    fmt_b, fmt_u = choose_format(*beside), choose_format(*below)
    order = {f: k for k, f in enumerate(FORMATS)}
    if fmt_b is None and fmt_u is None:
        raise DrawingError(f"Zhukovsky's lever is {cw:.0f} mm × {ch:.0f} mm with its forces and arms, beyond an A3 "
                           "sheet with its computation: turn a velocity plan of a coarser μV")
    use_beside = fmt_b is not None and (fmt_u is None or order[fmt_b] <= order[fmt_u])
    W, H = beside if use_beside else below
    fmt_ = (fmt_b if use_beside else fmt_u) or FORMATS[2]
    scales = f"μ_V = {lever.mu_v:g} (m/s)/mm (turned {lever.sense});  " + \
        (f"μ_F = {lever.mu:g} N/mm" if lever.forces else "μ_F: no force to draw")
    numbers = _arm_numbers(lever, detail)
    best: tuple[int, str] | None = None
    for asked in LABEL_ORDERS:
        crowded, svg = _lever_sheet(lever, heading, ident, style, fmt_, W, H, scales, cw, ch, use_beside, content,
                                    rows, text_h, numbers, detail, asked)
        if crowded == 0:
            return svg
        if best is None or crowded < best[0]:
            best = (crowded, svg)
    return best[1]


#: The orders in which the lever's labels are tried, until one places every label clear:
#: (images' letters first, arms' labels anywhere along their arms, the shortest arms' first).
LABEL_ORDERS = ((False, False, False), (True, True, False), (False, True, False), (True, False, False),
                (True, True, True), (False, True, True))


def _lever_sheet(lever: Lever, heading: Heading, ident: str, style: Style, fmt_, W: float, H: float, scales: str,
                 cw: float, ch: float, use_beside: bool, content, rows, text_h: float, numbers: dict[int, int],
                 detail: LeverDetail | None, order: tuple[bool, bool, bool]) -> tuple[int, str]:
    """The lever's sheet with its labels asked for in ``order`` (see LABEL_ORDERS): how many
    labels found no free place, and the SVG text."""
    dwg, canvas = new_sheet(fmt_, (0.0, 0.0, W, H), ident=ident, style=style,
                            block=TitleBlock(heading.mechanism, heading.sheet, heading.position, scales))
    ox, oy = canvas.dx, canvas.dy - H
    if use_beside:
        lever_box = (ox, oy, ox + cw, oy + H)
        tx, ty = ox + cw + PANEL_GAP_MM, oy + (H - text_h) / 2
    else:
        lever_box = (ox, oy, ox + W, oy + ch)
        tx, ty = ox, oy + ch + PANEL_GAP_MM
    _place(canvas, content, lever_box)
    _lever_layers(dwg, canvas, lever, ident, style, numbers=numbers, detail=detail, order=order)
    if detail is not None:
        _lever_detail_layers(dwg, canvas, lever, detail, ident, style, numbers, order)
    texts = dwg.g(id=f"{ident}-texts")
    for r, row in enumerate(rows):
        canvas.text(texts, (tx, ty + TABLE_LEAD_MM * (r + 0.8)), row, size=TABLE_TEXT_MM, ident=f"{ident}-w{r}")
    dwg.add(texts)
    canvas.place_labels(dwg.add(dwg.g(id=f"{ident}-leaders")))
    return canvas.crowded, dwg.tostring()


def _lever_detail_layers(dwg, canvas: Canvas, lever: Lever, detail: LeverDetail, ident: str, style: Style,
                         numbers: dict[int, int], order: tuple[bool, bool, bool] = (False, False, False)) -> None:
    """The pole detail: a thin circle round the region on the lever, the detail's own circle,
    its caption and the enlarged lever, a lever group of its own (``data-detail="pole"``)."""
    detail_frame(dwg, canvas, detail, lever_caption(lever, detail.k, detail.lever.mu), ident, style)
    index = {f.quantity: k for k, f in enumerate(lever.forces)}
    mine = {k: numbers[index[f.quantity]] for k, f in enumerate(detail.lever.forces) if index[f.quantity] in numbers}
    _lever_layers(dwg, canvas, detail.lever, f"{ident}-detail", style, numbers=mine, tag_detail=True, order=order)


def _lever_layers(dwg, canvas: Canvas, lever: Lever, ident: str, style: Style, *, numbers: dict[int, int],
                  detail: LeverDetail | None = None, tag_detail: bool = False,
                  order: tuple[bool, bool, bool] = (False, False, False)) -> None:
    """The turned plan, the tagged forces, their arms and the images' letters of ``lever``;
    ``numbers``: force index → its arm's number; ``detail``: the pole detail, whose images,
    arms and short forces are lettered there, not here; ``tag_detail``: this is that detail;
    ``order``: (the images' letters asked for first, an arm's label anywhere along its arm, the
    arms' labels after the forces' names, shortest arm first) — else each force's name and
    its arm's label in turn, the images' letters last, an arm's label by its middle."""
    images_first, anywhere, short_first = order
    hidden: set[str] = set()
    inside: set[str] = set()
    if detail is not None:
        hidden = {p.label for p in detail.lever.points if p.label != lever.pole}
        inside = detail.quantities
    turned = dwg.g(id=f"{ident}-turned", stroke=style.colour, stroke_width=fmt(style.vector, 3), fill="none")
    turned.attribs["data-role"] = "turned velocity plan"
    for k, (a, b) in enumerate(lever.segments):
        canvas.line(turned, a, b, width=style.vector, id=f"{ident}-s{k}")
    dwg.add(turned)
    g = dwg.g(id=f"{ident}-lever")
    g.attribs["data-mu"] = repr(lever.mu)
    g.attribs["data-plan"] = "lever"
    g.attribs["data-mu-v"] = repr(lever.mu_v)
    g.attribs["data-sense"] = lever.sense
    g.attribs["data-vectors"] = str(len(lever.forces))
    g.attribs["data-pole"] = ",".join(canvas.xy(lever.pole_xy))
    if tag_detail:
        g.attribs["data-detail"] = "pole"
    cons = dwg.g(id=f"{ident}-arms", stroke=style.construction_colour, stroke_width=fmt(style.thin, 3), fill="none")
    labels = dwg.g(id=f"{ident}-labels", fill=style.colour)
    pole = np.asarray(lever.pole_xy)
    crowd = (np.asarray(detail.middle), detail.region + NEAR_MM) if detail is not None else None
    # label requests (an arm's length to sort by, canvas.label's arguments, its keywords);
    # else (a force's name, then its arm's label) in turn
    force_labels: list[tuple] = []
    arm_labels: list[tuple] = []
    for k, f in enumerate(lever.forces):
        colour = style.component_colour if f.kind == "balance" else style.vector_colour
        draw = _dashed_vector if f.quantity.startswith("F:M:") else _solid_vector
        el = draw(canvas, g, f.tail, f.head, colour, f"{ident}-v{k}", f"{ident}-h{k}", style)
        _tag(el, canvas, f.quantity, f.value, f.tail, f.head, f.at, f.quantity)
        if f.value / lever.mu < SHORT_MM:
            # far too short for its ends to carry a direction (a zero, or vanishing, balancing
            # element: its head is its tail in floating point): the direction of its line
            el.attribs["data-direction"] = direction_text(f.direction[0], -f.direction[1])
        el.attribs["data-h"] = repr(f.arm)
        el.attribs["data-moment"] = repr(f.moment)
        el.attribs["data-kind"] = f.kind
        in_detail = f.quantity in inside
        if not (in_detail and crowd is not None and math.dist(f.head, crowd[0]) <= crowd[1]):
            # (a short force at the crowd is lettered in the detail)
            ask = (0.0, (labels, f.head, symbol(f.quantity)),
                   dict(size=style.text, prefer=np.subtract(f.head, f.tail), ident=f"{ident}-vl{k}", digits=False,
                        fill=colour, near=0.6))
            (force_labels if images_first or short_first else arm_labels).append(ask)
        if f.arm < MIN_ARM_MM:
            continue
        arm = canvas.line(cons, pole, f.foot, id=f"{ident}-a{k}")
        arm.attribs["data-construction"] = "arm"
        arm.attribs["data-arm"] = f.quantity
        # the line of action on to the foot, when the foot is off the arrow
        t, hd, foot = np.asarray(f.tail), np.asarray(f.head), np.asarray(f.foot)
        d = hd - t
        s = la.dot(foot - t, d) / la.dot(d, d) if la.dot(d, d) > 0 else 0.0
        if s < 0 or s > 1:
            near = t if s < 0 else hd
            ext = canvas.line(cons, near, foot, id=f"{ident}-e{k}", stroke_dasharray=style.dash)
            ext.attribs["data-construction"] = "line of action"
        if f.arm >= 3 * RIGHT_ANGLE_MM and math.dist(f.tail, f.head) > 0:
            e1 = (pole - foot) / f.arm
            e2 = d / math.sqrt(la.dot(d, d))
            if la.dot(t - foot, e2) < 0:
                e2 = -e2
            r = RIGHT_ANGLE_MM
            canvas.polyline(cons, [foot + r * e1, foot + r * (e1 + e2), foot + r * e2], id=f"{ident}-ra{k}")
        if in_detail:
            continue                    # its arm is labelled in the detail
        mid = (pole + foot) / 2
        n = np.array([-(foot - pole)[1], (foot - pole)[0]])
        along = tuple(tuple(pole + t * (foot - pole)) for t in ARM_LABEL_AT) if anywhere else ()
        arm_labels.append((f.arm, (labels, tuple(mid), f"h_{_sub(str(numbers[k]))}"),
                           dict(size=style.small_text + 0.5, prefer=n, ident=f"{ident}-al{k}", digits=False,
                                fill=style.construction_colour, near=0.4, also=along)))
    g.add(cons)
    centre = np.mean([p.xy for p in lever.points], axis=0)
    seen: list[tuple[float, float]] = []
    image_labels: list[tuple] = []
    for k, p in enumerate(lever.points):
        if any(math.dist(p.xy, q) < 0.3 for q in seen):
            continue
        same = [q.label for q in lever.points if math.dist(q.xy, p.xy) < 0.3]
        seen.append(p.xy)
        canvas.circle(labels, p.xy, 0.45, filled=True, id=f"{ident}-d{k}")
        same = [s for s in same if s not in hidden]
        if not same:
            continue
        away = np.subtract(p.xy, centre)
        image_labels.append((0.0, (labels, p.xy, " ≡ ".join(_markup(s) for s in same)),
                             dict(size=style.text, prefer=away if la.norm(away) > 1e-9 else (-0.6, -0.8),
                                  ident=f"{ident}-l{k}", digits=False, near=0.5)))
    if short_first:
        arm_labels.sort(key=lambda ask: ask[0])         # only arms' labels here: the shortest arm first
    asks = image_labels + force_labels + arm_labels if images_first else force_labels + arm_labels + image_labels
    for _, args, kwargs in asks:
        canvas.label(*args, **kwargs)
    g.add(labels)
    dwg.add(g)


"""A rotor's assignment sheet (kind ``balancing``): A3 landscape with the standard frame and
title block; in the left column the shaft from the side with its planes (the masses' numbered,
the balancing planes L, the reference, and M), the end view with each mass's radius at its angle
(counter-clockwise from θ = 0), the table of m, r, θ and plane (the balancing planes' m and θ
asked: "?"), and the task; on the right a framed area for each polygon the key draws (the couple
polygon, two planes only, then the force polygon), each as large as the key's with room for its
letters, the room left over shared out. An area the sheet has no room for goes on an answer
sheet (``-assignment-2.svg``), which the task names. The sheet carries no answer.

Knows the constructions' balancing, plans.dynamics' balancing and the drawing (imported only when
a sheet is drawn); must not import the writing, the index, the random draws or the command line.
"""

from __future__ import annotations

import math

from ..constructions.balancing import shaft_planes
from ..constructions.scales import fitting_scale
from ..drawing.style import Style
from ..drawing.text import Box, wrap
from ..dynamics.balancing import balance_rotor
from ..scene import Scene

__all__ = ["rotor_task", "rotor_cells", "rotor_sheets"]

#: The left column (shaft, end view, table, task) and the areas' room, paper mm (y down).
LEFT = Box(23.0, 8.0, 214.0, 254.0)
RIGHT = Box(220.0, 8.0, 412.0, 254.0)
#: An answer sheet's room for the areas the assignment sheet has no room for.
ANSWER = Box(23.0, 8.0, 412.0, 254.0)
GAP_MM = 4.0
ROW_MM = 7.0
#: Around a polygon of the key: room for its vertex letters and vector labels (drawn outside
#: the key's polygon group), mm.
LABEL_ROOM_MM = 8.0
#: The shaft's side view at most this long, and the end view's largest radius at most, mm.
SHAFT_MM = 150.0
END_MM = 45.0
#: The end view is left out when its largest radius would be shorter than this, mm.
MIN_END_MM = 15.0
_COLUMNS = ("", "m, kg", "r, m", "θ, °", "plane, m")
_AREAS = {"balance-couple": ("couple", "Couple polygon about plane L", "μ = ________ kg·m²/mm"),
          "balance-force": ("force", "Force polygon", "μ = ________ kg·m/mm")}


def rotor_task(scene: Scene) -> str:
    """The task: the polygons to draw and what they give."""
    r = scene.rotor
    if not r.dynamic:
        return ("Task: find each mass's m·r; draw the force polygon of the m·r to scale and close it with (m·r)_{L}: "
                "it gives the balancing mass m_{L} in plane L and its angle θ_{L} (counter-clockwise from θ = 0). "
                "One plane balances the forces only: the couple of the masses in other planes stays.")
    return ("Task: with plane L as the reference plane, find each mass's m·r and m·r·l (l from L along the shaft, "
            "+ the way the planes' coordinate grows); draw the couple polygon of the m·r·l to scale and close it "
            "with (m·r·l)_{M}: it gives the mass m_{M} in plane M and its angle θ_{M}; then draw the force polygon "
            "of the m·r and (m·r)_{M} and close it with (m·r)_{L}: it gives m_{L} and θ_{L} (angles "
            "counter-clockwise from θ = 0).")


def rotor_cells(scene: Scene) -> list[str]:
    """The given data as text cells (markup): each mass, then each balancing plane."""
    r = scene.rotor
    cells = [f"m_{{{m.index + 1}}} = {m.mass:g} kg, r_{{{m.index + 1}}} = {m.radius:g} m, θ_{{{m.index + 1}}} = "
             f"{m.angle:g}°" + (f", plane at {m.plane:g} m" if m.plane is not None else "") for m in r.masses]
    for name, plane, radius in zip(("L", "M"), r.planes, r.radii):
        cells.append(f"plane {name}{' (reference)' if name == 'L' else ''} at {plane:g} m, r_{{{name}}} = {radius:g} m")
    return cells


def _areas(key: str) -> list:
    """The key's polygons as framed areas (:class:`plans.drawing.assignment.Area`), in the key's
    order, each with room for its labels."""
    from ..drawing.assignment import Area, drawings

    out = []
    for what, b in drawings(key):
        if what in _AREAS:
            kind, name, scale = _AREAS[what]
            out.append(Area(kind, name, scale, ((b.x1 - b.x0 + 2 * LABEL_ROOM_MM, b.y1 - b.y0 + 2 * LABEL_ROOM_MM),)))
    return out


def _stack(areas: list, region: Box, style: Style) -> tuple[list, list]:
    """The first areas that fit ``region`` one above the other (at least one), each as wide as
    the region and heightened alike to fill it, with its frame; and the areas left over."""
    from ..drawing.assignment import area_size

    sizes = [area_size(a, style) for a in areas]
    n, used = 0, 0.0
    while n < len(areas) and (n == 0 or used + GAP_MM + sizes[n][1] <= region.y1 - region.y0) \
            and sizes[n][0] <= region.x1 - region.x0 + (n == 0) * 1e9:
        used += (GAP_MM if n else 0.0) + sizes[n][1]
        n += 1
    extra = max(0.0, (region.y1 - region.y0 - used) / max(n, 1))
    placed, y = [], region.y0
    for a, (_, h) in zip(areas[:n], sizes[:n]):
        h = min(h + extra, region.y1 - y)
        placed.append((a, Box(region.x0, y, region.x1, y + h)))
        y += h + GAP_MM
    return placed, areas[n:]


def _table(dwg, canvas, scene: Scene, top: float, style: Style) -> float:
    """The data table from ``top`` (paper mm); returns its bottom."""
    r = scene.rotor
    x0, x1 = LEFT.x0, LEFT.x1
    first = 16.0
    cw = (x1 - x0 - first) / (len(_COLUMNS) - 1)
    xs = [x0] + [x0 + first + k * cw for k in range(len(_COLUMNS) - 1)]
    rows = [_COLUMNS]
    rows += [(str(m.index + 1), f"{m.mass:g}", f"{m.radius:g}", f"{m.angle:g}",
              "—" if m.plane is None else f"{m.plane:g}") for m in r.masses]
    rows += [(name, "?", f"{radius:g}", "?", f"{plane:g}") for name, plane, radius in zip(("L", "M"), r.planes, r.radii)]
    g = dwg.add(dwg.g(id="assignment-data", stroke=style.colour, fill="none", stroke_width=f"{style.thin:g}"))
    texts = dwg.add(dwg.g(id="assignment-data-text"))
    canvas.text(texts, (x0, top - 2.5), "Given (L: the reference plane; ?: to find; angles counter-clockwise from "
                "θ = 0, planes along the shaft)", size=style.text * 0.8)
    for i, row in enumerate(rows):
        y = top + i * ROW_MM
        for c, cell in enumerate(row):
            right = xs[c + 1] if c + 1 < len(xs) else x1
            g.add(dwg.rect(insert=(f"{xs[c]:.3f}", f"{y:.3f}"), size=(f"{right - xs[c]:.3f}", f"{ROW_MM:.3f}")))
            canvas.text(texts, (xs[c] + 2.0, y + ROW_MM / 2 + 1.2), cell, size=style.text,
                        ident=f"assignment-given{i}-{c}")
    return top + len(rows) * ROW_MM


def _content(canvas, x: float, y: float) -> tuple[float, float]:
    """Paper point (mm, y down) as the canvas's content point (y up)."""
    return x - canvas.dx, canvas.dy - y


def _shaft(dwg, canvas, scene: Scene, y: float, style: Style) -> float:
    """The shaft from the side with its planes, its axis at paper ``y``; returns the bottom of
    the view (``y`` when no mass has a plane: nothing drawn)."""
    b = balance_rotor(scene.rotor)
    s = shaft_planes(b, SHAFT_MM)
    if s is None:
        return y - 14.0
    x0 = (LEFT.x0 + LEFT.x1) / 2 - (s.ends[0] + s.ends[1]) / 2
    g = dwg.add(dwg.g(id="assignment-shaft", stroke=style.colour, fill="none"))
    g.attribs.update({"data-plan": "scheme", "data-mu": repr(s.mu)})    # a scheme to scale: plans check measures none
    canvas.text(dwg.add(dwg.g(id="assignment-shaft-text")), (LEFT.x0, y - 12.0),
                f"Shaft, side view (μ_l = {s.mu:g} m/mm)", size=style.text)
    canvas.line(g, _content(canvas, x0 + s.ends[0], y), _content(canvas, x0 + s.ends[1], y), width=style.link,
                stroke_width=f"{style.link:g}", stroke_dasharray="8 1.5 1 1.5", id="assignment-shaft-axis")
    labels = dwg.add(dwg.g(id="assignment-shaft-labels"))
    for k, (name, x) in enumerate(s.planes):
        balancing = name in ("L", "M")
        canvas.line(g, _content(canvas, x0 + x, y - 4.0), _content(canvas, x0 + x, y + 4.0), width=style.vector,
                    stroke_width=f"{style.vector:g}", id=f"assignment-shaft-plane{k}",
                    stroke=style.component_colour if balancing else style.colour)
        canvas.label(labels, _content(canvas, x0 + x, y - 4.0), name, size=style.small_text + 0.5,
                     prefer=(0.0, 1.0), ident=f"assignment-shaft-n{k}", digits=False, near=0.5)
    return y + 6.0


def _end_view(dwg, canvas, scene: Scene, top: float, bottom: float, style: Style) -> None:
    """The end view between paper ``top`` and ``bottom``: each mass's radius at its angle, the
    reference direction θ = 0 dash-dotted; left out where the room is too small."""
    r = scene.rotor
    room = min(END_MM, (bottom - top - 14.0) / 2.0)
    if room < MIN_END_MM:
        return
    mu = fitting_scale(max(m.radius for m in r.masses), room)
    cx, cy = (LEFT.x0 + LEFT.x1) / 2, (top + 8.0 + bottom) / 2      # the view in the middle of its room
    canvas.text(dwg.add(dwg.g(id="assignment-end-text")), (LEFT.x0, top + 3.0),
                f"End view: the masses' radii (μ_r = {mu:g} m/mm), θ counter-clockwise from θ = 0", size=style.text)
    g = dwg.add(dwg.g(id="assignment-end", stroke=style.colour, fill="none"))
    g.attribs.update({"data-plan": "scheme", "data-mu": repr(mu)})
    labels = dwg.add(dwg.g(id="assignment-end-labels"))
    c = _content(canvas, cx, cy)
    reach = max(m.radius for m in r.masses) / mu + 6.0
    canvas.line(g, c, (c[0] + reach, c[1]), width=style.thin, stroke_width=f"{style.thin:g}",
                stroke_dasharray="8 1.5 1 1.5", id="assignment-end-axis")
    canvas.label(labels, (c[0] + reach, c[1]), "θ = 0", size=style.small_text + 0.5, prefer=(1.0, 0.0),
                 ident="assignment-end-zero", digits=False)
    canvas.circle(g, c, 2.5, id="assignment-end-shaft", stroke_width=f"{style.vector:g}")
    for m in r.masses:
        t = math.radians(m.angle)
        tip = (c[0] + m.radius / mu * math.cos(t), c[1] + m.radius / mu * math.sin(t))
        canvas.line(g, c, tip, width=style.vector, stroke_width=f"{style.vector:g}", id=f"assignment-end-r{m.index}")
        canvas.circle(g, tip, 1.2, filled=True, id=f"assignment-end-m{m.index}", fill=style.colour,
                      stroke="none")
        canvas.label(labels, tip, str(m.index + 1), size=style.small_text + 0.5, prefer=(math.cos(t), math.sin(t)),
                     ident=f"assignment-end-n{m.index}", digits=False)


def rotor_sheets(scene: Scene, key: str, variant: str, style: Style = Style()) -> tuple[str, ...]:
    """SVG texts of a rotor variant's assignment: the assignment sheet, then an answer sheet for
    each batch of areas it has no room for (``key``: the variant's -balancing sheet, whose
    polygons size the areas; ``variant``: "variant 01")."""
    from ..drawing.assignment import answer_sheets, frame_areas
    from ..drawing.sheet import FORMATS, TitleBlock, new_sheet

    r = scene.rotor
    fmt_ = FORMATS[2]
    placed, rest = _stack(_areas(key), RIGHT, style)
    batches = []
    while rest:
        batch, rest = _stack(rest, ANSWER, style)
        batches.append(batch)
    told = rotor_task(scene) + "".join(f" Answer sheet {k + 2}: " + "; ".join(a.name for a, _ in batch) + "."
                                       for k, batch in enumerate(batches))
    task = wrap(told, LEFT.x1 - LEFT.x0 - 2.0, style.text)
    planes = ", ".join(f"{name} {p:g} m" for name, p in zip(("L (reference)", "M"), r.planes))
    position = f"{len(r.masses)} masses; balancing planes {planes}"
    block = TitleBlock(scene.title, f"Assignment, {variant}", position, "polygon scales: the student's")
    dwg, canvas = new_sheet(fmt_, (0.0, 0.0, 1.0, 1.0), ident="assignment", style=style, block=block)
    dwg.attribs["data-sheet"] = "assignment"
    shaft_bottom = _shaft(dwg, canvas, scene, LEFT.y0 + 18.0, style)
    task_top = LEFT.y1 - 5.0 * len(task) + 3.5
    table_top = task_top - 8.0 - (len(r.masses) + 1 + len(r.planes)) * ROW_MM
    _end_view(dwg, canvas, scene, shaft_bottom + 4.0, table_top - 8.0, style)
    _table(dwg, canvas, scene, table_top, style)
    texts = dwg.add(dwg.g(id="assignment-task-text"))
    for k, line in enumerate(task):
        canvas.text(texts, (LEFT.x0, task_top + 5.0 * k), line, size=style.text, ident=f"assignment-task{k}")
    frame_areas(dwg, canvas, placed, "assignment", style)
    canvas.place_labels(dwg.add(dwg.g(id="assignment-leaders")))
    return (dwg.tostring(), *answer_sheets(scene.title, variant, position, "polygon scales: the student's", batches,
                                           fmt_, style))

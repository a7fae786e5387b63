"""A variant's assignment sheet, kind by kind (:mod:`.asked`): its given data, its task and the
framed areas where the student draws.

- kinematics: the scheme at the first position, the lengths and the drive; areas for the
  velocity and acceleration plans;
- forces: the same with the masses, moments of inertia, gravity and loads; areas for the two
  plans, the force plans and Zhukovsky's lever;
- dynamics: the scheme at the cycle's first position, the loads (a load that follows the cycle
  as its table), the mean speed and δ; areas for the diagrams and Wittenbauer's diagram;
- gears: the train's side and end views with its teeth and the input speeds, the rest of the
  speed table empty, the pictures' room left blank;
- balancing: the rotor's shaft, end view and table of masses; areas for the couple and force
  polygons (:mod:`.rotor_sheet`).

Knows :mod:`.variants`, :mod:`.solving`, the constructions and the drawing (imported only when a
sheet is drawn); must not import the writing, the index, the random draws or the command line.
"""

from __future__ import annotations

import math

from ..scene import Scene
from ..scene.turning import Torque
from .asked import Asked, asked, kind_of
from .rotor_sheet import rotor_cells, rotor_task
from .solving import variant_data
from .variants import Drawn, Handout

__all__ = ["assignment_svg", "law_corners", "loads_cells", "task_text", "torque_text", "variant_asked", "given_and_task",
           "answers_at", "TYPING"]


def _found(d: Drawn) -> tuple[list[str], list[str]]:
    """The points and links a linkage's assignment names: every point not on the frame, every
    moving link but the driving one."""
    motion = d.sheets.motion
    mech = motion.mechanism
    return ([p for p in mech.sketch if motion.carrier(p) != "0"],
            [n for n in mech.moving if n != d.scene.drive.link])


def variant_asked(d: Drawn) -> tuple[Asked, ...]:
    """What variant ``d``'s assignment asks, with the exact values of its key."""
    if d.scene.drive is None:
        return asked(d.scene, d.sheets.report)
    points, links = _found(d)
    return asked(d.scene, d.sheets.report, points=points, links=links)


def _names(asked: tuple[Asked, ...]) -> str:
    """The asked quantities' symbols, in order: ``v_{A}, v_{B}, ω_{2}``."""
    return ", ".join(a.symbol for a in asked)


#: How to type a value in a Moodle field (Moodle's numerical parsing: a "." makes every "," a
#: thousands separator, a lone "," is read by the site's language, on an English one as a
#: thousands separator; a German site flags a "." as its thousands separator).
TYPING = ("Type each value as a plain number with a decimal point (0.5336) or in e-notation (5.336e-1), without a "
          "unit, spaces or a thousands separator: a comma may be read as one (0,5336 as 5336). Only if Moodle asks "
          "for the number without the thousands separator (.), type a decimal comma instead (0,5336).")


def answers_at(d: Drawn) -> str | None:
    """The position a linkage's answers are for, the first given one (``φ_{1} = 30°``,
    ``s = 0.1 m``); ``None`` for a gear train's or a machine's cycle (no one position)."""
    scene = d.scene
    if scene.drive is None or kind_of(scene) not in ("kinematics", "forces"):
        return None
    x = scene.drive.values[0]
    if scene.drive.kind.angular:
        return f"φ_{{{scene.drive.link}}} = {(x % 360.0) + 0.0:g}°"
    return f"s = {x:g} m"


#: A law's point is left out of the task's text when the line through its neighbours passes
#: within this fraction of the law's largest |F| of it (the law read linearly is the same).
CORNER_TOLERANCE = 1e-9


def law_corners(law: tuple[tuple[float, float], ...]) -> tuple[tuple[float, float], ...]:
    """The points of a load ``law`` ((x, F) pairs, x increasing) where its slope changes: the
    first, the last, and every point off the line through the kept one before and the next one.
    Read linearly between them, they give the same law (a flat run of 3015.9 N over ten points
    is written as its two ends)."""
    if len(law) <= 2:
        return tuple(law)
    tol = CORNER_TOLERANCE * max(abs(F) for _, F in law)
    kept = [law[0]]
    for k in range(1, len(law) - 1):
        (x0, f0), (x, f), (x1, f1) = kept[-1], law[k], law[k + 1]
        if abs(f0 + (f1 - f0) * (x - x0) / (x1 - x0) - f) > tol:
            kept.append(law[k])
    kept.append(law[-1])
    return tuple(kept)


def loads_cells(scene: Scene, unit: str = "m") -> tuple[list[str], list[str]]:
    """The data cells of the masses, inertias, gravity and constant loads, and the sentences
    describing the loads that follow the cycle (their tables; the output's travel in ``unit``)."""
    cells, laws = [], []
    for link, m in scene.masses.items():
        cells.append(f"m_{{{link}}} = {m.mass:g} kg")
        if m.inertia:
            cells.append(f"J_{{{m.centre}}} = {m.inertia:g} kg·m²")
    if scene.gravity:
        cells.append(f"g = {scene.gravity:g} m/s²")
    for f in scene.forces:
        name = f"F_{{{f.link}}}" if sum(g.link == f.link for g in scene.forces) == 1 else f"F_{{{f.link},{f.index + 1}}}"
        if f.law:
            way = "against its point's velocity" if f.oppose or f.vector is None else \
                f"at {math.degrees(math.atan2(f.vector[1], f.vector[0])) % 360.0 + 0.0:g}°"
            stroke = {"working": "on the working stroke", "return": "on the return stroke"}.get(f.stroke, "")
            table = ", ".join(f"{x:g} {unit} → {y:g} N" for x, y in law_corners(f.law))
            laws.append(f"{name} acts at {f.at} {way}{' ' + stroke if stroke else ''}; it follows the output's "
                        f"travel from its {f.origin} extreme (travel → force, linear between): {table}.")
        elif f.vector is None:
            cells.append(f"{name} = {f.magnitude:g} N at {f.at}, against v_{{{f.at}}}")
        else:
            size = math.hypot(*f.vector)
            angle = math.degrees(math.atan2(f.vector[1], f.vector[0])) % 360.0 + 0.0
            cells.append(f"{name} = {size:g} N at {f.at}, {angle:g}°")
    for mo in scene.moments:
        if mo.law is not None:
            laws.append(f"M_{{{mo.link}}} on link {mo.link} (N·m, counter-clockwise +) against the angle φ link {scene.drive.link} turns "
                        f"from the first position: {torque_text(mo.law)}.")
        else:
            cells.append(f"M_{{{mo.link}}} = {mo.value:g} N·m")
    return cells, laws


def torque_text(law: Torque) -> str:
    """A law in the crank angle as a task states it: its table's corners (``0° → 0, 30° → 3000``,
    linear between), its harmonics (T0 + Σ A·sin(kφ + φ0)) or its shapes, each with its numbers."""
    if law.table:
        rows = ", ".join(f"{x:g}° → {y:g}" for x, y in law_corners(law.table))
        return f"{rows} (linear between)"
    if law.harmonics:
        terms = " ".join(f"{'+' if a >= 0 else '−'} {abs(a):g}·sin({k:g}φ{f' + {p:g}°' if p else ''})"
                         for a, k, p in law.harmonics)
        return f"{law.mean:g} {terms}"
    parts = []
    for sh in law.shapes:
        where = f"from {sh.start:g}° to {sh.end:g}°"
        if sh.kind == "triangle":
            parts.append(f"a triangle {where}, {sh.peak:g} at {sh.apex:g}°")
        else:
            parts.append(f"a {sh.kind} {where}, {'peak' if sh.kind == 'semicircle' else 'height'} {sh.peak:g}")
    return ("the sum of " if len(parts) > 1 else "") + "; ".join(parts) + " (zero elsewhere)"


def task_text(scene: Scene, asked: tuple[Asked, ...], laws: list[str], at: str | None = None) -> str:
    """The task of a forces, dynamics or gears assignment (the kinematics one is the drawing's);
    ``at``: the position a forces assignment's answers are for, named instead of "the given
    position" (``φ_{1} = 60° (the first given position)``)."""
    kind = kind_of(scene)
    if kind == "balancing":
        return rotor_task(scene)
    if kind == "gears":
        return (f"Task: draw the linear- and angular-velocity pictures of the train to scale; find {_names(asked)} "
                "(speeds in rpm, + in the sense of the input) and check them by Willis' formula.")
    j = scene.drive.link
    if kind == "forces":
        b = next(a for a in asked if a.symbol in ("M_{b}", "F_{b}"))
        what = "balancing moment" if b.symbol == "M_{b}" else "balancing force"
        text = (f"Task: at {at or 'the given position'} draw the velocity and acceleration plans, find the inertia "
                f"forces and moments, then, group by group from the last one attached, the reactions in the kinematic "
                f"pairs by force plans and the {what} {b.symbol} on link {j} (counter-clockwise +); check {b.symbol} "
                f"by Zhukovsky's lever.")
    else:
        fw = next(a for a in asked if a.symbol in ("J_{fw}", "δ"))
        aim = ("the flywheel's moment of inertia J_{fw} on link " + j + " that keeps the speed within the given δ"
               if fw.symbol == "J_{fw}" else "the coefficient of speed fluctuation δ reached with the given flywheel")
        dyn = scene.dynamics
        turns = round(dyn.period / 360.0)
        cycle = "the cycle's positions" if turns == 1 else f"the cycle's positions ({turns} turns of link {j})"
        if dyn.driving == "law":
            laws = [f"M_{{d}} on link {j} (N·m, in its sense of rotation) against the angle φ it turns from the first position: "
                    f"{torque_text(dyn.torque)}.", *laws]
            find = f"draw the given M_{{d}}(φ) beside M_r; find {aim}."
        else:
            find = f"find the constant driving moment M_{{d}} and {aim}."
        text = (f"Task: over {cycle} find the reduced moment of the loads and the reduced moment of "
                f"inertia on link {j}; draw the works' diagrams (by graphical integration by chords: over each "
                f"interval between two positions the ordinate of M_r at its middle), the kinetic energy's change and "
                f"Wittenbauer's diagram through the positions' points; {find}")
    return " ".join([text, *laws])


def _dynamics_cells(scene: Scene) -> tuple[list[str], str]:
    d, dyn = scene.drive, scene.dynamics
    j = d.link
    cells = [f"ω_{{{j}m}} = {d.speed:g} rad/s (mean)"]
    if dyn.flywheel is not None:
        cells.append(f"J_{{fw}} = {dyn.flywheel:g} kg·m²")
    else:
        cells.append(f"δ = {dyn.delta:g}")
    if dyn.rotor_inertia:
        cells.append(f"J_{{rotor}} = {dyn.rotor_inertia:g} kg·m²")
    n, turns = len(d.values), round(dyn.period / 360.0)
    over = "its cycle" if turns == 1 else f"each of the {turns} turns of its cycle"
    position = f"{n} positions of link {j} over {over}, ω_{{{j}m}} = {d.speed:g} rad/s"
    return cells, position


def _where(d: Drawn) -> tuple[str, str]:
    """Where a linkage's plans are drawn (the given position, or each of them) and the position
    its answers are for, named (the first when there are several)."""
    several = len(d.scene.drive.values) > 1
    return ("each given position" if several else "the given position",
            f"{answers_at(d)}{' (the first given position)' if several else ''}")


def _kinematics_task(d: Drawn, asked: tuple[Asked, ...]) -> str:
    """A linkage's kinematics task, naming the position its answers are for."""
    plans = " and the acceleration plan" if "acceleration" in d.scene.draw else ""
    where, at = _where(d)
    return f"Task: draw the velocity plan{plans} at {where} to scale; find {_names(asked)} (magnitudes) at {at}."


def given_and_task(h: Handout, d: Drawn, asked: tuple[Asked, ...]) -> tuple[list[str], str]:
    """The given data (cells in the sheets' markup: ``l_{OA} = 0.1 m``) and the task of variant
    ``d`` as its Moodle question states them: the sheet's, naming the position the answers are
    for, then how to type a value (:data:`TYPING`)."""
    from ..drawing.assignment import given_cells

    scene = d.scene
    if h.train:
        g = scene.gears
        cells = [f"z_{{{w.name}}} = {w.teeth}" for w in g.wheels]
        cells += [f"m_{{{w.name}}} = {w.module:g} mm" for w in g.wheels if w.module]
        cells += [f"n_{{{name}}} = {n:g} rpm" for name, n in g.inputs]
        cells += [f"n_{{{name}}} = 0 (held)" for name in g.fixed]
        return cells, f"{task_text(scene, asked, [])} {TYPING}"
    if h.rotor:
        return rotor_cells(scene), f"{rotor_task(scene)} {TYPING}"
    lengths = variant_data(h, d.variant).get("lengths")
    if h.kind == "kinematics":
        return given_cells(scene, lengths), f"{_kinematics_task(d, asked)} {TYPING}"
    report = d.sheets.report
    cells, laws = loads_cells(scene, report.get("cycle", {}).get("output", {}).get("unit", "m"))
    if h.kind == "forces":
        return given_cells(scene, lengths) + cells, f"{task_text(scene, asked, laws, at=_where(d)[1])} {TYPING}"
    more, _ = _dynamics_cells(scene)
    return given_cells(scene, lengths, drive=False) + cells + more, f"{task_text(scene, asked, laws)} {TYPING}"


def assignment_svg(h: Handout, d: Drawn, asked: tuple[Asked, ...]) -> str:
    """The assignment sheet's SVG of variant ``d`` (the first of :func:`assignment_sheets`)."""
    return _assignment(h, d, asked)[0]


def assignment_sheets(h: Handout, d: Drawn, asked: tuple[Asked, ...]) -> dict[str, str]:
    """Every sheet of variant ``d``'s assignment, file name → SVG text: the assignment sheet
    (``variant-01-assignment.svg``), then an answer sheet (``variant-01-assignment-2.svg``…)
    for each batch of framed areas it has no room for (every area holds what the key draws)."""
    return {f"{d.name}-assignment{'' if k == 0 else f'-{k + 1}'}.svg": svg
            for k, svg in enumerate(_assignment(h, d, asked))}


def _assignment(h: Handout, d: Drawn, asked: tuple[Asked, ...]) -> tuple[str, ...]:
    """The SVG texts of variant ``d``'s assignment sheets, the assignment sheet first."""
    variant = d.name.replace("variant-", "variant ")
    if h.train:
        return (_train_sheet(d, asked, variant),)
    if h.rotor:
        from .rotor_sheet import rotor_sheets

        return rotor_sheets(d.scene, d.sheets.sheets["balancing"].svg, variant)
    from ..constructions.scheme import scheme
    from ..drawing.assignment import draw_assignment

    motion = d.sheets.motion
    scene = d.scene
    lengths = variant_data(h, d.variant).get("lengths")
    points, links = _found(d)
    areas = answer_areas(h, d)
    if h.kind == "kinematics":
        return draw_assignment(lambda mu: scheme(motion, 0, mu), scene, variant=variant, points=points, links=links,
                               lengths=lengths, areas=areas)
    report = d.sheets.report
    cells, laws = loads_cells(scene, report.get("cycle", {}).get("output", {}).get("unit", "m"))
    task = task_text(scene, asked, laws, at=_where(d)[1] if h.kind == "forces" else None)
    if h.kind == "forces":
        return draw_assignment(lambda mu: scheme(motion, 0, mu), scene, variant=variant, points=points,
                               links=links, lengths=lengths, extra=cells, task=task, areas=areas)
    more, position = _dynamics_cells(scene)
    return draw_assignment(lambda mu: scheme(motion, 0, mu), scene, variant=variant, points=points, links=links,
                           lengths=lengths, extra=cells + more, task=task, areas=areas, position=position,
                           drawn_at=float(report["positions"][0]["angle"]))


#: A linkage assignment's areas: what the key's drawing is marked (``data-plan``), the area's
#: name and the scale the student writes in.
_AREAS = {"velocity": ("velocity", "Velocity plan (pole p)", "μ_V = ________ (m/s)/mm"),
          "acceleration": ("acceleration", "Acceleration plan (pole π)", "μ_a = ________ (m/s²)/mm"),
          "forces": ("force", "Groups drawn alone (μ_l, arms h, ΣM = 0) and force plans", "μ_F = ________ N/mm"),
          "lever": ("lever", "Zhukovsky's lever", "μ_F = ________ N/mm")}
#: The dynamics diagrams drawn one above the other on a common φ axis (``data-diagram``).
_DIAGRAMS = ("M", "A", "T")


def answer_areas(h: Handout, d: Drawn) -> list:
    """The framed areas of variant ``d``'s linkage assignment (:class:`plans.drawing.assignment.Area`),
    each with the size of what its key draws there (mm; a detail, an enlarged piece, left out):
    kinematics, the velocity and acceleration plans the scene draws at each position; forces,
    those at the first position, each group's force plan and Zhukovsky's lever; dynamics, the
    diagrams M, A, ΔT, I together and Wittenbauer's diagram."""
    import re

    from ..drawing.assignment import Area, drawings
    from ..pipeline.sheets.page import sheet_suffix

    motion, sheets = d.sheets.motion, d.sheets.sheets

    def held(name: str, what: tuple[str, ...], pages: bool = False) -> list:
        found = [n for n in sheets if n == name or pages and re.fullmatch(re.escape(name) + r"-\d+", n)]
        return [b for n in found for w, b in drawings(sheets[n].svg) if w in what]

    if h.kind == "dynamics":
        union = _union(held("dynamics", _DIAGRAMS))        # one above the other: the room of all of them
        return [Area("diagrams", "Diagrams M_{r}(φ), A(φ), ΔT(φ)", "μ_φ = ________ rad/mm", union),
                Area("wittenbauer", "Wittenbauer's diagram ΔT(I_{r}) by projection, I_{r}(φ) turned under it",
                     "μ_T = ________ J/mm", _union(held("dynamics", ("wittenbauer", "I"))))]
    drive = d.scene.drive
    if h.kind == "forces":
        kinds, positions = ("velocity", "acceleration", "forces", "lever"), range(1)
    else:
        kinds = tuple(k for k in ("velocity", "acceleration") if k in d.scene.draw) or ("velocity",)
        positions = range(len(motion))
    out = []
    for i in positions:
        suffix = sheet_suffix(motion, i)
        v = float(motion.values[i])
        at = "" if len(motion) == 1 else \
            f", φ_{{{drive.link}}} = {v % 360.0 + 0.0:g}°" if drive.kind.angular else f", s = {v:g} m"
        for kind in kinds:
            what, name, scale = _AREAS[kind]
            # the force sheets' groups drawn alone (with their arms and moment equations) get room too
            kinds_drawn = (what, "group") if kind == "forces" else (what,)
            out.append(Area(kind, name + at, scale, tuple(_sizes(held(kind + suffix, kinds_drawn, kind == "forces"))),
                            suffix))
    return out


def _union(boxes: list) -> tuple[tuple[float, float], ...]:
    """The size of the box holding all ``boxes`` (none when there are none), mm."""
    return ((max(b.x1 for b in boxes) - min(b.x0 for b in boxes), max(b.y1 for b in boxes) - min(b.y0 for b in boxes)),) \
        if boxes else ()


def _sizes(boxes: list) -> list[tuple[float, float]]:
    """Width and height of each box, mm."""
    return [(b.x1 - b.x0, b.y1 - b.y0) for b in boxes]


def _train_sheet(d: Drawn, asked: tuple[Asked, ...], variant: str) -> str:
    """A gear train's assignment: its gear sheet without the pictures, the speeds left empty
    but for the inputs and the held links; the pictures' room framed where the key draws them."""
    from ..constructions.gears import SIDE_MAX_MM, gear_sheet
    from ..drawing import Style
    from ..drawing.assignment import add_frames, gear_frames
    from ..drawing.gears import draw_gears, to_fit
    from ..drawing.svg import Heading

    scene, train = d.scene, d.sheets.train
    inputs = ", ".join(f"n_{{{name}}} = {n:g} rpm".replace("-", "−") for name, n in scene.gears.inputs)
    given = frozenset([name for name, _ in scene.gears.inputs] + list(scene.gears.fixed))
    notes = (f"Given: the teeth z in the table, {inputs}"
             + ("; every wheel's module " + ", ".join(f"m_{{{w.name}}} = {w.module:g} mm" for w in scene.gears.wheels)
                if all(w.module for w in scene.gears.wheels) else "") + ".",
             task_text(scene, asked, []))
    sheet = to_fit(lambda side: gear_sheet(train, side_max=side), SIDE_MAX_MM)       # as the key's
    svg = draw_gears(sheet, Heading(scene.title, f"Assignment, {variant}", inputs), ident="assignment",
                     style=Style(), notes=notes, given=given)
    key = next((s.svg for s in d.sheets if s.name == "gears"), None)
    return svg if key is None else add_frames(svg, gear_frames(key, svg), "assignment", Style())

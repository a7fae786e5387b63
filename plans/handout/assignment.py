"""A variant's assignment sheet, kind by kind (:mod:`.asked`): its given data, its task and the
framed areas where the student draws.

- kinematics: the scheme at the first position, the lengths and the drive; areas for the
  velocity and acceleration plans;
- forces: the same with the masses, moments of inertia, gravity and loads; areas for the two
  plans, the force plans and Zhukovsky's lever;
- dynamics: the scheme at the cycle's first position, the loads (a load that follows the cycle
  as its table), the mean speed and δ; areas for the diagrams and Wittenbauer's diagram;
- gears: the train's side and end views with its teeth and the input speeds, the rest of the
  speed table empty, the pictures' room left blank.

Knows :mod:`.variants`, :mod:`.solving`, the constructions and the drawing (imported only when a
sheet is drawn); must not import the writing, the index, the random draws or the command line.
"""

from __future__ import annotations

import math

from ..scene import Scene
from .asked import Asked, asked, kind_of
from .solving import variant_data
from .variants import Drawn, Handout

__all__ = ["assignment_svg", "law_corners", "loads_cells", "task_text", "variant_asked", "given_and_task"]


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
    return ", ".join(a.symbol for a in asked)


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
        cells.append(f"M_{{{mo.link}}} = {mo.value:g} N·m")
    return cells, laws


def task_text(scene: Scene, asked: tuple[Asked, ...], laws: list[str]) -> str:
    """The task of a forces, dynamics or gears assignment (the kinematics one is the drawing's)."""
    kind = kind_of(scene)
    if kind == "gears":
        return (f"Task: draw the linear- and angular-velocity pictures of the train to scale; find {_names(asked)} "
                "(speeds in rpm, + in the sense of the input) and check them by Willis' formula.")
    j = scene.drive.link
    if kind == "forces":
        b = next(a for a in asked if a.symbol in ("M_{b}", "F_{b}"))
        what = "balancing moment" if b.symbol == "M_{b}" else "balancing force"
        text = (f"Task: at the given position draw the velocity and acceleration plans, find the inertia forces and "
                f"moments, then, group by group from the last one attached, the reactions in the kinematic pairs by "
                f"force plans and the {what} {b.symbol} on link {j} (counter-clockwise +); check {b.symbol} by "
                f"Zhukovsky's lever.")
    else:
        fw = next(a for a in asked if a.symbol in ("J_{fw}", "δ"))
        aim = ("the flywheel's moment of inertia J_{fw} on link " + j + " that keeps the speed within the given δ"
               if fw.symbol == "J_{fw}" else "the coefficient of speed fluctuation δ reached with the given flywheel")
        text = (f"Task: over the cycle's positions find the reduced moment of the loads and the reduced moment of "
                f"inertia on link {j}; draw the works' diagrams (by graphical integration), the kinetic energy's "
                f"change and Wittenbauer's diagram; find the constant driving moment M_{{d}} and {aim}.")
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
    n = len(d.values)
    position = f"{n} positions of link {j} over its cycle, ω_{{{j}m}} = {d.speed:g} rad/s"
    return cells, position


def _kinematics_task(scene: Scene, asked: tuple[Asked, ...]) -> str:
    plans = " and the acceleration plan" if "acceleration" in scene.draw else ""
    return (f"Task: draw the velocity plan{plans} at the given position to scale and find {_names(asked)} "
            "(magnitudes).")


def given_and_task(h: Handout, d: Drawn, asked: tuple[Asked, ...]) -> tuple[list[str], str]:
    """The given data (cells in the sheets' markup: ``l_{OA} = 0.1 m``) and the task of variant
    ``d``, as its assignment sheet states them."""
    from ..drawing.assignment import given_cells

    scene = d.scene
    if h.train:
        g = scene.gears
        cells = [f"z_{{{w.name}}} = {w.teeth}" for w in g.wheels]
        cells += [f"m_{{{w.name}}} = {w.module:g} mm" for w in g.wheels if w.module]
        cells += [f"n_{{{name}}} = {n:g} rpm" for name, n in g.inputs]
        cells += [f"n_{{{name}}} = 0 (held)" for name in g.fixed]
        return cells, task_text(scene, asked, [])
    lengths = variant_data(h, d.variant).get("lengths")
    if h.kind == "kinematics":
        return given_cells(scene, lengths), _kinematics_task(scene, asked)
    report = d.sheets.report
    cells, laws = loads_cells(scene, report.get("cycle", {}).get("output", {}).get("unit", "m"))
    if h.kind == "forces":
        return given_cells(scene, lengths) + cells, task_text(scene, asked, laws)
    more, _ = _dynamics_cells(scene)
    return given_cells(scene, lengths, drive=False) + cells + more, task_text(scene, asked, laws)


def assignment_svg(h: Handout, d: Drawn, asked: tuple[Asked, ...]) -> str:
    """The assignment sheet's SVG of variant ``d``."""
    variant = d.name.replace("variant-", "variant ")
    if h.train:
        return _train_sheet(d, asked, variant)
    from ..constructions.scheme import scheme
    from ..drawing.assignment import draw_assignment

    motion = d.sheets.motion
    scene = d.scene
    lengths = variant_data(h, d.variant).get("lengths")
    points, links = _found(d)
    if h.kind == "kinematics":
        return draw_assignment(lambda mu: scheme(motion, 0, mu), scene, variant=variant, points=points, links=links,
                               lengths=lengths)
    report = d.sheets.report
    cells, laws = loads_cells(scene, report.get("cycle", {}).get("output", {}).get("unit", "m"))
    task = task_text(scene, asked, laws)
    if h.kind == "forces":
        areas = [("velocity", "Velocity plan (pole p)", "μ_V = ________ (m/s)/mm"),
                 ("acceleration", "Acceleration plan (pole π)", "μ_a = ________ (m/s²)/mm"),
                 ("forces", "Force plans", "μ_F = ________ N/mm"),
                 ("lever", "Zhukovsky's lever", "μ_F = ________ N/mm")]
        return draw_assignment(lambda mu: scheme(motion, 0, mu), scene, variant=variant, points=points,
                               links=links, lengths=lengths, extra=cells, task=task, areas=areas)
    more, position = _dynamics_cells(scene)
    areas = [("diagrams", "Diagrams M_{r}(φ), A(φ), ΔT(φ), I_{r}(φ)", "μ_φ = ________ rad/mm"),
             ("wittenbauer", "Wittenbauer's diagram ΔT(I_{r})", "μ_T = ________ J/mm")]
    return draw_assignment(lambda mu: scheme(motion, 0, mu), scene, variant=variant, points=points, links=links,
                           lengths=lengths, extra=cells + more, task=task, areas=areas, position=position,
                           drawn_at=float(report["positions"][0]["angle"]))


def _train_sheet(d: Drawn, asked: tuple[Asked, ...], variant: str) -> str:
    """A gear train's assignment: its gear sheet without the pictures, the speeds left empty
    but for the inputs and the held links."""
    from ..constructions.gears import gear_sheet
    from ..drawing import Style
    from ..drawing.gears import draw_gears
    from ..drawing.svg import Heading

    scene, train = d.scene, d.sheets.train
    inputs = ", ".join(f"n_{{{name}}} = {n:g} rpm".replace("-", "−") for name, n in scene.gears.inputs)
    given = frozenset([name for name, _ in scene.gears.inputs] + list(scene.gears.fixed))
    notes = (f"Given: the teeth z in the table, {inputs}"
             + ("; every wheel's module " + ", ".join(f"m_{{{w.name}}} = {w.module:g} mm" for w in scene.gears.wheels)
                if all(w.module for w in scene.gears.wheels) else "") + ".",
             task_text(scene, asked, []))
    return draw_gears(gear_sheet(train), Heading(scene.title, f"Assignment, {variant}", inputs), ident="assignment",
                      style=Style(), notes=notes, given=given)

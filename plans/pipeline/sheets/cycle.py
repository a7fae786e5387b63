"""The sheets of one revolution (``[drive] positions``): the positions of the mechanism with the
output's extremes (``-positions``), the kinematic diagrams of the output link (``-diagrams``)
and the velocity plans of every position with their table (``-velocities``); and the report's
``cycle``, made with them.

Reads a solved Cycle; imports nothing of the pipeline."""

from __future__ import annotations

import math

from ...checking import check_plan
from ...constructions import Scales
from ...constructions.cycle import positions_sheet, velocities_sheet
from ...constructions.diagrams import diagrams
from ...drawing import Heading, Style
from ...drawing.diagrams import draw_diagrams
from ...drawing.positions import draw_positions, draw_velocities
from ...errors import PlansError
from ...kinematics.cycle import Cycle
from ...scene import Scene

__all__ = ["cycle_sheets"]


def cycle_sheets(scene: Scene, cycle: Cycle, scales: Scales, stem: str, style: Style,
                 assembled=None) -> tuple[dict[str, str], dict]:
    """The cycle sheets the scene draws (positions, diagrams, velocities) and the report's
    ``cycle``: the positions, the output's extremes and, with velocities, the table of values
    (with diagrams, how far the graphical differentiation is from the exact values). With
    ``assembled`` (each cycle position's assemblies, ``draw`` asking for them): ``cycle.assemblies``
    = group → the count of real assemblies at each position, and the positions sheet names the
    intervals where a count changes (two assemblies merge at a branch point between them)."""
    c, motion, out = scene.cycle, cycle.motion, cycle.output
    d = motion.mechanism.drive
    unit = "m" if out.kind == "slider" else "rad"
    first = "extreme of link " + out.link if c.start == "extreme" else "angle"
    position = f"{c.positions} positions from φ_{d.link} = {cycle.start % 360.0:.6g}° ({first}), ω_{d.link} = " \
               f"{d.speed:g} rad/s"
    files: dict[str, str] = {}
    data: dict = {"positions": [float(v) for v in motion.values], "start": c.start, "step": cycle.step,
                  "output": {"link": out.link, "kind": out.kind, "point": out.point, "unit": unit}}
    ext = cycle.extreme_output
    if ext is not None:
        data["extremes"] = [{"angle": float(a) % 360.0, "s": float(s)}
                            for a, s in zip(cycle.extremes.values, ext.s)]
    changes: list[str] = []
    branches: set[tuple[int, int]] = set()
    if assembled is not None:
        counts = {g: [a[g].count for a in assembled] for g in assembled[0]}
        data["assemblies"] = counts
        for g, n in counts.items():
            for k in range(len(n)):
                j = (k + 1) % len(n)
                if n[k] != n[j]:
                    changes.append(f"{g}: {n[k]} → {n[j]} assemblies between positions {k} and {j}")
                    branches.add((k, j))
    if "positions" in scene.draw:
        sheet = positions_sheet(motion, cycle.extremes, cycle.dense, output=out.link, point=out.point,
                                kind=out.kind, extreme_s=None if ext is None else ext.s, trace=c.trace)
        notes = []
        if sheet.stroke is not None:
            a0, a1 = sheet.extreme_angles
            travel = f"H = {sheet.stroke:.4g} m, the stroke" if out.kind == "slider" else \
                f"ψ = {math.degrees(sheet.stroke):.4g}°, the swing"
            notes.append(f"{travel} of link {out.link} between its extreme positions {out.point}′ "
                         f"(φ_{d.link} = {a0:.2f}°) and {out.point}″ (φ_{d.link} = {a1:.2f}°), drawn thick")
        if changes:
            notes.append("The count of real assemblies changes (a branch point, where two assemblies merge, lies "
                         "between; marked \"branch\" on the crank's circle): " + "; ".join(changes))
        elif assembled is not None:
            notes.append("Every group keeps its count of real assemblies over the cycle: " + ", ".join(
                f"{g} {n[0]}" for g, n in data["assemblies"].items()))
        files[f"{stem}-positions.svg"] = draw_positions(
            sheet, Heading(scene.title, "Positions of the mechanism over one revolution", position),
            ident="positions", style=style, notes=tuple(notes), branches=tuple(sorted(branches)))
    if "diagrams" in scene.draw:
        dn = cycle.dense_output
        dia = diagrams(start=cycle.start, step=cycle.step, positions=c.positions, every=cycle.every, omega=d.speed,
                       link=out.link, point=out.point, kind=out.kind, s=dn.s, v=dn.v, a=dn.a)
        g = {gr.quantity: gr for gr in dia.graphs}
        sym = ("v", "a") if out.kind == "slider" else ("ω", "ε")
        notes = (f"Solid: exact; dashed: graphical differentiation by chords ({sym[0]} at the middles of the intervals "
                 f"from the chords of the first graph, {sym[1]} at the positions from the chords of the second).",
                 f"Graphical {sym[0]} differs from the exact by at most {100 * g['v'].error:.2g} % of {sym[0]}_max, "
                 f"graphical {sym[1]} by at most {100 * g['a'].error:.2g} % of {sym[1]}_max; "
                 f"t = (φ_{d.link} − {cycle.start % 360.0:.6g}°)/ω_{d.link}, T = {dia.period:.4g} s.")
        files[f"{stem}-diagrams.svg"] = draw_diagrams(
            dia, Heading(scene.title, f"Kinematic diagrams of link {out.link}", position), ident="diagrams",
            style=style, notes=notes)
        data["diagrams"] = {"mu_t": dia.mu_t, "mu_phi": dia.mu_phi, "period": dia.period,
                            "mu": {gr.quantity: gr.mu for gr in dia.graphs},
                            "graphical_error": {gr.quantity: gr.error for gr in dia.graphs if gr.graphical}}
    if "velocities" in scene.draw:
        sheet = velocities_sheet(motion)
        for cell in sheet.cells:
            failures = check_plan(cell.plan)
            if failures:
                raise PlansError(f"{scene.file or scene.title}: velocity plan of position {cell.index} failed its "
                                 f"geometric check: {failures[0]} (please report this scene)")
        files[f"{stem}-velocities.svg"] = draw_velocities(
            sheet, Heading(scene.title, "Velocity plans of every position", position), ident="velocities", style=style)
        t = sheet.table
        data["table"] = {"points": list(t.points), "links": list(t.links), "mu_v": sheet.mu_v,
                         "rows": [{"position": int(r[0]), "angle": r[1],
                                   "v": dict(zip(t.points, r[2:2 + len(t.points)])),
                                   "omega": dict(zip(t.links, r[2 + len(t.points):]))} for r in t.rows]}
    return files, data

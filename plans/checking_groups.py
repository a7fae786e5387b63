"""Checking a group drawn alone (``<g data-plan="group">``, written by
:mod:`plans.drawing.group_diagram`): its arms measured, and its moment equations recomputed
from the drawing.

``data-mu`` is μl (m/mm). A force's arrow is drawn to show its line of action, not its size:
its drawn direction must agree with ``data-direction`` (within what its rounded ends allow),
and its line is the one through its drawn tail in that recorded direction. Then:

1. **arms** — each ``<line data-quantity="h:<force>" data-about=…>`` must start at the centre
   of the equation ``data-about`` names, end on that force's line and be as long as the
   centre's distance from it; its length × μl must equal ``data-value`` (m). A force of an
   equation whose line passes at least :data:`MIN_ARM_MM` from the centre must have its arm
   drawn;
2. **moment equations** — each ``<g data-equation="<unknown>" data-links data-centre>``: the
   moments about the centre of every force and couple (``data-couple``, ``data-moment`` N·m)
   on those links, with the arms as drawn, must sum to zero with the unknown's tagged value:
   the unknown that follows from the drawing (R^τ, R^n or the balancing force, N; the
   balancing moment, N·m) equals the tagged one within what the rounding of the drawn lines
   allows, Σ F·2√2·precision over the unknown's arm (+ 1e-9 relative).

Part of :mod:`plans.checking`; must not import any plans module above the checking's own.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

from .checking_read import _SVG, _line_data, _number
from .checking_report import Check, Measurement, SvgReport

__all__ = ["check_group_diagram", "GROUP", "MIN_ARM_MM"]

#: ``data-plan`` of a group drawn alone.
GROUP = "group"
#: A force whose line passes this far (mm) or farther from an equation's centre must have its arm
#: drawn (the writer's promise, plans.constructions.group_diagram.ARM_MM, restated).
MIN_ARM_MM = 0.5
_REL = 1e-9


def _add(report: SvgReport, check: Check) -> None:
    report.checks.append(check)
    if not check.ok:
        report.problems.append(f"plan {check.plan}: {check.what}: {check.deviation:.3g} {check.unit} "
                               f"(tolerance {check.tolerance:.2g} {check.unit})")


def check_group_diagram(report: SvgReport, g: ET.Element, lines: list[ET.Element], mu: float, r: float) -> None:
    """Check one group diagram (see the module docstring); ``r``: the largest error of a drawn
    segment from its two rounded ends, mm."""
    gid = g.get("id") or GROUP
    forces: dict[str, tuple] = {}          # quantity → (tail, unit direction, value, link)
    arms: list[ET.Element] = []
    for line in lines:
        q = line.get("data-quantity") or ""
        if q.startswith("h:"):
            arms.append(line)
            continue
        data = _line_data(line)
        if data is None or line.get("data-link") is None:
            report.problems.append(f"plan {gid}: force {q}: coordinates, data-value, data-direction or data-link "
                                   "missing or not finite")
            continue
        (x1, y1, x2, y2), value, t = data
        u = (math.cos(t), math.sin(t))
        length = math.hypot(x2 - x1, y2 - y1)
        err = math.acos(max(-1.0, min(1.0, ((x2 - x1) * u[0] + (y2 - y1) * u[1]) / length))) if length > 0 else math.pi
        if length > r:
            _add(report, Check(gid, f"direction of {q}", err, math.asin(min(1.0, r / length)) + _REL, "rad"))
        forces[q] = ((x1, y1), u, value, line.get("data-link"))
    couples = []
    for el in g.iter():
        if el.get("data-couple") is not None:
            m = _number(el.get("data-moment"))
            if m is None or not math.isfinite(m):
                report.problems.append(f"plan {gid}: couple {el.get('data-couple')}: data-moment is not a number")
                continue
            couples.append((el.get("data-couple"), m, el.get("data-link")))
    equations = {}
    for el in g.iter(f"{_SVG}g"):
        if el.get("data-equation") is None:
            continue
        centre = [_number(c) for c in (el.get("data-centre") or "").split(",")]
        if len(centre) != 2 or None in centre or not all(math.isfinite(c) for c in centre):
            report.problems.append(f"plan {gid}: equation {el.get('data-equation')}: data-centre is not a paper x,y")
            continue
        equations[el.get("data-about") or ""] = equations.get(el.get("data-about") or "", [])
        equations[el.get("data-about") or ""].append((el.get("data-equation"), set((el.get("data-links") or "").split()),
                                                      tuple(centre)))
    drawn: set[tuple[str, str]] = set()
    for a in arms:
        _arm(report, gid, a, forces, equations, mu, r, drawn)
    for about, eqs in equations.items():
        for unknown, links, centre in eqs:
            _equation(report, gid, unknown, links, about, centre, forces, couples, mu, r, drawn)


def _arm(report, gid, a, forces, equations, mu, r, drawn) -> None:
    q = a.get("data-quantity")[2:]
    xy = [_number(a.get(k)) for k in ("x1", "y1", "x2", "y2")]
    value = _number(a.get("data-value"))
    about = a.get("data-about") or ""
    if None in xy or value is None or q not in forces or about not in equations:
        report.problems.append(f"plan {gid}: the arm of {q} about {about!r}: no coordinates, value, force or "
                               "equation to measure it by")
        return
    (tx, ty), u, _, _ = forces[q]
    cx, cy = equations[about][0][2]
    length = math.hypot(xy[2] - xy[0], xy[3] - xy[1])
    h = abs((cx - tx) * u[1] - (cy - ty) * u[0])
    start = math.hypot(xy[0] - cx, xy[1] - cy)
    off = abs((xy[2] - tx) * u[1] - (xy[3] - ty) * u[0])
    report.measurements.append(Measurement(f"h:{q}@{about}", GROUP, length, mu, value, mu * r + _REL * value))
    _add(report, Check(gid, f"arm of {q} about {about} (from the centre, to its line, its length)",
                       max(start, off, abs(length - h)), 1.5 * r + _REL * h, "mm"))
    drawn.add((q, about))


def _equation(report, gid, unknown, links, about, centre, forces, couples, mu, r, drawn) -> None:
    cx, cy = centre
    total = bound = 0.0
    x_arm = None
    for q, ((tx, ty), u, value, link) in forces.items():
        if link not in links:
            continue
        cross = (tx - cx) * u[1] - (ty - cy) * u[0]          # paper frame, y down: clockwise on paper positive
        if q == unknown:
            x_arm = abs(cross)
        elif abs(cross) >= MIN_ARM_MM + r and (q, about) not in drawn:     # + r: the tail's rounding
            report.problems.append(f"plan {gid}: {q}: its arm about {about} ({abs(cross):.3g} mm) is not drawn")
        total += -value * cross * mu                           # N·m, counter-clockwise positive
        bound += value * r * mu
    x_couple = None
    for q, m, link in couples:
        if link in links:
            total += m
            if q == unknown:
                x_couple = abs(m)
    if x_arm is not None and x_arm > 0:
        dev, tol, unit = abs(total) / (x_arm * mu), bound / (x_arm * mu) + _REL * forces[unknown][2], "N"
    elif x_couple is not None:
        dev, tol, unit = abs(total), bound + _REL * x_couple, "N·m"
    else:
        report.problems.append(f"plan {gid}: equation for {unknown} about {about}: its unknown is not drawn")
        return
    _add(report, Check(gid, f"ΣM_{about} = 0 gives {unknown} as tagged", dev, tol + 1e-12, unit))
    report.equations[gid] = report.equations.get(gid, 0) + 1

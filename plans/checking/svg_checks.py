"""The checks of one SVG file (:func:`inspect_svg`, :func:`check_svg`): every tagged vector's
length and direction, the vector equations' closure, the file's own contract, and a force
plan's or Zhukovsky's lever's balance (see :mod:`plans.checking`).

Knows :mod:`.report`, :mod:`.reading`, the drawing's :class:`~plans.drawing.style.Style` (for
the writer's precision) and the errors; must not import anything above the drawing.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

from ..drawing.style import Style
from ..errors import DrawingError
from .reading import (_SVG, _TRANSFORM, _Union, _decimals, _ends, _line_data, _number, _paper_problems, _point_name,
                      _transformed)
from .report import Check, Closure, Measurement, SvgReport

__all__ = ["WRITER_PRECISION", "FORCE_CLOSURE_REL", "FORCE", "LEVER", "MIN_ARM_MM", "SCHEME", "BOUND", "EMPTY",
           "inspect_svg", "check_svg"]

#: Rounding of one coordinate written by plans' own writer, mm: what ``plans check`` measures against.
WRITER_PRECISION = Style().precision
#: Relative slack on lengths (SI) and on the angular tolerance (rad) for floating-point noise.
_REL = 1e-9
#: A force polygon's recorded sides (value × direction) must sum to zero within this fraction of Σ values.
FORCE_CLOSURE_REL = 1e-6
#: Kinds of kinetostatic plan groups.
FORCE, LEVER = "force", "lever"
#: A lever force whose recorded arm is at least this long must have its arm drawn, mm (the
#: writer's promise, plans.drawing.forces.MIN_ARM_MM, restated so the checker does not read the writer).
MIN_ARM_MM = 0.5
#: Plans whose vectors are measured; a group with another ``data-plan`` is a plan too unless "scheme".
SCHEME = "scheme"
#: Vectors drawn at their points of application (measured, never closed: see plans.checking).
BOUND = "bound"
#: Kind of a plan sheet its writer drew with no vector (``data-vectors="0"``): the pole alone.
EMPTY = "empty"
#: Root ids written for plan sheets (a sheet claiming to be a plan must carry tagged vectors).
_PLAN_IDS = ("velocity", "acceleration", "koshel", "centres")


def inspect_svg(path: str | Path, precision: float | None = WRITER_PRECISION) -> SvgReport:
    """Check every tagged vector, every vector equation and the file's own geometry (see
    :mod:`plans.checking`). ``precision``: the rounding (mm) the file was written with — plans'
    writer by default; None: that of the coordinates actually written. Raises
    :class:`DrawingError` only when the file cannot be read as XML."""
    path = Path(path)
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as exc:
        raise DrawingError(f"{path}: cannot read the SVG ({exc})") from None
    parent = {c: p for p in root.iter() for c in p}
    tagged = [e for e in root.iter() if e.get("data-quantity") is not None]
    plan_groups = [g for g in root.iter(f"{_SVG}g") if g.get("data-mu") is not None]
    claims_plan = any(g.get("data-plan") != SCHEME for g in plan_groups) \
        or (root.get("id") or "").startswith(_PLAN_IDS)
    plans_ = [g for g in plan_groups if g.get("data-plan") != SCHEME]
    if not tagged:
        if plan_groups and not claims_plan:
            return SvgReport(str(path), SCHEME, precision or WRITER_PRECISION)
        if plans_ and all(g.get("data-vectors") == "0" for g in plans_):
            return SvgReport(str(path), EMPTY, precision or WRITER_PRECISION)
        return SvgReport(str(path), "none", precision or WRITER_PRECISION,
                         problems=["no tagged vectors: not a plan written by plans"])
    if precision is None:
        digits = max((_decimals(e.get(k) or "") for e in tagged for k in ("x1", "y1", "x2", "y2")), default=0)
        precision = 0.5 * 10.0 ** -digits
    report = SvgReport(str(path), "plan", precision)
    problems = report.problems
    if root.tag != f"{_SVG}svg":
        problems.append(f"the root element is <{root.tag}>, not an SVG <svg>")
    problems += _paper_problems(root)
    claimed = root.get("data-precision")
    if claimed is not None:
        c = _number(claimed)
        if c is None or not math.isfinite(c) or c <= 0:
            problems.append(f"data-precision {claimed!r} is not a positive number")
        elif c > precision * (1 + _REL):
            problems.append(f"data-precision {claimed} mm claims a looser drawing than plans checks against "
                            f"({precision:g} mm): refused")
    for style in root.iter(f"{_SVG}style"):
        if _TRANSFORM.search(style.text or ""):
            problems.append("a <style> sheet sets a transform: plan elements must not be transformed")
    for g in plan_groups:
        if g.get("data-plan") == SCHEME:
            continue
        for line in g.iter(f"{_SVG}line"):
            if line.get("data-quantity") is None and line.get("data-construction") is None:
                problems.append(f"plan {g.get('id')}: line {line.get('id')} is neither a tagged vector nor a "
                                "construction line")
    by_group: dict[ET.Element, list] = {}
    for line in tagged:
        q = line.get("data-quantity")
        chain, el, group = [], line, None
        while el in parent:
            el = parent[el]
            chain.append(el)
            if group is None and el.tag == f"{_SVG}g" and el.get("data-mu") is not None:
                group = el
        if line.tag != f"{_SVG}line":
            problems.append(f"{q}: tagged element <{line.tag.replace(_SVG, '')}> is not a <line>")
            continue
        bad = [e for e in [line] + chain if _transformed(e)]
        if bad:
            problems.append(f"{q}: transform on <{bad[0].tag.replace(_SVG, '')} id={bad[0].get('id')!r}>; "
                            "plan elements and everything above them must not be transformed")
        odd = [e for e in chain if e.tag != f"{_SVG}g" and e is not root]
        if odd:
            problems.append(f"{q}: inside <{odd[0].tag.replace(_SVG, '')}>; a vector may sit in <g> elements only")
        if group is None:
            problems.append(f"{q}: tagged vector outside any plan group (<g data-mu>)")
            continue
        by_group.setdefault(group, []).append(line)
    for g in plans_:
        declared, found = g.get("data-vectors"), len(by_group.get(g, []))
        if declared is not None and declared != str(found):
            problems.append(f"plan {g.get('id')}: {found} tagged vectors where the writer drew {declared!r}")
    for g, lines in by_group.items():
        _check_group(report, g, lines)
    return report


def _check_group(report: SvgReport, g: ET.Element, lines: list[ET.Element]) -> None:
    plan, gid, p = g.get("data-plan", ""), g.get("id") or g.get("data-plan", ""), report.precision
    mu = _number(g.get("data-mu"))
    if mu is None or not math.isfinite(mu) or mu <= 0:
        report.problems.append(f"plan {gid}: data-mu {g.get('data-mu')!r} is not a positive finite number")
        return
    r = 2.0 * math.sqrt(2.0) * p          # largest drawn-vector error from two rounded ends, mm
    ends = []                              # (name of the end, paper xy, absolute?, name token, label token)
    for line in lines:
        q = line.get("data-quantity")
        xy = [_number(line.get(k)) for k in ("x1", "y1", "x2", "y2")]
        value = _number(line.get("data-value"))
        theta = _number(line.get("data-direction"))
        if None in xy or not all(math.isfinite(c) for c in xy):
            report.measurements.append(Measurement(q, plan, math.nan, mu, value if value is not None else math.nan,
                                                   0.0, problem="coordinates missing or not finite numbers"))
            continue
        x1, y1, x2, y2 = xy
        length = math.hypot(x2 - x1, y2 - y1)
        problem = ""
        if value is None or not math.isfinite(value) or value < 0:
            problem = f"data-value {line.get('data-value')!r} is not a finite number ≥ 0"
            value = math.nan if value is None else value
        elif theta is None or not math.isfinite(theta):
            problem = ("no data-direction: exact direction not recorded (written by an older plans? re-render)"
                       if line.get("data-direction") is None else
                       f"data-direction {line.get('data-direction')!r}: exact direction not recorded")
        elif line.get("data-from") is None or line.get("data-to") is None:
            problem = "data-from/data-to: the images the vector joins are not recorded"
        tol = mu * r + _REL * abs(value) if math.isfinite(value) else 0.0
        angle_err, angle_tol = math.nan, math.pi
        if not problem:
            exact_mm = value / mu
            if exact_mm > r and length > 0:
                t = math.radians(theta)
                cos = ((x2 - x1) * math.cos(t) + (y2 - y1) * math.sin(t)) / length
                angle_err = math.acos(max(-1.0, min(1.0, cos)))
                angle_tol = math.asin(min(1.0, r / exact_mm)) + _REL
        report.measurements.append(Measurement(q, plan, length, mu, value, tol, angle_err, angle_tol, problem))
        if plan == BOUND:
            continue
        tail, head, absolute = _ends(q)
        for which, pt, name, label in (("tail", (x1, y1), tail, line.get("data-from")),
                                       ("head", (x2, y2), head, line.get("data-to"))):
            ends.append((f"{q} {which}", pt, absolute, name, label))
    if plan != BOUND:
        _closures(report, gid, ends, r + _REL)
    if plan == FORCE:
        _force_closure(report, gid, lines, r)
    elif plan == LEVER:
        _lever(report, g, gid, lines, r)


def _add(report: SvgReport, check: Check) -> None:
    report.checks.append(check)
    if not check.ok:
        report.problems.append(f"plan {check.plan}: {check.what}: {check.deviation:.3g} {check.unit} "
                               f"(tolerance {check.tolerance:.2g} {check.unit})")


def _force_closure(report: SvgReport, gid: str, lines: list[ET.Element], r: float) -> None:
    """A force polygon's sides sum to zero, drawn and as recorded."""
    sides = [d for d in (_line_data(l) for l in lines if l.get("data-role") == "side") if d is not None]
    if len([l for l in lines if l.get("data-role") == "side"]) != len(sides) or not sides:
        report.problems.append(f"plan {gid}: a force plan without readable sides (data-role=\"side\")")
        return
    dx = sum(x2 - x1 for (x1, _, x2, _), _, _ in sides)
    dy = sum(y2 - y1 for (_, y1, _, y2), _, _ in sides)
    _add(report, Check(gid, f"Σ of the {len(sides)} drawn sides", math.hypot(dx, dy), len(sides) * r + _REL, "mm"))
    ex = sum(v * math.cos(t) for _, v, t in sides)
    ey = sum(v * math.sin(t) for _, v, t in sides)
    total = sum(v for _, v, _ in sides)
    _add(report, Check(gid, "Σ of the recorded forces", math.hypot(ex, ey), FORCE_CLOSURE_REL * total + 1e-12, "N"))
    report.equations[gid] = report.equations.get(gid, 0) + 1


def _lever(report: SvgReport, g: ET.Element, gid: str, lines: list[ET.Element], r: float) -> None:
    """Arms and Σ M_p = 0 of Zhukovsky's lever (see :mod:`plans.checking`)."""
    pole = [_number(c) for c in (g.get("data-pole") or "").split(",")]
    if len(pole) != 2 or None in pole or not all(math.isfinite(c) for c in pole):
        report.problems.append(f"plan {gid}: the lever's data-pole {g.get('data-pole')!r} is not a paper point x,y")
        return
    px, py = pole
    arms = {}
    for a in g.iter(f"{_SVG}line"):
        if a.get("data-construction") == "arm":
            arms.setdefault(a.get("data-arm") or "", []).append(a)
    total = bound = scale = 0.0
    for line in lines:
        q, data = line.get("data-quantity"), _line_data(line)
        if data is None:
            continue                    # already a failed measurement
        (x1, y1, x2, y2), value, t = data
        ux, uy = math.cos(t), math.sin(t)
        cross = (x1 - px) * uy - (y1 - py) * ux        # paper frame, y down: clockwise on screen positive
        h = abs(cross)
        recorded = _number(line.get("data-h"))
        if recorded is None or not math.isfinite(recorded) or recorded < 0:
            report.problems.append(f"plan {gid}: {q}: data-h {line.get('data-h')!r} is not an arm in mm ≥ 0")
            continue
        _add(report, Check(gid, f"arm of {q} (drawn vs data-h)", abs(h - recorded), r + _REL * recorded, "mm"))
        drawn = arms.pop(q, [])
        if recorded >= MIN_ARM_MM and not drawn:
            report.problems.append(f"plan {gid}: {q}: its arm of {recorded:g} mm is not drawn")
        for a in drawn:
            ax = [_number(a.get(k)) for k in ("x1", "y1", "x2", "y2")]
            if None in ax:
                report.problems.append(f"plan {gid}: the arm of {q} has no coordinates")
                continue
            start = math.hypot(ax[0] - px, ax[1] - py)
            off = abs((ax[2] - x1) * uy - (ax[3] - y1) * ux)
            length = math.hypot(ax[2] - ax[0], ax[3] - ax[1])
            dev = max(start, off, abs(length - h))
            _add(report, Check(gid, f"arm of {q} (from the pole, to its line, its length)", dev, r + _REL * h, "mm"))
        moment = -math.copysign(value * h, cross)        # counter-clockwise positive, as on paper y up
        total += moment
        bound += value * r
        scale += abs(moment)
    for q in arms:
        report.problems.append(f"plan {gid}: an arm of {q!r}, which is no force of the lever")
    _add(report, Check(gid, "Σ M_p with the drawn arms", abs(total), bound + _REL * scale + 1e-12, "N·mm"))
    report.equations[gid] = report.equations.get(gid, 0) + 1


def _closures(report: SvgReport, gid: str, ends: list, tol: float) -> None:
    """Join the ends named alike (by label or by the quantity's name); every point's ends
    must coincide."""
    u = _Union()
    for k, (_, _, _, name, label) in enumerate(ends):
        u.find(("end", k))
        if name is not None:
            u.join(("end", k), ("name", name))
        if label is not None:
            u.join(("end", k), ("label", label))
    classes: dict = {}
    for k in range(len(ends)):
        classes.setdefault(u.find(("end", k)), []).append(k)
    count = 0
    for members in classes.values():
        if len(members) < 2:
            continue
        pts = [ends[k][1] for k in members]
        gap = max(math.dist(a, b) for a in pts for b in pts)
        labels = sorted({ends[k][4] for k in members if ends[k][4] is not None})
        names = sorted({_point_name(ends[k][3]) for k in members if ends[k][3] is not None})
        point = " = ".join(labels + [n for n in names if n not in labels]) or "?"
        report.closures.append(Closure(gid, point, tuple(ends[k][0] for k in members), gap, tol))
        if not all(ends[k][2] for k in members):   # the pole shared by absolute vectors only is no equation
            count += len(members) - 1
    report.equations[gid] = report.equations.get(gid, 0) + count


def check_svg(path: str | Path, precision: float | None = None) -> list[Measurement]:
    """Measure every tagged vector of the SVG at ``path`` (length and direction; see
    :func:`inspect_svg` for the closure and file checks). ``precision`` (mm) as there, but
    by default that of the coordinates actually written. Raises :class:`DrawingError` when the
    file breaks the SVG contract (a transform, a doctored data-precision, a bad data-mu …)."""
    report = inspect_svg(path, precision)
    if report.kind == "none":
        return []
    if report.problems:
        raise DrawingError(f"{path}: {report.problems[0]}")
    return report.measurements

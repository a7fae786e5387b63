"""Measuring drawings: every tagged vector of an SVG, and every construction with shapely.

``inspect_svg`` reads an SVG back (ElementTree) and checks, plan by plan (a ``<g>`` with
``data-mu``), what the drawing claims:

1. **length** — each ``<line data-quantity>`` measured in millimetres × the plan's
   ``data-mu`` equals ``data-value`` within ``mu · 2√2 · precision + 1e-9 · value`` (two end
   points, each rounded by at most ``precision`` per coordinate);
2. **direction** — the drawn direction ``(x2 − x1, y2 − y1)`` agrees with
   ``data-direction`` (degrees, SVG paper frame: x right, y down, tail → head). The exact
   vector is ``e = (value/μ)·(cos θ, sin θ)`` mm; two rounded ends move the drawn vector by at
   most ``r = 2√2 · precision`` mm, so the angle between drawn and exact may reach
   ``asin(r/|e|)`` ≈ ``2√2 · precision / |e|`` (+ 1e-9 rad): short vectors get a looser
   angular tolerance, and a vector shorter than ``r`` has no measurable direction;
3. **closure** — the vector equations close graphically. Each vector's ends are points
   (images) named twice: by the writer's labels ``data-from``/``data-to`` and by the
   quantity's name — ``v:X`` runs from the pole to x; ``v:X/Y`` (``a:X/Y``, ``r:X/Y``) from
   y to x; ``a:X/Y:n`` from y to n_XY and ``a:X/Y:t`` from n_XY to x; ``a:X/Y:cor`` from y to
   k_XY and ``a:X/Y:r`` from k_XY to x. Ends named alike (by either name) form one point,
   and all its ends must coincide within ``2√2 · precision`` — so ``p→a`` plus ``a→b`` ends
   where ``p→b`` ends. A name of another form adds no equation (never a failure); each
   plan's number of equations checked is reported (:attr:`SvgReport.equations`);
4. **the file itself** — the user unit is the millimetre (``width``/``height`` in mm equal
   to the ``viewBox``, origin 0 0); no ``transform`` (attribute or CSS) on a tagged line
   or any element above it, whose ancestors are ``<g>`` and the root ``<svg>`` only;
   ``data-mu`` positive and finite; ``data-value`` finite and ≥ 0; every ``<line>`` of a
   plan either a tagged vector or a construction line (``data-construction``).

**Precision.** The tolerance never comes from the file. ``plans check`` measures against
:data:`WRITER_PRECISION`, the rounding of plans' own writer (``Style().precision``); a
library caller that wrote with another :class:`~plans.drawing.style.Style` passes its
``precision``, and with ``precision=None`` it is the rounding of the coordinates actually
written (``0.5 · 10^-D``, D the most decimals of any vector coordinate). A root
``data-precision`` looser than that precision, or not a positive number, is a failure.

**Sheets.** Each plan's ``<g>`` states how many vectors its writer drew
(``data-vectors``); the tagged lines found must be that many. A file whose only plan group is
the scheme (``data-plan="scheme"``) has nothing to measure: it is reported as a scheme and is
not a failure; nor is a plan drawn with no vector (``data-vectors="0"``: the pole alone — a
mechanism at rest, or a construction not drawn at that position, as its subtitle says), nor a
handout's assignment or answer sheet (``data-sheet="assignment"``, no plan group: areas left for
the student). Any
other file without a tagged vector — a plan whose tags were removed, or an SVG not written by
plans — fails ("no tagged vectors: not a plan written by plans"). A centres sheet's measured
segments ``r:X/Pj`` run from the centre Pj to the point X and are checked like vectors.
**Kinetostatics.** A force plan (``data-plan="force"``, μ = μF in N/mm) is measured like
any plan (length × μF = the force in N, direction, ends named alike by their vertex labels
coincide — so a whole reaction ends where its two components do, and a reaction between the
group's links joins the vertices it must); besides, its sides (``data-role="side"``) must
sum to zero: drawn, within ``n · 2√2 · precision`` mm for n sides, and as recorded (value ×
direction), within :data:`FORCE_CLOSURE_REL` of Σ values — except in an enlarged detail of a
run of short sides (``data-detail``: an open run of the polygon's sides, measured and named
alike but not closed). Zhukovsky's lever
(``data-plan="lever"``, μ = μF, the pole's paper position in ``data-pole``): every force is
measured as a vector; its arm about the pole — the distance from the pole to the line
through its drawn tail in its recorded direction — must equal its ``data-h`` within
``2√2 · precision`` (two rounded points); each drawn arm (``data-construction="arm"``,
``data-arm`` = the force) must start at the pole, end on that line and be that long; and the
moments ± F·h with the drawn arms must sum to zero, Σ M_p = 0, within Σ F · 2√2 · precision
(+ 1e-9 relative) — except in the lever's enlarged detail of its pole region
(``data-detail="pole"``, its own μF and pole, arms k·h): its forces and arms are measured
alike, but it holds only the forces applied near the pole, so Σ M_p = 0 is not asked there.
Each of these is a :class:`Check`; a failed one is also a problem.

A group drawn alone (``data-plan="group"``, μ = μl: textbook Fig. 1.27 a) is checked by
:mod:`plans.checking_groups`: the directions of its forces, its arms (from the centre to the
force's line, length × μl = the arm) and its moment equations recomputed from the drawn arms
and the tagged forces.

A group with ``data-plan="bound"`` holds vectors drawn at their points of application on a
scheme (Koshel's V_S1, V_S2 drawn from S1, S2 in the plan's scale): each is measured for
length and direction, but its ends are no plan images, so it adds no closure equation.

A gear sheet's angular-velocity picture (``data-plan="gear-omega"``) is checked further by
:mod:`plans.checking_gears`: each ray starts at its pole, runs parallel to its link's velocity
line and ends where the link's ω ends, and the declared scales agree, μω = μV/(μl·h).

This module holds the checks of a file (:func:`inspect_svg`, :func:`check_svg`). Beside it:
:mod:`plans.checking_report` (what is found: :class:`Measurement`, :class:`Closure`,
:class:`Check`, :class:`SvgReport`), :mod:`plans.checking_read` (reading tagged vectors back)
and :mod:`plans.checking_geometry` (:func:`check_plan`, :func:`similarity_ratio`: shapely
checks of a constructed plan), all re-exported here. Knows those, the drawing's
:class:`~plans.drawing.style.Style` (the writer's precision) and the errors; must not import
the pipeline or anything above it.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import shapely

from .checking_geometry import GEOMETRY_TOL_MM, check_plan, similarity_ratio
from .checking_gears import gear_problems
from .checking_areas import area_checks
from .checking_groups import GROUP, check_group_diagram
from .checking_read import (_SVG, _TRANSFORM, _Union, _decimals, _ends, _line_data, _number, _paper_problems,
                            _point_name, _transformed)
from .checking_report import Check, Closure, Measurement, SvgReport
from .drawing.style import Style
from .errors import DrawingError, SceneError
from .scene import read_bytes

__all__ = ["Measurement", "Closure", "Check", "SvgReport", "inspect_svg", "check_svg", "check_plan", "GEOMETRY_TOL_MM",
           "WRITER_PRECISION", "similarity_ratio"]

#: Rounding of one coordinate written by plans' own writer, mm: what ``plans check`` measures against.
WRITER_PRECISION = Style().precision
#: Relative slack on lengths (SI) and on the angular tolerance (rad) for floating-point noise.
_REL = 1e-9
#: A force polygon's recorded sides (value × direction) must sum to zero within this fraction of Σ values.
FORCE_CLOSURE_REL = 1e-6
#: Kinds of kinetostatic plan groups.
FORCE, LEVER = "force", "lever"
#: A lever force whose recorded arm is at least this long must have its arm drawn, mm (the
#: writer's promise, plans.drawing.lever.MIN_ARM_MM, restated so the checker does not read the writer).
MIN_ARM_MM = 0.5
#: Plans whose vectors are measured; a group with another ``data-plan`` is a plan too unless "scheme".
SCHEME = "scheme"
#: Vectors drawn at their points of application (measured, never closed: see the module docstring).
BOUND = "bound"
#: Kind of a plan sheet its writer drew with no vector (``data-vectors="0"``): the pole alone.
EMPTY = "empty"
#: Kind of a handout's assignment or answer sheet (root ``data-sheet="assignment"``): framed areas
#: for the student's plans, nothing drawn to measure.
ASSIGNMENT = "assignment"
#: Largest SVG file checked, bytes (16 MB): plans' largest sheet is about 100 kB; a larger file,
#: or one that is not a regular file, is refused before it is read (plans.scene.read_bytes).
MAX_SVG_BYTES = 16_000_000
#: Root ids written for plan sheets (a sheet claiming to be a plan must carry tagged vectors).
_PLAN_IDS = ("velocity", "acceleration", "koshel", "centres")


def inspect_svg(path: str | Path, precision: float | None = WRITER_PRECISION) -> SvgReport:
    """Check every tagged vector, every vector equation and the file's own geometry (see the
    module docstring). ``precision``: the rounding (mm) the file was written with — plans'
    writer by default; None: that of the coordinates actually written. Raises
    :class:`DrawingError` only when the file cannot be read as XML."""
    path = Path(path)
    try:
        root = ET.fromstring(read_bytes(path, what="sheet (an SVG file)", limit=MAX_SVG_BYTES))
    except SceneError as exc:       # missing, not a regular file (a pipe, /dev/zero), too large
        raise DrawingError(str(exc)) from None
    except ET.ParseError as exc:
        raise DrawingError(f"{path}: cannot read the SVG ({exc})") from None
    tagged = [e for e in root.iter() if e.get("data-quantity") is not None]
    plan_groups = [g for g in root.iter(f"{_SVG}g") if g.get("data-mu") is not None]
    claims_plan = any(g.get("data-plan") != SCHEME for g in plan_groups) \
        or (root.get("id") or "").startswith(_PLAN_IDS)
    plans_ = [g for g in plan_groups if g.get("data-plan") != SCHEME]
    if not tagged:
        if plan_groups and not claims_plan:
            return SvgReport(str(path), SCHEME, precision or WRITER_PRECISION)
        if root.get("data-sheet") == ASSIGNMENT and not plans_:
            return SvgReport(str(path), ASSIGNMENT, precision or WRITER_PRECISION)
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
    above = _ancestry(root)             # one walk down the tree: linear in its size, at any depth
    for line in tagged:
        q = line.get("data-quantity")
        group, transformed, odd = above.get(line, (None, None, None))
        if line.tag != f"{_SVG}line":
            problems.append(f"{q}: tagged element <{line.tag.replace(_SVG, '')}> is not a <line>")
            continue
        bad = line if _transformed(line) else transformed
        if bad is not None:
            problems.append(f"{q}: transform on <{bad.tag.replace(_SVG, '')} id={bad.get('id')!r}>; "
                            "plan elements and everything above them must not be transformed")
        if odd is not None:
            problems.append(f"{q}: inside <{odd.tag.replace(_SVG, '')}>; a vector may sit in <g> elements only")
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
        if g.get("data-contact-ratio") is not None:
            _contact_ratio(report, g, lines)
    problems += gear_problems(root, precision)
    area_checks(report, root, precision)
    return report


def _contact_ratio(report: SvgReport, g: ET.Element, lines: list[ET.Element]) -> None:
    """An involute pair's ε_α read off the drawing: the drawn B1B2 over the drawn p_b against
    ``data-contact-ratio``, within what the two lengths' rounding allows."""
    gid = g.get("id") or "meshing"
    stated = _number(g.get("data-contact-ratio"))
    length = {}
    for line in lines:
        xy = [_number(line.get(k)) for k in ("x1", "y1", "x2", "y2")]
        if line.get("data-quantity") in ("B1B2", "pb") and None not in xy:
            length[line.get("data-quantity")] = math.hypot(xy[2] - xy[0], xy[3] - xy[1])
    if stated is None or not math.isfinite(stated) or set(length) != {"B1B2", "pb"} or length["pb"] <= 0:
        report.problems.append(f"plan {gid}: data-contact-ratio needs a finite value and the drawn B1B2 and pb")
        return
    r = 2.0 * math.sqrt(2.0) * report.precision
    ratio = length["B1B2"] / length["pb"]
    _add(report, Check(gid, "ε_α = B1B2/p_b (drawn) against the stated", abs(ratio - stated),
                       ratio * (r / length["B1B2"] + r / length["pb"]) + _REL * stated, ""))


def _check_group(report: SvgReport, g: ET.Element, lines: list[ET.Element]) -> None:
    plan, gid, p = g.get("data-plan", ""), g.get("id") or g.get("data-plan", ""), report.precision
    mu = _number(g.get("data-mu"))
    if mu is None or not math.isfinite(mu) or mu <= 0:
        report.problems.append(f"plan {gid}: data-mu {g.get('data-mu')!r} is not a positive finite number")
        return
    r = 2.0 * math.sqrt(2.0) * p          # largest drawn-vector error from two rounded ends, mm
    if plan == GROUP:
        check_group_diagram(report, g, lines, mu, r)
        return
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
    if plan == FORCE and g.get("data-detail") is None:
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
    """Arms and Σ M_p = 0 of Zhukovsky's lever (see the module docstring)."""
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
    if g.get("data-detail") is not None:
        return                          # a detail holds only some of the forces: no Σ M_p = 0
    _add(report, Check(gid, "Σ M_p with the drawn arms", abs(total), bound + _REL * scale + 1e-12, "N·mm"))
    report.equations[gid] = report.equations.get(gid, 0) + 1


def _ancestry(root: ET.Element) -> dict[ET.Element, tuple]:
    """For every element below ``root``, by one iterative walk down the tree: its nearest plan
    group above it (a ``<g data-mu>``), its nearest transformed element above it, and its nearest
    element above it that is neither a ``<g>`` nor the root (None where there is none)."""
    out: dict[ET.Element, tuple] = {}
    stack = [(root, (None, None, None))]
    while stack:
        el, (group, transformed, odd) = stack.pop()
        mine = (el if el.tag == f"{_SVG}g" and el.get("data-mu") is not None else group,
                el if _transformed(el) else transformed,
                el if el.tag != f"{_SVG}g" and el is not root else odd)
        for child in el:
            out[child] = mine
            stack.append((child, mine))
    return out


def _diameter(pts: list[tuple[float, float]]) -> float:
    """The largest distance between two of ``pts``: over their convex hull when there are many
    (a label shared by thousands of ends stays linear-logarithmic, not quadratic)."""
    if len(pts) > 64:
        hull = shapely.MultiPoint(pts).convex_hull
        pts = list(hull.exterior.coords) if hull.geom_type == "Polygon" else list(hull.coords)
    return max(math.dist(a, b) for a in pts for b in pts)


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
        gap = _diameter(pts)
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

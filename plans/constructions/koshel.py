"""Koshel's uncertain-scale plan fitted to its sheet, and the whole Koshel sheet.

Koshel draws the first velocity of a class III group to an arbitrary length and finds the
scale afterwards, so the length is the draughtsman's to choose: :func:`fit_segment` chooses
it from the series 1, 1.5, 2, 2.5, 3, 4, 5, 6, 8 × 10^k mm, as long as possible up to
UNCERTAIN_MM, so that the whole plan is at most KOSHEL_MAX_MM wide and high.

:func:`koshel_sheet` adds the scheme side of the method (Koshel & Koshel 2015, Fig. 1–2):
the base link's centre P_j found on the scheme where two lines meet — through each base pin
X whose velocity direction is known (its rod turns about, or slides on, the frame) ⊥ v_X
(variant 1), and through each special point S of the group that moves, ⊥ V_S, V_S being
drawn from S in the plan's scale K_V (variant 2) — the segments P_j–X of the proportion,
and the steps of the method with their numbers. Everything is geometry in paper mm (y up):
the scheme panel in scheme millimetres (world / μl), the plan in plan millimetres.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..errors import ConstructionError
from ..kinematics import Motion
from ..kinematics.state import J
from ..scene import FRAME, DriveKind
from ..structure import ComplexGroup
from .centres import REACH, CentreMark, CentreRay, _segment, _special_points, centre_label
from .detail import enlargeable
from .plans import AT_REST, EXTENSION_MM, UNCERTAIN_MM, ConstructionLine, Plan, PlanPoint
from .scales import fitting_scale
from .scheme import Scheme, scheme
from .. import linalg as la

__all__ = ["fit_segment", "KOSHEL_MAX_MM", "NICE_MM", "KoshelLine", "SpecialVector", "KoshelSheet", "koshel_sheet",
           "SCHEME_PANEL_MM"]

#: Largest width or height of Koshel's plan, mm (it shares an A4 sheet with its notes).
KOSHEL_MAX_MM = 150.0
#: Mantissas of the arbitrary segment's length, mm.
NICE_MM = (1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0)


def _extent(plan: Plan) -> float:
    pts = np.array([p.xy for p in plan.points] + [v.tail for v in plan.vectors] + [v.head for v in plan.vectors])
    return float(np.max(pts.max(axis=0) - pts.min(axis=0)))


def _nice_below(x: float) -> float:
    """The largest series length ≤ x (mm)."""
    k = math.floor(math.log10(x))
    return max(float(f"{m:g}e{e}") for e in (k - 1, k) for m in NICE_MM if float(f"{m:g}e{e}") <= x)


def fit_segment(plan: Plan, segment_mm: float = UNCERTAIN_MM, limit: float = KOSHEL_MAX_MM) -> tuple[Plan, float]:
    """Koshel's ``plan`` drawn with its arbitrary first segment ``segment_mm`` long, redrawn
    with the longest series segment ≤ segment_mm that keeps it within ``limit`` mm; returns
    the plan and the segment's length (mm). The scale K_V = μ grows as the plan shrinks, so
    every vector still measures its exact value; construction lines keep their EXTENSION_MM
    overrun past the images."""
    extent = _extent(plan)
    if extent <= limit:
        return plan, segment_mm
    seg = _nice_below(segment_mm * limit / extent)
    f = seg / segment_mm

    def s(p) -> tuple[float, float]:
        return (float(p[0]) * f, float(p[1]) * f)

    lines = []
    for l in plan.lines:
        a, b = np.array(s(l.start)), np.array(s(l.end))
        u = (b - a) / (la.norm(b - a) or 1.0)
        grow = EXTENSION_MM * (1.0 - f)
        lines.append(ConstructionLine(tuple(map(float, a - grow * u)), tuple(map(float, b + grow * u)), l.quantity,
                                      l.group))
    return replace(plan, mu=plan.mu / f, points=tuple(PlanPoint(p.label, s(p.xy)) for p in plan.points),
                   vectors=tuple(replace(v, tail=s(v.tail), head=s(v.head)) for v in plan.vectors),
                   lines=tuple(lines)), seg


#: Largest width and height of the scheme panel's geometry (scheme, P_j, S, V_S), mm.
SCHEME_PANEL_MM = (200.0, 150.0)
#: How far a construction line is drawn towards a centre off the panel, mm.
TOWARDS_MM = 40.0
#: How much coarser than the scheme's own μl the panel's μl may be, to make room for V_S.
COARSEN = 2.0


@dataclass(frozen=True)
class KoshelLine:
    """A dashed construction line of P_j on the scheme: through ``through`` (a base pin whose
    velocity direction is known, or a special point S), perpendicular to that velocity;
    ``start``/``end`` in scheme mm."""

    through: str
    start: tuple[float, float]
    end: tuple[float, float]


@dataclass(frozen=True)
class SpecialVector:
    """V_S drawn on the scheme from the special point ``name`` at ``tail`` in the plan's scale
    K_V: ``head`` = tail + v_S / K_V (mm), ``value`` = |v_S| (m/s)."""

    name: str
    tail: tuple[float, float]
    head: tuple[float, float]
    value: float


@dataclass(frozen=True)
class KoshelSheet:
    """Koshel's sheet of a class III group at one position.

    ``scheme`` (μl ``mu_l``) with the base link ``base``'s centre ``centre`` (a
    :class:`CentreMark`: at ``xy`` on the panel, or a direction when off it), the construction
    ``lines`` meeting there, the special points ``specials`` (name → mm; those that move get
    a vector in ``vectors``), the measured segments P_j–X (``rays``, m); the fitted
    uncertain-scale ``plan`` (K_V = plan.mu) and its arbitrary first segment ``segment``
    (mm); ``proportion``: (pin, |px| on the plan mm, |P_j X| on the scheme mm); ``steps``:
    the method step by step, in label markup."""

    scheme: Scheme
    mu_l: float
    base: str
    centre: CentreMark
    lines: tuple[KoshelLine, ...]
    specials: tuple[tuple[str, tuple[float, float]], ...]
    vectors: tuple[SpecialVector, ...]
    rays: tuple[CentreRay, ...]
    plan: Plan
    segment: float
    proportion: tuple[tuple[str, float, float], ...]
    steps: tuple[str, ...]

    @property
    def k_v(self) -> float:
        """The plan's scale K_V, (m/s)/mm."""
        return self.plan.mu


def _xy(v) -> tuple[float, float]:
    return (float(v[0]), float(v[1]))


def _cross(a, b) -> float:
    """The z component of a × b (plane vectors)."""
    return float(a[0] * b[1] - a[1] * b[0])


def _meet(p1, d1, p2, d2) -> np.ndarray | None:
    """The meeting point of the lines p1 + t·d1 and p2 + s·d2 (None when parallel)."""
    det = float(d1[0] * d2[1] - d1[1] * d2[0])
    if abs(det) < 1e-12:
        return None
    w = p2 - p1
    return p1 + float(w[0] * d2[1] - w[1] * d2[0]) / det * d1


def _sub(name: str) -> str:
    """A name with trailing digits as a braced subscript (S1 → S_{1}, P5 → P_{5})."""
    stem = name.rstrip("0123456789")
    return f"{stem}_{{{name[len(stem):]}}}" if stem != name else name


def koshel_sheet(motion: Motion, i: int, g: ComplexGroup, plan: Plan, segment: float) -> KoshelSheet:
    """Koshel's sheet of group ``g`` at position ``i``; ``plan`` is the fitted uncertain-scale
    plan (from :func:`~plans.constructions.plans.uncertain_plan` and :func:`fit_segment`),
    ``segment`` its arbitrary first segment, mm. Raises ConstructionError when the base link's
    centre cannot be constructed (fewer than two lines, or parallel ones)."""
    mech = motion.mechanism
    base = g.base
    pname = centre_label(mech, base)
    world = {p: motion.position(p)[i] for p in mech.sketch}
    pins = [p.point for p in g.inner if p.kind == "R"]
    driven = next(r for r in g.rods if r.form == "RR" and r.outer.b != FRAME)
    x_name, y_name = driven.inner.point, driven.outer.point
    speed = max(float(la.norm(motion.velocity(p, base)[i])) for p in pins)
    # the lines of known direction: base pins of rods on the frame (variant 1) …
    known = []                                   # (name, point m, unit direction ⊥ v, words)
    for rod, ax in zip(g.rods, motion.special_points[g.name].axes):
        if rod.outer.b == FRAME and rod.form in ("RR", "PR"):
            x = rod.inner.point
            why = f"v_{{{x}}} ⊥ {rod.outer.point}{x}" if rod.form == "RR" else \
                f"v_{{{x}}} ∥ the guide of {rod.link}"
            known.append((x, world[x], ax.direction[i], why))
    # … and the special points of the group that move (variant 2)
    specials, moving, resting = [], [], []
    for label, (s, v) in _special_points(motion, i).items():
        name, _, link = label.partition(":")
        if link != base:
            continue
        specials.append((name, s))
        if float(la.norm(v)) > AT_REST * speed:
            moving.append((name, s, v))
        else:
            resting.append(name)
    lines_m = [(n, p, d) for n, p, d, _ in known] + [(n, s, J(v) / la.norm(v)) for n, s, v in moving]
    if len(lines_m) < 2:
        raise ConstructionError(f"fewer than two lines of known direction for the centre of link {base}")
    centre = _meet(lines_m[0][1], lines_m[0][2], lines_m[1][1], lines_m[1][2])
    if centre is None:
        raise ConstructionError(f"the lines through {lines_m[0][0]} and {lines_m[1][0]} are parallel: link {base} "
                                "translates, its centre is at infinity")
    pts = np.array(list(world.values()))
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    middle, size = (lo + hi) / 2.0, float(np.hypot(*(hi - lo))) or mech.size
    near = float(la.norm(centre - middle)) <= REACH * size
    specials = [(n, s) for n, s in specials if la.norm(s - middle) <= REACH * size]
    every_moving = moving
    moving = [(n, s, v) for n, s, v in moving if la.norm(s - middle) <= REACH * size]
    k_v = plan.mu
    # μl: the series scale that fits the scheme, the centre and the special points; coarsened
    # (at most COARSEN times) so that V_S, drawn in K_V, fits too — else the longest V_S and
    # its point are left off the panel (the steps say so)
    panel = np.array(SCHEME_PANEL_MM)
    while True:
        every = np.vstack([pts] + [c[None, :] for c in ([centre] if near else []) + [s for _, s in specials]])
        ext = every.max(axis=0) - every.min(axis=0)

        def fitting(lim):
            return max(fitting_scale(float(ext[0]) or size, float(lim[0])),
                       fitting_scale(float(ext[1]) or size, float(lim[1])))

        def fits(mu):
            mm = np.vstack([every / mu] + [(s / mu + v / k_v)[None, :] for _, s, v in moving])
            return bool(np.all(mm.max(axis=0) - mm.min(axis=0) <= panel))

        mu0 = mu = fitting(panel)
        lim = panel
        while not fits(mu) and mu < COARSEN * mu0:
            lim = lim * 0.9
            mu = fitting(lim)
        if fits(mu) or not moving:
            break
        drop = max(moving, key=lambda m: float(la.norm(m[2])))
        moving = [m for m in moving if m[0] != drop[0]]
        specials = [x for x in specials if x[0] != drop[0]]
    if not fits(mu):
        mu = fitting(panel)
    sch = scheme(motion, i, mu)
    anchor = np.mean([world[p] for p in mech.links[base].points if p in world], axis=0) / mu
    if near:
        mark = CentreMark(pname, base, _xy(centre / mu), None, _xy(anchor), False)
    else:
        d = (centre - anchor * mu) / la.norm(centre - anchor * mu)
        mark = CentreMark(pname, base, None, _xy(d), _xy(anchor), False)
    # the construction lines, each through its points and on to P_j (or towards it)
    lines = []
    covered = []
    for n, p, d in lines_m:
        if any(abs(_cross(d, p - q)) < 1e-9 * size and abs(_cross(d, dq)) < 1e-9
               for q, dq in covered):
            continue                         # this line is drawn already (S on a rod's axis)
        on = [p / mu] + [s / mu for _, s in specials if abs(_cross(d, s - p)) < 1e-9 * size]
        if near:
            on.append(centre / mu)
        else:
            u = (centre - p) / la.norm(centre - p)
            on.append(p / mu + TOWARDS_MM * u)
        names = [n] + [m for m, s in specials if m != n and abs(_cross(d, s - p)) < 1e-9 * size]
        a, b = _segment(on)
        lines.append(KoshelLine(", ".join(names), a, b))
        covered.append((p, d))
    vectors = tuple(SpecialVector(n, _xy(s / mu), _xy(s / mu + v / k_v), float(la.norm(v)))
                    for n, s, v in moving)
    rays = tuple(CentreRay(f"r:{x}/{pname}", _xy(centre / mu), _xy(world[x] / mu),
                           float(la.norm(world[x] - centre))) for x in pins) if near else ()
    vec = {v.quantity: v for v in plan.vectors}
    first = x_name
    order = [first] + [p for p in pins if p != first]
    proportion = tuple((x, vec[f"v:{x}"].length, float(la.norm(world[x] - centre)) / mu) for x in order)
    steps = _steps(motion, i, g, plan, segment, mu, pname, known, every_moving, moving, resting, proportion, x_name, y_name,
                   driven)
    return KoshelSheet(sch, mu, base, mark, tuple(lines), tuple((n, _xy(s / mu)) for n, s in specials), vectors,
                       rays, plan, segment, proportion, steps)


def _crowded(plan: Plan) -> str:
    """What step 2 adds when images crowd the pole: they are drawn enlarged in a detail."""
    crowd = enlargeable(plan)
    if crowd is None:
        return ""
    names = ", ".join(sorted(crowd[0]))
    return f"; {names} lie within {crowd[1]:.2g} mm of p, so the region round the pole is drawn enlarged " \
        "beside the plan (its detail, in its own scale)"


def _steps(motion, i, g, plan, segment, mu, pname, known, moving, drawn, resting, proportion, x, y, driven) -> tuple[str, ...]:
    """The method step by step (label markup), with the numbers of this position."""
    mech = motion.mechanism
    P = _sub(pname)
    base = g.base
    out = []
    if len(known) >= 2:
        (c, _, _, wc), (d, _, _, wd) = known[:2]
        s1 = f"1) {P}, the centre of the base link {base}: {wc} and {wd} (the rods turn about, or slide on, the " \
             f"frame), so {P} is where the line through {c} ⊥ v_{{{c}}} meets the line through {d} ⊥ v_{{{d}}} " \
             "(Fig.\u00a01, variant 1)"
        if resting:
            s1 += f"; it is the special point {_sub(resting[0])} of the group"
        if len(moving) >= 2:
            (a, _, _), (b, _, _) = moving[:2]
            s1 += f". Variant\u00a02 (Fig.\u00a02): {_sub(a)}, {_sub(b)} (where the rods' axes meet) get V_{{{a}}}, V_{{{b}}} " \
                  f"from two known directions each, drawn from {_sub(a)}, {_sub(b)} in K_{{V}}; the lines through them " \
                  f"⊥ V_{{{a}}}, ⊥ V_{{{b}}} meet at {P} too"
    else:
        names = [n for n, _, _ in moving[:2]]
        s1 = f"1) {P}, the centre of the base link {base}: the special points {', '.join(map(_sub, names))} " \
             f"(where the rods' axes meet) get their velocities from two known directions each, drawn from them in " \
             f"K_{{V}}; {P} is where the lines through them ⊥ V_{{{names[0]}}}, ⊥ V_{{{names[1]}}} meet " \
             "(Fig.\u00a02, variant 2)"
    off = [n for n, _, _ in moving if n not in {m for m, _, _ in drawn}]
    if off:
        s1 += f" ({', '.join(map(_sub, off))} {'lies' if len(off) == 1 else 'lie'} off the sheet here, so " \
              f"{', '.join(f'V_{{{n}}}' for n in off)} {'is' if len(off) == 1 else 'are'} not drawn)"
    out.append(s1 + ".")
    out.append(f"2) p{x.lower()} = {segment:g} mm ⊥ {P}{x}, in the sense of ω_{{{base}}} (chosen): an arbitrary length "
               f"— K_{{V}} is not known yet, so the plan's size is chosen and its scale follows; {segment:g} mm is the "
               f"longest of the series 1, 1.5, 2, 2.5, 3, 4, 5, 6, 8 mm × a power of ten, up to {UNCERTAIN_MM:g} mm, "
               f"that keeps the whole plan within {KOSHEL_MAX_MM:g} × {KOSHEL_MAX_MM:g} mm{_crowded(plan)}.")
    drive = mech.drive
    crank = drive.kind == DriveKind.ROTARY and drive.link == driven.outer.b and drive.pivot is not None
    o = drive.pivot if crank else None
    along = f"⊥ {o}{y}" if crank else f"along v_{{{y}}} (link {driven.outer.b})"
    out.append(f"3) {y.lower()}: V_{{{y}}} = V_{{{x}}} + V_{{{y}{x}}}, V_{{{y}{x}}} ⊥ {y}{x} (a line through "
               f"{x.lower()}); V_{{{y}}} = V_{{{y}{o}}} {along} (a line through p); they meet at {y.lower()}. "
               f"Had p{y.lower()} come out against ω_1, ω_{{{base}}} would be reversed.")
    vec = {v.quantity: v for v in plan.vectors}
    py = vec[f"v:{y}"]
    if crank:
        l_oy = float(la.norm(motion.position(y)[i] - motion.position(o)[i]))
        out.append(f"4) K_{{V}} = V_{{{y}}} / p{y.lower()} = ω_1·l_{{{o}{y}}} / p{y.lower()} = {abs(motion.drive_rates(i)[0]):g} 1/s · "
                   f"{l_oy:.4g} m / {py.length:.2f} mm = {plan.mu:.4g} (m/s)/mm.")
    else:
        out.append(f"4) K_{{V}} = V_{{{y}}} / p{y.lower()} = {py.value:.4g} m/s / {py.length:.2f} mm = "
                   f"{plan.mu:.4g} (m/s)/mm.")
    ratios = " = ".join(f"{q:.2f}/{s:.2f}" for _, q, s in proportion)
    names = " = ".join(f"p{n.lower()}/{P}{n}" for n, _, _ in proportion)
    values = ", ".join(f"V_{{{n}}} = {q * plan.mu:.4g} m/s" for n, q, _ in proportion)
    omega = abs(float(motion.links[base].omega[i]))
    out.append(f"5) {names}: {ratios} = {proportion[0][1] / proportion[0][2]:.4f} (mm/mm), "
               f"each ⊥ {P}X; so {values}; ω_{{{base}}} = V_{{{x}}} / l_{{{x}{pname}}} = {omega:.4g} 1/s.")
    return tuple(out)

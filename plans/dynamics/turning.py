"""Flywheel problems without a linkage, as textbooks pose them (Khurmi & Gupta, *Theory of
Machines*, ch. 16 "Turning moment diagrams and flywheel"): a machine given by its crank torque T(θ)
over one cycle against a resisting torque T_res(θ) (:func:`analyse_turning`), and a punching or
riveting operation fed by a motor and a flywheel (:func:`analyse_operation`).

The cycle. E(θ) = ∫₀^θ (T − T_res) dθ (J, θ in radians) is the energy the flywheel has gained
since 0°; it is greatest and least where T crosses T_res, and ΔE = E_max − E_min is the
fluctuation of energy. With the mean speed ω_m = (ω_max + ω_min)/2 and δ = (ω_max − ω_min)/ω_m,
½J(ω_max² − ω_min²) = J·ω_m²·δ exactly, so J = ΔE/(ω_m²·δ) (the book's ΔE = I·ω²·C_s, and
the conventions of :mod:`.machine`, whose flywheel is the same with a constant reduced inertia).
The flywheel's angular acceleration is (T − T_res)/J. The rim: the hoop stress of a thin rim is
σ = ρ·v² (Khurmi & Gupta, "Dimensions of the flywheel rim"), so v = √(σ/ρ) and D = 2v/ω_m; the
rim's mass sits at its mean radius and carries the part ``share`` of J (1 by default: the whole,
the book's "neglecting the arms and hub"), m = share·J/(D/2)² (= ΔE/(v²·δ) for share 1); its
section A = m/(ρ·π·D) = b·t.

The operation. One operation takes E (J) in t (s); the motor works all the time at P = E/every
(or as given), so it gives P·t while the operation lasts and the flywheel the rest,
ΔE = E − P·t = ½J(ω1² − ω2²) (ω1 before, ω2 after).

Numerics, exactly. T and T_res are sums of pieces whose integrals and bounds have closed forms:
linear pieces (tables, triangles, rectangles: trapezoids are exact), harmonics A·sin(kθ + φ)
(∫ = A/k·(cos φ − cos(kθ + φ))), semicircles p·√(1 − u²) (∫ = p·h·(½(u√(1 − u²) + asin u) + π/4)).
Every table vertex, shape end, apex and semicircle centre is a break; on each piece between
breaks the crossings of T − T_res are found exactly where it is linear (the line's root) and
otherwise by certified isolation: the piece is halved until on each part either the exact range
of T − T_res (each term's own range: a line's or monotone semicircle's ends, sin's extremes where
they fall inside) excludes 0, or its derivative's range does (monotone: one root, by Brent's
method, SciPy's brentq, to 1e-13° plus 4 ulps); parts narrower than 1e-9° are a tangency (no
crossing) unless the sign changes. So no crossing is missed, however close two lie, but between two whose lobe stays
within :data:`NOISE` (1e-12) of the torques' size of 0 (its energy is then below 1e-12 of the size
times its width: rounding); and E, the areas and ΔE are closed forms evaluated at those crossings,
exact to rounding (~1e-15 relative).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import SceneError
from ..scene.dynamics import MAX_DELTA
from ..scene.turning import FlywheelSpec, OperationSpec, Torque, TurningSpec

__all__ = ["TurningAnalysis", "Rim", "OperationAnalysis", "analyse_turning", "analyse_operation", "STEADY_RTOL", "GRID_STEP_DEG"]

RAD = math.pi / 180.0
TWO_PI = 2.0 * math.pi
#: The driving and resisting works over the cycle may differ by this part of the larger before the
#: cycle is refused as not steady (the flywheel would gain or lose energy every cycle).
STEADY_RTOL = 1e-9
#: The dense grid's step, degrees (every break and crossing is added to it).
GRID_STEP_DEG = 0.5
#: Parts of a piece narrower than this (deg) are not halved further (a tangency: no crossing).
ISOLATE_TOL = 1e-9
#: Values of |T − T_res| below this part of the torques' size count as 0 (rounding).
NOISE = 1e-12
#: The grid's chords of T − T_res stay within this part of the drawn range max(0, T, T_res) −
#: min(0, T, T_res) per radian: the -turning sheet's areas are those chords, and plans check allows
#: 2√2 × 0.0005 mm × μT per radian, ≥ 1.3e-5 of the range (μT ≥ range/110 mm); about half of it.
#: Intervals are halved down to MIN_STEP_DEG (a semicircle's ends, a jump), MAX_GRID angles at most.
CHORD_RTOL, MIN_STEP_DEG, MAX_GRID = 6e-6, 2.0 ** -26, 200_000


@dataclass(frozen=True)
class _Curve:
    """A torque as a sum: ``constant``, ``segments`` (x0, x1, y0, y1) linear on [x0, x1) and 0 elsewhere,
    ``harmonics`` (k, a, b) a·sin(kθ) + b·cos(kθ), ``semis`` (x0, x1, p) p·√(1 − u²); degrees, N·m."""

    constant: float = 0.0
    segments: tuple[tuple[float, float, float, float], ...] = ()
    harmonics: tuple[tuple[float, float, float], ...] = ()
    semis: tuple[tuple[float, float, float], ...] = ()


def _curve(torque: Torque, other_mean: float = 0.0) -> _Curve:
    segs, semis = [], []
    for (x0, y0), (x1, y1) in zip(torque.table, torque.table[1:]):
        segs.append((x0, x1, y0, y1))
    for s in torque.shapes:
        if s.kind == "semicircle":
            semis.append((s.start, s.end, s.peak))
        elif s.kind == "rectangle":
            segs.append((s.start, s.end, s.peak, s.peak))
        else:
            segs += [seg for seg in ((s.start, s.apex, 0.0, s.peak), (s.apex, s.end, s.peak, 0.0)) if seg[1] > seg[0]]
    harm = tuple((k, a * math.cos(math.radians(phi)), a * math.sin(math.radians(phi))) for a, k, phi in torque.harmonics)
    return _Curve(other_mean if torque.other_mean else torque.mean, tuple(segs), harm, tuple(semis))


def _combine(*parts: tuple[float, _Curve]) -> _Curve:
    """Σ w·curve, harmonics of one order and semicircles on one base merged (so that equal terms of T
    and T_res cancel exactly)."""
    harm: dict[float, list[float]] = {}
    semis: dict[tuple[float, float], float] = {}
    segs = []
    for w, c in parts:
        segs += [(x0, x1, w * y0, w * y1) for x0, x1, y0, y1 in c.segments]
        for k, a, b in c.harmonics:
            h = harm.setdefault(k, [0.0, 0.0])
            h[0] += w * a
            h[1] += w * b
        for x0, x1, p in c.semis:
            semis[(x0, x1)] = semis.get((x0, x1), 0.0) + w * p
    return _Curve(sum(w * c.constant for w, c in parts), tuple(segs),
                  tuple((k, a, b) for k, (a, b) in sorted(harm.items()) if a != 0.0 or b != 0.0),
                  tuple((x0, x1, p) for (x0, x1), p in sorted(semis.items()) if p != 0.0))


def _sin_range(p: float, q: float) -> tuple[float, float]:
    """The least and greatest sin ψ for ψ in [p, q] (p ≤ q)."""
    if q - p >= TWO_PI:
        return -1.0, 1.0

    def has(c: float) -> bool:
        return c + TWO_PI * math.ceil((p - c) / TWO_PI) <= q

    sp, sq = math.sin(p), math.sin(q)
    return (-1.0 if has(-0.5 * math.pi) else min(sp, sq)), (1.0 if has(0.5 * math.pi) else max(sp, sq))


class _Pieces:
    """A curve on the pieces between ``breaks`` (deg): its values, its integral E (J) and, on a part
    of one piece, the exact ranges of its values and of its slope (N·m per degree)."""

    def __init__(self, curve: _Curve, breaks: np.ndarray):
        self.b = breaks
        n = len(breaks) - 1
        self.yl, self.yr = np.full(n, curve.constant), np.full(n, curve.constant)
        for x0, x1, y0, y1 in curve.segments:
            j = np.nonzero((breaks[:-1] >= x0) & (breaks[1:] <= x1))[0]
            s = (y1 - y0) / (x1 - x0)
            self.yl[j] += y0 + s * (breaks[j] - x0)
            self.yr[j] += y0 + s * (breaks[j + 1] - x0)
        self.harm = curve.harmonics
        self.amp = [(k * RAD, math.hypot(a, b), math.atan2(b, a)) for k, a, b in curve.harmonics]
        self.semis = [(x0, x1, p, 0.5 * (x0 + x1), 0.5 * (x1 - x0)) for x0, x1, p in curve.semis]
        widths = np.diff(breaks) * RAD
        self.cum = np.concatenate([[0.0], np.cumsum(0.5 * (self.yl + self.yr) * widths)])

    def piece(self, x: np.ndarray) -> np.ndarray:
        return np.clip(np.searchsorted(self.b, x, side="right") - 1, 0, len(self.b) - 2)

    def _linear(self, x: np.ndarray, j: np.ndarray) -> np.ndarray:
        t = (x - self.b[j]) / (self.b[j + 1] - self.b[j])
        return self.yl[j] + (self.yr[j] - self.yl[j]) * t

    def value(self, x) -> np.ndarray:
        """T(x) (N·m) at angles x (deg); at a jump (a rectangle's end) the value after it."""
        x = np.asarray(x, dtype=float)
        out = self._linear(x, self.piece(x))
        for k, r, phi in self.amp:
            out = out + r * np.sin(k * x + phi)
        for x0, x1, p, c, h in self.semis:
            u = (x - c) / h
            out = out + np.where((x >= x0) & (x <= x1), p * np.sqrt(np.maximum(1.0 - u * u, 0.0)), 0.0)
        return out

    def integral(self, x) -> np.ndarray:
        """∫₀^x T dθ (J, θ in radians), in closed form."""
        x = np.asarray(x, dtype=float)
        j = self.piece(x)
        out = self.cum[j] + 0.5 * (x - self.b[j]) * RAD * (self.yl[j] + self._linear(x, j))
        for k, a, b in self.harm:
            kx = k * RAD * x
            out = out + (a * (1.0 - np.cos(kx)) + b * np.sin(kx)) / k
        for x0, x1, p, c, h in self.semis:
            u = np.clip((x - c) / h, -1.0, 1.0)
            out = out + p * h * RAD * (0.5 * (u * np.sqrt(1.0 - u * u) + np.arcsin(u)) + 0.25 * math.pi)
        return out

    def at(self, x: float) -> float:
        return float(self.value(np.array([x]))[0])

    def linear_on(self, j: int) -> bool:
        lo, hi = self.b[j], self.b[j + 1]
        return not self.amp and not any(x0 <= lo and hi <= x1 for x0, x1, *_ in self.semis)

    def ranges(self, j: int, lo: float, hi: float) -> tuple[float, float, float, float]:
        """(least, greatest value; least, greatest slope) on [lo, hi] inside piece j: each term's exact
        range (a semicircle is monotone on a piece: its centre is a break)."""
        ends = self._linear(np.array([lo, hi]), np.array([j, j]))
        vmin, vmax = float(min(ends)), float(max(ends))
        s = (self.yr[j] - self.yl[j]) / (self.b[j + 1] - self.b[j])
        dmin = dmax = float(s)
        for k, r, phi in self.amp:
            smin, smax = _sin_range(k * lo + phi, k * hi + phi)
            cmin, cmax = _sin_range(k * lo + phi + 0.5 * math.pi, k * hi + phi + 0.5 * math.pi)
            vmin, vmax, dmin, dmax = vmin + r * smin, vmax + r * smax, dmin + r * k * cmin, dmax + r * k * cmax
        for x0, x1, p, c, h in self.semis:
            if not (x0 <= self.b[j] and self.b[j + 1] <= x1):
                continue
            ua, ub = max((lo - c) / h, -1.0), min((hi - c) / h, 1.0)
            va, vb = (p * math.sqrt(max(1.0 - u * u, 0.0)) for u in (ua, ub))
            ga, gb = (-p * u / (h * math.sqrt(1.0 - u * u)) if abs(u) < 1.0 else -math.copysign(math.inf, p * u)
                      for u in (ua, ub))
            vmin, vmax = vmin + min(va, vb), vmax + max(va, vb)
            dmin, dmax = dmin + min(ga, gb), dmax + max(ga, gb)
        return vmin, vmax, dmin, dmax


def _roots(f: _Pieces, j: int, eps: float) -> list[float]:
    """The angles in piece j where f is 0 or changes sign (deg): exact on a linear piece, else by
    certified isolation (see the module) and Brent's method."""
    lo, hi = float(f.b[j]), float(f.b[j + 1])
    if f.linear_on(j):
        yl, yr = float(f.yl[j]), float(f.yr[j])
        return [lo + yl * (hi - lo) / (yl - yr)] if yl * yr < 0.0 else []
    from scipy.optimize import brentq     # here: only a curved piece needs it

    out: list[float] = []
    stack = [(lo, hi, f.at(lo), f.at(hi))]
    while stack:
        a, b, fa, fb = stack.pop()
        vmin, vmax, dmin, dmax = f.ranges(j, a, b)
        if vmin > eps or vmax < -eps or (vmin >= -eps and vmax <= eps):
            if vmin >= -eps and vmax <= eps:
                out += [a, b]            # |f| is rounding here: its ends bound a stretch where f is 0
            continue
        if fa == 0.0 or fb == 0.0:
            out += [x for x, v in ((a, fa), (b, fb)) if v == 0.0]
        if dmin > 0.0 or dmax < 0.0 or b - a <= ISOLATE_TOL:
            if fa * fb < 0.0:
                out.append(brentq(f.at, a, b, xtol=1e-13, rtol=4 * np.finfo(float).eps))
            continue
        m = 0.5 * (a + b)
        fm = f.at(m)
        stack += [(m, b, fm, fb), (a, m, fa, fm)]
    return out


@dataclass(frozen=True)
class Rim:
    """The flywheel's rim: mean ``diameter`` D, ``width`` b and ``thickness`` t (m), ``mass`` (kg),
    ``area`` of its section (m²), peripheral ``speed`` v at D (m/s), its hoop ``stress`` ρ·v² (Pa)
    and the ``share`` of J it carries."""

    diameter: float
    width: float
    thickness: float
    mass: float
    area: float
    speed: float
    stress: float
    share: float


@dataclass(frozen=True, eq=False)
class TurningAnalysis:
    """One cycle of a machine given by its crank torque. Angles in degrees from the cycle's 0°,
    torques N·m, energies J.

    ``period``; ``omega`` ω_m (rad/s) and ``rpm``; ``theta`` a dense grid (every
    :data:`GRID_STEP_DEG`, every break and crossing) with ``torque`` T, ``resisting`` T_res and
    ``energy`` E = ∫₀^θ (T − T_res) dθ on it; ``breaks`` (table vertices, shape ends, apexes,
    semicircle centres); ``crossings`` where T − T_res changes sign, in [0, period); ``areas``
    the signed energies between 0°, the crossings and the period, in order; ``energy_at_crossings``
    E there; ``energy_max``, ``energy_min`` and where (``energy_max_at``, ``energy_min_at``: the
    speed is greatest and least there); ``energy_fluctuation`` ΔE; ``mean_torque`` (the driving
    torque's, = the resisting's), ``mean_resisting``, ``power`` (W), ``work_per_cycle``,
    ``energy_coefficient`` ΔE/work; ``delta`` δ, ``inertia`` J (kg·m²), ``radius`` k (m), ``mass``
    J/k² (kg), ``omega_max``, ``omega_min`` ω_m(1 ± δ/2) (rad/s), each None when not known;
    ``acceleration`` ((as written, deg, (T − T_res)/J rad/s²), …); ``rim``."""

    period: float
    omega: float
    theta: np.ndarray
    torque: np.ndarray
    resisting: np.ndarray
    energy: np.ndarray
    breaks: np.ndarray
    crossings: np.ndarray
    areas: np.ndarray
    energy_at_crossings: np.ndarray
    energy_max: float
    energy_min: float
    energy_max_at: float
    energy_min_at: float
    energy_fluctuation: float
    mean_torque: float
    mean_resisting: float
    power: float
    work_per_cycle: float
    energy_coefficient: float
    delta: float | None
    inertia: float | None
    radius: float | None
    mass: float | None
    omega_max: float | None
    omega_min: float | None
    acceleration: tuple[tuple[str, float, float], ...]
    rim: Rim | None

    @property
    def rpm(self) -> float:
        return self.omega * 30.0 / math.pi


def analyse_turning(spec: TurningSpec, flywheel: FlywheelSpec | None = None) -> TurningAnalysis:
    """The cycle of ``spec`` (``[turning]``) with ``flywheel`` (``[flywheel]``), exactly (see the
    module). A cycle whose torques do unequal work, or whose driving torque does none, is refused."""
    period, omega = spec.period, spec.omega
    breaks = {0.0, period}
    for torque in (spec.torque, spec.resisting):
        breaks.update(x for x, _ in torque.table)
        for s in torque.shapes:
            breaks.update((s.start, s.end, 0.5 * (s.start + s.end)) if s.kind == "semicircle" else
                          (s.start, s.end) + ((s.apex,) if s.apex is not None else ()))
    b = np.array(sorted(breaks))
    uniform = np.linspace(0.0, period, int(math.ceil(period / GRID_STEP_DEG)) + 1)
    mean_of = {}
    for name, torque in (("torque", spec.torque), ("resisting", spec.resisting)):
        if not torque.other_mean:
            mean_of[name] = float(_Pieces(_curve(torque), b).integral(period)) / (period * RAD)
    t_curve = _curve(spec.torque, mean_of.get("resisting", 0.0))
    r_curve = _curve(spec.resisting, mean_of.get("torque", 0.0))
    drive, resist = _Pieces(t_curve, b), _Pieces(r_curve, b)
    work, work_res = float(drive.integral(period)), float(resist.integral(period))
    grid = np.union1d(uniform, b)
    size = float(np.max(np.abs(drive.value(grid))) + np.max(np.abs(resist.value(grid)))) or 1.0
    if not work > 0.0:
        raise SceneError(f"the driving torque does {work:.6g} J over the cycle: it must do work (its mean "
                         f"{work / (period * RAD):.6g} N·m is not positive)", key="turning.torque")
    if abs(work - work_res) > STEADY_RTOL * max(abs(work), abs(work_res), size * period * RAD):
        raise SceneError(f"the torques do unequal work over the cycle (driving {work:.9g} J, resisting {work_res:.9g} J): "
                         "the flywheel would gain or lose energy every cycle; make their means equal "
                         '(resisting = "mean" does)', key="turning.resisting")
    f = _Pieces(_combine((1.0, t_curve), (-1.0, r_curve)), b)
    eps = NOISE * size
    crossings = _crossings(f, eps, period)
    bounds = np.concatenate([[0.0], crossings[crossings > 0.0], [period]])
    energies = f.integral(bounds)
    areas = np.diff(energies)
    at_cross = f.integral(crossings)
    candidates = np.concatenate([[0.0], crossings])
    values = np.concatenate([[0.0], at_cross])
    tie = NOISE * float(np.max(values) - np.min(values))     # equal extremes (to rounding): the first
    i_max = int(np.argmax(values >= np.max(values) - tie))
    i_min = int(np.argmax(values <= np.min(values) + tie))
    fluctuation = float(values[i_max] - values[i_min])
    lo = min(0.0, float(np.min(drive.value(grid))), float(np.min(resist.value(grid))))
    hi = max(0.0, float(np.max(drive.value(grid))), float(np.max(resist.value(grid))))
    theta = _refined(f, np.union1d(grid, crossings), CHORD_RTOL * (hi - lo))
    mean = work / (period * RAD)

    delta, inertia = spec.delta, spec.inertia
    if delta is not None:
        if not fluctuation > 0.0:
            raise SceneError("T and T_res are equal all over the cycle (ΔE = 0): no flywheel to find for delta",
                             key="turning.delta")
        inertia = fluctuation / (omega * omega * delta)
    elif inertia is not None:
        held = inertia * omega * omega           # J·ω_m² (J), compared before dividing: it may underflow
        if not (held > 0.0 and held * MAX_DELTA >= fluctuation):
            raise SceneError(f"a flywheel of J = {inertia:g} kg·m² at ω_m = {omega:g} rad/s lets the speed swing by "
                             f"δ = ΔE/(J·ω_m²) beyond {MAX_DELTA:g} (ΔE = {fluctuation:.6g} J): the crank would nearly "
                             "stop; give a larger flywheel, or delta (J is found)",
                             key="flywheel.mass" if flywheel is not None and flywheel.mass is not None
                             else "turning.inertia")
        delta = fluctuation / held
    radius = flywheel.radius if flywheel is not None else None
    mass = inertia / radius ** 2 if inertia is not None and radius is not None else None
    accel = tuple((label, x, float(f.at(x)) / inertia) for label, x in spec.at) if inertia is not None else ()
    rim = _rim(flywheel, inertia, omega) if flywheel is not None and flywheel.rim is not None else None
    return TurningAnalysis(
        period=period, omega=omega, theta=theta, torque=drive.value(theta), resisting=resist.value(theta),
        energy=f.integral(theta), breaks=b, crossings=crossings, areas=areas, energy_at_crossings=at_cross,
        energy_max=float(values[i_max]), energy_min=float(values[i_min]), energy_max_at=float(candidates[i_max]),
        energy_min_at=float(candidates[i_min]), energy_fluctuation=fluctuation, mean_torque=mean,
        mean_resisting=work_res / (period * RAD), power=mean * omega, work_per_cycle=work,
        energy_coefficient=fluctuation / work, delta=delta, inertia=inertia, radius=radius, mass=mass,
        omega_max=omega * (1 + delta / 2) if delta is not None else None,
        omega_min=omega * (1 - delta / 2) if delta is not None else None, acceleration=accel, rim=rim)


def _crossings(f: _Pieces, eps: float, period: float) -> np.ndarray:
    """Where f changes sign over the cycle, in [0, period) (0 when the sign at the cycle's end and at
    its start differ); across a stretch where f is 0, at the stretch's start."""
    cand = set(f.b.tolist())
    for j in range(len(f.b) - 1):
        cand.update(_roots(f, j, eps))
    pts = np.array(sorted(cand))
    mids = f.value(0.5 * (pts[:-1] + pts[1:]))
    signs = np.where(mids > eps, 1, np.where(mids < -eps, -1, 0))
    nonzero = [(float(pts[i]), float(pts[i + 1]), int(s)) for i, s in enumerate(signs) if s != 0]
    out = []
    for prev, cur in zip([nonzero[-1]] + nonzero[:-1], nonzero) if nonzero else ():
        if cur[2] != prev[2]:
            out.append(0.0 if prev[1] >= period else prev[1])
    return np.array(sorted(set(out)))


def _refined(f: _Pieces, grid: np.ndarray, tol: float) -> np.ndarray:
    """``grid`` (deg), intervals halved until |∫f − h·(f0 + f1)/2| ≤ ``tol``·h (N·m) on each, or it
    is MIN_STEP_DEG wide; only the new midpoints are evaluated."""
    y, e = f.value(grid), f.integral(grid)
    ends = (grid[:-1], grid[1:], y[:-1], y[1:], e[:-1], e[1:])
    added, count = [], len(grid)
    while True:
        a, b, ya, yb, ea, eb = ends
        h = (b - a) * RAD
        bad = (np.abs(eb - ea - 0.5 * h * (ya + yb)) > tol * h) & (b - a > MIN_STEP_DEG)
        if not bad.any():
            break
        a, b, ya, yb, ea, eb = (v[bad] for v in ends)
        m = 0.5 * (a + b)
        ym, em = f.value(m), f.integral(m)
        added.append(m)
        count += len(m)
        if count > MAX_GRID:
            raise SceneError(f"the torques vary too fast to be drawn: their chords would need more than {MAX_GRID} "
                             "angles over the cycle; fewer rows, shapes or lower harmonics", key="turning.torque")
        ends = tuple(np.concatenate(p) for p in ((a, m), (m, b), (ya, ym), (ym, yb), (ea, em), (em, eb)))
    return np.union1d(grid, np.concatenate(added)) if added else grid


def _rim(flywheel: FlywheelSpec, inertia: float | None, omega: float) -> Rim | None:
    rim = flywheel.rim
    if inertia is None:
        return None
    if rim.stress is not None:
        speed = math.sqrt(rim.stress / rim.density)
        diameter = 2.0 * speed / omega
    else:
        diameter = rim.diameter
        speed = 0.5 * omega * diameter
    radius2 = (0.5 * diameter) ** 2
    mass = rim.share * inertia / radius2 if radius2 > 0.0 else math.inf
    area = mass / (rim.density * math.pi * diameter)
    thickness = math.sqrt(area / rim.width_to_thickness)
    bad = next(((k, v) for k, v in (("diameter", diameter), ("mass", mass), ("section", area),
                                     ("thickness", thickness), ("width", rim.width_to_thickness * thickness))
                if not (0.0 < v < math.inf)), None)
    if bad is not None:
        raise SceneError(f"the rim's {bad[0]} comes out {bad[1]:g}, beyond the range of a double: check its density, "
                         "stress or diameter against the flywheel's J", key="flywheel.rim")
    return Rim(diameter=diameter, width=rim.width_to_thickness * thickness, thickness=thickness, mass=mass, area=area,
               speed=speed, stress=rim.density * speed * speed, share=rim.share)


@dataclass(frozen=True)
class OperationAnalysis:
    """A punching or riveting operation: ``energy`` E (J) in ``duration`` t (s); the motor's
    ``power`` P (W), ``every`` (s from one operation to the next: E/P when not given) and
    ``per_minute``; ``motor_energy`` P·t and ``flywheel_energy`` ΔE = E − P·t (J); the flywheel's
    ``rpm_before`` and ``rpm_after`` the operation, its ``inertia`` J (kg·m²) and ``mass`` (kg),
    each None when the problem does not give or find it."""

    energy: float
    duration: float
    power: float
    every: float
    per_minute: float
    motor_energy: float
    flywheel_energy: float
    rpm_before: float | None
    rpm_after: float | None
    inertia: float | None
    mass: float | None


def analyse_operation(spec: OperationSpec, flywheel: FlywheelSpec | None = None) -> OperationAnalysis:
    """The operation of ``spec`` (``[operation]``) with ``flywheel`` (``[flywheel]``):

    - ``rpm_before`` and ``rpm_after`` → J = 2ΔE/(ω1² − ω2²), the mass J/k²;
    - ``rpm_before`` and [flywheel] mass, radius → ω2 = √(ω1² − 2ΔE/J), refused when the
      flywheel would stop;
    - ``rpm`` and ``delta`` → J = ΔE/(ω_m²·δ), the mass J/k², rpm_after = rpm·(1 − δ/2);
    - ``speed`` v and ``delta`` → the mass ΔE/(v²·δ) (J = m·k² when the radius is given)."""
    power = spec.power if spec.power is not None else spec.energy / spec.every
    every = spec.every if spec.every is not None else spec.energy / power
    motor = power * spec.duration
    gives = spec.energy - motor
    radius = flywheel.radius if flywheel is not None else None
    w = math.pi / 30.0
    before, after, inertia, mass = spec.rpm_before, spec.rpm_after, None, None
    if spec.speed is not None:
        mass = gives / (spec.speed ** 2 * spec.delta)
        inertia = mass * radius ** 2 if radius is not None else None
    elif spec.rpm is not None:
        inertia = gives / ((w * spec.rpm) ** 2 * spec.delta)
        before, after = spec.rpm * (1 + spec.delta / 2), spec.rpm * (1 - spec.delta / 2)
    elif after is not None:
        w1, w2 = w * before, w * after
        inertia = 2.0 * gives / ((w1 - w2) * (w1 + w2))
    else:
        inertia, mass = flywheel.inertia, flywheel.mass
        w1 = w * before
        if not 0.5 * inertia * w1 * w1 > gives:      # ½Jω1² against ΔE, not divided: J may underflow
            raise SceneError(f"the flywheel holds ½Jω1² = {0.5 * inertia * w1 * w1:.6g} J at {before:g} rpm and must "
                             f"give {gives:.6g} J: it would stop; a larger flywheel or a higher speed",
                             key="operation.rpm_before")
        after = math.sqrt(w1 * w1 - 2.0 * gives / inertia) / w
    if mass is None and inertia is not None and radius is not None:
        mass = inertia / radius ** 2
    return OperationAnalysis(energy=spec.energy, duration=spec.duration, power=power, every=every,
                             per_minute=60.0 / every, motor_energy=motor, flywheel_energy=gives, rpm_before=before,
                             rpm_after=after, inertia=inertia, mass=mass)

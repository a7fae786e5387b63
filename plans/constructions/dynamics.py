"""The dynamics sheet's geometry (paper mm, y up): four graphs against the crank's turned angle
φ (from position 0, in its sense of rotation) and Wittenbauer's energy–mass diagram.

- M_r(φ): the reduced moment of the loads, positive where it drives the crank.
- A_r(φ) and A_d(φ): the work of what resists and of what drives (J). The loads' work is
  integrated graphically by chords, as on paper: over each interval between positions the
  curve M_r is replaced by its ordinate at the interval's middle, and the chord of the work
  curve rises by that ordinate times Δφ (the ray from a pole at distance H mm, so that
  μA = μM·μφ·H); the constant moment's work is the straight line from the origin to the end of
  the loads' work. Exact curves (solid) beside the chords (dashed).
- ΔT(φ) = A_d − A_r (J), exactly and as the difference of the graphical works.
- I_r(φ): the reduced moment of inertia with the rotor's (kg·m²).
- With a driving law (``[dynamics] driving`` in the crank angle), M_d(φ) is M_r's second curve
  and both works are integrated by chords: A_d = ∫M_d dφ (the graph's curve, tagged) and
  A_r = −∫M_r dφ (its second curve, tagged too: :class:`Second`).
- A cycle of several turns (``[dynamics] period``): every graph runs over the whole period; I_r
  repeats every turn, and its turned diagram is drawn over one turn.
- Wittenbauer: ΔT against I_r, built by projection as the textbook builds it: ΔT(φ) and
  Wittenbauer's diagram share μT and their ΔT = 0 level, so each position's ΔT is carried across
  by a horizontal line; I_r(φ) is drawn turned through 90° under Wittenbauer's diagram at its
  μI (I along x from the same I0, φ downwards at a μφ of its own), so each position's I_r is
  carried up by a vertical line; the curve's points are where the two lines meet. The tangents
  at ψ_max, ψ_min with tan ψ = ω_m²(1 ± δ)/2 (in the drawing's scales: × μI/μT) cut the segment
  kl on the ΔT axis (at I = I0, the axis's first value), kl·μT = ω_m²·δ·(J + I0), so
  J = kl·μT/(ω_m²·δ) − I0.

Every graph's ordinates at the positions are measured segments (length × μ = value); so is kl.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..dynamics import MachineDynamics, Startup
from .diagrams import Graph, make_graph, nice_step, ticks_for
from .scales import fitting_scale

__all__ = ["DynamicsDiagrams", "Wittenbauer", "Tangent", "Second", "dynamics_diagrams", "StartupDiagrams", "startup_diagrams", "PHI_MM", "GRAPH_MM", "GAP_MM",
           "WITTENBAUER_MM"]

#: Largest length of the φ axis (the cycle: one revolution, or the period's turns), mm.
PHI_MM = 190.0
#: Largest height of one graph, and the space between two, mm (ΔT(φ), which Wittenbauer's
#: diagram shares, is taller: :data:`ENERGY_MM`).
GRAPH_MM = 30.0
GAP_MM = 15.0
ENERGY_MM = 60.0
#: Largest length of the turned I_r(φ) diagram's φ axis (one revolution), mm.
TURNED_MM = 55.0
#: Largest width and height of Wittenbauer's diagram, mm.
WITTENBAUER_MM = (120.0, 195.0)
#: Samples of the exact curves per revolution (besides the positions and each side of every kink).
SAMPLES = 720


@dataclass(frozen=True)
class Tangent:
    """One of Wittenbauer's tangents: ``which`` "max" or "min", ``psi`` its angle on the paper
    (degrees), ``slope`` ω_m²(1 ± δ)/2 (J/(kg·m²)), ``touch`` (x, y) mm where it touches the
    curve, ``start`` (x, y) mm on the ΔT axis, ``end`` (x, y) mm past the touch point, and
    ``value`` its ΔT on the axis (J)."""

    which: str
    psi: float
    slope: float
    touch: tuple[float, float]
    start: tuple[float, float]
    end: tuple[float, float]
    value: float


@dataclass(frozen=True)
class Wittenbauer:
    """The energy–mass diagram: ``mu_i`` (kg·m²/mm), ``mu_t`` (J/mm), ``i0`` the I axis's first
    value (kg·m², at x = 0); the ``curve`` (mm), the ``at_positions`` (x, y mm, I, ΔT); the
    axes' ``i_ticks`` (I, x mm) and ``t_ticks`` (ΔT, y mm); ``width``, ``low``, ``high`` (mm);
    the two ``tangents`` (none for a given flywheel), ``segment`` kl (J: kl·μT) and ``inertia``
    J by the diagram (kg·m²)."""

    mu_i: float
    mu_t: float
    i0: float
    curve: tuple[tuple[float, float], ...]
    at_positions: tuple[tuple[float, float, float, float], ...]
    i_ticks: tuple[tuple[float, float], ...]
    t_ticks: tuple[tuple[float, float], ...]
    width: float
    low: float
    high: float
    tangents: tuple[Tangent, ...]
    segment: float | None
    inertia: float | None


@dataclass(frozen=True)
class Second:
    """A graph's second curve measured at the positions (with a driving law): the graph's
    ``quantity`` ("M" or "A"), the tags' ``name`` ("Md": M_d; "Ar": A_r), ``at_positions``
    (x mm, y mm, exact value) at the N + 1 positions, and for a work its ``chords`` (x mm,
    y mm, value) by graphical integration and their ``error`` (as :attr:`~.diagrams.Graph.error`)."""

    quantity: str
    name: str
    at_positions: tuple[tuple[float, float, float], ...]
    chords: tuple[tuple[float, float, float], ...] = ()
    error: float = 0.0


@dataclass(frozen=True)
class DynamicsDiagrams:
    """The sheet's graphs: ``mu_phi`` (rad/mm), ``length`` (mm, one revolution), ``positions``
    N, ``pole`` H (mm) of the graphical integration, ``loads_drive`` (True when the loads' work
    is A_d, as in an engine), the four ``graphs`` (M, A, T, I), ``works`` the names of the A
    graph's two curves (the loads' work, integrated by chords, and the constant moment's line;
    with a driving law A_d and A_r, both by chords) and ``wittenbauer``; ``mu_phi_turned`` the
    turned I_r(φ)'s φ scale (rad/mm, one turn); ``turns`` the cycle's turns (its φ axis spans
    them), ``per_turn`` the positions a turn, and ``seconds`` the second curves measured with a
    driving law (M_d, A_r)."""

    mu_phi: float
    length: float
    positions: int
    pole: float
    loads_drive: bool
    graphs: tuple[Graph, ...]
    works: tuple[str, str]
    wittenbauer: Wittenbauer
    mu_phi_turned: float = 0.0
    turns: int = 1
    per_turn: int = 0
    seconds: tuple[Second, ...] = ()


def dynamics_diagrams(machine: MachineDynamics) -> DynamicsDiagrams:
    """The sheet's geometry for a solved steady cycle (see the module)."""
    n = len(machine.theta)
    turns = round(machine.period / 360.0)
    two_pi = 2.0 * math.pi
    span = two_pi * turns                            # the cycle, rad
    mu_phi = fitting_scale(span, PHI_MM)
    length = span / mu_phi
    pos = np.append(machine.theta, span)
    mids = 0.5 * (pos[:-1] + pos[1:])
    eps = 1e-9
    kinks = np.concatenate([machine.breaks - eps, machine.breaks + eps]) if len(machine.breaks) else np.array([])
    theta = np.unique(np.concatenate([np.linspace(0.0, span, SAMPLES * turns + 1), pos, np.clip(kinks, 0.0, span)]))
    at = np.searchsorted(theta, pos)
    x = theta / mu_phi
    moment, inertia, energy = machine.moment(theta), machine.inertia(theta), machine.energy(theta)
    loads = machine.work(theta)                       # ∫M_r dφ
    # graphical integration by chords: the middle ordinate of each interval times Δφ
    steps = machine.moment(mids) * np.diff(pos)
    loads_g = np.concatenate([[0.0], np.cumsum(steps)])
    other_g = None
    if machine.driving is not None:   # a driving law: both works by chords, A_d the graph's curve
        drive = machine.driving_moment(theta)
        work, other, sym = machine.driving_work(theta), -loads, ("A_d", "A_r")
        work_g = np.concatenate([[0.0], np.cumsum(machine.driving_moment(mids) * np.diff(pos))])
        other_g = -loads_g
        t_g, loads_drive, extra_m, extra_sym = work_g + loads_g, False, drive, "M_d"
    else:
        line = machine.constant * theta                   # the constant moment's work
        line_g = -loads_g[-1] * pos / span              # the straight line to the chords' end
        loads_drive = machine.constant < 0.0
        if loads_drive:           # an engine: the loads drive, the constant moment is the consumer
            work, work_g, other, sym = loads, loads_g, -line, ("A_d", "A_r")
            t_g = loads_g + line_g
        else:
            work, work_g, other, sym = -loads, -loads_g, line, ("A_r", "A_d")
            t_g = line_g + loads_g
        extra_m, extra_sym = np.full_like(moment, machine.constant), "M_c" if machine.constant < 0.0 else "M_d"
    # M_r with M_d: the constant moment's line (driving a working machine, the consumer's in an engine) or the law
    m = _graph("M", "M_r" if machine.driving is None else "M_r, M_d", "N·m", top=0.0, x=x, values=moment, at=at, height=GRAPH_MM, extra=extra_m,
               extra_symbol=extra_sym)
    top = m.origin[1] + m.low - GAP_MM
    series = [work, work_g, other] + ([other_g] if other_g is not None else [])
    lo_ = min([0.0] + [float(np.min(v)) for v in series])
    hi_ = max([0.0] + [float(np.max(v)) for v in series])
    pole = fitting_scale(max(hi_ - lo_, 1e-300) / GRAPH_MM / (m.mu * mu_phi), 1.0)     # the series' next H
    a = _graph("A", "A", "J", top=top, x=x, values=work, at=at, graphical=(at, work_g), extra=other,
               extra_symbol=sym[1], mu=m.mu * mu_phi * pole)
    seconds: tuple[Second, ...] = ()
    if other_g is not None:
        a, seconds = _seconds(m, a, x[at], extra_m[at], other[at], other_g)
    top = a.origin[1] + a.low - GAP_MM
    t = _graph("T", "ΔT", "J", top=top, x=x, values=energy, at=at, graphical=(at, t_g), height=ENERGY_MM)
    witt = _wittenbauer(machine, inertia, energy, at[:-1], mu_t=t.mu)
    # I_r(φ) at Wittenbauer's μI, drawn turned under it (its φ at a scale of its own)
    top = t.origin[1] + t.low - GAP_MM
    i = _graph("I", "I_r", "kg·m²", top=top, x=x, values=inertia, at=at, mu=witt.mu_i)
    return DynamicsDiagrams(mu_phi=mu_phi, length=length, positions=n, pole=pole, loads_drive=loads_drive,
                            graphs=(m, a, t, i), works=sym, wittenbauer=witt,
                            mu_phi_turned=fitting_scale(two_pi, TURNED_MM), turns=turns, per_turn=n // turns,
                            seconds=seconds)


def _seconds(m: Graph, a: Graph, x: np.ndarray, drive: np.ndarray, other: np.ndarray,
             chords: np.ndarray) -> tuple[Graph, tuple[Second, ...]]:
    """With a driving law: M_d on the M graph and A_r (exact at the positions ``x`` mm, and by
    ``chords``) on the A graph, measured like the graphs' own curves; the A graph's drawn range
    widened to hold A_r's chords."""
    def pts(g: Graph, values: np.ndarray) -> tuple[tuple[float, float, float], ...]:
        return tuple((float(px), float(g.origin[1] + v / g.mu), float(v)) for px, v in zip(x, values))

    drawn = pts(a, chords)
    low = min([a.low] + [y - a.origin[1] for _, y, _ in drawn])
    high = max([a.high] + [y - a.origin[1] for _, y, _ in drawn])
    error = float(np.max(np.abs(chords - other)) / max(float(np.max(np.abs(other))), 1e-300))
    return replace(a, low=low, high=high), (Second("M", "Md", pts(m, drive)),
                                            Second("A", "Ar", pts(a, other), drawn, error))


def _graph(quantity: str, symbol: str, unit: str, *, top: float, x: np.ndarray, values: np.ndarray,
           at: np.ndarray, graphical: tuple[np.ndarray, np.ndarray] | None = None, extra: np.ndarray | None = None,
           extra_symbol: str = "", height: float = GRAPH_MM, mu: float | None = None) -> Graph:
    """:func:`~.diagrams.make_graph`, or for a quantity that is 0 over the whole cycle (I_r of a
    machine without masses or rotor, M_r of one without loads) its flat line on the φ axis at a
    unit scale (a range of 0 has no scale to fit, nor ticks to number but 0)."""
    series = [values] + ([graphical[1]] if graphical is not None else []) + ([extra] if extra is not None else [])
    if any(np.any(v != 0.0) for v in series):
        return make_graph(quantity, symbol, unit, top=top, x=x, values=values, at=at, graphical=graphical,
                          extra=extra, extra_symbol=extra_symbol, height=height, mu=mu)
    mu = 1.0 if mu is None or not mu > 0.0 else mu
    y = float(top)
    exact = tuple((float(px), y) for px in x)
    at_pos = tuple((float(x[k]), y, 0.0) for k in at)
    drawn = () if graphical is None else tuple((float(x[k]), y, 0.0) for k in graphical[0])
    more = () if extra is None else exact
    return Graph(quantity, symbol, unit, mu, (0.0, y), 0.0, 0.0, exact, at_pos, drawn, ((0.0, y),), 0.0, more,
                 extra_symbol)


def _wittenbauer(machine: MachineDynamics, inertia: np.ndarray, energy: np.ndarray, at: np.ndarray, *,
                 mu_t: float) -> Wittenbauer:
    """The diagram at ``mu_t`` (J/mm, the ΔT(φ) graph's, so that ΔT is projected across)."""
    i_lo, i_hi = float(np.min(inertia)), float(np.max(inertia))
    spread = i_hi - i_lo
    if not spread > 1e-9 * abs(i_hi):   # I_r constant (no masses: 0, or the rotor's): the I axis spans the
        swing = float(np.max(energy) - np.min(energy)) / machine.omega_m ** 2     # swing's inertia at ω_m
        spread = swing if swing > 0.0 else max(abs(i_hi), 1.0)
    i0 = 0.0
    if i_lo > 0.5 * spread:       # the I axis starts at a round value below the curve, not at 0
        step = nice_step(spread)
        i0 = math.floor(i_lo / step) * step
    i_end = i0 + max(i_hi - i0, spread)       # i_hi; with I_r constant, the spread past it
    mu_i = fitting_scale(i_end - i0, WITTENBAUER_MM[0] - 15.0)
    x_of = lambda v: (v - i0) / mu_i          # noqa: E731
    width = x_of(i_end) + 15.0
    wheel = machine.flywheel
    raw = []
    values = [0.0, float(np.min(energy)), float(np.max(energy))]
    for which, tg in (("max", wheel.tangent_max), ("min", wheel.tangent_min)):
        if tg is None:
            continue
        th, k, c = tg
        it, et = float(machine.inertia(th)), float(machine.energy(th))
        x_end = min(x_of(it) + 20.0, width - 2.0)
        ends = (c + k * i0, c + k * (i0 + x_end * mu_i))
        values += list(ends)
        raw.append((which, k, it, et, x_end, ends))
    lo, hi = min(values), max(values)
    tangents = tuple(Tangent(which, math.degrees(math.atan(k * mu_i / mu_t)), k, (x_of(it), et / mu_t),
                             (0.0, ends[0] / mu_t), (x_end, ends[1] / mu_t), ends[0])
                     for which, k, it, et, x_end, ends in raw)
    segment = inertia_w = None
    if len(tangents) == 2:
        segment = tangents[0].value - tangents[1].value
        inertia_w = segment / (machine.omega_m ** 2 * wheel.delta) - i0
    curve = tuple((float(x_of(v)), float(e / mu_t)) for v, e in zip(inertia, energy))
    pts = tuple((float(x_of(inertia[k])), float(energy[k] / mu_t), float(inertia[k]), float(energy[k])) for k in at)
    i_ticks = tuple((v, x_of(v)) for v in ticks_for(i0, i_end, 4) if x_of(v) >= -1e-9)
    t_ticks = tuple((v, v / mu_t) for v in ticks_for(lo, hi, 8)) if hi > lo else ((0.0, 0.0),)
    return Wittenbauer(mu_i=mu_i, mu_t=mu_t, i0=i0, curve=curve, at_positions=pts, i_ticks=i_ticks, t_ticks=t_ticks,
                       width=width, low=lo / mu_t, high=hi / mu_t, tangents=tangents, segment=segment,
                       inertia=inertia_w)


@dataclass(frozen=True)
class StartupDiagrams:
    """The start-up against time: ``mu_t`` (s/mm), ``length`` (mm, t_end), ``graphs`` ω(t)
    and the moments (the motor's; the loads', as ``extra``), ``time_ticks`` (t s, x mm) and
    ``steady`` (y mm of ω_max, ω_min on the ω graph) when the steady cycle was found."""

    mu_t: float
    length: float
    graphs: tuple[Graph, ...]
    time_ticks: tuple[tuple[float, float], ...]
    steady: tuple[float, float] | None


#: Width of the start-up's time axis and height of its graphs, mm.
STARTUP_MM = (330.0, 85.0)
#: Ordinates measured on the start-up's graphs: at this many equal steps of t.
STARTUP_ORDINATES = 12


def startup_diagrams(start: Startup) -> StartupDiagrams:
    """The start-up sheet's geometry from a simulated :class:`~plans.dynamics.Startup`."""
    mu_t = fitting_scale(start.t_end, STARTUP_MM[0])
    x = start.t / mu_t
    n = len(start.t)
    at = np.unique(np.round(np.linspace(0, n - 1, STARTUP_ORDINATES + 1)).astype(int))
    w = _graph("w", "ω_1", "rad/s", top=0.0, x=x, values=start.omega, at=at, height=STARTUP_MM[1])
    m = _graph("M", "M", "N·m", top=w.origin[1] + w.low - GAP_MM - 6.0, x=x, values=start.motor, at=at,
               extra=start.load, extra_symbol="M_r", height=STARTUP_MM[1])
    ticks = tuple((tv, tv / mu_t) for tv in ticks_for(0.0, start.t_end, 10) if tv / mu_t <= x[-1] + 1e-9)
    steady = None
    if start.steady is not None:
        steady = (w.origin[1] + start.steady.omega_max / w.mu, w.origin[1] + start.steady.omega_min / w.mu)
    return StartupDiagrams(mu_t=mu_t, length=float(x[-1]), graphs=(w, m), time_ticks=ticks, steady=steady)

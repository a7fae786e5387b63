"""Kinematic diagrams of the output link over one revolution, as geometry in paper mm (y up).

Three aligned graphs against time t (and the crank angle φ = ω1·t, ω1 constant): the
displacement s from the first position (a slider, m; a rocker's angle ψ, rad), the velocity v
(ω) and the acceleration a (ε). The exact curves are the solved motion at the dense samples;
beside them, the graphical differentiation by chords: between neighbouring positions i, i + 1
the chord's slope (s_{i+1} − s_i)/Δt is the velocity at the middle of the interval, and the
chords of that polyline give the acceleration at the positions (Δt = Δφ/ω1). Each graph states
how far its graphical values lie from the exact ones at the same instants.

Scales come from the standard series: μt (s/mm) so that one period T = 2π/|ω1| fits the
width, μφ = |ω1|·μt (rad/mm) follows; μs, μv, μa the smallest that keep each graph's range
within its height.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .scales import fitting_scale

__all__ = ["Graph", "Diagrams", "diagrams", "make_graph", "ticks_for", "nice_step", "WIDTH_MM", "GRAPH_MM", "GAP_MM"]

#: Largest length of the time axis (one period), mm: the width of an A3 sheet's drawing area
#: less room for the value numbers and the axis names.
WIDTH_MM = 330.0
#: Largest height of one graph, mm.
GRAPH_MM = 58.0
#: Space between two graphs (the position numbers, the next graph's name), mm.
GAP_MM = 20.0


@dataclass(frozen=True)
class Graph:
    """One diagram: ``quantity`` ("s", "v" or "a"), its ``symbol`` in label markup and ``unit``;
    ``mu`` (unit per mm); ``origin`` (mm: t = 0, value = 0); ``low``/``high`` the drawn range
    (mm from the origin, low ≤ 0 ≤ high); ``exact`` the dense curve (mm); ``at_positions``
    (x mm, y mm, exact value) at the N + 1 positions; ``graphical`` (x mm, y mm, value) the
    chord method's values (none for s); ``ticks`` (value, y mm); ``error`` the largest
    |graphical − exact| at the same instants over the largest |exact| (0 for s); ``extra`` a
    second exact curve (mm) on the same graph, named ``extra_symbol``."""

    quantity: str
    symbol: str
    unit: str
    mu: float
    origin: tuple[float, float]
    low: float
    high: float
    exact: tuple[tuple[float, float], ...]
    at_positions: tuple[tuple[float, float, float], ...]
    graphical: tuple[tuple[float, float, float], ...]
    ticks: tuple[tuple[float, float], ...]
    error: float
    extra: tuple[tuple[float, float], ...] = ()
    extra_symbol: str = ""


@dataclass(frozen=True)
class Diagrams:
    """The three graphs over one revolution: ``mu_t`` (s/mm), ``mu_phi`` (rad/mm), ``length``
    of the time axis (mm, one period), ``period`` T (s), ``omega`` ω1 (rad/s), ``start`` φ of
    position 0 (deg), ``step`` Δφ (deg), ``positions`` N, the output ``link`` and ``kind``
    ("slider", or "rocker" or "crank": a pivoted link, its angle), and ``time_ticks`` (t s, x mm)."""

    mu_t: float
    mu_phi: float
    length: float
    period: float
    omega: float
    start: float
    step: float
    positions: int
    link: str
    point: str
    kind: str
    graphs: tuple[Graph, ...]
    time_ticks: tuple[tuple[float, float], ...]


def nice_step(span: float, count: int = 5) -> float:
    """A tick step from the series 1, 2, 2.5, 5 × 10^k giving about ``count`` ticks over ``span``."""
    raw = span / count
    k = math.floor(math.log10(raw))
    return min((m * 10.0 ** k for m in (1.0, 2.0, 2.5, 5.0, 10.0)), key=lambda s: abs(math.log(s / raw)))


def ticks_for(low: float, high: float, count: int = 5) -> list[float]:
    """Values of the ticks from ``low`` to ``high`` (0 always among them), about ``count``."""
    step = nice_step(high - low, count)
    first = math.ceil(low / step - 1e-9)
    last = math.floor(high / step + 1e-9)
    return [round(k * step, 12) + 0.0 for k in range(first, last + 1)]


def make_graph(quantity: str, symbol: str, unit: str, *, top: float, x: np.ndarray, values: np.ndarray,
               at: slice | np.ndarray, graphical: tuple[slice | np.ndarray, np.ndarray] | None = None,
               extra: np.ndarray | None = None, extra_symbol: str = "", height: float = GRAPH_MM,
               mu: float | None = None) -> Graph:
    """One graph whose top is at ``top`` (mm): the exact ``values`` at abscissae ``x`` (mm), dots
    at the samples ``at``, the ``graphical`` values (at which samples, values) beside them, an
    ``extra`` exact curve on the same samples; ``mu`` the smallest series scale that keeps the
    range (0 always in it) within ``height`` unless given."""
    lo = min(0.0, float(np.min(values)), float(np.min(graphical[1])) if graphical is not None else 0.0,
             float(np.min(extra)) if extra is not None else 0.0)
    hi = max(0.0, float(np.max(values)), float(np.max(graphical[1])) if graphical is not None else 0.0,
             float(np.max(extra)) if extra is not None else 0.0)
    if mu is None:
        mu = fitting_scale(max(hi - lo, 1e-300), height)
    origin = (0.0, top - hi / mu)
    y = origin[1] + values / mu
    exact = tuple((float(px), float(py)) for px, py in zip(x, y))
    xa, va = x[at], values[at]
    at_pos = tuple((float(px), float(origin[1] + pv / mu), float(pv)) for px, pv in zip(xa, va))
    drawn, error = (), 0.0
    if graphical is not None:
        where, gv = graphical
        drawn = tuple((float(px), float(origin[1] + g / mu), float(g)) for px, g in zip(x[where], gv))
        error = float(np.max(np.abs(gv - values[where])) / np.max(np.abs(values)))
    more = () if extra is None else tuple((float(px), float(origin[1] + e / mu)) for px, e in zip(x, extra))
    ticks = tuple((tv, float(origin[1] + tv / mu)) for tv in (ticks_for(lo, hi) if hi > lo else [0.0]))
    return Graph(quantity, symbol, unit, mu, origin, lo / mu, hi / mu, exact, at_pos, drawn, ticks, error, more,
                 extra_symbol)


def diagrams(*, start: float, step: float, positions: int, every: int, omega: float, link: str, point: str,
             kind: str, s: np.ndarray, v: np.ndarray, a: np.ndarray) -> Diagrams:
    """The diagrams from the output's exact s, v, a at the dense samples of one revolution
    (2·every samples per position, the last at position N = position 0 a turn later; s a
    slider's displacement in m or a rocker's angle in rad). ``step`` Δφ in degrees (its sign
    the crank's sense), ``omega`` ω1 rad/s (≠ 0)."""
    period = 2.0 * math.pi / abs(omega)
    mu_t = fitting_scale(period, WIDTH_MM)
    length = period / mu_t
    dt = abs(math.radians(step) / omega)
    n_dense = len(s)
    t = np.arange(n_dense) * dt / (2 * every)
    x = t / mu_t
    s = s - s[0]                       # displacement from the first position
    pos = slice(0, n_dense, 2 * every)
    mid = slice(every, n_dense, 2 * every)
    s_pos = s[pos]                     # N + 1 values: positions 0 … N
    v_chord = np.diff(s_pos) / dt      # at the middles of the N intervals
    a_chord = (v_chord - np.roll(v_chord, 1)) / dt
    a_chord = np.append(a_chord, a_chord[0])   # position N is position 0 a turn later
    names = (("s", "m"), ("v", "m/s"), ("a", "m/s²")) if kind == "slider" else \
        (("ψ", "rad"), ("ω", "rad/s"), ("ε", "rad/s²"))      # a rocker or a crank: its angle
    sub = point if kind == "slider" else link
    graphs = []
    top = 0.0
    for (quantity, values, graphical_at, graphical), (sym, unit) in zip(
            (("s", s, None, None), ("v", v, mid, v_chord), ("a", a, pos, a_chord)), names):
        g = make_graph(quantity, f"{sym}_{{{sub}}}", unit, top=top, x=x, values=values, at=pos,
                       graphical=None if graphical is None else (graphical_at, graphical))
        graphs.append(g)
        top = g.origin[1] + g.low - GAP_MM
    time_ticks = tuple((tv, tv / mu_t) for tv in ticks_for(0.0, period, 8) if tv / mu_t <= length + 1e-9)
    return Diagrams(mu_t=mu_t, mu_phi=abs(omega) * mu_t, length=length, period=period, omega=omega, start=start,
                    step=step, positions=positions, link=link, point=point, kind=kind, graphs=tuple(graphs),
                    time_ticks=time_ticks)


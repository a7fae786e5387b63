"""The measurements of ``plans bench``, one function per section.

Each section function takes a :class:`Config` and returns a :class:`Section`: a table (rows
of raw numbers with a header and a format per column), notes that say how to read it,
headline figures (``summary``) and charts. Nothing here prints or writes files.

1. :func:`drawing_precision` — SVG coordinate decimals → error of the drawn vectors, size, time
2. :func:`solver_tolerance` — Newton tolerance → iterations, time, error vs a reference solution
3. :func:`cycle_resolution` — positions per revolution → error of graphical differentiation
4. :func:`throughput` / :func:`render_rate` — vectorised analysis vs a per-angle loop; sheets/s
5. :func:`peer_comparison` — the same cycles solved by pylinkage and by plans
6. :func:`numba_comparison` — crank-slider full kinematics: plans vs pylinkage's numba and pure-Python paths
7. :func:`class_cost` — class III and IV groups: cost per position against the crank-slider
"""

from __future__ import annotations

import math
import tempfile
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any, Callable

import numpy as np

from ..checking import check_svg
from ..drawing import Style
from ..errors import PlansError
from ..kinematics import analyse
from ..kinematics.state import LinkState
from ..model import Mechanism, build_mechanism
from ..pipeline import render_scene
from ..scene import read_scene
from ..structure import Structure, analyse_structure
from .chart import Chart, Series
from .timing import best_time, once

__all__ = ["Column", "Section", "Config", "FULL", "QUICK", "SECTIONS", "drawing_precision", "solver_tolerance",
           "cycle_resolution", "throughput", "render_rate", "peer_comparison", "THROUGHPUT_TARGET", "SolverCase",
           "SOLVER_CASES", "numba_comparison", "class_cost", "NUMBA_TARGET", "AGREEMENT_TARGET", "CLASS_COST_TARGET"]

#: The vectorised analysis should beat a per-angle Python loop by at least this factor.
THROUGHPUT_TARGET = 20.0
#: plans' full kinematics of the crank-slider should be at least this many times faster than
#: pylinkage's numba path …
NUMBA_TARGET = 3.0
#: … and agree with it to this, relative to the crank (|Δr|/r, |Δv|/ωr, |Δa|/ω²r).
AGREEMENT_TARGET = 1e-9
#: A class III or IV example may cost at most this many times the crank-slider per position.
CLASS_COST_TARGET = 10.0
#: Relative errors of drawn vectors are taken over vectors drawn at least this long (mm):
#: a vector of a few tenths of a millimetre has a large relative error at any precision.
LONG_MM = 10.0


@dataclass(frozen=True)
class Column:
    """A table column: JSON key, printed header, format spec of its values."""

    key: str
    header: str
    fmt: str = ""


@dataclass
class Section:
    """One measured section: a table with notes, headline figures and charts."""

    key: str
    title: str
    columns: tuple[Column, ...] = ()
    rows: list[tuple] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    summary: dict[str, Any] = field(default_factory=dict)
    charts: list[Chart] = field(default_factory=list)
    skipped: str | None = None

    def records(self) -> list[dict[str, Any]]:
        """The rows as dictionaries keyed by column (JSON)."""
        return [{c.key: _plain(v) for c, v in zip(self.columns, row)} for row in self.rows]


def _plain(v: Any) -> Any:
    if isinstance(v, (np.integer,)):
        return int(v)
    if isinstance(v, (np.floating, float)):
        return float(v) if math.isfinite(v) else None
    return v


@dataclass(frozen=True)
class Config:
    """What to measure; :data:`FULL` for ``plans bench``, :data:`QUICK` for tests."""

    name: str
    precision_scenes: tuple[str, ...]          # example stems rendered at each precision (empty: all)
    decimals: tuple[int, ...]
    tolerances: tuple[float, ...]
    solver_positions: int
    resolutions: tuple[int, ...]
    throughput_positions: int
    loop_positions: int                        # the per-angle loop is timed on this many of them
    batch_sizes: tuple[int, ...]
    render_scenes: tuple[str, ...]
    render_repeat: int                         # renders per scene and precision (the best one is timed)
    peer_positions: int
    repeat: int
    numba_positions: tuple[int, ...]           # crank-slider: plans vs pylinkage's numba and pure-Python paths
    class_positions: int                       # class III/IV vs crank-slider cost per position (72 a turn)
    class_large_positions: int                 # … and the same at this many positions, for comparison


FULL = Config("full", precision_scenes=(), decimals=(1, 2, 3, 4, 5, 6),
              tolerances=tuple(10.0 ** -k for k in range(2, 15)), solver_positions=360,
              resolutions=(8, 12, 24, 36, 72, 180, 360, 720, 3600), throughput_positions=3600, loop_positions=360,
              batch_sizes=(1, 10, 100, 360, 1000, 3600), render_scenes=("crank_slider_central", "six_link_press"),
              render_repeat=2, peer_positions=360, repeat=7, numba_positions=(3600, 100_000), class_positions=72,
              class_large_positions=3600)
QUICK = Config("quick", precision_scenes=("crank_slider_central",), decimals=(2, 4), tolerances=(1e-3, 1e-8, 1e-12),
               solver_positions=36, resolutions=(12, 36, 360), throughput_positions=360, loop_positions=12,
               batch_sizes=(10, 360), render_scenes=("crank_slider_central",), render_repeat=1, peer_positions=36,
               repeat=1, numba_positions=(36, 360), class_positions=72, class_large_positions=360)


# ---------------------------------------------------------------------------------------------
# helpers

def _example(stem: str) -> Path:
    return Path(str(resources.files("plans.examples") / f"{stem}.toml"))


def _all_examples() -> tuple[str, ...]:
    root = resources.files("plans.examples")
    return tuple(sorted(p.name[:-5] for p in root.iterdir() if p.name.endswith(".toml")))


def _load(stem: str) -> tuple[Mechanism, Structure]:
    mech = build_mechanism(read_scene(_example(stem)))
    return mech, analyse_structure(mech)


def _cycle(mech: Mechanism, n: int) -> np.ndarray:
    """``n`` crank angles (degrees) evenly over one turn, starting at the sketch."""
    return mech.drive.sketch_value + np.arange(n) * (360.0 / n)


def _local_distance(mech: Mechanism, link: str, p: str, q: str) -> float:
    loc = mech.links[link].local
    return float(np.linalg.norm(loc[p] - loc[q]))


def _max_norm(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.linalg.norm(np.asarray(a, float) - np.asarray(b, float), axis=-1)))


# ---------------------------------------------------------------------------------------------
# 1. drawing precision

def drawing_precision(cfg: Config) -> Section:
    """Render the examples with SVG coordinates rounded to 1…6 decimals, read every plan back
    with :func:`plans.checking.check_svg` and compare each drawn vector × μ with its exact value."""
    stems, failed = [], []
    for stem in cfg.precision_scenes or _all_examples():
        try:
            render_scene(_example(stem))
            stems.append(stem)
        except PlansError as exc:   # a bundled scene this version cannot render: say so, measure the rest
            failed.append(f"{stem} ({exc})")
    paths = [_example(s) for s in stems]
    rows = []
    with tempfile.TemporaryDirectory(prefix="plans-bench-") as tmp:
        for d in cfg.decimals:
            style = Style(decimals=d)
            seconds = 0.0
            sheets = plan_sheets = size = vectors = 0
            worst_rel = worst_mm = worst_frac = 0.0
            for path in paths:
                best, rendered = math.inf, None
                for _ in range(cfg.render_repeat):   # whole renders: some scenes take a good part of a second
                    t, rendered = once(lambda: render_scene(path, style))
                    best = min(best, t)
                seconds += best
                for name, text in rendered.files.items():
                    if not name.endswith(".svg"):
                        continue
                    sheets += 1
                    f = Path(tmp) / f"d{d}-{name}"
                    f.write_text(text, encoding="utf-8")
                    found = check_svg(f)
                    if not found:
                        continue   # a scheme: no tagged vectors
                    plan_sheets += 1
                    size += len(text.encode("utf-8"))
                    for m in found:
                        vectors += 1
                        worst_mm = max(worst_mm, m.error / m.mu)
                        worst_frac = max(worst_frac, m.error / m.tolerance)
                        if m.length_mm >= LONG_MM and m.value > 0:
                            worst_rel = max(worst_rel, m.error / abs(m.value))
            rows.append((d, vectors, worst_rel, worst_mm, worst_frac, size / plan_sheets / 1024,
                         seconds / sheets * 1e3))
    cols = (Column("decimals", "decimals", "d"), Column("vectors", "vectors", "d"),
            Column("worst_rel_error", f"worst rel. error (≥{LONG_MM:g} mm)", ".1e"),
            Column("worst_error_mm", "worst error (paper mm)", ".1e"),
            Column("worst_over_check_tol", "worst / check tol.", ".2f"),
            Column("kb_per_plan", "KB per plan", ".1f"), Column("ms_per_sheet", "ms per sheet", ".2f"))
    xs = tuple(float(r[0]) for r in rows)
    notes = [f"{len(stems)} scene(s): {', '.join(stems)}; every velocity and acceleration plan read back with "
             "plans.checking.check_svg, drawn length × μ against the exact data-value.",
             "worst / check tol. ≤ 1 means `plans check` accepts every vector (its bound is two rounded end points).",
             "ms per sheet: the whole render_scene (solve, constructions, checks, SVG, JSON) divided by its SVG "
             f"sheets, scheme included; best of {cfg.render_repeat} per scene."]
    if failed:
        notes.append("not measured, render_scene failed: " + "; ".join(failed))
    charts = [Chart("precision-error", "Drawing precision: error of the drawn vectors", "SVG coordinate decimals",
                    "error", (Series(f"worst relative error (vectors ≥ {LONG_MM:g} mm)", xs,
                                     tuple(r[2] for r in rows)),
                              Series("worst error in paper mm", xs, tuple(r[3] for r in rows))), log_y=True),
              Chart("precision-size", "Drawing precision: file size and render time", "SVG coordinate decimals",
                    "KB per plan sheet  /  ms per sheet",
                    (Series("KB per plan sheet", xs, tuple(r[5] for r in rows)),
                     Series("ms per sheet (render_scene)", xs, tuple(r[6] for r in rows))), y_from_zero=True)]
    summary = {"all_within_check_tolerance": all(r[4] <= 1.0 for r in rows),
               "default_decimals": Style().decimals}
    return Section("drawing_precision", "1. Drawing precision (SVG coordinate decimals)", cols, rows, notes,
                   summary, charts)


# ---------------------------------------------------------------------------------------------
# 2. solver tolerance
#
# The iterative position solvers under test, each on one scene, continued along a turn from
# the sketch (every position starts from the solver's own previous one), at tolerances
# 1e-2 … 1e-14, against a reference solution of the same positions. To measure another solver,
# add a SolverCase to SOLVER_CASES: its ``prepare(mech, structure, angles)`` returns
# (solve, exact, reference), where solve(tol) → (points (N, P, 2) in metres, Newton iterations
# (N,), converged (N,) booleans), exact is the reference points (N, P, 2) and reference says
# where they come from.

#: Newton steps allowed per position before it counts as not converged (the bench's own Newton).
MAX_ITERATIONS = 50
#: Seconds a section may spend repeating one timing (a slow solver is timed fewer times).
TIMING_BUDGET = 0.5

Solve = Callable[[float], tuple[np.ndarray, np.ndarray, np.ndarray]]


@dataclass(frozen=True)
class SolverCase:
    """An iterative position solver on one scene (see the comment above)."""

    label: str
    scene: str
    prepare: Callable[[Mechanism, Structure, np.ndarray], tuple[Solve, np.ndarray, str]]


def _generic_newton(mech: Mechanism, structure: Structure, angles: np.ndarray) -> tuple[Solve, np.ndarray, str]:
    """plans.kinematics.generic: Newton on the pair equations of the scene's class III/IV group,
    one position at a time from the previous one (the sketch, where every pose is the identity),
    stopping at |Φ| ≤ tol·size without the polishing step plans adds."""
    from ..kinematics.generic import GroupEquations

    group = next(g for g in structure.groups if g.klass > 2)
    eq = GroupEquations(mech, group.links, group.pairs)
    motion = analyse(mech, structure, angles, order=0)
    known = [{name: s.take(np.array([i])) for name, s in motion.links.items() if name not in eq.col}
             for i in range(len(angles))]
    local = [(c, mech.links[name].local[p]) for name, c in eq.col.items() for p in mech.links[name].points]

    def points(q: np.ndarray) -> np.ndarray:
        return np.stack([LinkState(q[:, c + 2], q[:, c:c + 2]).point(x) for c, x in local], axis=1)

    def solve(tol: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        q = np.zeros((len(angles), len(eq.col) * 3))
        iterations = np.zeros(len(angles), dtype=int)
        converged = np.zeros(len(angles), dtype=bool)
        guess = q[0]
        for i in range(len(angles)):
            r = eq.newton(guess[None, :], known[i], tol=tol, polish=False)
            q[i] = guess = r.q[0]
            iterations[i], converged[i] = r.iterations, r.converged
        return points(q), iterations, converged

    return solve, points(eq.pose(motion.links)), (f"plans.kinematics.analyse (the same Newton, polished to rounding) "
                                                   f"of group {group.name}")


def _four_bar_newton(mech: Mechanism, structure: Structure, angles: np.ndarray) -> tuple[Solve, np.ndarray, str]:
    """Newton's method written here on the loop closure of the four-bar O-A-B-C:

        Φ(θ2, θ3) = A(φ) + l2·e(θ2) − C − l3·e(θ3) = 0,   e(θ) = (cos θ, sin θ),

    with the Jacobian Φ_q = [l2·k×e(θ2), −l3·k×e(θ3)], whose determinant l2·l3·sin(θ3 − θ2)
    vanishes where coupler and rocker are collinear; scalar Python, one position after the
    other from the sketch, stopping when |Φ| ≤ tol·size. Reference: the closed form."""
    d = mech.drive
    ox, oy = (float(c) for c in mech.sketch[d.pivot])
    r = _local_distance(mech, d.link, d.pivot, d.tip)
    cx, cy = (float(c) for c in mech.sketch["C"])
    l2 = _local_distance(mech, "2", "A", "B")
    l3 = _local_distance(mech, "3", "C", "B")
    a0, b0 = mech.sketch["A"], mech.sketch["B"]
    t2_start = math.atan2(b0[1] - a0[1], b0[0] - a0[0])
    t3_start = math.atan2(b0[1] - cy, b0[0] - cx)
    size = mech.size
    phis = np.radians(angles).tolist()

    def solve(tol: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        out = np.empty((len(phis), 1, 2))
        iterations = np.empty(len(phis), dtype=int)
        t2, t3 = t2_start, t3_start
        bound = tol * size
        cos, sin = math.cos, math.sin
        for i, phi in enumerate(phis):
            ax, ay = ox + r * cos(phi), oy + r * sin(phi)
            k = 0
            while True:
                c2, s2, c3, s3 = cos(t2), sin(t2), cos(t3), sin(t3)
                fx = ax + l2 * c2 - cx - l3 * c3
                fy = ay + l2 * s2 - cy - l3 * s3
                if math.hypot(fx, fy) <= bound or k >= MAX_ITERATIONS:
                    break
                j11, j12, j21, j22 = -l2 * s2, l3 * s3, l2 * c2, -l3 * c3
                det = j11 * j22 - j12 * j21
                t2 += (-fx * j22 + fy * j12) / det       # Cramer's rule on Φ_q·Δq = −Φ
                t3 += (-fy * j11 + fx * j21) / det
                k += 1
            out[i, 0] = (ax + l2 * cos(t2), ay + l2 * sin(t2))
            iterations[i] = k
        return out, iterations, iterations < MAX_ITERATIONS

    exact = analyse(mech, structure, angles, order=0).position("B")[:, None, :]
    return solve, exact, "the closed form of plans.kinematics.analyse (point B)"


#: The solvers measured, in table order.
SOLVER_CASES = (
    SolverCase("plans generic Newton", "class3_six_link", _generic_newton),
    SolverCase("bench Newton, four-bar", "four_bar", _four_bar_newton),
)


def _best_of(fn: Callable[[], Any], repeat: int) -> tuple[float, Any]:
    """Best time of up to ``repeat`` calls (fewer when a call is slow) and the last result."""
    best, out, spent = math.inf, None, 0.0
    for _ in range(max(repeat, 1)):
        t, out = once(fn)
        best, spent = min(best, t), spent + t
        if spent > TIMING_BUDGET:
            break
    return best, out


def solver_tolerance(cfg: Config) -> Section:
    """Tolerance 1e-2 … 1e-14 → Newton iterations, time per position and error against a
    reference, for every case of SOLVER_CASES."""
    rows = []
    notes = []
    error_series, iteration_series = [], []
    n = cfg.solver_positions
    for case in SOLVER_CASES:
        try:
            mech, structure = _load(case.scene)
            angles = _cycle(mech, n)
            solve, exact, reference = case.prepare(mech, structure, angles)
            t_ref, _ = _best_of(lambda: analyse(mech, structure, angles, order=0), cfg.repeat)
            results = []
            for tol in cfg.tolerances:
                t, (pts, its, ok) = _best_of(lambda: solve(tol), cfg.repeat)
                results.append((tol, pts, its, ok, t))
        except (ImportError, AttributeError, TypeError, StopIteration, FileNotFoundError, PlansError) as exc:
            # the solver or its scene is not (yet) in this version: say so, measure the others
            notes.append(f"{case.label} on {case.scene}: not measured ({type(exc).__name__}: {exc})")
            continue
        xs = []
        for tol, pts, its, ok, t in results:
            err = _max_norm(pts, exact)
            rows.append((case.label, case.scene, tol, float(np.mean(its)), int(np.max(its)), int(np.sum(~ok)),
                         t / n * 1e6, err, err / mech.size))
            xs.append(tol)
        mine = rows[-len(results):]
        error_series.append(Series(f"{case.label} ({case.scene})", tuple(xs), tuple(r[8] for r in mine)))
        iteration_series.append(Series(f"{case.label} ({case.scene})", tuple(xs), tuple(r[3] for r in mine)))
        notes.append(f"{case.label} on {case.scene} (size {mech.size:.3g} m): reference {reference}; "
                     f"analyse(order=0) itself takes {t_ref / n * 1e6:.1f} µs per position at the same {n} positions.")
    cols = (Column("solver", "solver", "s"), Column("scene", "scene", "s"), Column("tolerance", "tolerance", ".0e"),
            Column("mean_iterations", "mean iter.", ".2f"), Column("max_iterations", "max iter.", "d"),
            Column("not_converged", "not conv.", "d"), Column("us_per_position", "µs per position", ".1f"),
            Column("max_error_m", "max error (m)", ".1e"), Column("error_over_size", "error / size", ".1e"))
    notes[:0] = [f"{n} positions per turn ({360 / n:g}° steps) from the sketch, each Newton solve starting from the "
                 "solver's previous position; stop when the largest residual ≤ tolerance × size of the mechanism; "
                 "error: largest distance of the group's points from the reference.",
                 f"time: best of up to {cfg.repeat} passes over the turn (fewer for a slow solver). To add or swap a "
                 "solver, edit SOLVER_CASES in plans/bench/sections.py."]
    xs_all = tuple(cfg.tolerances)
    charts = [Chart("solver-tolerance", "Solver tolerance: error against the reference", "tolerance",
                    "max error / size", tuple(error_series) + (Series("tolerance (reference line)", xs_all, xs_all),),
                    log_x=True, log_y=True),
              Chart("solver-iterations", "Solver tolerance: Newton iterations per position", "tolerance",
                    "mean iterations", tuple(iteration_series), log_x=True, y_from_zero=True)]
    summary = {"solvers": [c.label for c in SOLVER_CASES], "positions": n}
    return Section("solver_tolerance", "2. Solver tolerance (iterative position solves)", cols, rows, notes,
                   summary, charts)


# ---------------------------------------------------------------------------------------------
# 3. cycle resolution

CYCLE_SCENE = "crank_slider_central"


def cycle_resolution(cfg: Config) -> Section:
    """Positions per revolution → error of the slider's velocity and acceleration found by
    graphical differentiation (periodic central differences of s(φ)) against the exact ones."""
    mech, structure = _load(CYCLE_SCENE)
    prism = next(p for p in mech.prismatics if p.guide == "0")
    u = np.asarray(prism.direction, float)            # the guide is fixed in the frame: a world direction
    point = prism.label
    omega, eps = mech.drive.speed, mech.drive.rate

    def numeric(angles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        s = analyse(mech, structure, angles, order=0).position(point) @ u
        h = math.radians(360.0 / len(angles))
        nxt, prv = np.roll(s, -1), np.roll(s, 1)
        d1 = (nxt - prv) / (2 * h)
        d2 = (nxt - 2 * s + prv) / (h * h)
        return d1 * omega, d2 * omega ** 2 + d1 * eps   # v = s'·ω, a = s''·ω² + s'·ε

    rows = []
    prev = None
    for n in cfg.resolutions:
        angles = _cycle(mech, n)
        exact = analyse(mech, structure, angles, order=2)
        v_ex, a_ex = exact.velocity(point) @ u, exact.acceleration(point) @ u
        v_num, a_num = numeric(angles)
        ev = float(np.max(np.abs(v_num - v_ex)) / np.max(np.abs(v_ex)))
        ea = float(np.max(np.abs(a_num - a_ex)) / np.max(np.abs(a_ex)))
        order = None if prev is None else math.log(prev[1] / ev) / math.log(n / prev[0])
        t_num = best_time(lambda: numeric(angles), repeat=cfg.repeat)
        t_ex = best_time(lambda: analyse(mech, structure, angles, order=2), repeat=cfg.repeat)
        rows.append((n, 360.0 / n, ev, ea, order, t_num * 1e3, t_ex * 1e3))
        prev = (n, ev)
    cols = (Column("positions", "positions/turn", "d"), Column("step_deg", "step (°)", "g"),
            Column("v_rel_error", "v rel. error", ".1e"), Column("a_rel_error", "a rel. error", ".1e"),
            Column("observed_order_v", "order (v)", ".2f"), Column("ms_numeric", "ms differentiated", ".2f"),
            Column("ms_exact", "ms exact", ".2f"))
    xs = tuple(float(r[0]) for r in rows)
    notes = [f"slider {point} of {CYCLE_SCENE}: s(φ) along its guide at n evenly spaced crank angles; "
             "v = ω·(s[k+1] − s[k−1])/2h, a = ω²·(s[k+1] − 2s[k] + s[k−1])/h² (periodic), against "
             "plans.kinematics.analyse(order=2); errors relative to the largest |v|, |a| over the turn.",
             "ms differentiated: positions (order 0) + differences; ms exact: the analytic velocities and "
             f"accelerations at the same positions; best of {cfg.repeat}. Both walk the drive in 1° steps from "
             "the sketch, so below 360 positions the time hardly changes."]
    charts = [Chart("cycle-resolution", "Cycle resolution: graphical differentiation of s(φ)",
                    "positions per revolution", "relative error",
                    (Series("velocity", xs, tuple(r[2] for r in rows)),
                     Series("acceleration", xs, tuple(r[3] for r in rows))), log_x=True, log_y=True,
                    note="central differences: error ∝ h² (slope −2)")]
    return Section("cycle_resolution", "3. Cycle resolution (graphical differentiation vs exact)", cols, rows,
                   notes, {"scene": CYCLE_SCENE, "point": point}, charts)


# ---------------------------------------------------------------------------------------------
# 4. throughput

THROUGHPUT_SCENES = ("crank_slider_central", "six_link_press")
#: Passes of the per-angle loop (each some 0.2–1 s in the full bench); the best is kept.
LOOP_PASSES = 3


def throughput(cfg: Config) -> Section:
    """Positions per second of the full analysis (order 2) vectorised over N angles against
    a Python loop calling analyse with one angle at a time."""
    rows = []
    series = []
    loop_series = []
    batch: dict[str, dict[int, float]] = {}
    n = cfg.throughput_positions
    for stem in THROUGHPUT_SCENES:
        mech, structure = _load(stem)
        angles = _cycle(mech, n)
        t_vec = best_time(lambda: analyse(mech, structure, angles, order=2), repeat=cfg.repeat)
        vec = analyse(mech, structure, angles, order=2)
        pick = np.linspace(0, n, cfg.loop_positions, endpoint=False).astype(int)
        t_loop = math.inf
        for _ in range(min(cfg.repeat, LOOP_PASSES)):   # whole passes over the picked angles: the best one
            t, singles = once(lambda: [analyse(mech, structure, angles[i:i + 1], order=2) for i in pick])
            t_loop = min(t_loop, t)
        r_vec = {p: vec.position(p) for p in mech.sketch}
        a_vec = {p: vec.acceleration(p) for p in mech.sketch}
        a_max = max(float(np.max(np.linalg.norm(a, axis=1))) for a in a_vec.values())
        diff = max(max(_max_norm(m.position(p), r_vec[p][i:i + 1]),
                       _max_norm(m.acceleration(p), a_vec[p][i:i + 1]) / a_max)
                   for m, i in zip(singles, pick) for p in mech.sketch)
        per_vec, per_loop = t_vec / n, t_loop / len(pick)
        ratio = per_loop / per_vec
        rows.append((stem, n, 1 / per_vec, len(pick), 1 / per_loop, ratio,
                     "met" if ratio >= THROUGHPUT_TARGET else f"short ×{THROUGHPUT_TARGET / ratio:.2f}", diff))
        sizes = tuple(b for b in cfg.batch_sizes if b <= n)
        rates = []
        for b in sizes:
            sub = _cycle(mech, b)
            rates.append(b / best_time(lambda: analyse(mech, structure, sub, order=2), repeat=cfg.repeat))
        batch[stem] = dict(zip(sizes, rates))
        series.append(Series(f"{stem}: vectorised", tuple(float(b) for b in sizes), tuple(rates)))
        loop_series.append(Series(f"{stem}: per-angle loop", tuple(float(b) for b in sizes),
                                  tuple(1 / per_loop for _ in sizes)))
    cols = (Column("scene", "scene", "s"), Column("positions", "N", "d"),
            Column("vectorised_per_s", "vectorised pos/s", ",.0f"), Column("loop_timed_on", "loop timed on", "d"),
            Column("loop_per_s", "loop pos/s", ",.0f"), Column("ratio", "ratio", ".1f"),
            Column("target", f"≥{THROUGHPUT_TARGET:g}×", "s"), Column("max_rel_difference", "loop vs vec. Δ", ".0e"))
    notes = [f"full analysis (positions + velocities + accelerations, plans.kinematics.analyse order=2) over N "
             f"crank angles evenly over a turn in one call (best of {cfg.repeat}), against a Python loop calling "
             "analyse with one angle at a time.",
             f"The loop is timed on {cfg.loop_positions} of the N angles, evenly spread over the turn (best of "
             f"{min(cfg.repeat, LOOP_PASSES)} passes), and extrapolated per position; each call walks the drive "
             "from the sketch to its angle in 1° steps, as a single-angle render does.",
             "loop vs vec. Δ: largest difference between the two results (positions in m, accelerations "
             "relative to the largest), a check that both computed the same thing."]
    short = [r for r in rows if r[5] < THROUGHPUT_TARGET]
    summary = {"target": THROUGHPUT_TARGET, "met": not short, "ratios": {r[0]: r[5] for r in rows},
               "vectorised_per_s_by_batch": batch}
    if short:
        notes.append("below target: " + "; ".join(f"{r[0]} reaches {r[5]:.1f}×, short by a factor "
                                                  f"{THROUGHPUT_TARGET / r[5]:.2f}" for r in short))
    charts = [Chart("throughput", "Throughput of the full analysis (order 2)", "positions per call (N)",
                    "positions per second", tuple(series + loop_series), log_x=True, log_y=True)]
    return Section("throughput", f"4. Throughput (vectorised vs per-angle loop, target ≥ {THROUGHPUT_TARGET:g}×)",
                   cols, rows, notes, summary, charts)


def render_rate(cfg: Config) -> Section:
    """Plans rendered per second by plans.pipeline.render_scene (everything but writing files)."""
    rows = []
    for stem in cfg.render_scenes:
        path = _example(stem)
        r = render_scene(path)
        sheets = sum(name.endswith(".svg") for name in r.files)
        t = best_time(lambda: render_scene(path), repeat=cfg.repeat)
        rows.append((stem, len(r.motion), sheets, t * 1e3, sheets / t, 1 / t))
    cols = (Column("scene", "scene", "s"), Column("positions", "positions", "d"), Column("sheets", "sheets", "d"),
            Column("ms_per_scene", "ms per scene", ".1f"), Column("sheets_per_s", "sheets/s", ".0f"),
            Column("scenes_per_s", "scenes/s", ".1f"))
    notes = ["render_scene: read, solve, scales, constructions, shapely and similarity checks, SVG and JSON text "
             f"(files not written); sheets = scheme + velocity + acceleration plans per position; best of "
             f"{cfg.repeat}."]
    return Section("render_rate", "4b. Plans rendered per second", cols, rows, notes)


# ---------------------------------------------------------------------------------------------
# 5. peer comparison

PEER_SCENES = ("crank_slider_central", "four_bar")
INSTALL_HINT = 'pip install ".[bench]"'


def _pylinkage_model(pl, mech: Mechanism, stem: str, first_deg: float, step_deg: float):
    """The scene as a pylinkage Linkage: same dimensions, crank angles first_deg, first_deg +
    step_deg, … on its successive steps, the assembly branch of the sketch (given as the
    initial position of the dyad's joint). Returns the linkage, its crank, and the index in
    ``linkage.components`` of every compared point."""
    d = mech.drive
    o = mech.sketch[d.pivot]
    step = math.radians(step_deg)
    ground = pl.Ground(float(o[0]), float(o[1]), name=d.pivot)
    crank = pl.Crank(ground, _local_distance(mech, d.link, d.pivot, d.tip), angular_velocity=step,
                     initial_angle=math.radians(first_deg) - step, name=d.tip)   # step() turns before it yields
    if stem == "crank_slider_central":
        prism = next(p for p in mech.prismatics if p.guide == "0")
        b = mech.sketch[prism.label]
        anchor = np.asarray(prism.anchor["0"], float)
        ahead = anchor + np.asarray(prism.direction, float)
        line0 = pl.Ground(float(anchor[0]), float(anchor[1]), name="guide-0")
        line1 = pl.Ground(float(ahead[0]), float(ahead[1]), name="guide-1")
        slider = pl.RRPDyad(crank.output, line0, line1, _local_distance(mech, "2", d.tip, prism.label),
                            x=float(b[0]), y=float(b[1]), name=prism.label)
        components = [ground, line0, line1, crank, slider]
        points = {d.tip: 3, prism.label: 4}
    elif stem == "four_bar":
        c, b = mech.sketch["C"], mech.sketch["B"]
        pivot = pl.Ground(float(c[0]), float(c[1]), name="C")
        rocker = pl.RRRDyad(crank.output, pivot, _local_distance(mech, "2", "A", "B"),
                            _local_distance(mech, "3", "C", "B"), x=float(b[0]), y=float(b[1]), name="B")
        components = [ground, pivot, crank, rocker]
        points = {d.tip: 2, "B": 3}
    else:   # pragma: no cover - only the two scenes above are modelled
        raise ValueError(f"no pylinkage model of {stem}")
    linkage = pl.Linkage(components, name=stem)
    linkage.set_input_velocity(crank, d.speed, d.rate)
    return linkage, points


def peer_comparison(cfg: Config) -> Section:
    """The crank-slider and the four-bar over one turn, solved by pylinkage and by plans in the
    same run: time ratio and largest differences of positions, velocities, accelerations."""
    title = "5. Peer comparison (pylinkage, same cycles)"
    try:
        import pylinkage as pl
    except ImportError:
        return Section("peer_comparison", title, skipped="pylinkage is not installed: section skipped; install "
                       f"the bench extra: {INSTALL_HINT}")
    try:
        from pylinkage._numba_compat import HAS_NUMBA   # pylinkage's own flag; absent in other versions
    except ImportError:   # pragma: no cover
        HAS_NUMBA = None
    version = getattr(pl, "__version__", "?")
    n = cfg.peer_positions
    rows = []
    curves = []
    for stem in PEER_SCENES:
        mech, structure = _load(stem)
        angles = _cycle(mech, n)
        step = 360.0 / n

        def fresh():
            return _pylinkage_model(pl, mech, stem, float(angles[0]), step)

        def best_pyl(method: str) -> tuple[float, list]:
            warm, _ = fresh()   # numba compiles (or loads) its kernels on their first call: not timed
            list(getattr(warm, method)(2))
            best, out = math.inf, None
            for _ in range(max(cfg.repeat, 1)):
                linkage, _ = fresh()
                t, out = once(lambda: list(getattr(linkage, method)(n)))
                best = min(best, t)
            return best, out

        t_pyl_pos, steps = best_pyl("step")
        t_pyl_all, derived = best_pyl("step_with_derivatives")
        t_plans_pos = best_time(lambda: analyse(mech, structure, angles, order=0), repeat=cfg.repeat)
        t_plans_all = best_time(lambda: analyse(mech, structure, angles, order=2), repeat=cfg.repeat)
        motion = analyse(mech, structure, angles, order=2)
        _, index = fresh()
        dr = dr_all = dv = da = 0.0
        worst_curve = np.zeros(n)
        for p, k in index.items():
            pos = np.array([s[k] for s in steps], dtype=float)
            pos2 = np.array([s[0][k] for s in derived], dtype=float)
            vel = np.array([s[1][k] for s in derived], dtype=float)
            acc = np.array([s[2][k] for s in derived], dtype=float)
            gap = np.linalg.norm(pos - motion.position(p), axis=1)
            worst_curve = np.maximum(worst_curve, gap)
            dr = max(dr, float(np.max(gap)))
            dr_all = max(dr_all, _max_norm(pos2, motion.position(p)))
            dv = max(dv, _max_norm(vel, motion.velocity(p)))
            da = max(da, _max_norm(acc, motion.acceleration(p)))
        compared = ", ".join(index)
        rows.append((stem, "positions", n, t_plans_pos * 1e3, t_pyl_pos * 1e3, t_pyl_pos / t_plans_pos, dr,
                     None, None, compared))
        rows.append((stem, "pos + vel + acc", n, t_plans_all * 1e3, t_pyl_all * 1e3, t_pyl_all / t_plans_all,
                     dr_all, dv, da, compared))
        curves.append(Series(f"{stem} (points {compared})", tuple(float(a - angles[0]) for a in angles),
                             tuple(worst_curve)))
    cols = (Column("scene", "scene", "s"), Column("what", "what", "s"), Column("positions", "N", "d"),
            Column("plans_ms", "plans ms", ".2f"), Column("pylinkage_ms", "pylinkage ms", ".2f"),
            Column("speed_ratio", "pylinkage/plans time", ".2f"), Column("max_dr_m", "max |Δr| (m)", ".1e"),
            Column("max_dv", "max |Δv| (m/s)", ".1e"), Column("max_da", "max |Δa| (m/s²)", ".1e"),
            Column("points", "points", "s"))
    notes = [f"pylinkage {version} (numba {'installed' if HAS_NUMBA else 'not installed: its pure-Python path'}): "
             "Linkage.step() for positions, step_with_derivatives() with set_input_velocity(ω, ε) for velocities "
             "and accelerations; plans: analyse(order=0) and analyse(order=2).",
             f"Same dimensions (read from the plans model), same {n} crank angles from the sketch's "
             f"({360 / n:g}° steps), same assembly branch (pylinkage's dyad starts at the sketch's joint); model "
             f"construction not timed; best of {cfg.repeat}.",
             "pylinkage/plans time > 1: plans is faster. plans walks the drive from the sketch in 1° steps "
             "(branch continuation) whatever N, which is most of its time at small N.",
             "|Δr| grows along the turn because pylinkage turns its crank step by step (atan2 of the current "
             "position + Δφ), so its crank pin A itself drifts by rounding; plans places every angle directly."]
    summary = {"pylinkage": version, "numba": HAS_NUMBA,
               "max_position_difference_m": max(r[6] for r in rows),
               "plans_faster": {f"{r[0]} {r[1]}": r[5] > 1 for r in rows}}
    charts = [Chart("peer-difference", "pylinkage vs plans: position difference over the turn",
                    "crank turned from the sketch (°)", "largest |Δr| of the compared points (m)", tuple(curves),
                    log_y=True)]
    return Section("peer_comparison", title, cols, rows, notes, summary, charts)


# ---------------------------------------------------------------------------------------------
# 6. pylinkage's numba path
#
# pylinkage (≥ 1.3) picks its numba path at import: pylinkage._numba_compat binds ``njit`` to
# numba's when numba can be imported and to a no-op otherwise, so the same solver kernels run
# compiled or as plain Python. Linkage.step_fast_with_kinematics(n) runs n crank steps through
# those kernels at once (positions, velocities, accelerations as (n, components, 2) arrays) —
# the documented fast path (README: "step_fast() … without numba, the same code runs in pure
# Python/NumPy"). Both paths are measured in one run: the numba one here, the pure-Python one
# in a child Python process that hides numba before it imports pylinkage.

NUMBA_SCENE = "crank_slider_central"
#: Runs of pylinkage's pure-Python path per size (one run at 100 000 positions takes seconds).
PURE_PYTHON_REPEAT = 3
#: Seconds the child process measuring the pure-Python path may take.
PURE_PYTHON_TIMEOUT = 900.0

_PURE_PYTHON_CHILD = """
import importlib.abc, json, sys

class _HideNumba(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name == "numba" or name.startswith("numba."):
            raise ImportError("numba hidden by plans bench: pylinkage's pure-Python path")
        return None

_hide = _HideNumba()
sys.meta_path.insert(0, _hide)
import pylinkage
try:
    from pylinkage._numba_compat import HAS_NUMBA
except ImportError:
    HAS_NUMBA = None
sys.meta_path.remove(_hide)
from plans.bench.sections import _pure_python_child
_pure_python_child(json.loads(sys.stdin.read()), HAS_NUMBA)
"""


def _pure_python_child(args: dict, has_numba: bool | None) -> None:
    """In the child process (numba hidden): time pylinkage's step_fast_with_kinematics at each
    size, save the results of the last run as .npz in ``args["out"]``, print the times as JSON."""
    import json
    import pylinkage as pl

    mech, _ = _load(args["stem"])
    seconds = {}
    for n in args["positions"]:
        angles = _cycle(mech, n)
        warm, _ = _pylinkage_model(pl, mech, args["stem"], float(angles[0]), 360.0 / n)
        warm.compile()
        warm.step_fast_with_kinematics(min(n, 8))   # lazy imports, first-call costs
        best, out = math.inf, None
        for _ in range(max(1, args["repeat"])):
            linkage, _ = _pylinkage_model(pl, mech, args["stem"], float(angles[0]), 360.0 / n)
            linkage.compile()
            t, out = once(lambda: linkage.step_fast_with_kinematics(n))
            best = min(best, t)
        np.savez(Path(args["out"]) / f"pure-{n}.npz", pos=out[0], vel=out[1], acc=out[2])
        seconds[str(n)] = best
    print(json.dumps({"has_numba": has_numba, "seconds": seconds}))


def _pylinkage_pure_python(stem: str, sizes: tuple[int, ...], repeat: int, tmp: str) -> tuple[dict | None, str]:
    """Run :func:`_pure_python_child` in a new Python process; (its report, "") or (None, why not)."""
    import json
    import subprocess
    import sys

    args = {"stem": stem, "positions": list(sizes), "repeat": repeat, "out": tmp}
    try:   # -P: the current directory stays off sys.path (a stray timeit.py there would break numba)
        proc = subprocess.run([sys.executable, "-P", "-c", _PURE_PYTHON_CHILD], input=json.dumps(args),
                              capture_output=True, text=True, timeout=PURE_PYTHON_TIMEOUT)
    except (OSError, subprocess.TimeoutExpired) as exc:
        return None, f"pure-Python run failed: {exc}"
    lines = proc.stdout.strip().splitlines()
    if proc.returncode != 0 or not lines:
        why = (proc.stderr.strip().splitlines() or [f"exit status {proc.returncode}"])[-1]
        return None, f"pure-Python run failed: {why}"
    report = json.loads(lines[-1])
    if report["has_numba"]:
        return None, "pure-Python run failed: numba could not be hidden from pylinkage"
    return report, ""


def _relative_differences(index: dict[str, int], pos: np.ndarray, vel: np.ndarray, acc: np.ndarray, motion,
                          r: float, omega: float) -> tuple[float, float, float]:
    """Largest |Δr|/r, |Δv|/(ω·r), |Δa|/(ω²·r) over the compared points (r: the crank)."""
    v_scale = abs(omega) * r or r
    a_scale = omega * omega * r or r
    dr = max(_max_norm(pos[:, k], motion.position(p)) for p, k in index.items()) / r
    dv = max(_max_norm(vel[:, k], motion.velocity(p)) for p, k in index.items()) / v_scale
    da = max(_max_norm(acc[:, k], motion.acceleration(p)) for p, k in index.items()) / a_scale
    return dr, dv, da


def numba_comparison(cfg: Config) -> Section:
    """The crank-slider's full kinematics (positions, velocities, accelerations over a turn) at
    cfg.numba_positions positions: plans against pylinkage's numba path and its pure-Python
    path in the same run, time per position and agreement relative to the crank."""
    title = "6. Crank-slider full kinematics: plans vs pylinkage's numba and pure-Python paths"
    try:
        import pylinkage as pl
    except ImportError:
        pl = None
    has_numba = False
    version = numba_version = None
    if pl is not None:
        version = getattr(pl, "__version__", "?")
        try:
            from pylinkage._numba_compat import HAS_NUMBA as has_numba   # pylinkage's own flag
        except ImportError:   # pragma: no cover - another pylinkage layout
            has_numba = False
        if has_numba:
            import numba
            numba_version = numba.__version__
    mech, structure = _load(NUMBA_SCENE)
    d = mech.drive
    r = _local_distance(mech, d.link, d.pivot, d.tip)
    sizes = cfg.numba_positions
    pure, pure_why = None, "pylinkage not installed"
    rows = []
    with tempfile.TemporaryDirectory(prefix="plans-bench-") as tmp:
        if pl is not None:
            pure, pure_why = _pylinkage_pure_python(NUMBA_SCENE, sizes, min(max(cfg.repeat, 1), PURE_PYTHON_REPEAT),
                                                    tmp)
        if has_numba:   # compile (or load numba's cache) once, outside every timing
            warm, _ = _pylinkage_model(pl, mech, NUMBA_SCENE, d.sketch_value, 1.0)
            warm.compile()
            warm.step_fast_with_kinematics(8)
        for n in sizes:
            angles = _cycle(mech, n)
            analyse(mech, structure, angles, order=2)
            t_plans = best_time(lambda: analyse(mech, structure, angles, order=2), repeat=cfg.repeat)
            motion = analyse(mech, structure, angles, order=2)
            t_numba = speedup = None
            dr = dv = da = d_pure = t_pure = speedup_pure = None
            verdict = None
            if has_numba:
                linkage, index = _pylinkage_model(pl, mech, NUMBA_SCENE, float(angles[0]), 360.0 / n)
                linkage.compile()
                dr, dv, da = _relative_differences(index, *linkage.step_fast_with_kinematics(n), motion, r, d.speed)
                # every further call turns the crank through one more turn: the same work again
                t_numba = best_time(lambda: linkage.step_fast_with_kinematics(n), repeat=cfg.repeat)
                speedup = t_numba / t_plans
                verdict = "met" if speedup >= NUMBA_TARGET and max(dr, dv, da) <= AGREEMENT_TARGET else \
                    (f"short ×{NUMBA_TARGET / speedup:.2f}" if speedup < NUMBA_TARGET else "disagrees")
            if pure is not None:
                _, index = _pylinkage_model(pl, mech, NUMBA_SCENE, float(angles[0]), 360.0 / n)
                t_pure = pure["seconds"][str(n)]
                speedup_pure = t_pure / t_plans
                with np.load(Path(tmp) / f"pure-{n}.npz") as f:
                    d_pure = max(_relative_differences(index, f["pos"], f["vel"], f["acc"], motion, r, d.speed))
            if pl is None:
                status = "pylinkage not installed"
            elif not has_numba:
                status = "numba not installed" + ("" if pure else f"; {pure_why}")
            else:
                status = "numba + pure Python" if pure else f"numba only; {pure_why}"
            us = 1e6 / n
            rows.append((n, t_plans * us, None if t_numba is None else t_numba * us,
                         None if t_pure is None else t_pure * us, speedup, verdict, speedup_pure, dr, dv, da, d_pure,
                         status))
    cols = (Column("positions", "N", ",d"), Column("plans_us_per_position", "plans µs/pos", ".3f"),
            Column("numba_us_per_position", "numba µs/pos", ".3f"),
            Column("pure_python_us_per_position", "pure-Python µs/pos", ".2f"),
            Column("numba_over_plans", "numba/plans time", ".2f"),
            Column("target", f"≥{NUMBA_TARGET:g}×, ≤{AGREEMENT_TARGET:.0e}", "s"),
            Column("pure_python_over_plans", "pure-Py/plans time", ".1f"),
            Column("numba_dr_rel", "|Δr|/r", ".1e"), Column("numba_dv_rel", "|Δv|/ωr", ".1e"),
            Column("numba_da_rel", "|Δa|/ω²r", ".1e"), Column("pure_python_max_rel", "pure-Py max Δ", ".1e"),
            Column("pylinkage", "pylinkage", "s"))
    notes = [f"{NUMBA_SCENE} (crank r = {r:g} m, ω = {d.speed:g} rad/s), N crank angles evenly over one turn from "
             "the sketch. Full kinematics: positions, velocities and accelerations of the points. plans: "
             f"analyse(order=2), every point (O, A, B, C), one call, best of {cfg.repeat} after a warm-up call.",
             "pylinkage " + (f"{version}: Linkage.step_fast_with_kinematics(N) (set_input_velocity(ω, ε)), "
                             "positions, velocities and accelerations of A and B. numba path"
                             + (f" (numba {numba_version}): kernels compiled before timing, model built and "
                                f"compile()d outside the timing, best of {cfg.repeat}; " if has_numba else
                                ": numba not installed; ")
                             + f"pure-Python path: the same call in a child Python process with numba hidden "
                             f"(pylinkage then binds njit to a no-op), best of "
                             f"{min(max(cfg.repeat, 1), PURE_PYTHON_REPEAT)} at every N."
                             if pl is not None else f"not installed: its columns are empty; {INSTALL_HINT}"),
             "numba/plans time > 1: plans is faster (target ≥ "
             f"{NUMBA_TARGET:g}× and agreement ≤ {AGREEMENT_TARGET:.0e}). |Δr|/r, |Δv|/ωr, |Δa|/ω²r: largest "
             "difference from pylinkage's numba results over A and B and the turn, relative to the crank; "
             "pure-Py max Δ: the largest of the three against its pure-Python results."]
    summary = {"scene": NUMBA_SCENE, "pylinkage": version, "numba": numba_version, "target": NUMBA_TARGET,
               "agreement_target": AGREEMENT_TARGET,
               "met": {str(row[0]): row[5] == "met" for row in rows} if has_numba else None}
    xs = tuple(float(n) for n in sizes)
    series = [Series("plans analyse(order=2)", xs, tuple(row[1] for row in rows))]
    if has_numba:
        series.append(Series("pylinkage numba path", xs, tuple(row[2] for row in rows)))
    if pure is not None:
        series.append(Series("pylinkage pure-Python path", xs, tuple(row[3] for row in rows)))
    charts = [Chart("numba-cost", "Crank-slider full kinematics: time per position", "positions (N)",
                    "µs per position", tuple(series), log_x=True, log_y=True,
                    note="positions + velocities + accelerations over one turn, one call")]
    return Section("numba_comparison", title, cols, rows, notes, summary, charts)


# ---------------------------------------------------------------------------------------------
# 7. class III / IV cost per position

CLASS_SCENES = ("crank_slider_central", "class3_six_link", "class4_six_link")


def _timed(fn: Callable[[], Any], repeat: int) -> float:
    """Seconds per call after a warm-up call: short calls looped (best_time), slow ones repeated
    within TIMING_BUDGET."""
    first, _ = once(fn)
    if first < 0.05:
        return best_time(fn, repeat=repeat)
    return _best_of(fn, repeat)[0]


def class_cost(cfg: Config) -> Section:
    """Full analysis (order 2) time per position of a class III and a class IV example against
    the crank-slider, at cfg.class_positions (72) and cfg.class_large_positions a turn."""
    small, large = cfg.class_positions, cfg.class_large_positions
    measured = []
    for stem in CLASS_SCENES:
        mech, structure = _load(stem)
        per = []
        for n in (small, large):
            angles = _cycle(mech, n)
            per.append(_timed(lambda: analyse(mech, structure, angles, order=2), cfg.repeat) / n)
        groups = " ".join(str(g.name) for g in structure.groups)
        measured.append((stem, structure.klass, groups, per))
    ref = measured[0][3]
    rows = []
    for stem, klass, groups, per in measured:
        ratio = per[0] / ref[0]
        verdict = "reference" if stem == CLASS_SCENES[0] else \
            ("met" if ratio <= CLASS_COST_TARGET else f"over ×{ratio / CLASS_COST_TARGET:.1f}")
        rows.append((stem, klass, groups, small, per[0] * 1e6, ratio, verdict, large, per[1] * 1e6, per[1] / ref[1]))
    cols = (Column("scene", "scene", "s"), Column("class", "class", "d"), Column("groups", "groups", "s"),
            Column("positions", "N", "d"), Column("us_per_position", "µs/pos", ".1f"),
            Column("ratio", "× crank-slider", ".1f"), Column("target", f"≤{CLASS_COST_TARGET:g}×", "s"),
            Column("large_positions", "N'", "d"), Column("large_us_per_position", "µs/pos at N'", ".2f"),
            Column("large_ratio", "× crank-slider at N'", ".1f"))
    notes = ["plans.kinematics.analyse(mech, structure, angles, order=2): positions, velocities and accelerations "
             f"of every point at N = {small} crank angles evenly over one turn from the sketch (one call), per "
             f"position; × crank-slider: against {CLASS_SCENES[0]} at the same N "
             f"(target ≤ {CLASS_COST_TARGET:g}×).",
             f"N' = {large}: the same at more positions a turn, to show what is fixed cost per call. Warm-up call "
             f"first; best of {cfg.repeat} (calls over {TIMING_BUDGET:g} s: fewer, within that budget)."]
    summary = {"target": CLASS_COST_TARGET, "positions": small,
               "ratios": {row[0]: row[5] for row in rows[1:]},
               "met": all(row[5] <= CLASS_COST_TARGET for row in rows[1:])}
    xs = (float(small), float(large))
    charts = [Chart("class-cost", "Full analysis (order 2): time per position by group class",
                    "positions per turn", "µs per position",
                    tuple(Series(f"{row[0]} (class {row[1]})", xs, (row[4], row[8])) for row in rows),
                    log_x=True, log_y=True)]
    return Section("class_cost", f"7. Class III / IV cost per position (vs crank-slider, target ≤ "
                   f"{CLASS_COST_TARGET:g}× at {small} a turn)", cols, rows, notes, summary, charts)


#: Every section in the order ``plans bench`` runs and prints them.
SECTIONS: tuple[Callable[[Config], Section], ...] = (drawing_precision, solver_tolerance, cycle_resolution,
                                                     throughput, render_rate, peer_comparison,
                                                     numba_comparison, class_cost)

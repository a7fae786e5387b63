"""Section 2 of ``plans bench``: Newton tolerance → iterations, time per position and error
against a reference solution, for every iterative position solver of :data:`SOLVER_CASES`.

The iterative position solvers under test, each on one scene, continued along a turn from
the sketch (every position starts from the solver's own previous one), at tolerances
1e-2 … 1e-14, against a reference solution of the same positions. To measure another solver,
add a SolverCase to SOLVER_CASES: its ``prepare(mech, structure, angles)`` returns
(solve, exact, reference), where solve(tol) → (points (N, P, 2) in metres, Newton iterations
(N,), converged (N,) booleans), exact is the reference points (N, P, 2) and reference says
where they come from.

Knows the kinematics (``plans.kinematics.state.LinkState``, ``plans.kinematics.generic``);
must not import another section module, :mod:`plans.bench` itself or the command line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ...errors import PlansError
from ...kinematics import analyse
from ...kinematics.state import LinkState
from ...model import Mechanism
from ...structure import Structure
from ..chart import Chart, Series
from .common import Column, Config, Section, best_of, cycle_angles, load_example, local_distance, max_norm

__all__ = ["MAX_ITERATIONS", "Solve", "SolverCase", "SOLVER_CASES", "solver_tolerance"]

#: Newton steps allowed per position before it counts as not converged (the bench's own Newton).
MAX_ITERATIONS = 50

Solve = Callable[[float], tuple[np.ndarray, np.ndarray, np.ndarray]]


@dataclass(frozen=True)
class SolverCase:
    """An iterative position solver on one scene (see the module docstring)."""

    label: str
    scene: str
    prepare: Callable[[Mechanism, Structure, np.ndarray], tuple[Solve, np.ndarray, str]]


def _generic_newton(mech: Mechanism, structure: Structure, angles: np.ndarray) -> tuple[Solve, np.ndarray, str]:
    """plans.kinematics.generic: Newton on the pair equations of the scene's class III/IV group,
    one position at a time from the previous one (the sketch, where every pose is the identity),
    stopping at |Φ| ≤ tol·size without the polishing step plans adds."""
    from ...kinematics.generic import GroupEquations

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
    r = local_distance(mech, d.link, d.pivot, d.tip)
    cx, cy = (float(c) for c in mech.sketch["C"])
    l2 = local_distance(mech, "2", "A", "B")
    l3 = local_distance(mech, "3", "C", "B")
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



def solver_tolerance(cfg: Config) -> Section:
    """Tolerance 1e-2 … 1e-14 → Newton iterations, time per position and error against a
    reference, for every case of SOLVER_CASES."""
    rows = []
    notes = []
    error_series, iteration_series = [], []
    n = cfg.solver_positions
    for case in SOLVER_CASES:
        try:
            mech, structure = load_example(case.scene)
            angles = cycle_angles(mech, n)
            solve, exact, reference = case.prepare(mech, structure, angles)
            t_ref, _ = best_of(lambda: analyse(mech, structure, angles, order=0), cfg.repeat)
            results = []
            for tol in cfg.tolerances:
                t, (pts, its, ok) = best_of(lambda: solve(tol), cfg.repeat)
                results.append((tol, pts, its, ok, t))
        except (ImportError, AttributeError, TypeError, StopIteration, FileNotFoundError, PlansError) as exc:
            # the solver or its scene is not (yet) in this version: say so, measure the others
            notes.append(f"{case.label} on {case.scene}: not measured ({type(exc).__name__}: {exc})")
            continue
        xs = []
        for tol, pts, its, ok, t in results:
            err = max_norm(pts, exact)
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
                 "solver, edit SOLVER_CASES in plans/bench/sections/solver.py."]
    xs_all = tuple(cfg.tolerances)
    charts = [Chart("solver-tolerance", "Solver tolerance: error against the reference", "tolerance",
                    "max error / size", tuple(error_series) + (Series("tolerance (reference line)", xs_all, xs_all),),
                    log_x=True, log_y=True),
              Chart("solver-iterations", "Solver tolerance: Newton iterations per position", "tolerance",
                    "mean iterations", tuple(iteration_series), log_x=True, y_from_zero=True)]
    summary = {"solvers": [c.label for c in SOLVER_CASES], "positions": n}
    return Section("solver_tolerance", "2. Solver tolerance (iterative position solves)", cols, rows, notes,
                   summary, charts)


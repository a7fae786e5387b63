"""Section 6 of ``plans bench``: the crank-slider's full kinematics, plans against pylinkage's
numba path and its pure-Python path (measured in a child Python process with numba hidden).

pylinkage (≥ 1.3) picks its numba path at import: pylinkage._numba_compat binds ``njit`` to
numba's when numba can be imported and to a no-op otherwise, so the same solver kernels run
compiled or as plain Python. Linkage.step_fast_with_kinematics(n) runs n crank steps through
those kernels at once (positions, velocities, accelerations as (n, components, 2) arrays) —
the documented fast path (README: "step_fast() … without numba, the same code runs in pure
Python/NumPy"). Both paths are measured in one run: the numba one here, the pure-Python one
in a child Python process that hides numba before it imports pylinkage.

Knows the kinematics and :mod:`.pylinkage_model`; must not import another section module,
:mod:`plans.bench` itself or the command line.
"""

from __future__ import annotations

import math
import tempfile
from pathlib import Path

import numpy as np

from ...kinematics import analyse
from ..chart import Chart, Series
from ..timing import best_time, once
from .common import Column, Config, Section, cycle_angles, load_example, local_distance, max_norm
from .pylinkage_model import INSTALL_HINT, pylinkage_model

__all__ = ["NUMBA_TARGET", "AGREEMENT_TARGET", "NUMBA_SCENE", "PURE_PYTHON_REPEAT", "PURE_PYTHON_TIMEOUT",
           "numba_comparison"]

#: plans' full kinematics of the crank-slider should be at least this many times faster than
#: pylinkage's numba path …
NUMBA_TARGET = 3.0
#: … and agree with it to this, relative to the crank (|Δr|/r, |Δv|/ωr, |Δa|/ω²r).
AGREEMENT_TARGET = 1e-9

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
from plans.bench.sections.numba_path import _pure_python_child
_pure_python_child(json.loads(sys.stdin.read()), HAS_NUMBA)
"""


def _pure_python_child(args: dict, has_numba: bool | None) -> None:
    """In the child process (numba hidden): time pylinkage's step_fast_with_kinematics at each
    size, save the results of the last run as .npz in ``args["out"]``, print the times as JSON."""
    import json
    import pylinkage as pl

    mech, _ = load_example(args["stem"])
    seconds = {}
    for n in args["positions"]:
        angles = cycle_angles(mech, n)
        warm, _ = pylinkage_model(pl, mech, args["stem"], float(angles[0]), 360.0 / n)
        warm.compile()
        warm.step_fast_with_kinematics(min(n, 8))   # lazy imports, first-call costs
        best, out = math.inf, None
        for _ in range(max(1, args["repeat"])):
            linkage, _ = pylinkage_model(pl, mech, args["stem"], float(angles[0]), 360.0 / n)
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


def _pure_repeat(cfg: Config) -> int:
    """Runs of the pure-Python path per size: cfg.pure_python_repeat, at most cfg.repeat and
    PURE_PYTHON_REPEAT."""
    return max(1, min(cfg.repeat, cfg.pure_python_repeat, PURE_PYTHON_REPEAT))


def _relative_differences(index: dict[str, int], pos: np.ndarray, vel: np.ndarray, acc: np.ndarray, motion,
                          r: float, omega: float) -> tuple[float, float, float]:
    """Largest |Δr|/r, |Δv|/(ω·r), |Δa|/(ω²·r) over the compared points (r: the crank)."""
    v_scale = abs(omega) * r or r
    a_scale = omega * omega * r or r
    dr = max(max_norm(pos[:, k], motion.position(p)) for p, k in index.items()) / r
    dv = max(max_norm(vel[:, k], motion.velocity(p)) for p, k in index.items()) / v_scale
    da = max(max_norm(acc[:, k], motion.acceleration(p)) for p, k in index.items()) / a_scale
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
    mech, structure = load_example(NUMBA_SCENE)
    d = mech.drive
    r = local_distance(mech, d.link, d.pivot, d.tip)
    sizes = cfg.numba_positions
    pure, pure_why = None, "pylinkage not installed"
    rows = []
    with tempfile.TemporaryDirectory(prefix="plans-bench-") as tmp:
        if pl is not None:
            pure, pure_why = _pylinkage_pure_python(NUMBA_SCENE, sizes, _pure_repeat(cfg), tmp)
        if has_numba:   # compile (or load numba's cache) once, outside every timing
            warm, _ = pylinkage_model(pl, mech, NUMBA_SCENE, d.sketch_value, 1.0)
            warm.compile()
            warm.step_fast_with_kinematics(8)
        for n in sizes:
            angles = cycle_angles(mech, n)
            analyse(mech, structure, angles, order=2)
            t_plans = best_time(lambda: analyse(mech, structure, angles, order=2), repeat=cfg.repeat)
            motion = analyse(mech, structure, angles, order=2)
            t_numba = speedup = None
            dr = dv = da = d_pure = t_pure = speedup_pure = None
            verdict = None
            if has_numba:
                linkage, index = pylinkage_model(pl, mech, NUMBA_SCENE, float(angles[0]), 360.0 / n)
                linkage.compile()
                dr, dv, da = _relative_differences(index, *linkage.step_fast_with_kinematics(n), motion, r, d.speed)
                # every further call turns the crank through one more turn: the same work again
                t_numba = best_time(lambda: linkage.step_fast_with_kinematics(n), repeat=cfg.repeat)
                speedup = t_numba / t_plans
                verdict = "met" if speedup >= NUMBA_TARGET and max(dr, dv, da) <= AGREEMENT_TARGET else \
                    (f"short ×{NUMBA_TARGET / speedup:.2f}" if speedup < NUMBA_TARGET else "disagrees")
            if pure is not None:
                _, index = pylinkage_model(pl, mech, NUMBA_SCENE, float(angles[0]), 360.0 / n)
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
                             f"{_pure_repeat(cfg)} at every N."
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

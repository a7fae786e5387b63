"""``plans bench``: what accuracy costs in time, measured in one run.

Sections (see :mod:`plans.bench.sections`): drawing precision, solver tolerance, cycle
resolution, throughput (vectorised vs per-angle loop, plans rendered per second), a
comparison with the peer library pylinkage (skipped when it is not installed), the
crank-slider's full kinematics against pylinkage's numba and pure-Python paths, the cost
per position of class III/IV groups against the crank-slider, and a crank that cannot turn
fully asked for angles on both sides of its sketch, a class set, ``plans check`` on hostile
files, the start-up's integrator tolerance and render time per link of growing fans. Each
section prints a table; :func:`run` also writes ``bench.json`` (every figure, the machine, the
run time) and one SVG chart per figure into the output folder.

:data:`DEFAULT` (``plans bench``) measures every section at sizes that finish in under two
minutes on two cores; :data:`FULL` (``--full``) every example, tolerance and repeat, and says
first how long it will take (:func:`estimate`); :data:`QUICK` (``--quick``) is for the tests.
"""

from __future__ import annotations

import json
import math
import os
import platform
import sys
import time
from pathlib import Path
from typing import Any, TextIO

import numpy as np

from .chart import Chart, Series, draw_chart
from .sections import (AGREEMENT_TARGET, CLASS_COST_TARGET, DEFAULT, FAN_FLAT_TARGET, FULL, NUMBA_TARGET, QUICK,
                       SECTIONS, THROUGHPUT_TARGET, Column, Config, Section)
from .sections.common import example_path
from .timing import once

__all__ = ["run", "machine", "estimate", "format_table", "Chart", "Series", "Column", "Config", "Section", "DEFAULT",
           "FULL", "QUICK"]

#: Seconds of :func:`_calibrate` on the reference machine of Config.reference_s.
CALIBRATION_REFERENCE_S = 0.4


def machine() -> dict[str, Any]:
    """Cores, CPU model (from /proc/cpuinfo where there is one), Python and NumPy versions."""
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as fh:
            cpu = next((line.split(":", 1)[1].strip() for line in fh if line.startswith("model name")), cpu)
    except OSError:
        pass
    return {"cores": os.cpu_count(), "cpu": cpu, "python": platform.python_version(),
            "implementation": platform.python_implementation(), "numpy": np.__version__,
            "platform": platform.platform(), "load_average": _load_average()}


def _load_average() -> float | None:
    """The 1-minute load average (other processes share the cores and slow every timing)."""
    try:
        return round(os.getloadavg()[0], 2)
    except (AttributeError, OSError):
        return None


def _calibrate() -> float:
    """Seconds of a fixed piece of work (the six-link press rendered, best of 3 after a warm-up
    render): how fast this machine runs ``plans`` now, load included."""
    from ..pipeline import render_scene   # the bench's own sections import it anyway

    path = example_path("six_link_press")
    render_scene(path)
    return min(once(lambda: render_scene(path))[0] for _ in range(3))


def estimate(cfg: Config) -> tuple[float, float] | None:
    """(estimated seconds of a run of ``cfg`` here and now, speed factor against the reference
    machine), or None when ``cfg`` has no reference time."""
    if cfg.reference_s is None:
        return None
    factor = _calibrate() / CALIBRATION_REFERENCE_S
    return cfg.reference_s * factor, factor


def _minutes(seconds: float) -> str:
    return f"{seconds:.0f} s" if seconds < 100 else f"{seconds / 60:.1f} min"


def _cell(value: Any, fmt: str) -> str:
    if value is None:
        return "—"
    if isinstance(value, str):
        return value
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    return format(value, fmt)


def format_table(columns: tuple[Column, ...], rows: list[tuple]) -> str:
    """An aligned text table: text columns to the left, numbers to the right."""
    cells = [[_cell(v, c.fmt) for c, v in zip(columns, row)] for row in rows]
    widths = [max([len(c.header)] + [len(r[k]) for r in cells]) for k, c in enumerate(columns)]
    text = [all(isinstance(row[k], str) or row[k] is None for row in rows) for k in range(len(columns))]

    def line(values: list[str]) -> str:
        return "  ".join(v.ljust(w) if t else v.rjust(w) for v, w, t in zip(values, widths, text)).rstrip()

    out = [line([c.header for c in columns]), line(["-" * w for w in widths])]
    out += [line(r) for r in cells]
    return "\n".join(out)


def _print_section(s: Section, out: TextIO) -> None:
    print(f"\n{s.title}", file=out)
    if s.skipped:
        print(f"  {s.skipped}", file=out)
        return
    print(format_table(s.columns, s.rows), file=out)
    for note in s.notes:
        print(f"  · {note}", file=out)


def _headlines(sections: dict[str, Section]) -> list[str]:
    lines = []
    t = sections.get("throughput")
    if t and not t.skipped:
        for r in t.rows:
            verdict = "met" if r[5] >= THROUGHPUT_TARGET else \
                f"NOT met, short by a factor {THROUGHPUT_TARGET / r[5]:.2f}"
            lines.append(f"throughput {r[0]}: vectorised {r[5]:.1f}× the per-angle loop (target ≥ "
                         f"{THROUGHPUT_TARGET:g}×: {verdict})")
    p = sections.get("peer_comparison")
    if p:
        if p.skipped:
            lines.append(f"peer comparison: {p.skipped}")
        else:
            for r in p.rows:
                faster = f"plans {r[5]:.2f}× faster" if r[5] >= 1 else f"pylinkage {1 / r[5]:.2f}× faster"
                lines.append(f"pylinkage {r[0]} ({r[1]}): {faster}; max |Δr| = {r[6]:.1e} m")
    nb = sections.get("numba_comparison")
    if nb and not nb.skipped:
        for r in nb.rows:
            if r[2] is None:
                lines.append(f"crank-slider full kinematics, {r[0]:,} positions: plans {r[1]:.3f} µs/position; "
                             f"pylinkage's numba path not measured ({r[11]})")
                continue
            agree = max(r[7], r[8], r[9])
            short = "" if r[4] >= NUMBA_TARGET else f", short by a factor {NUMBA_TARGET / r[4]:.2f}"
            faster = f"plans {r[4]:.2f}× faster than pylinkage's numba path" if r[4] >= 1 else \
                f"pylinkage's numba path {1 / r[4]:.2f}× faster than plans"
            lines.append(f"crank-slider full kinematics, {r[0]:,} positions: {faster} (target ≥ {NUMBA_TARGET:g}×: "
                         f"{'met' if not short else 'NOT met'}"
                         f"{short}), agreement {agree:.1e} of the crank (≤ {AGREEMENT_TARGET:.0e}: "
                         f"{'met' if agree <= AGREEMENT_TARGET else 'NOT met'})"
                         + (f"; plans {r[6]:.1f}× faster than its pure-Python path" if r[6] is not None else ""))
    c = sections.get("class_cost")
    if c and not c.skipped:
        for r in c.rows[1:]:
            verdict = "met" if r[5] <= CLASS_COST_TARGET else \
                f"NOT met, over by a factor {r[5] / CLASS_COST_TARGET:.1f}"
            lines.append(f"class {r[1]} ({r[0]}) at {r[3]} positions a turn: {r[5]:.1f}× the crank-slider per "
                         f"position (target ≤ {CLASS_COST_TARGET:g}×: {verdict})")
    w = sections.get("limited_walk")
    if w and not w.skipped:
        for r in w.rows:
            lines.append(f"a crank that cannot turn fully ({r[0]}), {r[1]} angles on both sides of its sketch: "
                         f"{r[3]:,.0f} positions/s in one call, {r[6]:.1f}× walking each angle alone "
                         f"(difference {r[7]:.0e})")
    f = sections.get("fan_render")
    if f and not f.skipped and f.rows:
        per = [r[5] for r in f.rows]
        lines.append(f"render time per link, fans of {f.rows[0][0]} … {f.rows[-1][0]} dyads ({f.rows[0][1]} … "
                     f"{f.rows[-1][1]} links): {min(per):.4f} … {max(per):.4f} CPU s per link, max/min "
                     f"{f.summary['max_over_min']:.2f} (target ≤ {FAN_FLAT_TARGET:g}×: {f.summary['verdict']})")
    return lines


def run(out_dir: str | Path = "output/bench", *, quick: bool = False, full: bool = False,
        out: TextIO | None = None, config: Config | None = None) -> dict[str, Any]:
    """Measure every section of ``config`` (else :data:`QUICK` with ``quick``, :data:`FULL` with
    ``full``, :data:`DEFAULT`), print the tables to ``out`` (standard output by default), write
    ``bench.json`` and the charts into ``out_dir``; return the JSON report. A run of FULL first
    prints how long it will take."""
    cfg = config or (QUICK if quick else FULL if full else DEFAULT)
    out = out or sys.stdout
    start = time.perf_counter()
    info = machine()
    print(f"plans bench ({cfg.name}): {info['cores']} cores, {info['cpu']}, Python {info['python']}, "
          f"NumPy {info['numpy']}, load average {info['load_average']}", file=out)
    expected = estimate(cfg) if cfg is FULL else None
    if expected:
        seconds, factor = expected
        print(f"this run will take about {_minutes(seconds)} ({_minutes(seconds / factor)} on the reference "
              f"machine, 2 cores, × {factor:.2f} for this machine's speed now); `plans bench` without --full "
              f"takes about {_minutes(factor * (DEFAULT.reference_s or 0.0))}", file=out)
    out.flush()
    sections: dict[str, Section] = {}
    timings: dict[str, float] = {}
    for fn in SECTIONS:
        t0 = time.perf_counter()
        s = fn(cfg)
        timings[s.key] = time.perf_counter() - t0
        sections[s.key] = s
        _print_section(s, out)
        out.flush()
    target = Path(out_dir)
    target.mkdir(parents=True, exist_ok=True)
    charts = [c for s in sections.values() for c in s.charts]
    for c in charts:
        (target / f"{c.name}.svg").write_text(draw_chart(c), encoding="utf-8", newline="\n")
    elapsed = time.perf_counter() - start
    headlines = _headlines(sections)
    report = {
        "config": cfg.name,
        "estimated_s": expected[0] if expected else None,
        "speed_factor": expected[1] if expected else None,
        "machine": info,
        "runtime_s": elapsed,
        "load_average_end": _load_average(),
        "section_runtime_s": timings,
        "headlines": headlines,
        "charts": [f"{c.name}.svg" for c in charts],
        "sections": {k: {"title": s.title, "skipped": s.skipped, "notes": s.notes, "summary": s.summary,
                         "columns": {c.key: c.header for c in s.columns}, "rows": s.records()}
                     for k, s in sections.items()},
    }
    (target / "bench.json").write_text(json.dumps(_finite(report), indent=1, ensure_ascii=False, default=_json, allow_nan=False) + "\n",
                                       encoding="utf-8", newline="\n")
    print("", file=out)
    for h in headlines:
        print(h, file=out)
    print(f"wrote {len(charts)} charts and bench.json to {target}/ in {elapsed:.1f} s (load average "
          f"{info['load_average']} at the start, {report['load_average_end']} at the end)", file=out)
    return report


def _finite(v: Any) -> Any:
    """``v`` with every NaN or infinity (a ratio over a zero time, say) written as null: bench.json
    is strict JSON."""
    if isinstance(v, (float, np.floating)):
        return float(v) if math.isfinite(v) else None
    if isinstance(v, dict):
        return {k: _finite(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_finite(x) for x in v]
    return v


def _json(v: Any) -> Any:
    if isinstance(v, np.integer):
        return int(v)
    if isinstance(v, np.floating):
        return float(v)
    if isinstance(v, np.bool_):
        return bool(v)
    raise TypeError(f"{type(v).__name__} is not JSON serialisable")

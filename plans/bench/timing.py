"""Timing with ``time.perf_counter``: short calls are looped until a run lasts long enough,
runs are repeated, and the best (least disturbed) run is kept."""

from __future__ import annotations

import gc
import time
from typing import Callable

__all__ = ["best_time", "once"]


def _run(fn: Callable[[], object], loops: int) -> float:
    enabled = gc.isenabled()
    gc.disable()   # as timeit does: a collection mid-run is noise, not the code's cost
    try:
        t0 = time.perf_counter()
        for _ in range(loops):
            fn()
        return time.perf_counter() - t0
    finally:
        if enabled:
            gc.enable()


def best_time(fn: Callable[[], object], *, repeat: int = 5, min_run: float = 0.02) -> float:
    """Seconds per call of ``fn``: the best of ``repeat`` runs, each looping ``fn`` until it lasts
    at least ``min_run`` seconds (one warm-up call first)."""
    first = _run(fn, 1)
    loops = 1 if first >= min_run else min(10_000, int(min_run / max(first, 1e-7)) + 1)
    return min(_run(fn, loops) / loops for _ in range(repeat))


def once(fn: Callable[[], object]) -> tuple[float, object]:
    """Seconds of one call of ``fn`` and its result."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        t0 = time.perf_counter()
        out = fn()
        return time.perf_counter() - t0, out
    finally:
        if enabled:
            gc.enable()

"""What every section of ``plans bench`` shares: the table (:class:`Column`, :class:`Section`),
what to measure (:class:`Config`, :data:`DEFAULT`, :data:`FULL`, :data:`QUICK`), the bundled
example scenes, the crank angles of a turn and the budgeted timing of slow calls.

Knows the model, the structure and the bench's timing and charts; must not import a section
module, :mod:`plans.bench` itself or the command line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any, Callable

import numpy as np

from ...model import Mechanism, build_mechanism
from ...scene import read_scene
from ...structure import Structure, analyse_structure
from ..chart import Chart
from ..timing import once

__all__ = ["Column", "Section", "Config", "DEFAULT", "FULL", "QUICK", "PRECISION_SCENES", "REFERENCE_S",
           "TIMING_BUDGET", "example_path", "all_examples",
           "load_example", "cycle_angles", "local_distance", "max_norm", "best_of"]


#: The examples of section 1 in the default run: one of each kind of pair and group (offset
#: slider, rotating guide with Coriolis, slotted link, two sliders, class IV, six-links), each
#: rendered in well under a second; ``--full`` renders every example.
PRECISION_SCENES = ("crank_slider_offset", "quick_return", "whitworth", "sine_mechanism", "elliptic_trammel",
                    "six_link_press", "stephenson_six_bar", "class4_six_link")

#: Seconds of the default and the full run on the reference machine (2 cores, AMD EPYC, other
#: work running beside it): ``plans bench --full`` scales the second by the measured speed.
REFERENCE_S = (65.0, 260.0)


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
    """What to measure: :data:`DEFAULT` for ``plans bench``, :data:`FULL` for ``plans bench --full``,
    :data:`QUICK` for tests."""

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
    limited_positions: int                     # a crank that cannot turn fully, angles on both sides of the sketch
    limited_alone: int                         # … each angle walked alone, timed on this many of them
    startup_tolerances: tuple[float, ...] = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)   # the start-up's DOP853 rtol
    startup_t_end: float = 15.0                # seconds of the start-up simulated
    startup_reference_rtol: float = 1e-13      # rtol of the reference start-up
    pure_python_repeat: int = 3                # runs of pylinkage's pure-Python path per size (best kept)
    handout_variants: int = 12                 # variants of the timed class set
    check_sizes: tuple[int, int] = (5_000, 50_000)   # vectors of the two hostile files of each kind
    fan_dyads: tuple[int, ...] = (10, 20, 40, 80, 160)   # dyads of the fans rendered (2n + 2 links)
    fan_repeat: int = 1                        # renders per fan (the best one is timed)
    reference_s: float | None = None           # the run's time on the reference machine (s), for the estimate


#: ``plans bench``: every section, at sizes and repeats that finish in under two minutes on two cores.
DEFAULT = Config("default", precision_scenes=PRECISION_SCENES, decimals=(1, 2, 3, 4, 5, 6),
                 tolerances=tuple(10.0 ** -k for k in range(2, 15, 2)), solver_positions=120,
                 resolutions=(12, 36, 360, 3600), throughput_positions=3600, loop_positions=72,
                 batch_sizes=(1, 10, 100, 1000, 3600), render_scenes=("crank_slider_central", "six_link_press"),
                 render_repeat=1, peer_positions=360, repeat=3, numba_positions=(3600, 100_000), class_positions=72,
                 class_large_positions=3600, limited_positions=360, limited_alone=12,
                 startup_tolerances=(1e-4, 1e-7, 1e-10), startup_t_end=4.0, startup_reference_rtol=1e-12,
                 pure_python_repeat=1, handout_variants=3, check_sizes=(2_000, 20_000), fan_repeat=2,
                 reference_s=REFERENCE_S[0])
#: ``plans bench --full``: every example, every tolerance, more repeats (several minutes).
FULL = Config("full", precision_scenes=(), decimals=(1, 2, 3, 4, 5, 6),
              tolerances=tuple(10.0 ** -k for k in range(2, 15)), solver_positions=360,
              resolutions=(8, 12, 24, 36, 72, 180, 360, 720, 3600), throughput_positions=3600, loop_positions=360,
              batch_sizes=(1, 10, 100, 360, 1000, 3600), render_scenes=("crank_slider_central", "six_link_press"),
              render_repeat=2, peer_positions=360, repeat=7, numba_positions=(3600, 100_000), class_positions=72,
              class_large_positions=3600, limited_positions=360, limited_alone=36, fan_repeat=3,
              reference_s=REFERENCE_S[1])
#: The tests: a few small cases of every section (seconds).
QUICK = Config("quick", precision_scenes=("crank_slider_central",), decimals=(2, 4), tolerances=(1e-3, 1e-8, 1e-12),
               solver_positions=36, resolutions=(12, 36, 360), throughput_positions=360, loop_positions=12,
               batch_sizes=(10, 360), render_scenes=("crank_slider_central",), render_repeat=1, peer_positions=36,
               repeat=1, numba_positions=(36, 360), class_positions=72, class_large_positions=360,
               limited_positions=36, limited_alone=6, startup_tolerances=(1e-5, 1e-9), startup_t_end=2.0,
               startup_reference_rtol=1e-12, pure_python_repeat=1, handout_variants=3, check_sizes=(2_000, 10_000),
               fan_dyads=(1, 2, 4))


def example_path(stem: str) -> Path:
    """The bundled example scene ``plans/examples/<stem>.toml``."""
    return Path(str(resources.files("plans.examples") / f"{stem}.toml"))


def all_examples() -> tuple[str, ...]:
    """The stems of every bundled example scene, sorted."""
    root = resources.files("plans.examples")
    return tuple(sorted(p.name[:-5] for p in root.iterdir() if p.name.endswith(".toml")))


def load_example(stem: str) -> tuple[Mechanism, Structure]:
    """A bundled example's mechanism and its structure (Assur groups)."""
    mech = build_mechanism(read_scene(example_path(stem)))
    return mech, analyse_structure(mech)


def cycle_angles(mech: Mechanism, n: int) -> np.ndarray:
    """``n`` crank angles (degrees) evenly over one turn, starting at the sketch."""
    return mech.drive.sketch_value + np.arange(n) * (360.0 / n)


def local_distance(mech: Mechanism, link: str, p: str, q: str) -> float:
    """Distance (m) between points ``p`` and ``q`` of ``link``: a link length."""
    loc = mech.links[link].local
    return float(np.linalg.norm(loc[p] - loc[q]))


def max_norm(a: np.ndarray, b: np.ndarray) -> float:
    """Largest distance between matching vectors of ``a`` and ``b`` (last axis: x, y)."""
    return float(np.max(np.linalg.norm(np.asarray(a, float) - np.asarray(b, float), axis=-1)))


#: Seconds a section may spend repeating one timing (a slow solver is timed fewer times).
TIMING_BUDGET = 0.5


def best_of(fn: Callable[[], Any], repeat: int) -> tuple[float, Any]:
    """Best time of up to ``repeat`` calls (fewer when a call is slow) and the last result."""
    best, out, spent = math.inf, None, 0.0
    for _ in range(max(repeat, 1)):
        t, out = once(fn)
        best, spent = min(best, t), spent + t
        if spent > TIMING_BUDGET:
            break
    return best, out

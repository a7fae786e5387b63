"""The measurements of ``plans bench``, one module per section.

Each section function takes a :class:`Config` and returns a :class:`Section`: a table (rows
of raw numbers with a header and a format per column), notes that say how to read it,
headline figures (``summary``) and charts. Nothing here prints or writes files.

1. :func:`drawing_precision` (:mod:`.precision`) — SVG coordinate decimals → error of the drawn vectors, size, time
2. :func:`solver_tolerance` (:mod:`.solver`) — Newton tolerance → iterations, time, error vs a reference solution
3. :func:`cycle_resolution` (:mod:`.resolution`) — positions per revolution → error of graphical differentiation
4. :func:`throughput` / :func:`render_rate` (:mod:`.rates`) — vectorised analysis vs a per-angle loop; sheets/s
5. :func:`peer_comparison` (:mod:`.peer`) — the same cycles solved by pylinkage and by plans
6. :func:`numba_comparison` (:mod:`.numba_path`) — crank-slider full kinematics: plans vs pylinkage's numba and
   pure-Python paths
7. :func:`class_cost` (:mod:`.group_cost`) — class III and IV groups: cost per position against the crank-slider
8. :func:`limited_walk` (:mod:`.limited`) — a crank that cannot turn fully, angles on both sides of its sketch:
   one call against each angle walked alone
9. :func:`handout_time` (:mod:`.handout_time`) — a class set: time per variant, and for 999
10. :func:`check_scale` (:mod:`.check_scale`) — plans check on hostile files: linear in vectors and nesting depth
11. :func:`startup_tolerance` (:mod:`.startup_tolerance`) — the motor start-up's integrator tolerance → error, time
12. :func:`fan_render` (:mod:`.fan_time`) — fans of 10 … 160 four-bar dyads rendered: seconds per link

What several sections share lives in :mod:`.common` (table, configuration, scenes, timing) and
:mod:`.pylinkage_model` (a scene as a pylinkage Linkage). This package must not import
:mod:`plans.bench` itself or the command line.
"""

from __future__ import annotations

from typing import Callable

from .common import DEFAULT, FULL, QUICK, Column, Config, Section
from .fan_time import FAN_FLAT_TARGET, fan_render
from .group_cost import CLASS_COST_TARGET, class_cost
from .limited import limited_walk
from .check_scale import check_scale
from .handout_time import handout_time
from .numba_path import AGREEMENT_TARGET, NUMBA_TARGET, numba_comparison
from .peer import peer_comparison
from .precision import drawing_precision
from .rates import THROUGHPUT_TARGET, render_rate, throughput
from .resolution import cycle_resolution
from .solver import SOLVER_CASES, SolverCase, solver_tolerance
from .startup_tolerance import startup_tolerance

__all__ = ["handout_time", "check_scale", "Column", "Section", "Config", "DEFAULT", "FULL", "QUICK", "SECTIONS", "drawing_precision", "solver_tolerance",
           "cycle_resolution", "throughput", "render_rate", "peer_comparison", "THROUGHPUT_TARGET", "SolverCase",
           "SOLVER_CASES", "numba_comparison", "class_cost", "limited_walk", "NUMBA_TARGET", "AGREEMENT_TARGET",
           "CLASS_COST_TARGET", "startup_tolerance", "fan_render", "FAN_FLAT_TARGET"]

#: Every section in the order ``plans bench`` runs and prints them.
SECTIONS: tuple[Callable[[Config], Section], ...] = (drawing_precision, solver_tolerance, cycle_resolution,
                                                     throughput, render_rate, peer_comparison,
                                                     numba_comparison, class_cost, limited_walk, handout_time,
                                                     check_scale, startup_tolerance, fan_render)

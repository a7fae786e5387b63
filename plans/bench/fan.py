"""A fan of four-bar dyads on one crank pin: a scene whose size grows by one parameter.

The crank O-A (OA = 0.05 m) drives ``n`` dyads A-Bi-Ci, each a coupler A-Bi (0.25 m) and a
rocker Ci-Bi (0.2 m) pivoted on the frame at Ci, 0.24 m from O. Dyad i is the crank-rocker
four-bar O-A-Bi-Ci turned about O by 360°·i/n (Grashof: 0.05 + 0.25 <= 0.2 + 0.24, the crank
the shortest link), so every dyad assembles and the crank turns fully. The mechanism has
2n + 2 links (the frame, the crank, n couplers, n rockers): 99 dyads are 200 links.
Used by the render-scaling test and the benchmark.
"""

from __future__ import annotations

import contextlib
import importlib
import math
import time
import tomllib
from typing import Callable, Iterator

__all__ = ["fan_scene", "fan_links", "fan_report_entries", "stage_times", "STAGES", "CRANK", "COUPLER", "ROCKER",
           "FRAME_RADIUS", "ANGLE_DEG"]

CRANK = 0.05          #: OA, m
COUPLER = 0.25        #: ABi, m
ROCKER = 0.2          #: BiCi, m
FRAME_RADIUS = 0.24   #: OCi, m
ANGLE_DEG = 30.0      #: the crank's drawn angle, degrees
OMEGA = 10.0          #: ω1, rad/s


def fan_links(n_dyads: int) -> int:
    """Number of links of the fan of ``n_dyads`` dyads, the frame included."""
    return 2 * n_dyads + 2


def fan_report_entries(n_dyads: int) -> int:
    """Entries of the fan's JSON report at its one position: points, links, absolute centres
    and relative centres (one per pair of moving links: their number squared, by definition)."""
    moving = fan_links(n_dyads) - 1
    return (2 * n_dyads + 2) + fan_links(n_dyads) + moving + moving * (moving - 1) // 2


def _joint(a: tuple[float, float], c: tuple[float, float]) -> tuple[float, float]:
    """Bi on the circles (A, COUPLER) and (C, ROCKER), left of the line A → C (m)."""
    dx, dy = c[0] - a[0], c[1] - a[1]
    d = math.hypot(dx, dy)
    along = (COUPLER ** 2 - ROCKER ** 2 + d * d) / (2 * d)
    across = math.sqrt(COUPLER ** 2 - along ** 2)
    ux, uy = dx / d, dy / d
    return a[0] + along * ux - across * uy, a[1] + along * uy + across * ux


def fan_scene(n_dyads: int) -> str:
    """TOML text of the fan of ``n_dyads`` (>= 1) dyads, drawn at φ1 = 30° with the default sheets."""
    if n_dyads < 1:
        raise ValueError(f"n_dyads must be at least 1, got {n_dyads}")
    phi = math.radians(ANGLE_DEG)
    a = (CRANK * math.cos(phi), CRANK * math.sin(phi))
    points = ["O = [0.0, 0.0]", f"A = [{a[0]!r}, {a[1]!r}]"]
    frame = ["O"]
    links = ['1 = ["O", "A"]']
    lengths = [f"OA = {CRANK!r}"]
    for i in range(1, n_dyads + 1):
        turn = 2 * math.pi * (i - 1) / n_dyads
        c = (FRAME_RADIUS * math.cos(turn), FRAME_RADIUS * math.sin(turn))
        b = _joint(a, c)
        points += [f"B{i} = [{b[0]!r}, {b[1]!r}]", f"C{i} = [{c[0]!r}, {c[1]!r}]"]
        frame.append(f"C{i}")
        links += [f'{2 * i} = ["A", "B{i}"]', f'{2 * i + 1} = ["C{i}", "B{i}"]']
        lengths += [f'"A-B{i}" = {COUPLER!r}', f'"B{i}-C{i}" = {ROCKER!r}']
    frame_line = "0 = [" + ", ".join(f'"{p}"' for p in frame) + "]"
    return "\n".join([
        f'title = "Fan of {n_dyads} four-bar dyads"', "",
        "[points]", *points, "",
        "[links]", frame_line, *links, "",
        "[drive]", 'link = "1"', f"angle = {ANGLE_DEG!r}", f"omega = {OMEGA!r}", "epsilon = 0.0", "",
        "[lengths]", *lengths, "",
    ])


#: The render's stages timed by :func:`stage_times`: name → (module, attribute) of the function
#: (``Class.method`` for a method), as the render looks it up when it runs. Stages nest (the
#: plan sheets hold their labels and their pole detail).
STAGES: dict[str, tuple[str, str]] = {
    "structure": ("plans.pipeline.stages", "analyse_structure"),
    "motion": ("plans.pipeline", "solve_motion"),
    "scales": ("plans.pipeline", "scene_scales"),
    "scheme": ("plans.pipeline", "scheme_sheets"),
    "plans": ("plans.pipeline", "plan_sheets"),
    "pole detail": ("plans.drawing.svg", "pole_detail"),
    "labels": ("plans.drawing.canvas", "Canvas.place_labels"),
    "report": ("plans.pipeline", "report"),
    "json": ("plans.pipeline", "report_text"),
}


@contextlib.contextmanager
def _timed(totals: dict[str, float]) -> Iterator[None]:
    """Every function of :data:`STAGES` wrapped to add its CPU seconds (``time.process_time``)
    to ``totals`` while the block runs; the originals are put back after it."""
    undo: list[tuple[object, str, object]] = []

    def wrap(name: str, fn: Callable) -> Callable:
        def timed(*args, **kwargs):
            t0 = time.process_time()
            try:
                return fn(*args, **kwargs)
            finally:
                totals[name] = totals.get(name, 0.0) + time.process_time() - t0
        return timed

    try:
        for name, (module, attr) in STAGES.items():
            owner: object = importlib.import_module(module)
            *path, last = attr.split(".")
            for part in path:
                owner = getattr(owner, part)
            fn = owner.__dict__[last] if isinstance(owner, type) else getattr(owner, last)
            undo.append((owner, last, fn))
            setattr(owner, last, wrap(name, fn))
        yield
    finally:
        for owner, last, fn in reversed(undo):
            setattr(owner, last, fn)


def stage_times(n_dyads: int) -> dict[str, float]:
    """CPU seconds of each stage (:data:`STAGES`) and of the whole render (``"total"``) of the
    fan of ``n_dyads`` dyads, all in one run (``time.process_time``: time the other processes
    on the machine take is not counted)."""
    from ..pipeline import render
    from ..scene import parse_scene
    scene = parse_scene(tomllib.loads(fan_scene(n_dyads)))
    totals: dict[str, float] = {name: 0.0 for name in STAGES}
    with _timed(totals):
        t0 = time.process_time()
        render(scene, stem=f"fan{n_dyads}")
        totals["total"] = time.process_time() - t0
    return totals

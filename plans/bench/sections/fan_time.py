"""Section 12 of ``plans bench``: render time per link — fans of four-bar dyads on one crank pin
(:func:`plans.bench.fan.fan_scene`) of growing size rendered whole, seconds per link at each
size. Flat time per link is render time linear in the mechanism.

Knows the pipeline and the fan scene; must not import another section module,
:mod:`plans.bench` itself or the command line.
"""

from __future__ import annotations

import math
import tempfile
import time
from pathlib import Path

from ...pipeline import render_scene
from ..chart import Chart, Series
from ..fan import fan_links, fan_scene
from ..timing import once
from .common import Column, Config, Section

__all__ = ["FAN_FLAT_TARGET", "fan_render"]

#: The largest time per link over the smallest, from the smallest fan to the largest, should
#: be at most this (linear render time; issue 30).
FAN_FLAT_TARGET = 2.0


def _render(path: Path) -> tuple[float, float, int]:
    """(wall seconds, CPU seconds of this process, SVG sheets) of one render_scene of ``path``."""
    cpu = time.process_time()
    wall, rendered = once(lambda: render_scene(path))
    return wall, time.process_time() - cpu, sum(name.endswith(".svg") for name in rendered.files)


def fan_render(cfg: Config) -> Section:
    """Render fans of cfg.fan_dyads dyads (2n + 2 links) with render_scene; CPU seconds per link
    at each size, the time ratio between successive sizes and the spread of time per link."""
    measured = []
    with tempfile.TemporaryDirectory(prefix="plans-bench-") as tmp:
        warm = Path(tmp) / "fan-warm.toml"
        warm.write_text(fan_scene(2), encoding="utf-8")
        render_scene(warm)   # first-call costs (imports, caches): not timed
        for n in cfg.fan_dyads:
            path = Path(tmp) / f"fan{n}.toml"
            path.write_text(fan_scene(n), encoding="utf-8")
            wall = cpu = math.inf
            for _ in range(max(cfg.fan_repeat, 1)):
                w, c, sheets = _render(path)
                wall, cpu = min(wall, w), min(cpu, c)
            measured.append((n, fan_links(n), sheets, wall, cpu))
    low = min(t / links for _, links, _, _, t in measured)
    rows, prev = [], None
    for n, links, sheets, wall, t in measured:
        growth = None if prev is None else (t / prev[1]) / (links / prev[0])
        rows.append((n, links, sheets, wall, t, t / links, None if prev is None else t / prev[1], growth,
                     t / links / low))
        prev = (links, t)
    spread = max(r[8] for r in rows)
    cols = (Column("dyads", "dyads", "d"), Column("links", "links", "d"), Column("sheets", "sheets", "d"),
            Column("wall_s", "wall s", ".2f"), Column("seconds", "CPU s", ".2f"),
            Column("s_per_link", "CPU s per link", ".4f"),
            Column("time_ratio", "× previous time", ".2f"), Column("growth", "÷ link ratio", ".2f"),
            Column("per_link_over_min", "per link / min", ".2f"))
    notes = ["plans.bench.fan.fan_scene(n): a crank OA driving n four-bar dyads A-Bi-Ci on its pin A, turned "
             "about O by 360°/n each; 2n + 2 links (frame, crank, n couplers, n rockers). render_scene of the "
             "scene file: read, solve, scales, constructions (pole details and placed labels included), checks, "
             f"SVG and JSON text (files not written); best of {max(cfg.fan_repeat, 1)} per size after an untimed "
             "warm-up render. CPU s: this process's CPU seconds (time.process_time), which the other processes "
             "sharing the cores do not inflate; wall s beside it. Every ratio is of CPU seconds.",
             "× previous time: this size's time over the previous one's; ÷ link ratio: that over the ratio of "
             "links (1: linear, 2: quadratic). per link / min: time per link over the smallest time per link "
             f"(target ≤ {FAN_FLAT_TARGET:g}× over all sizes)."]
    verdict = "met" if spread <= FAN_FLAT_TARGET else f"NOT met, over by a factor {spread / FAN_FLAT_TARGET:.2f}"
    summary = {"s_per_link": {str(r[0]): r[5] for r in rows}, "max_over_min": spread,
               "target": FAN_FLAT_TARGET, "met": spread <= FAN_FLAT_TARGET, "verdict": verdict}
    xs = tuple(float(r[1]) for r in rows)
    charts = [Chart("fan-render", "Render time per link: fans of four-bar dyads", "links",
                    "s per link (render_scene)",
                    (Series("CPU s per link", xs, tuple(r[5] for r in rows)),
                     Series("wall s per link", xs, tuple(r[3] / r[1] for r in rows))),
                    log_x=True, y_from_zero=True, note="flat: render time linear in the mechanism")]
    return Section("fan_render", "12. Render time per link (fans of four-bar dyads on one crank pin)", cols, rows,
                   notes, summary, charts)

"""Section 9 of ``plans bench``: how long a class set takes — ``plans handout BASE --random N``
(draw, solve, and write every variant's sheets as SVG and PDF) timed at a few variants, per
variant, and the time it gives for the largest class sets.

Must not import another section module, :mod:`plans.bench` itself or the command line.
"""

from __future__ import annotations

import tempfile
import time

from ...handout import MAX_VARIANTS, random_variants, write_handout
from .common import Column, Config, Section, example_path

__all__ = ["handout_time", "HANDOUT_SCENE"]

#: The base scene of the class set timed.
HANDOUT_SCENE = "six_link_press"


def handout_time(cfg: Config) -> Section:
    """``plans handout`` with cfg.handout_variants random variants: seconds per variant drawing and
    solving, and writing SVG + PDF; minutes it gives for 999 and for the most variants."""
    n = cfg.handout_variants
    with tempfile.TemporaryDirectory() as out:
        t0 = time.perf_counter()
        h, drawn = random_variants(example_path(HANDOUT_SCENE), n, 1)
        t1 = time.perf_counter()
        write_handout(h, drawn, out)
        t2 = time.perf_counter()
    draw, write = (t1 - t0) / n, (t2 - t1) / n
    per = draw + write
    rows = [(HANDOUT_SCENE, n, draw, write, per, 999 * per / 60.0, MAX_VARIANTS * per / 60.0)]
    cols = (Column("scene", "base scene", "s"), Column("variants", "N", "d"),
            Column("draw_s", "draw + solve, s/variant", ".3f"), Column("write_s", "write SVG + PDF, s/variant", ".3f"),
            Column("per_variant_s", "s/variant", ".3f"), Column("minutes_999", "min for 999", ".1f"),
            Column("minutes_max", f"min for {MAX_VARIANTS}", ".1f"))
    notes = [f"plans handout {HANDOUT_SCENE}.toml --random {n} --seed 1, one process: drawing and solving the "
             "variants (random_variants), then writing each variant's sheets, assignment and key as SVG and PDF "
             "(write_handout); the time of a larger class set is this per-variant time times N (the variants are "
             "independent; the progress bar on a terminal shows the time left)."]
    return Section("handout_time", "9. A class set: time per variant", cols, rows, notes,
                   {"per_variant_s": per, "minutes_999": 999 * per / 60.0})

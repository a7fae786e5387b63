"""Section 1 of ``plans bench``: SVG coordinate decimals → error of the drawn vectors (read
back with :func:`plans.checking.check_svg`), file size and render time.

Knows the pipeline, drawing and checking; must not import another section module,
:mod:`plans.bench` itself or the command line.
"""

from __future__ import annotations

import math
import tempfile
from pathlib import Path

from ...checking import check_svg
from ...drawing import Style
from ...errors import PlansError
from ...pipeline import render_scene
from ..chart import Chart, Series
from ..timing import once
from .common import Column, Config, Section, all_examples, example_path

__all__ = ["LONG_MM", "drawing_precision"]

#: Relative errors of drawn vectors are taken over vectors drawn at least this long (mm):
#: a vector of a few tenths of a millimetre has a large relative error at any precision.
LONG_MM = 10.0


def drawing_precision(cfg: Config) -> Section:
    """Render the examples with SVG coordinates rounded to 1…6 decimals, read every plan back
    with :func:`plans.checking.check_svg` and compare each drawn vector × μ with its exact value."""
    stems = list(cfg.precision_scenes or all_examples())
    failed: list[str] = []
    render_scene(example_path("crank_slider_central"))   # first-call costs (imports, caches): not timed
    rows = []
    with tempfile.TemporaryDirectory(prefix="plans-bench-") as tmp:
        for d in cfg.decimals:
            style = Style(decimals=d)
            seconds = 0.0
            sheets = plan_sheets = size = vectors = 0
            worst_rel = worst_mm = worst_frac = 0.0
            for stem in list(stems):
                path = example_path(stem)
                best, rendered = math.inf, None
                try:
                    for _ in range(cfg.render_repeat):   # whole renders: some scenes take a good part of a second
                        t, rendered = once(lambda: render_scene(path, style))
                        best = min(best, t)
                except PlansError as exc:   # a bundled scene this version cannot render: say so, measure the rest
                    stems.remove(stem)
                    failed.append(f"{stem} at {d} decimals ({exc})")
                    continue
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
             f"sheets, scheme included; best of {cfg.render_repeat} per scene."
             + ("" if not cfg.precision_scenes else " `plans bench --full` measures every example.")]
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

"""Section 10 of ``plans bench``: ``plans check`` on hostile files — many vectors sharing one label,
and groups nested thousands deep — timed at two sizes in one run; the ratio of the times against
the ratio of the sizes shows the checker linear (it was quadratic in both).

Must not import another section module, :mod:`plans.bench` itself or the command line.
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

from ...checking import inspect_svg
from .common import Column, Config, Section

__all__ = ["check_scale", "hostile_svg", "CHECK_TARGET_S"]

#: A hostile file of 50,000 vectors must be checked within this, seconds (a smaller one scaled
#: linearly: within CHECK_TARGET_S · N / 50,000).
CHECK_TARGET_S = 10.0

_HEAD = ('<svg xmlns="http://www.w3.org/2000/svg" width="420mm" height="297mm" viewBox="0 0 420 297">'
         '<g data-mu="0.01" data-plan="velocity" id="p">')


def hostile_svg(kind: str, n: int) -> str:
    """``n`` tagged vectors of one plan, each from the pole to one image ``a`` (``shared``), or
    each in a group nested inside the previous one (``nested``, n deep)."""
    line = ('<line data-quantity="v:A{k}" data-value="0.1" data-direction="0.0" x1="10" y1="10" x2="20" y2="10" '
            'data-from="p" data-to="a{k}"/>')
    if kind == "shared":
        return _HEAD + "".join(line.format(k="") for _ in range(n)) + "</g></svg>"
    return _HEAD + "".join(f'<g id="g{k}">' + line.format(k=k) for k in range(n)) + "</g>" * n + "</g></svg>"


def check_scale(cfg: Config) -> Section:
    """plans check on the hostile files of :func:`hostile_svg` at the two sizes cfg.check_sizes:
    seconds each, their ratio (of CPU seconds) against the ratio of sizes."""
    small, large = cfg.check_sizes
    target = CHECK_TARGET_S * large / 50_000
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        warm = Path(tmp) / "warm.svg"
        warm.write_text(hostile_svg("nested", 10), encoding="utf-8")
        inspect_svg(warm)   # first-call costs: not timed
        for kind in ("shared", "nested"):
            times, cpu = [], []
            for n in (small, large):
                path = Path(tmp) / f"{kind}-{n}.svg"
                path.write_text(hostile_svg(kind, n), encoding="utf-8")
                c0, t0 = time.process_time(), time.perf_counter()
                report = inspect_svg(path)
                times.append(time.perf_counter() - t0)
                cpu.append(time.process_time() - c0)
                assert len(report.measurements) == n
            verdict = "met" if times[1] <= target else "over"
            rows.append((kind, small, times[0], large, times[1], cpu[1] / cpu[0], large / small, verdict))
    cols = (Column("file", "file", "s"), Column("n_small", "N", "d"), Column("s_small", "s", ".3f"),
            Column("n_large", "N'", "d"), Column("s_large", "s at N'", ".3f"),
            Column("time_ratio", "CPU time ratio", ".1f"), Column("size_ratio", "size ratio", ".0f"),
            Column("target", f"≤ {target:g} s at N'", "s"))
    notes = ["plans check (inspect_svg) on a plan of N vectors sharing one image label (shared), and of N vectors "
             "each in a <g> nested in the previous one (nested, N deep); one run each, both sizes in the same run, "
             "after an untimed warm-up. s: wall seconds; CPU time ratio: of this process's CPU seconds "
             "(time.process_time), which the other processes sharing the cores do not inflate. A time ratio near "
             "the size ratio is linear; quadratic would be its square. Target: "
             f"{CHECK_TARGET_S:g} s for 50,000 vectors, scaled linearly to N'."]
    return Section("check_scale", "10. plans check on hostile files: linear in vectors and in nesting depth", cols,
                   rows, notes, {"time_ratios": {r[0]: r[5] for r in rows}, "size_ratio": large / small,
                                 "target_s": target, "met": all(r[7] == "met" for r in rows)})

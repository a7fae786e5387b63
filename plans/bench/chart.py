"""Line charts of benchmark figures as SVG (svgwrite), one user unit = one millimetre.

A chart is a plain value (:class:`Chart`: title, axis labels, series, linear or logarithmic
axes); :func:`draw_chart` turns it into SVG text. Everything but the plotted numbers is
fixed: explicit ids, coordinates rounded to 0.01 mm, ticks chosen from the data range by a
fixed rule, so the same figures always give the same bytes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import svgwrite

__all__ = ["Series", "Chart", "draw_chart", "ticks"]

#: Sheet and plot area (mm).
WIDTH = 170.0
PLOT_LEFT, PLOT_RIGHT = 26.0, 162.0
PLOT_TOP, PLOT_BOTTOM = 18.0, 88.0
LEGEND_TOP = 106.0
LEGEND_ROW = 5.0
FONT = "DejaVu Sans, Arial, sans-serif"
COLOURS = ("#1f3a93", "#a12a2a", "#2e7d32", "#8e6c00", "#6a1b9a", "#00838f")
DASHES = ("", "4 1.5", "1.2 1.2", "6 1.5 1.2 1.5")
#: A series of more points is drawn as a line only.
MARKERS_UP_TO = 60
_SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


@dataclass(frozen=True)
class Series:
    """One line of a chart: points (x, y) joined in the given order, with markers."""

    label: str
    x: tuple[float, ...]
    y: tuple[float, ...]

    def __post_init__(self) -> None:
        if len(self.x) != len(self.y):
            raise ValueError(f"series {self.label!r}: {len(self.x)} x values but {len(self.y)} y values")


@dataclass(frozen=True)
class Chart:
    """A line chart: ``name`` is the file stem, the rest is drawn."""

    name: str
    title: str
    x_label: str
    y_label: str
    series: tuple[Series, ...]
    log_x: bool = False
    log_y: bool = False
    note: str = ""
    y_from_zero: bool = False   # a linear y axis that starts at 0 (sizes, counts)


def _fmt(x: float) -> str:
    s = f"{x:.2f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _label(value: float, log: bool) -> str:
    """A tick label: 10ᵏ on a logarithmic axis, a short decimal on a linear one."""
    if log:
        k = round(math.log10(value))
        return {0: "1", 1: "10"}.get(k, "10" + str(k).translate(_SUPERSCRIPT))
    if value != 0 and (abs(value) >= 1e5 or abs(value) < 1e-3):
        return f"{value:.0e}".replace("e+0", "e").replace("e-0", "e-")
    return f"{value:.10g}"


def ticks(lo: float, hi: float, log: bool) -> tuple[tuple[float, ...], float, float]:
    """Tick values and the axis range (lo', hi') that holds [lo, hi].

    Logarithmic: whole decades, every k-th decade so that at most 8 are labelled.
    Linear: steps of 1, 2 or 5 × 10ᵏ, about five of them."""
    if log:
        a, b = math.floor(math.log10(lo) + 1e-9), math.ceil(math.log10(hi) - 1e-9)
        b = max(b, a + 1)
        step = max(1, math.ceil((b - a) / 8))
        b = a + step * math.ceil((b - a) / step)
        return tuple(10.0 ** k for k in range(a, b + 1, step)), 10.0 ** a, 10.0 ** b
    if hi <= lo:
        lo, hi = lo - 0.5 * (abs(lo) or 1.0), hi + 0.5 * (abs(hi) or 1.0)
    raw = (hi - lo) / 5
    mag = 10.0 ** math.floor(math.log10(raw))
    step = next(m * mag for m in (1, 2, 5, 10) if m * mag >= raw * 0.999)
    a, b = math.floor(lo / step + 1e-9), math.ceil(hi / step - 1e-9)
    vals = tuple(round(k * step, 12) for k in range(a, b + 1))
    return vals, vals[0], vals[-1]


class _Axis:
    """Maps data values to paper millimetres along one axis."""

    def __init__(self, values: list[float], log: bool, p0: float, p1: float, zero: bool = False):
        self.log = log
        if log:
            values = [v for v in values if v > 0] or [1.0]
        elif zero:
            values = values + [0.0]
        self.ticks, self.lo, self.hi = ticks(min(values), max(values), log)
        self.p0, self.p1 = p0, p1

    def __call__(self, v: float) -> float:
        f = (math.log10(v) - math.log10(self.lo)) / (math.log10(self.hi) - math.log10(self.lo)) if self.log \
            else (v - self.lo) / (self.hi - self.lo)
        return self.p0 + f * (self.p1 - self.p0)


def _text(dwg, at: tuple[float, float], text: str, *, size: float = 3.0, anchor: str = "middle",
          ident: str, rotate: bool = False, weight: str = "normal"):
    t = dwg.text(text, insert=(_fmt(at[0]), _fmt(at[1])), font_size=_fmt(size), text_anchor=anchor,
                 font_family=FONT, font_weight=weight, fill="#000", id=ident)
    if rotate:
        t.attribs["transform"] = f"rotate(-90 {_fmt(at[0])} {_fmt(at[1])})"
    return t


def _marker(dwg, k: int, x: float, y: float, colour: str, ident: str):
    """Circle, square, triangle, diamond … by series index."""
    r = 0.9
    shape = k % 4
    if shape == 0:
        return dwg.circle(center=(_fmt(x), _fmt(y)), r=_fmt(r), fill=colour, id=ident)
    if shape == 1:
        return dwg.rect(insert=(_fmt(x - r), _fmt(y - r)), size=(_fmt(2 * r), _fmt(2 * r)), fill=colour, id=ident)
    pts = [(x, y - 1.2 * r), (x + 1.1 * r, y + 0.8 * r), (x - 1.1 * r, y + 0.8 * r)] if shape == 2 else \
        [(x, y - 1.3 * r), (x + r, y), (x, y + 1.3 * r), (x - r, y)]
    return dwg.polygon([(_fmt(a), _fmt(b)) for a, b in pts], fill=colour, id=ident)


def draw_chart(chart: Chart) -> str:
    """SVG text of ``chart``. Points with a non-positive value on a logarithmic axis are left out
    (the caption says how many)."""
    keep = []
    dropped = 0
    for s in chart.series:
        pts = [(x, y) for x, y in zip(s.x, s.y) if math.isfinite(x) and math.isfinite(y)
               and (x > 0 or not chart.log_x) and (y > 0 or not chart.log_y)]
        dropped += len(s.x) - len(pts)
        keep.append(pts)
    xs = [p[0] for pts in keep for p in pts] or [1.0]
    ys = [p[1] for pts in keep for p in pts] or [1.0]
    ax = _Axis(xs, chart.log_x, PLOT_LEFT, PLOT_RIGHT)
    ay = _Axis(ys, chart.log_y, PLOT_BOTTOM, PLOT_TOP, zero=chart.y_from_zero)
    # two legend columns unless a label would run into the next column (text ≈ 0.55 × height per glyph)
    columns = 2 if max((len(s.label) for s in chart.series), default=0) * 0.55 * 2.8 + 12 < \
        (PLOT_RIGHT - PLOT_LEFT) / 2 else 1
    rows = math.ceil(len(chart.series) / columns)
    height = LEGEND_TOP + LEGEND_ROW * rows + (5.0 if chart.note or dropped else 0.0) + 2.0
    w, h = _fmt(WIDTH), _fmt(height)
    name = chart.name
    dwg = svgwrite.Drawing(size=(f"{w}mm", f"{h}mm"), viewBox=f"0 0 {w} {h}", debug=False, profile="full")
    dwg.attribs["id"] = name
    dwg.add(dwg.rect(insert=(0, 0), size=(w, h), fill="#fff", id=f"{name}-paper"))
    dwg.add(_text(dwg, (WIDTH / 2, 9.0), chart.title, size=4.2, ident=f"{name}-title", weight="bold"))

    grid = dwg.g(id=f"{name}-grid", stroke="#ccc", stroke_width="0.15", fill="none")
    labels = dwg.g(id=f"{name}-ticks")
    for k, t in enumerate(ax.ticks):
        x = ax(t)
        grid.add(dwg.line(start=(_fmt(x), _fmt(PLOT_TOP)), end=(_fmt(x), _fmt(PLOT_BOTTOM)), id=f"{name}-gx{k}"))
        labels.add(dwg.line(start=(_fmt(x), _fmt(PLOT_BOTTOM)), end=(_fmt(x), _fmt(PLOT_BOTTOM + 1.5)),
                            stroke="#000", stroke_width="0.25", id=f"{name}-tx{k}"))
        labels.add(_text(dwg, (x, PLOT_BOTTOM + 5.0), _label(t, chart.log_x), size=2.8, ident=f"{name}-lx{k}"))
    for k, t in enumerate(ay.ticks):
        y = ay(t)
        grid.add(dwg.line(start=(_fmt(PLOT_LEFT), _fmt(y)), end=(_fmt(PLOT_RIGHT), _fmt(y)), id=f"{name}-gy{k}"))
        labels.add(dwg.line(start=(_fmt(PLOT_LEFT - 1.5), _fmt(y)), end=(_fmt(PLOT_LEFT), _fmt(y)),
                            stroke="#000", stroke_width="0.25", id=f"{name}-ty{k}"))
        labels.add(_text(dwg, (PLOT_LEFT - 2.5, y + 1.0), _label(t, chart.log_y), size=2.8, anchor="end",
                         ident=f"{name}-ly{k}"))
    dwg.add(grid)
    dwg.add(labels)
    dwg.add(dwg.rect(insert=(_fmt(PLOT_LEFT), _fmt(PLOT_TOP)), size=(_fmt(PLOT_RIGHT - PLOT_LEFT),
                     _fmt(PLOT_BOTTOM - PLOT_TOP)), fill="none", stroke="#000", stroke_width="0.35",
                     id=f"{name}-frame"))
    dwg.add(_text(dwg, ((PLOT_LEFT + PLOT_RIGHT) / 2, PLOT_BOTTOM + 11.0), chart.x_label, size=3.2,
                  ident=f"{name}-xlabel"))
    dwg.add(_text(dwg, (6.0, (PLOT_TOP + PLOT_BOTTOM) / 2), chart.y_label, size=3.2, rotate=True,
                  ident=f"{name}-ylabel"))

    for k, (s, pts) in enumerate(zip(chart.series, keep)):
        colour = COLOURS[k % len(COLOURS)]
        g = dwg.g(id=f"{name}-s{k}", stroke=colour, stroke_width="0.4", fill="none")
        g.attribs["data-label"] = s.label
        paper = [(ax(x), ay(y)) for x, y in pts]
        if len(paper) > 1:
            line = dwg.polyline([(_fmt(x), _fmt(y)) for x, y in paper], id=f"{name}-s{k}-line")
            if DASHES[k % len(DASHES)]:
                line.attribs["stroke-dasharray"] = DASHES[k % len(DASHES)]
            g.add(line)
        if len(paper) <= MARKERS_UP_TO:
            marks = dwg.g(id=f"{name}-s{k}-marks", stroke="none")
            for j, (x, y) in enumerate(paper):
                marks.add(_marker(dwg, k, x, y, colour, f"{name}-s{k}-m{j}"))
            g.add(marks)
        dwg.add(g)
        col, row = k % columns, k // columns
        lx, ly = PLOT_LEFT + col * (PLOT_RIGHT - PLOT_LEFT) / 2, LEGEND_TOP + row * LEGEND_ROW
        key = dwg.g(id=f"{name}-key{k}")
        sample = dwg.line(start=(_fmt(lx), _fmt(ly - 1.0)), end=(_fmt(lx + 8), _fmt(ly - 1.0)), stroke=colour,
                          stroke_width="0.4", id=f"{name}-key{k}-line")
        if DASHES[k % len(DASHES)]:
            sample.attribs["stroke-dasharray"] = DASHES[k % len(DASHES)]
        key.add(sample)
        if len(paper) <= MARKERS_UP_TO:
            key.add(_marker(dwg, k, lx + 4, ly - 1.0, colour, f"{name}-key{k}-mark"))
        key.add(_text(dwg, (lx + 10, ly), s.label, size=2.8, anchor="start", ident=f"{name}-key{k}-text"))
        dwg.add(key)
    caption = chart.note
    if dropped:
        caption = (caption + "; " if caption else "") + f"{dropped} point(s) ≤ 0 not shown on the log axis"
    if caption:
        dwg.add(_text(dwg, (PLOT_LEFT, LEGEND_TOP + LEGEND_ROW * rows + 3.0), caption, size=2.5, anchor="start",
                      ident=f"{name}-note"))
    return dwg.tostring() + "\n"

"""Marks shared by every sheet: image labels in label markup, arrowheads."""

from __future__ import annotations

import math
from typing import Iterable, Sequence

import numpy as np

from .canvas import Canvas, fmt
from .style import Style

__all__ = ["markup", "arrow", "vector", "bounds", "union", "NO_HEAD_MM", "LABEL_ROOM_MM"]

#: Room kept around a drawing's geometry for its labels, mm.
LABEL_ROOM_MM = 10.0
#: A vector shorter than this is drawn without an arrowhead (it stays tagged), mm; longer
#: ones get a head of Style.arrow_length, or half the vector when that is shorter.
NO_HEAD_MM = 2.0


def markup(label: str) -> str:
    """An image label in label markup: trailing digits (a point of link 3: ``a3``) as a subscript."""
    if "_" in label:
        return label
    k = len(label.rstrip("′"))
    head, primes = label[:k], label[k:]
    stem = head.rstrip("0123456789")
    return f"{stem}_{{{head[len(stem):]}}}{primes}" if stem and stem != head else label


def arrow(canvas: Canvas, parent, tail, head, colour: str, ident: str, style: Style, *, of: str) -> None:
    """The arrowhead ``ident`` of the drawn line ``of`` from ``tail`` to ``head`` (mm, y up):
    Style.arrow_length long, or half the line when that is shorter; none under NO_HEAD_MM."""
    L = math.dist(tail, head)
    if L >= NO_HEAD_MM:
        el = canvas.head(parent, tail, head, min(style.arrow_length, 0.5 * L), fill=colour, stroke="none",
                         id=ident)
        el.attribs["class"] = "head"
        el.attribs["data-for"] = of


def vector(canvas: Canvas, parent, tail, head, colour: str, ident: str, head_ident: str, style: Style):
    """A vector as one ``<line>`` from tail to head (it measures the whole vector) whose
    visible shaft stops under its arrowhead, and the head; returns the line for tagging."""
    L = math.dist(tail, head)
    head_len = min(style.arrow_length, 0.5 * L) if L >= NO_HEAD_MM else 0.0
    shaft = max(L - head_len * 0.8, 0.0)
    el = canvas.line(parent, tail, head, width=style.vector, id=ident, stroke=colour,
                     stroke_width=fmt(style.vector, 3), stroke_dasharray=f"{fmt(shaft, 3)} {fmt(L + 1, 3)}")
    arrow(canvas, parent, tail, head, colour, head_ident, style, of=ident)
    return el


def bounds(points: Iterable[Sequence[float]]) -> tuple[float, float, float, float]:
    """The content box of ``points`` (mm, y up) with LABEL_ROOM_MM all round."""
    arr = np.array(list(points), dtype=float).reshape(-1, 2)
    (x0, y0), (x1, y1) = arr.min(axis=0), arr.max(axis=0)
    r = LABEL_ROOM_MM
    return float(x0) - r, float(y0) - r, float(x1) + r, float(y1) + r


def union(a: Sequence[float], b: Sequence[float]) -> tuple[float, float, float, float]:
    """The box (x0, y0, x1, y1) holding boxes ``a`` and ``b`` (a drawing and its detail)."""
    return min(a[0], b[0]), min(a[1], b[1]), max(a[2], b[2]), max(a[3], b[3])

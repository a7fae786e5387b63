"""Marks shared by every sheet: image labels in label markup, arrowheads."""

from __future__ import annotations

import math

from .canvas import Canvas
from .style import Style

__all__ = ["markup", "arrow", "NO_HEAD_MM"]

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


def arrow(canvas: Canvas, parent, tail, head, colour: str, ident: str, style: Style) -> None:
    L = math.dist(tail, head)
    if L >= NO_HEAD_MM:
        el = canvas.head(parent, tail, head, min(style.arrow_length, 0.5 * L), fill=colour, stroke="none",
                         id=ident)
        el.attribs["class"] = "head"
        el.attribs["data-for"] = ident.replace("-h", "-v", 1) if "-h" in ident else ident



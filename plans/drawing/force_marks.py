"""What the force sheets share: the printed names of force tags (:func:`symbol`), numbers as
the sheets write them, solid and dashed vectors with their heads, the colours of the kinds of
force, the panels' text sizes and gaps, and placing content in a paper box."""

from __future__ import annotations

import math

import numpy as np

from ..constructions.forces import component_of
from .canvas import Canvas, fmt
from .marks import NO_HEAD_MM, arrow as _arrow
from .style import Style
from .. import linalg as la

__all__ = ["symbol", "PANEL_GAP_MM", "TABLE_TEXT_MM", "TABLE_LEAD_MM"]

#: Space between panels, mm.
PANEL_GAP_MM = 8.0
#: Height of the tables' and captions' text, and their line spacing, mm.
TABLE_TEXT_MM = 2.8
TABLE_LEAD_MM = 4.4
_KIND_COLOUR = {"gravity": "vector", "inertia": "vector", "external": "vector", "balance": "vector",
                "reaction": "component", "reaction_n": "component", "reaction_t": "component"}



def _sub(text: str) -> str:
    return "{" + text + "}"


def symbol(quantity: str) -> str:
    """The printed name of a force tag, in label markup: ``R:1-2`` → R₁₂, ``R:1-2:n`` → R₁₂,ₙ,
    ``R:1-2:t`` → R₁₂,τ, ``G:3`` → G₃, ``F:in:2`` → F_in,2, ``F:ext:B`` → F_B, ``F:bal`` →
    F_bal, ``M:2`` → M₂, ``M:in:2`` → M_in,2, ``M:ext:2`` → M₂, a couple's force ``F:M:2:a``
    (``F:M:ext:2:a``) → F′₂ (at a), ``F:M:in:2:a`` → F′_in,2."""
    parts = quantity.split(":")
    base, comp = component_of(quantity)
    if base.startswith("R:") and "-" in base:
        i, _, j = base[2:].partition("-")
        ij = f"{i}{j}" if len(i) == 1 and len(j) == 1 else f"{i},{j}"
        return f"R_{_sub(ij + ({'n': ',n', 't': ',τ'}[comp] if comp else ''))}"
    if len(parts) == 2 and parts[0] in ("G", "M", "F"):
        return f"{parts[0]}_{_sub(parts[1])}"
    if len(parts) == 3 and parts[:2] == ["F", "in"]:
        return f"F_{_sub('in,' + parts[2])}"
    if len(parts) == 3 and parts[:2] == ["F", "ext"]:
        return f"F_{_sub(parts[2])}"
    if len(parts) == 3 and parts[0] == "M":                 # M:in:2, M:ext:2 (the force analysis' tags)
        return f"M_{_sub(('in,' if parts[1] == 'in' else '') + parts[2])}"
    if len(parts) >= 4 and parts[:2] == ["F", "M"]:          # a couple's force: F:M:2:a, F:M:in:2:a
        which = parts[2:-1]
        return f"F′_{_sub(('in,' if which[0] == 'in' else '') + which[-1])}"
    return quantity.replace("_", " ")


def _number(v: float, digits: int = 4) -> str:
    """``v`` with ``digits`` significant figures, no exponent below 10^7, − for minus."""
    if v == 0 or not math.isfinite(v):
        return "0" if v == 0 else str(v)
    if abs(v) < 1e-3:                          # a rounding zero or a tiny value: in powers of ten
        return f"{v:.{digits - 1}e}".replace("-", "−")
    v = float(f"{v:.{digits}g}")               # rounded first: 9.99996 → 10.00, not 10.000
    places = max(0, digits - 1 - int(math.floor(math.log10(abs(v)))))
    s = f"{v:.{places}f}" if abs(v) < 1e7 else f"{v:.{digits - 1}e}"
    return s.replace("-", "−")


def _signed(v: float, digits: int = 4) -> str:
    return ("+" if v >= 0 else "") + _number(v, digits)


def _colour(style: Style, kind: str) -> str:
    return style.vector_colour if _KIND_COLOUR.get(kind) == "vector" else style.component_colour


def _dashed_vector(canvas: Canvas, parent, tail, head, colour: str, ident: str, head_ident: str, style: Style,
                   width_: float | None = None):
    """A dashed vector: one ``<line>`` tail → head (it measures the whole vector), dashes up to
    under its arrowhead, and the head."""
    L = math.dist(tail, head)
    head_len = min(style.arrow_length, 0.5 * L) if L >= NO_HEAD_MM else 0.0
    shaft = max(L - head_len * 0.8, 0.0)
    on, off = (float(x) for x in style.dash.split())
    pattern, done = [], 0.0
    while done + on < shaft:
        pattern += [on, off]
        done += on + off
    pattern += [max(min(on, shaft - done), 0.0), L + 1.0]
    w = style.vector if width_ is None else width_
    el = canvas.line(parent, tail, head, width=w, id=ident, stroke=colour, stroke_width=fmt(w, 3),
                     stroke_dasharray=" ".join(fmt(x, 3) for x in pattern))
    _arrow(canvas, parent, tail, head, colour, head_ident, style, of=ident)
    return el


def _solid_vector(canvas: Canvas, parent, tail, head, colour: str, ident: str, head_ident: str, style: Style,
                  width_: float | None = None):
    """A vector as one ``<line>`` whose visible shaft stops under its arrowhead (as marks.vector)."""
    L = math.dist(tail, head)
    head_len = min(style.arrow_length, 0.5 * L) if L >= NO_HEAD_MM else 0.0
    shaft = max(L - head_len * 0.8, 0.0)
    w = style.vector if width_ is None else width_
    el = canvas.line(parent, tail, head, width=w, id=ident, stroke=colour, stroke_width=fmt(w, 3),
                     stroke_dasharray=f"{fmt(shaft, 3)} {fmt(L + 1, 3)}")
    _arrow(canvas, parent, tail, head, colour, head_ident, style, of=ident)
    return el


def _side_label_direction(tail, head, centre) -> np.ndarray:
    """Perpendicular to a side, away from the polygon's centre."""
    d = np.subtract(head, tail)
    n = np.array([-d[1], d[0]])
    if la.norm(n) < 1e-12:
        return np.array([0.6, 0.8])
    mid = np.add(tail, head) / 2
    return n if la.dot(n, mid - np.asarray(centre)) >= 0 else -n


def _place(canvas: Canvas, content, box) -> None:
    """Move the canvas so that ``content`` (mm, y up) is centred in paper ``box`` (x0, y0, x1, y1)."""
    canvas.dx = (box[0] + box[2]) / 2 - (content[0] + content[2]) / 2
    canvas.dy = (box[1] + box[3]) / 2 + (content[1] + content[3]) / 2


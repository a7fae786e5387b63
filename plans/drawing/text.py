"""Text on the sheets: label markup (subscripts) and the metrics of the named font.

Every sheet names DejaVu Serif (Book for words, Italic for images and symbols); its advance
widths (:mod:`.font_metrics`) size every label, for the label placer and for the layout test
alike. A text box spans from ``ASCENT`` × size above the baseline (the height of b, d, l) to
``DESCENT`` × size below it (p, q, y), and a subscript run is ``SUB_SIZE`` × size high, its
baseline ``SUB_SHIFT`` × size lower.

Markup: ``n_BA`` and ``k_{C3C2}`` write the part after ``_`` as a subscript (a run of letters,
digits and primes, or the braced text); with ``digits``, trailing digits are a subscript too
(``a3`` → a₃, ``ω1`` → ω₁), as the textbook writes the point of link 3.
"""

from __future__ import annotations

import functools
import re
from dataclasses import dataclass

from .font_metrics import BOOK, ITALIC

__all__ = ["Run", "runs", "plain", "wrap", "width", "Box", "box", "ASCENT", "DESCENT", "SUB_SIZE", "SUB_SHIFT", "FONT"]

#: The family every sheet names (the metrics below are its own).
FONT = "DejaVu Serif"
ASCENT = 0.76
DESCENT = 0.24
SUB_SIZE = 0.7
SUB_SHIFT = 0.3
#: Width of a glyph the tables lack, em (wider than any Latin letter but W, M).
UNKNOWN_EM = 0.8

_SUB = re.compile(r"_(\{[^}]*\}|[0-9A-Za-zα-ωΑ-Ω′]+)")
_TRAILING = re.compile(r"^(.*?[^\d_])(\d+)(′*)$")


@dataclass(frozen=True)
class Run:
    """A piece of a label: its text and whether it is a subscript."""

    text: str
    sub: bool = False


@functools.lru_cache(maxsize=1 << 16)
def runs(label: str, *, digits: bool = False) -> tuple[Run, ...]:
    """A label split into normal and subscript runs (see the module docstring); remembered (a
    sheet measures the same few hundred labels and rows many times)."""
    out: list[Run] = []
    pos = 0
    for m in _SUB.finditer(label):
        if m.start() > pos:
            out.append(Run(label[pos:m.start()]))
        out.append(Run(m.group(1).strip("{}"), True))
        pos = m.end()
    if pos < len(label):
        out.append(Run(label[pos:]))
    if digits and len(out) == 1 and not out[0].sub:
        m = _TRAILING.match(out[0].text)
        if m:
            out = [Run(m.group(1)), Run(m.group(2), True)] + ([Run(m.group(3))] if m.group(3) else [])
    return tuple(r for r in out if r.text)


#: A hyphen that writes a negative number: before a digit or a decimal point and a digit, not
#: after a letter, digit, closing bracket or dot (``I(0-2-3)``, ``1e-05``, a name ``S-1``).
_NEGATIVE = re.compile(r"(?<![\w).])-(?=\.?\d)")


def minus_signs(text: str) -> str:
    """``text`` with the hyphen of every negative number replaced by the minus sign U+2212."""
    return _NEGATIVE.sub("−", text)


def significant(x: float, digits: int = 6) -> str:
    """``x`` to ``digits`` significant digits as the sheets write numbers: the minus sign U+2212,
    and a zero of either sign as ``0``."""
    return "0" if x == 0.0 else f"{x:.{digits}g}".replace("-", "−")


def plain(label: str) -> str:
    """A label's characters without markup (``φ_1`` → ``φ1``)."""
    return "".join(r.text for r in runs(label))


@functools.lru_cache(maxsize=1 << 16)
def _em(text: str, italic: bool) -> float:
    em, _, _, table = ITALIC if italic else BOOK
    default = UNKNOWN_EM * em
    return sum(table.get(c, default) for c in text) / em


def width(parts: tuple[Run, ...], size: float, italic: bool) -> float:
    """Advance width of the runs at text height ``size`` (mm)."""
    return sum(_em(r.text, italic) * size * (SUB_SIZE if r.sub else 1.0) for r in parts)


@dataclass(frozen=True)
class Box:
    """An axis-aligned box on the paper (SVG frame, y down), mm."""

    x0: float
    y0: float
    x1: float
    y1: float

    def overlaps(self, other: "Box", gap: float = 0.0) -> bool:
        return (self.x0 < other.x1 + gap and other.x0 < self.x1 + gap
                and self.y0 < other.y1 + gap and other.y0 < self.y1 + gap)

    def inside(self, other: "Box") -> bool:
        return other.x0 <= self.x0 and self.x1 <= other.x1 and other.y0 <= self.y0 and self.y1 <= other.y1


def box(parts: tuple[Run, ...], size: float, italic: bool, x: float, y: float, anchor: str = "start") -> Box:
    """The ink box of a text whose baseline starts (``anchor`` start), centres (middle) or
    ends (end) at paper point (x, y)."""
    w = width(parts, size, italic)
    left = x - {"start": 0.0, "middle": 0.5, "end": 1.0}[anchor] * w
    low = DESCENT * size
    if any(r.sub for r in parts):
        low = max(low, SUB_SHIFT * size + DESCENT * SUB_SIZE * size)
    return Box(left, y - ASCENT * size, left + w, y + low)


def wrap(text: str, room: float, size: float, *, indent: str = "") -> list[str]:
    """``text`` broken at spaces into rows at most ``room`` mm wide at height ``size`` (a
    single word wider than the room keeps a row of its own); rows after the first start
    with ``indent``."""
    rows, row = [], ""
    for word in text.split(" "):
        trial = f"{row} {word}" if row else word
        if row and width(runs(trial), size, False) > room:
            rows.append(row)
            trial = indent + word
        row = trial
    rows.append(row)
    return rows

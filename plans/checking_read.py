"""Reading a plan's SVG back: numbers and decimals of attributes, the paper's unit, transforms,
the points a quantity's name says its tail and head are (``v:X``, ``a:X/Y:n`` …), a tagged
line's coordinates, value and direction, and the union of ends named alike.

Part of :mod:`plans.checking` (its private helpers). Knows nothing of plans; must not import
any other plans module.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from decimal import Decimal, InvalidOperation

_SVG = "{http://www.w3.org/2000/svg}"
_NAME = re.compile(r"^(?P<sym>[A-Za-z]+):(?P<x>[^/:]+)(?:/(?P<y>[^/:]+))?(?::(?P<comp>n|t|cor|r))?$")
_TRANSFORM = re.compile(r"transform", re.IGNORECASE)


def _number(text: str | None) -> float | None:
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def _decimals(text: str) -> int:
    try:
        return max(0, -int(Decimal(text.strip()).as_tuple().exponent))
    except (InvalidOperation, ValueError, TypeError, AttributeError):
        return 0


def _mm(text: str | None) -> float | None:
    if text is None or not text.strip().endswith("mm"):
        return None
    return _number(text.strip()[:-2])


def _paper_problems(root: ET.Element) -> list[str]:
    """The user unit must be the millimetre: width/height in mm equal to the viewBox at 0 0."""
    w, h = _mm(root.get("width")), _mm(root.get("height"))
    box = (root.get("viewBox") or "").replace(",", " ").split()
    vals = [_number(b) for b in box]
    if w is None or h is None or len(vals) != 4 or None in vals:
        return ["the root <svg> needs width and height in mm and a viewBox (one user unit = one mm)"]
    if vals[0] != 0 or vals[1] != 0 or not math.isclose(vals[2], w, rel_tol=1e-9) \
            or not math.isclose(vals[3], h, rel_tol=1e-9):
        return [f"viewBox {' '.join(box)} does not match {root.get('width')} × {root.get('height')}: "
                "the user unit is not the millimetre"]
    return []


def _transformed(el: ET.Element) -> bool:
    return el.get("transform") is not None or bool(_TRANSFORM.search(el.get("style") or ""))


def _ends(quantity: str) -> tuple[tuple | None, tuple | None, bool]:
    """The points a quantity's name says its tail and head are (None: not known), and
    whether it is an absolute vector (from the pole)."""
    m = _NAME.match(quantity)
    if m is None:
        return None, None, False
    sym, x, y, comp = m["sym"], m["x"], m["y"], m["comp"]
    if y is None:
        if comp is None and sym in ("v", "a"):
            return ("pole",), ("pt", x), True
        return None, None, False
    if comp is None:
        return ("pt", y), ("pt", x), False
    mid = ("n" if comp in ("n", "t") else "k", x, y)
    return (("pt", y), mid, False) if comp in ("n", "cor") else (mid, ("pt", x), False)


def _point_name(token: tuple) -> str:
    if token[0] == "pole":
        return "pole"
    return token[1] if token[0] == "pt" else f"{token[0]}_{token[1]}{token[2]}"


class _Union:
    def __init__(self):
        self.up: dict = {}

    def find(self, a):
        self.up.setdefault(a, a)
        while self.up[a] != a:
            self.up[a] = self.up[self.up[a]]
            a = self.up[a]
        return a

    def join(self, a, b):
        self.up[self.find(a)] = self.find(b)


def _line_data(line: ET.Element):
    """(x1, y1, x2, y2), value, direction (rad) of a tagged line, or None when unreadable."""
    xy = [_number(line.get(k)) for k in ("x1", "y1", "x2", "y2")]
    value, theta = _number(line.get("data-value")), _number(line.get("data-direction"))
    if None in xy or value is None or theta is None or not all(math.isfinite(c) for c in xy + [value, theta]):
        return None
    return xy, value, math.radians(theta)


def _path_points(d: str | None) -> list[tuple[float, float]]:
    """The points of a path written as ``M x,y L x,y …`` (plans' own polylines and outlines)."""
    return [(float(a), float(b)) for a, b in re.findall(r"[ML]\s*([-+0-9.eE]+)\s*,\s*([-+0-9.eE]+)", d or "")]

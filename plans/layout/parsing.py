"""Small parsers of SVG text for :func:`plans.layout.measure_layout`: tags, attributes and
inline styles, numbers and lengths (to mm), paints (what is ink, what is paper), transforms
(3×3 matrices) and path data (subpaths as point lists).

Knows nothing of plans; must not import any other plans module.
"""

from __future__ import annotations

import math
import re

import numpy as np

from .. import linalg as la

__all__ = ["PALE"]

#: A paint lighter than this (relative luminance, 0 … 1) is paper, not ink.
PALE = 0.9
_INHERITED = ("fill", "stroke", "stroke-width", "stroke-linecap", "stroke-linejoin", "font-size", "font-style",
              "text-anchor", "fill-opacity", "stroke-opacity", "opacity", "visibility", "xml:space")
_NUM = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_UNITS = {"mm": 1.0, "cm": 10.0, "in": 25.4, "pt": 25.4 / 72.0, "pc": 25.4 / 6.0, "px": 25.4 / 96.0, "": None}
_NAMED = {"none": None, "transparent": None, "white": (1.0, 1.0, 1.0), "black": (0.0, 0.0, 0.0)}


def _local(tag) -> str:
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


_XML_SPACE = "{http://www.w3.org/XML/1998/namespace}space"


def _attr(el, name: str):
    return el.attrib.get(_XML_SPACE if name == "xml:space" else name)


_STYLED = frozenset(_INHERITED + ("display", "stroke-dasharray", "transform", "x", "y", "dx", "dy"))


def _style(el) -> dict[str, str]:
    """Presentation attributes of ``el``: its attributes, overridden by its ``style``."""
    out = {}
    for key, v in el.attrib.items():
        name = "xml:space" if key == _XML_SPACE else key
        if name in _STYLED:
            out[name] = v.strip()
    for decl in (el.attrib.get("style") or "").split(";"):
        if ":" in decl:
            k, v = decl.split(":", 1)
            out[k.strip()] = v.strip()
    return out


def _number(text: str | None, default: float = 0.0) -> float:
    if text is None:
        return default
    m = _NUM.search(text)
    return float(m.group()) if m else default


def _numbers(text: str | None) -> list[float]:
    return [float(v) for v in _NUM.findall(text or "")]


def _length_mm(text: str | None) -> float | None:
    """A root width or height in mm (user units are taken as mm)."""
    if not text:
        return None
    m = re.fullmatch(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([a-z%]*)\s*", text)
    if not m:
        return None
    unit = _UNITS.get(m.group(2), None)
    value = float(m.group(1))
    return value if m.group(2) == "" else value * unit if unit else None


def _paint(value: str | None, default):
    """The RGB (0 … 1) of a paint, None for none; an unknown paint counts as black."""
    if value is None:
        return default
    v = value.strip().lower()
    if v in _NAMED:
        return _NAMED[v]
    m = re.fullmatch(r"#([0-9a-f]{3}|[0-9a-f]{6})", v)
    if m:
        h = m.group(1)
        if len(h) == 3:
            h = "".join(c * 2 for c in h)
        return tuple(int(h[i:i + 2], 16) / 255.0 for i in (0, 2, 4))
    m = re.fullmatch(r"rgb\(\s*([^,]+),\s*([^,]+),\s*([^)]+)\)", v)
    if m:
        parts = [p.strip() for p in m.groups()]
        return tuple(float(p[:-1]) / 100.0 if p.endswith("%") else float(p) / 255.0 for p in parts)
    return (0.0, 0.0, 0.0)


def _inked(rgb, *opacities: str | None) -> bool:
    """A paint that marks the paper: not none, not transparent, not paper-pale."""
    if rgb is None or any(o is not None and _number(o, 1.0) <= 0.0 for o in opacities):
        return False
    r, g, b = rgb
    return 0.2126 * r + 0.7152 * g + 0.0722 * b < PALE


def _transform(text: str | None) -> np.ndarray:
    """The 3×3 matrix of an SVG ``transform`` list."""
    m = np.eye(3)
    for name, args in re.findall(r"(matrix|translate|scale|rotate|skewX|skewY)\s*\(([^)]*)\)", text or ""):
        a = _numbers(args)
        if name == "matrix" and len(a) == 6:
            t = np.array([[a[0], a[2], a[4]], [a[1], a[3], a[5]], [0, 0, 1]])
        elif name == "translate":
            t = np.array([[1, 0, a[0]], [0, 1, a[1] if len(a) > 1 else 0.0], [0, 0, 1]])
        elif name == "scale":
            t = np.diag([a[0], a[1] if len(a) > 1 else a[0], 1.0])
        elif name == "rotate":
            c, s = math.cos(math.radians(a[0])), math.sin(math.radians(a[0]))
            t = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
            if len(a) == 3:
                t = la.matmul(la.matmul(np.array([[1, 0, a[1]], [0, 1, a[2]], [0, 0, 1]]), t),
                              np.array([[1, 0, -a[1]], [0, 1, -a[2]], [0, 0, 1]]))
        elif name == "skewX":
            t = np.array([[1, math.tan(math.radians(a[0])), 0], [0, 1, 0], [0, 0, 1]])
        elif name == "skewY":
            t = np.array([[1, 0, 0], [math.tan(math.radians(a[0])), 1, 0], [0, 0, 1]])
        else:
            raise ValueError(f"cannot read transform {name}({args})")
        m = la.matmul(m, t)
    return m


def _path_subpaths(d: str) -> list[tuple[list[tuple[float, float]], bool]]:
    """The subpaths of a path of straight segments (M, L, H, V, Z, either case): points and
    whether each is closed. Curves are refused (ValueError): the sheets draw none."""
    tokens = re.findall(r"[A-Za-z]|[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?", d)
    out: list[tuple[list[tuple[float, float]], bool]] = []
    cur: list[tuple[float, float]] = []
    x = y = 0.0
    start = (0.0, 0.0)
    cmd = None
    i = 0

    def flush(closed: bool = False):
        nonlocal cur
        if cur:
            out.append((cur, closed))
        cur = []

    while i < len(tokens):
        t = tokens[i]
        if t.isalpha():
            cmd = t
            i += 1
            if cmd in "Zz":
                if cur:
                    flush(True)
                x, y = start
                continue
            if cmd not in "MmLlHhVv":
                raise ValueError(f"path command {cmd!r}: only straight segments are measured")
            continue
        if cmd is None:
            raise ValueError(f"path data starts without a command: {d[:40]!r}")
        if cmd in "Mm":
            nx, ny = float(tokens[i]), float(tokens[i + 1])
            i += 2
            if cmd == "m" and (out or cur):
                nx, ny = x + nx, y + ny
            flush()
            x, y = nx, ny
            start = (x, y)
            cur = [(x, y)]
            cmd = "L" if cmd == "M" else "l"
            continue
        if cmd in "Ll":
            nx, ny = float(tokens[i]), float(tokens[i + 1])
            i += 2
            x, y = (x + nx, y + ny) if cmd == "l" else (nx, ny)
        elif cmd in "Hh":
            v = float(tokens[i])
            i += 1
            x = x + v if cmd == "h" else v
        else:
            v = float(tokens[i])
            i += 1
            y = y + v if cmd == "v" else v
        if not cur:
            cur = [start] if start == (x, y) else [(x, y)]
        cur.append((x, y))
    flush()
    return out


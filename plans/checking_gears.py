"""The gear sheet's own equations, read back from its SVG: every ray of the angular-velocity
picture (``data-ray="L"``) must be parallel to link L's line in the linear-velocity picture
(``data-link-line="L"``), run from the pole (``data-pole``) and end where ω_L's segment ends.

A direction is compared as the cross product of the unit vectors, within the rounding of the
written coordinates: two ends each off by at most 2√2·precision over a length L give an angle of
at most 2·2√2·precision/L radians per line.

Imports only the standard library."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

__all__ = ["gear_problems"]

_SVG = "{http://www.w3.org/2000/svg}"


def _xy(line: ET.Element) -> tuple[float, float, float, float] | None:
    try:
        return tuple(float(line.get(k, "nan")) for k in ("x1", "y1", "x2", "y2"))  # type: ignore[return-value]
    except ValueError:
        return None


def gear_problems(root: ET.Element, precision: float) -> list[str]:
    """The failures of the gear sheet's rays (none when the file has no ``data-ray``)."""
    rays = [e for e in root.iter(f"{_SVG}line") if e.get("data-ray") is not None]
    if not rays:
        return []
    lines = {e.get("data-link-line"): _xy(e) for e in root.iter(f"{_SVG}line") if e.get("data-link-line")}
    heads = {}
    for e in root.iter(f"{_SVG}line"):
        q = e.get("data-quantity") or ""
        if q.startswith("omega:"):
            heads[q[len("omega:"):]] = _xy(e)
    out = []
    r = 2.0 * math.sqrt(2.0) * precision
    for ray in rays:
        name = ray.get("data-ray")
        a, b = _xy(ray), lines.get(name)
        if a is None or any(not math.isfinite(c) for c in a):
            out.append(f"ray of {name}: its ends are not numbers")
            continue
        if b is None or any(not math.isfinite(c) for c in b):
            out.append(f"ray of {name}: no velocity line of link {name} (data-link-line)")
            continue
        la, lb = math.hypot(a[2] - a[0], a[3] - a[1]), math.hypot(b[2] - b[0], b[3] - b[1])
        if la <= r or lb <= r:
            continue                                    # a link at rest: no direction to compare
        sin = ((a[2] - a[0]) * (b[3] - b[1]) - (a[3] - a[1]) * (b[2] - b[0])) / (la * lb)
        tol = 2.0 * r / la + 2.0 * r / lb
        if abs(sin) > tol:
            out.append(f"ray of {name} is not parallel to the link's velocity line: "
                       f"{math.degrees(math.asin(min(1.0, abs(sin)))):.3g}° apart (tol {math.degrees(tol):.2g}°)")
        head = heads.get(name)
        if head is not None and math.hypot(head[2] - a[2], head[3] - a[3]) > 2 * r:
            out.append(f"ray of {name} ends {math.hypot(head[2] - a[2], head[3] - a[3]):.3g} mm from the end of "
                       f"ω_{name}'s segment")
    return out

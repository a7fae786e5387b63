"""The gear sheet's own equations, read back from its SVG: every ray of the angular-velocity
picture (``data-ray="L"``) must start at the pole (``data-pole`` of its picture), be parallel to
link L's line in the linear-velocity picture (``data-link-line="L"``) and end where ω_L's segment
ends; and the picture's declared scales must agree: μω = μV/(μl·h), μω the angular picture's
``data-mu``, μV the linear picture's, μl the side view's (``<ident>-scheme``, the picture being
``<ident>-omega``) and h the drawn distance from the pole to the ω line (mm).

A direction is compared as the cross product of the unit vectors, within the rounding of the
written coordinates: two ends each off by at most 2√2·precision over a length L give an angle of
at most 2·2√2·precision/L radians per line. A point is where it should be within 2·2√2·precision
(both rounded), and h, measured between two rounded ordinates, within 2·precision, so μω·μl·h/μV
may differ from 1 by 2·precision/h (+ 1e-9: the scales are written to the last bit).

An involute pair's meshing sheet (:func:`contact_problems`): the pitch point P stated by its
detail (``data-pitch-point``) must lie on both working profiles drawn, within the rounding of
the written points (P is a vertex of each profile).

Imports only the standard library and its sibling :mod:`plans.checking_read` (reading a path's points)."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

from .checking_read import _path_points

__all__ = ["gear_problems"]

_SVG = "{http://www.w3.org/2000/svg}"
#: Relative rounding allowed in the scale relation besides the drawn h's (the written scales are reprs).
_SCALE_REL = 1e-9


def _xy(line: ET.Element) -> tuple[float, float, float, float] | None:
    try:
        return tuple(float(line.get(k, "nan")) for k in ("x1", "y1", "x2", "y2"))  # type: ignore[return-value]
    except ValueError:
        return None


def _float(text: str | None) -> float | None:
    """A finite number written in an attribute, else None."""
    try:
        x = float(text) if text is not None else math.nan
    except ValueError:
        return None
    return x if math.isfinite(x) else None


def _pole(group: ET.Element) -> tuple[float, float] | None:
    """The pole's paper position ``data-pole="x y"`` (mm), or None when it is not two numbers."""
    parts = (group.get("data-pole") or "").split()
    xy = [_float(p) for p in parts]
    return (xy[0], xy[1]) if len(xy) == 2 and None not in xy else None  # type: ignore[return-value]


def _distance_to_polyline(p: tuple[float, float], pts: list[tuple[float, float]]) -> float:
    best = math.inf
    for (ax, ay), (bx, by) in zip(pts, pts[1:]):
        dx, dy = bx - ax, by - ay
        L2 = dx * dx + dy * dy
        t = 0.0 if L2 == 0 else max(0.0, min(1.0, ((p[0] - ax) * dx + (p[1] - ay) * dy) / L2))
        best = min(best, math.hypot(ax + t * dx - p[0], ay + t * dy - p[1]))
    return best


def contact_problems(root: ET.Element, precision: float) -> list[str]:
    """An involute pair's meshing sheet: the pitch point ``data-pitch-point`` of its detail must lie
    on both working profiles drawn (``data-working-profile`` 1 and 2): its distance from each
    polyline within 2·precision (P is a vertex of both, each rounded)."""
    out = []
    for g in root.iter(f"{_SVG}g"):
        if g.get("data-pitch-point") is None:
            continue
        xy = [_float(c) for c in g.get("data-pitch-point").split(",")]
        if len(xy) != 2 or None in xy:
            out.append(f"plan {g.get('id')}: data-pitch-point {g.get('data-pitch-point')!r} is not a paper x,y")
            continue
        flanks = {e.get("data-working-profile"): _path_points(e.get("d")) for e in root.iter(f"{_SVG}path")
                  if e.get("data-working-profile") is not None}
        for wheel in ("1", "2"):
            pts = flanks.get(wheel)
            if not pts or len(pts) < 2:
                out.append(f"plan {g.get('id')}: the working profile of wheel {wheel} is not drawn")
                continue
            dist = _distance_to_polyline((xy[0], xy[1]), pts)
            if not dist <= 2.0 * precision + 1e-9:
                out.append(f"plan {g.get('id')}: P is {dist:.4g} mm off the working profile of wheel {wheel} "
                           f"(tolerance {2.0 * precision:.2g} mm): the pair drawn does not touch at P")
    return out


def gear_problems(root: ET.Element, precision: float) -> list[str]:
    """The failures of the gear sheet's rays and scales (none when the file has no ``data-ray``
    and no angular-velocity picture), and of a meshing sheet's contact at P."""
    contact = contact_problems(root, precision)
    if contact or any(g.get("data-pitch-point") is not None for g in root.iter(f"{_SVG}g")):
        return contact
    pictures = [g for g in root.iter(f"{_SVG}g") if g.get("data-plan") == "gear-omega"]
    rays = [e for e in root.iter(f"{_SVG}line") if e.get("data-ray") is not None]
    if not rays and not pictures:
        return []
    r = 2.0 * math.sqrt(2.0) * precision
    out: list[str] = []
    poles: dict[ET.Element, tuple[float, float] | None] = {}
    for g in pictures:
        poles.update({ray: _pole(g) for ray in g.iter(f"{_SVG}line") if ray.get("data-ray") is not None})
        out += _scale_problems(root, g, precision)
    lines = {e.get("data-link-line"): _xy(e) for e in root.iter(f"{_SVG}line") if e.get("data-link-line")}
    heads = {}
    for e in root.iter(f"{_SVG}line"):
        q = e.get("data-quantity") or ""
        if q.startswith("omega:"):
            heads[q[len("omega:"):]] = _xy(e)
    for ray in rays:
        name = ray.get("data-ray")
        a, b = _xy(ray), lines.get(name)
        if a is None or any(not math.isfinite(c) for c in a):
            out.append(f"ray of {name}: its ends are not numbers")
            continue
        pole = poles.get(ray)
        if pole is None:
            out.append(f"ray of {name}: no pole to start from (it lies outside an angular-velocity picture "
                       "with data-pole=\"x y\")")
        elif math.hypot(a[0] - pole[0], a[1] - pole[1]) > 2 * r:
            out.append(f"ray of {name} starts {math.hypot(a[0] - pole[0], a[1] - pole[1]):.3g} mm from the pole "
                       f"(tol {2 * r:.1e} mm): a ray runs from the pole")
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


def _scale_problems(root: ET.Element, picture: ET.Element, precision: float) -> list[str]:
    """μω = μV/(μl·h) among the scales the sheet declares (see the module); h measured from the
    pole to the ω line (``data-construction="ω line"``) of ``picture``."""
    gid = picture.get("id") or ""
    ident = gid.removesuffix("-omega")
    groups = {g.get("id"): g for g in root.iter(f"{_SVG}g") if g.get("data-mu") is not None}
    side = groups.get(f"{ident}-scheme")
    speed = next((g for g in groups.values() if g.get("data-plan") == "gear-velocity"
                  and (g.get("id") or "").removesuffix("-velocity") == ident), None)
    what = f"angular-velocity picture {gid}"
    if side is None or side.get("data-plan") != "scheme" or speed is None:
        return [f"{what}: no side view ({ident}-scheme, data-plan=\"scheme\") and linear-velocity picture "
                f"({ident}-velocity) to state μl and μV: its scale μω = μV/(μl·h) cannot be verified"]
    mu_w, mu_l, mu_v = (_float(g.get("data-mu")) for g in (picture, side, speed))
    pole = _pole(picture)
    line = next((_xy(e) for e in picture.iter(f"{_SVG}line") if e.get("data-construction") == "ω line"), None)
    if None in (mu_w, mu_l, mu_v) or min(mu_w, mu_l, mu_v) <= 0.0:
        return []                       # a bad data-mu is told by the plan's own check
    if pole is None or line is None or any(not math.isfinite(c) for c in line):
        return [f"{what}: no pole (data-pole) or ω line (data-construction=\"ω line\") to measure h from"]
    x1, y1, x2, y2 = line
    span = math.hypot(x2 - x1, y2 - y1)
    if span <= 2.0 * math.sqrt(2.0) * precision:
        return [f"{what}: its ω line has no length to measure h from"]
    h = abs((x2 - x1) * (pole[1] - y1) - (y2 - y1) * (pole[0] - x1)) / span
    if h <= 2.0 * precision:
        return [f"{what}: the pole lies on the ω line (h = {h:.3g} mm)"]
    ratio = mu_w * mu_l * h / mu_v
    tol = 2.0 * precision / h + _SCALE_REL
    if abs(ratio - 1.0) > tol:
        return [f"{what}: its scales disagree: μω = {mu_w:g} where μV/(μl·h) = {mu_v:g}/({mu_l:g} × {h:.4g} mm) "
                f"= {mu_v / (mu_l * h):.6g} (rel. {ratio - 1.0:+.2e}, tol {tol:.1e}); μω = μV/(μl·h)"]
    return []

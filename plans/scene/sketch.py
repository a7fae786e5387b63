"""Readers of the sketch: ``[points]`` (metres, x right, y up), ``[links]`` (lists of point
names, ``"0"`` the frame), ``[[sliders]]`` (prismatic pairs and their guides) and
``[lengths]`` (exact distances between two points of one link, m); and the shortest dimension
they may give (:func:`check_dimensions`).

Imports only plans.errors and modules of plans.scene (and the standard library).
"""

from __future__ import annotations

import math
from typing import Any, Callable, Mapping

from ..errors import SceneError
from .checks import COORD_WHY, SHOW, entry_key, link_ref, name_of, number, quoted, sketch_size
from .values import FRAME, MAX_ANGLE_DEG, MAX_COORD_M, MIN_LENGTH_RATIO, MIN_SIZE_M, Slider


def read_points(table: Mapping[str, Any]) -> dict[str, tuple[float, float]]:
    """``[points]``: each sketch point NAME = [x, y], m; the sketch at least MIN_SIZE_M across."""
    if not table:
        raise SceneError("no points given; list the sketch points as NAME = [x, y] in metres", key="points")
    points: dict[str, tuple[float, float]] = {}
    for name, xy in table.items():
        key = entry_key("points", name)
        name_of(name, key, "point")
        if not isinstance(xy, list) or len(xy) != 2:
            raise SceneError(f"a point is [x, y] in metres, got {SHOW.repr(xy)}", key=key)
        points[name] = (number(xy[0], key, bound=MAX_COORD_M, why=COORD_WHY),
                        number(xy[1], key, bound=MAX_COORD_M, why=COORD_WHY))
    size = sketch_size(points)
    if 0.0 < size < MIN_SIZE_M:
        raise SceneError(f"the sketch is {size:.3g} m across; a mechanism must be at least {MIN_SIZE_M:g} m "
                         "across (draw it in metres)", key="points")
    return points


def read_links(table: Mapping[str, Any],
               points: Mapping[str, tuple[float, float]]) -> dict[str, tuple[str, ...]]:
    """``[links]``: each link a list of the point names it carries; the frame ``"0"`` among them,
    every point on a link."""
    if FRAME not in table:
        raise SceneError('no frame: add 0 = ["O", ...] listing the fixed points', key="links")
    links: dict[str, tuple[str, ...]] = {}
    for name, pts in table.items():
        key = entry_key("links", name)
        name_of(name, key, "link")
        if not isinstance(pts, list):
            raise SceneError(f'a link is a list of point names, e.g. ["A", "B"]; got {SHOW.repr(pts)}', key=key)
        for p in pts:
            if not isinstance(p, str):
                raise SceneError(f"point names are strings: write {quoted(p)}, got {SHOW.repr(p)}; a link is a "
                                 'list of point names, e.g. ["A", "B"]', key=key)
        if not pts:
            raise SceneError("link has no points; list at least one point it carries", key=key)
        for p in pts:
            if p not in points:
                raise SceneError(f"unknown point {p!r}; add it to [points] or fix the name", key=key)
        if len(set(pts)) != len(pts):
            raise SceneError("a point is listed twice in the same link", key=key)
        links[name] = tuple(pts)
    for p in points:
        if not any(p in pts for pts in links.values()):
            raise SceneError(f"point {p!r} belongs to no link; list it in a link or remove it", key=f"points.{p}")
    return links


def read_sliders(items: Any, points: Mapping[str, Any], links: Mapping[str, Any]) -> tuple[Slider, ...]:
    """``[[sliders]]``: the prismatic pairs, each with its guide defined in the sketch."""
    if not isinstance(items, list):
        raise SceneError("sliders must be an array of tables [[sliders]]", key="sliders")
    sliders = []
    for i, item in enumerate(items):
        key = f"sliders[{i}]"
        if not isinstance(item, Mapping):
            raise SceneError("each [[sliders]] entry must be a table", key=key)
        extra = sorted(str(k) for k in set(item) - {"link", "on", "through", "angle"})
        if extra:
            raise SceneError(f"unknown key {extra[0]!r}; a slider has link, on, through, angle", key=key)
        for k in ("link", "on", "through"):
            if k not in item:
                raise SceneError(f"missing {k!r}; a slider needs link, on and through (and angle for one point)",
                                 key=key)
        link = link_ref(item["link"], f"{key}.link", links)
        on = link_ref(item["on"], f"{key}.on", links)
        if link == on:
            raise SceneError("a link cannot slide on itself; `on` must name the guide's link", key=key)
        through = item["through"]
        through = (through,) if isinstance(through, str) else through
        if (not isinstance(through, (list, tuple)) or not 1 <= len(through) <= 2
                or not all(isinstance(p, str) for p in through)):
            raise SceneError('through is a point name or a list of two point names', key=f"{key}.through")
        for p in through:
            if p not in points:
                raise SceneError(f"unknown point {p!r}: the guide is undefined; name a point of [points]",
                                 key=f"{key}.through")
        angle = None
        if len(through) == 1:
            if "angle" not in item:
                raise SceneError("guide direction undefined: give angle (degrees) or through = [P, Q]",
                                 key=f"{key}.angle")
            angle = number(item["angle"], f"{key}.angle", bound=MAX_ANGLE_DEG,
                           why="° (a direction; write it within one turn, e.g. 30.0)")
        else:
            if "angle" in item:
                raise SceneError("give either through = [P, Q] or one point with angle, not both", key=key)
            (x1, y1), (x2, y2) = points[through[0]], points[through[1]]
            if math.hypot(x2 - x1, y2 - y1) == 0.0:
                raise SceneError(f"guide undefined: points {through[0]} and {through[1]} coincide in the sketch",
                                 key=f"{key}.through")
        sliders.append(Slider(link=link, on=on, through=tuple(through), angle=angle, index=i))
    return tuple(sliders)


def length_points(key: str, points: Mapping[str, Any]) -> list[tuple[str, str]]:
    """Every way a ``[lengths]`` key names two of ``points``: ``A-B`` split at its hyphen, ``AB``
    at each place where both sides are point names (the reader refuses none, or more than one)."""
    if "-" in key:
        parts = key.split("-")
        return [(parts[0], parts[1])] if len(parts) == 2 and all(p in points for p in parts) else []
    return [(key[:i], key[i:]) for i in range(1, len(key)) if key[:i] in points and key[i:] in points]


def read_lengths(table: Mapping[str, Any], points: Mapping[str, Any],
                 links: Mapping[str, tuple[str, ...]]) -> dict[frozenset[str], float]:
    """``[lengths]``: AB or A-B = a distance (m) between two points of one link, none shorter
    than MIN_LENGTH_RATIO of the longest link dimension (:func:`_shortest`)."""
    lengths: dict[frozenset[str], float] = {}
    written: dict[frozenset[str], str] = {}
    for key, value in table.items():
        full = f"lengths.{key}"
        pairs = length_points(key, points)
        if not pairs:
            raise SceneError(f"{key!r} does not name two points; write e.g. AB or A-B with names from [points]",
                             key=full)
        if len(pairs) > 1:
            raise SceneError(f"{key!r} splits into points in more than one way; write it as P-Q", key=full)
        a, b = pairs[0]
        if a == b:
            raise SceneError("a length needs two different points", key=full)
        if not any(a in pts and b in pts for pts in links.values()):
            raise SceneError(f"{a} and {b} are not on one link, so their distance is not a link length", key=full)
        pair = frozenset((a, b))
        if pair in lengths:
            raise SceneError(f"length {a}{b} given twice", key=full)
        lengths[pair] = number(value, full, positive=True, bound=MAX_COORD_M, why=COORD_WHY)
        written[pair] = full
    bound, why = _shortest(points, links, lengths)
    for pair, d in lengths.items():
        if d < bound:
            raise SceneError(f"{why(d)}; give the link a real length, or make the two points one", key=written[pair])
    return lengths


def _shortest(points: Mapping[str, tuple[float, float]], links: Mapping[str, tuple[str, ...]],
              lengths: Mapping[frozenset[str], float]) -> tuple[float, Callable[[float], str]]:
    """The shortest dimension allowed (m): MIN_LENGTH_RATIO of the mechanism's longest (the
    largest distance between two points of one link, given in [lengths] or sketched; not the
    sketch's extent, which a block's point far out where two guides meet would set), and the
    words that say why a distance ``d`` is refused."""
    longest = max([math.dist(points[a], points[b]) for pts in links.values() for i, a in enumerate(pts)
                   for b in pts[i + 1:]] + list(lengths.values()), default=0.0)
    bound = MIN_LENGTH_RATIO * longest

    def why(d: float) -> str:
        return (f"{d:.3g} m is shorter than {bound:.3g} m, {MIN_LENGTH_RATIO:g} of the mechanism's longest link "
                f"dimension ({longest:.4g} m), beyond what can be drawn or computed reliably")
    return bound, why


def check_dimensions(points: Mapping[str, tuple[float, float]], links: Mapping[str, tuple[str, ...]],
                     sliders: tuple[Slider, ...], lengths: Mapping[frozenset[str], float]) -> None:
    """Refuse two points of one link that (nearly) coincide in the sketch, the link's directions
    coming from there, and a guide through = [P, Q] with P and Q that close: closer than the
    shortest dimension allowed (:func:`_shortest`; [lengths] values are checked as they are read).
    Points of different links may coincide: a pin over a pivot is a position, not a dimension."""
    bound, why = _shortest(points, links, lengths)
    for name, pts in links.items():
        for i, a in enumerate(pts):
            for b in pts[i + 1:]:
                d = math.dist(points[a], points[b])
                if d < bound:
                    raise SceneError(f"points {a} and {b} (nearly) coincide in the sketch: {why(d)}; draw them "
                                     "apart (a link's directions come from its sketch), or use one point",
                                     key=entry_key("links", name))
    for s in sliders:
        if len(s.through) == 2 and math.dist(*(points[p] for p in s.through)) < bound:
            raise SceneError(f"the guide through {s.through[0]} and {s.through[1]} is undefined: "
                             f"{why(math.dist(*(points[p] for p in s.through)))}; draw the points apart or give one "
                             "point and an angle", key=f"{s.key}.through")

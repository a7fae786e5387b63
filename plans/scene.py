"""Scene files: the TOML description of a mechanism, read and validated.

A scene gives a reference sketch (points in metres, x right, y up), the links as lists of
point names (``"0"`` is the frame), prismatic pairs (``[[sliders]]``), the drive, optional
exact lengths, scales and what to draw. Reading a scene checks every key and value and
raises :class:`~plans.errors.SceneError` naming the key and the fix; nothing is solved here.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

from .errors import SceneError

__all__ = ["Scene", "Slider", "Drive", "read_scene", "parse_scene", "FRAME", "DRAWABLE"]

FRAME = "0"
DRAWABLE = ("scheme", "velocity", "acceleration", "centres")
#: What a scene draws when [plans] says nothing.
DEFAULT_DRAW = ("scheme", "velocity", "acceleration")
_TOP_KEYS = {"title", "description", "points", "links", "sliders", "drive", "lengths", "plans", "scales"}


@dataclass(frozen=True)
class Slider:
    """A prismatic pair: link ``link`` slides along a line fixed in link ``on``.

    ``through`` holds one point name (then ``angle`` is the line's direction in degrees)
    or two point names (the line through both sketch points, directed first → second).
    """

    link: str
    on: str
    through: tuple[str, ...]
    angle: float | None
    index: int

    @property
    def key(self) -> str:
        return f"sliders[{self.index}]"


@dataclass(frozen=True)
class Drive:
    """The driving link and its law of motion.

    ``kind`` is ``"rotary"`` (``values`` are angles in degrees, ``speed`` ω in rad/s,
    ``rate`` ε in rad/s², CCW positive) or ``"linear"`` (a slider on the frame; ``values``
    are displacements in metres along its guide from the sketch position, ``speed`` in
    m/s, ``rate`` in m/s²).
    """

    link: str
    kind: str
    values: tuple[float, ...]
    speed: float
    rate: float

    @property
    def unit(self) -> str:
        return "deg" if self.kind == "rotary" else "m"


@dataclass(frozen=True)
class Scene:
    """A validated scene. ``lengths`` maps an unordered point pair to a distance in metres."""

    title: str
    points: Mapping[str, tuple[float, float]]
    links: Mapping[str, tuple[str, ...]]
    sliders: tuple[Slider, ...]
    drive: Drive
    lengths: Mapping[frozenset[str], float] = field(default_factory=dict)
    draw: tuple[str, ...] = DEFAULT_DRAW
    scales: Mapping[str, float] = field(default_factory=dict)
    description: str = ""
    file: str | None = None

    def links_of(self, point: str) -> tuple[str, ...]:
        """Names of the links that carry ``point``, in scene order."""
        return tuple(name for name, pts in self.links.items() if point in pts)


def read_scene(path: str | Path) -> Scene:
    """Read and validate a scene file; errors name the file and the key."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SceneError("no such scene file; check the path", file=str(path)) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise SceneError(f"cannot read the file ({exc.__class__.__name__}); it must be UTF-8 TOML",
                         file=str(path)) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(f"malformed TOML: {exc}; fix the syntax there", file=str(path)) from None
    try:
        return parse_scene(data, file=str(path))
    except SceneError as exc:
        raise exc.in_file(str(path)) from None


def parse_scene(data: Mapping[str, Any], *, file: str | None = None) -> Scene:
    """Validate a scene already loaded from TOML (a mapping) and build a :class:`Scene`."""
    unknown = sorted(set(data) - _TOP_KEYS)
    if unknown:
        raise SceneError(f"unknown top-level key {unknown[0]!r}; allowed: {', '.join(sorted(_TOP_KEYS))}",
                         key=unknown[0])
    title = data.get("title", "")
    if not isinstance(title, str):
        raise SceneError("title must be a string", key="title")
    description = data.get("description", "")
    if not isinstance(description, str):
        raise SceneError("description must be a string", key="description")
    points = _points(_table(data, "points", required=True))
    links = _links(_table(data, "links", required=True), points)
    sliders = _sliders(data.get("sliders", []), points, links)
    drive = _drive(_table(data, "drive", required=True), links, sliders)
    lengths = _lengths(_table(data, "lengths"), points, links)
    draw = _draw(_table(data, "plans"))
    scales = _scales(_table(data, "scales"))
    return Scene(title=title or "Mechanism", points=points, links=links, sliders=sliders, drive=drive,
                 lengths=lengths, draw=draw, scales=scales, description=description, file=file)


# --- helpers -----------------------------------------------------------------------------

def _table(data: Mapping[str, Any], key: str, *, required: bool = False) -> Mapping[str, Any]:
    if key not in data:
        if required:
            raise SceneError(f"missing table [{key}]; every scene needs [points], [links] and [drive]", key=key)
        return {}
    value = data[key]
    if not isinstance(value, Mapping):
        raise SceneError(f"[{key}] must be a table", key=key)
    return value


def _number(value: Any, key: str, *, positive: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise SceneError(f"expected a number, got {value!r}", key=key)
    x = float(value)
    if not math.isfinite(x):
        raise SceneError(f"{value!r} is not a finite number; give a real value", key=key)
    if positive and x <= 0.0:
        raise SceneError(f"must be positive, got {x:g}", key=key)
    return x


def _points(table: Mapping[str, Any]) -> dict[str, tuple[float, float]]:
    if not table:
        raise SceneError("no points given; list the sketch points as NAME = [x, y] in metres", key="points")
    points: dict[str, tuple[float, float]] = {}
    for name, xy in table.items():
        key = f"points.{name}"
        if not isinstance(xy, list) or len(xy) != 2:
            raise SceneError(f"a point is [x, y] in metres, got {xy!r}", key=key)
        points[name] = (_number(xy[0], key), _number(xy[1], key))
    return points


def _links(table: Mapping[str, Any], points: Mapping[str, tuple[float, float]]) -> dict[str, tuple[str, ...]]:
    if FRAME not in table:
        raise SceneError('no frame: add 0 = ["O", ...] listing the fixed points', key="links")
    links: dict[str, tuple[str, ...]] = {}
    for name, pts in table.items():
        key = f"links.{name}"
        if not isinstance(pts, list) or not all(isinstance(p, str) for p in pts):
            raise SceneError(f'a link is a list of point names, e.g. ["A", "B"]; got {pts!r}', key=key)
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


def _sliders(items: Any, points: Mapping[str, Any], links: Mapping[str, Any]) -> tuple[Slider, ...]:
    if not isinstance(items, list):
        raise SceneError("sliders must be an array of tables [[sliders]]", key="sliders")
    sliders = []
    for i, item in enumerate(items):
        key = f"sliders[{i}]"
        if not isinstance(item, Mapping):
            raise SceneError("each [[sliders]] entry must be a table", key=key)
        extra = sorted(set(item) - {"link", "on", "through", "angle"})
        if extra:
            raise SceneError(f"unknown key {extra[0]!r}; a slider has link, on, through, angle", key=key)
        for k in ("link", "on", "through"):
            if k not in item:
                raise SceneError(f"missing {k!r}; a slider needs link, on and through (and angle for one point)",
                                 key=key)
        link, on = item["link"], item["on"]
        for k, v in (("link", link), ("on", on)):
            if not isinstance(v, str) or v not in links:
                raise SceneError(f"unknown link {v!r}; use a name from [links]", key=f"{key}.{k}")
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
            angle = _number(item["angle"], f"{key}.angle")
        else:
            if "angle" in item:
                raise SceneError("give either through = [P, Q] or one point with angle, not both", key=key)
            (x1, y1), (x2, y2) = points[through[0]], points[through[1]]
            if math.hypot(x2 - x1, y2 - y1) == 0.0:
                raise SceneError(f"guide undefined: points {through[0]} and {through[1]} coincide in the sketch",
                                 key=f"{key}.through")
        sliders.append(Slider(link=link, on=on, through=tuple(through), angle=angle, index=i))
    return tuple(sliders)


def _drive(table: Mapping[str, Any], links: Mapping[str, Any], sliders: tuple[Slider, ...]) -> Drive:
    link = table.get("link")
    if not isinstance(link, str) or link not in links:
        raise SceneError(f"unknown driving link {link!r}; name a link of [links]", key="drive.link")
    if link == FRAME:
        raise SceneError("the frame cannot be the driving link", key="drive.link")
    rotary_keys, linear_keys = {"angle", "omega", "epsilon"}, {"displacement", "velocity", "acceleration"}
    extra = sorted(set(table) - rotary_keys - linear_keys - {"link"})
    if extra:
        raise SceneError(f"unknown key {extra[0]!r}", key=f"drive.{extra[0]}")
    if set(table) & rotary_keys and set(table) & linear_keys:
        raise SceneError("mixes a rotary drive (angle, omega) with a linear one (displacement, velocity)",
                         key="drive")
    if "displacement" in table or "velocity" in table:
        kind, pos_key, speed_key, rate_key = "linear", "displacement", "velocity", "acceleration"
        if not any(s.link == link and s.on == FRAME for s in sliders):
            raise SceneError(f"a linear drive needs link {link} to slide on the frame: add a [[sliders]] "
                             f'with link = "{link}", on = "0"', key="drive.link")
    else:
        kind, pos_key, speed_key, rate_key = "rotary", "angle", "omega", "epsilon"
    if pos_key not in table:
        raise SceneError(f"missing {pos_key}", key=f"drive.{pos_key}")
    raw = table[pos_key]
    raw_list = raw if isinstance(raw, list) else [raw]
    if not raw_list:
        raise SceneError(f"{pos_key} list is empty; give at least one value", key=f"drive.{pos_key}")
    values = tuple(_number(v, f"drive.{pos_key}") for v in raw_list)
    if len(set(values)) != len(values):
        raise SceneError(f"{pos_key} list repeats a value", key=f"drive.{pos_key}")
    if speed_key not in table:
        raise SceneError(f"missing {speed_key}", key=f"drive.{speed_key}")
    speed = _number(table[speed_key], f"drive.{speed_key}")
    rate = _number(table.get(rate_key, 0.0), f"drive.{rate_key}")
    return Drive(link=link, kind=kind, values=values, speed=speed, rate=rate)


def _lengths(table: Mapping[str, Any], points: Mapping[str, Any],
             links: Mapping[str, tuple[str, ...]]) -> dict[frozenset[str], float]:
    lengths: dict[frozenset[str], float] = {}
    for key, value in table.items():
        full = f"lengths.{key}"
        if "-" in key:
            parts = key.split("-")
            pairs = [tuple(parts)] if len(parts) == 2 and all(p in points for p in parts) else []
        else:
            pairs = [(key[:i], key[i:]) for i in range(1, len(key)) if key[:i] in points and key[i:] in points]
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
        lengths[pair] = _number(value, full, positive=True)
    return lengths


def _draw(table: Mapping[str, Any]) -> tuple[str, ...]:
    extra = sorted(set(table) - {"draw"})
    if extra:
        raise SceneError(f"unknown key {extra[0]!r}; [plans] has draw", key=f"plans.{extra[0]}")
    draw = table.get("draw", list(DEFAULT_DRAW))
    if not isinstance(draw, list) or not draw:
        raise SceneError(f"draw is a non-empty list of {', '.join(DRAWABLE)}", key="plans.draw")
    for item in draw:
        if item not in DRAWABLE:
            raise SceneError(f"cannot draw {item!r}; choose from {', '.join(DRAWABLE)}", key="plans.draw")
    return tuple(d for d in DRAWABLE if d in draw)


def _scales(table: Mapping[str, Any]) -> dict[str, float]:
    allowed = ("mu_l", "mu_v", "mu_a")
    out = {}
    for key, value in table.items():
        if key not in allowed:
            raise SceneError(f"unknown scale {key!r}; use mu_l, mu_v or mu_a", key=f"scales.{key}")
        out[key] = _number(value, f"scales.{key}", positive=True)
    return out

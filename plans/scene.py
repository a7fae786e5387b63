"""Scene files: the TOML description of a mechanism, read and validated.

A scene gives a reference sketch (points in metres, x right, y up), the links as lists of
point names (``"0"`` is the frame), prismatic pairs (``[[sliders]]``), the drive, optional
exact lengths, scales and what to draw. Reading a scene checks every key and value and
raises :class:`~plans.errors.SceneError` naming the key and the fix; nothing is solved here.
"""

from __future__ import annotations

import math
import re
import reprlib
import tomllib
from enum import StrEnum
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Iterator, Mapping

from .errors import SceneError

__all__ = ["Scene", "Slider", "Drive", "Cycle", "Mass", "AppliedForce", "AppliedMoment", "Balance", "read_scene", "parse_scene", "FRAME", "DRAWABLE", "MAX_COORD_M", "MIN_SIZE_M",
           "MAX_ANGLE_DEG", "MAX_WALK_STEPS", "MAX_POSITIONS", "MAX_OMEGA", "MAX_EPSILON", "MAX_SPEED",
           "MAX_ACCELERATION", "MIN_RATE", "MAX_TITLE_CHARS"]

FRAME = "0"
DRAWABLE = ("scheme", "velocity", "acceleration", "centres", "positions", "diagrams", "velocities", "forces", "lever")
#: What needs the force analysis (kinetostatics): the force plans and Zhukovsky's lever.
FORCE_SHEETS = ("forces", "lever")
#: Sheets of the whole cycle: they need ``[drive] positions = N``.
CYCLE_SHEETS = ("positions", "diagrams", "velocities")
#: Fewest and most positions of a cycle (``[drive] positions``): three chords at least for the
#: graphical differentiation; one a degree at most (as MAX_POSITIONS).
MIN_CYCLE_POSITIONS = 3
#: Most positions whose velocity plans share one sheet (``draw = ["velocities"]``): 24 plans
#: on an A3 sheet are about 60 mm each, still readable.
MAX_VELOCITY_PLANS = 24
#: How the cycle's first position is chosen (``[drive] start``).
CYCLE_STARTS = ("angle", "extreme")
#: What a scene draws when [plans] says nothing.
DEFAULT_DRAW = ("scheme", "velocity", "acceleration")
_TOP_KEYS = {"title", "description", "points", "links", "sliders", "drive", "lengths", "plans", "scales",
             "masses", "forces", "moments", "gravity", "balance"}

# --- bounds of what a scene may ask for ------------------------------------------------------
#: Largest |coordinate| of a sketch point and largest length, m. Real linkages measure metres to
#: tens of metres, but a construction point where two nearly parallel guides meet lies about
#: size/angle away: 1e-13° from parallel that is ~1e16 m for a 1 m mechanism (the property tests
#: sketch such points). 1e20 m allows them and keeps ω·r ≤ 1e26 m/s, ω²·r ≤ 1e32 m/s² and their
#: squares (≤ 1e64, vector lengths are square roots of sums of squares) far from overflow (1e308);
#: a mechanism scaled by 1e300, or a coordinate of 1e308, is refused.
MAX_COORD_M = 1e20
#: Smallest size of the sketch (its bounding-box diagonal), m: finer than any micro-mechanism,
#: and the scale of the scheme is chosen for extents of at least 1e-6 m (extent_of).
MIN_SIZE_M = 1e-6
#: Largest |drive angle| and |guide angle|, degrees (about 2800 turns). Doubles near 1e6 are
#: 1.2e-10° apart, so reducing the angle by whole turns stays exact far beyond drawing precision;
#: near 1e20 neighbouring doubles are 16000° apart and the angle drawn would not be the one asked.
MAX_ANGLE_DEG = 1e6
#: Most continuation steps the solver may walk: it walks from the sketch to every requested value
#: in 1° steps (a linear drive: size/200, see kinematics/solve.py ``_grid``), keeping every step's
#: pose. A class III group costs ~4 ms a step, so 7200 steps (20 turns: every position a crank
#: can take, many times over) take about 30 s; a class II mechanism, well under a second.
MAX_WALK_STEPS = 7200
#: The continuation walk's steps (kinematics/solve.py ``_grid``), here so that the bound above
#: and the solver read the same numbers: a crank steps STEP_DEG, a slider size/LINEAR_STEPS_PER_SIZE.
STEP_DEG = 1.0
LINEAR_STEPS_PER_SIZE = 200.0
#: Most drive positions in one scene: one a degree over a turn; each writes up to five sheets.
MAX_POSITIONS = 360
#: Largest |ω| of a crank, rad/s (ultracentrifuges turn at ~1e4 rad/s); with lengths up to
#: MAX_COORD_M every velocity and acceleration, and its square, is an ordinary double.
MAX_OMEGA = 1e6
#: Largest |ε| of a crank, rad/s² (ω² at MAX_OMEGA).
MAX_EPSILON = 1e12
#: Largest |velocity| of a linear drive, m/s (as ω·r at MAX_OMEGA and r = 1 m).
MAX_SPEED = 1e6
#: Largest |acceleration| of a linear drive, m/s² (as ω²·r at MAX_OMEGA and r = 1 m).
MAX_ACCELERATION = 1e12
#: Smallest nonzero |ω| or |velocity| of the drive (rad/s, m/s): one turn in 200 years. Smaller
#: speeds give velocities whose squares underflow (|v|² < 1e-308 when |v| < 1e-154), so the
#: plans' vector lengths would read 0; 0 itself is allowed (the mechanism at rest). The same bound
#: holds for ε (or the drive's acceleration) of a drive at rest, then the only source of motion.
MIN_RATE = 1e-9
#: Longest title, characters: it is one line of every sheet's title block, shrunk to fit down to
#: 2 mm text and cut short with "…" beyond that (about 130 characters); the whole title stays
#: in the SVG's <title> and in the JSON report.
MAX_TITLE_CHARS = 200
#: Largest |force| (N), |moment| (N·m), mass (kg), moment of inertia (kg·m²) and |g| (m/s²) a
#: scene may give: far beyond any machine, and with coordinates up to MAX_COORD_M and
#: accelerations up to ω²·r their products (m·a·r ≤ 1e20·1e32·1e20) stay ordinary doubles.
MAX_LOAD = 1e20

#: Values shown in error messages are abbreviated (a nested or huge value stays one short line).
_SHOW = reprlib.Repr()
_SHOW.maxlevel, _SHOW.maxstring, _SHOW.maxother, _SHOW.maxlist = 3, 60, 60, 6


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


class DriveKind(StrEnum):
    """How the drive moves: a crank turning about a frame pivot, a slider on a frame guide,
    a link not pivoted on the frame whose absolute angle is given (a coupler), or a linear
    motor between two moving links (a hydraulic cylinder: the rod slides in the cylinder)."""

    ROTARY = "rotary"
    LINEAR = "linear"
    COUPLER = "coupler"
    CYLINDER = "cylinder"

    @property
    def angular(self) -> bool:
        """True when the drive's values are angles (degrees; ω, ε), False for strokes (m; v, a)."""
        return self in (DriveKind.ROTARY, DriveKind.COUPLER)

    @property
    def unit(self) -> str:
        return "deg" if self.angular else "m"


@dataclass(frozen=True)
class Drive:
    """The driving link and its law of motion.

    ``kind`` is :attr:`DriveKind.ROTARY` or :attr:`DriveKind.COUPLER` (``values`` are angles in
    degrees, ``speed`` ω in rad/s, ``rate`` ε in rad/s², CCW positive; a coupler's angle is its
    absolute angle, of the line from its first point to its second) or :attr:`DriveKind.LINEAR` /
    :attr:`DriveKind.CYLINDER` (``values`` are displacements in metres of the link along its
    guide from the sketch position, ``speed`` in m/s, ``rate`` in m/s²; the guide is on the frame,
    or on link ``along`` for a cylinder, and the motion is relative to it).
    """

    link: str
    kind: DriveKind
    values: tuple[float, ...]
    speed: float
    rate: float
    along: str = FRAME

    @property
    def unit(self) -> str:
        return self.kind.unit


@dataclass(frozen=True)
class Cycle:
    """One revolution of a crank in ``positions`` equal steps (``[drive] positions = N``).

    ``start`` is ``"angle"`` (the first position is the drive's ``angle``) or ``"extreme"``
    (the first position is the one where the output link's displacement, or angle, is
    smallest: found by the kinematics). ``output`` names the output link (``[plans] output``,
    by default the last moving link); ``trace`` the points whose trajectories are drawn; ``at``
    the position numbers (0 … N−1) drawn on sheets of their own (scheme, plans, centres) — all of
    them when ``[plans] at`` is not given."""

    positions: int
    start: str = "angle"
    output: str = ""
    trace: tuple[str, ...] = ()
    at: tuple[int, ...] = ()


@dataclass(frozen=True)
class Mass:
    """The inertia of a moving link (``[masses.NAME]``): ``mass`` (kg), ``inertia`` (kg·m²,
    about the centre of mass, perpendicular to the plane) and ``centre``, the name of the
    link's point at its centre of mass."""

    link: str
    mass: float
    inertia: float
    centre: str


@dataclass(frozen=True)
class AppliedForce:
    """An external force (``[[forces]]``) on ``link`` at its point ``at``: ``vector`` (N) in
    the fixed x, y frame, the same at every position. ``index`` is its place in the list."""

    link: str
    at: str
    vector: tuple[float, float]
    index: int


@dataclass(frozen=True)
class AppliedMoment:
    """An external couple (``[[moments]]``) on ``link``: ``value`` (N·m, CCW positive)."""

    link: str
    value: float
    index: int


@dataclass(frozen=True)
class Balance:
    """The balancing element on the driving link (``[balance]``): ``kind`` ``"moment"`` (a
    couple on the link), ``"force"`` (a force at its point ``at`` along the line at ``angle``°
    drawn in the sketch, which turns with the link as a slider's guide angle does) or
    ``"actuator"`` (a hydraulic cylinder's force along its guide: on the rod, and opposite on
    the cylinder). ``given``: False when the scene has no [balance] (the default element)."""

    link: str
    kind: str
    at: str | None = None
    angle: float | None = None
    given: bool = True


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
    senses: bool = False          # the scheme shows the senses of ω and ε of every moving link
    description: str = ""
    file: str | None = None
    cycle: Cycle | None = None    # [drive] positions = N: the whole revolution (cycle sheets)
    masses: Mapping[str, Mass] = field(default_factory=dict)      # link → its mass, inertia, centre
    forces: tuple[AppliedForce, ...] = ()
    moments: tuple[AppliedMoment, ...] = ()
    gravity: float | None = None  # g (m/s², acting −y) when given, else no gravity
    balance: Balance | None = None  # the balancing element when forces are computed

    @property
    def wants_forces(self) -> bool:
        """Whether the force analysis runs: the force plans or the lever are drawn, or a
        [balance] is given."""
        return bool(set(FORCE_SHEETS) & set(self.draw)) or (self.balance is not None and self.balance.given)

    @property
    def wants_inertia(self) -> bool:
        """Whether the force analysis needs accelerations (a link has a mass or an inertia)."""
        return self.wants_forces and any(m.mass > 0.0 or m.inertia > 0.0 for m in self.masses.values())

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
    except RecursionError:   # the reader recurses once per level of nesting
        depth, where = _nesting(text)
        raise SceneError(f"values nested {depth} deep (more than the TOML reader can follow); a scene nests "
                         "at most a list in a table, e.g. A = [0.1, 0.2]", file=str(path),
                         key=_key_at(text, where)) from None
    except ValueError:   # not a TOMLDecodeError: an integer of more than 4300 digits
        match = _LONG_NUMBER.search(text)
        raise SceneError("a number with thousands of digits cannot be read; write an ordinary number, e.g. 10.0",
                         file=str(path), key=_key_at(text, match.start() if match else 0)) from None
    try:
        return parse_scene(data, file=str(path))
    except SceneError as exc:
        raise exc.in_file(str(path)) from None


#: A run of digits longer than Python converts to an int (4300 digits).
_LONG_NUMBER = re.compile(r"[0-9_]{4300,}")
#: A key (bare, quoted or dotted) at the start of a line, followed by "=".
_PART = r"""(?:[A-Za-z0-9_-]+|"[^"\n]*"|'[^'\n]*')"""
_BARE_KEY = re.compile(rf"\s*({_PART}(?:\s*\.\s*{_PART})*)\s*=")
#: A table header [name] or [[name]] on a line of its own.
_HEADER = re.compile(rf"\s*\[\[?\s*({_PART}(?:\s*\.\s*{_PART})*)\s*\]\]?\s*(#.*)?$")


def _nesting(text: str) -> tuple[int, int]:
    """Deepest nesting of arrays and inline tables in TOML ``text`` and the offset of the value
    (just after its ``=``) that reaches it; strings and comments are skipped, and a table header
    (a ``[`` opening a line outside any value) is not a value. Used only when the TOML reader
    gave up (RecursionError), to name the key."""
    depth = best = where = start = 0
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if c in "\"'":
            quote = text[i:i + 3] if text[i:i + 3] in ('"""', "'''") else c
            j = i + len(quote)
            while j < n and not text.startswith(quote, j):
                j += 2 if c == '"' and text[j] == "\\" else 1
            i, line_start = j + len(quote), False
            continue
        if c == "#":
            while i < n and text[i] != "\n":
                i += 1
            continue
        if c == "\n":
            line_start = True
        elif c == "=" and depth == 0:
            start, line_start = i + 1, False
        elif c in "[{":
            if depth == 0 and line_start and c == "[":     # a table header: skip its line
                while i < n and text[i] != "\n":
                    i += 1
                continue
            depth += 1
            if depth > best:
                best, where = depth, start
        elif c in "]}":
            depth = max(depth - 1, 0)
        elif not c.isspace():
            line_start = False
        i += 1
    return best, where


def _key_at(text: str, offset: int) -> str:
    """The dotted key of the TOML statement around ``offset`` (its table and its own key)."""
    table, key = "", ""
    for line in text[:offset + 1].splitlines() or [""]:
        header = _HEADER.match(line)
        if header:
            table, key = _unquote(header.group(1)), ""
            continue
        bare = _BARE_KEY.match(line)
        if bare:
            key = _unquote(bare.group(1))
    return ".".join(part for part in (table, key) if part) or "(top level)"


def _unquote(dotted: str) -> str:
    """``a."b.c"`` → ``a.b.c``: the parts of a dotted TOML key without their quotes."""
    return ".".join(part.strip("\"'") for part in re.findall(_PART, dotted))


def parse_scene(data: Mapping[str, Any], *, file: str | None = None) -> Scene:
    """Validate a scene already loaded from TOML (a mapping) and build a :class:`Scene`;
    errors name ``file`` (when given) and the key."""
    try:
        return _parse(data, file)
    except SceneError as exc:
        if file is None or exc.file:
            raise
        raise exc.in_file(file) from None


def _parse(data: Mapping[str, Any], file: str | None) -> Scene:
    if not isinstance(data, Mapping):
        raise SceneError(f"a scene is a TOML document of tables, got {_SHOW.repr(data)}", key="(top level)")
    unknown = sorted(str(k) for k in set(data) - _TOP_KEYS)
    if unknown:
        raise SceneError(f"unknown top-level key {unknown[0]!r}; allowed: {', '.join(sorted(_TOP_KEYS))}",
                         key=unknown[0])
    title = _text(data.get("title", ""), "title", line=True)
    if len(title) > MAX_TITLE_CHARS:
        raise SceneError(f"title has {len(title)} characters; it is one line at the top of every sheet, keep it "
                         f"within {MAX_TITLE_CHARS} (put the rest in description)", key="title")
    description = _text(data.get("description", ""), "description", line=False)
    points = _points(_table(data, "points", required=True))
    links = _links(_table(data, "links", required=True), points)
    sliders = _sliders(data.get("sliders", []), points, links)
    drive_table = _table(data, "drive", required=True)
    cycle_keys = {k: drive_table[k] for k in ("positions", "start") if k in drive_table}
    drive = _drive({k: v for k, v in drive_table.items() if k not in cycle_keys}, links, sliders, points,
                   cycle=cycle_keys)
    lengths = _lengths(_table(data, "lengths"), points, links)
    plans_table = _table(data, "plans")
    draw, senses = _draw({k: v for k, v in plans_table.items() if k not in ("output", "trace", "at")})
    cycle = _cycle(cycle_keys, drive, plans_table, draw, points, links)
    scales = _scales(_table(data, "scales"))
    masses = _masses(_table(data, "masses"), links)
    forces = _forces(data.get("forces", []), links)
    moments = _moments(data.get("moments", []), links)
    gravity = _number(data["gravity"], "gravity", bound=MAX_LOAD, why=" m/s²") if "gravity" in data else None
    balance = _balance(data["balance"] if "balance" in data else None, drive, links, points)
    return Scene(title=title or "Mechanism", points=points, links=links, sliders=sliders, drive=drive,
                 lengths=lengths, draw=draw, senses=senses, scales=scales, description=description, file=file,
                 cycle=cycle, masses=masses, forces=forces, moments=moments, gravity=gravity, balance=balance)


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


def _xml_invalid(c: str, *, line: bool) -> bool:
    """Whether character ``c`` cannot appear in the SVG text (XML 1.0 forbids C0 controls but
    tab, LF, CR; U+FFFE, U+FFFF; lone surrogates) or is an invisible control (DEL, C1); with
    ``line`` (a name or a title: one line of a drawing) tab, LF and CR too."""
    o = ord(c)
    if c in "\t\n\r":
        return line
    return o < 0x20 or 0x7F <= o <= 0x9F or 0xD800 <= o <= 0xDFFF or o in (0xFFFE, 0xFFFF)


def _text(value: Any, key: str, *, line: bool) -> str:
    """A title, description or name: a string of characters a drawing can hold."""
    if not isinstance(value, str):
        raise SceneError(f"{key.split('.')[0]} must be a string, got {_SHOW.repr(value)}", key=key)
    bad = next((c for c in value if _xml_invalid(c, line=line)), None)
    if bad is not None:
        what = "control character" if ord(bad) < 0xD800 else "character"
        raise SceneError(f"contains the {what} U+{ord(bad):04X}, which an SVG drawing cannot hold; remove it"
                         + (" (write a name or a title on one line)" if bad in "\t\n\r" else ""), key=key)
    return value


def _name(value: Any, key: str, what: str) -> str:
    """A point or link name: a non-empty one-line string."""
    if not isinstance(value, str):
        raise SceneError(f"{what} names are strings: write {_quoted(value)}, got {_SHOW.repr(value)}", key=key)
    if not value.strip():
        raise SceneError(f"empty {what} name {value!r}; give the {what} a name, e.g. \"A\"", key=key)
    return _text(value, key, line=True)


def _quoted(value: Any) -> str:
    """``value`` written as a TOML string, for messages (1 → "1")."""
    return f'"{value}"' if isinstance(value, (int, float)) and not isinstance(value, bool) else '"NAME"'


def _number(value: Any, key: str, *, positive: bool = False, bound: float | None = None, why: str = "") -> float:
    """A finite number; ``bound`` (SI) limits its magnitude, ``why`` says where the bound comes from."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise SceneError(f"expected a number, got {_SHOW.repr(value)}", key=key)
    try:
        x = float(value)
    except OverflowError:       # an integer beyond the largest double
        x = math.inf if value > 0 else -math.inf
    if not math.isfinite(x):
        raise SceneError(f"{_SHOW.repr(value)} is not a finite number; give a real value", key=key)
    if positive and x <= 0.0:
        raise SceneError(f"must be positive, got {x:g}", key=key)
    if bound is not None and abs(x) > bound:
        raise SceneError(f"{x:g} is out of range: |value| ≤ {bound:g}{why}", key=key)
    return x


_COORD_WHY = " m (far beyond any linkage; keeps the arithmetic far from overflow)"


def _points(table: Mapping[str, Any]) -> dict[str, tuple[float, float]]:
    if not table:
        raise SceneError("no points given; list the sketch points as NAME = [x, y] in metres", key="points")
    points: dict[str, tuple[float, float]] = {}
    for name, xy in table.items():
        key = _key("points", name)
        _name(name, key, "point")
        if not isinstance(xy, list) or len(xy) != 2:
            raise SceneError(f"a point is [x, y] in metres, got {_SHOW.repr(xy)}", key=key)
        points[name] = (_number(xy[0], key, bound=MAX_COORD_M, why=_COORD_WHY),
                        _number(xy[1], key, bound=MAX_COORD_M, why=_COORD_WHY))
    size = _size(points)
    if 0.0 < size < MIN_SIZE_M:
        raise SceneError(f"the sketch is {size:.3g} m across; a mechanism must be at least {MIN_SIZE_M:g} m "
                         "across (draw it in metres)", key="points")
    return points


def _key(table: str, name: str) -> str:
    """The dotted key of entry ``name`` of ``table`` (an empty name shown as "")."""
    return f"{table}.{name}" if name else f'{table}.""'


def _size(points: Mapping[str, tuple[float, float]]) -> float:
    """The sketch's bounding-box diagonal, m (the mechanism's size, as in model.Mechanism.size)."""
    xs, ys = [p[0] for p in points.values()], [p[1] for p in points.values()]
    return math.hypot(max(xs) - min(xs), max(ys) - min(ys)) if points else 0.0


def _links(table: Mapping[str, Any], points: Mapping[str, tuple[float, float]]) -> dict[str, tuple[str, ...]]:
    if FRAME not in table:
        raise SceneError('no frame: add 0 = ["O", ...] listing the fixed points', key="links")
    links: dict[str, tuple[str, ...]] = {}
    for name, pts in table.items():
        key = _key("links", name)
        _name(name, key, "link")
        if not isinstance(pts, list):
            raise SceneError(f'a link is a list of point names, e.g. ["A", "B"]; got {_SHOW.repr(pts)}', key=key)
        for p in pts:
            if not isinstance(p, str):
                raise SceneError(f"point names are strings: write {_quoted(p)}, got {_SHOW.repr(p)}; a link is a "
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


def _link_ref(value: Any, key: str, links: Mapping[str, Any], what: str = "link") -> str:
    """A reference to a link of [links] by name (a string, also when the name is a number)."""
    if isinstance(value, (int, float)) and not isinstance(value, bool) and str(value) in links:
        raise SceneError(f"link names are strings: write {key.rsplit('.', 1)[-1]} = \"{value}\"", key=key)
    if not isinstance(value, str) or value not in links:
        raise SceneError(f"unknown {what} {_SHOW.repr(value)}; use a name from [links] (a string, e.g. \"1\")",
                         key=key)
    return value


def _sliders(items: Any, points: Mapping[str, Any], links: Mapping[str, Any]) -> tuple[Slider, ...]:
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
        link = _link_ref(item["link"], f"{key}.link", links)
        on = _link_ref(item["on"], f"{key}.on", links)
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
            angle = _number(item["angle"], f"{key}.angle", bound=MAX_ANGLE_DEG,
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


def _drive(table: Mapping[str, Any], links: Mapping[str, Any], sliders: tuple[Slider, ...],
           points: Mapping[str, tuple[float, float]], cycle: Mapping[str, Any] | None = None) -> Drive:
    link = _link_ref(table.get("link"), "drive.link", links, "driving link")
    if link == FRAME:
        raise SceneError("the frame cannot be the driving link", key="drive.link")
    rotary_keys, linear_keys = {"angle", "omega", "epsilon"}, {"displacement", "velocity", "acceleration"}
    extra = sorted(str(k) for k in set(table) - rotary_keys - linear_keys - {"link", "along"})
    if extra:
        raise SceneError(f"unknown key {extra[0]!r}", key=f"drive.{extra[0]}")
    if set(table) & rotary_keys and set(table) & linear_keys:
        raise SceneError("mixes a rotary drive (angle, omega) with a linear one (displacement, velocity)",
                         key="drive")
    along = _link_ref(table["along"], "drive.along", links, "guide link") if "along" in table else FRAME
    if along == link:
        raise SceneError("a link cannot be driven along itself; `along` names the link carrying its guide "
                         "(the cylinder of a hydraulic drive)", key="drive.along")
    if "displacement" in table or "velocity" in table:
        kind, pos_key, speed_key, rate_key = DriveKind.LINEAR, "displacement", "velocity", "acceleration"
        if along != FRAME:
            kind = DriveKind.CYLINDER
        if not any(s.link == link and s.on == along for s in sliders):
            where = "on the frame" if along == FRAME else f"in link {along}"
            raise SceneError(f"a linear drive needs link {link} to slide {where}: add a [[sliders]] "
                             f'with link = "{link}", on = "{along}"', key="drive.link")
        pos_bound, pos_why = MAX_COORD_M, _COORD_WHY
        bounds = ((MAX_SPEED, "m/s"), (MAX_ACCELERATION, "m/s²"))
    else:
        if along != FRAME:
            raise SceneError("`along` names the cylinder of a linear drive (displacement, velocity); an angle "
                             "drive has none: remove it", key="drive.along")
        kind, pos_key, speed_key, rate_key = DriveKind.ROTARY, "angle", "omega", "epsilon"
        pos_bound, pos_why = MAX_ANGLE_DEG, "° (about 2800 turns; beyond that a double cannot hold the angle exactly)"
        bounds = ((MAX_OMEGA, "rad/s"), (MAX_EPSILON, "rad/s²"))
    if cycle:
        if kind != DriveKind.ROTARY:
            raise SceneError("positions = N divides one revolution of a crank; this drive is not a crank "
                             "(a rotary drive with angle, omega): list the drive's values instead",
                             key="drive.positions" if "positions" in cycle else "drive.start")
        count = _positions(cycle)
        if isinstance(table.get(pos_key), list):
            raise SceneError("positions = N gives N equal steps from one first angle; give angle as one number "
                             "(the first position), not a list, or leave positions out", key="drive.angle")
        if cycle.get("start") == "extreme":
            if pos_key in table:
                raise SceneError('start = "extreme" finds the first position itself (the output link\'s '
                                 'extreme); remove angle, or remove start to begin at angle', key="drive.angle")
            table = dict(table, angle=0.0)      # placeholder steps: the kinematics finds the start
        elif pos_key not in table:
            raise SceneError('missing angle: the first of the positions (or start = "extreme")', key="drive.angle")
        first = _number(table[pos_key], "drive.angle", bound=MAX_ANGLE_DEG, why="°")
        table = dict(table, angle=[first + 360.0 * k / count for k in range(count)])
    if pos_key not in table:
        raise SceneError(f"missing {pos_key}", key=f"drive.{pos_key}")
    raw = table[pos_key]
    raw_list = raw if isinstance(raw, list) else [raw]
    if not raw_list:
        raise SceneError(f"{pos_key} list is empty; give at least one value", key=f"drive.{pos_key}")
    if len(raw_list) > MAX_POSITIONS:
        raise SceneError(f"{pos_key} lists {len(raw_list)} positions; at most {MAX_POSITIONS} (each position "
                         "writes up to five sheets)", key=f"drive.{pos_key}")
    values = tuple(_number(v, f"drive.{pos_key}", bound=pos_bound, why=pos_why) for v in raw_list)
    if len(set(values)) != len(values):
        raise SceneError(f"{pos_key} list repeats a value", key=f"drive.{pos_key}")
    _walk(kind, values, points, f"drive.{pos_key}")
    if speed_key not in table:
        raise SceneError(f"missing {speed_key}", key=f"drive.{speed_key}")
    speed, rate = (_rate(table.get(k, 0.0), f"drive.{k}", bound, unit)
                   for k, (bound, unit) in zip((speed_key, rate_key), bounds))
    for k, x, unit, when in ((speed_key, speed, bounds[0][1], ""),
                             (rate_key, rate if speed == 0.0 else 0.0, bounds[1][1], f" while {speed_key} = 0")):
        if 0.0 < abs(x) < MIN_RATE:
            raise SceneError(f"{x:g} {unit}{when} is too small to compute with: give 0 (at rest) or at least "
                             f"{MIN_RATE:g} {unit} in magnitude", key=f"drive.{k}")
    return Drive(link=link, kind=kind, values=values, speed=speed, rate=rate, along=along)


def _positions(cycle: Mapping[str, Any]) -> int:
    """The number of positions of ``[drive] positions`` (and a valid ``start``)."""
    if "positions" not in cycle:
        raise SceneError('start chooses the first of positions = N; add positions (e.g. 12) or remove start',
                         key="drive.start")
    n = cycle["positions"]
    if isinstance(n, bool) or not isinstance(n, int):
        raise SceneError(f"positions is a whole number of equal steps per revolution (e.g. 12), got "
                         f"{_SHOW.repr(n)}", key="drive.positions")
    if not MIN_CYCLE_POSITIONS <= n <= MAX_POSITIONS:
        raise SceneError(f"positions = {n} is out of range: {MIN_CYCLE_POSITIONS} to {MAX_POSITIONS} equal steps per "
                         "revolution (the graphical differentiation needs three chords; one a degree is the most)",
                         key="drive.positions")
    start = cycle.get("start", "angle")
    if start not in CYCLE_STARTS:
        raise SceneError(f"start is \"angle\" (the first position is angle) or \"extreme\" (the output link's "
                         f"extreme position), got {_SHOW.repr(start)}", key="drive.start")
    return n


def _cycle(keys: Mapping[str, Any], drive: Drive, plans: Mapping[str, Any], draw: tuple[str, ...],
           points: Mapping[str, Any], links: Mapping[str, tuple[str, ...]]) -> Cycle | None:
    """The cycle of ``[drive] positions`` with ``[plans] output`` and ``trace``; None without
    positions (then the cycle sheets and keys are refused)."""
    if not keys:
        wanted = [d for d in draw if d in CYCLE_SHEETS]
        if wanted:
            raise SceneError(f"draw {wanted[0]!r} shows the whole revolution; add [drive] positions = N (e.g. 12)",
                             key="plans.draw")
        for key in ("output", "trace", "at"):
            if key in plans:
                raise SceneError(f"{key} belongs to the cycle sheets; add [drive] positions = N (e.g. 12)",
                                 key=f"plans.{key}")
        return None
    n = _positions(keys)
    if "velocities" in draw and n > MAX_VELOCITY_PLANS:
        raise SceneError(f"the velocities sheet holds at most {MAX_VELOCITY_PLANS} plans, positions = {n}; "
                         "lower positions or leave \"velocities\" out of draw", key="plans.draw")
    if "diagrams" in draw and drive.speed == 0.0:
        raise SceneError("the kinematic diagrams plot against time t = φ/ω1, which needs the crank to turn: give "
                         "omega ≠ 0 or leave \"diagrams\" out of draw", key="drive.omega")
    if "diagrams" in draw and drive.rate != 0.0:
        raise SceneError("the kinematic diagrams take ω1 constant (t = φ/ω1): give epsilon = 0 or leave "
                         "\"diagrams\" out of draw", key="drive.epsilon")
    moving = [name for name in links if name != FRAME]
    output = plans.get("output", moving[-1] if moving else "")
    if output not in moving:
        raise SceneError(f"output names the output link of the cycle, one of the moving links "
                         f"{', '.join(moving)} (a string, e.g. \"{moving[-1]}\"); got {_SHOW.repr(output)}",
                         key="plans.output")
    trace = plans.get("trace", [])
    if not isinstance(trace, list) or not all(isinstance(p, str) for p in trace):
        raise SceneError(f'trace is a list of point names, e.g. ["C"]; got {_SHOW.repr(trace)}', key="plans.trace")
    for p in trace:
        if p not in points:
            raise SceneError(f"unknown point {p!r} to trace; use a name from [points]", key="plans.trace")
    if len(set(trace)) != len(trace):
        raise SceneError("trace lists a point twice", key="plans.trace")
    at = plans.get("at", list(range(n)))
    if not isinstance(at, list) or not all(isinstance(k, int) and not isinstance(k, bool) for k in at) \
            or not all(0 <= k < n for k in at) or len(set(at)) != len(at):
        raise SceneError(f"at lists the position numbers (0 to {n - 1}, each once) drawn on sheets of their own, "
                         f"e.g. [0, 3]; got {_SHOW.repr(at)}", key="plans.at")
    return Cycle(positions=n, start=keys.get("start", "angle"), output=output, trace=tuple(trace),
                 at=tuple(sorted(at)))


def _rate(value: Any, key: str, bound: float, unit: str) -> float:
    """The drive's speed or acceleration, within ``bound`` in magnitude (0: at rest)."""
    return _number(value, key, bound=bound, why=f" {unit} (beyond any machine; keeps velocities and accelerations "
                                                "far from overflow)")


def _walk(kind: DriveKind, values: tuple[float, ...], points: Mapping[str, tuple[float, float]], key: str) -> None:
    """Refuse drive values whose continuation walk from the sketch would take more than
    MAX_WALK_STEPS steps (kinematics/solve.py ``_grid``: a crank's walk starts within half a turn
    of the values' median and steps 1°; a slider's starts at 0 and steps size/200)."""
    lo, hi = min(values), max(values)
    if kind.angular:
        step, unit = STEP_DEG, "°"
        steps = (hi - lo + 360.0) / step
    else:
        size = _size(points) or 1.0
        step, unit = size / LINEAR_STEPS_PER_SIZE, " m"
        steps = (max(hi, 0.0) - min(lo, 0.0)) / step
    if steps > MAX_WALK_STEPS:
        reach = (MAX_WALK_STEPS - (360.0 if kind.angular else 0.0)) * step
        raise SceneError(f"values from {lo:g} to {hi:g}{unit} need a walk of {steps:.3g} steps of {step:.3g}{unit} "
                         f"from the sketch (the solver follows the mechanism step by step); keep them within a span of "
                         f"{reach:.4g}{unit}" + ("" if kind.angular else " including 0 (the sketch)"), key=key)


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
        lengths[pair] = _number(value, full, positive=True, bound=MAX_COORD_M, why=_COORD_WHY)
    return lengths


def _draw(table: Mapping[str, Any]) -> tuple[tuple[str, ...], bool]:
    """What to draw, and whether the scheme shows the senses of ω and ε (``senses``)."""
    extra = sorted(str(k) for k in set(table) - {"draw", "senses"})
    if extra:
        raise SceneError(f"unknown key {extra[0]!r}; [plans] has draw and senses", key=f"plans.{extra[0]}")
    draw = table.get("draw", list(DEFAULT_DRAW))
    if not isinstance(draw, list) or not draw:
        raise SceneError(f"draw is a non-empty list of {', '.join(DRAWABLE)}", key="plans.draw")
    for item in draw:
        if not isinstance(item, str) or item not in DRAWABLE:
            raise SceneError(f"cannot draw {_SHOW.repr(item)}; choose from {', '.join(DRAWABLE)}", key="plans.draw")
    senses = table.get("senses", False)
    if not isinstance(senses, bool):
        raise SceneError(f"senses is true or false, not {_SHOW.repr(senses)}", key="plans.senses")
    if senses and "scheme" not in draw:
        raise SceneError("senses = true marks ω and ε on the scheme, which is not drawn; add \"scheme\" to draw",
                         key="plans.senses")
    return tuple(d for d in DRAWABLE if d in draw), senses


def _scales(table: Mapping[str, Any]) -> dict[str, float]:
    allowed = ("mu_l", "mu_v", "mu_a")
    out = {}
    for key, value in table.items():
        if key not in allowed:
            raise SceneError(f"unknown scale {key!r}; use mu_l, mu_v or mu_a", key=f"scales.{key}")
        out[key] = _number(value, f"scales.{key}", positive=True)
    return out


# --- loads: masses, forces, moments, the balancing element -----------------------------------

def _moving_link(value: Any, key: str, links: Mapping[str, Any], what: str) -> str:
    """A moving link named by ``value`` (the frame carries no load that does anything)."""
    link = _link_ref(value, key, links)
    if link == FRAME:
        raise SceneError(f"the frame does not move: {what} on it does nothing; name a moving link", key=key)
    return link


def _point_of(value: Any, key: str, link: str, links: Mapping[str, tuple[str, ...]]) -> str:
    """A point of ``link`` named by ``value``."""
    if not isinstance(value, str):
        raise SceneError(f"a point is named by a string, e.g. \"{links[link][0]}\"; got {_SHOW.repr(value)}", key=key)
    if value not in links[link]:
        where = "an unknown point" if not any(value in pts for pts in links.values()) else "not a point of that link"
        raise SceneError(f"{value!r} is {where}; use a point of link {link} ({', '.join(links[link])}) "
                         "or add it there in [links]", key=key)
    return value


def _masses(table: Mapping[str, Any], links: Mapping[str, tuple[str, ...]]) -> dict[str, Mass]:
    out = {}
    for name, entry in table.items():
        key = _key("masses", name)
        link = _moving_link(name, key, links, "a mass")
        if not isinstance(entry, Mapping):
            raise SceneError('[masses.NAME] is a table: mass = 2.0, inertia = 0.01, centre = "S2"', key=key)
        extra = sorted(str(k) for k in set(entry) - {"mass", "inertia", "centre"})
        if extra:
            raise SceneError(f"unknown key {extra[0]!r}; a link's mass has mass, inertia, centre", key=f"{key}.{extra[0]}")
        mass, inertia = (_number(entry.get(k, 0.0), f"{key}.{k}", bound=MAX_LOAD, why=unit)
                         for k, unit in (("mass", " kg"), ("inertia", " kg·m²")))
        for k, x in (("mass", mass), ("inertia", inertia)):
            if x < 0.0:
                raise SceneError(f"a {k} cannot be negative, got {x:g}; give 0 or more", key=f"{key}.{k}")
        if "centre" not in entry:
            raise SceneError("a mass without a centre: add centre = \"NAME\", the link's point at its centre of mass",
                             key=f"{key}.centre")
        centre = _point_of(entry["centre"], f"{key}.centre", link, links)
        out[link] = Mass(link=link, mass=mass, inertia=inertia, centre=centre)
    return out


def _load_entries(items: Any, name: str, allowed: set[str], required: tuple[str, ...], has: str,
                  needs: str) -> Iterator[tuple[int, str, Mapping[str, Any]]]:
    """The entries of an array of tables ``[[name]]`` (index, key, table), each checked for
    unknown keys (``has`` says what an entry has) and the ``required`` ones (``needs``)."""
    if not isinstance(items, list):
        raise SceneError(f"{name} must be an array of tables [[{name}]]", key=name)
    for i, item in enumerate(items):
        key = f"{name}[{i}]"
        if not isinstance(item, Mapping):
            raise SceneError(f"each [[{name}]] entry must be a table", key=key)
        extra = sorted(str(k) for k in set(item) - allowed)
        if extra:
            raise SceneError(f"unknown key {extra[0]!r}; {has}", key=f"{key}.{extra[0]}")
        for k in required:
            if k not in item:
                raise SceneError(f"missing {k!r}; {needs}", key=key)
        yield i, key, item


def _forces(items: Any, links: Mapping[str, tuple[str, ...]]) -> tuple[AppliedForce, ...]:
    out = []
    for i, key, item in _load_entries(items, "forces", {"link", "at", "vector", "magnitude", "angle"}, ("link", "at"),
                                      "a force has link, at, and vector or magnitude with angle",
                                      "a force needs link, at, and vector = [Fx, Fy] (N)"):
        link = _moving_link(item["link"], f"{key}.link", links, "a force")
        at = _point_of(item["at"], f"{key}.at", link, links)
        if "vector" in item:
            if "magnitude" in item or "angle" in item:
                raise SceneError("give either vector = [Fx, Fy] or magnitude with angle, not both", key=key)
            vec = item["vector"]
            if not isinstance(vec, list) or len(vec) != 2:
                raise SceneError(f"vector is [Fx, Fy] in newtons, got {_SHOW.repr(vec)}", key=f"{key}.vector")
            fx, fy = (_number(c, f"{key}.vector", bound=MAX_LOAD, why=" N") for c in vec)
        else:
            if "magnitude" not in item or "angle" not in item:
                raise SceneError("a force needs vector = [Fx, Fy] (N), or magnitude (N) with angle (°)", key=key)
            mag = _number(item["magnitude"], f"{key}.magnitude", bound=MAX_LOAD, why=" N")
            ang = math.radians(_number(item["angle"], f"{key}.angle", bound=MAX_ANGLE_DEG, why="°"))
            fx, fy = mag * math.cos(ang), mag * math.sin(ang)
        out.append(AppliedForce(link=link, at=at, vector=(fx, fy), index=i))
    return tuple(out)


def _moments(items: Any, links: Mapping[str, tuple[str, ...]]) -> tuple[AppliedMoment, ...]:
    out = []
    for i, key, item in _load_entries(items, "moments", {"link", "value"}, ("link", "value"),
                                      "a moment has link and value (N·m, CCW positive)",
                                      "a moment needs link and value (N·m, CCW positive)"):
        link = _moving_link(item["link"], f"{key}.link", links, "a moment")
        out.append(AppliedMoment(link=link, value=_number(item["value"], f"{key}.value", bound=MAX_LOAD, why=" N·m"),
                                 index=i))
    return tuple(out)


def _balance(table: Any, drive: Drive, links: Mapping[str, tuple[str, ...]],
             points: Mapping[str, tuple[float, float]]) -> Balance:
    """The balancing element: [balance] when given, else the drive's default (a moment on a
    crank or a coupler, a force along the guide of a slider or a cylinder)."""
    if table is None:
        kind = "moment" if drive.kind.angular else "actuator" if drive.kind == DriveKind.CYLINDER else "force"
        return Balance(link=drive.link, kind=kind, given=False)
    if not isinstance(table, Mapping):
        raise SceneError("[balance] must be a table: moment_on = \"1\", or force_on = \"1\" with at and angle",
                         key="balance")
    extra = sorted(str(k) for k in set(table) - {"moment_on", "force_on", "at", "angle"})
    if extra:
        raise SceneError(f"unknown key {extra[0]!r}; [balance] has moment_on, or force_on with at and angle",
                         key=f"balance.{extra[0]}")
    if ("moment_on" in table) == ("force_on" in table):
        raise SceneError("give one balancing element: moment_on = \"1\" (a moment on the driving link) or "
                         "force_on = \"1\" with at and angle", key="balance")
    which = "moment_on" if "moment_on" in table else "force_on"
    link = _link_ref(table[which], f"balance.{which}", links)
    if link != drive.link:
        raise SceneError(f"the balancing element belongs on the driving link {drive.link}, not on link {link}",
                         key=f"balance.{which}")
    if which == "moment_on":
        for k in ("at", "angle"):
            if k in table:
                raise SceneError(f"{k} places a balancing force; a moment has none: remove it", key=f"balance.{k}")
        if not drive.kind.angular:
            raise SceneError(f"link {link} slides and cannot turn, so a moment on it balances nothing: use "
                             "force_on with at and angle (the force along the guide)", key="balance.moment_on")
        return Balance(link=link, kind="moment")
    for k in ("at", "angle"):
        if k not in table:
            raise SceneError(f"a balancing force needs at (a point of link {link}) and angle (°, its line in the "
                             "sketch, turning with the link)", key=f"balance.{k}")
    at = _point_of(table["at"], "balance.at", link, links)
    angle = _number(table["angle"], "balance.angle", bound=MAX_ANGLE_DEG, why="°")
    return Balance(link=link, kind="force", at=at, angle=angle)

"""Handouts for a class: one base scene, many variants, an assignment and an answer key each.

A *variants file* names a base scene and lists per-variant values::

    base = "six_link_press.toml"       # relative to the variants file
    title = "TMM homework 2"           # optional (default: the base scene's title)

    [[variant]]
    lengths = { OA = 0.1, AB = 0.36 }  # any of the base's [lengths]; the rest keep the base's values
    angle = 30.0                        # the drive's value(s), a number or a list (linear drive: displacement)
    omega = 10.0                        # ω1 (linear drive: velocity)
    epsilon = 0.0                       # optional ε1 (linear drive: acceleration)

Every key of a variant is optional (a missing one keeps the base's value). Instead of a file,
:func:`random_variants` draws N variants around a base scene from ``numpy.random.default_rng(seed)``:
each length × U(1 − 20 %, 1 + 20 %) to three significant digits, a crank's angle over the turn
in 5° steps, ω1 from the series 1, 1.5, 2, 2.5, 3, 4, 5, 6, 8 × 10ᵏ within ½…2 × the base's;
a draw that does not assemble, or whose condition figure (``Motion.sines``) is below
:data:`MARGIN_SIN` at any asked position in any group, is drawn again.

:func:`write_handout` writes, into the output folder, ``variant-NN/`` (the assignment sheet and
the answer key: every sheet the scene draws, SVG and PDF, the JSON values and the variant's
own scene file), ``variants.toml`` (the variants, reproducible: ``plans handout`` on it gives the
same keys), a copy of the base scene and ``index.html``. Only the public API is used:
:func:`plans.parse_scene`, :func:`plans.render`, :meth:`plans.Sheets.save`.
"""

from __future__ import annotations

import copy
import json
import math
import re
import sys
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Mapping, Sequence, TextIO

import numpy as np

from .errors import PlansError, SceneError
from .export import convert
from .output import check_folder, write_files
from .pipeline import Sheets, render
from .kinematics import WARN_SIN
from .scene import Scene, parse_scene

__all__ = ["MARGIN_SIN", "LENGTH_SPREAD", "ANGLE_STEP_DEG", "SPEED_SERIES", "MAX_VARIANTS", "MAX_TRIES",
           "Variant", "Handout", "Drawn", "read_variants", "read_base", "random_variants", "variant_scene",
           "solve_variant", "write_handout", "Progress", "to_toml"]

#: Margin of the random mode: every asked position of every drawn variant has, in every group,
#: |condition| ≥ this (``Motion.sines``: the normalised determinant of the group's velocity
#: equations, 0 at a singular position; plans warns below WARN_SIN = 1e-2). 0.1 keeps the
#: unknown directions at least 5.7° from parallel.
MARGIN_SIN = 0.1
#: Groups whose condition figure is a sine (class II closed forms, class III groups); the others
#: (class IV groups, a drive inside the chain) report σmin/σmax of a Newton Jacobian, which is
#: small even far from a singular position (0.02–0.05 in the examples): for them the margin is
#: half the base scene's own smallest figure, between WARN_SIN and MARGIN_SIN.
SINE_GROUPS = ("II(", "III(")
#: Random lengths: the base's × U(1 − spread, 1 + spread).
LENGTH_SPREAD = 0.2
#: Random crank angles: multiples of this over the turn, degrees.
ANGLE_STEP_DEG = 5.0
#: Random ω1 (or a linear drive's speed): these mantissas × 10ᵏ within SPEED_RANGE × the base's.
SPEED_SERIES = (1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0)
SPEED_RANGE = (0.5, 2.0)
#: Most variants of one handout.
MAX_VARIANTS = 999
#: Draws tried for one random variant before giving up.
MAX_TRIES = 200
#: Files in the output folder besides the variants' folders.
INDEX, VARIANTS = "index.html", "variants.toml"

_DRIVE_KEYS = {True: ("angle", "omega", "epsilon"), False: ("displacement", "velocity", "acceleration")}


@dataclass(frozen=True)
class Variant:
    """One variant: its number (1, 2, …), the lengths it sets (base [lengths] key → m) and its
    drive values; ``None`` keeps the base's."""

    number: int
    lengths: Mapping[str, float] = field(default_factory=dict)
    values: tuple[float, ...] | None = None
    speed: float | None = None
    rate: float | None = None


@dataclass(frozen=True)
class Handout:
    """The base scene (its path, text and parsed TOML) and the variants; ``seed`` and ``margin``
    when the variants were drawn at random."""

    base: Path
    base_text: str
    base_data: Mapping[str, Any]
    variants: tuple[Variant, ...]
    title: str
    source: Path | None = None
    seed: int | None = None
    margin: float | None = None
    margins: Mapping[str, float] = field(default_factory=dict)
    redraws: int = 0

    @property
    def angular(self) -> bool:
        return "displacement" not in self.base_data["drive"] and "velocity" not in self.base_data["drive"]

    @property
    def keys(self) -> tuple[str, str, str]:
        """The drive's keys: angle, omega, epsilon (or displacement, velocity, acceleration)."""
        return _DRIVE_KEYS[self.angular]

    def name(self, v: Variant) -> str:
        """``variant-01`` (as many digits as the largest number needs, at least two)."""
        return f"variant-{v.number:0{max(2, len(str(len(self.variants))))}d}"


@dataclass(frozen=True)
class Drawn:
    """A variant solved: its scene and its rendered sheets."""

    variant: Variant
    name: str
    scene: Scene
    sheets: Sheets


# --- reading -------------------------------------------------------------------------------

def _load(path: Path, what: str) -> tuple[str, dict]:
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SceneError(f"no such {what}; check the path", file=str(path)) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise SceneError(f"cannot read the file ({exc.__class__.__name__}); it must be UTF-8 TOML",
                         file=str(path)) from None
    try:
        return text, tomllib.loads(text)
    except (tomllib.TOMLDecodeError, ValueError, RecursionError) as exc:
        raise SceneError(f"malformed TOML: {exc}; fix the syntax there", file=str(path)) from None


def read_base(path: str | Path) -> Handout:
    """A base scene for :func:`random_variants`: read and validated (no variants yet)."""
    path = Path(path)
    text, data = _load(path, "scene file")
    if "base" in data or "variant" in data:
        raise SceneError("is a variants file, not a scene; --random draws variants around a scene: give its base "
                         f"scene ({data.get('base', '?')}) instead", file=str(path), key="--random")
    scene = parse_scene(data, file=str(path))
    return Handout(base=path, base_text=text, base_data=data, variants=(), title=scene.title)


def read_variants(path: str | Path) -> Handout:
    """Read and validate a variants file; errors name the file, the key and the fix."""
    path = Path(path)
    text, data = _load(path, "variants file")
    f = str(path)
    if "base" not in data:
        if "points" in data and "drive" in data:
            raise SceneError("is a scene, not a variants file: add --random N to draw N variants around it, or "
                             'write a variants file with base = "<this scene>" and [[variant]] tables', file=f)
        raise SceneError('missing base: name the base scene, e.g. base = "six_link_press.toml" (a path relative '
                         "to this file)", file=f, key="base")
    extra = sorted(str(k) for k in set(data) - {"base", "title", "variant"})
    if extra:
        raise SceneError(f"unknown key {extra[0]!r}; a variants file has base, title and [[variant]] tables",
                         file=f, key=extra[0])
    if not isinstance(data["base"], str) or not data["base"].strip():
        raise SceneError(f"base is the path of the base scene (a string), got {data['base']!r}", file=f, key="base")
    base_path = path.parent / data["base"]
    if not base_path.is_file():
        raise SceneError(f"base scene {data['base']!r} not found (looked for {base_path}; the path is relative to "
                         "the variants file); fix the path", file=f, key="base")
    base = read_base(base_path)
    title = data.get("title", base.title)
    if not isinstance(title, str) or not title.isprintable():
        raise SceneError("title is one line of text (a string)", file=f, key="title")
    items = data.get("variant")
    if not isinstance(items, list) or not items:
        raise SceneError("no variants: add [[variant]] tables, e.g. [[variant]] with lengths = { OA = 0.1 }, "
                         "angle = 30.0, omega = 10.0", file=f, key="variant")
    if len(items) > MAX_VARIANTS:
        raise SceneError(f"{len(items)} variants; at most {MAX_VARIANTS}", file=f, key="variant")
    variants = tuple(_variant(item, k, base, f) for k, item in enumerate(items))
    return Handout(base=base_path, base_text=base.base_text, base_data=base.base_data, variants=variants,
                   title=title, source=path)


def _number(value: Any, key: str, file: str, *, positive: bool = False, unit: str = "") -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise SceneError(f"must be a number{' of ' + unit if unit else ''}, got {value!r}", file=file, key=key)
    x = float(value)
    if not math.isfinite(x):
        raise SceneError(f"{value!r} is not a finite number; give a real value", file=file, key=key)
    if positive and x <= 0.0:
        raise SceneError(f"must be positive, got {x:g}; give the length in metres, e.g. 0.1", file=file, key=key)
    return x


def _variant(item: Any, k: int, base: Handout, file: str) -> Variant:
    key = f"variant[{k}]"
    if not isinstance(item, Mapping):
        raise SceneError("each [[variant]] entry is a table", file=file, key=key)
    pos, speed, rate = base.keys
    allowed = ("lengths", pos, speed, rate)
    for name in item:
        if name not in allowed:
            other = _DRIVE_KEYS[not base.angular]
            hint = (f"; the base scene's drive is {'an angle' if base.angular else 'a linear'} drive: use "
                    f"{pos}, {speed}, {rate}") if name in other else ""
            raise SceneError(f"unknown key {name!r}; a variant has {', '.join(allowed)}{hint}", file=file,
                             key=f"{key}.{name}")
    base_lengths = base.base_data.get("lengths", {})
    lengths = item.get("lengths", {})
    if not isinstance(lengths, Mapping):
        raise SceneError("lengths is a table of the base's [lengths], e.g. lengths = { OA = 0.1 }", file=file,
                         key=f"{key}.lengths")
    for name in lengths:
        if name not in base_lengths:
            known = ", ".join(base_lengths) if base_lengths else "none: add the length to the base scene's [lengths]"
            raise SceneError(f"unknown length {name!r}; the base scene's [lengths] has {known}", file=file,
                             key=f"{key}.lengths.{name}")
    lengths = {n: _number(v, f"{key}.lengths.{n}", file, positive=True, unit="metres") for n, v in lengths.items()}
    values = None
    if pos in item:
        raw = item[pos] if isinstance(item[pos], list) else [item[pos]]
        if not raw:
            raise SceneError(f"{pos} is a number or a non-empty list", file=file, key=f"{key}.{pos}")
        values = tuple(_number(v, f"{key}.{pos}", file) for v in raw)
    return Variant(number=k + 1, lengths=lengths, values=values,
                   speed=_number(item[speed], f"{key}.{speed}", file) if speed in item else None,
                   rate=_number(item[rate], f"{key}.{rate}", file) if rate in item else None)


# --- solving -------------------------------------------------------------------------------

def variant_data(h: Handout, v: Variant) -> dict:
    """The base scene's TOML data with the variant's lengths and drive values."""
    data = copy.deepcopy(dict(h.base_data))
    if v.lengths:
        data["lengths"] = {**data.get("lengths", {}), **v.lengths}
    drive = data["drive"]
    for key, value in zip(h.keys, (list(v.values) if v.values is not None else None, v.speed, v.rate)):
        if value is not None:
            drive[key] = value[0] if isinstance(value, list) and len(value) == 1 else value
    return data


def _where(h: Handout, v: Variant) -> tuple[str, str]:
    """The file and key that name variant ``v`` in error messages."""
    return (str(h.source), f"variant[{v.number - 1}]") if h.source else (str(h.base), f"--random ({h.name(v)})")


def variant_scene(h: Handout, v: Variant) -> Scene:
    """The scene of variant ``v``; a value the scene refuses is reported at the variant's key."""
    file, key = _where(h, v)
    try:
        return parse_scene(variant_data(h, v), file=str(h.base))
    except SceneError as exc:
        sub = exc.key or ""
        for table, alias in (("drive.", ""), ("lengths.", "lengths.")):
            if sub.startswith(table):
                sub = alias + sub[len(table):]
        raise SceneError(f"{exc.message} ({h.name(v)})", file=file, key=f"{key}.{sub}" if sub else key) from None


def solve_variant(h: Handout, v: Variant) -> Drawn:
    """Variant ``v`` rendered (every sheet the scene draws); a variant that cannot be assembled
    or is singular is one error naming the variant and why."""
    scene = variant_scene(h, v)
    name = h.name(v)
    file, key = _where(h, v)
    try:
        sheets = render(scene, stem=name)
    except SceneError as exc:      # a link's lengths that cannot form its shape
        where = f" (link {exc.key[len('links.'):]})" if exc.key and exc.key.startswith("links.") else ""
        raise SceneError(f"{name} cannot be built: {exc.message}{where}", file=file, key=key) from None
    except PlansError as exc:      # does not assemble, or singular, at an asked position
        why = str(exc).removeprefix(f"{h.base}, ").removeprefix(f"{h.base}: ")
        raise SceneError(f"{name} cannot be drawn: {why}", file=file, key=key) from None
    return Drawn(v, name, scene, sheets)


def worst_sine(sheets: Sheets) -> float:
    """The smallest |condition figure| over every group and position (1 with no group)."""
    return min((float(np.min(np.abs(s))) for s in sheets.motion.sines.values()), default=1.0)


def group_margins(base: Sheets, margin: float = MARGIN_SIN) -> dict[str, float]:
    """The margin each group of the base scene must keep: ``margin`` for a group whose figure is
    a sine (SINE_GROUPS), else half the base's smallest |figure|, within WARN_SIN…margin."""
    out = {}
    for g, s in base.motion.sines.items():
        own = 0.5 * float(np.min(np.abs(s)))
        out[g] = margin if g.startswith(SINE_GROUPS) else min(margin, max(WARN_SIN, own))
    return out


def _short_of(sheets: Sheets, margins: Mapping[str, float]) -> str:
    """Why ``sheets`` misses the margins ("" when it keeps them all)."""
    for g, s in sheets.motion.sines.items():
        worst = float(np.min(np.abs(s)))
        if worst < margins.get(g, MARGIN_SIN):
            return f"group {g}: condition {worst:.3g} below the margin {margins.get(g, MARGIN_SIN):g}"
    return ""


# --- random variants -----------------------------------------------------------------------

def _round3(x: float) -> float:
    """``x`` to three significant digits (as its shortest decimal)."""
    return float(f"{x:.3g}")


def _speeds(base: float) -> tuple[float, ...]:
    """The series values within SPEED_RANGE × |base| (|base| itself when none), with its sign."""
    if base == 0.0:
        return (0.0,)
    lo, hi = abs(base) * SPEED_RANGE[0], abs(base) * SPEED_RANGE[1]
    k0 = math.floor(math.log10(lo)) - 1
    found = sorted({float(f"{m:g}e{k}") for k in range(k0, k0 + 4) for m in SPEED_SERIES
                    if lo * (1 - 1e-12) <= float(f"{m:g}e{k}") <= hi * (1 + 1e-12)})
    return tuple(math.copysign(s, base) for s in (found or [abs(base)]))


def _draw(h: Handout, rng: np.random.Generator, number: int) -> Variant:
    """One random variant (see the module docstring); the draws are made in a fixed order."""
    base_lengths = h.base_data.get("lengths", {})
    lengths = {n: _round3(float(x) * rng.uniform(1 - LENGTH_SPREAD, 1 + LENGTH_SPREAD))
               for n, x in base_lengths.items()}
    drive = h.base_data["drive"]
    pos, speed_key, _ = h.keys
    steps = int(round(360.0 / ANGLE_STEP_DEG))
    angle = float(rng.integers(0, steps)) * ANGLE_STEP_DEG
    rotary = h.angular and not _is_coupler(h)
    values = (angle,) if rotary else None
    speeds = _speeds(float(drive.get(speed_key, 0.0)))
    speed = speeds[int(rng.integers(0, len(speeds)))]
    return Variant(number=number, lengths=lengths, values=values, speed=speed)


def _is_coupler(h: Handout) -> bool:
    """Whether the angle drive turns a link with no pivot on the frame (its angle cannot go round)."""
    links = h.base_data["links"]
    return not set(links[str(h.base_data["drive"]["link"])]) & set(links["0"])


def random_variants(path: str | Path, count: int, seed: int, *, margin: float = MARGIN_SIN,
                    progress: Callable[[int, str], None] | None = None) -> tuple[Handout, list[Drawn]]:
    """``count`` variants around the base scene at ``path``, drawn from ``default_rng(seed)``,
    each solved and kept only when it assembles with |condition| ≥ ``margin`` everywhere; a
    failed draw is drawn again (up to MAX_TRIES times a variant). Returns the handout and the
    solved variants."""
    h = read_base(path)
    margins = group_margins(render(parse_scene(h.base_data, file=str(h.base))), margin)
    h = Handout(base=h.base, base_text=h.base_text, base_data=h.base_data, variants=tuple(Variant(k + 1)
                for k in range(count)), title=h.title, seed=seed, margin=margin, margins=margins)
    rng = np.random.default_rng(seed)
    drawn: list[Drawn] = []
    redraws = 0
    for number in range(1, count + 1):
        why = ""
        for _ in range(MAX_TRIES):
            v = _draw(h, rng, number)
            try:
                d = solve_variant(h, v)
            except PlansError as exc:
                why = str(exc)
                redraws += 1
                continue
            why = _short_of(d.sheets, margins)
            if not why:
                drawn.append(d)
                break
            why = f"{d.name}: {why}"
            redraws += 1
        else:
            raise SceneError(f"no variant among {MAX_TRIES} draws assembles keeping the margin from singular "
                             f"positions (the last: {why}); the base's lengths ±{LENGTH_SPREAD:.0%} give too few "
                             "mechanisms that work: check the base scene", file=str(h.base), key="--random")
        if progress:
            progress(number, drawn[-1].name)
    variants = tuple(d.variant for d in drawn)
    return Handout(base=h.base, base_text=h.base_text, base_data=h.base_data, variants=variants, title=h.title,
                   seed=seed, margin=margin, margins=margins, redraws=redraws), drawn


# --- writing -------------------------------------------------------------------------------

_BARE = re.compile(r"[A-Za-z0-9_-]+")


def _toml_key(k: str) -> str:
    return k if _BARE.fullmatch(k) else json.dumps(k, ensure_ascii=False)


def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf") if math.isinf(v) else repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False).replace("\x7f", "\\u007f")
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, Mapping):
        return "{ " + ", ".join(f"{_toml_key(k)} = {_toml_value(x)}" for k, x in v.items()) + " }" if v else "{}"
    raise TypeError(f"cannot write {type(v).__name__} as TOML")


def to_toml(data: Mapping[str, Any], *, _prefix: str = "") -> str:
    """TOML text of ``data`` (tables of scalars, lists, inline tables and arrays of tables, as a
    scene or a variants file holds them); ``tomllib.loads`` gives ``data`` back."""
    def aot(v: Any) -> bool:
        return isinstance(v, list) and bool(v) and all(isinstance(x, Mapping) for x in v)

    lines = [f"{_toml_key(k)} = {_toml_value(v)}" for k, v in data.items() if not isinstance(v, Mapping)
             and not aot(v)]
    for k, v in data.items():
        name = _prefix + _toml_key(k)
        if isinstance(v, Mapping):
            lines += ["", f"[{name}]", to_toml(v, _prefix=name + ".").rstrip("\n")]
        elif aot(v):
            for item in v:
                lines += ["", f"[[{name}]]", to_toml(item, _prefix=name + ".").rstrip("\n")]
    return "\n".join(line for line in lines).lstrip("\n") + "\n"


def _variants_file(h: Handout, base_name: str) -> str:
    """``variants.toml``: the handout's variants in the variants format, every value written
    (``plans handout`` on it, beside the base scene's copy, gives the same answer keys)."""
    lines = [f"# plans handout: {len(h.variants)} variants of {h.base.name}"]
    if h.seed is not None:
        lines.append(f"# drawn with --random {len(h.variants)} --seed {h.seed}: lengths ±{LENGTH_SPREAD:.0%}; every "
                     f"asked position keeps |condition| ≥ the margin of each group: {margin_text(h)}")
    lines += ["", f"base = {_toml_value(base_name)}", f"title = {_toml_value(h.title)}"]
    for v in h.variants:
        data = variant_data(h, v)
        lines += ["", "[[variant]]"]
        if data.get("lengths"):
            lines.append(f"lengths = {_toml_value(data['lengths'])}")
        lines += [f"{key} = {_toml_value(data['drive'][key])}" for key in h.keys if key in data["drive"]]
    return "\n".join(lines) + "\n"


def margin_text(h: Handout) -> str:
    """``II(2-3) 0.1, II(4-5) 0.1``: each group's margin, as the index page and variants.toml say it."""
    return ", ".join(f"{g} {m:g}" for g, m in h.margins.items()) or "no group to keep"


def _base_name(h: Handout) -> str:
    """The base scene's copy in the output folder: its own name unless that is taken."""
    return h.base.name if h.base.name not in (INDEX, VARIANTS) else "base.toml"


class Progress:
    """A progress bar on ``stream`` (stderr) while a handout is made, drawn only on a terminal:
    ``[#####-----] 12/30 variant-12``, rewritten in place, one line."""

    def __init__(self, total: int, what: str, stream: TextIO | None = None, width: int = 30):
        self.stream = sys.stderr if stream is None else stream
        self.on = bool(getattr(self.stream, "isatty", lambda: False)())
        self.total, self.what, self.width = max(total, 1), what, width

    def __call__(self, done: int, note: str = "") -> None:
        if not self.on:
            return
        filled = int(self.width * done / self.total)
        self.stream.write(f"\r{self.what} [{'#' * filled}{'-' * (self.width - filled)}] {done}/{self.total} "
                          f"{note:<16}")
        self.stream.flush()

    def close(self) -> None:
        if self.on:
            self.stream.write("\n")
            self.stream.flush()


def write_handout(h: Handout, drawn: Sequence[Drawn], out: str | Path, *,
                  progress: Callable[[int, str], None] | None = None) -> list[Path]:
    """Write every variant's folder, ``variants.toml``, the base scene's copy and ``index.html``
    into ``out``. Each folder is written all or nothing (:meth:`plans.Sheets.save`); an error
    removes what this call wrote before it. Returns the paths written."""
    from .drawing.assignment import draw_assignment   # the drawing is needed only here
    from .handout_index import index_html

    out = Path(out)
    check_folder(out)
    base_name = _base_name(h)
    written: list[Path] = []
    try:
        for k, d in enumerate(drawn, 1):
            folder = out / d.name
            svg = _assignment(h, d, draw_assignment)
            extra = {f"{d.name}-assignment.svg": svg}
            written += d.sheets.save(folder, formats="svg,pdf")
            written += write_files({**convert(extra, ("svg", "pdf")),
                                    f"{d.name}.toml": _scene_file(h, d)}, folder)
            if progress:
                progress(k, d.name)
        top = {VARIANTS: _variants_file(h, base_name), base_name: h.base_text,
               INDEX: index_html(h, drawn, margin=h.margin)}
        written += write_files(top, out)
    except BaseException:
        for p in reversed(written):
            try:
                p.unlink()
            except OSError:
                pass
        for d in drawn:
            try:
                (out / d.name).rmdir()
            except OSError:
                pass
        raise
    return written


def _assignment(h: Handout, d: Drawn, draw: Callable[..., str]) -> str:
    """The assignment sheet's SVG: the scheme at the variant's first position (constructed from
    the solved motion), its data, the points and links to find."""
    from .constructions.scheme import scheme

    motion = d.sheets.motion
    mech = motion.mechanism
    return draw(lambda mu: scheme(motion, 0, mu), d.scene, variant=d.name.replace("variant-", "variant "),
                points=[p for p in mech.sketch if motion.carrier(p) != "0"],
                links=[n for n in mech.moving if n != d.scene.drive.link],
                lengths=variant_data(h, d.variant).get("lengths"))


def _scene_file(h: Handout, d: Drawn) -> str:
    """The variant's own scene file (``plans render`` redraws its key from it)."""
    return (f"# {d.name} of {h.base.name} ({h.title}): the base scene with this variant's lengths and drive;\n"
            f"# plans render {d.name}.toml redraws its answer key\n" + to_toml(variant_data(h, d.variant)))

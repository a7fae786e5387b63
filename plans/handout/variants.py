"""A handout's data: the variants file's :class:`Variant` and :class:`Handout`, a solved
:class:`Drawn`, the bounds of the random mode, and the reading and validating of a base scene
and of a variants file (errors name the file, the key and the fix).

Knows the scene reader and the pipeline's :class:`plans.Sheets`; must not import the other
modules of :mod:`plans.handout`, the drawing or the command line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

from ..errors import SceneError
from ..pipeline import Sheets
from ..scene import Scene, as_float, parse_scene, parse_toml, read_text
from ..scene.checks import SHOW
from .asked import kind_of

__all__ = ["MARGIN_SIN", "LENGTH_SPREAD", "ANGLE_STEP_DEG", "SPEED_SERIES", "SPEED_RANGE",
           "MAX_VARIANTS", "MAX_TRIES", "MAX_ROTOR_MASSES", "Variant", "Handout", "Drawn", "read_base",
           "read_variants", "margin_text"]

#: Margin of the random mode: every asked position of every drawn variant has, in every group,
#: |condition| ≥ this (``Motion.sines``: the sine of a class II group's transmission angle, and
#: the same figure generalised for every other group, 0 at a singular position; plans warns
#: below WARN_SIN = 1e-2). 0.1 keeps the group's links at least 5.7° from a dead position's
#: alignment.
MARGIN_SIN = 0.1
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
#: Most masses of a rotor's handout: its assignment sheet's table holds 20 rows of 7 mm beside
#: the shaft and the task.
MAX_ROTOR_MASSES = 20

#: The tables only a scene has (a linkage, a gear train, a gear pair, a synthesis, a rotor): a file
#: with one of them and no base is a scene given where a variants file was expected.
_SCENE_KEYS = {"points", "links", "drive", "gears", "gear_pair", "synthesis", "rotor"}
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
    teeth: Mapping[str, int] = field(default_factory=dict)     # a gear train's: wheel → teeth
    inputs: Mapping[str, float] = field(default_factory=dict)  # a gear train's: link → rpm
    masses: tuple[Mapping[str, float], ...] = ()   # a rotor's: the k-th changes the base's k-th mass


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
    kind: str = "kinematics"        # what the assignment asks (plans.handout.asked.KINDS)

    @property
    def train(self) -> bool:
        """Whether the base is a gear train alone (its variants set teeth and input speeds)."""
        return self.kind == "gears"

    @property
    def rotor(self) -> bool:
        """Whether the base is a rotor ([rotor]: its variants set the masses)."""
        return self.kind == "balancing"

    @property
    def angular(self) -> bool:
        drive = self.base_data.get("drive", {})
        return "displacement" not in drive and "velocity" not in drive

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


def read_base(path: str | Path, *, cited: tuple[str, str] | None = None) -> Handout:
    """A base scene for :func:`random_variants` (``--random``), or the ``base`` of a variants file
    (``cited``: that file and its key, which errors about the base as a file then name): read
    through the scene's bounded reader and validated (no variants yet)."""
    path = Path(path)
    try:
        text = read_text(path)
    except SceneError as exc:
        if cited is None:
            raise
        raise SceneError(f"base scene {str(path)!r}: {exc.message}", file=cited[0], key=cited[1]) from None
    data = parse_toml(text, str(path))
    if "base" in data or "variant" in data:
        if cited is not None:
            raise SceneError(f"names {str(path)!r}, another variants file, not a scene: give the scene it is based on "
                             f"({data.get('base', '?')})", file=cited[0], key=cited[1])
        raise SceneError("is a variants file, not a scene; --random draws variants around a scene: give its base "
                         f"scene ({data.get('base', '?')}) instead", file=str(path), key="--random")
    scene = parse_scene(data, file=str(path))
    try:
        kind = kind_of(scene)
    except SceneError as exc:
        raise SceneError(exc.message, file=str(path), key=exc.key) from None
    if kind == "balancing" and "balancing" not in scene.draw:
        raise SceneError("a rotor's answer key is its -balancing sheet (the couple and force polygons): add draw = "
                         '["balancing"] to [plans]', file=str(path), key="plans.draw")
    if kind == "balancing" and len(scene.rotor.masses) > MAX_ROTOR_MASSES:
        raise SceneError(f"{len(scene.rotor.masses)} masses; a rotor's assignment sheet lists at most "
                         f"{MAX_ROTOR_MASSES}: give a rotor with fewer masses for a handout", file=str(path),
                         key="rotor.masses")
    return Handout(base=path, base_text=text, base_data=data, variants=(), title=scene.title, kind=kind)


def read_variants(path: str | Path) -> Handout:
    """Read and validate a variants file; errors name the file, the key and the fix."""
    path = Path(path)
    f = str(path)
    data = parse_toml(read_text(path, what="variants file"), f)
    if "base" not in data:
        if _SCENE_KEYS & set(data):
            raise SceneError("is a scene, not a variants file: add --random N to draw N variants around it, or "
                             f'write a variants file with base = "{path.name}" and [[variant]] tables', file=f)
        raise SceneError('missing base: name the base scene, e.g. base = "six_link_press.toml" (a path relative '
                         "to this file)", file=f, key="base")
    extra = sorted(str(k) for k in set(data) - {"base", "title", "variant"})
    if extra:
        raise SceneError(f"unknown key {extra[0]!r}; a variants file has base, title and [[variant]] tables",
                         file=f, key=extra[0])
    if not isinstance(data["base"], str) or not data["base"].strip():
        raise SceneError(f"base is the path of the base scene (a string), got {data['base']!r}", file=f, key="base")
    base_path = path.parent / data["base"]
    if not base_path.exists():
        raise SceneError(f"base scene {data['base']!r} not found (looked for {base_path}; the path is relative to "
                         "the variants file); fix the path", file=f, key="base")
    if base_path.resolve() == path.resolve():
        raise SceneError(f"base = {data['base']!r} names this variants file itself; base is the scene the variants "
                         "change: name that scene file (a path relative to this file)", file=f, key="base")
    base = read_base(base_path, cited=(f, "base"))
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
                   title=title, source=path, kind=base.kind)


def _number(value: Any, key: str, file: str, *, positive: bool = False, unit: str = "") -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise SceneError(f"must be a number{' of ' + unit if unit else ''}, got {SHOW.repr(value)}", file=file,
                         key=key)
    x = as_float(value)          # a TOML integer of hundreds of digits is inf here, not an OverflowError
    if not math.isfinite(x):
        raise SceneError(f"{SHOW.repr(value)} is not a finite number; give a real value", file=file, key=key)
    if positive and x <= 0.0:
        raise SceneError(f"must be positive, got {x:g}; give the length in metres, e.g. 0.1", file=file, key=key)
    return x


def _variant(item: Any, k: int, base: Handout, file: str) -> Variant:
    key = f"variant[{k}]"
    if not isinstance(item, Mapping):
        raise SceneError("each [[variant]] entry is a table", file=file, key=key)
    if base.train:
        return _train_variant(item, k, base, file)
    if base.rotor:
        return _rotor_variant(item, k, base, file)
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


def _train_variant(item: Mapping[str, Any], k: int, base: Handout, file: str) -> Variant:
    """A gear train's variant: ``teeth = { "1" = 20 }`` (any of the base's wheels) and
    ``input = { "1" = 1450.0 }`` (the base's input links, rpm)."""
    key = f"variant[{k}]"
    for name in item:
        if name not in ("teeth", "input"):
            raise SceneError(f"unknown key {name!r}; a gear train's variant has teeth and input", file=file,
                             key=f"{key}.{name}")
    gears = base.base_data["gears"]
    wheels, inputs = gears.get("wheels", {}), gears.get("input", {})
    teeth, speeds = item.get("teeth", {}), item.get("input", {})
    for table, given, known, what in (("teeth", teeth, wheels, "[gears.wheels]"),
                                      ("input", speeds, inputs, "[gears.input]")):
        if not isinstance(given, Mapping):
            raise SceneError(f"{table} is a table of the base's {what}, e.g. {table} = {{ \"1\" = 20 }}", file=file,
                             key=f"{key}.{table}")
        for name in given:
            if name not in known:
                raise SceneError(f"unknown {'wheel' if table == 'teeth' else 'input'} {name!r}; the base scene's "
                                 f"{what} has {', '.join(known) or 'none'}", file=file, key=f"{key}.{table}.{name}")
    for name, z in teeth.items():
        if isinstance(z, bool) or not isinstance(z, int) or z < 1:
            raise SceneError(f"teeth are a positive whole number, got {SHOW.repr(z)}", file=file,
                             key=f"{key}.teeth.{name}")
    return Variant(number=k + 1, teeth={str(n): int(z) for n, z in teeth.items()},
                   inputs={str(n): _number(v, f"{key}.input.{n}", file) for n, v in speeds.items()})


#: What a rotor variant's mass may set (as a [rotor] mass: kg, m, degrees, m along the shaft).
_MASS_KEYS = ("mass", "radius", "angle", "plane")


def _rotor_variant(item: Mapping[str, Any], k: int, base: Handout, file: str) -> Variant:
    """A rotor's variant: ``masses = [{ mass = 250.0, angle = 30.0 }, …]``, the k-th table
    changing the base's k-th mass (any of mass, radius, angle, plane; the rest, and the masses
    after the list's end, keep the base's). The values are checked by the scene's reader."""
    key = f"variant[{k}]"
    for name in item:
        if name != "masses":
            raise SceneError(f"unknown key {name!r}; a rotor's variant has masses (a list of the base's masses' "
                             "changes)", file=file, key=f"{key}.{name}")
    count = len(base.base_data["rotor"]["masses"])
    masses = item.get("masses", [])
    if not isinstance(masses, list) or len(masses) > count:
        raise SceneError(f"masses is a list of at most {count} tables (the base's masses, in order), e.g. masses = "
                         "[{ mass = 250.0, angle = 30.0 }]", file=file, key=f"{key}.masses")
    out = []
    for j, m in enumerate(masses):
        at = f"{key}.masses[{j}]"
        if not isinstance(m, Mapping):
            raise SceneError("each mass is a table of mass, radius, angle, plane, e.g. { mass = 250.0 }", file=file,
                             key=at)
        extra = [n for n in m if n not in _MASS_KEYS]
        if extra:
            raise SceneError(f"unknown key {extra[0]!r}; a mass has {', '.join(_MASS_KEYS)}", file=file,
                             key=f"{at}.{extra[0]}")
        out.append({n: _number(v, f"{at}.{n}", file) for n, v in m.items()})
    return Variant(number=k + 1, masses=tuple(out))


def margin_text(h: Handout) -> str:
    """``II(2-3) 0.1, II(4-5) 0.1``: each group's margin, as the index page and variants.toml say it."""
    return ", ".join(f"{g} {m:g}" for g, m in h.margins.items()) or "no group to keep"

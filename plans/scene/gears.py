"""The gear train of a scene (``[gears]``): wheels, carriers, meshes, fixed links, planets and
inputs, checked for names and numbers; the structure (mobility, a locked train) is checked by
:mod:`plans.gears`.

Imports only plans.errors and plans.scene.checks (and the standard library).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

from ..errors import SceneError
from .checks import SHOW, name_of, number, whole

#: Teeth of one wheel: 1 … MAX_TEETH (a ring gear of a large reducer has a few hundred).
MAX_TEETH = 10_000
#: The module, mm: 1e-3 … MAX_MODULE_MM (watch gears to mill gears).
MIN_MODULE_MM, MAX_MODULE_MM = 1e-3, 1e3
#: Speeds, rpm: |n| ≤ MAX_RPM.
MAX_RPM = 1e7
#: Planets on one carrier.
MAX_PLANETS = 24
#: Wheels of one train: a course's trains have a few dozen at most; the speeds are solved by
#: exact elimination over fractions, whose time grows as the cube of the wheels (100 idlers in a
#: row render in about 2 s, 200 in 13 s).
MAX_WHEELS = 100

_WHEEL_KEYS = {"teeth", "module", "internal", "on", "shaft"}
_GEAR_KEYS = {"wheels", "carriers", "meshes", "fixed", "planets", "input", "output"}


@dataclass(frozen=True)
class Wheel:
    """One toothed wheel (``[gears.wheels] NAME = {…}``): ``teeth``; ``module`` (mm, None when not
    given: the geometry goes unchecked); ``internal`` (a ring gear); ``on``, the carrier that
    carries its axis (None: the axis is fixed in the frame); ``shaft``, the wheel or carrier it
    is rigidly joined to (None: a link of its own)."""

    name: str
    teeth: int
    module: float | None = None
    internal: bool = False
    on: str | None = None
    shaft: str | None = None


@dataclass(frozen=True)
class GearTrain:
    """A gear train as the scene gives it. ``meshes`` are wheel-name pairs in scene order;
    ``fixed`` the wheels or carriers held still; ``inputs`` (name, rpm) pairs, counter-clockwise
    positive; ``planets`` the equally spaced copies of each carrier's planets (1: only the one
    described); ``output`` the wheel or carrier on the shaft of a linkage's crank, or None."""

    wheels: tuple[Wheel, ...]
    carriers: tuple[str, ...] = ()
    meshes: tuple[tuple[str, str], ...] = ()
    fixed: tuple[str, ...] = ()
    planets: int = 1
    inputs: tuple[tuple[str, float], ...] = ()
    output: str | None = None

    def wheel(self, name: str) -> Wheel:
        """The wheel called ``name`` (KeyError when there is none)."""
        for w in self.wheels:
            if w.name == name:
                return w
        raise KeyError(name)

    @property
    def names(self) -> tuple[str, ...]:
        """Every wheel and carrier name, wheels first, in scene order."""
        return tuple(w.name for w in self.wheels) + self.carriers


def read_gears(table: Mapping[str, Any]) -> GearTrain:
    """Validate ``[gears]`` (with its subtables ``wheels`` and ``input``) and build a :class:`GearTrain`."""
    if not isinstance(table, Mapping):
        raise SceneError("[gears] must be a table", key="gears")
    _only(table, _GEAR_KEYS, "gears", "[gears] has")
    wheels_table = table.get("wheels")
    if not isinstance(wheels_table, Mapping) or not wheels_table:
        raise SceneError("a gear train needs its wheels: [gears.wheels] a = { teeth = 20 }, …", key="gears.wheels")
    carriers = _names(table.get("carriers", []), "gears.carriers", "carrier")
    if len(wheels_table) > MAX_WHEELS:
        raise SceneError(f"{len(wheels_table)} wheels: a train takes at most {MAX_WHEELS} (its speeds are solved "
                         "exactly, in time that grows as the cube of the wheels); split it into trains of fewer "
                         "wheels", key="gears.wheels")
    wheels = tuple(_wheel(str(name), spec) for name, spec in wheels_table.items())
    names = [w.name for w in wheels]
    clash = next((c for c in carriers if c in names), None)
    if clash is not None:
        raise SceneError(f"{clash!r} is both a wheel and a carrier; give them different names",
                         key="gears.carriers")
    known = set(names) | set(carriers)
    for w in wheels:
        if w.on is not None and w.on not in carriers:
            hint = f"add it to [gears] carriers = [{w.on!r}]" if w.on not in names else "a wheel's axis is " \
                "carried by a carrier; name one from [gears] carriers"
            raise SceneError(f"on = {w.on!r} is not a carrier; {hint}", key=f"gears.wheels.{w.name}.on")
        if w.shaft is not None and w.shaft not in known:
            raise SceneError(f"shaft = {w.shaft!r} names no wheel or carrier; use one of {', '.join(sorted(known))}",
                             key=f"gears.wheels.{w.name}.shaft")
        if w.shaft == w.name:
            raise SceneError("a wheel cannot be joined to itself; shaft names another wheel or a carrier",
                             key=f"gears.wheels.{w.name}.shaft")
    meshes = _meshes(table.get("meshes", []), set(names), set(carriers))
    fixed = _names(table.get("fixed", []), "gears.fixed", "wheel or carrier")
    for f in fixed:
        if f not in known:
            raise SceneError(f"unknown wheel or carrier {f!r}; use one of {', '.join(sorted(known))}",
                             key="gears.fixed")
    raw = table.get("planets", 1)
    planets = whole(raw)
    if planets is None or not 1 <= planets <= MAX_PLANETS:
        raise SceneError(f"planets is a whole number 1 … {MAX_PLANETS} (equally spaced satellites), "
                         f"got {SHOW.repr(raw)}", key="gears.planets")
    inputs = _inputs(table.get("input", {}), known)
    output = table.get("output")
    if output is not None:
        output = name_of(output, "gears.output", "wheel or carrier")
        if output not in known:
            raise SceneError(f"unknown wheel or carrier {output!r}; name the one on the crank's shaft, one of "
                             f"{', '.join(sorted(known))}", key="gears.output")
    return GearTrain(wheels=wheels, carriers=carriers, meshes=meshes, fixed=fixed, planets=planets,
                     inputs=inputs, output=output)


def _only(table: Mapping[str, Any], allowed: set[str], key: str, has: str) -> None:
    """Refuse the first key of ``table`` (sorted) that is not ``allowed``, at ``key.<it>``."""
    unknown = sorted(str(k) for k in set(table) - allowed)
    if unknown:
        raise SceneError(f"unknown key {unknown[0]!r}; {has} {', '.join(sorted(allowed))}", key=f"{key}.{unknown[0]}")


def _names(value: Any, key: str, what: str) -> tuple[str, ...]:
    if not isinstance(value, list):
        raise SceneError(f"expected a list of {what} names, e.g. [\"H\"], got {SHOW.repr(value)}", key=key)
    out = tuple(name_of(v, key, what) for v in value)
    dup = next((n for k, n in enumerate(out) if n in out[:k]), None)
    if dup is not None:
        raise SceneError(f"{dup!r} is listed twice", key=key)
    return out


def _wheel(name: str, spec: Any) -> Wheel:
    key = f"gears.wheels.{name}"
    name = name_of(name, key, "wheel")
    if not isinstance(spec, Mapping):
        raise SceneError(f"a wheel is an inline table, e.g. {name} = {{ teeth = 20, module = 2.0 }}, got "
                         f"{SHOW.repr(spec)}", key=key)
    _only(spec, _WHEEL_KEYS, key, "a wheel has")
    if "teeth" not in spec:
        raise SceneError("missing teeth: the number of teeth of the wheel", key=f"{key}.teeth")
    teeth = whole(spec["teeth"])
    if teeth is None or not 1 <= teeth <= MAX_TEETH:
        raise SceneError(f"teeth is a whole number 1 … {MAX_TEETH}, got {SHOW.repr(spec['teeth'])}",
                         key=f"{key}.teeth")
    module = None
    if "module" in spec:
        module = number(spec["module"], f"{key}.module", positive=True, bound=MAX_MODULE_MM, why=" mm")
        if module < MIN_MODULE_MM:
            raise SceneError(f"module {module:g} mm is below {MIN_MODULE_MM:g} mm; give it in millimetres",
                             key=f"{key}.module")
    internal = spec.get("internal", False)
    if not isinstance(internal, bool):
        raise SceneError(f"internal is true (a ring gear) or false, got {SHOW.repr(internal)}",
                         key=f"{key}.internal")
    on = name_of(spec["on"], f"{key}.on", "carrier") if "on" in spec else None
    shaft = name_of(spec["shaft"], f"{key}.shaft", "wheel") if "shaft" in spec else None
    return Wheel(name=name, teeth=teeth, module=module, internal=internal, on=on, shaft=shaft)


def _meshes(value: Any, wheels: set[str], carriers: set[str]) -> tuple[tuple[str, str], ...]:
    if not isinstance(value, list) or not value:
        raise SceneError("meshes is a list of wheel pairs, e.g. [[\"a\", \"g\"], [\"g\", \"b\"]]",
                         key="gears.meshes")
    out: list[tuple[str, str]] = []
    for k, pair in enumerate(value):
        key = f"gears.meshes[{k}]"
        if not isinstance(pair, list) or len(pair) != 2:
            raise SceneError(f"a mesh is a pair of wheel names, e.g. [\"a\", \"g\"], got {SHOW.repr(pair)}", key=key)
        a, b = (name_of(n, key, "wheel") for n in pair)
        for n in (a, b):
            if n not in wheels:
                what = "a carrier has no teeth; mesh its wheels" if n in carriers else \
                    f"use one of {', '.join(sorted(wheels))}"
                raise SceneError(f"unknown wheel {n!r}; {what}", key=key)
        if a == b:
            raise SceneError(f"a wheel cannot mesh with itself ({a!r})", key=key)
        if {a, b} in ({x, y} for x, y in out):
            raise SceneError(f"the mesh of {a!r} and {b!r} is listed twice", key=key)
        out.append((a, b))
    return tuple(out)


def _inputs(value: Any, known: set[str]) -> tuple[tuple[str, float], ...]:
    if not isinstance(value, Mapping):
        raise SceneError("[gears.input] is a table: name = rpm (counter-clockwise positive)", key="gears.input")
    out = []
    for name, rpm in value.items():
        name = name_of(name, "gears.input", "wheel or carrier")
        if name not in known:
            raise SceneError(f"unknown wheel or carrier {name!r}; use one of {', '.join(sorted(known))}",
                             key=f"gears.input.{name}")
        out.append((name, number(rpm, f"gears.input.{name}", bound=MAX_RPM, why=" rpm")))
    return tuple(out)


@dataclass(frozen=True)
class Synthesis:
    """``[synthesis]``: find the teeth of a 2K-H planetary train (``kind`` "A" … "D") for ``ratio``
    (input → output) within ``tolerance`` (relative) with ``planets`` equally spaced planets, every
    wheel of ``module`` mm; the best candidate is drawn."""

    ratio: float
    kind: str
    planets: int
    tolerance: float = 0.01
    module: float = 1.0


_SYNTHESIS_KEYS = {"ratio", "type", "planets", "tolerance", "module"}


def read_synthesis(table: Any) -> Synthesis:
    """Validate ``[synthesis]`` (the bounds of each value are checked by the synthesis itself)."""
    if not isinstance(table, Mapping):
        raise SceneError("[synthesis] must be a table", key="synthesis")
    _only(table, _SYNTHESIS_KEYS, "synthesis", "[synthesis] has")
    for k in ("ratio", "type", "planets"):
        if k not in table:
            raise SceneError(f"missing {k}: [synthesis] needs ratio, type (A, B, C or D) and planets",
                             key=f"synthesis.{k}")
    kind = table["type"]
    if not isinstance(kind, str) or kind.strip().upper() not in ("A", "B", "C", "D"):
        raise SceneError(f"type is one of \"A\", \"B\", \"C\", \"D\", got {SHOW.repr(kind)}", key="synthesis.type")
    planets = whole(table["planets"])
    if planets is None or not 2 <= planets <= 12:
        raise SceneError(f"planets is a whole number 2 … 12, got {SHOW.repr(table['planets'])}",
                         key="synthesis.planets")
    ratio = number(table["ratio"], "synthesis.ratio", bound=1e6)
    if abs(ratio) <= 1.0:
        raise SceneError(f"a reducer's ratio is beyond ±1, got {ratio:g}", key="synthesis.ratio")
    tolerance = number(table.get("tolerance", 0.01), "synthesis.tolerance", positive=True, bound=0.2,
                       why=" (0.01 = 1 %)")
    module = number(table.get("module", 1.0), "synthesis.module", positive=True, bound=100.0, why=" mm")
    if module < 0.05:
        raise SceneError(f"module {module:g} mm is below 0.05 mm", key="synthesis.module")
    return Synthesis(ratio=ratio, kind=kind.strip().upper(), planets=planets, tolerance=tolerance, module=module)

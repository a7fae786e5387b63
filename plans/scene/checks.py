"""The checks every scene reader shares: tables, finite numbers within their bounds, names and
text a drawing can hold, references to links, and the short form of a bad value shown in a
message. Each failed check raises one :class:`~plans.errors.SceneError` naming the key.

Imports only plans.errors (and the standard library): every reader of plans.scene imports it.
"""

from __future__ import annotations

import math
import numbers
import reprlib
from typing import Any, Mapping

from ..errors import SceneError

#: Values shown in error messages are abbreviated (a nested or huge value stays one short line).
SHOW = reprlib.Repr()
SHOW.maxlevel, SHOW.maxstring, SHOW.maxother, SHOW.maxlist = 3, 60, 60, 6
#: Why coordinates and lengths are bounded by MAX_COORD_M (the tail of the bound's message).
COORD_WHY = " m (far beyond any linkage; keeps the arithmetic far from overflow)"


def subtable(data: Mapping[str, Any], key: str, *, required: bool = False) -> Mapping[str, Any]:
    """The table ``[key]`` of ``data``; {} when absent and not ``required``."""
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


def text(value: Any, key: str, *, line: bool) -> str:
    """A title, description or name: a string of characters a drawing can hold."""
    if not isinstance(value, str):
        raise SceneError(f"{key.split('.')[0]} must be a string, got {SHOW.repr(value)}", key=key)
    bad = next((c for c in value if _xml_invalid(c, line=line)), None)
    if bad is not None:
        what = "control character" if ord(bad) < 0xD800 else "character"
        raise SceneError(f"contains the {what} U+{ord(bad):04X}, which an SVG drawing cannot hold; remove it"
                         + (" (write a name or a title on one line)" if bad in "\t\n\r" else ""), key=key)
    return value


def name_of(value: Any, key: str, what: str) -> str:
    """A point or link name: a non-empty one-line string."""
    if not isinstance(value, str):
        raise SceneError(f"{what} names are strings: write {quoted(value)}, got {SHOW.repr(value)}", key=key)
    if not value.strip():
        raise SceneError(f"empty {what} name {value!r}; give the {what} a name, e.g. \"A\"", key=key)
    return text(value, key, line=True)


def quoted(value: Any) -> str:
    """``value`` written as a TOML string, for messages (1 → "1")."""
    return f'"{value}"' if isinstance(value, (int, float)) and not isinstance(value, bool) else '"NAME"'


def is_number(value: Any) -> bool:
    """Whether ``value`` is a real number a scene may give: an int or a float, or a NumPy (or other
    registered) integer or real of a mapping given to the Python API — not a bool, not complex."""
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def whole(value: Any) -> int | None:
    """``value`` as a Python int when it is a whole number (an int or a NumPy integer, not a bool
    and not a float such as 20.0), else None."""
    return int(value) if isinstance(value, numbers.Integral) and not isinstance(value, bool) else None


def as_float(value: int | float) -> float:
    """``value`` (a number read from TOML or JSON) as a float; an integer beyond the largest
    double (TOML integers have any number of digits, up to 4300) is ±inf, not an OverflowError,
    so that the caller's finiteness check refuses it in one line."""
    try:
        return float(value)
    except OverflowError:                        # a huge int (or Fraction)
        return math.inf if value > 0 else -math.inf


def number(value: Any, key: str, *, positive: bool = False, bound: float | None = None, why: str = "") -> float:
    """A finite number; ``bound`` (SI) limits its magnitude, ``why`` says where the bound comes from."""
    if not is_number(value):
        raise SceneError(f"expected a number, got {SHOW.repr(value)}", key=key)
    x = as_float(value)
    if not math.isfinite(x):
        raise SceneError(f"{SHOW.repr(value)} is not a finite number; give a real value", key=key)
    if positive and x <= 0.0:
        raise SceneError(f"must be positive, got {x:g}", key=key)
    if bound is not None and abs(x) > bound:
        raise SceneError(f"{x:g} is out of range: |value| ≤ {bound:g}{why}", key=key)
    return x


def entry_key(table: str, name: str) -> str:
    """The dotted key of entry ``name`` of ``table`` (an empty name shown as "")."""
    return f"{table}.{name}" if name else f'{table}.""'


def sketch_size(points: Mapping[str, tuple[float, float]]) -> float:
    """The sketch's bounding-box diagonal, m (the mechanism's size, as in model.Mechanism.size)."""
    xs, ys = [p[0] for p in points.values()], [p[1] for p in points.values()]
    return math.hypot(max(xs) - min(xs), max(ys) - min(ys)) if points else 0.0


def link_ref(value: Any, key: str, links: Mapping[str, Any], what: str = "link") -> str:
    """A reference to a link of [links] by name (a string, also when the name is a number)."""
    if isinstance(value, (int, float)) and not isinstance(value, bool) and str(value) in links:
        raise SceneError(f"link names are strings: write {key.rsplit('.', 1)[-1]} = \"{value}\"", key=key)
    if not isinstance(value, str) or value not in links:
        raise SceneError(f"unknown {what} {SHOW.repr(value)}; use a name from [links] (a string, e.g. \"1\")",
                         key=key)
    return value


def read_own_draw(data: Mapping[str, Any], sheets: tuple[str, ...], what: str) -> tuple[str, ...]:
    """``[plans]`` of a scene of a kind of its own (a rotor, a flywheel problem): ``draw`` alone,
    a list of ``sheets`` (empty: the report alone); ``what`` names the kind in the messages."""
    plans = data.get("plans", {})
    if not isinstance(plans, Mapping):
        raise SceneError("[plans] must be a table", key="plans")
    extra = sorted(str(k) for k in set(plans) - {"draw"})
    if extra:
        raise SceneError(f"{what}'s [plans] has only draw, not {extra[0]!r}", key=f"plans.{extra[0]}")
    draw = plans.get("draw", [])
    if not isinstance(draw, list) or any(d not in sheets for d in draw):
        raise SceneError(f"{what} draws {', '.join(repr(d) for d in sheets)} or [] (the report alone), got "
                         f"{SHOW.repr(draw)}", key="plans.draw")
    return tuple(dict.fromkeys(draw))

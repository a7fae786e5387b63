"""TOML text of a scene's or a variants file's data (``tomllib`` has no writer): tables of
scalars, lists, inline tables and arrays of tables.

Knows nothing of plans; must not import any other plans module.
"""

from __future__ import annotations

import json
import math
import re
from typing import Any, Mapping

__all__ = ["to_toml", "toml_value"]

_BARE = re.compile(r"[A-Za-z0-9_-]+")


def _toml_key(k: str) -> str:
    return k if _BARE.fullmatch(k) else json.dumps(k, ensure_ascii=False)


def toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf") if math.isinf(v) else repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False).replace("\x7f", "\\u007f")
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, Mapping):
        return "{ " + ", ".join(f"{_toml_key(k)} = {toml_value(x)}" for k, x in v.items()) + " }" if v else "{}"
    raise TypeError(f"cannot write {type(v).__name__} as TOML")


def to_toml(data: Mapping[str, Any], *, _prefix: str = "") -> str:
    """TOML text of ``data`` (tables of scalars, lists, inline tables and arrays of tables, as a
    scene or a variants file holds them); ``tomllib.loads`` gives ``data`` back."""
    def aot(v: Any) -> bool:
        return isinstance(v, list) and bool(v) and all(isinstance(x, Mapping) for x in v)

    lines = [f"{_toml_key(k)} = {toml_value(v)}" for k, v in data.items() if not isinstance(v, Mapping)
             and not aot(v)]
    for k, v in data.items():
        name = _prefix + _toml_key(k)
        if isinstance(v, Mapping):
            lines += ["", f"[{name}]", to_toml(v, _prefix=name + ".").rstrip("\n")]
        elif aot(v):
            for item in v:
                lines += ["", f"[[{name}]]", to_toml(item, _prefix=name + ".").rstrip("\n")]
    return "\n".join(line for line in lines).lstrip("\n") + "\n"

"""A scene file: read as UTF-8 TOML and parsed; when the TOML reader gives up (nesting too deep
for it, a number of thousands of digits) the key is found in the text itself.

Imports only plans.errors and modules of plans.scene (and the standard library).
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

from ..errors import SceneError
from .document import parse_scene
from .values import Scene


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

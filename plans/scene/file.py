"""A user's file, read once and bounded: :func:`read_bytes` and :func:`read_text` (a regular file
of at most MAX_FILE_BYTES, UTF-8), :func:`parse_toml` and :func:`read_scene`. Every command and
the API read a scene, a variants file, a base scene or an SVG to check through these, so that
/dev/zero, a pipe or a directory is one line and never a hang or a MemoryError. When the TOML
reader gives up (nesting too deep for it, a number of thousands of digits) the key is found in
the text itself.

Imports only plans.errors and modules of plans.scene (and the standard library).
"""

from __future__ import annotations

import os
import re
import stat
import tomllib
from pathlib import Path

from ..errors import SceneError
from .document import parse_scene
from .values import MAX_FILE_BYTES, Scene

__all__ = ["read_bytes", "read_text", "parse_toml", "read_scene"]

#: What a file that is not a regular file is, by its stat.S_IS* test.
_KINDS = ((stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a named pipe (FIFO)"), (stat.S_ISCHR, "a character device"),
          (stat.S_ISBLK, "a block device"), (stat.S_ISSOCK, "a socket"))


def read_bytes(path: str | Path, *, what: str = "scene file", limit: int = MAX_FILE_BYTES) -> bytes:
    """The bytes of the regular file ``path``, at most ``limit`` of them; a missing file, one
    that is not a regular file (a directory, a pipe, a device such as /dev/zero) or one over
    ``limit`` bytes is a :class:`SceneError` naming the file. Opened without blocking (a pipe
    with no writer) and checked on the open descriptor, so it cannot change in between."""
    file = str(path)
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0))
    except FileNotFoundError:
        raise SceneError(f"no such {what}; check the path", file=file) from None
    except ValueError:          # a NUL character, which no path can hold
        raise SceneError(f"no such {what}: the path holds a NUL character; check the path", file=file) from None
    except OSError as exc:
        raise SceneError(f"cannot read the file ({exc.__class__.__name__}); check the path and its permissions",
                         file=file) from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            kind = next((name for test, name in _KINDS if test(info.st_mode)), "not a regular file")
            raise SceneError(f"is {kind}, not a {what}; plans reads only regular files: give the path of a {what}",
                             file=file)
        data = b"" if info.st_size > limit else _read(fd, limit + 1, file)
    finally:
        os.close(fd)
    if info.st_size > limit or len(data) > limit:
        raise SceneError(f"is larger than {limit / 1e6:g} MB ({max(info.st_size, len(data))} bytes or more); a "
                         f"{what} is at most {limit} bytes: check the path", file=file)
    return data


def _read(fd: int, n: int, file: str) -> bytes:
    """Up to ``n`` bytes of the open file ``fd`` (fewer only at its end)."""
    chunks, got = [], 0
    try:
        while got < n:
            chunk = os.read(fd, min(n - got, 1 << 20))
            if not chunk:
                break
            chunks.append(chunk)
            got += len(chunk)
    except OSError as exc:
        raise SceneError(f"cannot read the file ({exc.__class__.__name__}); check the path and its permissions",
                         file=file) from None
    return b"".join(chunks)


def read_text(path: str | Path, *, what: str = "scene file", limit: int = MAX_FILE_BYTES) -> str:
    """The text of a UTF-8 file read by :func:`read_bytes`."""
    try:
        return read_bytes(path, what=what, limit=limit).decode("utf-8")
    except UnicodeDecodeError:
        raise SceneError("cannot read the file (UnicodeDecodeError); it must be UTF-8 TOML", file=str(path)) from None


def parse_toml(text: str, file: str) -> dict:
    """``text`` parsed as TOML; malformed TOML, values nested deeper than the reader follows and
    integers of thousands of digits are one :class:`SceneError` naming ``file`` (and the key)."""
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(f"malformed TOML: {exc}; fix the syntax there", file=file) from None
    except RecursionError:   # the reader recurses once per level of nesting
        depth, where = _nesting(text)
        raise SceneError(f"values nested {depth} deep (more than the TOML reader can follow); a scene nests "
                         "at most a list in a table, e.g. A = [0.1, 0.2]", file=file,
                         key=_key_at(text, where)) from None
    except ValueError:   # not a TOMLDecodeError: an integer of more than 4300 digits
        match = _LONG_NUMBER.search(text)
        raise SceneError("a number with thousands of digits cannot be read; write an ordinary number, e.g. 10.0",
                         file=file, key=_key_at(text, match.start() if match else 0)) from None


def read_scene(path: str | Path) -> Scene:
    """Read and validate a scene file; errors name the file and the key."""
    data = parse_toml(read_text(path), str(path))
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

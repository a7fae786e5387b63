"""File stems: the part of every file name of a scene before ``-<sheet>.svg`` and ``.json``.

Pure text; imports nothing of plans but plans.errors."""

from __future__ import annotations

import re
from pathlib import Path

from ..errors import OutputError

__all__ = ["MAX_STEM_CHARS", "stem_of", "checked_stem", "file_stem"]

#: Longest stem made from a title (characters).
MAX_STEM_CHARS = 60


def stem_of(title: str) -> str:
    """A file stem from a title: lower case, every run of characters other than letters,
    digits, ``-`` and ``_`` one ``_``, at most :data:`MAX_STEM_CHARS` characters; ``mechanism``
    when nothing is left."""
    stem = re.sub(r"[^\w-]+", "_", title.strip().lower())[:MAX_STEM_CHARS].strip("_-")
    return stem or "mechanism"


def checked_stem(stem: str) -> str:
    """``stem`` when it names files in one folder: one line of printable characters (no line
    break, tab or control character), no path separator, not empty, ``.`` or ``..``, at most
    :data:`MAX_STEM_CHARS` × 2 characters."""
    if not isinstance(stem, str) or not stem.strip() or stem in (".", "..") or re.search(r"[/\\]", stem) \
            or not stem.isprintable() or len(stem) > 2 * MAX_STEM_CHARS:
        raise OutputError(f"stem {stem!r} cannot name a file; give a plain name on one line such as 'four_bar'",
                          key="stem")
    return stem


def file_stem(path: str | Path) -> str:
    """The stem of the scene file ``path`` (``four_bar`` of ``examples/four_bar.toml``), which
    names its output files: refused, as :func:`checked_stem` refuses a ``stem``, when it holds a
    line break, tab or other control character."""
    stem = Path(path).stem
    if not stem.isprintable():
        raise OutputError("the file's name holds a line break, tab or control character, which would go into the "
                          "name of every output file; rename the file (from Python, or give render(..., stem=...))",
                          file=str(path))
    return stem

"""Exceptions of plans: one base class, a few meaningful kinds.

Every error carries enough structured context (file, key, group, angle) to be printed
as one line that names the culprit and the fix; the command line prints ``str(error)``
and exits with code 2.
"""

from __future__ import annotations

__all__ = [
    "PlansError",
    "SceneError",
    "StructureError",
    "AssemblyError",
    "SingularPositionError",
    "DrawingError",
    "ConstructionError",
    "OutputError",
    "one_line",
]


class PlansError(Exception):
    """Base class of every error raised by plans."""


def _located(message: str, file: str | None, key: str | None) -> str:
    """``file: [key]: message``, leaving out what is not known; characters that are not
    printable (controls, line breaks) are shown escaped, so the error stays one plain line."""
    where = ": ".join(part for part in (file, f"[{key}]" if key else None) if part)
    return one_line(f"{where}: {message}" if where else message)


def one_line(text: str) -> str:
    """``text`` with every non-printable character written as its escape (\\x01, \\n, \\u2028)."""
    if text.isprintable():
        return text
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in text)


class _Located(PlansError):
    """An error at a place: ``file: [key]: message``, one line."""

    def __init__(self, message: str, *, file: str | None = None, key: str | None = None):
        super().__init__(message)
        self.message = message
        self.file = file
        self.key = key

    def __str__(self) -> str:
        return _located(self.message, self.file, self.key)


class SceneError(_Located, ValueError):
    """The scene file is malformed or inconsistent.

    Parameters
    ----------
    message : what is wrong and how to fix it.
    file : the scene file, when known.
    key : dotted key path inside the scene (e.g. ``links.2`` or ``drive.omega``).
    """

    def in_file(self, file: str) -> "SceneError":
        """The same error, located in ``file``."""
        return type(self)(self.message, file=file, key=self.key)


class StructureError(SceneError):
    """The linkage's structure is not one this version can analyse (W != drives, class III, ...)."""


class AssemblyError(PlansError, ValueError):
    """A group cannot be assembled, or has no unique solution, at a requested position.

    ``at`` is the drive's value (degrees or metres) where a walk from the sketch stopped, when
    one did: the solver reaches the values beyond it another way (a crank the long way round).
    """

    def __init__(self, message: str, *, group: str | None = None, angle: str | None = None,
                 file: str | None = None, at: float | None = None):
        super().__init__(message)
        self.message = message
        self.group = group
        self.angle = angle
        self.file = file
        self.at = at

    def __str__(self) -> str:
        parts = [p for p in (self.file, self.group, None if self.angle is None else f"at {self.angle}") if p]
        return one_line(f"{', '.join(parts)}: {self.message}" if parts else self.message)

    def in_file(self, file: str) -> "AssemblyError":
        return type(self)(self.message, group=self.group, angle=self.angle, file=file, at=self.at)


class SingularPositionError(AssemblyError):
    """The group is assembled but its velocity equations are singular (dead centre, collinear links)."""


class DrawingError(PlansError, ValueError):
    """An SVG cannot be read back or checked."""


class ConstructionError(PlansError, ValueError):
    """A graphical construction that cannot be drawn at this position (a degenerate one, e.g.
    Koshel's uncertain-scale plan of a group momentarily at rest); the sheet states why, the
    other sheets and positions are unaffected."""


class OutputError(_Located):
    """The output cannot be written (``-o`` is a file or not writable, a folder stands where a
    file goes, the disk is full, two scenes would write the same files). Nothing is left behind.

    Parameters
    ----------
    message : what is wrong and how to fix it.
    file : the path concerned (the output folder or file, or the scene).
    key : the option or argument concerned (``-o``, ``SCENE.toml``).
    """

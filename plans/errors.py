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
]


class PlansError(Exception):
    """Base class of every error raised by plans."""


class SceneError(PlansError, ValueError):
    """The scene file is malformed or inconsistent.

    Parameters
    ----------
    message : what is wrong and how to fix it.
    file : the scene file, when known.
    key : dotted key path inside the scene (e.g. ``links.2`` or ``drive.omega``).
    """

    def __init__(self, message: str, *, file: str | None = None, key: str | None = None):
        super().__init__(message)
        self.message = message
        self.file = file
        self.key = key

    def __str__(self) -> str:
        where = ": ".join(part for part in (self.file, f"[{self.key}]" if self.key else None) if part)
        return f"{where}: {self.message}" if where else self.message

    def in_file(self, file: str) -> "SceneError":
        """The same error, located in ``file``."""
        return type(self)(self.message, file=file, key=self.key)


class StructureError(SceneError):
    """The linkage's structure is not one this version can analyse (W != drives, class III, ...)."""


class AssemblyError(PlansError, ValueError):
    """A group cannot be assembled, or has no unique solution, at a requested position."""

    def __init__(self, message: str, *, group: str | None = None, angle: str | None = None,
                 file: str | None = None):
        super().__init__(message)
        self.message = message
        self.group = group
        self.angle = angle
        self.file = file

    def __str__(self) -> str:
        parts = [p for p in (self.file, self.group, None if self.angle is None else f"at {self.angle}") if p]
        return f"{', '.join(parts)}: {self.message}" if parts else self.message

    def in_file(self, file: str) -> "AssemblyError":
        return type(self)(self.message, group=self.group, angle=self.angle, file=file)


class SingularPositionError(AssemblyError):
    """The group is assembled but its velocity equations are singular (dead centre, collinear links)."""


class DrawingError(PlansError, ValueError):
    """An SVG cannot be read back or checked."""


class ConstructionError(PlansError, ValueError):
    """A graphical construction that cannot be drawn at this position (a degenerate one, e.g.
    Koshel's uncertain-scale plan of a group momentarily at rest); the sheet states why, the
    other sheets and positions are unaffected."""

"""One position drawn on sheets of its own: the suffix of its sheets' names (the drive's
value) and the line under each heading (the drive's value, speed and rate).

Reads a solved Motion; imports nothing of plans.pipeline."""

from __future__ import annotations

from dataclasses import dataclass

from ...drawing import Style
from ...kinematics import Motion
from ...scene import Scene

__all__ = ["Page", "sheet_suffix", "position_label"]


@dataclass(frozen=True)
class Page:
    """Position ``i`` of ``motion`` as its sheets name it: files ``<stem>-<kind><suffix>.svg``,
    ids ``<kind><suffix>``, each heading's third line ``label``."""

    scene: Scene
    motion: Motion
    i: int
    stem: str
    style: Style
    suffix: str
    label: str

    @classmethod
    def at(cls, scene: Scene, motion: Motion, i: int, stem: str, style: Style) -> Page:
        return cls(scene, motion, i, stem, style, sheet_suffix(motion, i), position_label(motion, i))

    def file(self, kind: str) -> str:
        """The file name of this position's sheet of ``kind`` (``four_bar-velocity-30.svg``)."""
        return f"{self.stem}-{kind}{self.suffix}.svg"

    def ident(self, kind: str) -> str:
        """The id prefix of this position's sheet of ``kind`` (``velocity-30``)."""
        return f"{kind}{self.suffix or ''}"


def sheet_suffix(motion: Motion, i: int) -> str:
    """``-30``, ``-m22.5`` (m for minus) after a sheet's name when several positions are
    drawn: the drive's value with as few digits as keep every position's name distinct
    (6 significant digits, more when two values would print alike, e.g. 10.0000001)."""
    if len(motion) == 1:
        return ""
    values = [float(v) for v in motion.values]
    digits = next(d for d in range(6, 18) if len({f"{v:.{d}g}" for v in values}) == len(values))
    return "-" + f"{values[i]:.{digits}g}".replace("-", "m")


def position_label(motion: Motion, i: int) -> str:
    """The drive at position i: ``φ_1 = 30°, ω_1 = 10 rad/s, ε_1 = 0 rad/s²`` (or s, v, a in m)."""
    v = motion.values[i]
    d = motion.mechanism.drive
    j = d.link
    w, e = motion.drive_rates(i)
    return f"φ_{j} = {v:g}°, ω_{j} = {w:g} rad/s, ε_{j} = {e:g} rad/s²" if d.kind.angular else \
        f"s = {v:g} m, v = {d.speed:g} m/s, a = {d.rate:g} m/s²"

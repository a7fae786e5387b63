"""What ``plans check`` finds in a file: a measured vector (:class:`Measurement`), a point of a
plan reached by several vector ends (:class:`Closure`), a kinetostatic check (:class:`Check`)
and the file's whole :class:`SvgReport`. Lengths in paper mm, values in SI, angles in rad.

Part of :mod:`plans.checking`, which re-exports these names. Knows nothing of plans; must not
import any other plans module.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

__all__ = ["Measurement", "Closure", "Check", "SvgReport"]


@dataclass(frozen=True)
class Measurement:
    """One measured vector: drawn length (mm) × μ against the exact value (SI), and its drawn
    direction against the recorded one (``angle_error`` rad; NaN when unmeasurable).
    ``problem`` names what makes it unmeasurable (a non-finite value, no direction …)."""

    quantity: str
    plan: str
    length_mm: float
    mu: float
    value: float
    tolerance: float
    angle_error: float = 0.0
    angle_tolerance: float = math.pi
    problem: str = ""

    @property
    def measured(self) -> float:
        return self.length_mm * self.mu

    @property
    def error(self) -> float:
        err = abs(self.measured - self.value)
        return err if math.isfinite(err) else math.inf

    @property
    def length_ok(self) -> bool:
        return self.error <= self.tolerance

    @property
    def direction_ok(self) -> bool:
        return math.isnan(self.angle_error) or self.angle_error <= self.angle_tolerance

    @property
    def ok(self) -> bool:
        return not self.problem and self.length_ok and self.direction_ok


@dataclass(frozen=True)
class Closure:
    """One point of a plan reached by several vector ends: ``ends`` (``quantity tail|head``),
    their largest distance apart ``gap_mm`` and the tolerance."""

    plan: str
    point: str
    ends: tuple[str, ...]
    gap_mm: float
    tolerance_mm: float

    @property
    def ok(self) -> bool:
        return self.gap_mm <= self.tolerance_mm


@dataclass(frozen=True)
class Check:
    """One kinetostatic check of a force plan or lever: ``what`` (``Σ sides`` …, ``arm of F:bal``,
    ``Σ M_p``), the deviation found and its tolerance, in ``unit`` (mm, N, N·mm)."""

    plan: str
    what: str
    deviation: float
    tolerance: float
    unit: str

    @property
    def ok(self) -> bool:
        return math.isfinite(self.deviation) and self.deviation <= self.tolerance


@dataclass
class SvgReport:
    """Everything ``plans check`` found in one file. ``kind``: ``plan`` (tagged vectors),
    ``scheme`` (a scheme sheet: nothing to measure), ``empty`` (a plan its writer drew with no
    vector, ``data-vectors="0"``: the pole alone) or ``none`` (nothing tagged: a failure).
    ``equations``: plan group id → number of closure equations checked."""

    path: str
    kind: str
    precision: float
    measurements: list[Measurement] = field(default_factory=list)
    closures: list[Closure] = field(default_factory=list)
    problems: list[str] = field(default_factory=list)
    equations: dict[str, int] = field(default_factory=dict)
    checks: list[Check] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return (self.kind != "none" and not self.problems and all(m.ok for m in self.measurements)
                and all(c.ok for c in self.closures) and all(c.ok for c in self.checks))

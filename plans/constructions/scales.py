"""Scale factors μ = physical quantity / drawn length (per mm), from the standard series."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np

__all__ = ["SERIES", "Scales", "standard_scale", "choose_scales", "REFERENCE_MM"]

#: Mantissas of the standard scale series; a scale is m·10^k.
SERIES = (1.0, 1.25, 2.0, 2.5, 4.0, 5.0, 8.0)
#: Wanted length of the reference vector (pa, πa) on a plan, mm.
REFERENCE_MM = (80.0, 120.0)
#: Largest extent of a plan before the scale is coarsened, mm.
PLAN_MAX_MM = 240.0
#: Area the scheme must fit in, mm.
SCHEME_MM = (200.0, 140.0)


@dataclass(frozen=True)
class Scales:
    """μl in m/mm, μV in (m/s)/mm, μa in (m/s²)/mm (None when not computed)."""

    mu_l: float
    mu_v: float | None = None
    mu_a: float | None = None

    def as_dict(self) -> dict[str, float]:
        return {k: v for k, v in (("mu_l", self.mu_l), ("mu_v", self.mu_v), ("mu_a", self.mu_a)) if v is not None}


def _series_values(lo: float, hi: float) -> list[float]:
    kmin, kmax = math.floor(math.log10(lo)) - 1, math.ceil(math.log10(hi)) + 1
    return [round(m * 10.0 ** k, 12) for k in range(kmin, kmax + 1) for m in SERIES]


def standard_scale(reference: float, *, window: tuple[float, float] = REFERENCE_MM,
                   limit: float | None = None, extent: float = 0.0) -> float:
    """The series scale drawing ``reference`` closest to the middle of ``window`` (mm), among
    those that also keep ``extent`` (same units as reference) within ``limit`` mm."""
    if not (reference > 0.0 and math.isfinite(reference)):
        reference = extent if extent > 0.0 else 1.0
    mid = 0.5 * (window[0] + window[1])
    candidates = _series_values(reference / window[1] / 100.0, max(reference, extent) / window[0] * 100.0)
    fitting = [mu for mu in candidates if limit is None or extent / mu <= limit]
    return min(fitting, key=lambda mu: (abs(math.log(reference / mu / mid)), mu))


def fitting_scale(extent: float, limit: float) -> float:
    """The smallest series scale that draws ``extent`` within ``limit`` mm."""
    return min(mu for mu in _series_values(extent / limit / 100.0, extent / limit * 100.0) if extent / mu <= limit)


def choose_scales(*, extent: tuple[float, float], v_ref: float | None = None, v_extent: float = 0.0,
                  a_ref: float | None = None, a_extent: float = 0.0,
                  overrides: Mapping[str, float] | None = None) -> Scales:
    """Scales for a scene: μl so the scheme (``extent`` = width, height in m) fits the sheet,
    μV and μa so the reference vectors (crank tip velocity and acceleration) are 80–120 mm,
    coarser when the plan would exceed its extent limit. ``overrides`` win."""
    overrides = overrides or {}
    mu_l = overrides.get("mu_l") or max(fitting_scale(extent[0], SCHEME_MM[0]), fitting_scale(extent[1], SCHEME_MM[1]))
    mu_v = mu_a = None
    if v_ref is not None:
        mu_v = overrides.get("mu_v") or standard_scale(v_ref, limit=PLAN_MAX_MM, extent=v_extent)
    if a_ref is not None:
        mu_a = overrides.get("mu_a") or standard_scale(a_ref, limit=PLAN_MAX_MM, extent=a_extent)
    return Scales(mu_l=mu_l, mu_v=mu_v, mu_a=mu_a)


def extent_of(points: np.ndarray) -> tuple[float, float]:
    """Width and height of the bounding box of points (…, 2), never zero."""
    pts = points.reshape(-1, 2)
    span = pts.max(axis=0) - pts.min(axis=0)
    return float(max(span[0], 1e-6)), float(max(span[1], 1e-6))

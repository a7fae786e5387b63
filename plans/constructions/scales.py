"""Scale factors μ = physical quantity / drawn length (per mm), from the standard series."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np

from ..errors import SceneError

__all__ = ["SERIES", "Scales", "standard_scale", "choose_scales", "REFERENCE_MM", "MAX_DRAWING_MM", "MIN_DRAWING_MM"]

#: Mantissas of the standard scale series; a scale is m·10^k.
SERIES = (1.0, 1.25, 2.0, 2.5, 4.0, 5.0, 8.0)
#: Wanted length of the reference vector (pa, πa) on a plan, mm.
REFERENCE_MM = (80.0, 120.0)
#: Largest extent of a plan before the scale is coarsened, mm: a plan this wide and high fits
#: the drawing area of an A3 sheet (portrait 272 × 375 mm, less room for labels), the largest
#: sheet plans draws on.
PLAN_MAX_MM = 240.0
#: Area the scheme must fit in, mm.
SCHEME_MM = (200.0, 140.0)
#: Largest drawing a scale given in [scales] may make, mm: as for the automatic plan scales, a
#: drawing this wide and high fits the drawing area of an A3 sheet, the largest plans draws on.
MAX_DRAWING_MM = PLAN_MAX_MM
#: Smallest drawing a scale given in [scales] may make, mm: a scheme or plan under 1 mm (three
#: pen widths) cannot be read or measured.
MIN_DRAWING_MM = 1.0
_SYMBOLS = {"mu_v": "μ_V", "mu_a": "μ_a"}
_NAMES = {"mu_l": ("the scheme", "m/mm"), "mu_v": ("the velocity plan", "(m/s)/mm"),
          "mu_a": ("the acceleration plan", "(m/s²)/mm")}


@dataclass(frozen=True)
class Scales:
    """μl in m/mm, μV in (m/s)/mm, μa in (m/s²)/mm (None when not computed)."""

    mu_l: float
    mu_v: float | None = None
    mu_a: float | None = None
    notes: tuple[str, ...] = ()   # which rule gave way to which, when they conflicted

    def as_dict(self) -> dict[str, float]:
        return {k: v for k, v in (("mu_l", self.mu_l), ("mu_v", self.mu_v), ("mu_a", self.mu_a)) if v is not None}


def _series_values(lo: float, hi: float, series: tuple[float, ...] = SERIES) -> list[float]:
    """Series scales m·10^k (m in ``series``) from below ``lo`` to above ``hi``, each the double
    nearest its decimal (written as text, so 1.25e-15 stays 1.25e-15 where rounding to 12
    decimals gave 0)."""
    kmin, kmax = math.floor(math.log10(lo)) - 1, math.ceil(math.log10(hi)) + 1
    return [float(f"{m:g}e{k}") for k in range(kmin, kmax + 1) for m in series]


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
    coarser when the plan would exceed its extent limit (``v_extent``, ``a_extent``: the
    largest width or height of a plan, pole included, m/s and m/s²). ``overrides`` win, unless
    they would draw larger than MAX_DRAWING_MM or smaller than MIN_DRAWING_MM: then a
    :class:`~plans.errors.SceneError` names the scale, the size and the automatic choice."""
    overrides = overrides or {}
    auto = {"mu_l": max(fitting_scale(extent[0], SCHEME_MM[0]), fitting_scale(extent[1], SCHEME_MM[1]))}
    size = {"mu_l": max(extent)}
    notes = []
    for key, ref, ext in (("mu_v", v_ref, v_extent), ("mu_a", a_ref, a_extent)):
        if ref is None:
            continue
        auto[key], size[key] = standard_scale(ref, limit=PLAN_MAX_MM, extent=ext), ext
        if ref > 0 and ref / auto[key] < REFERENCE_MM[0] and standard_scale(ref) != auto[key]:
            notes.append(f"{_SYMBOLS[key]} = {auto[key]:g}: the reference vector is {ref / auto[key]:.0f} mm, under "
                         f"the {REFERENCE_MM[0]:g}–{REFERENCE_MM[1]:g} mm rule, which gave way so that the whole plan "
                         f"({ext / auto[key]:.0f} mm across) fits an A3 sheet")
    mu = dict(auto)
    for key, value in overrides.items():
        if key not in auto:
            continue            # a plan that is not drawn (or at rest) needs no scale
        drawn = size[key] / value
        if not MIN_DRAWING_MM <= drawn <= MAX_DRAWING_MM:
            what, unit = _NAMES[key]
            bound = (f"more than the {MAX_DRAWING_MM:g} mm that fit an A3 sheet" if drawn > MAX_DRAWING_MM
                     else f"less than {MIN_DRAWING_MM:g} mm, too small to see")
            raise SceneError(f"{key} = {value:g} {unit} would draw {what} {drawn:.3g} mm across, {bound}; use "
                             f"e.g. {key} = {auto[key]:g} (the automatic choice) or leave it out", key=f"scales.{key}")
        mu[key] = value
    notes = [n for n in notes if n.split(" ")[0] not in {_SYMBOLS[k] for k in overrides}]
    return Scales(mu_l=mu["mu_l"], mu_v=mu.get("mu_v"), mu_a=mu.get("mu_a"), notes=tuple(notes))


def extent_of(points: np.ndarray) -> tuple[float, float]:
    """Width and height of the bounding box of points (…, 2), never zero."""
    pts = points.reshape(-1, 2)
    span = pts.max(axis=0) - pts.min(axis=0)
    return float(max(span[0], 1e-6)), float(max(span[1], 1e-6))

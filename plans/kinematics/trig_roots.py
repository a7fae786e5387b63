"""Seed 002's machinery for listing every assembly of a group, shared by the eliminations of
:mod:`plans.kinematics.assemblies` (revolute pairs) and :mod:`.assemblies_prismatic` (groups
with a sliding pair): the certified search for every real root of a trigonometric polynomial
(:func:`trig_roots`), the residual of two conditions linear in (cos ψ, sin ψ)
(:func:`cramer_residual`) and the quadratics (7) in u = tan(ψ/2) that give ψ (:func:`half_angle_roots`).

Angles in radians; the conditions' units are the caller's (the residuals are scaled to O(1)).
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from ..errors import SceneError

__all__ = ["GRID", "MIN_CELL", "trig_roots", "group_roots", "cramer_residual", "half_angle_roots"]

#: Cells of the first grid over φ ∈ [−π, π) (each cell is then refined or excluded, see :func:`trig_roots`).
GRID = 720
#: Smallest cell of the certified search, rad: a cell this small that can hold a root of f without
#: a sign change is a (near-)tangency, tried as a candidate root.
MIN_CELL = 1e-9
#: Samples of f over the circle: its Fourier coefficients are exact for a degree below half of it.
SAMPLES = 64

Coefficients = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]]


def cramer_residual(coefficients: Coefficients, scale: float):
    """f(φ) = (N_c² + N_s² − Δ²)·scale for the two conditions A_k cos ψ + B_k sin ψ = D_k
    (k = 0, 1; ``coefficients(φ)`` gives A, B, D of shape (2, n)), Δ = A₀B₁ − A₁B₀,
    N_c = D₀B₁ − D₁B₀, N_s = A₀D₁ − A₁D₀: zero exactly where the two conditions have a common
    solution on the unit circle (Cramer's rule: Δ cos ψ = N_c, Δ sin ψ = N_s for any solution,
    so where Δ = 0 both N vanish too). For A, B, D of degree ≤ 1 in cos φ, sin φ, f is a
    trigonometric polynomial of degree ≤ 4: at most 8 roots on the circle."""

    def f(phi):
        a, b, d = coefficients(np.atleast_1d(np.asarray(phi, dtype=float)))
        det = a[0] * b[1] - a[1] * b[0]
        nc = d[0] * b[1] - d[1] * b[0]
        ns = a[0] * d[1] - a[1] * d[0]
        return (nc * nc + ns * ns - det * det) * scale
    return f


def half_angle_roots(a: np.ndarray, b: np.ndarray, d: np.ndarray) -> list[float]:
    """Every ψ with A₀ cos ψ + B₀ sin ψ = D₀ that also meets A₁ cos ψ + B₁ sin ψ = D₁ (a, b, d:
    the two conditions' coefficients, shape (2,)); both of the first's roots where the two
    conditions coincide."""
    # Seed 002, (6) → (7): A cos ψ + B sin ψ = D with cos ψ = (1 − u²)/(1 + u²), sin ψ = 2u/(1 + u²)
    # is (A + D)u² − 2Bu + (D − A) = 0; its discriminant /4, A² + B² − D², decides whether the
    # condition has real ψ (≥ 0), rounding clipped to 0 (a rod stretched straight).
    disc = a[0] ** 2 + b[0] ** 2 - d[0] ** 2
    if disc < -1e-9 * (a[0] ** 2 + b[0] ** 2):
        return []
    r = math.sqrt(max(disc, 0.0))
    out = []
    for sign in (1.0, -1.0):
        # u = (B ± √disc)/(A + D) = (D − A)/(B ∓ √disc): whichever form is better conditioned
        num, den = b[0] + sign * r, a[0] + d[0]
        alt = (d[0] - a[0], b[0] - sign * r)
        if math.hypot(*alt) > math.hypot(num, den):
            num, den = alt
        psi = 2.0 * math.atan2(num, den)
        miss = abs(a[1] * math.cos(psi) + b[1] * math.sin(psi) - d[1])
        if miss <= 1e-6 * (abs(a[1]) + abs(b[1]) + abs(d[1])):
            out.append(psi)
    return out


def trig_roots(f) -> list[float]:
    """Every real root of the trigonometric polynomial f on [−π, π) (rad).

    Bracketing, certified: f's Fourier coefficients c_k are exact from SAMPLES = 64 samples (its
    degree, ≤ 5 in every elimination of plans, is far below the 32 the samples resolve), so
    |f'| ≤ L = Σ k·|c_k| (every computed k, the zero ones included). A cell [a, b] whose ends
    have one sign and |f(a)| + |f(b)| > L·(b − a) holds no root (a root t would give
    |f(a)| ≤ L(t − a) and |f(b)| ≤ L(b − t)); likewise |f''| ≤ L₂ = Σ k²·|c_k|, so f' keeps its
    sign over a cell where |f'(mid)| > L₂·(b − a)/2. The circle is cut into GRID cells; a cell
    with a sign change where f' keeps its sign holds one root, found by Brent's method, an
    excluded cell none, any other (an end's exact zero, or a sign change with three roots or an
    end's root and one inside) is halved, down to MIN_CELL: what is left is a (near-)double
    root (a tangency, where two assemblies merge), refined by minimising |f| over the run of
    such cells, and kept when |f| is rounding there (the completion's polish decides, in the end)."""
    from scipy.optimize import brentq, minimize_scalar     # only when a scene asks for the assemblies

    n = SAMPLES
    samples = f(-math.pi + 2.0 * math.pi * np.arange(n) / n)
    c = np.fft.rfft(samples) / n
    k = np.arange(len(c))
    lip = float(np.sum(2.0 * k * np.abs(c))) * (1.0 + 1e-9)
    curv = float(np.sum(2.0 * k * k * np.abs(c))) * (1.0 + 1e-9)       # ≥ |f''|

    def slope(t):           # f'(t) = −2 Σ k·Im(c_k e^{ik(t + π)})
        return -2.0 * np.sum(np.imag(np.exp(1j * np.outer(t + math.pi, k)) * (k * c)), axis=1)
    noise = 1e-12 * float(np.max(np.abs(samples)) + 1e-300)      # f's rounding, relative to its size
    a = -math.pi + 2.0 * math.pi * np.arange(GRID) / GRID
    b = a + 2.0 * math.pi / GRID
    fa, fb = f(a), f(b)
    roots: list[float] = [float(x) for x in a[fa == 0.0]]
    leftovers: list[tuple[float, float]] = []
    while a.size:
        last = b[0] - a[0] < MIN_CELL or a.size > 100000
        # a sign change holds one root where f' keeps its sign: |f'(m)| > max|f''|·(b − a)/2;
        # otherwise (three roots, or an end's root and one inside) the cell is halved like any other
        change = (fa * fb < 0.0) & (last | (np.abs(slope(0.5 * (a + b))) > 0.5 * curv * (b - a)))
        roots += [brentq(lambda t: float(f(t)[0]), lo, hi, xtol=1e-15, rtol=1e-15) for lo, hi in zip(a[change], b[change])]
        doubt = ~change & (np.abs(fa) + np.abs(fb) <= lip * (b - a) + noise)
        a, b, fa, fb = a[doubt], b[doubt], fa[doubt], fb[doubt]
        if a.size == 0:
            break
        if last:
            leftovers += list(zip(a, b))
            break
        m = 0.5 * (a + b)
        fm = f(m)
        roots += [float(x) for x in m[fm == 0.0]]
        a, b, fa, fb = np.concatenate([a, m]), np.concatenate([m, b]), np.concatenate([fa, fm]), np.concatenate([fm, fb])
    for lo, hi in _runs(leftovers):
        sign = 1.0 if f(0.5 * (lo + hi))[0] >= 0.0 else -1.0
        best = minimize_scalar(lambda t: sign * float(f(t)[0]), bounds=(lo, hi), method="bounded",
                               options={"xatol": 1e-15})
        if abs(float(f(best.x)[0])) <= 1e3 * noise:
            roots.append(float(best.x))
    return sorted(roots)


def _runs(cells: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """Adjacent cells joined into runs (lo, hi)."""
    out: list[list[float]] = []
    for lo, hi in sorted(cells):
        if out and lo <= out[-1][1] + 1e-15:
            out[-1][1] = max(out[-1][1], hi)
        else:
            out.append([lo, hi])
    return [(lo, hi) for lo, hi in out]


def group_roots(g, f, unknown: str) -> list[float]:
    """The roots of group ``g``'s residual f (scaled to O(1)) by :func:`trig_roots`, after refusing an f
    that is rounding (≤ 1e-13) at 64 samples: the conditions then hold at every value of the
    ``unknown`` (a continuum of assemblies, e.g. a parallelogram), and the search would list its noise."""
    probe = f(np.linspace(-math.pi, math.pi, 64, endpoint=False))
    if not np.any(np.abs(probe) > 1e-13):
        raise SceneError(f"group {g.name} (form {g.form}): its conditions hold at every {unknown} (a continuum "
                         "of assemblies); leave \"assemblies\" out of draw", key="plans.draw")
    return trig_roots(f)

"""Functions of the crank's turned angle θ (rad) held exactly enough to integrate and search:
a polynomial of degree :data:`NODES` − 1 on each panel, through the values at the panel's
Gauss–Legendre nodes. Integrals of such a function are its Gauss quadrature (exact for the
polynomial); a smooth integrand on panels of 1° is held to ~1e-15 of its size, and every kink
or jump of a load (a law's knot, the end of a stroke) is a panel edge, never inside a panel.
"""

from __future__ import annotations

import bisect
import functools
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import legendre
from .. import linalg as la

__all__ = ["NODES", "Piecewise", "nodes_of", "fit"]

#: Gauss–Legendre nodes per panel (degree 7 polynomials; a panel's quadrature is exact to degree 15).
NODES = 8
_T, _W = legendre.leggauss(NODES)
#: How far (in half panel widths) an extended Piecewise continues its end panels' polynomials.
REACH = 1e3
_V_INV = la.inv(legendre.legvander(_T, NODES - 1))


def nodes_of(edges: np.ndarray) -> np.ndarray:
    """The Gauss nodes (P·NODES,) of the panels between ``edges`` (P + 1,), panel by panel."""
    a, b = edges[:-1, None], edges[1:, None]
    return (0.5 * (a + b) + 0.5 * (b - a) * _T[None, :]).ravel()


@dataclass(frozen=True, eq=False)
class Piecewise:
    """A piecewise polynomial on ``edges`` (P + 1,) with Legendre coefficients ``coef`` (P, K)
    on each panel's local t ∈ [−1, 1]."""

    edges: np.ndarray
    coef: np.ndarray
    #: beyond the first and last edges: the end panel's polynomial continued (True; up to
    #: :data:`REACH` panel widths, far past where it means anything: finite values for an
    #: integrator's trial step there to reject) or the value at the edge (False)
    extend: bool = False

    def __call__(self, theta: np.ndarray | float) -> np.ndarray:
        shape = np.shape(theta)
        theta = np.atleast_1d(np.asarray(theta, dtype=float)).ravel()
        k = np.clip(np.searchsorted(self.edges, theta, side="right") - 1, 0, len(self.edges) - 2)
        a, b = self.edges[k], self.edges[k + 1]
        t = (2.0 * theta - a - b) / (b - a)
        t = np.clip(t, -REACH, REACH) if self.extend else np.clip(t, -1.0, 1.0)
        c = self.coef[k]
        # Σ_j P_j(t)·c_j, the Legendre recurrence and the sum in a fixed order (element by
        # element: the same bits on every processor, and the same as :meth:`at`)
        p0, p1 = np.ones_like(t), t
        acc = p0 * c[:, 0]
        if c.shape[1] > 1:
            acc = acc + p1 * c[:, 1]
        for j in range(2, c.shape[1]):
            p0, p1 = p1, (p1 * t * (2 * j - 1) - p0 * (j - 1)) / j
            acc = acc + p1 * c[:, j]
        return acc.reshape(shape)

    def at(self, theta: float) -> float:
        """The value at one θ (rad) on Python floats: bit for bit ``float(self(theta))``, without
        numpy's per-call cost (an integrator's right-hand side calls it tens of thousands of times)."""
        edges = self._edges
        k = min(max(bisect.bisect_right(edges, theta) - 1, 0), len(edges) - 2)
        a, b = edges[k], edges[k + 1]
        t = (2.0 * theta - a - b) / (b - a)
        lim = REACH if self.extend else 1.0
        t = min(max(t, -lim), lim)
        c = self._rows[k]
        p0, p1 = 1.0, t
        acc = p0 * c[0]
        if len(c) > 1:
            acc = acc + p1 * c[1]
        for j in range(2, len(c)):
            p0, p1 = p1, (p1 * t * (2 * j - 1) - p0 * (j - 1)) / j
            acc = acc + p1 * c[j]
        return acc

    @functools.cached_property
    def _edges(self) -> list[float]:
        return self.edges.tolist()

    @functools.cached_property
    def _rows(self) -> list[list[float]]:
        return self.coef.tolist()

    def between(self, lo: float, hi: float) -> Piecewise:
        """The panels from the edge nearest ``lo`` to the edge nearest ``hi``, the end panels'
        polynomials continued beyond them: smooth across ``lo`` and ``hi`` (an integrator that
        stops at a kink of a load must not see the kink in the step that overshoots it)."""
        k0 = int(np.argmin(np.abs(self.edges - lo)))
        k1 = int(np.argmin(np.abs(self.edges - hi)))
        return Piecewise(self.edges[k0:k1 + 1], self.coef[k0:k1], extend=True)

    def integral(self, at_start: float = 0.0) -> Piecewise:
        """The antiderivative, ``at_start`` at the first edge, continuous across the edges."""
        half = 0.5 * np.diff(self.edges)[:, None]
        c = legendre.legint(self.coef, axis=1) * half           # ∫ from t = −1 (lbnd −1 … set below)
        c = c - legendre.legval(-1.0, c.T)[:, None] * np.eye(c.shape[1])[0]     # 0 at each panel's start
        ends = legendre.legval(1.0, c.T)
        start = at_start + np.concatenate([[0.0], np.cumsum(ends)[:-1]])
        c[:, 0] += start
        return Piecewise(self.edges, c)

    def total(self) -> float:
        """∫ over all panels."""
        return float(np.sum(np.diff(self.edges) * self.coef[:, 0]))

    def extreme(self, sign: float) -> tuple[float, float]:
        """(θ, value) of the largest (``sign`` +1) or smallest (−1) value, sampled at 33 points a
        panel and each edge, then refined by golden-section search around the best sample
        (a kink at an edge is found as well as a smooth top)."""
        m = 32
        t = np.linspace(self.edges[:-1], self.edges[1:], m + 1, axis=1).ravel()
        y = sign * self(t)
        j = int(np.argmax(y))
        lo, hi = t[max(j - 1, 0)], t[min(j + 1, len(t) - 1)]
        g = (np.sqrt(5.0) - 1.0) / 2.0
        x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
        f1, f2 = sign * float(self(x1)), sign * float(self(x2))
        for _ in range(80):
            if hi - lo <= 1e-15 * max(1.0, abs(hi)):
                break
            if f1 >= f2:
                hi, x2, f2 = x2, x1, f1
                x1 = hi - g * (hi - lo)
                f1 = sign * float(self(x1))
            else:
                lo, x1, f1 = x1, x2, f2
                x2 = lo + g * (hi - lo)
                f2 = sign * float(self(x2))
        best = max(((t[j], y[j]), (x1, f1), (x2, f2)), key=lambda p: p[1])
        return float(best[0]), sign * float(best[1])


def fit(edges: np.ndarray, values: np.ndarray) -> Piecewise:
    """The piecewise polynomial through ``values`` at :func:`nodes_of` (``edges``)."""
    y = np.asarray(values, dtype=float).reshape(len(edges) - 1, NODES)
    return Piecewise(np.asarray(edges, dtype=float), la.matmul(y, _V_INV.T))


def combine(*parts: tuple[float, Piecewise]) -> Piecewise:
    """Σ wᵢ·fᵢ of piecewise polynomials on the same edges (degrees may differ)."""
    k = max(p.coef.shape[1] for _, p in parts)
    edges = parts[0][1].edges
    coef = np.zeros((len(edges) - 1, k))
    for w, p in parts:
        coef[:, :p.coef.shape[1]] += w * p.coef
    return Piecewise(edges, coef)

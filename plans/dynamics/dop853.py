"""SciPy's DOP853 with its stage sums taken by :mod:`plans.linalg`: the same steps, and so the
same bits, on every processor.

SciPy's Runge–Kutta solvers combine their stages with ``np.dot`` and measure the error with
``np.linalg.norm``; both call OpenBLAS, whose kernels (picked for the processor) round the
last bit differently. An adaptive integrator amplifies that: one step accepted on one machine
and rejected on another changes every later step (a start-up took 20 498 evaluations on one
processor, 20 597 on another, its samples agreeing only to the tolerance). :class:`DOP853`
keeps SciPy's method, coefficients, step-size control, dense output and events (it is an
:class:`scipy.integrate.OdeSolver`, passed to ``solve_ivp`` as ``method``), and replaces those
sums and norms by fixed-order ones. Its first step follows Hairer's rule (Solving ODEs I,
II.4), as SciPy's does.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import DOP853 as _ScipyDOP853, DenseOutput

from .. import linalg as la

__all__ = ["DOP853"]

SAFETY = 0.9        # SciPy's step-size control: safety factor, and the bounds of one change
MIN_FACTOR = 0.2
MAX_FACTOR = 10.0


def _rms(x: np.ndarray) -> float:
    """√(Σx²/n): the error norm of SciPy's solvers, by a fixed-order sum."""
    return la.norm(x) / x.size ** 0.5


class DOP853(_ScipyDOP853):
    """Explicit Runge–Kutta of order 8 (5, 3 error estimators, order-7 dense output); see the
    module. Arguments as :class:`scipy.integrate.DOP853`."""

    def __init__(self, fun, t0, y0, t_bound, max_step=np.inf, rtol=1e-3, atol=1e-6,
                 vectorized=False, first_step=None, **extraneous) -> None:
        given = first_step
        if given is None and t_bound != t0:
            first_step = abs(t_bound - t0)       # a placeholder: the rule below needs f(t0)
        super().__init__(fun, t0, y0, t_bound, max_step, rtol, atol, vectorized, first_step, **extraneous)
        if given is None and t_bound != t0:
            self.h_abs = self._first_step()

    def _first_step(self) -> float:
        """Hairer's initial step: h0 from ‖y0‖/‖f0‖, h1 from the change of f over h0."""
        y0, f0 = self.y, self.f
        if y0.size == 0:
            return np.inf
        interval = abs(self.t_bound - self.t)
        scale = self.atol + np.abs(y0) * self.rtol
        d0, d1 = _rms(y0 / scale), _rms(f0 / scale)
        h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
        h0 = min(h0, interval)
        f1 = self.fun(self.t + h0 * self.direction, y0 + h0 * self.direction * f0)
        d2 = _rms((f1 - f0) / scale) / h0
        if d1 <= 1e-15 and d2 <= 1e-15:
            h1 = max(1e-6, h0 * 1e-3)
        else:
            h1 = (0.01 / max(d1, d2)) ** (1.0 / (self.error_estimator_order + 1))
        return min(100.0 * h0, h1, interval, self.max_step)

    def _stages(self, t: float, y: np.ndarray, f: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray]:
        """One step's stages into K; returns y(t + h), f(t + h)."""
        k = self.K
        k[0] = f
        for s, (a, c) in enumerate(zip(self.A[1:], self.C[1:]), start=1):
            k[s] = self.fun(t + c * h, y + la.matmul(a[:s], k[:s]) * h)
        y_new = y + h * la.matmul(self.B, k[:-1])
        f_new = self.fun(t + h, y_new)
        k[-1] = f_new
        return y_new, f_new

    def _error_norm(self, h: float, scale: np.ndarray) -> float:
        err5 = la.matmul(self.E5, self.K) / scale
        err3 = la.matmul(self.E3, self.K) / scale
        e5, e3 = la.dot(err5, err5), la.dot(err3, err3)
        if e5 == 0.0 and e3 == 0.0:
            return 0.0
        return abs(h) * e5 / np.sqrt((e5 + 0.01 * e3) * len(scale))

    def _step_impl(self):
        t, y = self.t, self.y
        min_step = 10 * np.abs(np.nextafter(t, self.direction * np.inf) - t)
        h_abs = min(max(self.h_abs, min_step), self.max_step)
        rejected = False
        while True:
            if h_abs < min_step:
                return False, self.TOO_SMALL_STEP
            t_new = t + h_abs * self.direction
            if self.direction * (t_new - self.t_bound) > 0:
                t_new = self.t_bound
            h = t_new - t
            h_abs = np.abs(h)
            y_new, f_new = self._stages(t, y, self.f, h)
            scale = self.atol + np.maximum(np.abs(y), np.abs(y_new)) * self.rtol
            error = self._error_norm(h, scale)
            if error < 1:
                factor = MAX_FACTOR if error == 0 else min(MAX_FACTOR, SAFETY * error ** self.error_exponent)
                h_abs *= min(1.0, factor) if rejected else factor
                break
            h_abs *= max(MIN_FACTOR, SAFETY * error ** self.error_exponent)
            rejected = True
        self.h_previous, self.y_old = h, y
        self.t, self.y, self.h_abs, self.f = t_new, y_new, h_abs, f_new
        return True, None

    def _dense_output_impl(self):
        k = self.K_extended
        h = self.h_previous
        for s, (a, c) in enumerate(zip(self.A_EXTRA, self.C_EXTRA), start=self.n_stages + 1):
            k[s] = self.fun(self.t_old + c * h, self.y_old + la.matmul(a[:s], k[:s]) * h)
        f = np.empty((self.D.shape[0] + 3, self.n), dtype=self.y_old.dtype)
        delta = self.y - self.y_old
        f[0] = delta
        f[1] = h * k[0] - delta
        f[2] = 2 * delta - h * (self.f + k[0])
        f[3:] = h * la.matmul(self.D, k)
        return _Dense(self.t_old, self.t, self.y_old, f)


class _Dense(DenseOutput):
    """DOP853's order-7 continuous extension on one step (SciPy's, element-wise only)."""

    def __init__(self, t_old: float, t: float, y_old: np.ndarray, f: np.ndarray) -> None:
        super().__init__(t_old, t)
        self.h, self.f, self.y_old = t - t_old, f, y_old

    def _call_impl(self, t: np.ndarray) -> np.ndarray:
        x = (t - self.t_old) / self.h
        if t.ndim == 0:
            y = np.zeros_like(self.y_old)
        else:
            x = x[:, None]
            y = np.zeros((len(x), len(self.y_old)), dtype=self.y_old.dtype)
        for i, f in enumerate(reversed(self.f)):
            y += f
            y *= x if i % 2 == 0 else 1 - x
        y += self.y_old
        return y.T

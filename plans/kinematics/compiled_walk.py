"""A class III/IV group's positions over a whole walk, with its compiled equations.

:func:`walk` finds the group's poses at every grid position of a sweep without stepping
Newton through every 1° step in Python:

1. an adaptive continuation over a coarse subset of the sweep's positions: tangent
   predictor (q' from J·q' = −∂Φ/∂x, ∂Φ/∂x by differences of the known links' points on the
   grid), Newton corrector, the step halved when Newton fails or the corrector lands far
   from the predictor (a jump), doubled again when the path is smooth;
2. batched Newton at every grid position at once, seeded by cubic Hermite interpolation
   between the coarse nodes (so close that the Jacobians of the seeds, inverted once for
   all positions, serve every step: :meth:`CompiledGroup.chord`; a position that does not
   converge so goes on with full Newton, :meth:`CompiledGroup.newton`);
3. the walk's own acceptance tests, vectorised over the whole sweep: every position
   converged, none far from its seed, and no step moving more than ``JUMP_RATIO`` times
   the step before (the jump test of the step-by-step walk).

When any of these fails the caller falls back to the step-by-step walk, which then reports
the failure (group, angle, reason) exactly as before; when they pass, every position is the
root the step-by-step walk reaches (the same branch, to rounding).
"""

from __future__ import annotations

import numpy as np

from .compiled import CompiledGroup, _max_abs
from .tolerances import COARSE_RTOL
from .. import linalg as la

__all__ = ["walk"]


def _hermite(q0, t0, q1, t1, x0, x1, x):
    """The cubic with values q0, q1 and slopes t0, t1 at x0, x1, at x (also beyond x1)."""
    h = x1 - x0
    s = ((np.asarray(x) - x0) / h)
    s = s[:, None] if np.ndim(s) == 1 else s
    h00 = (1 + 2 * s) * (1 - s) ** 2
    h10 = s * (1 - s) ** 2
    h01 = s * s * (3 - 2 * s)
    h11 = s * s * (s - 1)
    return h00 * q0 + h10 * h * t0 + h01 * q1 + h11 * h * t1


def _neighbours(x: np.ndarray, j: np.ndarray, step: float) -> tuple[np.ndarray, np.ndarray]:
    """Sweep positions around ``j`` at least about half a step apart (for differences)."""
    last = len(x) - 1
    lo, hi = np.maximum(j - 1, 0), np.minimum(j + 1, last)
    for _ in range(8):
        short = np.abs(x[hi] - x[lo]) < 0.5 * step
        if not short.any():
            break
        lo = np.where(short, np.maximum(lo - 1, 0), lo)
        hi = np.where(short, np.minimum(hi + 1, last), hi)
    return lo, hi


#: The coarse continuation's largest and first strides, in grid positions.
MAX_STRIDE = 64
FIRST_STRIDE = 16
#: A coarse step is accepted when Newton converges within this many iterations and its
#: corrector moves at most CORRECTOR × the step's own movement (else the step is halved).
COARSE_ITER = 5
CORRECTOR = 0.3
#: ... and the next stride is doubled when the corrector moved at most GROW × that.
GROW = 0.1
COARSE_TOLERANCE = COARSE_RTOL     # the coarse nodes' Newton stops there (× size); see tolerances.py
#: A position of the batched solve may lie at most SEED × its coarse interval's movement
#: from its interpolated seed (else: another branch may have been found; fall back).
SEED = 0.2


def walk(group: CompiledGroup, sweep: np.ndarray, x: np.ndarray, q0: np.ndarray, step: float,
         jump_ratio: float) -> np.ndarray | None:
    """Poses (len(sweep), n) at the grid positions ``sweep`` (drive values ``x``, monotone,
    the first already solved: ``q0``), or None when the fast continuation is not sure (the
    caller then walks step by step)."""
    m = len(sweep)
    n = group.n
    out = np.empty((m, n))
    out[0] = q0
    if m == 1:
        return out
    size = group.size
    cols = group.cols
    scale = np.ones(n)
    scale[2::3] = size          # compare poses in metres: angles × size

    limit = COARSE_TOLERANCE * size

    def settle(q: np.ndarray, idx: np.ndarray):
        """Newton (no polish) at a few positions: q, convergence, iterations and the
        Jacobian at the returned q."""
        it = 0
        for it in range(COARSE_ITER + 1):
            phi, a = group.evaluate(q, idx)
            r = np.abs(phi).max(axis=1)
            ok = r <= limit
            if it == COARSE_ITER or ok.all() or not np.isfinite(r).all():
                return q, ok, it, a
            try:
                dx = la.solve(a, -phi[..., None])[..., 0]
            except np.linalg.LinAlgError:
                return q, ok & False, it, a
            dx[:, 2::3] /= size
            q = q + np.where(ok[:, None], 0.0, dx)
        return q, ok, it, a

    def tangents(j: np.ndarray, q: np.ndarray, a: np.ndarray) -> np.ndarray | None:
        lo, hi = _neighbours(x, j, step)
        dphi = group.difference(q, sweep[hi], sweep[lo]) / (x[hi] - x[lo])[:, None]
        try:
            t = la.solve(a, -dphi[..., None])[..., 0]
        except np.linalg.LinAlgError:
            return None
        if not np.isfinite(t).all():
            return None
        t[:, 2::3] /= size
        return t

    # 1. adaptive coarse continuation; each step tries the stride, twice and three times it at once
    _, a0 = group.evaluate(q0[None, :], sweep[:1])
    t0 = tangents(np.array([0]), q0[None, :], a0)
    if t0 is None:
        return None
    nodes, qs, ts = [0], [q0], [t0[0]]
    stride = FIRST_STRIDE
    j = 0
    while j < m - 1:
        ks = np.array(sorted({min(j + stride * i, m - 1) for i in (1, 2, 3)}))
        hk = (x[ks] - x[j])[:, None]
        if len(nodes) > 1:     # third order: the Hermite cubic of the last two nodes, extended
            guess = _hermite(qs[-2], ts[-2], qs[-1], ts[-1], x[nodes[-2]], x[j], x[ks])
        else:
            guess = qs[-1] + hk * ts[-1]
        q, conv, it, a = settle(guess, sweep[ks])
        moved = np.max(np.abs((q - qs[-1]) * scale), axis=1)
        corr = np.max(np.abs((q - guess) * scale), axis=1)
        good = conv & (corr <= CORRECTOR * moved + 1e-9 * size)
        take = int(np.argmin(good)) if not good.all() else len(ks)    # the accepted prefix
        if take == 0:
            if stride == 1:
                return None
            stride = max(stride // 2, 1)
            continue
        t = tangents(ks[:take], q[:take], a[:take])
        if t is None:
            return None
        nodes += list(ks[:take])
        qs += list(q[:take])
        ts += list(t)
        stride = int(ks[take - 1] - j)
        if take == len(ks) and corr[take - 1] <= GROW * moved[take - 1] + 1e-9 * size:
            stride *= 2
        stride = max(1, min(stride, MAX_STRIDE))
        j = int(ks[take - 1])
    nodes = np.array(nodes)
    qs = np.array(qs)
    ts = np.array(ts)

    # 2. batched Newton everywhere, from cubic Hermite seeds
    seg = np.clip(np.searchsorted(nodes, np.arange(m), side="right") - 1, 0, len(nodes) - 2)
    a, b = nodes[seg], nodes[seg + 1]
    seed = _hermite(qs[seg], ts[seg], qs[seg + 1], ts[seg + 1], x[a][:, None], x[b][:, None], x[:, None])
    seed[nodes] = qs
    q, res, conv, _ = group.chord(seed[1:], sweep[1:])     # the nodes are polished here too
    if not conv.all():
        return None
    out[1:] = q

    # 3. the walk's acceptance tests
    interval = np.max(np.abs((qs[1:] - qs[:-1]) * scale), axis=1)     # per coarse interval
    off = _max_abs((out - seed) * scale)
    if np.any(off > SEED * interval[seg] + 1e-9 * size):
        return None
    moved = _max_abs(np.diff(out[:, cols], axis=0))
    before = np.concatenate([[0.0], moved[:-1]])
    if np.any((moved > 0.01 * size) & (moved > jump_ratio * before)):
        return None
    return out



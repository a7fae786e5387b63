"""A class III/IV group's pair equations compiled once, and its positions over a whole walk.

:class:`CompiledGroup` holds the same equations as :class:`~plans.kinematics.generic.GroupEquations`
(revolute pair: X_a(P) − X_b(P) = 0; prismatic pair: θ_s − θ_g = 0, (X_s − Y_g)·n_g = 0),
but as index arrays of local coordinates, with the known links' points precomputed at
every position of the walk's grid: one residual + Jacobian evaluation is a few dozen numpy
operations, for one position or for all of them at once. Rows and columns are scaled as in
``GroupEquations`` (angle columns ÷ size, angle rows × size: every entry dimensionless).

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

:class:`GroupRates` solves a group's velocities and accelerations at the requested positions
with the compiled Jacobian (which also gives the condition figure).
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass
from typing import Mapping

import numpy as np

from ..model import Mechanism
from .generic import TOLERANCE, GroupEquations, _with_rates
from .tolerances import COARSE_RTOL, MAX_ITER
from .state import LinkState, _spin, cos_sin

__all__ = ["CompiledGroup", "GroupRates", "walk"]

States = Mapping[str, LinkState]


#: From this many angles on, cos θ and sin θ come from :func:`~plans.kinematics.state.cos_sin`
#: (numpy's tan is vectorised: 3× faster, within one ulp of np.cos, np.sin); below it numpy's
#: per-call overhead dominates and np.cos, np.sin are faster.
TRIG_BATCH = 64


def _cos_sin(th: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """cos θ, sin θ of an array of angles, by the faster route for its size."""
    if th.size >= TRIG_BATCH:
        return cos_sin(th)
    return np.cos(th), np.sin(th)


#: Matrix products of many positions are taken in blocks of this many rows: a block's product
#: (≤ 512 × 48 × 8 multiply-adds) stays below the size from which OpenBLAS splits a product over
#: threads, which for these skinny products is no gain and, on a busy machine, waits milliseconds
#: for a second thread (measured: a class IV group at 3600 positions 3× slower).
PRODUCT_ROWS = 512


def _product(a: np.ndarray, w: np.ndarray) -> np.ndarray:
    """a @ w for a (M, K), w (K, N), in blocks of PRODUCT_ROWS rows."""
    m = len(a)
    if m <= PRODUCT_ROWS:
        return a @ w
    out = np.empty((m, w.shape[1]))
    for lo in range(0, m, PRODUCT_ROWS):
        np.matmul(a[lo:lo + PRODUCT_ROWS], w, out=out[lo:lo + PRODUCT_ROWS])
    return out


# the 2×2 minors of a 4×4 matrix's rows (0, 1) and (2, 3) on the column pairs (i, j), and the
# signs pairing each with its complement (Laplace's expansion by complementary minors)
_PAIRS_I = np.array([0, 0, 0, 1, 1, 2])
_PAIRS_J = np.array([1, 2, 3, 2, 3, 3])
_COMPLEMENT = np.array([5, 4, 3, 2, 1, 0])
_PAIR_SIGN = np.array([1.0, -1.0, 1.0, 1.0, -1.0, 1.0])


def _det(m: np.ndarray) -> np.ndarray:
    """det of every matrix of m (M, k, k): a 4×4 one (a class III/IV group's k) by Laplace's
    expansion over 2×2 minors (a few array operations, where numpy's LU costs ~0.2 µs a
    matrix), else numpy's. Used for signs away from zero (the exact figure comes from the SVD
    wherever it is small)."""
    if m.shape[-1] != 4:
        return np.linalg.det(m)
    top = m[:, 0, _PAIRS_I] * m[:, 1, _PAIRS_J] - m[:, 0, _PAIRS_J] * m[:, 1, _PAIRS_I]
    low = m[:, 2, _PAIRS_I] * m[:, 3, _PAIRS_J] - m[:, 2, _PAIRS_J] * m[:, 3, _PAIRS_I]
    return (top * low[:, _COMPLEMENT]) @ _PAIR_SIGN


def _max_abs(m: np.ndarray) -> np.ndarray:
    """max |m[i, j]| over j for every row i of m (M, n): the same numbers as
    np.max(np.abs(m), axis=1), reduced column by column (numpy reduces a short contiguous
    axis row by row, several times slower)."""
    out = np.empty(m.shape[::-1]).T
    np.abs(m, out=out)
    return out.max(axis=1)


#: The constant factors of :meth:`CompiledGroup._reduced`, by the group's equations (a few groups).
_REDUCED: dict = {}


@dataclass(frozen=True)
class _Constants:
    """What a group's compiled equations hold that depends on the mechanism only: Φ = known +
    T·q + Mc·cos θ + Ms·sin θ for the revolute pairs (T = ``template``; ``t``, ``mc``, ``ms``
    transposed for q @ …; ``jc``, ``js``: Mc, Ms ÷ size, the angle columns of A), the known
    links' pins (row, link, local point, sign) and the prismatic pairs (row, pair)."""

    n: int
    size: float
    index: dict[str, int]
    template: np.ndarray
    t: np.ndarray
    mc: np.ndarray
    ms: np.ndarray
    jc: np.ndarray
    js: np.ndarray
    cols: list[int]
    known_pins: tuple
    prismatic: tuple
    w: np.ndarray          # [T; Mc; Ms] transposed: [q, cos θ, sin θ] @ w = T·q + Mc·cos θ + Ms·sin θ
    k: np.ndarray          # [cos θ, sin θ] @ k = the angle columns of A, row by row (n·k values)


#: The constants of a few groups, by (id of the mechanism, links, pairs), with a weak reference
#: to the mechanism (an id can be reused once it is gone): analysing a mechanism again does
#: not build them again.
_CONSTANTS: dict = {}


def _constants(mech: Mechanism, links: tuple[str, ...], pairs: tuple) -> _Constants:
    """The group's mechanism-only data (see :class:`_Constants`), built once per mechanism."""
    key = (id(mech), links, pairs)
    hit = _CONSTANTS.get(key)
    if hit is not None and hit[0]() is mech:
        return hit[1]
    k = len(links)
    n = 3 * k
    if 2 * len(pairs) != n:
        raise ValueError("an Assur group has 3 equations per link: 2 per pair")
    size = float(mech.size)
    index = {name: i for i, name in enumerate(links)}
    loc = mech.links
    template = np.zeros((n, n))
    # revolute pairs: Φ = known + T·q + Mc·cos θ + Ms·sin θ (rows: x and y of each pair)
    mc = np.zeros((n, k))
    ms = np.zeros((n, k))
    known_pins, prismatic = [], []
    for k_pair, pair in enumerate(pairs):
        r = 2 * k_pair
        if pair.kind != "R":
            prismatic.append((r, pair.prismatic))
            continue
        for link, sign in ((pair.a, 1.0), (pair.b, -1.0)):
            local = loc[link].local[pair.point]
            if link not in index:
                known_pins.append((r, link, local, sign))
                continue
            L = index[link]
            template[r, 3 * L] += sign
            template[r + 1, 3 * L + 1] += sign
            mc[r, L] += sign * local[0]
            ms[r, L] -= sign * local[1]
            mc[r + 1, L] += sign * local[1]
            ms[r + 1, L] += sign * local[0]
    jc, js = mc / size, ms / size          # ∂Φ/∂θ = −sin θ·Mc + cos θ·Ms, θ scaled
    kmat = np.zeros((2 * k, n, k))
    for L in range(k):
        kmat[L, :, L] = js[:, L]
        kmat[k + L, :, L] = -jc[:, L]
    out = _Constants(n, size, index, template, np.ascontiguousarray(template.T), np.ascontiguousarray(mc.T),
                     np.ascontiguousarray(ms.T), jc, js, [c for c in range(n) if c % 3 != 2], tuple(known_pins),
                     tuple(prismatic), np.ascontiguousarray(np.concatenate([template.T, mc.T, ms.T])),
                     kmat.reshape(2 * k, n * k))
    if len(_CONSTANTS) >= 64:
        _CONSTANTS.clear()
    _CONSTANTS[key] = weakref.ref(mech), out
    return out


class CompiledGroup:
    """The pair equations of one group, with its known links' states over N positions."""

    def __init__(self, mech: Mechanism, links: tuple[str, ...], pairs: tuple, known: States):
        self.links = tuple(links)
        self.pairs = tuple(pairs)
        const = _constants(mech, self.links, self.pairs)
        self.n, self.size, self.index = const.n, const.size, const.index
        self.template, self._t, self._mc, self._ms, self._jc, self._js = \
            const.template, const.t, const.mc, const.ms, const.jc, const.js
        self.cols = const.cols
        self.known_pins = const.known_pins      # (row, link, local point, sign) of the known links' pins
        self._w, self._k = const.w, const.k
        n_pos = len(next(iter(known.values())).theta)
        self.n_pos = n_pos
        known_rows = np.zeros((n_pos, self.n))
        for r, link, local, sign in const.known_pins:
            known_rows[:, r:r + 2] += sign * known[link].point(local)
        self.known_rows = known_rows
        self.prismatic = []
        for r, p in const.prismatic:
            entry = {"row": r}
            for role, link in (("slider", p.slider), ("guide", p.guide)):
                anchor = p.anchor[link]
                if link in self.index:
                    entry[role] = (self.index[link], anchor)
                else:
                    st = known[link]
                    entry[role] = (None, (st.theta, st.point(anchor), st.origin,
                                          st.direction(p.normal) if role == "guide" else None))
            entry["normal"] = p.normal
            self.prismatic.append(entry)

    # -- equations -------------------------------------------------------------------------
    def evaluate(self, q: np.ndarray, idx: np.ndarray, jacobian: bool = True):
        """Scaled residual Φ (M, n) and, with ``jacobian``, scaled A (M, n, n) at poses ``q``
        (M, n) with the known links at grid positions ``idx`` (M,)."""
        th = q[:, 2::3]
        c, s = _cos_sin(th)
        qcs = np.concatenate((q, c, s), axis=1)
        phi = _product(qcs, self._w)           # T·q + Mc·cos θ + Ms·sin θ in one product
        phi += self.known_rows[idx]
        if jacobian:
            m, n = len(idx), self.n
            a = np.empty((m, n, n))
            a[:] = self.template
            a[:, :, 2::3] = _product(qcs[:, n:], self._k).reshape(m, n, n // 3)   # cos θ·Js − sin θ·Jc
        for e in self.prismatic:
            self._prismatic(e, q, c, s, idx, phi, a if jacobian else None)
        return (phi, a) if jacobian else phi

    def difference(self, q: np.ndarray, idx: np.ndarray, other: np.ndarray) -> np.ndarray:
        """Φ(q) with the known links at grid positions ``idx`` minus Φ(q) with them at ``other``
        (M, n): for revolute pairs only the known links' points differ (no evaluation)."""
        if not self.prismatic:
            return self.known_rows[idx] - self.known_rows[other]
        both = self.evaluate(np.concatenate([q, q]), np.concatenate([idx, other]), jacobian=False)
        return both[:len(q)] - both[len(q):]

    def _link_frame(self, L: int, q, c, s, local):
        """θ, world point of ``local``, origin and the rotation's (cos, sin) of group link L."""
        cl, sl = c[:, L], s[:, L]
        o = q[:, 3 * L:3 * L + 2]
        pt = o + np.column_stack([cl * local[0] - sl * local[1], sl * local[0] + cl * local[1]])
        return q[:, 3 * L + 2], pt, o, cl, sl

    def _prismatic(self, e, q, c, s, idx, phi, a) -> None:
        size, r = self.size, e["row"]
        nloc = e["normal"]
        Ls, sdat = e["slider"]
        Lg, gdat = e["guide"]
        if Ls is None:
            th_s, xs, os_ = sdat[0][idx], sdat[1][idx], sdat[2][idx]
        else:
            th_s, xs, os_, _, _ = self._link_frame(Ls, q, c, s, sdat)
        if Lg is None:
            th_g, yg, og, nrm = gdat[0][idx], gdat[1][idx], gdat[2][idx], gdat[3][idx]
        else:
            th_g, yg, og, cg, sg = self._link_frame(Lg, q, c, s, gdat)
            nrm = np.column_stack([cg * nloc[0] - sg * nloc[1], sg * nloc[0] + cg * nloc[1]])
        d = th_s - th_g
        gap = xs - yg
        phi[:, r] = size * np.arctan2(np.sin(d), np.cos(d))
        phi[:, r + 1] = gap[:, 0] * nrm[:, 0] + gap[:, 1] * nrm[:, 1]
        if a is None:
            return
        if Ls is not None:
            c0 = 3 * Ls
            rs = xs - os_
            a[:, r, c0 + 2] = 1.0
            a[:, r + 1, c0:c0 + 2] = nrm
            a[:, r + 1, c0 + 2] = (-rs[:, 1] * nrm[:, 0] + rs[:, 0] * nrm[:, 1]) / size
        if Lg is not None:
            c0 = 3 * Lg
            rg = yg - og
            a[:, r, c0 + 2] = -1.0
            a[:, r + 1, c0:c0 + 2] = -nrm
            a[:, r + 1, c0 + 2] = ((rg[:, 1] * nrm[:, 0] - rg[:, 0] * nrm[:, 1])
                                   + (-gap[:, 0] * nrm[:, 1] + gap[:, 1] * nrm[:, 0])) / size

    # -- Newton ------------------------------------------------------------------------------
    def newton(self, q: np.ndarray, idx: np.ndarray, *, maxiter: int = MAX_ITER, tol: float = TOLERANCE,
               polish: bool = True) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
        """Newton at every position at once from ``q`` (M, n): returns q, the final residuals
        (M,), convergence (M,) and the iterations taken. Converged positions stop moving;
        with ``polish`` each takes one more step, kept when it does not raise the residual
        (the step-by-step walk's rule)."""
        q = q.copy()
        limit = tol * self.size
        m = len(idx)
        res = np.full(m, np.inf)
        active = np.arange(m)
        done = np.zeros(m, dtype=bool)
        it = 0
        for it in range(maxiter + 1):
            phi, a = self.evaluate(q[active], idx[active])
            r = _max_abs(phi)
            res[active] = r
            ok = r <= limit
            bad = ~np.isfinite(r)
            if ok.any():
                done[active[ok]] = True
            keep = ~ok & ~bad
            if polish and ok.any():
                self._polish(q, active[ok], idx[active[ok]], a[ok], phi[ok], r[ok])
            if it == maxiter or not keep.any():
                break
            act = active[keep]
            try:
                dx = np.linalg.solve(a[keep], -phi[keep][..., None])[..., 0]
            except np.linalg.LinAlgError:
                break
            dx[:, 2::3] /= self.size
            q[act] += dx
            active = act
        return q, res, done, it

    def _polish(self, q, rows, idx, a, phi, res) -> None:
        try:
            dx = np.linalg.solve(a, -phi[..., None])[..., 0]
        except np.linalg.LinAlgError:
            return
        dx[:, 2::3] /= self.size
        trial = q[rows] + dx
        after = _max_abs(self.evaluate(trial, idx, jacobian=False))
        better = after <= res
        q[rows[better]] = trial[better]

    def chord(self, q: np.ndarray, idx: np.ndarray, *, maxiter: int = 10, tol: float = TOLERANCE
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
        """Newton with the Jacobian of the start kept (inverted once, for every position at
        once), for seeds already close to the solution; positions it does not bring below
        ``tol``·size within ``maxiter`` steps go on with :meth:`newton`. Converged positions
        take one more (polishing) step, kept when it does not raise the residual."""
        reduced = self._reduced()
        try:
            if reduced is None:
                phi, a = self.evaluate(q, idx)
                inv = np.linalg.inv(a)

                def step(phi):
                    return (inv @ phi[..., None])[..., 0]
            else:
                # revolute pairs only: A = [T B] (columns reordered), T constant = Q·[R₁; 0]:
                # only the k×k blocks Q₂ᵀB are inverted per position (see :meth:`_reduced`)
                phi = self.evaluate(q, idx, jacobian=False)
                step = self._block_solver(q)
        except np.linalg.LinAlgError:
            return self.newton(q, idx)
        q = q.copy()
        limit = tol * self.size
        m = len(idx)
        res = _max_abs(phi)
        done = np.zeros(m, dtype=bool)
        polished = np.zeros(m, dtype=bool)
        best = q.copy()
        best_res = np.full(m, np.inf)
        it = 0
        for it in range(maxiter + 2):
            ok = res <= limit
            # a converged position's first step below the limit is its polish: keep the better
            # (most steps change no position's state: the copies are skipped then)
            newly = ok & ~done
            if newly.any():
                np.copyto(best, q, where=newly[:, None])
                np.copyto(best_res, res, where=newly)
            finished = done & ~polished          # these have just taken their polish step
            if finished.any():
                pol = finished & (res <= best_res)
                np.copyto(best, q, where=pol[:, None])
                np.copyto(best_res, res, where=pol)
                polished |= finished
            done |= ok
            todo = ~polished
            everywhere = not polished.any()
            if not (everywhere or todo.any()) or it == maxiter + 1:
                break
            dx = step(phi)
            dx[:, 2::3] /= self.size
            if everywhere:
                q -= dx
            else:
                q -= np.where(todo[:, None], dx, 0.0)
            phi = self.evaluate(q, idx, jacobian=False)
            r = _max_abs(phi)
            res = r if everywhere else np.where(todo, r, res)
        out = np.where(polished[:, None], best, q)
        out_res = np.where(polished, best_res, res)
        conv = polished.copy()
        late = np.flatnonzero(~conv)
        if late.size:
            qn, rn, cn, _ = self.newton(q[late], idx[late])
            out[late], out_res[late], conv[late] = qn, rn, cn
        return out, out_res, conv, it

    def crossing_figure(self, q: np.ndarray, idx: np.ndarray, floor: float = 1e-5) -> np.ndarray:
        """A stand-in for the condition figure sign(det A)·σ_min/σ_max at poses ``q``, for
        the walk's crossing test only: the same sign, and the same value wherever the
        figure could be below ``floor``; elsewhere a lower bound of it (above ``floor``),
        σ_min ≥ |det A|·((n−1)/‖A‖_F²)^((n−1)/2) (Hong & Pan) and σ_max ≤ ‖A‖_F."""
        n = self.n
        reduced = self._reduced()
        if reduced is None:
            _, a = self.evaluate(q, idx)
            sign, logdet = np.linalg.slogdet(a)
            log_f = 0.5 * np.log(np.einsum("mij,mij->m", a, a))
        else:
            # revolute pairs only: A's translation columns T are constant, so with T = Q·[R; 0]
            # (once), det A = c0·det(Q₂ᵀ·B), B the k angle columns (Q₂ᵀB: k×k per position)
            c0_sign, c0_log, t_norm2, p_s, p_c = reduced
            th = q[:, 2::3]
            c, s = _cos_sin(th)
            det = _det(c[:, None, :] * p_s - s[:, None, :] * p_c)
            sign = c0_sign * np.sign(det)
            b = c[:, None, :] * self._js - s[:, None, :] * self._jc
            with np.errstate(divide="ignore"):
                logdet = c0_log + np.log(np.abs(det))
            log_f = 0.5 * np.log(t_norm2 + np.einsum("mij,mij->m", b, b))
        with np.errstate(all="ignore"):
            bound = np.exp(logdet + 0.5 * (n - 1) * (np.log(n - 1) - 2.0 * log_f) - log_f)
        bound = np.where(np.isfinite(bound), bound, 0.0)
        low = np.flatnonzero(bound < floor)
        if low.size:
            sv = np.linalg.svd(self.evaluate(q[low], idx[low])[1], compute_uv=False)
            bound[low] = sv[:, -1] / sv[:, 0]
        return sign * bound

    def _block_solver(self, q: np.ndarray):
        """x ↦ A⁻¹x (M, n) with A the scaled Jacobian at poses ``q`` of a revolute-only group."""
        _, _, _, p_s, p_c = self._reduced_
        q1t, r1_inv_t, q1_js, q1_jc = self._blocks
        th = q[:, 2::3]
        c, s = _cos_sin(th)
        c_inv = np.linalg.inv(c[:, None, :] * p_s - s[:, None, :] * p_c)    # (M, k, k)
        g = c[:, None, :] * q1_js - s[:, None, :] * q1_jc                      # Q₁ᵀB (M, 2k, k)
        cols = self.cols
        k2 = len(cols)

        def solve(phi: np.ndarray) -> np.ndarray:
            z = _product(phi, q1t)
            x_b = np.einsum("mij,mj->mi", c_inv, z[:, k2:])
            x_t = _product(z[:, :k2] - np.einsum("mij,mj->mi", g, x_b), r1_inv_t)
            out = np.empty_like(phi)
            out[:, cols] = x_t
            out[:, 2::3] = x_b
            return out
        return solve

    def _reduced(self):
        """For a group of revolute pairs only (else None): the constant factor of det A
        (its sign and log), ‖T‖_F² of the constant translation columns T, and Q₂ᵀ·Js, Q₂ᵀ·Jc,
        Q₂ the orthogonal complement of T's columns (see :meth:`crossing_figure`)."""
        if "_reduced_" in self.__dict__:
            return self._reduced_
        out = None
        n, k = self.n, self.n // 3
        key = (self.template.tobytes(), self._js.tobytes(), self._jc.tobytes()) if not self.prismatic else None
        if key in _REDUCED:          # the same equations again (another call of the same mechanism)
            self._reduced_, blocks = _REDUCED[key]
            if blocks is not None:
                self._blocks = blocks
            return self._reduced_
        if not self.prismatic:
            order = self.cols + list(range(2, n, 3))
            t = self.template[:, self.cols]
            qm, r = np.linalg.qr(t, mode="complete")
            diag = np.diag(r[:2 * k])
            if np.all(np.abs(diag) > 1e-9 * max(1.0, float(np.max(np.abs(diag))))):
                perm = np.eye(n)[:, order]
                c0 = np.linalg.det(perm) * np.linalg.det(qm)
                q2 = qm[:, 2 * k:]
                out = (float(np.sign(c0) * np.prod(np.sign(diag))), float(np.sum(np.log(np.abs(diag)))),
                       float(np.sum(t * t)), q2.T @ self._js, q2.T @ self._jc)
                q1 = qm[:, :2 * k]
                self._blocks = (np.ascontiguousarray(qm), np.ascontiguousarray(np.linalg.inv(r[:2 * k]).T),
                                q1.T @ self._js, q1.T @ self._jc)
        self._reduced_ = out
        if key is not None:
            if len(_REDUCED) >= 64:
                _REDUCED.clear()
            _REDUCED[key] = out, self.__dict__.get("_blocks")
        return out

    def condition(self, q: np.ndarray, idx: np.ndarray) -> np.ndarray:
        """sign(det A)·σ_min/σ_max of the scaled Jacobian (as GroupEquations.condition)."""
        _, a = self.evaluate(q, idx)
        sv = np.linalg.svd(a, compute_uv=False)
        return np.sign(np.linalg.det(a)) * sv[:, -1] / sv[:, 0]


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
                dx = np.linalg.solve(a, -phi[..., None])[..., 0]
            except np.linalg.LinAlgError:
                return q, ok & False, it, a
            dx[:, 2::3] /= size
            q = q + np.where(ok[:, None], 0.0, dx)
        return q, ok, it, a

    def tangents(j: np.ndarray, q: np.ndarray, a: np.ndarray) -> np.ndarray | None:
        lo, hi = _neighbours(x, j, step)
        dphi = group.difference(q, sweep[hi], sweep[lo]) / (x[hi] - x[lo])[:, None]
        try:
            t = np.linalg.solve(a, -dphi[..., None])[..., 0]
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


class GroupRates:
    """A class III/IV group's velocity and acceleration solves at its solved poses, sharing
    one scaled Jacobian A (the compiled group's, :meth:`CompiledGroup.evaluate`), which also
    gives the condition figure; for a group of revolute pairs only, right-hand sides assembled
    from the known links' pin motions without the generic per-pair terms (a group with a
    prismatic pair takes them from :class:`~plans.kinematics.generic.GroupEquations`).

    The same equations as ``GroupEquations.velocities``/``accelerations``, solved as they
    are (``numpy.linalg.solve``, LU with pivoting): the results agree to rounding (the tests
    compare both), and a link at rest comes out at rest exactly, as there. (The block
    solver of the walk, :meth:`CompiledGroup._block_solver`, leaves ~1e-17 of rounding on
    such a link, which the cross-check against the special points, relative to each link's
    own largest value, would report.)"""

    def __init__(self, mech: Mechanism, links: tuple[str, ...], pairs: tuple, states: States):
        self.mech = mech
        self.links = tuple(links)
        self.pairs = tuple(pairs)
        known = {name: s for name, s in states.items() if name not in self.links}
        self.group = group = CompiledGroup(mech, self.links, self.pairs, known)
        self.size = group.size
        self.col = {name: 3 * L for name, L in group.index.items()}
        n_pos = group.n_pos
        self.q = np.empty((n_pos, group.n))
        for name, c in self.col.items():
            s = states[name]
            self.q[:, c:c + 2] = s.origin
            self.q[:, c + 2] = s.theta
        self.idx = np.arange(n_pos)
        self._a: np.ndarray | None = None
        self.revolute_only = not group.prismatic

    def jacobian(self) -> np.ndarray:
        """The scaled Jacobian A (N, n, n) at the poses (computed once)."""
        if self._a is None:
            self._a = self.group.evaluate(self.q, self.idx)[1]
        return self._a

    def condition(self) -> np.ndarray:
        """sign(det A)·σ_min/σ_max of the scaled Jacobian (as GroupEquations.condition)."""
        a = self.jacobian()
        sv = np.linalg.svd(a, compute_uv=False)
        reduced = self.group._reduced()
        if reduced is None:
            sign = np.sign(np.linalg.det(a))
        else:     # det A = c0·det(Q₂ᵀB) (see CompiledGroup.crossing_figure): its sign, from k×k blocks
            c0_sign, _, _, p_s, p_c = reduced
            th = self.q[:, 2::3]
            c, s = _cos_sin(th)
            sign = c0_sign * np.sign(_det(c[:, None, :] * p_s - s[:, None, :] * p_c))
        return sign * sv[:, -1] / sv[:, 0]

    def _solve(self, rhs: np.ndarray) -> np.ndarray:
        """The group's rates x (N, n) from A·x = −rhs (rhs scaled as A's rows; x unscaled)."""
        x = np.linalg.solve(self.jacobian(), -rhs[..., None])[..., 0]
        x[:, 2::3] /= self.size
        return x

    def _known_rows(self, states: States, order: int) -> np.ndarray:
        """Σ ±(velocity, order 1, or acceleration, order 2) of the known links' points at the
        revolute pairs, in the pairs' rows (N, n); prismatic rows 0."""
        out = np.zeros((len(self.idx), self.group.n))
        for r, link, local, sign in self.group.known_pins:
            st = states[link]
            m = _spin_known(st, st.direction(local), order)
            if sign > 0:
                out[:, r:r + 2] += m
            else:
                out[:, r:r + 2] -= m
        return out

    def velocities(self, states: dict[str, LinkState]) -> None:
        """Solve the group's ω and v_o at every position (in place in ``states``)."""
        if self.revolute_only:
            rhs = self._known_rows(states, 1)
        else:
            rhs = self._generic_terms(states, 1)
        x = self._solve(rhs)
        for name, c in self.col.items():
            s = states[name]
            states[name] = s._keep_cos_sin(LinkState(s.theta, s.origin, x[:, c + 2].copy(), _columns(x, c)))

    def accelerations(self, states: dict[str, LinkState]) -> None:
        """Solve the group's ε and a_o at every position (in place in ``states``; the group's
        velocities solved)."""
        if self.revolute_only:
            rhs = self._known_rows(states, 2)
            g = self.group
            w = np.column_stack([states[name].omega for name in self.links])
            w2 = w * w
            th = self.q[:, 2::3]
            c, s = _cos_sin(th)
            # the group's links' centripetal terms: −ω²·R(θ)·local at every pin, with signs
            rhs -= _product(w2 * c, g._mc) + _product(w2 * s, g._ms)
        else:
            rhs = self._generic_terms(states, 2)
        x = self._solve(rhs)
        for name, c in self.col.items():
            s = states[name]
            states[name] = s._keep_cos_sin(LinkState(s.theta, s.origin, s.omega, s.v, x[:, c + 2].copy(),
                                                     _columns(x, c)))

    def _generic_terms(self, states: States, order: int) -> np.ndarray:
        eq = GroupEquations(self.mech, self.links, self.pairs)
        zero = {**states, **{n: _with_rates(states[n], order) for n in self.links}}
        terms = eq.velocity_terms(zero) if order == 1 else eq.acceleration_terms(zero)
        return eq._scale_rows(terms)


def _spin_known(st: LinkState, rel: np.ndarray, order: int) -> np.ndarray:
    """Velocity (order 1) or acceleration (2) of the point of known link ``st`` at ``rel``
    from its origin (N, 2)."""
    if order == 1:
        return _spin(st.v, st.omega, rel)
    w = st.omega
    return _spin(st.a, w, rel, w * w, st.epsilon)


def _columns(x: np.ndarray, c: int) -> np.ndarray:
    """x[:, c:c+2] as a fresh (N, 2) array stored by columns (as the rigid-body relations make them)."""
    out = np.empty((2, len(x))).T
    out[:] = x[:, c:c + 2]
    return out

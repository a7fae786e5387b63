"""A class III/IV group's pair equations compiled once.

:class:`CompiledGroup` holds the same equations as :class:`~plans.kinematics.generic.GroupEquations`
(revolute pair: X_a(P) − X_b(P) = 0; prismatic pair: θ_s − θ_g = 0, (X_s − Y_g)·n_g = 0),
but as index arrays of local coordinates, with the known links' points precomputed at
every position of the walk's grid: one residual + Jacobian evaluation is a few dozen numpy
operations, for one position or for all of them at once. Rows and columns are scaled as in
``GroupEquations`` (angle columns ÷ size, angle rows × size: every entry dimensionless).

The positions over a whole walk (:mod:`plans.kinematics.compiled_walk`) and the rate solves
(:mod:`plans.kinematics.compiled_rates`) use it.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass
from typing import Mapping

import numpy as np

from ..model import Mechanism
from .figure import polar_sine
from .generic import TOLERANCE
from .tolerances import MAX_ITER
from .state import LinkState, cos_sin
from .. import linalg as la

__all__ = ["CompiledGroup", "States"]

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
        return la.det(m)
    top = m[:, 0, _PAIRS_I] * m[:, 1, _PAIRS_J] - m[:, 0, _PAIRS_J] * m[:, 1, _PAIRS_I]
    low = m[:, 2, _PAIRS_I] * m[:, 3, _PAIRS_J] - m[:, 2, _PAIRS_J] * m[:, 3, _PAIRS_I]
    return la.matmul(top * low[:, _COMPLEMENT], _PAIR_SIGN)


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
    if len(_CONSTANTS) >= 64:          # drop the mechanisms gone, then the oldest: never the newest
        for dead in [k for k, (ref, _) in _CONSTANTS.items() if ref() is None]:
            del _CONSTANTS[dead]
        while len(_CONSTANTS) >= 64:
            del _CONSTANTS[next(iter(_CONSTANTS))]
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
        phi = la.matmul(qcs, self._w)           # T·q + Mc·cos θ + Ms·sin θ in one product
        phi += self.known_rows[idx]
        if jacobian:
            m, n = len(idx), self.n
            a = np.empty((m, n, n))
            a[:] = self.template
            a[:, :, 2::3] = la.matmul(qcs[:, n:], self._k).reshape(m, n, n // 3)   # cos θ·Js − sin θ·Jc
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
                dx = la.solve(a[keep], -phi[keep][..., None])[..., 0]
            except np.linalg.LinAlgError:
                break
            dx[:, 2::3] /= self.size
            q[act] += dx
            active = act
        return q, res, done, it

    def _polish(self, q, rows, idx, a, phi, res) -> None:
        try:
            dx = la.solve(a, -phi[..., None])[..., 0]
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
                inv = la.inv(a)

                def step(phi):
                    return np.einsum("mij,mj->mi", inv, phi)
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

    def condition(self, q: np.ndarray, idx: np.ndarray) -> np.ndarray | None:
        """The condition figure at poses ``q`` (N,) of a group of revolute pairs only, as
        :meth:`GroupEquations.condition <plans.kinematics.generic.GroupEquations.condition>`
        gives it: sign(det A) × the polar sine of Q₂ᵀ·B (k×k per position; see :meth:`_reduced`);
        None for a group with a prismatic pair (its figure needs the pairs' directions)."""
        reduced = self._reduced()
        if reduced is None:
            return None
        c0_sign, p_s, p_c = reduced
        c, s = _cos_sin(q[:, 2::3])
        m = c[:, None, :] * p_s - s[:, None, :] * p_c
        det = _det(m)
        return c0_sign * np.sign(det) * polar_sine(m, det)

    def _block_solver(self, q: np.ndarray):
        """x ↦ A⁻¹x (M, n) with A the scaled Jacobian at poses ``q`` of a revolute-only group."""
        _, p_s, p_c = self._reduced_
        q1t, r1_inv_t, q1_js, q1_jc = self._blocks
        th = q[:, 2::3]
        c, s = _cos_sin(th)
        c_inv = la.inv(c[:, None, :] * p_s - s[:, None, :] * p_c)    # (M, k, k)
        g = c[:, None, :] * q1_js - s[:, None, :] * q1_jc                      # Q₁ᵀB (M, 2k, k)
        cols = self.cols
        k2 = len(cols)

        def solve(phi: np.ndarray) -> np.ndarray:
            z = la.matmul(phi, q1t)
            x_b = np.einsum("mij,mj->mi", c_inv, z[:, k2:])
            x_t = la.matmul(z[:, :k2] - np.einsum("mij,mj->mi", g, x_b), r1_inv_t)
            out = np.empty_like(phi)
            out[:, cols] = x_t
            out[:, 2::3] = x_b
            return out
        return solve

    def _reduced(self):
        """For a group of revolute pairs only (else None): the sign of det A's constant factor,
        and Q₂ᵀ·Js, Q₂ᵀ·Jc, Q₂ the orthogonal complement of the constant translation columns T
        (T = Q·[R; 0] once; then det A = c0·det(Q₂ᵀ·B), B the k angle columns)."""
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
            qm, r = la.qr(t)
            diag = np.diag(r[:2 * k])
            if np.all(np.abs(diag) > 1e-9 * max(1.0, float(np.max(np.abs(diag))))):
                perm = np.eye(n)[:, order]
                c0 = la.det(perm) * la.det(qm)
                q2 = qm[:, 2 * k:]
                out = (float(np.sign(c0) * np.prod(np.sign(diag))), la.matmul(q2.T, self._js), la.matmul(q2.T, self._jc))
                q1 = qm[:, :2 * k]
                self._blocks = (np.ascontiguousarray(qm), np.ascontiguousarray(la.inv(r[:2 * k]).T),
                                la.matmul(q1.T, self._js), la.matmul(q1.T, self._jc))
        self._reduced_ = out
        if key is not None:
            if len(_REDUCED) >= 64:
                _REDUCED.clear()
            _REDUCED[key] = out, self.__dict__.get("_blocks")
        return out

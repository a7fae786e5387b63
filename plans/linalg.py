"""Small dense linear algebra that gives the same bits on every processor.

numpy's ``@``, ``dot``, ``linalg.norm`` (of a vector), ``solve``, ``inv``, ``det`` and ``qr``
call OpenBLAS/LAPACK, whose kernels are picked for the processor at load time (Haswell,
SkylakeX, Zen, Neoverse …) and sum in different orders or with fused multiply-adds. Their
results differ in the last bits from one processor to the next, and a drawing decision
downstream of an ill-conditioned step (an instantaneous centre far away, a label's slot)
can then flip. Everything in ``plans`` that feeds a value, a drawing or a report goes
through this module instead: each function is a fixed sequence of numpy element-wise
operations and reductions (IEEE 754 correctly rounded, in an order that does not depend on
the processor), so the same input gives the same bits on any machine with the same numpy.

The matrices here are small (a group's 2k × 2k Jacobian, k ≤ a few dozen; 3 × 3 transforms),
one or stacked over many positions. Accuracy is LAPACK's: the same algorithms (row pivoting by
largest magnitude; Householder QR). Speed is not: a 12 × 12 solve costs ~90 µs on Python floats
or ~0.3 ms stacked (numpy's per-call overhead, n steps), where LAPACK takes ~10 µs; a class III
group's walk is about 3× slower for it (the price of the same bits everywhere).
"""

from __future__ import annotations

import numpy as np
from numpy.linalg import LinAlgError

__all__ = ["LinAlgError", "det", "dot", "inv", "matmul", "norm", "qr", "solve"]


def dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Σ a_i·b_i over the last axis (broadcast over the others); a float for two vectors."""
    out = np.add.reduce(np.multiply(a, b), axis=-1)
    return float(out) if np.ndim(out) == 0 else out


def norm(x: np.ndarray, axis: int | None = None, keepdims: bool = False) -> np.ndarray:
    """Euclidean norm √Σx² over ``axis`` (all elements when None), like ``np.linalg.norm``
    without its BLAS dot for vectors; a float when the result is a scalar."""
    x = np.asarray(x, dtype=float)
    out = np.sqrt(np.add.reduce(x * x, axis=axis, keepdims=keepdims))
    return float(out) if np.ndim(out) == 0 else out


def matmul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a @ b (numpy's rules for 1-D and stacked operands) by numpy's own summation loops."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if a.ndim == 1 and b.ndim == 1:
        return dot(a, b)
    if a.ndim == 1:
        return np.einsum("j,...jk->...k", a, b)
    if b.ndim == 1:
        return np.einsum("...ij,j->...i", a, b)
    return np.einsum("...ij,...jk->...ik", a, b)


#: Up to this many rows in all (matrices × n), a stack is solved matrix by matrix on Python
#: floats: below it numpy's per-call overhead (≈ 15 calls a column) costs more than the
#: arithmetic (measured at n = 12: 3 matrices one by one ≈ 0.25 ms, stacked ≈ 0.3 ms).
ONE_BY_ONE = 36


def _lu(m: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Gaussian elimination with partial pivoting of the first n columns of every matrix of
    m (B, n, n + r), in place: m becomes U | L⁻¹P·rhs (below U's diagonal: what was there, never
    read again). Returns (m, the pivots (B, n), the
    row-swap parity (B,) as ±1). A zero pivot (a singular matrix) leaves its column as it is.
    The first largest |entry| is the pivot (as in :func:`_lu_one`)."""
    batch = np.arange(len(m))
    sign = np.ones(len(m))
    for j in range(n):
        p = j + np.argmax(np.abs(m[:, j:, j]), axis=1)
        swap = p != j
        if swap.any():
            rows = batch[swap]
            top = m[rows, j].copy()
            m[rows, j] = m[rows, p[swap]]
            m[rows, p[swap]] = top
            sign[swap] = -sign[swap]
        if j + 1 < n:
            piv = m[:, j, j]
            safe = np.where(piv == 0.0, 1.0, piv)
            factor = m[:, j + 1:, j] / safe[:, None]
            m[:, j + 1:, j + 1:] -= factor[:, :, None] * m[:, j, None, j + 1:]
    return m, np.diagonal(m[:, :, :n], axis1=1, axis2=2).copy(), sign


def _lu_one(m: list[list[float]], n: int) -> float:
    """:func:`_lu` of one matrix held as Python lists (the same operations in the same order, so
    the same bits; numpy's per-call overhead would cost ten times the arithmetic at these
    sizes). Returns the row-swap parity."""
    sign = 1.0
    for j in range(n):
        p, big = j, abs(m[j][j])
        for i in range(j + 1, n):
            if abs(m[i][j]) > big:
                p, big = i, abs(m[i][j])
        if p != j:
            m[j], m[p] = m[p], m[j]
            sign = -sign
        piv = m[j][j]
        if piv == 0.0:
            piv = 1.0
        top = m[j]
        for i in range(j + 1, n):
            row = m[i]
            factor = row[j] / piv
            for c in range(j + 1, len(row)):       # column j below the pivot is never read again
                row[c] -= factor * top[c]
    return sign


def _back_one(m: list[list[float]], n: int) -> list[list[float]]:
    """x from the eliminated rows U | y of one matrix, column by column: x_j = y_j / U_jj, then
    y_i −= U_ij·x_j for every row i above (as the stacked path does, in the same order)."""
    rhs = [row[n:] for row in m]
    x: list[list[float]] = [[]] * n
    for j in range(n - 1, -1, -1):
        d = m[j][j]
        xj = x[j] = [r / d for r in rhs[j]]
        for i in range(j):
            u = m[i][j]
            rhs[i] = [r - u * v for r, v in zip(rhs[i], xj)]
    return x


def solve(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """x with a·x = b for every matrix of the stack a (..., n, n); b is (..., n, k), or (n,)
    for one vector (numpy's rules). Raises :class:`LinAlgError` when a matrix is exactly
    singular (a zero pivot), as LAPACK's gesv does. One matrix is solved on Python floats,
    a stack by numpy over the stack: the same operations in the same order either way."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    vector = b.ndim == 1
    if vector:
        b = b[:, None]
    n = a.shape[-1]
    stack = np.broadcast_shapes(a.shape[:-2], b.shape[:-2])
    a = np.broadcast_to(a, stack + a.shape[-2:])
    b = np.broadcast_to(b, stack + b.shape[-2:])
    k = b.shape[-1]
    m = np.concatenate([a, b], axis=-1).reshape(-1, n, n + k)
    if len(m) * n <= ONE_BY_ONE:
        x = []
        for one in m.tolist():
            _lu_one(one, n)
            if any(one[j][j] == 0.0 for j in range(n)):
                raise LinAlgError("Singular matrix")
            x.append(_back_one(one, n))
        x = np.array(x, dtype=float).reshape(stack + (n, k))
        return x[..., 0] if vector else x
    m, pivots, _ = _lu(m.copy(), n)
    if (pivots == 0.0).any():
        raise LinAlgError("Singular matrix")
    x = m[:, :, n:].copy()                          # y, turned into x from the last row up
    for j in range(n - 1, -1, -1):
        x[:, j, :] /= m[:, j, j, None]
        if j:
            x[:, :j, :] -= m[:, :j, j, None] * x[:, j, None, :]
    x = x.reshape(stack + (n, k))
    return x[..., 0] if vector else x


def inv(a: np.ndarray) -> np.ndarray:
    """The inverse of every matrix of the stack a (..., n, n); :class:`LinAlgError` when singular."""
    a = np.asarray(a, dtype=float)
    return solve(a, np.broadcast_to(np.eye(a.shape[-1]), a.shape))


def det(a: np.ndarray) -> np.ndarray:
    """The determinant of every matrix of the stack a (..., n, n): 2 × 2 by ad − bc, larger by
    the pivots of the LU factors; a float for one matrix."""
    a = np.asarray(a, dtype=float)
    n = a.shape[-1]
    if n == 2:
        out = a[..., 0, 0] * a[..., 1, 1] - a[..., 0, 1] * a[..., 1, 0]
    elif a.ndim == 2 or a.size == n * n:
        rows = a.reshape(n, n).tolist()
        out = _lu_one(rows, n)
        for j in range(n):
            out *= rows[j][j]
        out = np.full(a.shape[:-2], out)
    else:
        m, pivots, sign = _lu(a.reshape(-1, n, n).copy(), n)
        out = sign
        for j in range(n):
            out = out * pivots[:, j]
        out = out.reshape(a.shape[:-2])
    return float(out) if np.ndim(out) == 0 else out


def qr(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Complete QR of every matrix of the stack a (..., m, n) by Householder reflections:
    Q (..., m, m) orthogonal, R (..., m, n) upper triangular, a = Q·R (the shapes of
    ``np.linalg.qr(a, mode="complete")``; the signs of R's diagonal may differ from LAPACK's).
    Q's columns past the first n span the orthogonal complement of a's columns (a subspace of
    it, when a's rank is below n)."""
    a = np.asarray(a, dtype=float)
    rows, cols = a.shape[-2:]
    r = a.reshape(-1, rows, cols).copy()
    q = np.broadcast_to(np.eye(rows), (len(r), rows, rows)).copy()
    for j in range(min(rows - 1, cols)):
        x = r[:, j:, j]
        size = norm(x, axis=1)
        v = x.copy()
        v[:, 0] += np.where(x[:, 0] >= 0.0, size, -size)
        length = norm(v, axis=1)
        v /= np.where(length > 0.0, length, 1.0)[:, None]       # a zero column: no reflection
        r[:, j:, :] -= 2.0 * v[:, :, None] * np.einsum("bi,bik->bk", v, r[:, j:, :])[:, None, :]
        q[:, :, j:] -= 2.0 * np.einsum("bki,bi->bk", q[:, :, j:], v)[:, :, None] * v[:, None, :]
        r[:, j + 1:, j] = 0.0                                      # reflected onto the axis exactly
    return q.reshape(a.shape[:-2] + (rows, rows)), r.reshape(a.shape)

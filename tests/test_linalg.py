"""plans.linalg: LAPACK's answers to rounding, without BLAS, and nothing in plans calling BLAS.

Bounds: Gaussian elimination with partial pivoting is backward stable, ‖a·x − b‖ ≤ c·n·ε·‖a‖·‖x‖
with a growth factor c that is small for random matrices (Higham, ch. 9); the tests allow
n·ε·‖a‖‖x‖ × 10 (c ≤ 10). Householder QR: ‖a − QR‖ and ‖QᵀQ − I‖ ≤ c·m·n·ε (Higham, ch. 19).
"""

from __future__ import annotations

import ast
from pathlib import Path

import numpy as np
import pytest

from plans import linalg as la

EPS = np.finfo(float).eps


@pytest.mark.parametrize("shape, k", [((2, 2), 1), ((3, 3), 2), ((50, 4, 4), 1), ((7, 12, 12), 3), ((6, 6), 6)])
def test_solve_is_backward_stable(shape, k):
    rng = np.random.default_rng(sum(shape) + k)
    a = rng.standard_normal(shape)
    b = rng.standard_normal(shape[:-1] + (k,))
    x = la.solve(a, b)
    n = shape[-1]
    residual = np.abs(np.einsum("...ij,...jk->...ik", a, x) - b).max(axis=(-2, -1))
    bound = 10 * n * EPS * np.abs(a).sum(axis=-1).max(axis=-1) * np.abs(x).max(axis=(-2, -1))
    assert np.all(residual <= bound)
    np.testing.assert_allclose(x, np.linalg.solve(a, b), rtol=1e-9, atol=1e-12)


def test_solve_vector_inverse_and_determinant_match_numpy():
    rng = np.random.default_rng(1)
    a = rng.standard_normal((5, 5))
    b = rng.standard_normal(5)
    np.testing.assert_allclose(la.solve(a, b), np.linalg.solve(a, b), rtol=1e-12)
    np.testing.assert_allclose(la.inv(a) @ a, np.eye(5), atol=1e-13)
    stack = rng.standard_normal((40, 3, 3))
    # det by LU: |error| ≤ n·ε·Π‖rows‖ (Hadamard's bound times the elimination's rounding)
    hadamard = np.prod(np.linalg.norm(stack, axis=2), axis=1)
    assert np.all(np.abs(la.det(stack) - np.linalg.det(stack)) <= 30 * EPS * hadamard)
    assert la.det(np.array([[3.0, 1.0], [4.0, 2.0]])) == 2.0
    assert la.det(np.eye(4)[[1, 0, 2, 3]]) == -1.0


def test_singular_matrix_is_an_error_not_nan():
    with pytest.raises(la.LinAlgError, match="Singular"):
        la.solve(np.array([[1.0, 2.0], [2.0, 4.0]]), np.ones(2))
    with pytest.raises(np.linalg.LinAlgError):          # the callers' except clauses catch it
        la.inv(np.zeros((3, 3)))
    assert la.det(np.array([[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 1.0, 1.0]])) == 0.0


def test_extreme_magnitudes():
    """Pivoting divides, never squares: 1e-300 and 1e300 entries solve without overflow."""
    for s in (1e-300, 1e300):
        a = np.array([[2.0, 1.0], [1.0, 3.0]]) * s
        x = la.solve(a, np.array([3.0, 4.0]) * s)
        np.testing.assert_allclose(x, [1.0, 1.0], rtol=4 * EPS)
    assert la.norm(np.array([3e150, 4e150])) == pytest.approx(5e150, rel=4 * EPS)
    assert la.norm(np.zeros(0)) == 0.0


@pytest.mark.parametrize("shape", [(6, 4), (5, 5), (3, 7, 2), (4, 1)])
def test_householder_qr(shape):
    rng = np.random.default_rng(len(shape) + shape[-1])
    a = rng.standard_normal(shape)
    q, r = la.qr(a)
    m, n = shape[-2:]
    bound = 10 * m * n * EPS
    assert q.shape == shape[:-2] + (m, m) and r.shape == a.shape
    assert np.abs(q @ r - a).max() <= bound * np.abs(a).max()
    assert np.abs(np.swapaxes(q, -1, -2) @ q - np.eye(m)).max() <= bound
    assert np.all(np.tril(r, -1) == 0.0)


def test_qr_complement_of_a_rank_deficient_matrix():
    """A zero column takes no reflection; Q's last columns stay orthogonal to a's columns."""
    a = np.array([[1.0, 0.0], [2.0, 0.0], [2.0, 0.0], [0.0, 0.0]])
    q, _ = la.qr(a)
    assert np.abs(q[:, 2:].T @ a).max() <= 10 * EPS


def test_norm_dot_matmul_match_numpy():
    rng = np.random.default_rng(7)
    v, w = rng.standard_normal((30, 2)), rng.standard_normal((30, 2))
    np.testing.assert_allclose(la.norm(v, axis=1), np.linalg.norm(v, axis=1), rtol=2 * EPS)
    np.testing.assert_allclose(la.dot(v, w), np.einsum("ij,ij->i", v, w), rtol=1e-13, atol=1e-15)
    assert isinstance(la.dot([1.0, 2.0], [3.0, 4.0]), float) and la.dot([1.0, 2.0], [3.0, 4.0]) == 11.0
    a, b = rng.standard_normal((4, 3, 5)), rng.standard_normal((4, 5, 2))
    np.testing.assert_allclose(la.matmul(a, b), a @ b, rtol=1e-13, atol=1e-14)
    np.testing.assert_allclose(la.matmul(a[0], b[0, :, 0]), a[0] @ b[0, :, 0], rtol=1e-13, atol=1e-14)
    np.testing.assert_allclose(la.matmul(b[0, :, 0], a[0].T), b[0, :, 0] @ a[0].T, rtol=1e-13, atol=1e-14)


#: What calls BLAS or LAPACK in numpy (the last bits then depend on the processor's kernel).
_BLAS_ATTRS = {"dot", "matmul", "inner", "vdot", "tensordot"}
_LAPACK_ATTRS = {"solve", "inv", "det", "norm", "qr", "lstsq", "pinv", "eig", "eigh", "slogdet", "matrix_power"}
#: Where a LAPACK call only decides a warning far from its threshold, or feeds no output.
_ALLOWED = {("kinetostatics/solver.py", "cond"), ("kinematics/generic.py", "svd")}


def test_no_blas_on_the_output_path():
    """No module of plans (but the benchmark's peer comparisons) multiplies matrices with @,
    or calls numpy's dot/matmul or its linalg (but a condition number for a warning, and the
    singular values of a figure's rare fallback): plans.linalg does it in fixed order."""
    root = Path(__file__).resolve().parent.parent / "plans"
    found = []
    for path in sorted(root.rglob("*.py")):
        rel = path.relative_to(root).as_posix()
        if rel.startswith("bench/") or rel == "linalg.py":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.BinOp) and isinstance(node.op, ast.MatMult):
                found.append(f"{rel}:{node.lineno} @")
            elif isinstance(node, ast.Attribute):
                owner = ast.unparse(node.value)
                if owner == "np" and node.attr in _BLAS_ATTRS or owner == "np.linalg" and (
                        node.attr in _LAPACK_ATTRS or node.attr in {"svd", "cond"}) and (rel, node.attr) not in _ALLOWED:
                    found.append(f"{rel}:{node.lineno} {owner}.{node.attr}")
                elif isinstance(node.value, ast.Name) and node.attr == "dot" and owner not in {"la", "np"}:
                    found.append(f"{rel}:{node.lineno} .dot")
    assert not found, found

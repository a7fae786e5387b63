"""The condition figure of a group solved by its pair equations (class III/IV, a drive inside
the chain): the sine of a class II group's transmission angle, generalised.

A class II group's figure is sin(U1, U2), the sine of the angle between its two unknown
directions (:mod:`plans.kinematics.groups`). Written as pair equations in the links' poses,
its velocity equations A·q̇ = r have 3k unknowns; the translations (v_o) are fixed by the
turning and sliding rates through the pairs, and eliminating them leaves the group's own
unknowns — one turning rate per set of links that turn together (a slider and its guide), one
sliding rate per prismatic pair whose stroke is not the drive — each with one column of
lever arms (turning) or a unit direction (sliding). The figure is the polar sine of those
columns, |det M| / Π‖M_j‖ (the volume they span over the product of their lengths): for a
class II group of any of the five forms it is |sin(U1, U2)| exactly; for a drive inside the
chain that forms a triangle (a cylinder pinned to a boom), the sine of the angle between the
cylinder's axis and the boom. It is 1 for columns at right angles, 0 at a singular position,
and invariant to the frame, the links' origins and the mechanism's scale; near a dead
position it is about the angle (rad) by which the group's links must still turn relative
to each other to reach it, as sin μ is for a class II group. Its sign is that of det A,
which changes across a singular position.

Rows: the pair equations as in :class:`~plans.kinematics.generic.GroupEquations`, a
prismatic pair's two (θ_s − θ_g = 0, the normal offset) completed by its offset along the
guide less the sliding σ, so that every pair fixes its points' relative position; the angle
rows only say which links turn together and are dropped. M = Qᵀ·[B | S]: Q the orthonormal
left null space of the translation columns (their combinations that drop out), B the
turning columns summed per set, S the sliding columns.
"""

from __future__ import annotations

import numpy as np
from .. import linalg as la

__all__ = ["polar_sine", "reduced_figure"]


def polar_sine(m: np.ndarray, det: np.ndarray | None = None) -> np.ndarray:
    """|det m| / Π‖m_j‖ over the columns of every square matrix of ``m`` (N, c, c) (N,): the
    volume the columns span over the product of their lengths, 1 when they are at right
    angles, 0 when they are dependent (1 for c = 0); ``det``: det m, when already at hand."""
    if m.shape[-1] == 0:
        return np.ones(m.shape[0])
    norms = np.prod(la.norm(m, axis=1), axis=1)
    if det is None:
        det = la.det(m)
    with np.errstate(invalid="ignore", divide="ignore"):
        out = np.abs(det) / norms
    return np.where(norms > 0.0, np.minimum(out, 1.0), 0.0)


def reduced_figure(rows: np.ndarray, sets: np.ndarray, sliding: list[int]) -> np.ndarray | None:
    """The polar sine of the group's reduced velocity equations (N,), None when they are not
    square (angle rows that depend on each other).

    ``rows`` (N, m, 3k): the pair equations' rows with every angle row dropped (metres; the
    turning columns may carry one common scale); ``sets`` (3k, c): for each set of links that
    turn together (and are not turned by a known link or the drive), 1 in their turning
    columns; ``sliding``: the row of each sliding rate's equation (its offset along the guide)."""
    n_pos, m, n = rows.shape
    k2 = 2 * (n // 3)
    if m - k2 != sets.shape[1] + len(sliding):
        return None
    t = rows[:, :, [c for c in range(n) if c % 3 != 2]]
    q = la.qr(t)[0][:, :, k2:]     # (N, m, m − 2k): an orthonormal basis of the complement of t's columns
    s = np.zeros((n_pos, m, len(sliding)))
    for j, r in enumerate(sliding):
        s[:, r, j] = -1.0
    cols = np.concatenate([la.matmul(rows, sets), s], axis=2)
    return polar_sine(la.matmul(np.swapaxes(q, 1, 2), cols))

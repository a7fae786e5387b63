"""The balancing element and the power balance: how the drive's balancing moment, force or
actuator force enters the original mechanism's equations (:class:`_BalanceSpec`), and the
same element found from Σ F·v + Σ M·ω = 0 alone, with the residual of that balance.

Must not import the solver (:mod:`.solver`) or anything above the kinetostatics.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import SceneError
from ..kinematics import Motion
from ..scene import Scene
from .loads import Couple, Load
from .pairs import _Geometry
from .results import Balancing


@dataclass(frozen=True, eq=False)
class _BalanceSpec:
    """The balancing element as the linear system takes it: ``kind`` ``"moment"`` or a force
    (``"force"``, ``"actuator"``) along ``direction`` at ``point``; ``acts_on``: (link, sign)."""

    kind: str
    acts_on: tuple[tuple[str, float], ...]
    direction: np.ndarray | None = None
    point: np.ndarray | None = None
    given: bool = True
    at: str | None = None


def _balance_spec(motion: Motion, scene: Scene, geo: _Geometry) -> _BalanceSpec:
    mech = motion.mechanism
    spec = scene.balance
    d = mech.drive
    if spec is None or spec.kind == "moment":
        if not d.kind.angular:
            raise SceneError(f"link {d.link} slides and cannot turn, so a moment on it balances nothing",
                             key="balance.moment_on")
        return _BalanceSpec("moment", ((d.link, 1.0),), given=spec is not None and spec.given)
    if spec.kind == "force" and spec.at is not None:
        rad = np.radians(spec.angle)
        w = motion.links[spec.link].direction(np.array([np.cos(rad), np.sin(rad)]))
        return _BalanceSpec("force", ((spec.link, 1.0),), w, motion.position(spec.at, spec.link), given=True,
                            at=spec.at)
    p = d.guide                       # along the drive's guide, at the pair's point
    u, _, r0 = geo.guide(p)
    if spec.kind == "actuator":
        return _BalanceSpec("actuator", ((d.link, 1.0), (p.other(d.link), -1.0)), u, r0, given=spec.given,
                            at=p.label)
    return _BalanceSpec("force", ((d.link, 1.0),), u, r0, given=spec.given, at=p.label)


def _power(motion: Motion, loads: tuple[Load, ...], couples: tuple[Couple, ...], bal: Balancing
           ) -> tuple[np.ndarray | None, np.ndarray | None]:
    """The balancing element from the power balance (d'Alembert, virtual work): Σ F·v + Σ M·ω
    over every load is zero, so value = −P/(its velocity factor): ω of the driving link for
    a moment, w·v of its point for a force, the sliding speed for a cylinder's actuator. And
    the residual of that balance with the group-by-group value. None when the drive stands."""
    if motion.order < 1 or motion.mechanism.drive.speed == 0.0:
        return None, None
    terms = [np.sum(l.force * motion.links[l.link].velocity(l.point), axis=1) for l in loads]
    terms += [c.moment * motion.links[c.link].omega for c in couples]
    total = np.sum(terms, axis=0) if terms else np.zeros(len(motion))
    if bal.kind == "moment":
        factor = motion.links[bal.link].omega
    else:
        v = motion.links[bal.link].velocity(bal.point)
        if bal.reacts_on is not None:
            v = v - motion.links[bal.reacts_on].velocity(bal.point)
        factor = np.sum(bal.direction * v, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        power = np.where(factor != 0.0, -total / np.where(factor != 0.0, factor, 1.0), np.nan)
    bal_term = bal.value * factor
    scale = np.max(np.abs(np.array(terms + [bal_term])), axis=0)
    residual = np.where(scale > 0.0, np.abs(total + bal_term) / np.where(scale > 0.0, scale, 1.0), 0.0)
    return power, residual

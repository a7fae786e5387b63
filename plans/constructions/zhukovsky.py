"""Zhukovsky's lever: the velocity plan turned 90° clockwise about its pole, loaded with the
mechanism's forces and couples at the turned images, and the balancing force or moment
found from Σ M_p = 0. Conventions: :mod:`plans.constructions.forces`.

Takes forces as numbers and a velocity plan's images; must not import kinematics, the
kinetostatics or the plan constructions (only their value types).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from .. import linalg as la

from ..errors import ConstructionError
from .force_polygon import _pt, _vec
from .plan_values import PlanPoint
from .scales import standard_scale

__all__ = ["LeverLoad", "LeverCouple", "BalanceForce", "BalanceMoment", "LeverForce", "Lever", "zhukovsky_lever",
           "LEVER_FORCE_MM", "SENSE", "ZERO_ARM_REL"]

#: Wanted drawn length of the largest force on the lever, mm (the lever itself is the velocity
#: plan, 80–120 mm: the forces are drawn shorter so that they do not hide it).
LEVER_FORCE_MM = (22.0, 36.0)
#: Sense in which the velocity plan is turned to make the lever.
SENSE = "clockwise"
#: An arm under this fraction of the lever's extent (the images' largest distance from the pole)
#: is a rounding of zero: the force's line passes through the pole; its arm and moment are 0.
ZERO_ARM_REL = 1e-9
#: Images of a couple's ends must be ⊥ the link within this fraction of their distance (ab ⊥ AB).
PERPENDICULAR_REL = 1e-6


@dataclass(frozen=True)
class LeverLoad:
    """A force ``force`` (N) at a point whose image on the *unturned* velocity plan is
    ``image`` (mm); ``label``: the image's name when it is no image of the plan (``s2``)."""

    quantity: str
    image: tuple[float, float]
    force: tuple[float, float]
    label: str = ""


@dataclass(frozen=True)
class LeverCouple:
    """A moment ``moment`` (N·m, counter-clockwise positive) on a link, as the couple of
    forces M / l ⊥ the link at two of its points: ``ends`` their images (mm, unturned plan),
    ``length_m`` their distance on the link (m), ``direction`` the link's direction from the
    first point to the second (any length; its sign fixes the couple's sense)."""

    quantity: str
    moment: float
    ends: tuple[tuple[float, float], tuple[float, float]]
    length_m: float
    direction: tuple[float, float]
    labels: tuple[str, str] = ("", "")


@dataclass(frozen=True)
class BalanceForce:
    """The unknown balancing force: its point's image (mm, unturned plan) and its line's
    direction (any length); the result is signed along ``direction``."""

    image: tuple[float, float]
    direction: tuple[float, float]
    quantity: str = "F:bal"
    label: str = ""


@dataclass(frozen=True)
class BalanceMoment:
    """The unknown balancing moment on the crank OA: ``ends`` the images of O and A (mm),
    ``length_m`` = l_OA (m), ``direction`` O → A on the mechanism; counter-clockwise positive."""

    ends: tuple[tuple[float, float], tuple[float, float]]
    length_m: float
    direction: tuple[float, float]
    quantity: str = "M:bal"
    labels: tuple[str, str] = ("", "")


@dataclass(frozen=True)
class LeverForce:
    """A force on the lever: applied at the turned image ``point`` (mm, label ``at``), drawn
    from ``tail`` (= point) to ``head`` in μF; ``force`` (N), ``moment`` about the pole (N·mm,
    counter-clockwise positive), ``arm`` h ≥ 0 (mm) and the foot of the perpendicular from the
    pole on its line (mm). ``kind``: ``load``, ``couple`` (one force of a moment's couple, of
    ``source``) or ``balance``."""

    quantity: str
    kind: str
    at: str
    point: tuple[float, float]
    force: tuple[float, float]
    tail: tuple[float, float]
    head: tuple[float, float]
    value: float
    moment: float
    arm: float
    foot: tuple[float, float]
    source: str = ""
    direction: tuple[float, float] = (1.0, 0.0)    # unit; a zero force keeps its line's direction

    @property
    def length(self) -> float:
        return float(math.dist(self.tail, self.head))


@dataclass(frozen=True)
class Lever:
    """Zhukovsky's lever at one position (see the module docstring).

    ``points``: the turned images (mm, the pole at ``pole_xy``); ``segments``: the turned
    plan's lines; ``forces``: every force drawn (the balancing one last, or the two of its
    couple; none for a balancing element of exactly 0, which is no force); ``balance``:
    ``force`` or ``moment``; ``result``: the balancing force (N, signed along the given
    direction) or moment (N·m, counter-clockwise positive);
    ``balance_vector``: the balancing force (N), or the crank's couple force at A;
    ``omega``: the crank's ω found from its images (rad/s; balance by a moment only);
    ``moment_sum``: Σ M_p of the given loads (N·mm); ``unit_moment``: the lever moment of a
    unit balancing force (N·mm/N, = ± h_bal) or moment (N·mm per N·m)."""

    mu_v: float
    mu: float
    pole: str
    pole_xy: tuple[float, float]
    points: tuple[PlanPoint, ...]
    segments: tuple[tuple[tuple[float, float], tuple[float, float]], ...]
    forces: tuple[LeverForce, ...]
    balance: str
    balance_quantity: str
    result: float
    balance_vector: tuple[float, float]
    moment_sum: float
    unit_moment: float
    omega: float | None = None
    sense: str = SENSE

    kind = "lever"

    @property
    def mu_F(self) -> float:   # noqa: N802 (the textbook's symbol)
        return self.mu

    @property
    def residual(self) -> float:
        """Σ M_p of every force on the lever, the balancing one included (N·mm; zero but rounding)."""
        return float(sum(f.moment for f in self.forces))


def _turn(r: np.ndarray, pole: np.ndarray) -> np.ndarray:
    """Image r turned 90° clockwise about the pole: (x, y) → (y, −x) relative to it."""
    d = r - pole
    return pole + np.array([d[1], -d[0]])


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _unit(v, what: str) -> np.ndarray:
    v = _vec(v, what)
    n = float(np.hypot(*v))
    if not n > 0:
        raise ConstructionError(f"{what}: the direction is the zero vector")
    return v / n


def _couple_direction(ends, length_m: float, direction, what: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The images of a couple's ends and J·û / l (1/m): the force at the second end per N·m."""
    e1, e2 = _vec(ends[0], what + ": first end"), _vec(ends[1], what + ": second end")
    if not (length_m > 0 and math.isfinite(length_m)):
        raise ConstructionError(f"{what}: length {length_m!r} m is not a positive number")
    u = _unit(direction, what)
    d = e2 - e1
    if abs(la.dot(d, u)) > PERPENDICULAR_REL * float(np.hypot(*d)) + 1e-9:
        raise ConstructionError(f"{what}: the images of its ends are not ⊥ the link's direction (ab ⊥ AB on a "
                                "velocity plan): wrong ends or direction")
    return e1, e2, np.array([-u[1], u[0]]) / length_m


def _fallback(quantity: str) -> str:
    """A name for the image of a load's point that is no image of the plan: ``s2`` for a force
    of link 2 (its centre of mass), ``b`` for one at B."""
    last = quantity.split(":")[-1]
    return f"s{last}" if last.isdigit() else last.lower()


def _label_of(plan_points: Sequence[PlanPoint], xy: np.ndarray, given: str, fallback: str) -> str:
    if given:
        return given
    for p in plan_points:
        if math.dist(p.xy, xy) <= 1e-6:
            return p.label
    return fallback


def zhukovsky_lever(plan, loads: Sequence[LeverLoad], balance: BalanceForce | BalanceMoment, *,
                    couples: Sequence[LeverCouple] = (), mu: float | None = None,
                    window: tuple[float, float] = LEVER_FORCE_MM) -> Lever:
    """Zhukovsky's lever of the velocity plan ``plan`` (a :class:`~plans.constructions.plans.Plan`
    of kind ``velocity``: its images in mm and μV) loaded with ``loads`` and ``couples``, and
    the balancing element ``balance`` found from Σ M_p = 0 (see the module docstring).

    ``mu``: the force scale μF (N/mm) of the forces drawn on the lever, by default the series
    value drawing the largest force ``window`` mm long."""
    if getattr(plan, "kind", "velocity") != "velocity":
        raise ConstructionError(f"Zhukovsky's lever is the velocity plan turned, not the {plan.kind} plan")
    pole = _vec(plan.point(plan.pole), "pole")
    pts = list(plan.points)
    items: list[tuple[str, str, np.ndarray, np.ndarray, str, str]] = []   # quantity, kind, image, F, label, source
    for ld in loads:
        img = _vec(ld.image, f"{ld.quantity}: image")
        items.append((ld.quantity, "load", img, _vec(ld.force, f"{ld.quantity}: force"),
                      _label_of(pts, img, ld.label, _fallback(ld.quantity)), ld.quantity))
    for c in couples:
        if not math.isfinite(c.moment):
            raise ConstructionError(f"{c.quantity}: moment {c.moment!r} is not a finite number")
        e1, e2, per = _couple_direction(c.ends, c.length_m, c.direction, c.quantity)
        names = [_label_of(pts, e, lab, f"m{c.quantity.split(':')[-1]}{'ab'[k]}") for k, (e, lab) in
                 enumerate(((e1, c.labels[0]), (e2, c.labels[1])))]
        for e, sign, name in ((e1, -1.0, names[0]), (e2, 1.0, names[1])):
            items.append((f"F:{c.quantity}:{name}", "couple", e, sign * c.moment * per, name, c.quantity))
    turned = [_turn(img, pole) for _, _, img, _, _, _ in items]
    total = sum(_cross(r - pole, f) for r, (_, _, _, f, _, _) in zip(turned, items))
    omega = None
    if isinstance(balance, BalanceForce):
        img = _vec(balance.image, f"{balance.quantity}: image")
        u = _unit(balance.direction, balance.quantity)
        r = _turn(img, pole)
        unit = _cross(r - pole, u)
        ref = float(np.hypot(*(r - pole)))
        if abs(unit) <= 1e-9 * max(ref, 1.0):
            raise ConstructionError(f"{balance.quantity}: its line passes through the pole of the lever (its point "
                                    "does not move along it now): it cannot balance; choose another direction or point")
        result = -total / unit
        bal = [(balance.quantity, "balance", img, result * u, _label_of(pts, img, balance.label, "bal"),
                balance.quantity)]
        kind, vec = "force", result * u
    elif isinstance(balance, BalanceMoment):
        e1, e2, per = _couple_direction(balance.ends, balance.length_m, balance.direction, balance.quantity)
        unit = _cross(_turn(e2, pole) - _turn(e1, pole), per)          # N·mm of the lever per N·m
        if abs(unit) <= 1e-12 * max(float(np.hypot(*(e2 - e1))), 1.0) / balance.length_m:
            raise ConstructionError(f"{balance.quantity}: the crank's images coincide (ω1 = 0 now): no moment "
                                    "balances the lever")
        result = -total / unit
        omega = unit * plan.mu          # (a − o)·J û / l · μV
        names = [_label_of(pts, e, lab, f"bal{k + 1}") for k, (e, lab) in
                 enumerate(((e1, balance.labels[0]), (e2, balance.labels[1])))]
        bal = [(f"F:{balance.quantity}:{name}", "balance", e, sign * result * per, name, balance.quantity)
               for e, sign, name in ((e1, -1.0, names[0]), (e2, 1.0, names[1]))]
        kind, vec = "moment", result * per
    else:
        raise ConstructionError(f"the balancing element {balance!r} is neither a BalanceForce nor a BalanceMoment")
    if result != 0.0:       # an element of exactly 0 is no force: nothing to draw, no arm
        items += bal
        turned += [_turn(img, pole) for _, _, img, _, _, _ in bal]
    result += 0.0           # not −0
    fmax = max([float(np.hypot(*f)) for _, _, _, f, _, _ in items] + [0.0])
    if mu is None:
        mu = standard_scale(fmax, window=window) if fmax > 0 else 1.0
    elif not (mu > 0 and math.isfinite(mu)):
        raise ConstructionError(f"lever: μF = {mu!r} is not a positive number")
    forces = []
    extent = max([float(np.hypot(*(r - pole))) for r in turned] + [0.0])
    for r, (q, k, _, f, label, src) in zip(turned, items):
        m = _cross(r - pole, f)
        fn = float(np.hypot(*f))
        if fn > 0:
            u = f / fn
            arm = abs(m) / fn
        else:                   # a zero load given to the lever: along x, its arm to that line
            u = np.array([1.0, 0.0])
            arm = abs(_cross(r - pole, u))
        if arm <= ZERO_ARM_REL * extent:        # its line passes through the pole: a rounding arm is none
            arm, m = 0.0, 0.0
        foot = r - la.dot(r - pole, u) * u
        forces.append(LeverForce(q, k, label, _pt(r), _pt(f), _pt(r), _pt(r + f / mu), fn, m, arm, _pt(foot), src,
                                 _pt(u)))
    rotated = []
    for p in pts:
        rotated.append(PlanPoint(p.label, _pt(_turn(np.asarray(p.xy, dtype=float), pole))))
    known = {p.label for p in rotated}
    for f in forces:
        if f.at not in known and all(math.dist(f.point, p.xy) > 1e-6 for p in rotated):
            rotated.append(PlanPoint(f.at, f.point))
            known.add(f.at)
    segs, seen = [], set()
    for v in plan.vectors:
        a, b = _pt(_turn(np.asarray(v.tail, float), pole)), _pt(_turn(np.asarray(v.head, float), pole))
        key = tuple(sorted((tuple(round(c, 9) for c in a), tuple(round(c, 9) for c in b))))
        if key not in seen and math.dist(a, b) > 1e-9:
            seen.add(key)
            segs.append((a, b))
    return Lever(float(plan.mu), float(mu), plan.pole, _pt(pole), tuple(rotated), tuple(segs), tuple(forces), kind,
                 balance.quantity, float(result), _pt(vec), float(total), float(unit), omega)

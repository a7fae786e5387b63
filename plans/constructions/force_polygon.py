"""Force plans of groups: the forces of one group head to tail from a start point, lettered
vertices, the whole reactions beside their components, inner reactions as diagonals, to a
force scale μF (N/mm). Conventions and quantity tags: :mod:`plans.constructions.forces`.

Lays out forces that arrive as numbers; must not import kinematics, the kinetostatics or
Zhukovsky's lever (:mod:`.zhukovsky`).
"""

from __future__ import annotations

import math
import string
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ..errors import ConstructionError
from .plan_values import EXTENSION_MM, ConstructionLine, PlanPoint
from .scales import SERIES, _series_values
from .. import linalg as la

__all__ = ["ForceTerm", "ForceVector", "ForcePlan", "force_plan", "KINDS", "CLOSURE_REL", "FORCE_REFERENCE_MM",
           "FORCE_SERIES", "FORCE_PLAN_MAX_MM", "component_of", "force_scale", "ForceDetail", "force_details",
           "SHORT_SIDE_MM", "RUN_SIDE_MM", "DETAIL_REFERENCE_MM", "TWO_FORCE_OFFSET_MM"]

#: The kinds of force a term may be.
KINDS = ("gravity", "inertia", "external", "reaction", "reaction_n", "reaction_t", "balance")
#: The forces of a polygon must sum to zero within this fraction of the sum of their magnitudes.
CLOSURE_REL = 1e-9
#: A force smaller than this fraction of the largest one is zero: not drawn, kept in the table.
ZERO_REL = 1e-12
#: Wanted drawn length of a plan's largest force (its largest side), mm, as the reference
#: vectors of the velocity and acceleration plans: never longer; shorter only where the
#: polygon would exceed FORCE_PLAN_MAX_MM.
FORCE_REFERENCE_MM = (100.0, 150.0)
#: Mantissas of μF: the standard series with 1.5, 3 and 6 between its steps of 1.6× (1.25 → 2,
#: 2.5 → 4, 5 → 8), wider than the window's 1.5×; no step is then over 4/3, so some μF always
#: draws the largest force within FORCE_REFERENCE_MM.
FORCE_SERIES = tuple(sorted(SERIES + (1.5, 3.0, 6.0)))
#: Largest width or height of a force plan, mm: one polygon of a panel on an A3 sheet.
FORCE_PLAN_MAX_MM = 240.0
#: A side drawn shorter than this (mm) cannot be read on the polygon: it is drawn again in an
#: enlarged detail, or listed as negligible in the force table.
SHORT_SIDE_MM = 2.0
#: Consecutive sides each drawn shorter than this (mm), among them one under SHORT_SIDE_MM,
#: form a run that gets a detail: the cluster of short sides read together.
RUN_SIDE_MM = 10.0
#: Wanted drawn length of the largest side of a detail, mm (never longer).
DETAIL_REFERENCE_MM = (40.0, 60.0)
#: A polygon of two forces (equal and opposite) draws its second force this far beside the
#: first, parallel, so that the two arrows do not lie on one segment, mm.
TWO_FORCE_OFFSET_MM = 4.0


def _vec(xy, what: str) -> np.ndarray:
    v = np.asarray(xy, dtype=float).reshape(-1)
    if v.shape != (2,) or not np.all(np.isfinite(v)):
        raise ConstructionError(f"{what}: {xy!r} is not a pair of finite numbers")
    return v


def _pt(v) -> tuple[float, float]:
    return (float(v[0]) + 0.0, float(v[1]) + 0.0)


def component_of(quantity: str) -> tuple[str, str]:
    """``R:0-3:n`` → (``R:0-3``, ``n``); a quantity without a component → (quantity, "")."""
    base, _, comp = quantity.rpartition(":")
    return (base, comp) if base.startswith("R:") and comp in ("n", "t") else (quantity, "")



@dataclass(frozen=True)
class ForceTerm:
    """One force of a group: its tag, its vector (N, x right, y up) and its kind (:data:`KINDS`)."""

    quantity: str
    vector: tuple[float, float]
    kind: str

    @property
    def value(self) -> float:
        """Magnitude, N."""
        return float(math.hypot(*self.vector))


@dataclass(frozen=True)
class ForceVector:
    """A drawn force: tail and head (mm), magnitude (N), kind and role — ``side`` (a term of
    the polygon), ``total`` (a reaction from its two components) or ``internal`` (a reaction
    between the group's own links, a diagonal)."""

    quantity: str
    tail: tuple[float, float]
    head: tuple[float, float]
    value: float
    kind: str
    role: str = "side"

    @property
    def length(self) -> float:
        return float(math.dist(self.tail, self.head))


@dataclass(frozen=True)
class ForcePlan:
    """The force polygon of one group at one position, in plan mm (the start point at the origin).

    ``mu`` (N/mm) is μF; ``points`` the lettered vertices (``start`` is the first);
    ``vectors`` what is drawn; ``lines`` the directions of the normal components;
    ``terms`` every force of the group in order, zero ones included; ``totals`` the whole
    reactions of component pairs; ``internal`` the reactions between the group's links."""

    group: str
    mu: float
    start: str
    points: tuple[PlanPoint, ...]
    vectors: tuple[ForceVector, ...]
    lines: tuple[ConstructionLine, ...]
    terms: tuple[ForceTerm, ...]
    totals: tuple[ForceTerm, ...]
    internal: tuple[ForceTerm, ...]

    kind = "force"

    @property
    def mu_F(self) -> float:   # noqa: N802 (the textbook's symbol)
        return self.mu

    def point(self, label: str) -> tuple[float, float]:
        return next(p.xy for p in self.points if p.label == label)

    @property
    def sides(self) -> tuple[ForceVector, ...]:
        return tuple(v for v in self.vectors if v.role == "side")


def _letters(n: int) -> list[str]:
    """a, b, …, z, then a′, b′, …"""
    return [string.ascii_lowercase[k % 26] + "′" * (k // 26) for k in range(n)]


def _check_terms(terms: Sequence[ForceTerm], what: str) -> list[ForceTerm]:
    out, seen = [], set()
    for t in terms:
        if not isinstance(t, ForceTerm):
            raise ConstructionError(f"{what}: {t!r} is not a ForceTerm")
        if not t.quantity or t.quantity in seen:
            raise ConstructionError(f"{what}: quantity {t.quantity!r} is empty or repeated")
        if t.kind not in KINDS:
            raise ConstructionError(f"{what}: {t.quantity}: kind {t.kind!r} is not one of {', '.join(KINDS)}")
        seen.add(t.quantity)
        out.append(ForceTerm(t.quantity, _pt(_vec(t.vector, f"{what}: {t.quantity}")), t.kind))
    return out


def force_plan(group: str, terms: Sequence[ForceTerm], *, internal: Sequence[ForceTerm] = (),
               mu: float | None = None, window: tuple[float, float] = FORCE_REFERENCE_MM,
               limit: float = FORCE_PLAN_MAX_MM, unmatched: str = "raise") -> ForcePlan:
    """The force polygon of ``group`` (see the module docstring).

    ``terms``: the group's forces in the order of its vector equation, summing to zero within
    :data:`CLOSURE_REL` of Σ|F| (else :class:`ConstructionError` giving the residual);
    ``internal``: reactions between its own links, each drawn as the diagonal of the polygon
    it equals (when none does — the forces on that link are not consecutive sides — an error,
    or with ``unmatched="skip"`` the reaction is left out of the plan);
    ``mu``: μF in N/mm, by default the series value that draws the largest force ``window``
    mm long and keeps the polygon within ``limit`` mm."""
    what = f"force plan of {group}"
    if unmatched not in ("raise", "skip"):
        raise ValueError(f"unmatched is 'raise' or 'skip', got {unmatched!r}")
    terms_ = _check_terms(terms, what)
    inner = _check_terms(internal, what + " (internal)")
    if not terms_:
        raise ConstructionError(f"{what}: no forces")
    vecs = np.array([t.vector for t in terms_])
    mags = np.hypot(vecs[:, 0], vecs[:, 1])
    fmax = float(mags.max())
    residual = vecs.sum(axis=0)
    if not fmax > 0:
        raise ConstructionError(f"{what}: every force is zero, nothing to draw")
    if float(np.hypot(*residual)) > CLOSURE_REL * float(mags.sum()):
        raise ConstructionError(f"{what}: the forces do not close: their sum is ({residual[0]:.6g}, "
                                f"{residual[1]:.6g}) N, more than {CLOSURE_REL:g} of Σ|F| = {mags.sum():.6g} N; "
                                "the polygon needs every force of the group, reactions included")
    drawn = [k for k in range(len(terms_)) if mags[k] > ZERO_REL * fmax]
    corners = np.vstack([np.zeros(2), np.cumsum(vecs[drawn], axis=0)])     # N, from the start point
    corners[-1] = 0.0                                                     # closed on the start point
    extent = float(max(np.ptp(corners[:, 0]), np.ptp(corners[:, 1]), fmax))
    if mu is None:
        mu = force_scale(fmax, extent, window=window, limit=limit)
    elif not (mu > 0 and math.isfinite(mu)):
        raise ConstructionError(f"{what}: μF = {mu!r} is not a positive number")
    xy = corners / mu
    labels = _letters(len(drawn))
    points = [PlanPoint(labels[k], _pt(xy[k])) for k in range(len(drawn))]
    vectors: list[ForceVector] = []
    for j, k in enumerate(drawn):
        t = terms_[k]
        vectors.append(ForceVector(t.quantity, _pt(xy[j]), _pt(xy[(j + 1) % len(drawn)]), float(mags[k]), t.kind))
    if len(drawn) == 2:
        # two forces, equal and opposite: the second beside the first (b′ → a′), not back along it
        d = xy[1] - xy[0]
        off = np.array([d[1], -d[0]]) / float(la.norm(d)) * TWO_FORCE_OFFSET_MM
        ends = [labels[1] + "′", labels[0] + "′"]
        points += [PlanPoint(ends[0], _pt(xy[1] + off)), PlanPoint(ends[1], _pt(xy[0] + off))]
        second = vectors[1]
        vectors[1] = ForceVector(second.quantity, _pt(xy[1] + off), _pt(xy[0] + off), second.value, second.kind)
    points = tuple(points)
    totals = _totals(terms_)
    sides = [terms_[k] for k in drawn]
    n = len(sides)
    for tot in totals:
        for j in range(n):
            a, b = sides[j], sides[(j + 1) % n]
            if n > 2 and {component_of(a.quantity), component_of(b.quantity)} == \
                    {(tot.quantity, "n"), (tot.quantity, "t")}:
                vectors.append(ForceVector(tot.quantity, _pt(xy[j]), _pt(xy[(j + 2) % n]), tot.value, "reaction",
                                           "total"))
                break
    scale = float(mags.sum())
    kept = []
    for t in inner:
        if not t.value > ZERO_REL * fmax:
            kept.append(t)
            continue
        hit = [(i, j) for i in range(n) for j in range(n) if i != j
               and float(np.hypot(*(corners[j] - corners[i] - t.vector))) <= 1e-7 * scale]
        if not hit and unmatched == "skip":
            continue
        kept.append(t)
        if not hit:
            raise ConstructionError(f"{what}: {t.quantity} = ({t.vector[0]:.6g}, {t.vector[1]:.6g}) N joins no two "
                                    "vertices of the polygon: list the forces on one link consecutively")
        i, j = hit[0]
        vectors.append(ForceVector(t.quantity, _pt(xy[i]), _pt(xy[j]), t.value, t.kind, "internal"))
    lines = []
    for j, t in enumerate(sides):
        if t.kind == "reaction_n":
            a, b = xy[j], xy[(j + 1) % n]
            u = (b - a) / float(la.norm(b - a))
            lines.append(ConstructionLine(_pt(a - EXTENSION_MM * u), _pt(b + EXTENSION_MM * u), t.quantity, group))
    return ForcePlan(group, float(mu), labels[0], points, tuple(vectors), tuple(lines), tuple(terms_), tuple(totals),
                     tuple(kept))


def force_scale(fmax: float, extent: float, *, window: tuple[float, float] = FORCE_REFERENCE_MM,
                limit: float = FORCE_PLAN_MAX_MM) -> float:
    """μF (N/mm) of :data:`FORCE_SERIES` that draws the largest force ``fmax`` (N) nearest the
    middle of ``window`` (mm, log scale) and never longer than its top, while the polygon's
    ``extent`` (N, its largest width or height) stays within ``limit`` mm; when the extent
    leaves no value drawing it within the window, the one drawing it longest below."""
    if not (fmax > 0 and math.isfinite(fmax)):
        raise ConstructionError(f"largest force {fmax!r} N is not a positive number")
    extent = max(extent, fmax)
    mid = math.sqrt(window[0] * window[1])
    fitting = [mu for mu in _series_values(fmax / window[1] / 10.0, extent / window[0] * 10.0, FORCE_SERIES)
               if fmax / mu <= window[1] * (1 + 1e-12) and extent / mu <= limit * (1 + 1e-12)]
    inside = [mu for mu in fitting if fmax / mu >= window[0] * (1 - 1e-12)]
    if inside:
        return min(inside, key=lambda mu: (abs(math.log(fmax / mu / mid)), mu))
    return min(fitting)


@dataclass(frozen=True)
class ForceDetail:
    """An enlarged detail of a run of short sides of a force plan: the sides ``first`` …
    ``first + len(vectors) − 1`` (indices into the plan's sides) drawn again head to tail from
    the origin at their own ``mu`` (N/mm), their ends lettered as on the polygon (``points``);
    ``negligible``: the quantities still shorter than :data:`SHORT_SIDE_MM` here."""

    mu: float
    first: int
    points: tuple[PlanPoint, ...]
    vectors: tuple[ForceVector, ...]
    negligible: tuple[str, ...]

    kind = "force"
    lines: tuple = ()

    @property
    def sides(self) -> tuple[ForceVector, ...]:
        return self.vectors


def _short_runs(lengths: Sequence[float], short: float, run: float) -> list[list[int]]:
    """Maximal runs (cyclic, in order) of consecutive sides each shorter than ``run`` with at
    least one shorter than ``short``: lists of side indices."""
    n = len(lengths)
    small = [L < run for L in lengths]
    if all(small) or n < 3:
        return []
    start = next(k for k in range(n) if not small[k])      # begin after a long side
    out, cur = [], []
    for m in range(1, n + 1):
        k = (start + m) % n
        if small[k]:
            cur.append(k)
        elif cur:
            out.append(cur)
            cur = []
    if cur:
        out.append(cur)
    return [r for r in out if len(r) > 1 and any(lengths[k] < short for k in r)]


def force_details(plan: ForcePlan, *, short: float = SHORT_SIDE_MM, run: float = RUN_SIDE_MM,
                  window: tuple[float, float] = DETAIL_REFERENCE_MM) -> tuple[ForceDetail, ...]:
    """The details of a plan's runs of short sides (see :class:`ForceDetail`): each run of
    consecutive sides shorter than ``run`` mm holding one shorter than ``short`` mm, at the
    series μF drawing its largest side in ``window`` mm (as :func:`force_scale`)."""
    sides = plan.sides
    if len(sides) < 3:
        return ()
    n = len(sides)
    names = [p.label for p in plan.points[:n]]        # side j runs from point j to point j + 1
    out = []
    for r in _short_runs([v.length for v in sides], short, run):
        vecs = np.array([np.subtract(sides[k].head, sides[k].tail) * plan.mu for k in r])   # N
        corners = np.vstack([np.zeros(2), np.cumsum(vecs, axis=0)])
        fmax = max(sides[k].value for k in r)
        extent = float(max(np.ptp(corners[:, 0]), np.ptp(corners[:, 1])))
        mu = force_scale(fmax, extent, window=window, limit=window[1] * 1.5)
        xy = corners / mu
        labels = [names[r[0]]] + [names[(k + 1) % n] for k in r]
        points = tuple(PlanPoint(labels[j], _pt(xy[j])) for j in range(len(labels)))
        vectors = tuple(ForceVector(sides[k].quantity, _pt(xy[j]), _pt(xy[j + 1]), sides[k].value, sides[k].kind)
                        for j, k in enumerate(r))
        negligible = tuple(v.quantity for v in vectors if v.length < short)
        out.append(ForceDetail(float(mu), r[0], points, vectors, negligible))
    return tuple(out)


def _totals(terms: Sequence[ForceTerm]) -> list[ForceTerm]:
    """The whole reaction of every pair of components ``R:…:n`` + ``R:…:t`` among the terms."""
    comps: dict[str, dict[str, ForceTerm]] = {}
    for t in terms:
        base, comp = component_of(t.quantity)
        if comp:
            comps.setdefault(base, {})[comp] = t
    out = []
    for base, pair in comps.items():
        if set(pair) == {"n", "t"}:
            v = np.add(pair["n"].vector, pair["t"].vector)
            out.append(ForceTerm(base, _pt(v), "reaction"))
    return out

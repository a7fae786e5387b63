"""Kinetostatics: the reactions of every pair and the balancing element, group by group.

The groups are solved from the farthest (the last attached) back to the original mechanism,
each with the loads of its links and the reactions the groups after it already put on them
(d'Alembert: every link is in equilibrium under its loads, its inertia included):

* a class II group in closed form, as the textbook builds its force plan:

  - RRR: R^τ of each outer pair from its link's moments about the inner pin E
    (R^τ_D = ΣM_E(link m)/l_DE, along k × (E − D)/l_DE), then R^n_D, R^n_F (along the links,
    D → E and F → E) from the group's force polygon (two known directions);
  - RRP: R^τ_D likewise, then R^n_D and the guide's normal reaction from the polygon;
  - RPR: the outer reactions' components along the slide from each link's forces along it,
    the rest from the group's moments about D and its polygon;
  - PRP: both normal reactions from the polygon; RPP: the two normal reactions on the middle
    link from its polygon, then R_D from the first link's.

  The inner reaction follows from one link's polygon, and each prismatic reaction's moment
  (where it acts along the guide) from its link's moments;
* a class III or IV group, and the original mechanism of a drive inside the chain, as one
  linear system: three equations a link (ΣFx, ΣFy, ΣM), two unknowns a pair (and the
  balancing element for the original mechanism), solved at every position at once;
* the driving link: its pairs with the frame and the balancing moment (or force) the same way.

A revolute pair's reaction acts at the pin. A prismatic pair's is normal to the guide, its
point of application unknown: it is held as the force N·ν (ν = k × u, u the guide's direction)
at the pair's reference point r0 plus a couple T (the reaction's moment about r0); it acts at
r0 + (T/N)·u along the guide.

Signs: ``R:i-j`` is the force of link i on link j (that of j on i is its opposite); moments
CCW positive; the balancing element is what the drive applies to the driving link, in
equilibrium with every load, inertia included.

The results are in :mod:`.results`, the pairs' geometry in :mod:`.pairs`, the solver (class
II closed forms, linear systems) in :mod:`.solver`, the balancing element and the power
balance in :mod:`.balance`; this module runs them in order and keeps every name importable
from here. Must not import constructions or anything above the kinetostatics.
"""

from __future__ import annotations

from typing import Mapping

import numpy as np

from ..kinematics import Motion
from ..scene import FRAME, Scene
from ..structure import ComplexGroup, DrivenGroup, Group, Pair
# every name importable from this module before the split stays importable from here
from .balance import _BalanceSpec, _balance_spec, _power
from .loads import Couple, Load, Travel
from .pairs import _Geometry, _Pair, _split, _unit
from .results import Balancing, Forces, ForceTerm, GroupForces, Reaction
from .solver import POINT_RTOL, SINGULAR_COND, _Solver

__all__ = ["ForceTerm", "GroupForces", "Reaction", "Balancing", "Forces", "solve_forces", "SINGULAR_COND",
           "POINT_RTOL"]


def _rod_components(s: _Solver, g: ComplexGroup, whole: list[ForceTerm]
                    ) -> tuple[list[ForceTerm], list[ForceTerm]] | None:
    """A class III group of three revolute rods (Assur's triad): each outer reaction split into
    R^τ (across its rod) and R^n (along it, outer pin → inner pin), for the polygon in the
    textbook's order — the R^τ first, then the loads, then the R^n, which close it. None for
    any other group (its reactions stay whole)."""
    rods = g.rods if isinstance(g, ComplexGroup) else ()
    if g.klass != 3 or len(rods) != 3 or any(r.form != "RR" for r in rods):
        return None
    taus, norms = [], []
    by_link = {t.quantity.rpartition("-")[2]: t for t in whole}
    for rod in rods:
        t = by_link[rod.link]
        nu, _ = _unit(s.geo.pin(rod.inner.point) - s.geo.pin(rod.outer.point))
        n = np.sum(t.vector * nu, axis=1)[:, None] * nu
        taus.append(ForceTerm(t.quantity + ":t", t.vector - n, "reaction"))
        norms.append(ForceTerm(t.quantity + ":n", n, "reaction"))
    return taus, norms


def solve_forces(motion: Motion, scene: Scene, *, closed_forms: bool = True, travel: Travel | None = None,
                 laws: Mapping[int, np.ndarray] | None = None) -> Forces:
    """The force analysis of ``scene`` on its solved ``motion`` (order 2 when a link has a
    mass or an inertia, order ≥ 1 for the power balance; order 0 gives no power check);
    ``travel``: the output's travel at the motion's positions, for forces with a law or a stroke;
    ``laws``: the values (N·m, CCW +) at the positions of the moments with a law in the crank angle.

    ``closed_forms=False`` solves the class II groups as linear systems too (the tests compare
    the two); their polygons then carry whole reactions, without the ``:n``/``:t`` split."""
    s = _Solver(motion, scene, travel, laws)
    mech, structure = s.mech, motion.structure
    for g in reversed(structure.groups):
        if isinstance(g, Group) and closed_forms:
            s.class2(g)
        else:
            if isinstance(g, Group):      # the dyad's pairs as a class III/IV group's
                g = ComplexGroup(links=(g.m, g.n), klass=2, inner=(
                    Pair(g.e.kind, g.m, g.n, g.e.point, g.e.prismatic),), outer=tuple(
                    Pair(j.kind, link, j.other, j.point, j.prismatic) for link, j in ((g.m, g.d), (g.n, g.f))))
            inner = [_Pair(p.a, p.b, p.kind, p.point, p.prismatic) for p in g.inner]
            outer = [_Pair(p.b, p.a, p.kind, p.point, p.prismatic) for p in g.outer]
            known = [t for link in g.links for t in s.terms_of(link)]
            s.system(g.name, g.links, inner + outer)
            whole = [ForceTerm(f"R:{p.first}-{p.second}", s.reactions[s._last_key(p.first, p.second)].force,
                               "reaction") for p in outer]
            split = _rod_components(s, g, whole)
            terms = known + whole if split is None else split[0] + known + split[1]
            inner_terms = tuple(ForceTerm(f"R:{p.first}-{p.second}",
                                          s.reactions[s._last_key(p.first, p.second)].force, "reaction") for p in inner)
            s.groups.append(GroupForces(g.name, g.links, tuple(terms), inner_terms))
    bal = _balance_spec(motion, scene, s.geo)
    driven: DrivenGroup | None = structure.driven
    if driven is not None:
        links = driven.links
        inner = [_Pair(p.a, p.b, p.kind, p.point, p.prismatic) for p in driven.inner]
        outer = [_Pair(p.b, p.a, p.kind, p.point, p.prismatic) for p in driven.outer]
        name = driven.name
    else:
        links = (mech.drive.link,)
        inner = []
        outer = [_Pair(FRAME, mech.drive.link, "R", point=r.point) for r in mech.revolutes
                 if {r.a, r.b} == {FRAME, mech.drive.link}]
        outer += [_Pair(FRAME, mech.drive.link, "P", prismatic=p) for p in mech.prismatics
                  if {p.slider, p.guide} == {FRAME, mech.drive.link}]
        name = structure.original
    known = [t for link in links for t in s.terms_of(link)]
    value = s.system(name, links, inner + outer, bal)
    if bal.kind == "moment":
        balancing = Balancing(mech.drive.link, "moment", value)
        bal_couples = (Couple("M:bal", mech.drive.link, value, "balance"),)
        bal_loads: tuple[Load, ...] = ()
        bal_terms: list[ForceTerm] = []
    else:
        other = bal.acts_on[1][0] if len(bal.acts_on) > 1 else None
        balancing = Balancing(mech.drive.link, bal.kind, value, at=bal.at, direction=bal.direction, point=bal.point,
                              reacts_on=other)
        vec = balancing.vector
        bal_loads = (Load("F:bal", mech.drive.link, bal.point, vec, "balance"),)
        if other is not None:
            bal_loads += (Load(f"F:bal:{other}", other, bal.point, -vec, "balance"),)
        bal_couples = ()
        bal_terms = [ForceTerm(l.quantity, l.force, "balance") for l in bal_loads]
    terms = known + bal_terms + [ForceTerm(f"R:{p.first}-{p.second}",
                                           s.reactions[s._last_key(p.first, p.second)].force, "reaction")
                                 for p in outer]
    inner_terms = tuple(ForceTerm(f"R:{p.first}-{p.second}", s.reactions[s._last_key(p.first, p.second)].force,
                                  "reaction") for p in inner)
    s.groups.append(GroupForces(name, links, tuple(terms), inner_terms))
    loads = s.loads + bal_loads
    couples = s.couples + bal_couples
    power, residual = _power(motion, s.loads, s.couples, balancing)
    return Forces(loads=loads, couples=couples, reactions=dict(s.reactions), groups=tuple(s.groups),
                  balance=balancing, power=power, power_residual=residual)

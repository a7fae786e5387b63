"""A group drawn alone with its forces (textbook Fig. 1.27 a, 1.28): the group's links cut free
of the links they join, at a μl of their own, every force at its point of application, the
outer pairs' reactions split into R^n (along the link) and R^τ (across it), the arms h of the
forces about the moment centres, and the moment equations that give the unknowns.

Which equations, by the group:

* **class II, RRR and RRP** — R^τ of each outer pin D from its link's moments about the inner
  pin E: ΣM_E(link) = 0, R^τ ⊥ DE, its arm l_DE; R^n passes through E. A slider's guide
  reaction is normal to the guide (no split) and drawn where it acts (its offset along the
  guide from the link's moments about E);
* **class III with three revolute rods** (Assur's triad, the forms RR-RR-RR) — R^τ of each
  rod's outer pin from the rod's moments about its inner pin, then the special point S where
  the lines of two rods meet: the group's moments about S give the third rod's R^n;
* **the driving link** — the balancing moment (or force) from its moments about its pivot;
* any other group (RPR, PRP, RPP, a class III group with sliders, class IV, a drive inside
  the chain) — its reactions whole, as the linear system of its equilibrium equations gives
  them; the diagram says so (:attr:`GroupDiagram.method`) and writes no moment equation.

Values are read from the solved :class:`~plans.kinetostatics.Forces` (the components are the
solved reactions' projections); each equation's unknown, recomputed from its terms, equals
them to rounding. Coordinates in diagram millimetres (world metres / μl, x right, y up),
forces in N, moments in N·m counter-clockwise positive, arms in m.
"""

from __future__ import annotations

import math

import numpy as np

from ..kinematics import Motion
from ..kinetostatics import Forces
from ..kinetostatics.loads import MIN_LOAD
from ..structure import ComplexGroup, Group
from .group_values import Arm, DiagramCouple, DiagramForce, GroupDiagram, MomentEquation, MomentTerm
from .scales import fitting_scale

__all__ = ["DiagramForce", "DiagramCouple", "Arm", "MomentTerm", "MomentEquation", "GroupDiagram",
           "group_diagrams", "DIAGRAM_MM", "LINK_MM", "ZERO_REL", "ARM_MM"]

#: Largest extent of a group drawn alone, mm: μl is the finest series scale that keeps it within
#: (of a single link, the driving link, :data:`LINK_MM`).
DIAGRAM_MM = 100.0
LINK_MM = 60.0
#: A force below this fraction of the diagram's largest is zero there: not drawn, no term.
ZERO_REL = 1e-12
#: An arm shorter than this on the diagram, mm, is not drawn (its force's line passes next to
#: the centre); its equation writes its length as a number instead of h_k.
ARM_MM = 0.5


def _pt(v) -> tuple[float, float]:
    return (float(v[0]) + 0.0, float(v[1]) + 0.0)


def _cross(a, b) -> float:
    return float(a[0]) * float(b[1]) - float(a[1]) * float(b[0])


class _Builder:
    """The world-frame pieces of one diagram at position ``i``."""

    def __init__(self, motion: Motion, forces: Forces, i: int, links: tuple[str, ...], solved: set[str]):
        self.motion, self.forces, self.i = motion, forces, i
        self.links, self.solved = links, solved
        self.mech = motion.mechanism
        self.forces_w: list[tuple[DiagramForce, np.ndarray]] = []      # with the world point (m)
        self.couples_w: list[tuple[DiagramCouple, np.ndarray]] = []

    def pos(self, point: str, link: str | None = None) -> np.ndarray:
        return np.asarray(self.motion.position(point, link)[self.i], dtype=float)

    def add_force(self, quantity, link, where: np.ndarray, point: str, vector, kind: str, known: bool) -> None:
        self.forces_w.append((DiagramForce(quantity, link, (0.0, 0.0), point, _pt(vector), kind, known), where))

    def add_couple(self, quantity, link, where: np.ndarray, value: float, known: bool) -> None:
        self.couples_w.append((DiagramCouple(quantity, link, (0.0, 0.0), float(value), known), where))

    def loads(self) -> None:
        """Every load of the group's links: gravity, inertia, external forces and couples, and
        the reactions of the groups solved before this one (known)."""
        i = self.i
        for l in self.forces.loads:
            if l.link in self.links and l.kind != "balance":
                self.add_force(l.quantity, l.link, np.asarray(l.point[i], float), self._name(l.point[i], l.link),
                               l.force[i], l.kind, True)
        for c in self.forces.couples:
            if c.link in self.links and c.kind != "balance":
                self.add_couple(c.quantity, c.link, self._centre(c.link), float(c.moment[i]), True)
        for r in self.forces.reactions.values():
            for on, other, sign in ((r.second, r.first, 1.0), (r.first, r.second, -1.0)):
                if on in self.links and other in self.solved:
                    self.reaction(r, on, other, sign, known=True)

    def reaction(self, r, on: str, other: str, sign: float, *, known: bool, quantity: str | None = None) -> None:
        """Reaction ``r`` as it acts on ``on`` (the force of ``other``), whole, where it acts."""
        i = self.i
        f = sign * np.asarray(r.force[i], float)
        q = quantity or f"R:{other}-{on}"
        if r.kind == "R":
            self.add_force(q, on, np.asarray(r.point[i], float), r.at, f, "reaction", known)
            return
        where = np.asarray(r.point[i], float)
        if not np.all(np.isfinite(where)):
            where = np.asarray(r.origin[i], float)            # a null reaction: drawn nowhere in particular
        self.add_force(q, on, where, r.at or "", f, "reaction", known)

    def _centre(self, link: str) -> np.ndarray:
        """Where a couple on ``link`` is drawn: its centre of mass (a load's point), else its
        first point."""
        for l in self.forces.loads:
            if l.link == link and l.kind in ("inertia", "gravity"):
                return np.asarray(l.point[self.i], float)
        return self.pos(self.mech.links[link].points[0], link)

    def _name(self, xy, link: str) -> str:
        for p in self.mech.links[link].points:
            if np.allclose(self.pos(p, link), xy, rtol=0.0, atol=1e-12 * self.mech.size):
                return p
        return ""


def _reaction_of(forces: Forces, first: str, second: str):
    """The reaction of ``first`` on ``second`` (the last recorded), with the sign to read it
    as the force of ``first`` on ``second``."""
    for r in reversed(list(forces.reactions.values())):
        if r.first == first and r.second == second:
            return r, 1.0
        if r.first == second and r.second == first:
            return r, -1.0
    raise KeyError(f"{first}-{second}")


def _moments(b: _Builder, links: tuple[str, ...], centre: np.ndarray, skip: set[str]) -> list[MomentTerm]:
    """The moments about ``centre`` of the forces and couples on ``links`` (but ``skip``)."""
    out = []
    for f, where in b.forces_w:
        if f.link not in links or f.quantity in skip or f.value == 0.0:
            continue
        m = _cross(where - centre, f.vector)
        arm = abs(m) / f.value
        out.append(MomentTerm(f.quantity, f.value, arm, math.copysign(1.0, m) if m else 1.0))
    for c, _ in b.couples_w:
        if c.link in links and c.quantity not in skip and c.value != 0.0:
            out.append(MomentTerm(c.quantity, abs(c.value), None, math.copysign(1.0, c.value)))
    return out


def _equation(b: _Builder, unknown: str, links: tuple[str, ...], about: str, centre: np.ndarray,
              skip: set[str]) -> MomentEquation:
    """ΣM_centre(links) = 0 for the drawn ``unknown`` (a force of the builder or a couple)."""
    terms = _moments(b, links, centre, skip | {unknown})
    known = sum(t.moment for t in terms)
    force = next((f for f, w in b.forces_w if f.quantity == unknown), None)
    if force is not None:
        where = next(w for f, w in b.forces_w if f.quantity == unknown)
        m = _cross(where - centre, force.direction)
        arm, sign = abs(m), (math.copysign(1.0, m) if m else 1.0)
        value = -known / (sign * arm) if arm > 0 else force.value
    else:
        couple = next(c for c, _ in b.couples_w if c.quantity == unknown)
        arm, sign = None, math.copysign(1.0, couple.value) if couple.value else 1.0
        value = -known / sign
    return MomentEquation(unknown, links, about, _pt(centre), tuple(terms), arm, sign, value)


def _split(b: _Builder, outer: str, on: str, pin: str, towards: np.ndarray) -> tuple[str, str]:
    """The reaction of ``outer`` on ``on`` at ``pin`` as R^n (along pin → ``towards``) and R^τ
    (across it), each drawn at the pin in its own sense; returns their quantities."""
    r, sign = _reaction_of(b.forces, outer, on)
    f = sign * np.asarray(r.force[b.i], float)
    at = b.pos(pin)
    d = towards - at
    u = d / math.hypot(*d)
    n = float(f[0] * u[0] + f[1] * u[1])
    rn, rt = n * u, f - n * u
    q = f"{outer}-{on}"
    b.add_force(f"Rt:{q}", on, at, pin, rt, "reaction_t", False)
    b.add_force(f"Rn:{q}", on, at, pin, rn, "reaction_n", False)
    return f"Rt:{q}", f"Rn:{q}"


def _whole(b: _Builder, outer: str, on: str) -> None:
    r, sign = _reaction_of(b.forces, outer, on)
    b.reaction(r, on, outer, sign, known=False)


def _meet(p1, d1, p2, d2) -> np.ndarray | None:
    """Where the lines p1 + s·d1 and p2 + t·d2 meet; None when (nearly) parallel."""
    det = _cross(d1, d2)
    if abs(det) < 1e-6 * math.hypot(*d1) * math.hypot(*d2):
        return None
    s = _cross(p2 - p1, d2) / det
    return p1 + s * d1


def _class2(b: _Builder, g: Group) -> tuple[list[tuple], str, list[str]]:
    """RRR, RRP: the R^τ equations (and the slider's offset); other forms whole."""
    eqs, notes = [], []
    if g.form in ("RRR", "RRP"):
        e = b.pos(g.e.point)
        for link, j in ((g.m, g.d), (g.n, g.f)):
            if j.kind == "R":
                t, n = _split(b, j.other, link, j.point, e)
                eqs.append((t, (link,), g.e.point, e, {n}))
            else:
                _whole(b, j.other, link)
        b.loads()
        if g.form == "RRP":
            r, sign = _reaction_of(b.forces, g.f.other, g.n)
            off = float(r.offset[b.i]) if r.offset is not None else math.nan
            q = f"R_{{{g.f.other}{g.n}}}" if len(g.f.other) == 1 == len(g.n) else f"R_{{{g.f.other},{g.n}}}"
            if math.isfinite(off):
                where = (f"through {r.at}" if abs(off) <= 1e-9 * b.mech.size else
                         f"{abs(off) * 1000:.4g} mm {'along' if off >= 0 else 'against'} the guide from {r.at}")
                notes.append(f"{q} is normal to the guide and acts {where} (ΣM_{g.e.point}({g.n}) = 0)")
        method = (f"moments about {g.e.point} of each link give R^τ; the polygon closes on the lines of R^n"
                  if g.form == "RRR" else
                  f"moments about {g.e.point} of link {g.m} give R^τ; the guide's reaction is normal to it "
                  "(no split); the polygon closes on its line and that of R^n")
        return eqs, method, notes
    for link, j in ((g.m, g.d), (g.n, g.f)):
        _whole(b, j.other, link)
    b.loads()
    return [], _SYSTEM[g.form], notes


_SYSTEM = {
    "RPR": "the sliding pair carries no force along the slide: each outer reaction's part along it from its "
           "link's forces along it, the rest from the group's moments about the first pin and its polygon",
    "PRP": "both guides' reactions are normal to them: their values from the group's polygon, where each acts "
           "from its link's moments about the pin",
    "RPP": "the middle link's two normal reactions from its polygon, then the first pin's from the first link's",
}


def _class3(b: _Builder, g: ComplexGroup) -> tuple[list[tuple], str, list[str], list[tuple]]:
    rods = g.rods
    if g.klass != 3 or len(rods) != 3 or any(r.form != "RR" for r in rods):
        for p in g.outer:
            _whole(b, p.b, p.a)
        b.loads()
        return [], ("solved as one linear system: three equilibrium equations a link (ΣF_x, ΣF_y, ΣM), two "
                    "unknowns a pair"), [], []
    eqs, lines = [], []
    for rod in rods:
        inner = b.pos(rod.inner.point)
        t, n = _split(b, rod.outer.b, rod.link, rod.outer.point, inner)
        eqs.append((t, (rod.link,), rod.inner.point, inner, {n}))
        lines.append((rod, b.pos(rod.outer.point), inner - b.pos(rod.outer.point), n))
    b.loads()
    # Assur's special point: the two rods' lines that meet at the best angle
    best = None
    for a, c, k in ((0, 1, 2), (0, 2, 1), (1, 2, 0)):
        (_, p1, d1, n1), (_, p2, d2, n2) = lines[a], lines[c]
        s = _meet(p1, d1, p2, d2)
        if s is None:
            continue
        sin = abs(_cross(d1, d2)) / (math.hypot(*d1) * math.hypot(*d2))
        if best is None or sin > best[0]:
            best = (sin, s, k, {n1, n2})
    special = []
    if best is not None:
        _, s, k, through = best
        eqs.append((lines[k][3], tuple(g.links), "S", s, through))
        special.append(("S", s))
        method = ("the group's moments about Assur's special point S, where the lines of two rods' R^n meet, give "
                  "the third rod's R^n; the polygon (R^τ of the rods, the loads, that R^n) closes on the lines of "
                  "the other two")
    else:
        method = "moments of each rod about its inner pin give R^τ; the rods are parallel (no special point)"
    return eqs, method, [], special


_TRIAD_TAU = "moments of each rod about its inner pin give its outer pin's R^τ"


def _driving(b: _Builder, motion: Motion, forces: Forces) -> tuple[list[tuple], str, list[str]]:
    mech = motion.mechanism
    link = mech.drive.link
    bal = forces.balance
    pivot = next((r for r in forces.reactions.values() if {r.first, r.second} == {"0", link}), None)
    for r in forces.reactions.values():
        if {r.first, r.second} == {"0", link}:
            b.reaction(r, link, "0", 1.0 if r.second == link else -1.0, known=False)
    b.loads()
    if bal.kind == "moment":
        b.add_couple("M:bal", link, b._centre(link) if pivot is None or pivot.kind != "R" else
                     np.asarray(pivot.point[b.i], float), float(bal.value[b.i]), False)
    elif bal.kind == "force":
        b.add_force("F:bal", link, np.asarray(bal.point[b.i], float), bal.at or "", bal.vector[b.i], "balance", False)
    if pivot is None or pivot.kind != "R" or bal.kind == "actuator":
        return [], ("the driving link's equilibrium: its pairs' reactions and the balancing element from its three "
                    "equations"), []
    o = np.asarray(pivot.point[b.i], float)
    unknown = "M:bal" if bal.kind == "moment" else "F:bal"
    skip = {q.quantity for q, _ in b.forces_w if q.quantity.startswith("R:0-")}
    return [(unknown, (link,), pivot.at, o, skip)], (f"moments about {pivot.at} give the balancing "
                                                     f"{'moment' if bal.kind == 'moment' else 'force'}; the "
                                                     "polygon gives the frame's reaction"), []


def group_diagrams(motion: Motion, forces: Forces, i: int) -> tuple[GroupDiagram, ...]:
    """Every group's diagram at position ``i``, in the order solved (the farthest group first,
    the driving link last), as :func:`~plans.constructions.kinetostatics.group_force_plans`."""
    structure = motion.structure
    by_name = {g.name: g for g in structure.groups}
    solved: set[str] = set()
    out = []
    for gf in forces.groups:
        b = _Builder(motion, forces, i, tuple(gf.links), set(solved))
        special: list[tuple] = []
        g = by_name.get(gf.group)
        if isinstance(g, Group):
            eqs, method, notes = _class2(b, g)
        elif isinstance(g, ComplexGroup):
            eqs, method, notes, special = _class3(b, g)
            if special:            # two views: the rods' R^τ, then the group about S
                out.append(_finish(b, gf.group, eqs[:-1], _TRIAD_TAU, notes, []))
                eqs, method = eqs[-1:], method
        elif gf.group == structure.original and structure.driven is None:
            eqs, method, notes = _driving(b, motion, forces)
        else:
            for p in structure.driven.outer if structure.driven is not None else ():
                _whole(b, p.b, p.a)
            b.loads()
            eqs, method, notes = [], ("solved as one linear system with the balancing element: three equations a "
                                      "link"), []
        out.append(_finish(b, gf.group, eqs, method, notes, special))
        solved |= set(gf.links)
    return tuple(out)


def _printed(quantity: str) -> str:
    """A tag in the sheets' label markup (R_{12,τ}, M_{bal}, F_{bal})."""
    kind, _, rest = quantity.partition(":")
    if kind in ("Rt", "Rn"):
        i, _, j = rest.partition("-")
        ij = f"{i}{j}" if len(i) == 1 == len(j) else f"{i},{j}"
        return f"R_{{{ij},{'τ' if kind == 'Rt' else 'n'}}}"
    return f"{kind}_{{{rest}}}"


def _finish(b: _Builder, group: str, eqs: list[tuple], method: str, notes: list[str], special: list[tuple]
            ) -> GroupDiagram:
    """Scale the world pieces to the diagram's μl, drop zero forces, number the arms."""
    notes = list(notes)
    mech = b.mech
    pts: dict[str, np.ndarray] = {}
    bars = []
    for link in b.links:
        names = tuple(mech.links[link].points)
        for p in names:
            pts.setdefault(p, b.pos(p, link))
        bars.append((link, names))
    xy = np.array(list(pts.values()) + [w for _, w in b.forces_w] + [s for _, s in special])
    extent = float(np.max(np.ptp(xy, axis=0))) if len(xy) > 1 else 0.0
    most = LINK_MM if len(b.links) == 1 else DIAGRAM_MM
    mu = fitting_scale(extent, most) if extent > 0 else fitting_scale(0.1 * mech.size, most)
    top = max((f.value for f, _ in b.forces_w), default=0.0)
    zero = max(ZERO_REL * top, MIN_LOAD)

    def mm(w) -> tuple[float, float]:
        return _pt(np.asarray(w, float) / mu)

    forces = tuple(DiagramForce(f.quantity, f.link, mm(w), f.point, f.vector, f.kind, f.known)
                   for f, w in b.forces_w if f.value > zero)
    couples = tuple(DiagramCouple(c.quantity, c.link, mm(w), c.value, c.known) for c, w in b.couples_w
                    if abs(c.value) > max(zero * mech.size, MIN_LOAD))
    drawn = {f.quantity for f in forces} | {c.quantity for c in couples}
    equations, arms = [], []
    for unknown, links, about, centre, skip in eqs:
        if unknown not in drawn:               # a zero unknown: nothing drawn, the sheet says why
            notes.append(f"{_printed(unknown)} = 0: the moments about {about} of the other forces cancel (each "
                         f"line through {about}, or their sum zero to rounding)")
            continue
        e = _equation(b, unknown, links, about, centre, skip)
        e = MomentEquation(e.unknown, e.links, e.about, mm(e.centre), tuple(t for t in e.terms if t.quantity in drawn),
                           e.arm, e.sign, e.value)
        equations.append(e)
        c = np.asarray(centre, float)
        for t in list(e.terms) + [MomentTerm(e.unknown, e.value, e.arm, e.sign)]:
            if t.arm is None or t.arm / mu < ARM_MM:
                continue
            f, where = next((f, w) for f, w in b.forces_w if f.quantity == t.quantity)
            d = np.asarray(f.direction)
            foot = where + float((c - where)[0] * d[0] + (c - where)[1] * d[1]) * d
            arms.append(Arm(t.quantity, about, mm(c), mm(foot), t.arm, len(arms) + 1))
    return GroupDiagram(group, mu, tuple((link, names, tuple(mm(pts[p]) for p in names)) for link, names in bars),
                        tuple((p, mm(w)) for p, w in pts.items()), forces, couples, tuple(arms), tuple(equations),
                        tuple((n, mm(s)) for n, s in special), method, tuple(notes))

"""Every real assembly of the class III and IV groups with sliding pairs of
tests/test_assemblies_prismatic.py (FORMS and LOCKED), against an independent enumeration at 60
digits (mpmath): the count and every point of the group's links agree with
plans.kinematics.assemblies within 1e-9 of the mechanism's size, one to one.

The enumeration is written here from the scene's sketch alone: a link's pose (θ, o) maps its sketch
point x to o + R(θ)x; a pin joins the links that list it; a [[sliders]] entry (link, on, through,
angle) keeps θ_link = θ_on and the point `through` of the slider on the guide's line, i.e.
(o_link − o_on) ∥ R(θ_on)·u(angle). It shares no code with plans' elimination and places each
group by other unknowns, two at most (plans eliminates the base's position C, or a link's angle by
Cramer on cos ψ, sin ψ, and maps a travel onto tan(φ/2)):

    form        unknowns (t; w)                          conditions (k: × (1 + t²)^k; w-degrees)
    RR-RR-RP    base angle; travel of pin D on its line   rods AB, FM: circles (k 1; 2, 2)
    RR-PR-PR    base angle; travel of block C             rod AB circle (1; 2), F on its guide (1; 1)
    PR-PR-RP    base angle; travel of block C             F on its guide (1; 1), A on the base's line (1; 1)
    RRPR-RR     plate 4's angle; travel of C along it     plate 2 closes |AC| (1; 2), rod BF (1; 2)
    RRRR-RP     plate 2's angle; travel of block 4        rods CD, BF (1; 2, 2)
    RRRR-PP     travel of plate 2 on the crank; of 4      rods CD, BF (plain; 2, 2)
    RR-RR-PP    rod AB's angle (the base only translates)  rod FM (1)
    RRPP-RR     the common angle of plates 2, 3, 4         rod BF (1)

An angle enters as t = tan(φ/2) (cos φ = (1 − t²)/(1 + t²), sin φ = 2t/(1 + t²)), a travel as a
plain unknown. Each condition × (1 + t²)^k is a polynomial; its coefficients are read off by
sampling it on the unit circle (points e^{iπ(2j+1)/n}, never ±i) and an inverse DFT, with twice the
samples the degree needs, the extra coefficients asserted to vanish (1e-45 relative): the degrees
above are checked, not assumed. w is eliminated by the Sylvester resultant (its determinant at each
sample of t), a polynomial R(t) of degree ≤ D = 2(k₁n + k₂m) (m, n the w-degrees); for an angle
R(t) = (1 + t²)^{D/2}·F(φ), F a trigonometric polynomial, so its leading coefficient is a multiple of
F(π): when it vanishes (≤ 1e-40 relative) φ = π (t = ∞) is a root and is added. For the plain
travels of RRRR-PP coefficients that vanish in exact arithmetic (the two conics share their quadratic
part: degree 2, not Bézout's 4) are ≤ 1e-50 relative and dropped, the kept leading one ≥ 1e-20.
R vanishes at every common root: w's leading coefficient never vanishes for real t (it is
(1 + t²)·|u|², (1 + t²)·u_C × u_F, (1 + t²)·|BA|²/|CA|² or 1), so a real assembly is a real root of R
with a finite w; a travel is never infinite at an assembly, so nothing is lost at w = ∞.
mpmath.polyroots (Durand–Kerner, extra precision) returns every complex root or raises. A root is
real when |Im t| ≤ 1e-20·max(1, |t|); each case asserts the clean gap of the revolute check
(tests/test_assemblies_precise.py): kept below 1e-30, rejected above 1e-6. At a real t, w is the
root of the condition of lower w-degree where the other holds (≤ 1e-25 relative; the other roots
above 1e-6), real (two real polynomials share a complex root only with its conjugate: both roots,
asserted not to happen). Every pose is checked on every pair equation of the sketch (pins coincide,
sliders parallel and on their lines, rotations unit) to 1e-40·size. Poses closer than 1e-9·size
count as one. The tolerance 1e-9·size is plans' SAME_RTOL (the rounding budget: see the revolute check).
"""

from __future__ import annotations

import copy
import math

import mpmath as mp
import pytest
from test_assemblies_precise import matched
from test_assemblies_prismatic import FORMS, LOCKED

from plans.errors import SceneError
from plans.kinematics.assemblies import group_assemblies
from plans.pipeline import solve_scene
from plans.scene import parse_scene

DPS = 60
REAL = mp.mpf("1e-20")      # |Im t| / max(1, |t|) of a real root
TOL = 1e-9                  # agreement, × size (plans' SAME_RTOL)
CASES = {**{f: d for f, (d, _) in FORMS.items()}, "RRPP-RR": LOCKED}
COUNTS = {**{f: n for f, (_, n) in FORMS.items()}, "RRPP-RR": 2}


# --- plane vectors (mp real or complex) --------------------------------------------------------

def _add(a, b):
    return (a[0] + b[0], a[1] + b[1])


def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def _mul(k, a):
    return (k * a[0], k * a[1])


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def _cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def _sq(a):
    return a[0] * a[0] + a[1] * a[1]


def _rot(v, cs, sn):
    return (cs * v[0] - sn * v[1], sn * v[0] + cs * v[1])


def _unit(deg):
    a = mp.radians(mp.mpf(deg))
    return (mp.cos(a), mp.sin(a))


# --- the scene ----------------------------------------------------------------------------------

class Scene:
    """The sketch (mp), the frame and crank poses at a drive angle (deg), and small placements.
    A pose is (cos θ, sin θ, o)."""

    def __init__(self, d: dict, angle: float):
        self.d = d
        self.sk = {p: (mp.mpf(x), mp.mpf(y)) for p, (x, y) in d["points"].items()}
        drive = d["drive"]["link"]
        pivot = next(p for p in d["links"][drive] if p in d["links"]["0"])
        tip = next(p for p in d["links"][drive] if p != pivot)
        arm = _sub(self.sk[tip], self.sk[pivot])
        th = mp.radians(mp.mpf(angle)) - mp.atan2(arm[1], arm[0])
        c, s = mp.cos(th), mp.sin(th)
        self.known = {"0": (mp.mpf(1), mp.mpf(0), (mp.mpf(0), mp.mpf(0))),
                      drive: (c, s, _sub(self.sk[pivot], _rot(self.sk[pivot], c, s)))}
        self.A = self.at(self.known[drive], tip)

    def at(self, pose, p):
        """World point of sketch point p on a link at ``pose``."""
        return _add(pose[2], _rot(self.sk[p], pose[0], pose[1]))

    def l2(self, p, q):
        return _dot(_sub(self.sk[p], self.sk[q]), _sub(self.sk[p], self.sk[q]))

    def guide(self, link, on):
        """The slider (link on ``on``)'s sketch anchor and local unit direction."""
        s = next(s for s in self.d["sliders"] if s["link"] == link and s["on"] == on)
        return self.sk[s["through"]], _unit(s["angle"])

    def pins(self, p, wp, q, wq):
        """The pose of a link with sketch points p, q at world wp, wq (a rotation where
        |wq − wp| = |q − p|; polynomial in wp, wq)."""
        a, b = _sub(self.sk[q], self.sk[p]), _sub(wq, wp)
        n = _dot(a, a)
        cs, sn = _dot(a, b) / n, _cross(a, b) / n
        return (cs, sn, _sub(wp, _rot(self.sk[p], cs, sn)))

    def pinned(self, cs, sn, p, wp):
        """The pose at angle (cs, sn) with sketch point p at world wp."""
        return (cs, sn, _sub(wp, _rot(self.sk[p], cs, sn)))


# --- the forms: (t kind, [(condition, k, w-degree)], D, pose) -------------------------------------
# A condition is f(x, w) with x = (cos, sin) for an angle, the value for a plain unknown.

def _rr_rr_rp(S):
    a, u = S.guide("4", "3")                        # pin D (frame) on the base's line through a

    def base(x, s):
        return (x[0], x[1], _sub(S.sk["D"], _rot(_add(a, _mul(s, u)), *x)))

    f1 = lambda x, s: _sq(_sub(S.at(base(x, s), "B"), S.A)) - S.l2("A", "B")
    f2 = lambda x, s: _sq(_sub(S.at(base(x, s), "F"), S.sk["M"])) - S.l2("F", "M")

    def pose(x, s):
        b = base(x, s)
        return {"3": b, "2": S.pins("A", S.A, "B", S.at(b, "B")), "5": S.pins("F", S.at(b, "F"), "M", S.sk["M"]),
                "4": S.pinned(*x, "D", S.sk["D"])}
    return "angle", [(f1, 1, 2), (f2, 1, 2)], None, pose


def _blocks(S):
    """RR-PR-PR (rod 2 from A to B) and PR-PR-RP (rod 2 pinned at A slides on the base): base 3 at
    angle x with block C moved s along its frame guide."""
    (_, uc), (_, uf) = S.guide("4", "0"), S.guide("5", "0")
    base = lambda x, s: S.pinned(*x, "C", _add(S.sk["C"], _mul(s, uc)))
    on_f = lambda x, s: _cross(_sub(S.at(base(x, s), "F"), S.sk["F"]), uf)          # block 5 moved along uf
    rod = "B" in S.d["links"]["2"]

    def pose(x, s):
        b = base(x, s)
        return {"3": b, "4": (1, 0, _mul(s, uc)), "5": (1, 0, _sub(S.at(b, "F"), S.sk["F"])),
                "2": S.pins("A", S.A, "B", S.at(b, "B")) if rod else S.pinned(*x, "A", S.A)}
    if rod:
        f = lambda x, s: _sq(_sub(S.at(base(x, s), "B"), S.A)) - S.l2("A", "B")
        return "angle", [(f, 1, 2), (on_f, 1, 1)], None, pose
    _, u = S.guide("2", "3")                        # rod 2 moved along the base's line
    on_a = lambda x, s: _cross(_sub(S.pinned(*x, "A", S.A)[2], base(x, s)[2]), _rot(u, *x))
    return "angle", [(on_f, 1, 1), (on_a, 1, 1)], None, pose


def _rr_rr_pp(S):
    (_, u4), (_, u3) = S.guide("4", "0"), S.guide("3", "4")       # θ3 = θ4 = 0: the base translates
    o3 = lambda x: _sub(_add(S.A, _rot(_sub(S.sk["B"], S.sk["A"]), *x)), S.sk["B"])
    rod = lambda x, w: _sq(_sub(_add(S.sk["F"], o3(x)), S.sk["M"])) - S.l2("F", "M")

    def pose(x, w):
        o = o3(x)
        k = _cross(o, u3) / _cross(u4, u3)            # o4 ∥ u4 and o3 − o4 ∥ u3 (equal angles)
        return {"2": S.pinned(*x, "A", S.A), "3": (1, 0, o), "4": (1, 0, _mul(k, u4)),
                "5": S.pins("F", _add(S.sk["F"], o), "M", S.sk["M"])}
    return "angle", [(rod, 1, 0)], None, pose


def _rrpr_rr(S):
    a, u = S.guide("3", "4")                        # C (pin of plate 2) along plate 4's line
    p4 = lambda x: S.pinned(*x, "E", S.sk["E"])
    cw = lambda x, s: _add(p4(x)[2], _rot(_add(a, _mul(s, u)), *x))
    p2 = lambda x, s: S.pins("A", S.A, "C", cw(x, s))
    f1 = lambda x, s: _sq(_sub(cw(x, s), S.A)) - S.l2("A", "C")
    f2 = lambda x, s: _sq(_sub(S.at(p2(x, s), "B"), S.at(p4(x), "F"))) - S.l2("B", "F")

    def pose(x, s):
        return {"4": p4(x), "3": S.pinned(*x, "C", cw(x, s)), "2": p2(x, s),
                "5": S.pins("F", S.at(p4(x), "F"), "B", S.at(p2(x, s), "B"))}
    return "angle", [(f1, 1, 2), (f2, 1, 2)], None, pose


def _rrrr_rp(S):
    a, u = S.guide("4", "0")
    p2 = lambda x: S.pinned(*x, "A", S.A)
    p4 = lambda s: (1, 0, _mul(s, u))
    f1 = lambda x, s: _sq(_sub(S.at(p2(x), "C"), S.at(p4(s), "D"))) - S.l2("C", "D")
    f2 = lambda x, s: _sq(_sub(S.at(p2(x), "B"), S.at(p4(s), "F"))) - S.l2("B", "F")

    def pose(x, s):
        return {"2": p2(x), "4": p4(s), "3": S.pins("C", S.at(p2(x), "C"), "D", S.at(p4(s), "D")),
                "5": S.pins("F", S.at(p4(s), "F"), "B", S.at(p2(x), "B"))}
    return "angle", [(f1, 1, 2), (f2, 1, 2)], None, pose


def _rrrr_pp(S):
    (_, u2), (_, u4) = S.guide("2", "1"), S.guide("4", "0")
    c1, s1, o1 = S.known["1"]
    p2 = lambda s: (c1, s1, _add(o1, _mul(s, _rot(u2, c1, s1))))      # θ2 = θ1, moved along the crank's line
    p4 = lambda s: (1, 0, _mul(s, u4))
    f1 = lambda s, w: _sq(_sub(S.at(p2(s), "C"), S.at(p4(w), "D"))) - S.l2("C", "D")
    f2 = lambda s, w: _sq(_sub(S.at(p2(s), "B"), S.at(p4(w), "F"))) - S.l2("B", "F")

    def pose(s, w):
        return {"2": p2(s), "4": p4(w), "3": S.pins("C", S.at(p2(s), "C"), "D", S.at(p4(w), "D")),
                "5": S.pins("F", S.at(p4(w), "F"), "B", S.at(p2(s), "B"))}
    return "plain", [(f1, 0, 2), (f2, 0, 2)], 4, pose


def _rrpp_rr(S):
    (_, u4), (_, u2) = S.guide("3", "4"), S.guide("3", "2")        # θ2 = θ3 = θ4
    p2 = lambda x: S.pinned(*x, "A", S.A)
    p4 = lambda x: S.pinned(*x, "E", S.sk["E"])
    rod = lambda x, w: _sq(_sub(S.at(p2(x), "B"), S.at(p4(x), "F"))) - S.l2("B", "F")

    def pose(x, w):
        o2, o4, r4, r2 = p2(x)[2], p4(x)[2], _rot(u4, *x), _rot(u2, *x)
        k = _cross(_sub(o2, o4), r2) / _cross(r4, r2)              # o3 = o4 + k·r4 = o2 + j·r2
        return {"2": p2(x), "4": p4(x), "3": (x[0], x[1], _add(o4, _mul(k, r4))),
                "5": S.pins("F", S.at(p4(x), "F"), "B", S.at(p2(x), "B"))}
    return "angle", [(rod, 1, 0)], None, pose


FORM = {"RR-RR-RP": _rr_rr_rp, "RR-PR-PR": _blocks, "PR-PR-RP": _blocks, "RR-RR-PP": _rr_rr_pp,
        "RRPR-RR": _rrpr_rr, "RRRR-RP": _rrrr_rp, "RRRR-PP": _rrrr_pp, "RRPP-RR": _rrpp_rr}


# --- polynomials from samples, the resultant, the real roots --------------------------------------

class Continuum(Exception):
    """R vanishes identically: the conditions hold along a curve of poses."""


def _coeffs(fun, deg: int, scale=lambda: 0) -> tuple[list, mp.mpf]:
    """The coefficients (lowest first) of the polynomial ``fun`` of degree ≤ deg, from its values at
    n = 4·⌈(2deg + 2)/4⌉ points e^{iπ(2j+1)/n} of the unit circle (never ±i) by the inverse DFT;
    those above deg are asserted to vanish (the degree is checked). Also the largest |coefficient|.
    Raises Continuum when that is below 1e-30·scale() (called after the sampling)."""
    n = 4 * -(-(2 * deg + 2) // 4)
    zs = [mp.expjpi(mp.mpf(2 * j + 1) / n) for j in range(n)]
    vals = [fun(z) for z in zs]
    c = [sum(v * z ** -k for v, z in zip(vals, zs)) / n for k in range(n)]
    big = max(abs(x) for x in c)
    if big <= mp.mpf(10) ** -30 * scale():
        raise Continuum
    assert all(abs(x) <= mp.mpf(10) ** -45 * big for x in c[deg + 1:])
    return c[:deg + 1], big


def _x(kind: str, t):
    """An unknown's representation in the conditions: (cos φ, sin φ) of t = tan(φ/2), or t itself."""
    return ((1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)) if kind == "angle" else t


def _sylvester(p: list, q: list):
    """The Sylvester resultant of p, q (coefficients lowest first, formal degrees len − 1)."""
    m, n = len(p) - 1, len(q) - 1
    rows = [[0] * i + p[::-1] + [0] * (n - 1 - i) for i in range(n)]
    rows += [[0] * i + q[::-1] + [0] * (m - 1 - i) for i in range(m)]
    return mp.det(mp.matrix(rows))


def _eliminated(kind: str, conds: list, deg: int | None, size) -> tuple[list, int]:
    """R(t) (coefficients, real), w eliminated by the Sylvester resultant, or the one condition (a
    rod's, m²) × (1 + t²)^k; its formal degree D. Raises Continuum when R is identically zero: its
    coefficients below 1e-30 of the products of its conditions' (or of size²)."""
    lift = (lambda t, k: (1 + t * t) ** k) if kind == "angle" else (lambda t, k: 1)
    if len(conds) == 1:
        f, k, _ = conds[0]
        c, big = _coeffs(lambda t: f(_x(kind, t), None) * lift(t, k), 2 * k, lambda: size ** 2)
    else:
        (f1, k1, m), (f2, k2, n) = conds
        D = deg or 2 * (k1 * n + k2 * m)
        sizes = []

        def res(t):
            x = _x(kind, t)
            (p, bp), (q, bq) = (_coeffs(lambda w: f(x, w) * lift(t, k), d) for f, k, d in conds)
            sizes.append(bp ** n * bq ** m)
            return _sylvester(p, q)
        c, big = _coeffs(res, D, lambda: max(sizes))
    assert all(abs(mp.im(x)) <= mp.mpf(10) ** -45 * big for x in c)
    return [mp.re(x) for x in c], len(c) - 1


def _real_roots(kind: str, poly: list) -> tuple[list, dict]:
    """Every real root (the representation of :func:`_x`) of R, φ = π added for each vanishing
    leading coefficient of an angle's R; the gap: the largest relative |Im t| kept, the smallest
    rejected, the roots at φ = π, and (a plain unknown) the kept leading coefficient ÷ the largest."""
    big = max(abs(c) for c in poly)
    out, trimmed = [], mp.mpf(0)
    while abs(poly[-1]) <= mp.mpf(10) ** -40 * big:
        trimmed = max(trimmed, abs(poly[-1]) / big)
        poly = poly[:-1]
        if kind == "angle":
            out.append((mp.mpf(-1), mp.mpf(0)))
    roots = mp.polyroots(poly, maxsteps=4000, extraprec=4 * mp.mp.prec, asc=True) if len(poly) > 1 else []
    rel = [abs(mp.im(r)) / max(1, abs(r)) for r in roots]
    for r, e in zip(roots, rel):
        if e <= REAL:
            phi = 2 * mp.atan(mp.re(r))
            out.append((mp.cos(phi), mp.sin(phi)) if kind == "angle" else mp.re(r))
    gap = {"kept": max([e for e in rel if e <= REAL], default=mp.mpf(0)),
           "rejected": min([e for e in rel if e > REAL], default=mp.inf), "pi": len(out) - sum(e <= REAL for e in rel),
           "lead": abs(poly[-1]) / big, "trimmed": trimmed}
    return out, gap


def _common(x, conds: list) -> tuple[list, mp.mpf]:
    """Every w where both conditions hold at the real x: the roots of the one of lower w-degree
    where the other vanishes (≤ 1e-25 relative); and the smallest relative value at the others."""
    (fa, _, da), (fb, _, db) = sorted(conds, key=lambda c: c[2])
    pa = [mp.re(c) for c in _coeffs(lambda w: fa(x, w), da)[0]]
    pb = [mp.re(c) for c in _coeffs(lambda w: fb(x, w), db)[0]]
    assert abs(pa[-1]) > mp.mpf(10) ** -20 * max(abs(c) for c in pa)     # w's leading coefficient (see the module)
    ws = [-pa[0] / pa[1]] if da == 1 else mp.polyroots(pa, maxsteps=400, extraprec=4 * mp.mp.prec, asc=True)
    out, other = [], mp.inf
    for w in ws:
        e = abs(mp.polyval(pb, w, asc=True)) / mp.fsum(abs(c) * max(1, abs(w)) ** k for k, c in enumerate(pb))
        if e <= mp.mpf(10) ** -25:
            assert abs(mp.im(w)) <= mp.mpf(10) ** -30 * max(1, abs(w))
            out.append(mp.re(w))
        else:
            other = min(other, e)
    return out, other


# --- the poses, checked on every pair of the sketch -----------------------------------------------

def _checked(S: Scene, poses: dict, size) -> dict:
    """The world points of the group's links at ``poses`` (links → pose), after asserting every pair
    equation touching the group to 1e-40·size: unit rotations, the owners of each pin at one
    point, each slider at its guide's angle with its anchor on the guide's line."""
    eps = mp.mpf(10) ** -40
    tol, allp = eps * size, {**S.known, **poses}
    for c, s, _ in poses.values():
        assert abs(c * c + s * s - 1) <= eps
    for p in S.sk:
        owners = [n for n, ps in S.d["links"].items() if p in ps]
        if len(owners) > 1 and set(owners) & set(poses):
            w = [S.at(allp[n], p) for n in owners]
            assert max(mp.sqrt(_sq(_sub(a, w[0]))) for a in w) <= tol
    for sl in S.d["sliders"]:
        if {sl["link"], sl["on"]} & set(poses):
            (c, s, o), (cg, sg, og) = allp[sl["link"]], allp[sl["on"]]
            assert abs(c - cg) <= eps and abs(s - sg) <= eps
            normal = _rot(_rot(_unit(sl["angle"]), 0, 1), cg, sg)
            assert abs(_dot(_sub(S.at((c, s, o), sl["through"]), S.at((cg, sg, og), sl["through"])), normal)) <= tol
    pts = {}
    for n, pose in poses.items():
        for p in S.d["links"][n]:
            pts.setdefault(p, S.at(pose, p))
    return pts


def precise_assemblies(form: str, d: dict, angle: float, size: float) -> tuple[list[dict], dict]:
    """Every real assembly of scene ``d``'s group of form ``form`` with the crank at ``angle`` (deg):
    the world points (floats, m) of its links, poses closer than TOL·size merged; and the gaps."""
    with mp.workdps(DPS):
        S = Scene(d, angle)
        kind, conds, deg, pose = FORM[form](S)
        poly, D = _eliminated(kind, conds, deg, mp.mpf(size))
        xs, gap = _real_roots(kind, poly)
        gap.update(degree=D, other=mp.inf)
        out = []
        for x in xs:
            ws = [None]
            if len(conds) == 2:
                ws, other = _common(x, conds)
                assert ws
                gap["other"] = min(gap["other"], other)
            for w in ws:
                pts = {p: (float(a), float(b)) for p, (a, b) in _checked(S, pose(x, w), mp.mpf(size)).items()}
                if not any(all(math.dist(pts[p], o[p]) <= TOL * size for p in pts) for o in out):
                    out.append(pts)
        return out, gap


# --- the comparison -------------------------------------------------------------------------------

def _agree(form: str, d: dict) -> tuple[list[int], float]:
    """At each crank angle of scene ``d``: plans' group has form ``form``, its count is the
    enumeration's and each enumerated pose is one of plans' within TOL·size at every point of the
    group's links (one to one); the roots' gaps are clean. The counts and the largest distance
    measured (× size)."""
    angles = d["drive"]["angle"]
    motion = solve_scene(parse_scene(d))
    g = motion.structure.groups[-1]
    assert g.form == form
    size = motion.mechanism.size
    counts, worst = [], 0.0
    for i, angle in enumerate(angles):
        found = group_assemblies(motion, g, i)
        want, gap = precise_assemblies(form, d, angle, size)
        assert gap["kept"] <= mp.mpf(10) ** -30 and gap["rejected"] >= mp.mpf(10) ** -6 and gap["other"] >= mp.mpf(10) ** -6
        assert gap["lead"] >= mp.mpf(10) ** -20 and gap["trimmed"] <= mp.mpf(10) ** -50
        worst = max(worst, matched(found, want, size))
        counts.append(found.count)
    return counts, worst


def _moved(form: str, crank: list[float], points=None, angles=()) -> dict:
    """The form's scene at these crank angles (deg), with sketch points and guide angles changed."""
    d = copy.deepcopy(CASES[form])
    d["drive"]["angle"] = crank
    d["points"].update(points or {})
    for s, a in zip(d["sliders"], angles):
        s["angle"] = a
    return d


@pytest.mark.parametrize("form", sorted(CASES))
def test_every_sliding_form_at_two_crank_angles(form):
    """FORMS and LOCKED at their 45° and at 30°: the counts of the multi-start search's test, the
    same at 30° (measured within 7.4e-16·size)."""
    assert _agree(form, _moved(form, [45.0, 30.0]))[0] == [COUNTS[form]] * 2


#: Forms with more assemblies than FORMS' (a random search over each form's sketch moved ±0.08 m
#: and its guides turned, seed 7, rounded to 0.1 mm, 0.1°), and RRRR-RP's own at 60°: six (within 5e-15·size).
MORE = {"RR-PR-PR": (4, {"B": [0.2773, 0.125], "F": [0.3127, 0.166], "C": [0.2601, -0.0464]}, [163.1, 68.6], 45.0),
        "PR-PR-RP": (4, {"B": [0.2017, 0.0924], "F": [0.4349, 0.1197], "C": [0.2406, -0.0744]}, [133.7, -151.0, -18.3],
                     45.0),
        "RRPR-RR": (4, {"B": [0.2326, 0.0639], "C": [0.2031, -0.0388], "F": [0.3226, 0.1526], "E": [0.384, -0.1165]},
                    [-105.9], 45.0),
        "RR-RR-RP": (6, {"B": [0.1975, 0.1509], "F": [0.4443, 0.1188], "C": [0.2367, -0.0366], "D": [0.5956, -0.1327],
                         "M": [0.2525, 0.4662]}, [-163.2], 45.0),
        "RRRR-RP": (6, {}, [20.0], 60.0)}


@pytest.mark.parametrize("form", sorted(MORE))
def test_forms_with_four_and_six_assemblies(form):
    count, points, angles, crank = MORE[form]
    assert _agree(form, _moved(form, [crank], points, angles))[0] == [count]


def test_a_plate_half_a_turn_from_the_sketch():
    """φ = π, t = ∞: RRRR-RP with dyadic pins (every number exact) and a frame guide at 0°, built so
    that plate 2 turned half a turn about A (B' = 2A − B, C' = 2A − C) with plate 4 moved
    s = −0.25 m closes: D on the bisector of C and C' − s·u, F of B and B' − s·u. The
    enumeration's leading coefficient vanishes (that root is added); four assemblies in all."""
    pts = {"A": [0.0625, 0.0625], "B": [0.25, 0.1875], "C": [0.1875, -0.0625], "D": [0.4375, 0.0625], "F": [0.3125, 0.0]}
    d = _moved("RRRR-RP", [45.0], pts, [0.0])
    assert precise_assemblies("RRRR-RP", d, 45.0, 1.0)[1]["pi"] == 1
    assert _agree("RRRR-RP", d)[0] == [4]


#: Parallelograms (dyadic, exact): plates 2 and 4 of RRPP-RR with B − A = F − E turn together
#: freely; RRRR-PP's plates, with C − D = B − F and plate 2 parallel to its sketch (the crank at
#: its sketch's 45°), slide along a curve keeping both rods' conditions one.
PLATES = {"A": [0.0625, 0.0625], "B": [0.1875, 0.125], "C": [0.1875, -0.0625]}
CONTINUA = {"RRPP-RR": {**PLATES, "E": [0.4375, -0.0625], "F": [0.5625, 0.0]},
            "RRRR-PP": {**PLATES, "F": [0.375, 0.1875], "D": [0.375, 0.0]}}


@pytest.mark.parametrize("form", sorted(CONTINUA))
def test_a_continuum_is_refused(form):
    """The enumeration's polynomial vanishes identically (below 1e-30 of its terms); plans refuses the
    group in one line (before, its root search listed the residual's rounding: 154 and 4287 poses)."""
    d = _moved(form, [45.0], CONTINUA[form])
    motion = solve_scene(parse_scene(d))
    with pytest.raises(Continuum):
        precise_assemblies(form, d, 45.0, motion.mechanism.size)
    with pytest.raises(SceneError, match=r"IV\(2-3-4-5\) .* continuum"):
        group_assemblies(motion, motion.structure.groups[-1], 0)

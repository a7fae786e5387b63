"""Every real assembly of a revolute class III triad and class IV group, against an independent
enumeration at 50 digits (mpmath): the count and every point of the group's links agree with
plans.kinematics.assemblies within 1e-9 of the mechanism's size.

The enumeration is written here from the scene's sketch alone (the group's pins, its rods'
lengths, the crank pin at the drive angle); it shares no code with plans' elimination and
eliminates differently:

* Triad (base link with pins b₁, b₂, b₃, rod k from the known point c_k to b_k, length l_k):
  the unknowns are the position Q of b₁ and the base's turn φ from the sketch. With
  s_k = b_k − b₁ (sketch) and Q' = Q − c₁, the conditions |Q' + R(φ)s_k − (c_k − c₁)|² = l_k²
  minus the first, |Q'|² = l₁², are two equations linear in Q' (k = 2, 3; their coefficients
  of degree 1 in cos φ, sin φ); Cramer gives Δ·Q' = N, and the first condition becomes
  |N|² − l₁²Δ² = 0, a trigonometric polynomial of degree 4. (Plans eliminates the rod angle ψ
  instead, by Cramer on cos ψ, sin ψ.)
* Class IV group (links x, y with the outer pins X, Y, joined by two rods): the conditions
  |X + R(φ)s_k − Y − R(ψ)v_k|² = l_k² (k = 1, 2; s_k, v_k the rods' pins from X, Y in the
  sketch) are, × (1 + u²) with u = tan(ψ/2), quadratics in u; ψ is eliminated by their
  Sylvester resultant (plans: by Cramer on cos ψ, sin ψ).

Both residuals, × (1 + t²)⁴ with t = tan(φ/2), are polynomials of degree ≤ 8 in t, formed at 50
digits from the sketch's doubles (exact in mpmath) and the crank pin at the drive angle (plans'
own, rounded, differs by ~1e-17 m). Why no assembly is missed: mpmath.polyroots (Durand–Kerner,
at 250 digits) returns all 8 complex roots or raises NoConvergence, never a partial list, and
stops only when every root moves less than 1e-50; φ = π (t = ∞) is a root exactly when the
leading coefficient (= the residual at φ = π) vanishes, and is then added. A root is real when
|Im t| ≤ 1e-20·max(1, |t|): a simple real root comes back with |Im t| ~ 1e-50, a double one
(a tangency) about the square root of that; every case below also asserts a clean gap — the
kept roots' |Im t| below 1e-30, the others' above 1e-6 — so the threshold decides nothing. A
real t gives a real pose (Q' = N/Δ; the common root u = −(a₂b₀ − b₂a₀)/(a₂b₁ − b₂a₁) of two real
quadratics, real unless they share both roots, asserted not to happen), checked on every
original condition to 1e-40 of size². Two poses closer than 1e-9·size count as one here; plans
lists as one those closer than its MERGE_RTOL, 1e-8·size (no case has two assemblies that close).

The bound 1e-9·size is the issue's (= plans' SAME_RTOL, its own test of "one assembly"):
plans' poses are doubles polished on the pair equations, so a pose is off by the rounding
(~1e-16·size) times the group's condition — measured at most 1e-15·size for the well-spread
assemblies below — and, where two assemblies are δ apart, by ~1e-16·size²/δ: 6e-11·size at
δ = 1e-6·size (measured below), the bound reached near δ ~ 1e-7·size.
"""

from __future__ import annotations

import math
import tomllib

import mpmath as mp
import pytest
from test_assemblies import FOUR, SIX, _symmetric, _triad
from test_assemblies_prismatic import _poly, _times

import plans
from plans.kinematics.assemblies import group_assemblies
from plans.pipeline import solve_scene
from plans.scene import parse_scene

EXAMPLES = plans.__path__[0] + "/examples"
DPS = 50
REAL = mp.mpf("1e-20")      # |Im t| / max(1, |t|) of a real root
TOL = 1e-9                  # agreement, × size (the issue's bound = plans' SAME_RTOL)


# --- polynomials in t (coefficient lists, lowest degree first; their sum and product are
# test_assemblies_prismatic's _poly and _times) and plane vectors, in mpmath ------------------

def _lift(f):
    """(1 + t²)·(a + b cos φ + c sin φ) for f = (a, b, c): cos φ = (1 − t²)/(1 + t²), sin φ = 2t/(1 + t²)."""
    a, b, c = f
    return [a + b, 2 * c, a - b]


def _at(f, cs, sn):
    return f[0] + f[1] * cs + f[2] * sn


def _val(p, t):
    return mp.fsum(c * t ** k for k, c in enumerate(p))


def _turn(v, cs, sn):
    return (cs * v[0] - sn * v[1], sn * v[0] + cs * v[1])


def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def _angles(poly) -> tuple[list, dict]:
    """Every real root φ (rad) of the polynomial (1 + t²)^4·f(φ) given by its coefficients in
    t = tan(φ/2), φ = π added when the leading one (f(π)) vanishes; and the gap: the largest
    relative |Im t| kept, the smallest rejected, whether φ = π was added."""
    big = max(abs(c) for c in poly)
    out = []
    while abs(poly[-1]) <= mp.mpf(10) ** -40 * big:       # f(π) = 0: t = ∞ is a root
        poly = poly[:-1]
        out.append(mp.pi)
    roots = mp.polyroots(poly, maxsteps=4000, extraprec=4 * mp.mp.prec, asc=True)
    rel = [abs(mp.im(r)) / max(1, abs(r)) for r in roots]
    out += [2 * mp.atan(mp.re(r)) for r, e in zip(roots, rel) if e <= REAL]
    gap = {"kept": max([e for e in rel if e <= REAL], default=mp.mpf(0)),
           "rejected": min([e for e in rel if e > REAL], default=mp.inf), "pi": bool(out) and out[0] == mp.pi}
    return out, gap


# --- the group from the scene's sketch ---------------------------------------------------------

def _known(d: dict, group: set[str], i: int) -> dict[str, tuple]:
    """World points (mp) of the group's outer pins at position i: frame points as sketched, the
    crank pin on its circle at the drive angle (absolute, counter-clockwise from x)."""
    drive = d["drive"]["link"]
    pts = {p: (mp.mpf(x), mp.mpf(y)) for p, (x, y) in d["points"].items()}
    pivot = next(p for p in d["links"][drive] if p in d["links"]["0"])
    angle = d["drive"]["angle"]
    th = mp.radians(mp.mpf(angle[i] if isinstance(angle, list) else angle))
    out = {}
    for p in {p for n in group for p in d["links"][n]}:
        owners = [n for n, ps in d["links"].items() if p in ps]
        if any(n not in group for n in owners):
            if drive in owners:
                r = mp.sqrt(_dot(_sub(pts[p], pts[pivot]), _sub(pts[p], pts[pivot])))
                out[p] = (pts[pivot][0] + r * mp.cos(th), pts[pivot][1] + r * mp.sin(th))
            else:
                out[p] = pts[p]
    return out


def _placed(d, link, a, wa, b, wb) -> dict:
    """Every point of ``link`` (world, mp) with its sketch points a, b at wa, wb."""
    s = {p: (mp.mpf(x), mp.mpf(y)) for p, (x, y) in d["points"].items()}
    sa, sb = s[a], s[b]
    ang = mp.atan2(wb[1] - wa[1], wb[0] - wa[0]) - mp.atan2(sb[1] - sa[1], sb[0] - sa[0])
    cs, sn = mp.cos(ang), mp.sin(ang)
    return {p: tuple(w + r for w, r in zip(wa, _turn(_sub(s[p], sa), cs, sn))) for p in d["links"][link]}


def _shape(d: dict, group: set[str]) -> tuple[dict, dict]:
    """The group's inner pins (point → its two links) and outer pins (point → its link)."""
    inner, outer = {}, {}
    for p in {p for n in group for p in d["links"][n]}:
        owners = [n for n, ps in d["links"].items() if p in ps]
        mine = [n for n in owners if n in group]
        if len(mine) == 2:
            inner[p] = mine
        elif len(owners) > 1:
            outer[p] = mine[0]
    return inner, outer


def _triad_poses(d, group, known, sk, size):
    inner, outer = _shape(d, group)
    base = next(n for n in group if sum(p in inner for p in d["links"][n]) == 3)
    rods = []
    for c, rod in outer.items():
        b = next(p for p in d["links"][rod] if p in inner)
        rods.append((rod, b, c, known[c], mp.sqrt(_dot(_sub(sk[b], sk[c]), _sub(sk[b], sk[c])))))
    rods.sort()
    (_, b1, _, c1, l1), *others = rods
    rows = []
    for _, b, _, c, l in others:
        s, dd = _sub(sk[b], sk[b1]), _sub(c, c1)
        # 2(R s − d)·Q' = l² − l₁² − |s|² − |d|² + 2 d·R s, each side a + b cos φ + c sin φ
        rows.append(((-2 * dd[0], 2 * s[0], -2 * s[1]), (-2 * dd[1], 2 * s[1], 2 * s[0]),
                     (l * l - l1 * l1 - _dot(s, s) - _dot(dd, dd), 2 * _dot(dd, s), 2 * (dd[1] * s[0] - dd[0] * s[1]))))
    (mx, my, r), (nx, ny, q) = [[_lift(f) for f in row] for row in rows]
    det = _poly((1, _times(mx, ny)), (-1, _times(my, nx)))
    qx = _poly((1, _times(r, ny)), (-1, _times(q, my)))
    qy = _poly((1, _times(mx, q)), (-1, _times(nx, r)))
    poly = _poly((1, _times(qx, qx)), (1, _times(qy, qy)), (-l1 * l1, _times(det, det)))
    phis, gap = _angles(poly)
    poses = []
    for phi in phis:
        cs, sn = mp.cos(phi), mp.sin(phi)
        (ax, ay, ar), (bx, by, br) = [[_at(f, cs, sn) for f in row] for row in rows]
        dt = ax * by - ay * bx
        assert abs(dt) > mp.mpf(10) ** -20 * size ** 2      # Cramer applies (never a dependent pair here)
        Q = (c1[0] + (ar * by - br * ay) / dt, c1[1] + (ax * br - bx * ar) / dt)
        pins = {b: tuple(w + v for w, v in zip(Q, _turn(_sub(sk[b], sk[b1]), cs, sn))) for _, b, *_ in rods}
        for _, b, _, c, l in rods:
            e = _sub(pins[b], c)
            assert abs(_dot(e, e) - l * l) <= mp.mpf(10) ** -40 * size ** 2
        pts = _placed(d, base, b1, pins[b1], others[0][1], pins[others[0][1]])
        for rod, b, c, w, _ in rods:
            pts.update(_placed(d, rod, c, w, b, pins[b]))
        poses.append(pts)
    return poses, gap


def _class4_poses(d, group, known, sk, size):
    _, outer = _shape(d, group)
    (X, x), (Y, y) = sorted(outer.items())
    rods = sorted(n for n in group if n not in (x, y))
    w = _sub(known[X], known[Y])
    forms, ends = [], []
    for rod in rods:
        px = next(p for p in d["links"][rod] if p in d["links"][x])
        py = next(p for p in d["links"][rod] if p in d["links"][y])
        ends.append((rod, px, py))
        s, v = _sub(sk[px], sk[X]), _sub(sk[py], sk[Y])
        l2 = _dot(_sub(sk[px], sk[py]), _sub(sk[px], sk[py]))
        gx, gy = (w[0], s[0], -s[1]), (w[1], s[1], s[0])         # g = w + R(φ)s
        E = (_dot(w, w) + _dot(s, s) + _dot(v, v) - l2, 2 * _dot(w, s), 2 * (w[1] * s[0] - w[0] * s[1]))
        P = tuple(a * v[0] + b * v[1] for a, b in zip(gx, gy))   # g·v
        S = tuple(b * v[0] - a * v[1] for a, b in zip(gx, gy))   # g × v
        # E − 2P cos ψ − 2S sin ψ = 0, × (1 + u²): (E + 2P)u² − 4S u + (E − 2P) = 0 (coefficients in φ)
        forms.append((tuple(e + 2 * p for e, p in zip(E, P)), tuple(-4 * c for c in S), tuple(e - 2 * p for e, p in zip(E, P))))
    (a2, a1, a0), (b2, b1, b0) = [[_lift(f) for f in q] for q in forms]
    xx = _poly((1, _times(a2, b0)), (-1, _times(b2, a0)))
    yy = _poly((1, _times(a2, b1)), (-1, _times(b2, a1)))
    zz = _poly((1, _times(a1, b0)), (-1, _times(b1, a0)))
    phis, gap = _angles(_poly((1, _times(xx, xx)), (-1, _times(yy, zz))))
    poses = []
    for phi in phis:
        (p2, p1, p0), (q2, q1, q0) = [[_at(f, mp.cos(phi), mp.sin(phi)) for f in q] for q in forms]
        num, den = p2 * q0 - q2 * p0, p2 * q1 - q2 * p1
        assert abs(den) > mp.mpf(10) ** -20 * size ** 4     # one common root u (never two here)
        psi = 2 * mp.atan(-num / den)
        cx, sx, cy, sy = mp.cos(phi), mp.sin(phi), mp.cos(psi), mp.sin(psi)
        pts = {p: tuple(a + b for a, b in zip(known[X], _turn(_sub(sk[p], sk[X]), cx, sx))) for p in d["links"][x]}
        pts.update({p: tuple(a + b for a, b in zip(known[Y], _turn(_sub(sk[p], sk[Y]), cy, sy))) for p in d["links"][y]})
        for rod, px, py in ends:
            e, f = _sub(pts[px], pts[py]), _sub(sk[px], sk[py])
            assert abs(_dot(e, e) - _dot(f, f)) <= mp.mpf(10) ** -40 * size ** 2
            pts.update(_placed(d, rod, px, pts[px], py, pts[py]))
        poses.append(pts)
    return poses, gap


def precise_assemblies(d: dict, group: set[str], i: int, size: float) -> tuple[list[dict], dict]:
    """Every real assembly of the revolute triad or class IV group ``group`` of scene ``d`` at
    position i: its links' world points (floats, m), poses closer than TOL·size merged; and the
    roots' gap (see :func:`_angles`)."""
    with mp.workdps(DPS):
        sk = {p: (mp.mpf(x), mp.mpf(y)) for p, (x, y) in d["points"].items()}
        known = _known(d, group, i)
        triad = any(sum(p in _shape(d, group)[0] for p in d["links"][n]) == 3 for n in group)
        poses, gap = (_triad_poses if triad else _class4_poses)(d, group, known, sk, mp.mpf(size))
        out = []
        for pose in poses:
            pts = {p: (float(x), float(y)) for p, (x, y) in pose.items()}
            if not any(all(math.dist(pts[p], o[p]) <= TOL * size for p in pts) for o in out):
                out.append(pts)
        return out, gap


# --- the comparison -------------------------------------------------------------------------------

def _agree(d: dict) -> tuple[list[int], float]:
    """At every analysed position of scene ``d`` (one class III or IV group after the crank): plans'
    count is the enumeration's and each enumerated pose is one of plans' within TOL·size at every
    point of the group's links. The counts, and the largest distance measured (× size)."""
    motion = solve_scene(parse_scene(d))
    g = motion.structure.groups[-1]
    size = motion.mechanism.size
    counts, worst = [], 0.0
    for i in range(len(motion)):
        found = group_assemblies(motion, g, i)
        want, gap = precise_assemblies(d, set(g.links), i, size)
        assert gap["kept"] <= mp.mpf(10) ** -30 and gap["rejected"] >= mp.mpf(10) ** -6
        worst = max(worst, matched(found, want, size))
        counts.append(found.count)
    return counts, worst


def matched(found, want: list[dict], size: float) -> float:
    """Plans' assemblies ``found`` against the enumeration's ``want`` (point → (x, y) each): the
    same count, each wanted pose matched by exactly one found within TOL·size at every point; the
    largest distance (÷ size)."""
    assert found.count == len(want)
    worst = 0.0
    for w in want:
        near = [a for a in found.assemblies if set(a.points) == set(w)
                and all(math.dist(w[p], a.points[p]) <= TOL * size for p in w)]
        assert len(near) == 1
        worst = max(worst, max(math.dist(w[p], near[0].points[p]) for p in w) / size)
    return worst


def _toml(name: str) -> dict:
    with open(f"{EXAMPLES}/{name}.toml", "rb") as f:
        return tomllib.load(f)


@pytest.mark.parametrize("name, positions", [("class3_six_link", 4), ("class3_forces", 2), ("koshel_variant1", 8),
                                             ("koshel_variant2", 8), ("triad_at_rest", 4), ("class4_six_link", 4)])
def test_the_bundled_class_iii_and_iv_examples(name, positions):
    """Every revolute class III and IV example at each of its positions (2 assemblies at each;
    measured within 4e-16·size)."""
    counts, _ = _agree(_toml(name))
    assert counts == [2] * positions


@pytest.mark.parametrize("scene, count", [(lambda: _symmetric(), 2), (lambda: _triad(FOUR, 45.0), 4),
                                          (lambda: _triad(SIX, 45.0), 6)])
def test_triads_with_two_four_and_six_assemblies(scene, count):
    """tests/test_assemblies.py's triads (measured within 1e-15·size)."""
    assert _agree(scene())[0] == [count]


def _class4(points: dict) -> dict:
    """class4_six_link.toml with these sketch points, analysed at its sketch (crank at 45°)."""
    d = _toml("class4_six_link")
    d["points"].update(points)
    d["drive"]["angle"] = [45.0]
    d["plans"] = {"draw": ["scheme"]}
    return d


#: Class IV groups with two, four and six real assemblies at 45° (a random search over
#: class4_six_link's B, C, D, F, E moved ±0.12 m, seed 4, rounded to 0.1 mm).
CLASS4 = {2: {"B": [0.1187, 0.0198], "C": [0.1651, -0.1438], "D": [0.308, 0.0734], "F": [0.4433, 0.2171],
              "E": [0.5176, -0.1127]},
          4: {"B": [0.1908, 0.0614], "C": [0.1114, -0.1555], "D": [0.3435, 0.1996], "F": [0.4219, 0.2186],
              "E": [0.5261, -0.1196]},
          6: {"B": [0.2217, 0.2031], "C": [0.2962, -0.0879], "D": [0.4937, 0.1642], "F": [0.367, 0.1245],
              "E": [0.34, -0.0708]}}


@pytest.mark.parametrize("count", sorted(CLASS4))
def test_class_iv_groups_with_two_four_and_six_assemblies(count):
    assert _agree(_class4(CLASS4[count]))[0] == [count]


#: Two groups analysed at their sketch, where a second assembly lies within one cell of plans'
#: first grid (2π/720) of the sketch's own, φ = 0 — on a grid point. Before trig_roots certified
#: that a sign change holds one root, plans missed it: in the triad, f(0) is exactly 0 and the
#: cell ending there was dropped with its inner root (at φ = −0.0011, the poses 0.17·size apart);
#: in the class IV group f(0) rounds to −1e-19 and the cell starting there holds the root at 0
#: and one at φ = 4.4e-4 (0.0002·size apart): Brent's method returned one. (Found by a sweep of
#: 3000 random sketches: 15 such misses, none after the fix.)
GRID_CELL = {"triad": _triad({"O": [0.0, 0.0], "A": [0.035355339, 0.035355339], "B": [0.325, 0.2661],
                              "F": [0.2512, 0.2988], "C": [0.3177, -0.112], "D": [0.5035, -0.0665],
                              "M": [0.3546, 0.297]}, 45.0),
             "class IV": _class4({"B": [0.3126, 0.0199], "C": [0.3103, 0.0232], "D": [0.3977, 0.091],
                                  "F": [0.4269, 0.1246], "E": [0.5232, 0.0631]})}


@pytest.mark.parametrize("case", sorted(GRID_CELL))
def test_two_assemblies_in_one_cell_of_the_grid(case):
    assert _agree(GRID_CELL[case])[0] == [2]


def test_a_base_turned_half_a_turn_from_the_sketch():
    """φ = π, t = ∞: the base's pins b_k (dyadic, so every number below is exact) and their
    images −b_k are both assemblies when each rod's pivot is on the bisector of b_k and −b_k,
    c_k = λ_k·J b_k; the crank OA (0.0625 m) at 0° ends at c₁. Six assemblies, one at φ = π (the
    enumeration's leading coefficient vanishes), another 0.053 rad from it."""
    b = [(0.25, 0.125), (0.125, 0.3125), (-0.0625, -0.1875)]
    c = [(lam * -p[1], lam * p[0]) for p, lam in zip(b, (1.5, 0.5, 1.25))]
    pts = {"O": (c[0][0] - 0.0625, c[0][1]), "A": c[0], "B": b[0], "F": b[1], "C": b[2], "M": c[1], "D": c[2]}
    d = _triad({k: list(v) for k, v in pts.items()}, 0.0)
    assert precise_assemblies(d, {"2", "3", "4", "5"}, 0, 1.0)[1]["pi"]
    assert _agree(d)[0] == [6]


@pytest.mark.parametrize("angle, apart", [(78.49661712381632, 1.00e-6), (78.49661712433831, 2.34e-7)])
def test_two_assemblies_about_to_merge(angle, apart):
    """The four-assembly triad near the crank angle where two of its assemblies merge (about
    78.4966171244°, the motion's own among them): 1.00e-6 and 2.34e-7 of the size apart. Plans
    finds all four, within 1e-9·size (a near-double root costs accuracy: the poses' rounding is
    divided by the separation, 3e-10·size at the closer one). Before MERGE_RTOL, at 2.34e-7 the
    search's two copies of one root, polished, were 4.3e-9·size apart (above SAME_RTOL), and it
    listed 5; closer still the motion itself refuses the position (a singular one on the walk)."""
    d = _triad(FOUR, 45.0)
    d["drive"]["angle"] = [angle]
    size = solve_scene(parse_scene(d)).mechanism.size
    want, _ = precise_assemblies(d, {"2", "3", "4", "5"}, 0, size)
    gap = min(max(math.dist(a[p], b[p]) for p in a) for k, a in enumerate(want) for b in want[k + 1:])
    assert gap / size == pytest.approx(apart, rel=1e-2)
    assert _agree(d)[0] == [4]

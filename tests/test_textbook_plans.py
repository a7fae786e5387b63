"""Plans as the textbook draws them (§2.2–2.3, Fig. 1.14/1.15).

- the total relative acceleration a→b (``a:B/A``) beside its components a→n_BA→b;
- closed similar figures: every side of a link with three or more points is a vector;
- class IV plans: each quantity once, no segment as two opposite vectors, nothing but the
  absolute vectors touches the pole, construction lines and n/τ components;
- class III plans: one special-point route, fewer vectors than the two routes drawn before;
- labels: a component's end is never printed with the letter of a point's image.

Values are compared with the independent reference solver (``tests/reference.py``), not
with the package's own kinematics.
"""

from __future__ import annotations

import math
import re
import tomllib
import xml.etree.ElementTree as ET
from collections import Counter

import numpy as np
import pytest
from shapely.geometry import LineString, Point

from conftest import EXAMPLES, toml_text
from reference import Reference
from plans.checking import check_plan, inspect_svg
from plans.constructions import acceleration_plan, velocity_plan
from plans.constructions.plans import PRIME
from plans.kinematics import analyse, special
from plans.model import build_mechanism
from plans.cli import main
from plans.pipeline.sheets.plans import similarity_failures as _similarity
from plans.scene import FRAME, parse_scene
from plans.structure import ComplexGroup, analyse_structure

BY_NAME = {p.stem: p for p in EXAMPLES}
CLASS_III = ["class3_six_link", "koshel_variant1", "koshel_variant2", "triad_at_rest", "triad_sliding_rod"]
#: Vectors of each class III example's acceleration plan, at every position, when both
#: special-point routes were drawn (26 component vectors; 24 for the sliding rod).
TWO_ROUTES_A = {"class3_six_link": 30, "koshel_variant1": 30, "koshel_variant2": 30, "triad_sliding_rod": 28}
MM = 1e-9          # mm: coincident images


class Case:
    """An example solved at its positions, with both plans at each and the reference states."""

    def __init__(self, stem: str):
        data = tomllib.loads(BY_NAME[stem].read_text(encoding="utf-8"))
        self.data = data
        self.mech = build_mechanism(parse_scene(data))
        self.motion = analyse(self.mech, analyse_structure(self.mech))
        self.ref = Reference(self.mech).solve(self.motion.values)
        m = self.motion
        v_max = max(float(np.max(np.linalg.norm(m.velocity(p), axis=1))) for p in self.mech.sketch)
        a_max = max(float(np.max(np.linalg.norm(m.acceleration(p), axis=1))) for p in self.mech.sketch)
        self.mu = {"v": v_max / 100.0 or 1.0, "a": a_max / 100.0 or 1.0}
        self.plans = [(i, velocity_plan(m, i, self.mu["v"]), acceleration_plan(m, i, self.mu["a"]))
                      for i in range(len(m))]

    def point_of(self, label: str) -> tuple[str, str | None] | None:
        """(point, link) of a plan label ``B`` or ``B3``; None for a special point (S1)."""
        if label in self.mech.sketch:
            return label, None
        for p in sorted(self.mech.sketch, key=len, reverse=True):
            if label.startswith(p) and label[len(p):] in self.mech.links:
                return p, label[len(p):]
        return None

    def exact(self, kind: str, i: int, label: str) -> np.ndarray | None:
        """v or a of the point a label names, from the reference solver (None: special point)."""
        pl = self.point_of(label)
        if pl is None:
            return None
        state = self.ref[i]
        point, link = pl
        if link is None or point in self.mech.links[link].local:
            return state.velocity(point, link) if kind == "v" else state.acceleration(point, link)
        # the point of ``link`` now at ``point`` (it carries another point P): rigid-body field
        p = next(iter(self.mech.links[link].local))
        r = state.position(point) - state.position(p, link)
        jr = np.array([-r[1], r[0]])
        w = state.omega(link)
        if kind == "v":
            return state.velocity(p, link) + w * jr
        return state.acceleration(p, link) + state.epsilon(link) * jr - w * w * r


_CASES: dict[str, Case] = {}


def case(stem: str) -> Case:
    if stem not in _CASES:
        _CASES[stem] = Case(stem)
    return _CASES[stem]


def at_pole(xy) -> bool:
    return math.hypot(*xy) <= MM


def same(p, q) -> bool:
    return math.dist(p, q) <= MM


def vectors(plan) -> dict:
    return {v.quantity: v for v in plan.vectors}


def printed(label: str) -> str:
    """The letter(s) a label is printed with, before its subscript."""
    return label.partition("_")[0]


STEMS = sorted(BY_NAME)


# --- no quantity twice, no segment both ways, nothing into the pole ------------------------------

@pytest.mark.parametrize("stem", STEMS)
def test_no_quantity_is_drawn_twice_and_no_segment_both_ways(stem):
    c = case(stem)
    for i, vp, ap in c.plans:
        for plan in (vp, ap):
            counts = Counter(v.quantity for v in plan.vectors)
            assert [q for q, n in counts.items() if n > 1] == [], (stem, i, plan.kind)
            for u in plan.vectors:
                for w in plan.vectors:
                    assert not (same(u.tail, w.head) and same(u.head, w.tail)), (stem, i, u.quantity, w.quantity)


@pytest.mark.parametrize("stem", STEMS)
def test_no_vector_ends_at_the_pole_but_at_a_point_momentarily_at_rest(stem):
    """Absolute vectors start at the pole; no vector ends there, unless the point it ends at
    is a moving point whose velocity (acceleration) is zero at that position — never a
    fixed point."""
    c = case(stem)
    fixed = set(c.mech.links[FRAME].points)
    for i, vp, ap in c.plans:
        for plan, sym in ((vp, "v"), (ap, "a")):
            for v in plan.vectors:
                if not at_pole(v.head) or at_pole(v.tail):
                    continue
                assert v.kind not in ("normal", "coriolis"), (stem, i, v.quantity)
                x = re.match(r"^[va]:([^/:]+)", v.quantity)[1]
                point = c.point_of(x)
                assert point is not None and point[0] not in fixed, (stem, i, v.quantity)
                assert np.linalg.norm(c.exact(sym, i, x)) <= 1e-9 * c.mu[sym] * 100, (stem, i, v.quantity)


# --- a→b: the total relative acceleration of every rigid relation ---------------------------------

@pytest.mark.parametrize("stem", STEMS)
def test_every_rigid_relation_has_its_total_relative_acceleration(stem):
    """Beside a:X/Y:n and a:X/Y:t the plan draws a:X/Y from y to x, equal to a_X − a_Y of the
    reference solver (vector and value); where y is at the pole the segment is a:X itself, and
    a special point S is no point of the link's figure."""
    c = case(stem)
    checked = 0
    for i, _, ap in c.plans:
        vs = vectors(ap)
        for q, t in vs.items():
            if not q.endswith(":t"):
                continue
            rel = q[:-2]
            x, y = rel[2:].split("/")
            if c.point_of(y) is None or c.point_of(x) is None:      # relative to a special point
                assert rel not in vs
                continue
            n = vs.get(rel + ":n")
            tail = n.tail if n is not None else t.tail      # no n: ω = 0, n is at y
            want = (c.exact("a", i, x) - c.exact("a", i, y)) / c.mu["a"]
            if at_pole(tail) and f"a:{x}" in vs:          # the segment y → x is a:X itself
                assert rel not in vs and same(vs[f"a:{x}"].head, t.head)
                continue
            if n is None:                                  # ω = 0: the tangential one is the whole
                assert rel not in vs
                assert np.allclose(np.subtract(t.head, t.tail), want, rtol=0, atol=1e-9 * max(1.0, np.linalg.norm(want)))
                continue
            total = vs[rel]
            assert same(total.tail, tail)
            assert total.kind == "relative" and same(total.head, t.head)
            assert np.allclose(np.subtract(total.head, total.tail), want, rtol=0, atol=1e-9 * max(1.0, np.linalg.norm(want)))
            assert total.value == pytest.approx(float(np.linalg.norm(want)) * c.mu["a"], rel=1e-9, abs=1e-12)
            checked += 1
    if stem in ("four_bar", "class4_six_link", "class3_six_link", "crank_slider_offset"):
        assert checked > 0


def test_four_bar_draws_a_to_b_and_closes_abm():
    """The four-bar's coupler ABM on the acceleration plan: a→b, a→m and b→m, each equal to the
    reference difference, and the triangle closes (a→b + b→m = a→m)."""
    c = case("four_bar")
    for i, vp, ap in c.plans:
        for plan, sym in ((vp, "v"), (ap, "a")):
            vs = vectors(plan)
            for q, (x, y) in {f"{sym}:B/A": ("B", "A"), f"{sym}:M/A": ("M", "A"), f"{sym}:M/B": ("M", "B")}.items():
                want = (c.exact(sym, i, x) - c.exact(sym, i, y)) / c.mu[sym]
                got = np.subtract(vs[q].head, vs[q].tail)
                assert np.allclose(got, want, rtol=0, atol=1e-9 * np.linalg.norm(want)), (i, q)
            ab, bm, am = (np.subtract(vs[q].head, vs[q].tail) for q in (f"{sym}:B/A", f"{sym}:M/B", f"{sym}:M/A"))
            assert np.allclose(ab + bm, am, rtol=0, atol=1e-9 * np.linalg.norm(am))


# --- closed similar figures ---------------------------------------------------------------------

@pytest.mark.parametrize("stem", STEMS)
def test_every_similar_figure_is_a_closed_polygon_of_vectors(stem):
    """For every link with three or more points, on both plans: each side of the polygon of its
    images (in the link's order) is a drawn vector (either way; a side from the pole is the
    absolute vector), each exact against the reference solver, and the oriented sides sum to
    zero."""
    c = case(stem)
    for i, vp, ap in c.plans:
        for plan, sym in ((vp, "v"), (ap, "a")):
            for link, labels in plan.similar:
                pts = c.mech.links[link].points
                images = [plan.point(lab) for lab in labels]
                total = np.zeros(2)
                for k in range(len(pts)):
                    p, q = images[k], images[(k + 1) % len(pts)]
                    if same(p, q):
                        continue
                    hits = [v for v in plan.vectors if (same(v.tail, p) and same(v.head, q))
                            or (same(v.tail, q) and same(v.head, p))]
                    # (a relative or absolute vector; a component where the other one is zero)
                    assert hits, (stem, i, sym, link, pts[k], pts[(k + 1) % len(pts)])
                    v = hits[0]
                    side = np.subtract(v.head, v.tail) * (1.0 if same(v.tail, p) else -1.0)
                    want = (c.exact(sym, i, pts[(k + 1) % len(pts)]) - c.exact(sym, i, pts[k])) / plan.mu
                    assert np.allclose(side, want, rtol=0, atol=1e-9 * max(1.0, np.linalg.norm(want)))
                    assert v.value == pytest.approx(np.linalg.norm(want) * plan.mu, rel=1e-9, abs=1e-12)
                    total += side
                assert np.linalg.norm(total) <= 1e-9 * max(1.0, max(math.hypot(*xy) for xy in images))


# --- class IV -------------------------------------------------------------------------------------

def test_class_iv_plans_are_drawn_like_class_ii():
    """Class IV (Fig. 1.10): no vector touches the pole but the absolute ones (which start
    there), every relation has its construction line, each image found by two lines has them
    meeting at it, and the acceleration plan has n and τ components with the reference's ω²·l,
    |ε|·l for every relation."""
    c = case("class4_six_link")
    (g,) = c.motion.structure.groups
    assert isinstance(g, ComplexGroup) and g.klass == 4
    for i, vp, ap in c.plans:
        for plan in (vp, ap):
            assert check_plan(plan) == []
            for v in plan.vectors:
                if v.kind != "absolute":
                    assert not at_pole(v.head), (i, v.quantity)
            groups: dict[str, list] = {}
            for line in plan.lines:
                groups.setdefault(line.group, []).append(line)
            assert set(groups) == {f"{g.name}:{x}" for x in "BCDF"}
            for x in "BC":             # b and c: from a (the crank's pin) and from f, d
                a, b = (LineString([l.start, l.end]) for l in groups[f"{g.name}:{x}"])
                meet = a.intersection(b)
                assert meet.geom_type == "Point" and meet.distance(Point(plan.point(x.lower()))) < 1e-6
            vs = vectors(plan)
            for line in plan.lines:   # every construction line carries its vector
                assert line.quantity in vs
        vs = vectors(ap)
        rels = [q[:-2] for q in vs if q.endswith(":t")]
        assert sorted(rels) == ["a:B/A", "a:B/F", "a:C/A", "a:C/D", "a:D/E", "a:F/E"]
        state = c.ref[i]
        for rel in rels:
            x, y = rel[2:].split("/")
            link = next(l for l in g.links if {x, y} <= set(c.mech.links[l].points))
            length = float(np.linalg.norm(state.position(x) - state.position(y)))
            assert vs[rel + ":n"].value == pytest.approx(state.omega(link) ** 2 * length, rel=1e-9)
            assert vs[rel + ":t"].value == pytest.approx(abs(state.epsilon(link)) * length, rel=1e-9)
            assert vs[rel + ":n"].length * ap.mu == pytest.approx(vs[rel + ":n"].value, rel=1e-9, abs=1e-12)
            assert vs[rel + ":t"].length * ap.mu == pytest.approx(vs[rel + ":t"].value, rel=1e-9, abs=1e-12)


# --- class III: one route -------------------------------------------------------------------------

@pytest.mark.parametrize("stem", CLASS_III)
def test_class_iii_plans_draw_one_special_point_route(stem):
    """One special point per plan; every base pin found by exactly two lines meeting at its
    image; fewer acceleration vectors than with both routes; the images of S and of the pins
    are the reference's velocities and accelerations."""
    c = case(stem)
    (g,) = [g for g in c.motion.structure.groups if isinstance(g, ComplexGroup)]
    pins = [p.point for p in g.inner if p.kind == "R"]
    for i, vp, ap in c.plans:
        for plan in (vp, ap):
            assert check_plan(plan) == []
            groups: dict[str, list] = {}
            for line in plan.lines:
                groups.setdefault(line.group, []).append(line)
            specials = [k for k in groups if re.fullmatch(rf"{re.escape(g.name)}:S[123]′*", k)]
            assert len(specials) == 1, (i, plan.kind, list(groups))
            for pin in pins:
                lines = groups[f"{g.name}:{pin}"]
                assert len(lines) == 2
                a, b = (LineString([l.start, l.end]) for l in lines)
                meet = a.intersection(b)
                assert meet.geom_type == "Point" and meet.distance(Point(plan.point(pin.lower()))) < 1e-6
        if stem in TWO_ROUTES_A:
            assert len(ap.vectors) < TWO_ROUTES_A[stem] and len(ap.vectors) <= 24
        # the special point's image, from the reference: v_S = v_P + ω × (S − P) and
        # a_S = a_P + ε × (S − P) − ω²(S − P), S where the two rods' axes meet (geometry)
        state = c.ref[i]
        where = {p.name: p.position[0] for p in special.special_points(
            g, c.mech, {k: s.take(np.array([i])) for k, s in c.motion.links.items()})}
        (s_name,) = {v.quantity[2:].split("/")[0] for v in vp.vectors + ap.vectors
                     if re.match(r"^[va]:S[123]/", v.quantity)}
        pin = pins[0]
        r = where[s_name] - state.position(pin, g.base)
        jr = np.array([-r[1], r[0]])
        w, e = state.omega(g.base), state.epsilon(g.base)
        want_v = (state.velocity(pin, g.base) + w * jr) / vp.mu
        want_a = (state.acceleration(pin, g.base) + e * jr - w * w * r) / ap.mu
        assert np.allclose(vp.point(s_name.lower()), want_v, rtol=0, atol=1e-9 * max(1.0, np.linalg.norm(want_v)))
        assert np.allclose(ap.point(s_name.lower()), want_a, rtol=0, atol=1e-9 * max(1.0, np.linalg.norm(want_a)))
        # and the pin images from the special route are the reference velocities
        for pin in pins:
            want = state.velocity(pin, g.base) / vp.mu
            assert np.allclose(vp.point(pin.lower()), want, rtol=0, atol=1e-9 * max(1.0, np.linalg.norm(want)))
            want = state.acceleration(pin, g.base) / ap.mu
            assert np.allclose(ap.point(pin.lower()), want, rtol=0, atol=1e-9 * max(1.0, np.linalg.norm(want)))


def test_class_iii_vector_counts_before_and_after():
    """The counts the report quotes: class3_six_link 30 → 24 acceleration vectors at every
    position (velocity 15–17 → 11–13)."""
    c = case("class3_six_link")
    assert [len(ap.vectors) for _, _, ap in c.plans] == [24] * len(c.plans)
    assert all(len(vp.vectors) <= 13 for _, vp, _ in c.plans)


# --- labels ---------------------------------------------------------------------------------------

def component_ends(plan) -> dict[str, str]:
    """Label of each component's end (normal, Coriolis) by the quantity of its vector."""
    out = {}
    for v in plan.vectors:
        if v.kind not in ("normal", "coriolis"):
            continue
        x, y = v.quantity[2:].rsplit(":", 1)[0].split("/")
        letter = "n" if v.kind == "normal" else "k"
        pattern = re.compile(rf"^{letter}{PRIME}*_{re.escape(x + y)}{PRIME}*$")
        labels = [p.label for p in plan.points if same(p.xy, v.head) and pattern.match(p.label)]
        assert len(labels) == 1, (v.quantity, [p.label for p in plan.points if same(p.xy, v.head)])
        out[v.quantity] = labels[0]
    return out


@pytest.mark.parametrize("stem", STEMS)
def test_a_component_end_is_never_printed_like_an_image(stem):
    c = case(stem)
    end = re.compile(rf"^[nk]{PRIME}*_")          # no example names a point n_… or k_…
    for i, vp, ap in c.plans:
        ends = set(component_ends(ap).values())
        assert all(end.match(lab) for lab in ends)
        ends |= {p.label for p in ap.points if end.match(p.label)}     # also the ends of vectors too short to draw
        images = {printed(p.label) for p in ap.points if p.label not in ends}
        assert not images & {printed(lab) for lab in ends}, (stem, i)
        assert len({p.label for p in ap.points}) == len(ap.points)


def test_tangent_mechanism_k_is_the_image_of_k_and_the_coriolis_end_is_primed():
    c = case("tangent_mechanism")
    for i, _, ap in c.plans:
        assert ap.point("k") == pytest.approx(tuple(c.exact("a", i, "K") / ap.mu), abs=1e-9)
        ends = component_ends(ap)
        assert ends == {"a:B2/B1:cor": f"k{PRIME}_B2B1"}


def test_normal_ends_keep_n_unless_a_point_is_printed_n():
    four = component_ends(case("four_bar").plans[0][2])
    assert four == {"a:B/A:n": "n_BA", "a:B/C:n": "n_BC"}
    koshel = component_ends(case("koshel_variant1").plans[0][2])          # points K and N
    assert koshel and all(printed(lab) == f"n{PRIME}" for lab in koshel.values())


# --- the drawings still measure -----------------------------------------------------------------

@pytest.mark.parametrize("stem", ["four_bar", "class4_six_link", "class3_six_link", "tangent_mechanism",
                                  "triad_sliding_rod", "koshel_variant2"])
def test_sheets_pass_plans_check(tmp_path, capsys, stem):
    """Each plan passes the render's own checks (check_plan, similarity), and `plans render`
    then `plans check` pass on its sheets: lengths, directions and every closure equation,
    with the new vectors."""
    c = case(stem)
    for i, vp, ap in c.plans:
        for plan in (vp, ap):
            assert check_plan(plan) == [] and _similarity(c.motion, plan, i) == []
    data = dict(c.data)
    data["plans"] = {"draw": ["velocity", "acceleration"]}
    scene = tmp_path / f"{stem}.toml"
    scene.write_text(toml_text(data), encoding="utf-8")
    out = tmp_path / "out"
    assert main(["render", str(scene), "-o", str(out), "-q"]) == 0
    sheets = sorted(out.glob(f"{stem}-velocity*.svg")) + sorted(out.glob(f"{stem}-acceleration*.svg"))
    assert len(sheets) == 2 * len(c.plans)
    capsys.readouterr()
    assert main(["check", *map(str, sheets)]) == 0
    for path in sheets:
        report = inspect_svg(path)
        assert report.ok and report.kind == "plan", (path.name, report.problems)
        quantities = [m.quantity for m in report.measurements]
        for g in ET.parse(path).getroot().iter("{http://www.w3.org/2000/svg}g"):
            if g.get("data-mu") is not None:     # no quantity twice in one plan (its detail may repeat some)
                drawn = [l.get("data-quantity") for l in g.iter() if l.get("data-quantity")]
                assert len(drawn) == len(set(drawn)), (path.name, g.get("id"))
        if "acceleration" in path.name and stem != "tangent_mechanism":
            assert any(re.fullmatch(r"a:[^/:]+/[^/:]+", q) for q in quantities)

"""Every real assembly of a class III or IV group with a sliding pair
(plans.kinematics.assemblies_prismatic): against an independent enumeration held here, the
poses close, the motion's pose is the chosen one, the sheet draws the sliders, and the count of
assemblies changes over a cycle where two of them merge (a branch point).

The independent enumeration of an RR-RR-PR triad (the example triad_sliding_rod's form) eliminates
the other unknown than the code: the block's travel s along its guide (the code eliminates the base
link's position C and never sees s). Each rod's condition |C0 + s·u + R(φ)p − P|² = l² is a
quadratic in s; × (1 + t²), t = tan(φ/2), its coefficients are polynomials in t; the Sylvester
resultant of the two quadratics in s is a polynomial of degree ≤ 8 in t, whose roots mpmath finds
at 60 digits (polyroots); each real root is completed by the common root s and polished by
mpmath's findroot on the two conditions. The other forms are compared with a multi-start least
squares on the pair equations (tests/test_assemblies.py)."""

from __future__ import annotations

import copy
import json
import math
import re
import tomllib
import xml.etree.ElementTree as ET

import mpmath as mp
import numpy as np
import pytest

import plans
from plans.checking import inspect_svg
from plans.errors import SceneError
from plans.kinematics.assemblies import SAME_RTOL, assemblies, group_assemblies
from plans.layout import measure_layout
from plans.pipeline import solve_scene
from plans.scene import parse_scene

from test_assemblies import _agree, _check_group

SVG = "{http://www.w3.org/2000/svg}"
EXAMPLES = plans.__path__[0] + "/examples"
GROUP = "III(2-3-4-5)"


def _toml(name: str) -> dict:
    with open(f"{EXAMPLES}/{name}.toml", "rb") as f:
        return tomllib.load(f)


SLIDING = _toml("triad_sliding_rod")
#: RR-RR-PR triads with four and six real assemblies at 45° (found by a random search over
#: triad_sliding_rod's sketch moved ±0.15 m and its guide turned, seed 4, rounded to 0.1 mm, 0.1°).
SLIDING_FOUR = ({"B": [0.2762, 0.2837], "F": [0.3851, 0.1581], "C": [0.3677, 0.0882], "M": [0.2299, 0.5307]}, 167.2)
SLIDING_SIX = ({"B": [0.3375, 0.2603], "F": [0.5248, 0.0544], "C": [0.352, -0.0042], "M": [0.275, 0.3234]}, 155.0)


def _sliding(points: dict | None = None, angle: float | None = None, drive=None, draw=("scheme",)) -> dict:
    d = copy.deepcopy(SLIDING)
    d["points"].update(points or {})
    if angle is not None:
        d["sliders"][0]["angle"] = angle
    if drive is not None:
        d["drive"].update(drive)
    d["plans"] = {"draw": list(draw)}
    return d


# --- the independent enumeration ---------------------------------------------------------------

def _poly(*terms):
    """Σ c·p for (c, p) in terms: polynomials as coefficient lists, lowest degree first."""
    n = max(len(p) for _, p in terms)
    return [mp.fsum(c * (p[k] if k < len(p) else 0) for c, p in terms) for k in range(n)]


def _times(p, q):
    out = [mp.mpf(0)] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        for j, b in enumerate(q):
            out[i + j] += a * b
    return out


def resultant_assemblies(d: dict, a_now) -> list[dict[str, tuple[float, float]]]:
    """Every assembly (points B, F, C, m) of the RR-RR-PR triad of scene ``d`` with the crank pin
    at ``a_now``: rod 2 from A to B, rod 5 from M to F, C on the frame guide through the sketch's C."""
    with mp.workdps(60):
        P = {k: [mp.mpf(v[0]), mp.mpf(v[1])] for k, v in d["points"].items()}
        a_now = [mp.mpf(float(a_now[0])), mp.mpf(float(a_now[1]))]
        ang = mp.radians(mp.mpf(d["sliders"][0]["angle"]))
        u = [mp.cos(ang), mp.sin(ang)]
        dot = lambda x, y: x[0] * y[0] + x[1] * y[1]
        sub = lambda x, y: [x[0] - y[0], x[1] - y[1]]
        C0 = P["C"]
        rods = ((P["B"], a_now, P["A"]), (P["F"], P["M"], P["M"]))
        one, even, two_t = [1, 0, 1], [1, 0, -1], [0, 2]        # 1 + t², 1 − t², 2t
        quads = []
        for pin, pivot, pivot0 in rods:
            p, w = sub(pin, C0), sub(C0, pivot)
            jp = [-p[1], p[0]]
            l2 = dot(sub(pin, pivot0), sub(pin, pivot0))
            # (1 + t²)·(s² + 2s u·(w + R p) + |w|² + |p|² − l² + 2 w·R p), R p = ((1 − t²)p + 2t Jp)/(1 + t²)
            quads.append((_poly((1, one)),
                          _poly((2 * dot(u, w), one), (2 * dot(u, p), even), (2 * dot(u, jp), two_t)),
                          _poly((dot(w, w) + dot(p, p) - l2, one), (2 * dot(w, p), even), (2 * dot(w, jp), two_t))))
        (a2, a1, a0), (b2, b1, b0) = quads
        x = _poly((1, _times(a2, b0)), (-1, _times(b2, a0)))
        y = _poly((1, _times(a2, b1)), (-1, _times(b2, a1)))
        z = _poly((1, _times(a1, b0)), (-1, _times(b1, a0)))
        res = _poly((1, _times(x, x)), (-1, _times(y, z)))      # Sylvester: (a2b0 − b2a0)² − (a2b1 − b2a1)(a1b0 − b1a0)
        assert abs(res[-1]) > mp.mpf(10) ** -20 * max(abs(c) for c in res)     # no root at t = ∞ (φ = π)
        out = []
        for r in mp.polyroots(res, maxsteps=400, extraprec=300, asc=True):
            if abs(mp.im(r)) > mp.mpf(10) ** -25:
                continue
            t = mp.re(r)
            at = lambda q: mp.fsum(c * t ** k for k, c in enumerate(q))
            s0 = -at(x) / at(y)

            def points(s, phi):
                c, sn = mp.cos(phi), mp.sin(phi)
                C = [C0[0] + s * u[0], C0[1] + s * u[1]]
                out = {"C": C}
                for name in ("B", "F"):
                    p = sub(P[name], C0)
                    out[name] = [C[0] + c * p[0] - sn * p[1], C[1] + sn * p[0] + c * p[1]]
                return out

            def conditions(s, phi):
                q = points(s, phi)
                return [dot(sub(q[pin], piv), sub(q[pin], piv)) - dot(sub(P[pin], piv0), sub(P[pin], piv0))
                        for pin, piv, piv0 in (("B", a_now, P["A"]), ("F", P["M"], P["M"]))]
            s, phi = mp.findroot(conditions, (s0, 2 * mp.atan(t)))
            assert max(abs(v) for v in conditions(s, phi)) < mp.mpf(10) ** -40
            out.append({k: (float(v[0]), float(v[1])) for k, v in points(s, phi).items()})
        return out


def _agrees_with_resultant(d: dict) -> list[int]:
    """Every analysed position of scene ``d``: the code's assemblies are the resultant's, point by
    point within 1e-9 of the size, every one closes (tests/test_assemblies.py's checks); the counts."""
    motion = solve_scene(parse_scene(d))
    g = motion.structure.groups[0]
    size = motion.mechanism.size
    counts = []
    for i in range(len(motion)):
        found = _check_group(motion, g, i)
        want = resultant_assemblies(d, motion.position("A")[i])
        assert found.count == len(want)
        for w in want:
            assert sum(all(math.dist(w[k], a.points[k]) <= 1e-9 * size for k in w) for a in found.assemblies) == 1
        counts.append(found.count)
    return counts


def test_the_sliding_rod_example_agrees_with_the_resultant():
    assert _agrees_with_resultant(_sliding()) == [2, 2, 2, 2]


@pytest.mark.parametrize("layout, count", [(SLIDING_FOUR, 4), (SLIDING_SIX, 6)])
def test_sliding_triads_with_four_and_six_assemblies(layout, count):
    points, angle = layout
    assert _agrees_with_resultant(_sliding(points, angle, {"angle": [45.0]})) == [count]


# --- other forms, against the multi-start least squares ----------------------------------------

def _group(example: str, links: dict, sliders: list, drop=()) -> dict:
    """``example``'s scene with ``links`` changed, the points ``drop`` removed and ``sliders``, at 45°."""
    d = _toml(example)
    d["links"].update(links)
    for p in drop:
        d["points"].pop(p)
    d["sliders"] = sliders
    d["drive"]["angle"] = [45.0]
    d["plans"] = {"draw": ["scheme"]}
    return d


def _class3(links: dict, sliders: list, drop=()) -> dict:
    return _group("class3_six_link", links, sliders, drop)


def _class4(links: dict, sliders: list, drop=()) -> dict:
    return _group("class4_six_link", links, sliders, drop)


def _slide(link, on, through, angle):
    return {"link": link, "on": on, "through": through, "angle": angle}


#: Class III and IV groups with sliding pairs of every kind the eliminations treat differently: a rod
#: pinned to the frame sliding in a slot of the base link (RP), two blocks on frame guides (two
#: lines and a circle), a rod sliding on both its pairs (the base angle fixed), three lines (no
#: circle), a class IV rod sliding on a plate, a class IV link sliding on the frame (its travel
#: through tan(φ/2)), and both of a class IV group's outer pairs sliding. Counts from the brute force.
FORMS = {
    "RR-RR-RP": (_class3({"4": ["D"]}, [_slide("4", "3", "D", 35.0)]), 4),
    "RR-PR-PR": (_class3({"0": ["O"], "4": ["C"], "5": ["F"]}, [_slide("4", "0", "C", 70.0), _slide("5", "0", "F", 10.0)],
                         ("D", "M")), 2),
    "RR-RR-PP": (_class3({"0": ["O", "M"], "4": ["C"], "3": ["B", "F"]},
                         [_slide("4", "0", "C", 70.0), _slide("3", "4", "C", -20.0)], ("D",)), 2),
    "PR-PR-RP": (_class3({"0": ["O"], "2": ["A"], "4": ["C"], "5": ["F"]},
                         [_slide("4", "0", "C", 70.0), _slide("5", "0", "F", 10.0), _slide("2", "3", "A", 100.0)],
                         ("D", "M")), 2),
    "RRPR-RR": (_class4({"3": ["C"], "4": ["E", "F"]}, [_slide("3", "4", "C", 35.0)], ("D",)), 2),
    "RRRR-RP": (_class4({"4": ["D", "F"], "0": ["O"]}, [_slide("4", "0", "D", 20.0)], ("E",)), 4),
    "RRRR-PP": (_class4({"4": ["D", "F"], "0": ["O"], "2": ["B", "C"]},
                        [_slide("4", "0", "D", 20.0), _slide("2", "1", "A", 80.0)], ("E",)), 2),
}


@pytest.mark.parametrize("form", sorted(FORMS))
def test_every_form_agrees_with_brute_force(form):
    d, count = FORMS[form]
    motion = solve_scene(parse_scene(d))
    g = motion.structure.groups[-1]
    assert g.form == form
    assert _agree(motion, g, 0, starts=120) == count


#: A class IV group whose rod 3 slides on both plates (C on plate 4 at 35°, on plate 2 at 100°):
#: plates 2 and 4 then turn together, and rod 5 alone decides where.
LOCKED = _class4({"3": ["C"], "2": ["A", "B"], "4": ["E", "F"]},
                 [_slide("3", "4", "C", 35.0), _slide("3", "2", "C", 100.0)], ("D",))


def test_a_class_iv_rod_sliding_on_both_pairs_agrees_with_brute_force():
    """Plates 2 and 4 pinned at A and E turn together (θ2 = θ4 = t): |B(t) − F(t)| = |BF| is
    |c + R(t)·w|² = l², a trigonometric polynomial of degree 1 (two roots at most, here both real);
    the multi-start search finds the same two, and at each the plates' angles are equal."""
    motion = solve_scene(parse_scene(LOCKED))
    g = motion.structure.groups[-1]
    assert g.form == "RRPP-RR"
    assert _agree(motion, g, 0, starts=120) == 2
    for a in group_assemblies(motion, g, 0).assemblies:
        assert math.isclose(a.poses["2"][2], a.poses["4"][2], abs_tol=1e-12) and a.poses["3"][2] == a.poses["2"][2]


def test_a_class_iv_rod_sliding_on_both_pairs_in_closed_form():
    """The two roots from the closed form: with A, E the pins and b = B − A, f = F − E in the
    sketch, v = A − E and w = b − f: |v + R(t)w|² = l² gives cos(t + ∠w − ∠v) = (l² − |v|² −
    |w|²)/(2|v||w|); both roots' plate angles equal the code's within 1e-12 rad."""
    motion = solve_scene(parse_scene(LOCKED))
    g = motion.structure.groups[-1]
    pts = LOCKED["points"]
    world_a = motion.position("A")[0]
    e, b, f = (np.array(pts[k], float) for k in ("E", "B", "F"))
    va, w = world_a - e, (b - np.array(pts["A"], float)) - (f - e)
    l2 = float(np.sum((b - f) ** 2))
    c = (l2 - va @ va - w @ w) / (2.0 * math.hypot(*va) * math.hypot(*w))
    tau = math.atan2(va[1], va[0]) - math.atan2(w[1], w[0])
    want = [tau + s * math.acos(c) for s in (1.0, -1.0)]
    got = [a.poses["2"][2] for a in group_assemblies(motion, g, 0).assemblies]
    assert len(got) == 2
    for t in want:       # each root is one assembly's angle, modulo a turn
        assert sum(abs(math.remainder(t - x, 2 * math.pi)) <= 1e-12 for x in got) == 1


# --- the sheet and the cycle ---------------------------------------------------------------------

def test_the_sheet_draws_the_sliders(tmp_path):
    """triad_sliding_rod with "assemblies": each small scheme draws block 4 on C (its centre the
    pin's circle), turned to the 70° guide, over a hatched frame guide; the JSON lists every pose;
    plans check reads each sheet as a scheme and the layout measurer finds nothing."""
    sheets = plans.render(parse_scene(_sliding(draw=("scheme", "assemblies"))), stem="tsr")
    report = json.loads(sheets.files["tsr.json"])
    motion = sheets.motion
    for i, pos in enumerate(report["positions"]):
        entry = pos["assemblies"][GROUP]
        found = group_assemblies(motion, motion.structure.groups[0], i)
        assert entry["count"] == found.count == 2
        name = f"tsr-assemblies-{pos['angle']:g}.svg"
        root = ET.fromstring(sheets.files[name])
        schemes = [g for g in root.iter(f"{SVG}g") if g.get("data-assembly") is not None]
        assert len(schemes) == 2
        for g, pose in zip(schemes, entry["poses"]):
            block = next(e for e in g.iter() if (e.get("id") or "").endswith("-block4"))
            corners = np.array([[float(v) for v in xy.split(",")] for xy in block.get("points").split()])
            joints = dict(zip(pose["points"], ((float(c.get("cx")), float(c.get("cy"))) for c in g.iter(f"{SVG}circle"))))
            c_mm = joints["C"]          # the joints are drawn in the order of the pose's points
            assert np.allclose(corners.mean(axis=0), c_mm, atol=0.01)
            along = corners[1] - corners[0]          # paper y down: the guide's 70° turns clockwise
            assert math.degrees(math.atan2(-along[1], along[0])) % 180.0 == pytest.approx(70.0, abs=0.05)
            assert any((e.get("id") or "").endswith("-gh0") for e in g.iter())      # the frame's hatching
        path = tmp_path / name
        path.write_text(sheets.files[name], encoding="utf-8")
        r = inspect_svg(path)
        assert r.kind == "scheme" and not r.problems
        assert measure_layout(sheets.files[name]).clean


def test_the_count_changes_over_the_cycle_at_branch_points():
    """The four-assembly triad over a revolution of 24 positions: two assemblies merge and part
    again (4 → 2 → 4). cycle.assemblies gives the counts, each the resultant's at that position's
    crank pin, and the positions sheet names every interval where a count changes."""
    points, angle = SLIDING_FOUR
    d = _sliding(points, angle, {"angle": 45.0, "positions": 24}, draw=("positions", "assemblies"))
    sheets = plans.render(parse_scene(d), stem="branch")
    report = json.loads(sheets.files["branch.json"])
    counts = report["cycle"]["assemblies"][GROUP]
    assert counts == [p["assemblies"][GROUP]["count"] for p in report["positions"]]
    assert counts == [len(resultant_assemblies(d, p["points"]["A"]["r"])) for p in report["positions"]]
    assert set(counts) == {2, 4}
    changes = [(k, (k + 1) % 24) for k in range(24) if counts[k] != counts[(k + 1) % 24]]
    assert len(changes) == 2
    root = ET.fromstring(sheets.files["branch-positions.svg"])
    words = re.sub(r"\s+", " ", " ".join("".join(t.itertext()) for t in root.iter(f"{SVG}text")))
    assert "The count of real assemblies changes" in words
    for k, j in changes:
        assert f"{GROUP}: {counts[k]} → {counts[j]} assemblies between positions {k} and {j}" in words
    # each branch marked on the crank's circle halfway between the two crank positions
    marks = {e.get("data-branch"): e for e in root.iter(f"{SVG}line") if e.get("data-branch")}
    assert set(marks) == {f"{k}-{j}" for k, j in changes}
    circle = next(e for e in root.iter(f"{SVG}circle") if (e.get("id") or "").endswith("crank-circle"))
    cx, cy, r = (float(circle.get(a)) for a in ("cx", "cy", "r"))
    for (k, j), e in zip(changes, (marks[f"{k}-{j}"] for k, j in changes)):
        x1, y1 = float(e.get("x1")), float(e.get("y1"))
        assert math.hypot(x1 - cx, y1 - cy) == pytest.approx(r, abs=2e-3)          # it starts on the circle
        tips = [next(el for el in root.iter(f"{SVG}g") if el.get("data-position") == str(i)) for i in (k, j)]
        angles = [float(t.get("data-angle")) for t in tips]
        step = abs(360.0 / 24)
        mark = math.degrees(math.atan2(-(y1 - cy), x1 - cx))                       # paper y down
        assert min(abs((mark - a + 180.0) % 360.0 - 180.0) for a in angles) == pytest.approx(step / 2, abs=0.05)
    size = sheets.motion.mechanism.size
    for p in report["positions"]:           # the drawn pose is one of them at every position
        chosen = next(q for q in p["assemblies"][GROUP]["poses"] if q["chosen"])
        assert all(math.dist(xy, p["points"][k]["r"]) <= SAME_RTOL * size for k, xy in chosen["points"].items())

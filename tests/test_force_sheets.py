"""Force sheets a teacher prints: each group's polygon drawn with its largest side 100–150 mm,
every side under 2 mm drawn again in an enlarged detail (or listed negligible in the force
table), a two-force polygon as two parallel arrows, and no two vertex letters on one spot —
read back from the SVG of every gallery example that draws force plans, and the layout
measurer's rule for vertex letters tried on hand-written sheets that have the fault.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from conftest import EXAMPLES
from plans.checking import inspect_svg
from plans.constructions.forces import ForceTerm, force_plan
from plans.constructions.scales import SERIES
from plans.drawing.forces import draw_force_plans, symbol
from plans.drawing.svg import Heading
from plans.drawing.text import runs
from plans.layout import measure_layout
from plans.pipeline import render_scene

SVG = "{http://www.w3.org/2000/svg}"
#: The window of the largest side, mm, and the length under which a side is unreadable, mm.
WINDOW = (100.0, 150.0)
SHORT = 2.0
FORCE_EXAMPLES = [p for p in EXAMPLES if any(w in p.stem for w in ("forces", "gravity", "flywheel", "startup"))]
HEADING = Heading("Test", "Force plans", "φ1 = 0°")


@pytest.fixture(scope="module")
def sheets(tmp_path_factory) -> dict[str, Path]:
    """Every force-plan sheet of the gallery, written to a folder: name → path."""
    out = tmp_path_factory.mktemp("force-sheets")
    files = {}
    for p in FORCE_EXAMPLES:
        for name, text in render_scene(p).files.items():
            if "-forces-" in name and name.endswith(".svg"):
                (out / name).write_text(text, encoding="utf-8")
                files[name] = out / name
    return files


def force_groups(root) -> list[ET.Element]:
    return [g for g in root.iter(f"{SVG}g") if g.get("data-plan") == "force"]


def sides(g) -> list[tuple[str, float, np.ndarray, np.ndarray]]:
    """(quantity, length mm, tail, head) of the tagged sides of a force plan group."""
    out = []
    for l in g.iter(f"{SVG}line"):
        if l.get("data-role") == "side":
            a = np.array([float(l.get("x1")), float(l.get("y1"))])
            b = np.array([float(l.get("x2")), float(l.get("y2"))])
            out.append((l.get("data-quantity"), float(np.linalg.norm(b - a)), a, b))
    return out


def text_of(root, ident: str) -> str:
    el = next((t for t in root.iter(f"{SVG}text") if t.get("id") == ident), None)
    return "" if el is None else "".join(el.itertext())


def series_lengths(value: float) -> list[float]:
    """The drawn lengths of ``value`` at every series scale m·10^k near it, mm."""
    k0 = math.floor(math.log10(value / WINDOW[1]))
    return [value / (m * 10.0 ** k) for k in range(k0 - 2, k0 + 3) for m in (*SERIES, 1.5, 3.0, 6.0)]


def test_the_gallery_draws_force_sheets(sheets):
    assert len(FORCE_EXAMPLES) >= 6
    assert len(sheets) >= 12


def test_largest_side_of_every_polygon_is_100_to_150_mm(sheets):
    """Within the window, unless the polygon would then outgrow its limit on a sheet beside its
    group's diagram (130 mm; a polygon of two forces, 70 mm): then the longest drawing of the
    series within that limit (both computed here from the series and the recorded forces)."""
    seen = 0
    for name, path in sheets.items():
        for g in force_groups(ET.parse(path).getroot()):
            if g.get("data-detail") is not None:
                continue
            lines = [l for l in g.iter(f"{SVG}line") if l.get("data-role") == "side"]
            q, L, _, _ = max(sides(g), key=lambda s: s[1])
            value = float(next(l.get("data-value") for l in lines if l.get("data-quantity") == q))
            mu = float(g.get("data-mu"))
            assert L == pytest.approx(value / mu, abs=2e-3)      # two ends rounded to 0.001 mm: ≤ √2·0.001
            # the polygon's corners from the recorded forces (N), as the construction lays them
            vec = np.array([[float(l.get("data-value")) * math.cos(math.radians(float(l.get("data-direction")))),
                             float(l.get("data-value")) * math.sin(math.radians(float(l.get("data-direction"))))]
                            for l in lines])
            corners = np.vstack([np.zeros(2), np.cumsum(vec, axis=0)])
            extent = max(float(np.ptp(corners[:, 0])), float(np.ptp(corners[:, 1])), value)
            limit = 70.0 if len(lines) == 2 else 130.0
            lengths = [x for x in series_lengths(value) if x <= WINDOW[1] + 1e-9 and x * extent / value <= limit + 1e-9]
            inside = [x for x in lengths if x >= WINDOW[0]]
            if inside:
                assert WINDOW[0] - 2e-3 <= L <= WINDOW[1] + 2e-3, (name, g.get("data-group"), L)
            else:
                assert L == pytest.approx(max(lengths), abs=2e-3), (name, g.get("data-group"), L)
            seen += 1
    assert seen >= 20


def test_every_short_side_is_in_a_detail_or_listed_negligible(sheets):
    details_seen = negligible_seen = 0
    for name, path in sheets.items():
        root = ET.parse(path).getroot()
        groups = force_groups(root)
        for g in groups:
            if g.get("data-detail") is not None:
                continue
            pid = g.get("id").removesuffix("-plan")
            # the force table of this panel: symbol → note
            notes = {}
            r = 0
            while text_of(root, f"{pid}-t{r}-0"):
                notes[text_of(root, f"{pid}-t{r}-0")] = text_of(root, f"{pid}-t{r}-3")
                r += 1
            details = [d for d in groups if d.get("data-detail") is not None and d.get("id").startswith(pid + "-x")]
            in_detail = {q: (L, float(d.get("data-mu"))) for d in details for q, L, _, _ in sides(d)}
            for q, L, _, _ in sides(g):
                if L >= SHORT:
                    continue
                words = "".join(r.text for r in runs(symbol(q), digits=False))
                note = notes[words]
                if q in in_detail and in_detail[q][0] >= SHORT:
                    details_seen += 1
                    assert "in detail" in note and in_detail[q][1] < float(g.get("data-mu")), (name, q, note)
                else:
                    negligible_seen += 1
                    assert note.startswith("negligible"), (name, q, note)
    assert details_seen >= 10 and negligible_seen >= 1


def test_a_detail_holds_a_run_of_consecutive_sides_stated_with_its_own_scale(sheets):
    # 240°: the ram presses, its 4 kN working force beside weights and inertia forces of a few N
    # (at 60° the ram rises: its working force is 0 there)
    path = sheets["six_link_press_forces-forces-240.svg"]
    root = ET.parse(path).getroot()
    groups = {g.get("id"): g for g in force_groups(root)}
    main = next(g for g in groups.values() if g.get("data-group") == "II(4-5)" and g.get("data-detail") is None)
    pid = main.get("id").removesuffix("-plan")
    detail = groups[f"{pid}-x0-plan"]
    assert detail.get("data-group") == main.get("data-group") == "II(4-5)"
    mu, mu_d = float(main.get("data-mu")), float(detail.get("data-mu"))
    assert text_of(root, f"{pid}-dcap0") == f"detail 1, μF = {mu_d:g} N/mm"
    order = [q for q, *_ in sides(main)]
    run = [q for q, *_ in sides(detail)]
    k = order.index(run[0])
    assert run == order[k:k + len(run)] and len(run) >= 2
    # each side drawn again mu/mu_d times as long, in the same direction, head to tail
    main_sides = {q: (b - a) for q, _, a, b in sides(main)}
    drawn = sides(detail)
    for (q, L, a, b), (_, _, a2, _) in zip(drawn, drawn[1:]):
        np.testing.assert_allclose(b, a2, atol=1e-3)
    for q, L, a, b in drawn:
        np.testing.assert_allclose((b - a) * mu_d / mu, main_sides[q], atol=2e-3 * mu_d / mu + 1e-3)


def test_plans_check_passes_on_every_force_sheet(sheets):
    for name, path in sheets.items():
        r = inspect_svg(path)
        assert r.ok, (name, r.problems)


def test_a_two_force_polygon_is_two_parallel_arrows_side_by_side(sheets):
    found = 0
    for name, path in sheets.items():
        root = ET.parse(path).getroot()
        heads = {h.get("data-for") for h in root.iter(f"{SVG}path") if "head" in (h.get("class") or "")}
        for g in force_groups(root):
            s = sides(g)
            if len(s) != 2 or g.get("data-detail") is not None:
                continue
            found += 1
            (q1, L1, a1, b1), (q2, L2, a2, b2) = s
            assert L1 == pytest.approx(L2, abs=2e-3) and L1 >= SHORT
            d1, d2 = (b1 - a1) / L1, (b2 - a2) / L2
            assert float(d1 @ d2) == pytest.approx(-1.0, abs=1e-6)          # opposite, parallel
            offset = abs(float(d1[0] * (a2 - a1)[1] - d1[1] * (a2 - a1)[0]))   # distance between their lines
            assert 2.0 <= offset <= 10.0, (name, offset)
            # side by side: the second runs back beside the first, over the same stretch
            assert float((a2 - a1) @ d1) == pytest.approx(L1, abs=2e-3)
            lines = [l for l in g.iter(f"{SVG}line") if l.get("data-role") == "side"]
            assert all(l.get("id") in heads for l in lines)
            assert len({l.get("data-from") for l in lines} | {l.get("data-to") for l in lines}) == 4
    assert found >= 4


def test_a_two_force_plan_drawn_alone_checks(tmp_path):
    fp = force_plan("I(0-1)", [ForceTerm("R:2-1", (300.0, 400.0), "reaction"),
                               ForceTerm("R:0-1", (-300.0, -400.0), "reaction")])
    assert fp.mu == 4.0                                                     # 500 N drawn 125 mm
    (svg,) = draw_force_plans([fp], HEADING, ident="forces")
    path = tmp_path / "two.svg"
    path.write_text(svg, encoding="utf-8")
    r = inspect_svg(path)
    assert r.ok, r.problems
    assert {c.what for c in r.checks} >= {"Σ of the 2 drawn sides", "Σ of the recorded forces"}
    assert measure_layout(svg).clean


# --- the measurer's rule: overlapping vertex letters -------------------------------------------------

def force_sheet(body: str) -> str:
    return ('<svg xmlns="http://www.w3.org/2000/svg" width="297mm" height="210mm" viewBox="0 0 297 210">'
            f'{body}</svg>')


def letter(x: float, y: float, text: str) -> str:
    return (f'<text class="label" x="{x}" y="{y}" font-size="3" font-style="italic" text-anchor="start">'
            f'<tspan>{text}</tspan></text>')


def vector(x1, y1, x2, y2, a: str, b: str, k: int) -> str:
    return (f'<line id="v{k}" data-quantity="F{k}" data-value="1" data-direction="0" data-role="side" '
            f'data-from="{a}" data-to="{b}" x1="{x1}" y1="{y1}" x2="{x2}" y2="{y2}" stroke="#000" '
            'stroke-width="0.35"/>')


def test_vertex_letters_on_one_spot_are_counted():
    """Three vertices within 1 mm (sides of 0.5 mm), each letter by its point, their boxes
    apart (as the placer put them on main's sheet): three pairs; a fourth vertex far away adds none."""
    body = ('<g id="p" data-plan="force" data-mu="50">'
            + vector(100, 100, 100.5, 100, "a", "b", 0) + vector(100.5, 100, 100.5, 100.5, "b", "c", 1)
            + vector(100.5, 100.5, 100, 60, "c", "d", 2) + vector(100, 60, 100, 100, "d", "a", 3)
            + letter(95, 100, "a") + letter(102, 99, "b") + letter(102, 104, "c") + letter(102, 60, "d") + '</g>')
    r = measure_layout(force_sheet(body))
    assert r.overlapping_vertex_letters == 3, r.vertex_letters
    assert r.overlapping_labels == 0
    assert "overlapping_vertex_letters" in r.counts and not r.clean


def test_overlapping_vertex_letters_far_apart_are_counted_and_clean_ones_are_not():
    poly = (vector(100, 100, 140, 100, "a", "b", 0) + vector(140, 100, 100, 100, "b", "a", 1))
    apart = '<g id="p" data-plan="force" data-mu="50">' + poly + letter(96, 100, "a") + letter(142, 100, "b") + '</g>'
    assert measure_layout(force_sheet(apart)).overlapping_vertex_letters == 0
    # b's letter drawn over a's
    over = '<g id="p" data-plan="force" data-mu="50">' + poly + letter(96, 100, "a") + letter(97, 100, "b") + '</g>'
    r = measure_layout(force_sheet(over))
    assert r.overlapping_vertex_letters == 1 and "overlaps" in r.vertex_letters[0]
    # the same texts outside a force plan are no vertex letters (only overlapping labels)
    plain = '<g id="p" data-plan="velocity" data-mu="50">' + poly + letter(96, 100, "a") + letter(97, 100, "b") + \
        '</g>'
    r = measure_layout(force_sheet(plain))
    assert r.overlapping_vertex_letters == 0 and r.overlapping_labels == 1
    # one label naming both vertices of a short side is no pair
    joined = ('<g id="p" data-plan="force" data-mu="50">' + vector(100, 100, 100.5, 100, "a", "b", 0)
              + vector(100.5, 100, 100, 100, "b", "a", 1) + letter(96, 100, "a, b") + '</g>')
    assert measure_layout(force_sheet(joined)).overlapping_vertex_letters == 0


def test_a_sheet_like_mains_is_counted():
    """The six-link press at 60° drawn as main drew it: every vertex lettered on its own at
    μF = 50 N/mm (the weights and inertia forces under 2 mm; the ram rises there, so its working
    force, which acts on the working stroke only, is 0)."""
    from plans.drawing import forces as drawing

    scene = next(p for p in EXAMPLES if p.stem == "six_link_press_forces")
    svg = render_scene(scene).files["six_link_press_forces-forces-60.svg"]
    root = ET.fromstring(svg)
    g = next(g for g in force_groups(root) if g.get("data-group") == "II(4-5)" and g.get("data-detail") is None)
    terms = []
    for l in g.iter(f"{SVG}line"):
        if l.get("data-role") == "side":
            v, t = float(l.get("data-value")), math.radians(float(l.get("data-direction")))
            terms.append(ForceTerm(l.get("data-quantity"), (v * math.cos(t), -v * math.sin(t)), l.get("data-kind")))
    crowded = force_plan("II(4-5)", terms, mu=50.0)
    # main's lettering: each vertex its own label, no detail
    old = drawing._vertex_labels
    try:
        drawing._vertex_labels = lambda points, hidden=frozenset(): [(p.xy, p.label) for p in points]
        (before,) = drawing.draw_force_plans([crowded], HEADING, ident="forces")
    finally:
        drawing._vertex_labels = old
    assert measure_layout(before).overlapping_vertex_letters >= 10
    (after,) = drawing.draw_force_plans([crowded], HEADING, ident="forces")
    assert measure_layout(after).overlapping_vertex_letters == 0


def test_the_rule_is_zero_on_every_gallery_force_sheet(sheets):
    bad = {}
    for name, path in sheets.items():
        r = measure_layout(path.read_text(encoding="utf-8"))
        if not r.clean:
            bad[name] = {k: r.offenders(k)[:3] for k, v in r.counts.items() if v}
    assert not bad, bad


# --- the scale and the details, as geometry ------------------------------------------------------

@pytest.mark.parametrize("fmax", [1.0, 3.3, 12.0, 99.0, 187.6, 199.9, 250.0, 380.0, 499.0, 760.0, 799.0, 4000.0,
                                  3839.0, 1.7e6, 1e-300 * 3.7, 2.3e300])
def test_force_scale_draws_the_largest_force_100_to_150_mm(fmax):
    """Every largest force, those where the standard series alone jumps over the window
    (187.5–200, 375–400, 750–800 × 10^k N) included, is drawn 100–150 mm, by a μF of the
    series with 1.5, 3 and 6 added, the one nearest the window's middle (log scale)."""
    from plans.constructions.forces import force_scale

    mu = force_scale(fmax, fmax)
    mantissa = mu / 10.0 ** math.floor(math.log10(mu))
    assert any(math.isclose(mantissa, m, rel_tol=1e-9) for m in (*SERIES, 1.5, 3.0, 6.0))
    L = fmax / mu
    assert WINDOW[0] * (1 - 1e-9) <= L <= WINDOW[1] * (1 + 1e-9)
    mid = math.sqrt(WINDOW[0] * WINDOW[1])
    best = min((x for x in series_lengths(fmax) if WINDOW[0] <= x <= WINDOW[1]), key=lambda x: abs(math.log(x / mid)))
    assert L == pytest.approx(best)


def test_a_wide_polygon_is_coarsened_to_fit():
    from plans.constructions.forces import force_scale

    # largest force 1000 N (125 mm at μF = 8) but the polygon 3000 N across: 240 mm at most
    mu = force_scale(1000.0, 3000.0)
    assert 3000.0 / mu <= 240.0 and mu == 12.5


def test_details_of_a_run_of_short_sides():
    """A 4 kN force closed by a 3.9 kN reaction and a run of small ones: the run (< 10 mm each,
    one < 2 mm) drawn again at the series μF that draws its largest side 40–60 mm."""
    from plans.constructions.forces import force_details

    small = [ForceTerm("G:4", (0.0, -39.24), "gravity"), ForceTerm("F:in:4", (-2.0, -3.3), "inertia"),
             ForceTerm("G:5", (0.0, -98.1), "gravity"), ForceTerm("F:in:5", (0.0, -21.4), "inertia")]
    rest = np.sum([t.vector for t in small], axis=0) + (0.0, 4000.0)
    terms = small + [ForceTerm("F:ext:E", (0.0, 4000.0), "external"),
                     ForceTerm("R:0-5", (-rest[0], -rest[1]), "reaction")]
    fp = force_plan("II(4-5)", terms)
    assert fp.mu == 30.0                                                  # 4000 N drawn 133 mm
    (d,) = force_details(fp)
    assert [v.quantity for v in d.vectors] == ["G:4", "F:in:4", "G:5", "F:in:5"]
    assert d.mu == 2.0                                                    # G5 = 98.1 N drawn 49 mm
    assert [p.label for p in d.points] == ["a", "b", "c", "d", "e"]
    for v, t in zip(d.vectors, small):
        np.testing.assert_allclose(np.subtract(v.head, v.tail) * d.mu, t.vector, atol=1e-9)
    # F_in,4 = 3.86 N: 1.93 mm even in the detail
    assert d.negligible == ("F:in:4",)
    # a run of one short side gets no detail
    lone = [ForceTerm("A", (0.0, 4000.0), "external"), ForceTerm("B", (1.0, -2000.0), "external"),
            ForceTerm("C", (0.0, -2000.0), "external"), ForceTerm("D", (-1.0, 0.0), "external")]
    assert force_details(force_plan("II", lone)) == ()

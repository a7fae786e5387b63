"""Printed sizes of a handout, as a teacher prints it from index.html.

1. index.html prints every sheet at 100 % on a page of its own size: each sheet's section is a
   named CSS page whose ``size`` is the sheet's SVG width and height in mm, without margins,
   and the sheet's ``<img>`` is given exactly that width and height (no fitting, no scaling);
   so a text keeps on paper the height it is drawn at.
2. Every framed answer area of the assignment (kinematics, forces, dynamics, gears: one
   variant each) is at least as wide and as tall, below its caption row, as each drawing the
   variant's answer key draws for it (measured here from the key's SVG with the layout
   reader: the ``<g data-plan>`` / ``<g data-diagram>`` groups, a detail left out); the areas
   stay inside the sheet's drawing area, apart from each other and from what the sheet draws.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from plans.cli import main
from plans.export import sheet_size_mm
from plans.handout import random_variants, read_variants, solve_variant, variant_asked
from plans.handout import assignment as handout_assignment
from plans.handout.index import index_html
from plans.layout import measure_layout
from plans.layout.sheet import _Reader, _sheet_size
from plans.pipeline.sheets.page import sheet_suffix

EX = Path(__file__).resolve().parent.parent / "examples"
KINDS = {"kinematics": EX / "four_bar.toml", "forces": EX / "six_link_press_forces.toml",
         "dynamics": EX / "six_link_press_flywheel.toml", "gears": EX / "gears" / "planetary_1_21.toml"}
#: The caption row at the top of an answer area (its name and the scale to write in), mm.
CAPTION_MM = 8.0
#: A3 landscape's drawing area: inside the frame, above the title block (mm, y down).
A3_AREA = (21.0, 6.0, 414.0, 256.0)
SVG = "{http://www.w3.org/2000/svg}"


# -- 1. index.html prints at 100 % ------------------------------------------------------------------

def _print_rules(html: str) -> tuple[dict[str, str], dict[str, str], dict[str, str]]:
    """The page's CSS: each named @page's body, each ``section.X`` rule's body and each
    ``section.X img.sheet`` rule's body (by X)."""
    css = "\n".join(re.findall(r"<style>(.*?)</style>", html, re.S))
    pages = {m.group(1): m.group(2) for m in re.finditer(r"@page\s+([\w-]+)\s*\{([^}]*)\}", css)}
    sections = {m.group(1): m.group(2) for m in re.finditer(r"section\.([\w-]+)\s*\{([^}]*)\}", css)}
    images = {m.group(1): m.group(2) for m in re.finditer(r"section\.([\w-]+)\s+img\.sheet\s*\{([^}]*)\}", css)}
    return pages, sections, images


def _mm(rule: str, name: str) -> list[float] | str:
    """The lengths (mm) a property ``name`` of a CSS rule gives (``size: 420mm 297mm`` →
    [420, 297], ``margin: 0`` → [0]), or its text when it gives none in mm (``A4 landscape``)."""
    m = re.search(rf"(?<![-\w]){name}\s*:\s*([^;]+)", rule)
    assert m, f"no {name} in {rule!r}"
    value = m.group(1).strip()
    return [float(x) for x in re.findall(r"([\d.]+)mm", value)] or ([0.0] if value == "0" else value)


#: A rule's ``page: NAME`` (not ``break-after: page``).
_PAGE = r"(?<![-\w])page\s*:\s*([\w-]+)"


def test_index_prints_every_sheet_at_its_own_size(tmp_path):
    out = tmp_path / "h"
    assert main(["handout", str(KINDS["kinematics"]), "--random", "2", "--seed", "3", "-o", str(out), "-q"]) == 0
    html = (out / "index.html").read_text(encoding="utf-8")
    pages, sections, images = _print_rules(html)
    found = re.findall(r'<section class="([^"]*)"[^>]*>\s*<h2>[^<]*</h2>\s*<img class="sheet" src="([^"]+)"', html)
    assert len(found) == html.count('<img class="sheet"') > 2
    for classes, src in found:
        w, h = sheet_size_mm((out / src).read_text(encoding="utf-8"))
        named = [c for c in classes.split() if re.search(_PAGE, sections.get(c, ""))]
        assert len(named) == 1, (src, classes)
        page = re.search(_PAGE, sections[named[0]]).group(1)
        assert _mm(pages[page], "size") == [w, h], (src, pages[page])             # the page is the sheet
        assert _mm(pages[page], "margin") == [0.0], (src, pages[page])
        assert (_mm(images[named[0]], "width"), _mm(images[named[0]], "height")) == ([w], [h]), src   # at 100 %
    print_css = re.search(r"@media print\s*\{(.*)", html, re.S).group(1)
    assert not re.search(r"img\.sheet[^{]*\{[^}]*max-(height|width)\s*:\s*\d", print_css)   # nothing shrinks it
    assert re.search(r"section\.sheet h2\s*\{\s*display:\s*none", print_css)          # the heading takes no room


def test_index_lists_each_answer_sheet_on_its_page(made):
    h, d, sheets, _ = made["forces"]
    html = index_html(h, [d], margin=h.margin, asked=[variant_asked(d)], assignments=[sheets])
    pages, sections, _ = _print_rules(html)
    srcs = re.findall(r'<section class="page sheet (\S+) assignment"[^>]*>\s*<h2>[^<]*</h2>\s*<img class="sheet" '
                      r'src="[^/]+/([^"]+)"', html)
    assert [s for _, s in srcs] == list(sheets) and len(sheets) > 1
    for name, src in srcs:
        assert _mm(pages[name], "size") == list(sheet_size_mm(sheets[src]))


# -- 2. the answer areas hold what the key draws ----------------------------------------------------

def _sheets(h, d) -> dict[str, str]:
    """Every sheet of the variant's assignment (file name → SVG), as the handout makes them."""
    a = variant_asked(d)
    if hasattr(handout_assignment, "assignment_sheets"):
        return handout_assignment.assignment_sheets(h, d, a)
    return {f"{d.name}-assignment.svg": handout_assignment.assignment_svg(h, d, a)}


#: The cases: a random variant of each kind, and a kinematics variant asked at two positions (a
#: velocity and an acceleration plan at each: four areas, more than one sheet holds).
CASES = [*KINDS, "two positions"]


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    from conftest import press_without_cycle

    out = {}
    for kind, path in KINDS.items():
        h, drawn = random_variants(path, 1, 3)
        d = drawn[0]
        out[kind] = (h, d, _sheets(h, d), {s.name: s.svg for s in d.sheets})
    folder = tmp_path_factory.mktemp("press")
    base = press_without_cycle(folder)
    (folder / "v.toml").write_text(f'base = "{base.name}"\n\n[[variant]]\nlengths = {{ CE = 0.4 }}\n'
                                   "angle = [120.0, 250.0]\nomega = -6.0\n", encoding="utf-8")
    h = read_variants(folder / "v.toml")
    d = solve_variant(h, h.variants[0])
    out["two positions"] = (h, d, _sheets(h, d), {s.name: s.svg for s in d.sheets})
    return out


def _box(reader: _Reader) -> tuple[float, float, float, float]:
    boxes = [i.geometry().bounds for i in reader.ink] + [t.box for t in reader.texts]
    return (min(b[0] for b in boxes), min(b[1] for b in boxes), max(b[2] for b in boxes), max(b[3] for b in boxes))


def _key_drawings(svg: str) -> list[tuple[str, tuple[float, float, float, float]]]:
    """(data-plan or data-diagram, box mm) of each drawing of a key sheet, a detail left out."""
    root = ET.fromstring(svg)
    _, _, m = _sheet_size(root)
    out = []
    for g in root.iter(f"{SVG}g"):
        what = g.get("data-plan") or g.get("data-diagram")
        if what in ("velocity", "acceleration", "force", "lever", "gear-velocity", "gear-omega", "M", "A", "T", "I",
                    "wittenbauer") and g.get("data-detail") is None and "-detail-" not in g.get("id", ""):
            reader = _Reader(root)
            reader.walk(g, {}, m)
            out.append((what, _box(reader)))
    return out


def _frames(svg: str) -> list[tuple[str, str, tuple[float, float, float, float]]]:
    """(data-area, data-position, box mm) of every answer area of an assignment sheet."""
    out = []
    for r in ET.fromstring(svg).iter(f"{SVG}rect"):
        if r.get("data-area"):
            x, y, w, h = (float(r.get(k)) for k in ("x", "y", "width", "height"))
            out.append((r.get("data-area"), r.get("data-position", ""), (x, y, x + w, y + h)))
    return out


def _size(b) -> tuple[float, float]:
    return b[2] - b[0], b[3] - b[1]


def _union(boxes):
    return (min(b[0] for b in boxes), min(b[1] for b in boxes), max(b[2] for b in boxes), max(b[3] for b in boxes))


def _wanted(kind: str, d, key: dict[str, str]) -> dict[tuple[str, str], list[tuple[float, float, float, float]]]:
    """What each answer area (data-area, data-position) must hold: the key's drawings."""
    if kind == "gears":
        return {("pictures", ""): [b for what, b in _key_drawings(key["gears"]) if what.startswith("gear-")]}
    if kind == "dynamics":
        got = _key_drawings(key["dynamics"])
        # I_r(φ) is drawn turned under Wittenbauer's diagram (its construction by projection)
        return {("diagrams", ""): [_union([b for what, b in got if what in "MAT"])],
                ("wittenbauer", ""): [_union([b for what, b in got if what in ("wittenbauer", "I")])]}
    names = {"velocity": "velocity", "acceleration": "acceleration", "forces": "force", "lever": "lever"}
    kinds = tuple(names) if kind == "forces" else ("velocity", "acceleration")
    motion = d.sheets.motion
    suffixes = [sheet_suffix(motion, i) for i in range(1 if kind == "forces" else len(motion))]
    out = {}
    for suffix in suffixes:
        for area in kinds:
            pages = [n for n in key if n == area + suffix or area == "forces" and re.fullmatch(
                re.escape(area + suffix) + r"-\d+", n)]
            out[(area, suffix)] = [b for n in pages for what, b in _key_drawings(key[n]) if what == names[area]]
            assert out[(area, suffix)], (kind, area, suffix, sorted(key))
    return out


@pytest.mark.parametrize("kind", CASES)
def test_each_answer_area_holds_what_the_key_draws(made, kind):
    h, d, sheets, key = made[kind]
    frames = [(area, pos, b, name) for name, svg in sheets.items() for area, pos, b in _frames(svg)]
    for (area, pos), drawn in _wanted(kind, d, key).items():
        mine = [f for f in frames if f[0] == area and (f[1] == pos or area == "pictures")]
        assert mine, f"{kind}: no area {area}{pos} on {list(sheets)}"
        if area == "pictures":          # drawn where the key draws them (beside the side view)
            for b in drawn:
                assert any(f[2][0] <= b[0] and f[2][1] <= b[1] and b[2] <= f[2][2] and b[3] <= f[2][3] for f in mine), \
                    (kind, b, [f[2] for f in mine])
            continue
        (_, _, frame, _), = mine
        w, hh = _size(frame)
        for b in drawn:
            bw, bh = _size(b)
            assert bw <= w and bh <= hh - CAPTION_MM, \
                f"{kind} {area}{pos}: area {w:.1f} × {hh - CAPTION_MM:.1f} mm in, key {bw:.1f} × {bh:.1f}"
        assert sum(_size(b)[0] * _size(b)[1] for b in drawn) <= w * (hh - CAPTION_MM)


@pytest.mark.parametrize("kind", CASES)
def test_answer_areas_stay_on_the_sheet_and_apart(made, kind):
    h, d, sheets, _ = made[kind]
    for name, svg in sheets.items():
        report = measure_layout(svg)
        assert report.clean, (name, report)                     # no text crosses a frame, none off the sheet
        frames = [b for _, _, b in _frames(svg)]
        size = sheet_size_mm(svg)
        area = A3_AREA if size == (420.0, 297.0) else (21.0, 6.0, size[0] - 6.0, size[1] - 41.0)
        if kind != "gears":
            assert size == (420.0, 297.0), name                  # A3 landscape, every one
        for k, b in enumerate(frames):
            assert area[0] <= b[0] and area[1] <= b[1] and b[2] <= area[2] and b[3] <= area[3], (name, b)
            for c in frames[k + 1:]:
                assert b[2] <= c[0] or c[2] <= b[0] or b[3] <= c[1] or c[3] <= b[1], (name, b, c)
        root = ET.fromstring(svg)
        _, _, m = _sheet_size(root)
        for g in root.iter(f"{SVG}g"):                           # the scheme and the data table keep clear
            if g.get("data-plan") == "scheme" or g.get("id", "").endswith(("-data", "-table")):
                reader = _Reader(root)
                reader.walk(g, {}, m)
                s = _box(reader)
                for b in frames:
                    assert b[2] <= s[0] or s[2] <= b[0] or b[3] <= s[1] or s[3] <= b[1], (name, g.get("id"), b, s)

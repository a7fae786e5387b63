"""Edges of the scheme and the positions sheet (issue 32, items 19 and 22–25), measured on the
drawn SVG and the constructions:

* 19: a walk that cannot assemble gives a measured value only with the drive's value it was
  measured at (the one where the walk failed), never beside another angle;
* 22: a hydraulic cylinder's barrel is shorter than its pin distance at every position, so the
  rod always shows;
* 23: a negative number on a sheet is written with the minus sign (U+2212), not a hyphen;
* 24: the drive's arc arrows ω, ε are short arcs by the pivot (radius ≤ ARC_MAX_MM) that cross
  no other link's line, on every example;
* 25: a slider's positions on the positions sheet are ticks on its guide, its block drawn at
  the extremes only (no two blocks overlap), every number by its tick or led to it.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import shapely

import plans
from plans.constructions import scheme
from plans.constructions.scheme import ARC_MAX_MM
from plans.constructions.scheme_drive import PIN_ROOM_MM
from plans.drawing import Style
from plans.drawing.positions import LABEL_NEAR_MM, TICK_MM
from plans.drawing.text import box, runs
from plans.errors import AssemblyError
from plans.kinematics import analyse
from plans.model import build_mechanism
from plans.scene import parse_scene
from plans.structure import analyse_structure

from test_scheme import EX, NS, _path_points, _shape, _solve, _svg

#: Written coordinates carry three decimals: a drawn point is within √2·0.0005 mm of the exact
#: one, a distance between two within twice that.
ROUND_MM = 2.0 * math.sqrt(2.0) * 0.0005


# -- 19. the value a failed walk measured, with the angle it measured it at ------------------------

def _four_bar(angle: float) -> dict:
    """Crank OA 0.18 m, coupler AB 0.2 m, rocker CB 0.2 m, frame OC 0.24 m, sketched at 90°: s + l
    = 0.42 > p + q = 0.40, so the crank rocks between ±144.1° (|AC| = AB + BC = 0.4 m there)."""
    a, c = np.array([0.0, 0.18]), np.array([0.24, 0.0])
    half = float(np.linalg.norm(c - a)) / 2
    u = (c - a) / (2 * half)
    b = (a + c) / 2 + math.sqrt(0.2 ** 2 - half ** 2) * np.array([-u[1], u[0]])
    return {"points": {"O": [0.0, 0.0], "C": [0.24, 0.0], "A": [0.0, 0.18], "B": [float(b[0]), float(b[1])]},
            "links": {"0": ["O", "C"], "1": ["O", "A"], "2": ["A", "B"], "3": ["C", "B"]},
            "drive": {"link": "1", "angle": angle, "omega": 10.0}}


def _ac(angle: float) -> float:
    """|AC| (m) at crank angle ``angle`` (deg), exact: A on the crank circle, C fixed."""
    t = math.radians(angle)
    return math.hypot(0.18 * math.cos(t) - 0.24, 0.18 * math.sin(t))


@pytest.mark.parametrize("asked", [170.0, 145.0, 560.0])
def test_a_walk_that_cannot_assemble_gives_its_value_at_the_angle_it_names(asked):
    """Asked 170° (or 560°, a turn on), the walk from the sketch's 90° fails at 145° (the first
    1° step past 144.1°), where |AC| = 0.400967 m > 0.4 m; at 170° |AC| is 0.4184 m. The value
    printed is |AC| at the last angle named before it, and that angle is where the walk failed."""
    mech = build_mechanism(parse_scene(_four_bar(asked)))
    with pytest.raises(AssemblyError) as err:
        analyse(mech, analyse_structure(mech), np.array([asked]))
    text = str(err.value)
    head, _, tail = text.partition("|AC| = ")
    value = float(re.match(r"([\d.eE+-]+) m", tail).group(1))
    named = float(re.findall(r"at (-?[\d.]+)°", head)[-1])       # the angle the value is given at
    assert named == 145.0, text
    assert value == pytest.approx(_ac(named), rel=1e-5), text    # printed to 6 significant digits
    assert value > 0.4                                              # why it cannot assemble there
    if asked != 145.0:                                              # not the value at the asked angle
        assert abs(_ac(asked) - value) > 1e-3, text
        assert f"at {asked:g}°" in text and "(the walk from the sketch at 90° fails at 145°)" in text, text
    assert "between 0 and 0.4 m" in text, text                     # equal links join from 0, not 2.8e-17


# -- 22. the barrel is shorter than the pin distance: the rod always shows -------------------------

def _by_part(els, part):
    return [el for el in els.values() if el.get("data-part") == part]


def _line_ends(el):
    return (np.array([float(el.get("x1")), float(el.get("y1"))]),
            np.array([float(el.get("x2")), float(el.get("y2"))]))


def _to_paper(els, sch):
    p = sch.joints[0]
    c = els["s-j0"]
    dx = float(c.get("cx")) - sch.points[p][0]
    dy = float(c.get("cy")) + sch.points[p][1]
    return lambda q: np.array([q[0] + dx, dy - q[1]])


def test_the_boom_barrel_is_shorter_than_its_pin_distance_at_every_position():
    """hydraulic_boom: rod BP = 0.3 m, strokes −0.12 … +0.18 m (0.30 m). At every position the
    barrel's mouth (measured along the axis from pivot A on the SVG) stops short of pin B by
    more than the pin's circle, so the rod shows, and the piston stays inside the barrel; the
    barrel has one length throughout: 24.28 mm, |AB| 27.28 … 51.28 mm. (Before: 28.78 mm, past B
    at −0.12 m.)"""
    motion, mu = _solve(EX["hydraulic_boom"])
    style = Style()
    mouths, shown = [], []
    for i in range(len(motion)):
        sch = scheme(motion, i, mu)
        els, _ = _svg(sch)
        paper = _to_paper(els, sch)
        a, b = (paper(motion.position(p)[i] / mu) for p in ("A", "B"))
        axis = (b - a) / np.linalg.norm(b - a)
        (barrel,), (rod,), (piston,) = _by_part(els, "barrel"), _by_part(els, "rod"), _by_part(els, "piston")
        corners = np.array(_shape(barrel).exterior.coords[:-1])
        mouth = float(np.max(np.dot(corners - a, axis)))
        pin = float(np.linalg.norm(b - a))
        assert mouth < pin, (i, mouth, pin)
        start, end = _line_ends(rod)
        assert np.linalg.norm(end - b) < ROUND_MM                 # the rod reaches its pin ...
        out = pin - mouth - style.joint_radius                    # ... and shows between mouth and pin
        assert out >= 1.0, (i, out)
        assert _shape(barrel).buffer(-0.1).contains(shapely.LineString(_line_ends(piston)))
        assert float(np.dot(start - a, axis)) < mouth             # the rod starts at the piston, inside
        mouths.append(mouth)
        shown.append(out)
    assert max(mouths) - min(mouths) <= 2 * ROUND_MM               # one barrel at every position
    assert min(shown) == pytest.approx(PIN_ROOM_MM - style.joint_radius, abs=0.01)   # at the shortest


# -- 23. negative numbers with the minus sign ----------------------------------------------------

#: A hyphen written as a number's sign: before a digit (or a point and a digit), not after a
#: letter, digit, bracket or point (``I(0-2-3-4)`` joins link numbers, ``1e-05`` is an exponent).
_HYPHEN_SIGN = re.compile(r"(?<![\w).])-(?=\.?\d)")


def _words(svg: str) -> list[str]:
    """Every text a sheet writes: its texts (runs joined), its title and description."""
    root = ET.fromstring(svg)
    out = ["".join(t.itertext()) for t in root.iter(f"{NS}text")]
    out += [el.text or "" for tag in ("title", "desc") for el in root.iter(f"{NS}{tag}")]
    return out


def test_negative_values_on_the_boom_sheets_are_written_with_the_minus_sign():
    sheets = plans.render(EX["hydraulic_boom"])
    negative = [name for name in sheets.sheets if "-m0." in name]      # s = −0.12 m, −0.06 m
    assert {"scheme-m0.12", "velocity-m0.06"} <= set(sheets.sheets), list(sheets.sheets)
    for name in sheets.sheets:
        for words in _words(sheets[name].svg):
            assert not _HYPHEN_SIGN.search(words), (name, words)
    for name in negative:
        stroke = "0.12" if "0.12" in name else "0.06"
        assert any(f"s = −{stroke} m" in w for w in _words(sheets[name].svg)), name


# -- 24. the drive's arc arrows: short, by the pivot, clear of the other links ---------------------

def _centre(sch, els, link: str) -> np.ndarray:
    """Where a drawn arc arrow of ``link`` turns about (paper mm): the driving crank's pivot
    (its pin's circle), or the middle of the link's drawn points (a coupler's ω, ε)."""
    if sch.drive_pivot is not None:
        c = els[f"s-j{sch.joints.index(sch.drive_pivot)}"]
        return np.array([float(c.get("cx")), float(c.get("cy"))])
    drawn = _shape(els[f"s-link{link}"])
    ring = drawn.exterior.coords[:-1] if drawn.geom_type == "Polygon" else drawn.coords
    return np.mean(np.array(ring), axis=0)


def _other_lines(sch, els, link: str):
    """(id, drawn line) of everything on the scheme that is not link ``link``'s: other links'
    bars and plates' outlines, blocks and their rods, guides (not ``link``'s slots) with the
    frame's ground lines and hatching, stems, supports, cylinders."""
    ids = [f"s-link{n}" for n, _ in sch.links if n != link]
    ids += [f"s-{kind}{b.link}" for b in sch.blocks if b.link != link for kind in ("block", "rod")]
    for k, gd in enumerate(sch.guides):
        ids += [f"s-gb{k}", f"s-gh{k}"] + ([f"s-guide{k}", f"s-stem{k}"] if gd.link != link else [])
    ids += [i for i in els if i.startswith(("s-sup", "s-cyl"))]
    out = []
    for i in ids:
        if i in els:
            s = _shape(els[i])
            out.append((i, s.boundary if s.geom_type == "Polygon" else s))
    return out


@pytest.mark.parametrize("stem", sorted(EX))
def test_every_drive_arc_arrow_is_short_and_clear_of_the_other_links(stem):
    """ω, ε arc arrows on every scheme of every example (every analysed position): radius (the
    drawn arc's distance from the pivot's pin, or a coupler's middle) at most ARC_MAX_MM = 15 mm and at least 4 mm, and
    0.8 mm or more from every line of another link (a 0.5 mm bar's edge clears a 0.25 mm arc).
    Before: tangent_mechanism's ω1 was 154 mm, whitworth's at 60° 56.6 mm across the slot."""
    motion, mu = _solve(EX[stem])
    for i in range(len(motion)):
        sch = scheme(motion, i, mu)
        els, _ = _svg(sch)
        for arc in sch.arcs:
            if arc.kind == "phi":
                continue
            key = f"s-{arc.kind}{arc.link}"
            dist = np.linalg.norm(np.array(_path_points(els[key].get("d"))) - _centre(sch, els, arc.link), axis=1)
            r = float(dist.max())
            assert r - float(dist.min()) < 2 * ROUND_MM               # a circle about the centre
            assert r == pytest.approx(arc.radius, abs=2 * ROUND_MM)   # the drawn arc is the constructed one
            assert 4.0 <= r <= ARC_MAX_MM + ROUND_MM, (stem, i, key, r)
            drawn = _shape(els[key]).union(_shape(els[f"{key}h"]))
            for other, line in _other_lines(sch, els, arc.link):
                assert drawn.distance(line) >= 0.8, (stem, i, key, other, drawn.distance(line))


# -- 25. a ram's positions: ticks on its guide, blocks at the extremes -----------------------------

def _label_box(el, markup: str):
    """The box of label ``el`` (paper mm), written ``markup`` (its subscripts sized as drawn)."""
    return box(runs(markup, digits=False), float(el.get("font-size")), el.get("font-style") == "italic",
               float(el.get("x")), float(el.get("y")))


def test_the_press_positions_are_ticks_with_numbers_and_blocks_at_the_extremes():
    """six_link_press-positions: 12 positions of ram 5 within 21.4 mm of guide. No two drawn
    blocks overlap (two, at E′ and E″); each position is a tick across the guide at the end of
    rod 4 of that position, and its number E_i either lies within LABEL_NEAR_MM of the tick's
    end or has a leader from the tick's end to its box. (Before: 12 blocks stacked on each
    other and E0 … E11 in two columns with no ticks or leaders.)"""
    svg = plans.render(EX["six_link_press"])["positions"].svg
    root = ET.fromstring(svg)
    els = {el.get("id"): el for el in root.iter() if el.get("id")}
    blocks = [_shape(el) for i, el in els.items() if "-block" in i]
    assert len(blocks) == 2
    for j in range(len(blocks)):
        for k in range(j):
            assert blocks[j].intersection(blocks[k]).area < 1e-9
    leaders = [el for el in root.iter(f"{NS}line") if el.get("class") == "leader"]
    for i in range(12):
        tick = _shape(els[f"positions-tick{i}"])
        assert tick.length == pytest.approx(TICK_MM, abs=2 * ROUND_MM)
        rod = _shape(els[f"positions-pos{i}-link4"])               # rod CE of position i ends at E_i
        assert tick.centroid.distance(shapely.Point(rod.coords[-1])) < 2 * ROUND_MM
        label = els[f"positions-o{i}"]
        assert "".join(label.itertext()) == f"E{i}"
        b = _label_box(label, f"E_{{{i}}}")
        rect = shapely.box(b.x0, b.y0, b.x1, b.y1)
        if rect.distance(tick) <= LABEL_NEAR_MM + ROUND_MM:
            continue
        led = [el for el in leaders if el.get("id") == f"positions-ol{i}"]
        assert led, f"E{i} is {rect.distance(tick):.1f} mm from its tick, with no leader"
        start, end = (shapely.Point(p) for p in _line_ends(led[0]))
        assert start.distance(tick) < 2 * ROUND_MM and end.distance(rect) < 2 * ROUND_MM

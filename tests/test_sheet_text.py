"""Text a teacher prints (issue 20, items 6 and 7): a title-block value stays in its cell —
shrunk, then wrapped on two lines —, the drive's angles are listed in 0 … 360°, and no sheet
writes centre- or end-aligned text with subscripts (cairosvg misplaces such text in PNG/PDF:
the construct is never written)."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import pytest

from conftest import EXAMPLES
from plans.cli import main
from plans.drawing import Style
from plans.drawing.sheet import FORMATS, METRIC_MARGIN, TitleBlock, new_sheet
from plans.drawing.text import box, runs

SVG = "{http://www.w3.org/2000/svg}"


def _title_texts(svg: str) -> list[tuple[str, float, float, float]]:
    """(text, x, baseline y, font size) of the title block's texts."""
    root = ET.fromstring(svg)
    g = next(e for e in root.iter(f"{SVG}g") if (e.get("id") or "").endswith("-title-text"))
    return [("".join(t.itertext()), float(t.get("x")), float(t.get("y")), float(t.get("font-size")))
            for t in g.iter(f"{SVG}text")]


@pytest.mark.parametrize("count", [3, 12, 24, 36])
def test_a_long_position_stays_in_its_cell(count):
    long = "φ_{1} = " + ", ".join(f"{k * 10}°" for k in range(count)) + ", ω_{1} = 6 rad/s, ε_{1} = 0 rad/s²"
    dwg, _ = new_sheet(FORMATS[2], (0, 0, 1, 1), ident="t", style=Style(),
                       block=TitleBlock("Mechanism", "Sheet", long, "μ_l = 0.005 m/mm"))
    texts = _title_texts(dwg.tostring())
    bx0, bx1 = 420.0 - 5.0 - 185.0, 420.0 - 5.0
    row_top, row_bottom = 297.0 - 5.0 - 35.0 + 11.0 + 8.0, 297.0 - 5.0 - 35.0 + 11.0 + 16.0
    rows = [t for t in texts if row_top < t[2] < row_bottom and t[1] > bx0 + 22.0]
    assert rows
    assert len(rows) <= 2
    for text, x, y, size in rows:
        assert size >= 2.0
        b = box(runs(text), size, False, x, y)
        # inside the cell, with the margin left for renderers' wider fonts (a few per cent)
        assert bx0 + 22.0 < b.x0 and b.x1 - b.x0 <= (bx1 - bx0 - 22.0) * (METRIC_MARGIN + 0.03)
        assert row_top <= b.y0 and b.y1 <= row_bottom
    if count >= 24:
        assert len(rows) == 2 or rows[0][0].endswith("…")


def test_assignment_lists_angles_within_a_turn(tmp_path):
    """six_link_press, three random variants (seed 1): its positions every 30° from 40° read
    … 340°, 10° — not 370°."""
    assert main(["handout", str(next(p for p in EXAMPLES if p.stem == "six_link_press")), "--random", "3",
                 "--seed", "1", "-o", str(tmp_path), "-q"]) == 0
    for svg in tmp_path.glob("variant-*/variant-*-assignment.svg"):
        text = svg.read_text(encoding="utf-8")
        angles = [float(a) for a in re.findall(r"(-?\d+(?:\.\d+)?)°", text)]
        assert angles and all(0.0 <= a < 360.0 for a in angles), svg.name


def test_no_aligned_text_with_subscripts_in_the_gallery(rendered):
    """Every sheet of every example: a <text> anchored "middle" or "end" holds one run only."""
    assert list(rendered.glob("*.svg"))
    found = _aligned_runs(rendered)
    assert not found, found[:5]


def _aligned_runs(folder) -> list[str]:
    """The texts anchored "middle" or "end" with more than one run, of every SVG below ``folder``."""
    found = []
    for svg in sorted(folder.rglob("*.svg")):
        root = ET.fromstring(svg.read_text(encoding="utf-8"))
        for t in root.iter(f"{SVG}text"):
            if t.get("text-anchor") in ("middle", "end") and len(list(t.iter(f"{SVG}tspan"))) > 1:
                found.append(f"{svg.name}: {''.join(t.itertext())}")
    return found


def test_no_aligned_text_with_subscripts_on_gear_and_handout_sheets(tmp_path, demo_rendered):
    """The same rule on the sheets outside the linkage gallery: every gear example's sheets (from
    the suite's one demo render) and the assignment sheets of each kind of handout (kinematics,
    forces, gears, dynamics)."""
    import shutil
    from pathlib import Path

    from plans.cli import main

    from conftest import stem_of

    root = Path(__file__).resolve().parent.parent / "examples"
    gears = {p.stem for p in (root / "gears").glob("*.toml")}
    (tmp_path / "gears").mkdir()
    for path in demo_rendered.glob("*.svg"):
        if stem_of(path.name) in gears:
            shutil.copyfile(path, tmp_path / "gears" / path.name)
    for k, base in enumerate(("four_bar.toml", "six_link_press_forces.toml", "gears/planetary_1_21.toml",
                              "six_link_press_flywheel.toml")):
        assert main(["handout", str(root / base), "--random", "1", "-o", str(tmp_path / f"h{k}"), "-q"]) == 0
    sheets = list(tmp_path.rglob("*.svg"))
    assert len(sheets) > 20 and sum(p.name.endswith("-assignment.svg") for p in sheets) == 4
    found = _aligned_runs(tmp_path)
    assert not found, found[:5]

"""Render time linear in the mechanism (issue 30): a fan of four-bar dyads on one crank pin
(:mod:`plans.bench.fan`) rendered at two sizes, each stage of the render timed in one run.

Timing: CPU seconds of this process (``time.process_time``, which the other processes on the
cores do not count), the best of a few renders of each size, the sizes alternated. The sizes
are 10 and 40 dyads (22 and 82 links), two doublings apart: a stage passes when its time grows
by at most 2.5× per doubling, (t40 / t10) ** (1 / 2) ≤ 2.5. Over two doublings, not one, because
a fixed-size sheet fills up as the fan grows and the label placer's work per label grows with
it until the sheet is full (more labels need the far candidates): a single doubling can fall
on that step, two even it out; a stage quadratic in the mechanism grows 4× per doubling and
fails either way. The JSON report holds one instantaneous centre per pair of links (their
number squared, by definition), so its two stages are timed per report entry. Stages of under
2 ms at 40 dyads are not judged (rounding of the clock, not the code).

The other tests check that the indexes which make the searches linear give the answers of
the plain searches they replace.
"""

from __future__ import annotations

import math
import random
import tomllib

import numpy as np
import pytest
import shapely

import plans
from plans.bench.fan import STAGES, fan_links, fan_report_entries, fan_scene, stage_times
from plans.drawing.sheet import _fit
from plans.drawing.text import runs, width
from plans.kinematics import centres as centres_module
from plans.spatial import BoxGrid, PointGrid, PointRaster, segments_meet_boxes

SMALL, LARGE = 10, 40
#: Most growth of a stage's time per doubling of the mechanism.
MOST_PER_DOUBLING = 2.5
#: Repeats of each size (the best is kept).
REPEATS = 4
#: Stages shorter than this at LARGE dyads are not judged, s.
FLOOR_S = 0.002
#: Stages timed per entry of the report, not per render.
PER_ENTRY = ("report", "json")


def test_fan_assembles_and_turns_fully():
    """Every dyad assembles at every crank angle of a turn (Grashof crank-rocker, turned)."""
    text = fan_scene(5).replace("angle = 30.0", "angle = [" + ", ".join(f"{a}.0" for a in range(0, 360, 30)) + "]")
    sheets = plans.render(plans.parse_scene(tomllib.loads(text)), stem="fan5")
    assert len(sheets.report["positions"]) == 12
    assert len(sheets.report["positions"][0]["links"]) == fan_links(5)
    for pos in sheets.report["positions"]:
        for i in range(1, 6):
            b, c = np.array(pos["points"][f"B{i}"]["r"]), np.array(pos["points"][f"C{i}"]["r"])
            assert math.isclose(float(np.hypot(*(b - c))), 0.2, rel_tol=1e-9)


def test_render_stages_grow_linearly():
    best: dict[int, dict[str, float]] = {}
    stage_times(2)   # imports and first-call costs: not timed
    for _ in range(REPEATS):
        for n in (SMALL, LARGE):
            t = stage_times(n)
            best[n] = t if n not in best else {k: min(best[n][k], v) for k, v in t.items()}
    growth = {}
    for name in (*STAGES, "total"):
        small, large = best[SMALL][name], best[LARGE][name]
        if large < FLOOR_S:
            continue
        if name in PER_ENTRY:
            small, large = small / fan_report_entries(SMALL), large / fan_report_entries(LARGE)
        growth[name] = math.sqrt(large / max(small, 1e-9))
    assert {"plans", "labels", "pole detail", "scheme", "total"} <= set(growth), growth
    slow = {k: round(g, 2) for k, g in growth.items() if g > MOST_PER_DOUBLING}
    assert not slow, (f"stages growing more than {MOST_PER_DOUBLING}× per doubling of the fan: {slow}; "
                      f"all: { {k: round(g, 2) for k, g in growth.items()} }; seconds: {best}")


# --- the fast paths answer as the plain searches --------------------------------------------

def test_segments_meet_boxes_is_shapely_intersects():
    rng = np.random.default_rng(7)
    n = 20000
    ends = rng.uniform(0, 20, (n, 4))
    ends[:500, 2:] = ends[:500, :2]                              # points
    x0, y0 = rng.uniform(0, 20, n), rng.uniform(0, 20, n)
    x0[500:1000], y0[500:1000] = ends[500:1000, 0], ends[500:1000, 1]   # a corner on the segment's end
    boxes = np.stack([x0, y0, x0 + rng.uniform(0, 4, n), y0 + rng.uniform(0, 4, n)], axis=1)
    ends[1000:1500, 1] = ends[1000:1500, 3] = boxes[1000:1500, 1]      # along the box's edge
    expected = shapely.intersects(shapely.linestrings(ends.reshape(-1, 2, 2)), shapely.box(*boxes.T))
    assert np.array_equal(segments_meet_boxes(ends, boxes), expected)


def test_point_raster_counts_only_points_inside():
    rng = np.random.default_rng(3)
    pts = rng.uniform(0, 50, (3000, 2))
    raster = PointRaster.of(pts, (0.0, 0.0, 50.0, 50.0), 0.5)
    x0, y0 = rng.uniform(-5, 50, 500), rng.uniform(-5, 50, 500)
    x1, y1 = x0 + rng.uniform(0, 8, 500), y0 + rng.uniform(0, 8, 500)
    inside = ((pts[None, :, 0] >= x0[:, None]) & (pts[None, :, 0] <= x1[:, None])
              & (pts[None, :, 1] >= y0[:, None]) & (pts[None, :, 1] <= y1[:, None])).sum(axis=1)
    counted = raster.count_inside(x0, y0, x1, y1)
    assert np.all(counted <= inside) and np.any(counted > 0)
    # a box of whole cells counts exactly
    assert raster.count_inside(np.array([10.0]), np.array([10.0]), np.array([20.0]), np.array([15.0]))[0] == \
        int(((pts[:, 0] >= 10) & (pts[:, 0] < 20) & (pts[:, 1] >= 10) & (pts[:, 1] < 15)).sum())


def test_grids_find_every_near_item():
    rng = random.Random(11)
    boxes, grid = [], BoxGrid(10.0)
    points, near = [], PointGrid(0.3)
    for _ in range(400):
        x, y = rng.uniform(0, 200), rng.uniform(0, 200)
        boxes.append((x, y, x + rng.uniform(0, 30), y + rng.uniform(0, 5)))
        grid.add(boxes[-1])
        points.append((x, y))
        near.add((x, y))
    for _ in range(200):
        x, y = rng.uniform(0, 200), rng.uniform(0, 200)
        q = (x, y, x + 12.0, y + 4.0)
        found = set(grid.near(*q).tolist())
        meets = {k for k, b in enumerate(boxes) if b[0] <= q[2] and q[0] <= b[2] and b[1] <= q[3] and q[1] <= b[3]}
        assert meets <= found
        assert {k for k, p in enumerate(points) if math.dist(p, (x, y)) <= 0.3} <= set(near.near((x, y)))
        assert near.near((x, y)) == sorted(near.near((x, y)))


def test_title_fit_cuts_where_the_plain_loop_does():
    def plain_fit(text: str, room: float, size: float, smallest: float) -> tuple[str, float]:
        w = width(runs(text), size, False)
        if w <= room:
            return text, size
        if w * smallest / size <= room:
            return text, size * room / w
        while text and width(runs(text + "…"), smallest, False) > room:
            text = text[:-1]
        return text.rstrip() + "…", smallest

    rng = random.Random(5)
    alphabet = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJ0123456789 ()-←ΙΠ≡′μ·,.WMjli_{}"
    for _ in range(300):
        text = "".join(rng.choice(alphabet) for _ in range(rng.randint(0, 400)))
        if rng.random() < 0.4:
            text = text.replace("_", "").replace("{", "").replace("}", "")
        room, size = rng.uniform(1, 200), rng.uniform(2, 5)
        assert _fit(text, room, size, 2.0) == plain_fit(text, room, size, 2.0)


@pytest.mark.parametrize("scene", ["fan", "examples/watt_six_bar.toml", "examples/whitworth.toml"])
def test_relative_centres_are_the_pairwise_ones(scene):
    """The centres of all pairs, found link by link, are those of each pair alone, bit for bit."""
    source = plans.parse_scene(tomllib.loads(fan_scene(6))) if scene == "fan" else scene
    motion = plans.render(source, stem="c").motion
    found = centres_module.centres(motion)
    scale = motion.rate_scale(1)
    for (a, b), centre in found.relative.items():
        alone = centres_module._centre(motion, a, b, scale)
        for field in ("point", "direction", "rest"):
            assert getattr(centre, field).tobytes() == getattr(alone, field).tobytes(), (a, b, field)

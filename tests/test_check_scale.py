"""plans check on hostile files: vectors nested thousands of groups deep and many vectors
sharing one label are checked in one pass (results as on small files), and what is refused
deep down — a transform far above a vector, a vector inside a non-group element — still is."""

from __future__ import annotations

import itertools
import math
import random

from plans.bench.sections.check_scale import hostile_svg
from plans.checking import _diameter, inspect_svg


def _write(tmp_path, text, name="f.svg"):
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


def test_the_diameter_of_many_points_is_the_largest_pairwise_distance():
    rng = random.Random(3)
    for n in (2, 10, 65, 300):
        pts = [(rng.uniform(-5, 5), rng.uniform(-5, 5)) for _ in range(n)]
        brute = max(math.dist(a, b) for a, b in itertools.product(pts, pts))
        assert abs(_diameter(pts) - brute) < 1e-12
    assert _diameter([(1.0, 1.0)] * 500) == 0.0
    assert abs(_diameter([(0.0, 0.0)] * 300 + [(3.0, 4.0)]) - 5.0) < 1e-12


def test_vectors_sharing_one_label_close_and_one_astray_is_found(tmp_path):
    text = hostile_svg("shared", 5000)
    r = inspect_svg(_write(tmp_path, text))
    assert r.ok and len(r.measurements) == 5000 and all(m.ok for m in r.measurements)
    astray = text.replace('x2="20" y2="10"', 'x2="20" y2="13"', 1)     # one head 3 mm off (and its length)
    r = inspect_svg(_write(tmp_path, astray, "g.svg"))
    bad = [c for c in r.closures if not c.ok]
    assert len(bad) == 1 and abs(bad[0].gap_mm - 3.0) < 1e-9


def test_deep_nesting_is_checked_in_one_pass(tmp_path):
    r = inspect_svg(_write(tmp_path, hostile_svg("nested", 20000)))
    assert r.ok and len(r.measurements) == 20000


def test_a_transform_far_above_and_a_non_group_parent_are_still_refused(tmp_path):
    text = hostile_svg("nested", 3000).replace('<g id="g5">', '<g id="g5" transform="scale(2)">', 1)
    r = inspect_svg(_write(tmp_path, text))
    assert any("transform on <g id='g5'>" in p for p in r.problems)
    assert sum("transform" in p for p in r.problems) == 3000 - 5       # every vector below it
    line = ('<line data-quantity="v:A{k}" data-value="0.1" data-direction="0.0" x1="10" y1="10" x2="20" y2="10" '
            'data-from="p" data-to="a{k}"/>')
    n = 50
    opening = "".join(f'<g id="g{k}">' + ("<a>" if k == 10 else "") + line.format(k=k) for k in range(n))
    closing = "".join(("</a>" if k == 10 else "") + "</g>" for k in reversed(range(n)))
    head = hostile_svg("nested", 0).removesuffix("</g></svg>")
    r = inspect_svg(_write(tmp_path, head + opening + closing + "</g></svg>", "a.svg"))
    assert sum("inside <a>" in p for p in r.problems) == n - 10       # every vector below the <a>

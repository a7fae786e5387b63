"""The gallery comparison (tests/gallery.py) lets rounding through and nothing a user can see."""

from __future__ import annotations

import math
import re

import pytest

from gallery import RTOL, difference, stale

FULL = re.compile(r"-?\d+\.\d{12,}(?:e-?\d+)?")


def _nudge(text: str, ulps: int) -> str:
    """Every full-precision number of text moved by ``ulps`` units in its last place."""
    def one(m: re.Match) -> str:
        x = float(m.group(0))
        for _ in range(abs(ulps)):
            x = math.nextafter(x, math.inf if ulps > 0 else -math.inf)
        return repr(x)
    return FULL.sub(one, text)


@pytest.mark.parametrize("name", ["crank_slider_central.json", "quick_return-acceleration-30.svg"])
def test_last_bits_pass(rendered, name):
    text = (rendered / name).read_text(encoding="utf-8")
    nudged = _nudge(text, 4)
    assert nudged != text
    assert difference(text, nudged) is None


def test_rounded_coordinate_one_digit_over_passes():
    assert difference('<line x1="61.501" y1="3"/>', '<line x1="61.502" y1="3"/>') is None


def test_rounding_noise_around_zero_passes():
    old = '{"v": [1.25, 1.941329317582808e-18], "a": 3.5}'
    new = '{"v": [1.25, -3.936745023113076e-18], "a": 3.5}'
    assert difference(old, new) is None


@pytest.mark.parametrize("old, new", [
    ('<text x="1.5">v<tspan>B</tspan></text>', '<text x="1.5">v<tspan>C</tspan></text>'),   # a label
    ('<line x1="61.501" y1="3"/>', '<line x1="61.511" y1="3"/>'),                           # moved 0.01 mm
    ('{"mu_v": 0.013460784593870148}', '{"mu_v": 0.013460798054654742}'),                 # 1e-6 off
    ('{"v": 0.13460784593870148}', f'{{"v": {0.13460784593870148 * (1 + 100 * RTOL)!r}}}'),
    ('{"evaluations": 20498}', '{"evaluations": 20499}'),                                  # an integer
    ('<g id="velocity-30-l1"/>', '<g id="velocity-30-l2"/>'),                              # an id
    ('<line x1="1.5"/>', '<line x1="1.5"/><line x1="2.5"/>'),                             # a new element
])
def test_what_a_user_sees_fails(old, new):
    assert difference(old, new) is not None


def test_vector_moved_on_a_real_sheet_fails(rendered):
    text = (rendered / "crank_slider_central-velocity.svg").read_text(encoding="utf-8")
    moved = re.sub(r'(data-quantity="v:B"[^>]*x2=")([-0-9.]+)',
                   lambda m: m.group(1) + f"{float(m.group(2)) + 0.05:.3f}", text, count=1)
    if moved == text:
        moved = re.sub(r'(x2=")([-0-9.]+)("[^>]*data-quantity="v:B")',
                       lambda m: m.group(1) + f"{float(m.group(2)) + 0.05:.3f}" + m.group(3), text, count=1)
    assert moved != text
    assert difference(text, moved) is not None


def test_missing_and_changed_files_are_listed(tmp_path):
    (tmp_path / "a.json").write_text('{"x": 1.0}', encoding="utf-8")
    (tmp_path / "b.json").write_text('{"x": 1.0}', encoding="utf-8")
    out = stale(tmp_path, {"a.json": '{"x": 1.0}', "b.json": '{"x": 2.0}', "c.svg": "<svg/>"})
    assert [o.split(":")[0] for o in out] == ["b.json", "c.svg"]

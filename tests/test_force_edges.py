"""Force sheets at their edges: a lever or force plans with no load in effect, a mechanism at
rest, a balancing element that is exactly or nearly zero (a dead centre, an extreme position of
the ram), and the press's cycle from its extreme with 4 kN on the ram. Every sheet asked for is
written (saying why it is empty, with a warning), and ``plans check`` passes on all of them."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from plans.checking import inspect_svg
from plans.cli import main

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
DRAW_ALL = 'draw = ["scheme", "velocity", "acceleration", "centres", "forces", "lever"]'


def _crank_slider(loads: str, *, draw: str = '["scheme", "velocity", "forces", "lever"]',
                  angles: str = "[45.0, 120.0]", omega: str = "10.0") -> str:
    text = (EXAMPLES / "crank_slider_forces.toml").read_text(encoding="utf-8")
    head = text.split("[masses.1]")[0].replace("gravity = 9.81  # m/s², acting -y\n", "")
    head = head.replace("angle = [45.0, 120.0]", f"angle = {angles}").replace("omega = 10.0", f"omega = {omega}")
    return head + loads + f"\n[plans]\ndraw = {draw}\n"


def _render(tmp_path: Path, text: str, capsys) -> tuple[Path, str]:
    scene = tmp_path / "s.toml"
    scene.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    assert main(["render", str(scene), "-o", str(out), "-q"]) == 0
    return out, capsys.readouterr().err


def _all_checked(out: Path) -> None:
    for svg in sorted(out.glob("*.svg")):
        r = inspect_svg(svg)
        assert r.ok, (svg.name, r.problems, [c for c in r.checks if not c.ok], [m for m in r.measurements if not m.ok])


NO_LOAD = {
    "no loads at all": "",
    "every mass zero": '[masses.1]\nmass = 0.0\ncentre = "S1"\n[masses.2]\nmass = 0.0\ncentre = "C"\n',
    "a force that rounds away": '[[forces]]\nlink = "3"\nat = "B"\nmagnitude = 1e-300\nangle = 180.0\n',
}


@pytest.mark.parametrize("case", sorted(NO_LOAD))
def test_a_lever_with_no_load_is_drawn_with_a_zero_balance_and_a_warning(case, tmp_path, capsys):
    out, err = _render(tmp_path, _crank_slider(NO_LOAD[case]), capsys)
    for angle in (45, 120):
        assert (out / f"s-lever-{angle}.svg").exists() and (out / f"s-forces-{angle}.svg").exists()
    assert "Zhukovsky's lever at 45°, 120°" in err and "warning:" in err
    data = json.loads((out / "s.json").read_text(encoding="utf-8"))
    for pos in data["positions"]:
        assert abs(pos["forces"]["lever"]["moment"]) < 1e-250 and abs(pos["forces"]["balance"]["moment"]) < 1e-250
    _all_checked(out)


def test_force_plans_with_no_load_are_a_sheet_saying_so(tmp_path, capsys):
    out, err = _render(tmp_path, _crank_slider("", draw='["scheme", "forces"]'), capsys)
    for angle in (45, 120):
        svg = out / f"s-forces-{angle}.svg"
        assert svg.exists() and "no load in effect" in svg.read_text(encoding="utf-8")
        assert inspect_svg(svg).kind == "empty"
    assert "force plans at 45°, 120°: no load in effect" in err


def test_a_lever_of_a_mechanism_at_rest_is_a_sheet_saying_so(tmp_path, capsys):
    loads = '[[forces]]\nlink = "3"\nat = "B"\nmagnitude = 100.0\nangle = 180.0\n'
    out, err = _render(tmp_path, _crank_slider(loads, omega="0.0"), capsys)
    for angle in (45, 120):
        svg = out / f"s-lever-{angle}.svg"
        assert svg.exists() and "at rest" in svg.read_text(encoding="utf-8")
    assert "Zhukovsky's lever at 45°, 120°: the mechanism is at rest" in err
    _all_checked(out)


def test_a_zero_balancing_moment_at_a_dead_centre_passes_check(tmp_path, capsys):
    loads = '[[forces]]\nlink = "3"\nat = "B"\nmagnitude = 100.0\nangle = 180.0\n'
    out, _ = _render(tmp_path, _crank_slider(loads, angles="[0.0, 90.0]"), capsys)
    data = json.loads((out / "s.json").read_text(encoding="utf-8"))
    assert abs(data["positions"][0]["forces"]["balance"]["moment"]) < 1e-12    # the slider is at rest: no work
    _all_checked(out)


def test_whitworth_near_the_rams_extreme_agrees_within_the_loads_scale(tmp_path, capsys):
    text = (EXAMPLES / "whitworth.toml").read_text(encoding="utf-8")
    text = text.replace('draw = ["scheme", "velocity", "acceleration", "centres"]', 'draw = ["scheme", "forces", "lever"]')
    text += '\n[[forces]]\nlink = "5"\nat = "E"\nvector = [-100.0, 0.0]\n'
    out, _ = _render(tmp_path, text, capsys)
    assert (out / "s-lever-330.svg").exists()
    data = json.loads((out / "s.json").read_text(encoding="utf-8"))
    at330 = data["positions"][3]["forces"]
    value = next(v for k, v in at330["balance"].items() if k in ("moment", "force"))
    assert abs(value if isinstance(value, float) else max(map(abs, value))) < 1e-6   # the ram near its extreme
    _all_checked(out)


def test_the_press_cycle_from_its_extreme_with_4kN_renders_every_force_and_lever_sheet(tmp_path, capsys):
    text = (EXAMPLES / "six_link_press.toml").read_text(encoding="utf-8")
    text = text.replace("angle = 60.0      # the first of the positions (the sketch's angle)\n", 'start = "extreme"\n')
    text = text.replace('draw = ["scheme", "velocity", "acceleration", "positions", "diagrams", "velocities"]',
                        'draw = ["scheme", "forces", "lever", "positions"]').replace("at = [0, 3]", "")
    text += '\n[[forces]]\nlink = "5"\nat = "E"\nvector = [0.0, 4000.0]\n'
    assert 'start = "extreme"' in text and '"lever"' in text
    out, _ = _render(tmp_path, text, capsys)
    data = json.loads((out / "s.json").read_text(encoding="utf-8"))
    angles = [p["angle"] for p in data["positions"]]
    assert len(angles) == 12
    for a in angles:
        suffix = f"{a:g}"
        assert (out / f"s-forces-{suffix}.svg").exists() and (out / f"s-lever-{suffix}.svg").exists(), suffix
    _all_checked(out)

"""A mechanism at rest, a sheet that cannot be drawn: warnings, not refusals.

A crank or a linear drive at rest renders with one warning (no plan to draw to a scale, zero
velocities; ε1 ≠ 0 still draws the acceleration plan); Koshel's sheet that cannot be drawn, or
fails its geometric check, says so on that sheet and every other sheet is drawn. A main plan
that fails its check stays an error: one line, exit 2, nothing written.
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import pytest

import plans.pipeline.sheets.koshel
import plans.pipeline.sheets.plans
from plans.cli import main
from plans.constructions.plans import ConstructionLine
from plans.errors import ConstructionError

from bad_input_cases import KOSHEL, LINEAR, _render_into, edit


# --- 12. a mechanism at rest -----------------------------------------------------------------

def _render_ok(tmp_path: Path, text: str, capsys, name: str = "rest") -> tuple[Path, list[str]]:
    scene = tmp_path / f"{name}.toml"
    scene.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    assert main(["render", str(scene), "-o", str(out), "-q"]) == 0
    err = capsys.readouterr().err.strip().splitlines()
    assert all(line.startswith("warning: ") for line in err), err
    return out, err


def test_crank_at_rest(tmp_path, capsys):
    out, err = _render_ok(tmp_path, edit("omega = 10.0", "omega = 0.0"), capsys)
    assert len(err) == 1 and "at rest" in err[0] and "ω1 = 0" in err[0]
    data = json.loads((out / "rest.json").read_text(encoding="utf-8"))
    pos = data["positions"][0]
    assert all(p["v"] == [0.0, 0.0] and p["a"] == [0.0, 0.0] for p in pos["points"].values())
    assert all(l["omega"] == 0.0 and l["epsilon"] == 0.0 for l in pos["links"].values())
    assert set(pos["scales"]) == {"mu_l"}            # no plan to draw to a scale
    for kind in ("velocity", "acceleration"):
        svg = (out / f"rest-{kind}.svg").read_text(encoding="utf-8")
        assert "at rest" in svg and "data-quantity" not in svg and "nan" not in svg
    assert main(["check", *map(str, sorted(out.glob("*.svg")))]) == 0


def test_crank_at_rest_with_an_angular_acceleration(tmp_path, capsys):
    """ω1 = 0, ε1 ≠ 0: velocities are zero, accelerations are not and their plan is drawn."""
    text = edit("epsilon = 0.0", "epsilon = 5.0", edit("omega = 10.0", "omega = 0.0"))
    out, err = _render_ok(tmp_path, text, capsys)
    assert len(err) == 1 and "velocit" in err[0] and "acceleration plan" not in err[0]
    data = json.loads((out / "rest.json").read_text(encoding="utf-8"))
    pos = data["positions"][0]
    assert set(pos["scales"]) == {"mu_l", "mu_a"}
    x, y = pos["points"]["A"]["r"]
    assert pos["points"]["A"]["a"] == pytest.approx([-5.0 * y, 5.0 * x], abs=1e-15)   # ε × r, no ω² r
    assert "at rest" in (out / "rest-velocity.svg").read_text(encoding="utf-8")
    assert "data-quantity" in (out / "rest-acceleration.svg").read_text(encoding="utf-8")
    capsys.readouterr()
    assert main(["check", *map(str, sorted(out.glob("*.svg")))]) == 0


def test_linear_drive_at_rest(tmp_path, capsys):
    out, err = _render_ok(tmp_path, edit("velocity = 1.0", "velocity = 0.0", LINEAR), capsys)
    assert len(err) == 1 and "v = 0" in err[0]
    pos = json.loads((out / "rest.json").read_text(encoding="utf-8"))["positions"][0]
    assert all(p["v"] == [0.0, 0.0] for p in pos["points"].values())


# --- 13. Koshel's sheet that cannot be drawn -------------------------------------------------

def test_koshel_construction_error_keeps_every_other_sheet(tmp_path, capsys, monkeypatch):
    real = plans.pipeline.sheets.koshel.uncertain_plan

    def degenerate(motion, i, g):
        if i == 1:
            raise ConstructionError("a test degeneracy")
        return real(motion, i, g)

    monkeypatch.setattr(plans.pipeline.sheets.koshel, "uncertain_plan", degenerate)
    out, err = _render_ok(tmp_path, KOSHEL.read_text(encoding="utf-8"), capsys, name="k")
    assert len(err) == 1 and "Koshel" in err[0] and "a test degeneracy" in err[0]
    angles = json.loads((out / "k.json").read_text(encoding="utf-8"))["positions"]
    for kind in ("scheme", "velocity", "acceleration", "koshel"):
        assert len(list(out.glob(f"k-{kind}-*.svg"))) == len(angles), kind
    second = f"{angles[1]['angle']:g}"
    assert "a test degeneracy" in (out / f"k-koshel-{second}.svg").read_text(encoding="utf-8")
    assert main(["check", *map(str, sorted(out.glob("*.svg")))]) == 0


def test_koshel_check_failure_is_a_sheet_not_a_refusal(tmp_path, capsys, monkeypatch):
    """Koshel's plan with a construction line off its vector fails check_plan: that sheet says
    so, every other sheet is drawn."""
    real = plans.pipeline.sheets.koshel.uncertain_plan

    def off_line(motion, i, g):
        plan = real(motion, i, g)
        v = plan.vectors[0]
        wrong = ConstructionLine((1000.0, 1000.0), (1001.0, 1000.0), v.quantity, "test")
        return dataclasses.replace(plan, lines=plan.lines + (wrong,))

    monkeypatch.setattr(plans.pipeline.sheets.koshel, "uncertain_plan", off_line)
    out, err = _render_ok(tmp_path, KOSHEL.read_text(encoding="utf-8"), capsys, name="k")
    koshel = sorted(out.glob("k-koshel-*.svg"))
    assert len(err) == len(koshel) > 0 and all("Koshel" in e and "geometric check" in e for e in err)
    assert len(list(out.glob("k-velocity-*.svg"))) == len(koshel)
    assert all("geometric check" in p.read_text(encoding="utf-8") for p in koshel)


def test_main_plan_check_failure_stays_an_error(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(plans.pipeline.sheets.plans, "check_plan", lambda plan, *a, **k: ["a test failure"])
    line = _render_into(tmp_path, tmp_path / "out", capsys)
    assert "a test failure" in line and "please report" in line
    assert not (tmp_path / "out").exists()

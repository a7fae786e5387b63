"""``plans bench --quick``: the tables, charts and bench.json are produced and every figure is
sane; the default run and ``--full`` measure what they promise (checked on their configurations,
not run). No time is asserted, only that times are positive and finite: how fast a machine is
belongs in the bench's report, not in a test."""

from __future__ import annotations

import builtins
import contextlib
import io
import json
import math
import xml.etree.ElementTree as ET

import pytest

import plans.bench as bench_module
from plans.bench import DEFAULT, FULL, QUICK, format_table
from plans.bench.chart import Chart, Series, draw_chart, ticks
from plans.bench.fan import fan_links
from plans.bench.sections import (AGREEMENT_TARGET, CLASS_COST_TARGET, FAN_FLAT_TARGET, NUMBA_TARGET, SECTIONS,
                                  Column, numba_comparison, peer_comparison)
from plans.bench.sections.common import all_examples
from plans.cli import main

SVG = "{http://www.w3.org/2000/svg}"
TITLES = ("1. Drawing precision", "2. Solver tolerance", "3. Cycle resolution", "4. Throughput",
          "4b. Plans rendered per second", "5. Peer comparison", "6. Crank-slider full kinematics",
          "7. Class III / IV cost per position", "8. A crank that cannot turn fully", "9. A class set",
          "10. plans check on hostile files", "11. Start-up", "12. Render time per link")


def _strict(text: str) -> dict:
    def no_constant(name: str):
        raise ValueError(f"bench.json holds {name}, which is not JSON")
    return json.loads(text, parse_constant=no_constant)


@pytest.fixture(scope="module")
def bench(tmp_path_factory):
    """One quick run through the command line: (stdout, report, output folder)."""
    out = tmp_path_factory.mktemp("bench")
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        assert main(["bench", "--quick", "-o", str(out)]) == 0
    return buf.getvalue(), _strict((out / "bench.json").read_text(encoding="utf-8")), out


def rows(report: dict, key: str) -> list[dict]:
    return report["sections"][key]["rows"]


def test_prints_every_section_and_table(bench):
    text, report, out = bench
    for title in TITLES:
        assert title in text
    assert "worst rel. error" in text and "µs per position" in text and "v rel. error" in text
    assert "vectorised pos/s" in text and "sheets/s" in text
    assert f"to {out}/" in text
    assert report["config"] == "quick"
    assert report["machine"]["cores"] >= 1 and report["machine"]["python"].count(".") == 2
    assert math.isfinite(report["runtime_s"]) and report["runtime_s"] > 0


def test_writes_every_chart_as_an_svg_plot(bench):
    _, report, out = bench
    assert len(report["charts"]) >= 6
    for name in report["charts"]:
        root = ET.parse(out / name).getroot()
        assert root.get("width").endswith("mm") and root.get("viewBox").startswith("0 0 ")
        ids = [e.get("id") for e in root.iter() if e.get("id")]
        assert len(ids) == len(set(ids)), f"{name}: duplicate ids"
        stem = name[:-4]
        assert root.find(f".//{SVG}g[@id='{stem}-ticks']") is not None, f"{name}: no axis ticks"
        labels = [t for t in root.iter(f"{SVG}text") if (t.get("id") or "").startswith(f"{stem}-l")]
        assert len(labels) >= 4, f"{name}: too few tick labels"
        assert root.find(f".//{SVG}text[@id='{stem}-xlabel']").text
        assert root.find(f".//{SVG}text[@id='{stem}-ylabel']").text
        series = [g for g in root.iter(f"{SVG}g") if g.get("data-label")]
        assert series, f"{name}: no data series"


def test_drawing_precision_follows_the_decimals(bench):
    _, report, _ = bench
    r = rows(report, "drawing_precision")
    assert [x["decimals"] for x in r] == list(QUICK.decimals)
    for x in r:
        # two rounded end points: at most 2·√2·(0.5·10^-d) mm on paper, which plans check accepts
        assert 0 < x["worst_error_mm"] <= math.sqrt(2) * 10.0 ** -x["decimals"] * (1 + 1e-9)
        assert x["worst_over_check_tol"] <= 1.0
        assert 0 < x["worst_rel_error"] < 10.0 ** (1 - x["decimals"])
        assert x["vectors"] > 0 and x["kb_per_plan"] > 0 and x["ms_per_sheet"] > 0
    assert r[0]["worst_rel_error"] > r[-1]["worst_rel_error"]
    assert r[0]["kb_per_plan"] <= r[-1]["kb_per_plan"]
    assert report["sections"]["drawing_precision"]["summary"]["all_within_check_tolerance"]


def test_solver_error_follows_the_tolerance(bench):
    _, report, _ = bench
    r = rows(report, "solver_tolerance")
    solvers = sorted({x["solver"] for x in r})
    assert "bench Newton, four-bar" in solvers
    for solver in solvers:
        mine = [x for x in r if x["solver"] == solver]
        assert [x["tolerance"] for x in mine] == list(QUICK.tolerances)
        for x in mine:
            assert x["not_converged"] == 0
            assert x["error_over_size"] <= 100 * x["tolerance"] + 1e-14
            assert x["us_per_position"] > 0 and x["max_iterations"] >= x["mean_iterations"]
        its = [x["mean_iterations"] for x in mine]
        assert its == sorted(its), f"{solver}: a tighter tolerance never takes fewer iterations"
        assert mine[-1]["error_over_size"] < 1e-11


def test_graphical_differentiation_converges_as_h_squared(bench):
    _, report, _ = bench
    r = rows(report, "cycle_resolution")
    assert [x["positions"] for x in r] == list(QUICK.resolutions)
    for a, b in zip(r, r[1:]):
        assert b["v_rel_error"] < a["v_rel_error"] and b["a_rel_error"] < a["a_rel_error"]
        assert 1.7 < b["observed_order_v"] < 2.3
    fine = r[-1]
    assert fine["positions"] == 360
    # Taylor's remainder: a central difference of step h is off by h²/6·s‴(ξ) (the first) and
    # h²/12·s⁗(ξ) (the second), so the relative errors are at most h²/6·max|s‴|/max|s′| and
    # h²/12·max|s⁗|/max|s″|; s(φ) = r·cos φ + √(l² − r²·sin²φ) is the central crank-slider's
    # (r = 0.1, l = 0.4 m), its derivatives by mpmath at every degree (the 1 % covers the maxima
    # between the samples: a smooth maximum sampled every 1° is within ~1e-4 of itself)
    import mpmath

    rod, crank = 0.4, 0.1
    s_of = lambda p: crank * mpmath.cos(p) + mpmath.sqrt(rod ** 2 - (crank * mpmath.sin(p)) ** 2)  # noqa: E731
    top = [float(max(abs(mpmath.diff(s_of, math.radians(k), n)) for k in range(360))) for n in (1, 2, 3, 4)]
    h = math.radians(1.0)
    assert fine["v_rel_error"] <= 1.01 * h * h / 6.0 * top[2] / top[0]
    assert fine["a_rel_error"] <= 1.01 * h * h / 12.0 * top[3] / top[1]
    assert all(x["ms_numeric"] > 0 and x["ms_exact"] > 0 for x in r)


def test_throughput_figures_are_consistent(bench):
    _, report, _ = bench
    r = rows(report, "throughput")
    assert [x["scene"] for x in r] == ["crank_slider_central", "six_link_press"]
    for x in r:
        assert x["positions"] == QUICK.throughput_positions and x["loop_timed_on"] == QUICK.loop_positions
        assert x["vectorised_per_s"] > 0 and x["loop_per_s"] > 0
        assert math.isclose(x["ratio"], x["vectorised_per_s"] / x["loop_per_s"], rel_tol=1e-9)
        assert x["max_rel_difference"] <= 1e-12, "the loop and the vectorised call disagree"
        assert x["target"] == "met" or x["target"].startswith("short ×")
    render = rows(report, "render_rate")
    assert render and all(x["sheets"] >= 3 and x["sheets_per_s"] > 0 for x in render)


def test_peer_comparison_agrees_or_says_how_to_install(bench):
    _, report, _ = bench
    peer = report["sections"]["peer_comparison"]
    if peer["skipped"]:
        assert 'pip install ".[bench]"' in peer["skipped"]
        return
    r = peer["rows"]
    assert {x["scene"] for x in r} == {"crank_slider_central", "four_bar"}
    for x in r:
        assert x["positions"] == QUICK.peer_positions
        assert x["max_dr_m"] < 1e-12, f"{x['scene']}: pylinkage and plans disagree by {x['max_dr_m']} m"
        assert x["plans_ms"] > 0 and x["pylinkage_ms"] > 0
        if x["what"] != "positions":
            assert x["max_dv"] < 1e-10 and x["max_da"] < 1e-9


@pytest.fixture
def without_pylinkage(monkeypatch):
    """Imports of pylinkage fail, as in an install without the bench extra."""
    real = builtins.__import__

    def no_pylinkage(name, *args, **kwargs):
        if name == "pylinkage" or name.startswith("pylinkage."):
            raise ImportError("No module named 'pylinkage'")
        return real(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_pylinkage)


def test_peer_comparison_is_skipped_without_pylinkage(without_pylinkage):
    s = peer_comparison(QUICK)
    assert s.skipped and 'pip install ".[bench]"' in s.skipped and not s.rows and not s.charts


def _positive(x) -> bool:
    return isinstance(x, (int, float)) and math.isfinite(x) and x > 0


def test_numba_comparison_times_both_pylinkage_paths_or_says_not_installed(bench):
    text, report, out = bench
    sec = report["sections"]["numba_comparison"]
    assert not sec["skipped"] and "numba-cost.svg" in report["charts"]
    r = sec["rows"]
    assert [x["positions"] for x in r] == list(QUICK.numba_positions)
    assert sec["summary"]["target"] == NUMBA_TARGET and sec["summary"]["agreement_target"] == AGREEMENT_TARGET
    for x in r:
        assert _positive(x["plans_us_per_position"])
        if sec["summary"]["pylinkage"] is None:
            assert x["pylinkage"] == "pylinkage not installed"
            assert x["numba_us_per_position"] is None and x["pure_python_us_per_position"] is None
            continue
        # the pure-Python path runs in a child process: it is measured whenever pylinkage is installed
        assert _positive(x["pure_python_us_per_position"]), x["pylinkage"]
        assert math.isclose(x["pure_python_over_plans"],
                            x["pure_python_us_per_position"] / x["plans_us_per_position"], rel_tol=1e-9)
        assert 0 <= x["pure_python_max_rel"] < AGREEMENT_TARGET
        if sec["summary"]["numba"] is None:
            assert x["pylinkage"].startswith("numba not installed") and x["numba_us_per_position"] is None
            continue
        assert x["pylinkage"] == "numba + pure Python"
        assert _positive(x["numba_us_per_position"])
        assert math.isclose(x["numba_over_plans"], x["numba_us_per_position"] / x["plans_us_per_position"],
                            rel_tol=1e-9)
        for key in ("numba_dr_rel", "numba_dv_rel", "numba_da_rel"):
            assert 0 <= x[key] < AGREEMENT_TARGET, f"{key}: pylinkage's numba path and plans disagree"
        assert x["target"] == "met" or x["target"].startswith("short ×")
    assert any(h.startswith("crank-slider full kinematics") for h in report["headlines"])


def test_numba_comparison_runs_without_pylinkage(without_pylinkage):
    s = numba_comparison(QUICK)
    assert not s.skipped and len(s.rows) == len(QUICK.numba_positions)
    for x in s.records():
        assert _positive(x["plans_us_per_position"])
        assert x["pylinkage"] == "pylinkage not installed" and x["numba_us_per_position"] is None
    assert any("not installed" in n and 'pip install ".[bench]"' in n for n in s.notes)
    assert [len(c.series) for c in s.charts] == [1]


def test_class_cost_is_per_position_against_the_crank_slider(bench):
    _, report, _ = bench
    sec = report["sections"]["class_cost"]
    assert "class-cost.svg" in report["charts"]
    r = sec["rows"]
    assert [x["scene"] for x in r] == ["crank_slider_central", "class3_six_link", "class4_six_link"]
    assert [x["class"] for x in r] == [2, 3, 4]
    for x in r:
        assert x["positions"] == QUICK.class_positions == 72 and x["large_positions"] == QUICK.class_large_positions
        assert _positive(x["us_per_position"]) and _positive(x["large_us_per_position"])
        assert math.isclose(x["ratio"], x["us_per_position"] / r[0]["us_per_position"], rel_tol=1e-9)
        assert math.isclose(x["large_ratio"], x["large_us_per_position"] / r[0]["large_us_per_position"],
                            rel_tol=1e-9)
    assert r[0]["target"] == "reference" and r[0]["ratio"] == 1.0
    for x in r[1:]:
        assert x["target"] == "met" or x["target"].startswith("over ×")
    assert sec["summary"]["target"] == CLASS_COST_TARGET
    assert set(sec["summary"]["ratios"]) == {"class3_six_link", "class4_six_link"}
    assert sum(h.startswith("class ") for h in report["headlines"]) == 2


def test_limited_walk_times_one_call_against_each_angle_alone(bench):
    _, report, _ = bench
    (r,) = rows(report, "limited_walk")
    assert r["positions"] == QUICK.limited_positions and r["alone_timed_on"] == QUICK.limited_alone
    assert _positive(r["call_s"]) and math.isclose(r["per_s"], r["positions"] / r["call_s"], rel_tol=1e-9)
    assert _positive(r["alone_per_s"]) and math.isclose(r["ratio"], r["per_s"] / r["alone_per_s"], rel_tol=1e-9)
    assert 0.0 <= r["max_rel_difference"] <= 1e-12
    assert any(h.startswith("a crank that cannot turn fully") for h in report["headlines"])


def test_chart_is_deterministic_and_drops_non_positive_values_on_log_axes():
    chart = Chart("c", "A chart", "x", "y", (Series("one", (1.0, 10.0, 100.0), (1e-3, 0.0, 1e-9)),
                                            Series("two", (1.0, 10.0, 100.0), (2e-3, 3e-5, 4e-8))),
                  log_x=True, log_y=True)
    a, b = draw_chart(chart), draw_chart(chart)
    assert a == b
    root = ET.fromstring(a)
    assert "1 point(s) ≤ 0 not shown" in root.find(f".//{SVG}text[@id='c-note']").text
    assert len(root.find(f".//{SVG}g[@id='c-s0-marks']")) == 2
    with pytest.raises(ValueError):
        Series("bad", (1.0, 2.0), (1.0,))


def test_ticks():
    vals, lo, hi = ticks(3e-9, 2e-3, log=True)
    assert lo == 1e-9 and hi == 1e-2 and len(vals) == 8
    vals, lo, hi = ticks(1e-16, 1e-2, log=True)
    assert len(vals) <= 9 and lo <= 1e-16 and hi >= 1e-2
    vals, lo, hi = ticks(0.0, 5.7, log=False)
    assert vals == (0.0, 2.0, 4.0, 6.0) or vals == (0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0)
    assert lo <= 0.0 and hi >= 5.7


def test_format_table_aligns_columns():
    text = format_table((Column("a", "name", "s"), Column("b", "value", ".2f"), Column("c", "n", "d")),
                        [("x", 1.0, 3), ("longer", None, 12)])
    lines = text.splitlines()
    assert lines[0].startswith("name") and "—" in lines[3]
    assert len({len(line) for line in lines[:2]}) == 1


def test_fan_render_reports_time_per_link(bench):
    _, report, _ = bench
    sec = report["sections"]["fan_render"]
    assert "fan-render.svg" in report["charts"]
    r = sec["rows"]
    assert [x["dyads"] for x in r] == list(QUICK.fan_dyads)
    low = min(x["seconds"] / x["links"] for x in r)
    for k, x in enumerate(r):
        assert x["links"] == fan_links(x["dyads"]) == 2 * x["dyads"] + 2 and x["sheets"] >= 3
        assert _positive(x["seconds"]) and _positive(x["wall_s"])
        assert math.isclose(x["s_per_link"], x["seconds"] / x["links"], rel_tol=1e-9)
        assert math.isclose(x["per_link_over_min"], x["seconds"] / x["links"] / low, rel_tol=1e-9)
        if k:
            assert math.isclose(x["time_ratio"], x["seconds"] / r[k - 1]["seconds"], rel_tol=1e-9)
    assert math.isclose(sec["summary"]["max_over_min"], max(x["per_link_over_min"] for x in r), rel_tol=1e-9)
    assert sec["summary"]["target"] == FAN_FLAT_TARGET
    assert any(h.startswith("render time per link") for h in report["headlines"])


def test_default_run_measures_every_section_and_the_issue_sizes():
    """The default run keeps what makes each figure mean something; --full measures more."""
    assert DEFAULT.name == "default" and FULL.name == "full" and QUICK.name == "quick"
    assert DEFAULT.fan_dyads == FULL.fan_dyads == (10, 20, 40, 80, 160)
    assert set(DEFAULT.precision_scenes) <= set(all_examples()) and not FULL.precision_scenes
    assert DEFAULT.decimals == FULL.decimals and set(DEFAULT.tolerances) <= set(FULL.tolerances)
    assert len(DEFAULT.resolutions) >= 3 and DEFAULT.numba_positions == FULL.numba_positions
    assert DEFAULT.check_sizes[1] == 10 * DEFAULT.check_sizes[0]
    assert DEFAULT.startup_reference_rtol < min(DEFAULT.startup_tolerances)
    assert 0 < DEFAULT.reference_s <= 120 < FULL.reference_s


def test_full_run_says_how_long_it_will_take_before_it_starts(monkeypatch, tmp_path):
    monkeypatch.setattr(bench_module, "SECTIONS", ())
    monkeypatch.setattr(bench_module, "_calibrate", lambda: 2 * bench_module.CALIBRATION_REFERENCE_S)
    buf = io.StringIO()
    report = bench_module.run(tmp_path, full=True, out=buf)
    first = buf.getvalue().splitlines()[1]
    assert first.startswith("this run will take about ") and "× 2.00" in first
    assert report["config"] == "full" and math.isclose(report["estimated_s"], 2 * FULL.reference_s)
    buf = io.StringIO()
    assert bench_module.run(tmp_path, out=buf)["config"] == "default" and "will take" not in buf.getvalue()


def test_full_and_quick_exclude_each_other(capsys):
    with pytest.raises(SystemExit):
        main(["bench", "--full", "--quick"])
    assert "not allowed with" in capsys.readouterr().err
    assert len(SECTIONS) == 13

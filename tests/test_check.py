"""`plans check` is not fooled: direction, closure, file contract, fixed tolerance.

Every example is rendered (the session fixture ``rendered``), every untouched sheet must pass,
and each doctored copy (written under ``tmp_path``) must fail with exit code 1: a reversed or
rotated vector, a changed ``data-mu``, a loose ``data-precision``, a transform above a plan, a
non-finite ``data-value``, removed tags, a relative vector shifted off the images it joins.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from plans.checking import WRITER_PRECISION, check_svg, inspect_svg
from plans.cli import main
from plans.constructions.plans import Plan, PlanPoint
from plans.drawing import Heading, draw_plan
from plans.errors import DrawingError

#: Sheets the doctoring tests edit: a four-bar (relative vectors, n/t components), the
#: quick-return (Coriolis, sliding), a class III plan through special points, Koshel's plan.
FOUR_V = "four_bar-velocity-30.svg"
FOUR_A = "four_bar-acceleration-30.svg"
QUICK_A = "quick_return-acceleration-30.svg"
CLASS3_V = "class3_six_link-velocity-30.svg"
CLASS3_A = "class3_six_link-acceleration-30.svg"
KOSHEL = "class3_six_link-koshel-30.svg"
SHEETS = (FOUR_V, FOUR_A, QUICK_A, CLASS3_V, CLASS3_A, KOSHEL)

_TAG = re.compile(r"<line\b[^>]*/>")
_ATTR = re.compile(r'([\w:-]+)="([^"]*)"')


def _attrs(tag: str) -> dict[str, str]:
    return dict(_ATTR.findall(tag))


def _tag(attrs: dict[str, str]) -> str:
    return "<line " + " ".join(f'{k}="{v}"' for k, v in attrs.items()) + " />"


def edit_line(text: str, quantity: str, fn) -> str:
    """``text`` with the tagged line of ``quantity`` rewritten by ``fn(attrs) -> attrs``: the plan's
    own line (a detail of the pole region, drawn after the plan, may repeat it at μ/k)."""
    hits = [m for m in _TAG.finditer(text) if _attrs(m.group()).get("data-quantity") == quantity]
    ids = [_attrs(m.group()).get("id", "") for m in hits]
    assert len(hits) == 1 or (len(hits) == 2 and "-detail-" in ids[1] and "-detail-" not in ids[0]), \
        f"{quantity}: {len(hits)} lines"
    m = hits[0]
    return text[:m.start()] + _tag(fn(_attrs(m.group()))) + text[m.end():]


def quantities(text: str) -> list[str]:
    return [_attrs(m.group())["data-quantity"] for m in _TAG.finditer(text) if "data-quantity" in m.group()]


XY = ("x1", "y1", "x2", "y2")
SVG = "{http://www.w3.org/2000/svg}"


def xy(a: dict[str, str]) -> tuple[float, float, float, float]:
    return tuple(float(a[k]) for k in XY)


def f3(x: float) -> str:
    return f"{x:.3f}"


def reverse(a):
    x1, y1, x2, y2 = xy(a)
    return {**a, "x1": f3(x2), "y1": f3(y2), "x2": f3(x1), "y2": f3(y1)}


def rotate(deg):
    def fn(a):
        x1, y1, x2, y2 = xy(a)
        c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
        dx, dy = x2 - x1, y2 - y1
        return {**a, "x2": f3(x1 + c * dx - s * dy), "y2": f3(y1 + s * dx + c * dy)}
    return fn


def shift(dx, dy):
    def fn(a):
        x1, y1, x2, y2 = xy(a)
        return {**a, "x1": f3(x1 + dx), "y1": f3(y1 + dy), "x2": f3(x2 + dx), "y2": f3(y2 + dy)}
    return fn


def run_check(tmp_path: Path, text: str, capsys, name: str = "doctored.svg") -> tuple[int, str]:
    bad = tmp_path / name
    bad.write_text(text, encoding="utf-8")
    capsys.readouterr()
    code = main(["check", str(bad)])
    return code, capsys.readouterr().out


def longest(text: str, prefix: str = "") -> str:
    """The longest tagged vector whose quantity starts with ``prefix``."""
    lines = [_attrs(m.group()) for m in _TAG.finditer(text)]
    lines = [a for a in lines if a.get("data-quantity", "").startswith(prefix) and "data-quantity" in a]
    best = max(lines, key=lambda a: math.hypot(xy(a)[2] - xy(a)[0], xy(a)[3] - xy(a)[1]))
    return best["data-quantity"]


# -- untouched sheets pass -------------------------------------------------------------------------

def test_every_untouched_sheet_of_every_example_passes(rendered, capsys):
    svgs = sorted(map(str, rendered.glob("*.svg")))
    assert svgs
    capsys.readouterr()
    assert main(["check", *svgs]) == 0
    out = capsys.readouterr().out
    assert "FAIL" not in out
    assert " 0 outside" in out and " 0 open" in out and f"0 of {len(svgs)} files failed" in out


def test_every_plan_checks_closure_equations(rendered):
    """Every velocity, acceleration and Koshel plan of the gallery with two or more vectors
    closes at least one vector equation; a centres sheet does wherever two of its segments
    share a centre or a point."""
    plans = 0
    for svg in sorted(rendered.glob("*.svg")):
        r = inspect_svg(svg)
        assert r.ok, (svg.name, r.problems)
        if r.kind != "plan":
            continue
        for gid, n in r.equations.items():
            if gid.endswith("-centres"):
                rays = [m.quantity[2:].split("/") for m in r.measurements]
                shared = len({x for x, _ in rays}) < len(rays) or len({c for _, c in rays}) < len(rays)
                assert (n > 0) == shared, (svg.name, n)
                continue
            if gid.endswith("-detail-plan"):
                # a detail of the pole region of absolute vectors only (Koshel's pb, pc, pd) has nothing
                # to close; one with a relative vector closes it with the absolute ones
                root = ET.parse(svg).getroot()
                group = next(g for g in root.iter(f"{SVG}g") if g.get("id") == gid)
                tagged = [l.get("data-quantity") for l in group.iter(f"{SVG}line") if l.get("data-quantity")]
                assert n > 0 or len(tagged) == 1 or not any("/" in q for q in tagged), (svg.name, gid, tagged)
                continue
            plans += 1
            # a plan of one vector has nothing to close: triad_at_rest at 0°, whose group is at rest
            # (every image but a at the pole; a→b would be p→a drawn back, so only pa is drawn)
            assert n > 0 or len(r.measurements) == 1, f"{svg.name}: no closure equation checked"
    assert plans > 50


def test_closure_equations_of_a_four_bar(rendered):
    """The four-bar's velocity plan: the pole p = c (v:A, v:B, v:M, v:B/C), a (v:A, v:B/A,
    v:M/A), b (v:B, v:B/A, v:B/C, v:M/B), m (v:M, v:M/A, v:M/B): 3 + 2 + 3 + 2 equations."""
    r = inspect_svg(rendered / FOUR_V)
    assert r.ok
    assert list(r.equations.values()) == [10]
    points = {c.point: len(c.ends) for c in r.closures}
    assert points == {"p = C = pole": 4, "a = A": 3, "b = B": 4, "m = M": 3}


def test_scheme_sheet_passes_and_says_so(rendered, capsys):
    scheme = next(iter(sorted(rendered.glob("four_bar-scheme-*.svg"))))
    capsys.readouterr()
    assert main(["check", str(scheme)]) == 0
    assert "scheme sheet: no vectors to measure" in capsys.readouterr().out


def test_plan_drawn_as_the_pole_alone_passes(tmp_path, capsys):
    plan = Plan(kind="velocity", mu=1.0, pole="p", points=(PlanPoint("p", (0.0, 0.0)),), vectors=(), lines=(),
                similar=())
    text = draw_plan(plan, Heading("At rest", "Velocity plan", "every image at the pole"), ident="velocity")
    code, out = run_check(tmp_path, text, capsys)
    assert code == 0 and "nothing to measure" in out
    # the same sheet claiming one vector it does not hold fails
    code, out = run_check(tmp_path, text.replace('data-vectors="0"', 'data-vectors="1"'), capsys)
    assert code == 1


# -- direction ---------------------------------------------------------------------------------------

@pytest.mark.parametrize("sheet", SHEETS)
def test_reversed_vector_fails(rendered, tmp_path, capsys, sheet):
    src = (rendered / sheet).read_text(encoding="utf-8")
    for q in (longest(src, "v:") if "velocity" in sheet or "koshel" in sheet else longest(src, "a:"),
              quantities(src)[0]):
        doctored = edit_line(src, q, reverse)
        bad = tmp_path / "reversed.svg"
        bad.write_text(doctored, encoding="utf-8")
        m = next(m for m in inspect_svg(bad).measurements if m.quantity == q)
        assert m.length_ok and not m.direction_ok, q    # same length, opposite direction
        code, out = run_check(tmp_path, doctored, capsys)
        assert code == 1 and f"FAIL {q} " in out


@pytest.mark.parametrize("sheet", SHEETS)
@pytest.mark.parametrize("deg", [3.0, -90.0])
def test_rotated_vector_fails(rendered, tmp_path, capsys, sheet, deg):
    src = (rendered / sheet).read_text(encoding="utf-8")
    q = longest(src)
    doctored = edit_line(src, q, rotate(deg))
    bad = tmp_path / "rotated.svg"
    bad.write_text(doctored, encoding="utf-8")
    m = next(m for m in inspect_svg(bad).measurements if m.quantity == q)
    assert not m.direction_ok and m.angle_error == pytest.approx(math.radians(abs(deg)), abs=1e-3)
    code, out = run_check(tmp_path, doctored, capsys)
    assert code == 1 and f"FAIL {q} " in out


def test_angular_tolerance_follows_the_length(rendered):
    """angle tol ≈ 2·√2·precision / length: short vectors get a looser one. The checker's is
    asin(x) + 1e-9 rad with x = 2·√2·precision/length: relative to x it differs by x²/6 + 1e-9/x,
    under 1.4e-6 + 3e-4 for 1 mm < length < 1 m, so rel=1e-3 (measured: 1.4e-4, the 1e-9 rad on
    the longest vector)."""
    r = inspect_svg(rendered / FOUR_A)
    for m in r.measurements:
        exact_mm = m.value / m.mu
        if exact_mm > 1.0:
            assert m.angle_tolerance == pytest.approx(2 * math.sqrt(2) * WRITER_PRECISION / exact_mm, rel=1e-3)


def test_missing_direction_fails(rendered, tmp_path, capsys):
    src = (rendered / FOUR_V).read_text(encoding="utf-8")
    doctored = edit_line(src, "v:B", lambda a: {k: v for k, v in a.items() if k != "data-direction"})
    code, out = run_check(tmp_path, doctored, capsys)
    assert code == 1 and "direction not recorded" in out


# -- tolerance and scale from the checker, not the file --------------------------------------------

@pytest.mark.parametrize("mu", ["x1.01", "x0.99", "-0.01", "0", "inf", "nan", "abc"])
def test_doctored_mu_fails(rendered, tmp_path, capsys, mu):
    src = (rendered / FOUR_A).read_text(encoding="utf-8")
    old = re.search(r'data-mu="([^"]+)"', src).group(1)
    new = repr(float(old) * float(mu[1:])) if mu.startswith("x") else mu
    doctored = src.replace(f'data-mu="{old}"', f'data-mu="{new}"')
    assert doctored != src
    code, _ = run_check(tmp_path, doctored, capsys)
    assert code == 1


@pytest.mark.parametrize("precision", ["10", "0.5", "0.0006", "-1", "inf", "nan"])
def test_loose_or_bad_data_precision_is_refused(rendered, tmp_path, capsys, precision):
    src = (rendered / FOUR_V).read_text(encoding="utf-8")
    doctored = src.replace('data-precision="0.0005"', f'data-precision="{precision}"')
    assert doctored != src
    code, out = run_check(tmp_path, doctored, capsys)
    assert code == 1 and "data-precision" in out
    with pytest.raises(DrawingError):
        check_svg(tmp_path / "doctored.svg")


def test_data_precision_does_not_set_the_tolerance(rendered, tmp_path):
    """Removing (or tightening) data-precision changes nothing: the tolerance is the checker's."""
    src = (rendered / FOUR_V).read_text(encoding="utf-8")
    (tmp_path / "a.svg").write_text(src.replace('data-precision="0.0005" ', ""), encoding="utf-8")
    (tmp_path / "b.svg").write_text(src.replace('data-precision="0.0005"', 'data-precision="0.00001"'),
                                    encoding="utf-8")
    base = [m.tolerance for m in inspect_svg(rendered / FOUR_V).measurements]
    assert [m.tolerance for m in inspect_svg(tmp_path / "a.svg").measurements] == base
    assert [m.tolerance for m in inspect_svg(tmp_path / "b.svg").measurements] == base
    assert inspect_svg(tmp_path / "a.svg").ok and inspect_svg(tmp_path / "b.svg").ok


def test_coarser_coordinates_fail_the_writers_precision(rendered, tmp_path, capsys):
    """Coordinates rounded to one decimal (and data-precision to match) are not plans' drawing."""
    src = (rendered / FOUR_V).read_text(encoding="utf-8")
    doctored = src.replace('data-precision="0.0005"', 'data-precision="0.05"')
    for q in quantities(src):
        doctored = edit_line(doctored, q, lambda a: {**a, **{k: f"{float(a[k]):.1f}" for k in XY}})
    code, _ = run_check(tmp_path, doctored, capsys)
    assert code == 1
    # a library caller that wrote with one decimal says so (or lets the coordinates say it)
    assert check_svg(tmp_path / "doctored.svg", precision=0.05)
    assert check_svg(tmp_path / "doctored.svg") and inspect_svg(tmp_path / "doctored.svg", None).precision == 0.05


# -- transforms and the paper ------------------------------------------------------------------------

@pytest.mark.parametrize("where", ["root", "outer-g", "plan-g", "line", "css", "style-sheet"])
def test_transform_above_a_plan_fails(rendered, tmp_path, capsys, where):
    src = (rendered / FOUR_V).read_text(encoding="utf-8")
    t = 'transform="translate(1,0)"'
    if where == "root":
        doctored = src.replace("<svg ", f"<svg {t} ", 1)
    elif where == "outer-g":
        head = src.index(">", src.index("<svg ")) + 1
        doctored = src[:head] + f"<g {t}>" + src[head:src.rindex("</svg>")] + "</g></svg>"
    elif where == "plan-g":
        doctored = src.replace("<g data-mu=", f"<g {t} data-mu=", 1)
    elif where == "line":
        doctored = edit_line(src, "v:B", lambda a: {**a, "transform": "rotate(180)"})
    elif where == "css":
        doctored = src.replace("<g data-mu=", '<g style="transform: translate(1mm, 0)" data-mu=', 1)
    else:
        head = src.index(">", src.index("<svg ")) + 1
        doctored = src[:head] + "<style>line { transform: scale(2) }</style>" + src[head:]
    assert doctored != src
    code, out = run_check(tmp_path, doctored, capsys)
    assert code == 1 and "transform" in out


def test_nested_svg_above_a_plan_fails(rendered, tmp_path, capsys):
    src = (rendered / FOUR_V).read_text(encoding="utf-8")
    head = src.index(">", src.index("<svg ")) + 1
    inner = '<svg x="5" viewBox="0 0 10 10" width="20">'
    doctored = src[:head] + inner + src[head:src.rindex("</svg>")] + "</svg></svg>"
    code, _ = run_check(tmp_path, doctored, capsys)
    assert code == 1


def test_viewbox_not_in_millimetres_fails(rendered, tmp_path, capsys):
    src = (rendered / FOUR_V).read_text(encoding="utf-8")
    w = re.search(r'width="([0-9.]+)mm"', src).group(1)
    doctored = src.replace(f'width="{w}mm"', f'width="{float(w) * 2:g}mm"', 1)
    code, out = run_check(tmp_path, doctored, capsys)
    assert code == 1 and "millimetre" in out


# -- values and tags ---------------------------------------------------------------------------------

@pytest.mark.parametrize("value", ["inf", "-inf", "nan", "-1.5", "", "abc"])
def test_non_finite_or_negative_value_fails(rendered, tmp_path, capsys, value):
    src = (rendered / FOUR_V).read_text(encoding="utf-8")
    doctored = edit_line(src, "v:B", lambda a: {**a, "data-value": value})
    code, out = run_check(tmp_path, doctored, capsys)
    assert code == 1 and "FAIL v:B " in out


def test_file_without_tags_fails(rendered, tmp_path, capsys):
    src = (rendered / FOUR_V).read_text(encoding="utf-8")
    doctored = re.sub(r' data-quantity="[^"]*"', "", src)
    code, out = run_check(tmp_path, doctored, capsys)
    assert code == 1
    # without the writer's vector count too: not a plan written by plans
    code, out = run_check(tmp_path, re.sub(r' data-vectors="[^"]*"', "", doctored), capsys)
    assert code == 1 and "no tagged vectors: not a plan written by plans" in out


def test_foreign_svg_fails(tmp_path, capsys):
    text = ('<svg xmlns="http://www.w3.org/2000/svg" width="10mm" height="10mm" viewBox="0 0 10 10">'
            '<line x1="0" y1="0" x2="5" y2="5" /></svg>')
    code, out = run_check(tmp_path, text, capsys)
    assert code == 1 and "no tagged vectors: not a plan written by plans" in out


def test_one_untagged_vector_fails(rendered, tmp_path, capsys):
    """Dropping the tag of a vector that would fail does not hide it."""
    src = (rendered / FOUR_V).read_text(encoding="utf-8")
    doctored = edit_line(src, "v:B/A", lambda a: {k: v for k, v in reverse(a).items() if not k.startswith("data-")})
    code, out = run_check(tmp_path, doctored, capsys)
    assert code == 1 and "tagged vectors where the writer drew" in out


# -- closure -----------------------------------------------------------------------------------------

@pytest.mark.parametrize("sheet, quantity", [(FOUR_V, "v:B/A"), (FOUR_V, "v:M/B"), (FOUR_A, "a:B/A:t"),
                                             (FOUR_A, "a:B/C:n"), (QUICK_A, "a:A3/A2:cor"), (QUICK_A, "a:A3/A2:r"),
                                             (QUICK_A, "a:A3/C:n"), (CLASS3_V, "v:S1/A"), (CLASS3_V, "v:C/S1"),
                                             (CLASS3_A, "a:S1/A:t"), (KOSHEL, "v:A/B")])
def test_shifted_vector_keeps_length_and_direction_but_does_not_close(rendered, tmp_path, capsys, sheet, quantity):
    src = (rendered / sheet).read_text(encoding="utf-8")
    assert quantity in quantities(src)
    doctored = edit_line(src, quantity, shift(1.0, 0.0))
    bad = tmp_path / "shifted.svg"
    bad.write_text(doctored, encoding="utf-8")
    r = inspect_svg(bad)
    m = next(m for m in r.measurements if m.quantity == quantity)
    assert m.ok                                   # the vector itself measures right
    open_ = [c for c in r.closures if not c.ok]
    assert open_ and all(any(e.startswith(quantity + " ") for e in c.ends) for c in open_)
    assert any(c.gap_mm == pytest.approx(1.0, abs=0.01) for c in open_)
    code, out = run_check(tmp_path, doctored, capsys)
    assert code == 1 and "FAIL closure at" in out and quantity in out


def test_relabelled_end_cannot_undo_a_name(rendered, tmp_path, capsys):
    """Labels only join points: a shifted v:B/A relabelled to fresh names still meets v:A and
    v:B by its name."""
    src = (rendered / FOUR_V).read_text(encoding="utf-8")
    doctored = edit_line(src, "v:B/A", lambda a: {**shift(1.0, 0.0)(a), "data-from": "z1", "data-to": "z2"})
    code, out = run_check(tmp_path, doctored, capsys)
    assert code == 1 and "FAIL closure at" in out


def test_missing_image_labels_fail(rendered, tmp_path, capsys):
    src = (rendered / FOUR_V).read_text(encoding="utf-8")
    doctored = edit_line(src, "v:B/A", lambda a: {k: v for k, v in a.items() if k not in ("data-from", "data-to")})
    code, out = run_check(tmp_path, doctored, capsys)
    assert code == 1 and "not recorded" in out

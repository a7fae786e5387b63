"""The atlas: every scene of ``plans/examples`` end to end over its reachable range.

For each scene the table below states the range of the drive that the scene can reach from
its sketch (a full turn of the crank unless said otherwise) and its structural formula. Each
scene is rendered (every sheet: scheme, velocity, acceleration, centres, Koshel's when there is
one) at 24 positions spread over that range plus the scene's own gallery positions, and
``plans check`` must pass on every sheet written. A property test then perturbs every scene's
sketch (so its dimensions) and asks the whole pipeline for random positions: the answer is
either one clear error line about an unreachable or singular position, or sheets that pass
``plans check``; never a traceback or a "please report" refusal.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import tempfile
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from conftest import toml_text
from plans.cli import main
from plans.kinematics import analyse
from plans.model import build_mechanism
from plans.scene import parse_scene
from plans.structure import analyse_structure

EXAMPLES_DIR = Path(__file__).resolve().parent.parent / "plans" / "examples"
SCENES = sorted(EXAMPLES_DIR.glob("*.toml"))
SHEETS = ("scheme", "velocity", "acceleration", "centres")
#: What a scene with loads draws besides (the force analysis runs for them; their sheets are
#: drawn by the lead's integration, the atlas checks the numbers: the power balance).
FORCE_SHEETS = ("forces", "lever")
#: Positions per scene over its range (at least 12).
POSITIONS = 24


@dataclass(frozen=True)
class Entry:
    """What the atlas knows of a scene: the drive's reachable interval (degrees or metres;
    ``None`` = a full turn of the crank), why, and the expected structural formula."""
    formula: str
    reach: tuple[float, float] | None = None
    why: str = "the crank turns fully"


II = "I(0-1) ← II(2-3)"
II_II = "I(0-1) ← II(2-3) ← II(4-5)"
III = "I(0-1) ← III(2-3-4-5)"

#: Every scene of the gallery. A scene that cannot make a full turn states its range here;
#: none is dropped silently (test_the_table_covers_every_example).
ATLAS = {
    "class3_six_link": Entry(III),
    "class3_forces": Entry(III),
    "class3_assemblies": Entry(III),
    "class4_six_link": Entry("I(0-1) ← IV(2-3-4-5)"),
    "crank_slider_central": Entry(II),
    "crank_slider_forces": Entry(II),
    "crank_slider_offset": Entry(II),
    "elliptic_trammel": Entry(II, (-0.45, 0.15), "linear drive: x_A = 0.15 m + s reaches ±AB = ±0.3 m (rod square "
                                                  "to B's guide, singular) at s = -0.45 and +0.15 m"),
    "four_bar": Entry(II),
    "four_bar_gravity": Entry(II),
    "four_bar_coupler_drive": Entry("I(0-1-2-3)", (29.0, 69.0), "the coupler's angle swings between 28.3° and "
                                    "69.6°, where crank and rocker are parallel (the drive's dead positions)"),
    "hydraulic_boom": Entry("I(0-2-3-4) ← II(5-6)", (-0.15, 0.22), "the piston head reaches the cylinder's bottom "
                            "at s = -0.161 m; tie rod 5 and rocker 6 come into line near s = +0.23 m"),
    "koshel_variant1": Entry(III),
    "koshel_variant2": Entry(III),
    "oscillating_cylinder": Entry(II),
    "quick_return": Entry(II_II),
    "scotch_yoke": Entry(II),
    "sine_mechanism": Entry(II),
    "six_link_press": Entry(II_II),
    "six_link_press_forces": Entry(II_II),
    "stephenson_six_bar": Entry(II_II),
    "tangent_mechanism": Entry(II, (-90.0, 90.0), "the slot is parallel to the guide at ±90° (singular): the "
                                                  "sketch at 30° reaches only -90° < φ < 90°"),
    "toggle_press": Entry(II_II),
    "triad_at_rest": Entry(III),
    "triad_sliding_rod": Entry(III),
    "watt_six_bar": Entry(II_II),
    "whitworth": Entry(II_II),
    "six_link_press_flywheel": Entry(II_II),
    "shaper_flywheel": Entry(II_II),
    "compressor_flywheel": Entry(II),
    "six_link_press_startup": Entry(II_II),
}


def load(stem: str) -> dict:
    """A scene as its file gives it, without the revolution of ``[drive] positions`` (the atlas
    chooses its own positions, a list of angles)."""
    data = tomllib.loads((EXAMPLES_DIR / f"{stem}.toml").read_text(encoding="utf-8"))
    for key in ("positions", "start"):
        data["drive"].pop(key, None)
    if "displacement" not in data["drive"]:
        data["drive"].setdefault("angle", 0.0)      # start = "extreme" gave the cycle's first angle
    # what belongs to the cycle goes with it: [dynamics], and the forces that follow the output
    data.pop("dynamics", None)
    data.pop("motor", None)
    data["forces"] = [f for f in data.get("forces", []) if not {"law", "stroke"} & set(f)]
    for key in ("output", "at", "trace"):
        data.get("plans", {}).pop(key, None)
    draw = data.get("plans", {}).get("draw")
    if draw:
        data["plans"]["draw"] = [d for d in draw if d not in ("positions", "diagrams", "velocities", "dynamics", "startup")]
    return data


def drive_key(data: dict) -> str:
    return "angle" if "angle" in data["drive"] else "displacement"


def positions(stem: str, data: dict) -> list[float]:
    """24 positions spread over the reachable range (every 15° of a full turn, from 0°: dead
    centres and sketches on the axes included), plus the scene's own gallery positions."""
    entry = ATLAS[stem]
    if entry.reach is None:
        spread = [15.0 * k for k in range(POSITIONS)]
    else:
        lo, hi = entry.reach
        step = (hi - lo) / POSITIONS
        spread = [round(lo + step * (k + 0.5), 9) for k in range(POSITIONS)]
    own = data["drive"][drive_key(data)]
    own = own if isinstance(own, list) else [own]
    return sorted(set(spread) | {float(v) for v in own})


def label(value: float) -> str:
    return f"{value:g}".replace("-", "m")   # the file suffix spells a minus as m


def _reject(name: str):
    """parse_constant for strict JSON: NaN, Infinity and -Infinity are not JSON."""
    raise ValueError(f"{name} in a report: not JSON")


def run(argv: list[str]) -> tuple[int, str, str]:
    """``plans`` in process: exit code, stdout, stderr."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(argv)
    return code, out.getvalue(), err.getvalue()


def test_the_table_covers_every_example():
    stems = {p.stem for p in SCENES}
    assert stems == set(ATLAS), (f"scenes without an atlas entry: {sorted(stems - set(ATLAS))}; "
                                 f"entries without a scene: {sorted(set(ATLAS) - stems)}")
    for stem, entry in ATLAS.items():
        data = load(stem)
        if entry.reach is None:
            assert "angle" in data["drive"], f"{stem}: a full turn needs a rotary drive"
        else:
            assert entry.why, f"{stem}: state why the range is limited"
        assert data["plans"]["draw"] in (list(SHEETS), list(SHEETS) + list(FORCE_SHEETS), list(SHEETS) + ["assemblies"]) \
            or stem in OLD_GALLERY, stem
        assert isinstance(data.get("title"), str) and data["title"], stem


#: Scenes that predate the atlas and draw fewer sheets in the gallery (the atlas draws all).
OLD_GALLERY = {"crank_slider_central", "crank_slider_offset", "four_bar", "quick_return", "scotch_yoke",
               "six_link_press", "tangent_mechanism"}


@pytest.mark.parametrize("stem", sorted(ATLAS))
def test_scene_over_its_range_renders_and_checks(tmp_path, stem):
    """Every sheet at every position is written, and `plans check` passes on all of them."""
    data = load(stem)
    values = positions(stem, data)
    data["drive"][drive_key(data)] = values
    data["plans"] = {"draw": list(SHEETS) + [d for d in data["plans"]["draw"] if d in FORCE_SHEETS]}
    scene = tmp_path / f"{stem}.toml"
    scene.write_text(toml_text(data), encoding="utf-8")
    out = tmp_path / "out"
    code, _, err = run(["render", str(scene), "-o", str(out), "-q"])
    assert code == 0, f"{stem} at {values}: {err.strip()}"
    assert "please report" not in err and "Traceback" not in err, err
    report = json.loads((out / f"{stem}.json").read_text(encoding="utf-8"), parse_constant=_reject)
    assert report["structure"]["dof"] == 1
    assert report["structure"]["formula"] == ATLAS[stem].formula
    assert [p.get("angle", p.get("displacement")) for p in report["positions"]] == pytest.approx(values)
    for p in report["positions"]:       # a scene with loads: the power balance closes at every position
        if "forces" in p:
            assert p["forces"]["power_residual"] < 1e-9, (p.get("angle"), p["forces"]["power_residual"])
    for kind in SHEETS:
        for v in values:
            assert (out / f"{stem}-{kind}-{label(v)}.svg").exists(), (kind, v)
    svgs = sorted(str(p) for p in out.glob("*.svg"))
    code, text, _ = run(["check", *svgs])
    assert code == 0, failures(text)


def failures(check_output: str) -> str:
    """The FAIL lines of `plans check`'s output, each with its file."""
    out, current = [], ""
    for line in check_output.splitlines():
        if line.endswith(".svg:"):
            current = Path(line[:-1]).name
        elif "FAIL" in line:
            out.append(f"{current}: {line.strip()}")
    return "\n".join(out[:20])


# --- property test: random dimensions over the whole pipeline ---------------------------------

#: What a clear refusal says: an unreachable or singular position.
REFUSALS = ("singular", "cannot assemble", "limit", "cannot be reached")


def perturbed(data: dict, factors: list[tuple[float, float]]) -> dict:
    """The scene with every sketch point moved: its offset from the frame's first point scaled
    by (1 + fx, 1 + fy). Without [lengths] the sketch is the shape of every link, so the
    perturbed sketch is itself an assembled pose (the drive's sketch value moves with it)."""
    out = {k: v for k, v in data.items() if k != "lengths"}
    base = data["points"][data["links"]["0"][0]]
    out["points"] = {name: [base[0] + (xy[0] - base[0]) * (1.0 + fx), base[1] + (xy[1] - base[1]) * (1.0 + fy)]
                     for (name, xy), (fx, fy) in zip(data["points"].items(), factors)}
    return out


@st.composite
def variants(draw, stem: str):
    data = load(stem)
    n = len(data["points"])
    factors = draw(st.lists(st.tuples(st.floats(-0.15, 0.15), st.floats(-0.15, 0.15)), min_size=n, max_size=n))
    entry = ATLAS[stem]
    if entry.reach is None:           # a full turn: [0°, 360°)
        lo, hi = 0.0, 360.0
        inside = lambda v: v < hi      # noqa: E731
    else:                              # an open interval: its ends are singular or unreachable
        lo, hi = entry.reach
        inside = lambda v: lo < v < hi  # noqa: E731
    values = draw(st.lists(st.floats(lo, hi).map(lambda v: round(v, 4)).filter(inside),
                           min_size=1, max_size=3, unique=True))
    scene = perturbed(data, factors)
    scene["drive"][drive_key(data)] = sorted(values)
    scene["plans"] = {"draw": list(SHEETS)}
    return scene


def _property(stem: str):
    # 12 draws a stem (324 random mechanisms over the 27 stems, each rendered and checked): the
    # draws are derandomized, the same every run, so more of them buy no new run-to-run coverage
    @settings(max_examples=12, deadline=None, derandomize=True, phases=[Phase.explicit, Phase.generate],
              suppress_health_check=[HealthCheck.too_slow])
    @given(scene=variants(stem))
    def test(scene):
        text = toml_text(scene)
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / f"{stem}.toml"
            path.write_text(text, encoding="utf-8")
            out = Path(tmp) / "out"
            try:
                code, _, err = run(["render", str(path), "-o", str(out), "-q"])
            except Exception as exc:  # noqa: BLE001 - a traceback is the failure being looked for
                raise AssertionError(f"render raised {exc!r} on:\n{text}") from exc
            if code == 2:
                lines = err.strip().splitlines()
                assert len(lines) == 1 and lines[0].startswith("plans: error:"), f"{err}\n{text}"
                assert "please report" not in err, f"{err}\n{text}"
                assert any(word in err for word in REFUSALS), f"not a clear refusal: {err}\n{text}"
                assert not out.exists() or not any(out.iterdir()), "an error must write no files"
                return
            assert code == 0, f"exit {code}: {err}\n{text}"
            assert "please report" not in err and "Traceback" not in err, f"{err}\n{text}"
            svgs = sorted(str(p) for p in out.glob("*.svg"))
            assert svgs
            code, report, _ = run(["check", *svgs])
            assert code == 0, failures(report) + "\n" + text
    test.__doc__ = f"{stem}: random dimensions (±15 % sketch), random positions: clear refusal or checked sheets."
    return test


@pytest.mark.parametrize("stem", sorted(ATLAS))
def test_random_dimensions_refuse_clearly_or_pass_check(stem):
    _property(stem)()


# --- what the new scenes' comments promise --------------------------------------------------------

def motion_over(stem: str, values) -> object:
    mech = build_mechanism(parse_scene(load(stem)))
    return analyse(mech, analyse_structure(mech), np.asarray(values, dtype=float))


TURN = np.arange(0.0, 360.0, 0.5)


def test_whitworth_lever_turns_fully_and_the_ram_stroke_is_twice_cd():
    m = motion_over("whitworth", TURN)
    lever = np.unwrap(m.links["3"].theta)
    assert lever[-1] - lever[0] == pytest.approx(2 * math.pi * (len(TURN) - 1) / len(TURN), abs=0.05)
    x = m.position("E")[:, 0]
    assert x.max() - x.min() == pytest.approx(0.2, abs=1e-4)        # C, D, E in line at both ends
    assert np.all(np.abs(m.links["2"].omega - m.links["3"].omega) < 1e-12)
    # working stroke 240 deg of the crank, return 120 deg: the ram's extremes are 120 deg of crank apart
    # where the slot is square to O-C... i.e. where OA makes cos = -OC/OA with the line of centres
    fine = motion_over("whitworth", np.arange(0.0, 360.0, 0.05))
    xf = fine.position("E")[:, 0]
    gap = abs(float(fine.values[np.argmax(xf)] - fine.values[np.argmin(xf)]))
    assert min(gap, 360.0 - gap) == pytest.approx(120.0, abs=0.1)


def test_oscillating_cylinder_swings_within_asin_oa_oc():
    m = motion_over("oscillating_cylinder", TURN)
    swing = np.unwrap(m.links["3"].theta)
    assert (swing.max() - swing.min()) / 2 == pytest.approx(math.asin(0.08 / 0.35), rel=1e-3)
    assert np.all(np.abs(m.links["2"].omega - m.links["3"].omega) < 1e-12)


def test_sine_mechanism_is_harmonic_with_amplitude_2oa_over_sqrt3():
    m = motion_over("sine_mechanism", TURN)
    x = m.position("Y")[:, 0]
    phi = np.radians(TURN)
    amplitude = 2 * 0.12 / math.sqrt(3)
    assert np.allclose(x - x.mean(), amplitude * np.cos(phi + math.radians(30.0)), atol=1e-12)


def test_elliptic_trammel_point_m_traces_its_ellipse():
    m = motion_over("elliptic_trammel", np.linspace(-0.44, 0.14, 59))
    x, y = m.position("M").T
    assert np.allclose((x / 0.1) ** 2 + (y / 0.2) ** 2, 1.0, atol=1e-12)


def test_toggle_press_stroke_and_bottom_dead_centre():
    m = motion_over("toggle_press", TURN)
    y = m.position("D")[:, 1]
    assert y.max() - y.min() == pytest.approx(0.0596, abs=2e-4)
    assert float(m.values[np.argmin(y)]) == pytest.approx(184.0, abs=1.5)
    knuckle = m.position("B")[:, 0]
    assert knuckle.min() > 0.02 and knuckle.max() < 0.121         # the toggle never passes straight


def test_six_bars_turn_fully_with_revolute_pairs_only():
    for stem in ("stephenson_six_bar", "watt_six_bar"):
        data = load(stem)
        assert "sliders" not in data
        m = motion_over(stem, TURN)
        assert np.all(np.isfinite(m.position("E")))


def test_triad_at_rest_at_zero_degrees():
    """Crank and rod in line: B, the base link 5 and the rockers 3, 4 stand still; the rod 2
    turns about B with ω2 = -v_A / AB (it is not at rest: its end A moves)."""
    m = motion_over("triad_at_rest", [0.0, 90.0])
    for link in ("3", "4", "5"):
        assert abs(m.links[link].omega[0]) < 1e-12 * 10.0
        assert abs(m.links[link].omega[1]) > 1e-3
    assert np.linalg.norm(m.velocity("B")[0]) < 1e-12
    assert m.links["2"].omega[0] == pytest.approx(-10.0 * 0.05 / 0.247, rel=1e-12)
    assert np.linalg.norm(m.acceleration("B")[0]) > 0.1               # only the velocities vanish


def test_a_crank_that_cannot_turn_fully_reaches_angles_on_both_sides_of_its_sketch(tmp_path):
    """Non-Grashof four-bar (OA 0.18, AB 0.20, BC 0.20, OC 0.24 m: s + l = 0.42 > p + q = 0.40),
    sketched at 0°: the crank rocks between ±144.1° (|AC| = AB + BC) and is asked for +30° and -30° (= 330°).
    Each angle renders alone; both at once must render too (not a TypeError from the walk that
    reaches each angle separately)."""
    text = "\n".join([
        'title = "non-Grashof four-bar"', "[points]", "O = [0.0, 0.0]", "C = [0.24, 0.0]", "A = [0.18, 0.0]",
        "B = [0.21, 0.197737199]", "[links]", '0 = ["O", "C"]', '1 = ["O", "A"]', '2 = ["A", "B"]',
        '3 = ["C", "B"]', "[drive]", 'link = "1"', "angle = [30.0, 330.0]", "omega = 10.0", "epsilon = 2.0",
        "[plans]", f"draw = {json.dumps(list(SHEETS))}", ""])
    scene = tmp_path / "rocker.toml"
    scene.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    code, _, err = run(["render", str(scene), "-o", str(out), "-q"])
    assert code == 0, err
    svgs = sorted(str(p) for p in out.glob("*.svg"))
    assert len(svgs) == 2 * len(SHEETS)
    code, text, _ = run(["check", *svgs])
    assert code == 0, failures(text)

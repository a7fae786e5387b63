"""Input at its edges: lengths next to nothing, points that (nearly) coincide, integers of
hundreds of digits, files that are not files (/dev/zero, a pipe, a directory) or too large,
keys a drive does not take, a variants file naming itself, an output crank called a rocker,
random draws that all clash with start = "extreme". Each is one line on stderr, exit 2, no
traceback, the key named; a file that could hang or fill the memory is read in a child process
with a time and memory limit."""

from __future__ import annotations

import itertools
import json
import math
import os
import re
import resource
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

import plans
import plans.handout.draws
from plans.cli import main
from plans.scene import MAX_FILE_BYTES, MIN_LENGTH_RATIO, parse_scene

from conftest import EXAMPLES

EXAMPLE = {p.stem: p for p in EXAMPLES}
FOUR_BAR, FORCES, PRESS = EXAMPLE["four_bar"], EXAMPLE["crank_slider_forces"], EXAMPLE["six_link_press"]
CENTRAL, TRAMMEL, BOOM = EXAMPLE["crank_slider_central"], EXAMPLE["elliptic_trammel"], EXAMPLE["hydraulic_boom"]
#: 10**400 written out: more than a double holds (an OverflowError if converted with float()).
HUGE = str(10 ** 400)


def _edit(path: Path, old: str, new: str) -> str:
    text = path.read_text(encoding="utf-8")
    assert old in text, old
    return text.replace(old, new, 1)


def _error_line(capsys, code: int) -> str:
    """The run's one stderr line, after exit 2 and no traceback or stdout."""
    captured = capsys.readouterr()
    assert code == 2, captured
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("plans: error: "), captured.err
    assert "Traceback" not in captured.err and not captured.out
    return lines[0]


def _render(tmp_path: Path, capsys, text: str, name: str = "scene.toml") -> str:
    scene = tmp_path / name
    scene.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    line = _error_line(capsys, main(["render", str(scene), "-o", str(out), "-q"]))
    assert not out.exists()
    return line


def _longest(path: Path, lengths: dict[str, float]) -> float:
    """The largest distance between two points of one link (sketch or [lengths]), computed here."""
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    pts = data["points"]
    sketch = [math.dist(pts[a], pts[b]) for link in data["links"].values() for a, b in itertools.combinations(link, 2)]
    return max(sketch + list(lengths.values()))


# --- 22.3: lengths next to nothing, points that coincide ------------------------------------------

@pytest.mark.parametrize("path, key, old", [
    (FOUR_BAR, "AB", "\nAB = 0.25"),
    (FORCES, "AB", "\nAB = 0.4"),
    (FORCES, "AC", "\nAC = 0.15"),        # the rod's centre of mass: "failed its geometric check" before
    (FOUR_BAR, "A-B", "\nAB = 0.25"),     # the key as written
], ids=["four-bar AB", "crank-slider AB", "centre of mass AC", "A-B"])
def test_a_length_next_to_nothing_is_one_line_naming_it_and_the_bound(tmp_path, capsys, path, key, old):
    line = _render(tmp_path, capsys, _edit(path, old, f"\n{key} = 1e-300"))
    lengths = {k: float(v) for k, v in tomllib.loads(path.read_text(encoding="utf-8"))["lengths"].items()}
    lengths[key.replace("-", "")] = 1e-300
    bound = MIN_LENGTH_RATIO * _longest(path, lengths)
    assert f"[lengths.{key}]: 1e-300 m is shorter than {bound:.3g} m" in line, line
    assert f"{MIN_LENGTH_RATIO:g} of the mechanism's longest link dimension" in line


def _four_bar_with_m(m: tuple[float, float]) -> str:
    """The four-bar with its coupler point M moved to ``m`` (no lengths to M: the sketch sets it)."""
    text = FOUR_BAR.read_text(encoding="utf-8")
    lines = [f"M = [{m[0]!r}, {m[1]!r}]" if ln.startswith("M = ") else ln for ln in text.splitlines()
             if not ln.startswith(("AM = ", "BM = "))]
    return "\n".join(lines) + "\n"


def test_points_of_one_link_closer_than_the_bound_are_refused(tmp_path, capsys):
    """M 0.1 µm from B on the 0.25 m coupler rendered before; the bound is 1e-6 × 0.25 m."""
    b = tomllib.loads(FOUR_BAR.read_text(encoding="utf-8"))["points"]["B"]
    line = _render(tmp_path, capsys, _four_bar_with_m((b[0], b[1] + 1e-7)))
    assert "[links.2]: points B and M (nearly) coincide in the sketch: 1e-07 m is shorter than 2.5e-07 m" in line


def test_points_just_beyond_the_bound_and_on_different_links_are_kept():
    b = tomllib.loads(FOUR_BAR.read_text(encoding="utf-8"))["points"]["B"]
    assert parse_scene(tomllib.loads(_four_bar_with_m((b[0], b[1] + 3e-7)))).points["M"][1] == b[1] + 3e-7
    data = tomllib.loads(FOUR_BAR.read_text(encoding="utf-8"))      # a frame point under the crank pin
    data["points"]["Z"] = data["points"]["A"]
    data["links"]["0"].append("Z")
    assert parse_scene(data).points["Z"] == parse_scene(data).points["A"]


def test_a_guide_through_two_points_that_nearly_coincide_is_refused(tmp_path, capsys):
    text = CENTRAL.read_text(encoding="utf-8")
    text = text.replace('through = "B"\nangle = 0.0', 'through = ["B", "Q"]').replace(
        "[links]", "Q = [0.464411172, 0.0]\n\n[links]").replace('0 = ["O"]', '0 = ["O", "Q"]')
    line = _render(tmp_path, capsys, text)
    assert "[sliders[0].through]: the guide through B and Q is undefined: 1e-07 m is shorter than 4.64e-07 m, " \
        "1e-06 of the mechanism's longest link dimension (0.4644 m)" in line, line      # OQ, on the frame


# --- 23.8 / 23.14: integers beyond a double, files that are not files ------------------------------

@pytest.mark.parametrize("key, line", [("lengths.AB", f"AB = {HUGE}"), ("drive.omega", f"omega = {HUGE}")])
def test_a_huge_integer_in_a_scene_is_one_line(tmp_path, capsys, key, line):
    old = "AB = 0.25" if key == "lengths.AB" else "omega = 10.0"
    assert f"[{key}]: " in _render(tmp_path, capsys, _edit(FOUR_BAR, old, line))


def _variants(tmp_path: Path, text: str, *extra: str, capsys) -> str:
    (tmp_path / "v.toml").write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    line = _error_line(capsys, main(["handout", str(tmp_path / "v.toml"), *extra, "-o", str(out)]))
    assert not out.exists()
    return line


@pytest.mark.parametrize("variant, key", [(f"lengths = {{ AB = {HUGE} }}", "variant[0].lengths.AB"),
                                          (f"omega = {HUGE}", "variant[0].omega"),
                                          (f"angle = [30.0, -{HUGE}]", "variant[0].angle")])
def test_a_huge_integer_in_a_variants_file_is_one_line(tmp_path, capsys, variant, key):
    line = _variants(tmp_path, f'base = "{FOUR_BAR}"\n[[variant]]\n{variant}\n', capsys=capsys)
    assert f"v.toml: [{key}]: " in line and "0000 is not a finite number; give a real value" in line, line


def _limit() -> None:
    """The child's limits: 2 GB of address space (a MemoryError, not the machine's memory) and
    no core file."""
    resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))


def _child(*args: str, cwd: Path) -> tuple[int, str]:
    """Run ``args`` under Python in a child process with limits; (exit code, stderr)."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(Path(__file__).resolve().parent.parent),
                                                         os.environ.get("PYTHONPATH", "")]))
    try:
        run = subprocess.run([sys.executable, *args], cwd=cwd, capture_output=True, text=True, timeout=120,
                             preexec_fn=_limit, env=env)
    except subprocess.TimeoutExpired:
        pytest.fail(f"{args} did not finish in 120 s (reading a pipe or a device without end?)")
    return run.returncode, run.stderr


def _one_line(code: int, err: str) -> str:
    assert code == 2, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


@pytest.fixture
def fifo(tmp_path: Path) -> Path:
    path = tmp_path / "pipe.toml"
    os.mkfifo(path)
    return path


@pytest.mark.skipif(not hasattr(os, "mkfifo") or not Path("/dev/zero").exists(), reason="needs /dev/zero and FIFOs")
def test_devices_pipes_and_directories_are_refused_by_every_reader(tmp_path, fifo):
    """plans render, plans check, a variants file's base, --random's base and plans.render."""
    out = str(tmp_path / "out")
    for args, start, kind in [
            (("render", "/dev/zero"), "/dev/zero: ", "a character device"),
            (("render", str(fifo)), f"{fifo}: ", "a named pipe (FIFO)"),
            (("render", str(tmp_path)), f"{tmp_path}: ", "a directory"),
            (("check", str(fifo)), f"{fifo}: ", "a named pipe (FIFO)"),
            (("handout", "/dev/zero", "--random", "1"), "/dev/zero: ", "a character device")]:
        line = _one_line(*_child("-m", "plans", *args, *(() if args[0] == "check" else ("-o", out)), cwd=tmp_path))
        assert line.startswith(f"plans: error: {start}is {kind}, not a "), line
        assert "plans reads only regular files" in line
    (tmp_path / "v.toml").write_text('base = "/dev/zero"\n[[variant]]\nomega = 5.0\n', encoding="utf-8")
    line = _one_line(*_child("-m", "plans", "handout", "v.toml", "-o", out, cwd=tmp_path))
    assert line == ("plans: error: v.toml: [base]: base scene '/dev/zero': is a character device, not a scene "
                    "file; plans reads only regular files: give the path of a scene file"), line
    code, err = _child("-c", "import plans\ntry:\n    plans.render('/dev/zero')\nexcept plans.SceneError as e:\n"
                       "    print(e)\n    raise SystemExit(2)", cwd=tmp_path)
    assert code == 2 and "Traceback" not in err, err
    assert not Path(out).exists()


def test_a_path_with_a_nul_character_is_a_scene_error():
    with pytest.raises(plans.SceneError, match=r"^a\\x00b: no such scene file: the path holds a NUL character"):
        plans.render("a\x00b")


def test_a_file_over_the_bound_is_refused_before_it_is_read(tmp_path, capsys):
    """A valid scene padded with a comment past MAX_FILE_BYTES (it rendered before)."""
    padding = "# " + "x" * 998 + "\n"
    text = FOUR_BAR.read_text(encoding="utf-8") + padding * (MAX_FILE_BYTES // len(padding) + 1)
    size = len(text.encode("utf-8"))
    line = _render(tmp_path, capsys, text, name="big.toml")
    assert line.endswith(f"big.toml: is larger than 4 MB ({size} bytes or more); a scene file is at most "
                         f"{MAX_FILE_BYTES} bytes: check the path"), line
    line = _variants(tmp_path, "base = 'scene.toml'\n" + padding * (MAX_FILE_BYTES // len(padding) + 1)
                     + "[[variant]]\nomega = 5.0\n", capsys=capsys)
    assert "v.toml: is larger than 4 MB" in line and "a variants file is at most" in line, line


# --- 22.11: words that mislead -----------------------------------------------------------------------

def test_a_variants_file_whose_base_is_itself_says_so(tmp_path, capsys):
    line = _variants(tmp_path, 'base = "v.toml"\n[[variant]]\nomega = 5.0\n', capsys=capsys)
    assert line == (f"plans: error: {tmp_path / 'v.toml'}: [base]: base = 'v.toml' names this variants file "
                    "itself; base is the scene the variants change: name that scene file (a path relative to this "
                    "file)"), line
    (tmp_path / "w.toml").write_text('base = "v.toml"\n[[variant]]\nomega = 5.0\n', encoding="utf-8")
    line = _error_line(capsys, main(["handout", str(tmp_path / "w.toml"), "-o", str(tmp_path / "o")]))
    assert "w.toml: [base]: names" in line and "another variants file, not a scene" in line
    assert "--random" not in line


@pytest.mark.parametrize("path, old, new, key, words", [
    (CENTRAL, 'link = "1"\n', 'link = "1"\nalong = "0"\n', "drive.along",
     "along does not apply to an angle drive (a crank or a coupler: angle, omega), whose [drive] keys are link, "
     "angle, omega, epsilon, positions, start: remove it"),
    (CENTRAL, 'link = "1"\n', 'link = "1"\nalong = "3"\n', "drive.along", "along does not apply to an angle drive"),
    (TRAMMEL, "velocity = ", "positions = 12\nvelocity = ", "drive.positions",
     "positions does not apply to a linear drive (a slider: displacement, velocity), whose [drive] keys are link, "
     "along, displacement, velocity, acceleration: positions = N divides one revolution of a crank"),
    (BOOM, "velocity = ", 'start = "extreme"\nvelocity = ', "drive.start",
     "start does not apply to a linear drive (a cylinder: displacement, velocity)"),
    (CENTRAL, 'link = "1"\n', 'link = "1"\nspeed = 3.0\n', "drive.speed",
     "unknown key 'speed'; [drive] has link, angle, omega, epsilon"),
], ids=["along 0 on a crank", "along 3 on a crank", "positions on a slider", "start on a cylinder", "unknown"])
def test_a_drive_key_that_does_not_apply_is_refused(tmp_path, capsys, path, old, new, key, words):
    line = _render(tmp_path, capsys, _edit(path, old, new))
    assert f"[{key}]: {words}" in line, line


def test_along_0_still_applies_to_a_slider_on_the_frame():
    data = tomllib.loads(TRAMMEL.read_text(encoding="utf-8"))
    data["drive"]["along"] = "0"
    assert parse_scene(data).drive == parse_scene(tomllib.loads(TRAMMEL.read_text(encoding="utf-8"))).drive


def _drag_link(first: str) -> str:
    """A drag-link four-bar (frame OC = 0.1 m the shortest link, crank OA = 0.25, coupler AB = 0.3,
    output BC = 0.28: Grashof 0.1 + 0.3 ≤ 0.25 + 0.28, so every link turns fully), sketched at
    φ = 60°, with the cycle of link 3."""
    a = (0.25 * math.cos(math.radians(60.0)), 0.25 * math.sin(math.radians(60.0)))
    ac = (0.1 - a[0], -a[1])
    d = math.hypot(*ac)
    x = (0.3 ** 2 - 0.28 ** 2 + d * d) / (2 * d)
    h = math.sqrt(0.3 ** 2 - x * x)
    b = (a[0] + (x * ac[0] - h * ac[1]) / d, a[1] + (x * ac[1] + h * ac[0]) / d)
    return (f'title = "Drag-link"\n[points]\nO = [0.0, 0.0]\nC = [0.1, 0.0]\nA = [{a[0]!r}, {a[1]!r}]\n'
            f'B = [{b[0]!r}, {b[1]!r}]\n[links]\n0 = ["O", "C"]\n1 = ["O", "A"]\n2 = ["A", "B"]\n3 = ["C", "B"]\n'
            f'[drive]\nlink = "1"\n{first}\npositions = 12\nomega = 10.0\n'
            '[lengths]\nOA = 0.25\nOC = 0.1\nAB = 0.3\nBC = 0.28\n[plans]\ndraw = ["scheme", "positions"]\n'
            'output = "3"\nat = [0]\n')


def test_the_output_of_a_drag_link_is_a_crank_and_has_no_extreme_start(tmp_path, capsys):
    scene = tmp_path / "drag.toml"
    scene.write_text(_drag_link("angle = 60.0"), encoding="utf-8")
    assert main(["render", str(scene), "-o", str(tmp_path / "out"), "-q"]) == 0
    report = json.loads((tmp_path / "out" / "drag.json").read_text(encoding="utf-8"))
    assert report["cycle"]["output"] == {"link": "3", "kind": "crank", "point": "B", "unit": "rad"}
    assert "extremes" not in report["cycle"]
    # link 3 does turn fully: its angle at the 12 positions steps the same way all round, 360° in all
    angles = [p["links"]["3"]["angle"] for p in report["positions"]]
    steps = [(b - a) % 360.0 for a, b in zip(angles, angles[1:] + angles[:1])]
    assert all(0.0 < s < 180.0 for s in steps) and math.isclose(sum(steps), 360.0)
    (tmp_path / "extreme").mkdir()
    line = _render(tmp_path / "extreme", capsys, _drag_link('start = "extreme"'), name="drag_extreme.toml")
    assert line.endswith('drag_extreme.toml: [drive.start]: the output link 3 turns fully (a crank, not a rocker): it '
                         'has no extreme position to start from; give the first position as angle instead of '
                         'start = "extreme"'), line


# --- 23.10: why no random variant works --------------------------------------------------------------

def test_random_draws_that_all_clash_with_an_extreme_start_say_so(tmp_path, capsys):
    base = tmp_path / "press.toml"          # the press's cycle from the extreme position of the ram
    base.write_text(_edit(PRESS, "\nangle = 60.0", '\nstart = "extreme"'), encoding="utf-8")
    out = tmp_path / "out"
    line = _error_line(capsys, main(["handout", str(base), "--random", "2", "-o", str(out)]))
    assert line.startswith(f"plans: error: {base}: [drive.start]: none of {plans.handout.draws.MAX_TRIES} draws "
                           f"gives a variant: {plans.handout.draws.MAX_TRIES} set angle, which the base scene "
                           "refuses; --random draws each variant's crank angle"), line
    assert 'instead of start = "extreme"' in line and "±20 %" not in line and "too few" not in line
    assert not out.exists()


def test_random_draws_refused_for_several_causes_are_counted(tmp_path, capsys, monkeypatch):
    """An offset crank-slider whose guide is almost out of the rod's reach: with 10 draws, each
    cause is counted and the most frequent named first (the counts add up to the draws)."""
    monkeypatch.setattr(plans.handout.draws, "MAX_TRIES", 10)
    base = tmp_path / "offset.toml"
    base.write_text(f'[points]\nO = [0.0, 0.0]\nA = [0.0, 0.1]\nB = [{math.sqrt(0.4 ** 2 - 0.395 ** 2)!r}, 0.495]\n'
                    '[links]\n0 = ["O"]\n1 = ["O", "A"]\n2 = ["A", "B"]\n3 = ["B"]\n'
                    '[[sliders]]\nlink = "3"\non = "0"\nthrough = "B"\nangle = 0.0\n'
                    '[drive]\nlink = "1"\nangle = 90.0\nomega = 10.0\n[lengths]\nOA = 0.1\nAB = 0.4\n',
                    encoding="utf-8")
    line = _error_line(capsys, main(["handout", str(base), "--random", "1", "-o", str(tmp_path / "out")]))
    head = line.split(": none of 10 draws gives a variant: ", 1)
    assert head[0] == f"plans: error: {base}: [--random]", line
    counts = [int(n) for n in re.findall(r"(?:^|, )(\d+) (?:did not|came closer|had lengths|set )",
                                         head[1].split(" (e.g. ")[0])]
    assert sum(counts) == 10 and counts == sorted(counts, reverse=True), line
    assert "did not assemble, or were singular, at the drawn position" in line

"""Bad input, bad output folders, a mechanism at rest: one clear line, exit 2, no files.

Every refusal is exactly one line on stderr, ``plans: error: <file>: [<key>]: <what and the
fix>``, exit code 2, no traceback, no Python warning (warnings are errors in the tests), and
nothing written: the -o folder is not even made. A fuzz test feeds random scenes to the reader.
"""

from __future__ import annotations

import contextlib
import dataclasses
import errno
import io
import json
import os
import stat
import tomllib
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import plans.output
import plans.pipeline
import plans.pipeline.sheets.koshel
import plans.pipeline.sheets.plans
from plans.cli import main
from plans.constructions.plans import ConstructionLine
from plans.errors import ConstructionError, PlansError, SceneError
from plans.scene import (MAX_ANGLE_DEG, MAX_COORD_M, MAX_OMEGA, MAX_WALK_STEPS, MIN_RATE, MIN_SIZE_M, Scene,
                         parse_scene, read_scene)

from conftest import CRANK_SLIDER, EXAMPLES, toml_text

GOOD = CRANK_SLIDER.read_text(encoding="utf-8")
#: The same crank-slider driven by its slider (a linear drive).
LINEAR = GOOD.replace('link = "1"\nangle = 45.0\nomega = 10.0\nepsilon = 0.0',
                      'link = "3"\ndisplacement = 0.0\nvelocity = 1.0\nacceleration = 0.0')
KOSHEL = next(p for p in EXAMPLES if p.stem == "koshel_variant1")


def edit(old: str, new: str, text: str = GOOD) -> str:
    assert old in text, old
    return text.replace(old, new, 1)


def scaled(factor: float) -> str:
    """The crank-slider with every coordinate and length multiplied by ``factor``."""
    data = tomllib.loads(GOOD)
    lines = []
    for line in GOOD.splitlines():
        name = line.split("=")[0].strip()
        if name in data["points"] and line.lstrip().startswith(name) and "[" in line:
            x, y = data["points"][name]
            line = f"{name} = [{x * factor!r}, {y * factor!r}]"
        elif name in data["lengths"]:
            line = f"{name} = {data['lengths'][name] * factor!r}"
        lines.append(line)
    return "\n".join(lines) + "\n"


def refused(tmp_path: Path, capsys, text: str, key: str, *needles: str, name: str = "bad.toml") -> str:
    """Render ``text``: exit 2, one line naming the file and [key] (and needles), nothing written."""
    scene = tmp_path / name
    scene.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    assert main(["render", str(scene), "-o", str(out), "-q"]) == 2
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1, captured.err
    line = lines[0]
    assert line.startswith(f"plans: error: {scene}: [{key}]: "), line
    for needle in needles:
        assert needle in line, (needle, line)
    assert "Traceback" not in captured.err and not captured.out
    assert not out.exists(), "a refused scene must write nothing"
    return line


# --- 1. nesting ------------------------------------------------------------------------------

@pytest.mark.parametrize("old, new, key", [
    ('title = "Central crank-slider mechanism"', "title = " + "[" * 50_000 + "]" * 50_000, "title"),
    ("omega = 10.0", "omega = " + "[" * 50_000 + "1" + "]" * 50_000, "drive.omega"),
    ("OA = 0.1", "OA = " + "{a = " * 5_000 + "1" + "}" * 5_000, "lengths.OA"),
])
def test_deep_nesting_is_refused(tmp_path, capsys, old, new, key):
    refused(tmp_path, capsys, edit(old, new), key, "nested")


def test_shallow_but_wrong_nesting_is_shown_short(tmp_path, capsys):
    line = refused(tmp_path, capsys, edit('title = "Central crank-slider mechanism"', "title = " + "[" * 100 + "]" * 100),
                   "title", "must be a string")
    assert len(line) < 300


def test_integer_of_thousands_of_digits(tmp_path, capsys):
    refused(tmp_path, capsys, edit("omega = 10.0", "omega = " + "9" * 5000), "drive.omega", "digits")
    refused(tmp_path, capsys, edit("omega = 10.0", "omega = " + "9" * 400), "drive.omega", "not a finite number")


# --- 2. rates --------------------------------------------------------------------------------

@pytest.mark.parametrize("old, new, key, needle", [
    ("omega = 10.0", "omega = 1e308", "drive.omega", f"≤ {MAX_OMEGA:g} rad/s"),
    ("omega = 10.0", "omega = -1e200", "drive.omega", "rad/s"),
    ("epsilon = 0.0", "epsilon = 1e20", "drive.epsilon", "rad/s²"),
    ("omega = 10.0", "omega = 1e-300", "drive.omega", f"at least {MIN_RATE:g}"),
])
def test_rates_out_of_range(tmp_path, capsys, old, new, key, needle):
    refused(tmp_path, capsys, edit(old, new), key, needle)


def test_tiny_epsilon_of_a_drive_at_rest(tmp_path, capsys):
    text = edit("epsilon = 0.0", "epsilon = 1e-200", edit("omega = 10.0", "omega = 0.0"))
    refused(tmp_path, capsys, text, "drive.epsilon", "omega = 0")


def test_tiny_epsilon_of_a_turning_crank_is_fine(tmp_path):
    scene = tmp_path / "ok.toml"
    scene.write_text(edit("epsilon = 0.0", "epsilon = 1e-200"), encoding="utf-8")
    assert main(["render", str(scene), "-o", str(tmp_path / "out"), "-q"]) == 0


@pytest.mark.parametrize("old, new, key", [
    ("velocity = 1.0", "velocity = 1e9", "drive.velocity"),
    ("acceleration = 0.0", "acceleration = -1e300", "drive.acceleration"),
])
def test_linear_rates_out_of_range(tmp_path, capsys, old, new, key):
    refused(tmp_path, capsys, edit(old, new, LINEAR), key, "out of range")


# --- 3. positions ----------------------------------------------------------------------------

@pytest.mark.parametrize("new, needle", [
    ("angle = 1e20", f"≤ {MAX_ANGLE_DEG:g}°"),
    ("angle = [-1e308, 1e308]", "out of range"),
    ("angle = [0, 1e12]", "out of range"),
    ("angle = [0.0, 2e5]", "steps"),
    ("angle = [-5e5, 5e5]", "steps"),
])
def test_drive_angles_out_of_range(tmp_path, capsys, new, needle):
    refused(tmp_path, capsys, edit("angle = 45.0", new), "drive.angle", needle)


def test_walk_bound_is_the_stated_number_of_steps(tmp_path, capsys):
    span = MAX_WALK_STEPS - 360.0
    ok = tmp_path / "ok.toml"
    ok.write_text(edit("angle = 45.0", f"angle = [0.0, {span - 1.0}]"), encoding="utf-8")
    assert main(["render", str(ok), "-o", str(tmp_path / "ok"), "-q"]) == 0
    text = edit("angle = 45.0", f"angle = [0.0, {span + 1.0}]")
    line = refused(tmp_path, capsys, text, "drive.angle", "steps")
    assert f"{span:g}°" in line


def test_slider_angle_out_of_range(tmp_path, capsys):
    refused(tmp_path, capsys, edit("angle = 0.0", "angle = 1e20"), "sliders[0].angle", "out of range")


@pytest.mark.parametrize("new, needle", [
    ("displacement = [0.0, 1000.0]", "steps"),
    ("displacement = 1e21", f"≤ {MAX_COORD_M:g} m"),
])
def test_linear_displacements_out_of_range(tmp_path, capsys, new, needle):
    refused(tmp_path, capsys, edit("displacement = 0.0", new, LINEAR), "drive.displacement", needle)


def test_too_many_positions(tmp_path, capsys):
    angles = ", ".join(str(0.5 * k) for k in range(400))
    refused(tmp_path, capsys, edit("angle = 45.0", f"angle = [{angles}]"), "drive.angle", "at most")


# --- 4. sizes --------------------------------------------------------------------------------

@pytest.mark.parametrize("factor, key, needle", [
    (1e300, "points.A", f"≤ {MAX_COORD_M:g} m"),
    (1e25, "points.A", "out of range"),
    (1e-300, "points", f"at least {MIN_SIZE_M:g} m"),
    (1e-7, "points", "across"),
])
def test_mechanism_scaled_out_of_range(tmp_path, capsys, factor, key, needle):
    refused(tmp_path, capsys, scaled(factor), key, needle)


def test_scaled_within_range_renders(tmp_path):
    for factor in (1e-5, 1e6):
        scene = tmp_path / f"s{factor:g}.toml"
        scene.write_text(scaled(factor), encoding="utf-8")
        assert main(["render", str(scene), "-o", str(tmp_path / "out"), "-q"]) == 0


@pytest.mark.parametrize("old, new, key", [
    ("B = [0.464411072, 0.0]", "B = [1e308, 0.0]", "points.B"),
    ("AB = 0.4", "AB = 1.7e308", "lengths.AB"),
])
def test_huge_coordinate_or_length(tmp_path, capsys, old, new, key):
    refused(tmp_path, capsys, edit(old, new), key, "out of range")


# --- 5. scales -------------------------------------------------------------------------------

@pytest.mark.parametrize("scale, key, needle", [
    ("mu_l = 1e-300", "scales.mu_l", "fit an A3 sheet"),
    ("mu_l = 1e6", "scales.mu_l", "less than 1 mm"),
    ("mu_v = 1e300", "scales.mu_v", "less than 1 mm"),
    ("mu_v = 1e-9", "scales.mu_v", "fit an A3 sheet"),
    ("mu_a = 1e-300", "scales.mu_a", "fit an A3 sheet"),
])
def test_scale_that_draws_off_the_paper_or_too_small(tmp_path, capsys, scale, key, needle):
    line = refused(tmp_path, capsys, GOOD + f"\n[scales]\n{scale}\n", key, needle, "the automatic choice")
    assert "nan" not in line


def test_sensible_scale_override_is_used(tmp_path):
    scene = tmp_path / "ok.toml"
    scene.write_text(GOOD + "\n[scales]\nmu_l = 0.005\nmu_v = 0.02\n", encoding="utf-8")
    assert main(["render", str(scene), "-o", str(tmp_path / "out"), "-q"]) == 0
    scales = json.loads((tmp_path / "out" / "ok.json").read_text(encoding="utf-8"))["positions"][0]["scales"]
    assert scales["mu_l"] == 0.005 and scales["mu_v"] == 0.02


# --- 6. characters ---------------------------------------------------------------------------

@pytest.mark.parametrize("old, new, key", [
    ('title = "Central', 'title = "\\u0001Central', "title"),
    ('title = "Central', 'title = "\\u001bCentral', "title"),
    ('title = "Central', 'title = "\\u007fCentral', "title"),
    ('title = "Central', 'title = "\\u0085Central', "title"),
    ('title = "Central', 'title = "Cent\\nral', "title"),
    ('title = "Central', 'title = "\\uFFFECentral', "title"),
    ('description = "Crank', 'description = "\\u0002Crank', "description"),
    ("O = [0.0, 0.0]", '"O\\u0001" = [0.0, 0.0]', 'points.O\x01'),
])
def test_characters_an_svg_cannot_hold(tmp_path, capsys, old, new, key):
    text = edit(old, new)
    if key.startswith("points."):
        text = text.replace('0 = ["O"]', '0 = ["O\\u0001"]').replace('1 = ["O", "A"]', '1 = ["O\\u0001", "A"]')
        key = "points.O\\x01"      # shown escaped: the error stays one line
    refused(tmp_path, capsys, text, key, "U+")


def test_control_character_in_a_link_name(tmp_path, capsys):
    text = edit('3 = ["B"]', '"3\\u007f" = ["B"]')
    refused(tmp_path, capsys, text, "links.3\\x7f", "U+007F")


def test_empty_names(tmp_path, capsys):
    text = edit("O = [0.0, 0.0]", '"" = [0.0, 0.0]')
    refused(tmp_path, capsys, text, 'points.""', "empty point name")
    text = edit('3 = ["B"]', '3 = ["B"]\n"" = ["C"]')
    refused(tmp_path, capsys, text, 'links.""', "empty link name")


def test_title_longer_than_a_sheet(tmp_path, capsys):
    refused(tmp_path, capsys, edit('title = "Central', 'title = "' + "x" * 5000), "title", "characters")


def test_description_may_span_lines(tmp_path):
    scene = tmp_path / "ok.toml"
    scene.write_text(edit('description = "Crank', 'description = "Two\\nlines\\tand a tab. Crank'), encoding="utf-8")
    assert main(["render", str(scene), "-o", str(tmp_path / "out"), "-q"]) == 0


# --- 7. link names are strings ---------------------------------------------------------------

@pytest.mark.parametrize("old, new, key", [
    ('[drive]\nlink = "1"', "[drive]\nlink = 1", "drive.link"),
    ('link = "3"\non = "0"', 'link = 3\non = "0"', "sliders[0].link"),
    ('link = "3"\non = "0"', 'link = "3"\non = 0', "sliders[0].on"),
])
def test_link_written_as_an_integer(tmp_path, capsys, old, new, key):
    name = key.rsplit(".", 1)[-1]
    value = new.split(f"{name} = ")[1].split("\n")[0]
    refused(tmp_path, capsys, edit(old, new), key, "names are strings", f'write {name} = "{value}"')


def test_point_written_as_an_integer_in_a_link(tmp_path, capsys):
    refused(tmp_path, capsys, edit('3 = ["B"]', '3 = ["B", 7]'), "links.3", "point names are strings", '"7"')


# --- 8. two scenes, one name -----------------------------------------------------------------

def test_two_scenes_with_the_same_stem(tmp_path, capsys):
    a, b = tmp_path / "a" / "x.toml", tmp_path / "b" / "x.toml"
    for p in (a, b):
        p.parent.mkdir()
        p.write_text(GOOD, encoding="utf-8")
    out = tmp_path / "out"
    assert main(["render", str(a), str(b), "-o", str(out), "-q"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"plans: error: {b}: [SCENE.toml]: ") and str(a) in err[0]
    assert not out.exists()
    assert main(["render", str(a), str(a), "-o", str(out), "-q"]) == 2
    assert "given twice" in capsys.readouterr().err
    assert not out.exists()


# --- 9. the output folder --------------------------------------------------------------------

def _render_into(tmp_path: Path, out: Path, capsys) -> str:
    scene = tmp_path / "good.toml"
    scene.write_text(GOOD, encoding="utf-8")
    assert main(["render", str(scene), "-o", str(out), "-q"]) == 2
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in captured.err, captured.err
    return lines[0]


def test_output_is_an_existing_file(tmp_path, capsys):
    out = tmp_path / "taken"
    out.write_text("mine", encoding="utf-8")
    line = _render_into(tmp_path, out, capsys)
    assert line.startswith(f"plans: error: {out}: [-o]: ") and "is a file" in line
    assert out.read_text(encoding="utf-8") == "mine"


def test_output_below_a_file(tmp_path, capsys):
    (tmp_path / "taken").write_text("mine", encoding="utf-8")
    out = tmp_path / "taken" / "deeper" / "out"
    line = _render_into(tmp_path, out, capsys)
    assert line.startswith(f"plans: error: {out}: [-o]: ") and "below the file" in line
    assert (tmp_path / "taken").read_text(encoding="utf-8") == "mine"


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() == 0,
                    reason="root writes in any folder whatever its mode; the monkeypatched test covers it")
def test_output_without_write_permission_for_real(tmp_path, capsys):
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(stat.S_IRUSR | stat.S_IXUSR)
    try:
        line = _render_into(tmp_path, locked / "out", capsys)
        assert "[-o]" in line and "permission" in line
        assert not any(locked.iterdir())
    finally:
        locked.chmod(stat.S_IRWXU)


def test_output_without_write_permission(tmp_path, capsys, monkeypatch):
    """As root no folder can be made unwritable: the permission test answers no."""
    out = tmp_path / "out"
    out.mkdir()
    monkeypatch.setattr(plans.output, "_writable", lambda folder: False)
    line = _render_into(tmp_path, out, capsys)
    assert line.startswith(f"plans: error: {out}: [-o]: ") and "permission" in line
    assert not any(out.iterdir())


def test_permission_denied_while_writing(tmp_path, capsys, monkeypatch):
    """The permission check passes but the system refuses the files (e.g. an ACL, a read-only mount)."""
    out = tmp_path / "out"

    def deny(*args, **kwargs):
        raise PermissionError(errno.EACCES, "Permission denied")

    monkeypatch.setattr(plans.output, "_temporary", deny)
    line = _render_into(tmp_path, out, capsys)
    assert "[-o]" in line and "permission" in line
    assert not out.exists()


# --- 10. all or nothing ----------------------------------------------------------------------

def test_a_folder_in_the_way(tmp_path, capsys):
    out = tmp_path / "out"
    (out / "good.json").mkdir(parents=True)
    line = _render_into(tmp_path, out, capsys)
    assert line.startswith(f"plans: error: {out / 'good.json'}: [-o]: ") and "folder" in line
    assert sorted(p.name for p in out.iterdir()) == ["good.json"]      # nothing else, no temporaries
    assert not any((out / "good.json").iterdir())


@pytest.mark.parametrize("fail_at", [1, 3])
def test_a_full_disk_leaves_nothing(tmp_path, capsys, monkeypatch, fail_at):
    out = tmp_path / "out"
    out.mkdir()
    (out / "old.txt").write_text("kept", encoding="utf-8")
    real = plans.output._write_all
    calls = []

    def write_all(fd, data):
        calls.append(fd)
        if len(calls) == fail_at:
            real(fd, data[: len(data) // 2])          # part of the file reaches the disk, then
            raise OSError(errno.ENOSPC, "No space left on device")
        real(fd, data)

    monkeypatch.setattr(plans.output, "_write_all", write_all)
    line = _render_into(tmp_path, out, capsys)
    assert "[-o]" in line and "disk is full" in line
    assert sorted(p.name for p in out.iterdir()) == ["old.txt"]
    assert (out / "old.txt").read_text(encoding="utf-8") == "kept"


def test_a_full_disk_removes_the_folders_it_made(tmp_path, capsys, monkeypatch):
    def full(fd, data):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(plans.output, "_write_all", full)
    _render_into(tmp_path, tmp_path / "new" / "out", capsys)
    assert not (tmp_path / "new").exists()


def test_several_scenes_are_written_all_or_nothing(tmp_path, capsys):
    """The second scene's file is blocked: the first scene's files are not written either."""
    a, b = tmp_path / "a.toml", tmp_path / "b.toml"
    a.write_text(GOOD, encoding="utf-8")
    b.write_text(GOOD, encoding="utf-8")
    out = tmp_path / "out"
    (out / "b-scheme.svg").mkdir(parents=True)
    assert main(["render", str(a), str(b), "-o", str(out), "-q"]) == 2
    assert "b-scheme.svg" in capsys.readouterr().err
    assert sorted(p.name for p in out.iterdir()) == ["b-scheme.svg"]


# --- 11. umask -------------------------------------------------------------------------------

@pytest.mark.parametrize("umask, mode", [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664)])
def test_files_respect_the_umask(tmp_path, umask, mode):
    scene = tmp_path / "good.toml"
    scene.write_text(GOOD, encoding="utf-8")
    old = os.umask(umask)
    try:
        assert main(["render", str(scene), "-o", str(tmp_path / "out"), "-q"]) == 0
    finally:
        os.umask(old)
    files = list((tmp_path / "out").iterdir())
    assert files and all(stat.S_IMODE(p.stat().st_mode) == mode for p in files)
    assert not any(p.name.startswith(".") for p in files)


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


# --- fuzz ------------------------------------------------------------------------------------

_CHARS = st.characters(codec="utf-8", exclude_categories=("Cs",))
_TEXT = st.one_of(st.text(_CHARS, max_size=6), st.sampled_from(["O", "A", "B", "C", "0", "1", "2", "3", "",
                                                                 "\x01", "\x1b", "\x7f", "\u0085", "A\nB"]))
_FLOAT = st.one_of(st.floats(), st.sampled_from([0.0, -0.0, 1e308, -1e308, 1e-308, 5e-324, 1e-300, 1e300,
                                                 1e20, 45.0, 10.0, 1e6, 1e21, 1e-7]))
_SCALAR = st.one_of(_TEXT, _FLOAT, st.integers(-10**30, 10**30), st.booleans())


def _nested(depth: int) -> st.SearchStrategy:
    """Scalars, and lists and tables of them nested up to ``depth`` levels."""
    if depth == 0:
        return _SCALAR
    inner = _nested(depth - 1)
    return st.one_of(_SCALAR, st.lists(inner, max_size=3), st.dictionaries(_TEXT, inner, max_size=3))


def _deep(n: int) -> list:
    value: list = []
    for _ in range(n):
        value = [value]
    return value


_VALUE = st.one_of(_nested(3), st.integers(1, 200).map(_deep))
_BASE = tomllib.loads(GOOD)
#: Where a mutation lands: a top-level key, or a key of one of the scene's tables.
_PLACES = [(k,) for k in list(_BASE) + ["junk"]] + [
    (t, k) for t in ("points", "links", "drive", "lengths", "plans", "scales") for k in
    list(_BASE.get(t, {})) + ["junk", "mu_l", "mu_v", "angle", "omega", "displacement", "velocity"]] + [
    ("sliders", 0, k) for k in ("link", "on", "through", "angle", "junk")]


@st.composite
def scenes(draw) -> dict:
    """The crank-slider with one to three keys replaced by random values, or removed."""
    data = json.loads(json.dumps(_BASE))
    for _ in range(draw(st.integers(1, 3))):
        place = draw(st.sampled_from(_PLACES))
        parent = data
        for step in place[:-1]:
            parent = parent[step] if isinstance(parent, dict) and step in parent or \
                isinstance(parent, list) and isinstance(step, int) and step < len(parent) else None
            if not isinstance(parent, (dict, list)):
                break
        if not isinstance(parent, dict):
            continue
        if draw(st.booleans()) and place[-1] in parent:
            del parent[place[-1]]
        else:
            parent[place[-1]] = draw(_VALUE)
    return data


def _one_line_naming(exc: PlansError, file: str | None) -> None:
    text = str(exc)
    assert "\n" not in text and "\r" not in text, text
    if isinstance(exc, SceneError):
        assert exc.key, text
        assert text.startswith(f"{file}: [" if file else "["), text


@settings(max_examples=150, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(data=scenes())
def test_fuzz_scene_reader(tmp_path_factory, data):
    """Random values in random places: a valid scene or a one-line SceneError, nothing else."""
    try:
        scene = parse_scene(data, file="fuzz.toml")
        assert isinstance(scene, Scene)
    except SceneError as exc:
        _one_line_naming(exc, "fuzz.toml")
    path = tmp_path_factory.mktemp("fuzz") / "fuzz.toml"
    path.write_text(toml_text(data), encoding="utf-8")
    try:
        assert isinstance(read_scene(path), Scene)
    except SceneError as exc:
        _one_line_naming(exc, str(path))


@settings(max_examples=60, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(data=scenes())
def test_fuzz_render(tmp_path_factory, data):
    """Random scenes through `plans render`: exit 0, or exit 2 with one line and no files."""
    folder = tmp_path_factory.mktemp("fuzz")
    path = folder / "fuzz.toml"
    path.write_text(toml_text(data), encoding="utf-8")
    out = folder / "out"
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        code = main(["render", str(path), "-o", str(out), "-q"])
    lines = err.getvalue().strip().splitlines()
    if code == 2:
        assert len(lines) == 1 and lines[0].startswith(f"plans: error: {path}"), lines
        assert not out.exists()
    else:
        assert code == 0 and all(line.startswith("warning: ") for line in lines), lines

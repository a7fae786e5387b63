"""Bad input, bad output folders, a mechanism at rest: one clear line, exit 2, no files.

Every refusal is exactly one line on stderr, ``plans: error: <file>: [<key>]: <what and the
fix>``, exit code 2, no traceback, no Python warning (warnings are errors in the tests), and
nothing written: the -o folder is not even made. A fuzz test feeds random scenes to the reader.

The scene's values are here (sections 1-8: nesting, rates, positions, sizes, scales, characters,
link names, two scenes of one name); bad output folders in ``test_bad_input_output.py``, a
mechanism at rest and sheets that cannot be drawn in ``test_bad_input_sheets.py``, the fuzz
tests in ``test_bad_input_fuzz.py``; the shared scene and runners in ``bad_input_cases.py``.
"""

from __future__ import annotations

import json

import pytest

from plans.cli import main
from plans.scene import MAX_ANGLE_DEG, MAX_COORD_M, MAX_OMEGA, MAX_WALK_STEPS, MIN_RATE, MIN_SIZE_M

from bad_input_cases import GOOD, LINEAR, edit, refused, scaled


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


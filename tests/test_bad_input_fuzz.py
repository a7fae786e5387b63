"""Fuzz: random scenes to the reader and to `plans render`.

The crank-slider with one to three keys replaced by random values (nested lists and tables,
huge and tiny floats, control characters, deep nesting) or removed: the reader returns a
valid scene or raises a one-line SceneError naming the file and the key; `plans render` exits
0, or exits 2 with exactly one line ``plans: error: <file>...`` and no files.
"""

from __future__ import annotations

import contextlib
import io
import json
import tomllib

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from plans.cli import main
from plans.errors import PlansError, SceneError
from plans.scene import Scene, parse_scene, read_scene

from bad_input_cases import GOOD
from conftest import toml_text


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

import math
from pathlib import Path

import numpy as np
import pytest

EXAMPLES = sorted((Path(__file__).resolve().parent.parent / "plans" / "examples").glob("*.toml"))
#: The example the bad-input and contract tests edit: the central crank-slider.
CRANK_SLIDER = next(p for p in EXAMPLES if p.stem == "crank_slider_central")

#: A central crank-slider machine's linkage as scene text (no title, loads or [dynamics]): crank
#: OA 0.1 m, rod AB 0.4 m, ω1 = 10 rad/s CCW, 12 positions from the outer extreme.
CRANK_SLIDER_MACHINE = """[points]
O = [0.0, 0.0]
A = [0.1, 0.0]
B = [0.5, 0.0]
[links]
0 = ["O"]
1 = ["O", "A"]
2 = ["A", "B"]
3 = ["B"]
[[sliders]]
link = "3"
on = "0"
through = "B"
angle = 0.0
[drive]
link = "1"
omega = 10.0
positions = 12
start = "extreme"
[lengths]
OA = 0.1
AB = 0.4
"""


def sheet_words(svg_text: str) -> str:
    """Everything a sheet writes, one ``<text>`` per line, its runs joined (a subscript run
    follows its base: P<sub>3</sub> reads "P3")."""
    import xml.etree.ElementTree as ET

    root = ET.fromstring(svg_text)
    return "\n".join("".join(t.itertext()) for t in root.iter("{http://www.w3.org/2000/svg}text"))


def stem_of(name: str) -> str:
    """The scene stem a rendered file belongs to: ``four_bar-velocity-30.svg`` → ``four_bar``."""
    return name.split("-")[0].split(".")[0]


#: How long a worker waits for the other workers' renders of the demo (s): ten times its ~20 s.
_DEMO_WAIT_S = 600.0


@pytest.fixture(scope="session")
def demo_rendered(tmp_path_factory):
    """Every bundled example, linkages and gears, rendered as ``plans demo`` renders them (what
    the README's first command puts into output/); read only. Under pytest-xdist the workers
    share the work: each example is rendered by the worker that first creates its
    ``demo-K.lock`` in the run's shared temporary folder, and every worker then waits for all
    the ``demo-K.done`` files (each says ``ok`` or why its render failed)."""
    import os
    import time

    from plans.cli import _examples, main

    root = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        root = root.parent                     # this run's folder, shared by its workers
    out = root / "demo"
    out.mkdir(exist_ok=True)
    scenes = _examples()
    for k, scene in enumerate(scenes):
        try:
            os.close(os.open(root / f"demo-{k}.lock", os.O_CREAT | os.O_EXCL | os.O_WRONLY))
        except FileExistsError:                # another worker renders this one
            continue
        state = f"plans render {scene.name} did not finish"
        try:
            code = main(["render", str(scene), "-o", str(out), "-q"])
            state = "ok" if code == 0 else f"plans render {scene.name} exited {code}"
        except BaseException as exc:           # the waiting workers must hear of it too
            state = f"plans render {scene.name} raised {exc!r}"
            raise
        finally:
            tmp = root / f"demo-{k}.done.tmp"
            tmp.write_text(state, encoding="utf-8")
            tmp.replace(root / f"demo-{k}.done")     # appears whole
    deadline = time.monotonic() + _DEMO_WAIT_S
    for k in range(len(scenes)):
        done = root / f"demo-{k}.done"
        while not done.exists():
            if time.monotonic() > deadline:
                pytest.fail(f"the demo render in {out} did not finish within {_DEMO_WAIT_S:.0f} s")
            time.sleep(0.05)
        state = done.read_text(encoding="utf-8")
        assert state == "ok", f"the demo render failed: {state}"
    return out


@pytest.fixture(scope="session")
def rendered(demo_rendered, tmp_path_factory):
    """Every linkage example's files (examples/*.toml, not the gears), from the one demo render."""
    import shutil

    out = tmp_path_factory.mktemp("render")
    stems = {p.stem for p in EXAMPLES}
    for path in demo_rendered.iterdir():
        if path.is_file() and stem_of(path.name) in stems:
            shutil.copyfile(path, out / path.name)
    return out


def _toml_string(s: str) -> str:
    """A TOML basic string; quotes, backslashes and control characters escaped."""
    out = []
    for c in s:
        if c in '"\\':
            out.append("\\" + c)
        elif ord(c) < 0x20 or ord(c) == 0x7F:
            out.append(f"\\u{ord(c):04x}")
        else:
            out.append(c)
    return '"' + "".join(out) + '"'


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, np.integer)):
        return repr(int(v))
    if isinstance(v, (float, np.floating)):
        x = float(v)
        return repr(x) if math.isfinite(x) else "nan" if x != x else "inf" if x > 0 else "-inf"
    if isinstance(v, str):
        return _toml_string(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    return "{" + ", ".join(f"{_toml_string(k)} = {_toml_value(x)}" for k, x in v.items()) + "}"


def toml_text(data: dict) -> str:
    """A scene dict written as TOML that tomllib reads back equal: every top-level key on one
    line ``"key" = value`` (inline tables, arrays of inline tables for [[sliders]])."""
    return "".join(f"{_toml_string(k)} = {_toml_value(v)}\n" for k, v in data.items())


def press_without_cycle(folder: Path) -> Path:
    """A copy of the six-link press in ``folder`` as it was before its cycle sheets: drive
    angles 60° and 200°, scheme and both plans, no ``positions`` (the handout tests count its
    sheets and pages)."""
    import tomllib

    data = tomllib.loads(next(p for p in EXAMPLES if p.stem == "six_link_press").read_text(encoding="utf-8"))
    for key in ("positions", "start"):
        data["drive"].pop(key, None)
    data["drive"]["angle"] = [60.0, 200.0]
    data["plans"] = {"draw": ["scheme", "velocity", "acceleration"]}
    path = Path(folder) / "six_link_press.toml"
    path.write_text(toml_text(data), encoding="utf-8")
    return path


def plans_cli(argv: list[str], cwd: Path | None = None):
    """``plans ARGV`` run in this process (the interpreter's start and numpy's import are a second
    a run, most of a refusal's cost), in ``cwd`` when given: a ``subprocess.CompletedProcess``
    with its exit code, stdout and stderr. An exception escapes as it would print a traceback."""
    import contextlib
    import io
    import subprocess

    from plans.cli import main

    out, err = io.StringIO(), io.StringIO()
    with contextlib.chdir(cwd or Path.cwd()), contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main([str(a) for a in argv])
        except SystemExit as exc:             # argparse's usage errors exit as the command would
            code = exc.code if isinstance(exc.code, int) else 2
    return subprocess.CompletedProcess(["plans", *argv], code, out.getvalue(), err.getvalue())


def refused_handout(tmp_path: Path, *args: str) -> str:
    """``plans handout ARGS -o tmp_path/out`` in ``tmp_path``: it must be refused — exit 2, one
    line on stderr, no output folder — and that line is returned."""
    r = plans_cli(["handout", *args, "-o", tmp_path / "out"], cwd=tmp_path)
    lines = r.stderr.strip().splitlines()
    assert r.returncode == 2 and len(lines) == 1, r.stderr
    assert not (tmp_path / "out").exists()
    return lines[0]


def refused_line(tmp_path: Path, scene_text: str) -> str:
    """Render ``scene_text`` through the command line; it must be refused — exit 2, one line on
    stderr, no output folder — and that line is returned."""
    scene = tmp_path / "bad.toml"
    scene.write_text(scene_text, encoding="utf-8")
    out = tmp_path / "out"
    r = plans_cli(["render", scene, "-o", out])
    lines = r.stderr.strip().splitlines()
    assert r.returncode == 2 and len(lines) == 1, r.stderr
    assert not out.exists()
    return lines[0]


def folding_four_bar() -> dict:
    """A four-bar whose crank cannot turn fully: coupler and rocker line up near φ ≈ 92.6°."""
    a = [0.1 / np.sqrt(2.0)] * 2
    return {"title": "folding four-bar",
            "points": {"O": [0.0, 0.0], "A": a, "B": [0.22918773, 0.13223321], "D": [0.3, 0.0]},
            "links": {"0": ["O", "D"], "1": ["O", "A"], "2": ["A", "B"], "3": ["B", "D"]},
            "drive": {"link": "1", "angle": [45.0], "omega": 10.0, "epsilon": 0.0}}

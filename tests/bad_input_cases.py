"""Shared helpers of the bad-input tests (``test_bad_input*.py``): the crank-slider scene they
edit (``GOOD``), its twin driven by the slider (``LINEAR``), Koshel's example, and the runners
that render a scene and read the one line it prints.

Every refusal is exactly one line on stderr, ``plans: error: <file>: [<key>]: <what and the
fix>``, exit code 2, no traceback, no Python warning (warnings are errors in the tests), and
nothing written: the -o folder is not even made (``refused``, ``_render_into``).
"""

from __future__ import annotations

import tomllib
from pathlib import Path

from plans.cli import main

from conftest import CRANK_SLIDER, EXAMPLES

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


def _render_into(tmp_path: Path, out: Path, capsys) -> str:
    scene = tmp_path / "good.toml"
    scene.write_text(GOOD, encoding="utf-8")
    assert main(["render", str(scene), "-o", str(out), "-q"]) == 2
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in captured.err, captured.err
    return lines[0]

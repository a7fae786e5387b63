"""Writing a handout into its output folder: every variant's folder (assignment sheet, answer
key, its scene file), ``variants.toml``, the base scene's copy and ``index.html``; and the
progress bar the command line shows meanwhile.

Knows :mod:`.variants`, :mod:`.solving`, :mod:`.rotor`'s bounds, :mod:`.toml_text`,
:mod:`.assignment`, :mod:`.index`, the export and the output; must not import the random draws or the command line.
"""

from __future__ import annotations

import re
import sys
import time
from pathlib import Path
from typing import Callable, Mapping, Sequence, TextIO

from ..errors import OutputError
from ..export import convert, output_names
from ..output import check_folder, refuse_inputs, write_files
from .asked import Asked
from .assignment import assignment_sheets, variant_asked
from .index import index_html
from .rotor import ANGLE_STEP_DEG, BALANCING_RANGE, MASS_SPREAD
from .solving import variant_data
from .toml_text import to_toml, toml_value
from .variants import LENGTH_SPREAD, Drawn, Handout, margin_text

__all__ = ["INDEX", "VARIANTS", "Progress", "write_handout"]

#: Files in the output folder besides the variants' folders.
INDEX, VARIANTS = "index.html", "variants.toml"


def _variants_file(h: Handout, base_name: str) -> str:
    """``variants.toml``: the handout's variants in the variants format, every value written
    (``plans handout`` on it, beside the base scene's copy, gives the same answer keys)."""
    lines = [f"# plans handout: {len(h.variants)} variants of {h.base.name}"]
    if h.seed is not None:
        lo, hi = BALANCING_RANGE
        lines.append(f"# drawn with --random {len(h.variants)} --seed {h.seed}: " + (
            f"teeth ±{LENGTH_SPREAD:.0%}, none undercut; the coaxial, assembly and neighbourhood conditions kept"
            if h.train else f"masses ±{MASS_SPREAD:.0%}, radii ±{LENGTH_SPREAD:.0%}, angles in {ANGLE_STEP_DEG:g}° "
            f"steps, the masses' planes moved in the base's order; balancing masses {lo:g}…{hi:g} × the base's"
            if h.rotor else f"lengths ±{LENGTH_SPREAD:.0%}; every asked position keeps |condition| ≥ the margin of "
            f"each group: {margin_text(h)}"))
    lines += ["", f"base = {toml_value(base_name)}", f"title = {toml_value(h.title)}"]
    for v in h.variants:
        data = variant_data(h, v)
        lines += ["", "[[variant]]"]
        if h.train:
            gears = data["gears"]
            lines += [f"teeth = {toml_value({n: w['teeth'] for n, w in gears['wheels'].items()})}",
                      f"input = {toml_value(dict(gears.get('input', {})))}"]
            continue
        if h.rotor:
            lines.append(f"masses = {toml_value(data['rotor']['masses'])}")
            continue
        if data.get("lengths"):
            lines.append(f"lengths = {toml_value(data['lengths'])}")
        lines += [f"{key} = {toml_value(data['drive'][key])}" for key in h.keys if key in data["drive"]]
    return "\n".join(lines) + "\n"


def _folder_names(d: Drawn, sheets: Mapping[str, str]) -> list[str]:
    """Every file name of variant ``d``'s folder: the key's sheets (SVG, PDF), its JSON, the
    assignment's ``sheets`` (SVG, PDF) and the variant's scene file (none may write over an input)."""
    return output_names({**d.sheets.files, **dict.fromkeys(sheets, ""), f"{d.name}.toml": ""}, ("svg", "pdf"))


def _stale(out: Path, drawn: Sequence[Drawn], assignments: Sequence[Mapping[str, str]]) -> list[Path]:
    """What an earlier handout left in ``out`` that this one would not write over: a
    ``variant-N`` entry this one has not (fewer or more variants), or a file in one of its
    variants' folders it does not write (another scene's sheets, other positions)."""
    if not out.is_dir():
        return []
    names = {d.name: set(_folder_names(d, sheets)) for d, sheets in zip(drawn, assignments)}
    stale = []
    for p in sorted(out.iterdir()):
        if not re.fullmatch(r"variant-\d+", p.name):
            continue
        if p.name not in names or not p.is_dir():
            stale.append(p)
        else:
            stale += [q for q in sorted(p.iterdir()) if q.name not in names[p.name]]
    return stale


def _base_name(h: Handout) -> str:
    """The base scene's copy in the output folder: its own name unless that is taken."""
    return h.base.name if h.base.name not in (INDEX, VARIANTS) else "base.toml"


class Progress:
    """A progress bar on ``stream`` (stderr) while a handout is made, drawn only on a terminal:
    ``[#####-----] 12/30 variant-12``, rewritten in place, one line."""

    def __init__(self, total: int, what: str, stream: TextIO | None = None, width: int = 30):
        self.stream = sys.stderr if stream is None else stream
        self.on = bool(getattr(self.stream, "isatty", lambda: False)())
        self.total, self.what, self.width = max(total, 1), what, width
        self.started = time.monotonic()

    def __call__(self, done: int, note: str = "") -> None:
        if not self.on:
            return
        filled = int(self.width * done / self.total)
        self.stream.write(f"\r{self.what} [{'#' * filled}{'-' * (self.width - filled)}] {done}/{self.total} "
                          f"{note:<16}{self.eta(done):>14}")
        self.stream.flush()

    def eta(self, done: int) -> str:
        """The time left, estimated from the time each item took so far (``about 1 min left``)."""
        if done <= 0 or done >= self.total:
            return ""
        left = (time.monotonic() - self.started) / done * (self.total - done)
        return f"about {left:.0f} s left" if left < 90 else f"about {left / 60:.0f} min left"

    def close(self) -> None:
        if self.on:
            self.stream.write("\n")
            self.stream.flush()


def write_handout(h: Handout, drawn: Sequence[Drawn], out: str | Path, *,
                  progress: Callable[[int, str], None] | None = None,
                  asked: Sequence[tuple[Asked, ...]] | None = None,
                  assignments: Sequence[Mapping[str, str]] | None = None) -> list[Path]:
    """Write every variant's folder, ``variants.toml``, the base scene's copy and ``index.html``
    into ``out``. Each folder is written all or nothing (:meth:`plans.Sheets.save`); an error
    removes what this call wrote before it. ``asked``, ``assignments``: what each variant asks
    and its assignment's sheets (:func:`~.assignment.assignment_sheets`: file name → SVG text),
    when already found. Returns the paths written."""
    out = Path(out)
    check_folder(out)
    base_name = _base_name(h)
    inputs = [p for p in (h.base, h.source) if p is not None]
    if asked is None:
        asked = [variant_asked(d) for d in drawn]
    if assignments is None:
        assignments = [assignment_sheets(h, d, a) for d, a in zip(drawn, asked)]
    refuse_inputs([out / n for n in (VARIANTS, base_name, INDEX)]
                  + [out / d.name / n for d, sheets in zip(drawn, assignments) for n in _folder_names(d, sheets)],
                  inputs)
    if stale := _stale(out, drawn, assignments):
        raise OutputError(f"holds an earlier handout's files that this one would not replace ({len(stale)}: "
                          f"{', '.join(str(p.relative_to(out)) for p in stale[:2])}{', …' if len(stale) > 2 else ''}): "
                          "they would be mixed into its folders; remove them or choose an empty folder for -o",
                          file=str(out), key="-o")
    written: list[Path] = []
    try:
        for k, d in enumerate(drawn, 1):
            folder = out / d.name
            written += d.sheets.save(folder, formats="svg,pdf")
            written += write_files({**convert(dict(assignments[k - 1]), ("svg", "pdf")),
                                    f"{d.name}.toml": _scene_file(h, d)}, folder)
            if progress:
                progress(k, d.name)
        top = {VARIANTS: _variants_file(h, base_name), base_name: h.base_text,
               INDEX: index_html(h, drawn, margin=h.margin, asked=asked, assignments=assignments)}
        written += write_files(top, out)
    except BaseException:
        for p in reversed(written):
            try:
                p.unlink()
            except OSError:
                pass
        for d in drawn:
            try:
                (out / d.name).rmdir()
            except OSError:
                pass
        raise
    return written


def _scene_file(h: Handout, d: Drawn) -> str:
    """The variant's own scene file (``plans render`` redraws its key from it)."""
    return (f"# {d.name} of {h.base.name} ({h.title}): the base scene with this variant's lengths and drive;\n"
            f"# plans render {d.name}.toml redraws its answer key\n" + to_toml(variant_data(h, d.variant)))

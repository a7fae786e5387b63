"""A handout as a Moodle XML question bank (``plans handout … --moodle quiz.xml``).

One ``category`` question names the handout's category (``top/<title>``: in the bank the import
is made into; ``$course$/top/…`` would send the questions to the course's default bank on
Moodle 5); then one Cloze (``multianswer``) question a variant, whose question text (HTML in
CDATA) holds:

- the assignment sheet as an image, a 256-colour palette PNG (under half the RGBA one's size),
  embedded as ``<file name="variant-01-assignment.png" path="/" encoding="base64">`` and shown
  by ``<img src="@@PLUGINFILE@@/variant-01-assignment.png">``;
- the given data and the task, as text, with how to type a number and the position the fields
  are for (the first given one);
- one NUMERICAL field a quantity the assignment asks (:mod:`.asked`):
  ``{1:NUMERICAL:=-52.2256:1.04452}`` — the value it is marked against (the exact one, or a
  graphical task's method at the task's positions: :class:`~.asked.Asked`) to
  :data:`ANSWER_DIGITS` significant digits (what Moodle's review shows as the correct answer)
  and an absolute tolerance (:func:`field_tolerance`: ``tolerance`` × |value|, never below the
  drawing's precision; an angle its precision alone) + the rounding, rounded up: every response
  within that of the value is right (Moodle's Cloze NUMERICAL takes an absolute, "nominal",
  tolerance t: a response r is right when |r − a| ≤ t + 10⁻¹⁴·max(t, |a|)). An angle within its
  tolerance of 0° or 360° has a second right answer a turn away (``=359:2~=-1:2``), so either
  way of writing the direction is right.

Import in Moodle: Question bank → Import → "Moodle XML format", choose the file, keep "Get
category from file" ticked; the questions land in a category named after the handout, one
per variant (add them to a quiz by "random question from category" to give each student one).
A bank above :data:`UPLOAD_LIMIT` (PHP's default ``upload_max_filesize``) is refused by a
default server: make fewer variants a bank.

Knows :mod:`.asked`, :mod:`.assignment`, :mod:`.variants` and the export (the PNG); must not
import the writing, the random draws or the command line.
"""

from __future__ import annotations

import base64
import html
import io
import math
import os
from decimal import ROUND_CEILING, Decimal
from pathlib import Path
from typing import Sequence

from ..errors import OutputError
from ..export import svg_to_png
from .asked import Asked, symbol_html
from .graphical import READ_MM
from .assignment import answers_at, assignment_svg, given_and_task
from .variants import Drawn, Handout

__all__ = ["DEFAULT_TOLERANCE", "MIN_TOLERANCE", "ANSWER_DIGITS", "PNG_DPI", "UPLOAD_LIMIT", "parse_tolerance",
           "answer_text", "field_tolerance", "cloze_field", "check_bank_path", "size_warning", "moodle_xml"]

#: The default relative tolerance of every field (2 %).
DEFAULT_TOLERANCE = 0.02
#: The smallest relative tolerance (0.01 %): Moodle keeps an answer to 14 digits and adds
#: 10⁻¹⁴ of slack, and a field's answer is rounded to ANSWER_DIGITS (5·10⁻⁶ relative at most).
MIN_TOLERANCE = 1e-4
#: Significant digits of a field's answer.
ANSWER_DIGITS = 6
#: The embedded assignment sheet's resolution (A3: 1654 × 1169 pixels).
PNG_DPI = 100.0
#: PHP's default ``upload_max_filesize`` (2M), bytes: a larger bank is refused by a default server.
UPLOAD_LIMIT = 2 * 1024 * 1024


def parse_tolerance(text: str) -> float:
    """A ``--tolerance`` value in percent (``2%`` or ``2``) as a fraction, MIN_TOLERANCE ≤ t < 1."""
    raw = text.strip().removesuffix("%").strip()
    try:
        value = float(raw)
    except ValueError:
        raise OutputError(f"--tolerance is a percentage of the exact value, e.g. 2%, got {text!r}",
                          key="--tolerance") from None
    if not math.isfinite(value) or not MIN_TOLERANCE * 100.0 <= value < 100.0:
        raise OutputError(f"--tolerance must lie between {MIN_TOLERANCE * 100:g} % and 100 %, 100 % excluded (it "
                          f"would mark 0 right; Moodle keeps 14 digits of an answer, so one under "
                          f"{MIN_TOLERANCE * 100:g} % is not met reliably), got {text!r}; e.g. 2%",
                          key="--tolerance")
    return value / 100.0


def answer_text(value: float) -> str:
    """``value`` to :data:`ANSWER_DIGITS` significant digits (``1.21548``, ``-52.2256``, ``1.5e-05``)."""
    return f"{value:.{ANSWER_DIGITS}g}"


def _up(x: float) -> str:
    """``x`` ≥ 0 rounded up to :data:`ANSWER_DIGITS` significant digits."""
    if x == 0.0:
        return "0"
    d = Decimal(x)       # exact: the float's own value
    up = d.quantize(Decimal(1).scaleb(d.adjusted() - ANSWER_DIGITS + 1), rounding=ROUND_CEILING)
    return f"{float(up):.{ANSWER_DIGITS}g}"      # the same digits (a carry's 10.0000 as 10), read back ≥ x


def field_tolerance(a: Asked, tolerance: float) -> float:
    """The half-width a field of ``a`` accepts around its value (before the answer's rounding):
    ``tolerance`` × |value|, or the drawing's precision when that is wider; an angle's precision
    alone (a share of an angle's value is no measure of how well a direction is drawn)."""
    return a.precision if a.angle else max(tolerance * abs(a.value), a.precision)


def cloze_field(a: Asked, tolerance: float, weight: int = 1) -> str:
    """The Cloze NUMERICAL field of ``a``: its value to :data:`ANSWER_DIGITS` digits, and the
    absolute tolerance :func:`field_tolerance` widened by that rounding (rounded up); an angle
    near 0° or 360° (within that tolerance) also right a turn away."""
    answer = answer_text(a.value)
    t = field_tolerance(a, tolerance)
    alternatives = [f"={answer}:{_up(t + abs(a.value - float(answer)))}"]
    if a.angle:
        for turn in (-360.0, 360.0):
            other = a.value + turn
            if -t < other < 360.0 + t:
                text = answer_text(other)
                alternatives.append(f"={text}:{_up(t + abs(other - float(text)))}")
    return f"{{{weight}:NUMERICAL:{'~'.join(alternatives)}}}"


def check_bank_path(bank: str, out: str) -> None:
    """Refuse, before anything is written, a ``--moodle`` path the bank cannot be written to:
    not a .xml name, a folder, below a file or an unwritable folder, or the ``-o`` folder (or
    one of its parents)."""
    if not bank.lower().endswith(".xml"):
        raise OutputError(f"--moodle names the question bank to write, a .xml file, got {bank!r}", key="--moodle")
    path = Path(bank)
    if path.is_dir() or (path.exists() and not path.is_file()):
        raise OutputError("is a folder (or another non-file), not the bank's file; give --moodle a file name, e.g. "
                          f"{path / 'bank.xml'}", file=bank, key="--moodle")
    target, folder = path.resolve(), Path(out).resolve()
    if target == folder or target in folder.parents:
        raise OutputError(f"-o {out} makes this path a folder (the handout's, or one above it); give --moodle a file "
                          f"of its own, e.g. {Path(out) / 'bank.xml'}", file=bank, key="--moodle")
    probe = path.parent       # the nearest existing folder up the bank's path: a file there, or no permission
    while not probe.exists() and probe.parent != probe:
        probe = probe.parent
    if probe.exists() and not probe.is_dir():
        raise OutputError(f"lies below the file {probe}, not in a folder; give --moodle a path in a folder",
                          file=bank, key="--moodle")
    if not os.access(probe, os.W_OK | os.X_OK):
        raise OutputError(f"no permission to write in {probe}; choose another --moodle or change its permissions",
                          file=bank, key="--moodle")


def size_warning(size: int, count: int) -> str | None:
    """A one-line warning when a bank of ``size`` bytes and ``count`` variants is above
    :data:`UPLOAD_LIMIT`, with the number of variants a bank that fits."""
    if size <= UPLOAD_LIMIT:
        return None
    fits = max(1, count * UPLOAD_LIMIT // size)
    return (f"the question bank is {size / 2 ** 20:.1f} MB, above the 2 MB PHP upload limit (upload_max_filesize) of "
            f"a default Moodle server: make fewer variants per bank (about {fits} fit), or raise the server's limit")


def _palette_png(png: bytes) -> bytes:
    """An RGBA PNG as a 256-colour palette PNG on white (the sheets' lines, greys and few tints
    keep their exact colours; max-coverage quantisation), its resolution kept. Byte-stable."""
    from PIL import Image   # cairosvg's own dependency

    rgba = Image.open(io.BytesIO(png)).convert("RGBA")
    flat = Image.alpha_composite(Image.new("RGBA", rgba.size, (255, 255, 255, 255)), rgba).convert("RGB")
    out = io.BytesIO()
    flat.quantize(256, method=Image.Quantize.MAXCOVERAGE).save(out, "PNG", dpi=(PNG_DPI, PNG_DPI))
    return out.getvalue()


def _cdata(text: str) -> str:
    return "<![CDATA[" + text.replace("]]>", "]]]]><![CDATA[>") + "]]>"


def _within(a: Asked, tolerance: float) -> str:
    """What a row adds when its field is not marked ±``tolerance`` of an exact value: the method
    its value is, and the margin when the drawing's precision widens it (or an angle's)."""
    out = f"; the value of {a.method}" if a.method else ""
    t = field_tolerance(a, tolerance)
    if a.angle or t > tolerance * abs(a.value):
        out += f"; accepted within ±{t:.2g}" + ("°" if a.unit == "°" else "" if a.unit == "—" else f" {a.unit}")
    return html.escape(out)


def _marking(asked: Sequence[Asked], tolerance: float) -> str:
    """The sentence saying how the fields are marked."""
    if not any(a.method or a.angle or a.precision > tolerance * abs(a.value) for a in asked):
        return f"Each value is accepted within ±{tolerance * 100:g} % of the exact one."
    out = (f"Each value is accepted within ±{tolerance * 100:g} % of the key's value, or within what a drawing read "
           f"to ±{READ_MM:g} mm at the key's scales gives where that is wider (its row says so)")
    if any(a.angle for a in asked):
        out += "; an angle within the margin its row gives, either side of 0°"
    if any(a.method for a in asked):
        out += ("; a graphical task's value is what its method gives at the positions the task gives (the answer "
                "key's dashed chords), not the exact value")
    return html.escape(out + ".")


def _question(h: Handout, d: Drawn, asked: Sequence[Asked], tolerance: float, svg: str) -> list[str]:
    """Variant ``d``'s Cloze question, its assignment sheet ``svg`` embedded as a PNG."""
    image = f"{d.name}-assignment.png"
    png = base64.b64encode(_palette_png(svg_to_png(svg, PNG_DPI))).decode("ascii")
    cells, task = given_and_task(h, d, tuple(asked))
    at = answers_at(d)
    rows = "".join(f"<tr><td>{symbol_html(a.symbol)}</td><td>{cloze_field(a, tolerance)}</td><td>{html.escape(a.unit)}"
                   f"</td><td>{html.escape(a.what)}{_within(a, tolerance)}</td></tr>" for a in asked)
    head = f"your value at {symbol_html(at)}" if at else "your value"
    body = (f"<p><strong>{html.escape(h.title)}, {html.escape(d.name.replace('-', ' '))}</strong></p>"
            f'<p><img src="@@PLUGINFILE@@/{image}" alt="{html.escape(d.name)}: assignment sheet" '
            f'style="max-width: 100%; height: auto;"></p>'
            f"<p>Given: {'; '.join(symbol_html(c) for c in cells)}.</p>"
            f"<p>{symbol_html(task)}</p>"
            f"<table><tr><th>quantity</th><th>{head}</th><th>unit</th><th></th></tr>{rows}</table>"
            f"<p>{_marking(asked, tolerance)}</p>")
    name = f"{h.title}: {d.name}"
    return ['  <question type="cloze">',
            f"    <name><text>{html.escape(name, quote=False)}</text></name>",
            '    <questiontext format="html">',
            f"      <text>{_cdata(body)}</text>",
            f'      <file name="{image}" path="/" encoding="base64">{png}</file>',
            "    </questiontext>",
            '    <generalfeedback format="html"><text></text></generalfeedback>',
            "    <penalty>0.3333333</penalty>",
            "    <hidden>0</hidden>",
            f"    <idnumber>{html.escape(d.name)}</idnumber>",
            "  </question>"]


def moodle_xml(h: Handout, drawn: Sequence[Drawn], asked: Sequence[Sequence[Asked]], *,
               tolerance: float = DEFAULT_TOLERANCE, assignments: Sequence[str] | None = None) -> str:
    """The Moodle XML text of the handout: its category, then a Cloze question a variant;
    ``assignments``: the variants' assignment sheets (SVG text) when already drawn."""
    if assignments is None:
        assignments = [assignment_svg(h, d, tuple(a)) for d, a in zip(drawn, asked)]
    name = f"{h.title} ({h.base.name}" + (f", seed {h.seed}" if h.seed is not None else "") + ")"
    category = "top/" + name.replace("/", "-")     # a "/" would open a subcategory
    out = ['<?xml version="1.0" encoding="UTF-8"?>', "<quiz>",
           f"  <!-- plans handout: {len(drawn)} variants -->",     # no file name: "--" may not stand in a comment
           '  <question type="category">',
           f"    <category><text>{html.escape(category, quote=False)}</text></category>",
           f'    <info format="html"><text>{_cdata(f"<p>{html.escape(h.title)}: {len(drawn)} variants made by plans.</p>")}</text></info>',
           "  </question>"]
    for d, a, svg in zip(drawn, asked, assignments):
        out += _question(h, d, a, tolerance, svg)
    out += ["</quiz>", ""]
    return "\n".join(out)

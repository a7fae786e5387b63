"""A handout as a Moodle XML question bank (``plans handout … --moodle quiz.xml``).

One ``category`` question names the handout's category (``$course$/top/<title>``); then one
Cloze (``multianswer``) question a variant, whose question text (HTML in CDATA) holds:

- the assignment sheet as an image, embedded as ``<file name="variant-01-assignment.png"
  path="/" encoding="base64">`` and shown by ``<img src="@@PLUGINFILE@@/variant-01-assignment.png">``;
- the given data and the task, as text;
- one NUMERICAL field a quantity the assignment asks (:mod:`.asked`):
  ``{1:NUMERICAL:=-52.2255506526:1.04451101305}`` — the exact value as Python's shortest
  round-trip decimal, and an absolute tolerance = ``tolerance`` × |value| (Moodle's Cloze
  NUMERICAL takes an absolute, "nominal", tolerance: a response r is right when
  |r − value| ≤ tolerance + 10⁻¹⁴·max(1, |value|)).

Import in Moodle: Question bank → Import → "Moodle XML format", choose the file, keep "Get
category from file" ticked; the questions land in a category named after the handout, one
per variant (add them to a quiz by "random question from category" to give each student one).

Knows :mod:`.asked`, :mod:`.assignment`, :mod:`.variants` and the export (the PNG); must not
import the writing, the random draws or the command line.
"""

from __future__ import annotations

import base64
import html
import math
from typing import Sequence

from ..errors import OutputError
from ..export import svg_to_png
from .asked import Asked, symbol_html
from .assignment import assignment_svg, given_and_task
from .variants import Drawn, Handout

__all__ = ["DEFAULT_TOLERANCE", "PNG_DPI", "parse_tolerance", "cloze_field", "moodle_xml"]

#: The default relative tolerance of every field (2 %).
DEFAULT_TOLERANCE = 0.02
#: The embedded assignment sheet's resolution (A3: 1654 × 1169 pixels).
PNG_DPI = 100.0


def parse_tolerance(text: str) -> float:
    """A ``--tolerance`` value in percent (``2%`` or ``2``) as a fraction, 0 < t < 1."""
    raw = text.strip().removesuffix("%").strip()
    try:
        value = float(raw)
    except ValueError:
        raise OutputError(f"--tolerance is a percentage of the exact value, e.g. 2%, got {text!r}",
                          key="--tolerance") from None
    if not math.isfinite(value) or not 0.0 < value < 100.0:
        raise OutputError(f"--tolerance must lie between 0 and 100 %, got {text!r}; e.g. 2%", key="--tolerance")
    return value / 100.0


def cloze_field(a: Asked, tolerance: float, weight: int = 1) -> str:
    """The Cloze NUMERICAL field of ``a``: its exact value and the absolute tolerance
    ``tolerance`` × |value|."""
    return f"{{{weight}:NUMERICAL:={a.value!r}:{tolerance * abs(a.value)!r}}}"


def _cdata(text: str) -> str:
    return "<![CDATA[" + text.replace("]]>", "]]]]><![CDATA[>") + "]]>"


def _question(h: Handout, d: Drawn, asked: Sequence[Asked], tolerance: float, svg: str) -> list[str]:
    """Variant ``d``'s Cloze question, its assignment sheet ``svg`` embedded as a PNG."""
    image = f"{d.name}-assignment.png"
    png = base64.b64encode(svg_to_png(svg, PNG_DPI)).decode("ascii")
    cells, task = given_and_task(h, d, tuple(asked))
    rows = "".join(f"<tr><td>{symbol_html(a.symbol)}</td><td>{cloze_field(a, tolerance)}</td><td>{html.escape(a.unit)}"
                   f"</td><td>{html.escape(a.what)}</td></tr>" for a in asked)
    body = (f"<p><strong>{html.escape(h.title)}, {html.escape(d.name.replace('-', ' '))}</strong></p>"
            f'<p><img src="@@PLUGINFILE@@/{image}" alt="{html.escape(d.name)}: assignment sheet" '
            f'style="max-width: 100%; height: auto;"></p>'
            f"<p>Given: {'; '.join(symbol_html(c) for c in cells)}.</p>"
            f"<p>{symbol_html(task)}</p>"
            f"<table><tr><th>quantity</th><th>your value</th><th>unit</th><th></th></tr>{rows}</table>"
            f"<p>Each value is accepted within ±{tolerance * 100:g} % of the exact one.</p>")
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
    category = "$course$/top/" + name.replace("/", "-")     # a "/" would open a subcategory
    out = ['<?xml version="1.0" encoding="UTF-8"?>', "<quiz>",
           f"  <!-- plans handout: {len(drawn)} variants of {html.escape(h.base.name)} -->",
           '  <question type="category">',
           f"    <category><text>{html.escape(category, quote=False)}</text></category>",
           f'    <info format="html"><text>{_cdata(f"<p>{html.escape(h.title)}: {len(drawn)} variants made by plans.</p>")}</text></info>',
           "  </question>"]
    for d, a, svg in zip(drawn, asked, assignments):
        out += _question(h, d, a, tolerance, svg)
    out += ["</quiz>", ""]
    return "\n".join(out)

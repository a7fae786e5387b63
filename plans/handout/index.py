"""``index.html`` of a handout: every variant's assignment and answer key, for the screen and
for printing.

On screen: a cover (title, base scene, seed and margin, a table of the variants' data with
links), then every page. In print the cover is left out; each sheet prints at 100 % on a page
of its own size (a named CSS page, ``@page s420x297 { size: 420mm 297mm; margin: 0 }``, the
size read from the sheet's SVG), so that every text keeps its drawn height: the assignments
first (the assignment sheet, then its answer sheets), then, variant by variant, an A4 page with
the key's values and a page per key sheet. The sheets are ``<img>`` of the SVG files beside it
(relative paths, so the folder can be moved); the text holds no date or absolute path: the same
handout gives the same bytes.

Knows :mod:`.asked` (an asked quantity), :mod:`.variants` (the handout, its solved variants, the
margins' wording), :mod:`.rotor`'s bounds and the export's sheet size; must not import the
solving, the random draws, the writing or the command line.
"""

from __future__ import annotations

import html
import json
from typing import Mapping, Sequence

from ..export import sheet_size_mm
from .asked import Asked, symbol_html
from .rotor import ANGLE_STEP_DEG, BALANCING_RANGE, MASS_SPREAD
from .variants import LENGTH_SPREAD, Drawn, Handout, margin_text

__all__ = ["index_html", "CSS", "page_css", "ASSIGNMENT_MM"]

#: The assignment sheet's size when its SVG is not given, mm (a linkage's: A3 landscape).
ASSIGNMENT_MM = (420.0, 297.0)

CSS = """\
body { font-family: "DejaVu Serif", serif; margin: 1em; color: #000; }
h1 { font-size: 1.5em; } h2 { font-size: 1.1em; margin: 0 0 0.4em; }
table { border-collapse: collapse; font-size: 0.9em; }
td, th { border: 1px solid #999; padding: 0.15em 0.5em; text-align: left; }
td.n { text-align: right; font-variant-numeric: tabular-nums; }
img.sheet { display: block; max-width: 100%; height: auto; border: 1px solid #ccc; }
section.page { margin: 2em 0; }
@page { size: A4 portrait; margin: 10mm; }
@media print {
  body { margin: 0; }
  .cover { display: none; }
  section.page { margin: 0; break-after: page; page-break-after: always; break-inside: avoid; }
  section.page:last-of-type { break-after: auto; page-break-after: auto; }
  section.sheet { overflow: hidden; }
  section.sheet h2 { display: none; }
  img.sheet { border: none; max-width: none; }
  h2 { font-size: 12pt; margin: 0 0 2mm; }
  table { font-size: 10pt; }          /* DejaVu Serif: capitals 0.729 em, 2.57 mm */
}
"""


def _size_name(size: tuple[float, float]) -> str:
    """The named page of a sheet ``size`` (mm): ``s420x297``, ``s241p8x297`` (p for a point)."""
    return "s" + "x".join(f"{x:g}".replace(".", "p") for x in size)


def page_css(sizes: Sequence[tuple[float, float]]) -> str:
    """The print rules of the sheets' pages: a named page per size (mm), as large as the sheet
    and without margins, and the sheet drawn at that size: at 100 %."""
    out = []
    for w, h in sorted(set(sizes)):
        n = _size_name((w, h))
        out.append(f"@page {n} {{ size: {w:g}mm {h:g}mm; margin: 0; }}\n"
                   f"@media print {{ section.{n} {{ page: {n}; width: {w:g}mm; height: {h:g}mm; }}\n"
                   f"  section.{n} img.sheet {{ width: {w:g}mm; height: {h:g}mm; }} }}\n")
    return "".join(out)


def _e(text: object) -> str:
    return html.escape(str(text), quote=True)


def _g(x: float) -> str:
    return f"{x:.4g}"


def _size(svg: str | None, default: tuple[float, float] = ASSIGNMENT_MM) -> tuple[float, float]:
    """A sheet's size in mm, from its SVG (``default`` when it gives none)."""
    return (sheet_size_mm(svg) if svg is not None else None) or default


def _values_table(report: dict, angular: bool, drive: str) -> str:
    """The key's values, position by position: |v|, |a| of the moving points, ω, ε of the links,
    the sliding v, a of the prismatic pairs, and the scales."""
    rows = []
    for pos in report["positions"]:
        where = f"φ<sub>{_e(drive)}</sub> = {pos['angle']:g}°" if angular else f"s = {pos['displacement']:g} m"
        rows.append(f'<tr><th colspan="3">{where}</th></tr>')
        rows.append("<tr><th>point</th><th>|v|, m/s</th><th>|a|, m/s²</th></tr>")
        for name, p in pos["points"].items():
            if "v" not in p or not any(p["v"]) and not any(p.get("a", [0.0])):
                continue
            a = _g(sum(c * c for c in p["a"]) ** 0.5) if "a" in p else "—"
            rows.append(f'<tr><td>{_e(name)}</td><td class="n">{_g(sum(c * c for c in p["v"]) ** 0.5)}</td>'
                        f'<td class="n">{a}</td></tr>')
        rows.append("<tr><th>link</th><th>ω, rad/s</th><th>ε, rad/s²</th></tr>")
        for name, link in pos["links"].items():
            if "omega" in link:
                rows.append(f'<tr><td>{_e(name)}</td><td class="n">{_g(link["omega"])}</td>'
                            f'<td class="n">{_g(link["epsilon"]) if "epsilon" in link else "—"}</td></tr>')
        sliders = [(k, s) for k, s in pos.get("sliders", {}).items() if "v" in s]
        if sliders:
            rows.append("<tr><th>slider</th><th>v<sub>rel</sub>, m/s</th><th>a<sub>rel</sub>, m/s²</th></tr>")
            for k, s in sliders:
                rows.append(f'<tr><td>{_e(k)}</td><td class="n">{_g(s["v"])}</td>'
                            f'<td class="n">{_g(s["a"]) if "a" in s else "—"}</td></tr>')
        scales = "; ".join(f"{_e(k.replace('mu_', 'μ'))} = {v:g}" for k, v in pos["scales"].items())
        rows.append(f'<tr><td colspan="3">scales: {scales}</td></tr>')
    return "<table>\n" + "\n".join(rows) + "\n</table>"


def _asked_table(asked: Sequence[Asked]) -> str:
    """What the assignment asks, with the values it is marked against (the key's exact values,
    or a graphical method's with the exact beside them) and, when stated, the drawing's
    precision of each."""
    exact = any(a.exact is not None for a in asked)
    precise = any(a.precision > 0.0 for a in asked)
    rows = ["<tr><th>asked</th><th>value</th>" + ("<th>exact</th>" if exact else "")
            + ("<th>drawing ±</th>" if precise else "") + "<th>unit</th><th>what</th></tr>"]
    for a in asked:
        how = f" ({_e(a.method)})" if a.method else ""
        rows.append(f'<tr><td>{symbol_html(a.symbol)}</td><td class="n">{a.value:.6g}</td>'
                    + (f'<td class="n">{a.exact:.6g}</td>' if a.exact is not None else "<td></td>" if exact else "")
                    + (f'<td class="n">{a.precision:.2g}</td>' if precise else "")
                    + f"<td>{_e(a.unit)}</td><td>{_e(a.what)}{how}</td></tr>")
    return "<table>\n" + "\n".join(rows) + "\n</table>"


def _train_rows(h: Handout, drawn: Sequence[Drawn]) -> tuple[str, list[str]]:
    """A gear train's cover table: the head (every wheel's teeth, the inputs' speeds) and a row
    of cells a variant."""
    gears = h.base_data["gears"]
    wheels, inputs = list(gears["wheels"]), list(gears.get("input", {}))
    head = "".join(f"<th>z<sub>{_e(n)}</sub></th>" for n in wheels) + \
        "".join(f"<th>n<sub>{_e(n)}</sub>, rpm</th>" for n in inputs)
    rows = []
    for d in drawn:
        g = d.scene.gears
        speeds = dict(g.inputs)
        rows.append("".join(f'<td class="n">{g.wheel(n).teeth}</td>' for n in wheels)
                    + "".join(f'<td class="n">{speeds[n]:g}</td>' for n in inputs))
    return head, rows


def _rotor_rows(h: Handout, drawn: Sequence[Drawn]) -> tuple[str, list[str]]:
    """A rotor's cover table: a column a mass (m, r, θ, plane)."""
    count = len(h.base_data["rotor"]["masses"])
    head = "".join(f"<th>mass {k + 1}: m, r, θ, plane</th>" for k in range(count))
    rows = []
    for d in drawn:
        rows.append("".join(f'<td class="n">{m.mass:g} kg, {m.radius:g} m, {m.angle:g}°'
                            + (f", {m.plane:g} m" if m.plane is not None else "") + "</td>"
                            for m in d.scene.rotor.masses))
    return head, rows


def index_html(h: Handout, drawn: Sequence[Drawn], *, margin: float | None = None,
               asked: Sequence[Sequence[Asked]] = (), assignments: Sequence[Mapping[str, str]] = ()) -> str:
    """The index page's text (see the module docstring); ``asked``: what each variant's
    assignment asks, with its key's values (listed first on its key's page); ``assignments``:
    each variant's assignment sheets (file name → SVG text, the assignment sheet first), when
    given (else its one sheet ``<name>-assignment.svg``, a gear train's the size of its key's
    gear sheet, a linkage's :data:`ASSIGNMENT_MM`)."""
    if h.train:
        return _page(h, drawn, margin, asked, assignments, *_train_rows(h, drawn))
    if h.rotor:
        return _page(h, drawn, margin, asked, assignments, *_rotor_rows(h, drawn))
    drive = str(h.base_data["drive"]["link"])
    sym = (f"φ<sub>{_e(drive)}</sub>, °", f"ω<sub>{_e(drive)}</sub>, rad/s", f"ε<sub>{_e(drive)}</sub>, rad/s²") \
        if h.angular else ("s, m", "v, m/s", "a, m/s²")
    names = list(h.base_data.get("lengths", {}))
    head = "".join(f"<th>{_e(n)}, m</th>" for n in names) + "".join(f"<th>{s}</th>" for s in sym)
    rows = []
    for d in drawn:
        dv = d.scene.drive
        cells = "".join(f'<td class="n">{_length(d, n, h):g}</td>' for n in names)
        rows.append(cells + f'<td class="n">{", ".join(f"{x:g}" for x in dv.values)}</td>'
                    f'<td class="n">{dv.speed:g}</td><td class="n">{dv.rate:g}</td>')
    return _page(h, drawn, margin, asked, assignments, head, rows)


def _assignment_sheets(d: Drawn, given: Mapping[str, str] | None) -> list[tuple[str, tuple[float, float]]]:
    """Variant ``d``'s assignment sheets: file name and size (mm) of each."""
    if given:
        return [(name, _size(svg)) for name, svg in given.items()]
    gears = next((s.svg for s in d.sheets if s.name == "gears"), None) if d.sheets.train is not None else None
    return [(f"{d.name}-assignment.svg", _size(gears))]


def _page(h: Handout, drawn: Sequence[Drawn], margin: float | None, asked: Sequence[Sequence[Asked]],
          assignments: Sequence[Mapping[str, str]], head: str, rows: list[str]) -> str:
    drive = str(h.base_data.get("drive", {}).get("link", ""))
    tasks = [_assignment_sheets(d, assignments[k] if k < len(assignments) else None) for k, d in enumerate(drawn)]
    sizes = [size for sheets in tasks for _, size in sheets] + [_size(s.svg) for d in drawn for s in d.sheets]
    out = ["<!DOCTYPE html>", '<html lang="en">', "<head>", '<meta charset="utf-8">',
           f"<title>{_e(h.title)} — handout, {len(drawn)} variants</title>",
           f"<style>\n{CSS}{page_css(sizes)}</style>", "</head>",
           "<body>", '<section class="cover">', f"<h1>{_e(h.title)}: {len(drawn)} variants</h1>",
           f"<p>Base scene: <code>{_e(h.base.name)}</code> (copied beside this page); the variants: "
           f'<a href="variants.toml">variants.toml</a>.</p>']
    if h.seed is not None and h.train:
        out.append(f"<p>Drawn at random with seed {h.seed}: each wheel's teeth within ±20 % of the base's (an "
                   "external wheel at least 17: none undercut), a central wheel's teeth closing the coaxial condition "
                   "of its carrier, the input speeds from a standard series; every variant meets the train's "
                   "coaxial, assembly and neighbourhood conditions.</p>")
    elif h.seed is not None and h.rotor:
        lo, hi = BALANCING_RANGE
        out.append(f"<p>Drawn at random with seed {h.seed}: each mass within ±{MASS_SPREAD:.0%} of the base's, each "
                   f"radius within ±{LENGTH_SPREAD:.0%}, the angles in {ANGLE_STEP_DEG:g}° steps over the turn, the "
                   "masses' planes moved along the shaft in the base's order (the balancing planes kept); every "
                   f"variant's balancing masses lie within {lo:g}…{hi:g} × the base's.</p>")
    elif h.seed is not None:
        margin = h.margin if margin is None else margin
        kept = "" if margin is None else (
            f" and every asked position keeps a margin from singular positions: |condition| ≥ {margin:g} in every "
            f"group whose condition is a sine (class II and III; plans warns below 0.01, 0 is singular); a class IV "
            f"group or a drive inside the chain keeps half the base's own smallest figure "
            f"(σ<sub>min</sub>/σ<sub>max</sub>). Here: {_e(margin_text(h))}")
        out.append(f"<p>Drawn at random with seed {h.seed}: each link's proportions within ±20 % of the base's (a "
                   f"point on a bar kept on it), the angle over the turn, ω from a standard series; every variant "
                   f"assembles{kept}.</p>")
    out.append("<p>Printing: every sheet prints at 100 % on a page of its own size (A3 or A4, as the sheet is; "
               "print at the actual size, without fitting to the page), so that its text keeps its drawn height. "
               "The assignments come first, each sheet a page; then each variant's answer key: its values on A4, "
               "then one page a sheet.</p>")
    out += ["<table>", f"<tr><th>variant</th>{head}<th>assignment</th><th>answer key</th></tr>"]
    for d, cells in zip(drawn, rows):
        n = _e(d.name)
        out.append(f'<tr><td><a href="#{n}">{n}</a></td>{cells}<td><a href="{n}/{n}-assignment.pdf">PDF</a></td>'
                   f'<td><a href="#{n}-key">values</a>, <a href="{n}/{n}.json">JSON</a></td></tr>')
    out += ["</table>", "</section>"]
    for d, sheets in zip(drawn, tasks):
        n = _e(d.name)
        for k, (file, size) in enumerate(sheets):
            what, anchor = ("assignment", f' id="{n}"') if k == 0 else (f"answer sheet {k + 1}", "")
            out += [f'<section class="page sheet {_size_name(size)} assignment"{anchor}>',
                    f"<h2>{_e(d.name)} — {what}</h2>",
                    f'<img class="sheet" src="{n}/{_e(file)}" alt="{n}: {what}">', "</section>"]
    for k, d in enumerate(drawn):
        n = _e(d.name)
        report = json.loads(d.sheets.json)
        out += [f'<section class="page values key" id="{n}-key">', f"<h2>{_e(d.name)} — answer key: values</h2>",
                _asked_table(asked[k]) if k < len(asked) else "",
                _values_table(report, h.angular, drive) if report.get("positions") else "",
                f'<p>Files: <a href="{n}/{n}.json">{n}.json</a>, <a href="{n}/{n}.toml">{n}.toml</a> (its scene).</p>',
                "</section>"]
        for sheet in d.sheets:
            f = _e(sheet.file)
            out += [f'<section class="page sheet {_size_name(_size(sheet.svg))} key-sheet">',
                    f"<h2>{_e(d.name)} — answer key: {_e(sheet.name)}</h2>",
                    f'<img class="sheet" src="{n}/{f}" alt="{n}: {_e(sheet.name)}">', "</section>"]
    out += ["</body>", "</html>", ""]
    return "\n".join(out)


def _length(d: Drawn, name: str, h: Handout) -> float:
    """The variant's value of the base length ``name`` (m)."""
    return float(d.variant.lengths.get(name, h.base_data["lengths"][name]))

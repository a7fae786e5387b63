"""The ``plans`` command: render scenes, check drawings, render the bundled examples, make handouts."""

from __future__ import annotations

import argparse
import math
import re
import sys
from importlib import resources
from pathlib import Path
from typing import Sequence

from .errors import OutputError, PlansError, SceneError, one_line
from .export import (DEFAULT_DPI, FORMATS, MAX_DPI, MIN_DPI, check_png_sizes, convert, output_names, parse_dpi,
                     parse_formats, require_cairo)
from .output import check_folder, refuse_inputs, write_files
from .pipeline import Rendered, render_scene
from . import linalg as la

__all__ = ["main"]


def _train_table(r: Rendered) -> list[str]:
    """The speeds of the scene's gear train, one line."""
    if r.train is None:
        return []
    s = r.train.speeds
    speeds = "; ".join(f"{name}: n = {float(n):.6g} rpm" for name, n in s.rpm.items())
    return [f"  gears: W = {s.structure.mobility}; {speeds}"]


def _rotor_table(r: Rendered) -> list[str] | None:
    """The balancing masses of a rotor alone, one line (None for any other scene)."""
    import json

    rotor = json.loads(r.files.get(f"{r.stem}.json", "{}")).get("rotor")
    if rotor is None:
        return None
    masses = "; ".join(f"plane {b['plane']:g} m: {b['mass']:.6g} kg at {b['angle']:.4g}°" for b in rotor["balancing"])
    return [f"{r.stem}: rotor, {rotor['kind']} balance", f"  {masses}"]


def _flywheel_table(r: Rendered) -> list[str] | None:
    """The flywheel of a flywheel problem alone ([turning], [operation]), a line each (None for any other scene)."""
    import json

    data = json.loads(r.files.get(f"{r.stem}.json", "{}"))
    if "turning" not in data and "operation" not in data:
        return None
    lines = [f"{r.stem}: flywheel problem"]
    if "turning" in data:
        t = data["turning"]
        known = "".join(f", {k} = {t[k]:.6g}{u}" for k, u in (("delta", ""), ("inertia", " kg·m²"), ("mass", " kg"))
                        if t[k] is not None)
        lines.append(f"  turning: P = {t['power']:.6g} W, ΔE = {t['energy_fluctuation']:.6g} J{known}")
    if "operation" in data:
        o = data["operation"]
        lines.append(f"  operation: P = {o['power']:.6g} W, {o['per_minute']:.4g} a minute"
                     + "".join(f", {k} = {o[k]:.6g}{u}" for k, u in (("rpm_after", " rpm"), ("mass", " kg"))
                               if o[k] is not None))
    return lines


def _table(r: Rendered) -> str:
    m = r.motion
    if m is None:
        rotor = (_rotor_table(r) or _flywheel_table(r)) if r.train is None else None
        return "\n".join(rotor if rotor is not None else [f"{r.stem}: gear train"] + _train_table(r))
    mech = m.mechanism
    unit = "deg" if mech.drive.kind.angular else "m"
    lines = [f"{r.stem}: {m.structure.formula}   μl = {r.scales.mu_l:g} m/mm"
             + (f", μV = {r.scales.mu_v:g} (m/s)/mm" if r.scales.mu_v else "")
             + (f", μa = {r.scales.mu_a:g} (m/s²)/mm" if r.scales.mu_a else "")]
    for i, value in enumerate(m.values):
        lines.append(f"  at {value:g} {unit}:")
        if m.order >= 1:
            row = []
            for p in mech.sketch:
                if m.carrier(p) == "0":
                    continue
                v = float(la.norm(m.velocity(p)[i]))
                a = f", a = {float(la.norm(m.acceleration(p)[i])):.4g}" if m.order >= 2 else ""
                row.append(f"{p}: v = {v:.4g}{a}")
            lines.append("    " + "; ".join(row))
            links = []
            for name in mech.moving:
                s = m.links[name]
                e = f", ε = {float(s.epsilon[i]):.4g}" if m.order >= 2 else ""
                links.append(f"{name}: ω = {float(s.omega[i]):.4g}{e}")
            lines.append("    " + "; ".join(links))
    return "\n".join(lines + _train_table(r))


def _render(paths: Sequence[str], out: str, quiet: bool, formats: Sequence[str] = ("svg",),
            dpi: float = DEFAULT_DPI) -> int:
    """Render every scene, convert its sheets to ``formats`` (PNG at ``dpi`` dots per inch),
    then write all their files at once: any error writes nothing."""
    _distinct_stems(paths)
    check_folder(out)
    if set(formats) - {"svg"}:
        require_cairo()          # a missing cairo is told before anything is computed
    rendered = [render_scene(p) for p in paths]
    refuse_inputs([Path(out) / name for r in rendered for name in output_names(r.files, formats)], paths)
    if "png" in formats:         # every scene's every sheet fits as a PNG before any is drawn
        for r in rendered:
            check_png_sizes(r.files, dpi)
    files: dict[str, str | bytes] = {}
    counts = []
    for path, r in zip(paths, rendered):
        converted = convert(r.files, formats, dpi)
        clash = next((name for name in converted if name in files), None)
        if clash:
            raise OutputError(f"would write {clash}, which another scene writes too; rename one scene",
                              file=path, key="SCENE.toml")
        files.update(converted)
        counts.append(len(converted))
    write_files(files, out, inputs=paths)
    for r, count in zip(rendered, counts):
        if not quiet:
            print(_table(r))
            print(f"  wrote {count} files to {out}/")
        for w in r.warnings:
            print(f"warning: {w}", file=sys.stderr)
    return 0


def _distinct_stems(paths: Sequence[str]) -> None:
    """Refuse two scenes with the same file stem: the second would overwrite the first's files."""
    seen: dict[str, str] = {}
    for p in paths:
        stem = Path(p).stem
        if stem in seen:
            same = Path(seen[stem]).resolve() == Path(p).resolve()
            raise OutputError("given twice; render it once" if same else
                              f"has the same name as {seen[stem]}: both would write {stem}.json and {stem}-*.svg, "
                              "the second over the first; rename one or render them with different -o",
                              file=p, key="SCENE.toml")
        seen[stem] = p


def _check(paths: Sequence[str]) -> int:
    """Lengths, directions, closures and the file contract of each SVG (plans.checking);
    exit 1 when anything fails, a plan without tagged vectors included; a scheme sheet has
    nothing to measure and passes."""
    from .checking import inspect_svg   # here: render and demo need none of it

    bad = total = equations = open_ = failed = 0
    for path in paths:
        r = inspect_svg(path)
        print(f"{path}:")
        if r.kind == "scheme":
            print("  scheme sheet: no vectors to measure (not a plan)")
        elif r.kind == "empty":
            print("  plan drawn with no vector (the pole alone, as its subtitle says): nothing to measure")
        elif r.kind == "assignment":
            print("  assignment sheet: areas left for the student, nothing to measure")
        for m in r.measurements:
            total += 1
            bad += not m.ok
            angle = "∠ —" if math.isnan(m.angle_error) else \
                f"∠ {math.degrees(m.angle_error):.2e}° (tol {math.degrees(m.angle_tolerance):.1e}°)"
            print(f"  {'ok  ' if m.ok else 'FAIL'} {m.quantity:<16} {m.length_mm:10.3f} mm × {m.mu:<8g} = "
                  f"{m.measured:<12.6g} exact {m.value:<12.6g} |Δ| = {m.error:.2e} (tol {m.tolerance:.1e}) {angle}"
                  + (f" — {m.problem}" if m.problem else ""))
        for c in r.closures:
            if not c.ok:
                open_ += 1
                print(f"  FAIL closure at {c.point}: {', '.join(c.ends)} are {c.gap_mm:.3f} mm apart "
                      f"(tol {c.tolerance_mm:.1e} mm)")
        for gid, n in r.equations.items():
            equations += n
            print(f"  {n} closure equations checked in {gid}")
        for c in r.checks:
            if c.ok and c.what.startswith("ε_α"):     # the pair's contact ratio read off the drawing
                print(f"  ok   {c.what}: |Δ| = {c.deviation:.2e} (tol {c.tolerance:.1e})")
        for problem in r.problems:
            print(f"  FAIL {problem}")
        failed += not r.ok
    print(f"{total - bad} vectors within drawing precision, {bad} outside; {equations} closure equations checked, "
          f"{open_} open; {failed} of {len(paths)} files failed")
    return 1 if failed else 0


def _handout(source: str, out: str, quiet: bool, random: str | None, seed: str | None, moodle: str | None = None,
             tolerance: str | None = None) -> int:
    """``plans handout``: variants from a variants file, or ``--random N`` around a base scene;
    every variant solved before anything is written (plans.handout); with ``--moodle`` also
    the Moodle XML question bank (its path checked with -o's, before anything is computed)."""
    from . import handout as ho   # here: the other commands need none of it
    from .handout.moodle import check_bank_path, size_warning

    check_folder(out)
    if tolerance is not None and moodle is None:
        raise OutputError("--tolerance goes with --moodle FILE.xml (the tolerance of its numerical fields)",
                          key="--tolerance")
    tol = ho.parse_tolerance(tolerance) if tolerance is not None else ho.DEFAULT_TOLERANCE
    if moodle is not None:
        check_bank_path(moodle, out)
    require_cairo()              # the answer keys are SVG and PDF
    if random is None:
        if seed is not None:
            raise OutputError("--seed goes with --random N (the variants file gives its variants)", key="--seed")
        h = ho.read_variants(source)
        bar = ho.Progress(len(h.variants), "solving")
        drawn = []
        for v in h.variants:
            drawn.append(ho.solve_variant(h, v))
            bar(v.number, drawn[-1].name)
    else:
        count = _count(random, "--random", 1, ho.MAX_VARIANTS)
        number = _count(seed if seed is not None else "0", "--seed", 0, 2 ** 63 - 1)
        bar = ho.Progress(count, "drawing")
        h, drawn = ho.random_variants(source, count, number, progress=bar)
    bar.close()
    bank, asked, assignments = None, None, None
    if moodle is not None:
        refuse_inputs([Path(moodle)], [p for p in (h.base, h.source) if p is not None], option="--moodle")
        asked = [ho.variant_asked(d) for d in drawn]
        assignments = [ho.assignment_sheets(h, d, a) for d, a in zip(drawn, asked)]   # drawn once: bank and folders
        firsts = [next(iter(sheets.values())) for sheets in assignments]                 # the bank shows the first
        bank = ho.moodle_xml(h, drawn, asked, tolerance=tol, assignments=firsts).encode("utf-8")
    bar = ho.Progress(len(drawn), "writing")
    ho.write_handout(h, drawn, out, progress=bar, asked=asked, assignments=assignments)
    bar.close()
    if bank is not None:
        write_files({Path(moodle).name: bank}, Path(moodle).parent, option="--moodle")   # checked above
    if not quiet:
        lo, hi = ho.BALANCING_RANGE
        kept = ("the train's conditions kept" if h.train else f"balancing masses within {lo:g}…{hi:g} × the base's"
                if h.rotor else f"margins |condition| ≥ {ho.margin_text(h)}")
        extra = f", seed {h.seed}, {kept} ({h.redraws} draw{'s' if h.redraws != 1 else ''} rejected and redrawn)" \
            if h.seed is not None else ""
        print(f"wrote {len(drawn)} variants of {h.base.name}{extra} to {out}/ (open {out}/index.html)"
              + (f"; the Moodle question bank to {moodle} ({len(bank) / 2 ** 20:.2f} MB, tolerance ±{tol * 100:g} %)"
                 if bank is not None else ""))
    if bank is not None and (warning := size_warning(len(bank), len(drawn))) is not None:
        print(f"warning: {moodle}: {warning}", file=sys.stderr)
    for d in drawn:
        for w in d.sheets.warnings:
            print(f"warning: {w}", file=sys.stderr)
    return 0


def _count(text: str, option: str, lo: int, hi: int) -> int:
    """A whole number ``lo``..``hi`` given to ``option`` (one line naming the option otherwise)."""
    try:
        n = int(text)
    except ValueError:
        raise OutputError(f"{text!r} is not a whole number; give one from {lo} to {hi}", key=option) from None
    if not lo <= n <= hi:
        raise OutputError(f"{n} is out of range; give one from {lo} to {hi}", key=option)
    return n


def _examples() -> list[Path]:
    """The bundled scenes: the linkages, then the gear trains (examples/gears), the rotors
    (examples/balancing), the flywheel problems without a linkage (examples/flywheel) and the
    linkages drawing their shaking force (examples/shaking)."""
    out = []
    for package in ("plans.examples", "plans.examples.gears", "plans.examples.balancing", "plans.examples.flywheel",
                    "plans.examples.shaking"):
        root = resources.files(package)
        out += sorted(Path(str(p)) for p in root.iterdir() if p.name.endswith(".toml"))
    return out


def _version() -> str:
    from . import __version__
    return __version__


#: A number on the command line (``--ratio``, ``--tolerance``, ``--module``): ASCII decimal digits, an
#: optional sign, point and exponent — no spaces or line breaks, no "nan", "inf" or "1_000" (which
#: float() would take), since the text also names the files written (synthesis_A_12-gears.svg).
_DECIMAL = re.compile(r"[+-]?([0-9]+(\.[0-9]*)?|\.[0-9]+)([eE][+-]?[0-9]+)?")
#: A whole number on the command line (``--planets``).
_WHOLE = re.compile(r"[+-]?[0-9]+")


def _option(value: str, flag: str, kind: type = float) -> float:
    """A finite number given on the command line as plain decimal text (``kind`` int: a whole
    number), or a one-line error naming ``flag``."""
    whole = kind is int
    if not (_WHOLE if whole else _DECIMAL).fullmatch(value):
        raise SceneError(f"expected {'a whole number' if whole else 'a number'} written in digits "
                         f"(e.g. {'3' if whole else '12 or 7.5'}), got {value!r}", key=flag)
    x = kind(value)
    if not math.isfinite(x):
        raise SceneError(f"{value} is beyond the largest number a double holds; give a finite value", key=flag)
    return x


def _synthesize(args: argparse.Namespace) -> int:
    """``plans gears synthesize``: print the verified candidates and draw the best."""
    from .gears.synthesis import synthesize    # here: the other commands need none of it
    from .pipeline import render
    from .scene import Scene

    ratio = _option(args.ratio, "--ratio")
    kind = args.type.strip().upper()
    planets = int(_option(args.planets, "--planets", int))
    found = synthesize(ratio, kind, planets, tolerance=_option(args.tolerance, "--tolerance"),
                       module=_option(args.module, "--module"))
    if not found:
        print(f"type {kind} cannot reach i = {ratio:g} with {planets} planets within ±{float(args.tolerance):g} "
              f"(external wheels 17 … 100 teeth, rings up to 250); try another type")
        return 0
    check_folder(args.output)
    best = found[0]
    stem = f"synthesis_{kind}_{args.ratio}".replace(".", "_").replace("-", "m").replace("+", "")
    title = f"Planetary train, type {kind}, i = {float(best.ratio):.6g} ({planets} planets)"
    sheets = render(Scene(title=title, points={}, links={}, sliders=(), drive=None, draw=("gears",),
                          gears=best.train), stem=stem)
    write_files(sheets.files, args.output)      # not Sheets.save: errors name -o, not save's folder
    if not args.quiet:
        print(f"type {kind}, i = {ratio:g} ± {float(args.tolerance):g}, {planets} planets: {len(found)} candidates, "
              "smallest first (each solved and checked as a train)")
        print(f"  {'#':>2}  {'teeth':<36} {'ratio':>22}  {'error':>8}  largest z")
        for k, c in enumerate(found, 1):
            teeth = ", ".join(f"z_{n} = {z}" for n, z in c.teeth.items())
            err = (float(c.ratio) - ratio) / ratio
            print(f"  {k:>2}  {teeth:<36} {str(c.ratio) + ' = ' + format(float(c.ratio), '.6g'):>22}  "
                  f"{err:>+8.2%}  {c.size}")
        print(f"  drew the best into {args.output}/{stem}-gears.svg")
    return 0


def _format_options(parser: argparse.ArgumentParser) -> None:
    """``--format`` and ``--dpi`` of render and demo (read as text: plans checks them, so a bad
    value is one line like every other error)."""
    parser.add_argument("--format", default="svg", metavar="LIST",
                        help=f"comma-separated output formats among {','.join(FORMATS)} (default svg); PNG and "
                        "PDF keep the sheet's size in mm and need cairosvg and the cairo library")
    parser.add_argument("--dpi", default=f"{DEFAULT_DPI:g}", metavar="N",
                        help=f"PNG resolution in dots per inch, {MIN_DPI:g} to {MAX_DPI:g} (default {DEFAULT_DPI:g}): "
                        "a side of the PNG is round(mm / 25.4 × N) pixels")


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="plans", description="Velocity and acceleration plans of planar "
                                     "linkages, drawn to scale from an exact vector core.")
    parser.add_argument("--version", action="version", version=f"plans {_version()}")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("render", help="render scene files to SVG and JSON")
    p.add_argument("scenes", nargs="+", metavar="SCENE.toml")
    p.add_argument("-o", "--output", default="output", metavar="DIR")
    p.add_argument("-q", "--quiet", action="store_true")
    _format_options(p)
    c = sub.add_parser("check", help="measure every vector of plan SVGs against its exact value")
    c.add_argument("svgs", nargs="+", metavar="FILE.svg")
    d = sub.add_parser("demo", help="render the bundled textbook examples")
    d.add_argument("-o", "--output", default="output", metavar="DIR")
    d.add_argument("-q", "--quiet", action="store_true")
    _format_options(d)
    h = sub.add_parser("handout", help="variants for a class: assignment sheets, answer keys (SVG, PDF, JSON) "
                       "and index.html")
    h.add_argument("source", metavar="VARIANTS.toml|BASE.toml",
                   help="a variants file (base = SCENE, [[variant]] tables), or with --random a base scene")
    h.add_argument("--random", metavar="N", help="draw N variants around the base scene (lengths ±20 %%, the "
                   "angle over the turn, ω from a standard series), each away from singular positions")
    h.add_argument("--seed", metavar="S", help="seed of --random (default 0): the same seed gives the same files")
    h.add_argument("-o", "--output", default="handout", metavar="DIR")
    h.add_argument("--moodle", metavar="FILE.xml", help="also write a Moodle XML question bank: a category for the "
                   "handout, a Cloze question a variant (the assignment as an image, the data, a numerical field per "
                   "asked quantity); a variant adds about 50 KB, and PHP's default upload limit is 2 MB")
    h.add_argument("--tolerance", metavar="P%", help="tolerance of the Moodle fields, percent of the exact value, "
                   "0.01 … 100 (default 2%%)")
    h.add_argument("-q", "--quiet", action="store_true")
    gr = sub.add_parser("gears", help="gear trains: planetary synthesis")
    gsub = gr.add_subparsers(dest="gears_command", required=True)
    sy = gsub.add_parser("synthesize", help="teeth of a 2K-H planetary train for a ratio: a table of verified "
                         "candidates, smallest first, and the best one drawn")
    sy.add_argument("--ratio", required=True, metavar="I", help="input → output ratio, beyond ±1")
    sy.add_argument("--type", required=True, metavar="A|B|C|D", help="A: sun-planet-ring; B: compound planet, "
                    "sun and ring; C: compound planet, two rings; D: compound planet, two suns")
    sy.add_argument("--planets", required=True, metavar="K", help="equally spaced planets, 2 … 12")
    sy.add_argument("--tolerance", default="0.01", metavar="T", help="relative tolerance of the ratio (default 0.01)")
    sy.add_argument("--module", default="1", metavar="M", help="module of every wheel, mm (default 1)")
    sy.add_argument("-o", "--output", default="output", metavar="DIR")
    sy.add_argument("-q", "--quiet", action="store_true")
    b = sub.add_parser("bench", help="measure what accuracy costs in time: tables, charts and bench.json "
                       "(under two minutes on two cores)")
    b.add_argument("-o", "--output", default="output/bench", metavar="DIR")
    size = b.add_mutually_exclusive_group()
    size.add_argument("--full", action="store_true", help="every example, tolerance and repeat (several minutes; "
                      "the estimate is printed first)")
    size.add_argument("--quick", action="store_true", help="a few small cases only (seconds; for tests)")
    args = parser.parse_args(argv)
    try:
        if args.command in ("render", "demo"):
            formats = parse_formats(args.format)      # both refused before anything is computed
            dpi = parse_dpi(args.dpi)
            scenes = args.scenes if args.command == "render" else [str(p) for p in _examples()]
            return _render(scenes, args.output, args.quiet, formats, dpi)
        if args.command == "handout":
            return _handout(args.source, args.output, args.quiet, args.random, args.seed, args.moodle,
                            args.tolerance)
        if args.command == "gears":
            return _synthesize(args)
        if args.command == "bench":
            from .bench import run   # imported here: the other commands need none of it

            check_folder(args.output)   # a bad -o is told before the minutes of measuring
            run(args.output, quick=args.quick, full=args.full)
            return 0
        return _check(args.svgs)
    except PlansError as exc:
        print(f"plans: error: {one_line(str(exc))}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())

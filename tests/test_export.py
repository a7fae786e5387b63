"""PNG and PDF export (plans/export.py, ``--format``, ``--dpi``): the sheet's physical size kept.

A PNG is round(mm / 25.4 × dpi) pixels a side and states its resolution (pHYs); a PDF page is
mm × 72 / 25.4 points a side; both are the same bytes every time. Bad ``--format``/``--dpi``
values are one line, exit 2, nothing written; without cairo, PNG/PDF say what to install and
SVG still works. The tests that draw need cairo: without it they are skipped, saying so.
"""

from __future__ import annotations

import re
import struct
import sys

import pytest

from plans.cli import main
from plans.errors import OutputError
from plans.export import (DEFAULT_DPI, convert, parse_dpi, parse_formats, require_cairo, sheet_size_mm,
                          svg_to_pdf, svg_to_png)
from plans.output import write_files
from plans.pipeline import render_scene

from conftest import CRANK_SLIDER

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def sheets() -> dict[str, str]:
    """The crank-slider's files (three SVG sheets and the JSON report), computed once."""
    return render_scene(CRANK_SLIDER).files


@pytest.fixture
def cairo():
    """Skip, saying why, when cairosvg or the cairo library cannot be loaded."""
    try:
        require_cairo()
    except OutputError as exc:
        pytest.skip(f"PNG/PDF export needs cairo, which cannot be loaded here: {exc}")


def svg_names(files) -> list[str]:
    return [name for name in files if name.endswith(".svg")]


def sheet_mm(svg: str) -> tuple[float, float]:
    """Width and height in mm, read from the root <svg> independently of plans.export."""
    root = re.search(r"<svg\b[^>]*>", svg).group(0)
    w = float(re.search(r'\swidth="([0-9.]+)mm"', root).group(1))
    h = float(re.search(r'\sheight="([0-9.]+)mm"', root).group(1))
    return w, h


def png_chunks(png: bytes) -> dict[bytes, bytes]:
    """Chunk type → data of the first chunk of each type."""
    assert png[:8] == PNG_SIGNATURE
    chunks, at = {}, 8
    while at < len(png):
        length, kind = struct.unpack(">I4s", png[at:at + 8])
        chunks.setdefault(kind, png[at + 8:at + 8 + length])
        at += 12 + length
    assert at == len(png) and b"IEND" in chunks
    return chunks


def png_pixels(png: bytes) -> tuple[int, int]:
    """Width and height from the IHDR chunk."""
    assert png[12:16] == b"IHDR"
    return struct.unpack(">II", png[16:24])


def pdf_media_box(pdf: bytes) -> list[float]:
    assert pdf.startswith(b"%PDF-")
    boxes = re.findall(rb"/MediaBox\s*\[\s*([-0-9.\s]+)\]", pdf)
    assert len(boxes) == 1, boxes           # one page
    return [float(x) for x in boxes[0].split()]


@pytest.mark.parametrize("dpi", [96, 150, 72.5])
def test_png_pixels_are_the_sheet_millimetres_at_the_dpi(sheets, cairo, dpi):
    for name in svg_names(sheets):
        w_mm, h_mm = sheet_mm(sheets[name])
        png = svg_to_png(sheets[name], dpi)
        assert png_pixels(png) == (round(w_mm / 25.4 * dpi), round(h_mm / 25.4 * dpi)), name
        x, y, unit = struct.unpack(">IIB", png_chunks(png)[b"pHYs"])
        assert unit == 1 and x == y == round(dpi / 0.0254)      # pixels per metre
        assert sheet_size_mm(sheets[name]) == (w_mm, h_mm)


def test_pdf_page_is_the_sheet(sheets, cairo):
    for name in svg_names(sheets):
        w_mm, h_mm = sheet_mm(sheets[name])
        x0, y0, x1, y1 = pdf_media_box(svg_to_pdf(sheets[name]))
        assert (x0, y0) == (0, 0)
        assert x1 == pytest.approx(w_mm * 72 / 25.4, abs=0.01), name
        assert y1 == pytest.approx(h_mm * 72 / 25.4, abs=0.01), name


def test_png_and_pdf_are_byte_stable(sheets, cairo):
    svg = sheets[svg_names(sheets)[0]]
    assert svg_to_png(svg, DEFAULT_DPI) == svg_to_png(svg, DEFAULT_DPI)
    first = svg_to_pdf(svg)
    assert b"/CreationDate" not in first
    assert first == svg_to_pdf(svg)


def test_convert_puts_png_and_pdf_beside_each_svg(sheets, cairo):
    stems = [name[:-4] for name in svg_names(sheets)]
    json_names = [name for name in sheets if name.endswith(".json")]
    everything = convert(sheets, ["svg", "png", "pdf"], 100)
    assert set(everything) == {*sheets, *(s + ".png" for s in stems), *(s + ".pdf" for s in stems)}
    assert all(everything[n] == sheets[n] for n in sheets)
    assert all(isinstance(everything[s + ext], bytes) for s in stems for ext in (".png", ".pdf"))
    png_only = convert(sheets, ["png"], 100)
    assert set(png_only) == {*json_names, *(s + ".png" for s in stems)}


def test_write_files_writes_bytes_and_text(tmp_path):
    data = bytes(range(256))
    written = write_files({"a.bin": data, "b.txt": "μ π\n"}, tmp_path / "out")
    assert [p.name for p in written] == ["a.bin", "b.txt"]
    assert (tmp_path / "out" / "a.bin").read_bytes() == data
    assert (tmp_path / "out" / "b.txt").read_bytes() == "μ π\n".encode("utf-8")


def test_cli_writes_svg_png_and_pdf_side_by_side(tmp_path, cairo):
    out = tmp_path / "out"
    assert main(["render", str(CRANK_SLIDER), "-o", str(out), "--format", "svg,png,pdf", "--dpi", "120", "-q"]) == 0
    names = {p.name for p in out.iterdir()}
    svgs = sorted(n for n in names if n.endswith(".svg"))
    assert len(svgs) >= 3
    for svg in svgs:
        stem = svg[:-4]
        assert {stem + ".png", stem + ".pdf"} <= names
        w_mm, h_mm = sheet_mm((out / svg).read_text(encoding="utf-8"))
        assert png_pixels((out / (stem + ".png")).read_bytes()) == (round(w_mm / 25.4 * 120),
                                                                    round(h_mm / 25.4 * 120))
        assert pdf_media_box((out / (stem + ".pdf")).read_bytes())[2] == pytest.approx(w_mm * 72 / 25.4, abs=0.01)
    assert f"{CRANK_SLIDER.stem}.json" in names
    assert names == {*svgs, *(s[:-4] + ".png" for s in svgs), *(s[:-4] + ".pdf" for s in svgs),
                     f"{CRANK_SLIDER.stem}.json"}


def test_cli_png_alone_writes_png_and_json_but_no_svg(tmp_path, cairo):
    out = tmp_path / "out"
    assert main(["render", str(CRANK_SLIDER), "-o", str(out), "--format", "png", "-q"]) == 0
    names = {p.name for p in out.iterdir()}
    assert f"{CRANK_SLIDER.stem}.json" in names
    assert not any(n.endswith(".svg") or n.endswith(".pdf") for n in names)
    pngs = [n for n in names if n.endswith(".png")]
    assert len(pngs) >= 3 and len(names) == len(pngs) + 1
    w, h = png_pixels((out / pngs[0]).read_bytes())
    assert w > 0 and h > 0


@pytest.mark.parametrize("args, culprit", [
    (["--format", "jpeg"], "jpeg"),
    (["--format", ""], "--format"),
    (["--format", "svg,,png"], "--format"),
    (["--dpi", "0"], "--dpi"),
    (["--dpi", "nan"], "nan"),
    (["--dpi", "inf"], "inf"),
    (["--dpi", "1e9"], "--dpi"),
    (["--dpi", "many"], "many"),
])
@pytest.mark.parametrize("command", ["render", "demo"])
def test_bad_format_or_dpi_is_one_line_exit_2_nothing_written(tmp_path, capsys, args, culprit, command):
    out = tmp_path / "out"
    scenes = [str(CRANK_SLIDER)] if command == "render" else []
    assert main([command, *scenes, "-o", str(out), *args]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    lines = captured.err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("plans: error: "), captured.err
    assert culprit in lines[0]
    assert "svg, png, pdf" in lines[0] if "--format" in args else "10 to 2400" in lines[0]
    assert not out.exists()


def test_format_and_dpi_values():
    assert parse_formats("SVG, pdf,svg") == ("svg", "pdf")
    assert parse_dpi("300") == 300.0 and parse_dpi(72.5) == 72.5
    for bad in ("", " ", "svg,", "png,gif"):
        with pytest.raises(OutputError, match="--format"):
            parse_formats(bad)
    for bad in ("0", "-150", "9.99", "2400.1", "nan", "-inf", ""):
        with pytest.raises(OutputError, match="--dpi"):
            parse_dpi(bad)


def test_a_png_beyond_cairo_is_refused_with_the_dpi_that_fits():
    svg = '<svg xmlns="http://www.w3.org/2000/svg" width="5000mm" height="3000mm" viewBox="0 0 5000 3000"/>'
    with pytest.raises(OutputError, match=r"--dpi.*give --dpi \d+ or less") as info:
        svg_to_png(svg, 2400)
    fits = int(re.search(r"give --dpi (\d+)", str(info.value)).group(1))
    w, h = round(5000 / 25.4 * fits), round(3000 / 25.4 * fits)
    assert max(w, h) <= 32767 and w * h <= 2 ** 28


def test_without_cairo_png_says_what_to_install_and_svg_still_works(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "cairosvg", None)      # `import cairosvg` now fails
    out = tmp_path / "out"
    assert main(["render", str(CRANK_SLIDER), "-o", str(out), "--format", "svg,pdf", "-q"]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and "pip install cairosvg" in err[0] and "libcairo2" in err[0], err
    assert not out.exists()
    assert main(["render", str(CRANK_SLIDER), "-o", str(out), "-q"]) == 0
    assert any(p.suffix == ".svg" for p in out.iterdir())
    assert not any(p.suffix in (".png", ".pdf") for p in out.iterdir())

"""PNG and PDF beside the SVG sheets, at the sheet's physical size.

Every sheet is an SVG whose root gives its size in millimetres (``width="241.8mm"``) and whose
user unit is the millimetre. The conversion (cairosvg, drawing with the system's cairo library)
keeps that size:

* PNG: ``round(mm / 25.4 * dpi)`` pixels a side, and a ``pHYs`` chunk stating the resolution
  (pixels per metre), so a viewer or printer puts 100 mm of the sheet on 100 mm of paper;
* PDF: one page of ``mm * 72 / 25.4`` points a side (1 pt = 1/72 inch), vector drawing.

Both are byte-stable: the same SVG and DPI give the same bytes (cairo's PDF creation date is
left out; the ``/Producer`` entry names the cairo version, so bytes may differ between
machines with different cairo versions, never between runs).

cairosvg is imported only here, and only when a PNG or PDF is asked for: ``plans render``
without ``--format`` never needs cairo. When it cannot be loaded the error says what to
install. Nothing here writes a file.
"""

from __future__ import annotations

import math
import re
import struct
import zlib
from typing import Mapping, Sequence

from .errors import OutputError

__all__ = ["FORMATS", "DEFAULT_DPI", "MIN_DPI", "MAX_DPI", "MAX_PNG_SIDE", "MAX_PNG_PIXELS",
           "parse_formats", "parse_dpi", "require_cairo", "sheet_size_mm", "png_size", "check_png_sizes",
           "output_names",
           "svg_to_png", "svg_to_pdf", "convert"]

#: Output formats ``--format`` accepts, in the order their files are listed.
FORMATS = ("svg", "png", "pdf")
#: Default PNG resolution, dots per inch: 150 dpi is a sharp print of line drawings and
#: keeps an A4-sized sheet near 1750 × 1240 px.
DEFAULT_DPI = 150.0
#: Accepted PNG resolutions, dots per inch (inclusive).
MIN_DPI, MAX_DPI = 10.0, 2400.0
#: Largest PNG side, pixels: cairo's own limit for an image surface.
MAX_PNG_SIDE = 32767
#: Largest PNG, pixels: 2**28 px are a 1 GiB drawing buffer (4 bytes a pixel).
MAX_PNG_PIXELS = 2 ** 28
#: Millimetres per inch.
MM_PER_INCH = 25.4
#: PDF points per inch.
PT_PER_INCH = 72.0

_INSTALL = "pip install cairosvg, and the cairo library (Debian/Ubuntu: apt install libcairo2)"
_ROOT = re.compile(r"<svg\b[^>]*>", re.S)
_LENGTH = r'\s{0}\s*=\s*["\']\s*([0-9.eE+-]+)\s*(mm)?\s*["\']'


def parse_formats(text: str) -> tuple[str, ...]:
    """The formats of a ``--format`` value (``"svg,png,pdf"``; case and spaces ignored,
    duplicates dropped), in the order given. Raises :class:`OutputError` naming an unknown
    or empty one."""
    names = [part.strip().lower() for part in str(text).split(",")]
    allowed = ", ".join(FORMATS)
    if not any(names):
        raise OutputError(f"no format given; choose one or more of {allowed}, separated by commas",
                          key="--format")
    for name in names:
        if not name:
            raise OutputError(f"an empty format in {text!r}; choose one or more of {allowed}, separated by commas",
                              key="--format")
        if name not in FORMATS:
            raise OutputError(f"unknown format {name!r}; choose one or more of {allowed}, separated by commas",
                              key="--format")
    return tuple(dict.fromkeys(names))


def parse_dpi(value: str | float) -> float:
    """The PNG resolution of a ``--dpi`` value, dots per inch: a finite number from
    :data:`MIN_DPI` to :data:`MAX_DPI`. Raises :class:`OutputError` otherwise."""
    try:
        dpi = float(value)
    except (TypeError, ValueError):
        dpi = math.nan
        shown = repr(value)
    else:
        shown = str(value)
    if not (math.isfinite(dpi) and MIN_DPI <= dpi <= MAX_DPI):
        raise OutputError(f"{shown} is not a resolution; give dots per inch as a number from {MIN_DPI:g} to "
                          f"{MAX_DPI:g} (default {DEFAULT_DPI:g})", key="--dpi")
    return dpi


def require_cairo():
    """The cairosvg module, imported now; :class:`OutputError` saying what to install when it
    or the cairo library cannot be loaded."""
    try:
        import cairosvg  # noqa: PLC0415  (lazy: only PNG and PDF need cairo)
    except (ImportError, OSError) as exc:
        reason = (str(exc).strip().splitlines() or [type(exc).__name__])[0][:160]
        raise OutputError(f"PNG and PDF need cairosvg and the cairo library, which cannot be loaded ({reason}); "
                          f"{_INSTALL}; or use --format svg", key="--format") from None
    return cairosvg


def sheet_size_mm(svg_text: str) -> tuple[float, float] | None:
    """The sheet's width and height in millimetres, from its root ``<svg>``'s ``width`` and
    ``height`` (``"241.8mm"``; a bare number is read as mm, since one user unit is 1 mm), or
    None when the root gives no such size."""
    root = _ROOT.search(svg_text)
    if root is None:
        return None
    size = []
    for name in ("width", "height"):
        m = re.search(_LENGTH.format(name), root.group(0))
        if m is None:
            return None
        try:
            size.append(float(m.group(1)))
        except ValueError:
            return None
    return size[0], size[1]


def png_size(width_mm: float, height_mm: float, dpi: float) -> tuple[int, int]:
    """Pixels of a sheet ``width_mm`` × ``height_mm`` at ``dpi`` dots per inch:
    ``round(mm / 25.4 * dpi)`` a side."""
    return round(width_mm / MM_PER_INCH * dpi), round(height_mm / MM_PER_INCH * dpi)


def svg_to_png(svg_text: str, dpi: float) -> bytes:
    """The sheet as a PNG of ``round(mm / 25.4 * dpi)`` pixels a side (``dpi``: dots per inch),
    with a ``pHYs`` chunk stating that resolution in pixels per metre. Byte-stable.

    Raises :class:`OutputError` when cairo cannot be loaded, when the image would exceed
    :data:`MAX_PNG_SIDE` px a side or :data:`MAX_PNG_PIXELS` px (the message gives the largest
    DPI that fits), or when the SVG cannot be drawn."""
    size = sheet_size_mm(svg_text)
    if size is not None:
        _check_png_size(size, dpi)
    cairosvg = require_cairo()
    try:
        png = cairosvg.svg2png(bytestring=svg_text.encode("utf-8"), dpi=dpi)
    except Exception as exc:    # cairosvg raises what its parser or cairo raise
        raise OutputError(f"cannot draw the sheet as PNG ({type(exc).__name__}: {exc})", key="--format") from None
    return _with_resolution(png, dpi)


def svg_to_pdf(svg_text: str) -> bytes:
    """The sheet as a one-page vector PDF whose page is ``mm * 72 / 25.4`` points a side, so
    it prints at the sheet's size. Byte-stable: cairo's ``/CreationDate`` is left out.

    Raises :class:`OutputError` when cairo cannot be loaded or the SVG cannot be drawn."""
    require_cairo()
    import cairocffi  # noqa: PLC0415  (loaded by cairosvg above)
    from cairosvg.surface import PDFSurface  # noqa: PLC0415

    class _Undated(PDFSurface):
        """cairosvg's PDF surface without the creation date cairo would stamp on it."""

        def _create_surface(self, width, height):
            surface, width, height = super()._create_surface(width, height)
            if hasattr(surface, "set_metadata"):
                try:    # a date cairo cannot read is left out (cairo >= 1.16)
                    surface.set_metadata(cairocffi.PDF_METADATA_CREATE_DATE, "")
                except (AttributeError, cairocffi.CairoError):
                    pass
            return surface, width, height

    try:
        pdf = _Undated.convert(bytestring=svg_text.encode("utf-8"))
    except Exception as exc:    # cairosvg raises what its parser or cairo raise
        raise OutputError(f"cannot draw the sheet as PDF ({type(exc).__name__}: {exc})", key="--format") from None
    return _undated(pdf)


def output_names(files: Mapping[str, str], formats: Sequence[str]) -> list[str]:
    """The names :func:`convert` gives ``files`` in ``formats``, without converting anything (to
    check the targets before any sheet is drawn)."""
    names = []
    for name in files:
        if not name.endswith(".svg"):
            names.append(name)
            continue
        names += [f"{name[:-len('.svg')]}.{f}" for f in FORMATS if f in formats]
    return names


def convert(files: Mapping[str, str], formats: Sequence[str], dpi: float = DEFAULT_DPI) -> dict[str, str | bytes]:
    """The files to write for ``formats``: beside each ``X.svg`` its ``X.png`` (at ``dpi``
    dots per inch) and ``X.pdf`` when asked for; ``X.svg`` itself only when ``"svg"`` is among
    ``formats``; every other file (the JSON report) as it is. Names keep their order.

    Raises :class:`OutputError` naming the sheet when one cannot be converted; nothing is
    written either way."""
    wanted = set(formats)
    unknown = wanted - set(FORMATS)
    if unknown or not wanted:
        raise OutputError(f"unknown format {sorted(unknown)[0]!r}" if unknown else "no format given",
                          key="--format")
    if "png" in wanted:        # every sheet's pixel size before any is drawn
        check_png_sizes(files, dpi)
    out: dict[str, str | bytes] = {}
    for name, text in files.items():
        if not name.endswith(".svg"):
            out[name] = text
            continue
        stem = name[:-len(".svg")]
        if "svg" in wanted:
            out[name] = text
        try:
            if "png" in wanted:
                out[stem + ".png"] = svg_to_png(text, dpi)
            if "pdf" in wanted:
                out[stem + ".pdf"] = svg_to_pdf(text)
        except OutputError as exc:
            raise OutputError(exc.message, file=exc.file or name, key=exc.key) from None
    return out


def check_png_sizes(files: Mapping[str, str], dpi: float) -> None:
    """Refuse, naming the sheet, a PNG at ``dpi`` dots per inch of any SVG sheet among ``files``
    (name → text) larger than cairo can draw: called for every sheet before any is drawn."""
    for name, text in files.items():
        size = sheet_size_mm(text) if name.endswith(".svg") else None
        if size is not None:
            try:
                _check_png_size(size, dpi)
            except OutputError as exc:
                raise OutputError(exc.message, file=name, key=exc.key) from None


def _check_png_size(size: tuple[float, float], dpi: float) -> None:
    """Refuse a PNG larger than cairo (or a sane amount of memory) can hold."""
    w, h = png_size(*size, dpi)
    if max(w, h) <= MAX_PNG_SIDE and w * h <= MAX_PNG_PIXELS:
        return
    side_in = max(size) / MM_PER_INCH
    area_in2 = size[0] * size[1] / MM_PER_INCH ** 2
    fits = min((MAX_PNG_SIDE - 0.5) / side_in, math.sqrt(MAX_PNG_PIXELS / area_in2) * 0.999)
    raise OutputError(f"a {size[0]:g} × {size[1]:g} mm sheet at {dpi:g} dpi would be a {w} × {h} px PNG, beyond "
                      f"the {MAX_PNG_SIDE} px a side and {MAX_PNG_PIXELS} px cairo can draw here; give --dpi "
                      f"{math.floor(fits)} or less", key="--dpi")


def _chunk(kind: bytes, data: bytes) -> bytes:
    """A PNG chunk: length, type, data, CRC of type and data."""
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def _with_resolution(png: bytes, dpi: float) -> bytes:
    """``png`` with a ``pHYs`` chunk (pixels per metre, both axes) right after its IHDR,
    unless a chunk before the image data states a resolution already."""
    signature, ihdr_end = 8, 8 + 4 + 4 + 13 + 4
    if png[12:16] != b"IHDR":
        return png
    at = signature
    while at + 8 <= len(png):
        length, kind = struct.unpack(">I4s", png[at:at + 8])
        if kind == b"pHYs":
            return png
        if kind == b"IDAT":
            break
        at += 12 + length
    per_metre = round(dpi / MM_PER_INCH * 1000)
    phys = _chunk(b"pHYs", struct.pack(">IIB", per_metre, per_metre, 1))
    return png[:ihdr_end] + phys + png[ihdr_end:]


def _undated(pdf: bytes) -> bytes:
    """``pdf`` without a ``/CreationDate`` entry (a cairo that ignored the request): the entry
    is overwritten with spaces of its own length, so every byte offset of the xref table stays
    true."""
    return re.sub(rb"/CreationDate\s*\((?:[^()\\]|\\.)*\)", lambda m: b" " * len(m.group(0)), pdf)

"""What the pipeline gives for one scene: :class:`Rendered` (its files, name → text, with its
motion, scales, warnings and forces) and, for the Python API, :class:`Sheets` and
:class:`Sheet`, which display themselves in Jupyter and save their files (SVG, PNG, PDF and
the JSON report), all or nothing.

Imports nothing of the pipeline's stages, sheets or report."""

from __future__ import annotations

import base64
import html
import json
import numbers
from dataclasses import dataclass
from pathlib import Path
from typing import Iterator, Sequence

from ..constructions import Scales
from ..errors import OutputError
from ..export import (DEFAULT_DPI, MAX_DPI, MIN_DPI, convert, output_names, parse_dpi, parse_formats,
                      require_cairo)
from ..gears import GearAnalysis
from ..kinematics import Motion
from ..kinetostatics import Forces
from ..output import check_folder, refuse_inputs, write_files

__all__ = ["Rendered", "Sheet", "Sheets", "save_files"]


@dataclass(frozen=True)
class Rendered:
    """The files of one scene (name → text), its motion, scales and warnings (motion and scales
    are None for a gear train alone)."""

    stem: str
    files: dict[str, str]
    motion: Motion
    scales: Scales
    warnings: tuple[str, ...]
    forces: Forces | None = None    # the force analysis, when the scene asks for it
    train: GearAnalysis | None = None   # the gear train, when the scene has [gears]
    source: str | None = None   # the scene file read, when one was: save never writes over it


@dataclass(frozen=True)
class Sheet:
    """One drawn sheet: ``name`` (``"velocity"``, ``"acceleration-30"``: the file name without
    the stem and ``.svg``), ``file`` (``"four_bar-velocity-30.svg"``) and ``svg`` (its text).
    Jupyter displays it (``_repr_svg_``)."""

    name: str
    file: str
    svg: str

    def _repr_svg_(self) -> str:
        return self.svg

    def save(self, folder: str | Path, formats: str | Sequence[str] = ("svg",), *,
             dpi: float = DEFAULT_DPI) -> list[Path]:
        """Write this sheet into ``folder`` in ``formats`` (see :meth:`Sheets.save`)."""
        return save_files({self.file: self.svg}, folder, formats, dpi)


@dataclass(frozen=True)
class Sheets(Rendered):
    """What :func:`render` computed for one scene: ``files`` (file name → text: every sheet's
    SVG and the JSON report), ``motion`` (:class:`~plans.kinematics.Motion`), ``scales``,
    ``warnings`` and ``stem``; nothing is written until :meth:`save`.

    ``sheets`` maps a sheet's name (``"scheme"``, ``"velocity-30"``) to its :class:`Sheet`;
    ``sheets_[name]``, iteration and ``len`` go through them too. ``report`` is the JSON report
    as a dict. In Jupyter the result shows every sheet (``_repr_html_``), or the first one where
    only SVG is shown (``_repr_svg_``)."""

    @property
    def sheets(self) -> dict[str, Sheet]:
        prefix = f"{self.stem}-"
        return {name[len(prefix):-len(".svg")]: Sheet(name[len(prefix):-len(".svg")], name, text)
                for name, text in self.files.items() if name.endswith(".svg")}

    @property
    def json(self) -> str:
        """The JSON report's text (the file ``<stem>.json``)."""
        return self.files[f"{self.stem}.json"]

    @property
    def title(self) -> str:
        """The scene's title (as its report gives it)."""
        return self.report["title"]

    @property
    def report(self) -> dict:
        """The JSON report, parsed: ``report["positions"][i]["points"]["B"]["v"]``."""
        return json.loads(self.json)

    def __getitem__(self, name: str) -> Sheet:
        sheets = self.sheets
        if name not in sheets:
            raise KeyError(f"no sheet {name!r}; the sheets are {', '.join(sheets) or 'none'}")
        return sheets[name]

    def __iter__(self) -> Iterator[Sheet]:
        return iter(self.sheets.values())

    def __len__(self) -> int:
        return sum(name.endswith(".svg") for name in self.files)

    def _repr_svg_(self) -> str | None:
        first = next(iter(self.sheets.values()), None)
        return None if first is None else first.svg

    def _repr_html_(self) -> str:
        """Every sheet, one below the other, each an ``<img>`` of its SVG (kept apart so that
        the ids of one sheet never meet another's), with its name above it."""
        parts = [f"<div><p><b>{html.escape(self.title)}</b> — {len(self)} sheets "
                 f"({html.escape(self.stem)})</p>"]
        for w in self.warnings:
            parts.append(f"<p>warning: {html.escape(w)}</p>")
        for sheet in self:
            data = base64.b64encode(sheet.svg.encode("utf-8")).decode("ascii")
            parts.append(f'<figure style="margin:0 0 1em 0"><figcaption>{html.escape(sheet.name)}</figcaption>'
                         f'<img src="data:image/svg+xml;base64,{data}" alt="{html.escape(sheet.file)}" '
                         f'style="max-width:100%"></figure>')
        return "".join(parts) + "</div>"

    def save(self, folder: str | Path, formats: str | Sequence[str] = ("svg",), *,
             dpi: float = DEFAULT_DPI) -> list[Path]:
        """Write the sheets in ``formats`` (``("svg", "png", "pdf")`` or ``"svg,png"``; PNG at
        ``dpi`` dots per inch) and the JSON report into ``folder`` (made if needed), as
        ``plans render --format`` does: all or nothing, nothing written on any error
        (:class:`~plans.errors.OutputError`, naming ``folder``, ``formats`` or ``dpi``), nor over
        the scene file it was rendered from (a scene ``x.json`` saved into its own folder).
        ``formats`` is a string of comma-separated names or a list or tuple of names; ``dpi``
        any real number from 10 to 2400 (``numpy`` numbers too; not a string). Returns the
        paths written."""
        return save_files(self.files, folder, formats, dpi, inputs=[self.source] if self.source else [])


#: The command line's words for save's arguments (errors raised below name the argument).
_ARGUMENTS = {"-o": "folder", "--format": "formats", "--dpi": "dpi"}


def _in_api_words(exc: OutputError) -> OutputError:
    """``exc`` naming ``save``'s argument instead of the command line's option."""
    message = exc.message
    for flag, words in (("use --format svg", 'pass formats="svg"'), ("give --dpi", "give dpi ="),
                        ("--format", "formats"), ("--dpi", "dpi"), ("another -o", "another folder"),
                        ("choose a folder for -o", "give the path of a folder"), ("for -o", "for folder")):
        message = message.replace(flag, words)
    return OutputError(message, file=exc.file, key=_ARGUMENTS.get(exc.key or "", exc.key))


def save_files(files: dict[str, str], folder: str | Path, formats: str | Sequence[str], dpi: float, *,
               inputs: Sequence[str | Path] = ()) -> list[Path]:
    """Write ``files`` (name → text) into ``folder`` in ``formats`` at ``dpi``, all or nothing,
    never over one of ``inputs`` (the scene file read). Every argument is checked first, by the
    command line's own checks of ``-o``, ``--format`` and ``--dpi``; an error names the argument
    (``folder``, ``formats``, ``dpi``)."""
    if isinstance(folder, bool) or not isinstance(folder, (str, Path)) or not str(folder).strip():
        raise OutputError(f"folder is the path of a folder (a str or Path), got {folder!r}", key="folder")
    if isinstance(formats, str):
        text = formats
    elif isinstance(formats, (list, tuple)) and all(isinstance(f, str) for f in formats):
        text = ",".join(formats)
    else:
        raise OutputError(f"formats is \"svg,png\" or a list such as [\"svg\", \"png\"] of svg, png, pdf; got "
                          f"{formats!r}", key="formats")
    if isinstance(dpi, bool) or not isinstance(dpi, numbers.Real):
        raise OutputError(f"dpi is a number of dots per inch from {MIN_DPI:g} to {MAX_DPI:g}, got {dpi!r}", key="dpi")
    try:
        wanted = parse_formats(text)
        dpi = parse_dpi(dpi)
        check_folder(folder)
        refuse_inputs([Path(folder) / name for name in output_names(files, wanted)], inputs)
        if set(wanted) - {"svg"}:
            require_cairo()
        return write_files(convert(files, wanted, dpi), folder, inputs=inputs)
    except OutputError as exc:
        raise _in_api_words(exc) from None

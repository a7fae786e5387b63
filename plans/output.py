"""Writing the rendered files: all or nothing.

Every file is first written to a hidden temporary next to its target (``.NAME.XXXXXXXX.tmp``,
created with mode 0o666 so the user's umask applies, as for any file the user creates); only
when every temporary is complete are they renamed onto their targets. Any error on the way
(a folder where a file goes, a full disk, no permission) removes every temporary, and the
folders this call created, and is reported as one :class:`~plans.errors.OutputError`.
"""

from __future__ import annotations

import errno
import os
import secrets
from pathlib import Path
from typing import Iterable, Mapping

from .errors import OutputError

__all__ = ["write_files", "check_folder"]

#: Option named in output errors.
OPTION = "-o"


def refuse_inputs(targets: Iterable[str | Path], inputs: Iterable[str | Path], option: str = OPTION) -> None:
    """Refuse, before anything is written, an output path that names one of ``inputs`` (the
    files the run read: links and ``..`` resolved); the error names ``option``, which chose it."""
    read = [Path(p) for p in inputs]
    for target in map(Path, targets):
        clash = next((p for p in read if _same_file(p, target)), None)
        if clash is not None:
            raise OutputError(f"would overwrite the input file {clash} with an output of the same name; choose "
                              f"another {option} (or rename the input)", file=str(target), key=option)


def _same_file(a: Path, b: Path) -> bool:
    """Whether paths ``a`` and ``b`` name one existing file (links and ``..`` resolved)."""
    try:
        return a.exists() and b.exists() and os.path.samefile(a, b)
    except OSError:
        return False


def check_folder(out_dir: str | Path, option: str = OPTION) -> None:
    """Refuse an output folder that cannot be made or written to, before anything is computed:
    an existing file, a path below a file, a folder (or its nearest existing parent) without
    write permission. ``option``: the command-line option that named it, as the errors say."""
    out = Path(out_dir)
    probe = out
    while not probe.exists() and not probe.is_symlink():
        if probe.parent == probe:
            break
        probe = probe.parent
    if probe.exists() and not probe.is_dir():
        what = "is a file" if probe == out else f"lies below the file {probe}"
        raise OutputError(f"{what}, not a folder; choose a folder for {option}", file=str(out), key=option)
    if probe.exists() and not _writable(probe):
        where = "" if probe == out else f" ({probe}, where it would be made)"
        raise OutputError(f"no permission to write in this folder{where}; choose another {option} or change its "
                          "permissions", file=str(out), key=option)


def _writable(folder: Path) -> bool:
    """Whether files can be created in ``folder`` (as far as permissions tell)."""
    return os.access(folder, os.W_OK | os.X_OK)


def write_files(files: Mapping[str, str | bytes], out_dir: str | Path, *, inputs: Iterable[str | Path] = (),
                option: str = OPTION) -> list[Path]:
    """Write ``files`` (name → text, written as UTF-8, or bytes, written as they are: a PNG,
    a PDF) into ``out_dir`` (made if needed), all or nothing. An output that would replace one
    of ``inputs`` (the files the run read) is refused before anything is written. ``option``:
    the command-line option that named the files' place, as the errors say."""
    out = Path(out_dir)
    check_folder(out, option)
    targets = [out / name for name in files]
    refuse_inputs(targets, inputs, option)
    for target in targets:
        if target.is_dir() or (target.exists() and not target.is_file()):
            raise OutputError("a folder (or another non-file) is where this output file goes; move it away or "
                              f"choose another {option}", file=str(target), key=option)
    made = _make_folder(out, option)
    temps: list[Path] = []
    current = out
    try:
        for target, content in zip(targets, files.values()):
            current = target
            data = content if isinstance(content, bytes) else content.encode("utf-8")
            temps.append(_temporary(out, target.name, data))
        for tmp, target in zip(temps, targets):   # targets checked above: a rename fails only on a broken disk
            current = target
            os.replace(tmp, target)
    except BaseException as exc:       # a full disk, no permission … or Ctrl-C: leave nothing behind
        for tmp in temps:
            _remove(tmp)
        _remove_folders(made)
        if isinstance(exc, OSError):
            raise OutputError(_why(exc, option), file=str(current), key=option) from None
        raise
    return targets


def _make_folder(out: Path, option: str = OPTION) -> list[Path]:
    """Make ``out`` and its missing parents; the folders made, outermost first."""
    missing = []
    probe = out
    while not probe.exists():
        missing.append(probe)
        if probe.parent == probe:
            break
        probe = probe.parent
    made = []
    try:
        for folder in reversed(missing):
            os.mkdir(folder)
            made.append(folder)
    except OSError as exc:
        _remove_folders(made)
        raise OutputError(_why(exc, option), file=str(out), key=option) from None
    return made


def _remove_folders(made: list[Path]) -> None:
    """Remove the folders this call made (outermost first in ``made``), innermost first."""
    for folder in reversed(made):
        try:
            folder.rmdir()
        except OSError:
            pass


def _temporary(out: Path, name: str, data: bytes) -> Path:
    """A hidden temporary in ``out`` holding ``data`` (mode 0o666 less the umask)."""
    while True:
        tmp = out / f".{name}.{secrets.token_hex(4)}.tmp"
        try:
            fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
            break
        except FileExistsError:
            continue
    try:
        try:
            _write_all(fd, data)
        finally:
            os.close(fd)        # may report a full disk too
    except BaseException:
        _remove(tmp)
        raise
    return tmp


def _remove(path: Path) -> None:
    """Remove a temporary file if it is still there (renamed ones are not)."""
    try:
        path.unlink()
    except FileNotFoundError:
        pass


def _write_all(fd: int, data: bytes) -> None:
    """Write all of ``data`` to file descriptor ``fd``."""
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view):]


def _why(exc: OSError, option: str = OPTION) -> str:
    """What an OSError means for the user, and the fix (``option``: the command-line option
    that named the place written to)."""
    if exc.errno == errno.ENOSPC or exc.errno == getattr(errno, "EDQUOT", None):
        return f"the disk is full (no space left); free some space or choose another {option}; nothing was written"
    if isinstance(exc, PermissionError) or exc.errno == errno.EROFS:
        return (f"no permission to write here (or a read-only file system); choose another {option} or change its "
                "permissions; nothing was written")
    if isinstance(exc, IsADirectoryError):
        return f"a folder is where this output file goes; move it away or choose another {option}; nothing was written"
    if isinstance(exc, (NotADirectoryError, FileExistsError)):
        return f"a file is where a folder must be; choose a folder for {option}; nothing was written"
    return f"cannot write ({exc.strerror or exc.__class__.__name__}); choose another {option}; nothing was written"

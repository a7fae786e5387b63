"""Bad output folders: one clear line naming [-o], exit 2, nothing written.

The -o folder is an existing file, lies below a file, is not writable (for real and
monkeypatched), the system refuses the files, a folder is in the way of a file, the disk fills
up: the render is refused in one line, and it is all or nothing (no file of any scene, no
temporaries, folders it made are removed). Files written respect the umask.
"""

from __future__ import annotations

import errno
import os
import stat

import pytest

import plans.output
from plans.cli import main

from bad_input_cases import GOOD, _render_into


# --- 9. the output folder --------------------------------------------------------------------

def test_output_is_an_existing_file(tmp_path, capsys):
    out = tmp_path / "taken"
    out.write_text("mine", encoding="utf-8")
    line = _render_into(tmp_path, out, capsys)
    assert line.startswith(f"plans: error: {out}: [-o]: ") and "is a file" in line
    assert out.read_text(encoding="utf-8") == "mine"


def test_output_below_a_file(tmp_path, capsys):
    (tmp_path / "taken").write_text("mine", encoding="utf-8")
    out = tmp_path / "taken" / "deeper" / "out"
    line = _render_into(tmp_path, out, capsys)
    assert line.startswith(f"plans: error: {out}: [-o]: ") and "below the file" in line
    assert (tmp_path / "taken").read_text(encoding="utf-8") == "mine"


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() == 0,
                    reason="root writes in any folder whatever its mode; the monkeypatched test covers it")
def test_output_without_write_permission_for_real(tmp_path, capsys):
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(stat.S_IRUSR | stat.S_IXUSR)
    try:
        line = _render_into(tmp_path, locked / "out", capsys)
        assert "[-o]" in line and "permission" in line
        assert not any(locked.iterdir())
    finally:
        locked.chmod(stat.S_IRWXU)


def test_output_without_write_permission(tmp_path, capsys, monkeypatch):
    """As root no folder can be made unwritable: the permission test answers no."""
    out = tmp_path / "out"
    out.mkdir()
    monkeypatch.setattr(plans.output, "_writable", lambda folder: False)
    line = _render_into(tmp_path, out, capsys)
    assert line.startswith(f"plans: error: {out}: [-o]: ") and "permission" in line
    assert not any(out.iterdir())


def test_permission_denied_while_writing(tmp_path, capsys, monkeypatch):
    """The permission check passes but the system refuses the files (e.g. an ACL, a read-only mount)."""
    out = tmp_path / "out"

    def deny(*args, **kwargs):
        raise PermissionError(errno.EACCES, "Permission denied")

    monkeypatch.setattr(plans.output, "_temporary", deny)
    line = _render_into(tmp_path, out, capsys)
    assert "[-o]" in line and "permission" in line
    assert not out.exists()


# --- 10. all or nothing ----------------------------------------------------------------------

def test_a_folder_in_the_way(tmp_path, capsys):
    out = tmp_path / "out"
    (out / "good.json").mkdir(parents=True)
    line = _render_into(tmp_path, out, capsys)
    assert line.startswith(f"plans: error: {out / 'good.json'}: [-o]: ") and "folder" in line
    assert sorted(p.name for p in out.iterdir()) == ["good.json"]      # nothing else, no temporaries
    assert not any((out / "good.json").iterdir())


@pytest.mark.parametrize("fail_at", [1, 3])
def test_a_full_disk_leaves_nothing(tmp_path, capsys, monkeypatch, fail_at):
    out = tmp_path / "out"
    out.mkdir()
    (out / "old.txt").write_text("kept", encoding="utf-8")
    real = plans.output._write_all
    calls = []

    def write_all(fd, data):
        calls.append(fd)
        if len(calls) == fail_at:
            real(fd, data[: len(data) // 2])          # part of the file reaches the disk, then
            raise OSError(errno.ENOSPC, "No space left on device")
        real(fd, data)

    monkeypatch.setattr(plans.output, "_write_all", write_all)
    line = _render_into(tmp_path, out, capsys)
    assert "[-o]" in line and "disk is full" in line
    assert sorted(p.name for p in out.iterdir()) == ["old.txt"]
    assert (out / "old.txt").read_text(encoding="utf-8") == "kept"


def test_a_full_disk_removes_the_folders_it_made(tmp_path, capsys, monkeypatch):
    def full(fd, data):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(plans.output, "_write_all", full)
    _render_into(tmp_path, tmp_path / "new" / "out", capsys)
    assert not (tmp_path / "new").exists()


def test_several_scenes_are_written_all_or_nothing(tmp_path, capsys):
    """The second scene's file is blocked: the first scene's files are not written either."""
    a, b = tmp_path / "a.toml", tmp_path / "b.toml"
    a.write_text(GOOD, encoding="utf-8")
    b.write_text(GOOD, encoding="utf-8")
    out = tmp_path / "out"
    (out / "b-scheme.svg").mkdir(parents=True)
    assert main(["render", str(a), str(b), "-o", str(out), "-q"]) == 2
    assert "b-scheme.svg" in capsys.readouterr().err
    assert sorted(p.name for p in out.iterdir()) == ["b-scheme.svg"]


# --- 11. umask -------------------------------------------------------------------------------

@pytest.mark.parametrize("umask, mode", [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664)])
def test_files_respect_the_umask(tmp_path, umask, mode):
    scene = tmp_path / "good.toml"
    scene.write_text(GOOD, encoding="utf-8")
    old = os.umask(umask)
    try:
        assert main(["render", str(scene), "-o", str(tmp_path / "out"), "-q"]) == 0
    finally:
        os.umask(old)
    files = list((tmp_path / "out").iterdir())
    assert files and all(stat.S_IMODE(p.stat().st_mode) == mode for p in files)
    assert not any(p.name.startswith(".") for p in files)

"""A scene's folder OUT/<scene>/ that cannot be written is refused before any solve, the same
way by every command that writes there (``modes``, ``export``, ``cycle``): exit status 2, one
line naming the folder, the folder and its files as they were, nothing left beside it.

Root writes into a chmod 500 folder anyway, so the refusal is also shown with the folder's
write probe made to fail, which works for any user."""

import os
import tempfile
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import CASES_DIR

from flexlink.cli import main

CASE1 = CASES_DIR / "case1.toml"
COMMANDS = {
    "modes": ["modes", "-e", "2", "-n", "1"],
    "export": ["export", "-e", "2", "-n", "1", "--phases", "2", "--no-pictures"],
    "cycle": ["cycle", "-e", "2", "-n", "1", "--poses", "3", "--sorted"],
}


def contents(folder: Path) -> dict:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file()}


def refused(out: Path, command: str):
    result = CliRunner().invoke(main, [*COMMANDS[command], str(CASE1), "--out", str(out)])
    assert result.exit_code == 2, result.output
    assert f"output folder {out / 'case1'} is not writable" in result.stderr
    return result


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_an_unwritable_scene_folder_is_refused_by_every_command(tmp_path, command, monkeypatch):
    out = tmp_path / "out"
    (out / "case1").mkdir(parents=True)
    (out / "case1" / "kept.txt").write_text("an earlier result")
    probe = tempfile.NamedTemporaryFile

    def read_only(*args, **kwargs):
        if Path(kwargs.get("dir", "")) == out / "case1":
            raise PermissionError(13, "Permission denied")
        return probe(*args, **kwargs)

    monkeypatch.setattr(tempfile, "NamedTemporaryFile", read_only)
    refused(out, command)
    assert contents(out) == {"case1/kept.txt": b"an earlier result"}
    assert sorted(p.name for p in out.iterdir()) == ["case1"]  # no .old, .stage or record


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into a chmod 500 folder")
@pytest.mark.parametrize("command", ["export", "cycle"])
def test_a_chmod_500_scene_folder_is_refused(tmp_path, command):
    out = tmp_path / "out"
    (out / "case1").mkdir(parents=True)
    (out / "case1").chmod(0o500)
    try:
        refused(out, command)
        assert sorted(p.name for p in out.iterdir()) == ["case1"]
    finally:
        (out / "case1").chmod(0o700)

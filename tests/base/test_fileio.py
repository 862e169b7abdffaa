"""Atomic output: a failed write keeps the old file and leaves no temporary file; final files
get a plain file's permissions under the umask; a staged folder replaces its target whole or
not at all; leftovers of dead processes are swept."""

import os
import stat
import subprocess
import sys

import pytest

from flexlink.errors import OutputError
from flexlink.fileio import prepare_out_dir, staged_folder, sweep_stale, write_atomic, write_atomic_with


class WriterDied(Exception):
    pass


def test_a_write_that_dies_part_way_keeps_the_old_file(tmp_path):
    target = tmp_path / "result.vtu"
    target.write_bytes(b"old complete result")

    def half_then_die(tmp):
        with open(tmp, "wb") as fh:
            fh.write(b"new, half writ")
            fh.flush()
        raise WriterDied("the writer failed half-way")

    with pytest.raises(WriterDied):
        write_atomic_with(target, half_then_die)
    assert target.read_bytes() == b"old complete result"


def test_no_temporary_file_is_left_after_a_failure(tmp_path):
    target = tmp_path / "result.vtu"
    target.write_bytes(b"old")

    def half_then_die(tmp):
        tmp.write_bytes(b"half")
        raise WriterDied

    with pytest.raises(WriterDied):
        write_atomic_with(target, half_then_die)

    def half_then_disk_full(tmp):
        tmp.write_bytes(b"half")
        raise OSError(28, "No space left on device")

    with pytest.raises(OutputError, match="No space left"):
        write_atomic_with(target, half_then_disk_full)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["result.vtu"]


@pytest.mark.parametrize("umask, file_mode, folder_mode", [(0o022, 0o644, 0o755),
                                                           (0o077, 0o600, 0o700)])
def test_outputs_get_the_permissions_of_the_umask(tmp_path, umask, file_mode, folder_mode):
    previous = os.umask(umask)
    try:
        text = write_atomic(tmp_path / "a.json", "{}")
        data = write_atomic(tmp_path / "b.png", b"\x89PNG")
        with staged_folder(tmp_path / "case") as stage:
            inner = write_atomic(stage / "c.vtu", "x")
    finally:
        os.umask(previous)
    for path in (text, data, tmp_path / "case" / inner.name):
        assert stat.S_IMODE(path.stat().st_mode) == file_mode, path
    assert stat.S_IMODE((tmp_path / "case").stat().st_mode) == folder_mode


def test_a_staged_folder_replaces_the_old_one_whole_or_not_at_all(tmp_path):
    target = tmp_path / "case1"
    target.mkdir()
    (target / "old.png").write_text("old")
    with pytest.raises(WriterDied):
        with staged_folder(target) as stage:
            write_atomic(stage / "new.vtu", "new")
            raise WriterDied
    assert sorted(p.name for p in tmp_path.rglob("*")) == ["case1", "old.png"]
    with staged_folder(target) as stage:
        write_atomic(stage / "new.vtu", "new")
    assert sorted(p.name for p in tmp_path.rglob("*")) == ["case1", "new.vtu"]


def dead_pid() -> int:
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid


def test_leftovers_of_dead_processes_are_swept_and_live_ones_kept(tmp_path):
    pid = dead_pid()
    frames = tmp_path / "case1" / "case1_mode1"
    frames.mkdir(parents=True)
    stale = [frames / f".phase03.vtu.~{pid}~k2j4h5g6.tmp",
             frames / ".phase00.vtu.a1b2c3d4.tmp",  # flexlink before process ids in names
             tmp_path / f".export.json.~{pid}~abcdefgh.tmp"]
    for p in stale:
        p.write_bytes(b"")
    stage = tmp_path / f".case2.~{pid}~qwertyui.stage"
    (stage / "sub").mkdir(parents=True)
    live = tmp_path / f".modes.json.~{os.getpid()}~zxcvbnma.tmp"
    live.write_bytes(b"being written")
    kept = [tmp_path / "case1" / "case1.vtu", tmp_path / "notes.tmp"]
    for p in kept:
        p.write_text("x")
    prepare_out_dir(tmp_path)
    assert not any(p.exists() for p in stale) and not stage.exists()
    assert live.exists() and all(p.exists() for p in kept)


def test_a_swap_cut_between_its_renames_is_undone(tmp_path):
    old = tmp_path / f".case1.~{dead_pid()}~asdfghjk.old"
    old.mkdir()
    (old / "case1.vtu").write_text("previous")
    sweep_stale(tmp_path)
    assert (tmp_path / "case1" / "case1.vtu").read_text() == "previous" and not old.exists()


def test_temporary_files_live_beside_their_target_under_a_sweepable_name(tmp_path):
    """The rename is atomic only within one file system, and sweep_stale can only find what it
    can read the writer's process id from."""
    seen = []

    def write(tmp):
        seen.append(tmp)
        tmp.write_text("x")

    target = tmp_path / "case1" / "modes.json"
    target.parent.mkdir()
    write_atomic_with(target, write)
    [tmp] = seen
    assert tmp.parent == target.parent
    assert tmp.name.startswith(f".modes.json.~{os.getpid()}~") and tmp.name.endswith(".tmp")
    assert target.read_text() == "x" and not tmp.exists()


def test_sweep_reports_what_it_removed_and_stops_at_its_depth(tmp_path):
    pid = dead_pid()
    levels = [tmp_path, tmp_path / "a", tmp_path / "a" / "b", tmp_path / "a" / "b" / "c"]
    levels[-1].mkdir(parents=True)
    planted = [level / f".f.vtu.~{pid}~abcdefgh.tmp" for level in levels]
    hidden = tmp_path / ".git"
    hidden.mkdir()
    planted_hidden = hidden / f".f.~{pid}~abcdefgh.tmp"
    for p in planted + [planted_hidden]:
        p.write_bytes(b"")
    removed = sweep_stale(tmp_path, depth=2)
    assert sorted(removed) == sorted(planted[:3])  # three levels: the folder and two below
    assert planted[3].exists() and planted_hidden.exists()


def test_a_live_process_of_another_id_keeps_its_temporary_files(tmp_path):
    sleeper = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(30)"])
    try:
        busy = tmp_path / f".modes.json.~{sleeper.pid}~abcdefgh.tmp"
        busy.write_bytes(b"being written")
        assert sweep_stale(tmp_path) == [] and busy.exists()
    finally:
        sleeper.kill()
        sleeper.wait()
    assert sweep_stale(tmp_path) == [busy] and not busy.exists()


def test_prepare_out_dir_makes_nested_folders_and_leaves_nothing_behind(tmp_path):
    out = prepare_out_dir(tmp_path / "runs" / "today" / "out")
    assert out.is_dir() and list(out.iterdir()) == []  # the write probe is gone


def test_a_write_that_cannot_start_names_the_file_and_the_reason(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    with pytest.raises(OutputError, match=r"cannot write .*file/modes\.json: Not a directory"):
        write_atomic(blocker / "modes.json", "{}")
    with pytest.raises(OutputError, match=r"file/out"):
        prepare_out_dir(blocker / "out")


def test_an_existing_folder_that_refuses_files_is_refused_before_any_work(tmp_path, monkeypatch):
    """The probe file is what finds a folder that exists but takes no files (read-only, or a
    folder of another user): mkdir(exist_ok=True) alone succeeds there. Root may write
    anywhere, so the refusal is simulated at the probe."""
    import tempfile

    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(tempfile, "NamedTemporaryFile", refuse)
    with pytest.raises(OutputError, match=rf"output folder {tmp_path} is not writable: "
                                          "Permission denied"):
        prepare_out_dir(tmp_path)


def test_a_swap_failing_after_the_old_folder_moved_aside_puts_it_back(tmp_path, monkeypatch):
    """The swap is two renames: target -> .old, stage -> target. If the second fails, the old
    folder goes back under its name and nothing is left beside it."""
    target = tmp_path / "scene"
    target.mkdir()
    (target / "modes.json").write_text("old")
    real = os.replace

    def replace(source, destination):
        if str(source).endswith(".stage"):
            raise OSError(18, "Invalid cross-device link")
        return real(source, destination)

    monkeypatch.setattr(os, "replace", replace)
    with pytest.raises(OutputError, match="cannot replace .*Invalid cross-device link"):
        with staged_folder(target) as stage:
            (stage / "modes.json").write_text("new")
    monkeypatch.undo()
    assert (target / "modes.json").read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene"]


def test_a_staged_folder_keeps_the_files_other_commands_wrote(tmp_path):
    target = tmp_path / "case1"
    target.mkdir()
    (target / "modes.json").write_text("from modes")
    (target / "case1_modes.vtu").write_text("old export")
    (target / "case1_mode9.png").write_text("old picture this run does not draw")
    with staged_folder(target, keep=lambda name: not name.startswith("case1_")) as stage:
        (stage / "case1_modes.vtu").write_text("new export")
    assert sorted(p.name for p in target.iterdir()) == ["case1_modes.vtu", "modes.json"]
    assert (target / "modes.json").read_text() == "from modes"
    assert (target / "case1_modes.vtu").read_text() == "new export"


def test_leftovers_of_another_users_live_process_are_kept(tmp_path, monkeypatch):
    """os.kill(pid, 0) on another user's process raises PermissionError: that process is
    alive, and its temporary file must stay."""
    leftover = tmp_path / ".modes.json.~4242~abc.tmp"
    leftover.write_text("being written by someone else")

    def not_ours(pid, sig):
        raise PermissionError(1, "Operation not permitted")

    monkeypatch.setattr(os, "kill", not_ours)
    assert sweep_stale(tmp_path) == []
    assert leftover.exists()

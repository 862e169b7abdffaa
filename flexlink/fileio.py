"""Atomic file output: nothing a run writes is ever seen half-written, and nothing it leaves
behind outlives it.

- A file goes to a temporary file in the target's folder, then is renamed over the target.
- A folder of files (one scene's export) is written into a staging folder beside the target,
  then swapped in whole (``staged_folder``).
- Temporary names carry the writing process's id (``.<name>.~<pid>~<random>.tmp``), so a later
  run can tell the leftovers of a dead process from the files of a live one
  (``sweep_stale``).
- A stopped run (``stopping.stop_on_signals``) raises an exception, so the ``finally`` clauses
  here remove their temporary files; the swap of a folder is never cut in two.
- Final files and folders get the permissions of a plain ``open``/``mkdir`` under the user's
  umask (``mkstemp``/``mkdtemp`` would leave them private, 0600/0700).
"""

from __future__ import annotations

import contextlib
import os
import re
import shutil
import signal
import tempfile
from collections.abc import Callable, Iterator
from pathlib import Path

from flexlink.errors import OutputError
from flexlink.stopping import signals_deferred

# .<target name>.~<pid>~<random>.tmp for files, .<target name>.~<pid>~<random>.stage for
# staging folders, .<target name>.~<pid>~<random>.old for a folder being replaced
_TEMP = re.compile(r"^\.(?P<name>.+)\.~(?P<pid>\d+)~[^.]+\.(?P<kind>tmp|stage|old)$")
# temporary files of earlier flexlink versions (no process id): .<target name>.<8 random>.tmp
_LEGACY_TEMP = re.compile(r"^\..+\.[a-z0-9_]{8}\.tmp$")
SWEEP_DEPTH = 2  # out/<scene>/<scene>_mode<n>/: the deepest folder flexlink writes into


def _umask() -> int:
    mask = os.umask(0o022)  # the only portable way to read it is to set it
    os.umask(mask)
    return mask


def _publish_mode(path: Path, directory: bool = False) -> None:
    """Give ``path`` the permissions ``open`` (0666) or ``mkdir`` (0777) would under the umask."""
    os.chmod(path, (0o777 if directory else 0o666) & ~_umask())


def _temp_prefix(path: Path) -> str:
    return f".{path.name}.~{os.getpid()}~"


def _remove(path: Path) -> None:
    """Delete a file or folder if it is there and we may; cleanup never raises over the error
    that made it necessary."""
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path, ignore_errors=True)
    else:
        with contextlib.suppress(OSError):
            path.unlink()


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # someone else's process: alive
        return True
    return True


def sweep_stale(folder: str | Path, depth: int = SWEEP_DEPTH) -> list[Path]:
    """Remove the temporary files and staging folders that processes no longer running left in
    ``folder`` and its (non-hidden) subfolders down to ``depth``; put back a replaced folder
    whose swap was cut short. Returns what was removed."""
    folder = Path(folder)
    removed = []
    try:
        entries = list(folder.iterdir())
    except OSError:
        return removed
    for entry in entries:
        match = _TEMP.match(entry.name)
        if match and not _alive(int(match["pid"])):
            target = entry.with_name(match["name"])
            if match["kind"] == "old" and not target.exists():
                with contextlib.suppress(OSError):  # the swap died between its renames: undo
                    entry.rename(target)
                continue
            _remove(entry)
            removed.append(entry)
        elif not match and _LEGACY_TEMP.match(entry.name) and entry.is_file():
            _remove(entry)
            removed.append(entry)
        elif depth > 0 and entry.is_dir() and not entry.name.startswith("."):
            removed += sweep_stale(entry, depth - 1)
    return removed


def prepare_out_dir(out: str | Path) -> Path:
    """Create ``out`` if needed, prove it is writable before any long computation, and sweep
    what interrupted runs left in it."""
    out = Path(out)
    try:
        out.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=out, prefix=_temp_prefix(Path("probe")), suffix=".tmp"):
            pass
    except OSError as exc:
        raise OutputError(f"output folder {out} is not writable: {exc.strerror or exc}") from None
    sweep_stale(out)
    return out


def write_atomic_with(path: str | Path, write: Callable[[Path], None]) -> Path:
    """Atomic output for writers that take a file name (meshio): ``write(tmp)`` fills a
    temporary file in the target's folder, which is then renamed over ``path``. Whatever
    ``write`` raises, the old ``path`` is untouched and the temporary file removed."""
    path = Path(path)
    tmp = None
    try:
        fd, name = tempfile.mkstemp(dir=path.parent, prefix=_temp_prefix(path), suffix=".tmp")
        os.close(fd)
        tmp = Path(name)
        write(tmp)
        _publish_mode(tmp)
        os.replace(tmp, path)
        tmp = None
    except OSError as exc:
        raise OutputError(f"cannot write {path}: {exc.strerror or exc}") from None
    finally:
        if tmp is not None:
            _remove(tmp)
    return path


def write_atomic(path: str | Path, data: str | bytes) -> Path:
    """Write ``data`` (text as UTF-8, newlines as given) to ``path`` atomically."""
    if isinstance(data, bytes):
        return write_atomic_with(path, lambda tmp: tmp.write_bytes(data))
    return write_atomic_with(path, lambda tmp: tmp.write_text(data, encoding="utf-8", newline=""))


@contextlib.contextmanager
def _signals_held() -> Iterator[None]:
    """Hold SIGINT and SIGTERM back (they arrive when the block ends): for steps that must not
    be cut in two."""
    if not hasattr(signal, "pthread_sigmask"):  # not on Windows: the renames stay unguarded
        yield
        return
    held = {signal.SIGINT, signal.SIGTERM}
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, held)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def _carry_over(target: Path, stage: Path, keep: Callable[[str], bool]) -> None:
    """Link (or, where the file system has no hard links, copy) into ``stage`` every entry of
    ``target`` that ``keep`` names and the stage does not have: other commands' files."""
    for entry in target.iterdir():
        if entry.name.startswith(".") or not keep(entry.name) or (stage / entry.name).exists():
            continue
        if entry.is_dir() and not entry.is_symlink():
            shutil.copytree(entry, stage / entry.name, symlinks=True, copy_function=_link_or_copy)
        else:
            _link_or_copy(entry, stage / entry.name)


def _link_or_copy(source, destination) -> None:
    try:
        os.link(source, destination, follow_symlinks=False)
    except OSError:
        shutil.copy2(source, destination, follow_symlinks=False)


@contextlib.contextmanager
def staged_folder(target: str | Path, keep: Callable[[str], bool] | None = None) -> Iterator[Path]:
    """Yield an empty staging folder beside ``target``; when the block ends normally, the staged
    folder replaces ``target`` as a whole (the old one is removed), otherwise it is deleted and
    ``target`` stays as it was. A reader sees the old folder or the new one, never a mix (except
    missing for the instant between two renames, which ``sweep_stale`` repairs should the
    process die right there).

    ``keep(name)``: which entries of the old ``target`` that the block did not write are carried
    into the new one (files other commands put in the same folder); the rest are dropped, so a
    writer's files from an earlier run with other settings do not linger."""
    target = Path(target)
    try:
        stage = Path(tempfile.mkdtemp(dir=target.parent, prefix=_temp_prefix(target), suffix=".stage"))
    except OSError as exc:
        raise OutputError(f"cannot create a folder beside {target}: {exc.strerror or exc}") from None
    try:
        yield stage
        old = stage.with_name(stage.name[:-len(".stage")] + ".old")
        try:
            _publish_mode(stage, directory=True)
            if keep is not None and target.is_dir():
                _carry_over(target, stage, keep)
            with signals_deferred():  # the swap, its repair and the removal of the old folder
                try:
                    with _signals_held():
                        if target.exists():
                            os.replace(target, old)
                        os.replace(stage, target)
                except OSError:
                    if old.exists() and not target.exists():
                        os.replace(old, target)
                    raise
                _remove(old)
        except OSError as exc:
            raise OutputError(f"cannot replace {target}: {exc.strerror or exc}") from None
    finally:
        _remove(stage)

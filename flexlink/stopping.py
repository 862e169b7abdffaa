"""How a run stops on SIGTERM or SIGINT: with one line, exit status 128 + the signal's number,
its temporary files removed and the previous output whole; never with a crash or a traceback.

- ``stop_on_signals`` makes both signals raise ``Terminated`` in the main thread, so the
  ``finally`` clauses of ``fileio`` remove temporary files and staging folders on the way out.
- An exception raised in the middle of importing a compiled library, or while a native call
  runs Python callbacks, can leave that library half set up: VTK, imported lazily by pyvista,
  has then crashed the process (segmentation fault) or turned the signal into an ImportError.
  So a signal arriving inside ``signals_deferred`` (and inside every import: ``_DeferredImports``)
  is only noted there, and raised when the block ends.
- Once the run is stopping, further signals are ignored, so a second Ctrl-C cannot cut the
  cleanup short.

The handler only sets a flag or raises between Python bytecodes; nothing here blocks signals
at the C level, so child processes (renderers, dask workers) start with the ordinary mask.
"""

from __future__ import annotations

import contextlib
import importlib.abc
import signal
import sys
import threading
from collections.abc import Iterator

STOP_SIGNALS = (signal.SIGTERM, signal.SIGINT)


class Terminated(BaseException):
    """The process received SIGTERM or SIGINT. A BaseException, like KeyboardInterrupt: no
    ``except Exception`` swallows it."""

    def __init__(self, signum: int):
        self.signum = signum
        super().__init__(f"stopped by signal {signal.Signals(signum).name}")


class _State:
    """The main thread's signal bookkeeping: how deep in deferred blocks it is, the first
    signal that arrived there, and whether the run is already stopping."""

    depth = 0
    pending: int | None = None
    stopping = False


def _in_main_thread() -> bool:
    return threading.current_thread() is threading.main_thread()


def _on_signal(signum, frame):
    if _State.stopping:  # the first signal is already ending the run
        return
    if _State.depth:
        _State.pending = _State.pending or signum
        return
    _State.stopping = True
    raise Terminated(signum)


@contextlib.contextmanager
def signals_deferred() -> Iterator[None]:
    """Hold SIGTERM and SIGINT back inside the block (imports of compiled libraries, drawing
    with VTK or matplotlib, renames that belong together); one that arrived meanwhile raises
    ``Terminated`` when the outermost such block ends. Other threads are never interrupted by
    a signal, so for them this does nothing."""
    if not _in_main_thread():
        yield
        return
    _State.depth += 1
    try:
        yield
    finally:
        _State.depth -= 1
        if not _State.depth and _State.pending and not _State.stopping:
            signum, _State.pending, _State.stopping = _State.pending, None, True
            raise Terminated(signum)


def _deferring(method):
    if getattr(method, "deferred", False):  # a loader that serves many modules (pytest's)
        return method

    def run(*args, **kwargs):
        with signals_deferred():
            return method(*args, **kwargs)
    run.deferred = True
    return run


class _DeferredImports(importlib.abc.MetaPathFinder):
    """First on ``sys.meta_path``: finds nothing itself, asks the finders after it, and makes
    the loader they return create and run the module inside ``signals_deferred``. Built-in and
    frozen modules (their loader is a class, shared) are left alone: they load in C at once."""

    def find_spec(self, name, path, target=None):
        finders = sys.meta_path
        later = finders[finders.index(self) + 1:] if self in finders else []
        for finder in later:
            find = getattr(finder, "find_spec", None)
            spec = find(name, path, target) if find is not None else None
            if spec is not None:
                loader = spec.loader
                if loader is not None and not isinstance(loader, type):
                    for method in ("create_module", "exec_module"):
                        if hasattr(loader, method):
                            with contextlib.suppress(AttributeError, TypeError):
                                setattr(loader, method, _deferring(getattr(loader, method)))
                return spec
        return None


@contextlib.contextmanager
def stop_on_signals(restore: bool = True) -> Iterator[None]:
    """Inside the block SIGTERM and SIGINT raise ``Terminated`` in the main thread (deferred
    during imports and ``signals_deferred`` blocks). ``restore``: put the previous handlers
    back afterwards (a test runner calling the CLI in its own process); otherwise the signals
    stay ignored after the block, so one arriving while the process exits changes nothing.
    A signal ignored when the block starts stays ignored. Outside the main thread, where Python
    allows no signal handler, nothing changes."""
    if not _in_main_thread():
        yield
        return
    _State.depth, _State.pending, _State.stopping = 0, None, False
    # a signal ignored from the start (a background job of a shell without job control) stays
    # ignored, as Python itself leaves SIGINT then
    previous = {s: signal.signal(s, _on_signal) for s in STOP_SIGNALS
                if signal.getsignal(s) is not signal.SIG_IGN}
    finder = _DeferredImports()
    sys.meta_path.insert(0, finder)
    try:
        yield
    finally:
        _State.stopping = True
        with contextlib.suppress(ValueError):
            sys.meta_path.remove(finder)
        if restore:
            for s, handler in previous.items():
                signal.signal(s, handler)
            _State.stopping = False
        else:
            # ignored at the OS level: the interpreter's own shutdown puts the default action
            # back for a Python handler, so a signal arriving then would kill the process
            # with no message after its work is done
            for s in previous:
                signal.signal(s, signal.SIG_IGN)

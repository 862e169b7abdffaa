"""A signal is held back while a module is imported or a deferred block runs, and raised as
``Terminated`` right after; outside them it is raised at once; a second signal never cuts the
cleanup of the first. The signals are sent by the test process to itself, so the moment is
exact (the subprocess tests in test_export_interrupted.py send them from outside)."""

import os
import signal
import sys

import pytest

from flexlink.stopping import Terminated, signals_deferred, stop_on_signals


@pytest.fixture(autouse=True)
def interruptible():
    """SIGINT as in an interactive process, even when the test run was started with it ignored
    (stop_on_signals leaves an ignored signal ignored)."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def test_a_signal_during_an_import_lets_the_module_finish_then_stops(tmp_path, monkeypatch):
    # the module signals itself half-way through its own body, as SIGTERM can arrive while
    # VTK's modules are being imported
    end = tmp_path / "reached the end"
    (tmp_path / "half_way.py").write_text(
        "import os, pathlib, signal\nos.kill(os.getpid(), signal.SIGTERM)\n"
        f"for _ in range(1000):\n    pass\npathlib.Path({str(end)!r}).touch()\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    with pytest.raises(Terminated) as stopped, stop_on_signals():
        import half_way  # noqa: F401
    assert stopped.value.signum == signal.SIGTERM
    assert end.exists()  # the module ran to its end before the signal stopped the run
    assert "half_way" not in sys.modules  # and the import is reported as not done


def test_a_signal_in_a_deferred_block_is_raised_when_the_outermost_block_ends():
    reached = []
    with pytest.raises(Terminated) as stopped, stop_on_signals():
        with signals_deferred():
            with signals_deferred():
                os.kill(os.getpid(), signal.SIGINT)
                sum(range(1000))  # bytecodes run, so the handler has had its chance
                reached.append("inner")
            reached.append("outer")
        reached.append("after")
    assert stopped.value.signum == signal.SIGINT
    assert reached == ["inner", "outer"]


def test_outside_deferred_blocks_the_signal_stops_at_once_and_a_second_is_ignored():
    cleaned = []
    with pytest.raises(Terminated) as stopped, stop_on_signals():
        try:
            os.kill(os.getpid(), signal.SIGTERM)
            for _ in range(1000):
                pass
            cleaned.append("not reached")
        finally:
            os.kill(os.getpid(), signal.SIGINT)  # a second Ctrl-C while cleaning up
            sum(range(1000))
            cleaned.append("cleanup done")
    assert stopped.value.signum == signal.SIGTERM
    assert cleaned == ["cleanup done"]


def test_the_previous_handlers_come_back_after_the_block():
    before = {s: signal.getsignal(s) for s in (signal.SIGTERM, signal.SIGINT)}
    with stop_on_signals():
        pass
    assert {s: signal.getsignal(s) for s in before} == before

"""The bar of steps within one speed (``commands._progress.step_progress``): counts what the
Floquet steps report on a terminal, and is absent for --json or a redirected stderr."""

import io
import sys

from flexlink.commands._progress import step_progress


class Terminal(io.StringIO):
    def isatty(self):
        return True


def test_steps_are_counted_on_a_terminal_only(monkeypatch):
    terminal = Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    with step_progress("Floquet steps", quiet=False) as on_steps:
        on_steps(256)
        on_steps(512)
        assert on_steps.__self__.n == 768  # the bar's count (its redraws are rate-limited)
    assert "Floquet steps" in terminal.getvalue() and "step/s" in terminal.getvalue()
    with step_progress("Floquet steps", quiet=True) as on_steps:
        assert on_steps is None
    monkeypatch.setattr(sys, "stderr", io.StringIO())
    with step_progress("Floquet steps", quiet=False) as on_steps:
        assert on_steps is None

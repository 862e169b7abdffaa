"""Warnings once per run: a kind of warning is shown once and its repeats counted; the warnings
of a batch of evaluations, in this process or in joblib workers, become one summary line."""

import logging
import subprocess
import sys

import pytest

from flexlink import logbook
from flexlink.parallel import run_tasks

from conftest import ROOT
log = logging.getLogger("flexlink.test_logbook")


@pytest.fixture
def configured():
    once = logbook.configure()
    yield once
    logging.getLogger().removeHandler(logbook._installed)


def warning_lines(text: str) -> list[str]:
    return [line for line in text.splitlines() if line.startswith("warning: ")]


def test_each_kind_is_shown_once_and_its_repeats_counted(configured, capsys):
    for ratio in (4.0, 3.9, 12.5):  # one kind: only the numbers differ
        log.warning("case1.toml: link crank: slenderness L/h = %g", ratio)
    log.warning("case2.toml: link crank: slenderness L/h = %g", 4.0)  # another case: a new kind
    shown = warning_lines(capsys.readouterr().err)
    assert shown == ["warning: case1.toml: link crank: slenderness L/h = 4",
                     "warning: case2.toml: link crank: slenderness L/h = 4"]
    logbook.report_repeats(configured)
    [repeat] = warning_lines(capsys.readouterr().err)
    assert "slenderness L/h = 4' came 3 times in all" in repeat


def test_a_batch_in_this_process_is_summarised_once(configured, capsys):
    tasks = [("L/h = %g", 1.0 + k) for k in range(5)] + [("round-off %g", 1e-6)]
    run_tasks(log.warning, tasks, n_jobs=1, label="test evaluations")
    [summary] = warning_lines(capsys.readouterr().err)
    assert "6 warnings of 2 kinds during 6 test evaluations; first: L/h = 1" in summary


def test_the_warnings_of_joblib_workers_come_back_as_one_summary():
    # a fresh process, so its workers start with nothing captured: whatever they print shows
    script = ("import logging\n"
              "from flexlink import logbook\n"
              "from flexlink.parallel import run_tasks\n"
              "logbook.configure()\n"
              "tasks = [('L/h = %g', 1.0 + k) for k in range(7)] + [('round-off %g', 1e-6)]\n"
              "run_tasks(logging.getLogger('flexlink.demo').warning, tasks, n_jobs=2,\n"
              "          label='worker evaluations')\n")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=300, env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
    assert done.returncode == 0, done.stderr
    lines = [line for line in done.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, done.stderr
    assert "8 warnings of 2 kinds during 8 worker evaluations; first: L/h = 1" in lines[0]

"""An export stopped by SIGTERM while it writes leaves the previous complete output as it was,
and no temporary file; the next run sweeps what a killed run left. A signal at any moment of a
run (imports, solve, files, the pictures' VTK import and rendering) ends it with one line and
128 + its number, never a crash, a traceback or click's "Aborted!".

An output left alone is compared byte for byte: its files are the very bytes written before,
never recomputed. A new output is compared with a whole run's (another process) by content
(`contents`): numbers to round-off, pictures by size and pixels, never by a hash."""

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

from click.testing import CliRunner

from flexlink.cli import main

from conftest import ROOT
from contents import content_mismatches, folder_contents

CASE3 = ROOT / "cases" / "case3.toml"
QUICK = ["-e", "2", "--no-pictures", "--phases", "2", "-n", "1"]
# thousands of larger frames: seconds of writing, so the signal comes while files are written
SLOW = ["-e", "8", "--subdivide", "16", "--no-pictures", "--phases", "1000", "-n", "4"]
# a small export whose run time is mostly the pictures: a rendering check in a child process,
# pyvista's lazy import of VTK, off-screen rendering
PICTURES = ["-e", "2", "-n", "1", "--phases", "2"]
EARLIER = ["-e", "2", "-n", "2", "--phases", "3", "--no-pictures"]  # other files, other bytes
# the console script's entry point, SIGINT first handled as Python does for a terminal
INTERACTIVE = ("import signal, sys; signal.signal(signal.SIGINT, signal.default_int_handler); "
               "from flexlink.cli import main; sys.argv[0] = 'flexlink'; main()")
DELAYS = 4  # signals spread evenly over one run's duration, SIGTERM and SIGINT in turn


def export(out: Path, args: list[str]) -> subprocess.Popen:
    """``flexlink export`` of case 3 in a process of its own, with SIGINT as in a terminal
    (a test run started in the background would pass it on ignored)."""
    return subprocess.Popen(
        [sys.executable, "-c", INTERACTIVE, "export", str(CASE3), *args, "--out", str(out)],
        env={**os.environ, "PYTHONPATH": str(ROOT)}, stdout=subprocess.PIPE,
        stderr=subprocess.PIPE, text=True)


def snapshot(out: Path) -> dict[str, bytes]:
    """Every file's bytes: of an output that must be left as it was."""
    return {str(p.relative_to(out)): p.read_bytes() for p in sorted(out.rglob("*"))
            if p.is_file()}


def wait_until_writing(out: Path, child: subprocess.Popen, files_before: int,
                       timeout: float = 120) -> None:
    """Return once the running export has written 20 files more than ``out`` held before."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        assert child.poll() is None, "the export ended before it was stopped"
        if sum(1 for p in out.rglob("*") if p.is_file()) >= files_before + 20:
            return
        time.sleep(0.01)
    raise AssertionError("the export did not start writing")


def test_sigterm_while_writing_keeps_the_previous_output_and_no_temp_files(tmp_path):
    out = tmp_path / "out"
    first = CliRunner().invoke(main, ["export", str(CASE3), *QUICK, "--out", str(out)])
    assert first.exit_code == 0, first.output
    before = snapshot(out)
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    child = subprocess.Popen([sys.executable, "-m", "flexlink.cli", "export", str(CASE3), *SLOW,
                              "--out", str(out)], env=env, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    try:
        wait_until_writing(out, child, len(before))
        child.send_signal(signal.SIGTERM)
        _, err = child.communicate(timeout=60)
    finally:
        child.kill()
    assert child.returncode == 128 + signal.SIGTERM, err
    assert "stopped by signal SIGTERM" in err
    assert snapshot(out) == before  # also: no temporary or staging file anywhere
    assert json.loads((out / "case3" / "export.json").read_text())["complete"] is True


def test_the_next_export_sweeps_what_a_killed_run_left(tmp_path):
    out = tmp_path / "out"
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()  # its process id now names no running process
    frames = out / "case3" / "case3_mode1"
    frames.mkdir(parents=True)
    planted = [frames / f".phase07.vtu.~{child.pid}~x1y2z3w4.tmp", frames / ".phase00.vtu.a1b2c3d4.tmp",
               out / f".case3.~{child.pid}~q1w2e3r4.stage" / "case3.vtu"]
    planted[-1].parent.mkdir()
    for p in planted:
        p.write_bytes(b"")
    result = CliRunner().invoke(main, ["export", str(CASE3), *QUICK, "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert not any(p.name.startswith(".") for p in out.rglob("*"))


def test_export_keeps_other_commands_files_and_drops_its_own_old_ones(tmp_path):
    out = tmp_path / "out"
    modes = CliRunner().invoke(main, ["modes", str(CASE3), "-e", "2", "--out", str(out)])
    assert modes.exit_code == 0, modes.output
    two = CliRunner().invoke(main, ["export", str(CASE3), *QUICK[:-1], "2", "--out", str(out)])
    assert two.exit_code == 0, two.output
    assert (out / "case3" / "case3_mode2.pvd").is_file()
    one = CliRunner().invoke(main, ["export", str(CASE3), *QUICK, "--out", str(out)])
    assert one.exit_code == 0, one.output
    names = sorted(p.name for p in (out / "case3").iterdir())
    assert "modes.json" in names and "modes.csv" in names  # the modes command's
    assert not any(n.startswith("case3_mode2") for n in names)  # the 2-mode export's


def test_report_keeps_the_pictures_of_an_earlier_export(tmp_path):
    """The main job runs export, then report into the same folder: report writes only the .vtu
    and .pvd files, so export's pictures and plot stay (and its old .vtu/.pvd are replaced)."""
    out = tmp_path / "out"
    export = CliRunner().invoke(main, ["export", str(CASE3), "-e", "2", "-n", "2", "--out", str(out)])
    assert export.exit_code == 0, export.output
    pictures = sorted(p.name for p in (out / "case3").glob("*.png"))
    assert "case3_mode1.png" in pictures and "case3_frequencies.png" in pictures
    report = CliRunner().invoke(main, ["report", str(CASE3), "-e", "2", "-n", "1",
                                       "--cycle-poses", "0", "--out", str(out)])
    assert report.exit_code == 0, report.output
    assert sorted(p.name for p in (out / "case3").glob("*.png")) == pictures
    assert not (out / "case3" / "case3_mode2.pvd").exists()  # the report wrote one mode


def folders(out: Path, copied_from: Path | None = None) -> dict[str, str]:
    """The folder names to replace in export.json (``out``, or ``copied_from`` when the files
    were copied), so that outputs written to two folders compare equal."""
    return {str(out): "OUT", **({str(copied_from): "OUT"} if copied_from else {})}


def normalised(out: Path, copied_from: Path | None = None) -> dict[str, bytes]:
    """``snapshot`` with the folder names replaced (``folders``)."""
    names = [name.encode() for name in folders(out, copied_from)]

    def replaced(data: bytes) -> bytes:
        for name in names:
            data = data.replace(name, b"OUT")
        return data
    return {name: replaced(data) for name, data in snapshot(out).items()}


def test_a_signal_at_any_moment_stops_with_one_line_and_whole_outputs(tmp_path):
    pristine, whole = tmp_path / "pristine", tmp_path / "whole"
    # the earlier output and one whole run side by side, as the trials run two at a time, so
    # the whole run's duration is measured under the trials' load
    start = time.monotonic()
    earlier, complete = export(pristine, EARLIER), export(whole, PICTURES)
    _, err = complete.communicate(timeout=600)
    duration = time.monotonic() - start
    assert complete.returncode == 0, err
    _, err = earlier.communicate(timeout=600)
    assert earlier.returncode == 0, err
    after = folder_contents(whole, folders(whole))  # what a run that is not stopped says
    before = normalised(pristine)  # the earlier output, byte for byte
    outcomes = []
    # two runs at a time (SIGTERM to one, SIGINT to the other), on the machine's two cores
    for k in range(0, DELAYS, 2):
        trials = []
        for signum, j in ((signal.SIGTERM, k), (signal.SIGINT, k + 1)):
            out = tmp_path / f"trial{j}"
            shutil.copytree(pristine, out)
            trials.append((duration * (j + 0.5) / DELAYS, signum, out, export(out, PICTURES)))
        began = time.monotonic()
        for delay, signum, _, child in trials:
            time.sleep(max(0.0, began + delay - time.monotonic()))
            child.send_signal(signum)
        for _, signum, out, child in trials:
            try:
                _, err = child.communicate(timeout=300)
            finally:
                child.kill()
            now = normalised(out, copied_from=pristine)
            if child.returncode == 0:  # it had finished before the signal came
                new = folder_contents(out, folders(out, pristine))
                assert not content_mismatches(new, after), content_mismatches(new, after)
                outcomes.append("finished")
                continue
            name = signal.Signals(signum).name
            assert child.returncode == 128 + signum, err
            assert err.splitlines()[-1] == f"flexlink: stopped by signal {name}", err
            assert "Traceback" not in err and "Aborted" not in err and "Error" not in err, err
            # the earlier output whole, or (stopped just after the swap) the new one whole;
            # either way no temporary file, staging or old folder anywhere
            if now != before:
                new = folder_contents(out, folders(out, pristine))
                assert not content_mismatches(new, after), content_mismatches(new, after)
            outcomes.append(name)
    assert outcomes.count("SIGTERM") + outcomes.count("SIGINT") >= DELAYS // 2, outcomes


def test_ctrl_c_stops_any_command_with_one_line(tmp_path):
    """Not export only: a long ``cycle`` stopped by SIGINT once it has made its folder ends with
    exit status 130 and one line (not click's "Aborted!" and status 1), nothing written."""
    out = tmp_path / "out"
    child = subprocess.Popen(
        [sys.executable, "-c", INTERACTIVE, "cycle", str(ROOT / "cases" / "case1.toml"), "-e", "1",
         "-n", "1", "--poses", "100000", "--sorted", "--out", str(out)],
        env={**os.environ, "PYTHONPATH": str(ROOT)}, stdout=subprocess.PIPE,
        stderr=subprocess.PIPE, text=True)
    try:
        end = time.monotonic() + 120
        while not (out / "case1").is_dir() and time.monotonic() < end:
            assert child.poll() is None, child.communicate()
            time.sleep(0.02)
        child.send_signal(signal.SIGINT)
        _, err = child.communicate(timeout=120)
    finally:
        child.kill()
    assert child.returncode == 130, err
    assert err.splitlines()[-1] == "flexlink: stopped by signal SIGINT", err
    assert "Traceback" not in err and "Aborted" not in err
    assert list(out.rglob("*")) == [out / "case1"]  # no cycle file, no temporary file

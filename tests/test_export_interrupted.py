"""An export stopped by SIGTERM while it writes leaves the previous complete output as it was,
and no temporary file; the next run sweeps what a killed run left."""

import hashlib
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

from click.testing import CliRunner

from flexlink.cli import main

ROOT = Path(__file__).resolve().parent.parent
CASE3 = ROOT / "cases" / "case3.toml"
QUICK = ["-e", "2", "--no-pictures", "--phases", "2", "-n", "1"]
# thousands of larger frames: seconds of writing, so the signal comes while files are written
SLOW = ["-e", "8", "--subdivide", "16", "--no-pictures", "--phases", "1000", "-n", "4"]


def snapshot(out: Path) -> dict[str, str]:
    return {str(p.relative_to(out)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(out.rglob("*")) if p.is_file()}


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
    assert json.loads((out / "export.json").read_text())["complete"] is True


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

"""The output layer, command by command: every command that writes files refuses an unwritable
output folder before any work (exit 2, one line), and a write that fails part-way (the disk
full half-way through a file) keeps every earlier file whole, leaves no temporary file, and
stops with exit 2 and one line.

The commands come from the CLI itself (every command with an ``--out`` option), so a new
command without cheap arguments in ``ARGS`` fails ``test_every_writing_command_is_covered``.
"""

from __future__ import annotations

import errno
import os
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import CASES_DIR, SCENES_DIR

import flexlink.fileio
from flexlink.cli import main

CASE1, CASE2 = str(CASES_DIR / "case1.toml"), str(CASES_DIR / "case2.toml")
# the cheapest arguments that still make each command write all its files (calibrate: one
# free input writes the same seven files as all of them, at a quarter of the fitting)
ARGS = {
    "calibrate": [str(CASES_DIR), "--starts", "1", "--samples", "2", "-e", "2", "--family",
                  "planar", "--jobs", "1", "--free", "L1=100 mm:1 m"],
    "compliant": [str(SCENES_DIR / "compliant_wiper.toml"), "-e", "2", "--angles", "12"],
    "campbell": [CASE1, "--speeds", "0:3000 rev/min", "--poses", "6", "-e", "2", "-n", "2"],
    "converge": [CASE1, "-n", "2", "--max-elements", "8", "--repeats", "1"],
    "correlate": [str(SCENES_DIR / "tests" / "case3_timoshenko.toml"),
                  str(SCENES_DIR / "tests" / "case3_synthetic.uff"), "-e", "2", "-n", "8"],
    "cycle": [CASE1, "--poses", "6", "-e", "2", "-n", "2"],
    "export": [CASE1, "--no-pictures", "-e", "2", "-n", "2", "--phases", "2"],
    "kinematics": [CASE1, "--poses", "8"],
    "life": [CASE1, "--speed", "600 rev/min", "-n", "2", "--elements", "2", "--no-estimate"],
    "mac": [CASE1, CASE2, "-e", "2", "-n", "2"],
    "outputs": [str(SCENES_DIR / "wiper.toml"), "--poses", "8"],
    "modes": [CASE1, "-e", "2", "-n", "2"],
    "prb": [str(SCENES_DIR / "compliant_wiper.toml"), "-e", "2", "-n", "2"],
    "report": [CASE1, "-e", "2", "-n", "2", "--cycle-poses", "0"],
    "response": [CASE1, "--speed", "1200 rev/min", "-n", "1"],
    "schema": [],
    "sensors": [CASE1, "--count", "3", "--modes", "2", "-e", "2"],
    "verify": [CASE1],
    "stability": [CASE1],  # the old name of verify, kept for one release
    "stability-map": [CASE1, "--speeds", "0:600 rev/min", "--count", "3", "-n", "2", "--poses", "13"],
    "torque": [CASE1, "--speed", "600 rev/min", "--poses", "8"],
    "torque-family": [str(SCENES_DIR / "extended_rocker_torque.toml"), "--poses", "8"],
}


@pytest.fixture(scope="module", autouse=True)
def studies_once():
    """The heavy studies (calibration, the stability checks, the periodic models with the
    stability map and the steady response computed on them) are computed once and reused by
    every run here: what is under test is how their results are written."""
    import flexlink.analysis.periodic
    import flexlink.studies.calibration.calibration
    import flexlink.studies.verification.self_checks
    import flexlink.studies.running.stability_map
    import flexlink.studies.running.steady_response

    def once(function, key):
        cache = {}

        def cached(*args, **kwargs):
            k = key(*args, **kwargs)
            if k not in cache:
                cache[k] = function(*args, **kwargs)
            return cache[k]
        return cached

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(flexlink.studies.calibration.calibration, "run_study", once(
            flexlink.studies.calibration.calibration.run_study, lambda files, family, *a, **k: (
                tuple(files), family)))
        mp.setattr(flexlink.studies.verification.self_checks, "run_checks", once(
            flexlink.studies.verification.self_checks.run_checks, lambda scene, **k: (scene.path,
                                                                       k.get("slow"))))
        # a scene is loaded afresh by every run, a model is the cached one (kept alive by the
        # cache, so its id names it)
        running = flexlink.studies.running
        for built, build, solved, solve in (
                (flexlink.analysis.periodic, "periodic_model", running.stability_map,
                 "stability_map"),
                (running.steady_response, "forced_model", running.steady_response,
                 "steady_response")):
            mp.setattr(built, build, once(getattr(built, build), lambda scene, *a, **k: (
                scene.path, repr(a), repr(sorted(k.items())))))
            mp.setattr(solved, solve, once(getattr(solved, solve), lambda model, *a, **k: (
                id(model), repr(a), repr(sorted(k.items())))))
        yield


def writing_commands() -> list[str]:
    import click

    ctx = click.Context(main)
    return sorted(name for name in main.list_commands(ctx)
                  if any(p.name == "out_dir" for p in main.get_command(ctx, name).params))


def test_every_writing_command_is_covered():
    assert set(writing_commands()) == set(ARGS)


def _one_error_line(result) -> str:
    lines = [line for line in result.stderr.splitlines() if line.strip()
             and not line.startswith("warning: ")]
    assert result.exit_code == 2, (result.output, result.exception)
    assert len(lines) == 1 and lines[0].startswith("flexlink: error: "), result.stderr
    return lines[0]


@pytest.mark.parametrize("command", sorted(ARGS))
def test_an_unwritable_out_folder_is_refused_before_any_work(tmp_path, monkeypatch, command):
    """The out folder lies under a plain file, so no one (not even root) can create it; any
    scene loaded before the refusal fails the test."""
    import flexlink.scene.load

    def no_work(*args, **kwargs):
        raise AssertionError("a scene was loaded before the output folder was checked")

    monkeypatch.setattr(flexlink.scene.load, "load_overridden", no_work)
    blocker = tmp_path / "a-file"
    blocker.write_text("not a folder")
    out = blocker / "out"
    result = CliRunner().invoke(main, [command, *ARGS[command], "--out", str(out)])
    line = _one_error_line(result)
    assert f"output folder {out}" in line and "not writable" in line, line


class Counted:
    """Stands in for ``fileio._publish_mode``, the step between a file's (or a staging
    folder's) writing and its rename into place: counts the calls and, at call ``fail_at``,
    cuts the file to half its size and raises ENOSPC, as a disk that filled up mid-write."""

    def __init__(self, fail_at: int | None = None):
        self.calls, self.fail_at = 0, fail_at
        self.real = flexlink.fileio._publish_mode

    def __call__(self, path: Path, directory: bool = False):
        self.calls += 1
        if self.calls == self.fail_at:
            if not directory:
                size = path.stat().st_size
                os.truncate(path, size // 2)
            raise OSError(errno.ENOSPC, "No space left on device")
        return self.real(path, directory)


def _files(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file()}


@pytest.fixture(scope="module")
def first_runs(tmp_path_factory):
    """Each command run once, counting its writes; its files then replaced by marked 'old'
    contents that no run writes."""
    runs = {}
    pair = tmp_path_factory.mktemp("pair")  # calibrate cross-validates: two scenes at least
    for name in ("_table2.toml", "case1.toml", "case3.toml"):
        (pair / name).write_bytes((CASES_DIR / name).read_bytes())
    for command, args in ARGS.items():
        if command == "calibrate":
            args = [str(pair), *args[1:]]
        out = tmp_path_factory.mktemp(command)
        counter = Counted()
        with pytest.MonkeyPatch.context() as mp:
            mp.setattr(flexlink.fileio, "_publish_mode", counter)
            result = CliRunner().invoke(main, [command, *args, "--out", str(out)])
        assert result.exit_code == 0, (command, result.output, result.exception)
        for path in out.rglob("*"):
            if path.is_file():
                path.write_bytes(b"old " + path.name.encode())
        runs[command] = (out, counter.calls, _files(out), args)
    return runs


@pytest.mark.parametrize("which", ["first", "last"])
@pytest.mark.parametrize("command", sorted(ARGS))
def test_a_write_failing_part_way_keeps_the_old_files(first_runs, monkeypatch, command, which):
    out, writes, old, args = first_runs[command]
    assert writes >= 1, command
    fail_at = 1 if which == "first" else writes
    counter = Counted(fail_at)
    monkeypatch.setattr(flexlink.fileio, "_publish_mode", counter)
    result = CliRunner().invoke(main, [command, *args, "--out", str(out)])
    line = _one_error_line(result)
    assert "No space left on device" in line, line
    now = _files(out)
    # no temporary file, staging folder or half-written file is left, and no file is lost
    assert sorted(now) == sorted(old), set(now) ^ set(old)
    kept = [name for name in old if now[name] == old[name]]
    renewed = [name for name in old if now[name] != old[name]]
    assert kept, "the failed write's target should keep its old contents"
    for name in renewed:  # a file written before the failure is a whole new file
        assert not now[name].startswith(b"old "), name
    if which == "first":
        assert renewed == [], renewed
    assert not any(p.name.startswith(".") for p in out.rglob("*")), list(out.rglob(".*"))
    # restore the marked contents for the next parametrisation on this folder
    for name, data in old.items():
        (out / name).write_bytes(data)

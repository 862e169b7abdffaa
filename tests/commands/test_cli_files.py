"""Result files never replace each other unseen, commands say what they wrote, the crank speed
of the resonance check means what it says, and commands stay thin (parse, call, print, write)."""

import ast
import json
import math
from pathlib import Path

import numpy as np
from click.testing import CliRunner

from flexlink.cli import main
from flexlink.studies.cycle.modal_map import ModalMap, resonance_speed, resonances

from conftest import ROOT
COMMANDS = ROOT / "flexlink" / "commands"


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_modes_of_two_scenes_one_after_the_other_keeps_both(tmp_path):
    first = run("modes", ROOT / "cases" / "case1.toml", "-e", "4", "--out", tmp_path)
    second = run("modes", ROOT / "cases" / "case2.toml", "-e", "4", "--json", "--out", tmp_path)
    assert first.exit_code == 0 and second.exit_code == 0, first.output + second.output
    for case in ("case1", "case2"):
        doc = json.loads((tmp_path / case / "modes.json").read_text())
        assert [Path(c["file"]).stem for c in doc["cases"]] == [case]
        assert (tmp_path / case / "modes.csv").read_text().count("\n") == 1 + 4
    assert not (tmp_path / "modes.json").exists()  # one scene: no combined file
    # the table run names each file on stderr; the JSON run lists them
    assert [f"wrote {tmp_path / 'case1' / n}" for n in ("modes.json", "modes.csv")] == [
        line for line in first.stderr.splitlines() if line.startswith("wrote ")]
    assert json.loads(second.stdout)["files"] == [str(tmp_path / "case2" / n)
                                                  for n in ("modes.json", "modes.csv")]
    assert second.stderr == ""


def test_same_scene_name_twice_is_refused_before_any_work(tmp_path):
    other = tmp_path / "elsewhere"
    other.mkdir()
    (other / "case1.toml").write_text("")  # refused before it is read
    result = run("modes", ROOT / "cases" / "case1.toml", other / "case1.toml", "--out", tmp_path)
    assert result.exit_code == 2 and "same folder 'case1'" in result.output


def _map(frequencies):
    q = np.linspace(0, 2 * math.pi, len(frequencies), endpoint=False)
    return ModalMap(scene="test", q=q, frequencies=np.array(frequencies, float)[:, None],
                    mechanism_counts=np.zeros(len(q), int), mu90={})


def test_negative_crank_speed_is_checked_at_its_magnitude():
    speed = 2 * math.pi * 10.0  # 10 Hz crank
    check, note = resonance_speed(-speed)
    assert check == speed and "opposite" in note and "600 rev/min" in note
    hits = resonances(_map([29.0, 30.5, 31.0]), check, margin=0.05, harmonics=5)
    assert [(h.harmonic, h.mode) for h in hits] == [(3, 1)]  # 30 Hz next to the 29..31 Hz mode
    assert resonance_speed(speed) == (speed, None)


def test_zero_or_no_crank_speed_says_the_check_is_skipped():
    assert resonance_speed(0.0)[0] is None and "skipped" in resonance_speed(0.0)[1]
    assert resonance_speed(None)[0] is None and "skipped" in resonance_speed(None)[1]


def test_cycle_command_with_negative_and_zero_speed(tmp_path):
    common = ("cycle", ROOT / "scenes" / "kineto_aluminium.toml", "--poses", "6", "-e", "3",
              "-n", "2", "--harmonics", "100", "--json", "--out", tmp_path)
    forward = json.loads(run(*common, "--speed", "600 rev/min").stdout)
    backward = json.loads(run(*common, "--speed", "-600 rev/min").stdout)
    assert forward["resonances"] and backward["resonances"] == forward["resonances"]
    assert backward["crank_speed_rev_per_min"] == -600.0
    assert backward["resonance_check"]["speed_rev_per_min"] == 600.0
    table = run(*common[:-3], "--out", tmp_path, "--speed", "0 rev/min")
    assert table.exit_code == 0, table.output
    assert "resonance check skipped" in table.stdout and "resonance:" not in table.stdout


def test_converge_and_kinematics_commands_hold_no_study_logic():
    """The commands call one study function; the study (levels, Richardson, limits, families)
    lives in the library. Guarded by what the commands may not name."""
    study_names = {"run_levels", "richardson", "cheapest", "relative_errors", "mesh_levels",
                   "limit_positions", "body_summary", "transmission_angles", "kinematic_cycle",
                   "raw"}
    for name in ("converge.py", "kinematics.py"):
        tree = ast.parse((COMMANDS / name).read_text())
        used = {n.attr if isinstance(n, ast.Attribute) else n.id for n in ast.walk(tree)
                if isinstance(n, (ast.Attribute, ast.Name))}
        assert used & study_names == set(), name
        defs = [n.name for n in tree.body if isinstance(n, ast.FunctionDef)]
        assert defs == ["command"], name


def test_a_folder_of_many_written_files_is_said_in_one_line(capsys, tmp_path):
    """A ParaView series' frames are one stderr line (count, first, last), the files beside
    them one line each, and the returned list (the JSON's ``files``) still has every path."""
    from flexlink.commands._written import FILES_LISTED_ONE_BY_ONE, announce

    frames = [tmp_path / "life" / f"angle{i:03d}.vtu" for i in range(FILES_LISTED_ONE_BY_ONE + 1)]
    listed = announce([tmp_path / "life.csv", *frames, tmp_path / "life.pvd"], quiet=False)
    assert listed == [str(p) for p in [tmp_path / "life.csv", *frames, tmp_path / "life.pvd"]]
    assert capsys.readouterr().err.splitlines() == [
        f"wrote {tmp_path / 'life.csv'}", f"wrote {tmp_path / 'life.pvd'}",
        f"wrote {len(frames)} files in {tmp_path / 'life'}/ (angle000.vtu ... "
        f"angle{len(frames) - 1:03d}.vtu)"]

"""Every command on a corpus of bad scenes: exit status 2 and one line naming the file, never a
traceback (issue 11, item 2); and a folder run keeps the good scenes' results (item 3)."""

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from flexlink.cli import main

from conftest import ROOT
RATIOS = "[linkage]\nR2 = 0.267\nR3 = 0.800\nR4 = 0.667\n"

CORPUS = {
    "binary": b"\xff\xfe\x00\x01 not text",
    "inf_reference": RATIOS + "[reference]\nEx_Hz = [inf, 85, 249, 610]\n",
    "overflow_stiffness": RATIOS + '[joints]\nKt = "1e400 N/m"\n',
    "typo_table": RATIOS + '[secton]\nwidth = "10 mm"\n',
    "unreachable_pose": RATIOS + '[pose]\ntransmission_angle = "20 deg"\n',
    "not_toml": "[linkage\nR2 = ",
}
COMMANDS = (["modes"], ["export", "--no-pictures"], ["verify"], ["converge"],
            ["cycle", "--poses", "8"], ["kinematics", "--poses", "8"], ["prb"],
            ["calibrate", "--starts", "1", "--samples", "2"], ["report", "--cycle-poses", "0"],
            ["campbell", "--speeds", "0:3000 rev/min", "--poses", "8"])


@pytest.fixture(scope="module")
def corpus(tmp_path_factory):
    folder = tmp_path_factory.mktemp("bad")
    (folder / "_table2.toml").write_text((ROOT / "cases" / "_table2.toml").read_text())
    paths = {}
    for name, text in CORPUS.items():
        path = folder / f"{name}.toml"
        if isinstance(text, bytes):
            path.write_bytes(text)
        else:
            path.write_text('base = "_table2.toml"\n' + text)
        paths[name] = path
    return paths


@pytest.mark.parametrize("command", COMMANDS, ids=lambda c: c[0])
@pytest.mark.parametrize("name", sorted(CORPUS))
def test_bad_scene_gives_exit_2_and_one_line_naming_the_file(corpus, tmp_path, command, name):
    path = corpus[name]
    result = CliRunner().invoke(main, [command[0], str(path), *command[1:], "--out",
                                       str(tmp_path)])
    assert result.exit_code == 2, (result.output, result.exception)
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("flexlink: error: ") and str(path) in lines[0], \
        result.stderr
    assert "Traceback" not in result.output


def test_synth_refuses_an_overflowing_angle():
    result = CliRunner().invoke(main, ["synth", "minimax", "1e400 deg", "20 deg"])
    assert result.exit_code == 2 and "not a finite number" in result.stderr, result.output


def test_folder_run_keeps_the_good_scenes_and_lists_the_bad(tmp_path):
    folder = tmp_path / "scenes"
    folder.mkdir()
    for name in ("_table2.toml", "case1.toml", "case3.toml"):
        (folder / name).write_text((ROOT / "cases" / name).read_text())
    bad = folder / "case9.toml"
    bad.write_text('base = "_table2.toml"\n' + RATIOS + '[pose]\ntransmission_angle = "20 deg"\n')
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["modes", str(folder), "-e", "4", "--json", "--out", str(out)])
    assert result.exit_code == 2
    doc = json.loads(result.stdout)
    assert [Path(c["file"]).name for c in doc["cases"]] == ["case1.toml", "case3.toml"]
    assert [f["file"] for f in doc["failures"]] == [str(bad)]
    assert "not reachable" in doc["failures"][0]["error"]
    for name in ("case1", "case3"):  # the good scenes' own files, and the combined one
        assert json.loads((out / name / "modes.json").read_text())["cases"][0]["scene"]
    assert len(json.loads((out / "modes.json").read_text())["cases"]) == 2
    lines = result.stderr.splitlines()
    assert str(bad) in lines[0] and "1 of 3 scene(s) failed" in lines[-1]


def test_an_analysis_error_names_the_scene_too(tmp_path):
    """The model has 17 elastic modes at 1 element per link: asking for 50 is refused, and the
    error line says which scene (the analysis itself does not know the file)."""
    scene = tmp_path / "coarse.toml"
    scene.write_text(f'base = "{ROOT / "cases" / "_table2.toml"}"\n' + RATIOS)
    result = CliRunner().invoke(main, ["cycle", str(scene), "-n", "50", "-e", "1", "--poses", "4",
                                       "--out", str(tmp_path / "out")])
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith(f"flexlink: error: {scene}: ") and \
        "50 elastic modes asked for" in result.stderr and result.stderr.count("\n") == 1, \
        result.stderr
    # the frequency-sorted map (the Craig-Bampton sweep) refuses the same way
    result = CliRunner().invoke(main, ["cycle", str(scene), "-n", "50", "-e", "1", "--poses", "4",
                                       "--sorted", "--out", str(tmp_path / "out")])
    assert result.exit_code == 2 and "50 elastic modes asked for" in result.stderr
    assert not (tmp_path / "out" / "coarse" / "cycle.json").exists()  # nothing half-written


def test_folder_export_keeps_the_good_scenes(tmp_path):
    folder = tmp_path / "scenes"
    folder.mkdir()
    for name in ("_table2.toml", "case2.toml"):
        (folder / name).write_text((ROOT / "cases" / name).read_text())
    bad = folder / "bad.toml"
    bad.write_text('base = "_table2.toml"\n' + RATIOS + '[secton]\nwidth = "1 mm"\n')
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["export", str(folder), "-e", "2", "-n", "2",
                                       "--no-pictures", "--out", str(out)])
    assert result.exit_code == 2, result.output
    listed = json.loads((out / "export.json").read_text())
    assert [Path(c["file"]).name for c in listed["cases"]] == ["case2.toml"]
    assert listed["failures"][0]["file"] == str(bad) and not listed["complete"]
    assert (out / "case2" / "case2.vtu").is_file()
    assert "[secton]: unknown table" in result.stderr and "1 of 2 scene(s) failed" in result.stderr

"""The command line: JSON document, files written, errors without tracebacks."""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from flexlink.cli import main

from conftest import ROOT


def test_modes_json_and_files(tmp_path):
    result = CliRunner().invoke(main, ["modes", str(ROOT / "cases"), "--json", "--out",
                                       str(tmp_path), "-e", "8"])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert len(doc["cases"]) == 4
    for case in doc["cases"]:
        assert len(case["modes"]) == 4
        assert abs(case["pose"]["mu_deg"] - 90) < 1e-9
        for row in case["modes"]:  # the % errors are what they say they are
            for ref in ("Ex", "FE"):
                expected = 100 * (row["computed_Hz"] - row[f"{ref}_Hz"]) / row[f"{ref}_Hz"]
                assert abs(row[f"error_vs_{ref}_pct"] - expected) < 1e-9
    assert json.loads((tmp_path / "modes.json").read_text()) == doc  # the combined file
    assert (tmp_path / "modes.csv").read_text().count("\n") == 1 + 16
    for case in doc["cases"]:  # and one pair per scene
        own = json.loads((tmp_path / Path(case["file"]).stem / "modes.json").read_text())
        assert own["cases"] == [case]


def test_table_output_lists_every_case(tmp_path):
    result = CliRunner().invoke(main, ["modes", str(ROOT / "cases"), "--out", str(tmp_path)])
    assert result.exit_code == 0
    for case in (1, 2, 3, 4):
        assert f"Table II case {case}" in result.output
    assert "overall mean |error|" in result.output


def test_bad_scene_is_one_clear_line(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[linkage]\nR2 = 0.3\n")
    result = CliRunner().invoke(main, ["modes", str(bad), "--out", str(tmp_path)])
    assert result.exit_code == 2
    assert "bad.toml" in result.output and "linkage" in result.output
    assert "Traceback" not in result.output


def test_unwritable_out_dir_fails_before_solving(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    result = CliRunner().invoke(main, ["modes", str(ROOT / "cases"), "--out", str(blocker / "o")])
    assert result.exit_code == 2 and "not writable" in result.output


def test_console_script_help():
    out = subprocess.run([sys.executable, "-m", "flexlink.cli", "--help"], capture_output=True,
                         text=True, check=True).stdout
    assert "modes" in out


def test_modes_follows_the_scene_model_family(tmp_path):
    """A scene that chooses the out-of-plane family is reported with that family's modes."""
    from flexlink.analysis.families import elastic_modes
    from flexlink.scene import load_scene

    scene_file = tmp_path / "oop.toml"
    scene_file.write_text(f'base = "{ROOT / "cases" / "case1.toml"}"\n[model]\nfamily = "out-of-plane"\n')
    result = CliRunner().invoke(main, ["modes", str(scene_file), "--json", "--out", str(tmp_path),
                                       "-e", "6"])
    assert result.exit_code == 0, result.output
    case = json.loads(result.stdout)["cases"][0]
    assert case["family"] == "out-of-plane"
    expected, kinds = elastic_modes(load_scene(scene_file), 4, 6)
    # the same solve again in this process: to round-off
    np.testing.assert_allclose([r["computed_Hz"] for r in case["modes"]], expected, rtol=1e-12)
    assert {r["kind"] for r in case["modes"]} == {"out-of-plane"}


def test_version_comes_from_the_package_metadata():
    from importlib.metadata import version

    result = CliRunner().invoke(main, ["--version"])
    assert result.exit_code == 0 and result.output == f"flexlink, version {version('flexlink')}\n"


@pytest.mark.parametrize("given, expected", [(None, "1"), ("3", "3")])
def test_the_command_line_takes_one_blas_thread_unless_told(given, expected):
    # the CLI sets the BLAS thread count before numpy is first imported (numpy reads it only
    # then), and leaves a count the user's environment gives alone
    env = {k: v for k, v in os.environ.items()
           if k not in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")}
    if given is not None:
        env["OPENBLAS_NUM_THREADS"] = given
    probe = ("import os, sys; import flexlink.cli; "
             "print(os.environ['OPENBLAS_NUM_THREADS'], 'numpy' in sys.modules)")
    run = subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True, text=True,
                         cwd=ROOT, check=True)
    assert run.stdout.split() == [expected, "False"]

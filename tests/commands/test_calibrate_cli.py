"""`flexlink calibrate` end to end on a tiny problem: JSON document, report and plots written."""

import json

from click.testing import CliRunner

from flexlink.cli import main

from conftest import CASES_DIR as CASES


def test_calibrate_writes_report_json_and_plots(tmp_path):
    args = ["calibrate", str(CASES / "case1.toml"), str(CASES / "case2.toml"),
            "--free", "Kt=1e4 N/m:1e9 N/m", "--starts", "1", "--samples", "2", "-e", "2",
            "--jobs", "1", "--json", "--out", str(tmp_path)]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    [study] = doc["studies"]
    assert study["family"] == "planar"
    errors = study["errors_mean_abs_pct"]
    # the assumed inputs are hundreds of % off and the fit starts from them: it must improve
    assert errors["calibrated_to_Ex_in_sample"] <= errors["assumed_inputs_vs_Ex"] + 1e-9
    assert len(study["cross_validation"]["errors_pct"]) == 2
    run = tmp_path / "case1+case2"  # the run's folder is named after its scenes
    assert sorted(doc["files"]) == sorted(str(p) for p in run.iterdir())
    report = (run / "report.md").read_text()
    assert "cross-validated" in report and "Proportionality" in report
    for name in ("frequencies", "cross_validation", "ratios", "intervals"):
        assert (run / f"{name}-planar.png").read_bytes()[:4] == b"\x89PNG"


def test_calibrate_refuses_a_bad_free_spec(tmp_path):
    result = CliRunner().invoke(main, ["calibrate", str(CASES), "--free", "L1=1:2",
                                       "--out", str(tmp_path)])
    assert result.exit_code == 2 and "--free" in result.output


def test_calibrate_refuses_one_scene_in_one_line(tmp_path):
    """Cross-validation leaves one case out: with one scene there is nothing left to fit."""
    result = CliRunner().invoke(main, ["calibrate", str(CASES / "case1.toml"), "--starts", "1",
                                       "--samples", "2", "-e", "2", "--out", str(tmp_path)])
    assert result.exit_code == 2, result.output
    assert "at least two scenes" in result.output and "Traceback" not in result.output

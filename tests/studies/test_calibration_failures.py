"""Calibration with a case that cannot be evaluated: the failure is reported by case and mode,
and no mean |error| quietly leaves it out."""

import json
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

import flexlink.studies.calibration.fit as calibration
from flexlink.cli import main
from flexlink.errors import NumericalError
from flexlink.output.calibration.calibration import fit_document

from conftest import CASES_DIR as CASES
FORCED = "forced failure for the test"


@pytest.fixture
def case2_fails(monkeypatch):
    real = calibration.elastic_modes

    def elastic_modes(scene, *args, **kwargs):
        if Path(scene.path).stem == "case2":
            raise NumericalError(FORCED)
        return real(scene, *args, **kwargs)

    monkeypatch.setattr(calibration, "elastic_modes", elastic_modes)


def test_a_failed_case_gives_no_mean_and_is_named(case2_fails):
    problem = calibration.Problem(scenes=(str(CASES / "case1.toml"), str(CASES / "case2.toml")),
                                  parameters=(calibration.parse_free("Kt=1e4 N/m:1e9 N/m"),),
                                  elements=2)
    [fit] = calibration.fit_many([problem], starts=1, n_jobs=1)
    assert fit.mean_abs_error_pct is None
    document = fit_document(fit)
    assert document["mean_abs_error_pct"] is None
    assert [(f["case"], f["mode"]) for f in document["failed"]] == [("case2", k) for k in (1, 2, 3, 4)]
    assert all(f["reason"] == FORCED for f in document["failed"])


def test_mean_abs_is_the_plain_mean_when_nothing_failed():
    assert calibration.mean_abs([[1.0, -3.0], [2.0, -6.0]]) == 3.0
    assert calibration.mean_abs([[1.0, float("nan")]]) is None


def test_calibrate_command_reports_the_failed_case(case2_fails, tmp_path):
    args = ["calibrate", str(CASES / "case1.toml"), str(CASES / "case2.toml"),
            "--free", "Kt=1e4 N/m:1e9 N/m", "--starts", "1", "--samples", "2", "-e", "2",
            "--jobs", "1", "--json", "--out", str(tmp_path)]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    [study] = json.loads(result.stdout)["studies"]
    means, failed = study["errors_mean_abs_pct"], study["errors_failed"]
    assert means["assumed_inputs_vs_Ex"] is None and means["cross_validated_vs_Ex"] is None
    assert [(f["case"], f["mode"]) for f in failed["assumed_inputs_vs_Ex"]] == [
        ("case2", k) for k in (1, 2, 3, 4)]
    assert study["errors_count"]["assumed_inputs_vs_Ex"] == 8
    assert means["paper_FE_vs_Ex"] is not None and failed["paper_FE_vs_Ex"] == []
    report = (tmp_path / "case1+case2" / "report.md").read_text()  # the run's folder
    assert "n/a (4 of 8 failed)" in report
    assert "### Failed evaluations" in report and FORCED in report
    # the model's warnings over the study's evaluations: one summary line at most, nothing
    # else (in a test process whose logging an earlier test set up, the line may go elsewhere)
    warned = [line for line in result.stderr.splitlines() if line.startswith("warning: ")]
    assert len(warned) <= 1, warned
    assert all(re.search(r"\d+ warnings? of \d+ kinds? during the planar calibration study",
                         line) for line in warned), warned

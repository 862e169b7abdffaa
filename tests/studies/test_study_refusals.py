"""What the studies say when an input cannot be used: the calibration's --free refusal quotes
what it could not read, a reference column too short for the fit names its file, and a Monte Carlo sample that fails is logged with its file and values
(and counted as NaN, never dropped)."""

import logging

import numpy as np
import pytest
from conftest import CASES_DIR

from flexlink.errors import InputError
from flexlink.studies.calibration.fit import Problem, measured, parse_free
from flexlink.studies.calibration.uncertainty import evaluate, scene_inputs

CASE2 = str(CASES_DIR / "case2.toml")


@pytest.mark.parametrize("spec", ["L1 0.1 m 1 m", "colour=1 m:2 m"])
def test_a_free_parameter_not_read_is_quoted(spec):
    with pytest.raises(InputError) as refused:
        parse_free(spec)
    assert f"cannot read {spec!r}" in str(refused.value) and refused.value.field == "--free"


def test_a_failing_sample_is_nan_and_logged_with_its_file_and_values(caplog):
    inputs = scene_inputs(CASE2, {}, vf_sd=0.05, thickness_sd=0.15e-3)
    bad = {"linkage.ground": "-1 mm"}  # a negative length: the scene refuses to load
    with caplog.at_level(logging.INFO, logger="flexlink.studies.calibration.uncertainty"):
        out = evaluate([CASE2], bad, inputs, inputs.nominal, 2, 4)
    assert out.shape == (1, 2) and np.isnan(out).all()
    messages = [r.getMessage() for r in caplog.records if r.name == "flexlink.studies.calibration.uncertainty"]
    assert len(messages) == 1
    assert messages[0].startswith(f"{CASE2} at {inputs.nominal}: ") and "linkage.ground" in messages[0]


def test_a_reference_column_too_short_names_its_file_and_field():
    """Case 2 gives four measured frequencies; a fit of five modes cannot use them."""
    problem = Problem(scenes=(CASE2,), parameters=(parse_free("L1=100 mm:1 m"),), n_modes=5)
    with pytest.raises(InputError) as refused:
        measured(problem)
    assert refused.value.source == CASE2 and refused.value.field == "reference.Ex_Hz"
    assert str(refused.value).startswith(f"{CASE2}: reference.Ex_Hz: needs 5 values")

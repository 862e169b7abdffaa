"""Calibration recovers known inputs from synthetic data; cross-validation and ratio residuals
do what they say; free-input specs are validated. Coarse meshes, few starts, one process."""

import dataclasses

import numpy as np
import pytest

from flexlink.studies.calibration.fit import (FreeParameter, Problem, cross_validation, fit_many,
                                  leave_one_out_problems, log_residuals, parse_free, predict)
from flexlink.errors import InputError

from conftest import CASES_DIR as CASES
TRUE = {"L1": 0.25, "Kt": 3e4}  # the "unknown" inputs the synthetic data are made with
# (Kt of the order of the flatwise strips' own stiffness, so the data can tell it)
ELEMENTS = 3


def synthetic_scene(tmp_path, case):
    """A copy of a shipped case whose Ex column is the model's own answer at TRUE inputs."""
    free = (FreeParameter("L1", 0.1, 1.0), FreeParameter("Kt", 1e4, 1e9))
    truth = Problem((str(CASES / f"case{case}.toml"),), free, elements=ELEMENTS)
    f = predict(truth, [TRUE["L1"], TRUE["Kt"]])[0]
    text = (CASES / f"case{case}.toml").read_text().replace('base = "_table2.toml"',
                                                          f'base = "{CASES / "_table2.toml"}"')
    text = text.split("[reference]")[0] + "[reference]\nEx_Hz = [" + ", ".join(repr(float(v)) for v in f) + "]\n"
    path = tmp_path / f"synthetic{case}.toml"
    path.write_text(text)
    return str(path), free


def test_parse_free_reads_units_and_refuses_bad_specs():
    p = parse_free("L1=100 mm:1 m")
    assert (p.name, p.low, p.high) == ("L1", pytest.approx(0.1), 1.0)
    assert p.overrides(0.3) == {"linkage.ground": "0.3 m"}
    for bad in ("L1=0.1:1", "L1=1 m:0.1 m", "colour=1 m:2 m", "L1 0.1 m 1 m", "Kt=1 m:2 m"):
        with pytest.raises(InputError):
            parse_free(bad)


def test_fit_recovers_the_inputs_of_synthetic_data(tmp_path):
    path, free = synthetic_scene(tmp_path, 2)
    problem = Problem((path,), free, elements=ELEMENTS)
    [fit] = fit_many([problem], starts=2, seed=3, n_jobs=1)
    np.testing.assert_allclose(fit.values, [TRUE["L1"], TRUE["Kt"]], rtol=1e-4)
    assert fit.mean_abs_error_pct < 1e-3
    assert fit.rel_se is not None and np.all(fit.rel_se < 1e-3)  # exact data: tiny errors
    assert fit.correlation.shape == (2, 2) and fit.correlation[0, 0] == pytest.approx(1.0)


def test_cross_validation_predicts_held_out_case_of_shared_truth(tmp_path):
    a, free = synthetic_scene(tmp_path, 1)
    b, _ = synthetic_scene(tmp_path, 4)
    problem = Problem((a, b), free, elements=ELEMENTS)
    folds = fit_many(leave_one_out_problems(problem), starts=1, seed=0, n_jobs=1)
    assert [f.problem.scenes for f in folds] == [(b,), (a,)]
    cv = cross_validation(problem, folds)
    # one shared truth: each case alone determines it, so the other case is predicted
    assert cv.mean_abs_error_pct < 1e-2


def test_ratio_residuals_ignore_a_common_scale():
    problem = Problem(("x",), (), target="ratios")
    f = np.array([[10.0, 25.0, 72.0, 173.0]])
    assert np.abs(log_residuals(problem, 3.7 * f, f)).max() < 1e-14
    absolute = dataclasses.replace(problem, target="frequencies")
    np.testing.assert_allclose(log_residuals(absolute, 3.7 * f, f), np.log(3.7))

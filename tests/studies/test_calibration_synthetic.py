"""Calibration, cross-validation and the comparison study on a synthetic problem whose answers
are known in closed form.

The FE model is replaced by f_ik = A_ik / L1^2 (case i, mode k), so ln f is linear in the free
input x = ln L1 and the least-squares fit, its standard error and every held-out prediction
follow by hand. The "measurements" are made by the same law at known L1 with known
log-errors e_ik: leakage in the cross-validation, a wrong residual variance or swapped Ex / FE
columns each move a number checked here.
"""

import dataclasses
import math
import re
from pathlib import Path

import numpy as np
import pytest

import flexlink.studies.calibration.fit as calibration
import flexlink.studies.calibration.uncertainty as uncertainty
from flexlink.studies.calibration.fit import (FreeParameter, Problem, cross_validation, fit_many,
                                          leave_one_out_problems)
from flexlink.studies.calibration.calibration import StudySettings, run_study
from flexlink.output.calibration.calibration import study_document
from flexlink.output.calibration.calibration_report import report_markdown, summary_text
from flexlink.studies.calibration.jacobian import CaseModes

from conftest import CASES_DIR as CASES
A = {"s1": np.array([3.0, 8.0, 24.0, 60.0]), "s2": np.array([4.5, 12.0, 30.0, 70.0])}  # [Hz m^2]
L_EX, L_FE, L_NOMINAL = 0.35, 0.2, 0.3  # [m]; L_NOMINAL is the scenes' assumed ground (300 mm)
E = {"s1": np.array([0.01, -0.02, 0.015, -0.005]), "s2": np.array([-0.01, 0.02, 0.0, 0.03])}
L1_FREE = FreeParameter("L1", 0.1, 1.0)


def ground_of(scene) -> float:
    """The one scene value the law reads [m] (kept here so a new scene type changes one line)."""
    return scene.four_bar.ground


def law(scene, n_modes, elements=None, solver=None):
    """Stand-in for analysis.families.elastic_modes: frequencies [Hz] A / L1^2, in-plane."""
    f = A[Path(scene.path).stem][:n_modes] / ground_of(scene) ** 2
    return f, ("in-plane",) * n_modes


def law_case(scene, n_modes, elements=None):
    """Stand-in for studies.calibration.jacobian.case_modes: the law's frequencies, no model parts."""
    return CaseModes(law(scene, n_modes)[0], (), tuple((0, k) for k in range(n_modes)))


def law_sensitivities(load, values, names, cases, n_modes, elements, cache, upper=None):
    """Stand-in for studies.calibration.jacobian.log_frequency_sensitivities: d ln f / d ln L1 = -2."""
    D = np.zeros((len(cases), n_modes, len(names)))
    D[..., list(names).index("L1")] = -2.0
    return D


def ex(name):
    return A[name] / L_EX**2 * np.exp(E[name])


def fe(name):
    return A[name] / L_FE**2


@pytest.fixture
def scenes(tmp_path, monkeypatch):
    """Two scene files (Table II cases 1 and 2 as written) whose reference columns are the law's
    values; the law stands in for the FE model in calibration and uncertainty, and its
    derivative for the model's eigenvalue sensitivities (tests/studies/test_jacobian.py checks those)."""
    monkeypatch.setattr(calibration, "elastic_modes", law)
    monkeypatch.setattr(calibration, "case_modes", law_case)
    monkeypatch.setattr(calibration, "log_frequency_sensitivities", law_sensitivities)
    monkeypatch.setattr(uncertainty, "elastic_modes", law)
    paths = []
    for name, case in (("s1", 1), ("s2", 2)):
        text = (CASES / f"case{case}.toml").read_text()
        text = text.replace('base = "_table2.toml"', f'base = "{CASES / "_table2.toml"}"')
        text = text.split("[reference]")[0] + (
            "[reference]\n"
            f"FE_Hz = [{', '.join(repr(float(v)) for v in fe(name))}]\n"
            f"Ex_Hz = [{', '.join(repr(float(v)) for v in ex(name))}]\n")
        path = tmp_path / f"{name}.toml"
        path.write_text(text)
        paths.append(str(path))
    return tuple(paths)


def best_l1(names):
    """Least squares of ln(A / L1^2) - ln Ex over the named cases: ln L1 = ln L_EX - mean(e)/2."""
    return L_EX * math.exp(-np.mean(np.concatenate([E[n] for n in names])) / 2)


def test_fit_and_its_standard_error_by_hand(scenes):
    [fit] = fit_many([Problem(scenes, (L1_FREE,))], starts=2, seed=0, n_jobs=1)
    assert fit.values[0] == pytest.approx(best_l1(["s1", "s2"]), rel=1e-7)
    assert fit.converged == (True, True)  # a linear problem: both starts stop at a tolerance
    # residuals r = e - mean(e) (m = 8, p = 1); Jacobian column d r / d ln L1 = -2 everywhere:
    # var(ln L1) = s^2 / (4 m), s^2 = sum r^2 / (m - p)
    e = np.concatenate([E["s1"], E["s2"]])
    r = e - e.mean()
    s2 = np.sum(r**2) / (r.size - 1)
    assert fit.rel_se[0] == pytest.approx(math.sqrt(s2 / (4 * r.size)), rel=1e-5)
    # in-sample errors: A / L*^2 against Ex = exp(mean(e) - e) - 1
    np.testing.assert_allclose(fit.errors_pct.ravel(), 100 * np.expm1(e.mean() - e), atol=1e-5)


def test_cross_validation_predicts_each_case_from_the_other_only(scenes):
    """Fold k sees only the other case: its L1 is that case's own best value, so the held-out
    error is exp(mean(e_other) - e_k) - 1. A fold that also saw case k would pull L1 towards
    case k's own best value and shrink this error."""
    problem = Problem(scenes, (L1_FREE,))
    folds = fit_many(leave_one_out_problems(problem), starts=1, seed=0, n_jobs=1)
    cv = cross_validation(problem, folds)
    for i, (held, other) in enumerate((("s1", "s2"), ("s2", "s1"))):
        assert folds[i].values[0] == pytest.approx(best_l1([other]), rel=1e-7)
        np.testing.assert_allclose(cv.predicted[i], A[held] / best_l1([other]) ** 2, rtol=1e-6)
        np.testing.assert_allclose(cv.errors_pct[i], 100 * np.expm1(E[other].mean() - E[held]),
                                   atol=1e-4)


def test_width_override_is_written_in_metres(scenes):
    width = FreeParameter("width", 5e-3, 60e-3)
    problem = Problem(scenes[:1], (width,))
    scene = problem.scene(scenes[0], [0.025])
    assert scene.sections["crank"].strip[0] == pytest.approx(0.025, rel=1e-15)


def test_calibration_study_errors_are_against_ex(scenes):
    settings = StudySettings(starts=2, seed=0, samples=3, elements=None, n_jobs=1)
    study = run_study(scenes, "planar", (L1_FREE,), settings)
    ex_all = np.array([ex("s1"), ex("s2")])
    fe_all = np.array([fe("s1"), fe("s2")])
    nominal = np.array([A["s1"], A["s2"]]) / L_NOMINAL**2
    np.testing.assert_allclose(study.ex, ex_all, rtol=1e-12)
    np.testing.assert_allclose(study.paper_fe, fe_all, rtol=1e-12)
    np.testing.assert_allclose(study.errors["assumed_inputs_vs_Ex"].errors_pct,
                               100 * (nominal / ex_all - 1), rtol=1e-9)
    errors = {k: e.mean_abs_pct for k, e in study.errors.items()}
    assert errors["assumed_inputs_vs_Ex"] == pytest.approx(np.mean(np.abs(100 * (nominal / ex_all - 1))))
    # the Ex fit lands on best_l1, the FE fit on L_FE exactly (FE has no noise)
    assert study.fit_ex.values[0] == pytest.approx(best_l1(["s1", "s2"]), rel=1e-7)
    assert study.fit_fe.values[0] == pytest.approx(L_FE, rel=1e-7)
    e = np.concatenate([E["s1"], E["s2"]])
    assert errors["calibrated_to_Ex_in_sample"] == pytest.approx(np.mean(np.abs(100 * np.expm1(e.mean() - e))), abs=1e-5)
    assert errors["calibrated_to_FE_vs_FE"] == pytest.approx(0.0, abs=1e-5)
    fe_vs_ex = np.mean(np.abs(100 * (fe_all / ex_all - 1)))  # about 206 %
    assert errors["calibrated_to_FE_vs_Ex"] == pytest.approx(fe_vs_ex, rel=1e-6)
    assert errors["paper_FE_vs_Ex"] == pytest.approx(fe_vs_ex, rel=1e-12)
    cv = [100 * np.expm1(E["s2"].mean() - E["s1"]), 100 * np.expm1(E["s1"].mean() - E["s2"])]
    assert errors["cross_validated_vs_Ex"] == pytest.approx(np.mean(np.abs(cv)), abs=1e-4)
    # each case's own fit lands on that case's best L1; the document says the same by name
    for fit, name in zip(study.per_case, ("s1", "s2")):
        assert fit.values[0] == pytest.approx(best_l1([name]), rel=1e-7)
    # the JSON document names the same numbers: each field checked against the closed form
    document = study_document(study)
    np.testing.assert_allclose(document["Ex_Hz"], ex_all, rtol=1e-12)
    np.testing.assert_allclose(document["paper_FE_Hz"], fe_all, rtol=1e-12)
    np.testing.assert_allclose(document["nominal_Hz"], nominal, rtol=1e-12)
    fitted = document["fit_Ex"]["parameters"][0]["value"]
    assert fitted == pytest.approx(best_l1(["s1", "s2"]), rel=1e-7)
    assert document["fit_FE"]["parameters"][0]["value"] == pytest.approx(L_FE, rel=1e-7)
    assert document["errors_mean_abs_pct"] == pytest.approx(errors)
    np.testing.assert_allclose(document["cross_validation"]["errors_pct"], cv, atol=1e-4)
    assert [c["case"] for c in document["per_case_fits"]] == ["s1", "s2"]
    assert [c["values"][0] for c in document["per_case_fits"]] == pytest.approx(
        [best_l1(["s1"]), best_l1(["s2"])], rel=1e-7)
    # ratios of A / L1^2 do not depend on L1: the model's ratios are A's at any L1
    np.testing.assert_allclose(document["ratios"]["best_model"],
                               [A[n] / A[n][0] for n in ("s1", "s2")], rtol=1e-12)


def test_the_result_type_refuses_arrays_of_the_wrong_shape(scenes):
    settings = StudySettings(starts=1, seed=0, samples=2, elements=None, n_jobs=1)
    study = run_study(scenes, "planar", (L1_FREE,), settings)
    shape = r"CalibrationStudy.ex has shape \(1, 4\), expected \(2, 4\)"
    with pytest.raises(ValueError, match=shape):
        dataclasses.replace(study, ex=study.ex[:1])
    with pytest.raises(ValueError, match="per_case has 1 fits, expected 2"):
        dataclasses.replace(study, per_case=study.per_case[:1])
    with pytest.raises(ValueError, match=r"FitResult.values has shape \(2,\), expected \(1,\)"):
        dataclasses.replace(study.fit_ex, values=np.ones(2))


def _floats(text: str) -> list[float]:
    return [float(x) for x in re.findall(r"[-+]?\d+\.?\d*(?:e[-+]?\d+)?", text)]


def _row(markdown: str, first: str) -> list[str]:
    """The cells of the first table row of ``markdown`` whose first cell is ``first``."""
    return next(cells for line in markdown.splitlines() if line.startswith("| ")
                for cells in [[c.strip() for c in line.strip("|").split("|")]]
                if cells[0] == first)


def test_summary_text_and_report_state_the_document(scenes):
    settings = StudySettings(starts=2, seed=0, samples=3, elements=None, n_jobs=1)
    study = run_study(scenes, "planar", (L1_FREE,), settings)
    doc = study_document(study)
    e = doc["errors_mean_abs_pct"]
    order = ("assumed_inputs_vs_Ex", "calibrated_to_Ex_in_sample", "cross_validated_vs_Ex",
             "paper_FE_vs_Ex")
    # each fit's own mean |error| is the comparison of that fit with its reference
    assert doc["fit_Ex"]["mean_abs_error_pct"] == pytest.approx(e["calibrated_to_Ex_in_sample"])
    assert doc["fit_FE"]["mean_abs_error_pct"] == pytest.approx(e["calibrated_to_FE_vs_FE"])
    first, fitted, inside = summary_text([study]).splitlines()
    # the text rounds each mean |error| to 0.1 %
    assert _floats(first.split(":", 2)[2]) == pytest.approx([round(e[k], 1) for k in order])
    [p] = doc["fit_Ex"]["parameters"]
    assert fitted == f"  fitted to Ex: L1 = {p['value']:.4g} m"
    u = doc["uncertainty_calibrated"]
    assert inside.endswith(f"{u['Ex_inside_count']} of {u['count']} modes")

    plots = {"planar": {k: f"{k}.png" for k in
                        ("frequencies", "cross_validation", "ratios", "intervals")}}
    report = report_markdown([study], plots, "flexlink calibrate s1.toml s2.toml")
    assert "Starts per fit: 2, seed 0" in report
    family = report.split("## Family: planar", 1)[1]
    assert _floats(family.split("\n\n", 2)[1])[:4] == pytest.approx(
        [round(e[k], 1) for k in order])
    name, assumed, value, se, bounds, _ = _row(family, "L1")
    assert _floats(value) == pytest.approx([p["value"]], rel=1e-3)  # 4 significant digits
    # the standard error of ln L1 is relative: in % of the fitted value
    assert se == f"±{100 * p['relative_se']:.3g} %"
    assert _floats(bounds) == pytest.approx([L1_FREE.low, L1_FREE.high])
    for key in ("uncertainty_nominal", "uncertainty_calibrated"):
        u = doc[key]
        assert (f"Ex inside the 95 % interval for {u['Ex_inside_count']} of {u['count']} modes"
                in family)
    cells = _row(family.split("inputs calibrated to Ex", 1)[1], "s1")
    lows, highs = u["first_order_low95_Hz"][0], u["first_order_high95_Hz"][0]
    assert _floats(cells[5]) == pytest.approx([lows[0], highs[0]], abs=0.051)  # 0.1 Hz shown

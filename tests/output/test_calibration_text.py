"""The calibration report as a reader gets it, from a hand-made study document (the form
``calibration_json.study_document`` gives; the report reads nothing else): the summary names
the family with the lowest cross-validated error, each failed evaluation is a row of its
table under named columns, the correlation of the fitted inputs is introduced and tabulated
to two decimals, and the plots label their axes (mode number against frequency in Hz).
Two cases, two modes, two fitted inputs: every number here is written by hand."""

from __future__ import annotations

import pytest

import flexlink.output.calibration.calibration_report as report
from flexlink.output.calibration.calibration_report import family_section, summary_lines

KEYS = ("assumed_inputs_vs_Ex", "calibrated_to_Ex_in_sample", "cross_validated_vs_Ex",
        "per_case_fit_in_sample", "calibrated_to_FE_vs_FE", "paper_FE_vs_Ex")
CASES = ["case1", "case2"]
EX = [[80.0, 200.0], [90.0, 210.0]]  # [Hz]
PLOTS = {name: f"{name}.png" for name in ("frequencies", "cross_validation", "ratios",
                                          "intervals")}
WHY = "forced failure: the held-out fit did not converge"


def _fit(correlation) -> dict:
    return {"parameters": [
                {"name": "E", "unit": "Pa", "low": 1e10, "high": 1e11, "value": 4e10,
                 "at_bound": False, "relative_se": 0.05},
                {"name": "Kt", "unit": "N/m", "low": 1e4, "high": 1e9, "value": 1e6,
                 "at_bound": False, "relative_se": 0.5}],
            "correlation": correlation, "start_costs": [0.01, 0.02], "evaluations": 40,
            "starts_converged": [True, True], "best_start": 0,
            "predicted_Hz": [[81.0, 198.0], [89.0, 212.0]],
            "errors_pct": [[1.25, -1.0], [-1.11, 0.95]], "mean_abs_error_pct": 1.08}


def _uncertainty() -> dict:
    return {"samples": 20, "seed": 1, "failed_samples": 0,
            "inputs": {"sd": {"vf": 0.02, "thickness": 2e-5}},
            "mean_Hz": [[80.5, 199.0], [89.5, 211.0]], "low95_Hz": [[75.0, 190.0], [84.0, 200.0]],
            "high95_Hz": [[86.0, 208.0], [95.0, 222.0]],
            "first_order_low95_Hz": [[75.5, 191.0], [84.5, 201.0]],
            "first_order_high95_Hz": [[85.5, 207.0], [94.5, 221.0]],
            "Ex_inside": [[True, True], [True, True]], "Ex_inside_count": 4, "count": 4,
            "ranked": [{"input": "E", "max_abs": 0.5}, {"input": "Kt", "max_abs": 0.1}]}


def study(family: str, cross_validated: float, failed: list[dict] = ()) -> dict:
    """A study document of ``family`` whose cross-validated mean |error| is ``cross_validated``
    [%] and whose cross-validation lists ``failed`` evaluations."""
    means = dict(zip(KEYS, (12.0, 1.1, cross_validated, 0.8, 0.5, 7.0)))
    if failed:
        means["cross_validated_vs_Ex"] = None
    return {
        "family": family, "cases": CASES,
        "free": [{"name": "E", "unit": "Pa", "low": 1e10, "high": 1e11, "nominal": 3e10},
                 {"name": "Kt", "unit": "N/m", "low": 1e4, "high": 1e9, "nominal": 1e6}],
        "Ex_Hz": EX, "paper_FE_Hz": [[85.0, 213.0], [95.0, 220.0]],
        "nominal_Hz": [[70.0, 180.0], [80.0, 190.0]],
        "nominal_errors_pct": [[-12.5, -10.0], [-11.1, -9.5]],
        "errors_mean_abs_pct": means,
        "errors_failed": {k: list(failed) if k == "cross_validated_vs_Ex" else [] for k in KEYS},
        "errors_count": dict.fromkeys(KEYS, 4),
        "fit_Ex": _fit([[1.0, -0.95], [-0.95, 1.0]]), "fit_FE": _fit(None),
        "cross_validation": {"predicted_Hz": [[82.0, 196.0], [88.0, 214.0]],
                             "errors_pct": [[2.5, -2.0], [-2.2, 1.9]],
                             "fold_fitted_mean_abs_pct": [1.0, 1.2],
                             "fold_predicted_mean_abs_pct": [2.25, 2.05]},
        "per_case_fits": [{"mean_abs_pct": 0.7}, {"mean_abs_pct": 0.9}],
        "ratios": {"measured": [[1.0, 2.5], [1.0, 2.33]], "nominal_model": [[1.0, 2.57],
                                                                            [1.0, 2.38]],
                   "best_model": [[1.0, 2.5], [1.0, 2.34]], "best_errors_pct": [[0.0], [0.4]],
                   "case_to_case_measured": [[1.0, 1.0], [1.125, 1.05]]},
        "uncertainty_nominal": _uncertainty(), "uncertainty_calibrated": _uncertainty(),
    }


def _table_rows(text: str, title: str) -> list[list[str]]:
    """The cells of the first Markdown table after the line ``title``."""
    lines = text.split(title + "\n", 1)[1].splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("| "))
    rows = []
    for line in lines[start:]:
        if not line.startswith("|"):
            break
        if not line.startswith("|---"):
            rows.append([c.strip() for c in line.strip().strip("|").split("|")])
    return rows


def _cells(table: str) -> list[list[str]]:
    return [[c.strip() for c in line.strip().strip("|").split("|")]
            for line in table.splitlines() if line.startswith("| ")]


def test_summary_names_the_family_with_the_lowest_cross_validated_error():
    studies = [study("planar", 9.4), study("woven", 3.2)]
    table, sentence = summary_lines(studies, "woven")
    header, *rows = _cells(table)
    assert header[:4] == ["family", "assumed inputs vs Ex", "calibrated to Ex (in sample)",
                          "cross-validated vs Ex"]
    assert [row[:4] for row in rows] == [["planar", "12.0", "1.1", "9.4"],
                                         ["woven", "12.0", "1.1", "3.2"]]
    assert sentence == ("\nBy the cross-validated error the **woven** family explains Table III "
                        "best (3.2 % mean |error| predicting a case it was not fitted to).")
    assert len(summary_lines(studies[:1], "planar")) == 1  # one family: nothing to compare


def test_each_failed_evaluation_is_a_row_under_named_columns():
    failed = [{"case": "case2", "mode": 2, "reason": WHY}]
    text = family_section(study("planar", 0.0, failed), PLOTS)
    assert "\n1 case/mode evaluations failed;" in text
    header, *rows = _table_rows(text, "### Failed evaluations")
    assert header == ["comparison", "case", "mode", "why"]
    assert rows == [["cross validated vs Ex", "case2", "2", WHY]]
    assert "cross-validated n/a (1 of 4 failed) %" in text  # no mean over the others
    assert "### Failed evaluations" not in family_section(study("planar", 2.0), PLOTS)


def test_the_correlation_of_the_fitted_inputs_is_introduced_and_tabulated():
    text = family_section(study("planar", 2.0), PLOTS)
    title = ("Correlation of the fitted ln inputs (Ex fit); |r| near 1 = the data cannot tell "
             "them apart:")
    assert f"\n{title}\n" in text
    assert _table_rows(text, title) == [["", "E", "Kt"], ["E", "+1.00", "-0.95"],
                                        ["Kt", "-0.95", "+1.00"]]
    one_input = study("planar", 2.0)
    one_input["fit_Ex"]["correlation"] = None  # one fitted input: no correlation to show
    assert "Correlation of the fitted" not in family_section(one_input, PLOTS)


@pytest.mark.parametrize("name", ["frequencies", "intervals", "ratios", "cross_validation"])
def test_each_plot_labels_its_axes(monkeypatch, name):
    drawn = []
    monkeypatch.setattr(report, "_png", lambda fig: drawn.append(fig) or b"")
    report.PLOTS[name](study("planar", 2.0))
    [fig] = drawn
    y_label = {"frequencies": "Hz", "intervals": "Hz", "ratios": "f_k / f_1",
               "cross_validation": "mean |error| vs Ex [%]"}[name]
    axes = fig.axes if name == "cross_validation" else fig.axes[:len(CASES)]
    for ax, case in zip(axes, CASES):
        assert ax.get_ylabel() == y_label
        if name == "cross_validation":  # one bar pair per case, named on the axis
            assert [t.get_text() for t in ax.get_xticklabels()] == CASES
        else:  # one panel per case, its modes along x
            assert ax.get_xlabel() == "mode" and ax.get_title() == f"{case} (planar)"
    import matplotlib.pyplot as plt
    plt.close(fig)

"""The JSON document of the calibration study (``studies.calibration.calibration``): every field
name of ``calibrate.json`` and ``study-<family>.json`` is declared here, once. Non-finite
numbers become null (JSON has neither NaN nor infinity)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexlink.studies.calibration.fit import FitResult, case_label, mean_abs
from flexlink.studies.calibration.calibration import CalibrationStudy, UncertaintySummary, best_family

NO_MODE = ("no elastic mode of this number (the model found fewer, or the reference is "
           "missing)")


def json_ready(value):
    """``value`` with arrays as lists and NaN, inf as None, recursively."""
    if isinstance(value, dict):
        return {k: json_ready(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_ready(v) for v in value]
    if isinstance(value, np.ndarray):
        return json_ready(value.tolist())
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    return value


def failures(errors, labels, reasons=()) -> list[dict]:
    """Every case and mode (1-based) whose error is NaN, with why when known: the error the
    case raised, else that the model found fewer elastic modes than the table has;
    ``reasons``: (case index, message) pairs."""
    why = dict(reasons)
    e = np.asarray(errors, dtype=float)
    return [{"case": labels[i], "mode": k + 1, "reason": why.get(i, NO_MODE)}
            for i, k in zip(*np.nonzero(np.isnan(e)))]


def fit_document(fit: FitResult) -> dict:
    """One least-squares fit: its inputs with standard errors, costs, predictions, errors."""
    se = fit.rel_se if fit.rel_se is not None else [None] * len(fit.values)
    return json_ready({
        "scenes": list(fit.problem.scenes), "reference": fit.problem.reference,
        "target": fit.problem.target,
        "parameters": [{"name": p.name, "unit": p.unit, "low": p.low, "high": p.high,
                        "value": float(v), "at_bound": bool(b),
                        "relative_se": None if fit.rel_se is None else float(s)}
                       for p, v, b, s in zip(fit.problem.parameters, fit.values, fit.at_bound, se)],
        "correlation": fit.correlation, "cost": fit.cost,
        "start_costs": fit.start_costs, "evaluations": fit.evaluations,
        "starts_converged": list(fit.converged), "best_start": fit.best,
        "predicted_Hz": fit.predicted, "reference_Hz": fit.reference,
        "errors_pct": fit.errors_pct, "mean_abs_error_pct": fit.mean_abs_error_pct,
        "failed": failures(fit.errors_pct, [case_label(p) for p in fit.problem.scenes],
                           fit.reasons),
    })


def _uncertainty(u: UncertaintySummary, settings) -> dict:
    mc, sens, inside = u.monte_carlo, u.sensitivities, u.inside
    return {
        "samples": settings.samples, "seed": settings.seed, "failed_samples": u.failed_samples,
        "inputs": {"nominal": u.inputs.nominal, "sd": u.inputs.sd},
        "mean_Hz": mc.mean, "low95_Hz": mc.low, "high95_Hz": mc.high,
        "Ex_inside": inside, "Ex_inside_count": int(inside.sum()), "count": int(inside.size),
        "first_order_sd_ln_f": sens.sd_ln_f,
        "first_order_low95_Hz": u.first_order_low, "first_order_high95_Hz": u.first_order_high,
        "sensitivities": {n: sens.values[n] for n in sens.names},
        "ranked": [{"input": n, "max_abs": v} for n, v in sens.ranked()],
    }


def study_document(s: CalibrationStudy) -> dict:
    """One family's study, as ``study-<family>.json`` holds it and the report reads it."""
    labels = list(s.cases)
    cv = s.cross_validation
    return json_ready({
        "family": s.family,
        "cases": labels, "files": list(s.files),
        "settings": dataclasses.asdict(s.settings),
        "free": [{"name": p.name, "unit": p.unit, "low": p.low, "high": p.high, "nominal": v}
                 for p, v in zip(s.free, s.free_nominal)],
        "Ex_Hz": s.ex, "paper_FE_Hz": s.paper_fe,
        "nominal_Hz": s.nominal, "nominal_errors_pct": s.errors["assumed_inputs_vs_Ex"].errors_pct,
        "errors_mean_abs_pct": {k: e.mean_abs_pct for k, e in s.errors.items()},
        "errors_failed": {k: failures(e.errors_pct, labels, e.reasons)
                          for k, e in s.errors.items()},
        "errors_count": {k: int(np.size(e.errors_pct)) for k, e in s.errors.items()},
        "fit_Ex": fit_document(s.fit_ex), "fit_FE": fit_document(s.fit_fe),
        "cross_validation": {
            "held_out": labels,
            "predicted_Hz": cv.predicted, "errors_pct": cv.errors_pct,
            "fold_fitted_mean_abs_pct": [f.mean_abs_error_pct for f in cv.folds],
            "fold_predicted_mean_abs_pct": [mean_abs(e) for e in cv.errors_pct],
            "fold_values": [f.values for f in cv.folds],
        },
        "per_case_fits": [{"case": label, "values": f.values,
                           "predicted_Hz": f.predicted[0], "errors_pct": f.errors_pct[0],
                           "mean_abs_pct": f.mean_abs_error_pct}
                          for label, f in zip(labels, s.per_case)],
        "ratios": {
            "measured": s.ratios.measured, "nominal_model": s.ratios.nominal_model,
            "best_model": s.ratios.best_model, "best_errors_pct": s.ratios.best_errors_pct,
            "best_values": [f.values for f in s.ratios.fits],
            "case_to_case_measured": s.ratios.case_to_case_measured,
        },
        "uncertainty_nominal": _uncertainty(s.uncertainty_nominal, s.settings),
        "uncertainty_calibrated": _uncertainty(s.uncertainty_calibrated, s.settings),
    })


def calibrate_document(studies: list[CalibrationStudy], written) -> dict:
    """What ``flexlink calibrate --json`` prints and writes as calibrate.json; ``written``: the
    files of the run, calibrate.json included."""
    document = {"command": "calibrate", "studies": [study_document(s) for s in studies],
                "files": [str(p) for p in written]}
    if len(studies) > 1:
        best = best_family(studies)
        document["best_family_by_cross_validation"] = best and best.family
    return document

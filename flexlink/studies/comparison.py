"""The whole honest comparison of one model family with a reference table, as one JSON-ready
document: assumed inputs, calibration against Ex and against the paper's FE, leave-one-case-out
cross-validation, per-case fits, the mode-ratio (proportionality) test, Monte Carlo intervals
and first-order sensitivities. ``calibration_report`` turns a list of these into Markdown."""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink import logbook
from flexlink.errors import InputError
from flexlink.meshes import FIT_ELEMENTS
from flexlink.studies.calibration import (DEFAULT_FREE, FreeParameter, Problem, case_label,
                                          cross_validation, failures, fit_many, json_ready,
                                          leave_one_out_problems, mean_abs, measured, parse_free,
                                          predict_with_failures, ratios, single_case_problems)
from flexlink.studies.uncertainty import monte_carlo, scene_inputs, sensitivities
from flexlink.units import percent_error

# inputs with no effect on a family are left out of its default free set (they could not be
# identified: zero Jacobian column)
NOT_IN_FAMILY = {"planar": {"Ktilt"}, "out-of-plane": {"Kr", "drive"}, "3d": set()}
DEFAULT_TILT = "Ktilt=1e-2 N*m/rad:1e5 N*m/rad"


def default_free(family: str) -> tuple[FreeParameter, ...]:
    specs = [parse_free(s) for s in (*DEFAULT_FREE, DEFAULT_TILT)]
    return tuple(p for p in specs if p.name not in NOT_IN_FAMILY[family])


@dataclasses.dataclass(frozen=True)
class StudySettings:
    starts: int = 8
    seed: int = 0
    samples: int = 200
    vf_sd: float = 0.05
    thickness_sd: float = 0.15e-3  # [m]
    elements: int | None = FIT_ELEMENTS
    n_jobs: int = -1
    progress: bool = False


def _pct(predicted, reference):
    return percent_error(np.asarray(predicted), np.asarray(reference))


def _uncertainty(paths, overrides, s: StudySettings, reference):
    inputs = scene_inputs(paths[0], overrides, s.vf_sd, s.thickness_sd)
    mc = monte_carlo(paths, overrides, inputs, s.samples, s.seed, elements=s.elements,
                     n_jobs=s.n_jobs, progress=s.progress)
    sens = sensitivities(paths, overrides, inputs, elements=s.elements, n_jobs=s.n_jobs,
                         progress=s.progress)
    inside = mc.contains(reference)
    return {
        "samples": s.samples, "seed": s.seed, "failed_samples": int(np.isnan(mc.samples).any(axis=(1, 2)).sum()),
        "inputs": {"nominal": inputs.nominal, "sd": inputs.sd},
        "mean_Hz": mc.mean, "low95_Hz": mc.low, "high95_Hz": mc.high,
        "Ex_inside": inside, "Ex_inside_count": int(inside.sum()), "count": int(inside.size),
        "first_order_sd_ln_f": sens.sd_ln_f,
        "first_order_low95_Hz": mc.mean * np.exp(-1.96 * sens.sd_ln_f),
        "first_order_high95_Hz": mc.mean * np.exp(1.96 * sens.sd_ln_f),
        "sensitivities": {n: sens.values[n] for n in sens.names},
        "ranked": [{"input": n, "max_abs": v} for n, v in sens.ranked()],
    }


def run_study(paths, family: str, free: tuple[FreeParameter, ...] | None,
              settings: StudySettings) -> dict:
    """Everything the report needs for one family (see the module docstring). The model's
    warnings over the study's thousands of evaluations are summarised in one line at its end.
    Needs two scenes or more: it cross-validates by leaving each one out."""
    with logbook.quiet(f"the {family} calibration study"):
        return _study(tuple(str(p) for p in paths), family, free, settings)


def _errors(named: dict, labels: list[str]) -> dict:
    """{name: (errors [%], {case index: reason})} -> the mean |error| per name (None if any case
    or mode failed: ``calibration.mean_abs``) and the failures per name."""
    return {"errors_mean_abs_pct": {k: mean_abs(e) for k, (e, _) in named.items()},
            "errors_failed": {k: failures(e, labels, why) for k, (e, why) in named.items()},
            "errors_count": {k: int(np.size(e)) for k, (e, _) in named.items()}}


def _study(paths: tuple[str, ...], family: str, free, s: StudySettings) -> dict:
    free = free or default_free(family)
    base = Problem(scenes=paths, parameters=free, reference="Ex", elements=s.elements,
                   fixed=(("model.family", family),))
    fe = dataclasses.replace(base, reference="FE")
    ex, fe_ref = measured(base), measured(fe)  # refuses scenes it cannot fit, before any fit
    if len(paths) < 2:
        raise InputError(f"the calibration study needs at least two scenes (it cross-validates "
                         f"leaving one out), got {len(paths)}", field="SCENES",
                         expected="two or more scene files, or a folder of them")
    problems = ([base, fe] + leave_one_out_problems(base) + single_case_problems(base, "frequencies")
                + single_case_problems(base, "ratios"))
    fits = fit_many(problems, s.starts, s.seed, s.n_jobs, s.progress)
    n = len(paths)
    labels = [case_label(p) for p in paths]
    ex_fit, fe_fit = fits[0], fits[1]
    cv = cross_validation(base, fits[2:2 + n])
    per_case, ratio_fits = fits[2 + n:2 + 2 * n], fits[2 + 2 * n:]

    nominal, nominal_why = predict_with_failures(base)
    ratio_best = np.array([f.predicted[0] / f.predicted[0, 0] for f in ratio_fits])
    calibrated = base.overrides(ex_fit.values)
    errors = _errors({
        "assumed_inputs_vs_Ex": (_pct(nominal, ex), nominal_why),
        "calibrated_to_Ex_in_sample": (ex_fit.errors_pct, dict(ex_fit.reasons)),
        "cross_validated_vs_Ex": (cv.errors_pct, dict(cv.reasons)),
        "calibrated_to_FE_vs_FE": (fe_fit.errors_pct, dict(fe_fit.reasons)),
        "calibrated_to_FE_vs_Ex": (_pct(fe_fit.predicted, ex), dict(fe_fit.reasons)),
        "paper_FE_vs_Ex": (_pct(fe_ref, ex), {}),
        "per_case_fit_in_sample": (np.array([f.errors_pct[0] for f in per_case]),
                                   {i: why for i, f in enumerate(per_case) for _, why in f.reasons}),
    }, labels)
    return json_ready({
        "family": family,
        "cases": labels, "files": list(paths),
        "settings": dataclasses.asdict(s),
        "free": [{"name": p.name, "unit": p.unit, "low": p.low, "high": p.high,
                  "nominal": p.nominal(base.scene(paths[0]))} for p in free],
        "Ex_Hz": ex, "paper_FE_Hz": fe_ref,
        "nominal_Hz": nominal, "nominal_errors_pct": _pct(nominal, ex),
        **errors,
        "fit_Ex": ex_fit.as_dict(), "fit_FE": fe_fit.as_dict(),
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
                          for label, f in zip(labels, per_case)],
        "ratios": {
            "measured": ratios(ex), "nominal_model": ratios(nominal), "best_model": ratio_best,
            "best_errors_pct": _pct(ratio_best[:, 1:], ratios(ex)[:, 1:]),
            "best_values": [f.values for f in ratio_fits],
            "case_to_case_measured": ex / ex[:1],
        },
        "uncertainty_nominal": _uncertainty(paths, dict(base.fixed), s, ex),
        "uncertainty_calibrated": _uncertainty(paths, calibrated, s, ex),
    })

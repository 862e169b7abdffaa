"""The calibration study of one model family against a reference table, as one frozen result:
the assumed inputs, calibration against Ex and against the paper's FE, leave-one-case-out
cross-validation, per-case fits, the mode-ratio (proportionality) test, and Monte Carlo
intervals with first-order sensitivities at the assumed and the calibrated inputs. The fitting
machinery is ``studies.calibration.fit``; ``output.calibration.calibration`` and
``output.calibration.calibration_report`` render a ``CalibrationStudy``."""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink import logbook
from flexlink.analysis.families import scene_family
from flexlink.errors import InputError
from flexlink.fe.motions import ModelFamily
from flexlink.meshes import FIT_ELEMENTS
from flexlink.scene import load_scene
from flexlink.studies.array_shapes import check_shape
from flexlink.studies.calibration.fit import (DEFAULT_FREE, CrossValidation, FitResult, FitTarget,
                                          FreeParameter,
                                          Problem, case_label, cross_validation, fit_many,
                                          leave_one_out_problems, mean_abs, measured, parse_free,
                                          predict_with_failures, ratios, single_case_problems)
from flexlink.units import percent_error
from flexlink.studies.calibration.uncertainty import (Inputs, MonteCarlo, Sensitivities, monte_carlo,
                                          scene_inputs, sensitivities)

# inputs with no effect on a family are left out of its default free set (they could not be
# identified: zero Jacobian column)
NOT_IN_FAMILY = {ModelFamily.PLANAR: {"Ktilt"}, ModelFamily.OUT_OF_PLANE: {"Kr", "drive"},
                 ModelFamily.THREE_D: set()}
DEFAULT_TILT = "Ktilt=1e-2 N*m/rad:1e5 N*m/rad"
# the comparisons of a study, each a table of errors [%] per case and mode
COMPARISONS = ("assumed_inputs_vs_Ex", "calibrated_to_Ex_in_sample", "cross_validated_vs_Ex",
               "calibrated_to_FE_vs_FE", "calibrated_to_FE_vs_Ex", "paper_FE_vs_Ex",
               "per_case_fit_in_sample")


def default_free(family: ModelFamily) -> tuple[FreeParameter, ...]:
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
    show_progress: bool = False


@dataclasses.dataclass(frozen=True)
class ErrorSummary:
    """One comparison's errors [%] per case and mode (NaN where a case or mode failed) and why
    cases failed: (case index, message) pairs."""

    errors_pct: np.ndarray
    reasons: tuple[tuple[int, str], ...] = ()

    def __post_init__(self):
        check_shape("ErrorSummary", "errors_pct", self.errors_pct, (None, None))

    @property
    def mean_abs_pct(self) -> float | None:
        """The mean |error| [%], None if any case or mode failed (``calibration.mean_abs``)."""
        return mean_abs(self.errors_pct)


@dataclasses.dataclass(frozen=True)
class UncertaintySummary:
    """Monte Carlo intervals and first-order sensitivities at one set of inputs, compared with
    the reference ``reference`` [Hz] (cases, n_modes)."""

    inputs: Inputs
    monte_carlo: MonteCarlo
    sensitivities: Sensitivities
    reference: np.ndarray

    def __post_init__(self):
        n = np.shape(self.reference)
        check_shape("UncertaintySummary", "reference", self.reference, (None, None))
        check_shape("UncertaintySummary", "monte_carlo.samples", self.monte_carlo.samples,
                     (None, *n))
        check_shape("UncertaintySummary", "sensitivities.sd_ln_f", self.sensitivities.sd_ln_f, n)

    @property
    def inside(self) -> np.ndarray:
        """Whether each reference value lies in its 95 % Monte Carlo interval (cases, n_modes)."""
        return self.monte_carlo.contains(self.reference)

    @property
    def failed_samples(self) -> int:
        return int(np.isnan(self.monte_carlo.samples).any(axis=(1, 2)).sum())

    @property
    def first_order_low(self) -> np.ndarray:
        """The first-order 95 % interval's low end [Hz]: the Monte Carlo mean / e^(1.96 sd)."""
        return self.monte_carlo.mean * np.exp(-1.96 * self.sensitivities.sd_ln_f)

    @property
    def first_order_high(self) -> np.ndarray:
        return self.monte_carlo.mean * np.exp(1.96 * self.sensitivities.sd_ln_f)


@dataclasses.dataclass(frozen=True)
class RatioTest:
    """The mode ratios f_k / f_1 per case (cases, n_modes): measured, of the model at the assumed
    inputs, and of the best fit of each case's ratios alone (``fits``, one per case)."""

    measured: np.ndarray
    nominal_model: np.ndarray
    best_model: np.ndarray
    fits: tuple[FitResult, ...]
    case_to_case_measured: np.ndarray  # each case's Ex over the first case's, per mode

    def __post_init__(self):
        n = np.shape(self.measured)
        check_shape("RatioTest", "measured", self.measured, (None, None))
        for name in ("nominal_model", "best_model", "case_to_case_measured"):
            check_shape("RatioTest", name, getattr(self, name), n)
        if len(self.fits) != n[0]:
            raise ValueError(f"RatioTest.fits has {len(self.fits)} fits, expected {n[0]} (one "
                             "per case)")

    @property
    def best_errors_pct(self) -> np.ndarray:
        """The best ratios' errors [%] for modes 2..n (cases, n_modes - 1)."""
        return 100.0 * (self.best_model[:, 1:] / self.measured[:, 1:] - 1.0)


@dataclasses.dataclass(frozen=True)
class CalibrationStudy:
    """Everything the calibration report says about one model family (module docstring).

    Frequencies [Hz] and errors [%] are arrays (cases, n_modes); ``free_nominal`` [SI] is each
    free input's assumed value in the first scene (inf for a rigid one)."""

    family: ModelFamily
    files: tuple[str, ...]
    settings: StudySettings
    free: tuple[FreeParameter, ...]
    free_nominal: np.ndarray
    ex: np.ndarray
    paper_fe: np.ndarray
    nominal: np.ndarray
    errors: dict[str, ErrorSummary]
    fit_ex: FitResult
    fit_fe: FitResult
    cross_validation: CrossValidation
    per_case: tuple[FitResult, ...]
    ratios: RatioTest
    uncertainty_nominal: UncertaintySummary
    uncertainty_calibrated: UncertaintySummary

    def __post_init__(self):
        n = (len(self.files), np.shape(self.ex)[-1] if np.ndim(self.ex) else 0)
        check_shape("CalibrationStudy", "free_nominal", self.free_nominal, (len(self.free),))
        for name in ("ex", "paper_fe", "nominal"):
            check_shape("CalibrationStudy", name, getattr(self, name), n)
        for name, fit in (("fit_ex", self.fit_ex), ("fit_fe", self.fit_fe),
                          ("cross_validation", self.cross_validation)):
            check_shape("CalibrationStudy", f"{name}.predicted", fit.predicted, n)
        if set(self.errors) != set(COMPARISONS):
            raise ValueError(f"CalibrationStudy.errors has {sorted(self.errors)}, expected "
                             f"{sorted(COMPARISONS)}")
        for name, summary in self.errors.items():
            check_shape("CalibrationStudy", f"errors[{name!r}].errors_pct", summary.errors_pct, n)
        if len(self.per_case) != n[0]:
            raise ValueError(f"CalibrationStudy.per_case has {len(self.per_case)} fits, expected "
                             f"{n[0]} (one per case)")
        check_shape("CalibrationStudy", "ratios.measured", self.ratios.measured, n)

    @property
    def cases(self) -> tuple[str, ...]:
        """The cases' labels (scene file stems)."""
        return tuple(case_label(p) for p in self.files)


def study_families(names, files) -> list[ModelFamily]:
    """The model families ``names`` once each, in order; None stands for the first scene
    file's own [model] family."""
    chosen = []
    for name in names:
        name = scene_family(load_scene(files[0])) if name is None else name
        if name not in chosen:
            chosen.append(name)
    return chosen


def best_family(studies) -> CalibrationStudy | None:
    """The study with the lowest cross-validated mean |error| vs Ex, among those whose every
    case and mode was evaluated (None if none was)."""
    complete = [s for s in studies if s.errors["cross_validated_vs_Ex"].mean_abs_pct is not None]
    return min(complete, key=lambda s: s.errors["cross_validated_vs_Ex"].mean_abs_pct,
               default=None)


def _pct(predicted, reference):
    return percent_error(np.asarray(predicted), np.asarray(reference))


def _uncertainty(paths, overrides, s: StudySettings, reference) -> UncertaintySummary:
    inputs = scene_inputs(paths[0], overrides, s.vf_sd, s.thickness_sd)
    mc = monte_carlo(paths, overrides, inputs, s.samples, s.seed, elements=s.elements,
                     n_jobs=s.n_jobs, show_progress=s.show_progress)
    sens = sensitivities(paths, overrides, inputs, elements=s.elements, n_jobs=s.n_jobs,
                         show_progress=s.show_progress)
    return UncertaintySummary(inputs=inputs, monte_carlo=mc, sensitivities=sens,
                              reference=reference)


def run_study(paths, family: ModelFamily, free: tuple[FreeParameter, ...] | None,
              settings: StudySettings) -> CalibrationStudy:
    """Everything the report needs for one family (see the module docstring). The model's
    warnings over the study's thousands of evaluations are summarised in one line at its end.
    Needs two scenes or more: it cross-validates by leaving each one out."""
    with logbook.quiet(f"the {family} calibration study"):
        return _study(tuple(str(p) for p in paths), family, free, settings)


def _study(paths: tuple[str, ...], family: ModelFamily, free, s: StudySettings) -> CalibrationStudy:
    free = free or default_free(family)
    base = Problem(scenes=paths, parameters=free, reference="Ex", elements=s.elements,
                   fixed=(("model.family", family),))
    fe = dataclasses.replace(base, reference="FE")
    # first, as they refuse a general scene or a missing reference column
    ex, fe_ref = measured(base), measured(fe)
    if len(paths) < 2:
        raise InputError(f"the calibration study needs at least two scenes (it cross-validates "
                         f"leaving one out), got {len(paths)}", field="SCENES",
                         expected="two or more scene files, or a folder of them")
    groups = {"Ex": [base], "FE": [fe], "folds": leave_one_out_problems(base),
              "per_case": single_case_problems(base, FitTarget.FREQUENCIES),
              "ratios": single_case_problems(base, FitTarget.RATIOS)}
    fitted = iter(fit_many([p for group in groups.values() for p in group], s.starts, s.seed,
                           s.n_jobs, s.show_progress))  # one pool for every fit
    fits = {name: [next(fitted) for _ in group] for name, group in groups.items()}
    [ex_fit], [fe_fit], per_case = fits["Ex"], fits["FE"], fits["per_case"]
    cv = cross_validation(base, fits["folds"])

    nominal, nominal_why = predict_with_failures(base)
    ratio_best = np.array([f.predicted[0] / f.predicted[0, 0] for f in fits["ratios"]])
    errors = {
        "assumed_inputs_vs_Ex": ErrorSummary(_pct(nominal, ex), tuple(nominal_why.items())),
        "calibrated_to_Ex_in_sample": ErrorSummary(ex_fit.errors_pct, ex_fit.reasons),
        "cross_validated_vs_Ex": ErrorSummary(cv.errors_pct, cv.reasons),
        "calibrated_to_FE_vs_FE": ErrorSummary(fe_fit.errors_pct, fe_fit.reasons),
        "calibrated_to_FE_vs_Ex": ErrorSummary(_pct(fe_fit.predicted, ex), fe_fit.reasons),
        "paper_FE_vs_Ex": ErrorSummary(_pct(fe_ref, ex)),
        "per_case_fit_in_sample": ErrorSummary(
            np.array([f.errors_pct[0] for f in per_case]),
            tuple((i, why) for i, f in enumerate(per_case) for _, why in f.reasons)),
    }
    return CalibrationStudy(
        family=family, files=paths, settings=s, free=free,
        free_nominal=np.array([p.nominal(base.scene(paths[0])) for p in free], dtype=float),
        ex=ex, paper_fe=fe_ref, nominal=nominal, errors=errors, fit_ex=ex_fit, fit_fe=fe_fit,
        cross_validation=cv, per_case=tuple(per_case),
        ratios=RatioTest(measured=ratios(ex), nominal_model=ratios(nominal),
                         best_model=ratio_best, fits=tuple(fits["ratios"]),
                         case_to_case_measured=ex / ex[:1]),
        uncertainty_nominal=_uncertainty(paths, dict(base.fixed), s, ex),
        uncertainty_calibrated=_uncertainty(paths, base.overrides(ex_fit.values), s, ex))

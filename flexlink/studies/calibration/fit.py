"""Model updating: fit assumed scene inputs to a reference table by least squares.

The user names the free inputs, each with physical bounds; one parameter set is shared by all
cases of a problem. Every free input is positive and is fitted as x = ln p, so the steps are
relative, inputs spanning decades (stiffnesses, masses) are handled like lengths, and a
standard error of x is a relative standard error of p. The residuals are
    "frequencies": ln f_model - ln f_ref, per case and mode (mode order pairing only), or
    "ratios":      ln(f_k / f_1)_model - ln(f_k / f_1)_ref, k = 2..n (scale-free shape test).
The Jacobian d r / d ln p comes from each mode's eigenvalue sensitivity (``studies.calibration.jacobian``),
not from a full evaluation per input. Standard errors come from it at the optimum,
cov = s^2 (J^T J)^+, with s^2 = sum r^2 / (m - p); they mean little for inputs sitting on a
bound or when m <= p. A start that stops at the evaluation limit is not a converged optimum;
the fit records which did (``FitResult.converged``) and the report says so.
"""

from __future__ import annotations

import dataclasses
import enum
import logging
import math
from pathlib import Path

import numpy as np

from flexlink.choices import parse_choice
from flexlink.errors import FlexlinkError, InputError
from flexlink.analysis.families import elastic_modes
from flexlink.studies.array_shapes import check_shape
from flexlink.studies.calibration.jacobian import case_modes, log_frequency_sensitivities
from flexlink.parallel import run_tasks
from flexlink.scene import Scene, load_scene
from flexlink.scene.contract import SceneKind
from flexlink.units import parse_range, percent_error

log = logging.getLogger(__name__)

JOINTS = ("O2", "A", "B", "O4")
MISSING_MODE_PENALTY = 5.0  # ln-residual used when the model has fewer modes than the table


def _nominal_section(index):
    def get(scene: Scene):
        s = scene.sections["crank"]
        return s.strip[index]
    return get


def _nominal_drive(scene: Scene):
    return scene.drive.stiffness if scene.drive else 0.0


def _nominal_tilt(scene: Scene):
    return next(iter(scene.options.tilt.values()), float("inf"))


# name -> (scene fields it sets, dimension, SI unit written into overrides, nominal(scene))
KNOWN = {
    "L1": (("linkage.ground",), "length", "m", lambda s: s.four_bar.ground),
    "width": (("section.width",), "length", "m", _nominal_section(0)),
    "thickness": (("section.thickness",), "length", "m", _nominal_section(1)),
    "Kt": (("joints.Kt",), "translational stiffness", "N/m", lambda s: s.joints[0].Kt),
    "Kr": (("joints.Kr",), "rotational stiffness", "N*m/rad", lambda s: s.joints[0].Kr),
    "drive": (("drive.stiffness",), "rotational stiffness", "N*m/rad", _nominal_drive),
    "joint_mass": (tuple(f"joints.{j}.mass" for j in JOINTS), "mass", "kg",
                   lambda s: s.joints[0].mass),
    "Ktilt": (("joints.Ktilt",), "rotational stiffness", "N*m/rad", _nominal_tilt),
}

DEFAULT_FREE = ("L1=0.1 m:1 m", "width=5 mm:60 mm", "thickness=0.5 mm:6 mm",
                "Kt=1e4 N/m:1e10 N/m", "Kr=1e-3 N*m/rad:1e4 N*m/rad",
                "drive=0.1 N*m/rad:1e6 N*m/rad", "joint_mass=1e-4 kg:0.2 kg")


@dataclasses.dataclass(frozen=True)
class FreeParameter:
    """A free scene input with bounds [low, high] (SI, both > 0); fitted as ln p."""

    name: str
    low: float
    high: float

    def __post_init__(self):
        if self.name not in KNOWN:
            raise InputError(f"unknown free input {self.name!r}", source="command line",
                             field="--free", expected=f"one of {sorted(KNOWN)}")
        if not (0 < self.low < self.high < math.inf):
            raise InputError(f"bounds must satisfy 0 < low < high < inf, got {self.low!r}, "
                             f"{self.high!r}", source="command line", field=f"--free {self.name}")

    @property
    def unit(self) -> str:
        return KNOWN[self.name][2]

    def overrides(self, value: float) -> dict[str, str]:
        return {field: f"{value!r} {self.unit}" for field in KNOWN[self.name][0]}

    def nominal(self, scene: Scene) -> float:
        return float(KNOWN[self.name][3](scene))


def parse_free(spec: str) -> FreeParameter:
    """``"NAME=LOW:HIGH"`` with units, e.g. ``"L1=100 mm:1 m"``, ``"Kt=1e4 N/m:1e9 N/m"``."""
    name, sep, bounds = spec.partition("=")
    name = name.strip()
    if not (sep and ":" in bounds) or name not in KNOWN:
        raise InputError(f"cannot read {spec!r}", source="command line", field="--free",
                         expected=f"NAME=LOW:HIGH with units, NAME one of {sorted(KNOWN)}, "
                                  "e.g. 'L1=100 mm:1 m'")
    low, high = parse_range(bounds, KNOWN[name][1], source="command line",
                            field=f"--free {name}")
    return FreeParameter(name, low, high)


class FitTarget(enum.StrEnum):
    """The residual a fit minimises: errors of the frequencies, or of their ratios to the first."""

    FREQUENCIES = "frequencies"
    RATIOS = "ratios"


@dataclasses.dataclass(frozen=True)
class Problem:
    """What to fit: scene files, free inputs, the reference column, the residual kind.

    ``fixed``: extra (field, value) overrides applied to every evaluation (e.g. the family)."""

    scenes: tuple[str, ...]
    parameters: tuple[FreeParameter, ...]
    reference: str = "Ex"
    target: FitTarget = FitTarget.FREQUENCIES
    n_modes: int = 4
    elements: int | None = None
    fixed: tuple[tuple[str, str], ...] = ()

    def __post_init__(self):
        object.__setattr__(self, "target", parse_choice(FitTarget, self.target, "target"))

    @property
    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return (np.log([p.low for p in self.parameters]), np.log([p.high for p in self.parameters]))

    def overrides(self, values) -> dict[str, str]:
        out = dict(self.fixed)
        for p, v in zip(self.parameters, values):
            out.update(p.overrides(float(v)))
        return out

    def scene(self, path, values=None) -> Scene:
        over = dict(self.fixed) if values is None else self.overrides(values)
        return load_scene(path, overrides=over)


def predict_with_failures(problem: Problem, values=None, scenes=None) -> tuple[np.ndarray, dict]:
    """``predict``, and why rows failed: {case index: the error's message}."""
    scenes = scenes or problem.scenes
    out = np.full((len(scenes), problem.n_modes), np.nan)
    reasons = {}
    for i, path in enumerate(scenes):
        try:
            out[i] = elastic_modes(problem.scene(path, values), problem.n_modes, problem.elements)[0]
        except FlexlinkError as exc:  # e.g. a bound combination the solver refuses
            log.info("%s at %s: %s", path, values, exc)
            reasons[i] = str(exc)
    return out, reasons


def predict(problem: Problem, values=None, scenes=None) -> np.ndarray:
    """Frequencies [Hz], shape (cases, n_modes), at ``values`` of the free inputs (None: the
    scenes' own assumed inputs). NaN where the model has fewer modes or fails its checks."""
    return predict_with_failures(problem, values, scenes)[0]


def mean_abs(errors) -> float | None:
    """Mean |error| over every case and mode, or None (reported as "n/a") if any failed.

    Not the mean of the others: failures are not random, they come where the model or its
    inputs go wrong, i.e. where the error would be largest, so the survivors' mean is biased
    low; and it would sit in one table with means over all cases of other fits and families,
    which is then not like with like. The failed cases and modes are listed beside it."""
    e = np.abs(np.asarray(errors, dtype=float))
    return None if np.isnan(e).any() else float(e.mean())


def measured(problem: Problem, scenes=None) -> np.ndarray:
    """The reference column, shape (cases, n_modes)."""
    rows = []
    for path in scenes or problem.scenes:
        scene = load_scene(path)
        if scene.kind is not SceneKind.FOUR_BAR:  # KNOWN's inputs (L1, the crank's section, O2..O4) are its
            raise InputError("calibration fits the inputs of four-bar scenes (L1, section, "
                             "joints O2, A, B, O4); this is a general scene", source=str(path),
                             field="linkage.type", expected="a four-bar scene")
        columns = scene.reference.columns if scene.reference else {}
        values = columns.get(problem.reference)
        if values is None or len(values) < problem.n_modes:
            raise InputError(f"needs {problem.n_modes} values in reference.{problem.reference}_Hz",
                             source=str(path), field=f"reference.{problem.reference}_Hz")
        rows.append(values[:problem.n_modes])
    return np.asarray(rows, dtype=float)


def log_residuals(problem: Problem, predicted: np.ndarray, reference: np.ndarray) -> np.ndarray:
    if problem.target is FitTarget.RATIOS:
        r = np.log(predicted[:, 1:] / predicted[:, :1]) - np.log(reference[:, 1:] / reference[:, :1])
    else:
        r = np.log(predicted) - np.log(reference)
    return np.nan_to_num(r, nan=MISSING_MODE_PENALTY).ravel()


class _Residuals:
    """The residuals of ``problem`` and their Jacobian (``studies.calibration.jacobian``) for one least-squares
    run; the Jacobian reuses the modes of the evaluation at the same x."""

    def __init__(self, problem: Problem, reference: np.ndarray):
        self.problem, self.reference = problem, reference
        self.names = tuple(p.name for p in problem.parameters)
        self.followers: dict = {}
        self._at, self._cases = None, None

    def _evaluate(self, x: np.ndarray) -> list:
        if self._at is None or not np.array_equal(self._at, x):
            cases = []
            for path in self.problem.scenes:
                try:
                    cases.append(case_modes(self.problem.scene(path, np.exp(x)),
                                            self.problem.n_modes, self.problem.elements))
                except FlexlinkError as exc:  # e.g. a bound combination the solver refuses
                    log.info("%s at %s: %s", path, np.exp(x), exc)
                    cases.append(None)
            self._at, self._cases = x.copy(), cases
        return self._cases

    def _predicted(self, x) -> np.ndarray:
        return np.array([np.full(self.problem.n_modes, np.nan) if c is None else c.frequencies
                         for c in self._evaluate(x)])

    def residuals(self, x) -> np.ndarray:
        return log_residuals(self.problem, self._predicted(x), self.reference)

    def jacobian(self, x) -> np.ndarray:
        """d r / d x (x = ln p): rows as ``residuals``, zero where a residual is the penalty."""
        predicted = self._predicted(x)
        D = log_frequency_sensitivities(
            lambda i, values: self.problem.scene(self.problem.scenes[i], values), np.exp(x),
            self.names, self._evaluate(x), self.problem.n_modes, self.problem.elements,
            self.followers, self.problem.bounds[1])
        D[np.isnan(predicted)] = 0.0
        if self.problem.target is FitTarget.RATIOS:
            J = D[:, 1:] - D[:, :1]
            J[np.isnan(predicted[:, 1:]) | np.isnan(predicted[:, :1])] = 0.0
        else:
            J = D
        return J.reshape(-1, len(self.names))


def _solve_from(problem: Problem, reference: np.ndarray, x0: np.ndarray):
    """One local least-squares run from ``x0`` (ln p); returns (x, cost, jac, nfev, whether it
    converged: False when it stopped at the evaluation limit)."""
    from scipy.optimize import least_squares

    fit = _Residuals(problem, reference)
    # ln-residuals to 1e-6 are far below the table's 1 Hz rounding (>= 0.07 %)
    result = least_squares(fit.residuals, x0, jac=fit.jacobian, bounds=problem.bounds,
                           method="trf", ftol=1e-6, xtol=1e-6, gtol=1e-6,
                           max_nfev=40 * (len(x0) + 1))
    return result.x, float(result.cost), result.jac, int(result.nfev), bool(result.status > 0)


class _PredictionErrors:
    """Errors of ``predicted`` against ``reference`` [Hz], shared by fits and cross-validation;
    ``reasons``: {case index: message} for cases whose evaluation raised."""

    @property
    def errors_pct(self) -> np.ndarray:
        return percent_error(self.predicted, self.reference)

    @property
    def mean_abs_error_pct(self) -> float | None:
        return mean_abs(self.errors_pct)


@dataclasses.dataclass(frozen=True)
class FitResult(_PredictionErrors):
    """Best of several starts. values [SI], rel_se = standard error of ln p (None if m <= p),
    correlation of the ln p estimates, predicted [Hz] and errors [%] per case and mode."""

    problem: Problem
    values: np.ndarray
    rel_se: np.ndarray | None
    correlation: np.ndarray | None
    at_bound: np.ndarray
    cost: float
    start_costs: np.ndarray
    predicted: np.ndarray
    reference: np.ndarray
    evaluations: int
    reasons: tuple[tuple[int, str], ...] = ()
    converged: tuple[bool, ...] = ()  # per start: False = stopped at the evaluation limit
    best: int = 0  # the start whose result this is

    def __post_init__(self):
        p = (len(self.problem.parameters),)
        cases = np.shape(self.reference)
        check_shape("FitResult", "reference", self.reference,
                    (len(self.problem.scenes), self.problem.n_modes))
        check_shape("FitResult", "predicted", self.predicted, cases)
        for name in ("values", "at_bound"):
            check_shape("FitResult", name, getattr(self, name), p)
        if self.rel_se is not None:
            check_shape("FitResult", "rel_se", self.rel_se, p)
        if self.correlation is not None:
            check_shape("FitResult", "correlation", self.correlation, p * 2)
        check_shape("FitResult", "start_costs", self.start_costs, (None,))


def start_points(problem: Problem, starts: int, rng: np.random.Generator) -> list[np.ndarray]:
    """The scenes' assumed inputs (pulled just inside the bounds), then uniform in ln p."""
    lo, hi = problem.bounds
    first = load_scene(problem.scenes[0], overrides=dict(problem.fixed))
    nominal = np.array([p.nominal(first) for p in problem.parameters])
    with np.errstate(divide="ignore"):
        x0 = np.clip(np.log(nominal), lo + 0.01 * (hi - lo), hi - 0.01 * (hi - lo))
    return [x0] + [rng.uniform(lo, hi) for _ in range(starts - 1)]


def _summarise(problem: Problem, reference: np.ndarray, runs) -> FitResult:
    costs = np.array([r[1] for r in runs])
    best = int(np.argmin(costs))
    x, cost, J = runs[best][:3]
    m, p = J.shape
    lo, hi = problem.bounds
    at_bound = (x - lo < 1e-3 * (hi - lo)) | (hi - x < 1e-3 * (hi - lo))
    rel_se = correlation = None
    if m > p:
        s2 = 2.0 * cost / (m - p)
        cov = s2 * np.linalg.pinv(J.T @ J)
        rel_se = np.sqrt(np.clip(np.diag(cov), 0.0, None))
        # an input the residuals do not depend on at all is not identifiable: no finite error
        blind = np.linalg.norm(J, axis=0) < 1e-9 * max(np.linalg.norm(J), 1e-300)
        rel_se[blind] = np.inf
        with np.errstate(divide="ignore", invalid="ignore"):
            correlation = cov / np.outer(rel_se, rel_se)
        correlation[blind, :] = np.nan
        correlation[:, blind] = np.nan
    values = np.exp(x)
    predicted, reasons = predict_with_failures(problem, values)
    return FitResult(problem=problem, values=values, rel_se=rel_se, correlation=correlation,
                     at_bound=at_bound, cost=cost, start_costs=costs, predicted=predicted,
                     reference=reference, evaluations=int(sum(r[3] for r in runs)),
                     reasons=tuple(reasons.items()), converged=tuple(r[4] for r in runs),
                     best=best)


def fit_many(problems: list[Problem], starts: int = 8, seed: int = 0, n_jobs: int = -1,
             show_progress: bool = False) -> list[FitResult]:
    """Fit every problem from ``starts`` start points each; all runs share one parallel pool.
    Start points are drawn in this process from ``seed``, so results do not depend on n_jobs."""
    rng = np.random.default_rng(seed)
    references = [measured(pr) for pr in problems]
    tasks, owner = [], []
    for k, (pr, ref) in enumerate(zip(problems, references)):
        for x0 in start_points(pr, starts, rng):
            tasks.append((pr, ref, x0))
            owner.append(k)
    runs = run_tasks(_solve_from, tasks, n_jobs=n_jobs, show_progress=show_progress, label="fits")
    return [_summarise(pr, ref, [r for r, o in zip(runs, owner) if o == k])
            for k, (pr, ref) in enumerate(zip(problems, references))]


@dataclasses.dataclass(frozen=True)
class CrossValidation(_PredictionErrors):
    """Leave one case out: fold k is fitted on the other cases and predicts case k."""

    folds: tuple[FitResult, ...]
    held_out: tuple[str, ...]
    predicted: np.ndarray  # (cases, n_modes) [Hz], each row from the fold that left it out
    reference: np.ndarray
    reasons: tuple[tuple[int, str], ...] = ()

    def __post_init__(self):
        cases = np.shape(self.reference)
        check_shape("CrossValidation", "reference", self.reference, (len(self.folds), None))
        check_shape("CrossValidation", "predicted", self.predicted, cases)
        if len(self.held_out) != len(self.folds):
            raise ValueError(f"CrossValidation.held_out has {len(self.held_out)} cases, expected "
                             f"{len(self.folds)} (one per fold)")


def leave_one_out_problems(problem: Problem) -> list[Problem]:
    return [dataclasses.replace(problem, scenes=tuple(s for s in problem.scenes if s != held))
            for held in problem.scenes]


def cross_validation(problem: Problem, folds: list[FitResult]) -> CrossValidation:
    """Assemble the held-out predictions of ``folds`` (fitted on ``leave_one_out_problems``)."""
    rows, reasons = [], []
    for i, (fold, held) in enumerate(zip(folds, problem.scenes)):
        row, why = predict_with_failures(problem, fold.values, scenes=(held,))
        rows.append(row[0])
        reasons += [(i, message) for message in why.values()]
    return CrossValidation(folds=tuple(folds), held_out=problem.scenes, predicted=np.array(rows),
                           reference=measured(problem), reasons=tuple(reasons))


def single_case_problems(problem: Problem, target: FitTarget) -> list[Problem]:
    return [dataclasses.replace(problem, scenes=(s,), target=target) for s in problem.scenes]


def ratios(frequencies: np.ndarray) -> np.ndarray:
    """f_k / f_1 per row."""
    return frequencies / frequencies[:, :1]


def case_label(path: str) -> str:
    return Path(path).stem

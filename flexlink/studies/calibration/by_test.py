"""Model updating against a modal test file: fit free scene inputs so that the model's
frequencies match the test's, each test mode compared with the model mode it pairs with by
shape (MAC, ``studies.correlation.correlation``), never by order.

Residuals at ln p (as ``fit``: relative steps, relative standard errors):
    ln f_model(j(i)) - ln f_test(i)      for each test mode i and its MAC partner j(i),
    w (1 - MAC(i, j(i)))                 with ``mac_weight`` w > 0 (optional),
    ``fit.MISSING_MODE_PENALTY``         for a test mode with no partner at that p.
The pairing is redone at every evaluation, so a pair of close modes that changes order as the
inputs move is followed by shape. The Jacobian is by finite differences in ln p (the pairing
makes the residuals piecewise smooth). The interval of each fitted input is ln p +- 1.96 se,
with se from cov = s^2 (J^T J)^-1, s^2 = sum r^2 / (m - p); it means little for an input on a
bound or with m <= p.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexlink.errors import FlexlinkError, InputError
from flexlink.scene import load_scene
from flexlink.studies.array_shapes import check_shape
from flexlink.studies.calibration.fit import MISSING_MODE_PENALTY, FreeParameter
from flexlink.studies.correlation.correlation import SPARE_MODES, TestCorrelation, correlate_test
from flexlink.studies.correlation.measured import ModalTest

Z95 = 1.959964  # two-sided 95 % quantile of the normal distribution


@dataclasses.dataclass(frozen=True)
class TestFit:
    """The fit of ``parameters`` of ``scene_path`` to ``test``: fitted ``values`` [SI], the
    ``nominal`` (the scene's own) values, 95 % ``low`` and ``high`` bounds (NaN when not
    determined), ``rel_se`` (standard error of ln p), the correlations at the ``start``
    (nominal inputs) and at the ``end`` (fitted), the final ``cost`` (0.5 sum r^2) and the
    model evaluations spent."""

    scene_path: str
    test: ModalTest
    parameters: tuple[FreeParameter, ...]
    mac_weight: float
    nominal: np.ndarray
    values: np.ndarray
    low: np.ndarray
    high: np.ndarray
    rel_se: np.ndarray
    start: TestCorrelation
    end: TestCorrelation
    cost: float
    evaluations: int
    converged: bool

    __test__ = False  # not a pytest class, whatever its name

    def __post_init__(self):
        p = (len(self.parameters),)
        for name in ("nominal", "values", "low", "high", "rel_se"):
            check_shape("TestFit", name, getattr(self, name), p)


def _overrides(parameters, values) -> dict[str, str]:
    out = {}
    for parameter, value in zip(parameters, values):
        out.update(parameter.overrides(float(value)))
    return out


def residuals_of(c: TestCorrelation, mac_weight: float) -> np.ndarray:
    """The residuals (module docstring) of one correlation: one per test mode, and with a
    MAC weight one more per test mode."""
    freq = np.full(c.test.n_modes, MISSING_MODE_PENALTY)
    mac = np.full(c.test.n_modes, mac_weight)
    for (i, j), v in zip(c.correlation.pairs, c.correlation.pair_mac):
        freq[i] = math.log(c.model.frequencies[j] / c.test.frequencies[i])
        mac[i] = mac_weight * (1.0 - v)
    return np.concatenate([freq, mac]) if mac_weight > 0 else freq


def fit_to_test(scene_path: str, test: ModalTest, parameters: tuple[FreeParameter, ...],
                elements: int | None = None, mac_weight: float = 0.0,
                n_modes: int | None = None) -> TestFit:
    """Fit ``parameters`` (each within its bounds, as ln p) of the scene in ``scene_path`` to
    ``test`` from the scene's own values (pulled inside the bounds), ``elements`` per link,
    against ``n_modes`` model modes (default: the test's + SPARE_MODES)."""
    from scipy.optimize import least_squares

    if not parameters:
        raise InputError("no free inputs", source="command line", field="--free",
                         expected="at least one NAME=LOW:HIGH")
    if mac_weight < 0:
        raise InputError(f"got {mac_weight!r}", source="command line", field="--mac-weight",
                         expected=">= 0")
    n_model = n_modes or test.n_modes + SPARE_MODES
    first = load_scene(scene_path)
    nominal = np.array([p.nominal(first) for p in parameters])
    lo = np.log([p.low for p in parameters])
    hi = np.log([p.high for p in parameters])
    with np.errstate(divide="ignore"):
        x0 = np.clip(np.log(nominal), lo + 0.01 * (hi - lo), hi - 0.01 * (hi - lo))
    evaluations = 0

    def correlation(x) -> TestCorrelation:
        scene = load_scene(scene_path, overrides=_overrides(parameters, np.exp(x)))
        return correlate_test(scene, test, n_model, elements, labelled=False)

    def residuals(x):
        nonlocal evaluations
        evaluations += 1
        try:
            return residuals_of(correlation(x), mac_weight)
        except FlexlinkError:  # e.g. a bound combination the solver refuses
            size = test.n_modes * (2 if mac_weight > 0 else 1)
            return np.full(size, MISSING_MODE_PENALTY)

    start = correlate_test(first, test, n_model, elements)
    # ln-residuals to 1e-8: far below the test's six significant digits (UFF 55)
    result = least_squares(residuals, x0, bounds=(lo, hi), method="trf", jac="2-point",
                           diff_step=1e-4, ftol=1e-10, xtol=1e-10, gtol=1e-10,
                           max_nfev=60 * (len(x0) + 1))
    m, p = result.jac.shape
    rel_se = np.full(p, np.nan)
    if m > p:
        s2 = 2.0 * result.cost / (m - p)
        cov = s2 * np.linalg.pinv(result.jac.T @ result.jac)
        rel_se = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    values = np.exp(result.x)
    end_scene = load_scene(scene_path, overrides=_overrides(parameters, values))
    end = correlate_test(end_scene, test, n_model, elements)
    return TestFit(scene_path, test, tuple(parameters), mac_weight, nominal, values,
                   np.exp(result.x - Z95 * rel_se), np.exp(result.x + Z95 * rel_se), rel_se,
                   start, end, float(result.cost), evaluations, bool(result.status > 0))

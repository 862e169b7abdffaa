"""Normalised sensitivities S = d ln f / d ln p by finite differences, and the first-order
spread they give: the one home of the difference formulas.

- ``log_slope``: the slope of ln f between two evaluations dx apart in ln p. The calibration
  Jacobian (``studies.calibration.jacobian``) uses it forward (dx = a step of 1e-5 in ln p) on full
  evaluations and on Rayleigh quotients; the uncertainty study uses it central.
- ``central_points`` / ``central_log_slopes``: central differences of +-``REL_STEP`` in p,
  dx = ln(1 + h) - ln(1 - h): second-order accurate, for inputs a step may not cross (a
  fraction, a modulus) and evaluated in parallel by the caller.
- ``first_order_sd``: the standard deviation of ln f, sqrt(sum_p (S_p sd_p / p)^2), for
  independent inputs with standard deviations sd_p.

The uncertainty study's inputs (constituent moduli and densities through the rule of mixtures,
the fibre fraction) are not the calibration's free inputs, and it keeps its central +-1 % steps
on full evaluations rather than the Jacobian's eigenvalue perturbation: the two agree to the
differencing errors only (measured for the thickness of case 2, planar, 6 elements/link: 1.2e-7
to 5.6e-7 of S), so changing one for the other would move every reported sensitivity and
first-order interval beyond round-off. ``studies.calibration.sensitivity`` takes no derivative: it
evaluates each assumed input at the two ends of its written range, a finite change on purpose.
"""

from __future__ import annotations

import numpy as np

REL_STEP = 0.01  # relative step of the central differences


def log_slope(f_high, f_low, dx):
    """(ln f_high - ln f_low) / dx: d ln f / d ln p between evaluations dx apart in ln p."""
    return (np.log(f_high) - np.log(f_low)) / dx


def central_points(nominal: dict[str, float], names) -> list[dict[str, float]]:
    """For each of ``names`` in order, ``nominal`` with that input times 1 + REL_STEP, then
    times 1 - REL_STEP: the inputs at which ``central_log_slopes`` wants evaluations."""
    points = []
    for name in names:
        for sign in (1.0, -1.0):
            values = dict(nominal)
            values[name] = float(nominal[name] * (1.0 + sign * REL_STEP))
            points.append(values)
    return points


def central_log_slopes(evaluations, names) -> dict[str, np.ndarray]:
    """{name: d ln f / d ln p} from the evaluations (arrays of frequencies, any shape) at
    ``central_points``, in that order."""
    dx = np.log1p(REL_STEP) - np.log1p(-REL_STEP)
    return {n: log_slope(evaluations[2 * k], evaluations[2 * k + 1], dx)
            for k, n in enumerate(names)}


def first_order_sd(slopes: dict[str, np.ndarray], nominal: dict[str, float],
                   sd: dict[str, float]) -> np.ndarray:
    """The first-order standard deviation of ln f: sqrt(sum (S sd / p)^2) over ``slopes``."""
    return np.sqrt(sum((slopes[n] * sd[n] / nominal[n]) ** 2 for n in slopes))

"""The difference formulas of studies/calibration/derivatives.py against closed forms: a power law
f = C p^a has d ln f / d ln p = a exactly, so any difference (forward or central, any step)
must return a to round-off; the first-order sd of independent inputs adds in quadrature."""

import math

import numpy as np
import pytest

from flexlink.studies.calibration.derivatives import (REL_STEP, central_log_slopes, central_points,
                                          first_order_sd, log_slope)

EXPONENTS = {"E": 0.5, "density": -0.5, "thickness": 1.0, "vf": 0.37}  # a per input


def power_law(values: dict) -> np.ndarray:
    """Two 'modes' f = C_k prod p^a_p [Hz], C = (3, 7)."""
    return np.array([3.0, 7.0]) * math.prod(values[n] ** a for n, a in EXPONENTS.items())


NOMINAL = {"E": 70e9, "density": 2700.0, "thickness": 1.5e-3, "vf": 0.55}


def test_central_slopes_of_a_power_law_are_its_exponents():
    names = tuple(sorted(NOMINAL))
    points = central_points(NOMINAL, names)
    # each input stepped up then down by REL_STEP, the others nominal
    assert points[0][names[0]] == NOMINAL[names[0]] * (1 + REL_STEP)
    assert points[1][names[0]] == NOMINAL[names[0]] * (1 - REL_STEP)
    assert all(p[names[1]] == NOMINAL[names[1]] for p in points[:2])
    slopes = central_log_slopes([power_law(p) for p in points], names)
    for name in names:  # ln f is linear in ln p: exact up to a few ulps of ln f / step
        np.testing.assert_allclose(slopes[name], EXPONENTS[name], rtol=1e-12)


def test_forward_slope_of_a_power_law_is_its_exponent():
    h = 1e-5
    f0, f1 = power_law(NOMINAL), power_law({**NOMINAL, "E": NOMINAL["E"] * math.exp(h)})
    # round-off of ln f (~1e-16 * |ln f| ~ 3e-15) over h = 1e-5: ~1e-9 relative
    np.testing.assert_allclose(log_slope(f1, f0, h), EXPONENTS["E"], rtol=1e-8)


def test_first_order_sd_adds_relative_spreads_in_quadrature():
    slopes = {"E": np.array([0.5]), "density": np.array([-0.5])}
    sd = {"E": 0.02 * NOMINAL["E"], "density": 0.04 * NOMINAL["density"]}
    # sqrt((0.5 * 0.02)^2 + (0.5 * 0.04)^2) = sqrt(1e-4 + 4e-4)
    assert first_order_sd(slopes, NOMINAL, sd)[0] == pytest.approx(math.sqrt(5e-4), rel=1e-14)

"""The labels of the stability map's unstable ranges (mode or mode pair, harmonic k, kind)
on periodic systems whose tongues are known, given directly as equations in the crank angle
theta (no basis): at crank speed Omega [rad/s], q'' + C q' + K(theta) q = 0 with theta = Omega t.

- One mode, K = omega0^2 (1 + epsilon cos theta): a Mathieu equation in theta with delta =
  (omega0 / Omega)^2 in its multiplicative form. Its k-th tongue sits at delta near k^2 / 4,
  Omega near 2 f0 / k: a "primary" range of mode 1 and harmonic k, edges from Hill's
  determinant (`tests/mathieu.py`).
- Two modes coupled only through their modulation, K = diag(omega1^2, omega2^2) + epsilon
  omega1 omega2 cos theta [[0, 1], [1, 0]]: no primary tongue to first order in epsilon, and a
  sum-type "combination" tongue of the pair (1, 2) near Omega = f1 + f2 (k = 1). Its edges come
  from the monodromy integrated here by scipy's DOP853 over one period, without flexlink.

Damping 0.001 of critical narrows the tongues by far less than one step of the speed grids.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from flexlink.studies.running.stability_map import PeriodicModel, stability_map

from mathieu import hill_edges

POSES = 9  # degree-1 modulation: 9 samples give its Fourier series exactly
ZETA = 0.001


def given_model(frequencies, modulation) -> PeriodicModel:
    """The equations K(theta) = diag((2 pi f)^2) + cos(theta) ``modulation``, M = I, no
    Coriolis or speed stiffness, damping ZETA of every mode."""
    f = np.asarray(frequencies, dtype=float)
    angles = 2 * np.pi * np.arange(POSES) / POSES
    stiffness = (np.diag((2 * np.pi * f) ** 2)[None]
                 + np.cos(angles)[:, None, None] * np.asarray(modulation, dtype=float)[None])
    eye = np.broadcast_to(np.eye(len(f)), stiffness.shape).copy()
    return PeriodicModel(angles=angles, mass=eye, coriolis=0 * eye, stiffness=stiffness,
                         speed_stiffness=0 * eye, frequencies=f, damping_ratio=ZETA)


def largest_modulus(frequencies, modulation, speed: float) -> float:
    """The largest Floquet multiplier modulus at ``speed`` [rad/s] of the equations of
    ``given_model``, from their monodromy integrated column by column (DOP853, rtol 1e-11)."""
    f = np.asarray(frequencies, dtype=float)
    n = len(f)
    damping = np.diag(2 * ZETA * 2 * np.pi * f)
    mean, amplitude = np.diag((2 * np.pi * f) ** 2), np.asarray(modulation, dtype=float)

    def rhs(t, x):
        k = mean + math.cos(speed * t) * amplitude
        return np.concatenate([x[n:], -damping @ x[n:] - k @ x[:n]])
    period = 2 * np.pi / speed
    columns = [solve_ivp(rhs, (0, period), e, method="DOP853", rtol=1e-11, atol=1e-13).y[:, -1]
               for e in np.eye(2 * n)]
    return float(np.abs(np.linalg.eigvals(np.column_stack(columns))).max())


@pytest.mark.parametrize("k, window", [(1, (17.0, 23.0)), (2, (9.7, 10.2))])
def test_a_mathieu_tongue_is_a_primary_range_of_mode_1_at_harmonic_k(k, window):
    epsilon, f0 = 0.3, 10.0
    model = given_model([f0], [[epsilon * (2 * np.pi * f0) ** 2]])
    revs = np.linspace(*window, 201)  # [rev/s]
    result = stability_map(model, 2 * np.pi * revs)
    [found] = result.ranges
    assert (found.modes, found.harmonic, found.kind) == ((1,), k, "primary")
    low_delta, high_delta = hill_edges(epsilon, k=k, multiplicative=True)
    # delta = (f0 / (Omega / 2 pi))^2: the tongue's upper delta edge is its lower speed edge
    step = revs[1] - revs[0]
    assert abs(found.low / (2 * np.pi) - f0 / math.sqrt(high_delta)) <= step
    assert abs(found.high / (2 * np.pi) - f0 / math.sqrt(low_delta)) <= step
    assert found.growth_rate > 0


def test_a_sum_combination_tongue_is_labelled_with_its_mode_pair():
    f1, f2, epsilon = 10.0, 17.0, 0.3
    w1, w2 = 2 * np.pi * f1, 2 * np.pi * f2
    coupling = epsilon * w1 * w2 * np.array([[0.0, 1.0], [1.0, 0.0]])
    model = given_model([f1, f2], coupling)
    revs = np.linspace(24.0, 30.0, 121)  # [rev/s] around f1 + f2 = 27
    result = stability_map(model, 2 * np.pi * revs)
    [found] = result.ranges
    assert (found.modes, found.harmonic, found.kind) == ((1, 2), 1, "combination")
    # the edges where the independently integrated multiplier crosses the unit circle,
    # bracketed by the map's own first and last unstable speeds and their stable neighbours
    step = revs[1] - revs[0]

    def excess(rev):
        return largest_modulus([f1, f2], coupling, 2 * np.pi * rev) - 1.0
    first, last = found.low / (2 * np.pi), found.high / (2 * np.pi)
    assert excess(first - step) < 0 < excess(first) and excess(last) > 0 > excess(last + step)
    low = brentq(excess, first - step, first, xtol=1e-6)
    high = brentq(excess, last, last + step, xtol=1e-6)
    assert low < f1 + f2 < high and excess(f1 + f2) > 0  # it holds the combination resonance
    # no primary range of either mode inside the window (2 f2 / k = 34, 17, 11.3 rev/s and
    # 2 f1 / k = 20, 10: none between 24 and 30)
    assert len(result.ranges) == 1

"""Floquet multipliers of the Mathieu equation q'' + 2 c q' + (delta + epsilon cos t) q = 0.

With period T = 2 pi in t, the first instability tongue emanates from delta = 1/4 (the
period-doubling tongue: a multiplier leaves the unit circle through -1).
"""
import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from flexlink.analysis.floquet import (first_order, floquet, monodromy, ordered_product,
                                       propagators)
from flexlink.errors import NumericalError

from mathieu import first_order_matrix, hill_edges

PERIOD = 2.0 * np.pi
STEPS = 200


def mathieu(delta: float, epsilon: float, c: float = 0.0):
    """A(t) of the (damped) Mathieu equation in first-order form, built by flexlink's
    first_order (the reference's matrix, as the first test checks)."""
    mass, damping = np.eye(1), np.array([[2.0 * c]])
    return lambda t: first_order(mass, damping, (delta + epsilon * np.cos(t))[..., None, None])


def multipliers(delta, epsilon, c=0.0, steps=STEPS, period=PERIOD):
    return monodromy(mathieu(delta, epsilon, c), period, steps)


def boundary(epsilon: float, side: int) -> float:
    """delta on the lower (side -1) or upper (+1) edge of the first tongue, undamped.

    The monodromy has det 1, so the edge is where its trace passes through -2."""
    def excess(delta):
        return -np.trace(multipliers(delta, epsilon).monodromy) - 2.0
    centre = 0.25 - epsilon**2 / 8.0
    return brentq(excess, centre, centre + side * (epsilon + 0.05), xtol=1e-13)


def test_first_order_builds_the_reference_matrix():
    t = np.linspace(0.0, PERIOD, 7)
    assert np.allclose(mathieu(0.3, 0.4, 0.02)(t), first_order_matrix(0.3, 0.4, 0.02)(t),
                       rtol=1e-15, atol=0)


@pytest.mark.parametrize("epsilon", [0.02, 0.05, 0.1])
def test_tongue_edges_follow_ince_strutt_for_small_epsilon(epsilon):
    # Ince-Strutt to second order: delta = 1/4 +- epsilon/2 - epsilon^2/8. The next term is
    # -+ epsilon^3/32, so the tolerance is epsilon^3/16 (twice the neglected term).
    for side in (-1, 1):
        second_order = 0.25 + side * epsilon / 2.0 - epsilon**2 / 8.0
        assert boundary(epsilon, side) == pytest.approx(second_order, abs=epsilon**3 / 16.0)


@pytest.mark.parametrize("epsilon", [0.1, 0.3, 0.5])
def test_tongue_edges_match_hill_determinant_up_to_half(epsilon):
    # Hill's determinant is exact to round-off at this order; the Magnus error at 200 steps
    # is below 1e-8 in delta (measured 1.2e-9 at epsilon 0.5), so 1e-8 is the bound.
    low, high = hill_edges(epsilon)
    assert boundary(epsilon, -1) == pytest.approx(low, abs=1e-8)
    assert boundary(epsilon, 1) == pytest.approx(high, abs=1e-8)


def test_hill_reference_is_converged_in_its_order():
    # The reference itself: doubling the truncation changes the edges only at round-off, which
    # scales with the largest diagonal entry (~3600 at order 60) times 2e-16: 1e-11.
    assert np.allclose(hill_edges(0.5, order=30), hill_edges(0.5, order=60), atol=1e-11, rtol=0)


def test_growth_rate_equals_long_time_integration_inside_tongue():
    # Centre of the tongue at epsilon 0.3: the growth rate ln|mu|/T must equal the slope of
    # ln|x| sampled once a period after the decaying solution has died out. Both are accurate
    # to far better than the 1 %; 1e-6 relative is the bound (the Magnus error at 400
    # steps and the integrator's tolerance 1e-12 are both well inside it).
    delta, epsilon = 0.25, 0.3
    rate = multipliers(delta, epsilon, steps=400).growth_rate
    system = mathieu(delta, epsilon)
    run = solve_ivp(lambda t, x: system(np.array(t)) @ x, (0.0, 30 * PERIOD), [1.0, 0.3], method="DOP853",
                    rtol=1e-12, atol=1e-14, t_eval=[10 * PERIOD, 30 * PERIOD])
    slope = np.log(np.linalg.norm(run.y[:, 1]) / np.linalg.norm(run.y[:, 0])) / (20 * PERIOD)
    assert rate > 0.1
    assert rate == pytest.approx(slope, rel=1e-6)


def test_no_modulation_no_instability():
    # epsilon = 0: a constant undamped oscillator; the Magnus step is then exact, so every
    # multiplier sits on the unit circle to round-off, even exactly on the tongue's root.
    for delta in (0.1, 0.25, 0.7, 1.0):
        assert multipliers(delta, 0.0).largest_modulus == pytest.approx(1.0, abs=1e-12)


def test_damping_scales_the_multipliers_exactly():
    # q = exp(-c t) y turns the damped equation into the undamped one with delta - c^2, so the
    # damped multipliers are exp(-c T) times the shifted undamped ones (to the Magnus error).
    c, delta, epsilon = 0.03, 0.26, 0.2
    damped = np.sort_complex(multipliers(delta, epsilon, c).multipliers)
    shifted = np.sort_complex(multipliers(delta - c * c, epsilon).multipliers)
    assert np.allclose(damped, np.exp(-c * PERIOD) * shifted, atol=1e-9)


def test_damping_narrows_the_tongue_and_lifts_it_off_the_axis():
    # First-order averaging about delta = 1/4 + sigma: the undamped exponent is
    # s = sqrt(epsilon^2/4 - sigma^2); damping c makes the motion grow only where s > c, so the
    # tongue's width is 2 sqrt(epsilon^2/4 - c^2) (narrower than epsilon) and it needs
    # epsilon > 2 c (it lifts off the epsilon = 0 axis). The width's error is second order in
    # epsilon (the edge shift -epsilon^2/8 is common to both edges), 2e-3 bounds it at 0.2.
    c, epsilon = 0.04, 0.2

    def growth(delta, eps=epsilon):
        return multipliers(delta, eps, c).growth_per_period

    centre = 0.25 - epsilon**2 / 8.0 - c * c
    low = brentq(growth, centre - 0.2, centre, xtol=1e-12)
    high = brentq(growth, centre, centre + 0.2, xtol=1e-12)
    undamped = boundary(epsilon, 1) - boundary(epsilon, -1)
    assert high - low < undamped
    assert high - low == pytest.approx(2.0 * np.sqrt(epsilon**2 / 4.0 - c * c), abs=2e-3)
    # Lift-off: below epsilon = 2 c nothing grows anywhere near the tongue; above it, it does.
    deltas = 0.25 - c * c + np.linspace(-0.05, 0.05, 41)
    assert max(growth(d, 1.6 * c) for d in deltas) < 0.0
    assert max(growth(d, 2.5 * c) for d in deltas) > 0.0


def test_monodromy_converges_at_fourth_order_in_the_step_count():
    # Fourth-order Magnus: halving the step divides the error of Phi(T) by 16 (order 4 +- 0.3).
    reference = multipliers(0.3, 0.4, 0.02, steps=3200).monodromy
    errors = [np.abs(multipliers(0.3, 0.4, 0.02, steps=s).monodromy - reference).max()
              for s in (25, 50, 100)]
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.abs(orders - 4.0) < 0.3), orders


def test_wrong_period_is_seen():
    # Integrating the same system over half its period gives another (stable) monodromy: the
    # tongue's centre is unstable only over the true period.
    assert multipliers(0.25, 0.3).largest_modulus > 1.1
    assert multipliers(0.25, 0.3, period=np.pi).largest_modulus == pytest.approx(1.0, abs=1e-6)


@pytest.mark.parametrize("intervals, steps", [(40, 30), (2, 1500)])
def test_interval_propagators_multiply_to_the_monodromy(intervals, steps):
    # The same Magnus steps grouped by interval (40 x 30: 34 intervals formed at once, then 6;
    # 2 x 1500: an interval longer than one chunk): their ordered product is the monodromy of
    # intervals x steps steps, and the k-th maps the solution from t_k to t_{k+1}. Only the
    # association of the products differs, so 1e-12 (round-off on entries of order one).
    system = mathieu(0.3, 0.4, 0.02)
    parts = propagators(system, PERIOD, intervals, steps)
    whole = multipliers(0.3, 0.4, 0.02, steps=intervals * steps).monodromy
    assert np.allclose(ordered_product(parts), whole, rtol=0, atol=1e-12)
    first = monodromy(system, PERIOD / intervals, steps).monodromy
    assert np.allclose(parts[0], first, rtol=0, atol=1e-12)
    assert not np.allclose(ordered_product(parts[::-1]), whole, rtol=0, atol=1e-6)


def test_an_overflowed_monodromy_is_refused_not_returned():
    # growth beyond the floating-point range over one period: no multipliers can be read from
    # an inf or NaN matrix, and none are returned as numbers
    with pytest.raises(NumericalError, match="overflowed over one period"):
        floquet(np.array([[np.inf, 0.0], [0.0, 1.0]]), 1.0)

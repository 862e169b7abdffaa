"""The steady periodic solution by shooting, against closed forms and a time integration.

One DOF, m q'' + c q' + k q = F cos(W t): the steady amplitude is
F / k / sqrt((1 - r^2)^2 + (2 zeta r)^2), r = W / w0, with phase lag atan2(2 zeta r, 1 - r^2)
(any vibrations text, e.g. Thomson, Theory of Vibration, section 3.1).
"""
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from flexlink.analysis.floquet import first_order
from flexlink.analysis.periodic_response import UnstableError, periodic_solution


def oscillator(w0: float, zeta: float):
    """A of q'' + 2 zeta w0 q' + w0^2 q = ... (unit mass), constant in time."""
    a = first_order(np.eye(1), np.array([[2 * zeta * w0]]), np.array([[w0**2]]))
    return lambda t: np.broadcast_to(a, (len(np.atleast_1d(t)), 2, 2))


def cosine(force: float, w: float):
    return lambda t: np.stack([0 * np.asarray(t), force * np.cos(w * np.asarray(t))], axis=-1)


@pytest.mark.parametrize("r", [0.3, 0.9, 1.0, 1.1, 2.5])
@pytest.mark.parametrize("zeta", [0.01, 0.1])
def test_one_dof_amplitude_and_phase_are_the_closed_form(r, zeta):
    w0, force, samples = 2 * np.pi * 5.0, 3.0, 64
    w = r * w0
    period = 2 * np.pi / w
    solution = periodic_solution(oscillator(w0, zeta), cosine(force, w), period, 400, samples)
    q = solution.states[:, 0]
    amplitude = force / w0**2 / np.hypot(1 - r**2, 2 * zeta * r)
    lag = np.arctan2(2 * zeta * r, 1 - r**2)
    exact = amplitude * np.cos(w * solution.times - lag)
    # 400 fourth-order Magnus steps over one forcing period with h w0 <= 0.05: the local
    # error is of order (h w0)^5 / 720 per step, far below the 1e-8 asked here
    assert np.abs(q - exact).max() <= 1e-8 * amplitude
    assert np.allclose(solution.states[:, 1], -amplitude * w * np.sin(w * solution.times - lag),
                       atol=1e-8 * amplitude * w)


def test_quasi_static_limit_is_force_over_stiffness():
    # r -> 0: the amplitude tends to F / k, its excess 1 / sqrt((1 - r^2)^2 + (2 zeta r)^2) - 1
    # ~ (1 - 2 zeta^2) r^2 quarters when r halves
    w0, zeta = 2 * np.pi * 50.0, 0.05
    excess, lag = [], []
    for r in (0.02, 0.01):
        w = r * w0
        s = periodic_solution(oscillator(w0, zeta), cosine(1.0, w), 2 * np.pi / w, 4000, 400)
        excess.append(np.abs(s.states[:, 0]).max() * w0**2 - 1.0)
        lag.append(np.abs(s.states[:, 0] * w0**2 - np.cos(w * s.times)).max())
    assert excess[0] == pytest.approx(4 * excess[1], rel=0.01)
    assert excess[0] == pytest.approx((1 - 2 * zeta**2) * 0.02**2, rel=0.01)
    # the largest deviation from F cos(W t) / k is |A exp(-i lag) - 1| (A the amplitude
    # ratio), led by the lag 2 zeta r; 400 samples a turn find the maximum to 1 - cos(pi/400)
    r = 0.02
    a = 1 / np.hypot(1 - r**2, 2 * zeta * r) * np.exp(-1j * np.arctan2(2 * zeta * r, 1 - r**2))
    assert lag[0] == pytest.approx(abs(a - 1), rel=1e-4)


def mathieu_forced(delta, epsilon, c, force):
    def a(t):
        t = np.atleast_1d(t)
        return first_order(np.eye(1), np.array([[2 * c]]),
                           (delta + epsilon * np.cos(t))[:, None, None])

    def b(t):
        t = np.atleast_1d(t)
        return np.stack([0 * t, force * np.sin(t) + 0.3 * force * np.cos(3 * t)], axis=-1)
    return a, b


def test_forced_damped_mathieu_equals_a_long_time_integration():
    # outside the tongue (delta 0.6) with damping, a DOP853 run from rest over 60 periods has
    # forgotten its start to exp(-c 60 T) ~ 5e-17; both then agree to the integrators' error
    delta, epsilon, c = 0.6, 0.3, 0.05
    a, b = mathieu_forced(delta, epsilon, c, 1.0)
    s = periodic_solution(a, b, 2 * np.pi, 600, 30)
    assert s.stability.largest_modulus < 1.0

    def rhs(t, x):
        return a(t)[0] @ x + b(t)[0]
    n = 60
    run = solve_ivp(rhs, (0, 2 * np.pi * n), [0.0, 0.0], method="DOP853", rtol=1e-12,
                    atol=1e-14, t_eval=2 * np.pi * (n - 1) + s.times)
    reference = run.y.T
    assert np.abs(s.states - reference).max() <= 1e-8 * np.abs(reference).max()


def test_inside_a_tongue_no_steady_state_is_returned():
    a, b = mathieu_forced(0.25, 0.3, 0.01, 1.0)  # the first tongue's centre: |mu| > 1
    with pytest.raises(UnstableError, match="no steady state"):
        periodic_solution(a, b, 2 * np.pi, 200, 8)

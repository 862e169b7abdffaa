"""The periodic solution by harmonic balance, against closed forms, a long time integration
and a solve with many more harmonics.

One DOF, m q'' + c q' + k q = F cos(W t): the steady amplitude is
F / k / sqrt((1 - r^2)^2 + (2 zeta r)^2), r = W / w0, with phase lag atan2(2 zeta r, 1 - r^2)
(any vibrations text, e.g. Thomson, Theory of Vibration, section 3.1).

In time, with theta = Omega t, the equations solved are
    q'' + D(Omega t) q' + S(Omega t) q = g(Omega t)   (' = d/dt),
written out here for the integrations; the module takes them in theta.
"""
import logging

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.special import iv

from flexlink.analysis.fourier import fourier_coefficients
from flexlink.analysis.harmonic_balance import (
    _band_preconditioner,
    _gmres,
    _hill_product,
    harmonic_balance,
)
from flexlink.errors import NumericalError


def one_dof(w0, zeta, force, harmonics=1):
    """Coefficients (S, D, g) of q'' + 2 zeta w0 q' + w0^2 q = force cos(theta)."""
    S = np.zeros((harmonics + 1, 1, 1), complex)
    D = np.zeros_like(S)
    g = np.zeros((harmonics + 1, 1), complex)
    S[0], D[0], g[1] = w0**2, 2 * zeta * w0, force / 2
    return S, D, g


@pytest.mark.parametrize("r", [0.3, 0.9, 1.0, 1.1, 2.5])
@pytest.mark.parametrize("zeta", [0.01, 0.1])
def test_one_dof_amplitude_and_phase_are_the_closed_form(r, zeta):
    w0, force = 2 * np.pi * 5.0, 3.0
    w = r * w0
    solution = harmonic_balance(*one_dof(w0, zeta, force), w)
    theta = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    amplitude = force / w0**2 / np.hypot(1 - r**2, 2 * zeta * r)
    lag = np.arctan2(2 * zeta * r, 1 - r**2)
    # constant coefficients: one harmonic, solved exactly up to GMRES' residual (1e-12) and
    # round-off of a 1 x 1 system
    assert np.abs(solution.at(theta)[:, 0] - amplitude * np.cos(theta - lag)).max() \
        <= 1e-10 * amplitude
    assert np.allclose(w * solution.at(theta, derivative=1)[:, 0],
                       -amplitude * w * np.sin(theta - lag), rtol=0, atol=1e-10 * amplitude * w)


def test_quasi_static_limit_is_force_over_stiffness():
    # r -> 0: the amplitude tends to F / k, its excess 1 / sqrt((1 - r^2)^2 + (2 zeta r)^2) - 1
    # ~ (1 - 2 zeta^2) r^2 quarters when r halves (to 1 %: the r^4 terms)
    w0, zeta = 2 * np.pi * 50.0, 0.05
    theta = np.linspace(0, 2 * np.pi, 400, endpoint=False)
    excess = [np.abs(harmonic_balance(*one_dof(w0, zeta, 1.0), r * w0).at(theta)).max()
              * w0**2 - 1.0 for r in (0.02, 0.01)]
    assert excess[0] == pytest.approx(4 * excess[1], rel=0.01)
    assert excess[0] == pytest.approx((1 - 2 * zeta**2) * 0.02**2, rel=0.01)


def mathieu(delta, epsilon, c, wobble):
    """A forced damped Mathieu equation with a varying damping, coefficients in theta and
    the functions of theta they stand for: S = delta (1 + epsilon cos theta), D = 2 c (1 +
    wobble sin theta), g = sin theta + 0.3 cos 3 theta."""
    def S(t): return delta * (1 + epsilon * np.cos(t))
    def D(t): return 2 * c * (1 + wobble * np.sin(t))
    def g(t): return np.sin(t) + 0.3 * np.cos(3 * t)
    theta = 2 * np.pi * np.arange(7) / 7  # degree 3: 7 samples give every coefficient
    return ((fourier_coefficients(S(theta)[:, None, None]),
             fourier_coefficients(D(theta)[:, None, None]), fourier_coefficients(g(theta)[:, None])),
            (S, D, g))


@pytest.mark.parametrize("speed", [1.0, 2.7])
def test_forced_damped_mathieu_equals_a_long_time_integration(speed):
    # outside the tongues (delta / speed^2 away from k^2 / 4) with damping: a DOP853 run from
    # rest over 60 periods has forgotten its start to exp(-c 60 T) < 1e-12; the two then agree
    # to the integrator's error. The varying damping and the speed are there so that a wrong
    # Omega (k - d) factor of the damping term cannot pass.
    delta, c = 0.6 * speed**2, 0.08 * speed
    coefficients, (S, D, g) = mathieu(delta, 0.5, c, 0.5)
    solution = harmonic_balance(*coefficients, speed, tolerance=1e-12)
    period, turns = 2 * np.pi / speed, 60
    t = np.linspace(0, period, 30, endpoint=False)

    def rhs(time, x):
        theta = speed * time
        return [x[1], g(theta) - D(theta) * x[1] - S(theta) * x[0]]
    run = solve_ivp(rhs, (0, turns * period), [0.0, 0.0], method="DOP853", rtol=1e-12,
                    atol=1e-14, t_eval=(turns - 1) * period + t)
    q, dq = solution.at(speed * t)[:, 0], speed * solution.at(speed * t, 1)[:, 0]
    scale = np.abs(run.y[0]).max()
    assert np.abs(q - run.y[0]).max() <= 1e-8 * scale
    assert np.abs(dq - run.y[1]).max() <= 1e-8 * speed * scale
    assert not solution.coefficients[0].imag.any()  # the mean of a real q is real


def test_a_tolerance_out_of_reach_within_the_cap_is_refused():
    # a stiff, strongly modulated equation (frozen frequency 100 (1 +- 0.9)^1/2 times the
    # speed): its harmonics are not settled within 20
    coefficients, _ = mathieu(1e4, 0.9, 0.02, 0.0)
    with pytest.raises(NumericalError, match="estimated error .* at 20 harmonics"):
        harmonic_balance(*coefficients, 1.0, tolerance=1e-8, max_harmonics=20)


def test_coefficients_of_mismatched_shapes_are_refused():
    S, D, g = one_dof(1.0, 0.1, 1.0)
    with pytest.raises(ValueError, match="must match"):
        harmonic_balance(S, D[:1], g, 1.0)


def test_without_forcing_the_periodic_solution_is_rest():
    S, D, g = one_dof(1.0, 0.1, 0.0)
    solution = harmonic_balance(S, D, g, 1.0)
    assert not solution.coefficients.any() and solution.error == solution.residual == 0.0


def test_at_constant_coefficients_the_preconditioner_inverts_the_hill_matrix():
    # constant coefficients couple no two harmonics: the band preconditioner over k = 0..H is
    # then the Hill matrix's exact inverse. Three coupled coordinates, frozen frequencies 1.3
    # to 3.1 times the speed, damping 0.1: the blocks' condition is ~1e2, so the round-off is
    # ~1e2 times double precision's 1e-16
    rng = np.random.default_rng(3)
    speed, H, n = 7.0, 10, 3
    modes = np.linalg.qr(rng.standard_normal((n, n)))[0]
    S = (modes * (speed * np.array([1.3, 2.2, 3.1])) ** 2) @ modes.T
    D = 0.2 * speed * np.eye(n) + 0.05 * speed * (modes - modes.T)  # with a gyroscopic part
    x = rng.standard_normal((H + 1, n)) + 1j * rng.standard_normal((H + 1, n))
    x[0] = x[0].real
    x = x.view(float).ravel()
    product = _hill_product(S[None], D[None], speed, H)
    precondition = _band_preconditioner(S[None], D[None], speed, H, 0)
    assert np.abs(precondition(product(x)) - x).max() <= 1e-12 * np.abs(x).max()


@pytest.mark.parametrize("w0", [1e20, 1e-30])
def test_the_answer_does_not_depend_on_the_time_unit(w0):
    # the one-DOF closed form with time in units 1e20 or 1e-30 times smaller: S ~ w0^2 = 1e40
    # and 1e-60, far from 1 (the solver scales nothing: GMRES' residual and the solve's error
    # are relative)
    r, zeta = 0.9, 0.01
    solution = harmonic_balance(*one_dof(w0, zeta, w0**2), r * w0)
    theta = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    amplitude = 1.0 / np.hypot(1 - r**2, 2 * zeta * r)
    lag = np.arctan2(2 * zeta * r, 1 - r**2)
    assert np.abs(solution.at(theta)[:, 0] - amplitude * np.cos(theta - lag)).max() \
        <= 1e-10 * amplitude


def test_coefficients_spanning_1e84_are_solved():
    # two uncoupled DOFs, frozen frequencies 1e-21 and 1e21 rad/s: S spans 1e84 (more than
    # single precision holds); each DOF gets its closed form
    w, zeta, r = np.array([1e-21, 1e21]), 0.05, 0.9
    S, D, g = np.zeros((2, 2, 2)), np.zeros((2, 2, 2)), np.zeros((2, 2), complex)
    S[0], D[0], g[1] = np.diag(w**2), np.diag(2 * zeta * w), w**2 / 2
    speed = r * w[0]
    solution = harmonic_balance(S, D, g, speed)
    ratio = speed / w
    amplitude = 1.0 / np.hypot(1 - ratio**2, 2 * zeta * ratio)
    lag = np.arctan2(2 * zeta * ratio, 1 - ratio**2)
    theta = np.linspace(0, 2 * np.pi, 64, endpoint=False)[:, None]
    assert np.abs(solution.at(theta[:, 0]) - amplitude * np.cos(theta - lag)).max() <= 1e-10


def hill_matrix(S, D, g, speed, H):
    """The Hill matrix over harmonics -H..H written out block by block, and its right-hand
    side: -(Omega k)^2 Q_k + sum_d [S_d + i Omega (k - d) D_d] Q_{k-d} = g_k."""
    P, n = S.shape[0] - 1, S.shape[-1]
    def harmonic(c, d):
        return c[d] if d >= 0 else np.conj(c[-d])
    A = np.zeros(((2 * H + 1) * n, (2 * H + 1) * n), complex)
    b = np.zeros((2 * H + 1, n), complex)
    for k in range(-H, H + 1):
        rows = slice((k + H) * n, (k + H + 1) * n)
        A[rows, rows] -= (speed * k) ** 2 * np.eye(n)
        if abs(k) <= P:
            b[k + H] = harmonic(g, k)
        for d in range(-P, P + 1):
            if abs(k - d) <= H:
                columns = slice((k - d + H) * n, (k - d + H + 1) * n)
                A[rows, columns] += harmonic(S, d) + 1j * speed * (k - d) * harmonic(D, d)
    return A, b.ravel()


def swinging_stiffness(P, w0=20.0, zeta=0.01, a=5.0):
    """One DOF, q'' + 2 zeta w0 q' + w0^2 exp(a cos theta) / I0(a) q = cos theta at speed 1:
    the frozen frequency swings from 0.016 w0 to 2.3 w0 over the turn (the stiffness'
    harmonics I_d(a) / I0(a), cut at P: 0.8, 0.5, .. 2e-3 at d = 8), so the crank harmonics
    2 to 46 cross it, lightly damped."""
    d = np.arange(P + 1)
    S = (w0**2 * iv(d, a) / iv(0, a)).astype(complex)[:, None, None]
    D = np.zeros_like(S)
    D[0] = 2 * zeta * w0
    g = np.zeros((P + 1, 1), complex)
    g[1] = 0.5
    return S, D, g


@pytest.mark.parametrize("P", [8, 16])
def test_a_fast_swinging_stiffness_widens_the_preconditioner_band(P, caplog):
    # the coefficients cut to |d| <= 4 misplace the swinging frozen frequency, so GMRES with
    # that band stagnates; with P = 8 the next band is the whole one (the last tried), with
    # P = 16 an intermediate one. The answer is the Hill system's own, solved here directly
    # (dense LU: round-off ~1e-16 times its condition, ~1e4), to the error the solver
    # accepts (SOLVE_ERROR, 1e-8; 1e-13 is reached)
    S, D, g = swinging_stiffness(P)
    with caplog.at_level(logging.INFO, logger="flexlink.analysis.harmonic_balance"):
        solution = harmonic_balance(S, D, g, 1.0)
    # band 4 tried at the first harmonic count only: the band that served is kept as H grows
    assert caplog.text.count("with the band 4 preconditioner") == 1
    assert "band 8 next" in caplog.text
    H = solution.harmonics
    A, b = hill_matrix(S, D, g, 1.0, H)
    direct = np.linalg.solve(A, b).reshape(2 * H + 1, 1)[H:]
    assert np.abs(solution.coefficients - direct).max() <= 1e-8 * np.abs(direct).max()


def stiff_and_soft(separation, zeta=0.01, r=0.9):
    """Two DOFs, a soft mode forced at r times its frequency and one ``separation`` times
    stiffer, mixed by a rotation R (so the soft response is a difference of stiff terms in
    every row of S q), and the closed form of the soft modal coordinate at theta."""
    w = np.array([1.0 / r, separation / r])
    c, s = np.cos(0.5), np.sin(0.5)
    R = np.array([[c, -s], [s, c]])
    S, D, g = np.zeros((2, 2, 2), complex), np.zeros((2, 2, 2), complex), np.zeros((2, 2), complex)
    S[0], D[0], g[1] = (R * w**2) @ R.T, (R * 2 * zeta * w) @ R.T, R[:, 0] * w[0] ** 2 / 2

    def soft(theta):
        return np.cos(theta - np.arctan2(2 * zeta * r, 1 - r**2)) / np.hypot(1 - r**2,
                                                                              2 * zeta * r)
    return (S, D, g), R, soft


def test_a_solve_at_the_round_off_floor_of_its_residual_is_accepted():
    # stiffness 1e8 times the soft mode's: S q rounds to ~1e8 eps of |S q| in double, so the
    # relative residual cannot reach RTOL (it stops near 1e-7, far above 1e3 RTOL); the error
    # the preconditioner estimates from it, and the true one against the closed form, are
    # ~1e-9: accepted
    equations, R, soft = stiff_and_soft(1e4)
    solution = harmonic_balance(*equations, 1.0)
    theta = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    assert solution.residual > 1e3 * 1e-12  # the path under test: the residual's floor
    assert np.abs((solution.at(theta) @ R)[:, 0] - soft(theta)).max() <= 1e-7 * soft(0).max()


def test_a_system_beyond_double_precision_is_refused():
    # stiffness 1e12 times the soft mode's: the round-off of S q is ~1e-4 of the soft
    # response, whose answer is then off by ~1e-3 (its closed form): refused in one line,
    # naming the estimated error, at every band
    equations, _, _ = stiff_and_soft(1e6, r=0.99)
    with pytest.raises(NumericalError, match=r"GMRES stalled .*estimated relative error"):
        harmonic_balance(*equations, 1.0)


def test_a_nan_is_never_accepted():
    # a NaN in the product (an overflow) reaches the residual; NaN compares false with
    # every bound, so the test is written to refuse it
    S, D, g = one_dof(2.0, 0.1, 1.0)
    H = 4
    product = _hill_product(S, D, 1.0, H)
    precondition = _band_preconditioner(S, D, 1.0, H, 0)
    b = np.zeros((H + 1, 1), complex)
    b[1] = g[1]
    b = b.view(float).ravel()

    def poisoned(x):
        y = product(x)
        y[2] = np.nan
        return y
    with pytest.raises(NumericalError, match="nan"):
        _gmres(poisoned, precondition, b, np.zeros_like(b))
    S[0, 0, 0] = np.nan
    with pytest.raises(NumericalError, match="nan"):
        harmonic_balance(S, D, g, 1.0)

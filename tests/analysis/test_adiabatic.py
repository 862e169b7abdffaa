"""The adiabatic integrator against closed forms and the Magnus reference.

Systems in the crank angle theta: dx/dtheta = (A0 / Omega + A1 + Omega A2) x, one turn 2 pi.
"""
import numpy as np
import pytest
import scipy.linalg as sla
from scipy.optimize import brentq

from flexlink.analysis import adiabatic
from flexlink.analysis.adiabatic import adiabatic_basis, adiabatic_monodromy, step_bounds
from flexlink.analysis.floquet import monodromy
from flexlink.errors import NumericalError

from mathieu import first_order_matrix, hill_edges

GRID = 256


def _turn(grid: int = GRID) -> np.ndarray:
    return 2.0 * np.pi * np.arange(grid + 1) / grid


def mathieu_basis(delta: float, epsilon: float, c: float = 0.0, grid: int = GRID):
    """q'' + 2 c q' + (delta + epsilon cos theta) q = 0 as A0 (A1 = A2 = 0)."""
    theta = _turn(grid)
    a0 = np.zeros((grid + 1, 2, 2))
    a0[:, 0, 1] = 1.0
    a0[:, 1, 0] = -(delta + epsilon * np.cos(theta))
    a0[:, 1, 1] = -2.0 * c
    a0_prime = np.zeros_like(a0)
    a0_prime[:, 1, 0] = epsilon * np.sin(theta)
    zero = np.zeros_like(a0)
    return adiabatic_basis(theta, a0, a0_prime, zero, zero)


def mathieu_reference(delta, epsilon, c, speed, steps=4000):
    """The same system in time t = theta / speed by the Magnus steps."""
    return monodromy(first_order_matrix(delta, epsilon, c, speed), 2.0 * np.pi / speed, steps)


def test_constant_coefficients_give_the_exact_exponential():
    # A0 constant (two coupled damped modes), A1 = A2 = 0: nothing turns the eigenbasis and
    # nothing couples the modes, the monodromy is expm(2 pi A0 / Omega) exactly, from the
    # phases Phi, the diagonal factors and the real bases alone. 1e-10: round-off of a
    # 1e2-sized exponent's exponential
    n = 2
    stiffness = np.array([[400.0, -50.0], [-50.0, 900.0]])
    damping = np.array([[0.3, 0.1], [0.1, 0.5]])
    a0 = np.block([[np.zeros((n, n)), np.eye(n)], [-stiffness, -damping]])
    grid = 64
    stack = [np.broadcast_to(m, (grid + 1, 2 * n, 2 * n)) for m in (a0, 0 * a0, 0 * a0, 0 * a0)]
    basis = adiabatic_basis(_turn(grid), *stack)
    speed = 7.0
    exact = sla.expm(2.0 * np.pi * a0 / speed)
    result = adiabatic_monodromy(basis, speed, least=16)
    assert np.abs(result.monodromy - exact).max() < 1e-10 * np.abs(exact).max()


@pytest.mark.parametrize("speed", [0.5, 1.0, 2.0])
def test_mathieu_agrees_with_the_magnus_reference_inside_and_outside_the_tongue(speed):
    # A0's frequency is 2 rad/s, so the first tongue is at speed 4; speeds 0.5 to 2 sit on
    # higher tongues and between them (growth and decay). The reference has 4000 Magnus steps
    # (error ~1e-12); 64 adiabatic steps agree to 1e-7 in ln |mu| and 1e-5 in the monodromy
    # (fourth order; measured 5e-6 at speed 0.5, where A0 turns 16 times per step's
    # wavelength of the slowest factor)
    delta, epsilon, c = 4.0, 1.2, 0.002
    reference = mathieu_reference(delta, epsilon, c, speed)
    result = adiabatic_monodromy(mathieu_basis(delta, epsilon, c), speed, least=64)
    assert result.growth_per_period == pytest.approx(reference.growth_per_period, abs=1e-7)
    assert np.abs(result.monodromy - reference.monodromy).max() < 1e-5 * np.abs(
        reference.monodromy).max()


def test_error_falls_at_fourth_order_in_the_step():
    # inside the first tongue (speed = 2 omega0, growth 0.155 per turn): halving the step
    # divides the monodromy's error by 2^4 = 16 for a fourth-order method; 10 leaves room for
    # the pre-asymptotic constant and fails a second-order one (4)
    delta, epsilon, c, speed = 100.0, 30.0, 0.1, 19.0
    basis = mathieu_basis(delta, epsilon, c, grid=1024)
    reference = mathieu_reference(delta, epsilon, c, speed, steps=20000).monodromy
    errors = [np.abs(adiabatic_monodromy(basis, speed, least=k).monodromy - reference).max()
              for k in (32, 64)]
    assert errors[0] / errors[1] > 10.0


def test_undamped_stable_multipliers_stay_on_the_unit_circle():
    # undamped (Hamiltonian) and between tongues: the multipliers are a pair on the unit
    # circle; det Phi = 1 exactly for a trace-free system. 1e-9: the method's error at 128
    # steps on this system
    result = adiabatic_monodromy(mathieu_basis(4.0, 1.0), 1.3, least=128)
    assert np.abs(np.abs(result.multipliers) - 1.0).max() < 1e-9


def test_mathieu_tongue_edges_equal_hills_determinant():
    # at speed 1 the system is the standard Mathieu equation; an edge of the first tongue is
    # where the undamped monodromy's trace passes through -2. 1e-8 in delta: the 128-step
    # error (fourth order) against Hill's determinant, which is exact to round-off
    epsilon = 0.1  # delta + epsilon cos theta stays positive: A0 underdamped at every angle

    def excess(delta):
        return -np.trace(adiabatic_monodromy(mathieu_basis(delta, epsilon), 1.0,
                                             least=128).monodromy) - 2.0
    low, high = hill_edges(epsilon)
    centre = 0.25 - epsilon**2 / 8.0
    assert brentq(excess, centre, centre - 0.6 * epsilon, xtol=1e-13) == pytest.approx(low, abs=1e-8)
    assert brentq(excess, centre, centre + 0.6 * epsilon, xtol=1e-13) == pytest.approx(high,
                                                                                  abs=1e-8)


def _turning_basis(grid: int = 1024, turn: float = 0.6, width: float = 0.05):
    """Two undamped-ish oscillators (stiffness 4 and 9, damping 0.02) whose principal axes turn
    by 2 ``turn`` [rad] within ``width`` [rad] of theta = pi (tanh): the eigenvalues stay put,
    the eigenvectors turn, so Q = -V^-1 V' is a narrow peak of height turn / width."""
    def stiffness(theta, derivative=False):
        phi = turn * np.tanh((theta - np.pi) / width)
        c, s = np.cos(phi), np.sin(phi)
        rotation = np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)
        diagonal = np.diag([4.0, 9.0])
        if not derivative:
            return rotation @ diagonal @ np.swapaxes(rotation, -1, -2)
        rate = turn / width / np.cosh((theta - np.pi) / width) ** 2
        turning = np.stack([np.stack([-s, -c], -1), np.stack([c, -s], -1)], -2)
        part = turning @ diagonal @ np.swapaxes(rotation, -1, -2)
        return rate[..., None, None] * (part + np.swapaxes(part, -1, -2))

    def first_order(k):
        a = np.zeros(k.shape[:-2] + (4, 4))
        a[..., :2, 2:] = np.eye(2)
        a[..., 2:, :2] = -k
        a[..., 2:, 2:] = -0.02 * np.eye(2)
        return a

    theta = _turn(grid)
    a0 = first_order(stiffness(theta))
    a0_prime = np.zeros_like(a0)
    a0_prime[:, 2:, :2] = -stiffness(theta, derivative=True)
    zero = np.zeros_like(a0)
    return adiabatic_basis(theta, a0, a0_prime, zero, zero), \
        lambda t: first_order(stiffness(np.asarray(t, dtype=float)))


def test_steps_crowd_where_the_coupling_peaks_and_win_there(monkeypatch):
    # the eigenvectors turn within 0.05 rad of pi: 128 equal steps (0.049 rad) do not
    # resolve the peak of Q; refined, a few steps more (10 here) halve down there alone and
    # the monodromy is 50 times closer to the reference than with the 128 equal steps
    # (measured 1.3e-5 against 7.4e-4 relative; 256 equal steps give 4.8e-5). The reference:
    # 40000 Magnus steps in time (h omega_max = 5e-4)
    basis, system = _turning_basis()
    reference = monodromy(system, 2.0 * np.pi, 40000).monodromy
    bounds = step_bounds(basis, 1.0, least=128)
    widths = np.diff(bounds)
    assert len(widths) < 160
    assert widths.max() == 8 and widths.min() < 8  # 1024 / 128 grid intervals a base step
    narrow = 0.5 * (bounds[:-1] + bounds[1:])[widths < 8] * 2.0 * np.pi / 1024
    assert np.abs(narrow - np.pi).max() < 0.3  # the halved steps sit at the peak
    refined = adiabatic_monodromy(basis, 1.0, least=128).monodromy
    monkeypatch.setattr(adiabatic, "step_bounds", lambda *args: np.arange(0, 1025, 8))
    equal = adiabatic_monodromy(basis, 1.0, least=128).monodromy
    scale = np.abs(reference).max()
    assert np.abs(refined - reference).max() < np.abs(equal - reference).max() / 20.0
    assert np.abs(refined - reference).max() < 5e-5 * scale


@pytest.mark.parametrize("least", [16, 64, 128])
def test_steps_are_dyadic_cells_covering_the_turn(least):
    # every step is a cell of the grid's dyadic hierarchy (length 2^j grid intervals, starting
    # at a multiple of it), the steps cover the turn once, there are at least `least`, and no
    # step is longer than the equal ones
    basis, _ = _turning_basis(grid=256)
    bounds = step_bounds(basis, 1.0, least=least)
    widths = np.diff(bounds)
    assert bounds[0] == 0 and bounds[-1] == 256 and np.all(widths > 0)
    assert np.all((widths & (widths - 1)) == 0) and np.all(bounds[:-1] % widths == 0)
    assert len(widths) >= least and widths.max() <= 256 // least


def test_an_overdamped_direction_is_refused_naming_its_angle():
    # q'' + 2 c q' + delta q = 0 with c^2 > delta: the eigenvalues are real, the frozen modes
    # do not oscillate, and the integrator's phases and tracking do not apply
    with pytest.raises(NumericalError, match="real eigenvalue at crank angle 0 rad: the "
                       "adiabatic integrator needs every direction underdamped"):
        mathieu_basis(0.04, 0.0, c=0.5)


def test_couplings_the_finest_cells_cannot_resolve_are_refused():
    # A2 (the part growing with the speed) couples the two Mathieu states: at 1e6 rad/s its
    # h ||Q|| on the finest cells (2 pi / 128) is far above COUPLING_STEP, where the Magnus
    # series diverges, so the step rule refuses rather than return an overflowed monodromy
    # (the map then takes the Magnus steps there)
    theta = _turn()
    a = np.zeros((GRID + 1, 2, 2))
    a[:, 0, 1], a[:, 1, 0] = 1.0, -4.0
    speed_part = np.zeros_like(a)
    speed_part[:, 1, 0] = 0.1 * np.cos(theta)
    basis = adiabatic_basis(theta, a, np.zeros_like(a), np.zeros_like(a), speed_part)
    adiabatic_monodromy(basis, 1.0, least=16)  # a moderate speed is taken
    with pytest.raises(NumericalError, match="couplings need steps shorter than the grid's"):
        adiabatic_monodromy(basis, 1e6, least=16)

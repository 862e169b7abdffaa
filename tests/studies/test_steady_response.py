"""The steady elastic response of a running linkage (``studies.steady_response``).

Each check is an independent route to the same answer: a time integration from rest run to
steady state, the quasi-static deflection under the inertia loads, the full finite-element
static solution, and the Campbell lines (k times the crank frequency on a frozen-pose
frequency).
"""
import math

import numpy as np
import pytest
import scipy.linalg as la
from conftest import CASES_DIR
from scipy.integrate import solve_ivp

from flexlink.errors import InputError
from flexlink.fe.assembly import assemble_reduced_dense, reduced_columns, reduction
from flexlink.fe.pose import pose_model
from flexlink.fe.preload import inertia_loads, static_displacement
from flexlink.kinematics.dynamics import rigid_motion
from flexlink.scene import load_scene
from flexlink.studies.operating_point import link_motion
from flexlink.studies.steady_response import (
    StrainPoint,
    forced_model,
    midspans,
    response_sweep,
    steady_response,
)
from flexlink.units import RPM

MESH = 4  # elements per link: enough for the checks, cheap for CI


@pytest.fixture(scope="module")
def case1():
    return load_scene(CASES_DIR / "case1.toml")


@pytest.fixture(scope="module")
def full(case1):
    """Case 1 at 1 element per link in all its modes (17), at 9 poses: a basis that spans
    every pose, so the reduced model is the finite-element one in other coordinates (a few
    reference modes do not represent the other poses well: docs/critical-speeds.md)."""
    return forced_model(case1, n_modes=_reduced_size(case1, 1), poses=9, elements_per_link=1)


def _rows(rows, angles, theta):
    """Samples (poses, ...) at crank angles theta by trigonometric interpolation, written
    out here: sample p sits at angles[p]."""
    N = len(angles)
    k = np.fft.fftfreq(N, 1.0 / N)
    c = np.fft.fft(rows, axis=0) / N
    return np.tensordot(np.exp(1j * np.outer(np.atleast_1d(theta) - angles[0], k)), c,
                        axes=(1, 0)).real


def test_periodic_solution_equals_a_long_time_integration(case1):
    # The same reduced equations, written out here from the model's samples, by DOP853 from
    # rest. zeta = 0.5 decays the free motion by exp(-0.5 * 2 pi 55.8 Hz * 0.15 s) ~ 4e-12
    # over 3 turns at 1200 rev/min, so the last turn is the steady state to far below 1e-6.
    # One mode keeps it cheap: in this basis the projected stiffness reaches (2460 Hz)^2 at
    # some crank angles, which sets the step of both integrators.
    model = forced_model(case1, n_modes=1, poses=9, damping_ratio=0.5, elements_per_link=MESH)
    p, speed = model.periodic, 1200 * RPM
    response = steady_response(model, speed, samples=24)
    damping = 2 * p.damping_ratio * 2 * np.pi * p.frequencies[0]
    samples = np.stack([a.reshape(len(p.angles)) for a in (
        p.mass, p.coriolis, p.stiffness, p.speed_stiffness, model.inertia_forcing,
        model.external_forcing)], axis=1)
    k = np.fft.fftfreq(len(p.angles), 1.0 / len(p.angles))
    coefficients = np.fft.fft(samples, axis=0) / len(p.angles)

    def rhs(t, x):
        m, g, k0, k2, f2, fe = (np.exp(1j * k * speed * t) @ coefficients).real
        force = speed**2 * f2 + fe - (damping + speed * g) * x[1] - (k0 + speed**2 * k2) * x[0]
        return [x[1], force / m]
    turns, period = 3, 2 * np.pi / speed
    run = solve_ivp(rhs, (0, turns * period), [0.0, 0.0], method="DOP853", rtol=1e-11,
                    atol=1e-18, dense_output=True)
    theta = response.angles - p.angles[0]
    q = run.sol((turns - 1) * period + theta / speed)[:1].T
    strain = -model.half_depth * np.einsum(
        "spn,sn->sp", _rows(model.curvature, p.angles, response.angles), q)
    error = np.abs(response.strain - strain).max() / np.abs(strain).max()
    assert error < 1e-6, error
    print(f"relative difference {error:.2e}, {run.nfev} DOP853 evaluations")


def test_low_speed_tends_to_the_quasi_static_deflection(full):
    # as Omega -> 0 the response tends to K(theta)^-1 Omega^2 f2(theta); what is left is the
    # damping's lag, of order 2 zeta Omega / omega_1, and the dynamic excess (Omega / omega_1)^2
    p = full.periodic
    gaps = []
    for rpm in (60.0, 30.0):
        speed = rpm * RPM
        r = steady_response(full, speed, samples=36)
        K = _rows(p.stiffness + speed**2 * p.speed_stiffness, p.angles, r.angles)
        f = speed**2 * _rows(full.inertia_forcing, p.angles, r.angles)
        q = np.linalg.solve(K, f[..., None])[..., 0]
        static = -full.half_depth * np.einsum("spn,sn->sp",
                                              _rows(full.curvature, p.angles, r.angles), q)
        gaps.append(np.abs(r.strain - static).max() / np.abs(static).max())
    assert gaps[0] < 0.01, gaps
    assert 1.8 < gaps[0] / gaps[1] < 4.2, gaps  # between first and second order in the speed


def _hermite_curvature(u, link, position):
    """d2v/dx2 of the cubic through the element's end values (Euler-Bernoulli), written out."""
    h = link.length / link.elements
    e = min(int(position / h), link.elements - 1)
    x = position / h - e
    c, s = math.cos(link.angle), math.sin(link.angle)
    n1, n2 = link.nodes[e], link.nodes[e + 1]
    v1, v2 = (-s * u[3 * n] + c * u[3 * n + 1] for n in (n1, n2))
    r1, r2 = u[3 * n1 + 2], u[3 * n2 + 2]
    return ((12 * x - 6) * (v1 - v2) / h**2 + (6 * x - 4) * r1 / h + (6 * x - 2) * r2 / h)


def test_forcing_and_strain_rows_match_the_full_static_solution(case1, full):
    # with every elastic mode in the basis, the modal static answer to the d'Alembert loads at
    # a pose is the full FE one; each pose is sampled exactly (no interpolation between them)
    topology = case1.topology(1)
    for p, angle in enumerate(full.periodic.angles):
        state = case1.rigid_state(angle)
        model = pose_model(topology, state.points)
        K, _ = assemble_reduced_dense(model, reduction(model))
        _, alpha, acc = link_motion(case1, model, topology,
                                    rigid_motion(case1.linkage, state, 1.0, 0.0))
        u = static_displacement(np.asarray(K), reduction(model), inertia_loads(model, acc, alpha))
        expected = np.array([_hermite_curvature(u, next(link for link in model.links
                                                         if link.name == pt.link), pt.position)
                             for pt in full.points])
        q = la.solve(full.periodic.stiffness[p], full.inertia_forcing[p])
        # the modal solve and the full one differ by round-off of a well-conditioned K
        assert full.curvature[p] @ q == pytest.approx(expected, rel=1e-7)


def _reduced_size(scene, elements):
    model = pose_model(scene.topology(elements), scene.rigid_state(None).points)
    return reduced_columns(reduction(model), model.n_dofs)[1]


@pytest.mark.slow
def test_peak_strain_resonances_sit_on_the_campbell_lines(full):
    # the second harmonic of the inertia loads meets mode 1 where 2 Omega = f_1(theta): the
    # swept peak strain of every link peaks inside mode 1's frozen-pose band over two (the
    # speed's own stiffening Omega^2 K2 included), well above the sweep's ends, and the
    # stability map is stable there (a forced resonance, not a parametric one)
    p = full.periodic
    f1 = p.frequencies[0]
    speeds = 2 * np.pi * f1 * np.linspace(0.44, 0.68, 13)
    sweep = response_sweep(full, speeds, samples=72)
    step = speeds[1] - speeds[0]
    for k in range(len(full.points)):
        i = int(np.argmax(sweep.peak_strain[:, k]))
        peak = speeds[i]
        band = [np.sqrt(la.eigh(K + peak**2 * K2, M, eigvals_only=True)[0])
                for K, K2, M in zip(p.stiffness, p.speed_stiffness, p.mass)]
        assert min(band) / 2 - step <= peak <= max(band) / 2 + step, (k, peak, band)
        assert sweep.peak_strain[i, k] > 1.3 * sweep.peak_strain[[0, -1], k].max()
    assert not sweep.unstable.any() and np.nanmax(sweep.largest_modulus) < 1.0


def test_a_point_outside_its_link_is_refused(case1):
    with pytest.raises(InputError, match="outside link 'coupler'"):
        forced_model(case1, n_modes=2, poses=3, elements_per_link=2,
                     points=(StrainPoint("coupler", 10.0),))
    with pytest.raises(InputError, match="no beam link named 'arm'"):
        forced_model(case1, n_modes=2, poses=3, elements_per_link=2,
                     points=(StrainPoint("arm", 0.0),))


def test_default_points_are_the_midspans(case1):
    points = midspans(case1)
    assert [p.link for p in points] == ["crank", "coupler", "rocker"]
    state = case1.rigid_state(None).points
    lengths = {"crank": ("O2", "A"), "coupler": ("A", "B"), "rocker": ("B", "O4")}
    for p in points:
        a, b = lengths[p.link]
        assert p.position == pytest.approx(
            np.hypot(*(np.asarray(state[b]) - np.asarray(state[a]))) / 2, rel=1e-12)

"""The stability map integrates in energy coordinates (R q, q'), R^2 the turn's mean stiffness:
a similarity, so the multipliers are those of (q, q'), with a step norm near its spectral
radius."""
import numpy as np
import pytest
from conftest import CASES_DIR, SCENES_DIR

from flexlink.analysis.floquet import monodromy
from flexlink.scene import load_scene
from flexlink.studies.running.stability_map import (
    FLOOR_POINTS,
    Integrator,
    periodic_model,
    speed_multipliers,
)
from flexlink.units import RPM


@pytest.fixture(scope="module")
def model():
    # the coarse case 1 of the convergence test: cheap, with the stiff directions of a checked
    # basis (top Ritz frequency several kHz)
    return periodic_model(load_scene(CASES_DIR / "case1.toml"), n_modes=2, poses=13,
                          elements_per_link=2)


def mass_weighted_mean_stiffness(model):
    """The turn's mean of C^-1 sym(K) C^-T, C C^T = M, at FLOOR_POINTS crank angles per pose."""
    theta = model.angles[0] + np.linspace(0.0, 2.0 * np.pi, FLOOR_POINTS * len(model.angles),
                                          endpoint=False)
    M, _, K, _ = model.matrices_at(theta)
    C = np.linalg.cholesky(M)
    weighted = np.linalg.solve(C, np.swapaxes(np.linalg.solve(C, 0.5 * (K + np.swapaxes(K, 1, 2))),
                                              1, 2))
    return weighted.mean(axis=0)


def test_energy_scale_squares_to_the_mean_stiffness(model):
    R = model.energy_scale
    mean = mass_weighted_mean_stiffness(model)
    # R is symmetric and R^2 the mean mass-weighted stiffness: round-off of an eigh on
    # entries up to omega_max^2, 1e-9 relative
    assert np.allclose(R, R.T, rtol=0, atol=1e-12 * np.abs(R).max())
    assert np.allclose(R @ R, mean, rtol=0, atol=1e-9 * np.abs(mean).max())


def test_energy_scale_is_real_where_the_mean_m_inverse_k_is_indefinite():
    # the wiper (rigid pins, stiff directions to ~57 kHz): the symmetric part of the turn's
    # mean M^-1 K has negative eigenvalues though every pose is stable, so its square root
    # would be NaN and the Magnus steps a traceback; the mass-weighted mean is positive
    # definite at every pose, and its root real
    wiper = periodic_model(load_scene(SCENES_DIR / "wiper.toml"), n_modes=6)
    mean = np.linalg.solve(wiper.mass, wiper.stiffness).mean(axis=0)
    assert np.linalg.eigvalsh(0.5 * (mean + mean.T))[0] < 0.0  # the case under test
    R = wiper.energy_scale
    assert np.all(np.isfinite(R)) and np.linalg.eigvalsh(R)[0] > 0.0


@pytest.mark.parametrize("rpm", [300.0, 2200.0])
def test_multipliers_are_those_of_the_plain_coordinates(model, rpm):
    # the same Magnus steps on S A S^-1 and on A: Phi differs by the similarity only, so the
    # monodromy (turned back) agrees to round-off amplified by the steps: 1e-9 of its size
    speed = rpm * RPM
    scaled = speed_multipliers(model, speed, integrator=Integrator.MAGNUS)
    plain_system = model.system(speed)
    size = np.abs(np.linalg.eigvals(plain_system((model.angles - model.angles[0]) / speed)))
    steps = max(200, int(np.ceil(2 * np.pi / speed * size.max() / 2.0)))
    plain = monodromy(plain_system, 2 * np.pi / speed, steps)
    scale = np.abs(plain.monodromy).max()
    assert np.allclose(scaled.monodromy, plain.monodromy, rtol=0, atol=1e-9 * scale)
    assert scaled.largest_modulus == pytest.approx(plain.largest_modulus, rel=1e-9)


def test_step_norm_is_near_the_spectral_radius(model):
    # why the coordinates: a step of h omega_max = 2 has a 1-norm of a few units in (R q, q')
    # (scaling and squaring then needs ~4 squarings), against tens in the balanced (q, q')
    speed = 1000 * RPM
    t = np.linspace(0, 2 * np.pi / speed, 64, endpoint=False)
    energy = model.system(speed, energy_coordinates=True)(t)
    radius = np.abs(np.linalg.eigvals(energy)).max()
    norm = np.abs(energy).sum(axis=-2).max()
    assert norm < 4.0 * radius

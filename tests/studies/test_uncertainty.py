"""Monte Carlo and sensitivities: reproducible from the seed, exact where a closed form exists."""


import numpy as np
import pytest

from flexlink.analysis.families import elastic_modes
from flexlink.scene import load_scene
from flexlink.studies.calibration.uncertainty import (MonteCarlo, draw_samples, monte_carlo, scene_inputs,
                                          sensitivities)

from conftest import CASES_DIR as CASES
PATHS = (str(CASES / "case2.toml"),)
# Rigid bearings, rigid drive, no joint masses: the planar frequencies then scale exactly as
# sqrt(E/rho) times the in-plane depth (the laminate thickness, the strips lying flatwise).
RIGID = {"joints.Kt": "rigid", "joints.Kr": "0 N*m/rad"}


def test_samples_reproducible_from_seed_and_spread_as_given():
    inputs = scene_inputs(PATHS[0], {}, vf_sd=0.05, thickness_sd=0.15e-3)
    a, b = draw_samples(inputs, 400, seed=7), draw_samples(inputs, 400, seed=7)
    assert a == b and a != draw_samples(inputs, 400, seed=8)
    fiber_E = np.array([s["fiber.E"] for s in a])
    # 400 normal draws: the sample sd lies within 15 % of the given spread (20 GPa)
    assert fiber_E.std() == pytest.approx(20e9, rel=0.15)


def test_monte_carlo_with_zero_spread_gives_the_scene_frequencies():
    """Zero spread: every sample is the nominal laminate; its frequencies must equal the scene's
    own (the scene builds its material from the [material.composite] table by itself, not
    through the Monte Carlo's material overrides: a second path)."""
    inputs = scene_inputs(PATHS[0], {}, vf_sd=0.0, thickness_sd=0.0)
    inputs.sd.update({k: 0.0 for k in inputs.sd})
    mc = monte_carlo(PATHS, {}, inputs, 3, seed=1, elements=3, n_jobs=1)
    scene_own = elastic_modes(load_scene(PATHS[0]), 4, 3)[0]
    # the material goes through a repr'd string once more: round-off level differences only
    np.testing.assert_allclose(mc.samples[:, 0], np.broadcast_to(scene_own, (3, 4)), rtol=1e-12)


def test_interval_is_the_central_95_percent():
    """1001 equally spaced samples 0..1000 Hz: the 2.5 % and 97.5 % points are 25 and 975 Hz
    (a 90 % interval would give 50 and 950)."""
    mc = MonteCarlo(samples=np.arange(1001.0).reshape(1001, 1, 1), seed=0)
    assert mc.low[0, 0] == pytest.approx(25.0) and mc.high[0, 0] == pytest.approx(975.0)
    assert mc.mean[0, 0] == pytest.approx(500.0)
    inside = mc.contains(np.array([[[24.0]], [[25.0]], [[975.0]], [[976.0]]]).reshape(4, 1))
    assert inside.ravel().tolist() == [False, True, True, False]


def test_sensitivities_match_the_scaling_laws():
    inputs = scene_inputs(PATHS[0], RIGID, vf_sd=0.05, thickness_sd=0.15e-3)
    s = sensitivities(PATHS, RIGID, inputs, elements=3, n_jobs=1)
    # flatwise strips (the Table II default): the thickness is the in-plane depth, EI ~ t^3 and
    # rhoA ~ t, so f ~ t and S = 1 (to round-off and the differencing error ~ step^2 = 1e-4)
    np.testing.assert_allclose(s.values["thickness"], 1.0, atol=3e-4)
    # f ~ rho^-1/2 with rho = vf rho_f + (1 - vf) rho_m: S = -1/2 vf rho_f / rho (central
    # difference error ~ step^2 = 1e-4 of the value)
    n = inputs.nominal
    rho = n["vf"] * n["fiber.density"] + (1 - n["vf"]) * n["matrix.density"]
    np.testing.assert_allclose(s.values["fiber.density"], -0.5 * n["vf"] * n["fiber.density"] / rho,
                               rtol=1e-3)
    # shear moduli do not enter the planar Euler-Bernoulli model at all
    assert np.abs(s.values["fiber.G"]).max() < 1e-9
    # flatwise, the ply stack's thickness (S = 1) outranks every material input (|S| <= 1/2)
    assert s.ranked()[0][0] == "thickness"


def test_fibre_fraction_draws_stay_inside_the_open_unit_interval():
    """A spread far larger than the mean: the draws are clipped to [0.01, 0.99] (a fraction of 0
    or 1 is not a composite), and both clips are reached."""
    inputs = scene_inputs(PATHS[0], {}, vf_sd=5.0, thickness_sd=0.0)
    vf = np.array([s["vf"] for s in draw_samples(inputs, 200, seed=2)])
    assert vf.min() == 0.01 and vf.max() == 0.99

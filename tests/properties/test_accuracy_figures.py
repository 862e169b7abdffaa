"""Every accuracy figure the tool prints, checked against the truth.

- The mesh rule's "estimated discretisation error" (``analysis.mesh``: the Richardson
  estimate |f_h - f_h/2| / (2^p - 1) / f with p = 2) against the actual relative error of the
  frequencies on the chosen mesh, measured against a mesh 8 times finer. Stated factor: the
  estimate is an upper bound (at least 0.9 x the actual error) and at most 6 x the actual
  error. Why those numbers: where the error really falls as h^2 (Timoshenko links, whose
  shear strain is constant per element) p = 2 is the true order and the estimate is the
  error itself; where it falls as h^4 (Euler-Bernoulli links, test_convergence_rate.py) the
  same formula over-estimates by (2^4 - 1) / (2^2 - 1) = 5. The reference's own error is at
  most 8^-2 = 1/64 of the actual one.
- The residuals and backward errors the solver reports, against a recomputation from K and M
  assembled here and the returned eigenpairs.
- The Monte Carlo 95 % interval (``studies.calibration.uncertainty``) against a case whose frequency
  distribution is known in closed form: only the fibre modulus scatters (normal), the joints
  are rigid or free and the drive rigid, so every stiffness is proportional to the laminate
  modulus E_lam and f = f0 sqrt(E_lam(E_f) / E_lam(E_f0)), increasing in E_f. Checked: the
  interval holds 2.5 % of the samples on each side, the samples mapped back through the law
  are standard normal, and the interval's true probability content Phi(z_high) - Phi(z_low)
  is 0.95 within sampling error.
"""

import dataclasses
import json
import math

import numpy as np
import pytest
import scipy.optimize as so
import scipy.stats as ss
from click.testing import CliRunner
from conftest import CASES_DIR
from hypothesis import given
from strategies import cantilever_toml, linkages, load, write_scene

from flexlink.analysis.mesh import ORDER, mesh_for_tolerance
from flexlink.analysis.modal import analyze
from flexlink.cli import main
from flexlink.fe.assembly import assemble, rigid_elimination
from flexlink.materials.mixtures import load_constituent, woven_composite
from flexlink.scene import load_scene
from flexlink.studies.calibration.uncertainty import Inputs, evaluate, monte_carlo, scene_inputs

N_MODES = 3
REFINE = 8  # the reference mesh: 8 x the chosen one
TOL = 1e-4  # the mesh rule's tolerance here: meshes of 16 to 64 elements per link
LOW, HIGH = 0.9, 6.0  # the stated factor (module docstring)

CANTILEVERS = {
    "euler-bernoulli slender cantilever": cantilever_toml(0.5, 0.3, 200e9, 77e9, 7800.0,
                                                          0.01, 0.004, "euler-bernoulli"),
    "timoshenko stubby cantilever": cantilever_toml(0.5, -1.0, 200e9, 77e9, 7800.0, 0.08,
                                                    0.01, "timoshenko"),
}


def actual_error(scene, elements, n=N_MODES) -> float:
    f = analyze(scene, n, elements).elastic_frequencies(n)
    ref = analyze(scene, n, REFINE * elements).elastic_frequencies(n)
    return float(np.max(np.abs(f - ref) / ref))


@pytest.mark.parametrize("name", sorted(CANTILEVERS))
def test_the_printed_discretisation_error_bounds_the_actual_one(name, tmp_path):
    """End to end: the figure ``flexlink modes`` prints, against the truth."""
    path = write_scene(CANTILEVERS[name])
    result = CliRunner().invoke(main, ["modes", str(path), "-n", str(N_MODES), "--tol",
                                       str(TOL), "--json", "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    mesh = json.loads(result.output)["cases"][0]["mesh"]
    assert mesh["richardson_order"] == ORDER
    estimate = mesh["estimated_relative_error"]
    assert estimate <= TOL
    actual = actual_error(load_scene(path), mesh["elements_per_link"])
    assert LOW * actual <= estimate <= HIGH * actual, (estimate, actual)


@pytest.mark.parametrize("beam", ["euler-bernoulli", "timoshenko"])
def test_the_mesh_rule_estimate_bounds_the_actual_error_of_a_composite_four_bar(beam):
    scene = load_scene(CASES_DIR / "case1.toml", overrides={"model.beam": beam})
    rule = mesh_for_tolerance(scene, N_MODES, TOL)
    actual = actual_error(scene, rule.elements)
    assert LOW * actual <= rule.estimate <= HIGH * actual, (rule, actual)


def _reduced(result):
    K, M = assemble(result.model)
    T = rigid_elimination(result.model)
    if T is None:
        return K.toarray(), M.toarray(), result.modes.shapes
    counts = np.asarray(T.sum(axis=0)).ravel()  # T merges DOFs with entries 1
    Q = (T.T @ result.modes.shapes) / counts[:, None]
    np.testing.assert_allclose(T @ Q, result.modes.shapes, atol=1e-12 * np.abs(Q).max())
    return (T.T @ K @ T).toarray(), (T.T @ M @ T).toarray(), Q


@given(linkages())
def test_reported_residuals_and_backward_errors_match_a_recomputation(spec):
    result = analyze(load(spec), N_MODES)
    modes = result.modes
    K, M, Q = _reduced(result)
    lam = modes.eigenvalues
    R = np.linalg.norm(K @ Q - (M @ Q) * lam, axis=0)
    def norm1(A):  # the matrix 1-norm: largest column sum
        return np.abs(A).sum(axis=0).max()

    backward = R / ((norm1(K) + np.abs(lam) * norm1(M)) * np.linalg.norm(Q, axis=0))
    residual = R / np.linalg.norm(K @ Q, axis=0)
    # The figures are round-off (backward errors 1e-20 to 1e-16): recomputed in another
    # order they differ by a small factor, measured at most 5 over 40 scenes x 7 modes;
    # 30 allows for that and still catches a missing norm or a mode paired with another's.
    assert np.all(np.abs(np.log10(backward / modes.backward_errors)) < math.log10(30)), (
        backward, modes.backward_errors)
    elastic = modes.elastic
    assert np.all(np.abs(np.log10(residual[elastic] / modes.residuals[elastic]))
                  < math.log10(30)), (residual, modes.residuals)
    # and what they claim: the pairs solve the model to round-off
    assert backward.max() < 1e-14


SCENE = """name = "composite four-bar"
[linkage]
type = "four-bar"
ground = "300 mm"
R2 = 0.267
R3 = 0.8
R4 = 0.667
[pose]
transmission_angle = "90 deg"
[material.composite]
fiber = "carbon_fiber"
matrix = "polyester"
fiber_volume_fraction = 0.5
[section]
bending = "flatwise"
width = "20 mm"
thickness = "1.5 mm"
[joints]
Kt = "rigid"
Kr = "0 N*m/rad"
[drive]
link = "crank"
joint = "O2"
stiffness = "rigid"
"""
SAMPLES, SEED, ELEMENTS = 250, 11, 1


def test_the_monte_carlo_interval_has_its_stated_coverage():
    path = write_scene(SCENE)
    given = scene_inputs(path, {}, 0.0, 0.0)
    sd = {name: 0.0 for name in given.sd}
    sd["fiber.E"] = given.sd["fiber.E"]  # Table I: 201 +- 20 GPa
    inputs = Inputs(given.nominal, sd, given.fiber_name, given.matrix_name)
    mean_E, sd_E = given.nominal["fiber.E"], sd["fiber.E"]
    fiber, matrix = load_constituent("carbon_fiber"), load_constituent("polyester")

    def laminate(E_f):
        return woven_composite(dataclasses.replace(fiber, E=E_f), matrix, 0.5).E

    f0 = evaluate([path], {}, inputs, dict(given.nominal), 1, ELEMENTS)[0, 0]

    def law(E_f):  # the closed form of f [Hz] at fibre modulus E_f [Pa]
        return f0 * math.sqrt(laminate(E_f) / laminate(mean_E))

    # the law holds where it matters: at the exact 2.5 and 97.5 % points of E_f
    z = ss.norm.ppf(0.975)
    for E_f in (mean_E - z * sd_E, mean_E + z * sd_E):
        values = {**given.nominal, "fiber.E": E_f}
        computed = evaluate([path], {}, inputs, values, 1, ELEMENTS)[0, 0]
        assert math.isclose(computed, law(E_f), rel_tol=1e-9)

    mc = monte_carlo([path], {}, inputs, SAMPLES, SEED, n_modes=1, elements=ELEMENTS, n_jobs=1)
    assert not np.isnan(mc.samples).any()
    low, high = float(mc.low[0, 0]), float(mc.high[0, 0])

    def probability_below(f):  # P(frequency <= f), through the inverse of the increasing law
        E_f = so.brentq(lambda e: law(e) - f, mean_E - 8 * sd_E, mean_E + 8 * sd_E, xtol=1e-3)
        return ss.norm.cdf((E_f - mean_E) / sd_E)

    # 1. The interval is the 2.5 and 97.5 % points of the samples drawn: so many samples lie
    # beyond each end (to one sample, whatever the interpolation between order statistics).
    drawn = mc.samples[:, 0, 0]
    for end, level in ((low, 0.025), (high, 0.975)):
        assert np.mean(drawn < end) <= level + 1 / SAMPLES, (end, level)
        assert np.mean(drawn <= end) >= level - 1 / SAMPLES, (end, level)
    # 2. The samples follow the known distribution: mapped back through the law they are
    # standard normal. Kolmogorov-Smirnov for the shape, and the mean and variance on their
    # own (the t and chi-square laws), which see a wrong spread far sooner; each p-value
    # below 1e-3 would be a 1-in-1000 accident.
    u = np.array([probability_below(f) for f in drawn])
    assert ss.kstest(u, "uniform").pvalue > 1e-3
    z = ss.norm.ppf(u)
    assert ss.ttest_1samp(z, 0.0).pvalue > 1e-3
    chi2 = (SAMPLES - 1) * z.var(ddof=1)
    dist = ss.chi2(SAMPLES - 1)
    assert 2 * min(dist.cdf(chi2), dist.sf(chi2)) > 1e-3, z.std(ddof=1)
    # 3. Hence the interval's true probability content: binomial sampling of the empirical
    # quantiles from SAMPLES draws, 3 standard deviations.
    below, above = probability_below(low), 1 - probability_below(high)
    tail_sd = math.sqrt(0.025 * 0.975 / SAMPLES)
    content_sd = math.sqrt(0.95 * 0.05 / SAMPLES)
    assert abs(below - 0.025) < 3 * tail_sd, below
    assert abs(above - 0.025) < 3 * tail_sd, above
    assert abs((1 - below - above) - 0.95) < 3 * content_sd, (below, above)
    # the mean against the law's expectation (Gauss-Hermite; the law is smooth, so 16 nodes
    # are exact to far below the sampling error)
    x, w = np.polynomial.hermite_e.hermegauss(16)  # nodes within 6.6 sd: E_f > 0
    expected = sum(wi * law(mean_E + xi * sd_E) for xi, wi in zip(x, w)) / math.sqrt(2 * math.pi)
    spread = f0 * 0.5 * sd_E / mean_E  # first-order sd of f
    assert abs(float(mc.mean[0, 0]) - expected) < 4 * spread / math.sqrt(SAMPLES)

"""The damping of the periodic equations at speed (``studies.periodic_damping``): the scene's
declared damping reaches the stability map and the steady response, one ratio per basis
vector; a ratio given on the command line overrides it; the default only where the scene
declares nothing."""
import numpy as np
import pytest
from click.testing import CliRunner
from conftest import CASES_DIR

from flexlink.analysis.damping import damping_ratios
from flexlink.analysis.modal import analyze
from flexlink.cli import main
from flexlink.output.running.stability_map import stability_document, stability_lines
from flexlink.output.running.steady_response import response_document, response_lines
from flexlink.scene import load_scene
from flexlink.analysis.damping import DEFAULT_DAMPING_RATIO
from flexlink.analysis.periodic import periodic_model
from flexlink.studies.running.stability_map import stability_map
from flexlink.studies.running.steady_response import forced_model, steady_response
from flexlink.units import RPM

CASE = CASES_DIR / "case1.toml"
SMALL = dict(n_modes=2, poses=13, elements_per_link=2)  # cheap; identities, not converged numbers
SPEEDS = np.array([1500.0, 2500.0]) * RPM


@pytest.fixture(scope="module")
def given():
    return forced_model(load_scene(CASE), damping_ratio=0.05, **SMALL)


def test_declared_ratio_gives_the_map_and_response_of_the_same_given_ratio(given):
    # [damping] ratio = 0.05 and --damping-ratio 0.05 build the same equations: the same
    # multipliers and strains to round-off (two builds of one model: 1e-12); the default 0.01
    # gives others (so the check sees whether the ratio reaches the equations at all)
    declared = forced_model(load_scene(CASE, {"damping.ratio": 0.05}), **SMALL)
    default = forced_model(load_scene(CASE), **SMALL)
    size = len(declared.periodic.frequencies)  # 9 modal vectors and the loads' static answers
    assert np.array_equal(declared.periodic.damping_ratio, np.full(size, 0.05))  # as given
    assert "[damping]" in declared.periodic.damping_source
    assert "--damping-ratio" in given.periodic.damping_source
    maps = [stability_map(m.periodic.stability, SPEEDS).largest_modulus
            for m in (declared, given, default)]
    np.testing.assert_allclose(maps[0], maps[1], rtol=1e-12, atol=0)
    assert not np.allclose(maps[0], maps[2], rtol=1e-3)
    responses = [steady_response(m, SPEEDS[0], samples=12) for m in (declared, given, default)]
    np.testing.assert_allclose(responses[0].strain, responses[1].strain, rtol=0,
                               atol=1e-12 * np.abs(responses[0].strain).max())
    assert not np.allclose(responses[0].strain, responses[2].strain, rtol=1e-3)
    # the response's JSON and text say where the ratios came from
    document = response_document("case 1", responses[0], declared)
    assert document["damping_source"] == declared.periodic.damping_source
    assert document["damping_ratio"] == [0.05] * size
    assert any("[damping]" in line for line in response_lines(document))


def test_given_ratio_overrides_the_declared_one():
    scene = load_scene(CASE, {"damping.ratio": 0.05})
    model = periodic_model(scene, damping_ratio=0.02, **SMALL)
    assert np.array_equal(model.damping_ratio, np.full(len(model.frequencies), 0.02))  # given


def test_rayleigh_coefficients_give_each_basis_vector_its_ratio():
    # zeta_i = alpha / (2 w_i) + beta w_i / 2 over the basis vectors' Ritz frequencies at the
    # scene's pose; at that pose M = I and C = diag(2 zeta_i w_i), which is the damping block
    # of the first-order matrix A at t = 0 (at a speed so small that the Coriolis term,
    # speed * G1, is below round-off of it)
    alpha, beta = 2.0, 2e-6
    model = periodic_model(load_scene(CASE, {"damping.rayleigh_alpha": alpha,
                                             "damping.rayleigh_beta": beta}), **SMALL)
    w = 2 * np.pi * model.frequencies
    zeta = alpha / (2 * w) + beta * w / 2
    assert np.allclose(model.damping_ratio, zeta, rtol=1e-14, atol=0)
    assert "Rayleigh" in model.damping_source
    n = len(w)
    block = model.system(1e-12)(np.zeros(1))[0, n:, n:]
    # M is the identity at the scene's pose to 1e-12 (its Ritz vectors are mass normalised)
    assert np.allclose(-np.diag(block), alpha + beta * w**2, rtol=1e-9, atol=0)


def test_written_loss_factors_weight_each_vector_by_its_strain_energy():
    # one material and rigid pins: all strain energy sits in the links, so every basis
    # vector gets eta / 2 to round-off (37 poses: 19 do not resolve the rigid pins' matrices
    # over the turn, and the model is refused)
    rigid = periodic_model(load_scene(CASE, {"material.loss_factor": 0.004, "joints.Kt": "rigid"}),
                           n_modes=2, poses=37, elements_per_link=2)
    assert np.allclose(rigid.damping_ratio, 0.002, rtol=1e-12, atol=0)
    # compliant pins hold energy without loss: the lowest vectors, which the basis check
    # matches to the scene pose's lowest modes, get those modes' ratios (the ones `modes`
    # gives); the shapes differ by the basis' small error (measured 1.5e-5 and 7e-5)
    scene = load_scene(CASE, {"material.loss_factor": 0.004})
    model = periodic_model(scene, **SMALL)
    result = analyze(scene, 2, SMALL["elements_per_link"])
    modes = damping_ratios(result.model, result.modes.shapes[:, result.modes.elastic[:2]],
                           scene.loss_factors)
    assert np.all(modes < 0.002)
    assert np.allclose(model.damping_ratio[:2], modes, rtol=1e-3, atol=0)
    assert "loss factors" in model.damping_source


def test_default_only_where_the_scene_declares_nothing(given):
    # case 1 writes no loss factor (its composite's is assumed) and no [damping] table
    model = periodic_model(load_scene(CASE), **SMALL)
    assert np.array_equal(model.damping_ratio, np.full(len(model.frequencies),  # as set
                                                       DEFAULT_DAMPING_RATIO))
    assert model.damping_source.startswith("default 0.01")
    document = stability_document("case 1", stability_map(given.periodic, SPEEDS[:1]),
                                  given.periodic)
    assert document["damping_source"] == given.periodic.damping_source
    assert document["damping_ratio"] == [0.05] * len(given.periodic.frequencies)
    assert any("--damping-ratio 0.05" in line for line in stability_lines(document))


@pytest.mark.parametrize("command", ["stability-map", "response"])
@pytest.mark.parametrize("damping, field", [("ratio = 1.2", "damping.ratio"),
                                            ("ratio = -0.1", "damping.ratio"),
                                            ("ratios = [0.01, 1.0]", "damping.ratios")])
def test_declared_damping_out_of_range_is_one_line(tmp_path, command, damping, field):
    scene = tmp_path / "declared.toml"
    scene.write_text(f'base = "{CASE.as_posix()}"\n[damping]\n{damping}\n')
    args = [command, str(scene), "--out", str(tmp_path / "out")]
    if command == "stability-map":
        args += ["--speeds", "100:200 rev/min"]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 2, result.output
    line = result.output.strip()
    assert "\n" not in line and "declared.toml" in line and field in line and "[0, 1)" in line

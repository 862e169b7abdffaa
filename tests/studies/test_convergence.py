"""Mesh convergence: the energy form of K, lumped mass, the observed order, the error floor, the
mesh rule and the converge command."""

import dataclasses
import json

import numpy as np
import pytest
from click.testing import CliRunner

from flexlink import analyze, load_scene
from flexlink.analysis.eigensolver import EigenSolver
from flexlink.analysis.mesh import SPARSE_SOLVER as SPARSE
from flexlink.studies.verification import convergence as cv
from flexlink.fe.assembly import assemble
from flexlink.cli import main
from flexlink.fe.energy import lumped_mass, twice_strain_energy
from flexlink.fe.model import build_model

from conftest import ROOT
CASE1 = ROOT / "cases" / "case1.toml"


@pytest.fixture(scope="module")
def scene():
    # edgewise strips (stubby in the plane): the axial P1 error then leads, which the order
    # test below relies on; flatwise (the Table II default) the bending h^4 error still
    # dominates at these meshes
    return load_scene(CASE1, overrides={"section.bending": "edgewise"})


def model_of(scene, elements):
    return build_model(scene.topology(elements), scene.rigid_pose().joints)


def test_energy_form_equals_assembled_stiffness(scene):
    # Random (rough) fields: no cancellation, so u^T K u from the matrix is exact to round-off.
    model = model_of(scene, 6)
    K, _ = assemble(model)
    U = np.random.default_rng(1).standard_normal((model.n_dofs, 5))
    expected = np.einsum("ij,ij->j", U, K @ U)
    assert np.allclose(twice_strain_energy(model, U), expected, rtol=1e-12, atol=0)


def test_lumped_mass_keeps_link_mass_and_is_diagonal(scene):
    model = model_of(scene, 7)
    M = lumped_mass(model)
    total = sum(l.section.mass_per_length * l.length for l in model.links)
    d = M.diagonal()
    assert M.nnz == model.n_dofs
    assert d[0::3].sum() == pytest.approx(total, rel=1e-14)
    assert np.array_equal(d[0::3], d[1::3])  # same in x and y: invariant under rotation


def test_refined_frequencies_do_not_depend_on_the_solver(scene):
    # 128 elements/link: K's entries are 1e8 times a smooth mode's energy scale, so the raw
    # eigenvalues of the two solvers differ by ~1e-9; the energy quotients agree to ~1e-13.
    dense = analyze(scene, 4, 128, EigenSolver("dense")).elastic_frequencies(4)
    sparse = analyze(scene, 4, 128, SPARSE).elastic_frequencies(4)
    assert np.max(np.abs(dense - sparse) / dense) < 1e-11


def test_observed_order_is_two_and_four_without_axial_strain(scene):
    levels = [cv.run_level(scene, cv.CHOICES[0], e, 4, 1) for e in (64, 128, 256)]
    # mode 2 is mostly bending: its h^4 share fades slowly (observed 2.19 here, 2.05 one level on)
    assert np.all(np.abs(cv.richardson(levels).observed - 2) < 0.25)
    # Links 1e4 times stiffer axially (same EI and mass per length): the P1 axial error goes
    # away and the Hermite bending order 4 shows.
    stiff = tuple(dataclasses.replace(link, section=dataclasses.replace(
        link.section, area=link.section.area * 1e4, density=link.section.density / 1e4))
        for link in scene.links)
    axially_rigid = dataclasses.replace(scene, links=stiff)
    levels = [cv.run_level(axially_rigid, cv.CHOICES[0], e, 4, 1) for e in (4, 8, 16)]
    assert np.all(np.abs(cv.richardson(levels).observed - 4) < 0.1)


def test_discretisation_error_reaches_1e_minus_8(scene):
    levels = [cv.run_level(scene, cv.CHOICES[0], e, 4, 1) for e in (64, 128, 256, 512)]
    ex = cv.richardson(levels)
    assert ex.asymptotic, ex.observed
    # an independent reference from the coarser three levels agrees far below the errors shown
    other = cv.richardson(levels[:3])
    assert np.max(np.abs(other.reference - ex.reference) / ex.reference) < 1e-10
    errors = cv.relative_errors(levels, ex.reference)
    # 512 elements/link: modes 1-3 at 3e-10 .. 3e-9, mode 4 at 1.1e-8 (measured 2026-11-22)
    assert np.sort(errors[-1])[:3].max() < 1e-8 and errors[-1].max() < 2e-8
    # from 128 elements/link on, the error falls by 2^p = 4 per halving, as the order used says
    assert np.all(np.abs(errors[1:-1] / errors[2:] - 4) < 0.15)


def test_mesh_rule_meets_its_tolerance(scene):
    tol = 1e-5
    rule = cv.mesh_for_tolerance(scene, 4, tol)
    # the true error against a mesh 16 times finer than needed (its own error is ~1e-9 here,
    # test_discretisation_error_reaches_1e_minus_8), not against the rule's own estimate
    fine = analyze(scene, 4, 512, SPARSE).elastic_frequencies(4)
    def true_error(elements):
        return np.max(np.abs(analyze(scene, 4, elements, SPARSE).elastic_frequencies(4) - fine)
                      / fine)
    assert true_error(rule.elements) <= tol
    # and the rule does not over-refine: half its mesh misses the tolerance
    assert true_error(rule.elements // 2) > tol


def test_converge_command(tmp_path):
    result = CliRunner().invoke(main, ["converge", str(CASE1), "--max-elements", "8",
                                       "--repeats", "1", "--tol", "1e-3", "--json",
                                       "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert doc["reference"]["order_used"] == 2
    assert doc["reference"]["levels"] == [2, 4, 8]
    assert all(r["runs"] == 1 for r in doc["levels"])
    choices = {r["choice"] for r in doc["levels"]}
    assert {"sparse/consistent", "dense/consistent", "sparse/lumped"} <= choices
    # the cheapest setting's frequencies really are within 1e-3 of a fine independent analysis
    best = doc["cheapest"]
    fine = analyze(load_scene(CASE1), 4, 256, SPARSE).elastic_frequencies(4)
    [level] = [r for r in doc["levels"] if r["choice"] == best["choice"]
               and r["elements_per_link"] == best["elements_per_link"]]
    assert np.max(np.abs(np.array(level["frequencies_Hz"]) - fine) / fine) <= 1e-3
    assert len(doc["model_error"]["error_pct"]) == 4
    assert (tmp_path / "case1" / "converge.png").read_bytes()[:4] == b"\x89PNG"
    assert json.loads((tmp_path / "case1" / "converge.json").read_text()) == doc


def test_modes_states_its_mesh_rule(tmp_path):
    result = CliRunner().invoke(main, ["modes", str(CASE1), "--tol", "1e-6", "--json",
                                       "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    case = json.loads(result.stdout)["cases"][0]
    assert case["mesh"]["rule"] == "tolerance" and case["mesh"]["tolerance"] == 1e-6
    # the frequencies printed meet the tolerance against a fine independent analysis
    fine = analyze(load_scene(CASE1), 4, 512, SPARSE).elastic_frequencies(4)
    computed = np.array([m["computed_Hz"] for m in case["modes"]])
    assert np.max(np.abs(computed - fine) / fine) <= 1e-6

"""The out-of-plane family's dense path (``outofplane.out_of_plane_modes`` on small models)
against the sparse path it replaces for them: per-link CSR assembly (``np.kron`` rotations,
``block_diag``), T^T K T in scipy.sparse, the same ``solve_modes`` checks.

The two paths share only the element closed forms (``strip_element_matrices``); rotation,
placement and reduction are computed independently, so the reduced matrices agree to
summation-order round-off (1e-14 of the largest entry is a few hundred eps) and the
frequencies to 1e-9 relative, the brief's bound.
"""

import dataclasses
import functools

import numpy as np
import pytest

from flexlink.analysis.eigensolver import AUTO_DENSE_MAX, EigenSolver
from flexlink.analysis import outofplane
from flexlink.analysis import solve as sv
from flexlink.fe.assembly import rigid_elimination
from flexlink.fe.model import Section
from flexlink.fe.strip import (StripProperties, assemble_out_of_plane,
                               assemble_out_of_plane_reduced_dense, out_of_plane_eigen_scale,
                               strip_element_matrices)
from flexlink.scene import load_scene

from conftest import ROOT
SCENES = [ROOT / "cases" / f"case{i}.toml" for i in (1, 2, 3, 4)] + [ROOT / "scenes" / "wiper.toml"]
EPS = np.finfo(float).eps
TILTS = {"rigid Ktilt": {}, "finite Ktilt": {"joints.Ktilt": "5 N*m/rad"}}


def joint_masses(path) -> dict[str, str]:
    """0.02 kg on every joint of the scene at ``path``."""
    return {f"joints.{j.name}.mass": "0.02 kg" for j in load_scene(path).joints}


def scene_model(path, elements, overrides):
    scene = load_scene(path, overrides=overrides)
    return outofplane.out_of_plane_model(scene.topology(elements), scene.rigid_pose().joints,
                                         outofplane.tilt_stiffnesses(scene))


def sparse_path(path, elements, overrides, n_modes):
    """What ``out_of_plane_modes`` did before the dense path: sparse K, M reduced by T in
    scipy.sparse, solved densely."""
    model, _ = scene_model(path, elements, overrides)
    K, M = assemble_out_of_plane(model, model.springs)
    solve = functools.partial(sv.solve_modes, K, M, T=rigid_elimination(model),
                              lambda_ref=out_of_plane_eigen_scale(model), solver=EigenSolver("dense"))
    return sv.require_elastic(sv.lowest_elastic(solve, n_modes), n_modes)


@pytest.mark.parametrize("path", SCENES, ids=lambda p: p.stem)
@pytest.mark.parametrize("elements", [2, 6, 12])
@pytest.mark.parametrize("tilt", TILTS.values(), ids=TILTS.keys())
@pytest.mark.parametrize("masses", [False, True], ids=["", "joint masses"])
def test_dense_path_equals_the_sparse_path(path, elements, tilt, masses, monkeypatch):
    overrides = {**tilt, **(joint_masses(path) if masses else {})}
    old = sparse_path(path, elements, overrides, 6)
    monkeypatch.setattr(outofplane, "assemble_out_of_plane", None)  # must not assemble sparse K
    new = outofplane.analyze_out_of_plane(load_scene(path, overrides=overrides), 6, elements)
    assert new.kinds == old.kinds and new.n_dofs == old.n_dofs <= AUTO_DENSE_MAX
    np.testing.assert_allclose(new.frequencies, old.frequencies, rtol=1e-9, atol=0)
    # the same mass-normalised shapes, up to sign, on every full DOF (modes 1 to 6 are distinct)
    elastic = [i for i, kind in enumerate(new.kinds) if kind == sv.ELASTIC]
    a, b = new.shapes[:, elastic], old.shapes[:, elastic]
    signs = np.sign(np.einsum("ij,ij->j", a, b))
    np.testing.assert_allclose(a * signs, b, atol=1e-7 * np.abs(b).max())
    assert new.backward_errors.max() <= 1e-10 and new.orthogonality_error <= 1e-6


def test_the_cases_cover_a_model_without_constraints_and_masses():
    """The finite-Ktilt cases have no rigid spring at all (T is None) and the mass overrides
    reach the out-of-plane model, so both branches of the scatter are exercised."""
    model, _ = scene_model(SCENES[0], 6, {**TILTS["finite Ktilt"], **joint_masses(SCENES[0])})
    assert rigid_elimination(model) is None and len(model.point_masses) == 4
    wiper, _ = scene_model(SCENES[4], 6, joint_masses(SCENES[4]))
    assert rigid_elimination(wiper) is not None and wiper.point_masses


def test_large_models_keep_the_sparse_path(monkeypatch):
    monkeypatch.setattr(outofplane, "assemble_out_of_plane_reduced_dense", None)
    modes = outofplane.analyze_out_of_plane(load_scene(SCENES[1]), 4, 96)
    assert modes.n_dofs > AUTO_DENSE_MAX and modes.solver == "sparse"


@pytest.mark.parametrize("path", SCENES, ids=lambda p: p.stem)
@pytest.mark.parametrize("tilt", TILTS.values(), ids=TILTS.keys())
def test_dense_reduced_matrices_equal_the_sparse_reduction(path, tilt):
    model, strips = scene_model(path, 6, {**tilt, **joint_masses(path)})
    K, M = assemble_out_of_plane(model, model.springs)
    T = rigid_elimination(model)
    Kd, Md = assemble_out_of_plane_reduced_dense(model, model.springs, T, strips)
    for dense, sparse in ((Kd, K), (Md, M)):
        reduced = (sparse if T is None else T.T @ sparse @ T).toarray()
        np.testing.assert_allclose(dense, reduced, rtol=0, atol=1e-14 * abs(dense).max())


def textbook_element(l: float, p: StripProperties):
    """The module docstring's closed forms in Python floats, (w1, w1', w2, w2') and (tx1, tx2)."""
    kb = p.EI / l**3 * np.array([[12, 6 * l, -12, 6 * l], [6 * l, 4 * l * l, -6 * l, 2 * l * l],
                                 [-12, -6 * l, 12, -6 * l], [6 * l, 2 * l * l, -6 * l, 4 * l * l]])
    mb = p.rhoA * l / 420 * np.array(
        [[156, 22 * l, 54, -13 * l], [22 * l, 4 * l * l, 13 * l, -3 * l * l],
         [54, 13 * l, 156, -22 * l], [-13 * l, -3 * l * l, -22 * l, 4 * l * l]])
    kt = p.GJ / l * np.array([[1.0, -1.0], [-1.0, 1.0]])
    mt = p.rhoIp * l / 6 * np.array([[2.0, 1.0], [1.0, 2.0]])
    return kb, mb, kt, mt


def test_element_matrices_of_many_lengths_round_as_the_textbook_form():
    """Every entry within 8 eps of the textbook form: each side is a product of at most four
    correctly rounded operations and one libm power (each within eps of exact), evaluated in
    another order, so they may differ by a few units in the last place on another CPU or
    libm, and by no more; a wrong coefficient or power of l is off by far more."""
    lengths = np.geomspace(1e-4, 10.0, 301)
    p = StripProperties.of(Section.rectangle(E=70e9, G=26e9, density=2700.0, width=0.02,
                                             thickness=0.002))
    many = StripProperties(*(np.full(lengths.shape, getattr(p, f.name))
                             for f in dataclasses.fields(p)))
    K, M = strip_element_matrices(lengths, many)
    bend, twist, slope = np.ix_([0, 2, 3, 5], [0, 2, 3, 5]), np.ix_([1, 4], [1, 4]), [1, 3]
    for l, k, m in zip(lengths, K, M):
        kb, mb, kt, mt = textbook_element(float(l), p)
        for part in (kb, mb):  # w' = -ty
            part[slope, :] *= -1
            part[:, slope] *= -1
        for ours, textbook in ((k[bend], kb), (m[bend], mb), (k[twist], kt), (m[twist], mt)):
            np.testing.assert_allclose(ours, textbook, rtol=8 * EPS, atol=0)

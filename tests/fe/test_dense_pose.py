"""The single-pose dense fast path (``modal.pose_modes`` on small models) against the sparse path
it replaces: COO -> CSR assembly, T^T K T in scipy.sparse, the same ``solve_modes`` checks.

Both paths hand the same dense eigen solver the same reduced matrices up to summation order, so
the energy-refined frequencies agree to round-off; 1e-9 relative is the brief's bound.
"""

import functools

import numpy as np
import pytest
import scipy.sparse as sp

from flexlink.analysis.eigensolver import AUTO_DENSE_MAX, EigenSolver
from flexlink.analysis import modal
from flexlink.analysis import solve as sv
from flexlink.errors import NumericalError
from flexlink.fe.assembly import assemble, assemble_reduced_dense, rigid_elimination
from flexlink.fe.energy import twice_strain_energy
from flexlink.fe.model_at_pose import in_plane_eigen_scale, pose_model
from flexlink.scene import load_scene

from conftest import ROOT
SCENES = [ROOT / "cases" / f"case{i}.toml" for i in (1, 2, 3, 4)] + [ROOT / "scenes" / "wiper.toml"]


def sparse_path(topology, points, n_modes):
    """What ``pose_modes`` did before the fast path: sparse K, M reduced by T in scipy.sparse."""
    model = pose_model(topology, points)
    K, M = assemble(model)
    solve = functools.partial(sv.solve_modes, K, M, T=rigid_elimination(model),
                              lambda_ref=in_plane_eigen_scale(model), solver=EigenSolver("dense"),
                              energy=lambda shapes: twice_strain_energy(model, shapes))
    return sv.require_elastic(sv.lowest_elastic(solve, n_modes), n_modes)


@pytest.mark.parametrize("path", SCENES, ids=lambda p: p.stem)
@pytest.mark.parametrize("elements", [2, 6, 12])
def test_dense_fast_path_equals_the_sparse_path(path, elements, monkeypatch):
    scene = load_scene(path)
    topology = scene.topology(elements)
    joints = scene.rigid_pose().joints
    old = sparse_path(topology, joints, 6)
    monkeypatch.setattr(modal, "assemble", None)  # the fast path must not assemble sparse K
    _, new, _ = modal.pose_modes(topology, joints, 6)
    assert isinstance(new, sv.ModalResult) and new.kinds == old.kinds
    assert new.n_dofs == old.n_dofs <= AUTO_DENSE_MAX and new.refined
    np.testing.assert_allclose(new.frequencies, old.frequencies, rtol=1e-9, atol=0)
    assert new.shapes.shape == old.shapes.shape
    # the same mass-normalised shapes, up to sign, on every full DOF
    signs = np.sign(np.einsum("ij,ij->j", new.shapes, old.shapes))
    np.testing.assert_allclose(new.shapes * signs, old.shapes, atol=1e-7 * np.abs(old.shapes).max())
    assert new.backward_errors.max() <= 1e-10 and new.orthogonality_error <= 1e-6


def test_large_models_keep_the_sparse_path(monkeypatch):
    scene = load_scene(SCENES[1])
    topology = scene.topology(64)  # 585 DOFs > AUTO_DENSE_MAX
    monkeypatch.setattr(modal, "assemble_reduced_dense", None)
    _, modes, _ = modal.pose_modes(topology, scene.rigid_pose().joints, 4)
    assert modes.n_dofs > AUTO_DENSE_MAX and modes.solver == "sparse"


JOINT_MASSES = {f"joints.{j}.mass": "0.02 kg" for j in ("O2", "A", "B", "O4")}
SPRINGS = {"joints.Kt": "1e6 N/m", "joints.Kr": "2 N*m/rad"}


@pytest.mark.parametrize("overrides", [JOINT_MASSES, SPRINGS], ids=["joint masses", "springs"])
def test_fast_path_with_joint_masses_and_finite_springs(overrides):
    scene = load_scene(SCENES[1], overrides=overrides)
    topology = scene.topology(6)
    joints = scene.rigid_pose().joints
    model = pose_model(topology, joints)
    assert model.point_masses if overrides is JOINT_MASSES else np.isfinite(model.springs.stiffness).any()
    old = sparse_path(topology, joints, 6)
    _, new, _ = modal.pose_modes(topology, joints, 6)
    np.testing.assert_allclose(new.frequencies, old.frequencies, rtol=1e-9, atol=0)


@pytest.mark.parametrize("path", [SCENES[4], SCENES[1]], ids=lambda p: p.stem)
def test_dense_reduced_matrices_equal_the_sparse_reduction(path):
    scene = load_scene(path, overrides=JOINT_MASSES if path == SCENES[1] else None)
    model = pose_model(scene.topology(6), scene.rigid_pose().joints)
    K, M = assemble(model)
    T = rigid_elimination(model)
    Kd, Md = assemble_reduced_dense(model, T)
    for dense, sparse in ((Kd, T.T @ K @ T), (Md, T.T @ M @ T)):
        np.testing.assert_allclose(dense, sparse.toarray(), rtol=0, atol=1e-14 * abs(dense).max())


# two unit masses on springs 1 and 4 to ground, a massless DOF tied to the first by a spring 1
K3 = np.array([[2.0, 0.0, -1.0], [0.0, 4.0, 0.0], [-1.0, 0.0, 1.0]])
M3 = np.diag([1.0, 1.0, 0.0])


def test_dense_massless_condensation_equals_the_sparse_one():
    dense, sparse = sv.prepare(K3, M3), sv.prepare(sp.csr_matrix(K3), sp.csr_matrix(M3))
    assert isinstance(dense.Ks, np.ndarray) and dense.n_solved == sparse.n_solved == 2
    np.testing.assert_allclose(dense.Ks, sparse.Ks.toarray(), atol=1e-15)
    np.testing.assert_allclose(dense.Ms, sparse.Ms.toarray(), atol=1e-15)
    np.testing.assert_allclose(dense.expand(np.eye(2)), sparse.expand(np.eye(2)), atol=1e-15)
    result = sv.solve_modes(K3, M3, 2, lambda_ref=1.0, solver=EigenSolver("dense"))
    np.testing.assert_allclose(result.eigenvalues, [1.0, 4.0], rtol=1e-14)
    assert result.condensed == 1


@pytest.mark.parametrize("as_matrix", [np.asarray, sp.csr_matrix], ids=["dense", "sparse"])
def test_a_dof_without_mass_or_stiffness_is_refused(as_matrix):
    K = K3.copy()
    K[2, :] = K[:, 2] = 0.0  # the massless DOF is now free
    K[0, 0] = 1.0
    with pytest.raises(NumericalError, match="neither mass nor stiffness"):
        sv.prepare(as_matrix(K), as_matrix(M3))

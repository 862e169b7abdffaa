"""The fast assembly paths give the same matrices as the textbook construction, to round-off.

Reference: each link's K, M rotated with the explicit T^T k T (T = blockdiag(R), built with
sp.kron), placed block-diagonally, springs added term by term, then reduced with T^T K T.
Tolerances: 1e-14 of the largest entry, i.e. a few dozen ulps of summation-order round-off.
"""

import math

import numpy as np
import pytest
import scipy.sparse as sp

from flexlink.analysis.eigensolver import EigenSolver
from flexlink.analysis.modal import analyze
from flexlink.fe.assembly import assemble, node_rotation, rigid_elimination, rotated_entries
from flexlink.fe.link import link_matrices
from flexlink.fe.model import GROUND, build_model
from flexlink.scene import load_scene
from flexlink.analysis.sweep import _DensePlan, modal_sweep, parallel_modal_sweep

from conftest import CASES_DIR as CASES
ROUND_OFF = 1e-14


def reference_matrices(model):
    k_blocks, m_blocks = [], []
    for link in model.links:
        k, m = link.local_matrices()
        T = sp.kron(sp.identity(link.elements + 1), sp.csr_matrix(node_rotation(link.angle)))
        k_blocks.append(T.T @ k @ T)
        m_blocks.append(T.T @ m @ T)
    K = sp.block_diag(k_blocks).toarray()
    M = sp.block_diag(m_blocks).toarray()
    for a, b, k in zip(model.springs.dof_a, model.springs.dof_b, model.springs.stiffness):
        if not math.isfinite(k):
            continue
        K[a, a] += k
        if b != GROUND:
            K[b, b] += k
            K[a, b] -= k
            K[b, a] -= k
    for node, mass in model.point_masses:
        M[3 * node, 3 * node] += mass
        M[3 * node + 1, 3 * node + 1] += mass
    return K, M


def close(A, B):
    return np.abs(A - B).max() <= ROUND_OFF * np.abs(B).max()


SCENES = [
    ("case1.toml", {}),
    ("case3.toml", {"joints.Kr": "5 N*m/rad"}),
    ("case2.toml", {"joints.Kt": "rigid", "drive.stiffness": "0 N*m/rad"}),  # pins merged
]


@pytest.mark.parametrize("name, overrides", SCENES)
def test_assemble_and_sweep_plan_match_reference(name, overrides):
    scene = load_scene(CASES / name, overrides=overrides)
    topology = scene.topology(5)
    plan = None
    for theta in np.radians([3.0, 97.0, 181.0, 275.0]):
        model = build_model(topology, scene.rigid_pose(theta).joints)
        K_ref, M_ref = reference_matrices(model)
        K, M = assemble(model)
        assert close(K.toarray(), K_ref) and close(M.toarray(), M_ref)
        T = rigid_elimination(model)
        plan = plan or _DensePlan(model, rigid_elimination(model))
        K_plan, M_plan = plan.matrices(model)
        T = sp.identity(model.n_dofs) if T is None else T
        assert close(K_plan, (T.T @ K_ref @ T)) and close(M_plan, (T.T @ M_ref @ T))


@pytest.mark.parametrize("elements", [1, 16, 64])
def test_link_matrices_equal_closed_form_at_any_mesh(elements):
    # Textbook element (link.py docstring), assembled by hand; the tiled element keeps round-off
    # at any mesh (a whole-chain scikit-fem mesh drifted to 2e-10 at 64 elements).
    L, EA, EI, rhoA = 0.4173, 5e6, 12.0, 0.3
    l = L / elements
    kb = EI / l**3 * np.array([[12, 6 * l, -12, 6 * l], [6 * l, 4 * l * l, -6 * l, 2 * l * l],
                               [-12, -6 * l, 12, -6 * l], [6 * l, 2 * l * l, -6 * l, 4 * l * l]])
    mb = rhoA * l / 420 * np.array([[156, 22 * l, 54, -13 * l], [22 * l, 4 * l * l, 13 * l, -3 * l * l],
                                    [54, 13 * l, 156, -22 * l], [-13 * l, -3 * l * l, -22 * l, 4 * l * l]])
    n = 3 * (elements + 1)
    K_ref, M_ref = np.zeros((n, n)), np.zeros((n, n))
    for e in range(elements):
        bend, axial = [3 * e + 1, 3 * e + 2, 3 * e + 4, 3 * e + 5], [3 * e, 3 * e + 3]
        K_ref[np.ix_(bend, bend)] += kb
        M_ref[np.ix_(bend, bend)] += mb
        K_ref[np.ix_(axial, axial)] += EA / l * np.array([[1, -1], [-1, 1]])
        M_ref[np.ix_(axial, axial)] += rhoA * l / 6 * np.array([[2, 1], [1, 2]])
    K, M = link_matrices(L, elements, EA, EI, rhoA)
    assert close(K.toarray(), K_ref) and close(M.toarray(), M_ref)


def test_sweep_finds_elastic_modes_past_a_mechanism():
    # no drive: the four-bar keeps its one mechanism mode, which must not take an elastic slot
    scene = load_scene(CASES / "case2.toml", overrides={"drive.stiffness": "0 N*m/rad"})
    sweep = modal_sweep(scene.topology(6), [scene.rigid_pose().joints] * 2, 4)
    single = analyze(scene, 4, 6).elastic_frequencies(4)
    # the sweep's raw eigenvalues against analyze's energy quotients: round-off only, 9e-12
    # measured with the flatwise strips (their stiffness spread is wider than edgewise)
    np.testing.assert_allclose(sweep.frequencies[0], single, rtol=1e-10)
    assert list(sweep.mechanism_counts) == [1, 1]


def test_rotated_entries_equal_explicit_transformation():
    k = sp.coo_matrix(link_matrices(0.3, 4, 5e6, 12.0, 0.3)[0])
    for angle in (0.3, 2.0, -2.9):
        c, s = np.full(k.nnz, np.cos(angle)), np.full(k.nnz, np.sin(angle))
        rows, cols, values = rotated_entries(k.row, k.col, k.data[None], c, s)
        rotated = sp.coo_matrix((values[0], (rows, cols)), shape=k.shape)
        T = sp.kron(sp.identity(5), sp.csr_matrix(node_rotation(angle)))
        assert close(rotated.toarray(), (T.T @ k @ T).toarray())


def test_parallel_sweep_equals_serial():
    scene = load_scene(CASES / "case4.toml")
    poses = [scene.rigid_pose(t).joints for t in np.radians([5.0, 95.0, 185.0, 275.0, 300.0])]
    serial = modal_sweep(scene.topology(4), poses, 3)
    parallel = parallel_modal_sweep(scene.topology(4), poses, 3, n_jobs=2)
    # worker processes solve the same eigenproblems; their BLAS may sum in another order
    # (thread count, alignment), so round-off of a dense eigen solve: 1e-12 relative
    np.testing.assert_allclose(parallel.frequencies, serial.frequencies, rtol=1e-12, atol=0)
    np.testing.assert_array_equal(parallel.mechanism_counts, serial.mechanism_counts)


def test_sweep_takes_the_sparse_path_above_the_dense_limit(monkeypatch):
    import flexlink.analysis.sweep as sweep

    def no_plan(*args):
        raise AssertionError("a dense plan was built for a model above the dense limit")

    scene = load_scene(CASES / "case1.toml")
    poses = [scene.rigid_pose().joints]
    dense = modal_sweep(scene.topology(8), poses, 4)
    monkeypatch.setattr(sweep, "_DensePlan", no_plan)
    sparse = modal_sweep(scene.topology(8), poses, 4, EigenSolver(dense_max=50))
    # ARPACK vs LAPACK: 3e-13 measured edgewise, 2.7e-11 with the flatwise strips (wider stiffness spread)
    np.testing.assert_allclose(sparse.frequencies, dense.frequencies, rtol=1e-10)

"""The Craig-Bampton sweep against the full FE model: Table II cases and a general scene at the
default converged mesh, rigid-body invariance, a free crank (mechanism mode), exactness with
every mode kept, full shapes from the reduced coordinates, and one link reduction per mesh
size shared by links of any length and section.

Tolerance 1e-6 relative on the first 6 modes: the mesh rule (convergence.DEFAULT_TOL) already
accepts a 1e-6 discretisation error, so the reduction may not add more than that. Measured over
576 poses of the four cycles at 128 elements/link (every 10th, four offsets): at most 3.2e-8
with CUTOFF 3, which is the full model's own round-off at that mesh (mode 1 of case 2); without
the truncation correction's eigenvector updates the same basis is off by up to 5e-6, so these
tests can fail."""

import dataclasses
import functools
import math

import numpy as np
import pytest
import scipy.linalg as la

from flexlink.analysis.eigensolver import EigenSolver
from flexlink.fe.assembly import assemble, rigid_elimination
from flexlink.fe.craig_bampton import SERIES, CraigBamptonPlan, _families, reduce_link
from flexlink.analysis.solve import solve_modes
from flexlink.analysis.stacked import stacked_modes
from flexlink.studies.cycle.modal_map import kinematic_cycle
from flexlink.fe.link import link_matrices
from flexlink.fe.model import build_model, layout
from flexlink.scene import load_scene
from flexlink.analysis import sweep
from flexlink.analysis.sweep import modal_sweep
from flexlink.fe import truncation

from conftest import ROOT
CASES = [ROOT / "cases" / f"case{i}.toml" for i in (1, 2, 3, 4)]
TOL = 1e-6
CONVERGED = 64  # elements/link the mesh rule picks for the Table II cases at 1e-6 (bench.py)


def cycle_poses(scene, count):
    return [scene.rigid_pose(t).joints
            for t in np.radians(np.arange(count) * 360.0 / count + 0.5)]


def max_difference(topology, poses, n_modes=6):
    full = modal_sweep(topology, poses, n_modes).frequencies
    reduced = modal_sweep(topology, poses, n_modes, reduction="craig-bampton").frequencies
    assert np.isfinite(full).all() and np.isfinite(reduced).all()
    return float(np.max(np.abs(reduced - full) / full))


@pytest.mark.parametrize("path", CASES, ids=lambda p: p.stem)
def test_table2_cases_match_full_model_at_converged_mesh(path):
    scene = load_scene(path)
    assert max_difference(scene.topology(CONVERGED), cycle_poses(scene, 3)) <= TOL


def test_general_scene_matches_full_model():
    scene = load_scene(ROOT / "scenes" / "wiper.toml")
    states = kinematic_cycle(scene, 4).states
    assert max_difference(scene.topology(32), [s.points for s in states]) <= TOL


def test_rotating_the_whole_linkage_changes_nothing():
    scene = load_scene(CASES[1])
    topology = scene.topology(16)
    points = cycle_poses(scene, 1)[0]
    c, s = math.cos(0.7), math.sin(0.7)
    turned = {k: (c * x - s * y + 0.3, s * x + c * y - 1.1) for k, (x, y) in points.items()}
    a, b = (modal_sweep(topology, [p], 6, reduction="craig-bampton").frequencies
            for p in (points, turned))
    np.testing.assert_allclose(a, b, rtol=1e-10)


def test_free_crank_keeps_its_mechanism_mode():
    scene = load_scene(CASES[0])
    free = dataclasses.replace(scene.topology(16), drive=None)  # Kr = 0 at every joint
    poses = cycle_poses(scene, 2)
    result = modal_sweep(free, poses, 4, reduction="craig-bampton")
    assert (result.mechanism_counts == 1).all()
    full = modal_sweep(free, poses, 4)
    np.testing.assert_array_equal(full.mechanism_counts, result.mechanism_counts)
    np.testing.assert_allclose(result.frequencies, full.frequencies, rtol=TOL)


def test_every_mode_kept_is_the_full_link_and_length_scaling_is_exact():
    args = (0.8, 6, 2.0e6, 15.0, 0.4)
    K, M = (A.toarray() for A in link_matrices(*args))
    whole = reduce_link(*args, lambda_cut=math.inf)
    assert whole.n_modes == K.shape[0] - 6
    free = lambda A, B: np.sort(np.linalg.eigvals(np.linalg.solve(B, A)).real)[3:]  # noqa: E731
    np.testing.assert_allclose(free(whole.K, whole.M), free(K, M), rtol=1e-9)
    # a reduction made at 0.8 m, rescaled to 1.1 m, has the 1.1 m link's spectrum (the modal
    # coordinates are scaled differently from a reduction made at 1.1 m, so compare spectra)
    K11, M11 = (A.toarray() for A in link_matrices(1.1, *args[1:]))
    np.testing.assert_allclose(free(*whole.matrices(1.1)), free(K11, M11), rtol=1e-9)


def test_links_of_another_length_reuse_the_first_poses_reduction():
    # the plan is built at the first pose; a linkage scaled by 1.3 has every link 1.3 x longer,
    # so its matrices and truncated-mode series come from the length rescaling alone
    scene = load_scene(CASES[1])
    topology = scene.topology(CONVERGED)
    points = cycle_poses(scene, 1)[0]
    poses = [points, {k: (1.3 * x, 1.3 * y) for k, (x, y) in points.items()}]
    assert max_difference(topology, poses) <= TOL


def test_shapes_from_reduced_coordinates_satisfy_the_full_model():
    scene = load_scene(CASES[2])
    topology = scene.topology(8)
    points = cycle_poses(scene, 1)[0]
    model = build_model(topology, points)
    plan = CraigBamptonPlan(model, layout(topology), math.inf)  # every mode: exact
    K, M = plan.matrices(model)
    modes = solve_modes(K, M, 4, lambda_ref=1.0, solver=EigenSolver("dense"))
    shapes = plan.shapes(model, modes.shapes)
    Kf, Mf = assemble(model)
    T = rigid_elimination(model)
    q = np.linalg.lstsq(T.toarray(), shapes, rcond=None)[0]
    assert np.allclose(T @ q, shapes, atol=1e-12 * np.abs(shapes).max())  # obeys rigid joints
    Kr, Mr = (T.T @ Kf @ T).toarray(), (T.T @ Mf @ T).toarray()
    residual = Kr @ q - Mr @ q * modes.eigenvalues
    assert np.abs(residual).max() <= 1e-8 * np.abs(Kr @ q).max()


def test_eigenvector_updates_make_the_small_basis_accurate(monkeypatch):
    # at CUTOFF 3 the Rayleigh functional of the reduced pencil's own vectors is off by about
    # 1e-6 (second order in their error); the updates bring it to the full model's round-off
    scene = load_scene(CASES[3])
    topology, poses = scene.topology(CONVERGED), cycle_poses(scene, 3)
    assert max_difference(topology, poses) <= 1e-8
    monkeypatch.setattr(sweep, "corrected", functools.partial(truncation.corrected, updates=0))
    assert max_difference(topology, poses) > 5e-7


def test_one_eigenvector_update_from_the_reduced_mode_reaches_round_off(monkeypatch):
    # at 16 elements/link: off by 2.4e-6 with no update and 4e-11 after one, since the update
    # starts from the reduced pencil's own mode (a = e_i) and puts back the first-order
    # correction; from 2 e_i it would put back twice that and leave 4e-8 (measured)
    scene = load_scene(CASES[3])
    topology, poses = scene.topology(16), cycle_poses(scene, 3)
    monkeypatch.setattr(sweep, "corrected", functools.partial(truncation.corrected, updates=1))
    assert max_difference(topology, poses) <= 1e-9


def test_rescaled_links_match_the_full_model_to_round_off():
    # the truncated modes' series at another length comes from the reference one by the
    # scaling of truncation.py; at 16 elements/link the reduction then agrees with the full
    # model to 2e-10, and a wrong power of the length ratio in a series term shows as 1e-6
    scene = load_scene(CASES[1])
    topology = scene.topology(16)
    points = cycle_poses(scene, 4)
    poses = [points[0]] + [{k: (f * x, f * y) for k, (x, y) in p.items()}
                           for f in (1.3, 0.8) for p in points]
    assert max_difference(topology, poses) <= 1e-8


def test_unconverged_correction_is_solved_on_a_larger_basis(monkeypatch):
    # with no change accepted, every pose climbs to a basis so large that the updates leave
    # its eigenvalues bit for bit (or to the complete basis, with nothing to correct)
    scene = load_scene(CASES[1])
    topology, poses = scene.topology(8), cycle_poses(scene, 3)
    sizes = []
    plan = sweep.CraigBamptonPlan

    def spy(*args):
        built = plan(*args)
        sizes.append(built.n)
        return built
    monkeypatch.setattr(sweep, "CraigBamptonPlan", spy)
    max_difference(topology, poses)
    usual = sizes[-1]
    monkeypatch.setattr(sweep, "CONVERGED", 0.0)
    assert max_difference(topology, poses) <= 1e-9
    assert sizes[-1] > usual


def test_chunks_change_nothing(monkeypatch):
    scene = load_scene(CASES[0])
    topology, poses = scene.topology(16), cycle_poses(scene, 12)
    whole = modal_sweep(topology, poses, 6, reduction="craig-bampton").frequencies
    monkeypatch.setattr(sweep, "CHUNK", 5)
    chunked = modal_sweep(topology, poses, 6, reduction="craig-bampton").frequencies
    np.testing.assert_array_equal(chunked, whole)


def test_mass_factor_whitens_the_plans_mass_matrices():
    # the structured factor (boundary-size Cholesky) must do what M's own Cholesky factor does
    scene = load_scene(CASES[1])
    topology = scene.topology(16)
    points = cycle_poses(scene, 4)
    poses = points + [{k: (1.3 * x, 1.3 * y) for k, (x, y) in points[1].items()}]
    plan = CraigBamptonPlan(build_model(topology, points[0]), layout(topology), 1e9)
    K, M = plan.stacked(*sweep.pose_geometry(topology, poses))
    factor = plan.mass_factor(M)
    whitened = factor @ M @ factor.transpose(0, 2, 1)
    np.testing.assert_allclose(whitened, np.broadcast_to(np.eye(plan.n), whitened.shape),
                               atol=1e-12)
    ones = np.ones(len(poses))
    fast = stacked_modes(K, M, ones, checked=10, factor=factor)
    plain = stacked_modes(K, M, ones, checked=10)
    # the two standard forms agree to the round-off of a dense solve (a few 100 eps lambda_max)
    difference = np.abs(fast.eigenvalues - plain.eigenvalues)
    assert (difference <= 1e-12 * plain.eigenvalues[:, -1:]).all()


def direct_reduction(length, elements, EA, EI, rhoA, lambda_cut):
    """``reduce_link``'s (K, M, basis, flexibility) made plainly from this link's own matrices:
    T^T K T, each family's interior modes from an eigen solve at this length and section, the
    truncated modes' series summed mode by mode."""
    K, M = (A.toarray() for A in link_matrices(length, elements, EA, EI, rhoA))
    local = np.arange(K.shape[0])
    end = np.isin(local // 3, (0, elements))
    boundary = local[end]
    static = np.eye(len(local))[:, boundary]
    for members in (local % 3 == 0, local % 3 != 0):
        b, i = local[members & end], local[members & ~end]
        static[np.ix_(i, np.searchsorted(boundary, b))] = -la.solve(K[np.ix_(i, i)],
                                                                    K[np.ix_(i, b)])
    columns, flexibility = [static], np.zeros((SERIES, 6, 6))
    for members in (local % 3 == 0, local % 3 != 0):
        i = local[members & ~end]
        lam, phi = la.eigh(K[np.ix_(i, i)], M[np.ix_(i, i)])
        modes = np.zeros((len(local), len(i)))
        modes[i] = phi
        kept = np.searchsorted(lam, lambda_cut, side="right")
        columns.append(modes[:, :kept])
        c = static.T @ M @ modes[:, kept:]
        flexibility += np.einsum("ak,bk,jk->jab", c, c,
                                 lam[kept:] ** -(np.arange(SERIES)[:, None] + 1.0))
    T = np.hstack(columns)
    return T.T @ K @ T, T.T @ M @ T, T, flexibility


def test_links_share_one_scaled_reduction_per_mesh():
    # every link of 16 elements is reduced from one unit chain, scaled; the result must be the
    # reduction made at the link's own length and section. Measured: within 5e-13 of it (the
    # round-off of two 16-element eigen solves); a wrong power of the element length or of
    # k / m in a scale factor is off by factors of h ~ 0.02 or more, so 1e-11 can fail
    _families.cache_clear()
    for length in (0.8, 0.35):
        args = (length, 16, 2.0e6, 15.0, 0.4)
        reduced = reduce_link(*args, lambda_cut=3e8)
        assert 0 < reduced.n_modes < 3 * 15
        K, M, T, F = direct_reduction(*args, lambda_cut=3e8)
        sign = np.sign(np.einsum("ik,ik->k", T, reduced.basis))  # each mode's sign is free
        for ours, plain in ((sign[:, None] * reduced.K * sign, K),
                            (sign[:, None] * reduced.M * sign, M),
                            (reduced.basis * sign, T), *zip(reduced.flexibility, F)):
            assert np.abs(ours - plain).max() <= 1e-11 * np.abs(plain).max()
    assert _families.cache_info().currsize == 1

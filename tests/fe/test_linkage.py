"""The four-bar models of the shipped scenes: invariants and limits."""

import dataclasses
import math

import numpy as np
import pytest

from flexlink.analysis.eigensolver import EigenSolver
from flexlink.analysis.modal import analyze
from flexlink.fe.model_at_pose import in_plane_eigen_scale
from flexlink.fe.assembly import assemble, rigid_elimination
from flexlink.fe.model import build_model
from flexlink.scene import load_scene
from flexlink.analysis.solve import solve_modes

from conftest import CASES_DIR as CASES


@pytest.fixture(scope="module")
def case1():
    return load_scene(CASES / "case1.toml")


def solve(topology, points, n=6, method="dense"):
    model = build_model(topology, points)
    K, M = assemble(model)
    return solve_modes(K, M, n, T=rigid_elimination(model), lambda_ref=in_plane_eigen_scale(model), solver=EigenSolver(method))


def test_matrices_symmetric(case1):
    pose = case1.rigid_pose()
    K, M = assemble(build_model(case1.topology(6), pose.joints))
    for A in (K, M):
        assert abs(A - A.T).max() <= 1e-12 * abs(A).max()


def test_rotating_the_whole_model_leaves_frequencies_unchanged(case1):
    pose = case1.rigid_pose()
    angle = 1.0471975 * 0.77  # arbitrary
    c, s = math.cos(angle), math.sin(angle)
    rotated = {k: (c * x - s * y + 0.123, s * x + c * y - 0.456) for k, (x, y) in pose.joints.items()}
    base = solve(case1.topology(8), pose.joints)
    turned = solve(case1.topology(8), rotated)
    np.testing.assert_allclose(turned.frequencies, base.frequencies, rtol=1e-9)


def with_joint_stiffness(scene, Kt, Kr=None):
    joints = tuple(dataclasses.replace(j, Kt=Kt, Kr=j.Kr if Kr is None else Kr) for j in scene.joints)
    return dataclasses.replace(scene, joints=joints)


def test_stiff_springs_approach_rigid_joints_from_below(case1):
    pose = case1.rigid_pose()
    rigid = solve(with_joint_stiffness(case1, math.inf).topology(8), pose.joints).elastic_frequencies[:4]
    previous = np.zeros(4)
    for Kt in (1e4, 1e6, 1e8, 1e10):
        f = solve(with_joint_stiffness(case1, Kt).topology(8), pose.joints).elastic_frequencies[:4]
        assert np.all(f > previous) and np.all(f < rigid * (1 + 1e-12))
        previous = f
    # penalty 1e10 N/m against exact constraints: within 1e-4 relative
    np.testing.assert_allclose(previous, rigid, rtol=1e-4)


def test_free_crank_gives_one_mechanism_mode(case1):
    """No drive and no torsional springs: the linkage has one degree of freedom, so exactly one
    zero mode, labelled as a mechanism mode and never paired with a measurement."""
    free = dataclasses.replace(case1, drive=None)
    result = analyze(free, n_modes=4, elements_per_link=8)
    assert result.modes.kinds.count("rigid-body/mechanism") == 1
    assert result.modes.kinds[0] == "rigid-body/mechanism"
    assert len(result.elastic_frequencies(4)) == 4
    assert result.elastic_frequencies(1)[0] > 1.0


@pytest.mark.parametrize("name", ["case1", "case2", "case3", "case4"])
def test_shipped_cases_give_checked_elastic_modes(name):
    result = analyze(load_scene(CASES / f"{name}.toml"), n_modes=4)
    f = result.elastic_frequencies(4)
    assert len(f) == 4 and np.all(np.diff(f) > 0)
    assert result.modes.kinds.count("elastic") == len(result.modes.kinds)  # drive holds the crank
    assert result.modes.backward_errors.max() < 1e-12
    assert result.modes.orthogonality_error < 1e-8
    assert math.isclose(math.degrees(result.pose.mu), 90.0, abs_tol=1e-9)


def test_dense_and_sparse_agree_on_a_case(case1):
    a = analyze(case1, 6, 32, solver=EigenSolver("dense")).modes.frequencies
    b = analyze(case1, 6, 32, solver=EigenSolver("sparse")).modes.frequencies
    np.testing.assert_allclose(a, b, rtol=1e-8)

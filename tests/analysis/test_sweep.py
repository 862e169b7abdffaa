"""modal_sweep agrees with the one-pose pipeline and respects mirror symmetry."""

import math

import numpy as np

from flexlink.analysis.modal import analyze
from flexlink.scene import load_scene
from flexlink.analysis.sweep import modal_sweep

from conftest import CASES_DIR as CASES


def test_sweep_matches_single_pose_analysis():
    scene = load_scene(CASES / "case2.toml")
    theta = scene.four_bar.crank_angles_for_mu(math.pi / 2)
    poses = [scene.four_bar.pose(t, "open").joints for t in theta]
    sweep = modal_sweep(scene.topology(8), poses, 4)
    single = analyze(scene, 4, 8).elastic_frequencies(4)
    # raw eigenvalues against energy quotients: round-off, 4.3e-12 measured (flatwise strips)
    np.testing.assert_allclose(sweep.frequencies[0], single, rtol=1e-10)
    # theta2 and 360 deg - theta2 on the other branch are mirror images: same spectrum
    mirrored = modal_sweep(scene.topology(8), [scene.four_bar.pose(theta[1], "crossed").joints], 4)
    np.testing.assert_allclose(mirrored.frequencies[0], single, rtol=1e-9)
    assert not sweep.mechanism_counts.any()


def _case1_poses(count):
    scene = load_scene(CASES / "case1.toml")
    return scene, [scene.rigid_pose(t).joints for t in np.radians(np.arange(count) * 90.0 + 0.5)]


def test_craig_bampton_counts_the_mechanism_of_an_undriven_four_bar():
    # without its drive a four-bar moves: one mechanism mode at every pose, below the elastic
    # ones; the reduction must find it and the same elastic spectrum as the full model, within
    # its tolerance of 1e-6 (tests/fe/test_craig_bampton.py)
    import dataclasses

    scene, poses = _case1_poses(3)
    topology = dataclasses.replace(scene.topology(8), drive=None)
    full = modal_sweep(topology, poses, 3)
    reduced = modal_sweep(topology, poses, 3, reduction="craig-bampton")
    np.testing.assert_array_equal(full.mechanism_counts, [1, 1, 1])
    np.testing.assert_array_equal(reduced.mechanism_counts, full.mechanism_counts)
    np.testing.assert_allclose(reduced.frequencies, full.frequencies, rtol=1e-6)


def test_a_sweep_reports_its_stiff_springs_once(caplog):
    # springs far stiffer than any element are made rigid, and said so at the first pose only
    import dataclasses

    scene, poses = _case1_poses(3)
    topology = scene.topology(4)
    stiff = dataclasses.replace(topology, joints=tuple(dataclasses.replace(j, Kt=1e20)
                                                       for j in topology.joints))
    with caplog.at_level("WARNING"):
        modal_sweep(stiff, poses, 2)
    assert sum("treated as rigid" in r.getMessage() for r in caplog.records) == 1


def test_a_parallel_sweep_of_no_poses_is_empty():
    from flexlink.analysis.sweep import parallel_modal_sweep

    scene, _ = _case1_poses(1)
    result = parallel_modal_sweep(scene.topology(4), [], 3, n_jobs=1)
    assert result.frequencies.shape == (0, 3) and result.mechanism_counts.shape == (0,)
    assert result.note is None

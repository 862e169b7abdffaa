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

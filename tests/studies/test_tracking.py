"""MAC (analysis/mac.py) and modes tracked by shape through a sequence of poses
(studies/cycle/tracking.py)."""

import numpy as np
import pytest
import scipy.linalg as la

from flexlink.analysis.mac import (compare_models, link_frame, link_frame_mass, mac_matrix,
                                   pair_modes)
from flexlink.analysis.modal import pose_modes
from flexlink.scene import load_scene
from flexlink.studies.cycle.tracking import track, tracked_map


def _case1_modes(elements, n=5, crank=None):
    scene = load_scene("cases/case1.toml")
    topology = scene.topology(elements)
    model, modes, _ = pose_modes(topology, scene.rigid_pose(crank).joints, n)
    return model, modes.shapes[:, modes.elastic[:n]]


def test_mac_of_a_mass_orthonormal_set_with_itself_is_the_identity():
    model, shapes = _case1_modes(8)
    local = link_frame(model, shapes)
    W = link_frame_mass(model)
    assert np.allclose(mac_matrix(local, local, W), np.eye(shapes.shape[1]), atol=1e-10)
    # the link frame is a rotation per node: the same MAC as with the global mass
    from flexlink.fe.assembly import assemble
    assert np.allclose(mac_matrix(shapes, shapes, assemble(model)[1]), np.eye(shapes.shape[1]),
                       atol=1e-10)


def test_mac_ignores_sign_and_scale_and_pairing_finds_a_permutation():
    rng = np.random.default_rng(1)
    A = rng.standard_normal((30, 4))
    B = -3.0 * A[:, [2, 0, 3, 1]]
    mac = mac_matrix(A, B)
    pairs = pair_modes(mac)
    assert list(pairs.b) == [1, 3, 0, 2]
    assert np.allclose(pairs.mac, 1.0)


def test_meshes_compared_at_stations_pair_mode_by_mode():
    coarse, fine = _case1_modes(8), _case1_modes(32)
    mac = compare_models(*coarse, *fine)
    pairs = pair_modes(mac)
    assert list(pairs.b) == list(range(5))
    assert pairs.mac.min() > 0.99  # the same physical modes, two meshes


def _two_dof(coupling, t):
    """K(t) = [[1 + t, c], [c, 2 - t]], M = I: the diagonal stiffnesses cross at t = 0.5."""
    freqs, shapes = [], []
    for s in t:
        vals, vecs = la.eigh([[1 + s, coupling], [coupling, 2 - s]])
        freqs.append(np.sqrt(vals) / (2 * np.pi))
        shapes.append(vecs)
    return np.array(freqs), shapes


def test_a_tracked_line_follows_its_shape_through_a_crossing():
    t = np.linspace(0, 1, 41)
    freqs, shapes = _two_dof(0.0, t)
    tracks = track(freqs, shapes, 2)
    e1 = np.array([[1.0], [0.0]])
    # line 1 starts as the lowest mode, x1 alone, and stays x1 past the crossing at t = 0.5
    assert all(mac_matrix(e1, s[:, [0]])[0, 0] > 1 - 1e-12 for s in tracks.shapes)
    assert np.allclose(tracks.frequencies[:, 0], np.sqrt(1 + t) / (2 * np.pi))
    assert [(e.kind, e.lines) for e in tracks.events] == [("crossing", (1, 2))]
    # between the two poses around t = 0.5 (the grid has t = 0.5 itself: the gap is zero there)
    assert t[tracks.events[0].pose - 1] <= 0.5 < t[tracks.events[0].pose]


def test_a_tracked_line_follows_one_shape_through_a_veering():
    t = np.linspace(0, 1, 41)
    c = 0.02
    freqs, shapes = _two_dof(c, t)
    tracks = track(freqs, shapes, 2)
    # the shape turns continuously from x1 to x2: the line stays on it (MAC to the previous
    # pose near 1 at every step) and so stays on the lower branch, whose closest approach is
    # the hand value: lambda = 1.5 -+ c at t = 0.5
    assert tracks.mac[1:].min() > 0.5
    assert np.allclose(tracks.frequencies[:, 0], freqs[:, 0])
    [event] = tracks.events
    assert event.kind == "veering" and event.lines == (1, 2)
    assert t[event.pose] == pytest.approx(0.5)
    assert event.gap == pytest.approx(np.sqrt((1.5 + c) / (1.5 - c)) - 1, rel=1e-9)


def test_cycle_lines_are_continuous_shapes():
    scene = load_scene("cases/case1.toml")
    result = tracked_map(scene, n_poses=36, n_modes=3, elements_per_link=8)
    assert result.frequencies.shape == (36, 3)
    assert np.isfinite(result.frequencies).all()
    assert result.tracks.mac[1:].min() > 0.5


def test_close_frequencies_without_a_shape_change_are_no_veering():
    t = np.linspace(0, 1, 41)
    freqs = np.sqrt(np.stack([1.45 - 0.2 * (t - 0.5)**2, 1.55 + 0.2 * (t - 0.5)**2], 1)) / (2 * np.pi)
    shapes = [np.eye(2)] * len(t)  # uncoupled: each mode keeps its shape, 3.4 % apart at t = 0.5
    assert track(freqs, shapes, 2).events == ()


def test_mac_command_pairs_two_meshes_of_one_scene(tmp_path):
    import json

    from click.testing import CliRunner

    from flexlink.cli import main

    result = CliRunner().invoke(main, ["mac", "cases/case1.toml", "cases/case1.toml", "-e", "8",
                                       "--elements-b", "16", "-n", "3", "--json", "--out",
                                       str(tmp_path)])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)  # stderr carries the run's warnings
    assert [(p["a"], p["b"]) for p in doc["pairs"]] == [(1, 1), (2, 2), (3, 3)]
    assert min(p["mac"] for p in doc["pairs"]) > 0.99
    assert np.array(doc["mac"]).shape == (3, 3)
    assert (tmp_path / "case1+case1" / "mac.csv").exists()


def test_cycle_command_tracks_by_mac_and_reports_the_nearest_harmonic(tmp_path):
    import json

    from click.testing import CliRunner

    from flexlink.cli import main

    args = ["cycle", "cases/case1.toml", "-e", "6", "--poses", "36", "-n", "2", "--speed",
            "100 rev/min", "--harmonics", "2", "--json", "--out", str(tmp_path)]
    doc = json.loads(CliRunner().invoke(main, args).output)
    assert doc["tracking"]["by"] == "MAC" and len(doc["tracking"]["labels"]) == 2
    # 2 x 100 rev/min = 3.33 Hz, far below mode 1: gap = 1 - 3.33 / f1_min
    near = doc["nearest_harmonic"]
    assert (near["mode"], near["harmonic"]) == (1, 2)
    assert near["relative_gap"] == pytest.approx(1 - (200 / 60) / doc["modes"][0]["min_Hz"])
    header = (tmp_path / "case1" / "cycle.csv").read_text().splitlines()[0]
    assert header.endswith("mac1,mac2,events")

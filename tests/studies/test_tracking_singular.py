"""Tracking through singular poses (studies/cycle/tracking.py): the change-point four-bar of
scenes/change_point.toml passes a flat pose at crank 180 deg, where a mechanism mode appears
and the assembly branch can change. Properties that hold for any linkage: the tracked lines
hold, at every pose, the same frequencies as the sorted map (so the lowest mode is never
lost); a full turn closes, or the result says why not."""

import json

import numpy as np
import pytest
from click.testing import CliRunner
from conftest import CASES_DIR, SCENES_DIR

from flexlink.cli import main
from flexlink.scene import load_scene
from flexlink.studies.cycle.bands import bands
from flexlink.studies.cycle.modal_map import modal_map
from flexlink.studies.cycle.tracking import track, tracked_map

CHANGE_POINT = SCENES_DIR / "change_point.toml"
ELEMENTS = 4  # the properties are about tracking, not the mesh: a coarse one is enough
# tracked and sorted maps solve the same pose matrices, the tracked one with two spare modes
# (pose_modes), the sorted one through the sweep: they agree to eigen-solver round-off
SAME = 1e-8


@pytest.fixture(scope="module", params=[90, 71], ids=["90 poses", "71 poses"])
def maps(request):
    """The tracked and sorted maps of the change-point scene: 90 poses (4 deg steps) land on
    the flat pose at 180 deg, where the unchecked tracking lost the lowest mode for the rest of
    the turn; 71 poses step over it."""
    scene = load_scene(CHANGE_POINT)
    return (tracked_map(scene, request.param, 3, ELEMENTS),
            modal_map(scene, request.param, 3, ELEMENTS, reduction=None))


def test_tracked_lines_hold_the_sorted_frequencies_at_every_pose(maps):
    tracked, sorted_map = maps
    assert np.allclose(np.sort(tracked.frequencies, axis=1), sorted_map.frequencies,
                       rtol=SAME, atol=0)
    # in particular the lowest tracked line at each pose is the lowest mode there
    assert np.allclose(tracked.frequencies.min(axis=1), sorted_map.frequencies[:, 0], rtol=SAME)


def test_campbell_bands_cover_every_sorted_mode(maps):
    tracked, sorted_map = maps
    found = bands(tracked.frequencies)
    for j in range(sorted_map.frequencies.shape[1]):
        f = sorted_map.frequencies[:, j]
        # each sorted value at each pose lies in some tracked band
        assert all(any(b.low * (1 - SAME) <= v <= b.high * (1 + SAME) for b in found) for v in f)
    # and no band reaches beyond the sorted modes: a line that wandered off to a higher mode
    # would widen its band past them
    top = sorted_map.frequencies.max()
    assert all(b.low >= sorted_map.frequencies.min() * (1 - SAME) and b.high <= top * (1 + SAME)
               for b in found), found
    # the band of the line starting as mode 1 holds the whole sorted mode-1 range here (the
    # lowest mode keeps its shape family on both sides of the flat pose)
    assert found[0].low <= sorted_map.frequencies[:, 0].min() * (1 + SAME)
    assert found[0].high >= sorted_map.frequencies[:, 0].max() * (1 - SAME)


def test_the_flat_pose_is_flagged_where_it_is_sampled(maps):
    tracked, _ = maps
    flat = np.flatnonzero(np.isclose(np.degrees(tracked.q), 180.0))
    singular = [r for r in tracked.tracks.reseeds if r.reason.startswith("singular")]
    # the flat pose, where sampled, with its mechanism mode; 71 poses step from one side to its
    # mirror image, where the shapes pair again (lines may still be handed over as a shape
    # climbs out of the lowest 3). Next to the flat pose the shapes change fast enough that a
    # 4 deg step may not pair either; nowhere else is singular.
    assert set(flat) <= {r.pose for r in singular}
    for r in singular:
        assert abs(np.degrees(tracked.q[r.pose]) - 180.0) < 10.0, r
        if r.pose in flat:
            assert "mechanism" in r.reason and "dead centre" in r.reason


def test_the_change_point_map_says_why_it_does_not_close(maps):
    tracked, _ = maps
    p = tracked.periodicity
    # the cycle leaves the flat pose on the mirror-image branch: the start pose comes back
    # only after a second turn
    assert not p.closes
    assert "does not come back to its start pose" in p.note


def test_a_table2_map_closes_after_one_turn():
    result = tracked_map(load_scene(CASES_DIR / "case1.toml"), 36, 3, ELEMENTS)
    p = result.periodicity
    assert p.closes and p.permutation == (0, 1, 2), p.note
    assert "closes after one turn" in p.note
    # the wrap step is one pose step like any other: no larger than the largest step inside
    steps = np.abs(np.diff(result.frequencies, axis=0)) / result.frequencies[:-1]
    assert np.all(p.step <= steps.max(axis=0) * 1.5)


def _uncoupled(t):
    """Two uncoupled DOFs, stiffnesses 1 + t and 2 - t (M = I): they cross at t = 0.5."""
    freqs = np.sqrt(np.stack([np.minimum(1 + t, 2 - t), np.maximum(1 + t, 2 - t)], 1)) / (2 * np.pi)
    shapes = [np.eye(2) if s <= 0.5 else np.eye(2)[:, ::-1] for s in t]
    return freqs, shapes


def test_a_shape_leaving_the_lowest_modes_hands_its_line_over():
    # one line out of two modes: the lowest mode's shape x1 climbs past x2 at t = 0.5; the
    # line must not follow it up and lose the lowest mode
    t = np.linspace(0, 1, 21)
    freqs, shapes = _uncoupled(t)
    tracks = track(freqs, shapes, 1)
    assert np.array_equal(tracks.frequencies[:, 0], freqs[:, 0])
    [reseed] = tracks.reseeds
    assert t[reseed.pose] > 0.5 and reseed.lines == (1,) and "leaves the lowest" in reseed.reason


def test_a_mechanism_mode_appearing_reseeds_by_frequency_order():
    # the mode shapes at pose 2 are unrelated to those before (a random rotation): no pairing
    # is trustworthy there, and a mechanism mode appears
    rng = np.random.default_rng(3)
    q, _ = np.linalg.qr(rng.standard_normal((3, 3)))
    freqs = np.array([[1.0, 2.0, 3.0]] * 5)
    shapes = [np.eye(3), np.eye(3), q, np.eye(3), np.eye(3)]
    tracks = track(freqs, shapes, 3, mechanism=[0, 0, 1, 0, 0])
    assert [r.pose for r in tracks.reseeds] == [2]
    assert np.array_equal(tracks.rank[2], [0, 1, 2])  # frequency order kept
    # pose 3 pairs with pose 1 (the last clear one), through the singular pose
    assert np.array_equal(tracks.rank[3], [0, 1, 2]) and tracks.mac[3].min() == 1.0


def test_cycle_command_reports_reseeds_and_periodicity(tmp_path):
    args = ["cycle", str(CHANGE_POINT), "-e", str(ELEMENTS), "--poses", "36", "--out",
            str(tmp_path)]
    text = CliRunner().invoke(main, args)
    assert text.exit_code == 0, text.output
    assert "re-seeded lines 1, 2, 3 at crank 180.0 deg: singular pose" in text.output
    assert "periodicity: the tracked map does not close after one turn" in text.output
    doc = json.loads((tmp_path / "change_point" / "cycle.json").read_text())
    assert doc["tracking"]["periodicity"]["closes"] is False
    assert [r["crank_deg"] for r in doc["tracking"]["reseeds"]] == [180.0]
    rows = (tmp_path / "change_point" / "cycle.csv").read_text().splitlines()
    assert "re-seeded 1 2 3: singular pose" in rows[1 + 18]


def test_the_mode_that_turns_into_a_mechanism_reaches_zero_hz_in_the_bands(maps):
    tracked, _ = maps
    from flexlink.analysis.modal import pose_modes
    from flexlink.studies.cycle.tracking import vanishing_lines

    scene = load_scene(CHANGE_POINT)
    # the claim checked by a solve between the samples: 0.01 deg before the flat pose the
    # lowest elastic frequency is far below every sampled value (it falls linearly to 0)
    joints = scene.rigid_pose(np.radians(179.99)).joints
    _, modes, _ = pose_modes(scene.topology(ELEMENTS), joints, 1)
    lowest = modes.frequencies[modes.elastic[0]]
    assert lowest < 0.05 * tracked.frequencies.min()
    flat_sampled = np.isclose(np.degrees(tracked.q), 180.0).any()
    assert vanishing_lines(tracked) == ((1,) if flat_sampled else ())
    found = bands(tracked.frequencies, vanishing_lines(tracked))
    assert (found[0].low == 0.0) == flat_sampled


def test_a_dead_centre_between_the_sampled_poses_is_named(maps):
    tracked, _ = maps
    flat_sampled = np.isclose(np.degrees(tracked.q), 180.0).any()
    # the flat pose is the change point's only dead centre (cos mu = -1 at crank 180 deg)
    assert tracked.unsampled == (() if flat_sampled else (np.pi,))
    # and the periodicity note names it either way
    assert "at crank 180" in tracked.periodicity.note

"""Speed-dependent Campbell diagram: the per-pose reduction against the full operating-point
solve, and the diagram at zero speed against the static (frozen-pose) one."""

import json
import math

import numpy as np
import pytest

from conftest import CASES_DIR
from flexlink.scene import load_scene
from flexlink.studies.campbell import bands
from flexlink.studies.cycle import kinematic_cycle
from flexlink.studies.dynamic_campbell import dynamic_campbell, dynamic_critical, reduce_pose
from flexlink.studies.operating_point import operating_modes
from flexlink.studies.tracking import tracked_map

RPM = 2 * math.pi / 60


@pytest.fixture(scope="module")
def case1():
    return load_scene(CASES_DIR / "case1.toml")


@pytest.mark.parametrize("pose", [0, 9, 20])
def test_reduced_pose_agrees_with_full_operating_point_solve(case1, pose):
    # Table II case 1 on 8 elements per link at 2000 rev/min: the 13-mode Galerkin reduction
    # against the full quadratic solve. Measured 6e-5 relative at the worst of the first five
    # modes; 3e-4 leaves room for the pose, while dropping the preload, the centrifugal or the
    # Coriolis term moves them by 1e-3 and more.
    state = kinematic_cycle(case1, 24).states[pose]
    reduced, _ = reduce_pose(case1, state, case1.topology(8), 13)
    s, _ = reduced.modes(2000 * RPM, 5)
    full = operating_modes(case1, 2000 * RPM, 5, 8, crank_angle=state.q)
    assert np.abs(s.imag) / (2 * math.pi) == pytest.approx(full.frequencies, rel=3e-4)
    assert full.frequencies != pytest.approx(full.static_frequencies, rel=1e-3)


def test_zero_speed_equals_static_campbell(case1):
    # at rest the reduced problem is diagonal in the static modes: the same tracked lines and
    # bands as the static cycle map, to round-off
    result = dynamic_campbell(case1, np.array([0.0, 500 * RPM]), n_poses=12, n_modes=3,
                              elements_per_link=8)
    static = tracked_map(case1, 12, 3, 8)
    assert result.frequencies[0] == pytest.approx(static.frequencies, rel=1e-12)
    assert result.static == pytest.approx(static.frequencies, rel=1e-12)
    low, high = result.bands()
    expected = bands(static.frequencies)
    assert low[0] == pytest.approx([b.low for b in expected], rel=1e-12)
    assert high[0] == pytest.approx([b.high for b in expected], rel=1e-12)
    assert not np.allclose(result.frequencies[1], result.frequencies[0], rtol=1e-4)


def test_critical_range_edges_follow_the_band_at_speed(case1):
    # with bands that do not move, the interpolated edges are the frozen closed form
    # Omega = 2 pi f (1 -+ m) / n to the grid's linear interpolation (exact for flat bands)
    result = dynamic_campbell(case1, np.array([0.0, 1.0]), n_poses=6, n_modes=1,
                              elements_per_link=4)
    flat = result.__class__(scene="flat", q=result.q, speeds=np.linspace(0, 400, 81),
                            frequencies=np.full((81, 6, 1), 30.0), static=np.full((6, 1), 30.0),
                            basis=1)
    [c] = [c for c in dynamic_critical(flat, 0.05, 1)]
    assert (c.low, c.high) == pytest.approx((2 * math.pi * 30 * 0.95, 2 * math.pi * 30 * 1.05),
                                            rel=1e-12)


def test_campbell_dynamic_command(tmp_path):
    from click.testing import CliRunner

    from flexlink.cli import main

    result = CliRunner().invoke(main, [
        "campbell", str(CASES_DIR / "case1.toml"), "--speeds", "0:2000 rev/min", "--dynamic",
        "--speed-steps", "3", "--poses", "6", "-e", "4", "-n", "2", "--json",
        "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    document = json.loads(result.output)
    at_speed = document["at_speed"]
    # the frozen bands of the diagram at speed are the static command's own bands
    edges = [[b["min_Hz"], b["max_Hz"]] for b in document["bands"]]
    assert np.ravel([[b["min_Hz"], b["max_Hz"]] for b in at_speed["frozen_bands"]]) \
        == pytest.approx(np.ravel(edges), rel=1e-12)
    first = at_speed["bands_at_speed"][0]
    assert first["min_Hz"] == pytest.approx([b["min_Hz"] for b in document["bands"]], rel=1e-12)
    assert [s["rev_per_min"] for s in at_speed["bands_at_speed"]] == pytest.approx(
        [0, 1000, 2000])
    assert (tmp_path / "case1" / "campbell_at_speed.csv").exists()
    assert all(s["frozen_rev_per_min"] or s["at_speed_rev_per_min"]
               for s in at_speed["critical_speeds"])

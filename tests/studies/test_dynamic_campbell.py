"""Speed-dependent Campbell diagram: the per-pose reduction against the full operating-point
solve, and the diagram at zero speed against the static (frozen-pose) one."""

import json
import math

import numpy as np
import pytest

from conftest import CASES_DIR
from flexlink.scene import load_scene
from flexlink.studies.cycle.bands import bands
from flexlink.studies.cycle.modal_map import kinematic_cycle
from flexlink.studies.running.dynamic_campbell import dynamic_campbell, dynamic_critical, project_pose
from flexlink.studies.running.modes_at_speed import operating_modes
from flexlink.studies.cycle.tracking import tracked_map

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
    reduced, _ = project_pose(case1, state, case1.topology(8), 13)
    s, _ = reduced.modes(2000 * RPM, 5)
    full = operating_modes(case1, 2000 * RPM, 5, 8, crank_angle=state.q)
    assert np.abs(s.imag) / (2 * math.pi) == pytest.approx(full.frequencies, rel=3e-4)
    assert full.frequencies != pytest.approx(full.static_frequencies, rel=1e-3)


@pytest.mark.parametrize("pose, acceleration", [(9, 5e3), (20, -5e3)])
def test_reduced_pose_with_crank_acceleration(case1, pose, acceleration):
    # the crank acceleration's part K1 (rigid accelerations p' qddot and alpha = K qddot in the
    # preload and the alpha S term) against the full solve with that acceleration: the same
    # 3e-4 as at constant speed, while 5e3 rad/s^2 moves the modes by 1e-2 and more
    state = kinematic_cycle(case1, 24).states[pose]
    reduced, _ = project_pose(case1, state, case1.topology(8), 13)
    s, _ = reduced.modes(2000 * RPM, 5, acceleration)
    full = operating_modes(case1, 2000 * RPM, 5, 8, crank_angle=state.q,
                           crank_acceleration=acceleration)
    assert np.abs(s.imag) / (2 * math.pi) == pytest.approx(full.frequencies, rel=3e-4)
    steady, _ = reduced.modes(2000 * RPM, 5)
    assert np.abs(steady.imag) != pytest.approx(np.abs(s.imag), rel=1e-2)


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
    # the grid: 3 speeds across the window, and each frozen critical range's ends (and
    # middle), so that a range narrower than the step is sampled where it is looked for
    grid = [s["rev_per_min"] for s in at_speed["bands_at_speed"]]
    wanted = [0, 1000, 2000] + [x for c in document["critical_speeds"]
                                for x in (c["from_rev_per_min"], c["to_rev_per_min"])]
    assert all(min(abs(g - w) for g in grid) <= 1e-6 * max(w, 1.0) for w in wanted), grid
    assert grid == sorted(grid)
    assert (tmp_path / "case1" / "campbell_at_speed.csv").exists()
    assert all(s["frozen_rev_per_min"] or s["at_speed_rev_per_min"]
               for s in at_speed["critical_speeds"])


def test_lines_follow_their_modes_through_the_speeds(case1):
    # Table II case 1 (8 elements per link, 12 poses), 1000 to 2400 rev/min in 200 rev/min
    # steps: the falling mode of the crank angles near 180 deg crosses the one above it there.
    # Tracked through the speeds, a line moves by at most 7.3 Hz per step (measured; the
    # falling mode near 2400 rev/min); lines re-tracked through the cycle at each speed alone
    # swapped at 1600 rev/min, a jump of 42 Hz (the gap between the two modes).
    speeds = np.arange(1000.0, 2401.0, 200.0) * RPM
    result = dynamic_campbell(case1, speeds, n_poses=12, n_modes=3, elements_per_link=8)
    assert result.divergence is None and result.ambiguous == 0
    step = np.abs(np.diff(result.frequencies, axis=0))
    assert step.max() < 10.0
    # at the first speed the lines are the cycle's tracked lines, as in the static map
    assert np.all(np.diff(np.sort(result.frequencies[0], axis=1), axis=1) >= 0)


def test_lines_cross_where_their_modes_cross_in_speed(case1, monkeypatch):
    # Each pose's reduced problem replaced by one whose two lowest modes cross in speed with
    # their shapes unchanged: k = diag(lam) + Omega^2 diag(+c, -c, 0, ...), no gyroscopic
    # term, so the lowest mode's frequency rises to the second's at the top speed and the
    # second falls to the first's (they cross at top / sqrt(2), between grid speeds). Each
    # line must follow its mode: sqrt(lam +- Omega^2 c) / (2 pi) exactly (round-off), where
    # frequency order would swap the lines at the crossing.
    import dataclasses

    from flexlink.studies.running import dynamic_campbell as studied

    real, top, slope = studied.project_pose, 100.0, {}

    def crossing(scene, state, topology, basis, form=None):
        pose, mass = real(scene, state, topology, basis)
        lam = np.diag(pose.k0).copy()
        c = (lam[1] - lam[0]) / top**2
        slope[round(float(state.q), 9)] = c
        d = np.zeros(len(lam))
        d[:2] = c, -c
        zero = np.zeros_like(pose.k0)
        return dataclasses.replace(pose, k0=np.diag(lam), k2=np.diag(d), g1=zero, k1=zero), mass

    monkeypatch.setattr(studied, "project_pose", crossing)
    speeds = np.linspace(0.0, top, 9)
    result = studied.dynamic_campbell(case1, speeds, n_poses=8, n_modes=2, elements_per_link=4)
    w0 = 2 * math.pi * result.frequencies[0]  # (poses, lines) at rest
    sign = np.where(w0 == w0.min(axis=1, keepdims=True), 1.0, -1.0)  # the lower one rises
    c = np.array([slope[round(float(q), 9)] for q in result.q])[:, None]
    expected = np.sqrt(w0**2 + sign * c * speeds[:, None, None] ** 2) / (2 * math.pi)
    assert result.frequencies == pytest.approx(expected, rel=1e-10)
    assert result.ambiguous == 0


def test_divergence_names_the_line_that_falls_to_zero(case1):
    # Past about 2750 rev/min case 1's lowest mode near crank angle 210 deg diverges: the
    # record gives the speed where the reduced stiffness at speed is singular at a sampled
    # pose, the line (1: the lines are numbered at the first speed, here at rest, as the
    # frozen-pose lines), and a real root that grows at the first grid speed past it.
    speeds = np.array([0.0, 1000.0, 2000.0, 2400.0, 2600.0, 2700.0, 2900.0]) * RPM
    result = dynamic_campbell(case1, speeds, n_poses=12, n_modes=3, elements_per_link=8)
    d = result.divergence
    assert d is not None and d.line == 1
    assert 2700 * RPM < d.speed < 2900 * RPM and d.grid_speed == speeds[-1]
    assert d.growth_rate > 0
    assert result.stable_speeds == 6 and np.isnan(result.frequencies[-1]).all()
    # the line's frequency at that pose falls towards 0 Hz as the speed comes up to it
    pose = int(np.argmin(np.abs(np.angle(np.exp(1j * (result.q - d.q))))))
    falling = result.frequencies[2:6, pose, 0]
    assert np.all(np.diff(falling) < 0) and falling[-1] < 0.5 * falling[0]
    # the full (unreduced) operating-point solve at that pose agrees where the divergence is:
    # 0.5 % below it all modes oscillate, 0.5 % above it the stiffness at speed is indefinite
    below = operating_modes(case1, 0.995 * d.speed, 3, 8, crank_angle=d.q)
    above = operating_modes(case1, 1.005 * d.speed, 3, 8, crank_angle=d.q)
    assert below.modes.negative_stiffness == 0 and above.modes.negative_stiffness > 0


@pytest.mark.parametrize("extra, message", [
    (["--crank-acceleration", "50 rad/s^2"], "--dynamic"),
    (["--dynamic", "--crank-acceleration", "50 rev/min"], "angular acceleration"),
    (["--dynamic", "--crank-acceleration", "nan rad/s^2"], "cannot read"),
    (["--dynamic", "--crank-acceleration", "1e400 rad/s^2"], "finite"),
])
def test_campbell_crank_acceleration_bad_input(tmp_path, extra, message):
    # an acceleration without the bands at speed, a wrong unit or NaN: exit 2, one line
    # naming the option, nothing computed
    from click.testing import CliRunner

    from flexlink.cli import main

    result = CliRunner().invoke(main, [
        "campbell", str(CASES_DIR / "case1.toml"), "--speeds", "0:2000 rev/min", "--poses", "6",
        "-e", "4", "-n", "1", "--out", str(tmp_path), *extra])
    assert result.exit_code == 2, result.output
    assert "--crank-acceleration" in result.output and message in result.output
    assert "Traceback" not in result.output
    assert not (tmp_path / "case1" / "campbell.json").exists()


def test_campbell_dynamic_with_crank_acceleration(tmp_path):
    # the acceleration reaches the bands at speed (at rest it acts alone: alpha = K qddot and
    # the accelerations p' qddot preload the frame), and the JSON states it
    from click.testing import CliRunner

    from flexlink.cli import main

    def bands(*extra):
        result = CliRunner().invoke(main, [
            "campbell", str(CASES_DIR / "case1.toml"), "--speeds", "0:1000 rev/min", "--dynamic",
            "--speed-steps", "2", "--poses", "6", "-e", "4", "-n", "2", "--json",
            "--out", str(tmp_path), *extra])
        assert result.exit_code == 0, result.output
        return json.loads(result.output)["at_speed"]

    steady, speeding = bands(), bands("--crank-acceleration", "2000 rad/s^2")
    assert steady["crank_acceleration_rad_s2"] == 0
    assert speeding["crank_acceleration_rad_s2"] == pytest.approx(2000.0)
    for a, b in zip(steady["bands_at_speed"], speeding["bands_at_speed"]):
        assert a["min_Hz"] != pytest.approx(b["min_Hz"], rel=1e-4)

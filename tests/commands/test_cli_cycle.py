"""The kinematics, cycle, synth and prb commands: one JSON document, files, clear errors."""

import dataclasses
import json
import math

import pytest
from click.testing import CliRunner

from flexlink.analysis.modal import analyze
from flexlink.cli import main
from flexlink.scene import load_scene

from conftest import ROOT


def run(*args):
    result = CliRunner().invoke(main, [str(a) for a in args])
    return result


def test_synth_minimax_json_recovers_case3():
    result = run("synth", "minimax", "100 deg", "20 deg", "--json")
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert [doc["ratios"][k] for k in ("R2", "R3", "R4")] == pytest.approx(
        [0.141, 0.900, 0.457], rel=0, abs=5e-4)  # as Table II prints them
    assert abs(doc["mu_min_deg"] + doc["mu_max_deg"] - 180) < 1e-9


def test_synth_brodell_soni_table():
    result = run("synth", "brodell-soni", "60 deg", "30 deg", "--ground", "400 mm")
    assert result.exit_code == 0, result.output
    assert "rocker swing 30.000 deg" in result.output


def test_kinematics_reports_synthesis_and_family(tmp_path):
    result = run("kinematics", ROOT / "scenes" / "extended_rocker.toml", "--poses", "36",
                 "--json", "--out", tmp_path)
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert doc["synthesis"]["lengths_m"]["rocker"] == 0.1  # the scene's "100 mm", parsed
    assert len(doc["family"]) == 3 + 15
    rocker = doc["bodies"]["rocker"]
    assert abs(rocker["swing_deg"] - 30) < 1e-9 and abs(rocker["time_ratio"] - 1) < 1e-9
    omega = 2000 * 2 * math.pi / 60
    assert abs(rocker["omega_rad_s"]["max"] - rocker["K"]["max"] * omega) < 1e-9
    assert (tmp_path / "extended_rocker" / "kinematics.csv").read_text().count("\n") == 1 + 36


def test_cycle_writes_csv_png_and_checks_resonance(tmp_path):
    scene_path = ROOT / "scenes" / "kineto_aluminium.toml"
    margin, harmonics = 0.05, 100
    result = run("cycle", scene_path, "--poses", "6", "-e", "3", "-n", "2", "--speed",
                 "600 rev/min", "--harmonics", str(harmonics), "--sorted", "--json",
                 "--out", tmp_path)
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    for name in ("cycle.csv", "cycle.png", "cycle.json"):
        assert (tmp_path / "kineto_aluminium" / name).stat().st_size > 0
    rows = [list(map(float, line.split(","))) for line in
            (tmp_path / "kineto_aluminium" / "cycle.csv").read_text().splitlines()[1:]]
    # every row of the map is the single-pose analysis at that crank angle (a second path:
    # the closed-loop pose, the full model, no Craig-Bampton), within the map's stated 1e-6
    scene = load_scene(scene_path)
    for row in rows[::2]:
        pose = dataclasses.replace(scene, start=math.radians(row[0]))
        assert row[1:] == pytest.approx(list(analyze(pose, 2, 3).elastic_frequencies(2)), rel=1e-6)
    # the resonance list, by hand from the map: harmonic n of 10 Hz hits mode j where
    # |f_j - 10 n| <= margin f_j at some pose, or where f_j crosses 10 n between two poses
    f_crank = 600 / 60

    def hit(n, j):
        f = [r[1 + j] for r in rows]
        near = any(abs(v - n * f_crank) <= margin * v for v in f)
        crossed = any((a - n * f_crank) * (b - n * f_crank) < 0 for a, b in zip(f, f[1:] + f[:1]))
        return near or crossed

    expected = {(n, j + 1) for n in range(1, harmonics + 1) for j in range(2) if hit(n, j)}
    assert {(h["harmonic"], h["mode"]) for h in doc["resonances"]} == expected
    assert expected  # 100 harmonics of 10 Hz reach both modes (41.6 .. 114 Hz)


def test_cycle_of_kinematics_only_scene_is_a_clear_error(tmp_path):
    result = run("cycle", ROOT / "scenes" / "extended_rocker.toml", "--out", tmp_path)
    assert result.exit_code == 2
    assert "no [links]" in result.output


def test_prb_command(tmp_path):
    result = run("prb", ROOT / "scenes" / "compliant_wiper.toml", "-e", "6", "--json",
                 "--out", tmp_path)
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    # Howell's spring by hand: K = gamma K_Theta E I / l, the strip 1 mm (in plane) x 30 mm,
    # l = |C O4| at the pose where the strip is straight
    points = doc["points_m"]
    length = math.dist(points["C"], points["O4"])
    spring = 0.85 * 2.65 * 210e9 * (30e-3 * 1e-3**3 / 12) / length
    assert doc["prb"]["spring_N_m_per_rad"] == pytest.approx(spring, rel=1e-12)
    assert doc["prb"]["first_Hz"] == pytest.approx(
        math.sqrt(doc["prb"]["generalized_stiffness_N_m"] / doc["prb"]["generalized_mass_kg_m2"])
        / (2 * math.pi), rel=1e-12)
    assert (tmp_path / "compliant_wiper" / "prb.json").is_file()

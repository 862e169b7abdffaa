"""The kinematics, cycle, synth and prb commands: one JSON document, files, clear errors."""

import json
import math
from pathlib import Path

from click.testing import CliRunner

from flexlink.cli import main

ROOT = Path(__file__).resolve().parent.parent


def run(*args):
    result = CliRunner().invoke(main, [str(a) for a in args])
    return result


def test_synth_minimax_json_recovers_case3():
    result = run("synth", "minimax", "100 deg", "20 deg", "--json")
    assert result.exit_code == 0, result.output
    doc = json.loads(result.output)
    assert [round(doc["ratios"][k], 3) for k in ("R2", "R3", "R4")] == [0.141, 0.900, 0.457]
    assert abs(doc["mu_min_deg"] + doc["mu_max_deg"] - 180) < 1e-9


def test_synth_brodell_soni_table():
    result = run("synth", "brodell-soni", "60 deg", "30 deg", "--ground", "400 mm")
    assert result.exit_code == 0, result.output
    assert "rocker swing 30.000 deg" in result.output


def test_kinematics_reports_synthesis_and_family(tmp_path):
    result = run("kinematics", ROOT / "scenes" / "extended_rocker.toml", "--poses", "36",
                 "--json", "--out", tmp_path)
    assert result.exit_code == 0, result.output
    doc = json.loads(result.output)
    assert doc["synthesis"]["lengths_m"]["rocker"] == 0.1
    assert len(doc["family"]) == 3 + 8
    rocker = doc["bodies"]["rocker"]
    assert abs(rocker["swing_deg"] - 30) < 1e-9 and abs(rocker["time_ratio"] - 1) < 1e-9
    omega = 2000 * 2 * math.pi / 60
    assert abs(rocker["omega_rad_s"]["max"] - rocker["K"]["max"] * omega) < 1e-9
    assert (tmp_path / "extended_rocker" / "kinematics.csv").read_text().count("\n") == 1 + 36


def test_cycle_writes_csv_png_and_checks_resonance(tmp_path):
    result = run("cycle", ROOT / "scenes" / "kineto_aluminium.toml", "--poses", "6", "-e", "3",
                 "-n", "2", "--speed", "600 rev/min", "--harmonics", "100", "--json",
                 "--out", tmp_path)
    assert result.exit_code == 0, result.output
    doc = json.loads(result.output)
    assert len(doc["modes"]) == 2
    for name in ("cycle.csv", "cycle.png", "cycle.json"):
        assert (tmp_path / "kineto_aluminium" / name).stat().st_size > 0
    f_crank = 10.0  # Hz
    for hit in doc["resonances"]:
        assert abs(hit["harmonic_Hz"] - hit["harmonic"] * f_crank) < 1e-9
    assert doc["resonances"]  # 100 harmonics of 10 Hz span every mode


def test_cycle_of_kinematics_only_scene_is_a_clear_error(tmp_path):
    result = run("cycle", ROOT / "scenes" / "extended_rocker.toml", "--out", tmp_path)
    assert result.exit_code == 2
    assert "no [links]" in result.output


def test_prb_command(tmp_path):
    result = run("prb", ROOT / "scenes" / "compliant_wiper.toml", "-e", "6", "--json",
                 "--out", tmp_path)
    assert result.exit_code == 0, result.output
    doc = json.loads(result.output)
    assert abs(doc["prb_vs_fe_pct"] - 100 * (doc["prb"]["first_Hz"] / doc["fe_Hz"][0] - 1)) < 1e-9

"""flexlink compliant: one JSON document with its files and the strip's life verdicts, and
one-line refusals (exit 2) for a scene without a [prb] table or a strip without strength data
(before any work, nothing written)."""

import json

from click.testing import CliRunner
from conftest import CASES_DIR, SCENES_DIR

from flexlink.cli import main


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_compliant_json_and_files(tmp_path):
    result = run("compliant", SCENES_DIR / "compliant_wiper.toml", "-e", "6", "--angles", "36",
                 "--json", "--out", tmp_path)
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    folder = tmp_path / "compliant_wiper"
    assert doc["files"] == [str(folder / n) for n in
                            ("compliant.csv", "compliant.png", "compliant.json")]
    assert all((folder / n).is_file() for n in ("compliant.csv", "compliant.png"))
    assert (folder / "compliant.csv").read_text().count("\n") == 1 + 36
    assert doc["fe"]["peak_stress_Pa"] > 1e8 and doc["prb"]["peak_stress_Pa"] > 1e8
    assert [v["model"] for v in doc["life"]["verdicts"]] == ["FE", "PRB"]
    fe = doc["life"]["verdicts"][0]
    assert fe["material"] == "aisi_1080" and fe["at_arc_length_m"] < 1e-12  # at the clamp


def test_scene_without_prb_is_refused_in_one_line(tmp_path):
    result = run("compliant", CASES_DIR / "case1.toml", "--out", tmp_path)
    assert result.exit_code == 2
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert len(lines) == 1 and "case1.toml" in lines[0] and "prb" in lines[0], result.output


def test_strip_without_strength_data_is_refused_before_the_study(tmp_path):
    scene = tmp_path / "wiper_e_only.toml"
    scene.write_text(f'base = "{(SCENES_DIR / "compliant_wiper.toml").as_posix()}"\n'
                     '[links.strip.material]\nE = "210 GPa"\ndensity = "7850 kg/m^3"\n')
    result = run("compliant", scene, "--out", tmp_path / "out")
    assert result.exit_code == 2, result.output
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert len(lines) == 1 and "strength" in lines[0], result.output
    assert not any((tmp_path / "out").rglob("compliant.*"))

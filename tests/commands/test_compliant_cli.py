"""flexlink compliant: one JSON document with its files, the life verdicts when the steel is
given, and a one-line refusal (exit 2) for a scene without a [prb] table."""

import json

from click.testing import CliRunner
from conftest import CASES_DIR, SCENES_DIR

from flexlink.cli import main


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_compliant_json_and_files(tmp_path):
    result = run("compliant", SCENES_DIR / "compliant_wiper.toml", "-e", "6", "--angles", "36",
                 "--steel", "aisi-1080-qt315", "--json", "--out", tmp_path)
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    folder = tmp_path / "compliant_wiper"
    assert doc["files"] == [str(folder / n) for n in
                            ("compliant.csv", "compliant.png", "compliant.json")]
    assert all((folder / n).is_file() for n in ("compliant.csv", "compliant.png"))
    assert (folder / "compliant.csv").read_text().count("\n") == 1 + 36
    assert doc["fe"]["peak_stress_Pa"] > 1e8 and doc["prb"]["peak_stress_Pa"] > 1e8
    assert len(doc["life"]["verdicts"]) == 4  # FE and PRB at both ends of Sut's range


def test_scene_without_prb_is_refused_in_one_line(tmp_path):
    result = run("compliant", CASES_DIR / "case1.toml", "--out", tmp_path)
    assert result.exit_code == 2
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert len(lines) == 1 and "case1.toml" in lines[0] and "prb" in lines[0], result.output

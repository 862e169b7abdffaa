"""``flexlink response``: bad input is one line naming the field, exit 2, before any work;
a run writes its three files and one JSON document."""
import json

import pytest
from click.testing import CliRunner
from conftest import CASES_DIR

from flexlink.cli import main

CASE1 = str(CASES_DIR / "case1.toml")


@pytest.mark.parametrize("args, words", [
    (["--speeds", "600:300 rev/min"], "--speeds"),  # backwards
    (["--speeds", "600:600 rev/min"], "--speeds"),  # zero width
    (["--speed", "600 rev/min", "--speeds", "0:600 rev/min"], "not both"),
    (["--speed", "600 m"], "--speed"),
    (["--speed", "-5 rev/min"], "crank speed -5 rev/min"),  # in the unit the user gave
    (["--speed", "600 rev/min", "--damping-ratio", "-0.1"], "--damping-ratio"),
    (["--speed", "600 rev/min", "--damping-ratio", "1.5"], "--damping-ratio"),
    (["--speed", "600 rev/min", "--at", "coupler:900 mm"], "outside link 'coupler'"),
    (["--speed", "600 rev/min", "--at", "arm:10 mm"], "no beam link named 'arm'"),
    (["--speed", "600 rev/min", "--at", "coupler"], "LINK:DISTANCE"),
    ([], "crank_speed"),  # case 1 declares no operating speed
])
def test_bad_input_is_one_line_with_the_field(tmp_path, args, words):
    result = CliRunner().invoke(main, ["response", CASE1, *args, "--out", str(tmp_path)])
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and words in lines[0] and "Traceback" not in result.output


def test_one_speed_writes_strain_over_the_turn(tmp_path):
    result = CliRunner().invoke(main, ["response", CASE1, "--speed", "1200 rev/min", "-n", "1",
                                       "--at", "coupler:60 mm", "--json", "--out",
                                       str(tmp_path)])
    assert result.exit_code == 0, result.output
    document = json.loads(result.stdout)
    [point] = document["points"]
    assert point["link"] == "coupler" and point["position_m"] == pytest.approx(0.06)
    assert point["peak_strain"] == pytest.approx(max(abs(x) for x in point["strain"]))
    for suffix in ("png", "csv", "json"):
        assert (tmp_path / "case1" / f"response.{suffix}").stat().st_size > 0
